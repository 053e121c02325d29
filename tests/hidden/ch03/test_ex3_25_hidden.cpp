// Hidden tests of ex-3.25, the quadrics' quadratic (see test_ex3_hidden.cpp
// for the rules of hidden tests).
//
// Rays whose quadratic degenerates or nearly does: parallel to a line of a
// cone, along and nearly along the axis of a paraboloid, parallel to the
// generating segment of a hyperboloid; and rays through the cut-away part of
// partial shapes, which must find the far root. The oracle
// (ch03/quadric_exact.h) solves the shape's implicit function, written from
// its definition, in long double.

#include "lrt/shapes/cylinder.h"
#include "lrt/shapes/cone.h"
#include "lrt/shapes/paraboloid.h"
#include "lrt/shapes/hyperboloid.h"

#include <gtest/gtest.h>

#include "ch03/quadric_exact.h"

#include <cmath>
namespace {

// Checks one ray against the oracle; returns false (with a failure) on a
// wrong answer.
bool AgreesWithOracle(const lrt::QuadricSpec &s, const lrt::Ray &ray,
                      const char *what) {
    Definition def{s};
    OracleHit want = Oracle(def, L(ray.o), L(ray.d), (LD)ray.tMax);
    lrt::ShapeHit got = lrt::ex::IntersectQuadric(s, ray, 0);
    if (got.hit != want.hit) {
        ADD_FAILURE() << what << ": ray " << Str(ToD(ray.o)) << " + t "
                      << Str(ToD(ray.d)) << ": lrt says "
                      << (got.hit ? "hit" : "miss") << ", the oracle "
                      << (want.hit ? "hit" : "miss");
        return false;
    }
    if (want.hit && std::abs((LD)got.tHit - want.t) >
                        1e-4L * want.t + 1e-5L) {
        ADD_FAILURE() << what << ": t = " << got.tHit << ", the oracle's "
                      << (double)want.t;
        return false;
    }
    return true;
}

}  // namespace

EXERCISE_TEST(Ex3_25_QuadricRootsHidden, RaysParallelToTheLinesOfTheSurface) {
    Rng rng(lrt::calls::Seed(3250));
    const int kRays = lrt::calls::Cases(400, 100);
    int wrong = 0, hits = 0;
    for (int i = 0; i < kRays && wrong < 5; ++i) {
        lrt::QuadricSpec s;
        lrt::Ray ray;
        double phi = rng.U(0, 2 * kPi);
        D3 radial(std::cos(phi), std::sin(phi), 0);
        if (i % 3 == 0) {  // a line of the cone: from the rim to the apex
            s.kind = lrt::kCone;
            s.height = 2;
            s.radius = 1;
            D3 line = D3(0, 0, 2) - radial;
            D3 o = D3(rng.U(-1.5, 1.5), rng.U(-1.5, 1.5), -1) - 2 * line;
            ray = lrt::Ray(ToP(o), ToV(line), 10);
        } else if (i % 3 == 1) {  // along, or nearly along, the axis
            s.kind = lrt::kParaboloid;
            s.radius = 1;
            s.zMin = 0;
            s.zMax = 2;
            D3 o(rng.U(-0.9, 0.9), rng.U(-0.9, 0.9), rng.U(3, 5));
            D3 d(i % 2 ? 0 : 1e-4 * rng.U(-1, 1), 0, -1);
            ray = lrt::Ray(ToP(o), ToV(d), 10);
        } else {  // parallel to the generating segment of a hyperboloid
            s.kind = lrt::kHyperboloid;
            s.p1 = lrt::Point3f(1, 0, -1);
            s.p2 = lrt::Point3f(0, 1, 1);
            D3 seg(-1, 1, 2);
            D3 o = D3(rng.U(-2, 2), rng.U(-2, 2), rng.U(-2, 2)) - 3 * seg;
            ray = lrt::Ray(ToP(o), ToV(seg), 10);
        }
        s.phiMax = 360;
        if (!AgreesWithOracle(s, ray, "a ray parallel to a line")) ++wrong;
        hits += lrt::ex::IntersectQuadric(s, ray, 0).hit;
    }
    EXPECT_EQ(wrong, 0);
    EXPECT_GT(hits, kRays / 4);
}

EXERCISE_TEST(Ex3_25_QuadricRootsHidden, RaysThroughTheMissingPartFindTheFarSide) {
    Rng rng(lrt::calls::Seed(3251));
    const int kRays = lrt::calls::Cases(400, 100);
    int wrong = 0, farSide = 0;
    for (int i = 0; i < kRays && wrong < 5; ++i) {
        lrt::QuadricSpec s;
        s.kind = i % 4;
        s.radius = 1;
        s.zMin = i % 4 == lrt::kParaboloid ? 0.25f : -1;
        s.zMax = 1.5f;
        s.height = 1.5f;
        s.p1 = lrt::Point3f(0.75f, 0.25f, -1);
        s.p2 = lrt::Point3f(0.25f, 1, 1.25f);
        s.phiMax = 180;
        // Aim through the open half (y < 0) at a point behind the axis.
        D3 target(rng.U(-0.2, 0.2), rng.U(0.1, 0.3), rng.U(0.3, 0.9));
        D3 o(rng.U(-0.3, 0.3), -4, target.z + rng.U(-0.2, 0.2));
        lrt::Ray ray(ToP(o), ToV(target - o), 10);
        if (!AgreesWithOracle(s, ray, "a ray through the cut")) ++wrong;
        lrt::ShapeHit h = lrt::ex::IntersectQuadric(s, ray, 0);
        if (h.hit && h.isect.p.y > 0) ++farSide;
    }
    EXPECT_EQ(wrong, 0);
    EXPECT_GT(farSide, kRays / 4);
}
