// Chapter 5, the slab test: random tests against independent oracles.
//
// - The box oracle intersects the ray with the box's six face rectangles
//   (and tests the origin for inclusion) in a wider precision than Float.
// - The triangle oracle is a Moller-Trumbore ray/triangle test in the same
//   wider precision; it checks that the box test is conservative: a ray that
//   the box test rejects never hits a triangle inside the box.
// - The tightness test builds rays that graze a box edge, with exact
//   (binary128) arithmetic deciding that they touch it, and shows that the
//   widening factor 1 + 2 gamma(3) is needed, sufficient, and attained.
//
// The oracles run in Wide precision: double when Float is float, long double
// (64-bit significand on x86-64) when Float is double. Whenever Wide's answer
// disagrees with a slab test, it is recomputed in binary128 (113 bits) where
// the compiler offers it, and that answer is the verdict: a ray nearly
// parallel to a face far from the origin can miss a box by less than Wide
// resolves in the coordinates, although the slab test, which works with
// parameter values, resolves it.

#include "lrt/core/slabtest.h"

#include "exercise_calls.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <random>
#include <string>
#include <type_traits>
#include <vector>

using namespace lrt;

namespace {

using Wide = std::conditional<std::is_same<Float, float>::value, double,
                              long double>::type;
#if defined(__SIZEOF_FLOAT128__)
using Exact = __float128;
#else
using Exact = long double;
#endif

constexpr int kOracleCases = 1000000;
constexpr int kTriangleCases = 1000000;
constexpr int kTightnessTries = 3000000;
// A reported hit of a ray that misses the box must come within this many
// units of roundoff (relative to the ray parameter) of touching it. The text
// derives about 13u for the far values and 10u for tMax.
constexpr double kMarginInU = 14;

const Float kInf = std::numeric_limits<Float>::infinity();
const Float kU = std::numeric_limits<Float>::epsilon() / 2;

std::string Hex(double v) {
    char buf[64];
    std::snprintf(buf, sizeof(buf), "%a", v);
    return buf;
}

std::string Describe(const Bounds3f &b, const Ray &r) {
    return "box [" + Hex(b.pMin.x) + " " + Hex(b.pMin.y) + " " +
           Hex(b.pMin.z) + "] - [" + Hex(b.pMax.x) + " " + Hex(b.pMax.y) +
           " " + Hex(b.pMax.z) + "], ray o (" + Hex(r.o.x) + " " +
           Hex(r.o.y) + " " + Hex(r.o.z) + ") d (" + Hex(r.d.x) + " " +
           Hex(r.d.y) + " " + Hex(r.d.z) + ") tMax " + Hex(r.tMax);
}

class Sampler {
  public:
    explicit Sampler(uint64_t seed) : rng(seed) {}
    double Uniform(double a, double b) {
        return a + (b - a) * std::uniform_real_distribution<double>()(rng);
    }
    int Int(int lo, int hi) {  // inclusive
        return std::uniform_int_distribution<int>(lo, hi)(rng);
    }
    bool Chance(double p) { return Uniform(0, 1) < p; }
    Float Step(Float v, int steps) {  // move v by `steps` Floats
        for (; steps > 0; --steps) v = std::nextafter(v, kInf);
        for (; steps < 0; ++steps) v = std::nextafter(v, -kInf);
        return v;
    }

