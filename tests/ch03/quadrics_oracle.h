// The long-double oracle and the test harness that test_cylinder.cpp,
// test_cone.cpp, test_paraboloid.cpp and test_hyperboloid.cpp share.
//
// All four shapes are surfaces of revolution about the z axis whose squared
// distance from the axis is a quadratic in z,
//
//     x^2 + y^2 = Q(z) = |La + (z - zr) Lb|^2 + c z,
//
// with two-vectors La, Lb: the cylinder has a constant L (its radius), the
// cone an L that shrinks linearly to zero at the apex, the paraboloid L = 0
// and c > 0, and the hyperboloid L(z) = the (x, y) part of the point of its
// segment at height z. Along a line o + t d the implicit function
// x^2 + y^2 - Q(z) is a quadratic in t whose coefficients follow directly,
// and the oracle solves it in long double. Its parameterization of each
// surface (u, v) -> P, and the unit normal as a function of (u, v), are
// written from the shapes' definitions, not from the library's formulas:
// the partial derivatives of P are differentiated by hand here, those of
// the unit normal by central differences in long double.
//
// The oracle also estimates how far a correct Float computation may place
// a hit along the ray (rounding of the quadratic's terms, of order epsilon
// times their magnitude, over the quadratic's slope at the root, plus the
// rounding of the world-to-object transformation), and flags rays whose
// hit-or-miss decision or choice of root could go either way within that
// distance: nearly tangent rays, hits near a cut edge (z range or phi),
// roots near t = 0 or tMax. Disagreements on flagged rays are counted (the
// "band misses") and bounded; any other disagreement fails.
//
// The shapes' Intersect() and IntersectP() depend on exercise ex-3.25 (the
// quadric's quadratic): the tests that intersect reach them only through
// the exercise call IntersectQuadric() (exercise_calls.h), in suites
// Ex3_25_<Shape>, with calls::Seed() and calls::Cases(); the tests that
// only construct shapes (bad input, bounds) construct them directly.
#pragma once

#include "lrt/shapes/cone.h"
#include "lrt/shapes/cylinder.h"
#include "lrt/shapes/hyperboloid.h"
#include "lrt/shapes/paraboloid.h"

#include <gtest/gtest.h>

#include "exercise_calls.h"
#include "quadric_oracle.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

// Width of the ambiguity bands, in units of Float's machine epsilon (as the
// sphere's and the disk's tests).
constexpr double kQBand = 256;
// The rounding of a correct computation's arithmetic, in units of epsilon
// times the magnitude of what it rounds (a few operations deep).
constexpr double kQAlg = 32;
// Largest tolerated number of band misses per 100,000 rays that are not
// aimed at a silhouette.
constexpr long kQMaxBandMissesPer100k = 50;

const LD kPiL = 3.14159265358979323846264338327950288L;

enum class QKind { Cylinder, Cone, Paraboloid, Hyperboloid };

// A shape's constructor arguments (before rounding to Float).
struct QuadricDef {
    QKind kind;
    // Cylinder: radius, zMin, zMax. Cone: height, radius. Paraboloid:
    // radius, z0, z1. Hyperboloid: p1, p2.
    double a = 0, b = 0, c = 0;
    D3 p1, p2;
    double phiMaxDeg = 360;
    std::string name;
};

inline QuadricDef CylinderDef(double r, double zMin, double zMax, double phi,
                              std::string name) {
    QuadricDef d{QKind::Cylinder, r, zMin, zMax, D3(), D3(), phi, name};
    return d;
}
inline QuadricDef ConeDef(double h, double r, double phi, std::string name) {
    QuadricDef d{QKind::Cone, h, r, 0, D3(), D3(), phi, name};
    return d;
}
inline QuadricDef ParaboloidDef(double r, double z0, double z1, double phi,
                                std::string name) {
    QuadricDef d{QKind::Paraboloid, r, z0, z1, D3(), D3(), phi, name};
    return d;
}
inline QuadricDef HyperboloidDef(D3 p1, D3 p2, double phi, std::string name) {
    QuadricDef d{QKind::Hyperboloid, 0, 0, 0, p1, p2, phi, name};
    return d;
}

inline lrt::Float F(double x) { return lrt::Float(x); }

inline std::unique_ptr<lrt::Shape> MakeShape(const QuadricDef &d,
                                             const lrt::Transform *o2w,
                                             const lrt::Transform *w2o,
                                             bool ro) {
    switch (d.kind) {
    case QKind::Cylinder:
        return std::make_unique<lrt::Cylinder>(o2w, w2o, ro, F(d.a), F(d.b),
                                               F(d.c), F(d.phiMaxDeg));
    case QKind::Cone:
        return std::make_unique<lrt::Cone>(o2w, w2o, ro, F(d.a), F(d.b),
                                           F(d.phiMaxDeg));
    case QKind::Paraboloid:
        return std::make_unique<lrt::Paraboloid>(o2w, w2o, ro, F(d.a), F(d.b),
                                                 F(d.c), F(d.phiMaxDeg));
    case QKind::Hyperboloid:
        return std::make_unique<lrt::Hyperboloid>(o2w, w2o, ro, ToP(d.p1),
                                                  ToP(d.p2), F(d.phiMaxDeg));
    }
    return nullptr;
}

// A shape as the exercise call builds it: its parameters, and the inverse
// of its transformation as the call computes it (Inverse()).
struct QTarget {
    lrt::QuadricSpec spec;
    lrt::Transform w2o;
};
inline QTarget Target(const QuadricDef &d, const lrt::Transform &o2w,
                      bool ro) {
    QTarget t;
    lrt::QuadricSpec &q = t.spec;
    switch (d.kind) {
    case QKind::Cylinder:
        q.kind = lrt::kCylinder;
        q.radius = F(d.a), q.zMin = F(d.b), q.zMax = F(d.c);
        break;
    case QKind::Cone:
        q.kind = lrt::kCone;
        q.height = F(d.a), q.radius = F(d.b);
        break;
    case QKind::Paraboloid:
        q.kind = lrt::kParaboloid;
        q.radius = F(d.a), q.zMin = F(d.b), q.zMax = F(d.c);
        break;
    case QKind::Hyperboloid:
        q.kind = lrt::kHyperboloid;
        q.p1 = ToP(d.p1), q.p2 = ToP(d.p2);
        break;
    }
    q.phiMax = F(d.phiMaxDeg);
    q.objectToWorld = o2w;
    q.reverseOrientation = ro;
    t.w2o = Inverse(o2w);
    return t;
}
// One ray against the shape, through the exercise call; tHit is what the
// call passes to Intersect(), which a miss must leave alone.
inline lrt::ShapeHit Ask(const QTarget &t, const lrt::Ray &r,
                         lrt::Float tHit = -1) {
    return lrt::ex::IntersectQuadric(t.spec, r, tHit);
}

// The surface in long double, from the parameters rounded to Float as the
// shape receives them.
struct Geom {
    QKind kind;
    LD phiMax = 0;
    LD zLo = 0, zHi = 0;   // the z range of the surface
    bool cutLo = true, cutHi = true, cutPhi = false;
    LD r = 0, h = 0;       // radius (cylinder, cone, paraboloid), height
    L3 p1, p2;             // the hyperboloid's segment
    LD Lax = 0, Lay = 0, Lbx = 0, Lby = 0, zr = 0, c = 0;  // Q(z), see above
    LD rRef = 0;           // largest distance of the surface from the axis
    bool hasApex = false;  // a cone's apex, where the surface is not flat
    L3 apex;

