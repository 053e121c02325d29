// Tests for the vectors, points, normals and rays of Chapter 2
// (lrt/core/geometry.h).
//
// Oracles: component-wise recomputation, long double arithmetic with
// analytic error bounds, exact integer arithmetic, and geometric
// properties (perpendicularity, unit length, orthonormal frames).

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <sstream>
#include <type_traits>

#include "lrt/core/geometry.h"

#include "exercise_calls.h"

using namespace lrt;

namespace {

typedef long double Ld;

constexpr int kRandomCases = 20000;
constexpr uint64_t kSeed = 0x6c72742d67656f6dull;  // "lrt-geom"

// Unit roundoff of Float and of the long double oracle, computed without
// the library's constants.
const Ld kU = Ld(std::numeric_limits<Float>::epsilon()) / 2;
const Ld kULd = std::numeric_limits<Ld>::epsilon() / 2;
const Ld kUDouble = Ld(std::numeric_limits<double>::epsilon()) / 2;
const Float kNaN = std::numeric_limits<Float>::quiet_NaN();

// Random Float with a random sign, a mantissa in [0.5, 1) and an exponent
// in [-e, e]: values spread over many orders of magnitude.
Float RandomWide(std::mt19937_64 &rng, int e) {
    std::uniform_real_distribution<double> m(0.5, 1);
    std::uniform_int_distribution<int> ex(-e, e), sign(0, 1);
    double v = std::ldexp(m(rng), ex(rng));
    return Float(sign(rng) ? v : -v);
}

Float RandomUniform(std::mt19937_64 &rng, double lo, double hi) {
    return Float(std::uniform_real_distribution<double>(lo, hi)(rng));
}

Vector3f RandomVector(std::mt19937_64 &rng, double lo = -1, double hi = 1) {
    return Vector3f(RandomUniform(rng, lo, hi), RandomUniform(rng, lo, hi),
                    RandomUniform(rng, lo, hi));
}

// A vector whose coordinates span many magnitudes, all scaled together by
// a common random factor so that none underflows when squared.
Vector3f RandomScaledVector(std::mt19937_64 &rng) {
    Float s = std::ldexp(Float(1), std::uniform_int_distribution<int>(
                                       -20, 20)(rng));
    return Vector3f(RandomWide(rng, 6), RandomWide(rng, 6),
                    RandomWide(rng, 6)) *
           s;
}

Point3f RandomPoint(std::mt19937_64 &rng, double lo = -10, double hi = 10) {
    return Point3f(RandomUniform(rng, lo, hi), RandomUniform(rng, lo, hi),
                   RandomUniform(rng, lo, hi));
}

Ld LengthLd(const Vector3f &v) {
    return std::sqrt(Ld(v.x) * v.x + Ld(v.y) * v.y + Ld(v.z) * v.z);
}

Ld DotLd(const Vector3f &a, const Vector3f &b) {
    return Ld(a.x) * b.x + Ld(a.y) * b.y + Ld(a.z) * b.z;
}

}  // namespace

// ---------------------------------------------------------------------------
// Vector3

TEST(Vector3, ConstructionAndIndexing) {
    Vector3f zero;
    EXPECT_EQ(zero.x, 0);
    EXPECT_EQ(zero.y, 0);
    EXPECT_EQ(zero.z, 0);
    Vector3f v(1, -2, 3);
    EXPECT_EQ(v[0], 1);
    EXPECT_EQ(v[1], -2);
    EXPECT_EQ(v[2], 3);
    v[1] = 7;
    EXPECT_EQ(v.y, 7);
    const Vector3f &cv = v;
    EXPECT_EQ(cv[1], 7);
    EXPECT_THROW(v[3], std::out_of_range);
    EXPECT_THROW(v[-1], std::out_of_range);
    EXPECT_THROW(cv[3], std::out_of_range);
    Vector3i vi(1, 2, 3);
    EXPECT_EQ(vi[2], 3);
}

TEST(Vector3, ArithmeticIsComponentwise) {
    std::mt19937_64 rng(kSeed);
    for (int i = 0; i < kRandomCases; ++i) {
        Vector3f a = RandomVector(rng, -100, 100);
        Vector3f b = RandomVector(rng, -100, 100);
        Float s = RandomUniform(rng, -10, 10);
        Vector3f sum = a + b, diff = a - b, scaled = a * s;
        for (int k = 0; k < 3; ++k) {
            ASSERT_EQ(sum[k], a[k] + b[k]);
            ASSERT_EQ(diff[k], a[k] - b[k]);
            ASSERT_EQ(scaled[k], s * a[k]);
            ASSERT_EQ((-a)[k], -a[k]);
        }
        ASSERT_EQ(s * a, a * s);
        Vector3f c = a;
        c += b;
        ASSERT_EQ(c, sum);
        c = a;
        c -= b;
        ASSERT_EQ(c, diff);
        c = a;
        c *= s;
        ASSERT_EQ(c, scaled);
        // Division multiplies by the reciprocal: within 2 roundings of the
        // exact quotient.
        if (s != 0) {
            Vector3f q = a / s;
            c = a;
            c /= s;
            ASSERT_EQ(c, q);
            for (int k = 0; k < 3; ++k) {
                Ld exact = Ld(a[k]) / s;
                ASSERT_LE(std::abs(q[k] - exact),
                          2.001L * kU * std::abs(exact));
            }
        }
    }
    EXPECT_EQ(Vector3i(1, 2, 3) * 2, Vector3i(2, 4, 6));
    EXPECT_EQ(2 * Vector3f(1, 2, 3), Vector3f(2, 4, 6));
}

