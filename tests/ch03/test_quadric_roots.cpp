// ex-3.25 (suite Ex3_25_QuadricRoots): rays from far away against the four
// quadrics of revolution, checked against a long-double oracle.
//
// The ray's origin and direction are the Float values that lrt receives,
// taken as exact. The shapes sit at the origin of world space, or translated
// by a vector whose coordinates are integers, so the exact object-space ray
// is known too.
//
// The oracle (quadric_exact.h) knows each shape only by its implicit
// function, from the shape's definition, and by its cut.
//
// A ray whose answer a small change of its aim would change (a hit near a
// silhouette or an edge of the cut, or a change of the surface hit first)
// lies in the band where a correct Float computation may decide either way,
// and is counted but not checked. Every other ray must get the oracle's
// answer: the same hit or miss, t within a relative 1e-4 (in float; the
// errors of a correct computation are below 1e-5 there), and a hit point
// whose error bound holds. A discriminant computed as b^2 - 4ac loses all of
// its digits for these rays in single precision and fails the test.

#include "lrt/shapes/cylinder.h"
#include "lrt/shapes/cone.h"
#include "lrt/shapes/paraboloid.h"
#include "lrt/shapes/hyperboloid.h"

#include <gtest/gtest.h>

#include "quadric_exact.h"

#include <cmath>
#include <cstdio>
#include <string>

