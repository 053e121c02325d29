// Chapter 4: Monte Carlo estimates of the shapes' areas from random lines
// (the Cauchy-Crofton formula), using nothing but the shapes' Intersect().
//
// For lines L chosen uniformly among those that meet a ball of radius R that
// contains the surface S (direction uniform on the sphere, then a point
// uniform on the disk of radius R perpendicular to it),
//
//     A(S) = 2 pi R^2 E[n_S(L)],
//
// where n_S(L) is the number of points where L crosses S. The test counts
// crossings by tracing a ray along the line and, after each hit, spawning a
// continuation ray from the hit point in the same direction.
//
// The tests that compare the estimates with Area() are public tests of the
// chapter's exercises (Ex4_9_* sphere, Ex4_10_* disk, Ex4_11_* triangle,
// Ex4_12_* paraboloid); those of the cylinder, the cone and the hyperboloid
// call the book's Area().
// The check of the estimator's constant and the test of wrong formulas
// compare the estimates with areas known in closed form (or computed here in
// double precision), call no Area() and belong to no exercise.
//
// The shapes that the lines cross are built here, with the book's code, and
// their estimates are computed once, in function-level statics: they do not
// depend on the code under test, and the grader runs a test's body several
// times (tests/calls/judge.cpp). The exercise calls build the same shapes
// for Area(). The seeds stay fixed: an estimate misses by more than four
// standard errors once in some 16000 tries, and a right answer must pass
// every time.

#include "lrt/shapes/sphere.h"
#include "lrt/shapes/disk.h"
#include "lrt/shapes/triangle.h"
#include "lrt/shapes/cylinder.h"
#include "lrt/shapes/cone.h"
#include "lrt/shapes/paraboloid.h"
#include "lrt/shapes/hyperboloid.h"

#include "area_oracles.h"
#include "exercise_calls.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <memory>
#include <random>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

using namespace lrt;

namespace {

// Random lines per shape, and the agreement required between the estimate
// and Area(), in standard errors of the estimate.
constexpr int kLinesPerShape = 1 << 17;
constexpr double kStandardErrors = 4;
// Random partial spheres, disks and triangles.
constexpr int kCroftonSpheres = 6;
constexpr int kCroftonDisks = 4;
constexpr int kCroftonTriangles = 4;
// No line crosses these shapes more than twice; a count above this limit
// means that a continuation ray found the same surface point again.
constexpr int kMaxCrossings = 4;
// Radius of the bounding ball of a sphere, relative to the sphere's radius.
// (With a margin, even the lines through a whole sphere vary in their
// number of crossings, so the standard error is positive.)
constexpr double kBallMargin = 1.1;

constexpr double kPi = 3.14159265358979323846;

struct Vec {
    double x, y, z;
};

struct CroftonEstimate {
    double area, standardError;
    int maxCount;
};

// Counts the points where the line through o with direction d crosses the
// shape; o is outside the ball that bounds the shape, so every crossing is
// at t > 0.
int CountCrossings(const Shape &shape, Ray ray) {
    int n = 0;
    Float tHit;
    SurfaceInteraction isect;
    while (n <= kMaxCrossings && shape.Intersect(ray, &tHit, &isect)) {
        ++n;
        ray = isect.SpawnRay(ray.d);
    }
    return n;
}

CroftonEstimate EstimateArea(const Shape &shape, const Vec &center, double R,
                             uint64_t seed) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> U(0, 1);
    double sum = 0, sum2 = 0;
    int maxCount = 0;
    for (int i = 0; i < kLinesPerShape; ++i) {
        // Direction uniform on the sphere: z uniform in [-1, 1] (the
        // hat-box theorem), azimuth uniform.
        double wz = 1 - 2 * U(rng), phi = 2 * kPi * U(rng);
        double s = std::sqrt(std::max(0.0, 1 - wz * wz));
        Vec w{s * std::cos(phi), s * std::sin(phi), wz};
        // An orthonormal basis (e1, e2) of the plane perpendicular to w.
        Vec e1 = std::abs(w.x) > std::abs(w.y)
                     ? Vec{-w.z, 0, w.x} : Vec{0, w.z, -w.y};
        double l1 = std::sqrt(e1.x * e1.x + e1.y * e1.y + e1.z * e1.z);
        e1 = {e1.x / l1, e1.y / l1, e1.z / l1};
        Vec e2{w.y * e1.z - w.z * e1.y, w.z * e1.x - w.x * e1.z,
               w.x * e1.y - w.y * e1.x};
        // A point uniform on the disk of radius R in that plane.
        double rho = R * std::sqrt(U(rng)), alpha = 2 * kPi * U(rng);
        double a = rho * std::cos(alpha), b = rho * std::sin(alpha);
        Vec o{center.x + a * e1.x + b * e2.x - 2 * R * w.x,
              center.y + a * e1.y + b * e2.y - 2 * R * w.y,
              center.z + a * e1.z + b * e2.z - 2 * R * w.z};
        Ray ray(Point3f(Float(o.x), Float(o.y), Float(o.z)),
                Vector3f(Float(w.x), Float(w.y), Float(w.z)));
        int n = CountCrossings(shape, ray);
        maxCount = std::max(maxCount, n);
        sum += n;
        sum2 += double(n) * n;
    }
    double N = kLinesPerShape;
    double mean = sum / N;
    double variance = std::max(0.0, (sum2 - N * mean * mean) / (N - 1));
    double scale = 2 * kPi * R * R;
    return {scale * mean, scale * std::sqrt(variance / N), maxCount};
}

