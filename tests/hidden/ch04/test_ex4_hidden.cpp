// Hidden tests of chapter 4's graded exercises (docs/exercises.md): they run
// at grading time only and never ship to students. The public tests of the
// same exercises are the suites Ex4_9_*, Ex4_10_*, Ex4_11_* and Ex4_12_* in
// tests/ch04/;
// these use other cases and, where they need an oracle, other methods:
//
// - areas known in closed form (whole spheres, hemispheres, half disks,
//   polyhedra), with pi in long double;
// - long double references computed from the values that the shapes store,
//   for slivers of small phiMax and for bands and rings a few units in the
//   last place thin;
// - Monte Carlo hit-or-miss estimates: normalized Gaussian points on the
//   sphere (which owe nothing to the hat-box theorem) and uniform points in a
//   square around a disk; for the paraboloid, uniform points in the square
//   around its shadow on the xy plane, weighted by the graph's area element;
// - properties over many random cases (bands of equal height have equal
//   areas; areas add up), and exact results (right triangles with dyadic
//   legs, collinear vertices).
//
// Every random test states its number of cases; the seeds change with every
// grading (calls::Seed), except those of the Monte Carlo estimates, which
// must pass every time for a right answer. Tests that could accept a wrong
// formula also check that they reject it.

#include "lrt/shapes/sphere.h"
#include "lrt/shapes/disk.h"
#include "lrt/shapes/triangle.h"
#include "lrt/shapes/paraboloid.h"

#include "ch04/exercise_calls.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <string>
#include <vector>

using namespace lrt;

namespace {

using LD = long double;
constexpr LD kPiLD = 3.141592653589793238462643383279502884L;
constexpr double kPi = 3.14159265358979323846;
constexpr LD kU = LD(MachineEpsilon);  // unit roundoff of Float

// Monte Carlo: points per shape, and the agreement required, in standard
// errors of the estimate.
constexpr int kPoints = 1 << 20;
constexpr double kSigmas = 4.5;
// Random cases of the property tests.
constexpr int kPropertyCases = 5000;
constexpr int kTriangleCases = 3000;

LD RelativeError(LD computed, LD exact) {
    return std::abs(computed - exact) / std::abs(exact);
}

// The phiMax, in radians, that chapter 3's constructors store for an angle
// given in degrees.
Float StoredPhiMax(Float degrees) {
    Float deg = Clamp(degrees, 0, 360);
    return (deg >= 360) ? 2 * Pi : Radians(deg);
}

std::string SphereText(Float r, Float z0, Float z1, Float deg) {
    return "sphere r=" + std::to_string(r) + " z=[" + std::to_string(z0) +
           ", " + std::to_string(z1) + "] phiMax=" + std::to_string(deg);
}

std::string DiskText(Float r, Float ri, Float deg) {
    return "disk r=" + std::to_string(r) + " ri=" + std::to_string(ri) +
           " phiMax=" + std::to_string(deg);
}

// A hit-or-miss estimate: the fraction of the points that hit, and the
// standard error of that fraction.
struct Fraction {
    double p, se;
};

Fraction HitOrMiss(long hits) {
    double p = double(hits) / kPoints;
    return {p, std::sqrt(p * (1 - p) / kPoints)};
}

// The fraction of the unit sphere with heights in [z0, z1] and azimuths in
// [0, phiMax]; the points are normalized triples of Gaussian numbers.
Fraction SphereFraction(double z0, double z1, double phiMax, uint64_t seed) {
    std::mt19937_64 rng(seed);
    std::normal_distribution<double> gauss;
    long hits = 0;
    for (int i = 0; i < kPoints; ++i) {
        double x = gauss(rng), y = gauss(rng), z = gauss(rng);
        double len = std::sqrt(x * x + y * y + z * z);
        double phi = std::atan2(y, x);
        if (phi < 0) phi += 2 * kPi;
        if (z >= z0 * len && z <= z1 * len && phi <= phiMax) ++hits;
    }
    return HitOrMiss(hits);
}

// The fraction of the square [-1, 1]^2 covered by the ring sector with radii
// in [ri, 1] and azimuths in [0, phiMax].
Fraction RingFraction(double ri, double phiMax, uint64_t seed) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> U(-1, 1);
    long hits = 0;
    for (int i = 0; i < kPoints; ++i) {
        double x = U(rng), y = U(rng);
        double rho2 = x * x + y * y;
        double phi = std::atan2(y, x);
        if (phi < 0) phi += 2 * kPi;
        if (rho2 <= 1 && rho2 >= ri * ri && phi <= phiMax) ++hits;
    }
    return HitOrMiss(hits);
}