    explicit Geom(const QuadricDef &d) : kind(d.kind) {
        double deg = std::clamp(d.phiMaxDeg, 0.0, 360.0);
        phiMax = deg >= 360 ? 2 * kPiL : (LD)deg * kPiL / 180;
        cutPhi = deg < 360;
        switch (kind) {
        case QKind::Cylinder: {
            r = ToFloat(d.a);
            LD z0 = ToFloat(d.b), z1 = ToFloat(d.c);
            zLo = std::min(z0, z1);
            zHi = std::max(z0, z1);
            Lax = r;
            rRef = r;
            break;
        }
        case QKind::Cone:
            h = ToFloat(d.a);
            r = ToFloat(d.b);
            zLo = 0;
            zHi = h;
            Lbx = -r / h;
            zr = h;
            rRef = r;
            hasApex = true;
            apex = L3(0, 0, h);
            break;
        case QKind::Paraboloid: {
            r = ToFloat(d.a);
            LD z0 = ToFloat(d.b), z1 = ToFloat(d.c);
            zHi = std::max(z0, z1);
            zLo = std::max(std::min(z0, z1), (LD)0);
            cutLo = zLo > 0;  // below z = 0 there is no surface to cut
            c = r * r / zHi;
            rRef = r;
            break;
        }
        case QKind::Hyperboloid: {
            p1 = L3(ToFloat(d.p1.x), ToFloat(d.p1.y), ToFloat(d.p1.z));
            p2 = L3(ToFloat(d.p2.x), ToFloat(d.p2.y), ToFloat(d.p2.z));
            zLo = std::min(p1.z, p2.z);
            zHi = std::max(p1.z, p2.z);
            Lax = p1.x;
            Lay = p1.y;
            Lbx = (p2.x - p1.x) / (p2.z - p1.z);
            Lby = (p2.y - p1.y) / (p2.z - p1.z);
            zr = p1.z;
            rRef = std::max(std::hypot(p1.x, p1.y), std::hypot(p2.x, p2.y));
            // Where the segment's line meets the axis, if it does.
            L3 e = p2 - p1;
            LD b2 = e.x * e.x + e.y * e.y;
            if (b2 > 0) {
                LD v = -(p1.x * e.x + p1.y * e.y) / b2;
                L3 q = p1 + v * e;
                if (std::hypot(q.x, q.y) <= 1e-9L * rRef) {
                    hasApex = true;
                    apex = L3(0, 0, q.z);
                }
            }
            break;
        }
        }
    }
    LD Height() const { return zHi - zLo; }
    // Is the point (of the surface of revolution) on the shape?
    bool Contains(L3 p) const;
    // Whether p lies within distance tol of the part that the cuts keep: a
    // point that rounding may carry across a cut.
    bool ContainsWithin(L3 p, LD tol) const;
    // Q(z), its derivative, and the magnitude of its terms.
    LD Q(LD z) const {
        LD lx = Lax + (z - zr) * Lbx, ly = Lay + (z - zr) * Lby;
        return lx * lx + ly * ly + c * z;
    }
    LD dQ(LD z) const {
        LD lx = Lax + (z - zr) * Lbx, ly = Lay + (z - zr) * Lby;
        return 2 * (lx * Lbx + ly * Lby) + c;
    }
    LD Implicit(LD x, LD y, LD z) const { return x * x + y * y - Q(z); }
    L3 Gradient(L3 p) const { return L3(2 * p.x, 2 * p.y, -dQ(p.z)); }

    // The parameterization and its partial derivatives.
    L3 P(LD u, LD v) const {
        LD phi = u * phiMax, cp = std::cos(phi), sp = std::sin(phi);
        switch (kind) {
        case QKind::Cylinder:
            return L3(r * cp, r * sp, zLo + v * Height());
        case QKind::Cone:
            return L3(r * (1 - v) * cp, r * (1 - v) * sp, v * h);
        case QKind::Paraboloid: {
            LD z = zLo + v * Height();
            LD rho = r * std::sqrt(std::max(z, (LD)0) / zHi);
            return L3(rho * cp, rho * sp, z);
        }
        case QKind::Hyperboloid: {
            L3 q = p1 + v * (p2 - p1);
            return L3(q.x * cp - q.y * sp, q.x * sp + q.y * cp, q.z);
        }
        }
        return L3();
    }
    L3 Pu(LD u, LD v) const {
        L3 p = P(u, v);
        return L3(-phiMax * p.y, phiMax * p.x, 0);
    }
    L3 Pv(LD u, LD v) const {
        LD phi = u * phiMax, cp = std::cos(phi), sp = std::sin(phi);
        switch (kind) {
        case QKind::Cylinder:
            return L3(0, 0, Height());
        case QKind::Cone:
            return L3(-r * cp, -r * sp, h);
        case QKind::Paraboloid: {
            LD H = Height(), z = zLo + v * H;
            LD dr = r * H / (2 * std::sqrt(z * zHi));
            return L3(dr * cp, dr * sp, H);
        }
        case QKind::Hyperboloid: {
            L3 e = p2 - p1;
            return L3(e.x * cp - e.y * sp, e.x * sp + e.y * cp, e.z);
        }
        }
        return L3();
    }
    L3 N(LD u, LD v) const { return norm3(cross3(Pu(u, v), Pv(u, v))); }

    // (u, v) of a point of the surface, its distance rho from the axis, and
    // the rate dTheta/dz at which the angle from which phi is measured turns
    // with height (nonzero only for a hyperboloid).
    struct UV {
        LD u, v, phi, rho, dThetaDz;
    };
    UV ToUV(L3 p) const {
        UV res;
        res.rho = std::sqrt(p.x * p.x + p.y * p.y);
        res.dThetaDz = 0;
        LD phi;
        switch (kind) {
        case QKind::Cylinder:
        case QKind::Paraboloid:
            res.v = (p.z - zLo) / Height();
            phi = std::atan2(p.y, p.x);
            break;
        case QKind::Cone:
            res.v = p.z / h;
            phi = std::atan2(p.y, p.x);
            break;
        case QKind::Hyperboloid:
        default: {
            res.v = (p.z - p1.z) / (p2.z - p1.z);
            L3 q = p1 + res.v * (p2 - p1);
            phi = std::atan2(q.x * p.y - q.y * p.x, q.x * p.x + q.y * p.y);
            LD q2 = q.x * q.x + q.y * q.y;
            L3 e = p2 - p1;
            if (q2 > 0)
                res.dThetaDz = std::abs((q.x * e.y - q.y * e.x) / q2 / e.z);
            else
                res.dThetaDz = std::numeric_limits<LD>::infinity();
            break;
        }
        }
        if (phi < 0) phi += 2 * kPiL;
        res.phi = phi;
        res.u = phi / phiMax;
        return res;
    }
};

inline bool Geom::Contains(L3 p) const {
    return !((cutLo && p.z < zLo) || (cutHi && p.z > zHi) ||
             ToUV(p).phi > phiMax);
}

inline bool Geom::ContainsWithin(L3 p, LD tol) const {
    if ((cutLo && p.z < zLo - tol) || (cutHi && p.z > zHi + tol)) return false;
    LD phi = ToUV(p).phi;
    if (phi <= phiMax) return true;
    // Past the cut: the distance to the nearer of the two half-planes that
    // bound the sector, phi = phiMax and phi = 0 (= 2 pi).
    const LD pi = 3.14159265358979323846264338327950288L;
    LD past = std::min(phi - phiMax, 2 * pi - phi);
    LD rho = std::hypot(p.x, p.y);
    return (past >= pi / 2 ? rho : rho * std::sin(past)) <= tol;
}

// The unit normal and its partial derivatives, by central differences of
// N(u, v) in long double.
struct Local {
    L3 p, n, dpdu, dpdv, dndu, dndv;
    bool ok = false;
};
inline Local LocalAt(const Geom &g, LD u, LD v) {
    Local l;
    l.p = g.P(u, v);
    l.dpdu = g.Pu(u, v);
    l.dpdv = g.Pv(u, v);
    l.n = g.N(u, v);
    const LD hu = 1e-6L, hv = std::min((LD)1e-6L, std::abs(v) / 4);
    l.dndu = (1 / (2 * hu)) * (g.N(u + hu, v) - g.N(u - hu, v));
    l.dndv = (1 / (2 * hv)) * (g.N(u, v + hv) - g.N(u, v - hv));
    l.ok = hv > 0 && std::isfinite(len3(l.dndu)) &&
           std::isfinite(len3(l.dndv)) && std::isfinite(len3(l.n));
    return l;
}

// The oracle's answer for one ray.
struct QOracle {
    bool hit = false;
    bool ambiguous = false;  // hit or miss, or which root, may differ
    const char *why = "";    // the first reason it is ambiguous
    bool nearPole = false;   // close to the axis: derivatives not compared
    bool nearSeam = false;   // u may be 0 or 1
    bool farRoot = false;    // the nearer positive root was cut away
    LD t = 0, posErr = 0;    // posErr: possible error of the hit along the ray
    L3 p;
    Geom::UV uv{};
    void Ambiguous(const char *reason) {
        if (!ambiguous) why = reason;
        ambiguous = true;
    }
};

// The quadratic in t of the line o + t d, and the magnitude of its terms
// at t.
struct Quadratic {
    LD A, B, C;
};
inline Quadratic Coefficients(const Geom &g, L3 o, L3 d) {
    LD l0x = g.Lax + (o.z - g.zr) * g.Lbx, l0y = g.Lay + (o.z - g.zr) * g.Lby;
    LD l1x = d.z * g.Lbx, l1y = d.z * g.Lby;
    Quadratic q;
    q.A = d.x * d.x + d.y * d.y - (l1x * l1x + l1y * l1y);
    q.B = 2 * (o.x * d.x + o.y * d.y - (l0x * l1x + l0y * l1y)) - g.c * d.z;
    q.C = o.x * o.x + o.y * o.y - (l0x * l0x + l0y * l0y) - g.c * o.z;
    return q;
}
// The magnitude of the terms of x^2 + y^2 - Q(z) at the point p: what
// rounding the surface's own constants and the point's coordinates costs.
inline LD Magnitude(const Geom &g, L3 p) {
    LD l = std::hypot(g.Lax, g.Lay) +
           std::abs(p.z - g.zr) * std::hypot(g.Lbx, g.Lby);
    return p.x * p.x + p.y * p.y + l * l + std::abs(g.c * p.z) +
           g.rRef * g.rRef;
}

