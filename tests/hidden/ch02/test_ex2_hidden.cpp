// Hidden tests of chapter 2's graded exercises (docs/exercises.md): they run
// at grading time only and never ship to students. The public tests of the
// same exercises are the suites Ex2_12_*, Ex2_13_* and Ex2_14_* in tests/ch02/.
//
// Oracles: lengths, dot and triple products in long double from the computed
// float results; the inverse transpose from cofactors in long double; set
// membership through Inside(), which is not part of any exercise. Random tests
// state their case counts; their seeds change with every grading
// (calls::Seed).

#include "lrt/core/transform.h"

#include "ch02/exercise_calls.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

using namespace lrt;

namespace {

using LD = long double;
constexpr Float kEps = std::numeric_limits<Float>::epsilon();

LD DotLD(const Vector3f &a, const Vector3f &b) {
    return LD(a.x) * b.x + LD(a.y) * b.y + LD(a.z) * b.z;
}

LD LengthLD(const Vector3f &a) { return std::sqrt(DotLD(a, a)); }

// v1, v2, v3 must be unit length, mutually perpendicular and right-handed
// (v1 . (v2 x v3) = 1), to a few units in the last place.
void ExpectFrame(const Vector3f &v1) {
    Vector3f v2(7, 7, 7), v3(7, 7, 7);
    ex::CoordinateSystem(v1, &v2, &v3);
    const LD tol = 10 * LD(kEps);
    EXPECT_NEAR(LengthLD(v2), 1, tol) << v1;
    EXPECT_NEAR(LengthLD(v3), 1, tol) << v1;
    EXPECT_NEAR(DotLD(v1, v2), 0, tol) << v1;
    EXPECT_NEAR(DotLD(v1, v3), 0, tol) << v1;
    EXPECT_NEAR(DotLD(v2, v3), 0, tol) << v1;
    LD triple = v1.x * (LD(v2.y) * v3.z - LD(v2.z) * v3.y) +
                v1.y * (LD(v2.z) * v3.x - LD(v2.x) * v3.z) +
                v1.z * (LD(v2.x) * v3.y - LD(v2.y) * v3.x);
    EXPECT_NEAR(triple, 1, 2 * tol) << v1;
}

// A unit vector correctly rounded from long double.
Vector3f UnitLD(LD x, LD y, LD z) {
    LD len = std::sqrt(x * x + y * y + z * z);
    return Vector3f(Float(x / len), Float(y / len), Float(z / len));
}

}  // namespace

EXERCISE_TEST(Ex2_12_CoordinateSystemHidden, NearlyAxisAlignedVectors) {
    // One large coordinate and two tiny ones: the vector to normalize must be
    // built from the large coordinate, or it underflows to zero.
    for (LD tiny : {LD(1e-3), LD(1e-12), LD(1e-30), LD(1e-38)}) {
        for (int s = -1; s <= 1; s += 2) {
            ExpectFrame(UnitLD(s, tiny, tiny));
            ExpectFrame(UnitLD(tiny, s, -tiny));
            ExpectFrame(UnitLD(-tiny, tiny, s));
        }
    }
}

EXERCISE_TEST(Ex2_12_CoordinateSystemHidden, TiesBetweenXAndY) {
    // |x| == |y| sits on the boundary between the two constructions.
    for (LD z : {LD(0), LD(0.25), LD(-0.9), LD(1e-20)}) {
        for (int sx = -1; sx <= 1; sx += 2)
            for (int sy = -1; sy <= 1; sy += 2) ExpectFrame(UnitLD(sx, sy, z));
    }
}

EXERCISE_TEST(Ex2_12_CoordinateSystemHidden, RandomDirections) {
    constexpr int kCases = 20000;
    std::mt19937_64 rng(calls::Seed(0x2c5));
    std::normal_distribution<double> gauss;
    for (int c = 0; c < kCases; ++c) {
        LD x = gauss(rng), y = gauss(rng), z = gauss(rng);
        if (x * x + y * y + z * z < 1e-6L) continue;
        ExpectFrame(UnitLD(x, y, z));
        if (::testing::Test::HasFailure()) return;
    }
}

