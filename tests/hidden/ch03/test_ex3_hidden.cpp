// Hidden tests of chapter 3's graded exercises (docs/exercises.md): they run
// at grading time only and never ship to students. The public tests of the
// same exercises are the suites Ex3_22_*, Ex3_23_* and Ex3_24_* in
// tests/ch03/.
//
// Oracles: the support distance and the separating plane of the error box in
// long double; Moller-Trumbore in long double on the triangles' (already
// rounded) vertices; analytic hit points of axis-parallel rays; closed and
// flat meshes whose shared vertices and edges rays must not slip through;
// PLY files written byte by byte by a writer of our own, with known
// contents. Random tests draw their cases from calls::Seed(), new at each
// grading, and state their case counts. The tests of one exercise use no
// code of another exercise, so each fails with its own exercise's message in
// the student edition; they reach the exercise's code only through the
// exercise calls of ch03/exercise_calls.h.

#include "lrt/shapes/sphere.h"
#include "lrt/shapes/disk.h"
#include "lrt/shapes/plyreader.h"

#include "ch03/exercise_calls.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <limits>
#include <map>
#include <memory>
#include <random>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

using namespace lrt;

namespace {

using LD = long double;

constexpr LD kPi = 3.141592653589793238462643383279502884L;

struct Rng {
    std::mt19937_64 g;
    explicit Rng(uint64_t seed) : g(seed) {}
    double U(double a = 0, double b = 1) {
        return std::uniform_real_distribution<double>(a, b)(g);
    }
    int I(int n) { return int(U(0, n)) % n; }
    Vector3f Dir() {
        double z = U(-1, 1), phi = U(0, 2 * double(kPi));
        double s = std::sqrt(1 - z * z);
        return Vector3f(Float(s * std::cos(phi)), Float(s * std::sin(phi)),
                        Float(z));
    }
};

// ---------------------------------------------------------------------------
// ex-3.22: OffsetRayOrigin()

// The expected result when the offset is along one axis and every number
// involved is exact: only that coordinate moves, to the sum, and then one
// floating-point number further.
void ExpectAxisOffset(const Point3f &p, const Vector3f &pError,
                      const Normal3f &n, const Vector3f &w, int axis,
                      Float moved, bool up) {
    Point3f po = ex::OffsetRayOrigin(p, pError, n, w);
    for (int i = 0; i < 3; ++i) {
        if (i != axis) {
            EXPECT_EQ(po[i], p[i]) << "coordinate " << i << ", n " << n
                                   << ", w " << w;
        } else {
            Float want = up ? NextFloatUp(moved) : NextFloatDown(moved);
            EXPECT_EQ(po[i], want) << "coordinate " << i << ", n " << n
                                   << ", w " << w;
        }
    }
}

EXERCISE_TEST(Ex3_22_OffsetOriginHidden, ExactCasesAlongTheAxes) {
    Point3f p(1, 2, 3);
    Vector3f err(0.25f, 0.5f, 0.125f);
    // Leaving to the side of the normal, against it, and in the tangent
    // plane, where the offset goes to the normal's side.
    ExpectAxisOffset(p, err, Normal3f(0, 1, 0), Vector3f(0.3f, 0.2f, -5), 1,
                     2.5f, true);
    ExpectAxisOffset(p, err, Normal3f(0, 1, 0), Vector3f(0, -1, 0), 1, 1.5f,
                     false);
    ExpectAxisOffset(p, err, Normal3f(0, 1, 0), Vector3f(1, 0, 7), 1, 2.5f,
                     true);
    // A normal that points away from the side the ray leaves to: the side
    // comes from w, not from n.
    ExpectAxisOffset(p, err, Normal3f(0, -1, 0), Vector3f(0, 1, 0), 1, 2.5f,
                     true);
    ExpectAxisOffset(p, err, Normal3f(0, -1, 0), Vector3f(-4, 0, 1), 1, 1.5f,
                     false);
    // Negative coordinates and a large one that must not move.
    ExpectAxisOffset(Point3f(-4, 0, 1e6f), Vector3f(0.125f, 7, 7),
                     Normal3f(-1, 0, 0), Vector3f(-1, 5, 5), 0, -4.125f,
                     false);
    ExpectAxisOffset(Point3f(-4, 0, 1e6f), Vector3f(0.125f, 7, 7),
                     Normal3f(-1, 0, 0), Vector3f(2, 5, 5), 0, -3.875f, true);
    // A coordinate that starts at zero.
    ExpectAxisOffset(Point3f(3, -1, 0), Vector3f(9, 9, 0.0009765625f),
                     Normal3f(0, 0, 1), Vector3f(0, 0, 1), 2, 0.0009765625f,
                     true);
    // A small offset from a large coordinate, which the addition alone
    // would lose: the rounding step still moves the point.
    ExpectAxisOffset(Point3f(0, 0, 1024), Vector3f(0, 0, 1e-6f),
                     Normal3f(0, 0, 1), Vector3f(0, 0, -1), 2,
                     Float(1024) - Float(1e-6f), false);
    // No error, or no normal: no offset at all.
    Point3f q(-7.5f, 1e-3f, 6e5f);
    EXPECT_EQ(ex::OffsetRayOrigin(q, Vector3f(0, 0, 0),
                                  Normal3f(0.6f, 0, 0.8f), Vector3f(1, 1, 1)),
              q);
    EXPECT_EQ(ex::OffsetRayOrigin(q, Vector3f(0, 0, 0),
                                  Normal3f(0.6f, 0, 0.8f),
                                  Vector3f(-1, -1, -1)),
              q);
    EXPECT_EQ(ex::OffsetRayOrigin(q, Vector3f(2, 2, 2), Normal3f(0, 0, 0),
                                  Vector3f(1, 1, 1)),
              q);
}

EXERCISE_TEST(Ex3_22_OffsetOriginHidden, EveryCoordinateMovesByItsShareOfTheSupport) {
    // For random points, error boxes, normals and directions over forty
    // orders of magnitude, each coordinate i must move by the exact offset
    // s d n_i (d the support distance in long double, s the side) up to a
    // few roundings of d and two units in the last place of the result: not
    // less, not in the wrong direction, and not at all where n_i or d is
    // zero. And every corner of the box must be on or behind the plane
    // through the result.
    const int kCases = calls::Cases(60000, 30000);
    Rng rng(calls::Seed(0x3a22));
    const LD eps = LD(MachineEpsilon);
    const LD tiny = LD(std::numeric_limits<Float>::denorm_min());
    long moved = 0, zeroShare = 0, tangent = 0;
    for (int c = 0; c < kCases; ++c) {
        // Error bounds small compared with the coordinates, as those of
        // computed points are: the rounding step of the text covers the
        // rounding error of d only then.
        double mag = std::pow(10.0, rng.U(-15, 25));
        Point3f p(Float(rng.U(-1, 1) * mag), Float(rng.U(-1, 1) * mag),
                  Float(rng.U(-1, 1) * mag));
        double e = mag * std::pow(10.0, rng.U(-9, -4));
        Vector3f err(Float(rng.U() * e), Float(rng.U() * e),
                     Float(rng.U() * e));
        if (c % 17 == 0) err[rng.I(3)] = 0;
        if (c % 29 == 0) err = Vector3f(0, 0, 0);
        Vector3f nv = rng.Dir();
        int shape = rng.I(6);
        if (shape == 0) {  // along an axis, either sign
            int a = rng.I(3);
            nv = Vector3f(0, 0, 0);
            nv[a] = rng.U() < 0.5 ? -1 : 1;
        } else if (shape == 1) {  // in a coordinate plane
            nv[rng.I(3)] = rng.U() < 0.5 ? Float(-0.0) : Float(0);
            nv = Normalize(nv);
        }
        Normal3f n(nv);
        // Where the normal has no component, the point may be at zero.
        for (int i = 0; i < 3; ++i)
            if (n[i] == 0 && rng.U() < 0.5) p[i] = 0;
        Vector3f w = rng.Dir();
        if (shape == 0 && rng.U() < 0.5) {
            // Exactly in the tangent plane.
            for (int i = 0; i < 3; ++i)
                if (n[i] != 0) w[i] = 0;
            ++tangent;
        }
        LD dot = LD(w.x) * n.x + LD(w.y) * n.y + LD(w.z) * n.z;
        LD wn = std::sqrt(LD(w.x) * w.x + LD(w.y) * w.y + LD(w.z) * w.z);
        if (dot != 0 && std::abs(dot) < 1e-4L * wn) continue;  // side unclear
        LD side = dot < 0 ? -1 : 1;
        LD d = std::abs(LD(n.x)) * err.x + std::abs(LD(n.y)) * err.y +
               std::abs(LD(n.z)) * err.z;
        Point3f po = ex::OffsetRayOrigin(p, err, n, w);
        for (int i = 0; i < 3; ++i) {
            LD share = side * d * n[i];
            if (share == 0) {
                ++zeroShare;
                ASSERT_EQ(po[i], p[i]) << "case " << c << ", coordinate " << i
                                       << ": n " << n << ", pError " << err;
                continue;
            }
            ++moved;
            LD step = LD(po[i]) - LD(p[i]);
            LD big = std::max(std::abs(LD(po[i])), std::abs(LD(p[i])));
            LD ulp = 2 * eps * big + tiny;
            ASSERT_GT(step * (share > 0 ? 1 : -1), 0)
                << "case " << c << ", coordinate " << i << " moved the "
                << "wrong way or not at all: p " << p << " -> " << po
                << ", n " << n << ", w " << w << ", pError " << err;
            ASSERT_GE(std::abs(step), std::abs(share) * (1 - 8 * eps) -
                                          4 * tiny)
                << "case " << c << ", coordinate " << i << " moved too "
                << "little: p " << p << " -> " << po << ", n " << n
                << ", pError " << err;
            ASSERT_LE(std::abs(step), std::abs(share) * (1 + 8 * eps) +
                                          2 * ulp + 4 * tiny)
                << "case " << c << ", coordinate " << i << " moved too "
                << "far: p " << p << " -> " << po << ", n " << n
                << ", pError " << err;
        }
        for (int k = 0; k < 8; ++k) {
            LD sep = 0;
            for (int i = 0; i < 3; ++i) {
                LD corner = LD(p[i]) + (((k >> i) & 1) ? 1 : -1) * err[i];
                sep += side * LD(n[i]) * (LD(po[i]) - corner);
            }
            ASSERT_GE(sep, 0) << "case " << c << ": corner " << k
                              << " is in front of the offset origin: p "
                              << p << " -> " << po << ", n " << n
                              << ", pError " << err;
        }
    }
    std::printf("[ offset   ] %ld coordinates moved, %ld stayed, %ld cases "
                "in the tangent plane\n", moved, zeroShare, tangent);
    EXPECT_GT(moved, kCases);
    EXPECT_GT(zeroShare, kCases / 4);
    EXPECT_GT(tangent, kCases / 20);
}

EXERCISE_TEST(Ex3_22_OffsetOriginHidden, ShadowRayBetweenTwoSlabsAvoidsBothErrorBoxes) {
    // Two points with error bounds along z only: the segment between the
    // offset ends must start above the first error slab and end below the
    // second one, whichever way the second point's normal faces.
    const Float e = 0.015625f;
    Interaction a(Point3f(1, 2, 0), Normal3f(0, 0, 1), Vector3f(0, 0, e),
                  Vector3f(0, 0, 1), 0.5f);
    for (Float nz : {Float(1), Float(-1)}) {
        Interaction b(Point3f(-3, 5, 8), Normal3f(0, 0, nz),
                      Vector3f(0, 0, e), Vector3f(0, 0, -1), 0.5f);
        Ray r = ex::SpawnRayTo(a, b);
        EXPECT_EQ(r.o, Point3f(1, 2, NextFloatUp(e)));
        EXPECT_EQ(r.tMax, 1 - ShadowEpsilon);
        EXPECT_EQ(r.time, 0.5f);
        Point3f end = r(1);
        EXPECT_NEAR(end.x, -3, 1e-6);
        EXPECT_NEAR(end.y, 5, 1e-6);
        EXPECT_NEAR(end.z, NextFloatDown(8 - e), 8e-6);
        EXPECT_LT(end.z, 8 - e);
        // The same from the other end.
        Ray back = ex::SpawnRayTo(b, a);
        EXPECT_EQ(back.o, Point3f(-3, 5, NextFloatDown(8 - e)));
        EXPECT_NEAR(back(1).z, NextFloatUp(e), 1e-6);
        EXPECT_NEAR(back(1).x, 1, 1e-6);
        // And a ray that leaves b upward, away from a.
        Ray up = ex::SpawnRay(b, Vector3f(0.5f, 0, 1));
        EXPECT_EQ(up.o, Point3f(-3, 5, NextFloatUp(8 + e)));
        EXPECT_EQ(up.tMax, Infinity);
    }
}

// A sphere or a disk far from the world's origin, relative to its size, so
// that the world-space error bounds come mostly from the transformation.
struct FarShape {
    std::unique_ptr<Transform> o2w, w2o;
    std::unique_ptr<Shape> shape;
    Point3f center;
};

FarShape MakeFar(Rng &rng, bool disk, double size, double distance) {
    FarShape f;
    Vector3f tr = Float(distance) * rng.Dir();
    f.o2w.reset(
        new Transform(Translate(tr) * Rotate(rng.U(0, 360), rng.Dir())));
    f.w2o.reset(new Transform(Inverse(*f.o2w)));
    f.center = (*f.o2w)(Point3f(0, 0, 0));
    Float r = Float(size);
    if (disk)
        f.shape.reset(new Disk(f.o2w.get(), f.w2o.get(), false, 0, r,
                               0.25f * r, 360));
    else
        f.shape.reset(new Sphere(f.o2w.get(), f.w2o.get(), false, r, -r, r,
                                 360));
    return f;
}

EXERCISE_TEST(Ex3_22_OffsetOriginHidden, RaysSpawnedFromDistantSpheresAndDisks) {
    // Spheres and rings of sizes 1e-2 to 1e3, at 50 and 2,000 times their
    // size from the origin. From each hit, rays leave the outside of a
    // sphere at an angle of at least 6 degrees from the tangent plane, and
    // either side of a ring at any angle above 0.06 degrees: none may hit
    // the surface again. Rays into a full sphere, steeper than 25 degrees,
    // must hit the far side at the length of the chord.
    Rng rng(calls::Seed(0x3a23));
    long spawned = 0, chords = 0, rehits = 0, badChords = 0;
    for (double size : {1e-2, 1.0, 1e3})
        for (double far : {50.0, 2000.0})
            for (int disk = 0; disk <= 1; ++disk)
                for (int placement = 0; placement < 3; ++placement) {
                    FarShape f = MakeFar(rng, disk, size, far * size);
                    for (int h = 0; h < 200; ++h) {
                        Float s = Float(size);
                        Point3f target = f.center +
                                         s * Float(rng.U(0, 1)) * rng.Dir();
                        Point3f o = f.center +
                                    s * Float(rng.U(2, 5)) * rng.Dir();
                        Float t;
                        SurfaceInteraction si;
                        if (!f.shape->Intersect(Ray(o, target - o), &t, &si))
                            continue;
                        Vector3f n = Normalize(Vector3f(si.n));
                        Vector3f out = disk ? n : Normalize(si.p - f.center);
                        for (int k = 0; k < 4; ++k) {
                            Vector3f w = rng.Dir();
                            Float minCos = disk ? 1e-3f : 0.1f;
                            if (!disk && Dot(w, out) < 0) w = -w;
                            if (std::abs(Dot(w, out)) < minCos) continue;
                            Ray r = ex::SpawnRay(si, w);
                            ++spawned;
                            Float t2;
                            SurfaceInteraction si2;
                            bool again = f.shape->Intersect(r, &t2, &si2);
                            if (again || f.shape->IntersectP(r)) {
                                if (++rehits <= 3)
                                    ADD_FAILURE()
                                        << (disk ? "disk" : "sphere")
                                        << " of size " << size << " at "
                                        << far << " sizes: " << r
                                        << " hit it again";
                            }
                        }
                        if (disk) continue;
                        Vector3f w = -rng.Dir();
                        if (Dot(w, out) > 0) w = -w;
                        Float cosA = -Dot(w, out);
                        if (cosA < 0.42f) continue;
                        ++chords;
                        Float t2;
                        SurfaceInteraction si2;
                        bool hit = f.shape->Intersect(ex::SpawnRay(si, w),
                                                      &t2, &si2);
                        // The chord's length is uncertain by the rounding
                        // error of coordinates as large as the distance.
                        Float R = Distance(si.p, f.center);
                        Float tol = 1e-3f * R + 20 * MachineEpsilon *
                                                    Float(far + 2) * R / cosA;
                        if (!hit || std::abs(t2 - 2 * R * cosA) > tol) {
                            if (++badChords <= 3)
                                ADD_FAILURE()
                                    << "sphere of size " << size << " at "
                                    << far << " sizes: chord "
                                    << (hit ? t2 : -1) << " for "
                                    << 2 * R * cosA;
                        }
                    }
                }
    std::printf("[ offset   ] %ld spawned rays, %ld re-hits; %ld chords, "
                "%ld wrong\n", spawned, rehits, chords, badChords);
    EXPECT_EQ(rehits, 0);
    EXPECT_EQ(badChords, 0);
    EXPECT_GT(spawned, 15000);
    EXPECT_GT(chords, 1000);
}

// ---------------------------------------------------------------------------
// ex-3.23: the ray's coordinate system in the triangle test

// A mesh with no transformation and no per-vertex data but positions.
MeshSpec Mesh(const std::vector<Point3f> &p, const std::vector<int> &indices) {
    MeshSpec m;
    m.p = p;
    m.indices = indices;
    return m;
}

MeshSpec OneTriangle(const Point3f &a, const Point3f &b, const Point3f &c) {
    return Mesh({a, b, c}, {0, 1, 2});
}

// Moller-Trumbore in long double on the Float vertices and ray: t and the
// barycentric coordinates of the intersection with the triangle's plane.
struct Exact {
    bool valid = false;
    LD t = 0, b0 = 0, b1 = 0, b2 = 0;
    LD margin() const { return std::min(b0, std::min(b1, b2)); }
};

Exact ExactHit(const Point3f &p0, const Point3f &p1, const Point3f &p2,
               const Ray &r) {
    LD e1[3], e2[3], d[3], s[3];
    for (int i = 0; i < 3; ++i) {
        e1[i] = LD(p1[i]) - p0[i];
        e2[i] = LD(p2[i]) - p0[i];
        d[i] = r.d[i];
        s[i] = LD(r.o[i]) - p0[i];
    }
    auto cross = [](const LD *a, const LD *b, LD *c) {
        c[0] = a[1] * b[2] - a[2] * b[1];
        c[1] = a[2] * b[0] - a[0] * b[2];
        c[2] = a[0] * b[1] - a[1] * b[0];
    };
    auto dot = [](const LD *a, const LD *b) {
        return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    };
    LD pv[3], qv[3];
    cross(d, e2, pv);
    LD det = dot(e1, pv);
    Exact x;
    if (det == 0) return x;
    x.valid = true;
    cross(s, e1, qv);
    x.b1 = dot(s, pv) / det;
    x.b2 = dot(d, qv) / det;
    x.b0 = 1 - x.b1 - x.b2;
    x.t = dot(e2, qv) / det;
    return x;
}

EXERCISE_TEST(Ex3_23_RayTriangleHidden, AxisParallelRaysInAllSixDirections) {
    // A triangle across each coordinate axis at distance 5 on either side,
    // hit by rays exactly along the axis, with direction lengths from 2^-12
    // to 2^20. The hit point is on the axis, at t = 5 / length.
    const Float lengths[] = {1, 0.000244140625f, 3, 1048576};
    for (int axis = 0; axis < 3; ++axis)
        for (int sign = -1; sign <= 1; sign += 2) {
            int a1 = (axis + 1) % 3, a2 = (axis + 2) % 3;
            auto at = [&](Float along, Float u, Float v) {
                Point3f q;
                q[axis] = along;
                q[a1] = u;
                q[a2] = v;
                return q;
            };
            Float h = Float(5 * sign);
            calls::Handle tri = ex::MakeMesh(
                OneTriangle(at(h, -1, -1), at(h, 2, -1), at(h, -1, 2)));
            // IntersectP() of the triangle.
            auto hitP = [&](const Ray &r) {
                return ex::IntersectTriangle(tri, 0, r, Float(-1)).hitP;
            };
            for (Float len : lengths) {
                Vector3f d(0, 0, 0);
                d[axis] = sign * len;
                Ray ray(Point3f(0, 0, 0), d);
                TriangleHit hit = ex::IntersectTriangle(tri, 0, ray, Float(-1));
                ASSERT_TRUE(hit.hit) << "axis " << axis << ", direction " << d;
                Float t = hit.tHit;
                const SurfaceHit &si = hit.isect;
                EXPECT_NEAR(t, 5 / len, 5 / len * 1e-6) << d;
                EXPECT_NEAR(si.p[axis], h, 1e-5) << d;
                EXPECT_NEAR(si.p[a1], 0, 1e-5) << d;
                EXPECT_NEAR(si.p[a2], 0, 1e-5) << d;
                // (u, v) of the default parameterization: b1 + b2 and b2,
                // with b1 = b2 = 1/3 at the origin of the plane.
                EXPECT_NEAR(si.uv.x, 2.0 / 3, 1e-5) << d;
                EXPECT_NEAR(si.uv.y, 1.0 / 3, 1e-5) << d;
                EXPECT_TRUE(hit.hitP);
                // Beside the triangle, behind the origin, short of it.
                Ray beside(at(0, 0.75f, 0.75f), d);
                EXPECT_FALSE(hitP(beside)) << d;
                EXPECT_FALSE(hitP(Ray(Point3f(0, 0, 0), -d))) << d;
                EXPECT_FALSE(hitP(Ray(Point3f(0, 0, 0), d, 0.999f * (5 / len))))
                    << d;
                EXPECT_TRUE(hitP(Ray(Point3f(0, 0, 0), d, 1.001f * (5 / len))))
                    << d;
                // Along the axis but off the origin, on the triangle's edge
                // u = -1 of the plane (edges count as inside).
                Ray edge(at(0, -1, 0.5f), d);
                EXPECT_TRUE(hitP(edge)) << d;
            }
        }
}

EXERCISE_TEST(Ex3_23_RayTriangleHidden, DirectionsWithTiedLargestComponents) {
    // When two or three components of the direction are equal in
    // magnitude, any of them may become z; the answers must not change.
    const Vector3f dirs[] = {
        Vector3f(1, 1, 0),   Vector3f(-1, 1, 0),  Vector3f(0, 1, -1),
        Vector3f(1, -1, 1),  Vector3f(-2, -2, -2), Vector3f(3, 0, -3),
        Vector3f(0.5f, -0.5f, 0.25f), Vector3f(-7, 7, 7)};
    Rng rng(calls::Seed(0x3b23));
    int tested = 0;
    for (const Vector3f &d : dirs)
        for (int k = 0; k < 200; ++k) {
            Point3f p[3];
            for (Point3f &q : p)
                q = Point3f(Float(rng.U(-2, 2)), Float(rng.U(-2, 2)),
                            Float(rng.U(-2, 2)));
            MeshSpec tri = OneTriangle(p[0], p[1], p[2]);
            double w0 = rng.U(0.1, 1), w1 = rng.U(0.1, 1), w2 = rng.U(0.1, 1);
            // Inside for even k, outside (one weight negative) for odd k.
            if (k % 2) w0 = -w0;
            double sum = w0 + w1 + w2;
            if (std::abs(sum) < 0.2) continue;
            Point3f target;
            for (int i = 0; i < 3; ++i)
                target[i] = Float((w0 * p[0][i] + w1 * p[1][i] +
                                   w2 * p[2][i]) / sum);
            Ray ray(target - 4 * d, d);
            Exact x = ExactHit(p[0], p[1], p[2], ray);
            Vector3f ng = Normalize(Cross(p[1] - p[0], p[2] - p[0]));
            if (std::abs(Dot(ng, Normalize(d))) < 0.05f) continue;
            if (!x.valid || std::abs(x.margin()) < 1e-3L) continue;
            ++tested;
            TriangleHit h = ex::IntersectTriangleOf(tri, 0, ray, Float(-1));
            bool want = x.margin() > 0 && x.t > 0;
            ASSERT_EQ(h.hit, want) << "direction " << d << ", case " << k;
            EXPECT_EQ(h.hitP, want) << d;
            if (h.hit) {
                EXPECT_NEAR(h.tHit, double(x.t), 1e-5 * double(x.t)) << d;
            }
        }
    EXPECT_GT(tested, 1000);
}

EXERCISE_TEST(Ex3_23_RayTriangleHidden, UnnormalizedAndPlanarDirectionsAgreeWithOracle) {
    // Random triangles and rays whose directions have lengths from 1e-6 to
    // 1e6, a fifth of them with one component exactly zero and a tenth
    // with two, and tMax infinite or within 1% of the hit; rays within
    // 1e-4 (barycentric) of an edge are left out.
    const int kCases = calls::Cases(40000, 16000);
    Rng rng(calls::Seed(0x3c23));
    int hits = 0, misses = 0, planar = 0;
    for (int c = 0; c < kCases; ++c) {
        Point3f center(Float(rng.U(-10, 10)), Float(rng.U(-10, 10)),
                       Float(rng.U(-10, 10)));
        Point3f p[3];
        for (Point3f &q : p) q = center + Float(rng.U(0.2, 1)) * rng.Dir();
        Vector3f d = rng.Dir();
        int zeros = c % 10 == 0 ? 2 : (c % 5 == 1 ? 1 : 0);
        int keep = rng.I(3);
        for (int z = 0; z < zeros; ++z) d[(keep + 1 + z) % 3] = 0;
        if (zeros) ++planar;
        d = Normalize(d);
        // Aim at a random point of the plane near the triangle; the origin
        // is the point minus a multiple of d, so the ray passes through it.
        double w0 = rng.U(-0.3, 1), w1 = rng.U(-0.3, 1), w2 = rng.U(-0.3, 1);
        double sum = w0 + w1 + w2;
        Point3f target;
        for (int i = 0; i < 3; ++i)
            target[i] = Float((w0 * p[0][i] + w1 * p[1][i] + w2 * p[2][i]) /
                              sum);
        Point3f o = target - Float(rng.U(-1, 5)) * d;
        Float len = Float(std::pow(10.0, rng.U(-6, 6)));
        Ray ray(o, len * d);
        Exact x = ExactHit(p[0], p[1], p[2], ray);
        if (!x.valid) continue;
        // The triangle must not be seen nearly edge-on. (e: the normal, as
        // long as twice the area.)
        Vector3f e = Cross(p[1] - p[0], p[2] - p[0]);
        if (std::abs(Dot(Normalize(e), d)) < 0.05f) continue;
        if (std::abs(x.margin()) < 1e-4L) continue;
        if (std::abs(x.t * len) < 1e-3L) continue;  // starts on the plane
        if (c % 3 == 0 && x.t > 0)
            ray.tMax = Float(x.t * (c % 2 ? 1.01L : 0.99L));
        bool want = x.margin() > 0 && x.t > 0 && x.t <= LD(ray.tMax);
        TriangleHit h = ex::IntersectTriangleOf(OneTriangle(p[0], p[1], p[2]),
                                                0, ray, Float(-1));
        bool hit = h.hit;
        Float t = h.tHit;
        const SurfaceHit &si = h.isect;
        ASSERT_EQ(hit, want) << "case " << c << ": ray " << ray << ", t "
                             << double(x.t) << ", margin "
                             << double(x.margin());
        if (!hit) {
            ++misses;
            continue;
        }
        ++hits;
        LD scale = 1 + std::abs(LD(center.x)) + std::abs(LD(center.y)) +
                   std::abs(LD(center.z));
        EXPECT_NEAR(t, double(x.t), double(2e-5L * x.t + 1e-5L * scale / len))
            << "case " << c;
        for (int i = 0; i < 3; ++i) {
            LD exact = x.b0 * p[0][i] + x.b1 * p[1][i] + x.b2 * p[2][i];
            EXPECT_NEAR(si.p[i], double(exact), double(2e-5L * scale))
                << "case " << c << ", coordinate " << i;
        }
        // Float barycentrics lose accuracy as the vertices' squared distance
        // from the origin grows against the triangle's area seen along d (a
        // sliver, or a triangle far off the origin): each edge function is a
        // difference of products of size R^2, divided by that area.
        LD seen = std::abs(LD(e.x) * d.x + LD(e.y) * d.y + LD(e.z) * d.z) /
                  std::max({std::abs(LD(d.x)), std::abs(LD(d.y)),
                            std::abs(LD(d.z))});
        LD r2 = 0;
        for (const Point3f &q : p)
            r2 = std::max(r2, LD(DistanceSquared(q, o)));
        double uvTol = double(1e-4L + 16 * LD(MachineEpsilon) * r2 / seen);
        EXPECT_NEAR(si.uv.x, double(x.b1 + x.b2), uvTol) << "case " << c;
        EXPECT_NEAR(si.uv.y, double(x.b2), uvTol) << "case " << c;
        if (::testing::Test::HasFailure()) return;
    }
    std::printf("[ triangle ] %d hits, %d misses, %d planar directions\n",
                hits, misses, planar);
    EXPECT_GT(hits, kCases / 5);
    EXPECT_GT(misses, kCases / 5);
}

// A sheet of n x n jittered cells in the plane where coordinate `axis` is
// h, two triangles per cell with alternating diagonals and shared vertices.
struct Sheet {
    std::vector<Point3f> p;
    std::vector<int> indices;
    std::vector<std::pair<int, int>> edges;
};

Sheet MakeSheet(Rng &rng, int n, int axis, Float h) {
    Sheet s;
    auto index = [&](int i, int j) { return i * (n + 1) + j; };
    for (int i = 0; i <= n; ++i)
        for (int j = 0; j <= n; ++j) {
            bool inner = i > 0 && j > 0 && i < n && j < n;
            Float u = Float(i + (inner ? rng.U(-0.3, 0.3) : 0)) / n;
            Float v = Float(j + (inner ? rng.U(-0.3, 0.3) : 0)) / n;
            Point3f q;
            q[axis] = h;
            q[(axis + 1) % 3] = 2 * u - 1;
            q[(axis + 2) % 3] = 2 * v - 1;
            s.p.push_back(q);
        }
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
            int a = index(i, j), b = index(i + 1, j), c = index(i + 1, j + 1),
                d = index(i, j + 1);
            int tris[2][3] = {{a, b, c}, {a, c, d}};
            if ((i + j) % 2) {
                tris[0][2] = d;
                tris[1][0] = b;
            }
            for (auto &t : tris)
                for (int k = 0; k < 3; ++k) {
                    s.indices.push_back(t[k]);
                    int x = t[k], y = t[(k + 1) % 3];
                    s.edges.push_back({std::min(x, y), std::max(x, y)});
                }
        }
    return s;
}

