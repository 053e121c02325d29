// Chapter 5, the slab test: exhaustive edge cases with exactly known answers.
//
// Every case goes through Check(), which runs both forms of
// Bounds3::IntersectP (with and without the reported interval, and the BVH
// form with a precomputed reciprocal direction), requires that they agree,
// and checks the invariants of a reported interval.

#include "lrt/core/slabtest.h"

#include "exercise_calls.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

using namespace lrt;

namespace {

const Float kInf = std::numeric_limits<Float>::infinity();
const Float kNaN = std::numeric_limits<Float>::quiet_NaN();
const Float kMax = std::numeric_limits<Float>::max();
// Unit roundoff u: half the distance from 1 to the next Float.
const Float kU = std::numeric_limits<Float>::epsilon() / 2;

// The number of cases of each exhaustive test below.
// 4 boxes, 3 axes, 2 signs, 4 zero signs, 125 origins, and those of the six
// tMax values (per origin) that are not negative:
constexpr int kAxisParallelCases = 53400;
constexpr int kBoundaryCases = 2 * 26 * 56 * 3;  // boxes, points, dirs, tMax
constexpr int kMovingAwayCases = 728;   // origins and directions that move away
constexpr int kEmptyBoxCases = 10 * 3 * 2 * 6 * 6 * 3 * 4;

std::string Hex(double v) {
    char buf[64];
    std::snprintf(buf, sizeof(buf), "%a", v);
    return buf;
}

std::string Describe(const Bounds3f &b, const Ray &r) {
    std::string s = "box [" + Hex(b.pMin.x) + " " + Hex(b.pMin.y) + " " +
                    Hex(b.pMin.z) + "] - [" + Hex(b.pMax.x) + " " +
                    Hex(b.pMax.y) + " " + Hex(b.pMax.z) + "], ray o (" +
                    Hex(r.o.x) + " " + Hex(r.o.y) + " " + Hex(r.o.z) +
                    ") d (" + Hex(r.d.x) + " " + Hex(r.d.y) + " " +
                    Hex(r.d.z) + ") tMax " + Hex(r.tMax);
    return s;
}

struct Result {
    bool hit;
    Float t0, t1;
};

// Both forms, with their agreement and the interval's invariants checked.
Result Check(const Bounds3f &b, const Ray &r) {
    const Float unset = -12345;
    Float t0 = unset, t1 = unset;
    bool hit = ex::IntersectP(b, r, &t0, &t1);
    bool hitNoOutput = ex::IntersectP(b, r);
    Float only0 = unset, only1 = unset;
    bool hitOnly0 = ex::IntersectP(b, r, &only0, nullptr);
    bool hitOnly1 = ex::IntersectP(b, r, nullptr, &only1);
    Vector3f invDir(1 / r.d.x, 1 / r.d.y, 1 / r.d.z);
    int dirIsNeg[3] = {invDir.x < 0, invDir.y < 0, invDir.z < 0};
    bool fast = ex::IntersectP(b, r, invDir, dirIsNeg);
    std::string what = Describe(b, r);
    EXPECT_EQ(hit, fast) << "the two IntersectP forms disagree: " << what;
    EXPECT_EQ(hit, hitNoOutput) << what;
    EXPECT_EQ(hit, hitOnly0) << what;
    EXPECT_EQ(hit, hitOnly1) << what;
    if (hit) {
        // Written both times, and the same both times (NaN-aware).
        EXPECT_TRUE(only0 == t0 || (std::isnan(only0) && std::isnan(t0)));
        EXPECT_TRUE(only1 == t1 || (std::isnan(only1) && std::isnan(t1)));
        EXPECT_FALSE(std::isnan(t0)) << what;
        if (!std::isnan(r.tMax)) {
            EXPECT_LE(Float(0), t0) << what;
            EXPECT_LE(t0, t1) << what;
            EXPECT_LE(t1, r.tMax) << what;
        }
    } else {
        // A miss leaves the outputs alone.
        EXPECT_EQ(t0, unset) << what;
        EXPECT_EQ(t1, unset) << what;
    }
    return {hit, t0, t1};
}

// The upper end of a reported interval is the exit value widened by at most
// a few units of roundoff, or tMax.
void ExpectExit(Float t1, Float exitT, Float tMax, const std::string &what) {
    if (exitT >= tMax) {
        EXPECT_EQ(t1, tMax) << what;
    } else {
        EXPECT_GE(t1, exitT) << what;
        EXPECT_LE(t1, exitT * (1 + 8 * kU)) << what;
    }
}

}  // namespace

