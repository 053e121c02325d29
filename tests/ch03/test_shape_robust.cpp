// Robustness of spawned rays at every scale: rays spawned from hit points
// with OffsetRayOrigin() never hit the surface they leave, and shadow rays
// find occluders however close; a fixed "bias" offset fails at large scales
// (self-intersection) and at small ones (light leaks). All of them spawn
// rays with OffsetRayOrigin() and belong to exercise ex-3.22 (Ex3_22_*): the
// rays are spawned by exercise calls (exercise_calls.h), and the shapes they
// must miss are intersected here.
#include "lrt/shapes/sphere.h"
#include "lrt/shapes/disk.h"

#include "exercise_calls.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <memory>
#include <random>
#include <string>
#include <vector>

namespace {

// Primary rays per shape and placement (in `make test`; fewer when graded),
// and rays spawned from each hit.
constexpr int kHitsPerShape = 1000;
constexpr int kSpawnedPerHit = 6;
// The fixed offset of the naive method: a typical hard-coded value.
constexpr lrt::Float kFixedEpsilon = 1e-4f;

const double kPi = 3.14159265358979323846;

struct Rng {
    std::mt19937_64 g;
    explicit Rng(uint64_t seed) : g(seed) {}
    double U(double a = 0, double b = 1) {
        return std::uniform_real_distribution<double>(a, b)(g);
    }
    lrt::Vector3f Dir() {
        double z = U(-1, 1), phi = U(0, 2 * kPi), s = std::sqrt(1 - z * z);
        return lrt::Vector3f(s * std::cos(phi), s * std::sin(phi), z);
    }
    // A random unit vector on the side of n, with a cosine to n that is
    // uniform in (0, 1] half of the time and tiny (grazing) otherwise.
    lrt::Vector3f Hemisphere(const lrt::Vector3f &n) {
        lrt::Vector3f t = lrt::Normalize(lrt::Cross(n, Dir()));
        double c = U() < 0.5 ? U(1e-6, 1) : std::pow(10.0, U(-6, -2));
        double s = std::sqrt(1 - c * c);
        return lrt::Normalize(lrt::Float(c) * n + lrt::Float(s) * t);
    }
};

// The scales at which the tests run: 1e-3 to 1e4, and the scale at which
// the rounding error of a coordinate is about ten times the fixed offset.
std::vector<double> Scales() {
    std::vector<double> s;
    for (int e = -3; e <= 4; ++e) s.push_back(std::pow(10.0, e));
    s.push_back(10 * kFixedEpsilon / lrt::MachineEpsilon);
    return s;
}

// A shape placed in the world at scale s: rotated, translated by a few times
// (or, when far is true, a few hundred times) its size, and scaled either
// by its own parameters or by the transformation.
struct Placed {
    std::unique_ptr<lrt::Transform> o2w, w2o;
    std::unique_ptr<lrt::Shape> shape;
    lrt::Point3f center, diskCenter;
    lrt::Vector3f diskNormal;
    double size;
    bool fullSphere = false;
};

Placed Place(Rng &rng, int kind, double s, bool far, bool scaleByTransform) {
    Placed p;
    p.size = s;
    lrt::Vector3f tr = lrt::Float(s * (far ? 300 : 3)) * rng.Dir();
    lrt::Float k = lrt::Float(scaleByTransform ? s : 1);
    lrt::Float r = lrt::Float(scaleByTransform ? 1 : s);
    p.o2w.reset(new lrt::Transform(lrt::Translate(tr) *
                                   lrt::Rotate(rng.U(0, 360), rng.Dir()) *
                                   lrt::Scale(k, k, k)));
    p.w2o.reset(new lrt::Transform(Inverse(*p.o2w)));
    p.center = (*p.o2w)(lrt::Point3f(0, 0, 0));
    p.diskCenter = (*p.o2w)(lrt::Point3f(0, 0, 0.2f * r));
    p.diskNormal = lrt::Normalize(
        lrt::Vector3f((*p.o2w)(lrt::Normal3f(0, 0, 1))));
    if (kind == 0) {
        p.shape.reset(new lrt::Sphere(p.o2w.get(), p.w2o.get(), false, r, -r,
                                      r, 360));
        p.fullSphere = true;
    } else if (kind == 1) {
        p.shape.reset(new lrt::Sphere(p.o2w.get(), p.w2o.get(), false, r,
                                      -0.6f * r, 0.8f * r, 250));
    } else {
        p.shape.reset(new lrt::Disk(p.o2w.get(), p.w2o.get(), false, 0.2f * r,
                                    r, 0.3f * r, 300));
    }
    return p;
}

const char *kKindNames[] = {"sphere", "partial sphere", "disk"};

// A primary ray toward a random point near the shape, from a few sizes away.
lrt::Ray PrimaryRay(Rng &rng, const Placed &p) {
    lrt::Float s = lrt::Float(p.size);
    lrt::Point3f target = p.center + s * lrt::Float(rng.U(0, 1.1)) * rng.Dir();
    lrt::Point3f o = p.center + s * lrt::Float(rng.U(2, 6)) * rng.Dir();
    return lrt::Ray(o, target - o);
}

// A textbook ray tracer's intersection routines, in plain floating point:
// they accept any root whose computed value is positive. Used to show what
// a fixed offset is up against without conservative bounds on t.
bool TextbookSphere(const lrt::Ray &r, const lrt::Point3f &c, lrt::Float R) {
    lrt::Vector3f oc = r.o - c;
    lrt::Float a = lrt::Dot(r.d, r.d), b = lrt::Dot(oc, r.d);
    lrt::Float cc = lrt::Dot(oc, oc) - R * R;
    lrt::Float disc = b * b - a * cc;
    if (!(disc >= 0)) return false;
    lrt::Float sq = std::sqrt(disc);
    return (-b - sq) / a > 0 || (-b + sq) / a > 0;
}

bool TextbookDisk(const lrt::Ray &r, const lrt::Point3f &c,
                  const lrt::Vector3f &n, lrt::Float rMax, lrt::Float rMin) {
    lrt::Float dn = lrt::Dot(r.d, n);
    if (dn == 0) return false;
    lrt::Float t = lrt::Dot(c - r.o, n) / dn;
    if (!(t > 0)) return false;
    lrt::Float dist = lrt::Distance(r(t), c);
    return dist <= rMax && dist >= rMin;
}

struct Counts {
    long spawned = 0, robustHits = 0, fixedHits = 0, noOffsetHits = 0;
    long inward = 0, inwardWrong = 0, uncertain = 0, uncertainHits = 0;
    long textbookFixed = 0, textbookOffset = 0;
    double pErrorSum = 0;
    long hits = 0;
};

}  // namespace

