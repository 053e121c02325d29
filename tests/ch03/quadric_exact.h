// The four quadrics of revolution by their definitions, for the tests of
// ex-3.25 (tests/ch03/test_quadric_roots.cpp and the hidden tests): each
// shape's implicit function F(p) and cut, written from the shape's
// definition in Chapter 3 (not from the coefficients of the chapter's
// implicit form), and the first hit of a ray, found by recovering the
// quadratic F(o + t d) from three of its values, solving it in long double
// and refining its roots with Newton steps.
#pragma once

#include "exercise_calls.h"
#include "quadric_oracle.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

namespace {

using lrt::QuadricSpec;

typedef V3<LD> L3v;
const LD kPiL = 3.141592653589793238462643383279502884L;

LD AzimuthL(LD x, LD y) {
    LD phi = std::atan2(y, x);
    return phi < 0 ? phi + 2 * kPiL : phi;
}

// The shape's implicit function and cut, in object space, from its
// definition.
struct Definition {
    QuadricSpec spec;
    LD F(L3v p) const {
        const QuadricSpec &s = spec;
        LD r = s.radius, rho2 = p.x * p.x + p.y * p.y;
        switch (s.kind) {
        case lrt::kCylinder:
            return rho2 - r * r;
        case lrt::kCone: {
            LD rz = r * (1 - p.z / (LD)s.height);  // radius at height z
            return rho2 - rz * rz;
        }
        case lrt::kParaboloid:
            return rho2 - r * r * p.z / (LD)std::max(s.zMin, s.zMax);
        default: {
            L3v a(s.p1.x, s.p1.y, s.p1.z), b(s.p2.x, s.p2.y, s.p2.z);
            LD v = (p.z - a.z) / (b.z - a.z);
            LD x = a.x + v * (b.x - a.x), y = a.y + v * (b.y - a.y);
            return rho2 - (x * x + y * y);
        }
        }
    }
    bool InCut(L3v p) const {
        const QuadricSpec &s = spec;
        LD phiMax = (LD)s.phiMax * kPiL / 180, z0 = 0, z1 = 0, phi = 0;
        switch (s.kind) {
        case lrt::kCylinder:
            z0 = std::min(s.zMin, s.zMax);
            z1 = std::max(s.zMin, s.zMax);
            break;
        case lrt::kCone:
            z1 = s.height;
            break;
        case lrt::kParaboloid:
            z0 = std::max(std::min(s.zMin, s.zMax), lrt::Float(0));
            z1 = std::max(s.zMin, s.zMax);
            break;
        default:
            z0 = std::min(s.p1.z, s.p2.z);
            z1 = std::max(s.p1.z, s.p2.z);
        }
        if (s.kind == lrt::kHyperboloid) {
            LD v = (p.z - s.p1.z) / ((LD)s.p2.z - s.p1.z);
            LD rx = s.p1.x + v * ((LD)s.p2.x - s.p1.x),
               ry = s.p1.y + v * ((LD)s.p2.y - s.p1.y);
            phi = AzimuthL(rx * p.x + ry * p.y, rx * p.y - ry * p.x);
        } else {
            phi = AzimuthL(p.x, p.y);
        }
        return p.z >= z0 && p.z <= z1 && phi <= phiMax;
    }
};

struct OracleHit {
    bool hit = false;
    LD t = 0;
    L3v p;
};

// The first root in (0, tMax] whose point is in the cut. F is sampled
// around the point of the ray nearest to the object-space origin, a unit of
// distance apart, so that its values are small and accurate even for an
// origin far away; Newton steps then refine each root.
OracleHit Oracle(const Definition &def, L3v o, L3v d, LD tMax) {
    auto at = [&](LD t) { return o + t * d; };
    LD tc = -dot3(o, d) / dot3(d, d), step = 1 / len3(d);
    LD f0 = def.F(at(tc)), fp = def.F(at(tc + step)),
       fm = def.F(at(tc - step));
    LD A = ((fp + fm) / 2 - f0) / (step * step), B = (fp - fm) / (2 * step),
       C = f0;
    std::vector<LD> roots;  // relative to tc
    if (std::abs(A) <= 1e-15L * (std::abs(B) + std::abs(C))) {
        if (B != 0) roots.push_back(-C / B);
    } else {
        LD D = B * B - 4 * A * C;
        if (D >= 0) {
            LD q = (B < 0) ? -(B - std::sqrt(D)) / 2 : -(B + std::sqrt(D)) / 2;
            roots.push_back(q / A);
            if (q != 0) roots.push_back(C / q);
        }
    }
    // Newton steps on F itself, evaluated at the root's point, where its
    // values are small: they remove the error that the fit leaves when the
    // root is far from tc (a long shape met far from its center).
    for (LD &t : roots) {
        t += tc;
        for (int k = 0; k < 3; ++k) {
            LD slope = 2 * A * (t - tc) + B;
            if (slope != 0) t -= def.F(at(t)) / slope;
        }
    }
    std::sort(roots.begin(), roots.end());
    OracleHit h;
    for (LD t : roots)
        if (t > 0 && t <= tMax && def.InCut(at(t))) {
            h.hit = true;
            h.t = t;
            h.p = at(t);
            break;
        }
    return h;
}

std::string Str(D3 a) {
    char buf[96];
    std::snprintf(buf, sizeof buf, "(%.17g, %.17g, %.17g)", a.x, a.y, a.z);
    return buf;
}

L3v L(const lrt::Point3f &p) { return L3v(p.x, p.y, p.z); }
L3v L(const lrt::Vector3f &v) { return L3v(v.x, v.y, v.z); }

}  // namespace
