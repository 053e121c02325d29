// Chapter 2 (second part): Matrix4x4 and Transform.
//
// The oracles are independent of the code under test: matrix inverses and
// determinants are computed in long double with cofactor expansion (not with
// elimination), rotations with Rodrigues' formula in long double, and the
// exact images of points for the rounding-error bounds in long double as
// well. Random tests use fixed seeds and state their case counts.

#include "lrt/core/transform.h"

#include "exercise_calls.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>

using namespace lrt;

namespace {

using LD = long double;
constexpr Float kEps = std::numeric_limits<Float>::epsilon();

struct MatLD {
    LD m[4][4];
};

MatLD ToLD(const Matrix4x4 &a) {
    MatLD r;
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) r.m[i][j] = a.m[i][j];
    return r;
}

MatLD MulLD(const MatLD &a, const MatLD &b) {
    MatLD r;
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) {
            r.m[i][j] = 0;
            for (int k = 0; k < 4; ++k) r.m[i][j] += a.m[i][k] * b.m[k][j];
        }
    return r;
}

// Determinant of the 3x3 matrix formed by rows r[0..2] and columns c[0..2],
// by the Leibniz formula.
LD Det3(const MatLD &a, const int r[3], const int c[3]) {
    auto e = [&](int i, int j) { return a.m[r[i]][c[j]]; };
    return e(0, 0) * e(1, 1) * e(2, 2) + e(0, 1) * e(1, 2) * e(2, 0) +
           e(0, 2) * e(1, 0) * e(2, 1) - e(0, 2) * e(1, 1) * e(2, 0) -
           e(0, 0) * e(1, 2) * e(2, 1) - e(0, 1) * e(1, 0) * e(2, 2);
}

LD Cofactor(const MatLD &a, int i, int j) {
    int r[3], c[3];
    for (int k = 0, n = 0; k < 4; ++k)
        if (k != i) r[n++] = k;
    for (int k = 0, n = 0; k < 4; ++k)
        if (k != j) c[n++] = k;
    LD minor = Det3(a, r, c);
    return ((i + j) % 2 == 0) ? minor : -minor;
}

LD Det4(const MatLD &a) {
    LD d = 0;
    for (int j = 0; j < 4; ++j) d += a.m[0][j] * Cofactor(a, 0, j);
    return d;
}

// Inverse by the adjugate: inv = adj(a) / det(a). Returns false if det = 0.
bool InverseLD(const MatLD &a, MatLD *inv) {
    LD det = Det4(a);
    if (det == 0) return false;
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) inv->m[j][i] = Cofactor(a, i, j) / det;
    return true;
}

LD NormInf(const MatLD &a) {
    LD best = 0;
    for (int i = 0; i < 4; ++i) {
        LD s = 0;
        for (int j = 0; j < 4; ++j) s += std::fabs(a.m[i][j]);
        best = std::max(best, s);
    }
    return best;
}

LD MaxAbs(const MatLD &a) {
    LD best = 0;
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) best = std::max(best, std::fabs(a.m[i][j]));
    return best;
}

// Determinant of the upper-left 3x3 block and the sum of the absolute
// values of its six Leibniz terms (which bounds its rounding error).
LD Det3Upper(const Matrix4x4 &m, LD *absTerms) {
    MatLD a = ToLD(m);
    const int r[3] = {0, 1, 2};
    LD t[6] = {a.m[0][0] * a.m[1][1] * a.m[2][2],
               a.m[0][1] * a.m[1][2] * a.m[2][0],
               a.m[0][2] * a.m[1][0] * a.m[2][1],
               a.m[0][2] * a.m[1][1] * a.m[2][0],
               a.m[0][0] * a.m[1][2] * a.m[2][1],
               a.m[0][1] * a.m[1][0] * a.m[2][2]};
    *absTerms = 0;
    for (LD v : t) *absTerms += std::fabs(v);
    return Det3(a, r, r);
}

Float Uniform(std::mt19937_64 &rng, double lo, double hi) {
    return Float(std::uniform_real_distribution<double>(lo, hi)(rng));
}

Vector3f RandomVector(std::mt19937_64 &rng, double lo, double hi) {
    return Vector3f(Uniform(rng, lo, hi), Uniform(rng, lo, hi),
                    Uniform(rng, lo, hi));
}

Point3f RandomPoint(std::mt19937_64 &rng, double lo, double hi) {
    return Point3f(Uniform(rng, lo, hi), Uniform(rng, lo, hi),
                   Uniform(rng, lo, hi));
}

Matrix4x4 RandomMatrix(std::mt19937_64 &rng, double lo, double hi) {
    Matrix4x4 m;
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) m.m[i][j] = Uniform(rng, lo, hi);
    return m;
}

Matrix4x4 RandomAffineMatrix(std::mt19937_64 &rng) {
    Matrix4x4 m = RandomMatrix(rng, -2, 2);
    m.m[3][0] = m.m[3][1] = m.m[3][2] = 0;
    m.m[3][3] = 1;
    return m;
}

// Condition number (infinity norm) of m, or infinity if m is singular.
LD Condition(const Matrix4x4 &m) {
    MatLD a = ToLD(m), inv;
    if (!InverseLD(a, &inv)) return std::numeric_limits<LD>::infinity();
    return NormInf(a) * NormInf(inv);
}

// A random rigid motion with a scale (factors of magnitude 1/4 to 4, sign
// chosen at random when mirrors are allowed), so the linear part has a
// condition number of at most 16.
Transform RandomTransform(std::mt19937_64 &rng, bool allowMirror) {
    auto factor = [&]() {
        Float s = Uniform(rng, 0.25, 4);
        if (allowMirror && Uniform(rng, 0, 1) < 0.5) s = -s;
        return s;
    };
    Vector3f axis = RandomVector(rng, -1, 1);
    while (axis.LengthSquared() < Float(1e-2)) axis = RandomVector(rng, -1, 1);
    return Translate(RandomVector(rng, -10, 10)) *
           Rotate(Uniform(rng, -180, 180), axis) *
           Scale(factor(), factor(), factor()) *
           Rotate(Uniform(rng, -180, 180), Vector3f(axis.y, axis.z, axis.x));
}

struct Vec3LD {
    LD x, y, z;
};

// Exact (long double) image of the point (x, y, z) with homogeneous divide.
Vec3LD ApplyPointLD(const Matrix4x4 &m, LD x, LD y, LD z) {
    LD r[4];
    for (int i = 0; i < 4; ++i)
        r[i] = m.m[i][0] * x + m.m[i][1] * y + m.m[i][2] * z + m.m[i][3];
    return {r[0] / r[3], r[1] / r[3], r[2] / r[3]};
}

Vec3LD ApplyVectorLD(const Matrix4x4 &m, LD x, LD y, LD z) {
    LD r[3];
    for (int i = 0; i < 3; ++i)
        r[i] = m.m[i][0] * x + m.m[i][1] * y + m.m[i][2] * z;
    return {r[0], r[1], r[2]};
}

LD DotLD(const Vector3f &a, const Vector3f &b) {
    return LD(a.x) * b.x + LD(a.y) * b.y + LD(a.z) * b.z;
}

LD DotLD(const Normal3f &a, const Vector3f &b) {
    return LD(a.x) * b.x + LD(a.y) * b.y + LD(a.z) * b.z;
}

LD LengthLD(const Vector3f &v) { return std::sqrt(DotLD(v, v)); }

void ExpectMatrixNear(const Matrix4x4 &a, const Matrix4x4 &b, Float tol) {
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j)
            EXPECT_NEAR(a.m[i][j], b.m[i][j], tol) << "entry " << i << j;
}

