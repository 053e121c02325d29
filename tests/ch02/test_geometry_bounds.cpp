// Tests for the bounding boxes of Chapter 2 (Bounds2 and Bounds3 in
// lrt/core/geometry.h).
//
// Oracles: set semantics checked point by point (a point is in the union,
// intersection, ... exactly when the definition says so), brute-force
// minima and maxima, long double measures, and the empty-box conventions
// stated in the text.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <sstream>
#include <vector>

#include "lrt/core/geometry.h"

#include "exercise_calls.h"

using namespace lrt;

namespace {

typedef long double Ld;

constexpr int kRandomCases = 20000;
constexpr uint64_t kSeed = 0x6c72742d626f7864ull;  // "lrt-boxd"

const Ld kU = Ld(std::numeric_limits<Float>::epsilon()) / 2;
const Float kNaN = std::numeric_limits<Float>::quiet_NaN();

Float RandomUniform(std::mt19937_64 &rng, double lo, double hi) {
    return Float(std::uniform_real_distribution<double>(lo, hi)(rng));
}

Point3f RandomPoint(std::mt19937_64 &rng, double lo = -10, double hi = 10) {
    return Point3f(RandomUniform(rng, lo, hi), RandomUniform(rng, lo, hi),
                   RandomUniform(rng, lo, hi));
}

Bounds3f RandomBox(std::mt19937_64 &rng, double lo = -10, double hi = 10) {
    return Bounds3f(RandomPoint(rng, lo, hi), RandomPoint(rng, lo, hi));
}

// Points that probe a box: random points, its corners, and points just
// inside and just outside its faces.
std::vector<Point3f> ProbePoints(std::mt19937_64 &rng,
                                 const std::vector<Bounds3f> &boxes) {
    std::vector<Point3f> pts;
    for (int i = 0; i < 64; ++i) pts.push_back(RandomPoint(rng, -12, 12));
    for (const Bounds3f &b : boxes) {
        if (b.IsEmpty()) continue;
        for (int c = 0; c < 8; ++c) {
            Point3f p = b.Corner(c);
            pts.push_back(p);
            for (int k = 0; k < 3; ++k) {
                Point3f q = p;
                q[k] = NextFloatUp(p[k]);
                pts.push_back(q);
                q[k] = NextFloatDown(p[k]);
                pts.push_back(q);
            }
        }
    }
    return pts;
}

bool InClosed(const Point3f &p, const Bounds3f &b) {
    for (int k = 0; k < 3; ++k)
        if (!(b.pMin[k] <= p[k] && p[k] <= b.pMax[k])) return false;
    return true;
}

}  // namespace

// ---------------------------------------------------------------------------
// Construction and the empty box

TEST(Bounds3, DefaultIsTheEmptyBox) {
    Bounds3f b;
    EXPECT_TRUE(b.IsEmpty());
    EXPECT_FALSE(b.IsDegenerate());
    EXPECT_EQ(b.pMin.x, std::numeric_limits<Float>::max());
    EXPECT_EQ(b.pMax.x, std::numeric_limits<Float>::lowest());
    EXPECT_EQ(b.SurfaceArea(), 0);
    EXPECT_EQ(b.Volume(), 0);
    EXPECT_EQ(Bounds3i().Volume(), 0);
    EXPECT_EQ(Bounds3i().SurfaceArea(), 0);
    std::mt19937_64 rng(kSeed);
    for (int i = 0; i < 1000; ++i) {
        Point3f p = RandomPoint(rng, -1e30, 1e30);
        ASSERT_FALSE(Inside(p, b));
        ASSERT_FALSE(InsideExclusive(p, b));
    }
    Float m = std::numeric_limits<Float>::max();
    EXPECT_FALSE(Inside(Point3f(m, m, m), b));
    EXPECT_FALSE(Inside(Point3f(-m, -m, -m), b));
    EXPECT_FALSE(Overlaps(b, b));
    EXPECT_FALSE(Overlaps(b, Bounds3f(Point3f(-m, -m, -m), Point3f(m, m, m))));
    Point3f c;
    Float r = -1;
    b.BoundingSphere(&c, &r);
    EXPECT_EQ(r, 0);
}