EXERCISE_TEST(Ex3_22_Reintersection, SpawnedRaysNeverRehitTheirSurface) {
    Rng rng(lrt::calls::Seed(340));
    const int hitsPerShape = lrt::calls::Cases(kHitsPerShape, 250);
    std::vector<double> scales = Scales();
    std::printf("[ spawn    ] %-8s %-15s %7s %11s %9s %9s %9s %9s %9s %s\n",
                "scale", "shape", "spawned", "mean pError", "lrt+offs",
                "lrt+eps", "lrt+none", "text+eps", "text+offs", "grazing");
    long total = 0, largestFixed = 0, smallestFixed = 0;
    for (double s : scales) {
        for (int kind = 0; kind < 3; ++kind) {
            Counts c;
            for (int placement = 0; placement < 4; ++placement) {
                Placed p = Place(rng, kind, s, placement & 1, placement & 2);
                for (int h = 0; h < hitsPerShape; ++h) {
                    lrt::Ray ray = PrimaryRay(rng, p);
                    lrt::Float tHit;
                    lrt::SurfaceInteraction si;
                    if (!p.shape->Intersect(ray, &tHit, &si)) continue;
                    ++c.hits;
                    c.pErrorSum += si.pError.Length();
                    lrt::Vector3f n(si.n);
                    // The side of the surface the primary ray came from, for
                    // a closed sphere the outside.
                    lrt::Vector3f side =
                        (lrt::Dot(n, ray.d) < 0) ? n : -n;
                    // The direction of the exact outward normal of a
                    // sphere is known only to within the error of the hit
                    // point relative to the radius.
                    double R = p.size, cone = 0;
                    if (kind < 2) {
                        cone = 4 * si.pError.Length() / R + 1e-6;
                        side = n;
                    }
                    for (int k = 0; k < kSpawnedPerHit; ++k) {
                        lrt::Vector3f w = rng.Hemisphere(side);
                        // Disks: both sides. Spheres: directions on the
                        // outside of the normal, which leave the convex
                        // surface for good unless they are so close to the
                        // tangent plane that they might in fact point
                        // inside; those are counted apart.
                        if (kind == 2 && k % 2) w = -w;
                        bool uncertain = false;
                        if (kind < 2) {
                            lrt::Vector3f out = lrt::Normalize(si.p - p.center);
                            uncertain = lrt::Dot(w, out) < cone;
                        }
                        lrt::Ray robust = lrt::ex::SpawnRay(si, w);
                        lrt::Float t2;
                        lrt::SurfaceInteraction si2;
                        bool again = p.shape->Intersect(robust, &t2, &si2);
                        EXPECT_EQ(again, p.shape->IntersectP(robust));
                        if (uncertain) {
                            ++c.uncertain;
                            if (again) ++c.uncertainHits;
                            continue;
                        }
                        ++c.spawned;
                        if (again) {
                            ++c.robustHits;
                            if (c.robustHits <= 3)
                                ADD_FAILURE()
                                    << kKindNames[kind] << " at scale " << s
                                    << ": spawned ray " << robust
                                    << " hit again at t=" << t2;
                        }
                        lrt::Float sgn = lrt::Dot(w, n) < 0 ? -1 : 1;
                        lrt::Ray fixed(si.p + sgn * kFixedEpsilon * n, w);
                        if (p.shape->IntersectP(fixed)) ++c.fixedHits;
                        if (p.shape->IntersectP(lrt::Ray(si.p, w)))
                            ++c.noOffsetHits;
                        if (kind == 0) {
                            lrt::Float Rw = lrt::Float(p.size);
                            c.textbookFixed +=
                                TextbookSphere(fixed, p.center, Rw);
                            c.textbookOffset +=
                                TextbookSphere(robust, p.center, Rw);
                        } else if (kind == 2) {
                            lrt::Float Rw = lrt::Float(p.size);
                            c.textbookFixed += TextbookDisk(
                                fixed, p.diskCenter, p.diskNormal, Rw,
                                0.3f * Rw);
                            c.textbookOffset += TextbookDisk(
                                robust, p.diskCenter, p.diskNormal, Rw,
                                0.3f * Rw);
                        }
                    }
                    // A full sphere, left inward at a steep angle: the ray
                    // must cross the whole sphere and hit the far side.
                    if (p.fullSphere) {
                        lrt::Vector3f out = lrt::Normalize(si.p - p.center);
                        lrt::Vector3f w = rng.Hemisphere(-out);
                        lrt::Float cosA = -lrt::Dot(w, out);
                        if (cosA < 0.1f) continue;
                        ++c.inward;
                        lrt::Float t2;
                        lrt::SurfaceInteraction si2;
                        lrt::Float R = lrt::Distance(si.p, p.center);
                        bool hit = p.shape->Intersect(lrt::ex::SpawnRay(si, w),
                                                      &t2, &si2);
                        // The chord's computed length is uncertain by the
                        // rounding error of the origin's coordinates, which
                        // for a small sphere far from the world's origin is
                        // large compared with the radius.
                        lrt::Point3f q = si.p;
                        lrt::Float mag = std::abs(q.x) + std::abs(q.y) +
                                         std::abs(q.z) + R;
                        lrt::Float tol = 1e-3f * R +
                                         20 * lrt::MachineEpsilon * mag / cosA;
                        if (!hit || std::abs(t2 - 2 * R * cosA) > tol)
                            ++c.inwardWrong;
                    }
                }
            }
            total += c.spawned;
            std::printf("[ spawn    ] %-8.3g %-15s %7ld %11.3g %9ld %9ld "
                        "%9ld %9ld %9ld %6ld/%ld\n", s, kKindNames[kind],
                        c.spawned, c.pErrorSum / std::max(c.hits, 1L),
                        c.robustHits, c.fixedHits, c.noOffsetHits,
                        c.textbookFixed, c.textbookOffset, c.uncertainHits,
                        c.uncertain);
            if (s == scales.back() && kind != 1) largestFixed += c.textbookFixed;
            if (s == scales.front() && kind != 1) smallestFixed += c.textbookFixed;
            EXPECT_EQ(c.robustHits, 0) << kKindNames[kind] << " scale " << s;
            EXPECT_EQ(c.inwardWrong, 0) << kKindNames[kind] << " scale " << s;
            EXPECT_GT(c.spawned, hitsPerShape);
        }
    }
    std::printf("[ spawn    ] %ld spawned rays in all\n", total);
    // A fixed offset protects a textbook intersector at small scales but
    // not at the largest, where rounding errors exceed it.
    EXPECT_EQ(smallestFixed, 0);
    EXPECT_GT(largestFixed, hitsPerShape / 10);
}