// The discriminant b^2 - 4ac, computed so that it stays accurate when
// those two terms nearly cancel (a line passing near an apex, or nearly
// tangent, far from its origin): then it is -4a times the quadratic's
// value at its vertex, evaluated at the vertex's point, where the terms of
// x^2 + y^2 - Q(z) are small.
inline LD Discriminant(const Geom &g, L3 o, L3 d, const Quadratic &q) {
    LD bb = q.B * q.B, ac4 = 4 * q.A * q.C;
    if (!(std::abs(ac4) > 0.5L * bb)) return bb - ac4;
    LD tv = -q.B / (2 * q.A);
    L3 p = o + tv * d;
    return -4 * q.A * g.Implicit(p.x, p.y, p.z);
}

// A root polished by Newton's method on x^2 + y^2 - Q(z) evaluated at the
// point o + t d (as long as that decreases the residual).
inline LD Refine(const Geom &g, L3 o, L3 d, LD t) {
    if (!std::isfinite(t)) return t;
    auto f = [&](LD s) {
        L3 p = o + s * d;
        return g.Implicit(p.x, p.y, p.z);
    };
    LD ft = f(t);
    for (int i = 0; i < 4 && ft != 0; ++i) {
        L3 p = o + t * d;
        LD slope = dot3(g.Gradient(p), d);
        if (!(slope != 0)) break;
        LD tn = t - ft / slope, fn = f(tn);
        if (!(std::abs(fn) < std::abs(ft))) break;
        t = tn;
        ft = fn;
    }
    return t;
}

// The roots of the line's quadratic, without any clipping.
inline std::vector<LD> ExactRoots(const Geom &g, const ObjectRay &ray) {
    Quadratic q = Coefficients(g, ray.o, ray.d);
    if (q.A == 0) {
        if (q.B == 0) return {};
        return {Refine(g, ray.o, ray.d, -q.C / q.B)};
    }
    LD disc = Discriminant(g, ray.o, ray.d, q);
    if (disc < 0) return {};
    LD s = std::sqrt(disc), qq = -0.5L * (q.B + (q.B < 0 ? -s : s));
    return {Refine(g, ray.o, ray.d, qq / q.A),
            Refine(g, ray.o, ray.d, qq != 0 ? q.C / qq : qq / q.A)};
}

inline QOracle Trace(const Geom &g, const ObjectRay &ray, LD tMax) {
    QOracle res;
    const L3 o = ray.o, d = ray.d;
    const LD dl = len3(d), el = len3(ray.e), gl = len3(ray.g);
    const LD eps = kEps;
    if (!(dl > 0)) return res;
    Quadratic q = Coefficients(g, o, d);
    // The error model of a correct Float computation, in three parts.
    // (1) The line moves by lineShift: the rounding of the origin and the
    // direction, in the transformation and in the computation (which
    // computes the discriminant from distances to the line, so that its
    // error is proportional to the distances involved, not to their
    // squares). Moving the line moves the hit along the ray by that over
    // the cosine of incidence, |grad F| |d| / |g'(t)|; so does the rounding
    // of the surface's own constants (tolG). These decide the tangent rays.
    const LD ol = len3(o);
    auto lineShift = [&](LD t) {
        return kQAlg * eps * (ol + std::abs(t) * dl) +
               (LD)kQBand * eps * g.rRef + 2 * (el + std::abs(t) * gl);
    };
    auto tolG = [&](LD t) {
        L3 p = o + t * d;
        return (LD)kQBand * eps * Magnitude(g, p) +
               len3(g.Gradient(p)) * lineShift(t);
    };
    auto moved = [&](LD t) {
        LD slope = std::abs(2 * q.A * t + q.B);
        return tolG(t) * dl / slope + lineShift(t);
    };
    // (2) The roots come from q = -(b + sign(b) sqrt(disc)) / 2 as q / a and
    // c / q, with a, b and c rounded to a relative epsilon of the
    // magnitudes of their terms: c's can be far larger than c itself when
    // the origin lies near the surface's (infinite) extension, far away.
    const LD l0x = g.Lax + (o.z - g.zr) * g.Lbx, l0y = g.Lay + (o.z - g.zr) * g.Lby;
    const LD l1x = d.z * g.Lbx, l1y = d.z * g.Lby;
    const LD Ma = d.x * d.x + d.y * d.y + l1x * l1x + l1y * l1y;
    const LD Mb = 2 * (std::abs(o.x * d.x) + std::abs(o.y * d.y) +
                       std::abs(l0x * l1x) + std::abs(l0y * l1y)) +
                  std::abs(g.c * d.z);
    const LD Mc = o.x * o.x + o.y * o.y + l0x * l0x + l0y * l0y +
                  std::abs(g.c * o.z) + g.rRef * g.rRef;
    LD roots[2], errs[2];
    int n = 0;
    if (q.A != 0) {
        LD disc = Discriminant(g, o, d, q);
        LD tv = -q.B / (2 * q.A);
        // A leading coefficient within rounding of zero (a ray along a line
        // of a cone or an asymptote of a hyperboloid) makes the far root's
        // sign uncertain, not the near root: the far one is then so far
        // away that it is cut whichever its sign. The vertex is as far, and
        // the discriminant, about b^2, is as accurate as its terms.
        const bool tinyA = std::abs(q.A) <= (LD)kQBand * eps * Ma;
        LD dDisc = tinyA ? kQAlg * eps * (Mb * Mb + 4 * Ma * Mc)
                         : 4 * std::abs(q.A) * tolG(tv);
        if (std::abs(disc) <= dDisc && (!tinyA || disc < 0))
            res.Ambiguous("nearly tangent");
        if (disc < 0) return res;
        LD s = std::sqrt(disc);
        LD qq = -0.5L * (q.B + (q.B < 0 ? -s : s));
        LD dq = kQAlg * eps * Mb + dDisc / (2 * s);
        LD ta = Refine(g, o, d, qq / q.A);
        LD tb = qq != 0 ? Refine(g, o, d, q.C / qq) : ta;
        LD ea = std::abs(ta) * (dq / std::abs(qq) + kQAlg * eps * Ma / std::abs(q.A));
        LD eb = (kQAlg * eps * Mc + std::abs(tb) * dq) / std::abs(qq);
        if (!(qq != 0)) eb = ea;
        // (3) All together, as a distance along the ray.
        ea = ea * dl + moved(ta);
        eb = eb * dl + moved(tb);
        const LD size = g.Height() + g.rRef;
        if (tinyA && std::abs(ta * d.z) > 10 * (std::abs(o.z) + size) &&
            std::abs(ta) > 10 * std::abs(tb)) {
            roots[0] = tb;
            errs[0] = eb;
            n = 1;
        } else {
            roots[0] = std::min(ta, tb);
            roots[1] = std::max(ta, tb);
            errs[0] = ta <= tb ? ea : eb;
            errs[1] = ta <= tb ? eb : ea;
            n = 2;
            if ((roots[1] - roots[0]) * dl <= errs[0] + errs[1])
                res.Ambiguous("roots closer than their errors");
        }
    } else if (q.B != 0) {
        roots[0] = Refine(g, o, d, -q.C / q.B);
        errs[0] = (kQAlg * eps * (Mc + std::abs(roots[0]) * Mb)) / std::abs(q.B) *
                      dl + moved(roots[0]);
        n = 1;
    } else {
        return res;  // the line runs along the surface or never meets it
    }
    bool cutBefore = false;
    for (int i = 0; i < n; ++i) {
        LD t = roots[i];
        if (!std::isfinite(t)) continue;
        LD pe = errs[i];
        if (std::abs(t) * dl <= pe) res.Ambiguous("a root near t = 0");
        if (!(t > 0)) continue;
        if (std::abs(t - tMax) * dl <= pe) res.Ambiguous("a root near tMax");
        if (t > tMax) break;
        L3 p = o + t * d;
        Geom::UV uv = g.ToUV(p);
        // The angle the hit may turn through within pe: along the circle,
        // and (hyperboloid) with the reference angle's turn with height.
        LD dPhi = pe / std::max(uv.rho, (LD)1e-300) + pe * uv.dThetaDz;
        if ((g.cutLo && std::abs(p.z - g.zLo) <= pe) ||
            (g.cutHi && std::abs(p.z - g.zHi) <= pe) ||
            (g.cutPhi && (std::abs(uv.phi - g.phiMax) <= dPhi ||
                          uv.phi <= dPhi || 2 * kPiL - uv.phi <= dPhi)))
            res.Ambiguous("a root near a cut edge");
        bool clipped = (g.cutLo && p.z < g.zLo) || (g.cutHi && p.z > g.zHi) ||
                       uv.phi > g.phiMax;
        if (clipped) {
            cutBefore = true;
            continue;
        }
        res.hit = true;
        res.t = t;
        res.p = p;
        res.uv = uv;
        res.posErr = pe;
        res.farRoot = cutBefore;
        res.nearPole = uv.rho <= 1e-2L * g.rRef;
        res.nearSeam = !g.cutPhi && (uv.phi <= dPhi || 2 * kPiL - uv.phi <= dPhi);
        return res;
    }
    return res;
}