// The widening constant of the text is exactly 1 + 6u in Float, the value
// the conservativeness argument of the chapter relies on.
TEST(SlabTest, WideningConstantIsOnePlusSixU) {
    EXPECT_EQ(1 + 2 * gamma(3), 1 + 6 * kU);
    EXPECT_GT(1 + 2 * gamma(3), Float(1));
}

// Axis-parallel rays, in every combination: each axis, both directions,
// +0 and -0 in the other two direction components, origins below, on the
// lower face, inside, on the upper face and above each slab, and tMax
// infinite, before, at, inside and after the box, and zero. Also for boxes
// that are flat (zero extent) on one axis.
EXERCISE_TEST(Ex5_9_SlabTest, AxisParallelRaysExhaustive) {
    const Bounds3f boxes[] = {
        Bounds3f(Point3f(1, 2, -3), Point3f(2, 6, -1)),
        Bounds3f(Point3f(1, 2, -3), Point3f(1, 6, -1)),   // flat in x
        Bounds3f(Point3f(1, 2, -3), Point3f(2, 2, -1)),   // flat in y
        Bounds3f(Point3f(1, 2, -3), Point3f(2, 6, -3)),   // flat in z
    };
    const int kPositions = 5;  // below, on min, middle, on max, above
    int cases = 0;
    for (const Bounds3f &b : boxes) {
        auto coord = [&](int axis, int pos) -> Float {
            Float lo = b.pMin[axis], hi = b.pMax[axis];
            switch (pos) {
            case 0: return lo - 2;
            case 1: return lo;
            case 2: return (lo + hi) / 2;
            case 3: return hi;
            default: return hi + 2;
            }
        };
        for (int axis = 0; axis < 3; ++axis)
            for (int sign = -1; sign <= 1; sign += 2)
                for (int zeros = 0; zeros < 4; ++zeros)
                    for (int px = 0; px < kPositions; ++px)
                        for (int py = 0; py < kPositions; ++py)
                            for (int pz = 0; pz < kPositions; ++pz) {
            int pos[3] = {px, py, pz};
            Point3f o(coord(0, px), coord(1, py), coord(2, pz));
            Vector3f d;
            int other = 0;
            for (int k = 0; k < 3; ++k) {
                if (k == axis) {
                    d[k] = Float(sign);
                } else {
                    d[k] = ((zeros >> other) & 1) ? -Float(0) : Float(0);
                    ++other;
                }
            }
            // Exact answer: the other coordinates must lie in their closed
            // slabs; along the axis the box occupies [enter, exit] in t.
            bool besideOk = true;
            for (int k = 0; k < 3; ++k)
                if (k != axis && (pos[k] == 0 || pos[k] == 4))
                    besideOk = false;
            Float lo = b.pMin[axis], hi = b.pMax[axis], oa = o[axis];
            Float enter = sign > 0 ? lo - oa : oa - hi;
            Float exit = sign > 0 ? hi - oa : oa - lo;
            Float tMaxes[] = {kInf,      enter / 2, enter,
                              (enter + exit) / 2,   exit * 2, Float(0)};
            for (Float tMax : tMaxes) {
                if (tMax < 0) continue;
                Ray r(o, d, tMax);
                bool expect = besideOk && exit >= 0 && enter <= tMax;
                Result res = Check(b, r);
                std::string what = Describe(b, r);
                ++cases;
                // A box entered after tMax by a clear margin is a miss; a
                // box entered at exactly tMax is a hit (closed intervals).
                EXPECT_EQ(res.hit, expect) << what;
                if (res.hit && expect) {
                    Float expect0 = std::max(Float(0), enter);
                    EXPECT_EQ(res.t0, expect0) << what;
                    ExpectExit(res.t1, exit, tMax, what);
                }
            }
                            }
    }
    EXPECT_EQ(cases, kAxisParallelCases);
}

