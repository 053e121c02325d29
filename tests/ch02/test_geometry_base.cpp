// Tests for the floating-point foundations of Chapter 2 (lrt/core/base.h):
// Float, constants, gamma(), bit manipulation, NextFloatUp/Down, the small
// numeric helpers, DifferenceOfProducts() and Quadratic().
//
// Oracles are independent of the code under test: std::nextafter, long
// double arithmetic, exact integer arithmetic, brute force, and equations
// constructed from known, exactly representable roots.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <random>
#include <type_traits>
#include <vector>

#include "lrt/core/geometry.h"

using namespace lrt;

namespace {

typedef long double Ld;

constexpr int kRandomCases = 20000;
constexpr uint64_t kSeed = 0x6c72742d63683032ull;  // "lrt-ch02"

// Unit roundoff of Float, computed without the library's constants.
const Ld kU = Ld(std::numeric_limits<Float>::epsilon()) / 2;
// Unit roundoff of long double (the oracle's precision).
const Ld kULd = std::numeric_limits<Ld>::epsilon() / 2;

bool SameBits(float a, float b) {
    return std::memcmp(&a, &b, sizeof(float)) == 0;
}
bool SameBits(double a, double b) {
    return std::memcmp(&a, &b, sizeof(double)) == 0;
}

// True if v is the Float nearest to the exact value x.
bool IsNearest(Float v, Ld x) {
    Ld up = std::nextafter(v, std::numeric_limits<Float>::infinity());
    Ld down = std::nextafter(v, -std::numeric_limits<Float>::infinity());
    Ld e = std::abs(Ld(v) - x);
    return e <= std::abs(up - x) && e <= std::abs(down - x);
}

// Distance from x to the next representable Float above |x|.
Ld Ulp(Float x) {
    Float a = std::abs(x);
    return Ld(std::nextafter(a, std::numeric_limits<Float>::infinity())) - a;
}

}  // namespace

// ---------------------------------------------------------------------------
// Float and constants

TEST(FloatType, MatchesBuildSwitch) {
#ifdef LRT_FLOAT_AS_DOUBLE
    EXPECT_TRUE((std::is_same<Float, double>::value));
#else
    EXPECT_TRUE((std::is_same<Float, float>::value));
#endif
}

TEST(Constants, MachineEpsilonIsUnitRoundoff) {
    EXPECT_EQ(Ld(MachineEpsilon),
              std::ldexp(Ld(1), -std::numeric_limits<Float>::digits));
    volatile Float one = 1;
    volatile Float eps = MachineEpsilon;
    // 1 + eps is a tie and rounds to even (1); 1 + 2 eps is representable.
    EXPECT_EQ(Float(one + eps), Float(1));
    EXPECT_GT(Float(one + 2 * eps), Float(1));
}

TEST(Constants, InfinityAndMaxFloat) {
    EXPECT_TRUE(std::isinf(Infinity));
    EXPECT_GT(Infinity, 0);
    EXPECT_TRUE(std::isfinite(MaxFloat));
    EXPECT_EQ(std::nextafter(MaxFloat, Infinity), Infinity);
    EXPECT_GT(ShadowEpsilon, 0);
    EXPECT_LT(ShadowEpsilon, Float(1e-3));
}

TEST(Constants, PiMultiplesAreNearestFloats) {
    const Ld pi = 3.141592653589793238462643383279502884L;
    EXPECT_TRUE(IsNearest(Pi, pi));
    EXPECT_TRUE(IsNearest(InvPi, 1 / pi));
    EXPECT_TRUE(IsNearest(Inv2Pi, 1 / (2 * pi)));
    EXPECT_TRUE(IsNearest(Inv4Pi, 1 / (4 * pi)));
    EXPECT_TRUE(IsNearest(PiOver2, pi / 2));
    EXPECT_TRUE(IsNearest(PiOver4, pi / 4));
    EXPECT_TRUE(IsNearest(Sqrt2, std::sqrt(Ld(2))));
}

// ---------------------------------------------------------------------------
// gamma(n)