// An affine transformation in long double: lrt's Float matrix and its
// inverse, computed here by cofactors.
struct LAffine {
    LD m[3][4], inv[3][4];
    LD norm = 1;     // Frobenius norm of the linear part (bounds its scale)
    LD invNorm = 1;  // that of the inverse: a world distance d is at most
                     // invNorm * d in object space
    bool mirror = false;
    explicit LAffine(const lrt::Transform &t) {
        const lrt::Matrix4x4 &M = t.GetMatrix();
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 4; ++j) m[i][j] = M.m[i][j];
        LD det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
                 m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
                 m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
        mirror = det < 0;
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) {
                int i1 = (j + 1) % 3, i2 = (j + 2) % 3;
                int j1 = (i + 1) % 3, j2 = (i + 2) % 3;
                inv[i][j] = (m[i1][j1] * m[i2][j2] - m[i1][j2] * m[i2][j1]) /
                            det;
            }
        for (int i = 0; i < 3; ++i)
            inv[i][3] = -(inv[i][0] * m[0][3] + inv[i][1] * m[1][3] +
                          inv[i][2] * m[2][3]);
        LD s = 0;
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) s += m[i][j] * m[i][j];
        norm = std::sqrt(s);
        LD si = 0;
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) si += inv[i][j] * inv[i][j];
        invNorm = std::sqrt(si);
    }
    static L3 Apply(const LD a[3][4], L3 p, LD w) {
        return L3(a[0][0] * p.x + a[0][1] * p.y + a[0][2] * p.z + a[0][3] * w,
                  a[1][0] * p.x + a[1][1] * p.y + a[1][2] * p.z + a[1][3] * w,
                  a[2][0] * p.x + a[2][1] * p.y + a[2][2] * p.z + a[2][3] * w);
    }
    L3 Point(L3 p) const { return Apply(m, p, 1); }
    L3 Vector(L3 v) const { return Apply(m, v, 0); }
    L3 InvPoint(L3 p) const { return Apply(inv, p, 1); }
    L3 Normal(L3 n) const {  // inverse transpose
        return L3(inv[0][0] * n.x + inv[1][0] * n.y + inv[2][0] * n.z,
                  inv[0][1] * n.x + inv[1][1] * n.y + inv[2][1] * n.z,
                  inv[0][2] * n.x + inv[1][2] * n.y + inv[2][2] * n.z);
    }
};

inline L3 ToL(const lrt::Point3f &p) { return L3(p.x, p.y, p.z); }
inline L3 ToL(const lrt::Vector3f &v) { return L3(v.x, v.y, v.z); }
inline L3 ToL(const lrt::Normal3f &n) { return L3(n.x, n.y, n.z); }
inline D3 ToD(L3 a) { return D3((double)a.x, (double)a.y, (double)a.z); }

inline std::string Str(L3 a) {
    char buf[160];
    std::snprintf(buf, sizeof(buf), "(%.9Lg, %.9Lg, %.9Lg)", a.x, a.y, a.z);
    return buf;
}

struct QStats {
    long rays = 0, hits = 0, ambiguous = 0, bandMisses = 0;
    long bandMissesAimed = 0, raysAimed = 0;  // rays not aimed at a silhouette
    long failures = 0, derivativeChecks = 0, farRootHits = 0;
    double worstTRel = 0, worstPRatio = 0, worstNAngle = 0;
    void Fail(const std::string &what) {
        if (++failures <= 10) ADD_FAILURE() << what;
    }
    void Add(const QStats &s) {
        rays += s.rays;
        hits += s.hits;
        ambiguous += s.ambiguous;
        bandMisses += s.bandMisses;
        bandMissesAimed += s.bandMissesAimed;
        raysAimed += s.raysAimed;
        failures += s.failures;
        derivativeChecks += s.derivativeChecks;
        farRootHits += s.farRootHits;
        worstTRel = std::max(worstTRel, s.worstTRel);
        worstPRatio = std::max(worstPRatio, s.worstPRatio);
        worstNAngle = std::max(worstNAngle, s.worstNAngle);
    }
};

inline void QReport(const std::string &what, const QStats &st) {
    std::printf("Quadric %s: %ld rays, %ld hits, worst |t| rel err %.3g, "
                "worst p err / pError %.3g, worst n angle %.3g, band misses "
                "%ld (%ld ambiguous rays; %ld hits on the far root, %ld "
                "derivative checks)\n",
                what.c_str(), st.rays, st.hits, st.worstTRel, st.worstPRatio,
                st.worstNAngle, st.bandMisses, st.ambiguous, st.farRootHits,
                st.derivativeChecks);
}

// The smallest s for which the box p +- s pError contains a point of the
// surface (world space, through the inverse of the shape's transformation):
// at most 1 if pError bounds the distance of p from the surface.
inline double PErrorRatio(const Geom &g, const LAffine &M, D3 p, D3 e) {
    auto f = [&](LD x, LD y, LD z) {
        L3 q = M.InvPoint(L3(x, y, z));
        return g.Implicit(q.x, q.y, q.z);
    };
    // Near an apex the surface is two nappes meeting at a point, which a
    // grid of samples can miss: a box that holds the apex holds a point of
    // the surface.
    // Where it curves tightly (a cone near its apex is thinner than the
    // box), the samples can all fall on one side; the segment through p
    // along the surface's normal, as far as the box reaches, finds the
    // nearest part of the surface.
    L3 apex = M.Point(g.apex);
    L3 pl(p.x, p.y, p.z);
    L3 nw = norm3(M.Normal(g.Gradient(M.InvPoint(pl))));
    auto straddles = [&](double s) {
        if (g.hasApex && std::abs(apex.x - p.x) <= s * e.x &&
            std::abs(apex.y - p.y) <= s * e.y &&
            std::abs(apex.z - p.z) <= s * e.z)
            return true;
        LD reach = std::numeric_limits<LD>::infinity();
        for (int i = 0; i < 3; ++i)
            if (nw[i] != 0) reach = std::min(reach, (LD)s * e[i] / std::abs(nw[i]));
        if (std::isfinite(reach)) {
            // Samples crowded near p: the segment may cross a thin part
            // of the surface twice.
            LD f0 = f(pl.x, pl.y, pl.z);
            for (int j = -16; j <= 16; ++j) {
                LD k = (LD)j / 16;
                L3 a = pl + (reach * k * k * k) * nw;
                if (f0 * f(a.x, a.y, a.z) <= 0) return true;
            }
        }
        return BoxStraddles(p, D3(s * e.x, s * e.y, s * e.z), f, 2);
    };
    if (straddles(0)) return 0;
    double lo = 0, hi = 1;
    while (!straddles(hi)) {
        lo = hi;
        hi *= 2;
        if (hi > 1e12) return hi;
    }
    for (int i = 0; i < 30; ++i) {
        double mid = 0.5 * (lo + hi);
        (straddles(mid) ? hi : lo) = mid;
    }
    return hi;
}

