// Tests of Cone against the long-double oracle of quadrics_oracle.h: random
// rays in object space and through affine transformations, cones far from
// the origin, spawned rays, the far root, rays parallel to a generator (the
// quadratic's leading coefficient vanishes), rays through the apex and
// along the axis, the bound, the orientation and bad input. The tests that
// intersect belong to exercise ex-3.25 (suite Ex3_25_Cone) and reach the
// shape through its exercise call; those that only construct it are suite
// Cone.
#include "quadrics_oracle.h"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

std::vector<QuadricDef> Cones() {
    return {ConeDef(1, 1, 360, "cone"),
            ConeDef(2, 0.5, 270, "tall partial cone"),
            ConeDef(0.3, 1.5, 120, "flat cone sector"),
            ConeDef(0.05, 0.02, 330, "small cone")};
}

}  // namespace

EXERCISE_TEST(Ex3_25_Cone, AgreesWithLongDoubleOracle) { RunOracle("Cone", Cones(), 3300); }

EXERCISE_TEST(Ex3_25_Cone, FarFromTheOriginWithinTheErrorBounds) {
    RunFar("Cone", Cones(), 3301);
}

EXERCISE_TEST(Ex3_25_Cone, SpawnedRaysNeverHitAgainNearTheirOrigin) {
    RunSpawn("Cone", Cones(), 3302);
}

EXERCISE_TEST(Ex3_25_Cone, ReverseOrientationFlipsNormalAndItsDerivatives) {
    RunReverse(Cones(), 3303);
}

EXERCISE_TEST(Ex3_25_Cone, FarRootWhenTheNearOneIsCut) {
    QuadricDef def = ConeDef(1, 1, 180, "half cone");
    std::vector<QRay> rays = {
        // Through the missing half (y < 0), then the wall at y > 0.
        {L3(0.3L, -3, 0.5L), L3(0, 1, 0)},
        // Down past the apex: the upper nappe (z > h) is cut away.
        {L3(0.05L, 0.1L, 3), L3(0.1L, 0.2L, -1)},
        // From below, outside: the near root is on the extension below the
        // base, the far one on the inside of the wall.
        {L3(-3, 0.2L, -1.5L), L3(1, 0, 0.6L)},
    };
    CheckFarRoots(def, rays);
}

EXERCISE_TEST(Ex3_25_Cone, RaysParallelToAGenerator) {
    // With height = radius, a direction (-cos phi, -sin phi, 1) is parallel
    // to the generator at phi: the quadratic's leading coefficient is zero
    // (exactly, for phi a multiple of 90 degrees) or nearly so, and its one
    // root is -c / b.
    QuadricDef def = ConeDef(1, 1, 360, "cone");
    Geom g(def);
    lrt::Transform id;
    LAffine I(id);
    QTarget cone = Target(def, id, false);
    Rng rng(lrt::calls::Seed(3304));
    QStats st;
    long exact = 0;
    const int rays = lrt::calls::Cases(4000, 200);
    for (int i = 0; i < rays; ++i) {
        double phi = (i % 2) ? (i / 2 % 4) * kPi / 2 : rng.U(0, 2 * kPi);
        L3 d(-std::cos(phi), -std::sin(phi), 1);
        if (i % 2) d = L3(std::round(d.x), std::round(d.y), 1);
        L3 o(rng.U(-2, 2), rng.U(-2, 2), rng.U(-2, 0.5));
        if (i % 8 == 7) o = o - (LD)2 * d;  // start farther back
        QRay r{o, (LD)rng.U(0.5, 2) * d};
        lrt::Ray wr = ToLrtRay(r);
        ObjectRay ob = ToObject(id, wr);
        if (Coefficients(g, ob.o, ob.d).A == 0) ++exact;
        CheckRay(cone, g, I, false, wr, "generator-parallel", true, st);
    }
    QReport("Cone parallel to a generator", st);
    EXPECT_EQ(st.failures, 0);
    EXPECT_GT(exact, rays / 4);
    EXPECT_GT(st.hits, rays / 20);
    EXPECT_LE(st.bandMisses, st.rays / 100 + 2);
}