TEST(Bounds3, PointAndTwoPointConstructors) {
    Point3f p(1, 2, 3);
    Bounds3f b(p);
    EXPECT_EQ(b.pMin, p);
    EXPECT_EQ(b.pMax, p);
    EXPECT_FALSE(b.IsEmpty());
    EXPECT_TRUE(b.IsDegenerate());
    EXPECT_TRUE(Inside(p, b));
    EXPECT_FALSE(InsideExclusive(p, b));
    EXPECT_EQ(b.SurfaceArea(), 0);
    EXPECT_EQ(b.Volume(), 0);
    // Any two opposite corners, in any order, give the same box.
    Bounds3f c(Point3f(4, -1, 3), Point3f(0, 5, -2));
    EXPECT_EQ(c.pMin, Point3f(0, -1, -2));
    EXPECT_EQ(c.pMax, Point3f(4, 5, 3));
    EXPECT_EQ(Bounds3f(Point3f(0, 5, 3), Point3f(4, -1, -2)), c);
    EXPECT_EQ(Bounds3f(c.pMax, c.pMin), c);
    EXPECT_FALSE(c.IsEmpty());
    EXPECT_FALSE(c.IsDegenerate());
    EXPECT_TRUE(c != b);
}

TEST(Bounds3, IndexingAndCorners) {
    Bounds3f b(Point3f(0, 1, 2), Point3f(3, 4, 5));
    EXPECT_EQ(b[0], b.pMin);
    EXPECT_EQ(b[1], b.pMax);
    b[1] = Point3f(6, 7, 8);
    EXPECT_EQ(b.pMax, Point3f(6, 7, 8));
    const Bounds3f &cb = b;
    EXPECT_THROW(cb[2], std::out_of_range);
    EXPECT_THROW(b[-1], std::out_of_range);
    for (int c = 0; c < 8; ++c) {
        Point3f p = b.Corner(c);
        EXPECT_EQ(p.x, (c & 1) ? b.pMax.x : b.pMin.x);
        EXPECT_EQ(p.y, (c & 2) ? b.pMax.y : b.pMin.y);
        EXPECT_EQ(p.z, (c & 4) ? b.pMax.z : b.pMin.z);
        EXPECT_TRUE(Inside(p, b));
        for (int d = 0; d < c; ++d) EXPECT_NE(p, b.Corner(d));
    }
    EXPECT_EQ(b.Corner(0), b.pMin);
    EXPECT_EQ(b.Corner(7), b.pMax);
    EXPECT_THROW(b.Corner(8), std::out_of_range);
    EXPECT_THROW(b.Corner(-1), std::out_of_range);
}

// ---------------------------------------------------------------------------
// Measures

TEST(Bounds3, DiagonalSurfaceAreaVolume) {
    Bounds3i bi(Point3i(0, 0, 0), Point3i(2, 3, 4));
    EXPECT_EQ(bi.Diagonal(), Vector3i(2, 3, 4));
    EXPECT_EQ(bi.SurfaceArea(), 52);
    EXPECT_EQ(bi.Volume(), 24);
    std::mt19937_64 rng(kSeed + 1);
    for (int i = 0; i < kRandomCases; ++i) {
        Bounds3f b = RandomBox(rng);
        Ld dx = Ld(b.pMax.x) - b.pMin.x, dy = Ld(b.pMax.y) - b.pMin.y,
           dz = Ld(b.pMax.z) - b.pMin.z;
        Vector3f d = b.Diagonal();
        ASSERT_LE(std::abs(d.x - dx), kU * dx);
        Ld area = 2 * (dx * dy + dx * dz + dy * dz);
        Ld vol = dx * dy * dz;
        ASSERT_LE(std::abs(b.SurfaceArea() - area), 6 * kU * area);
        ASSERT_LE(std::abs(b.Volume() - vol), 6 * kU * vol);
    }
}

TEST(Bounds3, MaximumExtent) {
    EXPECT_EQ(Bounds3f(Point3f(0, 0, 0), Point3f(3, 1, 2)).MaximumExtent(),
              0);
    EXPECT_EQ(Bounds3f(Point3f(0, 0, 0), Point3f(1, 3, 2)).MaximumExtent(),
              1);
    EXPECT_EQ(Bounds3f(Point3f(0, 0, 0), Point3f(1, 2, 3)).MaximumExtent(),
              2);
    std::mt19937_64 rng(kSeed + 2);
    std::uniform_int_distribution<int> d(0, 3);
    for (int i = 0; i < kRandomCases; ++i) {
        // Small integer extents produce ties.
        Bounds3f b(Point3f(0, 0, 0),
                   Point3f(Float(d(rng)), Float(d(rng)), Float(d(rng))));
        Vector3f diag = b.Diagonal();
        int axis = b.MaximumExtent();
        ASSERT_TRUE(axis >= 0 && axis < 3);
        ASSERT_EQ(diag[axis], MaxComponent(diag)) << b;
    }
}

