// Tests of Disk against an independent double-precision oracle.
//
// The oracle intersects the ray with the plane z = h in double precision
// and tests the radii and the azimuth of the hit point; (u, v) and the
// partial derivatives come from central finite differences of the
// parameterization. Rays whose answer may legitimately differ in Float
// (hit points within rounding distance of a rim or of a phiMax cut, origins
// on the plane, hits at tMax) are flagged as ambiguous; disagreements on
// them are counted and bounded, on any other ray they fail the test.
#include "lrt/shapes/disk.h"

#include <gtest/gtest.h>

#include "quadric_oracle.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <string>

namespace {

// Random rays per disk configuration in object space, and per
// configuration and transformation in world space.
constexpr int kRaysPerDisk = 100000;
constexpr int kRaysPerTransform = 10000;
// Largest tolerated number of disagreements on ambiguous rays, per 100,000.
constexpr int kMaxAmbiguousDisagreementsPer100k = 50;
// Width of the ambiguity bands, in units of Float's machine epsilon.
constexpr double kBand = 256;

struct DiskDef {
    double h, r, ri, phiMaxDeg;
    std::string name;
};

struct DiskGeom {
    double h, r, ri, phiMax;
    explicit DiskGeom(const DiskDef &d)
        : h(d.h), r(d.r), ri(d.ri),
          phiMax(std::min(d.phiMaxDeg, 360.0) * kPi / 180) {}
    D3 P(double u, double v) const {
        double phi = u * phiMax, rho = r - v * (r - ri);
        return D3(rho * std::cos(phi), rho * std::sin(phi), h);
    }
};

struct Oracle {
    bool hit = false;
    bool ambiguous = false;
    bool nearCenter = false;  // parameterization degenerate nearby
    bool nearSeam = false;    // u may be 0 or 1
    double posErr = 0;        // expected error of a Float hit point
    double tErr = 0;          // expected absolute error of a Float t
    double t = 0, u = 0, v = 0;
    D3 p, dpdu, dpdv;
};

// extraMag is the magnitude, in object space, of the world-space
// coordinates from which a transformed ray's object-space origin is
// computed; the origin's rounding error is proportional to it.
Oracle DiskOracle(const DiskDef &def, D3 o, D3 d, double tMax,
                  double extraMag = 0) {
    DiskGeom g(def);
    Oracle res;
    double dd = len3(d);
    if (!(dd > 0) || d.z == 0) return res;
    double lo = len3(o);
    double t = (g.h - o.z) / d.z;
    double mag = lo + std::abs(g.h) + g.r + extraMag;
    // Expected error of the object-space origin, and the resulting
    // uncertainty of t: the interval of t is about errO / |dz| wide.
    double errO = 4 * eps * mag;
    double tol = kBand * eps * mag;
    res.tErr = 2 * errO / std::abs(d.z);
    if (std::abs(g.h - o.z) <= tol) res.ambiguous = true;
    if (std::abs(t - tMax) * std::abs(d.z) <= tol) res.ambiguous = true;
    if (!(t > 0) || !(t < tMax)) return res;
    D3 p = o + t * d;
    p.z = g.h;
    double rho = std::sqrt(p.x * p.x + p.y * p.y);
    double phi = std::atan2(p.y, p.x);
    if (phi < 0) phi += 2 * kPi;
    double posTol = kBand * eps * (lo + t * dd + g.r);
    bool cutPhi = g.phiMax < 2 * kPi;
    if (std::abs(rho - g.r) <= posTol ||
        (g.ri > 0 && std::abs(rho - g.ri) <= posTol) ||
        (cutPhi && (rho * std::abs(phi - g.phiMax) <= posTol ||
                    rho * phi <= posTol || rho * (2 * kPi - phi) <= posTol)))
        res.ambiguous = true;
    if (rho > g.r || rho < g.ri || phi > g.phiMax) return res;
    res.hit = true;
    res.posErr = 8 * eps * (lo + t * dd + g.r) + res.tErr * dd;
    res.t = t;
    res.p = p;
    res.nearCenter = rho <= 1e-3 * g.r;
    res.nearSeam = rho * phi <= posTol || rho * (2 * kPi - phi) <= posTol;
    res.u = phi / g.phiMax;
    res.v = (g.r - rho) / (g.r - g.ri);
    const double h = 1e-6;
    res.dpdu = (0.5 / h) * (g.P(res.u + h, res.v) - g.P(res.u - h, res.v));
    res.dpdv = (0.5 / h) * (g.P(res.u, res.v + h) - g.P(res.u, res.v - h));
    return res;
}

struct TestRay {
    D3 o, d;
    double tMax = std::numeric_limits<double>::infinity();
};

// Random rays of several kinds: from either side toward the disk, grazing,
// aimed at the hole or the removed sector, parallel to the plane, with a
// finite tMax, and starting very close to the plane.
TestRay DiskRay(Rng &rng, const DiskDef &def, int i) {
    DiskGeom g(def);
    double R = g.r;
    TestRay ray;
    int kind = i % 10;
    auto side = [&]() { return rng.U() < 0.5 ? -1.0 : 1.0; };
    auto target = [&](double maxRho) {
        double rho = maxRho * std::sqrt(rng.U()), phi = rng.U(0, 2 * kPi);
        return D3(rho * std::cos(phi), rho * std::sin(phi), g.h);
    };
    if (kind < 4 || kind == 7) {
        ray.o = D3(rng.U(-3, 3) * R, rng.U(-3, 3) * R,
                   g.h + side() * rng.U(0.1, 5) * R);
        ray.d = rng.U(0.2, 5) * (target(1.3 * R) - ray.o);
        if (kind == 7) ray.tMax = rng.U(0, 2);
    } else if (kind == 4) {  // grazing
        D3 q = target(1.3 * R);
        D3 dir = norm3(D3(rng.U(-1, 1), rng.U(-1, 1),
                          side() * std::pow(10.0, rng.U(-7, -1))));
        ray.o = q - (R * rng.U(0.5, 3)) * dir;
        ray.d = rng.U(0.2, 5) * dir;
    } else if (kind == 5) {  // at the hole or the removed sector
        D3 q = target(1.3 * R);
        for (int k = 0; k < 100; ++k) {
            double rho = std::sqrt(q.x * q.x + q.y * q.y);
            double phi = std::atan2(q.y, q.x);
            if (phi < 0) phi += 2 * kPi;
            if (rho < g.ri || phi > g.phiMax) break;
            q = target(1.3 * R);
        }
        ray.o = D3(rng.U(-3, 3) * R, rng.U(-3, 3) * R,
                   g.h + side() * rng.U(0.1, 5) * R);
        ray.d = rng.U(0.2, 5) * (q - ray.o);
    } else if (kind == 6) {  // parallel to the plane, some in it
        ray.o = D3(rng.U(-3, 3) * R, rng.U(-3, 3) * R,
                   rng.U() < 0.5 ? g.h : g.h + rng.U(-1, 1) * R);
        ray.d = D3(rng.U(-1, 1), rng.U(-1, 1), 0);
    } else {  // starting very close to the plane
        D3 q = target(1.2 * R);
        ray.o = D3(q.x, q.y, g.h + side() * std::pow(10.0, rng.U(-8, -2)) * R);
        ray.d = rng.U(0.2, 5) * rng.Dir();
    }
    return ray;
}

lrt::Ray ToRay(const TestRay &t) {
    return lrt::Ray(ToP(t.o), ToV(t.d), lrt::Float(t.tMax));
}

struct Stats {
    long rays = 0, hits = 0, ambiguous = 0, ambiguousDisagree = 0;
    long failures = 0, derivativeChecks = 0, tOver1e4 = 0;
    void Fail(const std::string &what) {
        if (++failures <= 10) ADD_FAILURE() << what;
    }
};

bool Near(D3 a, D3 b, double tol) { return dist3(a, b) <= tol; }

std::string Str(D3 a) {
    char buf[128];
    std::snprintf(buf, sizeof(buf), "(%.17g, %.17g, %.17g)", a.x, a.y, a.z);
    return buf;
}

void Compare(const Oracle &orc, bool hit, lrt::Float tHit,
             const lrt::SurfaceInteraction &si, const lrt::Shape *shape,
             const DiskDef &def, const Affine &M, bool reverse,
             const TestRay &objRay, Stats &st) {
    ++st.rays;
    if (orc.ambiguous) ++st.ambiguous;
    auto where = [&]() {
        return def.name + " ray o=" + Str(objRay.o) + " d=" + Str(objRay.d);
    };
    double tTol = std::max(1e-4 * orc.t, orc.tErr);
    bool sameRoot = hit && orc.hit && std::abs(tHit - orc.t) <= tTol;
    if (hit != orc.hit || (hit && !sameRoot)) {
        if (orc.ambiguous)
            ++st.ambiguousDisagree;
        else
            st.Fail(where() + ": lrt " + (hit ? "hit" : "miss") + " t=" +
                    std::to_string(tHit) + ", oracle " +
                    (orc.hit ? "hit" : "miss") + " t=" +
                    std::to_string(orc.t));
        return;
    }
    if (!hit) return;
    ++st.hits;
    if (orc.ambiguous) return;
    if (std::abs(tHit - orc.t) > 1e-4 * orc.t) ++st.tOver1e4;
    DiskGeom g(def);
    double sgn = reverse ? -1 : 1;
    double scale = M.norm * (g.r + len3(objRay.o));
    D3 pw = M.Point(orc.p);
    if (!Near(ToD(si.p), pw, std::max(1e-4 * scale, M.norm * orc.posErr)))
        st.Fail(where() + ": p " + Str(ToD(si.p)) + " vs " + Str(pw));
    D3 nw = sgn * norm3(M.Normal(D3(0, 0, 1)));
    if (!Near(ToD(si.n), nw, 1e-5 * M.cond))
        st.Fail(where() + ": n " + Str(ToD(si.n)) + " vs " + Str(nw));
    double rho = std::max(std::sqrt(orc.p.x * orc.p.x + orc.p.y * orc.p.y),
                          1e-300);
    double tolU = std::max(1e-4, orc.posErr / (rho * g.phiMax));
    double tolV = std::max(1e-4, orc.posErr / (g.r - g.ri));
    if (!orc.nearSeam && std::abs(si.uv.x - orc.u) > tolU)
        st.Fail(where() + ": u " + std::to_string(si.uv.x) + " vs " +
                std::to_string(orc.u));
    if (std::abs(si.uv.y - orc.v) > tolV)
        st.Fail(where() + ": v " + std::to_string(si.uv.y) + " vs " +
                std::to_string(orc.v));
    if (!orc.nearCenter) {
        ++st.derivativeChecks;
        double rel = std::max(1e-4, orc.posErr / rho);
        if (!Near(ToD(si.dpdu), M.Vector(orc.dpdu),
                  rel * M.norm * g.phiMax * g.r))
            st.Fail(where() + ": dpdu " + Str(ToD(si.dpdu)) + " vs " +
                    Str(M.Vector(orc.dpdu)));
        if (!Near(ToD(si.dpdv), M.Vector(orc.dpdv),
                  rel * M.norm * (g.r - g.ri)))
            st.Fail(where() + ": dpdv " + Str(ToD(si.dpdv)) + " vs " +
                    Str(M.Vector(orc.dpdv)));
    }
    if (si.dndu.LengthSquared() != 0 || si.dndv.LengthSquared() != 0)
        st.Fail(where() + ": dndu, dndv of a plane must be zero");
    bool flip = reverse != M.mirror;
    D3 cr = cross3(ToD(si.dpdu), ToD(si.dpdv));
    if (!((flip ? -1 : 1) * dot3(ToD(si.n), cr) > 0))
        st.Fail(where() + ": normal vs dpdu x dpdv");
    if (si.flipNormal != flip) st.Fail(where() + ": flipNormal");
    if (si.shape != shape) st.Fail(where() + ": shape pointer");
    auto f = [&](LD x, LD y, LD z) {
        return (LD)M.inv[2][0] * x + (LD)M.inv[2][1] * y +
               (LD)M.inv[2][2] * z + (LD)M.inv[2][3] - (LD)g.h;
    };
    if (!BoxStraddles(ToD(si.p), ToD(si.pError), f))
        st.Fail(where() + ": pError box " + Str(ToD(si.pError)) +
                " misses the plane");
    D3 wo = norm3(-1.0 * M.Vector(objRay.d));
    if (!Near(ToD(si.wo), wo, 1e-4)) st.Fail(where() + ": wo");
}

const DiskDef kDisks[] = {
    {0.3, 1.5, 0, 360, "full disk"},
    {-1, 2, 0.7, 360, "annulus"},
    {2, 1, 0.3, 200, "partial annulus"},
    {0, 0.01, 0.002, 300, "small partial annulus"},
};

DiskDef AsStored(const DiskDef &d) {
    DiskDef s = d;
    s.h = ToFloat(d.h);
    s.r = ToFloat(d.r);
    s.ri = ToFloat(d.ri);
    return s;
}

lrt::Disk MakeDisk(const lrt::Transform *o2w, const lrt::Transform *w2o,
                   bool reverse, const DiskDef &d) {
    return lrt::Disk(o2w, w2o, reverse, lrt::Float(d.h), lrt::Float(d.r),
                     lrt::Float(d.ri), lrt::Float(d.phiMaxDeg));
}

void Report(const char *what, const Stats &st) {
    std::printf("[ disk     ] %-42s %6ld rays %6ld hits %6ld ambiguous "
                "%5ld disagree; %ld hits with t off by > 1e-4\n", what,
                st.rays, st.hits, st.ambiguous, st.ambiguousDisagree,
                st.tOver1e4);
}

// Rays of kind 4 graze the plane, at angles down to 1e-7, and rays of kind
// 6 are parallel to it in object space (after a transformation, nearly
// parallel); rays of kinds 8 and 9 start within 1e-2 of the plane, many of
// them within rounding distance of it. They are counted apart from the
// other rays: for them, disagreements on ambiguous rays are expected in
// numbers.
int RayClass(int i) {
    int kind = i % 10;
    return (kind == 4 || kind == 6) ? 1 : (kind >= 8 ? 2 : 0);
}

}  // namespace