TEST(Vector3, EqualityAndNaNs) {
    EXPECT_TRUE(Vector3f(1, 2, 3) == Vector3f(1, 2, 3));
    EXPECT_TRUE(Vector3f(1, 2, 3) != Vector3f(1, 2, 4));
    EXPECT_FALSE(Vector3f(1, 2, 3) != Vector3f(1, 2, 3));
    EXPECT_FALSE(Vector3f(1, 2, 3).HasNaNs());
    EXPECT_TRUE(Vector3f(kNaN, 2, 3).HasNaNs());
    EXPECT_TRUE(Vector3f(1, kNaN, 3).HasNaNs());
    EXPECT_TRUE(Vector3f(1, 2, kNaN).HasNaNs());
    EXPECT_FALSE(Vector3f(Infinity, -Infinity, 0).HasNaNs());
    EXPECT_FALSE(Vector3i(1, 2, 3).HasNaNs());
    // A vector with a NaN is not equal to itself.
    Vector3f n(kNaN, 0, 0);
    EXPECT_FALSE(n == n);
}

TEST(Vector3, LengthAgainstLongDouble) {
    std::mt19937_64 rng(kSeed + 1);
    for (int i = 0; i < kRandomCases; ++i) {
        Vector3f v = RandomScaledVector(rng);
        Ld exact2 = DotLd(v, v);
        ASSERT_LE(std::abs(v.LengthSquared() - exact2),
                  3.001L * kU * exact2);
        Ld exact = std::sqrt(exact2);
        ASSERT_LE(std::abs(v.Length() - exact), 2.6L * kU * exact);
    }
    EXPECT_EQ(Vector3f(3, 4, 12).Length(), 13);
    EXPECT_EQ(Vector3i(1, 2, 2).LengthSquared(), 9);
}

TEST(Vector3, AbsMinMaxComponents) {
    Vector3f v(-3, 2, -1);
    EXPECT_EQ(Abs(v), Vector3f(3, 2, 1));
    EXPECT_EQ(MinComponent(v), -3);
    EXPECT_EQ(MaxComponent(v), 2);
    EXPECT_EQ(MaxDimension(v), 1);
    EXPECT_EQ(MaxDimension(Vector3f(5, 1, 2)), 0);
    EXPECT_EQ(MaxDimension(Vector3f(0, 1, 2)), 2);
    EXPECT_EQ(Min(Vector3f(1, 5, -2), Vector3f(3, 0, -1)),
              Vector3f(1, 0, -2));
    EXPECT_EQ(Max(Vector3f(1, 5, -2), Vector3f(3, 0, -1)),
              Vector3f(3, 5, -1));
    // Small integer coordinates produce many ties.
    std::mt19937_64 rng(kSeed + 2);
    std::uniform_int_distribution<int> d(-2, 2);
    for (int i = 0; i < kRandomCases; ++i) {
        Vector3f w(Float(d(rng)), Float(d(rng)), Float(d(rng)));
        Float lo = w.x, hi = w.x;
        for (int k = 1; k < 3; ++k) {
            if (w[k] < lo) lo = w[k];
            if (w[k] > hi) hi = w[k];
        }
        ASSERT_EQ(MinComponent(w), lo);
        ASSERT_EQ(MaxComponent(w), hi);
        int dim = MaxDimension(w);
        ASSERT_TRUE(dim >= 0 && dim < 3);
        ASSERT_EQ(w[dim], hi) << w;
    }
}

TEST(Vector3, Permute) {
    Vector3f v(10, 20, 30);
    for (int x = 0; x < 3; ++x)
        for (int y = 0; y < 3; ++y)
            for (int z = 0; z < 3; ++z)
                EXPECT_EQ(Permute(v, x, y, z), Vector3f(v[x], v[y], v[z]));
    EXPECT_EQ(Permute(v, 2, 0, 1), Vector3f(30, 10, 20));
    EXPECT_THROW(Permute(v, 0, 1, 3), std::out_of_range);
}