TEST(Gamma, SmallValues) {
    EXPECT_EQ(gamma(0), 0);
    EXPECT_GE(Ld(gamma(1)), kU);
    for (int n = 1; n < 100; ++n) EXPECT_LT(gamma(n), gamma(n + 1));
    static_assert(gamma(0) == 0, "gamma() is usable in constant expressions");
}

// gamma(n) must bound the worst-case error factor (1 + u)^n - 1 (and
// 1 - (1 - u)^n, which is smaller), even after its own rounding, and must
// be within half an ulp of n u / (1 - n u).
TEST(Gamma, BoundsWorstCaseErrorFactor) {
    for (int n = 1; n <= 5000; ++n) {
        // (1 + u)^n - 1 by the binomial series: positive terms only, so the
        // long double sum is accurate to a few long double ulps.
        Ld term = 1, sum = 0;
        for (int k = 1; k <= n; ++k) {
            term *= Ld(n - k + 1) / Ld(k) * kU;
            sum += term;
            if (term < sum * Ld(1e-30)) break;
        }
        Ld g = gamma(n);
        ASSERT_GE(g, sum * (1 + 4 * kULd)) << "n = " << n;
        Ld exact = n * kU / (1 - n * kU);
        ASSERT_LE(std::abs(g - exact), Ulp(gamma(n)) / 2 * (1 + 1e-6L))
            << "n = " << n;
    }
}

// A sum of n numbers computed left to right is within
// gamma(n - 1) * sum |x_i| of the exact sum.
TEST(Gamma, BoundsErrorOfRandomSums) {
    std::mt19937_64 rng(kSeed);
    std::uniform_int_distribution<int> lenDist(2, 200);
    std::uniform_real_distribution<double> mant(-1, 1);
    std::uniform_int_distribution<int> expo(-12, 12);
    int inexact = 0;
    for (int c = 0; c < kRandomCases / 10; ++c) {
        int n = lenDist(rng);
        Float s = 0;
        Ld exact = 0, absSum = 0;
        for (int i = 0; i < n; ++i) {
            Float x = Float(std::ldexp(mant(rng), expo(rng)));
            s += x;
            exact += x;
            absSum += std::abs(Ld(x));
        }
        Ld err = std::abs(Ld(s) - exact);
        if (err > 0) ++inexact;
        Ld oracleErr = n * kULd * absSum;
        ASSERT_LE(err, Ld(gamma(n - 1)) * absSum + oracleErr);
    }
    // The test is meaningful only if rounding actually happened.
    EXPECT_GT(inexact, kRandomCases / 20);
}

// ---------------------------------------------------------------------------
// Bits

TEST(FloatBits, KnownPatterns) {
    EXPECT_EQ(FloatToBits(1.f), 0x3f800000u);
    EXPECT_EQ(FloatToBits(-0.f), 0x80000000u);
    EXPECT_EQ(FloatToBits(0.f), 0u);
    EXPECT_EQ(FloatToBits(std::numeric_limits<float>::infinity()),
              0x7f800000u);
    EXPECT_EQ(FloatToBits(std::numeric_limits<float>::denorm_min()), 1u);
    EXPECT_EQ(BitsToFloat(uint32_t(0x40490fdb)), 3.14159274f);
    EXPECT_EQ(BitsToFloat(uint32_t(0xbf800000)), -1.f);
    EXPECT_EQ(FloatToBits(1.0), 0x3ff0000000000000ull);
    EXPECT_EQ(FloatToBits(-2.0), 0xc000000000000000ull);
    EXPECT_EQ(FloatToBits(std::numeric_limits<double>::denorm_min()), 1ull);
    EXPECT_TRUE(std::isinf(BitsToFloat(uint64_t(0x7ff0000000000000ull))));
    EXPECT_TRUE(std::isnan(BitsToFloat(uint64_t(0x7ff8000000000000ull))));
    EXPECT_TRUE(std::isnan(BitsToFloat(uint32_t(0x7fc00000))));
}