// An origin on the boundary of the box is in the closed box: every ray
// from it hits, at t = 0, whatever its direction, including directions
// parallel to the face the origin lies on (the 0 * infinity = NaN case).
// Boundary points: the 6 face centers, 12 edge midpoints and 8 corners.
EXERCISE_TEST(Ex5_9_SlabTest, OriginOnTheBoundaryAlwaysHits) {
    const Bounds3f boxes[] = {
        Bounds3f(Point3f(-1, 0, 2), Point3f(3, 1, 6)),
        Bounds3f(Point3f(-1, 0, 2), Point3f(3, 0, 6)),  // flat in y
    };
    int cases = 0;
    for (const Bounds3f &b : boxes) {
        for (int cx = 0; cx < 3; ++cx)
            for (int cy = 0; cy < 3; ++cy)
                for (int cz = 0; cz < 3; ++cz) {
            int c[3] = {cx, cy, cz};
            if (cx == 1 && cy == 1 && cz == 1) continue;  // the center
            Point3f o;
            for (int k = 0; k < 3; ++k)
                o[k] = c[k] == 0 ? b.pMin[k]
                     : c[k] == 2 ? b.pMax[k]
                                 : (b.pMin[k] + b.pMax[k]) / 2;
            // All 26 directions with components in {-1, 0, 1}, every
            // zero as +0 and as -0 (the direction loop includes both).
            for (int dx = 0; dx < 4; ++dx)
                for (int dy = 0; dy < 4; ++dy)
                    for (int dz = 0; dz < 4; ++dz) {
                const Float values[4] = {-1, -Float(0), Float(0), 1};
                Vector3f d(values[dx], values[dy], values[dz]);
                if (d.x == 0 && d.y == 0 && d.z == 0) continue;
                for (Float tMax : {kInf, Float(1), Float(0)}) {
                    Ray r(o, d, tMax);
                    Result res = Check(b, r);
                    ++cases;
                    EXPECT_TRUE(res.hit) << Describe(b, r);
                    EXPECT_EQ(res.t0, Float(0)) << Describe(b, r);
                }
            }
        }
    }
    EXPECT_EQ(cases, kBoundaryCases);
}

// An origin outside the box that moves away from it, or parallel to it, in
// every axis on which it lies outside, never reaches the box.
EXERCISE_TEST(Ex5_9_SlabTest, OriginOutsideMovingAwayMisses) {
    const Bounds3f b(Point3f(-1, 0, 2), Point3f(3, 1, 6));
    int cases = 0;
    for (int cx = 0; cx < 3; ++cx)
        for (int cy = 0; cy < 3; ++cy)
            for (int cz = 0; cz < 3; ++cz) {
        int c[3] = {cx, cy, cz};
        if (cx == 1 && cy == 1 && cz == 1) continue;
        Point3f o;
        for (int k = 0; k < 3; ++k)
            o[k] = c[k] == 0 ? b.pMin[k] - Float(0.5)
                 : c[k] == 2 ? b.pMax[k] + Float(0.5)
                             : (b.pMin[k] + b.pMax[k]) / 2;
        const Float values[4] = {-1, -Float(0), Float(0), 1};
        for (int dx = 0; dx < 4; ++dx)
            for (int dy = 0; dy < 4; ++dy)
                for (int dz = 0; dz < 4; ++dz) {
            Vector3f d(values[dx], values[dy], values[dz]);
            if (d.x == 0 && d.y == 0 && d.z == 0) continue;
            bool away = true;
            for (int k = 0; k < 3; ++k) {
                if (c[k] == 0 && d[k] > 0) away = false;
                if (c[k] == 2 && d[k] < 0) away = false;
            }
            if (!away) continue;
            Ray r(o, d, kInf);
            ++cases;
            EXPECT_FALSE(Check(b, r).hit) << Describe(b, r);
        }
    }
    EXPECT_EQ(cases, kMovingAwayCases);
}