TEST(Disk, AgreesWithDoublePrecisionOracle) {
    lrt::Transform id;
    Affine I = Affine::Make(D3(1, 1, 1), D3(0, 0, 1), 0, D3(0, 0, 0));
    Rng rng(320);
    for (const DiskDef &def : kDisks) {
        lrt::Disk disk = MakeDisk(&id, &id, false, def);
        DiskDef used = AsStored(def);
        Stats st, grazing, near;
        Stats *cls[3] = {&st, &grazing, &near};
        for (int i = 0; i < kRaysPerDisk; ++i) {
            lrt::Ray ray = ToRay(DiskRay(rng, used, i));
            TestRay exact{ToD(ray.o), ToD(ray.d), (double)ray.tMax};
            Oracle orc = DiskOracle(used, exact.o, exact.d, exact.tMax);
            lrt::Float tHit = -1;
            lrt::SurfaceInteraction si;
            bool hit = disk.Intersect(ray, &tHit, &si);
            ASSERT_EQ(hit, disk.IntersectP(ray)) << i;
            Compare(orc, hit, tHit, si, &disk, used, I, false, exact,
                    *cls[RayClass(i)]);
        }
        Report((def.name + ", random").c_str(), st);
        Report((def.name + ", grazing").c_str(), grazing);
        Report((def.name + ", near the plane").c_str(), near);
        EXPECT_EQ(st.failures + grazing.failures + near.failures, 0)
            << def.name;
        EXPECT_LE(st.ambiguousDisagree,
                  kMaxAmbiguousDisagreementsPer100k * st.rays / 100000);
        EXPECT_GT(st.hits, st.rays / 10);
        EXPECT_GT(st.derivativeChecks, st.rays / 10);
    }
}

