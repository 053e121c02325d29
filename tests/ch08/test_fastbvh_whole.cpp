// Tests of chapter 7's FastBVHAccel as the book writes it: with every split
// method and several leaf sizes, and adopting BVHAccel's trees, against a
// brute-force loop over the primitives on thousands of random scenes of
// spheres, disks and triangles, and of every shape of chapter 3; structure invariants of every tree built;
// degenerate inputs; its triangle test against Triangle::Intersect(), bit
// for bit; its hits against BVHAccel's; rays with NaN and infinite
// components in every octant. The scenes and oracles are chapter 6's
// (bvh_scenes.h), which the tests of BVHAccel use too; the checks of the
// four-wide trees and the rays in every octant and with NaN components are
// those of chapter 7's exercise tests (fastbvh_checks.h).
//
// They live with chapter 8's tests because every ray they trace runs the
// code of chapter 7's graded exercises (the box test, the collapse into
// four-wide nodes, the sweep of the binned SAH), which chapter 7's student
// edition leaves out; a test outside the exercises must pass with their
// stubs. In chapter 8's student edition, chapter 7 is the book's. (Chapter
// 7's own tests of the exercises are tests/ch07/test_fastbvh_exercises.cpp.)

#include "ch06/bvh_checks.h"
#include "ch06/bvh_scenes.h"
#include "ch07/fastbvh_checks.h"
#include "lrt/accelerators/fastbvh.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <memory>
#include <random>
#include <set>
#include <string>
#include <vector>

using namespace lrt;
using namespace lrt_test;

namespace {

// The split methods whose records FastBVHAccel fills itself (the SAH) or by
// adopting BVHAccel's tree (Middle and EqualCounts).
const std::vector<SplitMethod> kPlainMethods = {
    SplitMethod::SAH, SplitMethod::Middle, SplitMethod::EqualCounts};

void AddAdopted(std::vector<Accel> *v, const BVHAccel &bvh,
                const Prims &prims, SplitMethod m, int leafSize) {
    auto adopted = std::make_unique<FastBVHAccel>(bvh);
    CheckStructure(*adopted, prims);
    v->push_back({Label("FastBVHAccel from BVHAccel", m, leafSize),
                  std::move(adopted)});
}

// FastBVHAccel built with the given methods, and BVHAccel's trees of the
// same methods adopted by a FastBVHAccel.
AccelSet Fast(std::vector<SplitMethod> methods) {
    return [methods](const Scene &scene, int leafSize) {
        const Prims &prims = scene.prims;
        std::vector<Accel> v;
        for (SplitMethod m : methods) {
            BVHAccel bvh(prims, leafSize, m);
            CheckStructure(bvh, prims);
            AddAdopted(&v, bvh, prims, m, leafSize);
            auto fast = std::make_unique<FastBVHAccel>(prims, leafSize, m);
            CheckStructure(*fast, prims);
            v.push_back({Label("FastBVHAccel", m, leafSize), std::move(fast)});
        }
        return v;
    };
}

// The same, and the BVHAccel itself, traced by its own Intersect() and
// IntersectP() (whose choice of the nearer child is chapter 6's exercise,
// here the book's code).
AccelSet FastAndBVH(std::vector<SplitMethod> methods) {
    return [methods](const Scene &scene, int leafSize) {
        std::vector<Accel> v = Fast(methods)(scene, leafSize);
        for (SplitMethod m : methods) {
            auto bvh = std::make_unique<BVHAccel>(scene.prims, leafSize, m);
            CheckStructure(*bvh, scene.prims);
            v.push_back({Label("BVHAccel", m, leafSize), std::move(bvh)});
        }
        return v;
    };
}

const std::vector<SplitMethod> kAllMethods(std::begin(kMethods),
                                           std::end(kMethods));

}  // namespace

TEST(FastBVHRandomScenes, SAH) {
    RunRandomScenes(Fast({SplitMethod::SAH}), 601, kRandomScenes);
}
TEST(FastBVHRandomScenes, HLBVH) {
    RunRandomScenes(Fast({SplitMethod::HLBVH}), 602, kRandomScenes);
}
TEST(FastBVHRandomScenes, Middle) {
    RunRandomScenes(Fast({SplitMethod::Middle}), 603, kRandomScenes);
}
TEST(FastBVHRandomScenes, EqualCounts) {
    RunRandomScenes(Fast({SplitMethod::EqualCounts}), 604, kRandomScenes);
}