EXERCISE_TEST(Ex3_23_WatertightHidden, SheetsSeenAlongTheAxesAndObliquely) {
    // Rays exactly parallel to a coordinate axis, and oblique ones, aimed
    // at the shared vertices of a jittered triangulated square and at
    // points on its inner edges, must hit at least one of its triangles.
    Rng rng(calls::Seed(0x3d23));
    const int raysPerSheet = calls::Cases(3000, 2000);
    long rays = 0, failures = 0;
    for (int axis = 0; axis < 3; ++axis)
        for (Float h : {Float(0), Float(0.3f), Float(-1234.5f)}) {
            Sheet s = MakeSheet(rng, 8, axis, h);
            calls::Handle tris = ex::MakeMesh(Mesh(s.p, s.indices));
            for (int i = 0; i < raysPerSheet; ++i) {
                Point3f target;
                if (i % 2 == 0) {
                    target = s.p[rng.I(int(s.p.size()))];
                } else {
                    const auto &e = s.edges[rng.I(int(s.edges.size()))];
                    Float l = Float(rng.U());
                    target = s.p[e.first] + l * (s.p[e.second] - s.p[e.first]);
                }
                // Keep away from the sheet's border, where rays may miss.
                bool border = false;
                for (int k = 1; k <= 2; ++k)
                    border |= std::abs(target[(axis + k) % 3]) > 0.999f;
                if (border) continue;
                Vector3f d(0, 0, 0);
                if (i % 3 == 0) {
                    d[axis] = rng.U() < 0.5 ? -1 : 1;
                } else {
                    d = rng.Dir();
                    if (std::abs(d[axis]) < 0.1f) d[axis] = 0.5f;
                }
                Float dist = Float(std::pow(10.0, rng.U(-2, 2)));
                Ray ray(target - dist * d, d);
                bool hit = ex::HitsMesh(tris, ray);
                ++rays;
                if (!hit && ++failures <= 3)
                    ADD_FAILURE() << "ray " << ray << " passed through the "
                                  << "sheet at " << target;
            }
        }
    std::printf("[ watertight] %ld rays at the vertices and edges of sheets: "
                "%ld passed through\n", rays, failures);
    EXPECT_EQ(failures, 0);
    EXPECT_GT(rays, 9 * raysPerSheet * 2 / 3);
}