TEST(Bounds3, LerpAndOffsetAreInverses) {
    std::mt19937_64 rng(kSeed + 3);
    for (int i = 0; i < kRandomCases; ++i) {
        Bounds3f b = RandomBox(rng);
        ASSERT_EQ(b.Lerp(Point3f(0, 0, 0)), b.pMin);
        ASSERT_EQ(b.Lerp(Point3f(1, 1, 1)), b.pMax);
        ASSERT_EQ(b.Offset(b.pMin), Vector3f(0, 0, 0));
        Point3f t(RandomUniform(rng, 0, 1), RandomUniform(rng, 0, 1),
                  RandomUniform(rng, 0, 1));
        Point3f p = b.Lerp(t);
        ASSERT_TRUE(Inside(p, b));
        Vector3f o = b.Offset(p);
        for (int k = 0; k < 3; ++k) {
            Ld extent = Ld(b.pMax[k]) - b.pMin[k];
            if (extent < 1e-3L) continue;
            Ld scale = std::abs(Ld(b.pMin[k])) + std::abs(Ld(b.pMax[k]));
            Ld tol = 8 * kU * scale / extent + 4 * kU;
            ASSERT_LE(std::abs(o[k] - t[k]), tol) << b << " " << t;
        }
        // The offset of a corner is 1 along every axis.
        Vector3f om = b.Offset(b.pMax);
        for (int k = 0; k < 3; ++k) ASSERT_EQ(om[k], 1);
    }
    Bounds3f b(Point3f(0, 0, 0), Point3f(2, 4, 8));
    EXPECT_EQ(b.Offset(Point3f(-2, 8, 4)), Vector3f(-1, 2, 0.5f));
}

TEST(Bounds3, OffsetOfDegenerateAxisIsFinite) {
    Bounds3f b(Point3f(0, 0, 5), Point3f(2, 4, 5));
    Vector3f o = b.Offset(Point3f(1, 1, 5));
    EXPECT_EQ(o, Vector3f(0.5f, 0.25f, 0));
    EXPECT_FALSE(b.Offset(Point3f(1, 1, 7)).HasNaNs());
    EXPECT_EQ(b.Offset(Point3f(1, 1, 7)).z, 2);
    EXPECT_TRUE(b.IsDegenerate());
}

TEST(Bounds3, BoundingSphereContainsCorners) {
    std::mt19937_64 rng(kSeed + 4);
    for (int i = 0; i < kRandomCases / 4; ++i) {
        Bounds3f b = RandomBox(rng);
        Point3f c;
        Float r;
        b.BoundingSphere(&c, &r);
        ASSERT_TRUE(Inside(c, b));
        Ld halfDiag = std::sqrt(std::pow(Ld(b.pMax.x) - b.pMin.x, 2) +
                                std::pow(Ld(b.pMax.y) - b.pMin.y, 2) +
                                std::pow(Ld(b.pMax.z) - b.pMin.z, 2)) /
                      2;
        ASSERT_LE(std::abs(r - halfDiag), 8 * kU * (halfDiag + 20));
        // Up to rounding errors of the size of the coordinates.
        Float m = std::max(MaxComponent(Abs(Vector3f(b.pMin))),
                           MaxComponent(Abs(Vector3f(b.pMax))));
        for (int k = 0; k < 8; ++k)
            ASSERT_LE(Distance(c, b.Corner(k)), r + 8 * kU * (r + m));
    }
    Point3f c;
    Float r;
    Bounds3f(Point3f(1, 2, 3)).BoundingSphere(&c, &r);
    EXPECT_EQ(c, Point3f(1, 2, 3));
    EXPECT_EQ(r, 0);
    Bounds3f(Point3f(-1, -1, -1), Point3f(1, 1, 1)).BoundingSphere(&c, &r);
    EXPECT_EQ(c, Point3f(0, 0, 0));
    EXPECT_LE(std::abs(r - std::sqrt(Ld(3))), 2 * kU * 2);
}

// ---------------------------------------------------------------------------
// Union, intersection and containment

