// Chapter 7: the Stanford bunny of data/bunny.ply, subdivided in code
// (ch06/bvh_bunny.h), traced by FastBVHAccel with every split method, and
// by FastBVHAccel adopting each of BVHAccel's trees, against brute force on
// a subset of camera and incoherent rays. (With chapter 8's tests, as
// test_fastbvh_whole.cpp says why.)

#include "ch06/bvh_bunny.h"
#include "lrt/accelerators/fastbvh.h"

#include <gtest/gtest.h>

#include <string>

using namespace lrt;
using lrt_test::Bunny;
using lrt_test::Check;
using lrt_test::TheBunny;
using SplitMethod = BVHAccel::SplitMethod;

TEST(FastBVHBunny, EverySplitMethod) {
    const Bunny *bunny = TheBunny();
    ASSERT_BUNNY(bunny);
    const auto &prims = bunny->scene.prims;
    for (SplitMethod m : {SplitMethod::SAH, SplitMethod::HLBVH,
                          SplitMethod::Middle, SplitMethod::EqualCounts}) {
        std::string name = BVHAccel::SplitMethodName(m);
        Check(*bunny, FastBVHAccel(prims, 8, m),
              ("FastBVHAccel " + name).c_str());
        Check(*bunny, FastBVHAccel(BVHAccel(prims, 4, m)),
              ("FastBVHAccel from BVHAccel " + name).c_str());
    }
}