void ExpectThrowsWithMessage(const std::function<void()> &f,
                             const std::string &message) {
    try {
        f();
        ADD_FAILURE() << "expected std::domain_error: " << message;
    } catch (const std::domain_error &e) {
        EXPECT_EQ(std::string(e.what()), message);
    }
}

}  // namespace

// ---------------------------------------------------------------------------
// Matrix4x4

TEST(Matrix4x4, DefaultIsIdentity) {
    Matrix4x4 m;
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) EXPECT_EQ(m.m[i][j], i == j ? 1 : 0);
}

TEST(Matrix4x4, ConstructorsStoreRowMajor) {
    Float a[4][4];
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) a[i][j] = Float(10 * i + j);
    Matrix4x4 fromArray(a);
    Matrix4x4 fromValues(0, 1, 2, 3, 10, 11, 12, 13, 20, 21, 22, 23, 30, 31,
                         32, 33);
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) {
            EXPECT_EQ(fromArray.m[i][j], Float(10 * i + j));
            EXPECT_EQ(fromValues.m[i][j], Float(10 * i + j));
        }
    EXPECT_TRUE(fromArray == fromValues);
}

TEST(Matrix4x4, EqualityIsExact) {
    Matrix4x4 a, b;
    EXPECT_TRUE(a == b);
    EXPECT_FALSE(a != b);
    b.m[2][3] = std::nextafter(Float(0), Float(1));
    EXPECT_FALSE(a == b);
    EXPECT_TRUE(a != b);
    // A NaN entry is unequal to itself, as in IEEE arithmetic.
    b.m[2][3] = std::numeric_limits<Float>::quiet_NaN();
    EXPECT_FALSE(b == b);
}

TEST(Matrix4x4, TransposeSwapsIndices) {
    Matrix4x4 m(0, 1, 2, 3, 10, 11, 12, 13, 20, 21, 22, 23, 30, 31, 32, 33);
    Matrix4x4 t = Transpose(m);
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) EXPECT_EQ(t.m[i][j], Float(10 * j + i));
    EXPECT_TRUE(Transpose(t) == m);
}

TEST(Matrix4x4, MulIntegerMatricesIsExact) {
    // Products and sums of small integers are exact in floating point, so
    // the result must equal the long double product exactly.
    constexpr int kCases = 2000;
    std::mt19937_64 rng(101);
    std::uniform_int_distribution<int> d(-50, 50);
    for (int c = 0; c < kCases; ++c) {
        Matrix4x4 a, b;
        for (int i = 0; i < 4; ++i)
            for (int j = 0; j < 4; ++j) {
                a.m[i][j] = Float(d(rng));
                b.m[i][j] = Float(d(rng));
            }
        Matrix4x4 p = Matrix4x4::Mul(a, b);
        MatLD q = MulLD(ToLD(a), ToLD(b));
        for (int i = 0; i < 4; ++i)
            for (int j = 0; j < 4; ++j) ASSERT_EQ(LD(p.m[i][j]), q.m[i][j]);
    }
}

TEST(Matrix4x4, MulRealMatricesWithinRoundingBound) {
    // A dot product of four terms computed left to right has error at most
    // gamma(4) times the sum of the absolute values of the products.
    constexpr int kCases = 2000;
    std::mt19937_64 rng(102);
    for (int c = 0; c < kCases; ++c) {
        Matrix4x4 a = RandomMatrix(rng, -100, 100);
        Matrix4x4 b = RandomMatrix(rng, -1e-3, 1e-3);
        Matrix4x4 p = Matrix4x4::Mul(a, b);
        for (int i = 0; i < 4; ++i)
            for (int j = 0; j < 4; ++j) {
                LD exact = 0, absSum = 0;
                for (int k = 0; k < 4; ++k) {
                    exact += LD(a.m[i][k]) * b.m[k][j];
                    absSum += std::fabs(LD(a.m[i][k]) * b.m[k][j]);
                }
                ASSERT_LE(std::fabs(p.m[i][j] - exact), gamma(4) * absSum);
            }
    }
    Matrix4x4 m = RandomMatrix(rng, -5, 5);
    EXPECT_TRUE(Matrix4x4::Mul(m, Matrix4x4()) == m);
    EXPECT_TRUE(Matrix4x4::Mul(Matrix4x4(), m) == m);
}

TEST(Matrix4x4, InverseOfPermutationAndPowerOfTwoScaleIsExact) {
    // Every step of the elimination is exact for these matrices.
    Matrix4x4 m(0, 0, 2, 0, 0.5, 0, 0, 0, 0, 0, 0, -4, 0, 8, 0, 0);
    Matrix4x4 inv = Inverse(m);
    Matrix4x4 expected(0, 2, 0, 0, 0, 0, 0, 0.125, 0.5, 0, 0, 0, 0, 0, -0.25,
                       0);
    EXPECT_TRUE(inv == expected);
    EXPECT_TRUE(Inverse(Matrix4x4()) == Matrix4x4());
}

TEST(Matrix4x4, InverseOfKnownMatrix) {
    // A unit upper triangular matrix and its inverse, worked out by hand.
    Matrix4x4 m(1, 2, 3, 4, 0, 1, 5, 6, 0, 0, 1, 7, 0, 0, 0, 1);
    Matrix4x4 expected(1, -2, 7, -41, 0, 1, -5, 29, 0, 0, 1, -7, 0, 0, 0, 1);
    ExpectMatrixNear(Inverse(m), expected, 256 * kEps);
}

TEST(Matrix4x4, InverseOfRandomWellConditionedMatrices) {
    // For well-conditioned matrices the computed inverse must agree with the
    // long double adjugate inverse to within a modest multiple of
    // kappa * epsilon, and M * Inverse(M), evaluated in long double, must be
    // the identity to the same order. About a third of the cases have a
    // zero diagonal, which forces the pivot search off the diagonal.
    constexpr int kCases = 5000;
    constexpr LD kMaxCondition = 1000;
    constexpr LD kFactor = 16;
    std::mt19937_64 rng(103);
    int tested = 0;
    for (int c = 0; c < kCases; ++c) {
        Matrix4x4 m = RandomMatrix(rng, -1, 1);
        if (c % 3 == 0)
            for (int i = 0; i < 4; ++i) m.m[i][i] = 0;
        if (c % 5 == 0)  // widely different scales in different rows
            for (int j = 0; j < 4; ++j) m.m[1][j] *= 1024;
        LD kappa = Condition(m);
        if (!(kappa <= kMaxCondition)) continue;
        ++tested;
        MatLD exact;
        ASSERT_TRUE(InverseLD(ToLD(m), &exact));
        Matrix4x4 inv = Inverse(m);
        LD scale = MaxAbs(exact);
        for (int i = 0; i < 4; ++i)
            for (int j = 0; j < 4; ++j)
                ASSERT_LE(std::fabs(inv.m[i][j] - exact.m[i][j]),
                          kFactor * kappa * kEps * scale)
                    << "case " << c << " entry " << i << j;
        MatLD prod = MulLD(ToLD(m), ToLD(inv));
        for (int i = 0; i < 4; ++i)
            for (int j = 0; j < 4; ++j)
                ASSERT_NEAR(double(prod.m[i][j]), i == j ? 1.0 : 0.0,
                            double(kFactor * kappa * kEps))
                    << "case " << c << " entry " << i << j;
    }
    EXPECT_GT(tested, kCases / 2);
}