TEST(FloatBits, RoundTripAndOrder) {
    std::mt19937_64 rng(kSeed + 1);
    for (int i = 0; i < kRandomCases; ++i) {
        uint32_t b32 = uint32_t(rng());
        float f = BitsToFloat(b32);
        if (!std::isnan(f)) {
            ASSERT_EQ(FloatToBits(f), b32);
        }
        uint64_t b64 = rng();
        double d = BitsToFloat(b64);
        if (!std::isnan(d)) {
            ASSERT_EQ(FloatToBits(d), b64);
        }
        // For non-negative values, the order of the values is the order of
        // the bit patterns.
        uint32_t c32 = uint32_t(rng()) & 0x7fffffffu;
        uint32_t a32 = b32 & 0x7fffffffu;
        float fa = BitsToFloat(a32), fc = BitsToFloat(c32);
        if (!std::isnan(fa) && !std::isnan(fc)) {
            ASSERT_EQ(fa < fc, a32 < c32);
        }
    }
}

// ---------------------------------------------------------------------------
// NextFloatUp / NextFloatDown, checked against std::nextafter bit for bit.

namespace {

template <typename F>
std::vector<F> SpecialValues() {
    typedef std::numeric_limits<F> L;
    return {F(0),           -F(0),          L::denorm_min(), -L::denorm_min(),
            L::min(),       -L::min(),      F(1),            F(-1),
            F(0.1),         F(-0.1),        F(2),            F(-2),
            L::max(),       L::lowest(),    L::infinity(),   -L::infinity(),
            L::quiet_NaN(), -L::quiet_NaN()};
}

template <typename F>
void CheckNext(F v) {
    F up = NextFloatUp(v), down = NextFloatDown(v);
    F refUp = std::nextafter(v, std::numeric_limits<F>::infinity());
    F refDown = std::nextafter(v, -std::numeric_limits<F>::infinity());
    if (std::isnan(v)) {
        EXPECT_TRUE(std::isnan(up));
        EXPECT_TRUE(std::isnan(down));
        return;
    }
    // std::nextafter(inf, inf) is inf: no successor, returned unchanged.
    EXPECT_TRUE(SameBits(up, refUp)) << v << ": " << up << " vs " << refUp;
    EXPECT_TRUE(SameBits(down, refDown))
        << v << ": " << down << " vs " << refDown;
}

}  // namespace

TEST(NextFloat, FloatSpecialValues) {
    for (float v : SpecialValues<float>()) CheckNext(v);
    EXPECT_EQ(NextFloatUp(-0.f), std::numeric_limits<float>::denorm_min());
    EXPECT_EQ(NextFloatUp(0.f), std::numeric_limits<float>::denorm_min());
    EXPECT_EQ(NextFloatDown(0.f), -std::numeric_limits<float>::denorm_min());
    EXPECT_EQ(NextFloatUp(std::numeric_limits<float>::max()),
              std::numeric_limits<float>::infinity());
    EXPECT_EQ(NextFloatUp(-std::numeric_limits<float>::infinity()),
              std::numeric_limits<float>::lowest());
    EXPECT_EQ(NextFloatDown(std::numeric_limits<float>::infinity()),
              std::numeric_limits<float>::max());
    EXPECT_EQ(NextFloatUp(1.f), 1.f + std::numeric_limits<float>::epsilon());
}

// NaNs whose bit patterns sit next to an infinity or at the end of the
// integer range: blindly stepping their patterns would produce an infinity
// or wrap around to zero.
TEST(NextFloat, NaNPatternsStayNaN) {
    for (uint32_t b : {0x7f800001u, 0xff800001u, 0x7fffffffu, 0xffffffffu}) {
        float v = BitsToFloat(b);
        ASSERT_TRUE(std::isnan(v));
        EXPECT_TRUE(std::isnan(NextFloatUp(v))) << std::hex << b;
        EXPECT_TRUE(std::isnan(NextFloatDown(v))) << std::hex << b;
    }
    for (uint64_t b : {0x7ff0000000000001ull, 0xfff0000000000001ull,
                       0x7fffffffffffffffull, 0xffffffffffffffffull}) {
        double v = BitsToFloat(b);
        ASSERT_TRUE(std::isnan(v));
        EXPECT_TRUE(std::isnan(NextFloatUp(v))) << std::hex << b;
        EXPECT_TRUE(std::isnan(NextFloatDown(v))) << std::hex << b;
    }
}

