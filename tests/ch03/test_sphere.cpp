// Tests of Sphere against an independent double-precision oracle.
//
// The oracle intersects rays with (partial) spheres geometrically: it finds
// the point of closest approach of the line to the center and the half
// chord t_hc, with the stable form for the near root, and it computes
// (u, v), the partial derivatives of the position and of the normal by
// central finite differences of the parameterization, not by the formulas
// of the chapter. Rays for which a correct single-precision computation may
// legitimately decide differently (nearly tangent rays, hit points within
// rounding distance of a clipping boundary, origins on the surface, hits at
// tMax) are flagged as ambiguous; disagreements on them are counted and
// bounded, disagreements on any other ray fail the test.
#include "lrt/shapes/sphere.h"

#include <gtest/gtest.h>

#include "quadric_oracle.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <string>

namespace {

// Random rays per sphere configuration in object space, and per
// configuration and transformation in world space.
constexpr int kRaysPerSphere = 100000;
constexpr int kRaysPerTransform = 10000;
// Largest tolerated number of disagreements on ambiguous rays, per 100,000.
constexpr int kMaxAmbiguousDisagreementsPer100k = 50;
// Width of the ambiguity bands, in units of Float's machine epsilon.
constexpr double kBand = 256;


struct SphereDef {
    double r, zMin, zMax, phiMaxDeg;
    std::string name;
};

// The oracle's answer for one ray.
struct Oracle {
    bool hit = false;
    bool ambiguous = false;  // hit or miss, or which root, may differ
    bool nearPole = false;   // parameterization degenerate nearby
    bool nearSeam = false;   // u may be 0 or 1
    // Expected uncertainty of a correct Float computation of the hit point,
    // along the surface: the rounding error of c = o.o - r^2, of order
    // eps |o|^2, moves the root by that over the derivative of the
    // quadratic, which is small at grazing incidence.
    double posErr = 0;
    double t = 0, u = 0, v = 0;
    D3 p, n, dpdu, dpdv, dndu, dndv;
};

struct SphereGeom {
    double r, zMin, zMax, thetaMin, thetaMax, phiMax;
    explicit SphereGeom(const SphereDef &s) : r(s.r) {
        zMin = std::clamp(std::min(s.zMin, s.zMax), -r, r);
        zMax = std::clamp(std::max(s.zMin, s.zMax), -r, r);
        thetaMin = std::acos(zMin / r);
        thetaMax = std::acos(zMax / r);
        phiMax = std::min(s.phiMaxDeg, 360.0) * kPi / 180;
    }
    D3 P(double u, double v) const {
        double phi = u * phiMax, th = thetaMin + v * (thetaMax - thetaMin);
        return D3(r * std::sin(th) * std::cos(phi),
                  r * std::sin(th) * std::sin(phi), r * std::cos(th));
    }
    D3 N(double u, double v) const { return (1 / r) * P(u, v); }
};

Oracle SphereOracle(const SphereDef &def, D3 o, D3 d, double tMax) {
    SphereGeom g(def);
    Oracle res;
    double r = g.r, dd = len3(d);
    if (!(dd > 0)) return res;
    D3 dh = (1 / dd) * d, L = -1.0 * o;
    double tca = dot3(L, dh);
    double m = len3(L - tca * dh);
    double lo = len3(o);
    double scale = r + lo;
    // Uncertainty of a correct Float computation in the discriminant, in
    // terms of the distance m of the line from the center.
    double tolTan = kBand * eps * (lo * lo / r + r);
    if (std::abs(m - r) <= tolTan) res.ambiguous = true;
    if (m > r) return res;
    double thc = std::sqrt((r - m) * (r + m));
    double cL = (lo - r) * (lo + r);
    double s0, s1;
    if (tca >= 0) {
        s1 = tca + thc;
        s0 = (s1 != 0) ? cL / s1 : 0;
    } else {
        s0 = tca - thc;
        s1 = cL / s0;
    }
    for (double s : {s0, s1}) {
        double t = s / dd;
        if (std::abs(s) <= kBand * eps * scale * 4) res.ambiguous = true;
        if (!(t > 0)) continue;
        if (std::abs(t - tMax) * dd <= kBand * eps * scale * 4)
            res.ambiguous = true;
        if (t >= tMax) break;
        D3 p = o + t * d;
        p = (r / len3(p)) * p;
        double phi = std::atan2(p.y, p.x);
        if (phi < 0) phi += 2 * kPi;
        double rho = std::sqrt(p.x * p.x + p.y * p.y);
        // Positional uncertainty of the hit point along the surface: the
        // error of t, magnified at grazing incidence.
        double cosInc = std::abs(dot3(dh, (1 / r) * p));
        double posTol =
            kBand * eps * (scale * scale / r) / std::max(cosInc, 1e-9);
        bool cutBelow = g.zMin > -r, cutAbove = g.zMax < r;
        bool cutPhi = g.phiMax < 2 * kPi;
        if ((cutBelow && std::abs(p.z - g.zMin) <= posTol) ||
            (cutAbove && std::abs(p.z - g.zMax) <= posTol) ||
            (cutPhi && (rho * std::abs(phi - g.phiMax) <= posTol ||
                        rho * phi <= posTol ||
                        rho * (2 * kPi - phi) <= posTol)))
            res.ambiguous = true;
        bool clipped = (cutBelow && p.z < g.zMin) ||
                       (cutAbove && p.z > g.zMax) || phi > g.phiMax;
        if (clipped) continue;
        res.hit = true;
        res.posErr = 8 * eps * (lo * lo + r * r) / (r * std::max(cosInc, 1e-9));
        res.t = t;
        res.p = p;
        res.n = (1 / r) * p;
        res.nearPole = rho <= 1e-3 * r;
        res.nearSeam = rho * phi <= posTol || rho * (2 * kPi - phi) <= posTol;
        res.u = phi / g.phiMax;
        double theta = std::acos(std::clamp(p.z / r, -1.0, 1.0));
        res.v = (theta - g.thetaMin) / (g.thetaMax - g.thetaMin);
        const double h = 1e-6;
        res.dpdu = (0.5 / h) * (g.P(res.u + h, res.v) - g.P(res.u - h, res.v));
        res.dpdv = (0.5 / h) * (g.P(res.u, res.v + h) - g.P(res.u, res.v - h));
        res.dndu = (0.5 / h) * (g.N(res.u + h, res.v) - g.N(res.u - h, res.v));
        res.dndv = (0.5 / h) * (g.N(res.u, res.v + h) - g.N(res.u, res.v - h));
        return res;
    }
    return res;
}

struct TestRay {
    D3 o, d;
    double tMax = std::numeric_limits<double>::infinity();
};

// Random rays of five kinds: from outside, from inside, nearly tangent,
// aimed at the clipped parts of a partial sphere, and with a finite tMax.
bool IsTangentKind(int i) { return i % 10 == 5 || i % 10 == 6; }

TestRay SphereRay(Rng &rng, const SphereDef &def, int i) {
    SphereGeom g(def);
    double R = g.r;
    TestRay ray;
    int kind = i % 10;
    if (kind < 3 || kind == 9) {  // from outside
        ray.o = (R * rng.U(1.05, 10)) * rng.Dir();
        ray.d = rng.U(0.2, 5) * (rng.InBall(1.3 * R) - ray.o);
        if (kind == 9) ray.tMax = rng.U(0, 1.2) * 2 * (len3(ray.o) + R) /
                                  len3(ray.d);
    } else if (kind < 5) {  // from inside the full sphere
        ray.o = rng.InBall(0.95 * R);
        ray.d = rng.U(0.2, 5) * rng.Dir();
    } else if (kind < 7) {  // nearly tangent
        D3 q = R * rng.Dir();
        D3 tdir = norm3(cross3(q, rng.Dir()));
        double delta = std::pow(10.0, rng.U(-9, -2)) * (rng.U() < 0.5 ? -1 : 1);
        D3 target = (1 + delta) * q;
        ray.o = target - (R * rng.U(0.5, 5)) * tdir;
        ray.d = rng.U(0.2, 5) * tdir;
    } else {  // aimed at a removed part, if any
        D3 q = R * rng.Dir();
        for (int k = 0; k < 100; ++k) {
            double phi = std::atan2(q.y, q.x);
            if (phi < 0) phi += 2 * kPi;
            if (q.z < g.zMin || q.z > g.zMax || phi > g.phiMax) break;
            q = R * rng.Dir();
        }
        ray.o = (R * rng.U(1.5, 8)) * rng.Dir();
        ray.d = rng.U(0.2, 5) * (q - ray.o);
    }
    return ray;
}

lrt::Ray ToRay(const TestRay &t) {
    return lrt::Ray(ToP(t.o), ToV(t.d), lrt::Float(t.tMax));
}

struct Stats {
    long rays = 0, hits = 0, ambiguous = 0, ambiguousDisagree = 0;
    long failures = 0, derivativeChecks = 0, relaxed = 0, tOver1e4 = 0;
    void Fail(const std::string &what) {
        if (++failures <= 10) ADD_FAILURE() << what;
    }
};

bool Near(D3 a, D3 b, double tol) { return dist3(a, b) <= tol; }

std::string Str(D3 a) {
    char buf[128];
    std::snprintf(buf, sizeof(buf), "(%.9g, %.9g, %.9g)", a.x, a.y, a.z);
    return buf;
}

// Compares one world-space result with the oracle's object-space answer,
// mapped through the transformation M.
void Compare(const Oracle &orc, bool hit, lrt::Float tHit,
             const lrt::SurfaceInteraction &si, const lrt::Shape *shape,
             const SphereDef &def, const Affine &M, bool reverse,
             bool compareDndu, const TestRay &objRay, Stats &st) {
    ++st.rays;
    if (orc.ambiguous) ++st.ambiguous;
    auto where = [&]() {
        return def.name + " ray o=" + Str(objRay.o) + " d=" + Str(objRay.d);
    };
    SphereGeom g(def);
    double dlen = len3(objRay.d);
    double tTol = std::max(1e-4 * orc.t, orc.posErr / dlen);
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
    // Tolerances: a relative 1e-4, or the expected error of a correct
    // computation where grazing incidence makes that larger.
    double rel = std::max(1e-4, orc.posErr / g.r);
    if (rel > 1e-4) ++st.relaxed;
    double rho = std::max(std::sqrt(orc.p.x * orc.p.x + orc.p.y * orc.p.y),
                          1e-300);
    double sgn = reverse ? -1 : 1;
    D3 pw = M.Point(orc.p);
    double scale = M.norm * (g.r + len3(objRay.o));
    if (!Near(ToD(si.p), pw, std::max(1e-4 * scale, M.norm * orc.posErr)))
        st.Fail(where() + ": p " + Str(ToD(si.p)) + " vs " + Str(pw));
    D3 nw = sgn * norm3(M.Normal(orc.n));
    if (!Near(ToD(si.n), nw, rel * M.cond))
        st.Fail(where() + ": n " + Str(ToD(si.n)) + " vs " + Str(nw));
    double tolU = std::max(1e-4, orc.posErr / (rho * g.phiMax));
    double dth = std::abs(g.thetaMax - g.thetaMin);
    double tolV = std::max(1e-4, orc.posErr / (g.r * dth));
    if (!orc.nearSeam && std::abs(si.uv.x - orc.u) > tolU)
        st.Fail(where() + ": u " + std::to_string(si.uv.x) + " vs " +
                std::to_string(orc.u));
    if (!orc.nearPole && std::abs(si.uv.y - orc.v) > tolV)
        st.Fail(where() + ": v " + std::to_string(si.uv.y) + " vs " +
                std::to_string(orc.v));
    if (!orc.nearPole) {
        ++st.derivativeChecks;
        double relV = rel * (1 + g.r / rho);
        if (!Near(ToD(si.dpdu), M.Vector(orc.dpdu),
                  rel * M.norm * g.phiMax * g.r))
            st.Fail(where() + ": dpdu " + Str(ToD(si.dpdu)) + " vs " +
                    Str(M.Vector(orc.dpdu)));
        if (!Near(ToD(si.dpdv), M.Vector(orc.dpdv),
                  relV * M.norm * dth * g.r))
            st.Fail(where() + ": dpdv " + Str(ToD(si.dpdv)) + " vs " +
                    Str(M.Vector(orc.dpdv)));
        if (compareDndu) {
            D3 dndu = sgn * M.Normal(orc.dndu), dndv = sgn * M.Normal(orc.dndv);
            if (!Near(ToD(si.dndu), dndu, rel * g.phiMax))
                st.Fail(where() + ": dndu " + Str(ToD(si.dndu)) + " vs " +
                        Str(dndu));
            if (!Near(ToD(si.dndv), dndv, relV * dth))
                st.Fail(where() + ": dndv " + Str(ToD(si.dndv)) + " vs " +
                        Str(dndv));
        }
    }
    // Orientation: outward unless reversed, whatever the transformation;
    // the flag and the cross product of the world tangents follow the
    // handedness.
    D3 center = M.Point(D3(0, 0, 0));
    if (!(sgn * dot3(ToD(si.n), ToD(si.p) - center) > 0))
        st.Fail(where() + ": normal does not face " +
                (reverse ? "inward" : "outward"));
    bool flip = reverse != M.mirror;
    D3 cr = cross3(ToD(si.dpdu), ToD(si.dpdv));
    if (!((flip ? -1 : 1) * dot3(ToD(si.n), cr) > 0))
        st.Fail(where() + ": normal vs dpdu x dpdv");
    if (si.flipNormal != flip) st.Fail(where() + ": flipNormal");
    if (si.shape != shape) st.Fail(where() + ": shape pointer");
    // The error bounds: the box around p contains a point of the sphere.
    D3 e = ToD(si.pError);
    auto f = [&](LD x, LD y, LD z) {
        LD q[3];
        for (int i = 0; i < 3; ++i)
            q[i] = (LD)M.inv[i][0] * x + (LD)M.inv[i][1] * y +
                   (LD)M.inv[i][2] * z + (LD)M.inv[i][3];
        return q[0] * q[0] + q[1] * q[1] + q[2] * q[2] - (LD)g.r * g.r;
    };
    if (!BoxStraddles(ToD(si.p), e, f))
        st.Fail(where() + ": pError box " + Str(e) + " misses the surface");
    D3 wo = norm3(-1.0 * M.Vector(objRay.d));
    if (!Near(ToD(si.wo), wo, 1e-4)) st.Fail(where() + ": wo");
}

const SphereDef kSpheres[] = {
    {1.7, -1.7, 1.7, 360, "full sphere"},
    {1.3, -0.9, 1.0, 250, "partial sphere (z and phi cut)"},
    {0.8, 0.2, 0.8, 360, "cap above z = 0.2"},
    {2.0, 0.0, 2.0, 90, "quarter of a hemisphere"},
    {0.05, -0.04, 0.03, 300, "small partial sphere"},
};

void Report(const char *what, const Stats &st) {
    std::printf("[ sphere   ] %-42s %6ld rays %6ld hits %6ld ambiguous "
                "%5ld disagree; %ld grazing hits with t off by > 1e-4, "
                "%ld checked with a widened tolerance\n", what, st.rays,
                st.hits, st.ambiguous, st.ambiguousDisagree, st.tOver1e4,
                st.relaxed);
}

}  // namespace