EXERCISE_TEST(Ex3_25_Cone, RaysThroughTheApexAndAlongTheAxis) {
    QuadricDef def = ConeDef(1.5, 0.8, 360, "cone");
    Geom g(def);
    lrt::Transform id;
    LAffine I(id);
    QTarget cone = Target(def, id, false);
    Rng rng(lrt::calls::Seed(3305));
    QStats st;
    const L3 apex(0, 0, 1.5L);
    for (int i = 0, n = lrt::calls::Cases(2000, 100); i < n; ++i) {
        L3 o = apex + (LD)rng.U(0.5, 4) * RandomDir(rng);
        lrt::Ray wr = ToLrtRay(QRay{o, (LD)rng.U(0.5, 2) * (apex - o)});
        CheckRay(cone, g, I, false, wr, "through the apex", true, st);
        lrt::ShapeHit h = Ask(cone, wr);
        if (h.hit) {
            EXPECT_FALSE(h.isect.n.HasNaNs()) << wr;
            EXPECT_FALSE(h.isect.dpdv.HasNaNs()) << wr;
            EXPECT_TRUE(std::isfinite(h.isect.uv.x) &&
                        std::isfinite(h.isect.uv.y));
        }
    }
    QReport("Cone through the apex", st);
    EXPECT_EQ(st.failures, 0);
    // Along the axis the line meets the cone at the apex only (a double
    // root): either answer, but nothing that is not finite.
    for (lrt::Float z : {-3.0f, 0.5f, 4.0f})
        for (lrt::Float dz : {1.0f, -1.0f}) {
            lrt::Ray r(lrt::Point3f(0, 0, z), lrt::Vector3f(0, 0, dz));
            lrt::ShapeHit h = Ask(cone, r);
            if (h.hit) {
                EXPECT_NEAR(h.isect.p.z, 1.5f, 1e-3f) << r;
                EXPECT_FALSE(h.isect.n.HasNaNs()) << r;
                EXPECT_FALSE(h.isect.dpdv.HasNaNs()) << r;
            }
        }
    // Parallel to the axis off it: the base circle's inside at x = 0.4
    // is hit once, at rho = 0.4, from below and from above.
    for (lrt::Float dz : {1.0f, -1.0f}) {
        lrt::Ray r(lrt::Point3f(0.4f, 0, dz > 0 ? -2 : 5),
                   lrt::Vector3f(0, 0, dz));
        lrt::ShapeHit h = Ask(cone, r);
        ASSERT_TRUE(h.hit) << r;
        EXPECT_NEAR(h.isect.p.z, 1.5f * (1 - 0.4f / 0.8f), 1e-5f) << r;
    }
}

TEST(Cone, ObjectBound) {
    CheckBound(ConeDef(2, 1.5, 360, "cone"), D3(-1.5, -1.5, 0),
               D3(1.5, 1.5, 2), 3306);
    CheckBound(ConeDef(0.5, 3, 45, "cone sector"), D3(-3, -3, 0),
               D3(3, 3, 0.5), 3307);
}

TEST(Cone, BadInput) {
    lrt::Transform id;
    const lrt::Float nan = std::numeric_limits<lrt::Float>::quiet_NaN();
    const lrt::Float inf = lrt::Infinity;
    auto make = [&](const lrt::Transform *a, const lrt::Transform *b,
                    lrt::Float h, lrt::Float r, lrt::Float phi) {
        return [=]() { lrt::Cone c(a, b, false, h, r, phi); };
    };
    ExpectRejected("Cone", {
        make(&id, &id, 0, 1, 360), make(&id, &id, -1, 1, 360),
        make(&id, &id, nan, 1, 360), make(&id, &id, inf, 1, 360),
        make(&id, &id, 1, 0, 360), make(&id, &id, 1, -2, 360),
        make(&id, &id, 1, nan, 360), make(&id, &id, 1, inf, 360),
        make(&id, &id, 1, 1, 0), make(&id, &id, 1, 1, -5),
        make(&id, &id, 1, 1, nan)});
    EXPECT_THROW(make(nullptr, &id, 1, 1, 360)(), std::invalid_argument);
    EXPECT_THROW(make(&id, nullptr, 1, 1, 360)(), std::invalid_argument);
}

EXERCISE_TEST(Ex3_25_Cone, BadRaysHitNothing) {
    ExpectNoHitOnBadRays(ConeDef(1, 1, 360, "cone"));
    ExpectNoHitOnBadRays(ConeDef(2, 0.5, 250, "partial cone"));
}
