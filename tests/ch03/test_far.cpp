// Spheres and disks far from the ray's origin, against a long-double oracle:
// the hit-or-miss decision of a sphere, its distance, the comparison with
// tMax, and the rays of two reported failures.
//
// The oracle takes the world ray as lrt rounds it to Float and maps it into
// object space with the Float matrix that the shape uses, in long double
// (exact for a translation, and 2^-40 more accurate than float otherwise).
// The bands within which a correct Float computation may decide either way
// are those the chapter derives (Section "Spheres Far from the Ray's
// Origin"); the tests count the decisions inside the bands and fail on any
// wrong decision outside them.
#include "lrt/shapes/sphere.h"
#include "lrt/shapes/disk.h"

#include <gtest/gtest.h>

#include "exercise_calls.h"
#include "quadric_oracle.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <memory>
#include <random>
#include <string>
#include <vector>

namespace {

// The exponent of the smallest relative offsets of the random rays: a tenth
// of machine epsilon, 6e-9 for float and 1e-17 for double.
const double kLogEps = std::log10((double)lrt::MachineEpsilon) - 1;

// The exact intersection of a line with a sphere of radius r at the
// origin, and the chapter's bounds on the errors of a Float computation.
struct SphereOracle {
    LD m = 0;           // distance of the line from the center
    LD t0 = 0, t1 = 0;  // roots, t0 <= t1, when m <= r
    bool line = false;  // the line meets the sphere
    // The decision band: a computed |f| is within w of m.
    LD w = 0;
    LD tHalfChord = 0;  // half the chord, as a distance (0 for a miss)
    LD K = 0;           // signed distance to the closest point along the ray
};

SphereOracle Intersect(const ObjectRay &ray, LD r) {
    SphereOracle s;
    LD a = dot3(ray.d, ray.d), dl = std::sqrt(a);
    LD k = -dot3(ray.o, ray.d) / a;
    L3 f = ray.o + k * ray.d;
    s.m = len3(f);
    s.K = k * dl;
    LD ol = len3(ray.o);
    s.w = Gamma(8) * ol + Gamma(4) * r + len3(ray.e) + ol * len3(ray.g) / dl;
    s.line = s.m <= r;
    if (!s.line) return s;
    LD h = std::sqrt((r - s.m) * (r + s.m) / a);
    s.tHalfChord = h * dl;
    LD c = (ol - r) * (ol + r);
    if (k >= 0) {
        s.t1 = k + h;
        s.t0 = c / (a * s.t1);
    } else {
        s.t0 = k - h;
        s.t1 = c / (a * s.t0);
    }
    return s;
}

// The chapter's bound on the error of the computed distance to a root,
// measured along the ray: the rounding of c and q and the error of the
// half chord, which grows near grazing incidence.
LD DistanceBound(const ObjectRay &ray, const SphereOracle &s, LD r, LD t) {
    LD dl = len3(ray.d), ol = len3(ray.o), el = len3(ray.e);
    LD dist = std::abs(t) * dl, hc = s.tHalfChord;
    return (Gamma(4) * ol * ol + Gamma(2) * r * r + 2 * ol * el) /
               (std::abs(s.K) + hc) +
           Gamma(3) * ol + el + ol * len3(ray.g) / dl + r * s.w / hc +
           Gamma(5) * (hc + dist);
}

// A random unit vector, and a random unit vector perpendicular to v.
L3 Dir(Rng &rng) {
    D3 u = rng.Dir();
    return L3(u.x, u.y, u.z);
}
L3 Perpendicular(Rng &rng, L3 v) {
    L3 u = Dir(rng);
    L3 p = u - (dot3(u, v) / dot3(v, v)) * v;
    return (1 / len3(p)) * p;
}

// A sphere with its transformations, translated to c and, if rotate, turned
// about a random axis.
struct PlacedSphere {
    std::unique_ptr<lrt::Transform> o2w, w2o;
    std::unique_ptr<lrt::Sphere> sphere;
    LD r;
    PlacedSphere(Rng &rng, L3 c, double radius, bool rotate) {
        lrt::Transform t = lrt::Translate(ToV(c));
        if (rotate)
            t = t * lrt::Rotate(lrt::Float(rng.U(0, 360)), ToV(Dir(rng)));
        o2w.reset(new lrt::Transform(t));
        w2o.reset(new lrt::Transform(Inverse(t)));
        lrt::Float rf = lrt::Float(radius);
        sphere.reset(
            new lrt::Sphere(o2w.get(), w2o.get(), false, rf, -rf, rf, 360));
        r = rf;
    }
};

// What one distance's rays found, for the rays aimed uniformly at the
// sphere ([0]) and at its silhouette ([1]).
struct Tally {
    long rays[2] = {0, 0}, inBand[2] = {0, 0}, wrong[2] = {0, 0};
    long wrongOutside[2] = {0, 0};
    double maxWrongRatio = 0;  // largest |m - r| / w of a wrong decision
    long tMaxDecisions = 0, tMaxWrong = 0, tMaxWrongOutside = 0;
    long tChecked = 0, tFailures = 0;
    double maxTRatio = 0;  // largest distance error over its bound
};

const double kDistances[] = {1e0, 1e1, 1e2, 1e3, 1e4};
constexpr int kSpheresPerDistance = 250;
constexpr int kRaysPerSphere = 40;

// Random rays from near the world origin at spheres whose centers are at
// distance D from it (radii 0.3 to 3, a tenth of that at D = 1), half of
// them rotated. Of the rays, 40% pass the center at distances uniform over
// the disk of radius 1.5 r, and 60% within a relative 6e-9 to 0.3 of the
// silhouette (1e-17 in double precision), inside or outside; every fourth
// ray that meets the sphere has a finite tMax within a relative 6e-8
// (1e-16) to 1e-3 of the oracle's hit. The length of the direction varies
// from 0.2 to 5.
Tally RunDistance(double D, uint64_t seed) {
    Rng rng(seed);
    Tally tl;
    double scale = std::min(1.0, D / 10);
    for (int s = 0; s < kSpheresPerDistance; ++s) {
        L3 c = D * Dir(rng);
        PlacedSphere ps(rng, c, scale * rng.U(0.3, 3), s % 2 == 1);
        for (int i = 0; i < kRaysPerSphere; ++i) {
            L3 o(rng.U(-0.5, 0.5) * scale, rng.U(-0.5, 0.5) * scale,
                 rng.U(-0.5, 0.5) * scale);
            L3 toC = c - o;
            int kind = i % 5 < 2 ? 0 : 1;
            double mt =
                kind == 0
                    ? 1.5 * ps.r * std::sqrt(rng.U())
                    : ps.r * (1 + (rng.U() < 0.5 ? -1 : 1) *
                                      std::pow(10.0, rng.U(kLogEps, -0.5)));
            // The direction from o at the angle whose sine is mt / |c - o|
            // to the center passes mt from it.
            LD sinA = mt / len3(toC), cosA = std::sqrt(1 - sinA * sinA);
            L3 dir = (cosA / len3(toC)) * toC + sinA * Perpendicular(rng, toC);
            lrt::Ray ray(ToP(o), ToV((LD)rng.U(0.2, 5) * dir));
            ObjectRay ob = ToObject(*ps.w2o, ray);
            SphereOracle orc = Intersect(ob, ps.r);
            bool finiteTMax = i % 4 == 3 && orc.line;
            if (finiteTMax) {
                LD rel = std::pow(10.0, rng.U(kLogEps + 1, -3)) *
                         (rng.U() < 0.5 ? -1 : 1);
                ray.tMax = lrt::Float(orc.t0 * (1 + rel));
            }
            lrt::Float tHit = -1;
            lrt::SurfaceInteraction si;
            bool hit = ps.sphere->Intersect(ray, &tHit, &si);
            EXPECT_EQ(hit, ps.sphere->IntersectP(ray));
            // The ray starts outside, and the sphere is in front.
            EXPECT_GT(orc.K, len3(ob.o) * 0.5);
            bool inBand = std::abs(orc.m - ps.r) <= orc.w;
            if (finiteTMax) {
                // The comparison with tMax is right outside the distance's
                // error bound (and that of the hit-or-miss decision).
                ++tl.tMaxDecisions;
                if (inBand) continue;
                LD bound = DistanceBound(ob, orc, ps.r, orc.t0) / len3(ob.d);
                if (hit != (orc.t0 <= ray.tMax)) {
                    ++tl.tMaxWrong;
                    if (std::abs(orc.t0 - ray.tMax) > bound &&
                        tl.tMaxWrongOutside++ < 5)
                        ADD_FAILURE()
                            << "D = " << D << ": " << (hit ? "hit" : "miss")
                            << " with tMax " << ray.tMax << ", exact t "
                            << (double)orc.t0 << ", error bound "
                            << (double)bound;
                }
                continue;
            }
            ++tl.rays[kind];
            tl.inBand[kind] += inBand;
            if (hit != orc.line) {
                ++tl.wrong[kind];
                double ratio = double(std::abs(orc.m - ps.r) / orc.w);
                tl.maxWrongRatio = std::max(tl.maxWrongRatio, ratio);
                if (!inBand && tl.wrongOutside[kind]++ < 5)
                    ADD_FAILURE()
                        << "D = " << D << ": lrt says "
                        << (hit ? "hit" : "miss") << " at t = " << tHit
                        << ", the line passes " << (double)orc.m
                        << " from the center, r = " << (double)ps.r << ", band "
                        << (double)orc.w << "; ray " << ray;
                continue;
            }
            if (hit && !inBand) {
                ++tl.tChecked;
                LD bound = DistanceBound(ob, orc, ps.r, orc.t0);
                LD err = std::abs(tHit - orc.t0) * len3(ob.d);
                tl.maxTRatio = std::max(tl.maxTRatio, double(err / bound));
                if (err > bound && tl.tFailures++ < 5)
                    ADD_FAILURE()
                        << "D = " << D << ": t = " << tHit << ", exact "
                        << (double)orc.t0 << ", error bound " << (double)bound;
            }
        }
    }
    std::printf(
        "[ far      ] D = %-5g wrong hit or miss: %4ld of %ld aimed "
        "uniformly (%ld outside the band), %4ld of %ld at the "
        "silhouette (%ld in the band, %ld wrong outside it; largest "
        "|m - r| of a wrong one %.3g w); wrong tMax decisions %ld of "
        "%ld (%ld outside the bound); t errors up to %.3g of the "
        "bound (%ld hits)\n",
        D, tl.wrong[0], tl.rays[0], tl.wrongOutside[0], tl.wrong[1], tl.rays[1],
        tl.inBand[1], tl.wrongOutside[1], tl.maxWrongRatio, tl.tMaxWrong,
        tl.tMaxDecisions, tl.tMaxWrongOutside, tl.maxTRatio, tl.tChecked);
    return tl;
}

// The closest of several shapes, found by testing them in the given order
// with a shrinking tMax, as an accelerator does.
const lrt::Shape *Closest(const std::vector<const lrt::Shape *> &shapes,
                          lrt::Ray ray, lrt::Float *t) {
    const lrt::Shape *closest = nullptr;
    for (const lrt::Shape *s : shapes) {
        lrt::Float tHit;
        lrt::SurfaceInteraction si;
        if (s->Intersect(ray, &tHit, &si)) {
            EXPECT_LE(tHit, ray.tMax);
            ray.tMax = tHit;
            closest = s;
        }
    }
    *t = ray.tMax;
    return closest;
}

}  // namespace