TEST(Disk, TransformedMatchesObjectSpaceThroughInverse) {
    struct Xf {
        Affine M;
        double translation;
        const char *name;
    } xfs[] = {
        {Affine::Make(D3(1, 1, 1), D3(1, 2, 3), 37, D3(1, -2, 0.5)), 2.3,
         "rotation"},
        {Affine::Make(D3(2, 0.5, 1.3), D3(-1, 0.3, 2), 71, D3(-3, 1, 2)), 3.8,
         "nonuniform scale"},
        {Affine::Make(D3(1, 1, -1), D3(0, 0, 1), 0, D3(0.5, 0, -1)), 1.2,
         "mirror"},
        {Affine::Make(D3(-1.5, 0.7, 2), D3(2, -1, 1), 123, D3(4, 4, -4)), 7,
         "mirrored nonuniform scale"},
        {Affine::Make(D3(3e3, 3e3, 3e3), D3(1, 1, 0), -50, D3(1e4, -2e4, 5e3)),
         2.3e4, "large uniform scale"},
    };
    Rng rng(321);
    long compared = 0, disagreeWithLrt = 0;
    for (const Xf &xf : xfs) {
        lrt::Transform o2w = xf.M.ToTransform();
        lrt::Transform w2o = Inverse(o2w);
        lrt::Transform id;
        for (int k = 0; k < 3; ++k) {
            const DiskDef &def = kDisks[k];
            DiskDef used = AsStored(def);
            for (bool reverse : {false, true}) {
                lrt::Disk world = MakeDisk(&o2w, &w2o, reverse, def);
                lrt::Disk object = MakeDisk(&id, &id, reverse, def);
                EXPECT_EQ(world.transformSwapsHandedness, xf.M.mirror);
                Stats st, grazing, near;
                Stats *cls[3] = {&st, &grazing, &near};
                for (int i = 0; i < kRaysPerTransform; ++i) {
                    TestRay tr = DiskRay(rng, used, i);
                    lrt::Ray wr(ToP(xf.M.Point(tr.o)), ToV(xf.M.Vector(tr.d)),
                                lrt::Float(tr.tMax));
                    TestRay ob{xf.M.InvPoint(ToD(wr.o)),
                               xf.M.InvVector(ToD(wr.d)), (double)wr.tMax};
                    double extraMag = (len3(ToD(wr.o)) + xf.translation) /
                                      xf.M.minScale;
                    Oracle orc =
                        DiskOracle(used, ob.o, ob.d, ob.tMax, extraMag);
                    Stats &cs = *cls[RayClass(i)];
                    lrt::Float tHit = -1;
                    lrt::SurfaceInteraction si;
                    bool hit = world.Intersect(wr, &tHit, &si);
                    ASSERT_EQ(hit, world.IntersectP(wr));
                    Compare(orc, hit, tHit, si, &world, used, xf.M, reverse,
                            ob, cs);
                    lrt::Float tObj = -1;
                    lrt::SurfaceInteraction siObj;
                    bool hitObj = object.Intersect(ToRay(ob), &tObj, &siObj);
                    ++compared;
                    if (hitObj != hit ||
                        (hit && std::abs(tObj - tHit) >
                                    std::max(1e-4 * tHit, orc.tErr))) {
                        if (orc.ambiguous)
                            ++disagreeWithLrt;
                        else
                            cs.Fail(std::string(xf.name) + ": world and "
                                    "object-space shapes disagree");
                    }
                }
                std::string what = std::string(xf.name) +
                                   (reverse ? ", rev, " : ", ") + def.name;
                Report(what.c_str(), st);
                Report((what + ", grazing").c_str(), grazing);
                Report((what + ", near").c_str(), near);
                EXPECT_EQ(st.failures + grazing.failures + near.failures, 0)
                    << what;
                EXPECT_LE(st.ambiguousDisagree,
                          kMaxAmbiguousDisagreementsPer100k * st.rays / 100000 +
                              2);
            }
        }
    }
    std::printf("[ disk     ] world vs object-space lrt: %ld rays, %ld "
                "ambiguous disagreements\n", compared, disagreeWithLrt);
}