EXERCISE_TEST(Ex3_23_WatertightHidden, LatitudeLongitudeSphereFromInside) {
    // A closed sphere of latitude-longitude triangles, with fans of 24
    // triangles at the poles. Rays from inside aimed exactly at vertices,
    // the poles included, and at points on edges must hit it.
    const int nLat = 10, nLon = 24;
    for (Float r : {Float(1e-3), Float(1), Float(1e3)}) {
        Point3f c(Float(0.25) * r, -3 * r, Float(1.5) * r);
        std::vector<Point3f> p;
        p.push_back(c + Vector3f(0, 0, r));
        for (int i = 1; i < nLat; ++i)
            for (int j = 0; j < nLon; ++j) {
                double th = double(kPi) * i / nLat;
                double ph = 2 * double(kPi) * j / nLon;
                p.push_back(c + r * Vector3f(Float(std::sin(th) * std::cos(ph)),
                                             Float(std::sin(th) * std::sin(ph)),
                                             Float(std::cos(th))));
            }
        p.push_back(c + Vector3f(0, 0, -r));
        int south = int(p.size()) - 1;
        auto ring = [&](int i, int j) { return 1 + (i - 1) * nLon + j % nLon; };
        std::vector<int> idx;
        for (int j = 0; j < nLon; ++j) {
            idx.insert(idx.end(), {0, ring(1, j), ring(1, j + 1)});
            idx.insert(idx.end(),
                       {south, ring(nLat - 1, j + 1), ring(nLat - 1, j)});
            for (int i = 1; i + 1 < nLat; ++i) {
                idx.insert(idx.end(), {ring(i, j), ring(i + 1, j),
                                       ring(i + 1, j + 1)});
                idx.insert(idx.end(), {ring(i, j), ring(i + 1, j + 1),
                                       ring(i, j + 1)});
            }
        }
        calls::Handle tris = ex::MakeMesh(Mesh(p, idx));
        std::vector<std::vector<int>> around(p.size());
        std::vector<std::pair<int, int>> edges;
        for (size_t t = 0; t < idx.size() / 3; ++t)
            for (int k = 0; k < 3; ++k) {
                around[idx[3 * t + k]].push_back(int(t));
                edges.push_back({idx[3 * t + k], idx[3 * t + (k + 1) % 3]});
            }
        Rng rng(calls::Seed(0x3e23));
        long failures = 0;
        const int rays = calls::Cases(8000, 4000);
        for (int i = 0; i < rays; ++i) {
            Point3f target;
            std::vector<int> cand;
            if (i % 2 == 0) {
                int v = i % 10 == 0 ? (i % 20 ? 0 : south)
                                    : rng.I(int(p.size()));
                target = p[v];
                cand = around[v];
            } else {
                auto e = edges[rng.I(int(edges.size()))];
                Float l = Float(rng.U());
                target = p[e.first] + l * (p[e.second] - p[e.first]);
                cand = around[e.first];
                cand.insert(cand.end(), around[e.second].begin(),
                            around[e.second].end());
            }
            Point3f o = c;
            if (i % 4 != 0)
                o += Float(0.5) * r * Float(rng.U()) * rng.Dir();
            Ray ray(o, target - o);
            bool hit = false;
            for (const TriangleVerdict &v :
                 ex::IntersectTriangles(tris, cand, ray))
                hit = hit || v.hitP;
            if (!hit && ++failures <= 3)
                ADD_FAILURE() << "radius " << r << ": ray " << ray
                              << " left the sphere at " << target;
        }
        EXPECT_EQ(failures, 0) << "radius " << r;
    }
}