TEST(Sphere, AgreesWithDoublePrecisionOracle) {
    lrt::Transform id;
    Affine I = Affine::Make(D3(1, 1, 1), D3(0, 0, 1), 0, D3(0, 0, 0));
    Rng rng(310);
    for (const SphereDef &def : kSpheres) {
        lrt::Sphere sphere(&id, &id, false, lrt::Float(def.r),
                           lrt::Float(def.zMin), lrt::Float(def.zMax),
                           lrt::Float(def.phiMaxDeg));
        // The sphere's parameters as the library stores them.
        SphereDef used = def;
        used.r = ToFloat(def.r);
        used.zMin = ToFloat(def.zMin);
        used.zMax = ToFloat(def.zMax);
        Stats st, tan;
        for (int i = 0; i < kRaysPerSphere; ++i) {
            TestRay tr = SphereRay(rng, used, i);
            lrt::Ray ray = ToRay(tr);
            TestRay exact{ToD(ray.o), ToD(ray.d), (double)ray.tMax};
            Oracle orc = SphereOracle(used, exact.o, exact.d, exact.tMax);
            lrt::Float tHit = -1;
            lrt::SurfaceInteraction si;
            bool hit = sphere.Intersect(ray, &tHit, &si);
            ASSERT_EQ(hit, sphere.IntersectP(ray)) << i;
            Compare(orc, hit, tHit, si, &sphere, used, I, false, true, exact,
                    IsTangentKind(i) ? tan : st);
        }
        Report((def.name + ", random").c_str(), st);
        Report((def.name + ", tangent").c_str(), tan);
        EXPECT_EQ(st.failures + tan.failures, 0) << def.name;
        EXPECT_LE(st.ambiguousDisagree,
                  kMaxAmbiguousDisagreementsPer100k * st.rays / 100000);
        EXPECT_GT(st.hits, st.rays / 10);
        EXPECT_GT(st.derivativeChecks, st.rays / 10);
    }
}