// Compares lrt's world-space answer with the oracle's object-space one,
// mapped through the shape's transformation M. Tolerances: a relative 1e-4
// plus twice what the quantity changes by when the hit moves by the
// oracle's posErr along the surface.
inline void QCompare(const Geom &g, const QOracle &orc, const ObjectRay &ob,
                     const LAffine &M, bool reverse, const lrt::ShapeHit &h,
                     const std::string &what, bool aimed, QStats &st) {
    const bool hit = h.hit;
    const lrt::Float tHit = h.tHit;
    const lrt::SurfaceHit &si = h.isect;
    ++st.rays;
    if (aimed) ++st.raysAimed;
    if (orc.ambiguous) ++st.ambiguous;
    auto where = [&]() {
        return what + " object ray o=" + Str(ob.o) + " d=" + Str(ob.d);
    };
    const LD dl = len3(ob.d);
    LD tTol = 4 * orc.posErr / dl + 1e-5L * orc.t;
    bool sameRoot = hit && orc.hit && std::abs(tHit - orc.t) <= tTol;
    if (hit != orc.hit || (hit && !sameRoot)) {
        if (orc.ambiguous) {
            ++st.bandMisses;
            if (aimed) ++st.bandMissesAimed;
        } else {
            st.Fail(where() + ": lrt " + (hit ? "hit" : "miss") + " t=" +
                    std::to_string(tHit) + ", oracle " +
                    (orc.hit ? "hit" : "miss") + " t=" +
                    std::to_string((double)orc.t) + " (tolerance " +
                    std::to_string((double)tTol) + ")");
        }
        return;
    }
    if (!hit) return;
    ++st.hits;
    // The error bound holds on every hit, ambiguous or not: the box
    // p +- pError contains a point of the surface.
    double ratio = PErrorRatio(g, M, ToD(si.p), ToD(si.pError));
    st.worstPRatio = std::max(st.worstPRatio, ratio);
    if (!(ratio <= 1))
        st.Fail(where() + ": the box p +- pError, p = " + Str(ToL(si.p)) +
                ", pError = " + Str(ToL(si.pError)) +
                ", misses the surface (needs " + std::to_string(ratio) +
                " pError); in object space p = " +
                Str(M.InvPoint(ToL(si.p))) + ", exact hit " +
                (orc.hit ? Str(orc.p) : std::string("none")));
    if (si.shapeIndex != 0) st.Fail(where() + ": the hit names no shape");
    // The normal's side of dpdu x dpdv follows the orientation and the
    // handedness of the transformation.
    bool flip = reverse != M.mirror;
    if (!((flip ? -1 : 1) *
              dot3(ToL(si.n), cross3(ToL(si.dpdu), ToL(si.dpdv))) > 0))
        st.Fail(where() + ": n " + Str(ToL(si.n)) + " on the wrong side of "
                "dpdu x dpdv");
    if (orc.ambiguous) return;
    if (orc.farRoot) ++st.farRootHits;
    st.worstTRel = std::max(st.worstTRel,
                            (double)(std::abs(tHit - orc.t) / orc.t));

    const LD sgn = reverse ? -1 : 1;
    const LD u = orc.uv.u, v = orc.uv.v;
    Local l = LocalAt(g, u, v);
    // Where the hit may lie: (u, v) moved by posErr along the surface.
    // (At a paraboloid's tip dpdv is infinite: no sensitivity known, no
    // constraint from it.)
    auto step = [&](L3 dp) {
        LD x = orc.posErr / std::max(len3(dp), (LD)1e-300);
        return x >= 0 ? std::min(x, (LD)0.5) : (LD)0.5;
    };
    LD du = step(l.dpdu), dv = step(l.dpdv);
    auto clampV = [&](LD x) {
        // The paraboloid's parameterization ends at its tip.
        return g.kind == QKind::Paraboloid && !g.cutLo ? std::max(x, (LD)1e-9)
                                                       : x;
    };
    Local nb[4] = {LocalAt(g, u + du, v), LocalAt(g, u - du, v),
                   LocalAt(g, u, clampV(v + dv)), LocalAt(g, u, clampV(v - dv))};
    auto envelope = [&](auto get) {
        LD e = 0;
        for (const Local &x : nb) e = std::max(e, len3(get(x) - get(l)));
        return e;
    };

    L3 pw = M.Point(orc.p);
    LD pTol = 4 * M.norm * orc.posErr + 1e-5L * M.norm * g.rRef +
              64 * kEps * len3(pw);
    if (!(dist3(ToL(si.p), pw) <= pTol))
        st.Fail(where() + ": p " + Str(ToL(si.p)) + " vs " + Str(pw));
    L3 nw = sgn * norm3(M.Normal(l.n));
    LD nAngle = 2 * std::asin(std::min((LD)1, dist3(ToL(si.n), nw) / 2));
    LD nEnv = envelope([&](const Local &x) { return norm3(M.Normal(x.n)); });
    if (!orc.nearPole) st.worstNAngle = std::max(st.worstNAngle, (double)nAngle);
    if (!(dist3(ToL(si.n), nw) <= 1e-4L + 2 * nEnv) && !orc.nearPole)
        st.Fail(where() + ": n " + Str(ToL(si.n)) + " vs " + Str(nw));
    if (!orc.nearSeam && !(std::abs(si.uv.x - u) <= 1e-5L + 4 * du))
        st.Fail(where() + ": u " + std::to_string(si.uv.x) + " vs " +
                std::to_string((double)u) + " at " + Str(orc.p) + ", " +
                std::to_string((double)orc.uv.rho) +
                " from the axis; position error bound " +
                std::to_string((double)orc.posErr) + ", lrt's p " +
                Str(ToL(si.p)) + " vs " + Str(pw));
    if (!(std::abs(si.uv.y - v) <= 1e-5L + 4 * dv))
        st.Fail(where() + ": v " + std::to_string(si.uv.y) + " vs " +
                std::to_string((double)v));
    if (orc.nearPole || !l.ok) return;
    ++st.derivativeChecks;
    L3 dpdu = M.Vector(l.dpdu), dpdv = M.Vector(l.dpdv);
    LD pScale = 1e-4L * (len3(dpdu) + len3(dpdv));
    LD envU = envelope([&](const Local &x) { return M.Vector(x.dpdu); });
    LD envV = envelope([&](const Local &x) { return M.Vector(x.dpdv); });
    if (!(dist3(ToL(si.dpdu), dpdu) <= pScale + 2 * envU))
        st.Fail(where() + ": dpdu " + Str(ToL(si.dpdu)) + " vs " + Str(dpdu));
    if (!(dist3(ToL(si.dpdv), dpdv) <= pScale + 2 * envV))
        st.Fail(where() + ": dpdv " + Str(ToL(si.dpdv)) + " vs " + Str(dpdv));
    L3 dndu = sgn * M.Normal(l.dndu), dndv = sgn * M.Normal(l.dndv);
    LD nScale = 1e-4L * (len3(dndu) + len3(dndv) + len3(M.Normal(l.n)));
    LD envNu = envelope([&](const Local &x) { return M.Normal(x.dndu); });
    LD envNv = envelope([&](const Local &x) { return M.Normal(x.dndv); });
    if (!(dist3(ToL(si.dndu), dndu) <= nScale + 2 * envNu))
        st.Fail(where() + ": dndu " + Str(ToL(si.dndu)) + " vs " + Str(dndu));
    if (!(dist3(ToL(si.dndv), dndv) <= nScale + 2 * envNv))
        st.Fail(where() + ": dndv " + Str(ToL(si.dndv)) + " vs " + Str(dndv));
}

struct QRay {
    L3 o, d;
    double tMax = std::numeric_limits<double>::infinity();
};

inline L3 ToL(D3 a) { return L3(a.x, a.y, a.z); }
inline L3 RandomDir(Rng &rng) { return ToL(rng.Dir()); }

// A uniformly random point of the whole surface of revolution (any phi)
// with v in [v0, v1].
inline L3 SurfacePoint(Rng &rng, const Geom &g, double v0, double v1,
                       LD *u = nullptr, LD *v = nullptr) {
    LD uu = rng.U(0, 1) * 2 * kPiL / g.phiMax, vv = rng.U(v0, v1);
    if (u) *u = uu;
    if (v) *v = vv;
    return g.P(uu, vv);
}

// Random rays of several kinds, in object space: from outside at points
// near the surface (kinds 0-2), with a finite tMax (9), from inside the
// surface of revolution (3, 4), nearly tangent (5, 6: "aimed" is false), and
// at the parts cut away, the missing phi wedge and the extension of the
// surface beyond its z range, so that the near root is cut and the far one
// counts (7, 8).
inline bool IsTangentKind(int i) { return i % 10 == 5 || i % 10 == 6; }

inline QRay RandomRay(Rng &rng, const Geom &g, int i) {
    QRay ray;
    const LD R = g.rRef, H = g.Height();
    const L3 center(0, 0, (g.zLo + g.zHi) / 2);
    const LD Rb = std::sqrt(R * R + H * H / 4);
    const int kind = i % 10;
    // The paraboloid does not extend below its tip.
    const double vBelow =
        g.kind == QKind::Paraboloid ? std::max(-0.3, double(-g.zLo / H)) : -0.3;
    auto outside = [&]() {
        return center + (Rb * (LD)rng.U(1.05, 10)) * RandomDir(rng);
    };
    if (kind < 3 || kind == 9) {
        ray.o = outside();
        L3 target(R * rng.U(-1.2, 1.2), R * rng.U(-1.2, 1.2),
                  g.zLo + H * rng.U(-0.2, 1.2));
        if (i % 20 < 10) target = SurfacePoint(rng, g, vBelow, 1.2);
        ray.d = (LD)rng.U(0.2, 5) * (target - ray.o);
        if (kind == 9)
            ray.tMax = rng.U(0, 1.2) * 2 * (double)((len3(ray.o - center) + Rb) /
                                                    len3(ray.d));
    } else if (kind < 5) {
        LD z = g.zLo + H * (LD)rng.U(0, 1);
        LD rho = 0.95L * std::sqrt(std::max(g.Q(z), (LD)0)) * std::sqrt(rng.U());
        LD a = rng.U(0, 2 * kPi);
        ray.o = L3(rho * std::cos(a), rho * std::sin(a), z);
        ray.d = (LD)rng.U(0.2, 5) * RandomDir(rng);
    } else if (kind < 7) {
        LD u, v;
        L3 q = SurfacePoint(rng, g, 0.02, 0.98, &u, &v);
        L3 n = g.N(u, v);
        L3 t = norm3(cross3(n, RandomDir(rng)));
        LD delta = std::pow(10.0, rng.U(-9, -2)) * (rng.U() < 0.5 ? -1 : 1);
        L3 target = q + (delta * R) * n;
        ray.o = target - (R * (LD)rng.U(0.5, 5)) * t;
        ray.d = (LD)rng.U(0.2, 5) * t;
    } else {
        LD u = 0, v = 0;
        L3 q;
        for (int k = 0; k < 100; ++k) {
            q = SurfacePoint(rng, g, vBelow, 1.3, &u, &v);
            if (u * g.phiMax > g.phiMax || v < 0 || v > 1) break;
        }
        ray.o = outside();
        ray.d = (LD)rng.U(0.2, 5) * (q - ray.o);
    }
    return ray;
}