TEST(Matrix4x4, InverseOfSingularMatricesThrows) {
    const std::string msg = "Matrix4x4::Inverse: singular matrix";
    Matrix4x4 zero(0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0);
    ExpectThrowsWithMessage([&] { Inverse(zero); }, msg);
    std::mt19937_64 rng(104);
    Matrix4x4 zeroRow = RandomMatrix(rng, -1, 1);
    for (int j = 0; j < 4; ++j) zeroRow.m[2][j] = 0;
    ExpectThrowsWithMessage([&] { Inverse(zeroRow); }, msg);
    Matrix4x4 zeroColumn = RandomMatrix(rng, -1, 1);
    for (int i = 0; i < 4; ++i) zeroColumn.m[i][1] = 0;
    ExpectThrowsWithMessage([&] { Inverse(zeroColumn); }, msg);

    // A row that is a power-of-two multiple of another stays exactly so
    // through every elimination step (scaling by 2^k commutes with
    // rounding), so the singularity is detected exactly, wherever the
    // pivots fall.
    constexpr int kCases = 2000;
    const Float factors[] = {1, -1, 2, -0.5, 4, 0.25, -8};
    for (int c = 0; c < kCases; ++c) {
        Matrix4x4 m = RandomMatrix(rng, -1, 1);
        int r1 = c % 4, r2 = (c / 4 + 1 + c % 4) % 4;
        if (r1 == r2) r2 = (r1 + 1) % 4;
        Float f = factors[c % 7];
        for (int j = 0; j < 4; ++j) m.m[r2][j] = f * m.m[r1][j];
        ASSERT_THROW(Inverse(m), std::domain_error) << "case " << c;
        ASSERT_THROW(Transform{m}, std::domain_error) << "case " << c;
    }
}

TEST(Matrix4x4, InverseWhoseEntriesOverflowThrows) {
    // 1 / denorm_min overflows in float and in double.
    Float tiny = std::numeric_limits<Float>::denorm_min();
    Matrix4x4 m(tiny, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1);
    ExpectThrowsWithMessage([&] { Inverse(m); },
                            "Matrix4x4::Inverse: singular matrix");
}

TEST(Matrix4x4, InverseRejectsNonFiniteEntries) {
    const std::string msg = "Matrix4x4::Inverse: matrix has a non-finite entry";
    Matrix4x4 m;
    m.m[1][2] = std::numeric_limits<Float>::quiet_NaN();
    ExpectThrowsWithMessage([&] { Inverse(m); }, msg);
    m.m[1][2] = Infinity;
    ExpectThrowsWithMessage([&] { Inverse(m); }, msg);
    m.m[1][2] = -Infinity;
    ExpectThrowsWithMessage([&] { Inverse(m); }, msg);
}

// ---------------------------------------------------------------------------
// Transform: construction and basic operations

TEST(Transform, DefaultIsIdentity) {
    Transform t;
    EXPECT_TRUE(t.IsIdentity());
    EXPECT_TRUE(t.GetMatrix() == Matrix4x4());
    EXPECT_TRUE(t.GetInverseMatrix() == Matrix4x4());
    EXPECT_FALSE(t.HasScale());
    EXPECT_FALSE(t.SwapsHandedness());
    EXPECT_TRUE(t.IsAffine());
    Point3f p(1.5, -2, 3);
    EXPECT_EQ(t(p), p);
}

TEST(Transform, ConstructorsComputeOrKeepInverse) {
    std::mt19937_64 rng(201);
    Matrix4x4 m = RandomAffineMatrix(rng);
    while (Condition(m) > 100) m = RandomAffineMatrix(rng);
    Transform t(m);
    EXPECT_TRUE(t.GetMatrix() == m);
    EXPECT_TRUE(t.GetInverseMatrix() == Inverse(m));
    Float a[4][4];
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) a[i][j] = m.m[i][j];
    EXPECT_TRUE(Transform(a) == t);
    // The two-matrix constructor trusts its caller.
    Matrix4x4 fake = RandomMatrix(rng, -1, 1);
    Transform u(m, fake);
    EXPECT_TRUE(u.GetMatrix() == m);
    EXPECT_TRUE(u.GetInverseMatrix() == fake);
    Matrix4x4 singular = m;
    for (int j = 0; j < 4; ++j) singular.m[3][j] = 0;
    EXPECT_THROW(Transform{singular}, std::domain_error);
}

TEST(Transform, InverseAndTranspose) {
    std::mt19937_64 rng(202);
    Matrix4x4 m = RandomMatrix(rng, -1, 1), mi = RandomMatrix(rng, -1, 1);
    Transform t(m, mi);
    Transform inv = Inverse(t);
    EXPECT_TRUE(inv.GetMatrix() == mi);
    EXPECT_TRUE(inv.GetInverseMatrix() == m);
    EXPECT_TRUE(Inverse(inv) == t);
    Transform tr = Transpose(t);
    EXPECT_TRUE(tr.GetMatrix() == Transpose(m));
    EXPECT_TRUE(tr.GetInverseMatrix() == Transpose(mi));
}

TEST(Transform, EqualityAndOrdering) {
    Transform a = Translate(Vector3f(1, 0, 0));
    Transform b = Translate(Vector3f(2, 0, 0));
    Transform a2 = Translate(Vector3f(1, 0, 0));
    EXPECT_TRUE(a == a2);
    EXPECT_FALSE(a != a2);
    EXPECT_TRUE(a != b);
    EXPECT_FALSE(a < a);
    EXPECT_NE(a < b, b < a);
    EXPECT_TRUE(a < b);
    // Equal matrices but different inverses are different transformations.
    Transform c(a.GetMatrix(), Matrix4x4());
    EXPECT_FALSE(c == a);
    EXPECT_FALSE(a < c);
    EXPECT_FALSE(c < a);
}

TEST(Transform, IsIdentity) {
    EXPECT_TRUE(Translate(Vector3f(0, 0, 0)).IsIdentity());
    EXPECT_TRUE(Scale(1, 1, 1).IsIdentity());
    EXPECT_FALSE(Translate(Vector3f(0, 0, 1e-6f)).IsIdentity());
    EXPECT_FALSE(RotateX(30).IsIdentity());
}

// ---------------------------------------------------------------------------
// Basic transformations

EXERCISE_TEST(Ex2_13_Transform, TranslateMovesPointsButNotVectorsOrNormals) {
    Transform t = Translate(Vector3f(1, -2, 0.5));
    EXPECT_EQ(t(Point3f(1, 2, 3)), Point3f(2, 0, 3.5));
    EXPECT_EQ(t(Vector3f(1, 2, 3)), Vector3f(1, 2, 3));
    EXPECT_EQ(ex::Apply(t, Normal3f(1, 2, 3)), Normal3f(1, 2, 3));
    EXPECT_EQ(Inverse(t)(Point3f(2, 0, 3.5)), Point3f(1, 2, 3));
    EXPECT_TRUE(Matrix4x4::Mul(t.GetMatrix(), t.GetInverseMatrix()) ==
                Matrix4x4());
    EXPECT_FALSE(t.HasScale());
    EXPECT_FALSE(t.SwapsHandedness());
}

EXERCISE_TEST(Ex2_13_Transform, ScaleAndItsInverse) {
    Transform s = Scale(2, -4, 0.5);
    EXPECT_EQ(s(Point3f(1, 1, 1)), Point3f(2, -4, 0.5));
    EXPECT_EQ(s(Vector3f(1, 2, 3)), Vector3f(2, -8, 1.5));
    EXPECT_EQ(Inverse(s)(Point3f(2, -4, 0.5)), Point3f(1, 1, 1));
    // Normals scale inversely.
    EXPECT_EQ(ex::Apply(s, Normal3f(1, 1, 1)), Normal3f(0.5, -0.25, 2));
    EXPECT_TRUE(s.HasScale());
    EXPECT_TRUE(s.SwapsHandedness());
    EXPECT_THROW(Scale(0, 1, 1), std::domain_error);
    EXPECT_THROW(Scale(1, 0, 1), std::domain_error);
    EXPECT_THROW(Scale(1, 1, -0.0f), std::domain_error);
}

