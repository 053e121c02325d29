// Hidden tests of chapter 5's graded exercises (docs/exercises.md): they run
// at grading time only and never ship to students. The public tests of the
// same exercises are the suites Ex5_9_*, Ex5_10_* and Ex5_11_* in tests/ch05/.
//
// Each exercise's tests reach its own code first: the ex-5.9 tests use the
// first form with an unbounded ray, the ex-5.10 tests the BVH form with an
// unbounded ray (and no first form, so that they grade ex-5.10 alone), and
// the ex-5.11 tests rays with a finite tMax. Expected answers are exact.

#include "lrt/core/slabtest.h"

#include "ch05/exercise_calls.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

using namespace lrt;

namespace {

const Float kInf = std::numeric_limits<Float>::infinity();
const Float kU = std::numeric_limits<Float>::epsilon() / 2;

const Bounds3f kUnitBox(Point3f(0, 0, 0), Point3f(1, 1, 1));

// The direction components used below: -1, -0, +0, +1.
const Float kComponents[4] = {-1, -Float(0), Float(0), 1};

}  // namespace

// Rays from every direction with components in {-1, -0, +0, +1} toward the
// unit box's centre, from outside: the entry is at t = 1.5 exactly on every
// moving axis, and the box is left at 2.5.
EXERCISE_TEST(Ex5_9_SlabHidden, SignedZerosTowardTheCentre) {
    int cases = 0;
    for (Float dx : kComponents)
        for (Float dy : kComponents)
            for (Float dz : kComponents) {
                Vector3f d(dx, dy, dz);
                if (dx == 0 && dy == 0 && dz == 0) continue;
                Point3f o(Float(0.5) - 2 * dx, Float(0.5) - 2 * dy,
                          Float(0.5) - 2 * dz);
                Ray r(o, d);
                Float t0 = -1, t1 = -1;
                ASSERT_TRUE(ex::IntersectP(kUnitBox, r, &t0, &t1))
                    << dx << " " << dy << " " << dz;
                EXPECT_EQ(t0, Float(1.5));
                EXPECT_GE(t1, Float(2.5));
                EXPECT_LE(t1, Float(2.5) * (1 + 8 * kU));
                ++cases;
            }
    EXPECT_EQ(cases, 56);  // 4^3 sign patterns less the 8 zero vectors (+-0)
}

// The same rays shifted off the box on a zero axis miss it, whatever the
// sign of the zero; moving away from the centre, they miss it too.
EXERCISE_TEST(Ex5_9_SlabHidden, SignedZerosBesideAndMovingAway) {
    for (Float dx : kComponents)
        for (Float dy : kComponents)
            for (Float dz : kComponents) {
                Vector3f d(dx, dy, dz);
                if (dx == 0 && dy == 0 && dz == 0) continue;
                Point3f away(Float(0.5) + 2 * dx, Float(0.5) + 2 * dy,
                             Float(0.5) + 2 * dz);
                EXPECT_FALSE(ex::IntersectP(kUnitBox, Ray(away, d)));
                if (dx == 0) {
                    Point3f beside(2, Float(0.5) - 2 * dy, Float(0.5) - 2 * dz);
                    EXPECT_FALSE(ex::IntersectP(kUnitBox, Ray(beside, d)));
                    Point3f inside(Float(0.25), Float(0.5) - 2 * dy,
                                   Float(0.5) - 2 * dz);
                    EXPECT_TRUE(ex::IntersectP(kUnitBox, Ray(inside, d)));
                }
            }
}

// Directions that are not powers of two: the entry values are products with
// rounded reciprocals, and the interval is still the right one to a few ulps.
EXERCISE_TEST(Ex5_9_SlabHidden, ObliqueRaysFromBelow) {
    const Bounds3f b(Point3f(1, 1, 1), Point3f(2, 2, 2));
    for (int k = 3; k <= 40; ++k) {
        Float s = Float(k) / 8;  // the ray passes (1.5, 1.5, 1.5) at t = 1.5 / s
        Ray r(Point3f(0, 0, 0), Vector3f(s, s, s));
        Float t0 = -1, t1 = -1;
        ASSERT_TRUE(ex::IntersectP(b, r, &t0, &t1)) << k;
        EXPECT_NEAR(t0, 1 / s, 4 * kU * (1 / s)) << k;
        EXPECT_NEAR(t1, 2 / s, 12 * kU * (2 / s)) << k;
        Ray back(Point3f(3, 3, 3), Vector3f(-s, -s, -s));
        ASSERT_TRUE(ex::IntersectP(b, back, &t0, &t1)) << k;
        EXPECT_NEAR(t0, 1 / s, 4 * kU * (1 / s)) << k;
        EXPECT_NEAR(t1, 2 / s, 12 * kU * (2 / s)) << k;
    }
}