// How far the value is from the estimate, in standard errors.
double Deviation(double value, const CroftonEstimate &e) {
    return std::abs(value - e.area) / e.standardError;
}

// A random rigid motion.
Transform RandomRigid(std::mt19937_64 &rng) {
    std::uniform_real_distribution<double> U(-1, 1);
    Vector3f axis(Float(U(rng)), Float(U(rng)), Float(U(rng)) + Float(1.5));
    return Translate(Vector3f(Float(5 * U(rng)), Float(5 * U(rng)),
                              Float(5 * U(rng)))) *
           Rotate(Float(180 * U(rng)), axis);
}

Vec Apply(const Transform &t, const Point3f &p) {
    Point3f q = t(p);
    return {q.x, q.y, q.z};
}

void ExpectAgreement(double area, const CroftonEstimate &e,
                     const std::string &what) {
    EXPECT_LE(e.maxCount, 2) << what;
    EXPECT_GT(e.standardError, 0) << what;
    EXPECT_LE(Deviation(area, e), kStandardErrors)
        << what << ": Area() " << area << ", estimate " << e.area << " +- "
        << e.standardError;
}

// Random partial spheres (the first a whole sphere, the second a
// hemisphere), disks and triangles, each with the estimate of its area.
struct CroftonSphere {
    Transform toWorld;
    bool reverseOrientation;
    Float r, z0, z1, phiMax;
    CroftonEstimate e;
};
struct CroftonDisk {
    Transform toWorld;
    Float height, r, ri, phiMax;
    CroftonEstimate e;
};
struct CroftonTriangle {
    Transform toWorld;
    Point3f P[3];
    CroftonEstimate e;
};

const std::vector<CroftonSphere> &CroftonSpheres() {
    static const std::vector<CroftonSphere> spheres = [] {
        std::vector<CroftonSphere> v;
        std::mt19937_64 rng(0x5eed0422);
        std::uniform_real_distribution<double> U(0, 1);
        for (int i = 0; i < kCroftonSpheres; ++i) {
            Transform toWorld = RandomRigid(rng), toObject = Inverse(toWorld);
            Float r = Float(0.3 + 3 * U(rng));
            Float z0, z1;
            do {
                z0 = Float((2 * U(rng) - 1) * r);
                z1 = Float((2 * U(rng) - 1) * r);
            } while (std::abs(z1 - z0) < 0.1f * r);
            if (i == 0) z0 = -r, z1 = r;  // a whole sphere
            if (i == 1) z0 = 0, z1 = r;   // a hemisphere
            Float phi = (i < 2) ? 360 : Float(30 + 330 * U(rng));
            Sphere sphere(&toWorld, &toObject, i % 2 == 1, r, z0, z1, phi);
            CroftonEstimate e = EstimateArea(
                sphere, Apply(toWorld, Point3f(0, 0, 0)), kBallMargin * r,
                0x5eed0430 + i);
            v.push_back({toWorld, i % 2 == 1, r, z0, z1, phi, e});
        }
        return v;
    }();
    return spheres;
}

