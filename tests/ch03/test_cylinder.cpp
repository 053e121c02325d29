// Tests of Cylinder against the long-double oracle of quadrics_oracle.h:
// random rays in object space and through affine transformations, shapes
// far from the origin, spawned rays, the far root, special rays, the bound,
// the orientation and bad input. The tests that intersect belong to
// exercise ex-3.25 (suite Ex3_25_Cylinder) and reach the shape through its
// exercise call; those that only construct it are suite Cylinder.
#include "quadrics_oracle.h"

#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

std::vector<QuadricDef> Cylinders() {
    return {CylinderDef(1.0, -1, 1, 360, "full cylinder"),
            CylinderDef(0.7, -0.3, 1.2, 250, "partial cylinder"),
            CylinderDef(2.0, 0.5, 0.9, 90, "short quarter cylinder"),
            CylinderDef(0.05, -0.02, 0.1, 300, "small cylinder")};
}

}  // namespace

EXERCISE_TEST(Ex3_25_Cylinder, AgreesWithLongDoubleOracle) {
    RunOracle("Cylinder", Cylinders(), 3200);
}

EXERCISE_TEST(Ex3_25_Cylinder, FarFromTheOriginWithinTheErrorBounds) {
    RunFar("Cylinder", Cylinders(), 3201);
}

EXERCISE_TEST(Ex3_25_Cylinder, SpawnedRaysNeverHitAgainNearTheirOrigin) {
    RunSpawn("Cylinder", Cylinders(), 3202);
}

EXERCISE_TEST(Ex3_25_Cylinder, ReverseOrientationFlipsNormalAndItsDerivatives) {
    RunReverse(Cylinders(), 3203);
}

EXERCISE_TEST(Ex3_25_Cylinder, FarRootWhenTheNearOneIsCut) {
    // Through the missing wedge (phi from 270 to 360 degrees), through the
    // open ends, and from inside: the oracle must find the far root, and
    // lrt must agree.
    QuadricDef def = CylinderDef(1, -1, 1, 270, "three-quarter cylinder");
    std::vector<QRay> rays = {
        {L3(0.5L, -3, 0), L3(0, 1, 0)},         // wedge, then the wall
        {L3(-3, 0.3L, 3.5L), L3(1, 0, -1)},     // in at the top end
        {L3(-3, 0.3L, -3.5L), L3(1, 0, 1)},     // in at the bottom end
        {L3(3, -0.5L, 0.2L), L3(-1, 0.1L, 0.05L)},  // wedge, from +x
    };
    CheckFarRoots(def, rays);
}