// Scenes of every shape of chapter 3 (cylinders, cones, paraboloids and
// hyperboloids with spheres, disks and triangles), partial and cut, under
// random transformations, with rays from inside them: FastBVHAccel and
// BVHAccel, each with its own traversal, against brute force.
TEST(FastBVHRandomScenesOfAllShapes, SAH) {
    RunRandomScenes(FastAndBVH({SplitMethod::SAH}), 821, kRandomScenes,
                    Shapes::All);
}
TEST(FastBVHRandomScenesOfAllShapes, HLBVH) {
    RunRandomScenes(FastAndBVH({SplitMethod::HLBVH}), 822, kRandomScenes,
                    Shapes::All);
}
TEST(FastBVHRandomScenesOfAllShapes, Middle) {
    RunRandomScenes(FastAndBVH({SplitMethod::Middle}), 823, kRandomScenes,
                    Shapes::All);
}
TEST(FastBVHRandomScenesOfAllShapes, EqualCounts) {
    RunRandomScenes(FastAndBVH({SplitMethod::EqualCounts}), 824,
                    kRandomScenes, Shapes::All);
}

TEST(FastBVHDegenerate, OnePrimitive) { CheckOnePrimitive(Fast(kAllMethods)); }

TEST(FastBVHDegenerate, Scenes) { CheckDegenerateScenes(Fast(kAllMethods)); }

// FastBVHAccel reports the SAH cost of its tree as BVHAccel does, with
// c_T = c_I = 1: for a two-level tree, the definition of the tree cost.
TEST(FastBVHAccel, StatsSAHCost) {
    Scene scene;
    UnitSphereAt(scene, Point3f(0, 0, 0));
    UnitSphereAt(scene, Point3f(4, 0, 0));
    FastBVHAccel fast(scene.prims, 1);
    // Root box 6 x 2 x 2 (area 56), leaves 2 x 2 x 2 (area 24).
    EXPECT_NEAR(fast.Stats().sahCost, 1 + 2 * 24.0 / 56.0, 1e-6);
}

// The fast BVH over triangles gives bit for bit the hits of BVHAccel, on a
// closed mesh (a subdivided octahedron) and rays from all directions.
TEST(FastBVHAccel, SameHitsAsBVHAccelOnAClosedMesh) {
    Scene scene = ClosedMeshScene(5);
    std::mt19937_64 rng(615);
    for (SplitMethod m : kMethods)
        ExpectSameHitsOnAClosedMesh(BVHAccel(scene.prims, 4, m),
                                    FastBVHAccel(scene.prims, 8, m), rng,
                                    20000);
}
// Every member of two interactions, compared exactly.
bool SameInteraction(const SurfaceInteraction &a, const SurfaceInteraction &b) {
    return a.p == b.p && a.time == b.time && a.pError == b.pError &&
           a.wo == b.wo && a.n == b.n && a.uv == b.uv && a.dpdu == b.dpdu &&
           a.dpdv == b.dpdv && a.dndu == b.dndu && a.dndv == b.dndv &&
           a.shape == b.shape && a.shading.n == b.shading.n &&
           a.shading.dpdu == b.shading.dpdu &&
           a.shading.dpdv == b.shading.dpdv &&
           a.shading.dndu == b.shading.dndu &&
           a.shading.dndv == b.shading.dndv && a.faceIndex == b.faceIndex &&
           a.flipNormal == b.flipNormal;
}