// ---------------------------------------------------------------------------
// ex-3.24: the PLY header

enum class Enc { Ascii, Little, Big };

const char *EncName(Enc e) {
    return e == Enc::Ascii    ? "ascii"
           : e == Enc::Little ? "binary_little_endian"
                              : "binary_big_endian";
}

// Values of PLY types, as text or as bytes in either order.
struct Writer {
    Enc enc;
    std::string header, body;
    void Line(const std::string &l) { header += l + "\n"; }
    template <typename T>
    void Bin(T v) {
        unsigned char b[sizeof(T)];
        std::memcpy(b, &v, sizeof(T));
        uint16_t one = 1;
        unsigned char first;
        std::memcpy(&first, &one, 1);
        bool little = first == 1;
        for (size_t i = 0; i < sizeof(T); ++i)
            body += char(b[little == (enc == Enc::Little) ? i
                                                          : sizeof(T) - 1 - i]);
    }
    // type: the PLY type's size in bytes, and whether it is signed or a
    // floating-point number.
    void Put(const std::string &type, double v) {
        if (enc == Enc::Ascii) {
            char buf[64];
            std::snprintf(buf, sizeof(buf), "%.17g ", v);
            body += buf;
            return;
        }
        if (type == "char" || type == "int8") Bin(int8_t(v));
        else if (type == "uchar" || type == "uint8") Bin(uint8_t(v));
        else if (type == "short" || type == "int16") Bin(int16_t(v));
        else if (type == "ushort" || type == "uint16") Bin(uint16_t(v));
        else if (type == "int" || type == "int32") Bin(int32_t(v));
        else if (type == "uint" || type == "uint32") Bin(uint32_t(v));
        else if (type == "float" || type == "float32") Bin(float(v));
        else if (type == "double" || type == "float64") Bin(double(v));
        else ADD_FAILURE() << "writer: unknown type " << type;
    }
    void End() {
        if (enc == Enc::Ascii) body += "\n";
    }
};