  private:
    std::mt19937_64 rng;
};

bool BothForms(const Bounds3f &b, const Ray &r, Float *t0, Float *t1) {
    bool hit = ex::IntersectP(b, r, t0, t1);
    Vector3f invDir(1 / r.d.x, 1 / r.d.y, 1 / r.d.z);
    int dirIsNeg[3] = {invDir.x < 0, invDir.y < 0, invDir.z < 0};
    bool fast = ex::IntersectP(b, r, invDir, dirIsNeg);
    EXPECT_EQ(hit, fast) << "the two forms disagree: " << Describe(b, r);
    return hit;
}

template <typename W> struct WideRay {
    W o[3], d[3], tMax;
    explicit WideRay(const Ray &r) : tMax(r.tMax) {
        for (int i = 0; i < 3; ++i) {
            o[i] = r.o[i];
            d[i] = r.d[i];
        }
    }
};

// Oracle 1: the closed box is hit if the origin is in it or if the ray
// crosses one of its six face rectangles at some t in [0, tMax].
template <typename W> bool OracleBoxHit(const Bounds3f &b, const Ray &ray) {
    WideRay<W> r(ray);
    W lo[3], hi[3];
    bool inside = true;
    for (int i = 0; i < 3; ++i) {
        lo[i] = b.pMin[i];
        hi[i] = b.pMax[i];
        if (r.o[i] < lo[i] || r.o[i] > hi[i]) inside = false;
    }
    if (inside) return r.tMax >= 0;
    for (int a = 0; a < 3; ++a) {
        if (r.d[a] == 0) continue;
        for (W plane : {lo[a], hi[a]}) {
            W t = (plane - r.o[a]) / r.d[a];
            if (!(t >= 0 && t <= r.tMax)) continue;
            bool onFace = true;
            for (int k = 0; k < 3; ++k) {
                if (k == a) continue;
                W p = r.o[k] + t * r.d[k];
                if (p < lo[k] || p > hi[k]) onFace = false;
            }
            if (onFace) return true;
        }
    }
    return false;
}

// The slab interval [T, U] in Wide precision, used to measure how far a
// reported near miss is from touching the box. False if the ray is parallel
// to a slab and outside it (no margin can explain a hit then).
bool WideInterval(const Bounds3f &b, const Ray &ray, Wide *T, Wide *U) {
    WideRay<Wide> r(ray);
    Wide t0 = 0, t1 = r.tMax;
    for (int i = 0; i < 3; ++i) {
        Wide lo = b.pMin[i], hi = b.pMax[i];
        if (r.d[i] == 0) {
            if (r.o[i] < lo || r.o[i] > hi) return false;
            continue;
        }
        Wide ta = (lo - r.o[i]) / r.d[i], tb = (hi - r.o[i]) / r.d[i];
        t0 = std::max(t0, std::min(ta, tb));
        t1 = std::min(t1, std::max(ta, tb));
    }
    *T = t0;
    *U = t1;
    return true;
}

// True if the ray misses the box by a relative margin in t of at least
// 2^-30, far more than the few units of Wide roundoff in T and U, so that
// the exact ray surely misses it.
bool ClearlyMisses(const Bounds3f &b, const Ray &r) {
    Wide T, U;
    if (!WideInterval(b, r, &T, &U)) return true;
    return U < 0 || T - U > std::ldexp(Wide(1), -30) * std::abs(U);
}

// True if the ray passes through the box within a few units of roundoff
// (relative to t) of missing it: the cases whose slab values, rounded, can
// cross, so that a test without the widening of Section 5.4 misses the box.
// A random test that holds none of them cannot tell a robust slab test from
// a naive one.
bool Grazes(const Bounds3f &b, const Ray &r) {
    Wide T, U;
    return WideInterval(b, r, &T, &U) && U > 0 && T <= U &&
           U - T <= 8 * Wide(kU) * U;
}

// Distance from a point to a box, in Wide precision.
Wide DistanceToBox(const Bounds3f &b, const Wide p[3]) {
    Wide sum = 0;
    for (int i = 0; i < 3; ++i) {
        Wide lo = b.pMin[i], hi = b.pMax[i];
        Wide e = p[i] < lo ? lo - p[i] : (p[i] > hi ? p[i] - hi : 0);
        sum += e * e;
    }
    return std::sqrt(sum);
}

// Oracle 2: closed ray/triangle intersection (Moller-Trumbore) in Wide
// precision, edges and vertices included, t in [0, tMax].
template <typename W>
bool OracleTriangleHit(const Point3f v[3], const Ray &ray, W *tHit) {
    WideRay<W> r(ray);
    W p0[3], e1[3], e2[3];
    for (int i = 0; i < 3; ++i) {
        p0[i] = v[0][i];
        e1[i] = W(v[1][i]) - p0[i];
        e2[i] = W(v[2][i]) - p0[i];
    }
    auto cross = [](const W a[3], const W b[3], W c[3]) {
        c[0] = a[1] * b[2] - a[2] * b[1];
        c[1] = a[2] * b[0] - a[0] * b[2];
        c[2] = a[0] * b[1] - a[1] * b[0];
    };
    auto dot = [](const W a[3], const W b[3]) {
        return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    };
    W pv[3], tv[3], qv[3];
    cross(r.d, e2, pv);
    W det = dot(e1, pv);
    if (det == 0) return false;
    for (int i = 0; i < 3; ++i) tv[i] = r.o[i] - p0[i];
    W u = dot(tv, pv) / det;
    if (u < 0 || u > 1) return false;
    cross(tv, e1, qv);
    W v2 = dot(r.d, qv) / det;
    if (v2 < 0 || u + v2 > 1) return false;
    W t = dot(e2, qv) / det;
    if (t < 0 || t > r.tMax) return false;
    *tHit = t;
    return true;
}

Point3f RandomPoint(Sampler &s, double lo, double hi) {
    return Point3f(Float(s.Uniform(lo, hi)), Float(s.Uniform(lo, hi)),
                   Float(s.Uniform(lo, hi)));
}

Point3f Scaled(const Point3f &p, Float scale, const Point3f &offset) {
    return Point3f(p.x * scale + offset.x, p.y * scale + offset.y,
                   p.z * scale + offset.z);
}

Bounds3f BoundsOf(const Point3f &a, const Point3f &b, const Point3f &c) {
    return Bounds3f(Point3f(std::min({a.x, b.x, c.x}),
                            std::min({a.y, b.y, c.y}),
                            std::min({a.z, b.z, c.z})),
                    Point3f(std::max({a.x, b.x, c.x}),
                            std::max({a.y, b.y, c.y}),
                            std::max({a.z, b.z, c.z})));
}

// A ray from o toward target, sometimes with one direction component
// replaced by +0 or -0 (and then sometimes with the origin moved onto a
// plane of the box on that axis, the 0 * infinity case).
Vector3f DirectionTo(Sampler &s, Point3f *o, const Point3f &target,
                     const Bounds3f &b) {
    Vector3f d(target.x - o->x, target.y - o->y, target.z - o->z);
    if (s.Chance(0.08)) {
        int a = s.Int(0, 2);
        d[a] = s.Chance(0.5) ? Float(0) : -Float(0);
        if (s.Chance(0.3)) (*o)[a] = b[s.Int(0, 1)][a];
    }
    return d;
}

// The scale and offset of a random scene: scales 2^-20 .. 2^20, and now
// and then an offset of up to 1000 box sizes.
void RandomFrame(Sampler &s, Float *scale, Point3f *offset) {
    *scale = std::ldexp(Float(1), s.Int(-20, 20));
    *offset = Point3f(0, 0, 0);
    if (s.Chance(0.2)) {
        Point3f off = RandomPoint(s, -1000, 1000);
        *offset = Point3f(off.x * *scale, off.y * *scale, off.z * *scale);
    }
}

}  // namespace