// A partial sphere under a rigid motion and a uniform scale by kScale.
constexpr Float kScale = 2.5f;
const CroftonSphere &ScaledSphere() {
    static const CroftonSphere sphere = [] {
        std::mt19937_64 rng(0x5eed0423);
        Transform toWorld = RandomRigid(rng) * Scale(kScale, kScale, kScale);
        Transform toObject = Inverse(toWorld);
        const Float r = 0.8f, z0 = -0.3f, z1 = 0.7f, phi = 250;
        Sphere sphere(&toWorld, &toObject, false, r, z0, z1, phi);
        CroftonEstimate e = EstimateArea(
            sphere, Apply(toWorld, Point3f(0, 0, 0)), kScale * r, 0x5eed0424);
        return CroftonSphere{toWorld, false, r, z0, z1, phi, e};
    }();
    return sphere;
}

const std::vector<CroftonDisk> &CroftonDisks() {
    static const std::vector<CroftonDisk> disks = [] {
        std::vector<CroftonDisk> v;
        std::mt19937_64 rng(0x5eed0425);
        std::uniform_real_distribution<double> U(0, 1);
        for (int i = 0; i < kCroftonDisks; ++i) {
            Transform toWorld = RandomRigid(rng), toObject = Inverse(toWorld);
            Float r = Float(0.3 + 3 * U(rng));
            Float ri = (i == 0) ? 0 : Float(0.8 * U(rng) * r);
            Float h = Float(2 * U(rng) - 1);
            Float phi = (i < 2) ? 360 : Float(30 + 330 * U(rng));
            Disk disk(&toWorld, &toObject, false, h, r, ri, phi);
            CroftonEstimate e = EstimateArea(
                disk, Apply(toWorld, Point3f(0, 0, h)), r, 0x5eed0440 + i);
            v.push_back({toWorld, h, r, ri, phi, e});
        }
        return v;
    }();
    return disks;
}

// Triangles of a mesh with a general affine transformation.
const std::vector<CroftonTriangle> &CroftonTriangles() {
    static const std::vector<CroftonTriangle> triangles = [] {
        std::vector<CroftonTriangle> v;
        std::mt19937_64 rng(0x5eed0426);
        std::uniform_real_distribution<double> U(-1, 1);
        for (int i = 0; i < kCroftonTriangles; ++i) {
            CroftonTriangle t;
            for (Point3f &p : t.P)
                p = Point3f(Float(U(rng)), Float(U(rng)), Float(U(rng)));
            Matrix4x4 m;
            for (int r = 0; r < 3; ++r)
                for (int c = 0; c < 4; ++c)
                    m.m[r][c] = Float((r == c ? 1.5 : 0) + 0.6 * U(rng));
            t.toWorld = Transform(m);
            Transform toObject = Inverse(t.toWorld);
            int indices[3] = {0, 1, 2};
            std::vector<std::shared_ptr<Shape>> tri = CreateTriangleMesh(
                &t.toWorld, &toObject, false, 1, indices, 3, t.P, nullptr,
                nullptr, nullptr);
            Vec w[3];
            for (int k = 0; k < 3; ++k) w[k] = Apply(t.toWorld, t.P[k]);
            Vec c{(w[0].x + w[1].x + w[2].x) / 3,
                  (w[0].y + w[1].y + w[2].y) / 3,
                  (w[0].z + w[1].z + w[2].z) / 3};
            double R = 0;
            for (const Vec &p : w)
                R = std::max(R, std::sqrt((p.x - c.x) * (p.x - c.x) +
                                          (p.y - c.y) * (p.y - c.y) +
                                          (p.z - c.z) * (p.z - c.z)));
            t.e = EstimateArea(*tri[0], c, 1.001 * R, 0x5eed0450 + i);
            v.push_back(t);
        }
        return v;
    }();
    return triangles;
}

}  // namespace

// The constant of the estimator, checked on the whole sphere of radius r in
// a ball of radius 1.5 r: every line through the sphere crosses it twice.
// (Ex4_9_SphereCrofton.PartialSpheres compares a whole sphere's Area().)
TEST(CauchyCrofton, WholeSphereChecksTheConstant) {
    Transform identity;
    const Float r = 2;
    Sphere sphere(&identity, &identity, false, r, -r, r, 360);
    CroftonEstimate e = EstimateArea(sphere, {0, 0, 0}, 1.5 * r, 0x5eed0421);
    ExpectAgreement(4 * kPi * r * r, e, "whole sphere");
}