inline lrt::Ray ToLrtRay(const QRay &r) {
    return lrt::Ray(ToP(r.o), ToV(r.d), lrt::Float(r.tMax));
}

// Intersect() and IntersectP() of one world ray, compared with the oracle.
inline void CheckRay(const QTarget &shape, const Geom &g, const LAffine &M,
                     bool reverse, const lrt::Ray &wr, const std::string &what,
                     bool aimed, QStats &st) {
    ObjectRay ob = ToObject(shape.w2o, wr);
    QOracle orc = Trace(g, ob, (LD)wr.tMax);
    lrt::ShapeHit h = Ask(shape, wr);
    if (h.hit != h.hitP)
        st.Fail(what + ": Intersect and IntersectP disagree on " +
                Str(ob.o) + " " + Str(ob.d));
    if (!h.hit && h.tHit != -1)
        st.Fail(what + ": a miss changed tHit");
    QCompare(g, orc, ob, M, reverse, h, what, aimed, st);
}

// Random affine transformations: rigid, nonuniform scales, mirrors, and a
// large one.
struct QXf {
    Affine M;
    const char *name;
};
inline std::vector<QXf> Transforms() {
    return {
        {Affine::Make(D3(1, 1, 1), D3(1, 2, 3), 37, D3(1, -2, 0.5)),
         "rotation"},
        {Affine::Make(D3(2, 0.5, 1.3), D3(-1, 0.3, 2), 71, D3(-3, 1, 2)),
         "nonuniform scale"},
        {Affine::Make(D3(-1, 1, 1), D3(0, 0, 1), 0, D3(0.5, 0, -1)), "mirror"},
        {Affine::Make(D3(-1.5, 0.7, 2), D3(2, -1, 1), 123, D3(4, 4, -4)),
         "mirrored nonuniform scale"},
        {Affine::Make(D3(3e3, 3e3, 3e3), D3(1, 1, 0), -50, D3(1e4, -2e4, 5e3)),
         "large uniform scale"},
    };
}

// Random rays per parameter set in object space, and per transformation,
// set and orientation (in `make test`; far fewer when graded, where every
// ray crosses to the student's code and back).
inline int RaysPerDef() { return lrt::calls::Cases(20000, 250); }
inline int RaysPerTransform() { return lrt::calls::Cases(2500, 25); }

// The random-ray comparison of one shape: every parameter set in object
// space, and the first two under each transformation, in both
// orientations. Prints the shape's summary line.
inline void RunOracle(const char *shapeName, const std::vector<QuadricDef> &defs,
                      uint64_t seed) {
    Rng rng(lrt::calls::Seed(seed));
    QStats total;
    lrt::Transform id;
    LAffine I(id);
    for (const QuadricDef &def : defs) {
        Geom g(def);
        QTarget shape = Target(def, id, false);
        QStats st;
        for (int i = 0, n = RaysPerDef(); i < n; ++i) {
            QRay r = RandomRay(rng, g, i);
            CheckRay(shape, g, I, false, ToLrtRay(r), def.name,
                     !IsTangentKind(i), st);
        }
        EXPECT_EQ(st.failures, 0) << def.name;
        EXPECT_LE(st.bandMissesAimed,
                  kQMaxBandMissesPer100k * st.raysAimed / 100000 + 2)
            << def.name;
        // The rays reach what they are meant to (bounds loose enough for
        // the few rays of a graded run).
        EXPECT_GT(st.hits, st.rays / 100) << def.name;
        EXPECT_GE(st.derivativeChecks, st.rays / 100) << def.name;
        if (g.cutPhi || g.cutHi) {
            EXPECT_GE(st.farRootHits, st.rays / 400) << def.name;
        }
        total.Add(st);
    }
    for (const QXf &xf : Transforms()) {
        lrt::Transform o2w = xf.M.ToTransform();
        LAffine M(o2w);
        EXPECT_EQ(M.mirror, xf.M.mirror);
        for (size_t k = 0; k < 2 && k < defs.size(); ++k) {
            const QuadricDef &def = defs[k];
            Geom g(def);
            for (bool reverse : {false, true}) {
                QTarget shape = Target(def, o2w, reverse);
                QStats st;
                std::string what = def.name + ", " + xf.name +
                                   (reverse ? ", reversed" : "");
                for (int i = 0, n = RaysPerTransform(); i < n; ++i) {
                    QRay r = RandomRay(rng, g, i);
                    lrt::Ray wr(ToP(xf.M.Point(ToD(r.o))),
                                ToV(xf.M.Vector(ToD(r.d))), lrt::Float(r.tMax));
                    CheckRay(shape, g, M, reverse, wr, what,
                             !IsTangentKind(i), st);
                }
                EXPECT_EQ(st.failures, 0) << what;
                EXPECT_LE(st.bandMissesAimed,
                          kQMaxBandMissesPer100k * st.raysAimed / 100000 + 2)
                    << what;
                total.Add(st);
            }
        }
    }
    QReport(shapeName, total);
}

// Shapes translated 1e4 from the world origin and turned about a random
// axis, seen from near the world origin (1e4 away) and from 1e3 away, at
// random points of the surface and, half of the time, at points displaced
// a relative 1e-7 to 1e-2 off it along the normal (grazing the silhouette
// when seen edge-on). Every answer must be within the error bounds.
inline void RunFar(const char *shapeName, const std::vector<QuadricDef> &defs,
                   uint64_t seed, double shapeDistance = 1e4,
                   double originDistance = 1e3) {
    Rng rng(lrt::calls::Seed(seed));
    QStats total;
    const int placements = lrt::calls::Cases(100, 10);
    const int rays = lrt::calls::Cases(100, 20);
    for (size_t k = 0; k < 2 && k < defs.size(); ++k) {
        const QuadricDef &def = defs[k];
        Geom g(def);
        for (int s = 0; s < placements; ++s) {
            L3 c = (LD)shapeDistance * RandomDir(rng);
            lrt::Transform o2w =
                lrt::Translate(ToV(c)) *
                lrt::Rotate(lrt::Float(rng.U(0, 360)), ToV(RandomDir(rng)));
            LAffine M(o2w);
            QTarget shape = Target(def, o2w, s % 2 == 1);
            QStats st;
            for (int i = 0; i < rays; ++i) {
                LD u, v;
                double vBelow = g.kind == QKind::Paraboloid
                                    ? std::max(-0.1, double(-g.zLo / g.Height()))
                                    : -0.1;
                L3 q = SurfacePoint(rng, g, vBelow, 1.1, &u, &v);
                if (i % 2)
                    q = q + (LD)(g.rRef * std::pow(10.0, rng.U(-7, -2)) *
                                 (rng.U() < 0.5 ? -1 : 1)) * g.N(u, v);
                L3 target = M.Point(q);
                L3 o = (i % 4 < 2) ? L3(rng.U(-1, 1), rng.U(-1, 1), rng.U(-1, 1))
                                   : M.Point((LD)originDistance * RandomDir(rng));
                lrt::Ray wr(ToP(o), ToV((LD)rng.U(0.2, 5) * (target - o)));
                CheckRay(shape, g, M, s % 2 == 1, wr, def.name + ", far",
                         i % 2 == 0, st);
            }
            total.Add(st);
        }
    }
    char where[64];
    std::snprintf(where, sizeof(where), " far (%g from the origin)",
                  shapeDistance);
    QReport(std::string(shapeName) + where, total);
    EXPECT_EQ(total.failures, 0);
    // Far from the origin the bands are wide (a relative 1e-3 of the
    // shape's size at 1e4); inside them lrt must still be right most of
    // the time.
    EXPECT_LE(total.bandMisses, total.ambiguous / 10 + 2);
    EXPECT_GT(total.hits, total.rays / 4);
}

// The library's rule for leaving a surface, written here so that these
// suites do not depend on exercise ex-3.22's OffsetRayOrigin(): move the
// point along the normal, to the side of w, by the projection of the error
// box onto the normal, and round away from the point.
inline lrt::Ray OffsetRay(const lrt::SurfaceHit &si, lrt::Vector3f w) {
    lrt::Vector3f n(si.n);
    lrt::Float d = std::abs(n.x) * si.pError.x + std::abs(n.y) * si.pError.y +
                   std::abs(n.z) * si.pError.z;
    lrt::Vector3f off = d * n;
    if (lrt::Dot(w, n) < 0) off = -off;
    lrt::Point3f o = si.p + off;
    for (int i = 0; i < 3; ++i) {
        if (off[i] > 0) o[i] = lrt::NextFloatUp(o[i]);
        else if (off[i] < 0) o[i] = lrt::NextFloatDown(o[i]);
    }
    return lrt::Ray(o, w);
}