TEST(SphereFar, HitOrMissMatchesLongDoubleOutsideTheBand) {
    for (int k = 0; k < 5; ++k) {
        Tally tl = RunDistance(kDistances[k], 3100 + k);
        SCOPED_TRACE(kDistances[k]);
        EXPECT_EQ(tl.wrongOutside[0] + tl.wrongOutside[1], 0);
        EXPECT_EQ(tl.tMaxWrongOutside, 0);
        EXPECT_EQ(tl.tFailures, 0);
        // The rays must exercise the band, the uniform part and tMax.
        EXPECT_GT(tl.inBand[1], tl.rays[1] / 10);
        EXPECT_GT(tl.tChecked, tl.rays[0] / 2);
        EXPECT_GT(tl.tMaxDecisions, 500);
    }
}

// Rays from near the surface of spheres of radius 1 to 1e4, from inside
// and outside, in random directions: a root whose exact distance is not
// positive is never reported, and a root farther than its error bound from
// the origin is found.
TEST(SphereFar, RaysStartingNearHugeSpheres) {
    Rng rng(3110);
    long rays = 0, ambiguous = 0, failures = 0, nearZero = 0;
    for (int k = 0; k < 5; ++k) {
        double R = kDistances[k];
        for (int s = 0; s < 100; ++s) {
            L3 c = (R * rng.U(0, 2)) * Dir(rng);
            PlacedSphere ps(rng, c, R * rng.U(0.5, 1.5), s % 2 == 1);
            for (int i = 0; i < 40; ++i) {
                double rel =
                    (i % 2 ? 1 : -1) * std::pow(10.0, rng.U(kLogEps + 1, -0.5));
                L3 o = c + (LD)(ps.r * (1 + rel)) * Dir(rng);
                lrt::Ray ray(ToP(o), ToV((LD)rng.U(0.2, 5) * Dir(rng)));
                ObjectRay ob = ToObject(*ps.w2o, ray);
                SphereOracle orc = Intersect(ob, ps.r);
                lrt::Float tHit = -1;
                lrt::SurfaceInteraction si;
                bool hit = ps.sphere->Intersect(ray, &tHit, &si);
                EXPECT_EQ(hit, ps.sphere->IntersectP(ray));
                ++rays;
                LD dl = len3(ob.d);
                // A hit must be one of the roots, and a root in front.
                if (hit) {
                    if (!orc.line && std::abs(orc.m - ps.r) > orc.w) {
                        if (failures++ < 5)
                            ADD_FAILURE()
                                << "R = " << R << ": hit at t = " << tHit
                                << ", but the line misses "
                                << "by " << double(orc.m - ps.r);
                        continue;
                    }
                    if (!orc.line) {
                        ++ambiguous;
                        continue;
                    }
                    bool near0 =
                        std::abs(tHit - orc.t0) <= std::abs(tHit - orc.t1);
                    LD root = near0 ? orc.t0 : orc.t1;
                    if (!(root > 0)) {
                        if (failures++ < 5)
                            ADD_FAILURE()
                                << "R = " << R << ": reported t = " << tHit
                                << " is a root at exact t = " << (double)root;
                        continue;
                    }
                }
                // Which root a correct computation must find, if it is
                // certain: the first root farther than its bound.
                bool certain = std::abs(orc.m - ps.r) > orc.w;
                LD expectT = -1;
                if (certain && orc.line) {
                    for (LD t : {orc.t0, orc.t1}) {
                        LD b = DistanceBound(ob, orc, ps.r, t) / dl;
                        if (std::abs(t) <= 2 * b) {
                            certain = false;
                            ++nearZero;
                            break;
                        }
                        if (t > 0) {
                            expectT = t;
                            break;
                        }
                    }
                }
                if (!certain) {
                    ++ambiguous;
                    continue;
                }
                bool expected = expectT > 0;
                if (hit != expected ||
                    (hit && std::abs(tHit - expectT) * dl >
                                DistanceBound(ob, orc, ps.r, expectT))) {
                    if (failures++ < 5)
                        ADD_FAILURE()
                            << "R = " << R << ": lrt " << (hit ? "hit" : "miss")
                            << " t = " << tHit << ", expected "
                            << (expected ? "hit" : "miss")
                            << " t = " << (double)expectT << "; ray " << ray;
                }
            }
        }
    }
    std::printf(
        "[ far      ] rays from near huge spheres: %ld rays, %ld "
        "undecided (%ld with a root within its bound of zero), %ld "
        "failures\n",
        rays, ambiguous, nearZero, failures);
    EXPECT_EQ(failures, 0);
    EXPECT_LT(ambiguous, rays / 2);
}