// Oblique rays from outside with exactly representable crossings: tMax
// before, at, between and after the crossings, and infinite.
EXERCISE_TEST(Ex5_9_SlabTest, TMaxBeforeAtAndAfterTheBox) {
    // Along d = (1, 2, 4) from the origin, the ray is in the box
    // [4, 10] x [2, 40] x [8, 100] for t in [max(4, 1, 2), min(10, 20, 25)].
    const Bounds3f b(Point3f(4, 2, 8), Point3f(10, 40, 100));
    const Point3f o(0, 0, 0);
    const Vector3f d(1, 2, 4);
    struct Case {
        Float tMax;
        bool hit;
    } cases[] = {{0, false}, {1, false},  {2, false},   {3.5, false},
                 {4, true},  {7, true},   {10, true},   {11, true},
                 {1e6, true}, {kInf, true}};
    for (const Case &c : cases) {
        Ray r(o, d, c.tMax);
        Result res = Check(b, r);
        EXPECT_EQ(res.hit, c.hit) << Describe(b, r);
        if (res.hit) {
            EXPECT_EQ(res.t0, Float(4));
            ExpectExit(res.t1, 10, c.tMax, Describe(b, r));
        }
    }
    // The same ray reversed has the box behind it.
    Ray back(o, Vector3f(-1, -2, -4), kInf);
    EXPECT_FALSE(Check(b, back).hit);
    // Starting inside: the interval starts at 0.
    Ray inside(Point3f(5, 10, 20), d, kInf);
    Result in = Check(b, inside);
    EXPECT_TRUE(in.hit);
    EXPECT_EQ(in.t0, Float(0));
    ExpectExit(in.t1, 5, kInf, Describe(b, inside));
    // Starting inside with tMax = 0: only the origin, which is inside.
    Ray point(Point3f(5, 10, 20), d, 0);
    Result p = Check(b, point);
    EXPECT_TRUE(p.hit);
    EXPECT_EQ(p.t0, Float(0));
    EXPECT_EQ(p.t1, Float(0));
}

// A tMax just short of the entry: rays that stop within the widening margin
// of the box are reported as hits (conservative), rays that stop clearly
// short are not.
EXERCISE_TEST(Ex5_11_SlabTest, TMaxWithinRoundingMarginOfTheEntry) {
    const Bounds3f b(Point3f(4, 2, 8), Point3f(10, 40, 100));
    const Ray justShort(Point3f(0, 0, 0), Vector3f(1, 2, 4),
                        std::nextafter(Float(4), Float(0)));
    EXPECT_TRUE(Check(b, justShort).hit);
    const Ray clearlyShort(Point3f(0, 0, 0), Vector3f(1, 2, 4),
                           4 * (1 - 16 * kU));
    EXPECT_FALSE(Check(b, clearlyShort).hit);
}

// dirIsNeg must come from the reciprocal: for a direction component of -0,
// d < 0 is false while 1/d = -infinity is negative. With the signs taken
// from the reciprocal, a ray inside the slab hits; with signs taken from
// the direction, the near value becomes +infinity and the box is missed.
EXERCISE_TEST(Ex5_10_SlabTest, SignsMustComeFromTheReciprocal) {
    const Bounds3f b(Point3f(0, 0, 0), Point3f(1, 1, 1));
    const Ray r(Point3f(Float(0.5), Float(0.5), -1), Vector3f(-Float(0), 0, 1));
    Vector3f invDir(1 / r.d.x, 1 / r.d.y, 1 / r.d.z);
    int right[3] = {invDir.x < 0, invDir.y < 0, invDir.z < 0};
    int fromDirection[3] = {r.d.x < 0, r.d.y < 0, r.d.z < 0};
    EXPECT_EQ(right[0], 1);
    EXPECT_EQ(fromDirection[0], 0);
    EXPECT_TRUE(ex::IntersectP(b, r, invDir, right));
    EXPECT_TRUE(Check(b, r).hit);
    EXPECT_FALSE(ex::IntersectP(b, r, invDir, fromDirection));
}