EXERCISE_TEST(Ex2_14_Bounds3, UnionWithEmptyIsIdentity) {
    Point3f p(1, -2, 3);
    EXPECT_EQ(Union(Bounds3f(), p), Bounds3f(p));
    EXPECT_EQ(Union(Bounds3i(), Point3i(4, 5, 6)), Bounds3i(Point3i(4, 5, 6)));
    Bounds3f b(Point3f(0, 0, 0), Point3f(1, 2, 3));
    EXPECT_EQ(ex::Union(Bounds3f(), b), b);
    EXPECT_EQ(ex::Union(b, Bounds3f()), b);
    EXPECT_EQ(ex::Union(Bounds3f(), Bounds3f()), Bounds3f());
    EXPECT_TRUE(ex::Union(Bounds3f(), Bounds3f()).IsEmpty());
}

TEST(Bounds3, UnionOfPointsIsTheirBoundingBox) {
    std::mt19937_64 rng(kSeed + 5);
    for (int i = 0; i < kRandomCases / 20; ++i) {
        int n = 1 + i % 40;
        std::vector<Point3f> pts;
        Bounds3f b;
        for (int j = 0; j < n; ++j) {
            pts.push_back(RandomPoint(rng));
            b = Union(b, pts.back());
        }
        // Brute force: extremes over all points.
        for (int k = 0; k < 3; ++k) {
            Float lo = pts[0][k], hi = pts[0][k];
            for (const Point3f &p : pts) {
                if (p[k] < lo) lo = p[k];
                if (p[k] > hi) hi = p[k];
            }
            ASSERT_EQ(b.pMin[k], lo);
            ASSERT_EQ(b.pMax[k], hi);
        }
        for (const Point3f &p : pts) ASSERT_TRUE(Inside(p, b));
    }
}

EXERCISE_TEST(Ex2_14_Bounds3, UnionContainsBothAndIsSetUnionHull) {
    std::mt19937_64 rng(calls::Seed(kSeed + 6));
    for (int i = 0; i < kRandomCases / 20; ++i) {
        Bounds3f a = RandomBox(rng), b = RandomBox(rng);
        Point3f p = RandomPoint(rng);
        Bounds3f u = ex::Union(a, b), up = Union(a, p);
        ASSERT_EQ(u, ex::Union(b, a));
        ASSERT_TRUE(Inside(p, up));
        for (int c = 0; c < 8; ++c) {
            ASSERT_TRUE(Inside(a.Corner(c), u));
            ASSERT_TRUE(Inside(b.Corner(c), u));
            ASSERT_TRUE(Inside(a.Corner(c), up));
        }
        // Smallest: every face of the union touches one of the inputs.
        for (int k = 0; k < 3; ++k) {
            ASSERT_TRUE(u.pMin[k] == a.pMin[k] || u.pMin[k] == b.pMin[k]);
            ASSERT_TRUE(u.pMax[k] == a.pMax[k] || u.pMax[k] == b.pMax[k]);
            ASSERT_TRUE(up.pMin[k] == a.pMin[k] || up.pMin[k] == p[k]);
            ASSERT_TRUE(up.pMax[k] == a.pMax[k] || up.pMax[k] == p[k]);
        }
    }
}

TEST(Bounds3, UnionIgnoresNaNCoordinates) {
    Bounds3f b(Point3f(0, 0, 0), Point3f(1, 1, 1));
    Bounds3f u = Union(b, Point3f(kNaN, 2, kNaN));
    EXPECT_FALSE(u.pMin.HasNaNs());
    EXPECT_FALSE(u.pMax.HasNaNs());
    EXPECT_EQ(u, Bounds3f(Point3f(0, 0, 0), Point3f(1, 2, 1)));
    // A NaN point added to the empty box leaves it empty along that axis.
    Bounds3f e = Union(Bounds3f(), Point3f(kNaN, kNaN, kNaN));
    EXPECT_TRUE(e.IsEmpty());
    EXPECT_FALSE(Inside(Point3f(kNaN, 0, 0), b));
    EXPECT_FALSE(InsideExclusive(Point3f(0, 0, kNaN), b));
}