TEST(Sphere, TransformedMatchesObjectSpaceThroughInverse) {
    struct Xf {
        Affine M;
        bool rigid;  // dndu is compared only for rigid transformations
        const char *name;
    } xfs[] = {
        {Affine::Make(D3(1, 1, 1), D3(1, 2, 3), 37, D3(1, -2, 0.5)), true,
         "rotation"},
        {Affine::Make(D3(2, 0.5, 1.3), D3(-1, 0.3, 2), 71, D3(-3, 1, 2)),
         false, "nonuniform scale"},
        {Affine::Make(D3(-1, 1, 1), D3(0, 0, 1), 0, D3(0.5, 0, -1)), true,
         "mirror"},
        {Affine::Make(D3(-1.5, 0.7, 2), D3(2, -1, 1), 123, D3(4, 4, -4)),
         false, "mirrored nonuniform scale"},
        {Affine::Make(D3(3e3, 3e3, 3e3), D3(1, 1, 0), -50, D3(1e4, -2e4, 5e3)),
         false, "large uniform scale"},
    };
    Rng rng(311);
    long disagreeWithLrt = 0, compared = 0;
    for (const Xf &xf : xfs) {
        lrt::Transform o2w = xf.M.ToTransform();
        lrt::Transform w2o = Inverse(o2w);
        lrt::Transform id;
        EXPECT_EQ(o2w.SwapsHandedness(), xf.M.mirror);
        for (int s = 0; s < 2; ++s) {
            const SphereDef &def = kSpheres[s];
            SphereDef used = def;
            used.r = ToFloat(def.r);
            used.zMin = ToFloat(def.zMin);
            used.zMax = ToFloat(def.zMax);
            for (bool reverse : {false, true}) {
                lrt::Sphere world(&o2w, &w2o, reverse, lrt::Float(def.r),
                                  lrt::Float(def.zMin), lrt::Float(def.zMax),
                                  lrt::Float(def.phiMaxDeg));
                lrt::Sphere object(&id, &id, reverse, lrt::Float(def.r),
                                   lrt::Float(def.zMin), lrt::Float(def.zMax),
                                   lrt::Float(def.phiMaxDeg));
                EXPECT_EQ(world.transformSwapsHandedness, xf.M.mirror);
                lrt::Bounds3f wb = world.WorldBound();
                Stats st, tan;
                for (int i = 0; i < kRaysPerTransform; ++i) {
                    TestRay tr = SphereRay(rng, used, i);
                    // The world ray, rounded to Float...
                    lrt::Ray wr(ToP(xf.M.Point(tr.o)), ToV(xf.M.Vector(tr.d)),
                                lrt::Float(tr.tMax));
                    // ...and, in double, seen through the inverse.
                    TestRay ob{xf.M.InvPoint(ToD(wr.o)),
                               xf.M.InvVector(ToD(wr.d)), (double)wr.tMax};
                    Oracle orc = SphereOracle(used, ob.o, ob.d, ob.tMax);
                    lrt::Float tHit = -1;
                    lrt::SurfaceInteraction si;
                    bool hit = world.Intersect(wr, &tHit, &si);
                    ASSERT_EQ(hit, world.IntersectP(wr));
                    Stats &cs = IsTangentKind(i) ? tan : st;
                    Compare(orc, hit, tHit, si, &world, used, xf.M, reverse,
                            xf.rigid, ob, cs);
                    // The untransformed shape, given the object-space ray.
                    lrt::Float tObj = -1;
                    lrt::SurfaceInteraction siObj;
                    bool hitObj = object.Intersect(ToRay(ob), &tObj, &siObj);
                    ++compared;
                    if (hitObj != hit ||
                        (hit && std::abs(tObj - tHit) > 1e-4 * tHit)) {
                        if (orc.ambiguous || orc.posErr / len3(ob.d) >
                                                 1e-4 * orc.t)
                            ++disagreeWithLrt;
                        else
                            cs.Fail(std::string(xf.name) + ": world and "
                                    "object-space shapes disagree");
                    }
                    if (hit) {
                        lrt::Point3f p = si.p;
                        lrt::Float tol = 1e-4f * (wb.pMax.x - wb.pMin.x);
                        EXPECT_TRUE(p.x >= wb.pMin.x - tol &&
                                    p.y >= wb.pMin.y - tol &&
                                    p.z >= wb.pMin.z - tol &&
                                    p.x <= wb.pMax.x + tol &&
                                    p.y <= wb.pMax.y + tol &&
                                    p.z <= wb.pMax.z + tol);
                    }
                }
                std::string what = std::string(xf.name) + (reverse ? ", rev" :
                                                           "") + ", " +
                                   def.name.substr(0, 12);
                Report(what.c_str(), st);
                EXPECT_EQ(st.failures + tan.failures, 0) << what;
                EXPECT_LE(st.ambiguousDisagree,
                          kMaxAmbiguousDisagreementsPer100k * st.rays / 100000 +
                              2);
            }
        }
    }
    std::printf("[ sphere   ] world vs object-space lrt: %ld rays, %ld "
                "ambiguous disagreements\n", compared, disagreeWithLrt);
}