// The slab test against the six-face oracle over random boxes (15% of them
// flat on one axis) and rays aimed at edges, corners, the box, and anywhere,
// with infinite, random and near-boundary tMax. Every oracle hit must be
// reported; a reported hit that the oracle calls a miss must come within
// kMarginInU units of roundoff of touching the box.
EXERCISE_TEST(Ex5_9_SlabTest, AgreesWithSixFaceOracle) {
    Sampler s(calls::Seed(0x5eed0005));
    long oracleHits = 0, slabHits = 0, nearMisses = 0, falseMisses = 0;
    long grazingHits = 0, flatBoxes = 0, parallel = 0;
    long exactVerdicts = 0;
    double maxGapInU = 0, maxDistanceInU = 0;
    const int cases = calls::Cases(kOracleCases, 100000);
    for (int n = 0; n < cases; ++n) {
        Float scale;
        Point3f offset;
        RandomFrame(s, &scale, &offset);
        Point3f p = RandomPoint(s, -1, 1), q = RandomPoint(s, -1, 1);
        if (s.Chance(0.15)) {
            int a = s.Int(0, 2);
            q[a] = p[a];
            ++flatBoxes;
        }
        Bounds3f b(Scaled(p, scale, offset), Scaled(q, scale, offset));
        Point3f o = Scaled(RandomPoint(s, -4, 4), scale, offset);
        Point3f target;
        double kind = s.Uniform(0, 1);
        if (kind < 0.4) {
            // A point on an edge, moved by a few Floats: grazing rays.
            int a = s.Int(0, 2);
            for (int k = 0; k < 3; ++k)
                target[k] = b[s.Int(0, 1)][k];
            Float t = Float(s.Uniform(0, 1));
            target[a] = b.pMin[a] + t * (b.pMax[a] - b.pMin[a]);
            for (int k = 0; k < 3; ++k)
                target[k] = s.Step(target[k], s.Int(-3, 3));
        } else if (kind < 0.5) {
            for (int k = 0; k < 3; ++k) target[k] = b[s.Int(0, 1)][k];
        } else if (kind < 0.8) {
            for (int k = 0; k < 3; ++k) {
                Float lo = b.pMin[k], hi = b.pMax[k], pad = (hi - lo) / 10;
                target[k] = Float(s.Uniform(lo - pad, hi + pad));
            }
        } else {
            target = Scaled(RandomPoint(s, -4, 4), scale, offset);
        }
        Vector3f d = DirectionTo(s, &o, target, b);
        if (d.x == 0 || d.y == 0 || d.z == 0) ++parallel;
        Ray r(o, d, kInf);
        double tKind = s.Uniform(0, 1);
        Wide T, U;
        if (tKind < 0.2) {
            r.tMax = Float(s.Uniform(0, 2));
        } else if (tKind < 0.5 && WideInterval(b, r, &T, &U) &&
                   std::isfinite(double(T)) && std::isfinite(double(U))) {
            Wide edge = s.Chance(0.5) ? T : U;
            r.tMax = std::max(Float(0), s.Step(Float(edge), s.Int(-8, 8)));
        }

        Float t0 = -1, t1 = -1;
        bool hit = BothForms(b, r, &t0, &t1);
        // Every disagreement, every grazing ray and every miss that is not a
        // miss by a wide margin is judged in binary128.
        bool oracle = OracleBoxHit<Wide>(b, r);
        bool grazes = Grazes(b, r);
        if (oracle != hit || grazes || (!oracle && !ClearlyMisses(b, r))) {
            oracle = OracleBoxHit<Exact>(b, r);
            ++exactVerdicts;
        }
        oracleHits += oracle;
        slabHits += hit;
        if (oracle && grazes) ++grazingHits;
        if (oracle && !hit) {
            if (++falseMisses <= 10)
                ADD_FAILURE() << "missed a box the ray hits: "
                              << Describe(b, r);
            continue;
        }
        bool haveInterval = WideInterval(b, r, &T, &U);
        if (hit && !oracle) {
            ++nearMisses;
            // How far from touching the box is this ray?
            double gapInU = !haveInterval || U <= 0
                                ? std::numeric_limits<double>::infinity()
                                : double((T - U) / U) / kU;
            maxGapInU = std::max(maxGapInU, gapInU);
            EXPECT_LE(gapInU, kMarginInU) << Describe(b, r);
            if (haveInterval && U > 0) {
                WideRay<Wide> wr(r);
                Wide at[3], len2 = 0;
                for (int i = 0; i < 3; ++i) {
                    at[i] = wr.o[i] + U * wr.d[i];
                    len2 += wr.d[i] * wr.d[i];
                }
                Wide dist = DistanceToBox(b, at);
                double distInU =
                    double(dist / (U * std::sqrt(len2))) / kU;
                maxDistanceInU = std::max(maxDistanceInU, distInU);
                // Where it leaves the last slab, the ray is within that many
                // units of roundoff, relative to the distance travelled, of
                // the box.
                EXPECT_LE(distInU, kMarginInU) << Describe(b, r);
            }
        }
        if (hit && oracle && haveInterval && T <= U) {
            // The reported interval is the true one, to within roundoff.
            if (T > 0) {
                EXPECT_GE(Wide(t0), T * (1 - 4 * Wide(kU))) << Describe(b, r);
                EXPECT_LE(Wide(t0), T * (1 + 4 * Wide(kU))) << Describe(b, r);
            } else {
                EXPECT_EQ(t0, Float(0)) << Describe(b, r);
            }
            if (std::isfinite(double(U))) {
                EXPECT_GE(Wide(t1), U * (1 - 2 * Wide(kU))) << Describe(b, r);
                EXPECT_LE(Wide(t1), U * (1 + 11 * Wide(kU)))
                    << Describe(b, r);
            }
        }
    }
    std::printf("[ stats    ] %d cases (%ld flat boxes, %ld rays with a zero "
                "direction component): oracle hits %ld, slab-test hits %ld\n"
                "[ stats    ] false misses %ld; near-miss hits %ld, the "
                "farthest %.2f u in t and %.2f u in distance/length; "
                "grazing hits %ld; binary128 verdicts %ld\n",
                cases, flatBoxes, parallel, oracleHits, slabHits,
                falseMisses, nearMisses, maxGapInU, maxDistanceInU,
                grazingHits, exactVerdicts);
    EXPECT_EQ(falseMisses, 0);
    // The cases include grazing rays, which need the widening.
    EXPECT_GT(grazingHits, cases / 1000);
    // And they are not trivial: both outcomes are common.
    EXPECT_GT(oracleHits, cases / 5);
    EXPECT_LT(oracleHits, cases - cases / 5);
}

