// Tests of chapter 7's FastBVHAccel that reach no graded exercise's code,
// so that they pass in the student edition too: accelerators over no
// primitives, the checks of the constructor's arguments, the box test's
// mask (EnteredChildren(), against its definition, NaNs included), the
// large arrays, and the refusal of a worker's answer that is not a tree.
//
// The graded exercises (the box test, the collapse into four-wide nodes and
// the sweep of the binned SAH) are in every tree of more than one leaf and
// every ray traced; their tests are test_fastbvh_exercises.cpp, through the
// exercise calls. The tests of the rest of FastBVHAccel as the book writes
// it, which trace rays through such trees (its triangle test against
// Triangle::Intersect(), its hits against BVHAccel's and brute force's on
// random scenes and on the bunny), are chapter 8's: in chapter 8's student
// edition, chapter 7's code is the book's.

#include "ch06/bvh_scenes.h"
#include "ch07/remote_fastbvh.h"
#include "lrt/accelerators/fastbvh.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <iterator>
#include <limits>
#include <memory>
#include <random>
#include <stdexcept>
#include <vector>

using namespace lrt;
using namespace lrt_test;

TEST(FastBVHDegenerate, NoPrimitives) {
    std::vector<std::shared_ptr<Primitive>> none;
    for (SplitMethod m : kMethods) {
        BVHAccel bvh(none, 4, m);
        FastBVHAccel fast(none, 4, m);
        FastBVHAccel adopted(bvh);
        for (const FastBVHAccel *p : {&fast, &adopted}) {
            EXPECT_TRUE(p->Nodes().empty());
            EXPECT_TRUE(p->Primitives().empty());
            EXPECT_EQ(p->Stats().TotalNodes(), 0);
            Ray ray(Point3f(0, 0, 0), Vector3f(0, 0, 1));
            SurfaceInteraction si;
            EXPECT_FALSE(p->Intersect(ray, &si));
            EXPECT_EQ(ray.tMax, Infinity);
            EXPECT_FALSE(p->IntersectP(ray));
            EXPECT_TRUE(p->WorldBound().IsEmpty());
        }
    }
}

TEST(FastBVHDegenerate, ArgumentChecks) {
    Scene scene;
    UnitSphereAt(scene, Point3f(0, 0, 0));
    std::vector<std::shared_ptr<Primitive>> withNull = scene.prims;
    withNull.push_back(nullptr);
    EXPECT_THROW(FastBVHAccel(withNull, 4), std::invalid_argument);
    EXPECT_THROW(FastBVHAccel(scene.prims, 4, SplitMethod(17)),
                 std::invalid_argument);
    // Leaf sizes are clamped to [1, 255].
    EXPECT_EQ(FastBVHAccel(scene.prims, 0).MaxPrimsInNode(), 1);
    EXPECT_EQ(FastBVHAccel(scene.prims, 1000).MaxPrimsInNode(), 255);
}

// EnteredChildren() builds the traversal's mask of entered children, with
// a vector instruction where the processor has one (chapter 7, "Four Boxes
// at Once") and with the portable loop elsewhere; in this build, float
// takes the first where there is SSE2 and double always the second. Both
// must set bit c exactly when !(tNear[c] > tFar[c]), so that a NaN on
// either side keeps the child: every pair of special values in every lane,
// and random lanes.
template <typename T>
void CheckEnteredChildren() {
    const T inf = std::numeric_limits<T>::infinity();
    const T nan = std::numeric_limits<T>::quiet_NaN();
    const T values[] = {-inf, T(-1), T(-0.0), T(0),
                        std::numeric_limits<T>::denorm_min(), T(1),
                        T(1) + std::numeric_limits<T>::epsilon(),
                        std::numeric_limits<T>::max(), inf, nan, -nan};
    auto expected = [](const T *tNear, const T *tFar) {
        unsigned m = 0;
        for (int c = 0; c < 4; ++c) m |= unsigned(!(tNear[c] > tFar[c])) << c;
        return m;
    };
    for (int c = 0; c < 4; ++c)
        for (T a : values)
            for (T b : values) {
                // The other lanes: one entered (0 <= 1), one missed (1 > 0),
                // one with a NaN, so that each lane's bit stays in place.
                T tNear[4] = {T(0), T(1), nan, T(0)};
                T tFar[4] = {T(1), T(0), T(0), T(0)};
                tNear[c] = a;
                tFar[c] = b;
                ASSERT_EQ(EnteredChildren(tNear, tFar), expected(tNear, tFar))
                    << "lane " << c << ": " << a << " against " << b;
            }
    std::mt19937 rng(6);
    std::uniform_int_distribution<int> pick(0, int(std::size(values)) - 1);
    for (int i = 0; i < 20000; ++i) {
        T tNear[4], tFar[4];
        for (int c = 0; c < 4; ++c) {
            tNear[c] = values[pick(rng)];
            tFar[c] = values[pick(rng)];
        }
        ASSERT_EQ(EnteredChildren(tNear, tFar), expected(tNear, tFar)) << i;
    }
}