// Rays spawned from hits toward random directions on both sides never hit
// the same shape at t near 0: any hit must lie farther from the origin than
// the chord of the surface's curvature can make it. The property belongs to
// shapes that are large beside the error bounds of their hit points: a shape
// a few hundred units in the last place wide (the small shapes far from the
// origin) fits in a few of its hit points' error boxes, and a ray offset out
// of one box may still be within rounding of the shape's other side. Such a
// placement, a shape less than a thousand units in the last place of its
// position wide, is counted and skipped, decided from the shape and its
// transformation alone (never from the bounds the code under test reports,
// which a looser bound could otherwise use to escape the test).
inline void RunSpawn(const char *shapeName, const std::vector<QuadricDef> &defs,
                     uint64_t seed) {
    Rng rng(lrt::calls::Seed(seed));
    const int primary = lrt::calls::Cases(400, 15);
    long spawned = 0, nearHits = 0, fartherHits = 0, grazing = 0, chords = 0;
    long unoffsetNear = 0, tooSmall = 0;
    const LD eps = std::numeric_limits<lrt::Float>::epsilon() / 2;
    std::vector<QXf> xfs = Transforms();
    for (const QuadricDef &def : defs) {
        Geom g(def);
        for (size_t x = 0; x <= xfs.size(); ++x) {
            // Object space, each transformation, and far from the origin.
            Affine A = x < xfs.size()
                           ? xfs[x].M
                           : Affine::Make(D3(1, 1, 1), D3(1, -1, 2), 20,
                                          D3(6e3, -7e3, 3e3));
            lrt::Transform o2w = A.ToTransform();
            LAffine M(o2w);
            QTarget shape = Target(def, o2w, x % 2 == 1);
            LD worldR = M.norm * g.rRef;
            LD where = std::max({std::abs(M.m[0][3]), std::abs(M.m[1][3]),
                                 std::abs(M.m[2][3])}) + worldR;
            if (worldR < 1000 * eps * where) {
                ++tooSmall;
                continue;
            }
            for (int i = 0; i < primary; ++i) {
                QRay r = RandomRay(rng, g, i % 10 == 5 ? 0 : i);
                lrt::Ray wr(ToP(M.Point(r.o)), ToV(M.Vector(r.d)));
                lrt::ShapeHit first = Ask(shape, wr);
                if (!first.hit) continue;
                const lrt::SurfaceHit &si = first.isect;
                L3 q = M.InvPoint(ToL(si.p));
                if (std::hypot(q.x, q.y) < 0.1L * g.rRef) continue;
                lrt::Vector3f n = lrt::Normalize(lrt::Vector3f(si.n));
                for (int k = 0; k < 4; ++k) {
                    lrt::Vector3f w = lrt::Normalize(ToV(RandomDir(rng)));
                    if ((k % 2 == 0) != (lrt::Dot(w, n) > 0)) w = -w;
                    if (std::abs(lrt::Dot(w, n)) < 1e-2f) {
                        ++grazing;
                        continue;
                    }
                    lrt::Ray sr = OffsetRay(si, w);
                    ++spawned;
                    // For comparison, the same ray from the hit point itself
                    // (lrt's conservative bound on t rejects most such hits).
                    lrt::ShapeHit h0 = Ask(shape, lrt::Ray(si.p, w));
                    if (h0.hit &&
                        h0.tHit * len3(ToL(w)) <= 16 * len3(ToL(si.pError)))
                        ++unoffsetNear;
                    lrt::ShapeHit h2 = Ask(shape, sr);
                    if (h2.hit != h2.hitP)
                        ADD_FAILURE() << def.name << ": Intersect and "
                                      << "IntersectP disagree on a spawned ray";
                    if (!h2.hit) continue;
                    const lrt::Float t2 = h2.tHit;
                    const lrt::SurfaceHit &si2 = h2.isect;
                    // A hit near the origin is a self-intersection unless
                    // the exact line does meet the shape there, in front
                    // (a short chord across a concave side), or within the
                    // slack of a cut (rounding may carry a point across it).
                    LD dl = len3(ToL(sr.d)), dist = t2 * dl;
                    LD slack = 4 * std::max(len3(ToL(si.pError)),
                                            len3(ToL(si2.pError))) +
                               1e-5L * worldR;
                    LD limit = 1e-5L * worldR + 16 * len3(ToL(si.pError));
                    if (dist > limit) {
                        ++fartherHits;
                        continue;
                    }
                    ObjectRay ob = ToObject(shape.w2o, sr);
                    bool real = false;
                    for (LD t : ExactRoots(g, ob))
                        if (t > 0 && std::abs(t - t2) * dl <= slack &&
                            g.ContainsWithin(ob.o + t * ob.d,
                                             M.invNorm * slack))
                            real = true;
                    if (real) {
                        ++chords;
                    } else if (nearHits++ < 5) {
                        ADD_FAILURE()
                            << def.name << ": ray spawned from " << si.p
                            << " (pError " << si.pError << ") toward " << w
                            << " hit again at t = " << t2;
                    }
                }
            }
        }
    }
    std::printf("Quadric %s spawned rays: %ld rays, %ld hit again near the "
                "origin where the exact line does not (%ld short chords that "
                "it does), %ld hit the shape farther away, %ld grazing "
                "directions skipped, %ld placements of shapes too small "
                "beside their rounding skipped; from the hit points themselves, "
                "%ld hit again near the origin\n",
                shapeName, spawned, nearHits, chords, fartherHits, grazing,
                tooSmall, unoffsetNear);
    EXPECT_EQ(nearHits, 0);
    EXPECT_GT(spawned, lrt::calls::Cases(1000, 20));
}

// reverseOrientation negates n, dndu and dndv and nothing else.
inline void RunReverse(const std::vector<QuadricDef> &defs, uint64_t seed) {
    Rng rng(lrt::calls::Seed(seed));
    const int rays = lrt::calls::Cases(300, 10);
    std::vector<QXf> xfs = Transforms();
    long checked = 0;
    for (const QuadricDef &def : defs) {
        Geom g(def);
        for (const QXf &xf : {xfs[0], xfs[3]}) {
            lrt::Transform o2w = xf.M.ToTransform();
            QTarget out = Target(def, o2w, false), in = Target(def, o2w, true);
            for (int i = 0; i < rays; ++i) {
                QRay r = RandomRay(rng, g, 0);
                lrt::Ray wr(ToP(xf.M.Point(ToD(r.o))), ToV(xf.M.Vector(ToD(r.d))));
                lrt::ShapeHit h1 = Ask(out, wr), h2 = Ask(in, wr);
                ASSERT_EQ(h1.hit, h2.hit) << def.name;
                if (!h1.hit) continue;
                ++checked;
                const lrt::SurfaceHit &a = h1.isect, &b = h2.isect;
                EXPECT_EQ(h1.tHit, h2.tHit);
                EXPECT_EQ(a.p, b.p);
                EXPECT_EQ(a.uv, b.uv);
                EXPECT_EQ(b.n, -a.n) << def.name;
                EXPECT_EQ(b.dndu, -a.dndu) << def.name;
                EXPECT_EQ(b.dndv, -a.dndv) << def.name;
                EXPECT_EQ(b.dpdu, a.dpdu);
                EXPECT_EQ(b.dpdv, a.dpdv);
                // (Which side dpdu x dpdv puts n on, the flag, is checked
                // against the oracle.)
            }
        }
    }
    EXPECT_GT(checked, (long)defs.size() * rays / 2);
}