// Conservativeness: a ray that the box test rejects never hits a triangle
// inside the box. Triangles are general, lie in an axis-aligned plane, or
// have an edge along an edge of their box; the box is the triangle's bounds
// or larger; rays aim at edges, vertices, the interior and around, with
// tMax infinite, random, or exactly at the triangle hit.
EXERCISE_TEST(Ex5_11_SlabTest, ConservativeForTrianglesInsideTheBox) {
    Sampler s(calls::Seed(0xc0115e05));
    long triangleHits = 0, grazingHits = 0, tMaxAtEntry = 0;
    long falseMisses = 0, exactVerdicts = 0;
    const int cases = calls::Cases(kTriangleCases, 100000);
    for (int n = 0; n < cases; ++n) {
        Float scale;
        Point3f offset;
        RandomFrame(s, &scale, &offset);
        Point3f v[3];
        double kind = s.Uniform(0, 1);
        for (int k = 0; k < 3; ++k) v[k] = RandomPoint(s, -1, 1);
        if (kind < 0.3) {
            // v0 v1 parallel to axis a and on the lower edge of the box in
            // the other two axes.
            int a = s.Int(0, 2), b1 = (a + 1) % 3, b2 = (a + 2) % 3;
            v[1] = v[0];
            v[1][a] = Float(s.Uniform(-1, 1));
            v[2][b1] = v[0][b1] + Float(s.Uniform(0.01, 1));
            v[2][b2] = v[0][b2] + Float(s.Uniform(0.01, 1));
        } else if (kind < 0.5) {
            int a = s.Int(0, 2);
            v[1][a] = v[2][a] = v[0][a];
        }
        for (int k = 0; k < 3; ++k) v[k] = Scaled(v[k], scale, offset);
        Bounds3f b = BoundsOf(v[0], v[1], v[2]);
        if (s.Chance(0.25)) {
            for (int k = 0; k < 3; ++k) {
                Float ext = (b.pMax[k] - b.pMin[k]) + scale;
                b.pMin[k] -= Float(s.Uniform(0, 0.3)) * ext;
                b.pMax[k] += Float(s.Uniform(0, 0.3)) * ext;
            }
        }
        Point3f o = Scaled(RandomPoint(s, -4, 4), scale, offset);
        Point3f target;
        double aim = s.Uniform(0, 1);
        if (aim < 0.4) {
            int i = s.Int(0, 2), j = (i + 1) % 3;
            Float t = Float(s.Uniform(0, 1));
            for (int k = 0; k < 3; ++k)
                target[k] = s.Step(v[i][k] + t * (v[j][k] - v[i][k]),
                                   s.Int(-2, 2));
        } else if (aim < 0.55) {
            target = v[s.Int(0, 2)];
        } else if (aim < 0.8) {
            double b1 = s.Uniform(0, 1), b2 = s.Uniform(0, 1);
            if (b1 + b2 > 1) {
                b1 = 1 - b1;
                b2 = 1 - b2;
            }
            for (int k = 0; k < 3; ++k)
                target[k] = Float(v[0][k] + b1 * (v[1][k] - v[0][k]) +
                                  b2 * (v[2][k] - v[0][k]));
        } else {
            for (int k = 0; k < 3; ++k) {
                Float lo = b.pMin[k], hi = b.pMax[k];
                Float pad = (hi - lo) / 5 + scale / 100;
                target[k] = Float(s.Uniform(lo - pad, hi + pad));
            }
        }
        Vector3f d = DirectionTo(s, &o, target, b);
        Ray r(o, d, kInf);
        double tKind = s.Uniform(0, 1);
        Wide tHit;
        if (tKind < 0.25) {
            r.tMax = Float(s.Uniform(0, 2));
        } else if (tKind < 0.6 && OracleTriangleHit<Wide>(v, r, &tHit)) {
            // tMax at the hit: the Float at or just above it, or a step
            // or two further either way.
            Float t = Float(tHit);
            if (Wide(t) < tHit) t = std::nextafter(t, kInf);
            r.tMax = s.Chance(0.6) ? t : s.Step(t, s.Int(-2, 2));
        }

        Float t0, t1;
        bool hit = BothForms(b, r, &t0, &t1);
        // Whenever the box test says miss, binary128 decides.
        bool triangle = OracleTriangleHit<Wide>(v, r, &tHit);
        if (!hit) {
            Exact tExact = 0;  // read below even when there is no hit
            ++exactVerdicts;
            triangle = OracleTriangleHit<Exact>(v, r, &tExact);
            tHit = Wide(tExact);
        }
        if (!triangle) continue;
        ++triangleHits;
        // Rays that graze the box, and rays whose tMax is within roundoff of
        // where they enter it: the cases for the widening of the far values
        // and of tMax.
        Ray unbounded = r;
        unbounded.tMax = kInf;
        Wide T, U;
        if (Grazes(b, unbounded)) ++grazingHits;
        if (std::isfinite(r.tMax) && WideInterval(b, unbounded, &T, &U) &&
            std::abs(Wide(r.tMax) - T) <= 8 * Wide(kU) * Wide(r.tMax))
            ++tMaxAtEntry;
        if (!hit) {
            if (++falseMisses <= 10)
                ADD_FAILURE() << "rejected a box whose triangle the ray "
                              << "hits at t = " << Hex(double(tHit)) << ": "
                              << Describe(b, r);
        }
    }
    std::printf("[ stats    ] %d cases: triangle hits %ld, box misses among "
                "them %ld; grazing the box %ld, tMax at the entry %ld; "
                "binary128 verdicts %ld\n",
                cases, triangleHits, falseMisses, grazingHits, tMaxAtEntry,
                exactVerdicts);
    EXPECT_EQ(falseMisses, 0);
    EXPECT_GT(triangleHits, cases / 4);
    // Both halves of the widening matter for these cases.
    EXPECT_GT(grazingHits, cases / 1000);
    EXPECT_GT(tMaxAtEntry, cases / 1000);
}

