// Tests of Paraboloid against the long-double oracle of quadrics_oracle.h:
// random rays in object space and through affine transformations,
// paraboloids far from the origin, spawned rays, the far root, rays through
// the tip and along the axis, the bound, the orientation and bad input. The
// tests that intersect belong to exercise ex-3.25 (suite Ex3_25_Paraboloid)
// and reach the shape through its exercise call; those that only construct
// it are suite Paraboloid.
#include "quadrics_oracle.h"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

std::vector<QuadricDef> Paraboloids() {
    return {ParaboloidDef(1, 0, 1, 360, "paraboloid"),
            ParaboloidDef(0.8, 0.3, 1.5, 200, "cut partial paraboloid"),
            ParaboloidDef(2, 0.5, -1, 300, "wide paraboloid, z0 < 0"),
            ParaboloidDef(0.05, 0.01, 0.06, 90, "small quarter paraboloid")};
}

}  // namespace

EXERCISE_TEST(Ex3_25_Paraboloid, AgreesWithLongDoubleOracle) {
    RunOracle("Paraboloid", Paraboloids(), 3400);
}

EXERCISE_TEST(Ex3_25_Paraboloid, FarFromTheOriginWithinTheErrorBounds) {
    RunFar("Paraboloid", Paraboloids(), 3401);
}

EXERCISE_TEST(Ex3_25_Paraboloid, SpawnedRaysNeverHitAgainNearTheirOrigin) {
    RunSpawn("Paraboloid", Paraboloids(), 3402);
}

EXERCISE_TEST(Ex3_25_Paraboloid, ReverseOrientationFlipsNormalAndItsDerivatives) {
    RunReverse(Paraboloids(), 3403);
}

EXERCISE_TEST(Ex3_25_Paraboloid, FarRootWhenTheNearOneIsCut) {
    QuadricDef def = ParaboloidDef(1, 0.2, 1, 270, "cut paraboloid");
    std::vector<QRay> rays = {
        // Over the rim, into the open top, to the far wall.
        {L3(-3, 0.2L, 2.2L), L3(1, 0, -0.5L)},
        // Through the missing quarter (x > 0, y < 0).
        {L3(0.4L, -3, 0.6L), L3(0, 1, 0)},
        // Up through the hole cut at z = 0.2, from outside and below.
        {L3(-2.218L, 0.05L, -1), L3(1.729L, 0, 1)},
    };
    CheckFarRoots(def, rays);
}

EXERCISE_TEST(Ex3_25_Paraboloid, RaysThroughTheTipAndAlongTheAxis) {
    QuadricDef def = ParaboloidDef(1, 0, 1, 360, "paraboloid");
    Geom g(def);
    lrt::Transform id;
    LAffine I(id);
    QTarget par = Target(def, id, false);
    Rng rng(lrt::calls::Seed(3404));
    QStats st;
    for (int i = 0, n = lrt::calls::Cases(2000, 100); i < n; ++i) {
        L3 o = (LD)rng.U(0.5, 4) * RandomDir(rng);
        lrt::Ray wr = ToLrtRay(QRay{o, (LD)rng.U(0.5, 2) * (L3(0, 0, 0) - o)});
        CheckRay(par, g, I, false, wr, "through the tip", true, st);
        lrt::ShapeHit h = Ask(par, wr);
        if (h.hit) {
            EXPECT_FALSE(h.isect.n.HasNaNs()) << wr;
            EXPECT_TRUE(std::isfinite(h.isect.uv.x) &&
                        std::isfinite(h.isect.uv.y));
        }
    }
    QReport("Paraboloid through the tip", st);
    EXPECT_EQ(st.failures, 0);
    // Along the axis, from below and from above (in at the open top): the
    // tip, at t = 2 and t = 5; the quadratic is linear there. The normal's
    // limit at the tip is -z (dpdu x dpdv points away from the inside).
    for (lrt::Float dz : {1.0f, -1.0f}) {
        lrt::Ray r(lrt::Point3f(0, 0, dz > 0 ? -2 : 5), lrt::Vector3f(0, 0, dz));
        lrt::ShapeHit h = Ask(par, r);
        const lrt::SurfaceHit &si = h.isect;
        ASSERT_TRUE(h.hit) << r;
        EXPECT_NEAR(h.tHit, dz > 0 ? 2 : 5, 1e-5) << r;
        EXPECT_LE(std::abs(si.p.z), si.pError.z + 1e-6f) << r;
        EXPECT_FALSE(si.n.HasNaNs()) << r << " n " << si.n;
        if (!si.n.HasNaNs()) {
            EXPECT_LT(si.n.z, -0.99f) << r << " n " << si.n;
        }
    }
    // Parallel to the axis off it: one root, at z = rho^2 zMax / r^2.
    lrt::ShapeHit h =
        Ask(par, lrt::Ray(lrt::Point3f(0.6f, 0, -1), lrt::Vector3f(0, 0, 3)));
    ASSERT_TRUE(h.hit);
    EXPECT_NEAR(h.isect.p.z, 0.36f, 1e-6f);
    EXPECT_NEAR(h.tHit, 1.36f / 3, 1e-6f);
    EXPECT_NEAR(h.isect.uv.y, 0.36f, 1e-6f);
}

