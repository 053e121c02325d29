// Chapter 4's oracles for areas, shared by its tests. None of them uses the
// area formulas that the chapter derives for its shapes:
//
// - adaptive Gauss-Kronrod quadrature of the surface-of-revolution integral
//
//       A = phiMax * integral of rho(t) * sqrt(rho'(t)^2 + z'(t)^2) dt
//
//   for a profile curve given with its derivatives, in any floating-point
//   type (double, or long double where a reference must be far more precise
//   than Float);
// - a triangle's area from its three side lengths (Kahan's stable form of
//   Heron's formula), for well-shaped triangles;
// - a triangle's area from the areas of its projections onto the coordinate
//   planes (the shoelace formula, in exact arithmetic), for any triangle.

#ifndef LRT_TESTS_CH04_AREA_ORACLES_H
#define LRT_TESTS_CH04_AREA_ORACLES_H

#include "lrt/core/base.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <queue>

namespace area_oracles {

// ---------------------------------------------------------------------------
// Quadrature

// Gauss-Kronrod 7-15 rule on [-1, 1] (the constants of QUADPACK's qk15).
// kXgk holds the Kronrod nodes in decreasing order; the odd-numbered ones
// and 0 are the 7-point Gauss nodes, with the weights kWg.
constexpr long double kXgk[8] = {
    0.991455371120812639206854697526329L, 0.949107912342758524526189684047851L,
    0.864864423359769072789712788640926L, 0.741531185599394439863864773280788L,
    0.586087235467691130294144845693013L, 0.405845151377397166906606412076961L,
    0.207784955007898467600689403773245L, 0.0L};
constexpr long double kWgk[8] = {
    0.022935322010529224963732008058970L, 0.063092092629978553290700663189204L,
    0.104790010322250183839876322541518L, 0.140653259715525918745189590510238L,
    0.169004726639267902826583426598550L, 0.190350578064785409913256402421014L,
    0.204432940075298892414161999234649L, 0.209482141084727828012999174891714L};
constexpr long double kWg[4] = {
    0.129484966168869693270611432679082L, 0.279705391489276667901467771423780L,
    0.381830050505118944950369775488975L, 0.417959183673469387755102040816327L};

// Most bisections the adaptive integrator may make for one integral.
constexpr int kMaxBisections = 4000;

template <typename T>
using Integrand = std::function<T(T)>;

template <typename T>
struct Estimate {
    T value, error;
};

// One application of the 15-point rule on [a, b]; the error estimate is the
// difference between the Kronrod and the embedded Gauss result.
template <typename T>
Estimate<T> GaussKronrod15(const Integrand<T> &f, T a, T b) {
    T c = (a + b) / 2, h = (b - a) / 2;
    T fc = f(c);
    T kronrod = T(kWgk[7]) * fc, gauss = T(kWg[3]) * fc;
    for (int j = 0; j < 7; ++j) {
        T x = h * T(kXgk[j]);
        T sum = f(c - x) + f(c + x);
        kronrod += T(kWgk[j]) * sum;
        if (j % 2 == 1) gauss += T(kWg[j / 2]) * sum;
    }
    return {kronrod * h, std::abs((kronrod - gauss) * h)};
}

template <typename T>
struct Integral {
    T value;
    bool converged;
};

// Globally adaptive quadrature, as in QUADPACK: keep bisecting the piece
// with the largest error estimate until the estimates sum to at most relTol
// times the integral. The rule never evaluates f at a or b.
template <typename T>
Integral<T> Integrate(const Integrand<T> &f, T a, T b, T relTol) {
    struct Piece {
        T a, b;
        Estimate<T> est;
        bool operator<(const Piece &p) const { return est.error < p.est.error; }
    };
    std::priority_queue<Piece> pieces;
    pieces.push({a, b, GaussKronrod15(f, a, b)});
    T value = pieces.top().est.value, error = pieces.top().est.error;
    for (int i = 0; i < kMaxBisections; ++i) {
        if (error <= relTol * std::abs(value)) break;
        Piece p = pieces.top();
        pieces.pop();
        T m = (p.a + p.b) / 2;
        Piece left{p.a, m, GaussKronrod15(f, p.a, m)};
        Piece right{m, p.b, GaussKronrod15(f, m, p.b)};
        value += left.est.value + right.est.value - p.est.value;
        error += left.est.error + right.est.error - p.est.error;
        pieces.push(left);
        pieces.push(right);
    }
    // Sum the pieces afresh, so that the running updates leave no trace.
    T sum = 0, err = 0;
    for (; !pieces.empty(); pieces.pop()) {
        sum += pieces.top().est.value;
        err += pieces.top().est.error;
    }
    return {sum, err <= relTol * std::abs(sum)};
}

// A profile curve (rho(t), z(t)) with its derivatives.
template <typename T>
struct ProfilePoint {
    T rho, z, drho, dz;
};
template <typename T>
using Profile = std::function<ProfilePoint<T>(T)>;

// The surface-of-revolution integral for the profile over [t0, t1].
template <typename T>
Integral<T> RevolutionArea(const Profile<T> &profile, T t0, T t1, T phiMax,
                           T relTol) {
    Integral<T> in = Integrate<T>(
        [&](T t) {
            ProfilePoint<T> p = profile(t);
            return p.rho * std::sqrt(p.drho * p.drho + p.dz * p.dz);
        },
        t0, t1, relTol);
    return {phiMax * in.value, in.converged};
}

// The sphere's profile as the graph rho = f(z) = sqrt(r^2 - z^2), t = z.
template <typename T>
Profile<T> SphereGraphProfile(T r) {
    return [r](T z) {
        T q = (r - z) * (r + z);
        T f = std::sqrt(q);
        return ProfilePoint<T>{f, z, -z / f, 1};
    };
}

// The sphere's profile by polar angle: rho = r sin t, z = r cos t.
template <typename T>
Profile<T> SpherePolarProfile(T r) {
    return [r](T t) {
        return ProfilePoint<T>{r * std::sin(t), r * std::cos(t),
                               r * std::cos(t), -r * std::sin(t)};
    };
}

// The disk's profile by distance from the axis: rho = t, z = h.
template <typename T>
Profile<T> DiskProfile(T h) {
    return [h](T t) { return ProfilePoint<T>{t, h, 1, 0}; };
}

// The circle that sweeps a torus: center distance R, tube radius r.
template <typename T>
Profile<T> TorusProfile(T R, T r) {
    return [R, r](T t) {
        return ProfilePoint<T>{R + r * std::cos(t), r * std::sin(t),
                               -r * std::sin(t), r * std::cos(t)};
    };
}

// ---------------------------------------------------------------------------
// Triangles

// Kahan's stable form of Heron's formula: the area of a triangle from its
// side lengths, in any order. It is accurate for the given lengths; but the
// area of a needle depends so strongly on them that rounded lengths make it
// a reference for well-shaped triangles only.
template <typename T>
T HeronArea(T s0, T s1, T s2) {
    T s[3] = {s0, s1, s2};
    std::sort(s, s + 3);
    T c = s[0], b = s[1], a = s[2];  // a >= b >= c
    // The lengths of a degenerate triangle, rounded, may break the triangle
    // inequality (c < a - b) by a rounding error: its area is then 0.
    T product = (a + (b + c)) * (c - (a - b)) * (c + (a - b)) * (a + (b - c));
    return std::sqrt(std::max(product, T(0))) / 4;
}

// The same, for the triangle p0 p1 p2 with its side lengths in T.
template <typename T>
T HeronArea(const lrt::Point3f &p0, const lrt::Point3f &p1,
            const lrt::Point3f &p2) {
    auto side = [](const lrt::Point3f &p, const lrt::Point3f &q) {
        T dx = T(p.x) - T(q.x), dy = T(p.y) - T(q.y), dz = T(p.z) - T(q.z);
        return std::sqrt(dx * dx + dy * dy + dz * dz);
    };
    return HeronArea(side(p0, p1), side(p1, p2), side(p2, p0));
}

// Arithmetic in which the products of two Float coordinates are exact, and
// sums of a few of them lose nothing that matters: binary128 where the
// compiler offers it (113 bits), else long double (64 bits, enough for
// Float = float).
#if defined(__SIZEOF_FLOAT128__)
using Exact = __float128;
#else
using Exact = long double;
#endif

// Twice the signed area of the projection of p0 p1 p2 onto the plane of the
// coordinates i and j, by the shoelace formula, exactly.
inline long double TwiceProjectedArea(const lrt::Point3f &p0,
                                      const lrt::Point3f &p1,
                                      const lrt::Point3f &p2, int i, int j) {
    const lrt::Point3f *p[3] = {&p0, &p1, &p2};
    Exact sum = 0;
    for (int k = 0; k < 3; ++k) {
        const lrt::Point3f &a = *p[k], &b = *p[(k + 1) % 3];
        sum += Exact(a[i]) * Exact(b[j]) - Exact(b[i]) * Exact(a[j]);
    }
    return (long double)(sum);
}

// The area of the triangle p0 p1 p2 in long double, for any triangle: the
// square of a plane figure's area is the sum of the squares of the areas of
// its projections onto the three coordinate planes.
inline long double ProjectionArea(const lrt::Point3f &p0,
                                  const lrt::Point3f &p1,
                                  const lrt::Point3f &p2) {
    long double yz = TwiceProjectedArea(p0, p1, p2, 1, 2),
                zx = TwiceProjectedArea(p0, p1, p2, 2, 0),
                xy = TwiceProjectedArea(p0, p1, p2, 0, 1);
    return std::sqrt(yz * yz + zx * zx + xy * xy) / 2;
}

}  // namespace area_oracles

#endif  // LRT_TESTS_CH04_AREA_ORACLES_H
