// Helpers shared by the quadric oracles of test_sphere.cpp, test_disk.cpp,
// test_far.cpp and the tests of the other quadrics (quadrics_oracle.h): a
// small vector type (in double and in long double precision), conversions to
// and from lrt's types, a seeded random source, affine transformations with
// inverses written down from their factors (independent of lrt's Inverse),
// the object-space ray of a world ray with the bounds on its rounding errors,
// and the test whether an error box contains a point of a surface.
#pragma once

#include "lrt/core/transform.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>

namespace {

typedef long double LD;

// A vector of three numbers of type T: D3 in double precision for most
// oracles, L3 in long double where double is not accurate enough.
template <typename T>
struct V3 {
    typedef T Scalar;
    T x = 0, y = 0, z = 0;
    V3() {}
    V3(T x, T y, T z) : x(x), y(y), z(z) {}
    T operator[](int i) const { return i == 0 ? x : (i == 1 ? y : z); }
};
typedef V3<double> D3;
typedef V3<LD> L3;
template <typename T>
V3<T> operator+(V3<T> a, V3<T> b) {
    return V3<T>(a.x + b.x, a.y + b.y, a.z + b.z);
}
template <typename T>
V3<T> operator-(V3<T> a, V3<T> b) {
    return V3<T>(a.x - b.x, a.y - b.y, a.z - b.z);
}
template <typename T>
V3<T> operator*(typename V3<T>::Scalar s, V3<T> a) {
    return V3<T>(s * a.x, s * a.y, s * a.z);
}
template <typename T>
T dot3(V3<T> a, V3<T> b) {
    return a.x * b.x + a.y * b.y + a.z * b.z;
}
template <typename T>
V3<T> cross3(V3<T> a, V3<T> b) {
    return V3<T>(a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z,
                 a.x * b.y - a.y * b.x);
}
template <typename T>
T len3(V3<T> a) {
    return std::sqrt(dot3(a, a));
}
template <typename T>
V3<T> norm3(V3<T> a) {
    return (1 / len3(a)) * a;
}
template <typename T>
T dist3(V3<T> a, V3<T> b) {
    return len3(a - b);
}

inline D3 ToD(const lrt::Point3f &p) { return D3(p.x, p.y, p.z); }
inline D3 ToD(const lrt::Vector3f &v) { return D3(v.x, v.y, v.z); }
inline D3 ToD(const lrt::Normal3f &n) { return D3(n.x, n.y, n.z); }
template <typename T>
lrt::Point3f ToP(V3<T> a) {
    return lrt::Point3f(lrt::Float(a.x), lrt::Float(a.y), lrt::Float(a.z));
}
template <typename T>
lrt::Vector3f ToV(V3<T> a) {
    return lrt::Vector3f(lrt::Float(a.x), lrt::Float(a.y), lrt::Float(a.z));
}

// Rounds a double to the nearest Float. The volatile keeps GCC 12.2 at -O2
// from folding two adjacent float truncations and extensions into a no-op
// when its SLP vectorizer combines them (a miscompilation observed with
// Debian's g++ 12.2.0).
inline double ToFloat(double x) {
    volatile lrt::Float f = lrt::Float(x);
    return f;
}

const double kPi = 3.14159265358979323846;
const double eps = (double)lrt::MachineEpsilon;

struct Rng {
    std::mt19937_64 g;
    explicit Rng(uint64_t seed) : g(seed) {}
    double U(double a = 0, double b = 1) {
        return std::uniform_real_distribution<double>(a, b)(g);
    }
    D3 Dir() {
        double z = U(-1, 1), phi = U(0, 2 * kPi), s = std::sqrt(1 - z * z);
        return D3(s * std::cos(phi), s * std::sin(phi), z);
    }
    D3 InBall(double r) { return (r * std::cbrt(U())) * Dir(); }
};

// An affine transformation M = T * R * S in double precision, with its
// inverse written down from the factors.
struct Affine {
    double m[3][4], inv[3][4];
    bool mirror = false;
    double norm = 1;  // largest scale factor of the linear part
    double cond = 1;  // largest over smallest scale factor
    double minScale = 1;
    static Affine Make(D3 scale, D3 axis, double angleDeg, D3 translate) {
        Affine a;
        D3 k = norm3(axis);
        double th = angleDeg * kPi / 180, c = std::cos(th), s = std::sin(th);
        double R[3][3] = {
            {c + k.x * k.x * (1 - c), k.x * k.y * (1 - c) - k.z * s,
             k.x * k.z * (1 - c) + k.y * s},
            {k.y * k.x * (1 - c) + k.z * s, c + k.y * k.y * (1 - c),
             k.y * k.z * (1 - c) - k.x * s},
            {k.z * k.x * (1 - c) - k.y * s, k.z * k.y * (1 - c) + k.x * s,
             c + k.z * k.z * (1 - c)}};
        for (int i = 0; i < 3; ++i) {
            for (int j = 0; j < 3; ++j) {
                a.m[i][j] = R[i][j] * scale[j];
                a.inv[i][j] = R[j][i] / scale[i];
            }
            a.m[i][3] = translate[i];
        }
        for (int i = 0; i < 3; ++i)
            a.inv[i][3] = -(a.inv[i][0] * translate.x +
                            a.inv[i][1] * translate.y +
                            a.inv[i][2] * translate.z);
        a.mirror = scale.x * scale.y * scale.z < 0;
        a.norm = std::max({std::abs(scale.x), std::abs(scale.y),
                           std::abs(scale.z)});
        a.minScale = std::min({std::abs(scale.x), std::abs(scale.y),
                               std::abs(scale.z)});
        a.cond = a.norm / a.minScale;
        return a;
    }
    D3 Point(D3 p) const { return Apply(m, p, 1); }
    D3 Vector(D3 v) const { return Apply(m, v, 0); }
    D3 InvPoint(D3 p) const { return Apply(inv, p, 0 + 1); }
    D3 InvVector(D3 v) const { return Apply(inv, v, 0); }
    D3 Normal(D3 n) const {  // inverse transpose
        return D3(inv[0][0] * n.x + inv[1][0] * n.y + inv[2][0] * n.z,
                  inv[0][1] * n.x + inv[1][1] * n.y + inv[2][1] * n.z,
                  inv[0][2] * n.x + inv[1][2] * n.y + inv[2][2] * n.z);
    }
    static D3 Apply(const double a[3][4], D3 p, double w) {
        return D3(a[0][0] * p.x + a[0][1] * p.y + a[0][2] * p.z + a[0][3] * w,
                  a[1][0] * p.x + a[1][1] * p.y + a[1][2] * p.z + a[1][3] * w,
                  a[2][0] * p.x + a[2][1] * p.y + a[2][2] * p.z + a[2][3] * w);
    }
    lrt::Transform ToTransform() const {
        lrt::Matrix4x4 mm, mi;
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 4; ++j) {
                mm.m[i][j] = lrt::Float(m[i][j]);
                mi.m[i][j] = lrt::Float(inv[i][j]);
            }
        return lrt::Transform(mm, mi);
    }
};