TEST(NextFloat, DoubleSpecialValues) {
    for (double v : SpecialValues<double>()) CheckNext(v);
    EXPECT_EQ(NextFloatUp(-0.0), std::numeric_limits<double>::denorm_min());
    EXPECT_EQ(NextFloatDown(-0.0),
              -std::numeric_limits<double>::denorm_min());
    EXPECT_EQ(NextFloatUp(1.0), 1.0 + std::numeric_limits<double>::epsilon());
}

TEST(NextFloat, FloatRandomBitPatterns) {
    std::mt19937_64 rng(kSeed + 2);
    for (int i = 0; i < kRandomCases; ++i) {
        float v = BitsToFloat(uint32_t(rng()));
        CheckNext(v);
        if (!std::isnan(v) && !std::isinf(v)) {
            ASSERT_EQ(NextFloatDown(NextFloatUp(v)), v);
            ASSERT_EQ(NextFloatUp(NextFloatDown(v)), v);
            ASSERT_GT(NextFloatUp(v), v);
            ASSERT_LT(NextFloatDown(v), v);
        }
    }
}

TEST(NextFloat, DoubleRandomBitPatterns) {
    std::mt19937_64 rng(kSeed + 3);
    for (int i = 0; i < kRandomCases; ++i) {
        double v = BitsToFloat(uint64_t(rng()));
        CheckNext(v);
        if (!std::isnan(v) && !std::isinf(v)) {
            ASSERT_EQ(NextFloatDown(NextFloatUp(v)), v);
            ASSERT_EQ(NextFloatUp(NextFloatDown(v)), v);
        }
    }
}

TEST(NextFloat, OrdinaryValuesAndStepping) {
    // Stepping up k times from 1 moves by exactly k ulps.
    float f = 1.f;
    for (int k = 0; k < 1000; ++k) f = NextFloatUp(f);
    EXPECT_EQ(f, 1.f + 1000 * std::numeric_limits<float>::epsilon());
    // Stepping through zero from below visits -0/+0 once.
    float g = -2 * std::numeric_limits<float>::denorm_min();
    g = NextFloatUp(g);
    EXPECT_EQ(g, -std::numeric_limits<float>::denorm_min());
    g = NextFloatUp(g);
    EXPECT_EQ(g, 0.f);
    g = NextFloatUp(g);
    EXPECT_EQ(g, std::numeric_limits<float>::denorm_min());
}

// ---------------------------------------------------------------------------
// Small numeric helpers

TEST(Lerp, EndpointsAreExact) {
    std::mt19937_64 rng(kSeed + 4);
    std::uniform_real_distribution<double> d(-1e6, 1e6);
    for (int i = 0; i < kRandomCases; ++i) {
        Float a = Float(d(rng)), b = Float(d(rng));
        ASSERT_EQ(Lerp(0, a, b), a);
        ASSERT_EQ(Lerp(1, a, b), b);
    }
}

TEST(Lerp, InteriorAgainstLongDouble) {
    std::mt19937_64 rng(kSeed + 5);
    std::uniform_real_distribution<double> d(-100, 100), td(0, 1);
    for (int i = 0; i < kRandomCases; ++i) {
        Float a = Float(d(rng)), b = Float(d(rng)), t = Float(td(rng));
        Ld exact = (1 - Ld(t)) * a + Ld(t) * b;
        Ld bound = 3 * kU / (1 - 3 * kU) *
                   (std::abs((1 - Ld(t)) * a) + std::abs(Ld(t) * b));
        ASSERT_LE(std::abs(Lerp(t, a, b) - exact), bound * (1 + 1e-6L));
    }
    EXPECT_EQ(Lerp(Float(0.5), 2, 4), 3);
    EXPECT_EQ(Lerp(2, 0, 1), 2);  // extrapolation is allowed
}