EXERCISE_TEST(Ex2_14_Bounds3, InfiniteCoordinates) {
    Bounds3f b(Point3f(0, 0, 0), Point3f(1, 1, 1));
    Bounds3f u = Union(b, Point3f(Infinity, 0, -Infinity));
    EXPECT_EQ(u.pMax.x, Infinity);
    EXPECT_EQ(u.pMin.z, -Infinity);
    EXPECT_FALSE(u.IsEmpty());
    Bounds3f all(Point3f(-Infinity, -Infinity, -Infinity),
                 Point3f(Infinity, Infinity, Infinity));
    EXPECT_TRUE(Inside(Point3f(1e30f, -1e30f, 0), all));
    EXPECT_TRUE(Inside(Point3f(Infinity, 0, 0), all));
    EXPECT_FALSE(InsideExclusive(Point3f(Infinity, 0, 0), all));
    EXPECT_TRUE(InsideExclusive(Point3f(-Infinity, 0, 0), all));
    EXPECT_EQ(ex::Intersect(all, b), b);
    EXPECT_TRUE(Overlaps(all, b));
    // The empty box overlaps nothing, not even a box of infinite extent.
    EXPECT_FALSE(Overlaps(Bounds3f(), all));
    EXPECT_FALSE(Overlaps(all, Bounds3f()));
    EXPECT_TRUE(ex::Intersect(all, Bounds3f()).IsEmpty());
}

EXERCISE_TEST(Ex2_14_Bounds3, IntersectIsTheSetIntersection) {
    std::mt19937_64 rng(calls::Seed(kSeed + 7));
    int nonEmpty = 0, empty = 0;
    for (int i = 0; i < kRandomCases / 20; ++i) {
        Bounds3f a = RandomBox(rng), b = RandomBox(rng);
        // Shrink some boxes so that roughly half the pairs are disjoint.
        if (i % 2) b = Bounds3f(b.pMin, b.pMin + (b.pMax - b.pMin) * 0.2f);
        Bounds3f x = ex::Intersect(a, b);
        ASSERT_EQ(x, ex::Intersect(b, a));
        if (x.IsEmpty()) {
            ++empty;
            ASSERT_EQ(x, Bounds3f()) << "empty results are canonical";
            ASSERT_FALSE(Overlaps(a, b));
        } else {
            ++nonEmpty;
            ASSERT_TRUE(Overlaps(a, b));
        }
        // A point is in the intersection exactly when it is in both.
        for (const Point3f &p : ProbePoints(rng, {a, b, x}))
            ASSERT_EQ(Inside(p, x), Inside(p, a) && Inside(p, b))
                << a << b << p;
    }
    EXPECT_GT(nonEmpty, kRandomCases / 200);
    EXPECT_GT(empty, kRandomCases / 200);
}

EXERCISE_TEST(Ex2_14_Bounds3, OverlapsIncludesTouchingBoxes) {
    Bounds3f a(Point3f(0, 0, 0), Point3f(1, 1, 1));
    Bounds3f face(Point3f(1, 0, 0), Point3f(2, 1, 1));
    Bounds3f corner(Point3f(1, 1, 1), Point3f(2, 2, 2));
    Bounds3f apart(Point3f(NextFloatUp(Float(1)), 0, 0), Point3f(2, 1, 1));
    EXPECT_TRUE(Overlaps(a, face));
    EXPECT_TRUE(Overlaps(face, a));
    EXPECT_TRUE(Overlaps(a, corner));
    EXPECT_FALSE(Overlaps(a, apart));
    EXPECT_FALSE(Overlaps(apart, a));
    EXPECT_TRUE(ex::Intersect(a, face).IsDegenerate());
    EXPECT_EQ(ex::Intersect(a, corner), Bounds3f(Point3f(1, 1, 1)));
    EXPECT_TRUE(ex::Intersect(a, apart).IsEmpty());
    EXPECT_TRUE(Overlaps(a, a));
}