const LD kEps = (LD)lrt::MachineEpsilon;
inline LD Gamma(int n) { return n * kEps / (1 - n * kEps); }

// The object-space ray of a Float world ray, and the bounds e and g on the
// rounding errors of its origin and direction that the transformation
// computes (@eq:point-error of Chapter 2), evaluated independently here.
struct ObjectRay {
    L3 o, d, e, g;
};

inline ObjectRay ToObject(const lrt::Transform &w2o, const lrt::Ray &r) {
    const lrt::Matrix4x4 &m = w2o.GetMatrix();
    LD o[3] = {r.o.x, r.o.y, r.o.z}, d[3] = {r.d.x, r.d.y, r.d.z};
    LD ro[3], rd[3], e[3], g[3];
    for (int i = 0; i < 3; ++i) {
        ro[i] = m.m[i][3];
        rd[i] = 0;
        e[i] = std::abs((LD)m.m[i][3]);
        g[i] = 0;
        for (int j = 0; j < 3; ++j) {
            ro[i] += (LD)m.m[i][j] * o[j];
            rd[i] += (LD)m.m[i][j] * d[j];
            e[i] += std::abs((LD)m.m[i][j] * o[j]);
            g[i] += std::abs((LD)m.m[i][j] * d[j]);
        }
        e[i] *= Gamma(3);
        g[i] *= Gamma(3);
    }
    ObjectRay res;
    res.o = L3(ro[0], ro[1], ro[2]);
    res.d = L3(rd[0], rd[1], rd[2]);
    res.e = L3(e[0], e[1], e[2]);
    res.g = L3(g[0], g[1], g[2]);
    return res;
}

// Does the box p +- e contain a point of the surface f = 0? The surface is
// nearly flat at the scale of the box, so it suffices that f changes sign
// (or vanishes) over the box's corners; where it may not be (the apex of a
// cone), n > 1 samples the box on a grid of n + 1 points a side.
template <typename F>
bool BoxStraddles(D3 p, D3 e, F f, int n = 1) {
    LD lo = std::numeric_limits<LD>::infinity(), hi = -lo;
    for (int i = 0; i <= n; ++i)
        for (int j = 0; j <= n; ++j)
            for (int k = 0; k <= n; ++k) {
                LD x = (LD)p.x + (LD)e.x * (2 * i - n) / n;
                LD y = (LD)p.y + (LD)e.y * (2 * j - n) / n;
                LD z = (LD)p.z + (LD)e.z * (2 * k - n) / n;
                LD v = f(x, y, z);
                lo = std::min(lo, v);
                hi = std::max(hi, v);
            }
    return lo <= 0 && hi >= 0;
}

}  // namespace