TEST(Clamp, BasicsAndNaN) {
    EXPECT_EQ(Clamp(5, 0, 3), 3);
    EXPECT_EQ(Clamp(-5, 0, 3), 0);
    EXPECT_EQ(Clamp(2, 0, 3), 2);
    EXPECT_EQ(Clamp(Float(-1.5), 0, 1), Float(0));
    EXPECT_EQ(Clamp(Float(1.5), 0, 1), Float(1));
    EXPECT_EQ(Clamp(Float(0.25), 0, 1), Float(0.25));
    EXPECT_TRUE((std::is_same<decltype(Clamp(Float(1), 0, 1.0)),
                              Float>::value));
    EXPECT_TRUE(std::isnan(Clamp(std::numeric_limits<Float>::quiet_NaN(),
                                 0, 1)));
    EXPECT_EQ(Clamp(Infinity, 0, 1), Float(1));
    EXPECT_EQ(Clamp(-Infinity, 0, 1), Float(0));
}

TEST(AngleConversion, RadiansAndDegrees) {
    EXPECT_LE(std::abs(Radians(180) - Pi), Ulp(Pi));
    EXPECT_LE(std::abs(Radians(90) - PiOver2), Ulp(PiOver2));
    EXPECT_LE(std::abs(Degrees(Pi) - 180), 2 * Ulp(180));
    EXPECT_EQ(Radians(0), 0);
    std::mt19937_64 rng(kSeed + 6);
    std::uniform_real_distribution<double> d(-720, 720);
    for (int i = 0; i < kRandomCases; ++i) {
        Float deg = Float(d(rng));
        Ld exact = Ld(deg) * 3.141592653589793238462643L / 180;
        ASSERT_LE(std::abs(Radians(deg) - exact),
                  3 * kU * std::abs(exact) + 1e-30L);
        ASSERT_LE(std::abs(Degrees(Radians(deg)) - deg),
                  6 * kU * std::abs(Ld(deg)) + 1e-30L);
    }
}

TEST(Mod, IntegersAreNonNegative) {
    for (int a = -60; a <= 60; ++a) {
        for (int b = 1; b <= 12; ++b) {
            int r = Mod(a, b);
            ASSERT_GE(r, 0);
            ASSERT_LT(r, b);
            ASSERT_EQ((a - r) % b, 0) << a << " mod " << b;
        }
    }
    EXPECT_EQ(Mod(-1, 3), 2);
    EXPECT_EQ(Mod(int64_t(-7), int64_t(5)), int64_t(3));
    EXPECT_THROW(Mod(3, 0), std::domain_error);
    EXPECT_THROW(Mod(3, -2), std::domain_error);
}

TEST(Mod, FloatingPoint) {
    EXPECT_EQ(Mod(Float(-1), Float(3)), Float(2));
    EXPECT_EQ(Mod(Float(7.5), Float(2)), Float(1.5));
    // A tiny negative remainder would round up to b; it wraps to 0.
    EXPECT_EQ(Mod(Float(-1e-30), Float(1)), Float(0));
    EXPECT_THROW(Mod(Float(1), Float(0)), std::domain_error);
    EXPECT_THROW(Mod(Float(1), std::numeric_limits<Float>::quiet_NaN()),
                 std::domain_error);
    std::mt19937_64 rng(kSeed + 7);
    std::uniform_real_distribution<double> ad(-1000, 1000), bd(0.01, 50);
    for (int i = 0; i < kRandomCases; ++i) {
        Float a = Float(ad(rng)), b = Float(bd(rng));
        Float r = Mod(a, b);
        ASSERT_GE(r, 0);
        ASSERT_LT(r, b);
        // fmodl is exact; the only rounding is in adding b.
        Ld exact = std::fmod(Ld(a), Ld(b));
        if (exact < 0) exact += b;
        Ld diff = std::abs(Ld(r) - exact);
        bool wrapped = (r == 0 && exact >= b * (1 - 2 * kU));
        ASSERT_TRUE(diff <= kU * b || wrapped) << a << " mod " << b;
    }
}