EXERCISE_TEST(Ex3_24_PlyHeaderHidden, AllTypeNamesListsAndSkippedElements) {
    // An element before the vertices with a property of every type name in
    // both spellings and lists with three count types; vertices whose
    // coordinates come in the order z, y, x with three different types and
    // a list between them; faces with a scalar before the indices; an
    // element of count zero at the end. In all three encodings.
    const char *types[] = {"char",  "int8",   "uchar",  "uint8",
                           "short", "int16",  "ushort", "uint16",
                           "int",   "int32",  "uint",   "uint32",
                           "float", "float32", "double", "float64"};
    const double extremes[][2] = {
        {-128, 127}, {-128, 127}, {0, 255}, {0, 255},
        {-32768, 32767}, {-32768, 32767}, {0, 65535}, {0, 65535},
        {-2147483648.0, 2147483647}, {-2147483648.0, 2147483647},
        {0, 4294967295.0}, {0, 4294967295.0},
        {-1.5e38, 0.1}, {-1.5e38, 0.1}, {-1e300, 0.1}, {-1e300, 0.1}};
    const double xs[] = {-1.25, 0.5, 3.75, -1024.5, 1e-3};
    const double ys[] = {7, -300, 0, 32767, -32768};
    const double zs[] = {0.125, -2.5e30, 6, 1.0 / 3, -0.0};
    for (Enc enc : {Enc::Ascii, Enc::Little, Enc::Big}) {
        Writer w{enc, "", ""};
        w.Line("ply");
        w.Line(std::string("format  ") + EncName(enc) + "\t1.0");
        w.Line("comment written by the hidden tests");
        w.Line("element material 002");
        for (int k = 0; k < 16; ++k)
            w.Line(std::string("property ") + types[k] + " m" +
                   std::to_string(k));
        w.Line("property list ushort int16 tags");
        w.Line("property list int32 float64 weights");
        w.Line("property list uint8 char code");
        w.Line("element   vertex 5");
        w.Line("property double z");
        w.Line("property list uint32 uint16 neighbors");
        w.Line("property int16 y");
        w.Line("property float32 x");
        w.Line("obj_info between the properties");
        w.Line("element face 3");
        w.Line("property uchar flags");
        w.Line("property list uint16 uint32 vertex_indices");
        w.Line("property double quality");
        w.Line("element edge 0");
        w.Line("property int vertex1");
        w.Line("property list uchar int more");
        w.Line("end_header");
        for (int m = 0; m < 2; ++m) {
            for (int k = 0; k < 16; ++k) w.Put(types[k], extremes[k][m]);
            w.Put("ushort", 3 * m);
            for (int i = 0; i < 3 * m; ++i) w.Put("int16", -1000 * i - 7);
            w.Put("int32", 2 - m);
            for (int i = 0; i < 2 - m; ++i) w.Put("float64", 1e200 * (i + 1));
            w.Put("uint8", 1);
            w.Put("char", -5);
            w.End();
        }
        for (int v = 0; v < 5; ++v) {
            w.Put("double", zs[v]);
            w.Put("uint32", v % 3);
            for (int i = 0; i < v % 3; ++i) w.Put("uint16", 65535 - i);
            w.Put("int16", ys[v]);
            w.Put("float32", xs[v]);
            w.End();
        }
        const std::vector<std::vector<int>> faces = {
            {0, 1, 2}, {4, 3, 2, 1}, {0, 2, 4, 1, 3}};
        for (const auto &f : faces) {
            w.Put("uchar", 200);
            w.Put("uint16", double(f.size()));
            for (int i : f) w.Put("uint32", i);
            w.Put("double", -0.5);
            w.End();
        }
        PlyMesh m = ex::ReadPly(std::string("types_") + EncName(enc) + ".ply",
                                w.header + w.body);
        ASSERT_EQ(m.nVertices(), 5) << EncName(enc);
        for (int v = 0; v < 5; ++v) {
            Point3f want(Float(float(xs[v])), Float(ys[v]), Float(zs[v]));
            EXPECT_EQ(m.p[v], want) << EncName(enc) << ", vertex " << v;
        }
        EXPECT_TRUE(m.n.empty());
        EXPECT_TRUE(m.uv.empty());
        EXPECT_EQ(m.vertexIndices,
                  (std::vector<int>{0, 1, 2, 4, 3, 2, 4, 2, 1, 0, 2, 4, 0,
                                    4, 1, 0, 1, 3}))
            << EncName(enc);
    }
}