EXERCISE_TEST(Ex2_13_TransformNormalsHidden, ExactCases) {
    // A non-uniform scale: the inverse transpose is diag(1/2, 1/4, 1/8).
    EXPECT_EQ(ex::Apply(Scale(2, 4, 8), Normal3f(1, 1, 1)),
              Normal3f(0.5, 0.25, 0.125));
    // The result is not normalized.
    EXPECT_EQ(ex::Apply(Scale(2, 2, 2), Normal3f(0, 0, 1)),
              Normal3f(0, 0, 0.5));
    // A shear x' = x + y, given with its exact inverse: M^-T maps (1, 0, 0)
    // to (1, -1, 0), which stays perpendicular to the sheared tangents.
    Matrix4x4 m(1, 1, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1);
    Matrix4x4 mInv(1, -1, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1);
    Transform shear(m, mInv);
    EXPECT_EQ(ex::Apply(shear, Normal3f(1, 0, 0)), Normal3f(1, -1, 0));
    EXPECT_EQ(ex::Apply(shear, Normal3f(0, 0, 1)), Normal3f(0, 0, 1));
    // Translations do not touch normals, however large.
    EXPECT_EQ(ex::Apply(Translate(Vector3f(1e6, -3, 0.5)),
                        Normal3f(0.25, -2, 8)),
              Normal3f(0.25, -2, 8));
}

EXERCISE_TEST(Ex2_13_TransformNormalsHidden, MatchesTheInverseTransposeInLongDouble) {
    constexpr int kCases = 5000;
    std::mt19937_64 rng(calls::Seed(0x2d3));
    std::uniform_real_distribution<double> entry(-2, 2);
    int tested = 0;
    for (int c = 0; c < kCases; ++c) {
        Matrix4x4 m;
        LD a[3][3];
        for (int i = 0; i < 3; ++i) {
            for (int j = 0; j < 3; ++j) {
                m.m[i][j] = Float(entry(rng));
                a[i][j] = m.m[i][j];
            }
            m.m[i][3] = Float(entry(rng));
        }
        // The inverse transpose of the linear part is cof(A) / det(A).
        LD cof[3][3];
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) {
                int i1 = (i + 1) % 3, i2 = (i + 2) % 3, j1 = (j + 1) % 3,
                    j2 = (j + 2) % 3;
                cof[i][j] = a[i1][j1] * a[i2][j2] - a[i1][j2] * a[i2][j1];
            }
        LD det = a[0][0] * cof[0][0] + a[0][1] * cof[0][1] + a[0][2] * cof[0][2];
        LD normA = 0, normCof = 0;
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) {
                normA += a[i][j] * a[i][j];
                normCof += cof[i][j] * cof[i][j];
            }
        LD kappa = std::sqrt(normA * normCof) / std::fabs(det);
        if (!(kappa < 100)) continue;
        ++tested;
        Transform t(m);
        Normal3f n(Float(entry(rng)), Float(entry(rng)), Float(entry(rng)));
        Normal3f got = ex::Apply(t, n);
        LD scale = std::sqrt(normCof) / std::fabs(det) *
                   std::sqrt(LD(n.x) * n.x + LD(n.y) * n.y + LD(n.z) * n.z);
        for (int i = 0; i < 3; ++i) {
            LD expected = (cof[i][0] * n.x + cof[i][1] * n.y + cof[i][2] * n.z) / det;
            ASSERT_NEAR(got[i], expected, 32 * kappa * kEps * scale)
                << "case " << c << ", coordinate " << i;
        }
    }
    EXPECT_GT(tested, kCases / 2);
}