// The example of the text: a ray through a box edge (and through a vertex
// of the triangle that the box bounds) at t = 1 exactly. Without widening,
// the computed near value 1 exceeds the computed far value 107 * (1/107),
// which rounds to 1 - u in float and in double.
EXERCISE_TEST(Ex5_11_SlabTest, GrazingEdgeExampleFromTheText) {
    const Bounds3f b(Point3f(1, 106, 0), Point3f(2, 107, 1));
    const Ray r(Point3f(0, 0, 0), Vector3f(1, 107, Float(0.5)));
    // The ray's point at t = 1 is on the box's edge, exactly.
    EXPECT_EQ(r.o.x + r.d.x, b.pMin.x);
    EXPECT_EQ(r.o.y + r.d.y, b.pMax.y);
    // What the unwidened test would compare.
    Float inv107 = 1 / Float(107);
    Float farY = (Float(107) - 0) * inv107;
    Float nearX = (Float(1) - 0) * (1 / Float(1));
    EXPECT_EQ(nearX, Float(1));
    EXPECT_EQ(farY, 1 - kU);
    EXPECT_GT(nearX, farY);
    // The widened test finds the hit.
    Result res = Check(b, r);
    EXPECT_TRUE(res.hit);
    EXPECT_EQ(res.t0, Float(1));
    EXPECT_GE(res.t1, Float(1));
}

// Boxes far from the origin, where the spacing of Floats is large.
EXERCISE_TEST(Ex5_9_SlabTest, BoxesFarFromTheOrigin) {
    const Float c = 1e7f;
    const Bounds3f b(Point3f(c, c, c), Point3f(c + 8, c + 8, c + 8));
    // From the origin toward the center, and through an edge exactly.
    EXPECT_TRUE(Check(b, Ray(Point3f(0, 0, 0),
                             Vector3f(c + 4, c + 4, c + 4))).hit);
    EXPECT_TRUE(Check(b, Ray(Point3f(0, 0, 0),
                             Vector3f(c, c + 8, c + 4))).hit);
    EXPECT_TRUE(Check(b, Ray(Point3f(0, 0, 0),
                             Vector3f(c + 8, c, c + 8))).hit);
    // Aimed 200 units beside the box (2e-5 relative): a clear miss.
    EXPECT_FALSE(Check(b, Ray(Point3f(0, 0, 0),
                              Vector3f(c + 4, c - 200, c + 4))).hit);
    EXPECT_FALSE(Check(b, Ray(Point3f(0, 0, 0),
                              Vector3f(c + 208, c + 4, c + 4))).hit);
    // Axis-parallel rays at that distance, from near and from afar.
    Result z = Check(b, Ray(Point3f(c + 4, c + 4, 0), Vector3f(0, 0, 1)));
    EXPECT_TRUE(z.hit);
    EXPECT_EQ(z.t0, c);
    EXPECT_GE(z.t1, c + 8);
    EXPECT_TRUE(Check(b, Ray(Point3f(c + 4, c + 4, c + 9),
                             Vector3f(0, 0, -1))).hit);
    EXPECT_TRUE(Check(b, Ray(Point3f(c + 8, c + 8, c + 9),
                             Vector3f(-Float(0), Float(0), -1))).hit);
    EXPECT_FALSE(Check(b, Ray(Point3f(c + 9, c + 4, 0),
                              Vector3f(0, 0, 1))).hit);
    EXPECT_FALSE(Check(b, Ray(Point3f(c + 4, c + 4, c + 9),
                              Vector3f(0, 0, 1))).hit);
    // A ray from the far side, far away, through the center.
    EXPECT_TRUE(Check(b, Ray(Point3f(2 * c, 2 * c, 2 * c),
                             Vector3f(-1, -1, -1))).hit);
}