// Half the length of the cross product of the edges from p0, in long double,
// and the sine of the angle at p0.
LD CrossAreaLD(const Point3f &p0, const Point3f &p1, const Point3f &p2,
               LD *sine) {
    LD a[3], b[3];
    for (int k = 0; k < 3; ++k) {
        a[k] = LD(p1[k]) - LD(p0[k]);
        b[k] = LD(p2[k]) - LD(p0[k]);
    }
    LD cx = a[1] * b[2] - a[2] * b[1], cy = a[2] * b[0] - a[0] * b[2],
       cz = a[0] * b[1] - a[1] * b[0];
    LD c = std::sqrt(cx * cx + cy * cy + cz * cz);
    LD la = std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
    LD lb = std::sqrt(b[0] * b[0] + b[1] * b[1] + b[2] * b[2]);
    *sine = c / (la * lb);
    return c / 2;
}

// The bound of Section 4.5 (the triangle), as in the public tests: the
// final rounding to Float plus a few roundings of double precision relative
// to the cross product's length.
LD TriangleBound(LD sine) {
    const LD unitDouble = 1.1102230246251565404e-16L;  // 2^-53
    return 4 * kU + 8 * unitDouble / sine;
}

}  // namespace

// ---------------------------------------------------------------------------
// Exercise 4.9: Sphere::Area()

// Whole spheres and hemispheres, asked for directly and through heights and
// angles that the constructor clamps, over radii from 1e-6 to 2.5e7.
EXERCISE_TEST(Ex4_9_SphereAreaHidden, WholeSpheresAndHemispheresInClosedForm) {
    for (Float r : {Float(1e-6), Float(0.125), Float(1), Float(3.7),
                    Float(1e3), Float(2.5e7)}) {
        const LD r2 = LD(r) * LD(r);
        struct Case {
            Float z0, z1, degrees;
            LD area;
        };
        // Pi is rounded once (half a unit) and a conversion from degrees
        // rounds twice more; the formula itself stays within gamma_3.
        const Case cases[] = {
            {-r, r, 360, 4 * kPiLD * r2},
            {3 * r, -3 * r, 1000, 4 * kPiLD * r2},
            {0, 2 * r, 360, 2 * kPiLD * r2},
            {-5 * r, 0, 400, 2 * kPiLD * r2},
            {-r, r, 180, 2 * kPiLD * r2},
            {0, r, 180, kPiLD * r2},
            {-r, 0, 90, kPiLD * r2 / 2}};
        for (const Case &c : cases) {
            Float area = ex::SphereArea(Transform(), false, r, c.z0, c.z1,
                                        c.degrees);
            EXPECT_LE(RelativeError(area, c.area), LD(gamma(7)))
                << SphereText(r, c.z0, c.z1, c.degrees) << ": Area() "
                << area << ", exact " << double(c.area);
        }
    }
}

// Slivers of small phiMax, caps, bands and bands a unit or two in the last
// place high, against the exact area of the stored surface.
EXERCISE_TEST(Ex4_9_SphereAreaHidden, SliversAndThinBandsWithinGamma3) {
    bool thetaFormulaFails = false;
    int tested = 0;
    for (Float r : {Float(0.7), Float(42), Float(3e-3)}) {
        std::vector<std::pair<Float, Float>> bands = {
            {-r, r}, {Float(0.99) * r, r}, {Float(-0.3) * r, Float(0.2) * r}};
        Float z = Float(0.6) * r;
        bands.push_back({z, std::nextafter(z, r)});
        bands.push_back({z, std::nextafter(std::nextafter(z, r), r)});
        Float zn = Float(-0.85) * r;
        bands.push_back({std::nextafter(zn, -r), zn});
        for (Float deg : {Float(1e-4), Float(0.01), Float(0.5), Float(1),
                          Float(7.5), Float(45), Float(179.5), Float(359.9)}) {
            for (const auto &b : bands) {
                Float phi = StoredPhiMax(deg);
                LD exact = LD(phi) * LD(r) * (LD(b.second) - LD(b.first));
                Float area = ex::SphereArea(Transform(), false, r, b.first,
                                            b.second, deg);
                ASSERT_GT(area, 0) << SphereText(r, b.first, b.second, deg);
                ASSERT_LE(RelativeError(area, exact), LD(gamma(3)))
                    << SphereText(r, b.first, b.second, deg) << ": Area() "
                    << area << ", exact " << double(exact);
                ++tested;
                // The same band through the polar angles: cos(acos(z / r))
                // loses the band's height when the band is thin.
                Float ct0 = std::cos(std::acos(b.first / r));
                Float ct1 = std::cos(std::acos(b.second / r));
                Float viaTheta = phi * r * r * (ct0 - ct1);
                if (RelativeError(viaTheta, exact) > LD(gamma(3)))
                    thetaFormulaFails = true;
            }
        }
    }
    EXPECT_EQ(tested, 3 * 6 * 8);
    EXPECT_TRUE(thetaFormulaFails)
        << "the test cannot tell an area computed from the polar angles";
}