EXERCISE_TEST(Ex4_9_SphereCrofton, PartialSpheres) {
    for (const CroftonSphere &s : CroftonSpheres())
        ExpectAgreement(ex::SphereArea(s.toWorld, s.reverseOrientation, s.r,
                                       s.z0, s.z1, s.phiMax),
                        s.e,
                        "sphere r=" + std::to_string(s.r) + " z=[" +
                            std::to_string(std::min(s.z0, s.z1)) + ", " +
                            std::to_string(std::max(s.z0, s.z1)) +
                            "] phiMax=" + std::to_string(s.phiMax));
}

// Sphere::Area() is an object-space area: under a uniform scale by s the
// world-space area, which the lines measure, is s^2 times larger.
EXERCISE_TEST(Ex4_9_SphereCrofton, UniformlyScaledSphere) {
    const CroftonSphere &s = ScaledSphere();
    Float area =
        ex::SphereArea(s.toWorld, false, s.r, s.z0, s.z1, s.phiMax);
    ExpectAgreement(kScale * kScale * area, s.e, "scaled sphere");
    EXPECT_GT(Deviation(area, s.e), kStandardErrors);
}

EXERCISE_TEST(Ex4_10_DiskCrofton, Disks) {
    for (const CroftonDisk &d : CroftonDisks())
        ExpectAgreement(ex::DiskArea(d.toWorld, false, d.height, d.r, d.ri,
                                     d.phiMax),
                        d.e,
                        "disk r=" + std::to_string(d.r) +
                            " ri=" + std::to_string(d.ri) +
                            " phiMax=" + std::to_string(d.phiMax));
}

// The lines see the world-space triangle, and so must Area().
EXERCISE_TEST(Ex4_11_TriangleCrofton, Triangles) {
    int i = 0;
    for (const CroftonTriangle &t : CroftonTriangles())
        ExpectAgreement(ex::TriangleArea(t.toWorld, t.P[0], t.P[1], t.P[2]),
                        t.e, "triangle " + std::to_string(i++));
}

// The same estimator must accept the right areas and reject plausible wrong
// formulas. The right areas are computed here, not by Area(), so that this
// test checks the method alone.
TEST(CauchyCrofton, RejectsWrongFormulas) {
    Transform identity;
    // A hemisphere of radius 2.5: the right area is 2 pi r^2.
    const Float r = 2.5f;
    Sphere hemi(&identity, &identity, false, r, 0, r, 360);
    CroftonEstimate e = EstimateArea(hemi, {0, 0, 0}, r, 0x5eed0427);
    EXPECT_LE(Deviation(2 * kPi * r * r, e), kStandardErrors);
    for (double wrong : {2 * kPi * r, 4 * kPi * r * r, kPi * r * r,
                         2 * kPi * kPi * r * r / 4 /* phi int f dz */})
        EXPECT_GT(Deviation(wrong, e), kStandardErrors) << wrong;

    // Five sixths of the upper hemisphere of radius 1.25 (phiMax 300
    // degrees): by symmetry, five sixths of 2 pi r^2. An area proportional
    // to the range of polar angles, phiMax r^2 (pi / 2 - 0), is pi / 2 times
    // larger.
    const double rs = 1.25, phi = 300 * kPi / 180;
    Sphere sector(&identity, &identity, false, Float(rs), 0, Float(rs), 300);
    CroftonEstimate es = EstimateArea(sector, {0, 0, 0}, rs, 0x5eed0428);
    EXPECT_LE(Deviation(5.0 / 6 * 2 * kPi * rs * rs, es), kStandardErrors);
    EXPECT_GT(Deviation(phi * rs * rs * kPi / 2, es), kStandardErrors);

    // A ring of radii 2 and 1.2.
    Disk ring(&identity, &identity, false, 0, 2, 1.2f, 360);
    CroftonEstimate er = EstimateArea(ring, {0, 0, 0}, 2, 0x5eed0429);
    const double ri = 1.2f;  // the Float value the ring stores
    EXPECT_LE(Deviation(kPi * (4 - ri * ri), er), kStandardErrors);
    for (double wrong : {kPi * 2.0, kPi * (2 - 1.2) * (2 - 1.2),
                         2 * kPi * (4 - 1.44), kPi * 4})
        EXPECT_GT(Deviation(wrong, er), kStandardErrors) << wrong;

    // A triangle: its area, not that of the parallelogram on two of its
    // sides.
    Point3f P[3] = {Point3f(0, 0, 0), Point3f(1.5f, 0.2f, 0),
                    Point3f(0.3f, 1.1f, 0.4f)};
    int indices[3] = {0, 1, 2};
    std::vector<std::shared_ptr<Shape>> tri = CreateTriangleMesh(
        &identity, &identity, false, 1, indices, 3, P, nullptr, nullptr,
        nullptr);
    CroftonEstimate et = EstimateArea(*tri[0], {0.6, 0.43, 0.13}, 1.1,
                                      0x5eed042a);
    // Heron's formula, from the side lengths.
    double area = area_oracles::HeronArea<double>(P[0], P[1], P[2]);
    EXPECT_LE(Deviation(area, et), kStandardErrors);
    EXPECT_GT(Deviation(2 * area, et), kStandardErrors);
}