TEST(Sphere, SpecialRays) {
    lrt::Transform id;
    lrt::Sphere unit(&id, &id, false, 1, -1, 1, 360);
    lrt::Float tHit;
    lrt::SurfaceInteraction si;
    // Along the z axis: hits exactly at the poles, where the
    // parameterization degenerates. The normal must still be finite.
    for (int sgn : {-1, 1}) {
        lrt::Ray r(lrt::Point3f(0, 0, 5 * sgn), lrt::Vector3f(0, 0, -sgn));
        ASSERT_TRUE(unit.Intersect(r, &tHit, &si));
        EXPECT_NEAR(tHit, 4, 1e-5);
        EXPECT_FALSE(si.n.HasNaNs());
        EXPECT_FALSE(si.dpdu.HasNaNs());
        EXPECT_FALSE(si.dndu.HasNaNs());
        EXPECT_NEAR(si.n.z, sgn, 1e-6);
        EXPECT_NEAR(si.uv.y, sgn > 0 ? 1 : 0, 1e-5);
        EXPECT_LE(std::abs(lrt::Distance(si.p, lrt::Point3f(0, 0, 0)) - 1),
                  si.pError.Length());
    }
    // From the center: t is the radius over the direction's length.
    ASSERT_TRUE(unit.Intersect(
        lrt::Ray(lrt::Point3f(0, 0, 0), lrt::Vector3f(0, 2, 0)), &tHit, &si));
    EXPECT_NEAR(tHit, 0.5, 1e-6);
    EXPECT_NEAR(si.n.y, 1, 1e-6);  // outward also when hit from inside
    // Exactly tangent: either answer is acceptable, but no NaN.
    bool tangent = unit.Intersect(
        lrt::Ray(lrt::Point3f(-5, 1, 0), lrt::Vector3f(1, 0, 0)), &tHit, &si);
    if (tangent) {
        EXPECT_NEAR(tHit, 5, 1e-2);
        EXPECT_FALSE(si.n.HasNaNs());
    }
    // The seam of a full sphere at phi = 2 pi has no crack: rays at tiny
    // negative y hit at azimuths just below 2 pi.
    int seamHits = 0;
    for (int i = 1; i <= 1000; ++i) {
        lrt::Float y = -lrt::Float(i) * lrt::Float(1e-9);
        lrt::Ray r(lrt::Point3f(3, y, 0.1f), lrt::Vector3f(-1, 0, 0));
        if (unit.Intersect(r, &tHit, &si)) {
            ++seamHits;
            EXPECT_GT(si.uv.x, 0.99f);
        }
    }
    EXPECT_EQ(seamHits, 1000);
    // A ray whose tMax ends before the sphere, and one that starts past it.
    EXPECT_FALSE(unit.IntersectP(
        lrt::Ray(lrt::Point3f(0, 0, -5), lrt::Vector3f(0, 0, 1), 3.9f)));
    EXPECT_TRUE(unit.IntersectP(
        lrt::Ray(lrt::Point3f(0, 0, -5), lrt::Vector3f(0, 0, 1), 4.1f)));
    EXPECT_FALSE(unit.IntersectP(
        lrt::Ray(lrt::Point3f(0, 0, 5), lrt::Vector3f(0, 0, 1))));
    // Through the hole of a partial sphere to the far side: the near root
    // is clipped by zMax, the far one is kept.
    lrt::Sphere bowl(&id, &id, false, 1, -1, 0.5f, 360);
    ASSERT_TRUE(bowl.Intersect(
        lrt::Ray(lrt::Point3f(0, 0, 5), lrt::Vector3f(0, 0, -1)), &tHit, &si));
    EXPECT_NEAR(tHit, 6, 1e-5);
    EXPECT_NEAR(si.n.z, -1, 1e-5);  // the outside of the bowl faces down
    // Both roots clipped.
    lrt::Sphere band(&id, &id, false, 1, -0.1f, 0.1f, 360);
    EXPECT_FALSE(band.IntersectP(
        lrt::Ray(lrt::Point3f(0, 0, 5), lrt::Vector3f(0, 0, -1))));
}