// Archimedes: bands of equal height have equal areas wherever they cut the
// sphere, and the areas of adjacent bands and sectors add up. The heights
// are multiples of 2^-12 r, so that every sum and difference below is exact
// in Float and the bands compared really have the same height.
EXERCISE_TEST(Ex4_9_SphereAreaHidden, EqualHeightsEqualAreasAndAdditivity) {
    std::mt19937_64 rng(calls::Seed(0x4e9a11));
    std::uniform_int_distribution<int> grid(-4096, 4096);
    std::uniform_real_distribution<double> U(0, 1);
    const LD tol = 4 * LD(gamma(3));
    bool thetaFormulaFails = false;
    for (int i = 0; i < kPropertyCases; ++i) {
        Float r = std::ldexp(Float(1), int(40 * U(rng)) - 20);
        Float unit = std::ldexp(r, -12);
        int k0 = grid(rng), k1 = grid(rng), k2 = grid(rng);
        int lo = std::min(k0, k1), hi = std::max(k0, k1);
        if (hi - lo < 1) continue;
        int height = hi - lo;
        // A second band of the same height, anywhere on the sphere.
        int lo2 = -4096 + int((8192 - height) * U(rng));
        Float deg = Float(1 + 359 * U(rng));
        auto band = [&](int from, int to, Float degrees) {
            return ex::SphereArea(Transform(), false, r, from * unit,
                                  to * unit, degrees);
        };
        Float a = band(lo, hi, deg), b = band(lo2, lo2 + height, deg);
        std::string what = SphereText(r, lo * unit, hi * unit, deg);
        ASSERT_LE(RelativeError(b, a), tol)
            << what << " and the band from " << lo2 * unit;
        // Areas proportional to the polar angle would differ.
        LD thetaA = std::acos(LD(lo) / 4096) - std::acos(LD(hi) / 4096);
        LD thetaB = std::acos(LD(lo2) / 4096) -
                    std::acos(LD(lo2 + height) / 4096);
        if (RelativeError(thetaB, thetaA) > tol) thetaFormulaFails = true;
        // Split the band at a third height, and the azimuths in two.
        if (k2 > lo && k2 < hi) {
            ASSERT_LE(RelativeError(LD(band(lo, k2, deg)) +
                                        LD(band(k2, hi, deg)),
                                    LD(a)),
                      tol)
                << what << " split at " << k2 * unit;
        }
        ASSERT_LE(RelativeError(2 * LD(band(lo, hi, 180)),
                                LD(band(lo, hi, 360))),
                  tol)
            << what;
    }
    EXPECT_TRUE(thetaFormulaFails)
        << "the test cannot tell areas proportional to the polar angle";
}

// Hit-or-miss estimates of the fraction of the whole sphere, 4 pi r^2, that
// the partial sphere covers. (The estimates are computed once, in statics:
// they do not depend on the code under test, and the grader runs a test's
// body several times.)
EXERCISE_TEST(Ex4_9_SphereAreaHidden, MatchesGaussianPointsOnTheSphere) {
    struct Case {
        Float r, z0, z1, degrees;
    };
    static const Case cases[] = {{0.8f, 0, 0.8f, 360},      // hemisphere
                          {2, -2, -1.5f, 360},       // cap at the south pole
                          {1, -0.25f, 0.25f, 200},   // equatorial band
                          {3, 2.25f, 2.85f, 330},    // band near the pole
                          {1.25f, -1.25f, 1.25f, 5}, // sliver, pole to pole
                          {0.5f, 0.4f, 0.5f, 60},    // small cap, narrow
                          {4, -3, 1, 123.5f}};
    static const std::vector<Fraction> fractions = [] {
        std::vector<Fraction> v;
        uint64_t seed = 0x4e9c0;
        for (const Case &c : cases)
            v.push_back(SphereFraction(c.z0 / double(c.r), c.z1 / double(c.r),
                                       double(c.degrees) * kPi / 180, ++seed));
        return v;
    }();
    for (size_t k = 0; k < fractions.size(); ++k) {
        const Case &c = cases[k];
        const Fraction &f = fractions[k];
        Float area = ex::SphereArea(Transform(), false, c.r, c.z0, c.z1,
                                    c.degrees);
        double r = c.r, phi = double(c.degrees) * kPi / 180;
        double whole = 4 * kPi * r * r;
        double estimate = whole * f.p, se = whole * f.se;
        std::string what = SphereText(c.r, c.z0, c.z1, c.degrees);
        ASSERT_GT(se, 0) << what;
        EXPECT_LE(std::abs(area - estimate), kSigmas * se)
            << what << ": Area() " << area << ", estimate " << estimate
            << " +- " << se;
        // Two plausible mistakes, away from the equator where they are
        // large: areas proportional to the polar angle, and thin cylinders
        // without the slope factor (phiMax times the integral of the
        // profile).
        if (c.z0 > 0 || c.z1 < 0) {
            double t0 = std::acos(c.z0 / r), t1 = std::acos(c.z1 / r);
            auto segment = [r](double z) {
                return 0.5 * (z * std::sqrt(r * r - z * z) +
                              r * r * std::asin(z / r));
            };
            double byTheta = phi * r * r * (t0 - t1);
            double cylinders = phi * (segment(c.z1) - segment(c.z0));
            EXPECT_GT(std::abs(byTheta - estimate), kSigmas * se) << what;
            EXPECT_GT(std::abs(cylinders - estimate), kSigmas * se) << what;
        }
    }
}

