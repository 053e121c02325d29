// Chapter 4: the rounding error of the Area() methods, and their edge
// cases. The references are computed in long double from the values that
// the shapes store, so that they are exact to far more digits than Float
// has; the bounds are those stated in the chapter (gamma_3 for spheres,
// gamma_4 for disks, about one unit in the last place for Float = float
// triangles, a multiple of epsilon / sin(theta) for Float = double).
//
// All of them are public tests of the chapter's exercises: Ex4_9_* for the
// sphere, Ex4_10_* for the disk, Ex4_11_* for the triangle.

#include "lrt/lrt.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
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

struct Edges {
    LD ax, ay, az, bx, by, bz;
};

Edges EdgesOf(const Point3f &p0, const Point3f &p1, const Point3f &p2) {
    return {LD(p1.x) - LD(p0.x), LD(p1.y) - LD(p0.y), LD(p1.z) - LD(p0.z),
            LD(p2.x) - LD(p0.x), LD(p2.y) - LD(p0.y), LD(p2.z) - LD(p0.z)};
}

// The area of the stored triangle by the cross product in long double, and
// the sine of its angle at p0.
LD CrossArea(const Edges &e, LD *sine = nullptr) {
    LD cx = e.ay * e.bz - e.az * e.by, cy = e.az * e.bx - e.ax * e.bz,
       cz = e.ax * e.by - e.ay * e.bx;
    LD c = std::sqrt(cx * cx + cy * cy + cz * cz);
    if (sine) {
        LD la = std::sqrt(e.ax * e.ax + e.ay * e.ay + e.az * e.az);
        LD lb = std::sqrt(e.bx * e.bx + e.by * e.by + e.bz * e.bz);
        *sine = c / (la * lb);
    }
    return c / 2;
}

// Kahan's stable form of Heron's formula, from the three side lengths:
// it uses no cross product at all.
LD KahanHeron(const Point3f &p0, const Point3f &p1, const Point3f &p2) {
    auto dist = [](const Point3f &p, const Point3f &q) {
        LD dx = LD(p.x) - LD(q.x), dy = LD(p.y) - LD(q.y),
           dz = LD(p.z) - LD(q.z);
        return std::sqrt(dx * dx + dy * dy + dz * dz);
    };
    LD s[3] = {dist(p0, p1), dist(p1, p2), dist(p2, p0)};
    std::sort(s, s + 3);
    LD c = s[0], b = s[1], a = s[2];  // a >= b >= c
    return std::sqrt((a + (b + c)) * (c - (a - b)) * (c + (a - b)) *
                     (a + (b - c))) / 4;
}

// A single triangle of a mesh built with the given transformation; the
// returned mesh holds the world-space vertices that the triangle uses.
struct OneTriangle {
    std::shared_ptr<TriangleMesh> mesh;
    std::unique_ptr<Triangle> triangle;
};

OneTriangle MakeTriangle(const Transform *toWorld, const Transform *toObject,
                         const Point3f P[3]) {
    static const int indices[3] = {0, 1, 2};
    OneTriangle t;
    t.mesh = std::make_shared<TriangleMesh>(*toWorld, false, 1, indices, 3,
                                            P, nullptr, nullptr, nullptr);
    t.triangle.reset(new Triangle(toWorld, toObject, false, t.mesh, 0));
    return t;
}

}  // namespace

// The constructor orders and clamps the heights; Area() reports the surface
// that is actually stored, through the Shape interface.
TEST(Ex4_9_SphereRounding, ClampedAndSwappedHeights) {
    Transform identity;
    const Float r = 1.5f;
    Sphere whole(&identity, &identity, false, r, 5, -5, 400);
    const Shape &shape = whole;
    const LD exact = 4 * LD(3.14159265358979323846L) * r * r;
    EXPECT_LE(RelativeError(shape.Area(), exact), 8 * LD(MachineEpsilon));
    Sphere a(&identity, &identity, false, r, 0.5f, -0.25f, 123);
    Sphere b(&identity, &identity, false, r, -0.25f, 0.5f, 123);
    EXPECT_EQ(a.Area(), b.Area());
}