// The BVH form alone, with arguments prepared as the text prescribes: hits
// toward the centre, misses beside the box and moving away, signed zeros
// included.
EXERCISE_TEST(Ex5_10_SlabHidden, PrecomputedReciprocalsGiveExactVerdicts) {
    int cases = 0;
    for (Float dx : kComponents)
        for (Float dy : kComponents)
            for (Float dz : kComponents) {
                Vector3f d(dx, dy, dz);
                if (dx == 0 && dy == 0 && dz == 0) continue;
                Vector3f invDir(1 / dx, 1 / dy, 1 / dz);
                int dirIsNeg[3] = {invDir.x < 0, invDir.y < 0, invDir.z < 0};
                Point3f toward(Float(0.5) - 2 * dx, Float(0.5) - 2 * dy,
                               Float(0.5) - 2 * dz);
                EXPECT_TRUE(ex::IntersectP(kUnitBox, Ray(toward, d), invDir, dirIsNeg));
                Point3f away(Float(0.5) + 2 * dx, Float(0.5) + 2 * dy,
                             Float(0.5) + 2 * dz);
                EXPECT_FALSE(ex::IntersectP(kUnitBox, Ray(away, d), invDir, dirIsNeg));
                if (dz == 0) {
                    Point3f beside(Float(0.5) - 2 * dx, Float(0.5) - 2 * dy, -1);
                    EXPECT_FALSE(
                        ex::IntersectP(kUnitBox, Ray(beside, d), invDir, dirIsNeg));
                }
                ++cases;
            }
    EXPECT_EQ(cases, 56);  // 4^3 sign patterns less the 8 zero vectors (+-0)
}

// The BVH form takes the near and far planes from the given signs: a ray
// along +z, once with the right signs, once claiming a negative z (near
// plane z = 1 at t = 2, far plane z = 0 at t = 1: empty), and once with the
// reciprocal and sign of the opposite direction (the box is behind it).
EXERCISE_TEST(Ex5_10_SlabHidden, UsesTheGivenSignsAndReciprocals) {
    const Ray r(Point3f(Float(0.5), Float(0.5), -1), Vector3f(0, 0, 1));
    Vector3f invDir(kInf, kInf, 1);
    int right[3] = {0, 0, 0};
    EXPECT_TRUE(ex::IntersectP(kUnitBox, r, invDir, right));
    // Claiming a negative z: the near plane is z = 1 at t = 2 and the far
    // plane z = 0 at t = 1, an empty interval.
    int wrongZ[3] = {0, 0, 1};
    EXPECT_FALSE(ex::IntersectP(kUnitBox, r, invDir, wrongZ));
    // A reciprocal of -1 on z with its sign: the box is behind the ray.
    Vector3f flipped(kInf, kInf, -1);
    int flippedNeg[3] = {0, 0, 1};
    EXPECT_FALSE(ex::IntersectP(kUnitBox, r, flipped, flippedNeg));
}

// A tMax at the true entry distance, rounded up to a Float: the exact ray
// reaches the box within [0, tMax], so the test must report a hit, even when
// the computed entry value rounds above tMax; and the reported interval stays
// within [0, tMax].
EXERCISE_TEST(Ex5_11_SlabHidden, TMaxAtTheTrueEntryDistance) {
    int hits = 0, roundedAbove = 0;
    for (int k = 3; k <= 2000; ++k) {
        Float d = Float(k);
        for (Float x0 : {Float(1), Float(5), Float(7), Float(11)}) {
            long double exact = (long double)x0 / k;
            Float tMax = Float(exact);
            if ((long double)tMax < exact)
                tMax = std::nextafter(tMax, kInf);
            Float near = x0 * (1 / d);
            if (near > tMax) ++roundedAbove;
            const Bounds3f b(Point3f(x0, -1, -1), Point3f(x0 + 1, 1, 1));
            Ray r(Point3f(0, 0, 0), Vector3f(d, 0, 0), tMax);
            Float t0 = -1, t1 = -1;
            bool hit = ex::IntersectP(b, r, &t0, &t1);
            EXPECT_TRUE(hit) << k << " " << x0;
            if (hit) {
                ++hits;
                EXPECT_LE(t0, t1);
                EXPECT_LE(t1, tMax);
            }
        }
    }
    EXPECT_EQ(hits, 1998 * 4);
    EXPECT_GT(roundedAbove, 0);  // the cases that need the widened extent
}

// Rays through a box edge at t = 1 exactly, as in the text's example, for
// many slopes: the entry on x and the exit on y coincide, and rounding of
// the far value must not turn the graze into a miss.
EXERCISE_TEST(Ex5_11_SlabHidden, GrazingEdgesForManySlopes) {
    int unwidenedMisses = 0;
    for (int k = 3; k <= 3000; ++k) {
        Float y = Float(k);
        const Bounds3f b(Point3f(1, y - 1, 0), Point3f(2, y, 1));
        Ray r(Point3f(0, 0, 0), Vector3f(1, y, Float(0.5)), Float(10));
        if (y * (1 / y) < 1) ++unwidenedMisses;
        Float t0 = -1, t1 = -1;
        ASSERT_TRUE(ex::IntersectP(b, r, &t0, &t1)) << k;
        EXPECT_EQ(t0, Float(1)) << k;
        EXPECT_GE(t1, Float(1)) << k;
        Vector3f invDir(1, 1 / y, 2);
        int dirIsNeg[3] = {0, 0, 0};
        EXPECT_TRUE(ex::IntersectP(b, r, invDir, dirIsNeg)) << k;
    }
    EXPECT_GT(unwidenedMisses, 0);
}