TEST(Vector3, DotAgainstLongDouble) {
    std::mt19937_64 rng(kSeed + 3);
    const Ld g3 = 3 * kU / (1 - 3 * kU);
    for (int i = 0; i < kRandomCases; ++i) {
        Vector3f a = RandomScaledVector(rng), b = RandomScaledVector(rng);
        Ld exact = DotLd(a, b);
        Ld absTerms = std::abs(Ld(a.x) * b.x) + std::abs(Ld(a.y) * b.y) +
                      std::abs(Ld(a.z) * b.z);
        ASSERT_LE(std::abs(Dot(a, b) - exact), g3 * absTerms * 1.0001L);
        ASSERT_EQ(Dot(a, b), Dot(b, a));
        ASSERT_EQ(AbsDot(a, b), std::abs(Dot(a, b)));
        ASSERT_EQ(Dot(a, a), a.LengthSquared());
    }
    EXPECT_EQ(Dot(Vector3f(1, 2, 3), Vector3f(4, -5, 6)), 12);
    EXPECT_EQ(AbsDot(Vector3f(1, 0, 0), Vector3f(-2, 0, 0)), 2);
    EXPECT_EQ(Dot(Vector3i(1, 2, 3), Vector3i(4, 5, 6)), 32);
}

TEST(Vector3, CrossOfBasisVectors) {
    Vector3f x(1, 0, 0), y(0, 1, 0), z(0, 0, 1);
    EXPECT_EQ(Cross(x, y), z);
    EXPECT_EQ(Cross(y, z), x);
    EXPECT_EQ(Cross(z, x), y);
    EXPECT_EQ(Cross(y, x), -z);
    EXPECT_EQ(Cross(x, x), Vector3f(0, 0, 0));
    EXPECT_EQ(Cross(Vector3i(1, 0, 0), Vector3i(0, 1, 0)), Vector3i(0, 0, 1));
    EXPECT_EQ(Cross(Vector3f(1, 2, 3), Vector3f(4, 5, 6)),
              Vector3f(-3, 6, -3));
}

// Nearly parallel integer vectors: the products cancel almost completely.
// The exact result is known from 64-bit integer arithmetic; with the
// products computed exactly in double, each coordinate of the computed
// cross product must be the correctly rounded exact value.
TEST(Vector3, CrossIsExactUnderCancellation) {
    std::mt19937_64 rng(kSeed + 4);
    std::uniform_int_distribution<int64_t> big(-(1 << 22), 1 << 22);
    std::uniform_int_distribution<int64_t> small(-4, 4);
    std::uniform_int_distribution<int64_t> mult(1, 3);
    for (int i = 0; i < kRandomCases; ++i) {
        int64_t a[3], b[3];
        int64_t m = mult(rng);
        for (int k = 0; k < 3; ++k) {
            a[k] = big(rng);
            b[k] = m * a[k] + small(rng);
        }
        Vector3f va{Float(a[0]), Float(a[1]), Float(a[2])};
        Vector3f vb{Float(b[0]), Float(b[1]), Float(b[2])};
        int64_t e[3] = {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2],
                        a[0] * b[1] - a[1] * b[0]};
        Vector3f c = Cross(va, vb);
        for (int k = 0; k < 3; ++k) ASSERT_EQ(c[k], Float(e[k])) << va << vb;
        ASSERT_EQ(Cross(vb, va), -c);
    }
}

TEST(Vector3, CrossErrorBound) {
    std::mt19937_64 rng(kSeed + 5);
    for (int i = 0; i < kRandomCases; ++i) {
        Vector3f a = RandomScaledVector(rng), b = RandomScaledVector(rng);
        // Make some pairs nearly parallel.
        if (i % 3 == 0) b = a * RandomUniform(rng, -4, 4) + b * Float(1e-4);
        Vector3f c = Cross(a, b);
        Ld p[3] = {Ld(a.y) * b.z, Ld(a.z) * b.x, Ld(a.x) * b.y};
        Ld q[3] = {Ld(a.z) * b.y, Ld(a.x) * b.z, Ld(a.y) * b.x};
        for (int k = 0; k < 3; ++k) {
            Ld exact = p[k] - q[k];
            Ld mag = std::abs(p[k]) + std::abs(q[k]);
            // Rounding to Float, the double computation, and the oracle.
            Ld bound = kU * std::abs(exact) +
                       2 * kUDouble * (mag + std::abs(exact)) +
                       4 * kULd * mag;
            ASSERT_LE(std::abs(c[k] - exact), bound) << a << b;
        }
        ASSERT_EQ(Cross(b, a), -c);
    }
}

TEST(Vector3, CrossIsPerpendicularAndHasParallelogramArea) {
    std::mt19937_64 rng(kSeed + 6);
    for (int i = 0; i < kRandomCases; ++i) {
        Vector3f a = RandomScaledVector(rng), b = RandomScaledVector(rng);
        Vector3f c = Cross(a, b);
        Ld mag[3] = {
            std::abs(Ld(a.y) * b.z) + std::abs(Ld(a.z) * b.y),
            std::abs(Ld(a.z) * b.x) + std::abs(Ld(a.x) * b.z),
            std::abs(Ld(a.x) * b.y) + std::abs(Ld(a.y) * b.x)};
        Ld tolA = 0, tolB = 0;
        for (int k = 0; k < 3; ++k) {
            Ld errK = 2 * (kU + kUDouble) * mag[k];
            tolA += errK * std::abs(Ld(a[k]));
            tolB += errK * std::abs(Ld(b[k]));
        }
        ASSERT_LE(std::abs(DotLd(c, a)), tolA * 1.001L) << a << b;
        ASSERT_LE(std::abs(DotLd(c, b)), tolB * 1.001L) << a << b;
        // Lagrange's identity: |a x b|^2 = |a|^2 |b|^2 - (a . b)^2.
        Ld aa = DotLd(a, a), bb = DotLd(b, b), ab = DotLd(a, b);
        Ld c2 = DotLd(c, c);
        ASSERT_LE(std::abs(c2 - (aa * bb - ab * ab)), 16 * kU * aa * bb);
    }
}