// Area() is measured in object space (as in pbrt): it does not change with
// the transformation. (The Cauchy-Crofton test shows the world-space area
// of a scaled sphere.)
TEST(Ex4_9_SphereRounding, IsObjectSpace) {
    Transform identity, scale = Scale(2, 3, 4), inv = Inverse(scale);
    Sphere s0(&identity, &identity, false, 1, -0.5f, 1, 300);
    Sphere s1(&scale, &inv, false, 1, -0.5f, 1, 300);
    EXPECT_EQ(s0.Area(), s1.Area());
}

TEST(Ex4_10_DiskRounding, IsObjectSpace) {
    Transform identity, scale = Scale(2, 3, 4), inv = Inverse(scale);
    Disk d0(&identity, &identity, false, 0, 1, 0.5f, 300);
    Disk d1(&scale, &inv, false, 0, 1, 0.5f, 300);
    EXPECT_EQ(d0.Area(), d1.Area());
}

// phiMax = 360 degrees is stored as exactly 2 * Pi, so the exact area of the
// stored sphere is 2 Pi r (zMax - zMin) with the Float value of Pi.
TEST(Ex4_9_SphereRounding, WithinGamma3OfStoredBand) {
    Transform identity;
    std::mt19937_64 rng(0x5eed0461);
    std::uniform_real_distribution<double> U(0, 1);
    for (int i = 0; i < kRoundingCases; ++i) {
        Float r = Float(std::exp(-27.6 + 55.2 * U(rng)));  // 1e-12 .. 1e12
        Float z0 = Float((2 * U(rng) - 1) * r);
        Float z1 = Float((2 * U(rng) - 1) * r);
        // One band in ten is a single unit in the last place thin.
        if (i % 10 == 0 && std::abs(z0) > r / 4)
            z1 = std::nextafter(z0, Float(0));
        if (!(z0 != z1 && std::abs(z1) <= r)) continue;
        Sphere s(&identity, &identity, false, r, z0, z1, 360);
        LD exact = LD(2 * Pi) * LD(r) * std::abs(LD(z1) - LD(z0));
        ASSERT_LE(RelativeError(s.Area(), exact), LD(gamma(3)))
            << "r=" << r << " z0=" << z0 << " z1=" << z1;
    }
}

TEST(Ex4_10_DiskRounding, WithinGamma4OfStoredRing) {
    Transform identity;
    std::mt19937_64 rng(0x5eed0462);
    std::uniform_real_distribution<double> U(0, 1);
    for (int i = 0; i < kRoundingCases; ++i) {
        Float r = Float(std::exp(-27.6 + 55.2 * U(rng)));
        Float ri = (i % 5 == 0) ? 0 : Float(U(rng) * r);
        if (!(ri < r)) continue;
        Disk d(&identity, &identity, false, Float(U(rng)), r, ri, 360);
        LD exact = LD(Pi) * (LD(r) - LD(ri)) * (LD(r) + LD(ri));
        ASSERT_LE(RelativeError(d.Area(), exact), LD(gamma(4)))
            << "r=" << r << " ri=" << ri;
    }
}

// Rings whose width is a few units in the last place of their radius: the
// factored formula keeps its gamma_4 bound, while r^2 - ri^2 evaluated in
// Float would be off by far more.
TEST(Ex4_10_DiskRounding, ThinRingsAreAccurate) {
    Transform identity;
    bool naiveFails = false;
    for (Float r : {Float(1), Float(0.7), Float(3.3), Float(1e5)}) {
        Float ri = r;
        for (int k = 1; k <= 64; ++k) {
            ri = std::nextafter(ri, Float(0));
            Disk d(&identity, &identity, false, 0, r, ri, 360);
            LD exact = LD(Pi) * (LD(r) - LD(ri)) * (LD(r) + LD(ri));
            ASSERT_LE(RelativeError(d.Area(), exact), LD(gamma(4)))
                << "r=" << r << " ri=" << ri;
            Float naive = Pi * (r * r - ri * ri);
            if (RelativeError(naive, exact) > 100 * LD(gamma(4)))
                naiveFails = true;
        }
    }
    EXPECT_TRUE(naiveFails) << "the test cannot tell the naive formula";
}