namespace {

// A point of the surface at parameters (u, v) in (0, 1), from the shape's
// definition.
L3v SurfacePoint(const QuadricSpec &s, LD u, LD v) {
    LD phi = u * (LD)s.phiMax * kPiL / 180, c = std::cos(phi),
       sn = std::sin(phi);
    switch (s.kind) {
    case lrt::kCylinder: {
        LD z = s.zMin + v * ((LD)s.zMax - s.zMin);
        return L3v(s.radius * c, s.radius * sn, z);
    }
    case lrt::kCone: {
        LD r = s.radius * (1 - v);
        return L3v(r * c, r * sn, v * s.height);
    }
    case lrt::kParaboloid: {
        LD zMax = std::max(s.zMin, s.zMax);
        LD zMin = std::max(std::min(s.zMin, s.zMax), lrt::Float(0));
        LD z = zMin + v * (zMax - zMin), r = s.radius * std::sqrt(z / zMax);
        return L3v(r * c, r * sn, z);
    }
    default: {
        L3v a(s.p1.x, s.p1.y, s.p1.z), b(s.p2.x, s.p2.y, s.p2.z);
        L3v pr = a + v * (b - a);
        return L3v(pr.x * c - pr.y * sn, pr.x * sn + pr.y * c, pr.z);
    }
    }
}

std::vector<QuadricSpec> Shapes() {
    std::vector<QuadricSpec> shapes;
    auto add = [&](int kind, lrt::Float radius, lrt::Float zMin, lrt::Float zMax,
                   lrt::Float height, lrt::Float phiMax, lrt::Point3f p1 = {},
                   lrt::Point3f p2 = {}) {
        QuadricSpec s;
        s.kind = kind;
        s.radius = radius;
        s.zMin = zMin;
        s.zMax = zMax;
        s.height = height;
        s.phiMax = phiMax;
        s.p1 = p1;
        s.p2 = p2;
        shapes.push_back(s);
    };
    add(lrt::kCylinder, 1, -1, 1.5f, 0, 360);
    add(lrt::kCylinder, 0.5f, 0, 2, 0, 250);
    add(lrt::kCone, 1, 0, 0, 2, 360);
    add(lrt::kCone, 1.5f, 0, 0, 0.75f, 200);
    add(lrt::kParaboloid, 1, 0, 2, 0, 360);
    add(lrt::kParaboloid, 1.25f, 0.5f, 1.5f, 0, 300);
    add(lrt::kHyperboloid, 0, 0, 0, 0, 360, {1, 0, -1}, {0.5f, 1, 1});
    add(lrt::kHyperboloid, 0, 0, 0, 0, 270, {0.25f, 1, 0.5f}, {1, -0.5f, 2});
    return shapes;
}

struct Tally {
    int rays = 0, hits = 0, band = 0, wrong = 0;
    double worstOff = 0;  // the largest distance from the exact hit
};

// Long shapes: a ray that meets one of them far from its center passes the
// center far away too, and the discriminant computed as b^2 - 4ac cancels
// most of its digits.
std::vector<QuadricSpec> LongShapes() {
    std::vector<QuadricSpec> shapes(4);
    for (int k = 0; k < 4; ++k) shapes[k].kind = k;
    shapes[lrt::kCylinder].zMin = -1000;
    shapes[lrt::kCylinder].zMax = 1000;
    shapes[lrt::kCone].radius = 2;
    shapes[lrt::kCone].height = 1000;
    shapes[lrt::kParaboloid].radius = 2;
    shapes[lrt::kParaboloid].zMin = 0;
    shapes[lrt::kParaboloid].zMax = 1000;
    shapes[lrt::kHyperboloid].p1 = lrt::Point3f(1, 0, -1000);
    shapes[lrt::kHyperboloid].p2 = lrt::Point3f(0, 1, 1000);
    return shapes;
}

// Rays from `distance` away at the shapes, translated by up to
// `translation`; with `ends`, aimed at the parts of the shapes far from
// their centers (v in [0.05, 0.3] or [0.7, 0.95]). Hit points must be within
// 1e-6 times the distance of the exact ones in float (1e-14 in double).
void CheckFarRays(const std::vector<QuadricSpec> &shapes, bool ends,
                  double distance, double translation, uint64_t seed,
                  int raysPerShape, Tally *tally) {
    Rng rng(seed);
    const double tolerance =
        distance * (sizeof(lrt::Float) == 4 ? 1e-6 : 1e-14);
    for (QuadricSpec s : shapes) {
        // The shape at an integer translation c: the object-space ray is
        // the world ray minus c, exactly.
        D3 c(std::round(translation * rng.U(-1, 1)),
             std::round(translation * rng.U(-1, 1)),
             std::round(translation * rng.U(-1, 1)));
        s.objectToWorld = lrt::Translate(ToV(c));
        Definition def{s};
        for (int i = 0; i < raysPerShape; ++i) {
            // Aim at a point of the surface, or near it, from far away.
            double v = rng.U();
            if (ends) v = (i % 2 ? 0.05 : 0.7) + 0.25 * rng.U();
            L3v target = SurfacePoint(s, rng.U(), v);
            if (i % 3 == 2)
                target = target + (LD)0.3 * L3v(rng.U(-1, 1), rng.U(-1, 1),
                                                rng.U(-1, 1));
            D3 dir = rng.Dir();
            lrt::Point3f o = ToP(
                D3((double)target.x, (double)target.y, (double)target.z) +
                c + distance * dir);
            LD tTarget = 1 + 0.5 * rng.U();  // the ray reaches the target at t
            lrt::Vector3f d = ToV(
                (double)(1 / tTarget) *
                (D3((double)target.x, (double)target.y, (double)target.z) +
                 c - ToD(o)));
            lrt::Ray ray(o, d, lrt::Float(3));
            L3v oObj = L(o) - L3v(c.x, c.y, c.z), dObj = L(d);
            OracleHit want = Oracle(def, oObj, dObj, 3);
            // The band: a change of the aim by a hundredth of the shape's
            // size changes the answer.
            bool band = false;
            for (int k = 0; k < 6 && !band; ++k) {
                L3v shift((k / 2 == 0) * (k % 2 ? 1 : -1),
                          (k / 2 == 1) * (k % 2 ? 1 : -1),
                          (k / 2 == 2) * (k % 2 ? 1 : -1));
                L3v dk = dObj + ((LD)0.01 / tTarget) * shift;
                OracleHit other = Oracle(def, oObj, dk, 3);
                if (other.hit != want.hit ||
                    (want.hit &&
                     std::abs(other.t - want.t) * len3(dObj) > 0.1))
                    band = true;
            }
            ++tally->rays;
            if (band) {
                ++tally->band;
                continue;
            }
            lrt::ShapeHit got = lrt::ex::IntersectQuadric(s, ray, 0);
            std::string what = "kind " + std::to_string(s.kind) + ", ray " +
                               Str(ToD(o)) + " + t " + Str(ToD(d));
            if (got.hit != want.hit) {
                if (++tally->wrong <= 5)
                    ADD_FAILURE() << what << ": lrt says "
                                  << (got.hit ? "hit" : "miss")
                                  << ", the oracle "
                                  << (want.hit ? "hit at t = " : "miss")
                                  << (double)want.t;
                continue;
            }
            if (!want.hit) continue;
            ++tally->hits;
            double off = (double)(std::abs(got.tHit - want.t) * len3(dObj));
            tally->worstOff = std::max(tally->worstOff, off);
            if (off > tolerance && ++tally->wrong <= 5)
                ADD_FAILURE() << what << ": t = " << got.tHit
                              << ", the oracle's " << (double)want.t
                              << ", a distance of " << off << " along the ray";
            // The error bound: for the shapes that evaluate the ray
            // equation the exact hit is in the box; the cylinder's point is
            // projected onto its surface, and its box reaches the surface.
            L3v p = L(got.isect.p) - L3v(c.x, c.y, c.z),
                e = L(got.isect.pError);
            bool holds;
            if (s.kind == lrt::kCylinder) {
                LD rho = std::sqrt(p.x * p.x + p.y * p.y);
                holds = std::abs(rho - s.radius) <=
                        std::sqrt(e.x * e.x + e.y * e.y) * (1 + 1e-6L);
            } else {
                L3v gap = want.p - p;
                holds = std::abs(gap.x) <= e.x * (1 + 1e-6L) &&
                        std::abs(gap.y) <= e.y * (1 + 1e-6L) &&
                        std::abs(gap.z) <= e.z * (1 + 1e-6L);
            }
            if (!holds && ++tally->wrong <= 5)
                ADD_FAILURE() << what << ": the error bound "
                              << Str(ToD(got.isect.pError))
                              << " misses the exact point";
        }
    }
}

}  // namespace