// Tiny boxes, 1e-7 on a side, near and away from the origin.
EXERCISE_TEST(Ex5_9_SlabTest, TinyBoxes) {
    const Float s = 1e-7f;
    const Bounds3f b(Point3f(s, s, s), Point3f(2 * s, 2 * s, 2 * s));
    // From the origin toward the center: in the box for t in [2/3, 4/3].
    Result c = Check(b, Ray(Point3f(0, 0, 0),
                            Vector3f(1.5f * s, 1.5f * s, 1.5f * s)));
    EXPECT_TRUE(c.hit);
    EXPECT_NEAR(c.t0, 2.0 / 3.0, 1e-6);
    EXPECT_NEAR(c.t1, 4.0 / 3.0, 1e-6);
    // From distance 1 along x, through the box and just beside it.
    EXPECT_TRUE(Check(b, Ray(Point3f(-1, 1.5f * s, 1.5f * s),
                             Vector3f(1, 0, 0))).hit);
    EXPECT_TRUE(Check(b, Ray(Point3f(-1, 2 * s, s),
                             Vector3f(1, 0, -Float(0)))).hit);
    EXPECT_FALSE(Check(b, Ray(Point3f(-1, 2.5f * s, 1.5f * s),
                              Vector3f(1, 0, 0))).hit);
    EXPECT_FALSE(Check(b, Ray(Point3f(-1, 1.5f * s, 0.5f * s),
                              Vector3f(1, 0, 0))).hit);
    // Aimed from far away with a tiny offset: the box subtends 1e-7 rad.
    EXPECT_TRUE(Check(b, Ray(Point3f(-1, -1, -1),
                             Vector3f(1 + 1.5f * s, 1 + 1.5f * s,
                                      1 + 1.5f * s))).hit);
    // Aimed 1e-5 beside it: a clear miss even in float, where the widening
    // margin at this distance is about 13u, or 8e-7.
    EXPECT_FALSE(Check(b, Ray(Point3f(-1, -1, -1),
                              Vector3f(1 + 1.5f * s, 1 + 1e-5f,
                                       1 + 1.5f * s))).hit);
    // A box of 1e-7 far from the origin (at 1): a different relative size.
    const Bounds3f far(Point3f(1, 1, 1), Point3f(1 + s, 1 + s, 1 + s));
    EXPECT_TRUE(Check(far, Ray(Point3f(0, 0, 0), Vector3f(1, 1, 1))).hit);
    EXPECT_FALSE(Check(far, Ray(Point3f(0, 1 - s, 1),
                                Vector3f(1, 0, 0))).hit);
}

// The empty box of the default constructor is never hit by a ray that is
// not NaN on all three axes.
EXERCISE_TEST(Ex5_9_SlabTest, EmptyBoxIsNeverHit) {
    const Bounds3f empty;
    const Float coords[] = {0,    1,     -1,    -Float(0), 1e30f,
                            -1e30f, kMax, -kMax, kInf,      -kInf};
    const Float dirs[] = {1, -1, Float(0), -Float(0), 1e-30f, -1e30f};
    int cases = 0;
    for (Float ox : coords)
        for (Float oy : {Float(0), kMax, -kInf})
            for (Float oz : {Float(0), -kMax})
                for (Float dx : dirs)
                    for (Float dy : dirs)
                        for (Float dz : {Float(1), -Float(0), Float(0)}) {
            for (Float tMax : {kInf, Float(1), Float(0), kMax}) {
                Ray r(Point3f(ox, oy, oz), Vector3f(dx, dy, dz), tMax);
                ++cases;
                EXPECT_FALSE(Check(empty, r).hit) << Describe(empty, r);
            }
        }
    // NaN on one or two axes is not enough to hit it either.
    EXPECT_FALSE(Check(empty, Ray(Point3f(kNaN, 0, 0),
                                  Vector3f(1, 1, 1))).hit);
    EXPECT_FALSE(Check(empty, Ray(Point3f(kNaN, kNaN, 0),
                                  Vector3f(1, 1, 1))).hit);
    EXPECT_FALSE(Check(empty, Ray(Point3f(0, 0, 0),
                                  Vector3f(kNaN, kNaN, 1))).hit);
    EXPECT_EQ(cases, kEmptyBoxCases);
}

// The direction is the zero vector: the "ray" is its origin, and it hits
// the box exactly when the origin lies in the closed box, even for an
// infinite tMax (a box reached only at t = infinity is not hit).
EXERCISE_TEST(Ex5_9_SlabTest, ZeroDirectionHitsOnlyWhenTheOriginIsInside) {
    const Bounds3f b(Point3f(0, 0, 0), Point3f(1, 2, 3));
    const Float zeros[2] = {Float(0), -Float(0)};
    const Float xs[] = {-1, 0, Float(0.5), 1, 2};
    for (int signs = 0; signs < 8; ++signs) {
        Vector3f d(zeros[signs & 1], zeros[(signs >> 1) & 1],
                   zeros[(signs >> 2) & 1]);
        for (Float x : xs)
            for (Float tMax : {kInf, Float(5)}) {
                Ray r(Point3f(x, 1, 1), d, tMax);
                Result res = Check(b, r);
                bool inside = x >= 0 && x <= 1;
                EXPECT_EQ(res.hit, inside) << Describe(b, r);
                if (res.hit) {
                    EXPECT_EQ(res.t0, Float(0));
                    EXPECT_EQ(res.t1, tMax);
                }
            }
    }
}

