// Tests of the Shape interface, of OffsetRayOrigin() and of the
// Interaction::SpawnRay*() methods. The tests of OffsetRayOrigin() and of
// the methods that call it belong to exercise ex-3.22 (suites Ex3_22_*) and
// reach that code through the exercise calls of exercise_calls.h.
#include "lrt/shapes/sphere.h"
#include "lrt/shapes/disk.h"

#include "exercise_calls.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

namespace {

typedef long double LD;

constexpr int kOffsetCases = 100000;

// A minimal shape for testing the interface's default methods: an
// unbounded plane z = 0 in object space, which counts its calls.
class CountingPlane : public lrt::Shape {
  public:
    CountingPlane(const lrt::Transform *o2w, const lrt::Transform *w2o)
        : Shape(o2w, w2o, false) {}
    lrt::Bounds3f ObjectBound() const override {
        return lrt::Bounds3f(lrt::Point3f(-1, -2, 0), lrt::Point3f(3, 4, 0.5f));
    }
    bool Intersect(const lrt::Ray &r, lrt::Float *tHit,
                   lrt::SurfaceInteraction *isect, bool alpha) const override {
        ++calls;
        lastAlpha = alpha;
        lrt::Ray ray = (*WorldToObject)(r);
        if (ray.d.z == 0) return false;
        lrt::Float t = -ray.o.z / ray.d.z;
        if (!(t > 0 && t < ray.tMax)) return false;
        *tHit = t;
        *isect = lrt::SurfaceInteraction(
            ray(t), lrt::Vector3f(0, 0, 0), lrt::Point2f(0, 0), -ray.d,
            lrt::Vector3f(1, 0, 0), lrt::Vector3f(0, 1, 0),
            lrt::Normal3f(0, 0, 0), lrt::Normal3f(0, 0, 0), ray.time, false);
        return true;
    }
    // Not part of the interface as of chapter 3; chapter 4 makes it a pure
    // virtual method of Shape, which this then overrides.
    lrt::Float Area() const { return 0; }
    mutable int calls = 0;
    mutable bool lastAlpha = false;
};

struct Rng {
    std::mt19937_64 g;
    explicit Rng(uint64_t seed) : g(seed) {}
    double U(double a = 0, double b = 1) {
        return std::uniform_real_distribution<double>(a, b)(g);
    }
    lrt::Vector3f Dir() {
        double z = U(-1, 1), phi = U(0, 6.283185307179586);
        double s = std::sqrt(1 - z * z);
        return lrt::Vector3f(s * std::cos(phi), s * std::sin(phi), z);
    }
};

}  // namespace

TEST(Shape, RejectsNullTransforms) {
    lrt::Transform id;
    EXPECT_THROW(CountingPlane(nullptr, &id), std::invalid_argument);
    EXPECT_THROW(CountingPlane(&id, nullptr), std::invalid_argument);
    EXPECT_NO_THROW(CountingPlane(&id, &id));
}

TEST(Shape, TransformSwapsHandedness) {
    lrt::Transform id, mirror = lrt::Scale(-1, 1, 1),
                       rot = lrt::Rotate(40, lrt::Vector3f(1, 2, 3));
    lrt::Transform mirrorInv = Inverse(mirror), rotInv = Inverse(rot);
    lrt::Transform both = rot * mirror, bothInv = Inverse(both);
    lrt::Transform twice = mirror * lrt::Scale(1, -2, 1);
    lrt::Transform twiceInv = Inverse(twice);
    EXPECT_FALSE(CountingPlane(&id, &id).transformSwapsHandedness);
    EXPECT_TRUE(CountingPlane(&mirror, &mirrorInv).transformSwapsHandedness);
    EXPECT_FALSE(CountingPlane(&rot, &rotInv).transformSwapsHandedness);
    EXPECT_TRUE(CountingPlane(&both, &bothInv).transformSwapsHandedness);
    EXPECT_FALSE(CountingPlane(&twice, &twiceInv).transformSwapsHandedness);
    lrt::Sphere s(&mirror, &mirrorInv, true, 1, -1, 1, 360);
    EXPECT_TRUE(s.transformSwapsHandedness);
    EXPECT_TRUE(s.reverseOrientation);
}

TEST(Shape, WorldBoundTransformsObjectBound) {
    lrt::Transform t = lrt::Translate(lrt::Vector3f(1, 2, 3)) *
                       lrt::Rotate(30, lrt::Vector3f(0, 1, 1));
    lrt::Transform tInv = Inverse(t);
    CountingPlane p(&t, &tInv);
    lrt::Bounds3f wb = p.WorldBound(), expect = t(p.ObjectBound());
    EXPECT_EQ(wb.pMin, expect.pMin);
    EXPECT_EQ(wb.pMax, expect.pMax);
}