TEST(Bounds3, InsideAndInsideExclusiveBoundaries) {
    Bounds3f b(Point3f(0, 0, 0), Point3f(1, 1, 1));
    Float above = NextFloatUp(Float(1)), below = NextFloatDown(Float(0));
    EXPECT_TRUE(Inside(Point3f(0, 0, 0), b));
    EXPECT_TRUE(InsideExclusive(Point3f(0, 0, 0), b));
    EXPECT_TRUE(Inside(Point3f(1, 1, 1), b));
    EXPECT_FALSE(InsideExclusive(Point3f(1, 1, 1), b));
    EXPECT_TRUE(Inside(Point3f(0.5f, 1, 0.5f), b));
    EXPECT_FALSE(InsideExclusive(Point3f(0.5f, 1, 0.5f), b));
    EXPECT_TRUE(InsideExclusive(Point3f(0.5f, NextFloatDown(Float(1)), 0), b));
    EXPECT_FALSE(Inside(Point3f(above, 0.5f, 0.5f), b));
    EXPECT_FALSE(Inside(Point3f(0.5f, 0.5f, below), b));
    EXPECT_FALSE(InsideExclusive(Point3f(0.5f, 0.5f, below), b));
    // Random points agree with the definition.
    std::mt19937_64 rng(kSeed + 8);
    for (int i = 0; i < kRandomCases / 20; ++i) {
        Bounds3f box = RandomBox(rng);
        for (const Point3f &p : ProbePoints(rng, {box})) {
            ASSERT_EQ(Inside(p, box), InClosed(p, box));
            bool excl = true;
            for (int k = 0; k < 3; ++k)
                excl = excl && box.pMin[k] <= p[k] && p[k] < box.pMax[k];
            ASSERT_EQ(InsideExclusive(p, box), excl);
        }
    }
}

// Half-open cells partition space: every integer point of a grid lies in
// exactly one cell under InsideExclusive(), while the closed test counts
// points on shared faces several times.
TEST(Bounds3, InsideExclusivePartitionsAGrid) {
    std::vector<Bounds3i> cells;
    for (int x = 0; x < 4; x += 2)
        for (int y = 0; y < 4; y += 2)
            for (int z = 0; z < 4; z += 2)
                cells.push_back(Bounds3i(Point3i(x, y, z),
                                         Point3i(x + 2, y + 2, z + 2)));
    int multiplyCounted = 0;
    for (int x = 0; x < 4; ++x)
        for (int y = 0; y < 4; ++y)
            for (int z = 0; z < 4; ++z) {
                int exclusive = 0, closed = 0;
                for (const Bounds3i &c : cells) {
                    exclusive += InsideExclusive(Point3i(x, y, z), c);
                    closed += Inside(Point3i(x, y, z), c);
                }
                EXPECT_EQ(exclusive, 1);
                if (closed > 1) ++multiplyCounted;
            }
    EXPECT_GT(multiplyCounted, 0);
}

EXERCISE_TEST(Ex2_14_Bounds3, Expand) {
    Bounds3f b(Point3f(0, 0, 0), Point3f(1, 2, 3));
    Bounds3f e = Expand(b, 1);
    EXPECT_EQ(e, Bounds3f(Point3f(-1, -1, -1), Point3f(2, 3, 4)));
    EXPECT_EQ(Expand(b, Float(-0.5)),
              Bounds3f(Point3f(0.5f, 0.5f, 0.5f), Point3f(0.5f, 1.5f, 2.5f)));
    // Shrinking past the center leaves nothing: the canonical empty box.
    EXPECT_EQ(Expand(b, -1), Bounds3f());
    // Padding nothing gives nothing, however large the padding.
    EXPECT_EQ(Expand(Bounds3f(), 1), Bounds3f());
    EXPECT_EQ(Expand(Bounds3f(), Float(1e38)), Bounds3f());
    EXPECT_EQ(Expand(Bounds3f(), MaxFloat), Bounds3f());
    EXPECT_EQ(Expand(Bounds3f(), Infinity), Bounds3f());
    EXPECT_EQ(Expand(Bounds3i(), 5), Bounds3i());
    std::mt19937_64 rng(calls::Seed(kSeed + 9));
    for (int i = 0; i < kRandomCases / 4; ++i) {
        Bounds3f box = RandomBox(rng);
        Float delta = RandomUniform(rng, 0, 5);
        Bounds3f grown = Expand(box, delta);
        for (int c = 0; c < 8; ++c) ASSERT_TRUE(Inside(box.Corner(c), grown));
        ASSERT_EQ(ex::Union(grown, box), grown);
    }
}