TEST(IsPowerOf2, AgainstBitCount) {
    for (int v = -100; v <= 70000; ++v) {
        int bits = 0;
        for (unsigned u = unsigned(v > 0 ? v : 0); u; u >>= 1) bits += u & 1;
        ASSERT_EQ(IsPowerOf2(v), v > 0 && bits == 1) << v;
    }
    EXPECT_TRUE(IsPowerOf2(int64_t(1) << 62));
    EXPECT_FALSE(IsPowerOf2((int64_t(1) << 62) + (int64_t(1) << 20)));
    EXPECT_FALSE(IsPowerOf2(std::numeric_limits<int>::min()));
    EXPECT_TRUE(IsPowerOf2(uint32_t(1) << 31));
    static_assert(IsPowerOf2(64) && !IsPowerOf2(0), "constexpr");
}

TEST(Log2Int, AgainstBruteForce) {
    for (uint32_t v = 1; v < 200000; ++v) {
        int expected = -1;
        for (uint32_t u = v; u; u >>= 1) ++expected;
        ASSERT_EQ(Log2Int(v), expected);
        ASSERT_EQ(Log2Int(int32_t(v)), expected);
        ASSERT_EQ(Log2Int(uint64_t(v)), expected);
        ASSERT_EQ(Log2Int(int64_t(v)), expected);
    }
    for (int k = 0; k < 32; ++k) {
        EXPECT_EQ(Log2Int(uint32_t(1) << k), k);
        if (k > 1) {
            EXPECT_EQ(Log2Int((uint32_t(1) << k) - 1), k - 1);
        }
    }
    for (int k = 0; k < 64; ++k) {
        EXPECT_EQ(Log2Int(uint64_t(1) << k), k);
        if (k > 1) {
            EXPECT_EQ(Log2Int((uint64_t(1) << k) - 1), k - 1);
        }
    }
    EXPECT_EQ(Log2Int(std::numeric_limits<int32_t>::max()), 30);
    EXPECT_EQ(Log2Int(std::numeric_limits<int64_t>::max()), 62);
    EXPECT_THROW(Log2Int(uint32_t(0)), std::domain_error);
    EXPECT_THROW(Log2Int(int32_t(0)), std::domain_error);
    EXPECT_THROW(Log2Int(int32_t(-8)), std::domain_error);
    EXPECT_THROW(Log2Int(uint64_t(0)), std::domain_error);
    EXPECT_THROW(Log2Int(int64_t(-1)), std::domain_error);
}

// ---------------------------------------------------------------------------
// DifferenceOfProducts: exact integer oracle, with operands chosen so that
// the two products nearly cancel.

TEST(DifferenceOfProducts, RelativeErrorUnderCancellation) {
    std::mt19937_64 rng(kSeed + 8);
    // Integers below 2^(digits - 1) are exactly representable, and their
    // products fit comfortably in int64_t.
    const int bits = std::min(std::numeric_limits<Float>::digits - 1, 30);
    std::uniform_int_distribution<int64_t> big(-(int64_t(1) << bits),
                                               int64_t(1) << bits);
    std::uniform_int_distribution<int64_t> small(-3, 3);
    for (int i = 0; i < kRandomCases; ++i) {
        int64_t a = big(rng), b = big(rng);
        int64_t c = a + small(rng), d = b + small(rng);
        if (std::abs(c) > (int64_t(1) << bits)) c = a;
        if (std::abs(d) > (int64_t(1) << bits)) d = b;
        int64_t exact = a * b - c * d;
        Float r = DifferenceOfProducts(Float(a), Float(b), Float(c),
                                       Float(d));
        Ld err = std::abs(Ld(r) - Ld(exact));
        ASSERT_LE(err, 2 * kU * std::abs(Ld(exact)))
            << a << " " << b << " " << c << " " << d;
    }
    EXPECT_EQ(DifferenceOfProducts(Float(3), Float(4), Float(2), Float(6)),
              Float(0));
}