TEST(Shape, WorldBoundsContainTheShapes) {
    // Points sampled on spheres and disks under random transformations lie
    // inside the world bounds.
    Rng rng(330);
    for (int k = 0; k < 50; ++k) {
        lrt::Vector3f tr(rng.U(-10, 10), rng.U(-10, 10), rng.U(-10, 10));
        lrt::Transform t = lrt::Translate(tr) *
                           lrt::Rotate(rng.U(0, 360), rng.Dir()) *
                           lrt::Scale(rng.U(0.2, 3), rng.U(0.2, 3),
                                      rng.U(0.2, 3) * (k % 2 ? -1 : 1));
        lrt::Transform tInv = Inverse(t);
        lrt::Sphere sphere(&t, &tInv, false, 1.5f, -0.5f, 1.2f, 270);
        lrt::Disk disk(&t, &tInv, false, 0.7f, 2, 0.5f, 300);
        lrt::Bounds3f sb = sphere.WorldBound(), db = disk.WorldBound();
        lrt::Float tol = 1e-5f * 20;
        for (int i = 0; i < 200; ++i) {
            // Sphere: a point on the band between the cuts.
            double z = rng.U(-0.5, 1.2), phi = rng.U(0, 1.5 * 3.141592653589793);
            double rho = std::sqrt(1.5 * 1.5 - z * z);
            lrt::Point3f ps = t(lrt::Point3f(rho * std::cos(phi),
                                             rho * std::sin(phi), z));
            // Disk: a point of the ring.
            double rr = rng.U(0.5, 2), ph = rng.U(0, 5.235987755982988);
            lrt::Point3f pd = t(lrt::Point3f(rr * std::cos(ph),
                                             rr * std::sin(ph), 0.7f));
            for (int c = 0; c < 3; ++c) {
                EXPECT_GE(ps[c], sb.pMin[c] - tol);
                EXPECT_LE(ps[c], sb.pMax[c] + tol);
                EXPECT_GE(pd[c], db.pMin[c] - tol);
                EXPECT_LE(pd[c], db.pMax[c] + tol);
            }
        }
    }
}

TEST(Shape, DefaultIntersectPCallsIntersect) {
    lrt::Transform t = lrt::Translate(lrt::Vector3f(0, 0, 2));
    lrt::Transform tInv = Inverse(t);
    CountingPlane p(&t, &tInv);
    lrt::Ray up(lrt::Point3f(0, 0, 0), lrt::Vector3f(0, 0, 1));
    lrt::Ray down(lrt::Point3f(0, 0, 0), lrt::Vector3f(0, 0, -1));
    EXPECT_TRUE(p.IntersectP(up));
    EXPECT_EQ(p.calls, 1);
    EXPECT_TRUE(p.lastAlpha);
    EXPECT_FALSE(p.IntersectP(down, false));
    EXPECT_EQ(p.calls, 2);
    EXPECT_FALSE(p.lastAlpha);
    // Through the base class, and with a tMax short of the plane.
    const lrt::Shape &s = p;
    EXPECT_FALSE(s.IntersectP(lrt::Ray(up.o, up.d, 1.5f)));
    EXPECT_EQ(p.calls, 3);
    lrt::Float tHit;
    lrt::SurfaceInteraction si;
    ASSERT_TRUE(s.Intersect(up, &tHit, &si));
    EXPECT_NEAR(tHit, 2, 1e-6);
}

EXERCISE_TEST(Ex3_22_OffsetRayOrigin, LeavesTheErrorBoxOnTheSideOfTheDirection) {
    // For random points, error boxes, normals and directions: every corner
    // of the box p +- pError lies on or behind the plane through the offset
    // origin perpendicular to n, as seen from the side w points to.
    Rng rng(lrt::calls::Seed(331));
    const int cases = lrt::calls::Cases(kOffsetCases, 50000);
    long strictlyOutside = 0;
    for (int i = 0; i < cases; ++i) {
        double mag = std::pow(10.0, rng.U(-4, 5));
        lrt::Point3f p(rng.U(-1, 1) * mag, rng.U(-1, 1) * mag,
                       rng.U(-1, 1) * mag);
        double e = std::pow(10.0, rng.U(-8, -3)) * mag;
        lrt::Vector3f pError(rng.U(0, 1) * e, rng.U(0, 1) * e, rng.U(0, 1) * e);
        if (i % 10 == 0) pError = lrt::Vector3f(0, 0, 0);
        lrt::Normal3f n(rng.Dir());
        lrt::Vector3f w = rng.Dir();
        lrt::Point3f po = lrt::ex::OffsetRayOrigin(p, pError, n, w);
        LD side = lrt::Dot(w, n) < 0 ? -1 : 1;
        LD minSep = std::numeric_limits<LD>::infinity();
        for (int c = 0; c < 8; ++c) {
            LD sep = 0;
            for (int k = 0; k < 3; ++k) {
                LD corner = (LD)p[k] + ((c >> k) & 1 ? 1 : -1) * (LD)pError[k];
                sep += side * (LD)n[k] * ((LD)po[k] - corner);
            }
            minSep = std::min(minSep, sep);
        }
        ASSERT_GE(minSep, 0) << "case " << i;
        if (minSep > 0) ++strictlyOutside;
        // The offset is not much larger than it needs to be: the support
        // distance plus one unit in the last place per coordinate.
        LD moved = 0, need = 0;
        for (int k = 0; k < 3; ++k) {
            moved += ((LD)po[k] - p[k]) * ((LD)po[k] - p[k]);
            need += std::abs((LD)n[k]) * pError[k];
        }
        LD ulp = 4 * (LD)lrt::MachineEpsilon *
                 (std::abs((LD)p.x) + std::abs((LD)p.y) + std::abs((LD)p.z));
        EXPECT_LE(std::sqrt(moved), need * (1 + 1e-5) + ulp) << "case " << i;
        if (pError == lrt::Vector3f(0, 0, 0)) {
            EXPECT_EQ(po, p);
        }
    }
    EXPECT_GT(strictlyOutside, cases * 8 / 10);
}

