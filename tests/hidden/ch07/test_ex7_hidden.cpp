// Hidden tests of chapter 7's graded exercises (docs/exercises.md): new
// random cases for the checks of the public tests, scenes those do not
// draw (grids of equal cubes, closed meshes, boxes of zero area, larger
// trees), rays along the faces of boxes, and agreement with BVHAccel, bit
// for bit, on closed meshes.

#include "../../ch07/fastbvh_checks.h"
#include "../../ch07/remote_fastbvh.h"
#include "ch06/bvh_scenes.h"

#include <gtest/gtest.h>

#include <map>
#include <memory>
#include <random>
#include <string>
#include <vector>

using namespace lrt;
using namespace lrt_test;

namespace {

// n hollow unit cubes on a grid with gaps of one, logged with their index.
Scene HollowGrid(int side, std::vector<int> *log) {
    Scene scene;
    int i = 0;
    for (int x = 0; x < side; ++x)
        for (int y = 0; y < side; ++y)
            for (int z = 0; z < side; ++z, ++i) {
                Point3f c(Float(2 * x), Float(2 * y), Float(2 * z));
                scene.AddBox(Bounds3f(c, c + Vector3f(1, 1, 1)), false, log, i);
            }
    return scene;
}

}  // namespace

// Rays along the faces and edges of the cubes of a grid, parallel to
// coordinate planes (their distances to the planes they lie in are NaN),
// and rays through the gaps, in every octant: the primitives tested are
// those of the leaves whose boxes the ray enters.
EXERCISE_TEST(Ex7_8_FourBoxes, RaysAlongTheFacesOfAGrid) {
    std::mt19937_64 rng(calls::Seed(7801));
    std::vector<int> log;
    Scene scene = HollowGrid(5, &log);
    LeavesTested count;
    int failures = 0;
    const SplitMethod methods[] = {SplitMethod::SAH, SplitMethod::Middle,
                                   SplitMethod::EqualCounts};
    for (SplitMethod m : methods)
        for (int leafSize : {1, 3}) {
            ex::FastBVHAccel bvh(scene, leafSize, m);
            std::map<const Primitive *, int> at = Positions(bvh);
            for (int r = 0; r < calls::Cases(600, 200); ++r) {
                Point3f o(Float(rng() % 11) - 1, Float(rng() % 11) - 1,
                          Float(rng() % 11) - 1);
                if (r % 3 == 0) o[rng() % 3] += Float(0.5);
                Vector3f d = RandomDirection(rng);
                int zeros = int(rng() % 3);
                for (int k = 0; k < zeros; ++k)
                    d[rng() % 3] = rng() % 2 ? Float(0) : -Float(0);
                if (d.LengthSquared() == 0) d.x = rng() % 2 ? 1 : -1;
                Ray ray(o, d, r % 4 == 0 ? Float(U(rng, 0, 12)) : Infinity);
                log.clear();
                EXPECT_FALSE(bvh.IntersectP(ray));
                std::vector<int> tested;
                for (int id : log)
                    tested.push_back(at.at(scene.prims[id].get()));
                CheckLeavesTested(bvh, ray, tested, &count, &failures,
                                  std::string(MethodName(m)) + "(" +
                                      std::to_string(leafSize) + ")");
            }
        }
    EXPECT_EQ(failures, 0);
    EXPECT_GT(count.surelyTested, count.rays);
}

// Bit for bit the hits of BVHAccel on a closed mesh, from trees whose build
// holds no exercise but the collapse.
EXERCISE_TEST(Ex7_8_FourBoxes, SameHitsAsBVHAccelOnAClosedMesh) {
    Scene scene = ClosedMeshScene(4);
    std::mt19937_64 rng(calls::Seed(7802));
    for (SplitMethod m : {SplitMethod::Middle, SplitMethod::EqualCounts})
        ExpectSameHitsOnAClosedMesh(BVHAccel(scene.prims, 4, m),
                                    ex::FastBVHAccel(scene, 8, m), rng,
                                    calls::Cases(4000, 1500));
}

// Larger trees, closed meshes and grids of equal cubes (whose nodes tie in
// area), adopted from every builder.
EXERCISE_TEST(Ex7_9_FourChildren, LargerTreesAndTies) {
    std::mt19937_64 rng(calls::Seed(7901));
    CollapseCount count;
    const SplitMethod methods[] = {SplitMethod::SAH, SplitMethod::HLBVH,
                                   SplitMethod::Middle,
                                   SplitMethod::EqualCounts};
    std::vector<Scene> scenes = {ClosedMeshScene(3), HollowGrid(4, nullptr),
                                 HollowGrid(6, nullptr)};
    for (int i = 0; i < calls::Cases(12, 6); ++i)
        scenes.push_back(RandomBoxScene(rng, 200 + int(rng() % 800)));
    for (size_t s = 0; s < scenes.size(); ++s)
        for (SplitMethod m : methods)
            for (int leafSize : {1, 2, 5}) {
                CheckAdoptedTree(scenes[s], m, leafSize, &count,
                                 "scene " + std::to_string(s));
                if (::testing::Test::HasFailure()) return;
            }
    EXPECT_GT(count.full, count.nodes / 3);
}

// New random cases, and scenes of boxes of zero area (flat, on a line,
// repeated) at every leaf size, and a few large ones.
EXERCISE_TEST(Ex7_10_BinnedSAH, MoreDecisions) {
    std::mt19937_64 rng(calls::Seed(7001));
    const int leafSizes[] = {1, 2, 3, 5, 8, 12, 40, 255};
    SAHCount count;
    const int scenes = calls::Cases(400, 120);
    for (int sceneIndex = 0; sceneIndex < scenes; ++sceneIndex) {
        int n = 2 + int(rng() % 30);
        if (sceneIndex % 20 == 0) n = 1000 + int(rng() % 1000);
        Scene scene = RandomBoxScene(rng, n);
        int leafSize = leafSizes[rng() % 8];
        CheckSAHTree(scene, leafSize, &count,
                     "scene " + std::to_string(sceneIndex));
        if (::testing::Test::HasFailure()) return;
    }
    EXPECT_GT(count.decisions, 3 * scenes);
}

// The SAH's trees over closed meshes find BVHAccel's hits, bit for bit.
EXERCISE_TEST(Ex7_10_BinnedSAH, SameHitsAsBVHAccelOnAClosedMesh) {
    std::mt19937_64 rng(calls::Seed(7002));
    for (int levels : {2, 4}) {
        Scene scene = ClosedMeshScene(levels);
        for (int leafSize : {1, 8})
            ExpectSameHitsOnAClosedMesh(
                BVHAccel(scene.prims, 4, SplitMethod::Middle),
                ex::FastBVHAccel(scene, leafSize, SplitMethod::SAH), rng,
                calls::Cases(3000, 1000));
    }
}