TEST(Transform, HasScale) {
    EXPECT_FALSE(Transform().HasScale());
    EXPECT_FALSE(RotateY(37).HasScale());
    EXPECT_FALSE(Translate(Vector3f(5, 6, 7)).HasScale());
    EXPECT_TRUE(Scale(1, 1, 1.01f).HasScale());
    EXPECT_TRUE(Scale(0.5, 1, 1).HasScale());
    // Mirrors preserve lengths.
    EXPECT_FALSE(Scale(-1, 1, 1).HasScale());
    // A product of many rotations accumulates rounding error but is still
    // a rotation to within the tolerance.
    Transform r;
    for (int i = 0; i < 1000; ++i)
        r = r * Rotate(Float(7.3 * i), Vector3f(1, Float(i % 3), 2));
    EXPECT_FALSE(r.HasScale());
}

TEST(Transform, AxisRotationsOfNinetyDegrees) {
    const Float tol = 4 * kEps;
    auto near = [&](const Vector3f &a, const Vector3f &b) {
        EXPECT_NEAR(a.x, b.x, tol);
        EXPECT_NEAR(a.y, b.y, tol);
        EXPECT_NEAR(a.z, b.z, tol);
    };
    // A positive rotation about x turns y toward z, about y turns z toward
    // x, and about z turns x toward y.
    near(RotateX(90)(Vector3f(0, 1, 0)), Vector3f(0, 0, 1));
    near(RotateX(90)(Vector3f(0, 0, 1)), Vector3f(0, -1, 0));
    near(RotateY(90)(Vector3f(0, 0, 1)), Vector3f(1, 0, 0));
    near(RotateY(90)(Vector3f(1, 0, 0)), Vector3f(0, 0, -1));
    near(RotateZ(90)(Vector3f(1, 0, 0)), Vector3f(0, 1, 0));
    near(RotateZ(90)(Vector3f(0, 1, 0)), Vector3f(-1, 0, 0));
    // The axis itself is fixed exactly.
    EXPECT_EQ(RotateX(33)(Vector3f(2, 0, 0)), Vector3f(2, 0, 0));
    EXPECT_EQ(RotateY(33)(Vector3f(0, 2, 0)), Vector3f(0, 2, 0));
    EXPECT_EQ(RotateZ(33)(Vector3f(0, 0, 2)), Vector3f(0, 0, 2));
    // Rotations are orthogonal: the stored inverse is the transpose.
    EXPECT_TRUE(RotateX(33).GetInverseMatrix() ==
                Transpose(RotateX(33).GetMatrix()));
    EXPECT_FALSE(RotateZ(-170).SwapsHandedness());
}

TEST(Transform, RotateAgreesWithAxisRotations) {
    constexpr int kCases = 2000;
    std::mt19937_64 rng(301);
    for (int c = 0; c < kCases; ++c) {
        Float theta = Uniform(rng, -720, 720);
        Float len = Uniform(rng, 0.01, 100);
        ExpectMatrixNear(Rotate(theta, Vector3f(len, 0, 0)).GetMatrix(),
                         RotateX(theta).GetMatrix(), 2 * kEps);
        ExpectMatrixNear(Rotate(theta, Vector3f(0, len, 0)).GetMatrix(),
                         RotateY(theta).GetMatrix(), 2 * kEps);
        ExpectMatrixNear(Rotate(theta, Vector3f(0, 0, len)).GetMatrix(),
                         RotateZ(theta).GetMatrix(), 2 * kEps);
        if (HasFailure()) break;
    }
}

TEST(Transform, RotateMatchesRodriguesAndPreservesLengthsAndAxis) {
    constexpr int kCases = 5000;
    std::mt19937_64 rng(302);
    const LD pi = 3.14159265358979323846264338327950288L;
    for (int c = 0; c < kCases; ++c) {
        Vector3f axis = RandomVector(rng, -1, 1);
        if (axis.LengthSquared() < Float(1e-4)) continue;
        Float theta = Uniform(rng, -360, 360);
        Transform r = Rotate(theta, axis);
        Vector3f v = RandomVector(rng, -10, 10);
        Vector3f rv = r(v);

        // Rodrigues' formula in long double, about the exact unit axis.
        LD al = std::sqrt(LD(axis.x) * axis.x + LD(axis.y) * axis.y +
                          LD(axis.z) * axis.z);
        LD ax = axis.x / al, ay = axis.y / al, az = axis.z / al;
        LD th = LD(theta) * pi / 180;
        LD cs = std::cos(th), sn = std::sin(th);
        LD adv = ax * v.x + ay * v.y + az * v.z;
        LD cx = ay * v.z - az * v.y, cy = az * v.x - ax * v.z,
           cz = ax * v.y - ay * v.x;
        LD ex = v.x * cs + cx * sn + ax * adv * (1 - cs);
        LD ey = v.y * cs + cy * sn + ay * adv * (1 - cs);
        LD ez = v.z * cs + cz * sn + az * adv * (1 - cs);
        LD vlen = LengthLD(v);
        // The rotation angle itself is rounded (Radians() in Float), an
        // error of a few epsilon times |theta| <= 2 pi radians.
        LD tol = 32 * kEps * vlen;
        ASSERT_NEAR(double(rv.x), double(ex), double(tol)) << "case " << c;
        ASSERT_NEAR(double(rv.y), double(ey), double(tol)) << "case " << c;
        ASSERT_NEAR(double(rv.z), double(ez), double(tol)) << "case " << c;

        // Lengths are preserved, the axis is fixed, and the inverse undoes.
        ASSERT_NEAR(double(LengthLD(rv)), double(vlen), double(8 * kEps * vlen));
        Vector3f ra = r(axis);
        LD alen = LengthLD(axis);
        ASSERT_NEAR(ra.x, axis.x, double(8 * kEps * alen));
        ASSERT_NEAR(ra.y, axis.y, double(8 * kEps * alen));
        ASSERT_NEAR(ra.z, axis.z, double(8 * kEps * alen));
        Vector3f back = Inverse(r)(rv);
        ASSERT_NEAR(back.x, v.x, double(16 * kEps * vlen));
        ASSERT_NEAR(back.y, v.y, double(16 * kEps * vlen));
        ASSERT_NEAR(back.z, v.z, double(16 * kEps * vlen));
        ASSERT_FALSE(r.SwapsHandedness());
        ASSERT_FALSE(r.HasScale());
    }
}

TEST(Transform, RotateRejectsDegenerateAxis) {
    EXPECT_THROW(Rotate(30, Vector3f(0, 0, 0)), std::domain_error);
    EXPECT_THROW(Rotate(30, Vector3f(Infinity, 0, 0)), std::domain_error);
    EXPECT_THROW(Rotate(30, Vector3f(std::numeric_limits<Float>::quiet_NaN(),
                                     1, 0)),
                 std::domain_error);
}

TEST(Transform, LookAtCanonicalFrameIsIdentity) {
    Transform t = LookAt(Point3f(0, 0, 0), Point3f(0, 0, 5), Vector3f(0, 3, 0));
    ExpectMatrixNear(t.GetMatrix(), Matrix4x4(), 2 * kEps);
}