TEST(Vector3, NormalizeGivesUnitLength) {
    std::mt19937_64 rng(kSeed + 7);
    for (int i = 0; i < kRandomCases; ++i) {
        Vector3f v = RandomScaledVector(rng);
        Vector3f n = Normalize(v);
        // About 4.5 u by the analysis in the text.
        ASSERT_LE(std::abs(LengthLd(n) - 1), 5 * kU) << v;
        // Same direction: each coordinate is v_i / |v| to within 4.5 u.
        Ld len = LengthLd(v);
        for (int k = 0; k < 3; ++k) {
            Ld exact = v[k] / len;
            ASSERT_LE(std::abs(n[k] - exact), 5 * kU * std::abs(exact));
        }
    }
    EXPECT_EQ(Normalize(Vector3f(0, -2, 0)), Vector3f(0, -1, 0));
    // The zero vector has no direction: the result is NaN, detectably.
    EXPECT_TRUE(Normalize(Vector3f(0, 0, 0)).HasNaNs());
}

namespace {

void CheckFrame(const Vector3f &v1) {
    Vector3f v2, v3;
    ex::CoordinateSystem(v1, &v2, &v3);
    const Ld tol = 10 * kU;
    EXPECT_LE(std::abs(LengthLd(v2) - 1), tol) << v1;
    EXPECT_LE(std::abs(LengthLd(v3) - 1), tol) << v1;
    EXPECT_LE(std::abs(DotLd(v1, v2)), tol) << v1;
    EXPECT_LE(std::abs(DotLd(v1, v3)), tol) << v1;
    EXPECT_LE(std::abs(DotLd(v2, v3)), tol) << v1;
    // Determinant [v1 v2 v3] = v1 . (v2 x v3) = +1.
    Ld det = v1.x * (Ld(v2.y) * v3.z - Ld(v2.z) * v3.y) +
             v1.y * (Ld(v2.z) * v3.x - Ld(v2.x) * v3.z) +
             v1.z * (Ld(v2.x) * v3.y - Ld(v2.y) * v3.x);
    EXPECT_LE(std::abs(det - 1), 2 * tol) << v1;
    EXPECT_FALSE(v2.HasNaNs());
    EXPECT_FALSE(v3.HasNaNs());
}

}  // namespace

EXERCISE_TEST(Ex2_12_Vector3, CoordinateSystemIsOrthonormal) {
    std::mt19937_64 rng(calls::Seed(kSeed + 8));
    for (int i = 0; i < kRandomCases; ++i) {
        Vector3f v = RandomVector(rng);
        Ld len = LengthLd(v);
        if (len < 1e-3L) continue;
        // A unit vector correctly rounded from long double.
        Vector3f u(Float(v.x / len), Float(v.y / len), Float(v.z / len));
        CheckFrame(u);
        if (::testing::Test::HasFailure()) return;
    }
    // The axes and ties between |x| and |y| exercise both branches.
    for (int s = -1; s <= 1; s += 2) {
        CheckFrame(Vector3f(Float(s), 0, 0));
        CheckFrame(Vector3f(0, Float(s), 0));
        CheckFrame(Vector3f(0, 0, Float(s)));
        Float h = std::sqrt(Float(0.5));
        CheckFrame(Vector3f(h * s, h, 0));
        CheckFrame(Vector3f(h, h * s, 0));
    }
}

TEST(Vector3, StreamOutput) {
    std::ostringstream os;
    os << Vector3f(1, 2, 3);
    EXPECT_EQ(os.str(), "[ 1, 2, 3 ]");
}

// ---------------------------------------------------------------------------
// Vector2

