// Tests of Hyperboloid against the long-double oracle of quadrics_oracle.h:
// random rays in object space and through affine transformations,
// hyperboloids far from the origin, spawned rays, the far root, rays along
// the axis, the bound, the orientation and bad input; and the two
// degenerate hyperboloids, whose segment is parallel to the axis (a
// cylinder) or meets it (a cone), against Cylinder and Cone on the same
// rays. The tests that intersect belong to exercise ex-3.25 (suite
// Ex3_25_Hyperboloid) and reach the shapes through its exercise call; those
// that only construct them are suite Hyperboloid.
#include "quadrics_oracle.h"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

std::vector<QuadricDef> Hyperboloids() {
    return {HyperboloidDef(D3(1, 0, -1), D3(0, 1, 1), 360,
                           "hyperboloid of one sheet"),
            HyperboloidDef(D3(0.3, 0.4, 0.2), D3(1.2, -0.5, 1.5), 240,
                           "partial hyperboloid"),
            HyperboloidDef(D3(0.5, 0, 1), D3(0.5, 0.3, -0.5), 300,
                           "hyperboloid, point2 below point1"),
            HyperboloidDef(D3(0.02, 0.03, 0), D3(-0.04, 0.01, 0.05), 180,
                           "small half hyperboloid"),
            HyperboloidDef(D3(0.8, 0, -0.5), D3(0.8, 0, 0.7), 360,
                           "hyperboloid that is a cylinder"),
            HyperboloidDef(D3(1, 0, 0), D3(0, 0, 1.2), 300,
                           "hyperboloid that is a cone")};
}

}  // namespace

EXERCISE_TEST(Ex3_25_Hyperboloid, AgreesWithLongDoubleOracle) {
    RunOracle("Hyperboloid", Hyperboloids(), 3500);
}

EXERCISE_TEST(Ex3_25_Hyperboloid, FarFromTheOriginWithinTheErrorBounds) {
    RunFar("Hyperboloid", Hyperboloids(), 3501);
}

EXERCISE_TEST(Ex3_25_Hyperboloid, SpawnedRaysNeverHitAgainNearTheirOrigin) {
    RunSpawn("Hyperboloid", Hyperboloids(), 3502);
}

EXERCISE_TEST(Ex3_25_Hyperboloid, ReverseOrientationFlipsNormalAndItsDerivatives) {
    RunReverse(Hyperboloids(), 3503);
}

EXERCISE_TEST(Ex3_25_Hyperboloid, FarRootWhenTheNearOneIsCut) {
    QuadricDef def = HyperboloidDef(D3(1, 0, -1), D3(0, 1, 1), 270,
                                    "three-quarter hyperboloid");
    std::vector<QRay> rays = {
        // Across the extension above the top end, then down to the wall.
        {L3(2.7L, -0.5L, 3.4L), L3(-1, -0.1L, -1)},
        {L3(-1.5L, -1.4L, 2.3L), L3(0.7L, 0.8L, -1)},
        // The same below the bottom end.
        {L3(-1.5L, 2.5L, -3.9L), L3(0.3L, -0.8L, 1)},
        // Through the missing quarter (phi past 270 degrees from the
        // segment's direction at that height) to the inside of the wall.
        {L3(3, -1, 0.3L), L3(-1, 0.35L, 0)},
    };
    CheckFarRoots(def, rays);
}

EXERCISE_TEST(Ex3_25_Hyperboloid, SegmentParallelToTheAxisIsACylinder) {
    CompareWithEquivalent(
        HyperboloidDef(D3(0.8, 0, -0.5), D3(0.8, 0, 0.7), 360, "hyperboloid"),
        CylinderDef(0.8, -0.5, 0.7, 360, "cylinder"), 3504);
    CompareWithEquivalent(
        HyperboloidDef(D3(1.3, 0, 0.2), D3(1.3, 0, 1), 250,
                       "partial hyperboloid"),
        CylinderDef(1.3, 0.2, 1, 250, "partial cylinder"), 3505);
}

EXERCISE_TEST(Ex3_25_Hyperboloid, SegmentThroughTheAxisIsACone) {
    CompareWithEquivalent(
        HyperboloidDef(D3(1, 0, 0), D3(0, 0, 1.2), 360, "hyperboloid"),
        ConeDef(1.2, 1, 360, "cone"), 3506);
    CompareWithEquivalent(
        HyperboloidDef(D3(0.6, 0, 0), D3(0, 0, 2), 200, "partial hyperboloid"),
        ConeDef(2, 0.6, 200, "partial cone"), 3507);
}