TEST(Transform, LookAtMapsEyeToOriginAndLookPointToPlusZ) {
    constexpr int kCases = 3000;
    std::mt19937_64 rng(303);
    for (int c = 0; c < kCases; ++c) {
        Point3f eye = RandomPoint(rng, -10, 10);
        Point3f look = RandomPoint(rng, -10, 10);
        Vector3f up = RandomVector(rng, -1, 1);
        Vector3f dir = look - eye;
        if (dir.Length() < 0.1 || up.Length() < 0.1) continue;
        // Keep the up vector clearly away from the viewing direction.
        if (Cross(Normalize(up), Normalize(dir)).Length() < 0.1) continue;
        Transform t = LookAt(eye, look, up);
        LD dist = LengthLD(dir);
        LD scale = 10;  // magnitude of the coordinates involved
        Point3f e = t(eye), l = t(look);
        ASSERT_NEAR(e.x, 0, double(32 * kEps * scale)) << "case " << c;
        ASSERT_NEAR(e.y, 0, double(32 * kEps * scale));
        ASSERT_NEAR(e.z, 0, double(32 * kEps * scale));
        ASSERT_NEAR(l.x, 0, double(32 * kEps * scale));
        ASSERT_NEAR(l.y, 0, double(32 * kEps * scale));
        ASSERT_NEAR(l.z, double(dist), double(32 * kEps * scale));
        // The up vector lands in the camera's y-z plane, on the +y side.
        Vector3f u = t(up);
        ASSERT_NEAR(u.x, 0, double(32 * kEps));
        ASSERT_GT(u.y, 0);
        // A rigid motion: lengths kept, no mirror.
        Vector3f w = RandomVector(rng, -1, 1);
        ASSERT_NEAR(double(LengthLD(t(w))), double(LengthLD(w)),
                    double(16 * kEps));
        ASSERT_FALSE(t.SwapsHandedness());
        ASSERT_FALSE(t.HasScale());
    }
}

TEST(Transform, LookAtWithNearlyParallelUpIsStillRigid) {
    // The cross product of nearly parallel vectors has a large relative
    // error (unless it is computed in higher precision); the Gram-Schmidt
    // step must still give an orthonormal camera frame.
    constexpr int kCases = 300;
    std::mt19937_64 rng(306);
    const Float tilts[] = {Float(1e-2), Float(1e-3), 10 * std::sqrt(kEps),
                           std::sqrt(kEps)};
    for (int c = 0; c < kCases; ++c) {
        Vector3f dir = RandomVector(rng, -1, 1);
        if (dir.Length() < 0.1) continue;
        dir = Normalize(dir);
        Vector3f perp = Cross(dir, RandomVector(rng, -1, 1));
        if (perp.Length() < 0.1) continue;
        perp = Normalize(perp);
        Float tilt = tilts[c % 4];
        Vector3f up = dir + tilt * perp;
        Point3f eye = RandomPoint(rng, -10, 10);
        Point3f look = eye + 10 * dir;
        Transform t = LookAt(eye, look, up);
        const Matrix4x4 &m = t.GetInverseMatrix();  // camera to world
        Vector3f r(m.m[0][0], m.m[1][0], m.m[2][0]);
        Vector3f u(m.m[0][1], m.m[1][1], m.m[2][1]);
        Vector3f d(m.m[0][2], m.m[1][2], m.m[2][2]);
        ASSERT_NEAR(double(DotLD(r, d)), 0, double(8 * kEps)) << c;
        ASSERT_NEAR(double(DotLD(r, u)), 0, double(8 * kEps)) << c;
        ASSERT_NEAR(double(DotLD(u, d)), 0, double(8 * kEps)) << c;
        ASSERT_NEAR(double(LengthLD(r)), 1, double(8 * kEps)) << c;
        ASSERT_NEAR(double(LengthLD(u)), 1, double(8 * kEps)) << c;
        ASSERT_NEAR(double(LengthLD(d)), 1, double(8 * kEps)) << c;
        // The camera's up vector lies on the side of the given one.
        ASSERT_GT(DotLD(u, perp), 0) << c;
    }
}

TEST(Transform, LookAtRejectsDegenerateInput) {
    Point3f eye(1, 2, 3);
    ExpectThrowsWithMessage(
        [&] { LookAt(eye, Point3f(1, 5, 3), Vector3f(0, 2, 0)); },
        "LookAt: up vector and viewing direction are parallel");
    ExpectThrowsWithMessage(
        [&] { LookAt(eye, Point3f(1, 5, 3), Vector3f(0, -1, 0)); },
        "LookAt: up vector and viewing direction are parallel");
    ExpectThrowsWithMessage(
        [&] { LookAt(eye, eye, Vector3f(0, 1, 0)); },
        "LookAt: eye and look-at points coincide");
    ExpectThrowsWithMessage(
        [&] { LookAt(eye, Point3f(0, 0, 0), Vector3f(0, 0, 0)); },
        "LookAt: up vector is zero");
    const Float nan = std::numeric_limits<Float>::quiet_NaN();
    EXPECT_THROW(LookAt(eye, Point3f(0, 0, 0), Vector3f(nan, 1, 0)),
                 std::domain_error);
    EXPECT_THROW(LookAt(eye, Point3f(0, nan, 0), Vector3f(0, 1, 0)),
                 std::domain_error);
}

TEST(Transform, PerspectiveMapsTheViewingFrustum) {
    constexpr int kCases = 3000;
    std::mt19937_64 rng(304);
    const LD pi = 3.14159265358979323846264338327950288L;
    for (int c = 0; c < kCases; ++c) {
        Float fov = Uniform(rng, 10, 170);
        Float n = Uniform(rng, 0.01, 2);
        Float f = n * Uniform(rng, 2, 1000);
        Transform p = Perspective(fov, n, f);
        ASSERT_FALSE(p.IsAffine());
        Float z = Uniform(rng, n, f);
        Float x = Uniform(rng, -z, z), y = Uniform(rng, -z, z);
        LD invTan = 1 / std::tan(LD(fov) * pi / 360);
        LD ex = x * invTan / z, ey = y * invTan / z;
        LD ez = LD(f) * (LD(z) - n) / (LD(z) * (LD(f) - n));
        Point3f q = p(Point3f(x, y, z));
        // x' and y' have a relative error of a few epsilon. The depth z'
        // is a difference of two terms of size up to f/(f-n), so its error
        // is bounded relative to that size rather than to z' itself.
        LD txy = 64 * kEps * (std::fabs(ex) + std::fabs(ey) + invTan);
        ASSERT_NEAR(double(q.x), double(ex), double(txy)) << "case " << c;
        ASSERT_NEAR(double(q.y), double(ey), double(txy)) << "case " << c;
        ASSERT_NEAR(double(q.z), double(ez), double(64 * kEps * f / (f - n)))
            << "case " << c;
        // The near and far planes map to 0 and 1, the edges of the field of
        // view to -1 and +1.
        Float zt = Uniform(rng, n, f);
        Float edge = Float(zt * std::tan(LD(fov) * pi / 360));
        Point3f e = p(Point3f(edge, -edge, zt));
        ASSERT_NEAR(e.x, 1, double(64 * kEps));
        ASSERT_NEAR(e.y, -1, double(64 * kEps));
        ASSERT_NEAR(p(Point3f(x, y, n)).z, 0, double(8 * kEps * f / (f - n)));
        ASSERT_NEAR(p(Point3f(x, y, f)).z, 1, double(8 * kEps * f / (f - n)));
    }
}

TEST(Transform, PerspectiveRejectsInvalidParameters) {
    EXPECT_THROW(Perspective(0, 1, 10), std::domain_error);
    EXPECT_THROW(Perspective(180, 1, 10), std::domain_error);
    EXPECT_THROW(Perspective(-30, 1, 10), std::domain_error);
    EXPECT_THROW(Perspective(60, 0, 10), std::domain_error);
    EXPECT_THROW(Perspective(60, -1, 10), std::domain_error);
    EXPECT_THROW(Perspective(60, 10, 10), std::domain_error);
    EXPECT_THROW(Perspective(60, 10, 1), std::domain_error);
    EXPECT_THROW(Perspective(60, 1, Infinity), std::domain_error);
    EXPECT_THROW(Perspective(std::numeric_limits<Float>::quiet_NaN(), 1, 10),
                 std::domain_error);
    EXPECT_NO_THROW(Perspective(90, 1e-2f, 1000));
}