TEST(Vector2, Basics) {
    Vector2f zero;
    EXPECT_EQ(zero, Vector2f(0, 0));
    Vector2f a(3, -4), b(1, 2);
    EXPECT_EQ(a + b, Vector2f(4, -2));
    EXPECT_EQ(a - b, Vector2f(2, -6));
    EXPECT_EQ(a * 2, Vector2f(6, -8));
    EXPECT_EQ(2 * a, Vector2f(6, -8));
    EXPECT_EQ(a / 2, Vector2f(1.5, -2));
    EXPECT_EQ(-a, Vector2f(-3, 4));
    Vector2f c = a;
    c += b;
    EXPECT_EQ(c, a + b);
    c -= b;
    EXPECT_EQ(c, a);
    c *= 3;
    EXPECT_EQ(c, Vector2f(9, -12));
    c /= 3;
    EXPECT_EQ(c, a);
    EXPECT_EQ(a.LengthSquared(), 25);
    EXPECT_EQ(a.Length(), 5);
    EXPECT_EQ(Dot(a, b), -5);
    EXPECT_EQ(AbsDot(a, b), 5);
    EXPECT_EQ(Abs(a), Vector2f(3, 4));
    EXPECT_NEAR(Normalize(a).x, 0.6, 3 * kU);
    EXPECT_NEAR(Normalize(a).y, -0.8, 3 * kU);
    EXPECT_EQ(a[0], 3);
    EXPECT_EQ(a[1], -4);
    a[0] = 1;
    EXPECT_EQ(a.x, 1);
    EXPECT_THROW(a[2], std::out_of_range);
    const Vector2f &ca = a;
    EXPECT_THROW(ca[-1], std::out_of_range);
    EXPECT_TRUE(Vector2f(kNaN, 0).HasNaNs());
    EXPECT_FALSE(Vector2f(0, 0).HasNaNs());
    EXPECT_TRUE(Vector2f(1, 2) != Vector2f(1, 3));
    EXPECT_EQ(Vector2i(1, 2) * 3, Vector2i(3, 6));
}

TEST(Vector2, NormalizeGivesUnitLength) {
    std::mt19937_64 rng(kSeed + 9);
    for (int i = 0; i < kRandomCases; ++i) {
        Vector2f v(RandomWide(rng, 20), RandomWide(rng, 20));
        if (std::abs(v.x) > 1e4 * std::abs(v.y) ||
            std::abs(v.y) > 1e4 * std::abs(v.x))
            continue;
        Vector2f n = Normalize(v);
        Ld len = std::sqrt(Ld(n.x) * n.x + Ld(n.y) * n.y);
        ASSERT_LE(std::abs(len - 1), 5 * kU) << v;
    }
}

// ---------------------------------------------------------------------------
// Point3

TEST(Point3, TypesOfDifferencesAndSums) {
    Point3f p(1, 2, 3), q(4, 6, 8);
    Vector3f v(1, 1, 1);
    EXPECT_TRUE((std::is_same<decltype(q - p), Vector3f>::value));
    EXPECT_TRUE((std::is_same<decltype(p + v), Point3f>::value));
    EXPECT_TRUE((std::is_same<decltype(p - v), Point3f>::value));
    EXPECT_TRUE((std::is_same<decltype(p + q), Point3f>::value));
    // Points and vectors do not convert implicitly.
    EXPECT_FALSE((std::is_convertible<Point3f, Vector3f>::value));
    EXPECT_FALSE((std::is_convertible<Vector3f, Point3f>::value));
    EXPECT_FALSE((std::is_convertible<Normal3f, Vector3f>::value));
    EXPECT_FALSE((std::is_convertible<Vector3f, Normal3f>::value));
    EXPECT_FALSE((std::is_convertible<Point3f, Point2f>::value));
    EXPECT_EQ(q - p, Vector3f(3, 4, 5));
    EXPECT_EQ(p + v, Point3f(2, 3, 4));
    EXPECT_EQ(p - v, Point3f(0, 1, 2));
    EXPECT_EQ(p + (q - p), q);
}

TEST(Point3, ArithmeticIsComponentwise) {
    std::mt19937_64 rng(kSeed + 10);
    for (int i = 0; i < kRandomCases; ++i) {
        Point3f p = RandomPoint(rng), q = RandomPoint(rng);
        Vector3f v = RandomVector(rng, -5, 5);
        Float s = RandomUniform(rng, 0.5, 2);
        Point3f pv = p + v, pmv = p - v, pq = p + q, ps = p * s;
        Vector3f d = p - q;
        for (int k = 0; k < 3; ++k) {
            ASSERT_EQ(pv[k], p[k] + v[k]);
            ASSERT_EQ(pmv[k], p[k] - v[k]);
            ASSERT_EQ(pq[k], p[k] + q[k]);
            ASSERT_EQ(ps[k], s * p[k]);
            ASSERT_EQ(d[k], p[k] - q[k]);
            ASSERT_EQ((-p)[k], -p[k]);
        }
        ASSERT_EQ(s * p, ps);
        Point3f r = p;
        r += v;
        ASSERT_EQ(r, pv);
        r = p;
        r -= v;
        ASSERT_EQ(r, pmv);
        r = p;
        r += q;
        ASSERT_EQ(r, pq);
        r = p;
        r *= s;
        ASSERT_EQ(r, ps);
        r = p;
        r /= s;
        ASSERT_EQ(r, p / s);
        for (int k = 0; k < 3; ++k) {
            Ld exact = Ld(p[k]) / s;
            ASSERT_LE(std::abs((p / s)[k] - exact),
                      2.001L * kU * std::abs(exact));
        }
    }
}