TEST(Disk, SpecialRays) {
    lrt::Transform id;
    lrt::Disk disk(&id, &id, false, 0.5f, 1, 0, 360);
    lrt::Float tHit;
    lrt::SurfaceInteraction si;
    // Exactly at the center, where the parameterization degenerates.
    ASSERT_TRUE(disk.Intersect(
        lrt::Ray(lrt::Point3f(0, 0, 3), lrt::Vector3f(0, 0, -1)), &tHit, &si));
    EXPECT_EQ(tHit, 2.5f);
    EXPECT_FALSE(si.n.HasNaNs());
    EXPECT_FALSE(si.dpdv.HasNaNs());
    EXPECT_NEAR(si.n.z, 1, 1e-6);
    EXPECT_NEAR(si.uv.y, 1, 1e-4);
    EXPECT_EQ(si.p.z, 0.5f);
    // Exactly on the plane in object space; the (identity) transformation
    // to world space adds its own bound of gamma(3) times the coordinates.
    EXPECT_LE(si.pError.z, 2 * lrt::gamma(3) * 0.5f);
    EXPECT_LE(si.pError.x, 2 * lrt::gamma(3) * 1e-5f);
    EXPECT_EQ(si.pError.y, 0);
    // From below: the normal still faces +z.
    ASSERT_TRUE(disk.Intersect(
        lrt::Ray(lrt::Point3f(0.3f, 0.2f, -3), lrt::Vector3f(0, 0, 2)), &tHit,
        &si));
    EXPECT_EQ(tHit, 1.75f);
    EXPECT_NEAR(si.n.z, 1, 1e-6);
    // Parallel to the plane, in it and beside it.
    EXPECT_FALSE(disk.IntersectP(
        lrt::Ray(lrt::Point3f(-2, 0, 0.5f), lrt::Vector3f(1, 0, 0))));
    EXPECT_FALSE(disk.IntersectP(
        lrt::Ray(lrt::Point3f(-2, 0, 0.6f), lrt::Vector3f(1, 0, 0))));
    // Starting exactly on the plane: t = 0 is not a hit.
    EXPECT_FALSE(disk.IntersectP(
        lrt::Ray(lrt::Point3f(0.1f, 0, 0.5f), lrt::Vector3f(0, 1, 1))));
    // Through the hole of an annulus, and through the removed sector.
    lrt::Disk ring(&id, &id, false, 0, 1, 0.5f, 90);
    EXPECT_FALSE(ring.IntersectP(
        lrt::Ray(lrt::Point3f(0.1f, 0.1f, 1), lrt::Vector3f(0, 0, -1))));
    EXPECT_FALSE(ring.IntersectP(
        lrt::Ray(lrt::Point3f(-0.7f, 0.1f, 1), lrt::Vector3f(0, 0, -1))));
    EXPECT_TRUE(ring.IntersectP(
        lrt::Ray(lrt::Point3f(0.6f, 0.1f, 1), lrt::Vector3f(0, 0, -1))));
    // Exactly on the rims: inside.
    EXPECT_TRUE(ring.IntersectP(
        lrt::Ray(lrt::Point3f(1, 0, 1), lrt::Vector3f(0, 0, -1))));
    EXPECT_TRUE(ring.IntersectP(
        lrt::Ray(lrt::Point3f(0, 0.5f, 1), lrt::Vector3f(0, 0, -1))));
    // The bound is flat.
    lrt::Bounds3f b = ring.ObjectBound();
    EXPECT_EQ(b.pMin, lrt::Point3f(-1, -1, 0));
    EXPECT_EQ(b.pMax, lrt::Point3f(1, 1, 0));
}