TEST(Sphere, ObjectBound) {
    lrt::Transform id;
    lrt::Sphere s(&id, &id, false, 2, 1.5f, -0.5f, 90);  // heights swapped
    lrt::Bounds3f b = s.ObjectBound();
    EXPECT_EQ(b.pMin, lrt::Point3f(-2, -2, -0.5f));
    EXPECT_EQ(b.pMax, lrt::Point3f(2, 2, 1.5f));
    lrt::Sphere clamped(&id, &id, false, 1, -7, 9, 400);
    EXPECT_EQ(clamped.ObjectBound().pMin, lrt::Point3f(-1, -1, -1));
    EXPECT_EQ(clamped.ObjectBound().pMax, lrt::Point3f(1, 1, 1));
}

TEST(Sphere, ReverseOrientationFlipsNormalAndItsDerivatives) {
    lrt::Transform id;
    lrt::Sphere out(&id, &id, false, 1, -1, 1, 360);
    lrt::Sphere in(&id, &id, true, 1, -1, 1, 360);
    Rng rng(312);
    for (int i = 0; i < 1000; ++i) {
        D3 o = 5.0 * rng.Dir();
        lrt::Ray r(ToP(o), ToV(rng.InBall(0.9) - o));
        lrt::Float t1, t2;
        lrt::SurfaceInteraction a, b;
        ASSERT_TRUE(out.Intersect(r, &t1, &a));
        ASSERT_TRUE(in.Intersect(r, &t2, &b));
        EXPECT_EQ(t1, t2);
        EXPECT_EQ(b.n, -a.n);
        EXPECT_EQ(b.shading.n, -a.shading.n);
        EXPECT_EQ(b.dndu, -a.dndu);
        EXPECT_EQ(b.dndv, -a.dndv);
        EXPECT_EQ(b.dpdu, a.dpdu);
        EXPECT_TRUE(b.flipNormal);
        EXPECT_FALSE(a.flipNormal);
    }
}