// ---------------------------------------------------------------------------
// Quadratic

namespace {

// Builds a x^2 + b x + c = a (x - r0)(x - r1) with a, r0 and r1 of few
// significant bits, so that b and c are exactly representable and the exact
// roots are known. Returns false if that failed (then the case is skipped).
bool ExactQuadratic(std::mt19937_64 &rng, Float *a, Float *b, Float *c,
                    Ld *r0, Ld *r1, bool nearlyEqual) {
    const int digits = std::numeric_limits<Float>::digits;
    const int mbits = (digits - 4) / 2;  // bits of each root's mantissa
    const int maxSpread = digits - mbits - 4;
    std::uniform_int_distribution<int64_t> mant(-(int64_t(1) << mbits),
                                                int64_t(1) << mbits);
    std::uniform_int_distribution<int> expo(-8, 8), aexp(-4, 4), coin(0, 1);
    int64_t m0 = mant(rng), m1 = mant(rng);
    int e0 = expo(rng), e1 = expo(rng);
    if (nearlyEqual) {
        m1 = m0 + 1;
        e1 = e0;
    }
    if (std::abs(e0 - e1) > maxSpread) e1 = e0;
    Ld ma = (coin(rng) ? 1 : 3) * (coin(rng) ? 1 : -1);
    Ld A = std::ldexp(ma, aexp(rng));
    *r0 = std::ldexp(Ld(m0), e0);
    *r1 = std::ldexp(Ld(m1), e1);
    Ld B = -A * (*r0 + *r1), C = A * *r0 * *r1;
    *a = Float(A);
    *b = Float(B);
    *c = Float(C);
    if (Ld(*b) != B || Ld(*c) != C) return false;
    if (*r0 > *r1) std::swap(*r0, *r1);
    return true;
}

::testing::AssertionResult RootClose(Float t, Ld r, Ld ulps) {
    Ld err = std::abs(Ld(t) - r);
    if (err <= ulps * kU * std::abs(r)) return ::testing::AssertionSuccess();
    return ::testing::AssertionFailure()
           << "computed " << t << ", exact " << double(r) << ", error "
           << double(err / (kU * std::abs(r))) << " u";
}

}  // namespace

TEST(Quadratic, RecoversExactRoots) {
    std::mt19937_64 rng(kSeed + 9);
    int tested = 0;
    for (int i = 0; i < kRandomCases; ++i) {
        Float a, b, c, t0, t1;
        Ld r0, r1;
        if (!ExactQuadratic(rng, &a, &b, &c, &r0, &r1, i % 4 == 0)) continue;
        ++tested;
        ASSERT_TRUE(Quadratic(a, b, c, &t0, &t1))
            << a << " " << b << " " << c;
        ASSERT_LE(t0, t1);
        // Each root is within about 4 u of the exact root (see the text).
        ASSERT_TRUE(RootClose(t0, r0, 6)) << a << " " << b << " " << c;
        ASSERT_TRUE(RootClose(t1, r1, 6)) << a << " " << b << " " << c;
    }
    EXPECT_GT(tested, kRandomCases * 9 / 10);
}

TEST(Quadratic, WidelySeparatedRoots) {
    // Roots 1 and 2^k: the textbook formula loses the small root entirely
    // for large k; the stable formulation keeps it exact.
    for (int k = 1; k < std::numeric_limits<Float>::digits - 1; ++k) {
        Float big = std::ldexp(Float(1), k);
        Float t0, t1;
        ASSERT_TRUE(Quadratic(1, -(big + 1), big, &t0, &t1));
        EXPECT_TRUE(RootClose(t0, 1, 4)) << "k = " << k;
        EXPECT_TRUE(RootClose(t1, big, 4)) << "k = " << k;
        // Same with a negative leading coefficient.
        ASSERT_TRUE(Quadratic(-2, 2 * (big + 1), -2 * big, &t0, &t1));
        EXPECT_TRUE(RootClose(t0, 1, 4)) << "k = " << k;
        EXPECT_TRUE(RootClose(t1, big, 4)) << "k = " << k;
    }
}