TEST(Transform, OrthographicMapsNearAndFarPlanes) {
    Transform o = Orthographic(2, 10);
    EXPECT_TRUE(o.IsAffine());
    EXPECT_EQ(o(Point3f(3, -4, 2)), Point3f(3, -4, 0));
    EXPECT_EQ(o(Point3f(3, -4, 10)), Point3f(3, -4, 1));
    EXPECT_NEAR(o(Point3f(0, 0, 6)).z, 0.5, 2 * kEps);
    EXPECT_THROW(Orthographic(1, 1), std::domain_error);
    EXPECT_THROW(Orthographic(2, 1), std::domain_error);
    EXPECT_THROW(Orthographic(0, Infinity), std::domain_error);
}

// ---------------------------------------------------------------------------
// Applying transformations

TEST(Transform, PointsUndergoTheHomogeneousDivide) {
    // w' = z: a pure perspective divide.
    Transform t(Matrix4x4(1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 0, 1, 0, 0, 1, 0));
    EXPECT_FALSE(t.IsAffine());
    EXPECT_EQ(t(Point3f(2, 4, 2)), Point3f(1, 2, 0.5));
    EXPECT_EQ(t(Point3f(-3, 6, 4)), Point3f(-0.75, 1.5, 0.25));
    // Vectors ignore the bottom row.
    EXPECT_EQ(t(Vector3f(2, 4, 2)), Vector3f(2, 4, 0));
    // A point on the plane w' = 0 goes to infinity.
    Point3f inf = t(Point3f(1, 1, 0));
    EXPECT_TRUE(std::isinf(inf.x));
    EXPECT_TRUE(std::isinf(inf.y));
}

TEST(Transform, CompositionAppliesTheRightFactorFirst) {
    constexpr int kCases = 2000;
    std::mt19937_64 rng(401);
    for (int c = 0; c < kCases; ++c) {
        Transform a = RandomTransform(rng, true);
        Transform b = RandomTransform(rng, true);
        Transform ab = a * b;
        Point3f p = RandomPoint(rng, -5, 5);
        Point3f q1 = ab(p), q2 = a(b(p));
        // Both are affine images of magnitude at most ~ 16*5*4 + 40.
        double tol = 2000 * kEps;
        ASSERT_NEAR(q1.x, q2.x, tol);
        ASSERT_NEAR(q1.y, q2.y, tol);
        ASSERT_NEAR(q1.z, q2.z, tol);
        // The composed inverse is B^-1 A^-1.
        Point3f back = Inverse(ab)(q1);
        ASSERT_NEAR(back.x, p.x, 40 * tol);
        ASSERT_NEAR(back.y, p.y, 40 * tol);
        ASSERT_NEAR(back.z, p.z, 40 * tol);
        MatLD prod = MulLD(ToLD(ab.GetMatrix()), ToLD(ab.GetInverseMatrix()));
        for (int i = 0; i < 4; ++i)
            for (int j = 0; j < 4; ++j)
                ASSERT_NEAR(double(prod.m[i][j]), i == j ? 1 : 0, 40 * tol);
    }
    // Order matters: translating then scaling is not scaling then
    // translating.
    Transform s = Scale(2, 2, 2), t = Translate(Vector3f(1, 0, 0));
    EXPECT_EQ((s * t)(Point3f(0, 0, 0)), Point3f(2, 0, 0));
    EXPECT_EQ((t * s)(Point3f(0, 0, 0)), Point3f(1, 0, 0));
}

EXERCISE_TEST(Ex2_13_Transform, NormalsStayPerpendicularToTangents) {
    constexpr int kCases = 5000;
    std::mt19937_64 rng(calls::Seed(402));
    LD worstVectorRule = 0;
    for (int c = 0; c < kCases; ++c) {
        Matrix4x4 m = RandomAffineMatrix(rng);
        LD kappa = Condition(m);
        if (!(kappa < 100)) continue;
        Transform t(m);
        Vector3f t1 = RandomVector(rng, -1, 1), t2 = RandomVector(rng, -1, 1);
        Vector3f cr = Cross(t1, t2);
        if (cr.Length() < 0.05) continue;
        Normal3f n(cr);
        Normal3f tn = ex::Apply(t, n);
        for (const Vector3f &tangent : {t1, t2, t1 + t2, t1 - 2 * t2}) {
            Vector3f tt = t(tangent);
            LD cosAngle = DotLD(tn, tt) / (LengthLD(Vector3f(tn)) *
                                           LengthLD(tt));
            ASSERT_LE(std::fabs(cosAngle), 16 * kappa * kEps)
                << "case " << c;
            // Transforming the normal like a vector would generally fail.
            Vector3f wrong = t(Vector3f(n));
            worstVectorRule =
                std::max(worstVectorRule, std::fabs(DotLD(wrong, tt)) /
                                              (LengthLD(wrong) * LengthLD(tt)));
        }
    }
    EXPECT_GT(worstVectorRule, 0.1);
}

TEST(Transform, RaysTransformOriginDirectionAndKeepTime) {
    Transform t = Translate(Vector3f(1, 2, 3)) * Scale(2, 2, 2);
    Ray r(Point3f(1, 0, 0), Vector3f(0, 1, 0), 10, 0.25);
    Ray tr = t(r);
    EXPECT_EQ(tr.d, Vector3f(0, 2, 0));
    EXPECT_EQ(tr.time, Float(0.25));
    // The origin moves forward by at most its error bound; the far end
    // does not move.
    EXPECT_NEAR(tr.o.x, 3, 8 * kEps);
    EXPECT_NEAR(tr.o.y, 2, 64 * kEps);
    EXPECT_NEAR(tr.o.z, 3, 8 * kEps);
    EXPECT_GE(tr.o.y, 2);
    Point3f end = tr(tr.tMax);
    EXPECT_NEAR(end.y, 22, 64 * kEps);
    Ray inf(Point3f(1, 0, 0), Vector3f(0, 1, 0));
    EXPECT_TRUE(std::isinf(t(inf).tMax));
    // A ray with a zero direction is transformed without an offset.
    Ray zero(Point3f(1, 0, 0), Vector3f(0, 0, 0), 5);
    Ray tz = t(zero);
    EXPECT_EQ(tz.o, Point3f(3, 2, 3));
    EXPECT_EQ(tz.tMax, Float(5));
}

TEST(Transform, BoundsContainTransformedCornersAndInteriorPoints) {
    constexpr int kCases = 2000;
    constexpr int kPointsPerBox = 20;
    std::mt19937_64 rng(403);
    for (int c = 0; c < kCases; ++c) {
        Transform t = RandomTransform(rng, true);
        Bounds3f b(RandomPoint(rng, -5, 5), RandomPoint(rng, -5, 5));
        Bounds3f tb = t(b);
        ASSERT_FALSE(tb.IsEmpty());
        // The box is exactly the union of the transformed corners: it
        // contains each, and each face touches one.
        bool touches[6] = {false, false, false, false, false, false};
        Float maxErr = 0;
        for (int i = 0; i < 8; ++i) {
            Vector3f err;
            Point3f q = t(b.Corner(i), &err);
            ASSERT_EQ(q, t(b.Corner(i)));
            ASSERT_TRUE(Inside(q, tb)) << "case " << c << " corner " << i;
            for (int d = 0; d < 3; ++d) {
                touches[d] = touches[d] || q[d] == tb.pMin[d];
                touches[3 + d] = touches[3 + d] || q[d] == tb.pMax[d];
            }
            maxErr = std::max({maxErr, err.x, err.y, err.z});
        }
        for (bool f : touches) ASSERT_TRUE(f) << "case " << c;
        // Points inside the box: their exact images lie in the convex hull
        // of the exact corner images, which are within maxErr of the
        // computed corners. The computed images may stray by their own
        // error bound as well.
        for (int k = 0; k < kPointsPerBox; ++k) {
            Point3f p = b.Lerp(Point3f(Uniform(rng, 0, 1), Uniform(rng, 0, 1),
                                       Uniform(rng, 0, 1)));
            ASSERT_TRUE(Inside(p, b));
            Vec3LD e = ApplyPointLD(t.GetMatrix(), p.x, p.y, p.z);
            LD exact[3] = {e.x, e.y, e.z};
            Vector3f perr;
            Point3f q = t(p, &perr);
            for (int d = 0; d < 3; ++d) {
                ASSERT_GE(exact[d], LD(tb.pMin[d]) - maxErr);
                ASSERT_LE(exact[d], LD(tb.pMax[d]) + maxErr);
                ASSERT_GE(q[d], tb.pMin[d] - (maxErr + perr[d]));
                ASSERT_LE(q[d], tb.pMax[d] + (maxErr + perr[d]));
            }
        }
    }
}