EXERCISE_TEST(Ex3_22_Reintersection, ShadowRaysBetweenPointsOfOneSurface) {
    // Segments between two points of a convex sphere run through its
    // inside, and segments between two points of a disk lie in its plane:
    // with both ends offset, neither may be blocked by the surface itself.
    Rng rng(lrt::calls::Seed(341));
    long tested = 0;
    for (double s : Scales()) {
        for (int kind : {0, 2}) {
            Placed p = Place(rng, kind, s, tested % 2, false);
            std::vector<lrt::SurfaceInteraction> pts;
            for (int h = 0; h < 200 && pts.size() < 100; ++h) {
                lrt::Ray ray = PrimaryRay(rng, p);
                lrt::Float t;
                lrt::SurfaceInteraction si;
                if (p.shape->Intersect(ray, &t, &si)) pts.push_back(si);
            }
            for (size_t i = 0; i + 1 < pts.size(); ++i) {
                lrt::Ray r = lrt::ex::SpawnRayTo(pts[i], pts[i + 1]);
                EXPECT_FALSE(p.shape->IntersectP(r))
                    << kKindNames[kind] << " at scale " << s;
                ++tested;
            }
        }
    }
    EXPECT_GT(tested, 1000);
}

EXERCISE_TEST(Ex3_22_FixedEpsilon, FailsAtLargeAndSmallScalesWhereOffsetsSucceed) {
    // Two parallel disks a small distance apart, like a floor and a thin
    // slab lying on it, with a light far above. Points on the floor under
    // the slab are in shadow. A shadow ray started a fixed distance above
    // the floor misses the slab when the gap is smaller than that distance
    // (a light leak); a ray spawned with OffsetRayOrigin() does not. Large
    // scales are covered by the self-intersection counts of the test above.
    Rng rng(lrt::calls::Seed(342));
    const int rays = lrt::calls::Cases(2000, 1000);
    std::printf("[ leak     ] %-8s %9s %12s %12s\n", "scale", "gap",
                "fixed eps", "robust");
    long leaksAtSmallest = -1;
    for (double s : Scales()) {
        lrt::Float gap = lrt::Float(0.02 * s);
        lrt::Vector3f tr = lrt::Float(3 * s) * rng.Dir();
        lrt::Transform o2w = lrt::Translate(tr) *
                             lrt::Rotate(rng.U(0, 360), rng.Dir());
        lrt::Transform w2o = Inverse(o2w);
        lrt::Float S = lrt::Float(s);
        lrt::Disk floor(&o2w, &w2o, false, 0, 2 * S, 0, 360);
        lrt::Disk slab(&o2w, &w2o, false, gap, 4 * S, 0, 360);
        lrt::Point3f light = o2w(lrt::Point3f(0, 0, 10 * S));
        long fixedLeaks = 0, robustLeaks = 0, shots = 0;
        for (int i = 0; i < rays; ++i) {
            // A ray from inside the gap down to the floor.
            double a = rng.U(0, 2 * kPi), rho = s * std::sqrt(rng.U());
            lrt::Point3f o = o2w(lrt::Point3f(rho * std::cos(a),
                                              rho * std::sin(a), gap / 2));
            lrt::Vector3f d = o2w(lrt::Vector3f(rng.U(-1, 1), rng.U(-1, 1),
                                                -1));
            lrt::Float t;
            lrt::SurfaceInteraction si;
            if (!floor.Intersect(lrt::Ray(o, d), &t, &si)) continue;
            ++shots;
            lrt::Ray robust = lrt::ex::SpawnRayTo(si, light);
            if (!slab.IntersectP(robust)) ++robustLeaks;
            EXPECT_FALSE(floor.IntersectP(robust));
            lrt::Vector3f n(si.n);
            if (lrt::Dot(n, light - si.p) < 0) n = -n;
            lrt::Point3f biased = si.p + kFixedEpsilon * n;
            lrt::Ray fixed(biased, light - biased, 1 - lrt::ShadowEpsilon);
            if (!slab.IntersectP(fixed)) ++fixedLeaks;
        }
        std::printf("[ leak     ] %-8.3g %9.3g %5ld/%-6ld %5ld/%-6ld\n", s,
                    (double)gap, fixedLeaks, shots, robustLeaks, shots);
        EXPECT_EQ(robustLeaks, 0) << "scale " << s;
        EXPECT_GT(shots, rays / 2);
        if (leaksAtSmallest < 0) leaksAtSmallest = fixedLeaks;
    }
    // At the smallest scale the gap, 2e-5, is below the fixed offset, and
    // every shadow ray leaks.
    EXPECT_GT(leaksAtSmallest, rays / 2);
}