TEST(Quadratic, RandomCoefficientsAgainstLongDouble) {
    std::mt19937_64 rng(kSeed + 10);
    std::uniform_real_distribution<double> d(-10, 10);
    int real = 0, compared = 0;
    for (int i = 0; i < kRandomCases; ++i) {
        Float a = Float(d(rng)), b = Float(d(rng)), c = Float(d(rng));
        Ld disc = Ld(b) * b - 4 * Ld(a) * c;
        // Skip cases the long double oracle cannot resolve: its own
        // discriminant error must be far below Float's.
        Ld oracleErr = 4 * kULd * (Ld(b) * b + 4 * std::abs(Ld(a) * c));
        if (std::abs(disc) > 0 && oracleErr > std::abs(disc) * kU / 16)
            continue;
        Float t0, t1;
        bool found = Quadratic(a, b, c, &t0, &t1);
        ++compared;
        ASSERT_EQ(found, disc >= 0) << a << " " << b << " " << c;
        if (!found) continue;
        ++real;
        Ld s = std::sqrt(disc);
        Ld q = -(Ld(b) + (b < 0 ? -s : s)) / 2;
        Ld r0 = q / a, r1 = c / q;
        if (r0 > r1) std::swap(r0, r1);
        ASSERT_TRUE(RootClose(t0, r0, 6)) << a << " " << b << " " << c;
        ASSERT_TRUE(RootClose(t1, r1, 6)) << a << " " << b << " " << c;
    }
    EXPECT_GT(compared, kRandomCases / 2);
    EXPECT_GT(real, compared / 4);
}

TEST(Quadratic, SpecialCases) {
    Float t0 = -1, t1 = -1;
    EXPECT_FALSE(Quadratic(1, 0, 1, &t0, &t1));  // x^2 + 1
    ASSERT_TRUE(Quadratic(1, -2, 1, &t0, &t1));  // double root
    EXPECT_EQ(t0, 1);
    EXPECT_EQ(t1, 1);
    ASSERT_TRUE(Quadratic(1, -3, 0, &t0, &t1));  // c = 0
    EXPECT_EQ(t0, 0);
    EXPECT_EQ(t1, 3);
    ASSERT_TRUE(Quadratic(1, 0, 0, &t0, &t1));  // b = c = 0
    EXPECT_EQ(t0, 0);
    EXPECT_EQ(t1, 0);
    ASSERT_TRUE(Quadratic(1, 0, -4, &t0, &t1));  // b = 0
    EXPECT_EQ(t0, -2);
    EXPECT_EQ(t1, 2);
    ASSERT_TRUE(Quadratic(-1, 0, 4, &t0, &t1));  // a < 0, still ordered
    EXPECT_EQ(t0, -2);
    EXPECT_EQ(t1, 2);
    // Linear equations.
    ASSERT_TRUE(Quadratic(0, 2, -4, &t0, &t1));
    EXPECT_EQ(t0, 2);
    EXPECT_EQ(t1, 2);
    EXPECT_FALSE(Quadratic(0, 0, 1, &t0, &t1));
    EXPECT_FALSE(Quadratic(0, 0, 0, &t0, &t1));
    // NaN anywhere means no roots.
    const Float nan = std::numeric_limits<Float>::quiet_NaN();
    EXPECT_FALSE(Quadratic(nan, 1, -1, &t0, &t1));
    EXPECT_FALSE(Quadratic(1, nan, -1, &t0, &t1));
    EXPECT_FALSE(Quadratic(1, 1, nan, &t0, &t1));
    EXPECT_FALSE(Quadratic(0, nan, 1, &t0, &t1));
    EXPECT_FALSE(Quadratic(0, 1, nan, &t0, &t1));
}