EXERCISE_TEST(Ex2_14_BoundsHidden, EmptyBoxIsTheIdentityOfUnionAndAbsorbsIntersection) {
    Bounds3f empty;
    Bounds3f b(Point3f(-1, 2, -3), Point3f(4, 5, 6));
    EXPECT_EQ(ex::Union(empty, b), b);
    EXPECT_EQ(ex::Union(b, empty), b);
    EXPECT_TRUE(ex::Union(empty, empty).IsEmpty());
    EXPECT_TRUE(ex::Intersect(empty, b).IsEmpty());
    EXPECT_TRUE(ex::Intersect(b, empty).IsEmpty());
    EXPECT_EQ(ex::Intersect(b, b), b);
    // Boxes apart along one axis: the intersection is the empty box itself,
    // not a box inverted along that axis.
    EXPECT_EQ(ex::Intersect(b, Bounds3f(Point3f(0, 6, 0), Point3f(1, 7, 1))),
              empty);
    EXPECT_EQ(ex::Intersect(Bounds3f(Point3f(-2, 3, 7), Point3f(9, 4, 8)), b),
              empty);
}

EXERCISE_TEST(Ex2_14_BoundsHidden, IntegerAndInfiniteBoxes) {
    Bounds3i a(Point3i(0, 0, 0), Point3i(4, 4, 4)), b(Point3i(2, -1, 3), Point3i(9, 1, 7));
    EXPECT_EQ(ex::Union(a, b), Bounds3i(Point3i(0, -1, 0), Point3i(9, 4, 7)));
    EXPECT_EQ(ex::Intersect(a, b), Bounds3i(Point3i(2, 0, 3), Point3i(4, 1, 4)));
    EXPECT_EQ(ex::Intersect(a, Bounds3i(Point3i(5, 0, 0), Point3i(6, 1, 1))),
              Bounds3i());
    const Float inf = std::numeric_limits<Float>::infinity();
    Bounds3f all(Point3f(-inf, -inf, -inf), Point3f(inf, inf, inf));
    Bounds3f box(Point3f(1, 2, 3), Point3f(2, 3, 4));
    EXPECT_EQ(ex::Intersect(all, box), box);
    EXPECT_EQ(ex::Union(all, box), all);
}

EXERCISE_TEST(Ex2_14_BoundsHidden, MembershipAgreesWithInsideOnAGrid) {
    // Boxes with corners on a small integer grid overlap, touch and miss each
    // other often; every grid point, boundaries included, is in the
    // intersection exactly when it is in both boxes, and in the union's box
    // whenever it is in either.
    constexpr int kCases = 2000;
    std::mt19937_64 rng(calls::Seed(0x2e1));
    std::uniform_int_distribution<int> coord(-3, 3);
    auto randomBox = [&]() {
        return Bounds3f(Point3f(coord(rng), coord(rng), coord(rng)),
                        Point3f(coord(rng), coord(rng), coord(rng)));
    };
    for (int c = 0; c < kCases; ++c) {
        Bounds3f a = randomBox(), b = randomBox();
        Bounds3f u = ex::Union(a, b), i = ex::Intersect(a, b);
        bool anyInBoth = false;
        for (int x = -4; x <= 4; ++x)
            for (int y = -4; y <= 4; ++y)
                for (int z = -4; z <= 4; ++z) {
                    Point3f p(x, y, z);
                    bool inA = Inside(p, a), inB = Inside(p, b);
                    ASSERT_EQ(Inside(p, i), inA && inB) << "case " << c << " at " << p;
                    if (inA || inB) {
                        ASSERT_TRUE(Inside(p, u)) << "case " << c << " at " << p;
                    }
                    anyInBoth = anyInBoth || (inA && inB);
                }
        // The union is the smallest such box: each face touches a or b.
        for (int axis = 0; axis < 3; ++axis) {
            EXPECT_EQ(u.pMin[axis], std::min(a.pMin[axis], b.pMin[axis]));
            EXPECT_EQ(u.pMax[axis], std::max(a.pMax[axis], b.pMax[axis]));
        }
        EXPECT_EQ(i.IsEmpty(), !anyInBoth) << "case " << c;
        if (::testing::Test::HasFailure()) return;
    }
}