TEST(Paraboloid, ObjectBound) {
    CheckBound(ParaboloidDef(1.5, 0, 2, 360, "paraboloid"),
               D3(-1.5, -1.5, 0), D3(1.5, 1.5, 2),
               3405);
    CheckBound(ParaboloidDef(0.5, 1, 0.25, 60, "paraboloid, z swapped"),
               D3(-0.5, -0.5, 0.25), D3(0.5, 0.5, 1),
               3406);
    CheckBound(ParaboloidDef(1, -3, 2, 360, "paraboloid, z0 < 0"),
               D3(-1, -1, 0), D3(1, 1, 2), 3407);
}

TEST(Paraboloid, BadInput) {
    lrt::Transform id;
    const lrt::Float nan = std::numeric_limits<lrt::Float>::quiet_NaN();
    const lrt::Float inf = lrt::Infinity;
    auto make = [&](const lrt::Transform *a, const lrt::Transform *b,
                    lrt::Float r, lrt::Float z0, lrt::Float z1,
                    lrt::Float phi) {
        return [=]() { lrt::Paraboloid p(a, b, false, r, z0, z1, phi); };
    };
    ExpectRejected("Paraboloid", {
        make(&id, &id, 0, 0, 1, 360), make(&id, &id, -1, 0, 1, 360),
        make(&id, &id, nan, 0, 1, 360), make(&id, &id, inf, 0, 1, 360),
        make(&id, &id, 1, -2, -1, 360),  // zMax < 0
        make(&id, &id, 1, -1, 0, 360),   // zMax = 0
        make(&id, &id, 1, 0, inf, 360), make(&id, &id, 1, 0, nan, 360),
        make(&id, &id, 1, nan, 1, 360),
        make(&id, &id, 1, 0.5f, 0.5f, 360),  // zMin == zMax
        make(&id, &id, 1, 0, 1, 0), make(&id, &id, 1, 0, 1, -90),
        make(&id, &id, 1, 0, 1, nan)});
    EXPECT_THROW(make(nullptr, &id, 1, 0, 1, 360)(), std::invalid_argument);
    EXPECT_THROW(make(&id, nullptr, 1, 0, 1, 360)(), std::invalid_argument);
}

EXERCISE_TEST(Ex3_25_Paraboloid, BadRaysHitNothing) {
    ExpectNoHitOnBadRays(ParaboloidDef(1, 0, 1, 360, "paraboloid"));
    ExpectNoHitOnBadRays(ParaboloidDef(1, 0.3, 1, 250, "partial paraboloid"));
}