// Boxes with infinite extent contain every finite point.
EXERCISE_TEST(Ex5_9_SlabTest, InfiniteBoxes) {
    const Bounds3f all(Point3f(-kInf, -kInf, -kInf),
                       Point3f(kInf, kInf, kInf));
    const Bounds3f halfSpace(Point3f(0, -kInf, -kInf),
                             Point3f(kInf, kInf, kInf));
    Result r1 = Check(all, Ray(Point3f(1, 2, 3), Vector3f(1, -1, 0), 7));
    EXPECT_TRUE(r1.hit);
    EXPECT_EQ(r1.t0, Float(0));
    EXPECT_EQ(r1.t1, Float(7));
    Result r2 = Check(halfSpace, Ray(Point3f(-2, 5, 5), Vector3f(1, 0, 0)));
    EXPECT_TRUE(r2.hit);
    EXPECT_EQ(r2.t0, Float(2));
    EXPECT_FALSE(Check(halfSpace, Ray(Point3f(-2, 5, 5),
                                      Vector3f(-1, 0, 0))).hit);
    EXPECT_FALSE(Check(halfSpace, Ray(Point3f(-2, 5, 5),
                                      Vector3f(0, 1, 1))).hit);
}

// NaN inputs. The defined result (see the text): a slab whose near or far
// value is NaN places no constraint on the ray. So a NaN in one component of
// the origin or the direction removes that slab from the test, a ray that is
// NaN on all three axes hits every box with the interval [0, tMax], and a
// NaN tMax hits every box that is not reached only at infinite t.
EXERCISE_TEST(Ex5_9_SlabTest, NaNInputsHaveTheDefinedResult) {
    const Bounds3f b(Point3f(0, 0, 0), Point3f(1, 1, 1));
    // NaN origin y: the y slab drops out; x and z decide.
    Result a = Check(b, Ray(Point3f(-5, kNaN, Float(0.5)), Vector3f(1, 0, 0)));
    EXPECT_TRUE(a.hit);
    EXPECT_EQ(a.t0, Float(5));
    EXPECT_FALSE(Check(b, Ray(Point3f(-5, kNaN, 7), Vector3f(1, 0, 0))).hit);
    EXPECT_FALSE(Check(b, Ray(Point3f(-5, kNaN, Float(0.5)),
                              Vector3f(-1, 0, 0))).hit);
    // NaN direction z: the z slab drops out.
    Result c = Check(b, Ray(Point3f(-5, Float(0.5), 9),
                            Vector3f(1, 0, kNaN)));
    EXPECT_TRUE(c.hit);
    EXPECT_EQ(c.t0, Float(5));
    EXPECT_FALSE(Check(b, Ray(Point3f(-5, 3, 9), Vector3f(1, 0, kNaN))).hit);
    // NaN on every axis: every box is hit, even the empty one.
    const Ray allNaN(Point3f(kNaN, kNaN, kNaN), Vector3f(1, 1, 1), 3);
    Result n = Check(b, allNaN);
    EXPECT_TRUE(n.hit);
    EXPECT_EQ(n.t0, Float(0));
    EXPECT_EQ(n.t1, Float(3));
    EXPECT_TRUE(Check(Bounds3f(), allNaN).hit);
    const Ray nanDir(Point3f(7, 7, 7), Vector3f(kNaN, kNaN, kNaN));
    EXPECT_TRUE(Check(b, nanDir).hit);
    // NaN tMax: nothing can be rejected, not even a box behind the ray.
    Result m = Check(b, Ray(Point3f(2, Float(0.5), Float(0.5)),
                            Vector3f(1, 0, 0), kNaN));
    EXPECT_TRUE(m.hit);
    EXPECT_TRUE(std::isnan(m.t1));
    // ...except a box reached only at infinite t.
    EXPECT_FALSE(Check(b, Ray(Point3f(-1, Float(0.5), Float(0.5)),
                              Vector3f(0, 0, 0), kNaN)).hit);
}