// The ray of a reported failure: it passes 0.440 from the center of a
// sphere of radius 0.349, about 1,000 units away, and must miss it.
TEST(SphereFar, DistantMissIsAMiss) {
    Rng rng(0);
    lrt::Transform o2w =
        lrt::Translate(lrt::Vector3f(1001.685f, 2.416f, 1.018f));
    lrt::Transform w2o = Inverse(o2w);
    lrt::Sphere s(&o2w, &w2o, false, 0.34888f, -0.34888f, 0.34888f, 360);
    lrt::Ray ray(lrt::Point3f(-9.32228088f, -15.9393663f, -18.6916981f),
                 lrt::Vector3f(0.993147433f, 0.0182505064f, 0.0189888962f));
    SphereOracle orc = Intersect(ToObject(w2o, ray), 0.34888f);
    EXPECT_NEAR((double)orc.m, 0.440, 1e-3);
    lrt::Float tHit = -1;
    lrt::SurfaceInteraction si;
    EXPECT_FALSE(s.Intersect(ray, &tHit, &si)) << "t = " << tHit;
    EXPECT_FALSE(s.IntersectP(ray));
}

// The other ray of that report: two spheres about 1,000 units away, whose
// hits are 0.98 apart along the ray. The nearer must be the closest hit
// whichever is tested first.
TEST(SphereFar, NearerOfTwoDistantSpheresWinsInEitherOrder) {
    lrt::Ray ray(lrt::Point3f(5.96165085f, 69.1183395f, -37.0091896f),
                 lrt::Vector3f(1.31817114f, -0.0912237391f, 0.0508610234f));
    lrt::Transform o2wA = lrt::Translate(lrt::Vector3f(1000.4f, -1.85f, 2.02f));
    lrt::Transform w2oA = Inverse(o2wA);
    lrt::Sphere a(&o2wA, &w2oA, false, 2.875f, -2.875f, 2.875f, 360);
    lrt::Float tA = -1;
    lrt::SurfaceInteraction si;
    ASSERT_TRUE(a.Intersect(ray, &tA, &si));
    SphereOracle orcA = Intersect(ToObject(w2oA, ray), 2.875f);
    EXPECT_NEAR(tA, (double)orcA.t0, 1e-6 * orcA.t0);
    // Sphere B, of radius 0.5, is centered on the ray's line so that the
    // ray enters it 0.984 (in units of t) after entering A.
    L3 o(ray.o.x, ray.o.y, ray.o.z), d(ray.d.x, ray.d.y, ray.d.z);
    LD tB = orcA.t0 + 0.984L;
    L3 cB = o + (tB + 0.5L / len3(d)) * d;
    lrt::Transform o2wB = lrt::Translate(ToV(cB));
    lrt::Transform w2oB = Inverse(o2wB);
    lrt::Sphere b(&o2wB, &w2oB, false, 0.5f, -0.5f, 0.5f, 360);
    lrt::Float t;
    EXPECT_EQ(Closest({&a, &b}, ray, &t), &a);
    EXPECT_EQ(t, tA);
    EXPECT_EQ(Closest({&b, &a}, ray, &t), &a) << "t = " << t;
    EXPECT_EQ(t, tA);
}