EXERCISE_TEST(Ex3_24_PlyHeaderHidden, CountsBeyondFourBillionAreCounts) {
    // A skipped element may declare more instances than an int holds, here
    // 2^32 + 3; the reader must accept the count and fail only when the
    // data runs out, in the fifth instance (a count cut to 32 bits, 3,
    // would leave bytes unread after the last element).
    Writer w{Enc::Little, "", ""};
    w.Line("ply");
    w.Line("format binary_little_endian 1.0");
    w.Line("element vertex 3");
    w.Line("property float x");
    w.Line("property float y");
    w.Line("property float z");
    w.Line("element face 1");
    w.Line("property list uchar int vertex_indices");
    w.Line("element blob 4294967299");
    w.Line("property uint16 value");
    w.Line("end_header");
    for (int i = 0; i < 9; ++i) w.Put("float", i);
    w.Put("uchar", 3);
    for (int i = 0; i < 3; ++i) w.Put("int", i);
    for (int i = 0; i < 4; ++i) w.Put("uint16", i);
    w.Put("uchar", 1);  // half of the fifth blob
    std::string message = ex::ReadPlyError("bigcount.ply", w.header + w.body);
    EXPECT_NE(message.find("blob 4"), std::string::npos) << message;
    EXPECT_NE(message.find("unexpected end of file"), std::string::npos)
        << message;
}