// ---------------------------------------------------------------------------
// Exercise 4.10: Disk::Area()

// Full disks, half disks, sectors and rings whose area is pi r^2 times a
// simple fraction, over radii from 1e-5 to 6.5e5 and heights far from 0.
EXERCISE_TEST(Ex4_10_DiskAreaHidden, FullDisksHalfDisksAndSectorsInClosedForm) {
    for (Float r : {Float(1e-5), Float(0.3), Float(1), Float(17),
                    Float(6.5e5)}) {
        const LD r2 = LD(r) * LD(r);
        struct Case {
            Float height, ri, degrees;
            LD area;
        };
        const Case cases[] = {
            {0, 0, 360, kPiLD * r2},
            {-2.5f, 0, 720, kPiLD * r2},
            {1e10f, 0, 180, kPiLD * r2 / 2},
            {3, r / 2, 360, kPiLD * r2 * 3 / 4},
            {-7, r / 2, 90, kPiLD * r2 * 3 / 16},
            {0.5f, r / 4, 45, kPiLD * r2 * 15 / 128},
            {0, r / 8, 270, kPiLD * r2 * 3 * 63 / 256}};
        for (const Case &c : cases) {
            Float area = ex::DiskArea(Transform(), false, c.height, r, c.ri,
                                      c.degrees);
            EXPECT_LE(RelativeError(area, c.area), LD(gamma(7)))
                << DiskText(r, c.ri, c.degrees) << " h=" << c.height
                << ": Area() " << area << ", exact " << double(c.area);
        }
    }
}

// The thinnest rings there are: the inner radius one, two or three units in
// the last place below the outer one (equal radii describe no surface and
// the constructor rejects them), with narrow and wide sectors.
EXERCISE_TEST(Ex4_10_DiskAreaHidden, ThinnestRingsAndNarrowSectorsWithinGamma4) {
    bool naiveFails = false;
    int tested = 0;
    for (Float r : {Float(2.5), Float(1e-4), Float(12345.6), Float(0.3),
                    Float(7e7)}) {
        Float ri = r;
        for (int k = 1; k <= 3; ++k) {
            ri = std::nextafter(ri, Float(0));
            for (Float deg : {Float(1e-3), Float(1), Float(90), Float(359),
                              Float(360)}) {
                Float phi = StoredPhiMax(deg);
                LD exact = LD(phi) / 2 * (LD(r) - LD(ri)) * (LD(r) + LD(ri));
                Float area =
                    ex::DiskArea(Transform(), false, Float(-1.5), r, ri, deg);
                ASSERT_GT(area, 0) << DiskText(r, ri, deg);
                ASSERT_LE(RelativeError(area, exact), LD(gamma(4)))
                    << DiskText(r, ri, deg) << ": Area() " << area
                    << ", exact " << double(exact);
                ++tested;
                Float naive = Float(0.5) * phi * (r * r - ri * ri);
                if (RelativeError(naive, exact) > 100 * LD(gamma(4)))
                    naiveFails = true;
            }
        }
    }
    EXPECT_EQ(tested, 5 * 3 * 5);
    EXPECT_TRUE(naiveFails) << "the test cannot tell the unfactored formula";
}

// Hit-or-miss estimates of the fraction of the square [-r, r]^2 that the
// disk covers (computed once, as for the sphere).
EXERCISE_TEST(Ex4_10_DiskAreaHidden, MatchesUniformPointsInTheSquare) {
    struct Case {
        Float height, r, ri, degrees;
    };
    static const Case cases[] = {{0.5f, 1, 0, 360},        // full disk
                          {-3, 2.5f, 2, 360},       // ring
                          {1e3f, 0.75f, 0, 45},     // sector
                          {0, 4, 3.5f, 20},         // narrow ring sector
                          {2, 1.5f, 0.3f, 271},
                          {0, 3, 1, 180}};          // half ring
    static const std::vector<Fraction> fractions = [] {
        std::vector<Fraction> v;
        uint64_t seed = 0x4ea0;
        for (const Case &c : cases)
            v.push_back(RingFraction(double(c.ri) / double(c.r),
                                     double(c.degrees) * kPi / 180, ++seed));
        return v;
    }();
    for (size_t k = 0; k < fractions.size(); ++k) {
        const Case &c = cases[k];
        const Fraction &f = fractions[k];
        Float area = ex::DiskArea(Transform(), false, c.height, c.r, c.ri,
                                  c.degrees);
        double r = c.r, ri = c.ri, phi = double(c.degrees) * kPi / 180;
        double square = 4 * r * r;
        double estimate = square * f.p, se = square * f.se;
        std::string what = DiskText(c.r, c.ri, c.degrees);
        ASSERT_GT(se, 0) << what;
        EXPECT_LE(std::abs(area - estimate), kSigmas * se)
            << what << ": Area() " << area << ", estimate " << estimate
            << " +- " << se;
        // Plausible mistakes: the square of the width instead of the
        // difference of squares, a missing half, the hole ignored.
        if (ri > 0) {
            for (double wrong : {0.5 * phi * (r - ri) * (r - ri),
                                 phi * (r * r - ri * ri), 0.5 * phi * r * r,
                                 phi * r * (r - ri)})
                EXPECT_GT(std::abs(wrong - estimate), kSigmas * se)
                    << what << ": " << wrong;
        }
    }
}