// Two parallel disks 1e-3 apart, turned about a random axis and moved 1e4
// away from the world origin, seen from a few units away: the rounding
// errors of the transformed origin make the interval of each disk's t far
// wider than the gap, but the nearer disk is the closest hit whichever is
// tested first.
TEST(DiskFar, NearerOfTwoCloseDisksWinsInEitherOrder) {
    Rng rng(3120);
    int checked = 0;
    for (int i = 0; i < 200; ++i) {
        lrt::Transform o2w =
            lrt::Translate(ToV((LD)1e4 * Dir(rng))) *
            lrt::Rotate(lrt::Float(rng.U(0, 360)), ToV(Dir(rng)));
        lrt::Transform w2o = Inverse(o2w);
        lrt::Disk nearer(&o2w, &w2o, false, 0, 2, 0, 360);
        lrt::Disk farther(&o2w, &w2o, false, -1e-3f, 2, 0, 360);
        // From 3 to 5 units above the disks, at a point within radius 1.
        L3 target(rng.U(-0.7, 0.7), rng.U(-0.7, 0.7), 0);
        L3 from = target +
                  (LD)rng.U(3, 5) * L3(rng.U(-0.5, 0.5), rng.U(-0.5, 0.5), 1);
        lrt::Point3f o = o2w(ToP(from));
        lrt::Vector3f d = o2w(ToP(target)) - o;
        lrt::Ray ray(o, d);
        lrt::Float tNear, tFar;
        lrt::SurfaceInteraction si;
        if (!nearer.Intersect(ray, &tNear, &si) ||
            !farther.Intersect(ray, &tFar, &si) || !(tNear < tFar))
            continue;  // the gap is too small to resolve along this ray
        ++checked;
        lrt::Float t;
        EXPECT_EQ(Closest({&nearer, &farther}, ray, &t), &nearer);
        EXPECT_EQ(t, tNear);
        EXPECT_EQ(Closest({&farther, &nearer}, ray, &t), &nearer)
            << "ray " << ray << ": t = " << t << ", nearer disk at " << tNear
            << ", farther at " << tFar;
        EXPECT_EQ(t, tNear);
    }
    EXPECT_GT(checked, 150);
}