EXERCISE_TEST(Ex3_24_PlyHeaderHidden, MalformedHeaderLinesNameLineAndProblem) {
    struct Case {
        const char *name;
        std::string text;
        int line;
        std::string expect;
    };
    auto ascii = [](const std::string &rest) {
        return "ply\nformat ascii 1.0\n" + rest;
    };
    const std::vector<Case> cases = {
        {"formatagain", ascii("element vertex 1\nformat ascii 1.0\n"), 4,
         "more than one format line"},
        {"formatshort", "ply\nformat ascii\n", 2, "malformed format line"},
        {"formatlong", "ply\nformat ascii 1.0 1.0\n", 2,
         "malformed format line"},
        {"formatcase", "ply\nformat ASCII 1.0\n", 2,
         "unsupported format \"ASCII\""},
        {"formatversion", "ply\ncomment c\nformat binary_big_endian 1.1\n", 3,
         "unsupported version \"1.1\""},
        {"elementshort", ascii("element vertex\n"), 3,
         "malformed element line"},
        {"elementlong", ascii("element vertex 3 4\n"), 3,
         "malformed element line"},
        {"elementoverflow", ascii("element face 99999999999999999999\n"), 3,
         "bad count \"99999999999999999999\" for element face"},
        {"elementhex", ascii("comment x\nelement vertex 0x10\n"), 4,
         "bad count \"0x10\" for element vertex"},
        {"elementfraction", ascii("element vertex 3.0\n"), 3,
         "bad count \"3.0\" for element vertex"},
        {"elementnegative", ascii("element edge -0.5\n"), 3,
         "bad count \"-0.5\" for element edge"},
        {"propertyalone", ascii("element vertex 3\nproperty\n"), 4,
         "malformed property line"},
        {"propertylong", ascii("element vertex 3\nproperty float x y\n"), 4,
         "malformed property line"},
        {"listshort", ascii("element face 1\nproperty list uchar int\n"), 4,
         "malformed property line"},
        {"listlong",
         ascii("element face 1\nproperty list uchar int vertex_indices x\n"),
         4, "malformed property line"},
        {"listdoublecount",
         ascii("element face 1\nproperty list double int vertex_indices\n"), 4,
         "count must have an integer type"},
        {"listunknowncount",
         ascii("element face 1\nproperty list byte int vertex_indices\n"), 4,
         "unknown type \"byte\""},
        {"listunknownitem",
         ascii("element face 1\nproperty list uchar integer vertex_indices\n"),
         4, "unknown type \"integer\""},
        {"scalarunknown", ascii("element vertex 1\nproperty real x\n"), 4,
         "unknown type \"real\""},
        {"propertyfirst",
         ascii("comment hi\nobj_info x\nproperty float x\n"), 5,
         "property declared before any element"},
    };
    for (const Case &c : cases) {
        std::string name = std::string(c.name) + ".ply";
        std::string message = ex::ReadPlyError(name, c.text);
        size_t file = ex::PlyFilePrefix(message, name);
        std::string line = "line " + std::to_string(c.line) + ": ";
        EXPECT_TRUE(file > 0 && message.compare(file, line.size(), line) == 0)
            << c.name << ": \"" << message << "\"";
        EXPECT_NE(message.find(c.expect), std::string::npos)
            << c.name << ": \"" << message << "\" lacks \"" << c.expect
            << "\"";
    }
}

}  // namespace