TEST(Point3, IndexingEqualityNaNs) {
    Point3f p(1, 2, 3);
    EXPECT_EQ(p[0], 1);
    EXPECT_EQ(p[2], 3);
    p[2] = 5;
    EXPECT_EQ(p.z, 5);
    const Point3f &cp = p;
    EXPECT_THROW(cp[3], std::out_of_range);
    EXPECT_THROW(p[-1], std::out_of_range);
    EXPECT_TRUE(Point3f(1, 2, 3) != Point3f(1, 2, 4));
    EXPECT_EQ(Point3f(), Point3f(0, 0, 0));
    EXPECT_TRUE(Point3f(0, kNaN, 0).HasNaNs());
    EXPECT_FALSE(Point3f(0, Infinity, 0).HasNaNs());
}

TEST(Point3, Conversions) {
    Point3f p(1.75f, -2.5f, 3);
    Vector3f v(p);
    EXPECT_EQ(v, Vector3f(1.75f, -2.5f, 3));
    EXPECT_EQ(Vector3f(p), Vector3f(1.75f, -2.5f, 3));
    EXPECT_EQ(Point3f(v), p);
    // Conversion to integer coordinates truncates, as a C++ cast does.
    Point3i pi(p);
    EXPECT_EQ(pi, Point3i(1, -2, 3));
    EXPECT_EQ(Point3f(Point3i(4, 5, 6)), Point3f(4, 5, 6));
    Point2f p2(p);
    EXPECT_EQ(p2, Point2f(1.75f, -2.5f));
    Vector2f v2(p);
    EXPECT_EQ(v2, Vector2f(1.75f, -2.5f));
}

TEST(Point3, DistanceAgainstLongDouble) {
    std::mt19937_64 rng(kSeed + 11);
    for (int i = 0; i < kRandomCases; ++i) {
        Point3f p = RandomPoint(rng, -1000, 1000);
        Point3f q = RandomPoint(rng, -1000, 1000);
        Ld dx = Ld(p.x) - q.x, dy = Ld(p.y) - q.y, dz = Ld(p.z) - q.z;
        Ld exact2 = dx * dx + dy * dy + dz * dz;
        // One rounding per difference, then as for LengthSquared().
        ASSERT_LE(std::abs(DistanceSquared(p, q) - exact2),
                  5.001L * kU * exact2);
        ASSERT_LE(std::abs(Distance(p, q) - std::sqrt(exact2)),
                  4 * kU * std::sqrt(exact2));
        ASSERT_EQ(Distance(p, q), Distance(q, p));
    }
    EXPECT_EQ(Distance(Point3f(1, 1, 1), Point3f(4, 5, 1)), 5);
    EXPECT_EQ(DistanceSquared(Point3f(1, 1, 1), Point3f(4, 5, 1)), 25);
    EXPECT_EQ(Distance(Point3f(2, 3, 4), Point3f(2, 3, 4)), 0);
}

TEST(Point3, LerpEndpointsAndInterior) {
    std::mt19937_64 rng(kSeed + 12);
    for (int i = 0; i < kRandomCases; ++i) {
        Point3f p0 = RandomPoint(rng), p1 = RandomPoint(rng);
        ASSERT_EQ(Lerp(0, p0, p1), p0);
        ASSERT_EQ(Lerp(1, p0, p1), p1);
        Float t = RandomUniform(rng, 0, 1);
        Point3f p = Lerp(t, p0, p1);
        for (int k = 0; k < 3; ++k) {
            Ld a = (1 - Ld(t)) * p0[k], b = Ld(t) * p1[k];
            Ld bound = 3 * kU / (1 - 3 * kU) * (std::abs(a) + std::abs(b));
            ASSERT_LE(std::abs(p[k] - (a + b)), bound * 1.0001L);
        }
    }
    EXPECT_EQ(Lerp(Float(0.5), Point3f(0, 0, 0), Point3f(2, 4, -6)),
              Point3f(1, 2, -3));
}

TEST(Point3, MinMaxFloorCeilAbsPermute) {
    Point3f a(1.5f, -2.5f, 3), b(-1, 4, 3.25f);
    EXPECT_EQ(Min(a, b), Point3f(-1, -2.5f, 3));
    EXPECT_EQ(Max(a, b), Point3f(1.5f, 4, 3.25f));
    EXPECT_EQ(Floor(a), Point3f(1, -3, 3));
    EXPECT_EQ(Ceil(a), Point3f(2, -2, 3));
    EXPECT_EQ(Abs(a), Point3f(1.5f, 2.5f, 3));
    EXPECT_EQ(Permute(a, 2, 0, 1), Point3f(3, 1.5f, -2.5f));
    EXPECT_EQ(Permute(a, 1, 1, 1), Point3f(-2.5f, -2.5f, -2.5f));
    // Min/Max keep the first argument when the second is a NaN.
    Point3f n(kNaN, kNaN, kNaN);
    EXPECT_EQ(Min(a, n), a);
    EXPECT_EQ(Max(a, n), a);
}

TEST(Point3, StreamOutput) {
    std::ostringstream os;
    os << Point3f(1, -2, 3.5f);
    EXPECT_EQ(os.str(), "[ 1, -2, 3.5 ]");
}

// ---------------------------------------------------------------------------
// Point2