namespace {

// The rule that every shape follows (Section "Which Hits Count"): a hit is
// accepted if and only if the distance the shape reports is at most tMax. A
// ray that hits at t must hit at the same t with tMax = t, and miss with
// tMax one floating-point number below t; then testing shapes in any order
// with a shrinking tMax finds the least distance. Shapes near and far from
// the world origin, translated up to 1e4 and rotated; kinds 0, 1 and 2 are
// partial spheres, rings and triangles. Returns the number of hits checked.
// What a shape answers for a ray: Intersect()'s verdict and distance, and
// IntersectP()'s verdict.
struct Answer {
    bool hit = false, hitP = false;
    lrt::Float t = 0;
};

long CheckTMaxRule(int kind, uint64_t seed) {
    Rng rng(seed);
    const char *names[3] = {"sphere", "disk", "triangle"};
    long checked = 0, failures = 0;
    for (int i = 0; i < 1000; ++i) {
        double D = std::pow(10.0, rng.U(0, 4));
        L3 c = D * Dir(rng);
        lrt::Transform o2w =
            lrt::Translate(ToV(c)) *
            lrt::Rotate(lrt::Float(rng.U(0, 360)), ToV(Dir(rng)));
        lrt::Transform w2o = Inverse(o2w);
        std::shared_ptr<lrt::Shape> shape;
        lrt::MeshSpec triangle;
        if (kind == 0) {
            shape = std::make_shared<lrt::Sphere>(&o2w, &w2o, false, 1.5f, -1,
                                                  1.5f, 300);
        } else if (kind == 1) {
            shape = std::make_shared<lrt::Disk>(&o2w, &w2o, false, 0.2f, 1.5f,
                                                0.3f, 300);
        } else {
            // A world-space triangle, asked through ex-3.23's calls.
            triangle.p = {o2w(lrt::Point3f(-1.5f, -1, 0)),
                          o2w(lrt::Point3f(1.5f, -1, 0.2f)),
                          o2w(lrt::Point3f(0, 1.5f, -0.3f))};
            triangle.indices = {0, 1, 2};
        }
        auto ask = [&](const lrt::Ray &r) {
            Answer a;
            if (shape) {
                lrt::SurfaceInteraction si;
                a.hit = shape->Intersect(r, &a.t, &si);
                a.hitP = shape->IntersectP(r);
            } else {
                lrt::TriangleHit h = lrt::ex::IntersectTriangleOf(triangle, 0, r, 0);
                a = Answer{h.hit, h.hitP, h.tHit};
            }
            return a;
        };
        // From near the world origin or from near the shape.
        L3 o = (i % 2) ? L3(rng.U(-1, 1), rng.U(-1, 1), rng.U(-1, 1))
                       : c + (LD)rng.U(2, 10) * Dir(rng);
        L3 target = c + (LD)rng.U(0, 1.5) * Dir(rng);
        lrt::Ray ray(ToP(o), ToV((LD)rng.U(0.2, 5) * (target - o)));
        Answer first = ask(ray);
        if (!first.hit) continue;
        ++checked;
        const lrt::Float t = first.t;
        ray.tMax = t;
        Answer at = ask(ray);
        bool atT = at.hit && at.t == t && at.hitP;
        ray.tMax = lrt::NextFloatDown(t);
        Answer past = ask(ray);
        bool below = past.hit || past.hitP;
        if ((!atT || below) && failures++ < 5)
            ADD_FAILURE() << names[kind] << " hit at t = " << t
                          << ": with tMax = t " << (atT ? "hit" : "no hit at t")
                          << ", with tMax one below "
                          << (below ? "hit" : "no hit");
    }
    std::printf("[ tMax     ] %ld %s hits checked, %ld failures\n", checked,
                names[kind], failures);
    EXPECT_EQ(failures, 0);
    return checked;
}

}  // namespace

TEST(ShapeTMax, SpheresAndDisksAcceptAHitExactlyWhenItIsAtMostTMax) {
    EXPECT_GT(CheckTMaxRule(0, 3130), 300);
    EXPECT_GT(CheckTMaxRule(1, 3131), 300);
}

// The same rule for triangles, whose test uses the code of exercise ex-3.23.
EXERCISE_TEST(Ex3_23_TriangleTMax, AHitIsAcceptedExactlyWhenItIsAtMostTMax) {
    EXPECT_GT(CheckTMaxRule(2, lrt::calls::Seed(3132)), 300);
}