// ---------------------------------------------------------------------------
// Exercise 4.11: Triangle::Area()

// Octahedra, cubes and regular tetrahedra, whose faces have areas known in
// closed form, with exactly representable vertices; then under a
// non-uniform scale (exact vertices again) and a rotation (rounded ones).
EXERCISE_TEST(Ex4_11_TriangleAreaHidden, PolyhedraOfKnownArea) {
    const LD sqrt3 = std::sqrt(LD(3));
    for (Float s : {Float(1), Float(0.375), Float(1024), Float(1.0 / 64)}) {
        const LD s2 = LD(s) * LD(s);
        // Octahedron: 8 equilateral faces of side s sqrt(2).
        std::vector<Point3f> oct = {Point3f(s, 0, 0), Point3f(-s, 0, 0),
                                    Point3f(0, s, 0), Point3f(0, -s, 0),
                                    Point3f(0, 0, s), Point3f(0, 0, -s)};
        std::vector<int> octIdx;
        for (int x = 0; x < 2; ++x)
            for (int y = 2; y < 4; ++y)
                for (int z = 4; z < 6; ++z) octIdx.insert(octIdx.end(),
                                                          {x, y, z});
        // Cube [0, s]^3: 6 faces, 12 right triangles with legs s.
        std::vector<Point3f> cube;
        for (int i = 0; i < 8; ++i)
            cube.push_back(Point3f(i & 1 ? s : 0, i & 2 ? s : 0,
                                   i & 4 ? s : 0));
        std::vector<int> cubeIdx = {0, 1, 3, 0, 3, 2, 4, 5, 7, 4, 7, 6,
                                    0, 1, 5, 0, 5, 4, 2, 3, 7, 2, 7, 6,
                                    0, 2, 6, 0, 6, 4, 1, 3, 7, 1, 7, 5};
        // Regular tetrahedron: 4 equilateral faces of side 2 s sqrt(2).
        std::vector<Point3f> tet = {Point3f(s, s, s), Point3f(s, -s, -s),
                                    Point3f(-s, s, -s), Point3f(-s, -s, s)};
        std::vector<int> tetIdx = {0, 1, 2, 0, 3, 1, 0, 2, 3, 1, 3, 2};

        struct Solid {
            const char *name;
            const std::vector<Point3f> &P;
            const std::vector<int> &idx;
            LD face;
        };
        const Solid solids[] = {{"octahedron", oct, octIdx, sqrt3 / 2 * s2},
                                {"cube", cube, cubeIdx, s2 / 2},
                                {"tetrahedron", tet, tetIdx, 2 * sqrt3 * s2}};
        for (const Solid &solid : solids) {
            for (Float area :
                 ex::TriangleAreas(Transform(), solid.idx, solid.P))
                EXPECT_LE(RelativeError(area, solid.face), 4 * kU)
                    << solid.name << " s=" << s;
        }

        // The cube stretched to a box of sides 2s, 3s, 5s: the world-space
        // area is 2 (6 + 10 + 15) s^2, the object-space area 6 s^2.
        LD sum = 0;
        for (Float area : ex::TriangleAreas(Scale(2, 3, 5), cubeIdx, cube))
            sum += area;
        EXPECT_LE(RelativeError(sum, 62 * s2), 4 * kU) << "box s=" << s;

        // The octahedron rotated: every face keeps its area, up to the
        // rounding of the rotated vertices.
        Transform rot = Rotate(33, Vector3f(1, 2, 2));
        for (Float area : ex::TriangleAreas(rot, octIdx, oct))
            EXPECT_LE(RelativeError(area, sqrt3 / 2 * s2), 64 * kU)
                << "rotated octahedron s=" << s;
    }
}

