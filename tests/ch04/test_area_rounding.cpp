// Chapter 4: the rounding error of the Area() methods, and their edge
// cases. The references are computed from the values that the shapes store,
// to far more digits than Float has, by methods other than the chapter's
// formulas (area_oracles.h): the area of a sphere's band by quadrature in
// long double; a ring as a whole disk less its hole, with the squares of the
// radii exact; a triangle from the areas of its projections onto the
// coordinate planes (shoelace sums in exact arithmetic) or, for well-shaped
// triangles, from its side lengths (Heron). The bounds are those stated in
// the chapter (gamma_3 for spheres, gamma_4 for disks, about one unit in the
// last place for Float = float triangles, a multiple of epsilon / sin(theta)
// for Float = double).
//
// All of them are public tests of the chapter's exercises: Ex4_9_* for the
// sphere, Ex4_10_* for the disk, Ex4_11_* for the triangle.

#include "lrt/shapes/sphere.h"
#include "lrt/shapes/disk.h"
#include "lrt/shapes/triangle.h"

#include "area_oracles.h"
#include "exercise_calls.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <string>
#include <vector>

using namespace lrt;

namespace {

// Random cases per test.
constexpr int kRoundingCases = 10000;
constexpr int kTriangleCases = 2000;
// Triangles whose smallest angle at the first vertex has a sine below this
// are left to the needle test.
constexpr long double kMinSine = 0.05L;
// Relative error of the long double references (64-bit significands): a
// few roundings of 2^-64, far below every bound that is checked.
constexpr long double kUnitLD = 5.421010862427522170e-20L;  // 2^-64
// Relative tolerance of the long double quadrature of a sphere's band, far
// below gamma_3 even for Float = double.
constexpr long double kBandRelTol = 1e-17L;

using LD = long double;

LD RelativeError(LD computed, LD exact) {
    return std::abs(computed - exact) / std::abs(exact);
}

// The bound for the triangle: the final rounding to Float (one unit in the
// last place is 2 MachineEpsilon; the square root and the halving add at
// most another), plus the error of the edges and of the double-precision
// cross product, relative to the cross product's length.
LD TriangleBound(LD sine) {
    const LD unitDouble = LD(1.1102230246251565404e-16L);  // 2^-53
    return 4 * LD(MachineEpsilon) + 8 * unitDouble / sine;
}

// The sine of the triangle's angle at p0, from its area and the lengths of
// the two sides that meet there.
LD SineAtFirstVertex(const Point3f &p0, const Point3f &p1, const Point3f &p2,
                     LD area) {
    auto length = [](const Point3f &p, const Point3f &q) {
        LD dx = LD(p.x) - LD(q.x), dy = LD(p.y) - LD(q.y),
           dz = LD(p.z) - LD(q.z);
        return std::sqrt(dx * dx + dy * dy + dz * dz);
    };
    return 2 * area / (length(p0, p1) * length(p0, p2));
}

// The exact area of the band that a sphere stores (heights in either order,
// phiMax in radians), by quadrature of its graph profile in long double.
LD StoredBandArea(Float r, Float z0, Float z1, Float phiMax) {
    area_oracles::Integral<LD> a = area_oracles::RevolutionArea<LD>(
        area_oracles::SphereGraphProfile<LD>(r), std::min(z0, z1),
        std::max(z0, z1), phiMax, kBandRelTol);
    EXPECT_TRUE(a.converged) << "r=" << r << " z0=" << z0 << " z1=" << z1;
    return a.value;
}

// The exact area of a full ring (phiMax stored as 2 Pi): the disk of radius
// r less the disk of radius ri, with both squares exact and their difference
// rounded once, in binary128 (or, without it, long double, where the squares
// of floats are still exact).
LD StoredRingArea(Float r, Float ri) {
    using area_oracles::Exact;
    Exact outer = Exact(r) * Exact(r), hole = Exact(ri) * Exact(ri);
    return LD(Pi) * LD(outer - hole);
}

}  // namespace

// The constructor orders and clamps the heights; Area() reports the surface
// that is actually stored, through the Shape interface.
EXERCISE_TEST(Ex4_9_SphereRounding, ClampedAndSwappedHeights) {
    const Float r = 1.5f;
    const LD whole = 4 * LD(3.14159265358979323846L) * r * r;
    EXPECT_LE(RelativeError(ex::SphereArea(Transform(), false, r, 5, -5, 400),
                            whole),
              8 * LD(MachineEpsilon));
    EXPECT_EQ(ex::SphereArea(Transform(), false, r, 0.5f, -0.25f, 123),
              ex::SphereArea(Transform(), false, r, -0.25f, 0.5f, 123));
}

// Area() is measured in object space (as in pbrt): it does not change with
// the transformation. (The Cauchy-Crofton test shows the world-space area
// of a scaled sphere.)
EXERCISE_TEST(Ex4_9_SphereRounding, IsObjectSpace) {
    EXPECT_EQ(ex::SphereArea(Transform(), false, 1, -0.5f, 1, 300),
              ex::SphereArea(Scale(2, 3, 4), false, 1, -0.5f, 1, 300));
}