TEST(Transform, BoundsOfEmptyAndDegenerateBoxes) {
    Transform t = RotateX(30) * Translate(Vector3f(1, 2, 3));
    EXPECT_TRUE(t(Bounds3f()).IsEmpty());
    Bounds3f inverted;
    inverted.pMin = Point3f(1, 1, 1);
    inverted.pMax = Point3f(2, 0, 2);
    EXPECT_TRUE(t(inverted).IsEmpty());
    // A single point maps to a single point.
    Bounds3f pt(Point3f(1, 1, 1));
    Bounds3f tp = t(pt);
    EXPECT_EQ(tp.pMin, t(Point3f(1, 1, 1)));
    EXPECT_EQ(tp.pMax, t(Point3f(1, 1, 1)));
    // A rotation by 45 degrees about z widens a unit square by sqrt(2).
    Bounds3f sq(Point3f(-1, -1, 0), Point3f(1, 1, 0));
    Bounds3f r = RotateZ(45)(sq);
    EXPECT_NEAR(r.pMax.x, std::sqrt(2.0), 8 * kEps);
    EXPECT_NEAR(r.pMin.y, -std::sqrt(2.0), 8 * kEps);
}

TEST(Transform, SwapsHandednessIffDeterminantIsNegative) {
    constexpr int kCases = 10000;
    std::mt19937_64 rng(404);
    int tested = 0, negative = 0;
    for (int c = 0; c < kCases; ++c) {
        Matrix4x4 m = RandomMatrix(rng, -3, 3);
        LD absTerms;
        LD det = Det3Upper(m, &absTerms);
        // The sign of a determinant that is within the rounding error of
        // its Float evaluation is not determined; skip those few cases.
        if (std::fabs(det) <= 16 * kEps * absTerms) continue;
        ++tested;
        negative += det < 0;
        Transform t(m, Matrix4x4());  // the inverse does not matter here
        ASSERT_EQ(t.SwapsHandedness(), det < 0) << "case " << c;
    }
    EXPECT_GT(tested, kCases * 9 / 10);
    EXPECT_GT(negative, tested / 3);
    EXPECT_LT(negative, 2 * tested / 3);
    EXPECT_TRUE(Scale(-1, 1, 1).SwapsHandedness());
    EXPECT_FALSE(Scale(-1, -1, 1).SwapsHandedness());
    EXPECT_TRUE(Scale(-1, -1, -1).SwapsHandedness());
    EXPECT_TRUE((RotateX(40) * Scale(1, 1, -2)).SwapsHandedness());
    EXPECT_FALSE(Translate(Vector3f(-1, -1, -1)).SwapsHandedness());
}

// ---------------------------------------------------------------------------
// Rounding-error bounds

namespace {

// Checks that the exact value e lies within [v - err, v + err].
::testing::AssertionResult Within(LD exact, Float v, Float err) {
    if (std::fabs(exact - LD(v)) <= LD(err))
        return ::testing::AssertionSuccess();
    return ::testing::AssertionFailure()
           << "exact " << double(exact) << " computed " << v << " error "
           << double(std::fabs(exact - LD(v))) << " > bound " << err;
}

// A point with coordinates of widely varying magnitude and sign.
Point3f WildPoint(std::mt19937_64 &rng) {
    auto coord = [&]() {
        Float mag = std::pow(Float(2), Uniform(rng, -20, 20));
        return Uniform(rng, -1, 1) * mag;
    };
    return Point3f(coord(), coord(), coord());
}

}  // namespace

TEST(Transform, PointErrorBoundContainsExactResult) {
    constexpr int kCases = 20000;
    std::mt19937_64 rng(501);
    for (int c = 0; c < kCases; ++c) {
        Transform t = (c % 2) ? RandomTransform(rng, true)
                              : Transform(RandomAffineMatrix(rng),
                                          Matrix4x4());
        Point3f p = WildPoint(rng);
        Vector3f err;
        Point3f q = t(p, &err);
        ASSERT_EQ(q, t(p));
        Vec3LD e = ApplyPointLD(t.GetMatrix(), p.x, p.y, p.z);
        ASSERT_TRUE(Within(e.x, q.x, err.x)) << "case " << c;
        ASSERT_TRUE(Within(e.y, q.y, err.y)) << "case " << c;
        ASSERT_TRUE(Within(e.z, q.z, err.z)) << "case " << c;
        ASSERT_GE(err.x, 0);
    }
    // The identity introduces no error at all, and says so.
    Vector3f err;
    Transform id;
    Point3f q = id(Point3f(1, 2, 3), &err);
    EXPECT_EQ(q, Point3f(1, 2, 3));
    EXPECT_LE(err.x, gamma(3) * 1);
}

TEST(Transform, PointErrorBoundForProjectiveTransformations) {
    constexpr int kCases = 20000;
    std::mt19937_64 rng(502);
    int finite = 0;
    for (int c = 0; c < kCases; ++c) {
        Transform t;
        Point3f p;
        if (c % 2) {
            t = Perspective(Uniform(rng, 20, 160), Uniform(rng, 0.01, 1),
                            Uniform(rng, 10, 1000));
            p = Point3f(Uniform(rng, -5, 5), Uniform(rng, -5, 5),
                        Uniform(rng, 0.01, 1000));
        } else {
            Matrix4x4 m = RandomMatrix(rng, -2, 2);
            t = Transform(m, Matrix4x4());
            p = RandomPoint(rng, -10, 10);
        }
        Vector3f err;
        Point3f q = t(p, &err);
        if (std::isinf(err.x)) continue;  // w' indistinguishable from 0
        ++finite;
        Vec3LD e = ApplyPointLD(t.GetMatrix(), p.x, p.y, p.z);
        ASSERT_TRUE(Within(e.x, q.x, err.x)) << "case " << c;
        ASSERT_TRUE(Within(e.y, q.y, err.y)) << "case " << c;
        ASSERT_TRUE(Within(e.z, q.z, err.z)) << "case " << c;
    }
    EXPECT_GT(finite, kCases * 9 / 10);
    // A point on the plane w' = 0 has an infinite bound.
    Transform t(Matrix4x4(1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 0, 1, 0, 0, 1, 0));
    Vector3f err;
    t(Point3f(1, 1, 0), &err);
    EXPECT_TRUE(std::isinf(err.x));
}