// Right triangles with dyadic legs, in each coordinate plane, far from the
// origin and with the vertices in every order: the edges and the cross
// product are exact, so the area is a b / 2 to within the final rounding.
EXERCISE_TEST(Ex4_11_TriangleAreaHidden, RightTrianglesInEveryPlane) {
    std::mt19937_64 rng(calls::Seed(0x4eb1));
    std::uniform_int_distribution<int> leg(1, 4096), offset(-4096, 4096);
    std::uniform_int_distribution<int> axis(0, 2), order(0, 5);
    const int perms[6][3] = {{0, 1, 2}, {1, 2, 0}, {2, 0, 1},
                             {0, 2, 1}, {2, 1, 0}, {1, 0, 2}};
    for (int i = 0; i < kTriangleCases; ++i) {
        Float a = Float(leg(rng)) / 256, b = Float(leg(rng)) / 256;
        Point3f o(Float(offset(rng)), Float(offset(rng)), Float(offset(rng)));
        int u = axis(rng), v = (u + 1 + axis(rng) % 2) % 3;
        Point3f p1 = o, p2 = o;
        p1[u] += a;
        p2[v] += b;
        Point3f corners[3] = {o, p1, p2};
        const int *p = perms[order(rng)];
        std::vector<Point3f> P = {corners[p[0]], corners[p[1]],
                                  corners[p[2]]};
        LD exact = LD(a) * LD(b) / 2;
        ASSERT_LE(RelativeError(ex::TriangleArea(Transform(), P[0], P[1], P[2]),
                                exact),
                  4 * kU)
            << "legs " << a << ", " << b << " at " << o << " axes " << u
            << ", " << v;
    }
}

// Needles built around a long segment, with the third vertex beside it,
// before it or beyond it, and the vertices in a random order, so that the
// narrow angle (or the angle close to pi) may be at any of them.
EXERCISE_TEST(Ex4_11_TriangleAreaHidden, NeedlesWithTheNarrowAngleAnywhere) {
    std::mt19937_64 rng(calls::Seed(0x4eb2));
    std::uniform_real_distribution<double> U(0, 1);
    const int perms[6][3] = {{0, 1, 2}, {1, 2, 0}, {2, 0, 1},
                             {0, 2, 1}, {2, 1, 0}, {1, 0, 2}};
    bool floatEdgesFail = false;
    int tested = 0;
    for (int i = 0; i < kTriangleCases; ++i) {
        double A[3], d[3], n[3];
        for (int k = 0; k < 3; ++k) {
            A[k] = 40 * U(rng) - 20;
            d[k] = 2 * U(rng) - 1;
        }
        // A unit vector n perpendicular to d.
        double len = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
        double scale = (1 + 2 * U(rng)) / len;
        for (double &x : d) x *= scale;
        double e[3] = {0, 0, 0};
        e[i % 3] = 1;
        n[0] = d[1] * e[2] - d[2] * e[1];
        n[1] = d[2] * e[0] - d[0] * e[2];
        n[2] = d[0] * e[1] - d[1] * e[0];
        double nl = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
        if (nl < 0.1) continue;
        double t = -0.4 + 1.8 * U(rng);
        double h = scale * len * std::pow(10.0, -5 + 3 * U(rng));
        Point3f corners[3];
        for (int k = 0; k < 3; ++k) {
            corners[0][k] = Float(A[k]);
            corners[1][k] = Float(A[k] + d[k]);
            corners[2][k] = Float(A[k] + t * d[k] + h * n[k] / nl);
        }
        const int *p = perms[i % 6];
        std::vector<Point3f> P = {corners[p[0]], corners[p[1]],
                                  corners[p[2]]};
        LD sine;
        LD exact = CrossAreaLD(P[0], P[1], P[2], &sine);
        if (!(exact > 0)) continue;
        ASSERT_LE(RelativeError(ex::TriangleArea(Transform(), P[0], P[1], P[2]),
                                exact),
                  TriangleBound(sine))
            << "needle " << i << ": " << P[0] << " " << P[1] << " " << P[2];
        ++tested;
        Vector3f c = Cross(P[1] - P[0], P[2] - P[0]);
        if (RelativeError(Float(0.5) * c.Length(), exact) >
            TriangleBound(sine))
            floatEdgesFail = true;
    }
    EXPECT_GT(tested, kTriangleCases * 9 / 10);
    if (sizeof(Float) == sizeof(float)) {
        EXPECT_TRUE(floatEdgesFail) << "the test cannot tell float edges";
    }
}