EXERCISE_TEST(Ex4_10_DiskRounding, IsObjectSpace) {
    EXPECT_EQ(ex::DiskArea(Transform(), false, 0, 1, 0.5f, 300),
              ex::DiskArea(Scale(2, 3, 4), false, 0, 1, 0.5f, 300));
}

// phiMax = 360 degrees is stored as exactly 2 * Pi, the Float value of 2 pi.
EXERCISE_TEST(Ex4_9_SphereRounding, WithinGamma3OfStoredBand) {
    std::mt19937_64 rng(calls::Seed(0x5eed0461));
    std::uniform_real_distribution<double> U(0, 1);
    for (int i = 0; i < kRoundingCases; ++i) {
        Float r = Float(std::exp(-27.6 + 55.2 * U(rng)));  // 1e-12 .. 1e12
        Float z0 = Float((2 * U(rng) - 1) * r);
        Float z1 = Float((2 * U(rng) - 1) * r);
        // One band in ten is a single unit in the last place thin.
        if (i % 10 == 0 && std::abs(z0) > r / 4)
            z1 = std::nextafter(z0, Float(0));
        if (!(z0 != z1 && std::abs(z1) <= r)) continue;
        Float area = ex::SphereArea(Transform(), false, r, z0, z1, 360);
        ASSERT_LE(RelativeError(area, StoredBandArea(r, z0, z1, 2 * Pi)),
                  LD(gamma(3)))
            << "r=" << r << " z0=" << z0 << " z1=" << z1;
    }
}

EXERCISE_TEST(Ex4_10_DiskRounding, WithinGamma4OfStoredRing) {
    std::mt19937_64 rng(calls::Seed(0x5eed0462));
    std::uniform_real_distribution<double> U(0, 1);
    for (int i = 0; i < kRoundingCases; ++i) {
        Float r = Float(std::exp(-27.6 + 55.2 * U(rng)));
        Float ri = (i % 5 == 0) ? 0 : Float(U(rng) * r);
        if (!(ri < r)) continue;
        Float h = Float(U(rng));
        Float area = ex::DiskArea(Transform(), false, h, r, ri, 360);
        ASSERT_LE(RelativeError(area, StoredRingArea(r, ri)), LD(gamma(4)))
            << "r=" << r << " ri=" << ri;
    }
}

// Rings whose width is a few units in the last place of their radius: the
// area keeps its gamma_4 bound, while r^2 - ri^2 evaluated in Float would be
// off by far more.
EXERCISE_TEST(Ex4_10_DiskRounding, ThinRingsAreAccurate) {
    bool naiveFails = false;
    for (Float r : {Float(1), Float(0.7), Float(3.3), Float(1e5)}) {
        Float ri = r;
        for (int k = 1; k <= 64; ++k) {
            ri = std::nextafter(ri, Float(0));
            LD exact = StoredRingArea(r, ri);
            ASSERT_LE(RelativeError(ex::DiskArea(Transform(), false, 0, r,
                                                 ri, 360),
                                    exact),
                      LD(gamma(4)))
                << "r=" << r << " ri=" << ri;
            Float naive = Pi * (r * r - ri * ri);
            if (RelativeError(naive, exact) > 100 * LD(gamma(4)))
                naiveFails = true;
        }
    }
    EXPECT_TRUE(naiveFails) << "the test cannot tell the naive formula";
}

// Well-shaped triangles under random affine transformations: Area() is the
// area of the world-space triangle, which Heron's formula gives from its
// side lengths.
EXERCISE_TEST(Ex4_11_TriangleRounding, MatchesHeronOfWorldSpaceVertices) {
    std::mt19937_64 rng(calls::Seed(0x5eed0463));
    std::uniform_real_distribution<double> U(-1, 1);
    int tested = 0;
    for (int i = 0; i < kTriangleCases; ++i) {
        Matrix4x4 m;
        for (int r = 0; r < 3; ++r)
            for (int c = 0; c < 4; ++c)
                m.m[r][c] = Float((r == c ? 2 : 0) + U(rng)) *
                            Float(c == 3 ? 10 : 1);
        Transform toWorld(m);
        Point3f P[3];
        for (Point3f &p : P)
            p = Point3f(Float(U(rng)), Float(U(rng)), Float(U(rng)));
        // The world-space vertices that the mesh stores.
        Point3f w0 = toWorld(P[0]), w1 = toWorld(P[1]), w2 = toWorld(P[2]);
        LD heron = area_oracles::HeronArea<LD>(w0, w1, w2);
        LD sine = SineAtFirstVertex(w0, w1, w2, heron);
        if (sine < kMinSine) continue;
        ++tested;
        // The two references agree with each other...
        LD projections = area_oracles::ProjectionArea(w0, w1, w2);
        ASSERT_LE(RelativeError(projections, heron), 1e-15L);
        // ...and with Area().
        ASSERT_LE(RelativeError(ex::TriangleArea(toWorld, P[0], P[1], P[2]),
                                heron),
                  TriangleBound(sine) + 1e-15L)
            << "triangle " << i;
    }
    EXPECT_GT(tested, kTriangleCases / 2);
}