EXERCISE_TEST(Ex3_25_Cylinder, SpecialRays) {
    lrt::Transform id;
    QTarget c = Target(CylinderDef(1, -1, 1, 360, "cylinder"), id, false);
    // Parallel to the axis, inside or outside: the quadratic vanishes.
    for (lrt::Point3f o : {lrt::Point3f(0, 0, -5), lrt::Point3f(0.5f, 0.2f, 5),
                           lrt::Point3f(2, 0, -5)})
        for (lrt::Float dz : {1.0f, -1.0f}) {
            lrt::Ray r(o, lrt::Vector3f(0, 0, dz));
            lrt::ShapeHit h = Ask(c, r, 7);
            EXPECT_FALSE(h.hit) << r;
            EXPECT_FALSE(h.hitP) << r;
            EXPECT_EQ(h.tHit, 7) << r;
        }
    // Along the surface itself: either answer, but no NaN.
    lrt::ShapeHit along =
        Ask(c, lrt::Ray(lrt::Point3f(1, 0, -5), lrt::Vector3f(0, 0, 1)));
    if (along.hit) {
        EXPECT_FALSE(along.isect.n.HasNaNs());
        EXPECT_FALSE(std::isnan(along.tHit));
    }
    // From the axis, perpendicular to it: t is the radius over |d|, the
    // normal points outward although the ray comes from inside.
    lrt::ShapeHit h =
        Ask(c, lrt::Ray(lrt::Point3f(0, 0, 0.3f), lrt::Vector3f(0, -2, 0)));
    ASSERT_TRUE(h.hit);
    EXPECT_NEAR(h.tHit, 0.5, 1e-6);
    EXPECT_NEAR(h.isect.n.y, -1, 1e-6);
    EXPECT_NEAR(h.isect.uv.x, 0.75, 1e-6);
    EXPECT_NEAR(h.isect.uv.y, 0.65, 1e-6);
    // The seam at phi = 2 pi has no crack.
    int seamHits = 0;
    const int seamRays = lrt::calls::Cases(1000, 50);
    for (int i = 1; i <= seamRays; ++i) {
        lrt::Float y = -lrt::Float(i) * lrt::Float(1e-9);
        lrt::ShapeHit s =
            Ask(c, lrt::Ray(lrt::Point3f(3, y, 0.1f), lrt::Vector3f(-1, 0, 0)));
        if (s.hit) {
            ++seamHits;
            EXPECT_GT(s.isect.uv.x, 0.99f);
        }
    }
    EXPECT_EQ(seamHits, seamRays);
    // tMax just before and just after the hit.
    EXPECT_FALSE(Ask(c, lrt::Ray(lrt::Point3f(-5, 0, 0), lrt::Vector3f(1, 0, 0),
                                 3.99f)).hitP);
    EXPECT_TRUE(Ask(c, lrt::Ray(lrt::Point3f(-5, 0, 0), lrt::Vector3f(1, 0, 0),
                                4.01f)).hitP);
}

TEST(Cylinder, ObjectBound) {
    CheckBound(CylinderDef(1.5, -0.5, 2, 360, "cylinder"),
               D3(-1.5, -1.5, -0.5), D3(1.5, 1.5, 2),
               3204);
    CheckBound(CylinderDef(0.3, 0.7, 0.2, 100, "cylinder, z swapped"),
               D3(-0.3, -0.3, 0.2), D3(0.3, 0.3, 0.7),
               3205);
    // Clamped phiMax: 400 degrees is a full turn.
    CheckBound(CylinderDef(2, -1, 1, 400, "cylinder, phiMax 400"),
               D3(-2, -2, -1), D3(2, 2, 1), 3206);
}

TEST(Cylinder, BadInput) {
    lrt::Transform id;
    const lrt::Float nan = std::numeric_limits<lrt::Float>::quiet_NaN();
    const lrt::Float inf = lrt::Infinity;
    auto make = [&](const lrt::Transform *a, const lrt::Transform *b,
                    lrt::Float r, lrt::Float z0, lrt::Float z1,
                    lrt::Float phi) {
        return [=]() { lrt::Cylinder c(a, b, false, r, z0, z1, phi); };
    };
    ExpectRejected("Cylinder", {
        make(&id, &id, 0, -1, 1, 360), make(&id, &id, -1, -1, 1, 360),
        make(&id, &id, nan, -1, 1, 360), make(&id, &id, inf, -1, 1, 360),
        make(&id, &id, 1, 0.5f, 0.5f, 360), make(&id, &id, 1, nan, 1, 360),
        make(&id, &id, 1, -1, nan, 360), make(&id, &id, 1, -inf, 1, 360),
        make(&id, &id, 1, -1, inf, 360), make(&id, &id, 1, -1, 1, 0),
        make(&id, &id, 1, -1, 1, -20), make(&id, &id, 1, -1, 1, nan)});
    EXPECT_THROW(make(nullptr, &id, 1, -1, 1, 360)(), std::invalid_argument);
    EXPECT_THROW(make(&id, nullptr, 1, -1, 1, 360)(), std::invalid_argument);
}

EXERCISE_TEST(Ex3_25_Cylinder, BadRaysHitNothing) {
    ExpectNoHitOnBadRays(CylinderDef(1, -1, 1, 360, "cylinder"));
    ExpectNoHitOnBadRays(CylinderDef(1, -0.5, 1, 200, "partial cylinder"));
}