// Vertices on one line, p0 + m d with small integers m (equal m: coincident
// vertices) and dyadic p0 and d, so that they are exact and every pair of
// edges is exactly parallel: the area must be exactly zero, in any order.
EXERCISE_TEST(Ex4_11_TriangleAreaHidden, CollinearVerticesHaveZeroArea) {
    std::mt19937_64 rng(calls::Seed(0x4eb3));
    std::uniform_int_distribution<int> coord(-4096, 4096), dir(-32, 32),
        mult(-8, 8);
    for (int i = 0; i < kTriangleCases; ++i) {
        Point3f p0(Float(coord(rng)) / 64, Float(coord(rng)) / 64,
                   Float(coord(rng)) / 64);
        Vector3f d(Float(dir(rng)) / 16, Float(dir(rng)) / 16,
                   Float(dir(rng)) / 16);
        int m1 = mult(rng), m2 = mult(rng);
        std::vector<Point3f> P = {p0, p0 + Float(m1) * d, p0 + Float(m2) * d};
        std::rotate(P.begin(), P.begin() + i % 3, P.end());
        ASSERT_EQ(ex::TriangleArea(Transform(), P[0], P[1], P[2]), 0)
            << P[0] << " " << P[1] << " " << P[2];
    }
    // Far from the origin, two vertices coincide.
    const Float big = 1e30f;
    std::vector<Point3f> P = {Point3f(big, -big, big), Point3f(0, 1, 2),
                              Point3f(big, -big, big)};
    EXPECT_EQ(ex::TriangleArea(Transform(), P[0], P[1], P[2]), 0);
}

// ---------------------------------------------------------------------------
// Exercise 4.12: Paraboloid::Area()

namespace {

// The area of the graph z = h(x, y) over a region is the integral of
// sqrt(1 + |grad h|^2) over the region. For the paraboloid z = (x^2 + y^2) / c
// that is sqrt(1 + 4 rho^2 / c^2). The estimate averages it over uniform
// points in the square [-r, r]^2, counting 0 outside the shadow of the
// surface (radii from rhoMin to r, azimuths up to phiMax).
struct Weighted {
    double mean, se;
};

Weighted ParaboloidShadowMean(double r, double zMin, double zMax,
                              double phiMax, uint64_t seed) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> U(-1, 1);
    double c = r * r / zMax, rhoMin = r * std::sqrt(zMin / zMax);
    double sum = 0, sum2 = 0;
    for (int i = 0; i < kPoints; ++i) {
        double x = r * U(rng), y = r * U(rng);
        double rho = std::sqrt(x * x + y * y);
        double phi = std::atan2(y, x);
        if (phi < 0) phi += 2 * kPi;
        double f = 0;
        if (rho <= r && rho >= rhoMin && phi <= phiMax)
            f = std::sqrt(1 + 4 * rho * rho / (c * c));
        sum += f;
        sum2 += f * f;
    }
    double mean = sum / kPoints;
    double var = std::max(0.0, sum2 / kPoints - mean * mean);
    return {mean, std::sqrt(var / kPoints)};
}

}  // namespace

// Paraboloids whose heights make the closed form's powers rational: with
// r = 2 zMax, 1 + 4 zMax z / r^2 = 1 + z / zMax, which is 2 at the rim and
// 1.5625 = 1.25^2 at zMin = 0.5625 zMax. The areas are then
// phiMax (4/3) zMax^2 (2 sqrt 2 - 1) with the tip and
// phiMax (4/3) zMax^2 (2 sqrt 2 - 1.953125) for the band, in long double.
EXERCISE_TEST(Ex4_12_ParaboloidAreaHidden, SpecialHeightsInClosedForm) {
    std::mt19937_64 rng(calls::Seed(0x4ea12));
    std::uniform_real_distribution<double> U(0, 1);
    const LD root2 = std::sqrt(LD(2));
    for (int i = 0; i < kPropertyCases / 10; ++i) {
        // Powers of two keep r = 2 zMax and 0.5625 zMax exact.
        Float zMax = std::ldexp(Float(1), int(-40 + 80 * U(rng)));
        Float r = 2 * zMax;
        Float deg = (i % 3 == 0) ? 360 : Float(1 + 359 * U(rng));
        LD phi = StoredPhiMax(deg);
        LD tip = phi * 4 / 3 * LD(zMax) * zMax * (2 * root2 - 1);
        LD band = phi * 4 / 3 * LD(zMax) * zMax * (2 * root2 - 1.953125L);
        EXPECT_LE(RelativeError(ex::ParaboloidArea(Transform(), false, r, 0,
                                                   zMax, deg),
                                tip),
                  LD(gamma(20)))
            << "zMax=" << zMax << " phiMax=" << deg;
        EXPECT_LE(RelativeError(ex::ParaboloidArea(Transform(), false, r,
                                                   0.5625f * zMax, zMax, deg),
                                band),
                  LD(gamma(20)))
            << "zMax=" << zMax << " phiMax=" << deg;
    }
}