void Report(const char *what, const Tally &tally) {
    std::printf("quadrics, %s: %d rays, %d hits, %d in the band, hits at "
                "most %.3g from the exact ones\n",
                what, tally.rays, tally.hits, tally.band, tally.worstOff);
    EXPECT_EQ(tally.wrong, 0);
    EXPECT_GT(tally.hits, tally.rays / 4);
    EXPECT_LT(tally.band, tally.rays / 5);
}

EXERCISE_TEST(Ex3_25_QuadricRoots, RaysFromFarAwayGetTheExactAnswer) {
    const int kRays = lrt::calls::Cases(1500, 300);
    for (double distance : {1e3, 1e4}) {
        Tally tally;
        CheckFarRays(Shapes(), false, distance, 0,
                     lrt::calls::Seed(2520) + uint64_t(distance), kRays,
                     &tally);
        Report(distance == 1e3 ? "rays from 1e3 away" : "rays from 1e4 away",
               tally);
    }
}

EXERCISE_TEST(Ex3_25_QuadricRoots, ShapesFarFromTheOriginOfTheWorld) {
    const int kRays = lrt::calls::Cases(1500, 300);
    Tally tally;
    CheckFarRays(Shapes(), false, 20, 1e4, lrt::calls::Seed(2521), kRays,
                 &tally);
    Report("shapes 1e4 from the world's origin", tally);
}

EXERCISE_TEST(Ex3_25_QuadricRoots, LongShapesHitFarFromTheirCenters) {
    const int kRays = lrt::calls::Cases(3000, 600);
    Tally tally;
    CheckFarRays(LongShapes(), true, 3000, 0, lrt::calls::Seed(2522), kRays,
                 &tally);
    Report("long shapes, rays from 3e3 away", tally);
}