// ---------------------------------------------------------------------------
// The other quadrics, each under a random rigid motion: the lines see them
// only through Intersect(). No line crosses a quadric more than twice. The
// hyperboloids include a cylinder and a cone (a vertical segment, a segment
// ending on the axis) and a segment that crosses the axis.

namespace {

struct CroftonQuadric {
    std::string name;
    std::unique_ptr<Transform> toWorld, toObject;
    std::shared_ptr<Shape> shape;
    // The paraboloid's constructor arguments, for its exercise call.
    Float radius, z0, z1, phiMax;
    CroftonEstimate e;
};

// The center and radius of a ball around the shape's world bound.
void BoundingBall(const Shape &shape, Vec *center, double *radius) {
    Bounds3f b = shape.WorldBound();
    *center = {0.5 * (double(b.pMin.x) + b.pMax.x),
               0.5 * (double(b.pMin.y) + b.pMax.y),
               0.5 * (double(b.pMin.z) + b.pMax.z)};
    double dx = double(b.pMax.x) - b.pMin.x, dy = double(b.pMax.y) - b.pMin.y,
           dz = double(b.pMax.z) - b.pMin.z;
    *radius = 0.5 * std::sqrt(dx * dx + dy * dy + dz * dz);
}

const std::vector<CroftonQuadric> &CroftonQuadrics() {
    static const std::vector<CroftonQuadric> quadrics = [] {
        std::vector<CroftonQuadric> v;
        std::mt19937_64 rng(0x5eed042b);
        auto add = [&](std::string name, auto make) {
            CroftonQuadric q;
            q.name = name;
            q.toWorld.reset(new Transform(RandomRigid(rng)));
            q.toObject.reset(new Transform(Inverse(*q.toWorld)));
            q.radius = q.z0 = q.z1 = q.phiMax = 0;
            q.shape = make(q);
            v.push_back(std::move(q));
        };
        add("cylinder", [](CroftonQuadric &q) {
            return std::make_shared<Cylinder>(q.toWorld.get(),
                                              q.toObject.get(), false, 1.2f,
                                              -0.4f, 1.6f, 360);
        });
        add("partial cylinder", [](CroftonQuadric &q) {
            return std::make_shared<Cylinder>(q.toWorld.get(),
                                              q.toObject.get(), true, 0.7f,
                                              1.5f, -1, 230);
        });
        add("cone", [](CroftonQuadric &q) {
            return std::make_shared<Cone>(q.toWorld.get(), q.toObject.get(),
                                          false, 2, 1.25f, 360);
        });
        add("partial flat cone", [](CroftonQuadric &q) {
            return std::make_shared<Cone>(q.toWorld.get(), q.toObject.get(),
                                          false, 0.3f, 1.5f, 300);
        });
        auto paraboloid = [](Float r, Float z0, Float z1, Float phi,
                             bool ro) {
            return [=](CroftonQuadric &q) {
                q.radius = r, q.z0 = z0, q.z1 = z1, q.phiMax = phi;
                return std::make_shared<Paraboloid>(
                    q.toWorld.get(), q.toObject.get(), ro, r, z0, z1, phi);
            };
        };
        add("paraboloid", paraboloid(1.3f, 0, 1.8f, 360, false));
        add("paraboloid cut above its tip", paraboloid(1, 2, 0.6f, 260, true));
        add("flat paraboloid", paraboloid(2, -0.5f, 0.25f, 360, false));
        auto hyperboloid = [](Point3f p1, Point3f p2, Float phi) {
            return [=](CroftonQuadric &q) {
                return std::make_shared<Hyperboloid>(
                    q.toWorld.get(), q.toObject.get(), false, p1, p2, phi);
            };
        };
        add("hyperboloid", hyperboloid(Point3f(1, 0, -1), Point3f(0, 1, 1),
                                       360));
        add("partial hyperboloid",
            hyperboloid(Point3f(0.5f, 0.8f, 1.2f), Point3f(-1.2f, 0.3f, -0.2f),
                        280));
        add("hyperboloid as cylinder",
            hyperboloid(Point3f(0.6f, -0.8f, 0), Point3f(0.6f, -0.8f, 1.5f),
                        360));
        add("hyperboloid as cone",
            hyperboloid(Point3f(1.4f, 0, 0), Point3f(0, 0, 1.1f), 320));
        add("hyperboloid crossing the axis",
            hyperboloid(Point3f(1, 0.5f, -1), Point3f(-0.5f, -0.25f, 1), 360));
        for (size_t i = 0; i < v.size(); ++i) {
            Vec center;
            double R;
            BoundingBall(*v[i].shape, &center, &R);
            v[i].e = EstimateArea(*v[i].shape, center, 1.001 * R,
                                  0x5eed0460 + i);
        }
        return v;
    }();
    return quadrics;
}

}  // namespace