TEST(Sphere, BadInput) {
    lrt::Transform id;
    const lrt::Float nan = std::numeric_limits<lrt::Float>::quiet_NaN();
    const lrt::Float inf = lrt::Infinity;
    EXPECT_THROW(lrt::Sphere(&id, &id, false, 0, -1, 1, 360),
                 std::invalid_argument);
    EXPECT_THROW(lrt::Sphere(&id, &id, false, -1, -1, 1, 360),
                 std::invalid_argument);
    EXPECT_THROW(lrt::Sphere(&id, &id, false, nan, -1, 1, 360),
                 std::invalid_argument);
    EXPECT_THROW(lrt::Sphere(&id, &id, false, inf, -1, 1, 360),
                 std::invalid_argument);
    EXPECT_THROW(lrt::Sphere(&id, &id, false, 1, 0.5f, 0.5f, 360),
                 std::invalid_argument);
    EXPECT_THROW(lrt::Sphere(&id, &id, false, 1, 2, 3, 360),
                 std::invalid_argument);
    EXPECT_THROW(lrt::Sphere(&id, &id, false, 1, nan, 1, 360),
                 std::invalid_argument);
    EXPECT_THROW(lrt::Sphere(&id, &id, false, 1, -1, 1, 0),
                 std::invalid_argument);
    EXPECT_THROW(lrt::Sphere(&id, &id, false, 1, -1, 1, -20),
                 std::invalid_argument);
    EXPECT_THROW(lrt::Sphere(&id, &id, false, 1, -1, 1, nan),
                 std::invalid_argument);
    EXPECT_THROW(lrt::Sphere(nullptr, &id, false, 1, -1, 1, 360),
                 std::invalid_argument);
    EXPECT_THROW(lrt::Sphere(&id, nullptr, false, 1, -1, 1, 360),
                 std::invalid_argument);

    lrt::Sphere s(&id, &id, false, 1, -1, 1, 360);
    const lrt::Float sentinel = 12345;
    lrt::Ray rays[] = {
        lrt::Ray(lrt::Point3f(0, 0, -5), lrt::Vector3f(0, 0, 0)),
        lrt::Ray(lrt::Point3f(0, 0, 0), lrt::Vector3f(0, 0, 0)),
        lrt::Ray(lrt::Point3f(nan, 0, -5), lrt::Vector3f(0, 0, 1)),
        lrt::Ray(lrt::Point3f(0, 0, -5), lrt::Vector3f(0, nan, 1)),
        lrt::Ray(lrt::Point3f(0, 0, -5), lrt::Vector3f(0, 0, 1), nan),
        lrt::Ray(lrt::Point3f(nan, nan, nan), lrt::Vector3f(nan, nan, nan)),
        lrt::Ray(lrt::Point3f(-inf, 0, 0), lrt::Vector3f(1, 0, 0)),
        lrt::Ray(lrt::Point3f(0, 0, -5), lrt::Vector3f(0, 0, inf)),
    };
    lrt::Transform rot = lrt::Rotate(30, lrt::Vector3f(1, 1, 0));
    lrt::Transform rotInv = Inverse(rot);
    lrt::Sphere moved(&rot, &rotInv, false, 1, -0.5f, 1, 200);
    for (const lrt::Sphere *sp : {&s, &moved})
        for (const lrt::Ray &r : rays) {
            lrt::Float tHit = sentinel;
            lrt::SurfaceInteraction si;
            EXPECT_FALSE(sp->Intersect(r, &tHit, &si)) << r;
            EXPECT_EQ(tHit, sentinel);
            EXPECT_FALSE(sp->IntersectP(r)) << r;
        }
}