// Needles: the angle at the first vertex has a sine between 1e-5 and 1e-2,
// and the angle at the third is close to pi. Area() must stay within the
// bound; a Float = float computation of the edges (as in pbrt-v3) would not.
EXERCISE_TEST(Ex4_11_TriangleRounding, NeedleTriangles) {
    std::mt19937_64 rng(calls::Seed(0x5eed0464));
    std::uniform_real_distribution<double> U(0, 1);
    bool floatEdgesFail = false;
    for (int i = 0; i < kTriangleCases; ++i) {
        double x0 = 10 * U(rng) - 5, y0 = 10 * U(rng) - 5, z0 = 10 * U(rng);
        double len = 0.5 + U(rng), h = len * std::pow(10.0, -5 + 3 * U(rng));
        double a = 2 * 3.14159265358979 * U(rng);
        Point3f P[3] = {
            Point3f(Float(x0), Float(y0), Float(z0)),
            Point3f(Float(x0 + len * std::cos(a)),
                    Float(y0 + len * std::sin(a)), Float(z0 + 0.1 * len)),
            Point3f(Float(x0 + 0.7 * len * std::cos(a) - h * std::sin(a)),
                    Float(y0 + 0.7 * len * std::sin(a) + h * std::cos(a)),
                    Float(z0 + 0.07 * len))};
        LD exact = area_oracles::ProjectionArea(P[0], P[1], P[2]);
        if (!(exact > 0)) continue;
        LD sine = SineAtFirstVertex(P[0], P[1], P[2], exact);
        ASSERT_LE(RelativeError(ex::TriangleArea(Transform(), P[0], P[1], P[2]),
                                exact),
                  TriangleBound(sine))
            << "needle " << i << " sine " << double(sine);
        Vector3f c = Cross(P[1] - P[0], P[2] - P[0]);
        Float floatEdges = Float(0.5) * c.Length();
        if (RelativeError(floatEdges, exact) > TriangleBound(sine))
            floatEdgesFail = true;
    }
    if (sizeof(Float) == sizeof(float)) {
        EXPECT_TRUE(floatEdgesFail) << "the test cannot tell float edges";
    }
}

EXERCISE_TEST(Ex4_11_TriangleRounding, DegenerateTrianglesHaveZeroArea) {
    std::vector<std::vector<Point3f>> cases = {
        {Point3f(1, 2, 3), Point3f(1, 2, 3), Point3f(-4, 5, 0.5f)},
        {Point3f(1, 2, 3), Point3f(1, 2, 3), Point3f(1, 2, 3)},
        {Point3f(0, 0, 0), Point3f(1, 2, 3), Point3f(2, 4, 6)},
        {Point3f(0.1f, 0.2f, 0.3f), Point3f(0.1f, 0.2f, 0.3f),
         Point3f(0.1f, 0.2f, 0.3f)}};
    for (const auto &c : cases)
        EXPECT_EQ(ex::TriangleArea(Transform(), c[0], c[1], c[2]), 0);
}

// The area does not depend on which vertex the edges start from, up to the
// rounding bound: the six orders of the vertices are six triangles of one
// mesh.
EXERCISE_TEST(Ex4_11_TriangleRounding, IndependentOfVertexOrder) {
    std::mt19937_64 rng(calls::Seed(0x5eed0465));
    std::uniform_real_distribution<double> U(-3, 3);
    const std::vector<int> orders = {0, 1, 2, 1, 2, 0, 2, 0, 1,
                                     0, 2, 1, 2, 1, 0, 1, 0, 2};
    for (int i = 0; i < kTriangleCases; ++i) {
        std::vector<Point3f> P(3);
        for (Point3f &p : P)
            p = Point3f(Float(U(rng)), Float(U(rng)), Float(U(rng)));
        LD exact = area_oracles::ProjectionArea(P[0], P[1], P[2]);
        if (SineAtFirstVertex(P[0], P[1], P[2], exact) < kMinSine) continue;
        std::vector<Float> areas = ex::TriangleAreas(Transform(), orders, P);
        for (size_t k = 0; k < areas.size(); ++k) {
            const Point3f &q0 = P[orders[3 * k]], &q1 = P[orders[3 * k + 1]],
                          &q2 = P[orders[3 * k + 2]];
            ASSERT_LE(RelativeError(areas[k], exact),
                      TriangleBound(SineAtFirstVertex(q0, q1, q2, exact)) +
                          64 * kUnitLD)
                << "order " << k;
        }
    }
}