EXERCISE_TEST(Ex3_25_Hyperboloid, SpecialRays) {
    lrt::Transform id;
    QTarget h = Target(
        HyperboloidDef(D3(1, 0, -1), D3(0, 1, 1), 360, "hyperboloid"), id,
        false);
    // Along the axis, through the waist (radius 1/sqrt 2): no hit.
    for (lrt::Float dz : {1.0f, -1.0f}) {
        lrt::Ray r(lrt::Point3f(0, 0, -5 * dz), lrt::Vector3f(0, 0, dz));
        EXPECT_FALSE(Ask(h, r).hitP) << r;
    }
    // Perpendicular to the axis from it, at the waist: t = 1/sqrt 2 over
    // |d|, v = 1/2, and u = 0 on the segment's midpoint (1/2, 1/2, 0).
    lrt::ShapeHit w =
        Ask(h, lrt::Ray(lrt::Point3f(0, 0, 0), lrt::Vector3f(0.5f, 0.5f, 0)));
    const lrt::SurfaceHit &si = w.isect;
    ASSERT_TRUE(w.hit);
    EXPECT_NEAR(w.tHit, 1, 1e-6);
    EXPECT_NEAR(si.uv.y, 0.5, 1e-6);
    EXPECT_TRUE(si.uv.x < 1e-5f || si.uv.x > 1 - 1e-5f) << si.uv;
    EXPECT_NEAR(si.n.x, std::sqrt(0.5), 1e-5) << si.n;
    EXPECT_NEAR(si.n.y, std::sqrt(0.5), 1e-5) << si.n;
}

TEST(Hyperboloid, ObjectBound) {
    CheckBound(HyperboloidDef(D3(1, 0, -1), D3(0, 1, 1), 360, "hyperboloid"),
               D3(-1, -1, -1), D3(1, 1, 1), 3508);
    // rMax from the farther endpoint; the waist is nearer the axis.
    double r2 = std::hypot(1.2, -0.5);
    CheckBound(HyperboloidDef(D3(0.3, 0.4, 1.5), D3(1.2, -0.5, 0.2), 240,
                              "hyperboloid, point2 below point1"),
               D3(-r2, -r2, 0.2), D3(r2, r2, 1.5), 3509);
    CheckBound(HyperboloidDef(D3(0.5, 0, 1), D3(0, 0, 0), 360,
                              "hyperboloid that is a cone"),
               D3(-0.5, -0.5, 0), D3(0.5, 0.5, 1),
               3510);
}

TEST(Hyperboloid, BadInput) {
    lrt::Transform id;
    const lrt::Float nan = std::numeric_limits<lrt::Float>::quiet_NaN();
    const lrt::Float inf = lrt::Infinity;
    auto make = [&](const lrt::Transform *a, const lrt::Transform *b,
                    lrt::Point3f p1, lrt::Point3f p2, lrt::Float phi) {
        return [=]() { lrt::Hyperboloid h(a, b, false, p1, p2, phi); };
    };
    using P = lrt::Point3f;
    std::vector<std::function<void()>> bad = {
        make(&id, &id, P(1, 0, 0.5f), P(0, 1, 0.5f), 360),  // z1 == z2
        make(&id, &id, P(0, 0, 0), P(0, 0, 1), 360),         // on the axis
        make(&id, &id, P(1, 0, 0), P(0, 1, 1), 0),
        make(&id, &id, P(1, 0, 0), P(0, 1, 1), -10),
        make(&id, &id, P(1, 0, 0), P(0, 1, 1), nan)};
    for (int k = 0; k < 6; ++k)
        for (lrt::Float x : {nan, inf, -inf}) {
            P p1(1, 0, 0), p2(0, 1, 1);
            if (k < 3) p1[k] = x;
            else p2[k - 3] = x;
            bad.push_back(make(&id, &id, p1, p2, 360));
        }
    ExpectRejected("Hyperboloid", bad);
    EXPECT_THROW(make(nullptr, &id, P(1, 0, 0), P(0, 1, 1), 360)(),
                 std::invalid_argument);
    EXPECT_THROW(make(&id, nullptr, P(1, 0, 0), P(0, 1, 1), 360)(),
                 std::invalid_argument);
}

EXERCISE_TEST(Ex3_25_Hyperboloid, BadRaysHitNothing) {
    ExpectNoHitOnBadRays(
        HyperboloidDef(D3(1, 0, -1), D3(0, 1, 1), 360, "hyperboloid"));
    ExpectNoHitOnBadRays(
        HyperboloidDef(D3(0.5, 0.2, -1), D3(0.7, 0.5, 1), 250,
                       "partial hyperboloid"));
}