TEST(Disk, BadInput) {
    lrt::Transform id;
    const lrt::Float nan = std::numeric_limits<lrt::Float>::quiet_NaN();
    const lrt::Float inf = lrt::Infinity;
    EXPECT_THROW(lrt::Disk(&id, &id, false, 0, 0, 0, 360),
                 std::invalid_argument);
    EXPECT_THROW(lrt::Disk(&id, &id, false, 0, -1, 0, 360),
                 std::invalid_argument);
    EXPECT_THROW(lrt::Disk(&id, &id, false, 0, 1, 1, 360),
                 std::invalid_argument);
    EXPECT_THROW(lrt::Disk(&id, &id, false, 0, 1, 2, 360),
                 std::invalid_argument);
    EXPECT_THROW(lrt::Disk(&id, &id, false, 0, 1, -0.5f, 360),
                 std::invalid_argument);
    EXPECT_THROW(lrt::Disk(&id, &id, false, nan, 1, 0, 360),
                 std::invalid_argument);
    EXPECT_THROW(lrt::Disk(&id, &id, false, inf, 1, 0, 360),
                 std::invalid_argument);
    EXPECT_THROW(lrt::Disk(&id, &id, false, 0, nan, 0, 360),
                 std::invalid_argument);
    EXPECT_THROW(lrt::Disk(&id, &id, false, 0, 1, 0, 0),
                 std::invalid_argument);
    EXPECT_THROW(lrt::Disk(&id, &id, false, 0, 1, 0, nan),
                 std::invalid_argument);
    EXPECT_THROW(lrt::Disk(nullptr, &id, false, 0, 1, 0, 360),
                 std::invalid_argument);

    lrt::Disk d(&id, &id, false, 0, 1, 0.2f, 360);
    lrt::Transform rot = lrt::Rotate(30, lrt::Vector3f(1, 1, 0));
    lrt::Transform rotInv = Inverse(rot);
    lrt::Disk moved(&rot, &rotInv, false, 0, 1, 0.2f, 200);
    const lrt::Float sentinel = 12345;
    lrt::Ray rays[] = {
        lrt::Ray(lrt::Point3f(0.5f, 0, -5), lrt::Vector3f(0, 0, 0)),
        lrt::Ray(lrt::Point3f(nan, 0, -5), lrt::Vector3f(0, 0, 1)),
        lrt::Ray(lrt::Point3f(0.5f, 0, -5), lrt::Vector3f(nan, 0, 1)),
        lrt::Ray(lrt::Point3f(0.5f, 0, -5), lrt::Vector3f(0, 0, 1), nan),
        lrt::Ray(lrt::Point3f(nan, nan, nan), lrt::Vector3f(nan, nan, nan)),
        lrt::Ray(lrt::Point3f(0.5f, 0, -inf), lrt::Vector3f(0, 0, 1)),
        lrt::Ray(lrt::Point3f(0.5f, 0, -5), lrt::Vector3f(0, 0, inf)),
    };
    for (const lrt::Disk *dp : {&d, &moved})
        for (const lrt::Ray &r : rays) {
            lrt::Float tHit = sentinel;
            lrt::SurfaceInteraction si;
            EXPECT_FALSE(dp->Intersect(r, &tHit, &si)) << r;
            EXPECT_EQ(tHit, sentinel);
            EXPECT_FALSE(dp->IntersectP(r)) << r;
        }
}