TEST(Point2, Basics) {
    Point2f p(1, 2), q(4, 6);
    Vector2f v(1, 1);
    EXPECT_EQ(Point2f(), Point2f(0, 0));
    EXPECT_TRUE((std::is_same<decltype(q - p), Vector2f>::value));
    EXPECT_EQ(q - p, Vector2f(3, 4));
    EXPECT_EQ(p + v, Point2f(2, 3));
    EXPECT_EQ(p - v, Point2f(0, 1));
    EXPECT_EQ(p + q, Point2f(5, 8));
    EXPECT_EQ(p * 2, Point2f(2, 4));
    EXPECT_EQ(2 * p, Point2f(2, 4));
    EXPECT_EQ(q / 2, Point2f(2, 3));
    EXPECT_EQ(-p, Point2f(-1, -2));
    Point2f r = p;
    r += v;
    EXPECT_EQ(r, p + v);
    r -= v;
    EXPECT_EQ(r, p);
    r += q;
    EXPECT_EQ(r, p + q);
    r *= 2;
    EXPECT_EQ(r, Point2f(10, 16));
    r /= 2;
    EXPECT_EQ(r, Point2f(5, 8));
    EXPECT_EQ(Distance(p, q), 5);
    EXPECT_EQ(DistanceSquared(p, q), 25);
    EXPECT_EQ(Lerp(0, p, q), p);
    EXPECT_EQ(Lerp(1, p, q), q);
    EXPECT_EQ(Lerp(Float(0.5), p, q), Point2f(2.5f, 4));
    EXPECT_EQ(Min(p, Point2f(0, 5)), Point2f(0, 2));
    EXPECT_EQ(Max(p, Point2f(0, 5)), Point2f(1, 5));
    EXPECT_EQ(Floor(Point2f(1.5f, -1.5f)), Point2f(1, -2));
    EXPECT_EQ(Ceil(Point2f(1.5f, -1.5f)), Point2f(2, -1));
    EXPECT_EQ(p[1], 2);
    EXPECT_THROW(p[2], std::out_of_range);
    EXPECT_TRUE(Point2f(kNaN, 0).HasNaNs());
    EXPECT_TRUE(Point2f(1, 2) != Point2f(2, 1));
    EXPECT_EQ(Point2i(Point2f(2.5f, -3.5f)), Point2i(2, -3));
    EXPECT_EQ(Point2f(Vector2f(1, 2)), Point2f(1, 2));
    EXPECT_EQ(Vector2f(Point2f(1, 2)), Vector2f(1, 2));
    EXPECT_EQ(Vector2f(p), Vector2f(1, 2));
}

// ---------------------------------------------------------------------------
// Normal3

TEST(Normal3, ConversionsAndArithmetic) {
    Vector3f v(1, 2, 3);
    Normal3f n(v);
    EXPECT_EQ(n, Normal3f(1, 2, 3));
    EXPECT_EQ(Vector3f(n), v);
    EXPECT_EQ(Normal3f(), Normal3f(0, 0, 0));
    EXPECT_EQ(n + n, Normal3f(2, 4, 6));
    EXPECT_EQ(n - Normal3f(1, 1, 1), Normal3f(0, 1, 2));
    EXPECT_EQ(n * 2, Normal3f(2, 4, 6));
    EXPECT_EQ(2 * n, Normal3f(2, 4, 6));
    EXPECT_EQ(n / 2, Normal3f(0.5f, 1, 1.5f));
    EXPECT_EQ(-n, Normal3f(-1, -2, -3));
    Normal3f m = n;
    m += n;
    EXPECT_EQ(m, n * 2);
    m -= n;
    EXPECT_EQ(m, n);
    m *= 4;
    EXPECT_EQ(m, Normal3f(4, 8, 12));
    m /= 4;
    EXPECT_EQ(m, n);
    EXPECT_EQ(n.LengthSquared(), 14);
    EXPECT_EQ(Normal3f(2, 3, 6).Length(), 7);
    EXPECT_EQ(Abs(Normal3f(-1, 2, -3)), Normal3f(1, 2, 3));
    EXPECT_EQ(n[1], 2);
    n[1] = 5;
    EXPECT_EQ(n.y, 5);
    EXPECT_THROW(n[3], std::out_of_range);
    const Normal3f &cn = n;
    EXPECT_THROW(cn[-1], std::out_of_range);
    EXPECT_TRUE(Normal3f(0, 0, kNaN).HasNaNs());
    EXPECT_FALSE(Normal3f(0, 0, 1).HasNaNs());
    EXPECT_TRUE(Normal3f(0, 0, 1) != Normal3f(0, 1, 0));
    std::ostringstream os;
    os << Normal3f(0, 1, 0);
    EXPECT_EQ(os.str(), "[ 0, 1, 0 ]");
}