TEST(Bounds3, DistanceToPoint) {
    std::mt19937_64 rng(kSeed + 10);
    for (int i = 0; i < kRandomCases; ++i) {
        Bounds3f b = RandomBox(rng);
        Point3f p = RandomPoint(rng, -20, 20);
        // Brute force: the nearest point of the box clamps each coordinate.
        Ld d2 = 0;
        for (int k = 0; k < 3; ++k) {
            Ld c = std::min(std::max(Ld(p[k]), Ld(b.pMin[k])),
                            Ld(b.pMax[k]));
            d2 += (Ld(p[k]) - c) * (Ld(p[k]) - c);
        }
        if (Inside(p, b)) {
            ASSERT_EQ(DistanceSquared(p, b), 0);
            ASSERT_EQ(Distance(p, b), 0);
        }
        ASSERT_LE(std::abs(DistanceSquared(p, b) - d2), 6 * kU * d2);
        ASSERT_LE(std::abs(Distance(p, b) - std::sqrt(d2)),
                  4 * kU * std::sqrt(d2));
    }
    Bounds3f b(Point3f(0, 0, 0), Point3f(1, 1, 1));
    EXPECT_EQ(Distance(Point3f(4, 5, 0.5f), b), 5);
    EXPECT_EQ(Distance(Point3i(4, 5, 0), Bounds3i(Point3i(0, 0, 0),
                                                  Point3i(1, 1, 1))),
              5);
}

TEST(Bounds3, ConversionBetweenCoordinateTypes) {
    Bounds3f b(Point3f(0.5f, -1.5f, 2), Point3f(3.75f, 4, 5.5f));
    Bounds3i bi(b);
    EXPECT_EQ(bi, Bounds3i(Point3i(0, -1, 2), Point3i(3, 4, 5)));
    EXPECT_EQ(Bounds3f(Bounds3i(Point3i(1, 2, 3), Point3i(4, 5, 6))),
              Bounds3f(Point3f(1, 2, 3), Point3f(4, 5, 6)));
    // The empty box converts to the empty box.
    EXPECT_EQ(Bounds3i(Bounds3f()), Bounds3i());
    EXPECT_EQ(Bounds3f(Bounds3i()), Bounds3f());
}

TEST(Bounds3, EmptyAndDegenerateClassification) {
    Bounds3f flat(Point3f(0, 0, 1), Point3f(1, 1, 1));
    EXPECT_FALSE(flat.IsEmpty());
    EXPECT_TRUE(flat.IsDegenerate());
    EXPECT_EQ(flat.Volume(), 0);
    EXPECT_EQ(flat.SurfaceArea(), 2);
    // A box inverted along one axis only is empty, though not canonical.
    Bounds3f inv;
    inv.pMin = Point3f(5, 0, 0);
    inv.pMax = Point3f(3, 10, 10);
    EXPECT_TRUE(inv.IsEmpty());
    EXPECT_FALSE(inv.IsDegenerate());
    EXPECT_EQ(inv.Volume(), 0);
    EXPECT_FALSE(Inside(Point3f(4, 5, 5), inv));
}

TEST(Bounds3, StreamOutput) {
    std::ostringstream os;
    os << Bounds3f(Point3f(0, 0, 0), Point3f(1, 1, 1));
    EXPECT_EQ(os.str(), "[ [ 0, 0, 0 ] - [ 1, 1, 1 ] ]");
}

// ---------------------------------------------------------------------------
// Bounds2

TEST(Bounds2, EmptyBoxAndConstructors) {
    Bounds2f e;
    EXPECT_TRUE(e.IsEmpty());
    EXPECT_EQ(e.Area(), 0);
    EXPECT_FALSE(Inside(Point2f(0, 0), e));
    EXPECT_EQ(Union(e, Point2f(1, 2)), Bounds2f(Point2f(1, 2)));
    Bounds2f b(Point2f(3, -1), Point2f(1, 4));
    EXPECT_EQ(b.pMin, Point2f(1, -1));
    EXPECT_EQ(b.pMax, Point2f(3, 4));
    EXPECT_EQ(b[0], b.pMin);
    EXPECT_EQ(b[1], b.pMax);
    EXPECT_THROW(b[2], std::out_of_range);
    Bounds2f pt(Point2f(1, 1));
    EXPECT_TRUE(pt.IsDegenerate());
    EXPECT_FALSE(b.IsDegenerate());
    EXPECT_TRUE(b != pt);
}