TEST(FastBVHAccel, EnteredChildrenMatchesItsDefinition) {
    CheckEnteredChildren<float>();
    CheckEnteredChildren<double>();
}

// FastBVHAccel keeps its nodes, triangles and references in LargeArrays
// (chapter 7, "Pages of Memory"): on Linux an array of 8 MB (four large
// pages) or more is aligned to 2 MB, so that the kernel can map it with
// large pages; smaller arrays, and all arrays elsewhere, have their type's
// alignment. Growing an array across the threshold keeps its contents.
TEST(LargeArray, AlignmentAndGrowthAcrossTheThreshold) {
    const size_t largePage = size_t(2) << 20, threshold = 4 * largePage;
    auto address = [](const void *p) { return reinterpret_cast<uintptr_t>(p); };
    LargeArray<FastBVHNode> small(3);
    EXPECT_EQ(address(small.data()) % alignof(FastBVHNode), 0u);
    LargeArray<FastBVHNode> big(threshold / sizeof(FastBVHNode) + 1);
    EXPECT_EQ(address(big.data()) % alignof(FastBVHNode), 0u);
#if defined(__linux__)
    EXPECT_EQ(address(big.data()) % largePage, 0u);
#endif
    LargeArray<FastTriangle> tris;
    size_t n = 3 * threshold / sizeof(FastTriangle);
    for (size_t i = 0; i < n; ++i) {
        FastTriangle t;
        for (int a = 0; a < 3; ++a)
            for (int j = 0; j < 4; ++j) t.c[a][j] = Float(i % 1000 + 4 * a + j);
        tris.push_back(t);
    }
    ASSERT_EQ(tris.size(), n);
    for (size_t i = 0; i < n; i += 997)
        ASSERT_EQ(tris[i].c[1][2], Float(i % 1000 + 6)) << i;
#if defined(__linux__)
    EXPECT_EQ(address(tris.data()) % largePage, 0u);
#endif
    tris.resize(10);
    tris.shrink_to_fit();
    EXPECT_EQ(tris[9].c[0][0], Float(9));
    EXPECT_EQ(address(tris.data()) % alignof(FastTriangle), 0u);
}

// A worker's four-wide tree must be a tree whose leaves hold each primitive
// once (remote_fastbvh.h): leaves that overlap would let the checks that
// walk the tree do the work of every leaf for every primitive, and a tree of
// no primitives must have an empty leaf as its root, which no check follows.
// Made by hand, since building one runs the exercises' code.
TEST(ExerciseCalls, WideAnswersThatAreNotATreeAreRefused) {
    const FastBVHChild interior = {0, fastBVHInterior, 0}, empty = {0, 0, 0};
    std::vector<FastBVHNode> nodes(1);
    for (int c = 0; c < fastBVHWidth; ++c)
        nodes[0].child[c] = {uint32_t(c), 1, 0};
    EXPECT_NO_THROW(ex::CheckIsWideTree(nodes, interior, 4));
    EXPECT_NO_THROW(ex::CheckIsWideTree({}, empty, 0));
    std::vector<FastBVHNode> overlapping = nodes;
    overlapping[0].child[1].offset = 0;
    EXPECT_THROW(ex::CheckIsWideTree(overlapping, interior, 4), std::runtime_error);
    std::vector<FastBVHNode> wholeLeaves = nodes;
    for (int c = 0; c < fastBVHWidth; ++c)
        wholeLeaves[0].child[c] = {0, 4, 0};
    EXPECT_THROW(ex::CheckIsWideTree(wholeLeaves, interior, 4), std::runtime_error);
    EXPECT_THROW(ex::CheckIsWideTree(nodes, interior, 5), std::runtime_error);
    EXPECT_THROW(ex::CheckIsWideTree({}, interior, 0), std::runtime_error);
    EXPECT_THROW(ex::CheckIsWideTree(nodes, interior, 0), std::runtime_error);
}