// FastBVHAccel's triangle test is Triangle's, reorganized: on a single
// triangle it must agree with Triangle::Intersect() bit for bit, including
// rays aimed exactly at edges and vertices (which exercise the double
// precision fallback) and degenerate triangles. Its interaction must be
// Triangle::Intersect()'s, member for member, both for meshes of positions
// only (completed from the FastTriangleInfo record, which must then carry
// the right face index and orientation: reversed, mirrored by the
// transformation, or both) and for meshes with normals, tangents or (u,v)
// (completed by the Triangle). The split methods without exercises cycle,
// since the record is filled by the SAH builder and by the copy of
// BVHAccel's trees.
TEST(FastBVHAccel, TriangleTestMatchesTriangleIntersect) {
    std::mt19937_64 rng(614);
    Transform id, mirror = Scale(-1, 1, 1), mirrorInverse = Inverse(mirror);
    ASSERT_TRUE(mirror.SwapsHandedness());
    int tri[3] = {0, 1, 2};
    int disagreements = 0, hits = 0, plainHits = 0, attributeHits = 0,
        flippedHits = 0;
    constexpr int kTriangles = 4000, kRays = 40;
    for (int i = 0; i < kTriangles; ++i) {
        Point3f c = RandomPoint(rng, Point3f(0, 0, 0), 10);
        double size = std::pow(10.0, U(rng, -4, 1));
        Point3f p[3];
        for (Point3f &q : p) q = RandomPoint(rng, c, size);
        if (i % 10 == 0) p[2] = p[0] + (p[1] - p[0]) * Float(U(rng, 0, 1));
        if (i % 17 == 0) p[1] = p[0];
        // Orientation, face index and vertex attributes vary with i.
        bool reverse = i % 3 == 1;
        const Transform *toWorld = i % 4 == 2 ? &mirror : &id;
        const Transform *toObject = i % 4 == 2 ? &mirrorInverse : &id;
        int face = 1000 + i;
        const int *faceIndices = i % 2 == 1 ? &face : nullptr;
        Point2f uv[3] = {Point2f(0.25f, 0.5f), Point2f(0.75f, 0.125f),
                         Point2f(0.5f, 1)};
        Normal3f n[3] = {Normal3f(0, 0, 1), Normal3f(0, 1, 1),
                         Normal3f(1, 0, 1)};
        Vector3f ss[3] = {Vector3f(1, 0, 0), Vector3f(1, 1, 0),
                          Vector3f(0, 1, 0)};
        int attributes = i % 8;  // 0 to 4: none; 5: uv; 6: n; 7: s
        auto shapes = CreateTriangleMesh(
            toWorld, toObject, reverse, 1, tri, 3, p,
            attributes == 7 ? ss : nullptr, attributes == 6 ? n : nullptr,
            attributes == 5 ? uv : nullptr, faceIndices);
        const auto &triangle = static_cast<const Triangle &>(*shapes[0]);
        Point3f w[3];
        triangle.GetVertices(&w[0], &w[1], &w[2]);
        auto prim = std::make_shared<GeometricPrimitive>(shapes[0]);
        std::vector<std::shared_ptr<Primitive>> one = {prim};
        SplitMethod method = kPlainMethods[(i / 3) % kPlainMethods.size()];
        FastBVHAccel fast(one, 8, method);
        for (int r = 0; r < kRays; ++r) {
            // A target on the triangle, on an edge, or at a vertex.
            Float b0 = Float(U(rng, 0, 1)), b1 = Float(U(rng, 0, 1 - b0));
            if (r % 4 == 1) b1 = 1 - b0;
            if (r % 4 == 2) b0 = 1, b1 = 0;
            Point3f target = w[0] * b0 + w[1] * b1 + w[2] * (1 - b0 - b1);
            Point3f o = RandomPoint(rng, Point3f((*toWorld)(c)),
                                    20 * size + 1);
            Ray ray(o, target - o);
            if (r % 5 == 0) ray.d = Normalize(ray.d);
            if (r % 7 == 0) ray.tMax = Float(U(rng, 0.5, 1.5));
            ray.time = Float(r) / kRays;
            Float tShape;
            SurfaceInteraction siShape, siFast;
            bool shapeHit = shapes[0]->Intersect(ray, &tShape, &siShape);
            Ray rf = ray;
            bool fastHit = fast.Intersect(rf, &siFast);
            bool ok = shapeHit == fastHit &&
                      fast.IntersectP(ray) == shapes[0]->IntersectP(ray);
            if (ok && shapeHit)
                ok = rf.tMax == tShape && SameInteraction(siFast, siShape) &&
                     siFast.primitive == prim.get();
            hits += shapeHit;
            plainHits += shapeHit && attributes < 5;
            attributeHits += shapeHit && attributes >= 5;
            flippedHits += shapeHit && siShape.flipNormal;
            if (!ok && disagreements++ < kMaxFailuresReported)
                ADD_FAILURE() << "triangle " << i << " ray " << ray
                              << ": shape " << shapeHit << " t " << tShape
                              << ", fast " << fastHit << " t " << rf.tMax;
        }
    }
    EXPECT_EQ(disagreements, 0);
    EXPECT_GT(hits, kTriangles * kRays / 4);
    // Each kind of mesh and both orientations were hit often.
    EXPECT_GT(plainHits, hits / 2);
    EXPECT_GT(attributeHits, hits / 5);
    EXPECT_GT(flippedHits, hits / 4);
}