#if defined(__SIZEOF_FLOAT128__)
namespace {

// A ray from o with direction (dx, dy, 0), dx, dy > 0, enters the slab
// x >= bx at tn = (bx - ox) / dx and leaves the slab y <= by at
// tf = (by - oy) / dy. Is tn <= tf, exactly? The operands are chosen so
// that both products are exact in binary128 (see the test).
bool EnterNoLaterThanLeave(Float bx, Float ox, Float dx, Float by, Float oy,
                           Float dy) {
    return (Exact(bx) - Exact(ox)) * Exact(dy) <=
           (Exact(by) - Exact(oy)) * Exact(dx);
}

// The relative error of Float's 1/d, exactly, in units of u.
double ReciprocalErrorInU(Float d) {
    Float r = 1 / d;
    return double(Exact(r) * Exact(d) - 1) / kU;
}

// The relative error of Float's a - b, exactly, in units of u.
double DifferenceErrorInU(Float a, Float b) {
    Exact exact = Exact(a) - Exact(b);
    return double((Exact(a - b) - exact) / exact) / kU;
}

}  // namespace

// The widening factor is needed, sufficient, and attained. Rays graze the
// edge where the slab x >= bx meets y <= by, with binary128 arithmetic
// deciding that they touch it (tn <= tf exactly), and with operands chosen
// so that the roundings push the computed near value up and the far value
// down as far as they go. For every such ray, the computed tn must not
// exceed the widened computed tf (and the library must report a hit). The
// test also counts rays for which the comparison holds with equality, and
// for which a smaller factor, 1 + 4u, or none would fail.
EXERCISE_TEST(Ex5_11_SlabTest, WideningFactorIsNeededSufficientAndTight) {
    // A fixed seed: the construction below must yield its rare cases (the
    // equality and the 1 + 4u failures), which are about the bound, not the
    // code under test.
    Sampler s(0x7187);
    // Directions whose reciprocal rounds up (for x) or down (for y) by
    // nearly the most it can, 0.9u or more.
    std::vector<Float> up, down;
    while (up.size() < 2000 || down.size() < 2000) {
        Float d = Float(s.Uniform(1, 2));
        double e = ReciprocalErrorInU(d);
        if (e >= 0.9 && up.size() < 2000) up.push_back(d);
        if (e <= -0.9 && down.size() < 2000) down.push_back(d);
    }
    const Float widen = 1 + 2 * gamma(3);
    const Float smaller = 1 + 4 * kU;
    long tried = 0, equal = 0, smallerFails = 0, unwidenedFails = 0;
    long widenedFails = 0, libraryMisses = 0;
    for (int n = 0; n < kTightnessTries; ++n) {
        Float dx = up[s.Int(0, int(up.size()) - 1)];
        Float dy = down[s.Int(0, int(down.size()) - 1)];
        // by in [4, 7.5), oy and ox in [-1/8, -1/16): then bx < 16, and
        // every difference needs at most 60 significant bits, so that the
        // products in EnterNoLaterThanLeave are exact even for double.
        Float by = Float(s.Uniform(4, 7.5));
        Float oy = Float(-s.Uniform(0.0625, 0.125));
        if (DifferenceErrorInU(by, oy) > -0.5) continue;  // want rounding down
        Float ox = Float(-s.Uniform(0.0625, 0.125));
        // The largest bx with tn <= tf: the ray touches the edge or passes
        // within a hair of it on the inside.
        Float bx = Float(Wide(ox) + (Wide(by) - Wide(oy)) / Wide(dy) *
                                        Wide(dx));
        while (!EnterNoLaterThanLeave(bx, ox, dx, by, oy, dy))
            bx = std::nextafter(bx, -kInf);
        while (EnterNoLaterThanLeave(std::nextafter(bx, kInf), ox, dx, by, oy,
                                     dy))
            bx = std::nextafter(bx, kInf);
        if (DifferenceErrorInU(bx, ox) < 0.5) continue;  // want rounding up
        ++tried;
        Float tn = (bx - ox) * (1 / dx);
        Float tf = (by - oy) * (1 / dy);
        Float widened = tf * widen;
        if (tn > widened) ++widenedFails;
        if (tn == widened) ++equal;
        if (tn > tf * smaller) ++smallerFails;
        if (tn > tf) ++unwidenedFails;
        // The same ray and a box with that edge, through the library.
        Bounds3f b(Point3f(bx, by - 1, 0), Point3f(bx + 1, by, 1));
        Ray r(Point3f(ox, oy, Float(0.5)), Vector3f(dx, dy, 0));
        Float t0, t1;
        if (!BothForms(b, r, &t0, &t1)) {
            if (++libraryMisses <= 10)
                ADD_FAILURE() << "missed a grazing ray: " << Describe(b, r);
        }
    }
    std::printf("[ stats    ] %ld grazing rays: widened test fails %ld, "
                "equality %ld; factor 1 + 4u fails %ld; unwidened fails "
                "%ld\n",
                tried, widenedFails, equal, smallerFails, unwidenedFails);
    EXPECT_GT(tried, 50000);
    EXPECT_EQ(widenedFails, 0);
    EXPECT_EQ(libraryMisses, 0);
    EXPECT_GT(equal, 0);
    EXPECT_GT(smallerFails, 0);
    EXPECT_GT(unwidenedFails, 0);
}
#endif