// Properties over random paraboloids: the part of a paraboloid below a
// quarter of its height is the paraboloid of half its radius (both exact in
// binary), so the areas of [0, zMax / 4] with radius r / 2 and of
// [zMax / 4, zMax] with radius r add up to that of [0, zMax] with radius r;
// scaling every length by a power of two scales the area by its square; the
// azimuths add up; and a thinner band has a smaller area.
EXERCISE_TEST(Ex4_12_ParaboloidAreaHidden, AdditivityScalingAndMonotony) {
    std::mt19937_64 rng(calls::Seed(0x4ea13));
    std::uniform_real_distribution<double> U(0, 1);
    const LD tol = 3 * LD(gamma(20));
    for (int i = 0; i < kPropertyCases; ++i) {
        Float r = Float(std::exp(-10 + 20 * U(rng)));
        Float zMax = Float(r * std::exp(-9 + 18 * U(rng)));
        Float deg = Float(1 + 359 * U(rng));
        auto A = [&](Float radius, Float z0, Float z1, Float d) {
            return LD(ex::ParaboloidArea(Transform(), false, radius, z0, z1,
                                         d));
        };
        LD whole = A(r, 0, zMax, deg);
        LD parts = A(r / 2, 0, zMax / 4, deg) + A(r, zMax / 4, zMax, deg);
        ASSERT_LE(RelativeError(parts, whole), tol)
            << "r=" << r << " zMax=" << zMax;
        Float zMin = Float(U(rng) * zMax);
        if (!(zMin < zMax)) continue;
        int k = int(-10 + 20 * U(rng));
        LD scaled = A(std::ldexp(r, k), std::ldexp(zMin, k),
                      std::ldexp(zMax, k), deg);
        ASSERT_LE(RelativeError(scaled, std::ldexp(A(r, zMin, zMax, deg),
                                                   2 * k)),
                  tol)
            << "r=" << r << " zMin=" << zMin << " zMax=" << zMax << " k=" << k;
        LD half = A(r, zMin, zMax, deg / 2);
        ASSERT_LE(RelativeError(2 * half, A(r, zMin, zMax, deg)), tol)
            << "r=" << r << " zMin=" << zMin << " zMax=" << zMax;
        Float zMid = Float(zMin + 0.5 * (double(zMax) - zMin));
        if (zMid > zMin && zMid < zMax) {
            ASSERT_LT(A(r, zMid, zMax, deg), A(r, zMin, zMax, deg))
                << "r=" << r << " zMin=" << zMin << " zMax=" << zMax;
        }
    }
}

// Monte Carlo over the shadow of the surface, which owes nothing to the
// surface-of-revolution integral; and plausible mistakes that the estimate
// must reject: the shadow's area alone (no slope), the cone through the
// rims, and the difference of powers without the factor 1/12.
EXERCISE_TEST(Ex4_12_ParaboloidAreaHidden, MatchesTheShadowsAreaElement) {
    struct Case {
        Float r, z0, z1, degrees;
    };
    static const Case cases[] = {{1, 0, 1, 360},         // with its tip
                                 {1.5f, 0.4f, 2, 360},   // cut above it
                                 {2, 0, 0.3f, 200},      // shallow dish
                                 {0.5f, 1, 3, 300},      // deep band
                                 {1, -1, 0.75f, 90}};    // clamped at 0
    static const std::vector<Weighted> means = [] {
        std::vector<Weighted> v;
        uint64_t seed = 0x4eb0;
        for (const Case &c : cases) {
            double zMin = std::max(0.0, double(std::min(c.z0, c.z1)));
            double zMax = std::max(c.z0, c.z1);
            v.push_back(ParaboloidShadowMean(c.r, zMin, zMax,
                                             double(c.degrees) * kPi / 180,
                                             ++seed));
        }
        return v;
    }();
    for (size_t k = 0; k < means.size(); ++k) {
        const Case &c = cases[k];
        double r = c.r, square = 4 * r * r;
        double estimate = square * means[k].mean, se = square * means[k].se;
        double zMin = std::max(0.0, double(std::min(c.z0, c.z1)));
        double zMax = std::max(c.z0, c.z1);
        double phi = double(c.degrees) * kPi / 180;
        std::string what = "paraboloid r=" + std::to_string(c.r) + " z=[" +
                           std::to_string(c.z0) + ", " +
                           std::to_string(c.z1) + "]";
        Float area = ex::ParaboloidArea(Transform(), false, c.r, c.z0, c.z1,
                                        c.degrees);
        ASSERT_GT(se, 0) << what;
        EXPECT_LE(std::abs(area - estimate), kSigmas * se)
            << what << ": Area() " << area << ", estimate " << estimate
            << " +- " << se;
        double rhoMin = r * std::sqrt(zMin / zMax);
        double k4 = 4 * zMax / (r * r);
        double powers = std::pow(1 + k4 * zMax, 1.5) -
                        std::pow(1 + k4 * zMin, 1.5);
        double slant = std::hypot(r - rhoMin, zMax - zMin);
        for (double wrong : {0.5 * phi * (r * r - rhoMin * rhoMin),
                             0.5 * phi * (r + rhoMin) * slant,
                             phi * r * r * r * r / (zMax * zMax) * powers})
            EXPECT_GT(std::abs(wrong - estimate), kSigmas * se)
                << what << ": " << wrong;
    }
}