TEST(Transform, PropagatedPointErrorBoundContainsExactResult) {
    // The exact point is anywhere in p +- pError; its exact image must lie
    // within the returned bound of the computed image of p.
    constexpr int kCases = 20000;
    std::mt19937_64 rng(503);
    std::uniform_real_distribution<long double> unit(-1, 1);
    for (int c = 0; c < kCases; ++c) {
        Transform t = (c % 3 == 0)
                          ? Perspective(60, 0.1, 100)
                          : RandomTransform(rng, true);
        Point3f p = (c % 3 == 0) ? Point3f(Uniform(rng, -1, 1),
                                           Uniform(rng, -1, 1),
                                           Uniform(rng, 1, 50))
                                 : WildPoint(rng);
        Vector3f pError(std::fabs(p.x) * Uniform(rng, 0, 1e-3),
                        std::fabs(p.y) * Uniform(rng, 0, 1e-3),
                        std::fabs(p.z) * Uniform(rng, 0, 1e-3));
        Vector3f err;
        Point3f q = t(p, pError, &err);
        ASSERT_EQ(q, t(p));
        if (std::isinf(err.x)) continue;
        for (int k = 0; k < 4; ++k) {
            // Corners of the error box and a random interior point.
            LD sx = (k < 3) ? ((k & 1) ? 1 : -1) : unit(rng);
            LD sy = (k < 3) ? ((k & 2) ? 1 : -1) : unit(rng);
            LD sz = (k < 3) ? (k == 2 ? 1 : -1) : unit(rng);
            Vec3LD e = ApplyPointLD(t.GetMatrix(), p.x + sx * pError.x,
                                    p.y + sy * pError.y, p.z + sz * pError.z);
            ASSERT_TRUE(Within(e.x, q.x, err.x)) << "case " << c;
            ASSERT_TRUE(Within(e.y, q.y, err.y)) << "case " << c;
            ASSERT_TRUE(Within(e.z, q.z, err.z)) << "case " << c;
        }
    }
}

TEST(Transform, VectorErrorBoundsContainExactResult) {
    constexpr int kCases = 20000;
    std::mt19937_64 rng(504);
    std::uniform_real_distribution<long double> unit(-1, 1);
    for (int c = 0; c < kCases; ++c) {
        Transform t = (c % 2) ? RandomTransform(rng, true)
                              : Transform(RandomAffineMatrix(rng),
                                          Matrix4x4());
        Vector3f v = Vector3f(WildPoint(rng));
        Vector3f err;
        Vector3f w = t(v, &err);
        ASSERT_EQ(w, t(v));
        Vec3LD e = ApplyVectorLD(t.GetMatrix(), v.x, v.y, v.z);
        ASSERT_TRUE(Within(e.x, w.x, err.x)) << "case " << c;
        ASSERT_TRUE(Within(e.y, w.y, err.y)) << "case " << c;
        ASSERT_TRUE(Within(e.z, w.z, err.z)) << "case " << c;

        Vector3f vError(std::fabs(v.x) * Uniform(rng, 0, 1e-3),
                        std::fabs(v.y) * Uniform(rng, 0, 1e-3),
                        std::fabs(v.z) * Uniform(rng, 0, 1e-3));
        Vector3f err2;
        Vector3f w2 = t(v, vError, &err2);
        ASSERT_EQ(w2, w);
        LD sx = unit(rng), sy = unit(rng), sz = unit(rng);
        Vec3LD e2 = ApplyVectorLD(t.GetMatrix(), v.x + sx * vError.x,
                                  v.y + sy * vError.y, v.z + sz * vError.z);
        ASSERT_TRUE(Within(e2.x, w2.x, err2.x)) << "case " << c;
        ASSERT_TRUE(Within(e2.y, w2.y, err2.y)) << "case " << c;
        ASSERT_TRUE(Within(e2.z, w2.z, err2.z)) << "case " << c;
    }
}

TEST(Transform, RayOriginIsOffsetPastItsErrorBox) {
    constexpr int kCases = 20000;
    std::mt19937_64 rng(505);
    for (int c = 0; c < kCases; ++c) {
        Transform t = RandomTransform(rng, true);
        Point3f o = WildPoint(rng);
        Vector3f d = RandomVector(rng, -1, 1);
        if (d.LengthSquared() == 0) continue;
        Float tMax = (c % 4 == 0) ? Infinity : Uniform(rng, 0.5, 100);
        Ray r(o, d, tMax, Uniform(rng, 0, 1));
        Vector3f oError, dError;
        Ray tr = t(r, &oError, &dError);
        Ray tr1 = t(r);
        ASSERT_EQ(tr1.o, tr.o);
        ASSERT_EQ(tr1.d, tr.d);
        ASSERT_EQ(tr1.tMax, tr.tMax);
        ASSERT_EQ(tr.time, r.time);

        // The direction and the error bounds are those of the point and
        // vector forms.
        Vector3f oErr2, dErr2;
        Point3f oc = t(o, &oErr2);
        ASSERT_EQ(tr.d, t(d, &dErr2));
        ASSERT_EQ(oError, oErr2);
        ASSERT_EQ(dError, dErr2);

        // The exact origin lies in the error box around the computed one.
        Vec3LD e = ApplyPointLD(t.GetMatrix(), o.x, o.y, o.z);
        ASSERT_TRUE(Within(e.x, oc.x, oError.x));
        ASSERT_TRUE(Within(e.y, oc.y, oError.y));
        ASSERT_TRUE(Within(e.z, oc.z, oError.z));

        // The whole error box lies behind the new origin along d, up to the
        // rounding of the offset computation itself.
        const Vector3f &td = tr.d;
        LD slack = 4 * kEps *
                   (std::fabs(LD(tr.o.x) * td.x) + std::fabs(LD(tr.o.y) * td.y) +
                    std::fabs(LD(tr.o.z) * td.z));
        for (int k = 0; k < 8; ++k) {
            LD cx = LD(oc.x) + ((k & 1) ? oError.x : -oError.x);
            LD cy = LD(oc.y) + ((k & 2) ? oError.y : -oError.y);
            LD cz = LD(oc.z) + ((k & 4) ? oError.z : -oError.z);
            LD ahead = (cx - tr.o.x) * td.x + (cy - tr.o.y) * td.y +
                       (cz - tr.o.z) * td.z;
            ASSERT_LE(ahead, slack) << "case " << c << " corner " << k;
        }
        // The offset is forward, and the far end of the ray stays put.
        LD moved = (LD(tr.o.x) - oc.x) * td.x + (LD(tr.o.y) - oc.y) * td.y +
                   (LD(tr.o.z) - oc.z) * td.z;
        ASSERT_GE(moved, -slack);
        if (std::isinf(tMax)) {
            ASSERT_TRUE(std::isinf(tr.tMax));
        } else {
            Point3f end = tr(tr.tMax);
            LD scale = std::fabs(LD(oc.x)) + std::fabs(LD(oc.y)) +
                       std::fabs(LD(oc.z)) + tMax * LengthLD(td);
            ASSERT_NEAR(end.x, double(oc.x + LD(tMax) * td.x),
                        double(8 * kEps * scale));
            ASSERT_NEAR(end.y, double(oc.y + LD(tMax) * td.y),
                        double(8 * kEps * scale));
            ASSERT_NEAR(end.z, double(oc.z + LD(tMax) * td.z),
                        double(8 * kEps * scale));
            ASSERT_LE(tr.tMax, tMax);
            // tMax shrinks by the parametric offset of Equation (ray-offset),
            // up to the rounding of tMax itself.
            LD dt = (std::fabs(LD(td.x)) * oError.x +
                     std::fabs(LD(td.y)) * oError.y +
                     std::fabs(LD(td.z)) * oError.z) /
                    (LD(td.x) * td.x + LD(td.y) * td.y + LD(td.z) * td.z);
            ASSERT_NEAR(double(LD(tMax) - tr.tMax), double(dt),
                        double(kEps * tMax + 8 * kEps * dt))
                << "case " << c;
        }
    }
}
