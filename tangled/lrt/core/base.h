// lrt/core/base.h: tangled from chapters/02-geometry.md. Edit the chapter, not this file.
#pragma once

// base.h includes
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <type_traits>

namespace lrt {

// Global Forward Declarations
class Shape;
class Primitive;
class Transform;
struct Interaction;
class SurfaceInteraction;
// Floating-Point Type Definition
#ifdef LRT_FLOAT_AS_DOUBLE
typedef double Float;
#else
typedef float Float;
#endif
// Global Constants
inline constexpr Float MaxFloat = std::numeric_limits<Float>::max();
inline constexpr Float Infinity = std::numeric_limits<Float>::infinity();
inline constexpr Float MachineEpsilon =
    std::numeric_limits<Float>::epsilon() * Float(0.5);
inline constexpr Float ShadowEpsilon = 0.0001f;
inline constexpr Float Pi = 3.14159265358979323846;
inline constexpr Float InvPi = 0.31830988618379067154;
inline constexpr Float Inv2Pi = 0.15915494309189533577;
inline constexpr Float Inv4Pi = 0.07957747154594766788;
inline constexpr Float PiOver2 = 1.57079632679489661923;
inline constexpr Float PiOver4 = 0.78539816339744830962;
inline constexpr Float Sqrt2 = 1.41421356237309504880;
// Global Inline Functions
inline constexpr Float gamma(int n) {
    return (n * MachineEpsilon) / (1 - n * MachineEpsilon);
}
inline uint32_t FloatToBits(float f) {
    uint32_t ui;
    std::memcpy(&ui, &f, sizeof(float));
    return ui;
}

inline float BitsToFloat(uint32_t ui) {
    float f;
    std::memcpy(&f, &ui, sizeof(uint32_t));
    return f;
}

inline uint64_t FloatToBits(double f) {
    uint64_t ui;
    std::memcpy(&ui, &f, sizeof(double));
    return ui;
}

inline double BitsToFloat(uint64_t ui) {
    double f;
    std::memcpy(&f, &ui, sizeof(uint64_t));
    return f;
}
inline float NextFloatUp(float v) {
    if (std::isnan(v) || (std::isinf(v) && v > 0)) return v;
    if (v == -0.f) v = 0.f;
    uint32_t ui = FloatToBits(v);
    if (v >= 0)
        ++ui;
    else
        --ui;
    return BitsToFloat(ui);
}
inline float NextFloatDown(float v) {
    if (std::isnan(v) || (std::isinf(v) && v < 0)) return v;
    if (v == 0.f) v = -0.f;
    uint32_t ui = FloatToBits(v);
    if (v > 0)
        --ui;
    else
        ++ui;
    return BitsToFloat(ui);
}
inline double NextFloatUp(double v) {
    if (std::isnan(v) || (std::isinf(v) && v > 0)) return v;
    if (v == -0.0) v = 0.0;
    uint64_t ui = FloatToBits(v);
    if (v >= 0)
        ++ui;
    else
        --ui;
    return BitsToFloat(ui);
}

inline double NextFloatDown(double v) {
    if (std::isnan(v) || (std::isinf(v) && v < 0)) return v;
    if (v == 0.0) v = -0.0;
    uint64_t ui = FloatToBits(v);
    if (v > 0)
        --ui;
    else
        ++ui;
    return BitsToFloat(ui);
}
inline Float Lerp(Float t, Float v1, Float v2) {
    return (1 - t) * v1 + t * v2;
}
template <typename T, typename U, typename V>
inline T Clamp(T val, U low, V high) {
    if (val < low) return T(low);
    if (val > high) return T(high);
    return val;
}
inline Float Radians(Float deg) { return (Pi / 180) * deg; }
inline Float Degrees(Float rad) { return (180 / Pi) * rad; }
template <typename T>
inline T Mod(T a, T b) {
    if (!(b > 0)) throw std::domain_error("Mod: modulus must be positive");
    if constexpr (std::is_floating_point<T>::value) {
        T r = std::fmod(a, b);
        if (r < 0) r += b;
        return (r < b) ? r : T(0);
    } else {
        T r = a % b;
        return (r < 0) ? r + b : r;
    }
}
template <typename T>
inline constexpr bool IsPowerOf2(T v) {
    return v > 0 && (v & (v - 1)) == 0;
}
inline int Log2Int(uint32_t v) {
    if (v == 0) throw std::domain_error("Log2Int: argument must be positive");
    return 31 - __builtin_clz(v);
}

inline int Log2Int(int32_t v) {
    if (v <= 0) throw std::domain_error("Log2Int: argument must be positive");
    return Log2Int(uint32_t(v));
}

inline int Log2Int(uint64_t v) {
    if (v == 0) throw std::domain_error("Log2Int: argument must be positive");
    return 63 - __builtin_clzll(v);
}

inline int Log2Int(int64_t v) {
    if (v <= 0) throw std::domain_error("Log2Int: argument must be positive");
    return Log2Int(uint64_t(v));
}
template <typename T>
inline T DifferenceOfProducts(T a, T b, T c, T d) {
    T cd = c * d;
    T err = std::fma(-c, d, cd);
    T dop = std::fma(a, b, -cd);
    return dop + err;
}
inline bool Quadratic(Float a, Float b, Float c, Float *t0, Float *t1) {
    // Handle the linear case of Quadratic()
    if (a == 0) {
        if (b == 0) return false;
        Float t = -c / b;
        if (std::isnan(t)) return false;
        *t0 = *t1 = t;
        return true;
    }
    Float discrim = DifferenceOfProducts(b, b, 4 * a, c);
    if (!(discrim >= 0)) return false;
    Float rootDiscrim = std::sqrt(discrim);
    // Compute the roots of the quadratic from q
    Float q = Float(-0.5) * (b + std::copysign(rootDiscrim, b));
    *t0 = q / a;
    *t1 = (q != 0) ? c / q : *t0;
    if (*t0 > *t1) std::swap(*t0, *t1);
    return true;
}

}  // namespace lrt