// The object bound contains random points of the surface and is the box of
// the specification: attained at its extremes.
inline void CheckBound(const QuadricDef &def, D3 lo3, D3 hi3, uint64_t seed) {
    // The corners as the shape's Float parameters give them.
    lrt::Point3f pMin(ToFloat(lo3.x), ToFloat(lo3.y), ToFloat(lo3.z));
    lrt::Point3f pMax(ToFloat(hi3.x), ToFloat(hi3.y), ToFloat(hi3.z));
    lrt::Transform id;
    auto shape = MakeShape(def, &id, &id, false);
    lrt::Bounds3f b = shape->ObjectBound();
    for (int i = 0; i < 3; ++i) {
        EXPECT_NEAR(b.pMin[i], pMin[i], 4 * lrt::MachineEpsilon * std::abs(pMin[i]))
            << def.name << " axis " << i;
        EXPECT_NEAR(b.pMax[i], pMax[i], 4 * lrt::MachineEpsilon * std::abs(pMax[i]))
            << def.name << " axis " << i;
    }
    Geom g(def);
    Rng rng(seed);
    LD lo[3] = {1e30L, 1e30L, 1e30L}, hi[3] = {-1e30L, -1e30L, -1e30L};
    for (int i = 0; i < 20000; ++i) {
        LD u = rng.U(), v = rng.U();
        if (i < 4) {
            u = i % 2;
            v = i / 2;
        }
        L3 p = g.P(u, v);
        for (int k = 0; k < 3; ++k) {
            lo[k] = std::min(lo[k], p[k]);
            hi[k] = std::max(hi[k], p[k]);
            LD slack = 4 * kEps * (std::abs(p[k]) + g.rRef);
            EXPECT_TRUE(p[k] >= b.pMin[k] - slack && p[k] <= b.pMax[k] + slack)
                << def.name << ": " << Str(p) << " outside the bound";
        }
    }
    // Tight in z (the surface reaches both ends) and, for a full turn, in x
    // and y: the sampled extremes come within 1% of the faces.
    LD size = std::max(g.rRef, g.Height());
    EXPECT_NEAR((double)lo[2], b.pMin.z, 1e-6 * size) << def.name;
    EXPECT_NEAR((double)hi[2], b.pMax.z, 1e-6 * size) << def.name;
    if (!g.cutPhi)
        for (int k = 0; k < 2; ++k) {
            EXPECT_NEAR((double)lo[k], b.pMin[k], 1e-2 * size) << def.name;
            EXPECT_NEAR((double)hi[k], b.pMax[k], 1e-2 * size) << def.name;
        }
}

// Hand-built rays whose near root is cut away: the oracle must find the far
// root, unambiguously, and lrt must agree with it on everything.
inline void CheckFarRoots(const QuadricDef &def, const std::vector<QRay> &rays) {
    Geom g(def);
    lrt::Transform id;
    LAffine I(id);
    QTarget shape = Target(def, id, false);
    QStats st;
    for (const QRay &r : rays) {
        lrt::Ray wr = ToLrtRay(r);
        QOracle orc = Trace(g, ToObject(id, wr), (LD)wr.tMax);
        EXPECT_TRUE(orc.hit && orc.farRoot && !orc.ambiguous)
            << def.name << ": the oracle finds no clear far root for " << wr;
        CheckRay(shape, g, I, false, wr, def.name + ", far root", true, st);
    }
    EXPECT_EQ(st.failures, 0);
    EXPECT_EQ(st.farRootHits, (long)rays.size());
}

// Every constructor call throws std::invalid_argument with a message that
// names the shape.
inline void ExpectRejected(const std::string &name,
                           const std::vector<std::function<void()>> &makes) {
    int i = 0;
    for (const auto &make : makes) {
        try {
            make();
            ADD_FAILURE() << name << ": bad parameter set " << i
                          << " was accepted";
        } catch (const std::invalid_argument &e) {
            EXPECT_NE(std::string(e.what()).find(name), std::string::npos)
                << e.what();
        }
        ++i;
    }
}

// Rays with a zero or non-finite origin, direction or tMax hit nothing and
// leave tHit alone, in object space and through a rotation.
inline void ExpectNoHitOnBadRays(const QuadricDef &def) {
    const lrt::Float nan = std::numeric_limits<lrt::Float>::quiet_NaN();
    const lrt::Float inf = lrt::Infinity;
    Geom g(def);
    lrt::Float zm = lrt::Float((g.zLo + g.zHi) / 2);
    lrt::Ray rays[] = {
        lrt::Ray(lrt::Point3f(-5, 0.1f, zm), lrt::Vector3f(0, 0, 0)),
        lrt::Ray(lrt::Point3f(0, 0, zm), lrt::Vector3f(0, 0, 0)),
        lrt::Ray(lrt::Point3f(nan, 0.1f, zm), lrt::Vector3f(1, 0, 0)),
        lrt::Ray(lrt::Point3f(-5, 0.1f, zm), lrt::Vector3f(1, nan, 0)),
        lrt::Ray(lrt::Point3f(-5, 0.1f, zm), lrt::Vector3f(1, 0, 0), nan),
        lrt::Ray(lrt::Point3f(nan, nan, nan), lrt::Vector3f(nan, nan, nan)),
        lrt::Ray(lrt::Point3f(-inf, 0.1f, zm), lrt::Vector3f(1, 0, 0)),
        lrt::Ray(lrt::Point3f(-5, 0.1f, zm), lrt::Vector3f(inf, 0, 0)),
    };
    lrt::Transform id, rot = lrt::Rotate(30, lrt::Vector3f(1, 1, 0));
    QTarget a = Target(def, id, false), b = Target(def, rot, false);
    // The good ray these are spoiled from hits.
    EXPECT_TRUE(Ask(a, lrt::Ray(lrt::Point3f(-5, 0.1f, zm),
                                lrt::Vector3f(1, 0, 0))).hitP)
        << def.name;
    for (const QTarget *s : {&a, &b})
        for (const lrt::Ray &r : rays) {
            lrt::ShapeHit h = Ask(*s, r, 12345);
            EXPECT_FALSE(h.hit) << def.name << " " << r;
            EXPECT_EQ(h.tHit, 12345) << def.name;
            EXPECT_FALSE(h.hitP) << def.name << " " << r;
        }
}

// A hyperboloid and the cylinder or cone it equals, on the same rays: both
// agree with the cylinder's or cone's oracle, and with each other (hit or
// miss, t, p, n, uv, dpdu, dpdv, dndu and dndv) wherever the oracle is
// certain.
inline void CompareWithEquivalent(const QuadricDef &hyp, const QuadricDef &other,
                           uint64_t seed) {
    Geom g(other);
    Rng rng(lrt::calls::Seed(seed));
    const int rays = lrt::calls::Cases(10000, 100);
    QStats stH, stO;
    long compared = 0, bothHit = 0;
    std::vector<QXf> xfs = Transforms();
    for (const Affine &A :
         {Affine::Make(D3(1, 1, 1), D3(0, 0, 1), 0, D3(0, 0, 0)), xfs[3].M}) {
        lrt::Transform o2w = A.ToTransform();
        LAffine M(o2w);
        QTarget h = Target(hyp, o2w, false), o = Target(other, o2w, false);
        for (int i = 0; i < rays; ++i) {
            QRay r = RandomRay(rng, g, i);
            lrt::Ray wr(ToP(M.Point(r.o)), ToV(M.Vector(r.d)),
                        lrt::Float(r.tMax));
            CheckRay(h, g, M, false, wr, hyp.name, !IsTangentKind(i), stH);
            CheckRay(o, g, M, false, wr, other.name, !IsTangentKind(i), stO);
            QOracle orc = Trace(g, ToObject(o.w2o, wr), (LD)wr.tMax);
            if (orc.ambiguous) continue;
            ++compared;
            lrt::ShapeHit hh = Ask(h, wr), ho = Ask(o, wr);
            const lrt::SurfaceHit &a = hh.isect, &b = ho.isect;
            const lrt::Float tH = hh.tHit, tO = ho.tHit;
            EXPECT_EQ(hh.hit, ho.hit) << wr;
            if (!hh.hit || !ho.hit) continue;
            ++bothHit;
            LD tol = 4 * orc.posErr / len3(ToL(wr.d)) + 1e-5L * orc.t;
            EXPECT_LE(std::abs(tH - tO), tol) << wr;
            LD pTol = 4 * (len3(ToL(a.pError)) + len3(ToL(b.pError))) +
                      8 * M.norm * orc.posErr + 1e-5L * M.norm * g.rRef;
            EXPECT_LE(dist3(ToL(a.p), ToL(b.p)), pTol) << wr;
            EXPECT_LE(dist3(ToL(a.n), ToL(b.n)), 1e-3) << wr;
            if (orc.nearPole) continue;
            EXPECT_NEAR(a.uv.x, b.uv.x, 1e-3) << wr;
            EXPECT_NEAR(a.uv.y, b.uv.y, 1e-3) << wr;
            // Relative to the size of the pair of derivatives (a cone's
            // dndv is zero).
            auto close = [&](L3 x, L3 y, LD scale) {
                return dist3(x, y) <= 1e-3L * scale;
            };
            LD sp = len3(ToL(b.dpdu)) + len3(ToL(b.dpdv));
            LD sn = len3(ToL(b.dndu)) + len3(ToL(b.dndv));
            EXPECT_TRUE(close(ToL(a.dpdu), ToL(b.dpdu), sp)) << wr;
            EXPECT_TRUE(close(ToL(a.dpdv), ToL(b.dpdv), sp)) << wr;
            EXPECT_TRUE(close(ToL(a.dndu), ToL(b.dndu), sn))
                << wr << ": " << a.dndu << " vs " << b.dndu;
            EXPECT_TRUE(close(ToL(a.dndv), ToL(b.dndv), sn))
                << wr << ": " << a.dndv << " vs " << b.dndv;
        }
    }
    QReport(hyp.name + " (against " + other.name + "'s oracle)", stH);
    QReport(other.name, stO);
    EXPECT_EQ(stH.failures, 0);
    EXPECT_EQ(stO.failures, 0);
    EXPECT_GT(bothHit, compared / 10);
}

}  // namespace
