// lrt/core/efloat.h: tangled from chapters/03-shapes.md. Edit the chapter, not this file.
#pragma once

#include "lrt/core/base.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

namespace lrt {

// EFloat Declarations
class EFloat {
  public:
    // EFloat Public Methods
    EFloat() = default;
    EFloat(Float v, Float err = 0) : v(v) {
        if (err == 0) {
            low = high = v;
        } else {
            err = std::abs(err);
            low = NextFloatDown(v - err);
            high = NextFloatUp(v + err);
        }
        SetPrecise(v);
    }
    #ifdef LRT_EFLOAT_PRECISE
    EFloat(Float v, long double precise, Float err) : EFloat(v, err) {
        SetPrecise(precise);
    }
    #endif
    void Check() const {
        if (low > high)
            throw std::logic_error("EFloat::Check: inverted interval");
    #ifdef LRT_EFLOAT_PRECISE
        if (std::isfinite(vPrecise) && (vPrecise < low || vPrecise > high))
            throw std::logic_error("EFloat::Check: precise value outside bounds");
    #endif
    }
    explicit operator float() const { return v; }
    explicit operator double() const { return v; }
    Float LowerBound() const { return low; }
    Float UpperBound() const { return high; }
    long double PreciseValue() const {
    #ifdef LRT_EFLOAT_PRECISE
        return vPrecise;
    #else
        return v;
    #endif
    }
    Float GetAbsoluteError() const {
        return NextFloatUp(std::max(std::abs(high - v), std::abs(v - low)));
    }
  private:
    // EFloat Private Methods
    void SetPrecise([[maybe_unused]] long double precise) {
    #ifdef LRT_EFLOAT_PRECISE
        vPrecise = precise;
        Check();
    #endif
    }
    void SetBounds(const Float c[4]) {
        for (int i = 0; i < 4; ++i)
            if (std::isnan(c[i])) {
                low = -Infinity;
                high = Infinity;
                return;
            }
        low = NextFloatDown(std::min(std::min(c[0], c[1]), std::min(c[2], c[3])));
        high = NextFloatUp(std::max(std::max(c[0], c[1]), std::max(c[2], c[3])));
    }
    // EFloat Private Data
    Float v = 0, low = 0, high = 0;
    #ifdef LRT_EFLOAT_PRECISE
    long double vPrecise = 0;
    #endif
    // EFloat Friends
    friend EFloat operator+(EFloat a, EFloat b) {
        EFloat r;
        r.v = a.v + b.v;
        r.low = NextFloatDown(a.low + b.low);
        r.high = NextFloatUp(a.high + b.high);
        r.SetPrecise(a.PreciseValue() + b.PreciseValue());
        return r;
    }
    friend EFloat operator-(EFloat a, EFloat b) {
        EFloat r;
        r.v = a.v - b.v;
        r.low = NextFloatDown(a.low - b.high);
        r.high = NextFloatUp(a.high - b.low);
        r.SetPrecise(a.PreciseValue() - b.PreciseValue());
        return r;
    }

    friend EFloat operator-(EFloat a) {
        EFloat r;
        r.v = -a.v;
        r.low = -a.high;
        r.high = -a.low;
        r.SetPrecise(-a.PreciseValue());
        return r;
    }
    friend EFloat operator*(EFloat a, EFloat b) {
        EFloat r;
        r.v = a.v * b.v;
        Float c[4] = {a.low * b.low, a.high * b.low, a.low * b.high,
                      a.high * b.high};
        r.SetBounds(c);
        r.SetPrecise(a.PreciseValue() * b.PreciseValue());
        return r;
    }
    friend EFloat operator/(EFloat a, EFloat b) {
        EFloat r;
        r.v = a.v / b.v;
        if (b.low <= 0 && b.high >= 0) {
            r.low = -Infinity;
            r.high = Infinity;
        } else {
            Float c[4] = {a.low / b.low, a.high / b.low, a.low / b.high,
                          a.high / b.high};
            r.SetBounds(c);
        }
        r.SetPrecise(a.PreciseValue() / b.PreciseValue());
        return r;
    }
    friend EFloat sqrt(EFloat a) {
        EFloat r;
        r.v = std::sqrt(a.v);
        r.low = (a.low > 0) ? NextFloatDown(std::sqrt(a.low)) : 0;
        r.high = NextFloatUp(std::sqrt(a.high));
        r.SetPrecise(std::sqrt(a.PreciseValue()));
        return r;
    }

    friend EFloat abs(EFloat a) {
        if (a.low >= 0) return a;
        if (a.high <= 0) return -a;
        EFloat r;
        r.v = std::abs(a.v);
        r.low = 0;
        r.high = std::max(-a.low, a.high);
        r.SetPrecise(std::abs(a.PreciseValue()));
        return r;
    }
    friend bool Quadratic(EFloat a, EFloat b, EFloat c, EFloat *t0, EFloat *t1);
    friend bool QuadraticRoots(EFloat a, EFloat b, EFloat c, EFloat discrim,
                               EFloat *t0, EFloat *t1);
};

// EFloat Inline Functions
inline bool Quadratic(EFloat a, EFloat b, EFloat c, EFloat *t0, EFloat *t1) {
    // Handle the linear case of the EFloat Quadratic()
    if (a.v == 0) {
        if (b.v == 0) return false;
        EFloat t = -c / b;
        if (std::isnan(t.v)) return false;
        *t0 = *t1 = t;
        return true;
    }
    // Compute the discriminant of the EFloat quadratic
    EFloat discrim = b * b - EFloat(4) * a * c;
    discrim.v = Clamp(DifferenceOfProducts(b.v, b.v, 4 * a.v, c.v), discrim.low,
                      discrim.high);
    return QuadraticRoots(a, b, c, discrim, t0, t1);
}

inline bool QuadraticRoots(EFloat a, EFloat b, EFloat c, EFloat discrim,
                           EFloat *t0, EFloat *t1) {
    if (!(discrim.v >= 0)) return false;
    EFloat rootDiscrim = sqrt(discrim);
    // Compute the EFloat roots from q
    EFloat q = (b.v < 0) ? Float(-0.5) * (b - rootDiscrim)
                         : Float(-0.5) * (b + rootDiscrim);
    *t0 = q / a;
    *t1 = (q.v != 0) ? c / q : *t0;
    if (t0->v > t1->v) std::swap(*t0, *t1);
    return true;
}

}  // namespace lrt
