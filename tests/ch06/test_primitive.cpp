// Tests of chapter 6's primitives: GeometricPrimitive, TransformedPrimitive
// and Aggregate. Oracles: the shape's own intersection routine, and the same
// shape placed in world space by its ObjectToWorld transformation.

#include "bvh_checks.h"
#include "lrt/accelerators/bvh.h"
#include "lrt/shapes/sphere.h"
#include "lrt/shapes/triangle.h"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <random>
#include <vector>

using namespace lrt;
using lrt_test::TreeWalker;

namespace {

constexpr int kRandomRays = 20000;
// Relative tolerance for distances computed along two different routes
// (transforming the ray vs. transforming the shape).
const Float kRelTol = 1e4 * std::numeric_limits<Float>::epsilon();

Vector3f RandomDirection(std::mt19937_64 &rng) {
    std::normal_distribution<double> n(0, 1);
    for (;;) {
        double x = n(rng), y = n(rng), z = n(rng);
        double l = std::sqrt(x * x + y * y + z * z);
        if (l > 1e-3) return Vector3f(Float(x / l), Float(y / l), Float(z / l));
    }
}

Point3f RandomPoint(std::mt19937_64 &rng, double extent) {
    std::uniform_real_distribution<double> u(-extent, extent);
    return Point3f(Float(u(rng)), Float(u(rng)), Float(u(rng)));
}

}  // namespace

TEST(GeometricPrimitive, RejectsNullShape) {
    EXPECT_THROW(GeometricPrimitive(nullptr), std::invalid_argument);
}

TEST(GeometricPrimitive, ForwardsToShapeAndRecordsItself) {
    Transform o2w = Translate(Vector3f(0.5f, -1, 2)), w2o = Inverse(o2w);
    auto sphere = std::make_shared<Sphere>(&o2w, &w2o, false, 1.5f, -1.5f,
                                           1.5f, 360.f);
    GeometricPrimitive prim(sphere);
    EXPECT_EQ(prim.GetShape(), sphere.get());
    EXPECT_EQ(prim.WorldBound(), sphere->WorldBound());
    std::mt19937_64 rng(61);
    int hits = 0;
    for (int i = 0; i < kRandomRays; ++i) {
        Point3f o = RandomPoint(rng, 4);
        Point3f target = Point3f(0.5f, -1, 2) + Vector3f(RandomPoint(rng, 2));
        Ray ray(o, i % 4 ? target - o : RandomDirection(rng));
        if (i % 3 == 0) ray.tMax = Float(std::uniform_real_distribution<>(
                                      0.1, 6)(rng));
        Float tShape;
        SurfaceInteraction siShape, siPrim;
        bool shapeHit = sphere->Intersect(ray, &tShape, &siShape);
        Float tMaxBefore = ray.tMax;
        bool primHit = prim.Intersect(ray, &siPrim);
        ASSERT_EQ(shapeHit, primHit);
        EXPECT_EQ(prim.IntersectP(Ray(ray.o, ray.d, tMaxBefore)), shapeHit);
        if (primHit) {
            ++hits;
            EXPECT_EQ(ray.tMax, tShape);
            EXPECT_EQ(siPrim.primitive, &prim);
            EXPECT_EQ(siPrim.p, siShape.p);
            EXPECT_EQ(siPrim.n, siShape.n);
        } else {
            EXPECT_EQ(ray.tMax, tMaxBefore);
        }
    }
    EXPECT_GT(hits, kRandomRays / 3);
}

TEST(TransformedPrimitive, RejectsNullPrimitive) {
    EXPECT_THROW(TransformedPrimitive(nullptr, Transform()),
                 std::invalid_argument);
}

// An instance of a unit sphere under PrimitiveToWorld must behave like the
// same sphere given PrimitiveToWorld as its ObjectToWorld transformation.
TEST(TransformedPrimitive, MatchesShapeTransformedDirectly) {
    Transform identity;
    auto unitSphere = std::make_shared<Sphere>(&identity, &identity, false,
                                               1.f, -1.f, 1.f, 360.f);
    auto model = std::make_shared<GeometricPrimitive>(unitSphere);
    Transform place = Translate(Vector3f(1, 2, -0.5f)) *
                      Rotate(30, Vector3f(1, 1, 0)) * Scale(2, 0.5f, 1.25f);
    Transform placeInv = Inverse(place);
    auto placed = std::make_shared<Sphere>(&place, &placeInv, false, 1.f,
                                           -1.f, 1.f, 360.f);
    GeometricPrimitive direct(placed);
    TransformedPrimitive instance(model, place);

    Bounds3f b = instance.WorldBound();
    EXPECT_EQ(b, place(model->WorldBound()));

    std::mt19937_64 rng(62);
    int hits = 0, compared = 0;
    for (int i = 0; i < kRandomRays; ++i) {
        Point3f o = RandomPoint(rng, 5);
        Ray ray(o, i % 4 ? place(RandomPoint(rng, 1.2)) - o
                         : RandomDirection(rng));
        Ray rayDirect = ray;
        SurfaceInteraction siInst, siDirect;
        bool hitInst = instance.Intersect(ray, &siInst);
        bool hitDirect = direct.Intersect(rayDirect, &siDirect);
        EXPECT_EQ(instance.IntersectP(Ray(ray.o, ray.d)), hitInst);
        if (hitInst != hitDirect) {
            // Only grazing rays may disagree: the two routes round
            // differently. Such a ray passes within a hair of the sphere.
            Ray r = hitInst ? ray : rayDirect;
            SurfaceInteraction &si = hitInst ? siInst : siDirect;
            Vector3f n = Normalize(Vector3f(si.n));
            EXPECT_LT(std::abs(Dot(n, Normalize(r.d))), 1e-2) << i;
            continue;
        }
        if (!hitInst) continue;
        ++hits;
        ++compared;
        // The direct route moves the ray's origin by its rounding error
        // (Transform's ray form), so t differs by about that, absolutely.
        EXPECT_NEAR(ray.tMax, rayDirect.tMax, kRelTol * (rayDirect.tMax + 1))
            << i;
        EXPECT_EQ(siInst.primitive, model.get());
        Vector3f dp = siInst.p - siDirect.p;
        EXPECT_LT(dp.Length(), kRelTol * 10) << i;
        Vector3f ni = Normalize(Vector3f(siInst.n)),
                 nd = Normalize(Vector3f(siDirect.n));
        EXPECT_GT(Dot(ni, nd), 1 - 1e-3) << i;
    }
    EXPECT_GT(hits, kRandomRays / 3);
    EXPECT_EQ(hits, compared);
}