// Degenerate triangles (collinear or coincident vertices, or so small that
// the normal underflows) are kept with the other primitives rather than in
// the fast path, whose test no longer checks for them; rays aimed at them
// and at their neighbors get brute force's closest hit, and IntersectP()
// agrees.
TEST(FastBVHAccel, DegenerateTrianglesStayOutOfTheFastPath) {
    std::mt19937_64 rng(615);
    Scene scene;
    std::vector<Point3f> p;
    std::vector<int> indices;
    int degenerate = 0;
    for (int i = 0; i < 300; ++i) {
        Point3f c = RandomPoint(rng, Point3f(0, 0, 0), 5);
        Point3f q[3] = {RandomPoint(rng, c, 0.5), RandomPoint(rng, c, 0.5),
                        RandomPoint(rng, c, 0.5)};
        if (i % 3 == 1) q[2] = q[0] + (q[1] - q[0]) * Float(0.25);
        if (i % 6 == 2) q[1] = q[0];
        if (i % 12 == 5) {
            q[1] = q[0] + Vector3f(1e-30f, 0, 0);
            q[2] = q[0] + Vector3f(0, 1e-30f, 0);
        }
        for (const Point3f &v : q) {
            indices.push_back(int(p.size()));
            p.push_back(v);
        }
    }
    scene.AddTriangles(p, indices);
    for (const auto &prim : scene.prims)
        degenerate += IsDegenerate(*AsTriangle(prim.get()));
    ASSERT_GT(degenerate, 60);   // 75 by construction, some collinear ones
    ASSERT_LT(degenerate, 200);  // most collinear ones are not, after rounding
    for (SplitMethod method : kPlainMethods) {
        SCOPED_TRACE(MethodName(method));
        FastBVHAccel fast(scene.prims, 4, method);
        CheckStructure(fast, scene.prims);
        int fastTriangles = 0;
        std::function<void(FastBVHChild)> count = [&](FastBVHChild c) {
            if (c.IsLeaf()) {
                fastTriangles += c.nTriangles;
                return;
            }
            for (const FastBVHChild &child : fast.Nodes()[c.offset].child)
                if (!child.IsEmpty()) count(child);
        };
        count(fast.Root());
        EXPECT_EQ(fastTriangles, int(scene.prims.size()) - degenerate);
        int disagreements = 0;
        for (size_t k = 0; k < scene.prims.size(); ++k) {
            Point3f q[3];
            AsTriangle(scene.prims[k].get())->GetVertices(&q[0], &q[1], &q[2]);
            Point3f target = (q[0] + q[1] + q[2]) / 3;
            Point3f o = RandomPoint(rng, Point3f(0, 0, 0), 20);
            Ray ray(o, target - o);
            Float tBrute = Infinity;
            const Primitive *closest = nullptr;
            for (const auto &prim : scene.prims) {
                Ray r = ray;
                SurfaceInteraction si;
                if (prim->Intersect(r, &si) && r.tMax < tBrute) {
                    tBrute = r.tMax;
                    closest = prim.get();
                }
            }
            Ray r = ray;
            SurfaceInteraction si;
            bool hit = fast.Intersect(r, &si);
            bool ok = hit == (closest != nullptr) &&
                      fast.IntersectP(ray) == hit &&
                      (!hit || (r.tMax == tBrute && si.primitive == closest));
            if (!ok && disagreements++ < kMaxFailuresReported)
                ADD_FAILURE() << "ray " << k << ": fast " << hit << " t "
                              << r.tMax << ", brute force t " << tBrute;
        }
        EXPECT_EQ(disagreements, 0);
    }
}

// FastBVHAccel's nodes have four slots, and the unused ones hold an empty
// box. A ray that is NaN on every axis passes every box test (a NaN never
// rejects, Section 5.4), also the empty boxes, so for such rays the
// traversal visits the unused slots too; they must be empty leaves, not
// references to node 0, or the traversal would never end. Rays NaN on some
// axes and rays with infinite components must get the same answer from
// every tree. (The trees are FastBVHAccel's own SAH tree and the Middle and
// EqualCounts trees it adopts, whose builders hold no exercise, so that
// this test runs in the student edition too.)
TEST(FastBVHAccel, RaysWithNaNAndInfinityEndAndAgreeAcrossTrees) {
    std::mt19937_64 rng(616);
    Scene scene = SmallTriangles(rng);
    std::vector<Ray> rays = RaysWithNaNAndInfinity(rng, 200);
    FastBVHAccel sah(scene.prims, 8, SplitMethod::SAH);
    FastBVHAccel middle(scene.prims, 4, SplitMethod::Middle);
    FastBVHAccel equal(scene.prims, 2, SplitMethod::EqualCounts);
    ExpectSameAnswers({&sah, &middle, &equal}, rays);
}

// FastBVHAccel traverses with one instance of its loop per octant of the
// ray's direction, each with the near and far planes of its octant built in
// (chapter 7, "Fast Traversal"). Every octant, with zero components of either sign (whose
// sign the reciprocal decides), must find what brute force finds.
TEST(FastBVHAccel, EveryOctantWithSignedZerosAgreesWithBruteForce) {
    std::mt19937_64 rng(6177);
    int hitsPerOctant[8] = {};
    for (int sceneIndex = 0; sceneIndex < 20; ++sceneIndex) {
        Scene scene = RandomScene(rng);
        FastBVHAccel sah(scene.prims, 8, SplitMethod::SAH);
        FastBVHAccel middle(scene.prims, 4, SplitMethod::Middle);
        CheckEveryOctant(rng, scene, {&sah, &middle}, hitsPerOctant);
    }
    for (int octant = 0; octant < 8; ++octant)
        EXPECT_GT(hitsPerOctant[octant], 50) << "octant " << octant;
}