TEST(QuadricCrofton, CylindersConesHyperboloids) {
    for (const CroftonQuadric &q : CroftonQuadrics())
        if (q.name.find("paraboloid") == std::string::npos)
            ExpectAgreement(q.shape->Area(), q.e, q.name);
}

EXERCISE_TEST(Ex4_12_ParaboloidCrofton, Paraboloids) {
    for (const CroftonQuadric &q : CroftonQuadrics())
        if (q.name.find("paraboloid") != std::string::npos)
            ExpectAgreement(ex::ParaboloidArea(*q.toWorld, false, q.radius,
                                               q.z0, q.z1, q.phiMax),
                            q.e, q.name);
}

// The estimator rejects plausible wrong areas of the quadrics; the right
// ones are computed here in double, not by Area().
TEST(CauchyCrofton, RejectsWrongQuadricFormulas) {
    const std::vector<CroftonQuadric> &q = CroftonQuadrics();
    auto find = [&](const std::string &name) -> const CroftonQuadric & {
        for (const CroftonQuadric &c : q)
            if (c.name == name) return c;
        throw std::logic_error("no quadric " + name);
    };
    // The cone of height 2 and radius 1.25: the slant height, not the
    // height.
    const CroftonEstimate &cone = find("cone").e;
    double l = std::sqrt(4 + 1.25 * 1.25);
    EXPECT_LE(Deviation(kPi * 1.25 * l, cone), kStandardErrors);
    EXPECT_GT(Deviation(kPi * 1.25 * 2, cone), kStandardErrors);
    // The paraboloid of radius 1.3 and height 1.8 with its tip: the slope
    // factor, and the disk of its rim.
    const CroftonEstimate &dish = find("paraboloid").e;
    EXPECT_GT(Deviation(2 * kPi * 1.3 * 1.8 * 2 / 3, dish), kStandardErrors);
    EXPECT_GT(Deviation(kPi * 1.3 * 1.3, dish), kStandardErrors);
    // The skew hyperboloid: the distance from the axis integrated along the
    // segment overcounts.
    const CroftonEstimate &skew = find("hyperboloid").e;
    double along = 0;  // integral of |(1 - v, v)| dv by the midpoint rule
    const int n = 100000;
    for (int i = 0; i < n; ++i) {
        double s = (i + 0.5) / n;
        along += std::hypot(1 - s, s) / n;
    }
    EXPECT_GT(Deviation(2 * kPi * std::sqrt(6.0) * along, skew),
              kStandardErrors);
}