// Well-shaped triangles under random affine transformations: Area() is the
// area of the stored world-space triangle, by Kahan's Heron formula.
TEST(Ex4_11_TriangleRounding, MatchesHeronOfWorldSpaceVertices) {
    std::mt19937_64 rng(0x5eed0463);
    std::uniform_real_distribution<double> U(-1, 1);
    int tested = 0;
    for (int i = 0; i < kTriangleCases; ++i) {
        Matrix4x4 m;
        for (int r = 0; r < 3; ++r)
            for (int c = 0; c < 4; ++c)
                m.m[r][c] = Float((r == c ? 2 : 0) + U(rng)) *
                            Float(c == 3 ? 10 : 1);
        Transform toWorld(m), toObject = Inverse(toWorld);
        Point3f P[3];
        for (Point3f &p : P)
            p = Point3f(Float(U(rng)), Float(U(rng)), Float(U(rng)));
        OneTriangle t = MakeTriangle(&toWorld, &toObject, P);
        const Point3f &w0 = t.mesh->p[0], &w1 = t.mesh->p[1],
                      &w2 = t.mesh->p[2];
        LD sine;
        LD exact = CrossArea(EdgesOf(w0, w1, w2), &sine);
        if (sine < kMinSine) continue;
        ++tested;
        LD heron = KahanHeron(w0, w1, w2);
        // The two references agree with each other...
        ASSERT_LE(RelativeError(heron, exact), 1e-15L);
        // ...and with Area().
        ASSERT_LE(RelativeError(t.triangle->Area(), heron),
                  TriangleBound(sine) + 1e-15L)
            << "triangle " << i;
    }
    EXPECT_GT(tested, kTriangleCases / 2);
}

// Needles: the angle at the first vertex has a sine between 1e-5 and 1e-2.
// Area() must stay within the bound; a Float = float computation of the
// edges (as in pbrt-v3) would not.
TEST(Ex4_11_TriangleRounding, NeedleTriangles) {
    std::mt19937_64 rng(0x5eed0464);
    std::uniform_real_distribution<double> U(0, 1);
    Transform identity;
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
        OneTriangle t = MakeTriangle(&identity, &identity, P);
        LD sine;
        LD exact = CrossArea(EdgesOf(P[0], P[1], P[2]), &sine);
        if (!(exact > 0)) continue;
        ASSERT_LE(RelativeError(t.triangle->Area(), exact),
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

TEST(Ex4_11_TriangleRounding, DegenerateTrianglesHaveZeroArea) {
    Transform identity;
    std::vector<std::vector<Point3f>> cases = {
        {Point3f(1, 2, 3), Point3f(1, 2, 3), Point3f(-4, 5, 0.5f)},
        {Point3f(1, 2, 3), Point3f(1, 2, 3), Point3f(1, 2, 3)},
        {Point3f(0, 0, 0), Point3f(1, 2, 3), Point3f(2, 4, 6)},
        {Point3f(0.1f, 0.2f, 0.3f), Point3f(0.1f, 0.2f, 0.3f),
         Point3f(0.1f, 0.2f, 0.3f)}};
    for (const auto &c : cases) {
        Point3f P[3] = {c[0], c[1], c[2]};
        OneTriangle t = MakeTriangle(&identity, &identity, P);
        EXPECT_EQ(t.triangle->Area(), 0);
    }
}

// The area does not depend on which vertex the edges start from, up to the
// rounding bound.
TEST(Ex4_11_TriangleRounding, IndependentOfVertexOrder) {
    Transform identity;
    std::mt19937_64 rng(0x5eed0465);
    std::uniform_real_distribution<double> U(-3, 3);
    for (int i = 0; i < kTriangleCases; ++i) {
        Point3f P[3];
        for (Point3f &p : P)
            p = Point3f(Float(U(rng)), Float(U(rng)), Float(U(rng)));
        LD sine;
        LD exact = CrossArea(EdgesOf(P[0], P[1], P[2]), &sine);
        if (sine < kMinSine) continue;
        int perms[6][3] = {{0, 1, 2}, {1, 2, 0}, {2, 0, 1},
                           {0, 2, 1}, {2, 1, 0}, {1, 0, 2}};
        for (const auto &p : perms) {
            Point3f Q[3] = {P[p[0]], P[p[1]], P[p[2]]};
            OneTriangle t = MakeTriangle(&identity, &identity, Q);
            LD s;
            CrossArea(EdgesOf(Q[0], Q[1], Q[2]), &s);
            ASSERT_LE(RelativeError(t.triangle->Area(), exact),
                      TriangleBound(s) + 64 * kUnitLD);
        }
    }
}