// The distances an instance reports are distances along the caller's ray:
// an instance that is hit at t and a world-space triangle at a slightly
// larger t must yield the instance, and the other way round.
TEST(TransformedPrimitive, DistancesAreComparableWithWorldSpace) {
    Transform identity;
    int indices[3] = {0, 1, 2};
    Point3f p[3] = {Point3f(-1, -1, 0), Point3f(1, -1, 0), Point3f(0, 1, 0)};
    auto tri = CreateTriangleMesh(&identity, &identity, false, 1, indices, 3,
                                  p, nullptr, nullptr, nullptr);
    auto model = std::make_shared<GeometricPrimitive>(tri[0]);
    for (Float z : {Float(2), Float(5), Float(-3)}) {
        Transform place = Translate(Vector3f(0, 0, z)) * Scale(3, 3, 3);
        TransformedPrimitive instance(model, place);
        Ray ray(Point3f(0.1f, 0.2f, 10), Vector3f(0, 0, -1));
        SurfaceInteraction si;
        ASSERT_TRUE(instance.Intersect(ray, &si));
        EXPECT_NEAR(ray.tMax, 10 - z, 1e-5f * (10 - z));
        EXPECT_NEAR(si.p.z, z, 1e-5f);
        Ray shortRay(Point3f(0.1f, 0.2f, 10), Vector3f(0, 0, -1), 9.99f - z);
        EXPECT_FALSE(instance.Intersect(shortRay, &si));
        EXPECT_FALSE(instance.IntersectP(shortRay));
    }
}

// Instances of an aggregate: a BVH over a small mesh, placed twice. (Its
// trees are traced by TreeWalker: BVHAccel's traversal holds an exercise.)
TEST(TransformedPrimitive, InstancesOfAnAggregate) {
    Transform identity;
    std::vector<int> indices;
    std::vector<Point3f> p;
    for (int i = 0; i < 8; ++i) {
        Float a = 2 * Pi * i / 8, b = 2 * Pi * (i + 1) / 8;
        p.push_back(Point3f(0, 0, 0.5f));
        p.push_back(Point3f(std::cos(a), std::sin(a), 0));
        p.push_back(Point3f(std::cos(b), std::sin(b), 0));
        for (int k = 0; k < 3; ++k) indices.push_back(3 * i + k);
    }
    auto shapes = CreateTriangleMesh(&identity, &identity, false, 8,
                                     indices.data(), int(p.size()), p.data(),
                                     nullptr, nullptr, nullptr);
    std::vector<std::shared_ptr<Primitive>> prims;
    for (auto &s : shapes) prims.push_back(std::make_shared<GeometricPrimitive>(s));
    auto model = std::make_shared<TreeWalker>(std::make_shared<BVHAccel>(
        prims, 2, BVHAccel::SplitMethod::Middle));
    Transform t1 = Translate(Vector3f(-3, 0, 0)),
              t2 = Translate(Vector3f(3, 0, 0)) * RotateX(180);
    std::vector<std::shared_ptr<Primitive>> scene = {
        std::make_shared<TransformedPrimitive>(model, t1),
        std::make_shared<TransformedPrimitive>(model, t2)};
    TreeWalker top(std::make_shared<BVHAccel>(scene, 1,
                                              BVHAccel::SplitMethod::Middle));
    Ray r1(Point3f(-3, 0, 5), Vector3f(0, 0, -1));
    SurfaceInteraction si;
    ASSERT_TRUE(top.Intersect(r1, &si));
    EXPECT_NEAR(r1.tMax, 4.5f, 1e-5f);
    // The primitive recorded is the triangle inside the model.
    bool found = false;
    for (auto &pr : prims) found |= (si.primitive == pr.get());
    EXPECT_TRUE(found);
    Ray r2(Point3f(3, 0, -5), Vector3f(0, 0, 1));
    ASSERT_TRUE(top.Intersect(r2, &si));
    EXPECT_NEAR(r2.tMax, 4.5f, 1e-5f);
    Ray r3(Point3f(0, 0, 5), Vector3f(0, 0, -1));
    EXPECT_FALSE(top.IntersectP(r3));
}
