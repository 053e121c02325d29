// Chapter 6: the Stanford bunny of data/bunny.ply, subdivided in code, traced
// by BVHAccel's trees and by brute force on a subset of camera and incoherent rays.
// The suites Ex6_5_SAHBunny, Ex6_6_HLBVHBunny and Ex6_7_TraversalBunny
// test the chapter's graded exercises on it, through the exercise calls (the
// worker gets the subdivided mesh as values); BunnyTest uses no exercise's
// code: BVHAccel's Middle and EqualCounts trees, traced by a TreeWalker.

#include "bvh_bunny.h"
#include "bvh_checks.h"
#include "remote_bvh.h"
#include "lrt/accelerators/bvh.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <memory>
#include <string>

using namespace lrt;
using lrt_test::Bunny;
using lrt_test::Check;
using lrt_test::CheckMortonOrder;
using lrt_test::CheckSAHChoices;
using lrt_test::CountingPrimitive;
using lrt_test::SAHCheck;
using lrt_test::TheBunny;
using lrt_test::TreeWalker;
using SplitMethod = BVHAccel::SplitMethod;

TEST(BunnyTest, BaseMeshIsThePackagedBunny) {
    const Bunny *bunny = TheBunny();
    ASSERT_BUNNY(bunny);
    EXPECT_EQ(bunny->baseTriangles, 3674);
    EXPECT_EQ(bunny->scene.prims.size(), 4u * 3674u);
}

// BVHAccel's Middle and EqualCounts trees, traced without its own
// traversal, which is Exercise 6.7's (the SAH tree is Exercise 6.5's).
TEST(BunnyTest, MiddleAndEqualCounts) {
    const Bunny *bunny = TheBunny();
    ASSERT_BUNNY(bunny);
    const auto &prims = bunny->scene.prims;
    for (SplitMethod m : {SplitMethod::Middle, SplitMethod::EqualCounts})
        Check(*bunny,
              TreeWalker(std::make_shared<BVHAccel>(prims, 4, m)),
              (std::string("BVHAccel ") + BVHAccel::SplitMethodName(m) +
               " traced by TreeWalker").c_str());
}

// The exercises' tests on the bunny, which the worker gets as values.

// BVHAccel's SAH tree, four primitives per leaf as in the benchmark: every
// decision follows the cost model, and the tree, traced without BVHAccel's
// traversal, finds the hits that brute force finds.
EXERCISE_TEST(Ex6_5_SAHBunny, TreeFollowsTheCostModel) {
    const Bunny *bunny = TheBunny();
    ASSERT_BUNNY(bunny);
    for (int leafSize : {1, 4}) {
        auto bvh = std::make_shared<ex::BVHAccel>(bunny->scene, leafSize,
                                                  SplitMethod::SAH);
        SAHCheck c = CheckSAHChoices(*bvh, "the bunny's SAH tree");
        EXPECT_GT(c.decisions, int(bunny->scene.prims.size()) / 8);
        Check(*bunny, TreeWalker(bvh), "BVHAccel SAH traced by TreeWalker");
    }
}

// BVHAccel's HLBVH tree: its primitives are in Morton order, and it finds
// the hits that brute force finds, traced without BVHAccel's traversal.
EXERCISE_TEST(Ex6_6_HLBVHBunny, TreeFollowsTheCurve) {
    const Bunny *bunny = TheBunny();
    ASSERT_BUNNY(bunny);
    auto bvh = std::make_shared<ex::BVHAccel>(bunny->scene, 4,
                                              SplitMethod::HLBVH);
    EXPECT_GT(CheckMortonOrder(*bvh, "the bunny's HLBVH tree"),
              int(bunny->scene.prims.size()) / 2);
    Check(*bunny, TreeWalker(bvh), "BVHAccel HLBVH traced by TreeWalker");
}

EXERCISE_TEST(Ex6_7_TraversalBunny, MiddleAndEqualCounts) {
    const Bunny *bunny = TheBunny();
    ASSERT_BUNNY(bunny);
    Check(*bunny, ex::BVHAccel(bunny->scene, 4, SplitMethod::Middle),
          "BVHAccel Middle");
    Check(*bunny, ex::BVHAccel(bunny->scene, 4, SplitMethod::EqualCounts),
          "BVHAccel EqualCounts");
}

// Visiting the near child first is what keeps the number of triangles a
// ray tests low: after a hit, the far child's box often lies behind it. On
// the bunny's rays, Intersect() must test at most a quarter more triangles
// than a traversal that visits the child whose box the ray enters first
// (which costs two box tests per node to decide); pbrt's order tests about
// as many. Visiting the first or the second child first, whatever the
// ray's direction, tests about twice and two and a half times as many.
// (The worker reports the triangles its traversal tested.)
EXERCISE_TEST(Ex6_7_TraversalBunny, TestsFewTriangles) {
    const Bunny *bunny = TheBunny();
    ASSERT_BUNNY(bunny);
    int64_t count = 0;
    ex::Scene counted = bunny->scene;
    for (auto &p : counted.prims)
        p = std::make_shared<CountingPrimitive>(p, &count);
    for (SplitMethod m : {SplitMethod::Middle, SplitMethod::EqualCounts}) {
        auto bvh = std::make_shared<ex::BVHAccel>(counted, 1, m);
        TreeWalker nearest(bvh, TreeWalker::Order::Distance);
        int64_t tested = 0, yardstick = 0;
        for (const Ray &ray : bunny->rays) {
            Ray r1 = ray, r2 = ray;
            SurfaceInteraction s1, s2;
            count = 0;
            bvh->Intersect(r1, &s1);
            tested += count;
            count = 0;
            nearest.Intersect(r2, &s2);
            yardstick += count;
        }
        EXPECT_LE(tested, yardstick + yardstick / 4)
            << "triangles tested by BVHAccel::Intersect() with "
            << (m == SplitMethod::Middle ? "Middle" : "EqualCounts")
            << ", against " << yardstick << " when visiting the child "
            << "entered first";
    }
}
