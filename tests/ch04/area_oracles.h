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
// - the same quadrature, nested, of the area element |dp/du x dp/dv| of a
//   parametric surface, for chapter 3's quadrics in their (u, v)
//   parametrizations;
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
#include <utility>

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

// The cylinder's profile as the graph rho = r, t = z.
template <typename T>
Profile<T> CylinderProfile(T r) {
    return [r](T z) { return ProfilePoint<T>{r, z, 0, 1}; };
}

// The cone's profile as the graph rho = r (1 - z / h), t = z.
template <typename T>
Profile<T> ConeProfile(T r, T h) {
    return [r, h](T z) { return ProfilePoint<T>{r * (1 - z / h), z, -r / h, 1}; };
}

// The paraboloid x^2 + y^2 = r^2 z / zMax: its profile as the graph
// rho = r sqrt(z / zMax) (t = z; the slope is infinite at the tip), and by
// the distance from the axis, z = zMax rho^2 / r^2 (t = rho).
template <typename T>
Profile<T> ParaboloidGraphProfile(T r, T zMax) {
    return [r, zMax](T z) {
        T f = r * std::sqrt(z / zMax);
        return ProfilePoint<T>{f, z, r / (2 * std::sqrt(z * zMax)), 1};
    };
}
template <typename T>
Profile<T> ParaboloidRadialProfile(T r, T zMax) {
    return [r, zMax](T rho) {
        return ProfilePoint<T>{rho, zMax * rho * rho / (r * r), 1,
                               2 * zMax * rho / (r * r)};
    };
}

// The hyperboloid swept by the segment from (x1, y1, z1) to (x2, y2, z2):
// its profile as the graph rho(z) = |(x, y)| of the segment's point at the
// height z (which must differ at the two ends).
template <typename T>
Profile<T> HyperboloidGraphProfile(T x1, T y1, T z1, T x2, T y2, T z2) {
    return [=](T z) {
        T s = (z - z1) / (z2 - z1);
        T x = x1 + s * (x2 - x1), y = y1 + s * (y2 - y1);
        T dx = (x2 - x1) / (z2 - z1), dy = (y2 - y1) / (z2 - z1);
        T rho = std::sqrt(x * x + y * y);
        return ProfilePoint<T>{rho, z, (x * dx + y * dy) / rho, 1};
    };
}

// The same profile parametrized along the segment, t in [0, 1]: exact for
// bands so thin that heights between their ends are not representable.
template <typename T>
Profile<T> HyperboloidSegmentProfile(T x1, T y1, T z1, T x2, T y2, T z2) {
    return [=](T t) {
        T x = x1 + t * (x2 - x1), y = y1 + t * (y2 - y1);
        T rho = std::sqrt(x * x + y * y);
        return ProfilePoint<T>{rho, z1 + t * (z2 - z1),
                               (x * (x2 - x1) + y * (y2 - y1)) / rho,
                               z2 - z1};
    };
}

// ---------------------------------------------------------------------------
// Parametric surfaces

// A point of a parametric surface p(u, v) with its partial derivatives.
template <typename T>
struct SurfacePoint {
    T p[3], dpdu[3], dpdv[3];
};
template <typename T>
using Surface = std::function<SurfacePoint<T>(T u, T v)>;

// The area element |dp/du x dp/dv|.
template <typename T>
T AreaElement(const SurfacePoint<T> &s) {
    const T *a = s.dpdu, *b = s.dpdv;
    T c0 = a[1] * b[2] - a[2] * b[1], c1 = a[2] * b[0] - a[0] * b[2],
      c2 = a[0] * b[1] - a[1] * b[0];
    return std::sqrt(c0 * c0 + c1 * c1 + c2 * c2);
}

// The area of the surface over [0, 1]^2 in (u, v): the integral over u of
// the integral over v of the area element. The inner integral is split at
// vSplit, if it lies inside (0, 1), where the area element has a kink (a
// cone's apex inside the segment that sweeps a hyperboloid).
template <typename T>
Integral<T> ParametricArea(const Surface<T> &surface, T relTol,
                           T vSplit = -1) {
    bool converged = true;
    Integral<T> outer = Integrate<T>(
        [&](T u) {
            Integrand<T> element = [&](T v) {
                return AreaElement(surface(u, v));
            };
            bool split = vSplit > 0 && vSplit < 1;
            T ends[3] = {0, split ? vSplit : T(1), 1};
            T value = 0;
            for (int i = 0; i < (split ? 2 : 1); ++i) {
                Integral<T> inner =
                    Integrate<T>(element, ends[i], ends[i + 1], relTol);
                converged = converged && inner.converged;
                value += inner.value;
            }
            return value;
        },
        0, 1, relTol);
    return {outer.value, converged && outer.converged};
}

// The (u, v) parametrizations of chapter 3's quadrics, phi = u phiMax.
template <typename T>
SurfacePoint<T> Revolve(T phiMax, T u, T x, T y, T z, T dx, T dy, T dz) {
    // The point (x, y, z) of the profile at phi = 0 and its v-derivative,
    // turned by phi about z; d/du turns it by a right angle and scales by
    // phiMax.
    T c = std::cos(u * phiMax), s = std::sin(u * phiMax);
    T px = c * x - s * y, py = s * x + c * y;
    return SurfacePoint<T>{{px, py, z},
                           {-phiMax * py, phiMax * px, 0},
                           {c * dx - s * dy, s * dx + c * dy, dz}};
}

template <typename T>
Surface<T> CylinderSurface(T r, T zMin, T zMax, T phiMax) {
    return [=](T u, T v) {
        return Revolve<T>(phiMax, u, r, 0, zMin + v * (zMax - zMin), 0, 0,
                          zMax - zMin);
    };
}

template <typename T>
Surface<T> ConeSurface(T r, T h, T phiMax) {
    return [=](T u, T v) {
        return Revolve<T>(phiMax, u, r * (1 - v), 0, v * h, -r, 0, h);
    };
}

template <typename T>
Surface<T> ParaboloidSurface(T r, T zMin, T zMax, T phiMax) {
    return [=](T u, T v) {
        T z = zMin + v * (zMax - zMin), rho = r * std::sqrt(z / zMax);
        return Revolve<T>(phiMax, u, rho, 0, z,
                          (zMax - zMin) * rho / (2 * z), 0, zMax - zMin);
    };
}

template <typename T>
Surface<T> HyperboloidSurface(T x1, T y1, T z1, T x2, T y2, T z2,
                              T phiMax) {
    return [=](T u, T v) {
        return Revolve<T>(phiMax, u, x1 + v * (x2 - x1), y1 + v * (y2 - y1),
                          z1 + v * (z2 - z1), x2 - x1, y2 - y1, z2 - z1);
    };
}

// Where the segment's projection onto the xy plane passes nearest the
// origin, as a parameter along the segment (-1 for a vertical segment).
template <typename T>
T NearestToAxis(T x1, T y1, T x2, T y2) {
    T dx = x2 - x1, dy = y2 - y1, d2 = dx * dx + dy * dy;
    return d2 > 0 ? -(x1 * dx + y1 * dy) / d2 : T(-1);
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