TEST(Normal3, DotCrossAndNormalizeMatchVectors) {
    std::mt19937_64 rng(kSeed + 13);
    for (int i = 0; i < kRandomCases; ++i) {
        Vector3f a = RandomScaledVector(rng), b = RandomScaledVector(rng);
        Normal3f na(a), nb(b);
        ASSERT_EQ(Dot(na, b), Dot(a, b));
        ASSERT_EQ(Dot(a, nb), Dot(a, b));
        ASSERT_EQ(Dot(na, nb), Dot(a, b));
        ASSERT_EQ(AbsDot(na, b), AbsDot(a, b));
        ASSERT_EQ(AbsDot(a, nb), AbsDot(a, b));
        ASSERT_EQ(AbsDot(na, nb), AbsDot(a, b));
        ASSERT_EQ(Cross(a, nb), Cross(a, b));
        ASSERT_EQ(Cross(na, b), Cross(a, b));
        Normal3f n = Normalize(na);
        ASSERT_EQ(Vector3f(n), Normalize(a));
        ASSERT_LE(std::abs(LengthLd(Vector3f(n)) - 1), 5 * kU);
    }
}

TEST(Normal3, Faceforward) {
    std::mt19937_64 rng(kSeed + 14);
    for (int i = 0; i < kRandomCases; ++i) {
        Vector3f a = RandomVector(rng), b = RandomVector(rng);
        Normal3f na(a), nb(b);
        bool flip = Dot(a, b) < 0;
        Normal3f f1 = Faceforward(na, b);
        Normal3f f2 = Faceforward(na, nb);
        Vector3f f3 = Faceforward(a, b);
        Vector3f f4 = Faceforward(a, nb);
        ASSERT_EQ(f1, flip ? -na : na);
        ASSERT_EQ(f2, flip ? -na : na);
        ASSERT_EQ(f3, flip ? -a : a);
        ASSERT_EQ(f4, flip ? -a : a);
        ASSERT_GE(Dot(f1, b), 0);
        ASSERT_GE(Dot(f3, b), 0);
    }
    // Perpendicular: no flip.
    EXPECT_EQ(Faceforward(Normal3f(0, 0, 1), Vector3f(1, 0, 0)),
              Normal3f(0, 0, 1));
    EXPECT_EQ(Faceforward(Normal3f(0, 0, 1), Vector3f(0, 0, -1)),
              Normal3f(0, 0, -1));
}

// ---------------------------------------------------------------------------
// Ray

TEST(Ray, DefaultAndConstruction) {
    Ray r;
    EXPECT_EQ(r.o, Point3f(0, 0, 0));
    EXPECT_EQ(r.d, Vector3f(0, 0, 0));
    EXPECT_EQ(r.tMax, Infinity);
    EXPECT_EQ(r.time, 0);
    Ray s(Point3f(1, 2, 3), Vector3f(0, 0, 1));
    EXPECT_EQ(s.o, Point3f(1, 2, 3));
    EXPECT_EQ(s.d, Vector3f(0, 0, 1));
    EXPECT_EQ(s.tMax, Infinity);
    EXPECT_EQ(s.time, 0);
    Ray t(Point3f(1, 2, 3), Vector3f(0, 0, 1), 10, Float(0.5));
    EXPECT_EQ(t.tMax, 10);
    EXPECT_EQ(t.time, Float(0.5));
}

TEST(Ray, EvaluatesPointsAlongTheRay) {
    std::mt19937_64 rng(kSeed + 15);
    for (int i = 0; i < kRandomCases; ++i) {
        Point3f o = RandomPoint(rng);
        Vector3f d = RandomVector(rng);
        Ray r(o, d);
        Float t = RandomUniform(rng, -10, 10);
        Point3f p = r(t);
        for (int k = 0; k < 3; ++k) ASSERT_EQ(p[k], o[k] + d[k] * t);
        ASSERT_EQ(r(0), o);
    }
    Ray r(Point3f(1, 1, 1), Vector3f(2, 0, -1));
    EXPECT_EQ(r(Float(1.5)), Point3f(4, 1, Float(-0.5)));
}

TEST(Ray, TMaxIsMutableThroughConstReference) {
    Ray r(Point3f(0, 0, 0), Vector3f(1, 0, 0));
    const Ray &cr = r;
    cr.tMax = 3;  // what an intersection routine does on finding a hit
    EXPECT_EQ(r.tMax, 3);
    EXPECT_TRUE((std::is_const<
                 std::remove_reference<decltype((cr.o))>::type>::value));
}

TEST(Ray, HasNaNs) {
    EXPECT_FALSE(Ray(Point3f(0, 0, 0), Vector3f(1, 0, 0)).HasNaNs());
    EXPECT_TRUE(Ray(Point3f(kNaN, 0, 0), Vector3f(1, 0, 0)).HasNaNs());
    EXPECT_TRUE(Ray(Point3f(0, 0, 0), Vector3f(1, kNaN, 0)).HasNaNs());
    EXPECT_TRUE(Ray(Point3f(0, 0, 0), Vector3f(1, 0, 0), kNaN).HasNaNs());
    EXPECT_FALSE(
        Ray(Point3f(0, 0, 0), Vector3f(1, 0, 0), Infinity).HasNaNs());
    std::ostringstream os;
    os << Ray(Point3f(0, 0, 0), Vector3f(1, 0, 0), 2);
    EXPECT_NE(os.str().find("tMax=2"), std::string::npos);
}