TEST(Bounds2, Measures) {
    Bounds2f b(Point2f(0, 0), Point2f(4, 2));
    EXPECT_EQ(b.Diagonal(), Vector2f(4, 2));
    EXPECT_EQ(b.Area(), 8);
    EXPECT_EQ(b.MaximumExtent(), 0);
    EXPECT_EQ(Bounds2f(Point2f(0, 0), Point2f(1, 3)).MaximumExtent(), 1);
    EXPECT_EQ(Bounds2i(Point2i(0, 0), Point2i(5, 3)).Area(), 15);
    EXPECT_EQ(Bounds2i().Area(), 0);
    EXPECT_EQ(b.Lerp(Point2f(0.5f, 0.5f)), Point2f(2, 1));
    EXPECT_EQ(b.Lerp(Point2f(0, 0)), b.pMin);
    EXPECT_EQ(b.Lerp(Point2f(1, 1)), b.pMax);
    EXPECT_EQ(b.Offset(Point2f(1, 1)), Vector2f(0.25f, 0.5f));
    EXPECT_EQ(Bounds2f(Point2f(0, 1), Point2f(2, 1)).Offset(Point2f(1, 3)),
              Vector2f(0.5f, 2));
    Point2f c;
    Float r;
    b.BoundingSphere(&c, &r);
    EXPECT_EQ(c, Point2f(2, 1));
    EXPECT_LE(std::abs(r - std::sqrt(Ld(5))), 4 * kU * 3);
    Bounds2f().BoundingSphere(&c, &r);
    EXPECT_EQ(r, 0);
}

// Rectangles share the union and intersection of boxes (ex-2.14's
// fragments): the empty rectangle is their identity and absorbing element,
// and they contain or hold exactly the right points.
EXERCISE_TEST(Ex2_14_Rectangles, EmptyRectangleAndSetOperations) {
    Bounds2f e;
    Bounds2f b(Point2f(3, -1), Point2f(1, 4));
    EXPECT_EQ(ex::Union(e, e), e);
    EXPECT_EQ(ex::Union(e, b), b);
    EXPECT_EQ(ex::Union(b, e), b);
    EXPECT_EQ(ex::Intersect(e, b), e);
    EXPECT_EQ(ex::Intersect(b, b), b);
    std::mt19937_64 rng(calls::Seed(kSeed + 11));
    for (int i = 0; i < kRandomCases / 4; ++i) {
        Bounds2f a(Point2f(RandomUniform(rng, -5, 5), RandomUniform(rng, -5, 5)),
                   Point2f(RandomUniform(rng, -5, 5), RandomUniform(rng, -5, 5)));
        Bounds2f b(Point2f(RandomUniform(rng, -5, 5), RandomUniform(rng, -5, 5)),
                   Point2f(RandomUniform(rng, -5, 5), RandomUniform(rng, -5, 5)));
        Bounds2f u = ex::Union(a, b), x = ex::Intersect(a, b);
        ASSERT_EQ(Overlaps(a, b), !x.IsEmpty());
        if (x.IsEmpty()) {
            ASSERT_EQ(x, Bounds2f());
        }
        for (int j = 0; j < 32; ++j) {
            Point2f p(RandomUniform(rng, -6, 6), RandomUniform(rng, -6, 6));
            bool ina = Inside(p, a), inb = Inside(p, b);
            ASSERT_EQ(Inside(p, x), ina && inb);
            if (ina || inb) {
                ASSERT_TRUE(Inside(p, u));
            }
            ASSERT_TRUE(Inside(p, Union(a, p)));
        }
    }
}

TEST(Bounds2, PixelRectanglesExpandAndPrint) {
    Bounds2i px(Point2i(0, 0), Point2i(4, 3));
    EXPECT_TRUE(InsideExclusive(Point2i(0, 0), px));
    EXPECT_TRUE(InsideExclusive(Point2i(3, 2), px));
    EXPECT_FALSE(InsideExclusive(Point2i(4, 2), px));
    EXPECT_FALSE(InsideExclusive(Point2i(3, 3), px));
    EXPECT_TRUE(Inside(Point2i(4, 3), px));
    EXPECT_EQ(Expand(px, 1), Bounds2i(Point2i(-1, -1), Point2i(5, 4)));
    EXPECT_EQ(Expand(px, -2), Bounds2i());
    EXPECT_EQ(Expand(Bounds2i(), 3), Bounds2i());
    EXPECT_EQ(Expand(Bounds2f(), Infinity), Bounds2f());
    EXPECT_EQ(Bounds2i(Bounds2f(Point2f(0.5f, 1.5f), Point2f(2.5f, 3.5f))),
              Bounds2i(Point2i(0, 1), Point2i(2, 3)));
    EXPECT_EQ(Bounds2i(Bounds2f()), Bounds2i());
    std::ostringstream os;
    os << px;
    EXPECT_EQ(os.str(), "[ [ 0, 0 ] - [ 4, 3 ] ]");
}