EXERCISE_TEST(Ex3_22_OffsetRayOrigin, ZeroNormalOrZeroErrorMeansNoOffset) {
    lrt::Point3f p(1, 2, 3);
    EXPECT_EQ(lrt::ex::OffsetRayOrigin(p, lrt::Vector3f(1, 1, 1),
                                       lrt::Normal3f(), lrt::Vector3f(0, 0, 1)),
              p);
    EXPECT_EQ(lrt::ex::OffsetRayOrigin(p, lrt::Vector3f(0, 0, 0),
                                       lrt::Normal3f(0, 0, 1),
                                       lrt::Vector3f(0, 0, 1)),
              p);
    // Along an axis: only that coordinate moves, by the error plus rounding.
    lrt::Point3f po = lrt::ex::OffsetRayOrigin(
        p, lrt::Vector3f(0.5f, 0.5f, 0.25f), lrt::Normal3f(0, 0, 1),
        lrt::Vector3f(1, 0, -1));
    EXPECT_EQ(po.x, 1);
    EXPECT_EQ(po.y, 2);
    EXPECT_EQ(po.z, lrt::NextFloatDown(lrt::Float(2.75f)));
}

EXERCISE_TEST(Ex3_22_Interaction, SpawnRay) {
    lrt::Interaction it(lrt::Point3f(1, 2, 3), lrt::Normal3f(0, 1, 0),
                        lrt::Vector3f(1e-3f, 2e-3f, 3e-3f),
                        lrt::Vector3f(0, 1, 0), 0.25f);
    lrt::Vector3f d(0.3f, 0.4f, -0.5f);
    lrt::Ray r = lrt::ex::SpawnRay(it, d);
    EXPECT_EQ(r.o, lrt::ex::OffsetRayOrigin(it.p, it.pError, it.n, d));
    EXPECT_GT(r.o.y, lrt::Float(2) + lrt::Float(2e-3f));
    EXPECT_EQ(r.d, d);
    EXPECT_EQ(r.tMax, lrt::Infinity);
    EXPECT_EQ(r.time, 0.25f);
    lrt::Ray back = lrt::ex::SpawnRay(it, -d);
    EXPECT_LT(back.o.y, lrt::Float(2) - lrt::Float(2e-3f));
}

EXERCISE_TEST(Ex3_22_Interaction, SpawnRayTo) {
    Rng rng(lrt::calls::Seed(332));
    // The rays between two interactions, whose far ends are checked in a
    // second pass: the calls that check them take the rays' origins, and the
    // grader's judge (tests/calls/judge.cpp) answers the calls of each pass
    // together.
    struct Between {
        lrt::Point3f target;
        lrt::Normal3f n2;
        lrt::Ray rb;
    };
    std::vector<Between> between;
    const lrt::Vector3f err(1e-5f, 2e-5f, 1e-5f);
    for (int i = 0; i < 1000; ++i) {
        lrt::Point3f p(rng.U(-10, 10), rng.U(-10, 10), rng.U(-10, 10));
        lrt::Normal3f n(rng.Dir());
        lrt::Interaction a(p, n, err, lrt::Vector3f(0, 0, 0), 1.5f);
        lrt::Point3f target(rng.U(-10, 10), rng.U(-10, 10), rng.U(-10, 10));
        lrt::Ray r = lrt::ex::SpawnRayTo(a, target);
        EXPECT_EQ(r.tMax, 1 - lrt::ShadowEpsilon);
        EXPECT_EQ(r.time, 1.5f);
        // The ray reaches the target at t = 1.
        lrt::Point3f end = r(1);
        EXPECT_LE(lrt::Distance(end, target), 1e-5f);
        EXPECT_EQ(r.o, lrt::ex::OffsetRayOrigin(p, err, n, target - p));
        // Between two interactions, both ends are offset.
        lrt::Normal3f n2(rng.Dir());
        lrt::Interaction b(target, n2, err, lrt::Vector3f(0, 0, 0), 1.5f);
        lrt::Ray rb = lrt::ex::SpawnRayTo(a, b);
        EXPECT_EQ(rb.tMax, 1 - lrt::ShadowEpsilon);
        between.push_back({target, n2, rb});
    }
    for (const Between &t : between) {
        lrt::Point3f tgt =
            lrt::ex::OffsetRayOrigin(t.target, err, t.n2, t.rb.o - t.target);
        EXPECT_LE(lrt::Distance(t.rb(1), tgt), 1e-5f);
    }
}
