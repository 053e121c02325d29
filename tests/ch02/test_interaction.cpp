// Chapter 2 (second part): Interaction, SurfaceInteraction, and
// transforming a SurfaceInteraction.

#include "lrt/core/interaction.h"
#include "lrt/core/transform.h"

#include "exercise_calls.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

using namespace lrt;

namespace {

using LD = long double;
constexpr Float kEps = std::numeric_limits<Float>::epsilon();

Float Uniform(std::mt19937_64 &rng, double lo, double hi) {
    return Float(std::uniform_real_distribution<double>(lo, hi)(rng));
}

Vector3f RandomVector(std::mt19937_64 &rng, double lo, double hi) {
    return Vector3f(Uniform(rng, lo, hi), Uniform(rng, lo, hi),
                    Uniform(rng, lo, hi));
}

Point3f RandomPoint(std::mt19937_64 &rng, double lo, double hi) {
    return Point3f(Uniform(rng, lo, hi), Uniform(rng, lo, hi),
                   Uniform(rng, lo, hi));
}

Normal3f RandomNormal(std::mt19937_64 &rng) {
    return Normal3f(RandomVector(rng, -1, 1));
}

template <typename A, typename B>
LD DotLD(const A &a, const B &b) {
    return LD(a.x) * b.x + LD(a.y) * b.y + LD(a.z) * b.z;
}

template <typename A>
LD LengthLD(const A &a) {
    return std::sqrt(DotLD(a, a));
}

// Cosine of the angle between a and b, in long double.
template <typename A, typename B>
LD CosLD(const A &a, const B &b) {
    return DotLD(a, b) / (LengthLD(a) * LengthLD(b));
}

// Cross product in long double.
struct V3 {
    LD x, y, z;
};
V3 CrossLD(const Vector3f &a, const Vector3f &b) {
    return {LD(a.y) * b.z - LD(a.z) * b.y, LD(a.z) * b.x - LD(a.x) * b.z,
            LD(a.x) * b.y - LD(a.y) * b.x};
}

// Two tangents that are clearly not parallel.
void RandomTangents(std::mt19937_64 &rng, Vector3f *dpdu, Vector3f *dpdv) {
    do {
        *dpdu = RandomVector(rng, -2, 2);
        *dpdv = RandomVector(rng, -2, 2);
    } while (Cross(*dpdu, *dpdv).Length() <
             Float(0.2) * dpdu->Length() * dpdv->Length());
}

// A random transformation: rotation, scale (optionally mirroring) and
// translation, with a linear part whose condition number is at most 16.
Transform RandomTransform(std::mt19937_64 &rng, bool mirror) {
    Vector3f axis = RandomVector(rng, -1, 1);
    while (axis.LengthSquared() < Float(1e-2)) axis = RandomVector(rng, -1, 1);
    Float sx = Uniform(rng, 0.25, 4), sy = Uniform(rng, 0.25, 4),
          sz = Uniform(rng, 0.25, 4);
    if (mirror) sy = -sy;
    return Translate(RandomVector(rng, -10, 10)) *
           Rotate(Uniform(rng, -180, 180), axis) * Scale(sx, sy, sz) *
           Rotate(Uniform(rng, -180, 180), Vector3f(axis.z, axis.x, axis.y));
}

// Random arguments for the SurfaceInteraction constructors.
struct ConstructorArgs {
    Vector3f dpdu, dpdv;
    Normal3f dndu, dndv;
    Point3f p;
    Vector3f pError, wo;
    Point2f uv;
};

ConstructorArgs RandomConstructorArgs(std::mt19937_64 &rng) {
    ConstructorArgs a;
    RandomTangents(rng, &a.dpdu, &a.dpdv);
    a.dndu = RandomNormal(rng);
    a.dndv = RandomNormal(rng);
    a.p = RandomPoint(rng, -5, 5);
    a.pError = Vector3f(1e-4f, 2e-4f, 3e-4f);
    a.wo = RandomVector(rng, -1, 1);
    a.uv = Point2f(Uniform(rng, 0, 1), Uniform(rng, 0, 1));
    return a;
}

SurfaceInteraction RandomSurfaceInteraction(std::mt19937_64 &rng,
                                            bool flipNormal) {
    Vector3f dpdu, dpdv;
    RandomTangents(rng, &dpdu, &dpdv);
    Point3f p = RandomPoint(rng, -5, 5);
    Vector3f pError(Uniform(rng, 0, 1e-4), Uniform(rng, 0, 1e-4),
                    Uniform(rng, 0, 1e-4));
    return SurfaceInteraction(p, pError, Point2f(Uniform(rng, 0, 1),
                                                 Uniform(rng, 0, 1)),
                              RandomVector(rng, -1, 1), dpdu, dpdv,
                              RandomNormal(rng), RandomNormal(rng),
                              Uniform(rng, 0, 1), flipNormal,
                              int(Uniform(rng, 0, 100)));
}

}  // namespace

// ---------------------------------------------------------------------------
// Interaction

TEST(Interaction, DefaultIsNotOnASurface) {
    Interaction in;
    EXPECT_EQ(in.p, Point3f(0, 0, 0));
    EXPECT_EQ(in.time, 0);
    EXPECT_EQ(in.pError, Vector3f(0, 0, 0));
    EXPECT_EQ(in.wo, Vector3f(0, 0, 0));
    EXPECT_EQ(in.n, Normal3f(0, 0, 0));
    EXPECT_FALSE(in.IsSurfaceInteraction());
}

TEST(Interaction, ConstructorsStoreTheirArguments) {
    Interaction a(Point3f(1, 2, 3), Normal3f(0, 0, 1), Vector3f(1e-3f, 0, 0),
                  Vector3f(0, 3, 4), 0.5);
    EXPECT_EQ(a.p, Point3f(1, 2, 3));
    EXPECT_EQ(a.n, Normal3f(0, 0, 1));
    EXPECT_EQ(a.pError, Vector3f(1e-3f, 0, 0));
    EXPECT_EQ(a.time, Float(0.5));
    // wo is normalized.
    EXPECT_NEAR(a.wo.x, 0, kEps);
    EXPECT_NEAR(a.wo.y, 0.6, 2 * kEps);
    EXPECT_NEAR(a.wo.z, 0.8, 2 * kEps);
    EXPECT_TRUE(a.IsSurfaceInteraction());

    Interaction b(Point3f(1, 2, 3), Vector3f(-2, 0, 0), 0.25);
    EXPECT_EQ(b.wo, Vector3f(-1, 0, 0));
    EXPECT_EQ(b.time, Float(0.25));
    EXPECT_FALSE(b.IsSurfaceInteraction());

    Interaction c(Point3f(4, 5, 6), 2);
    EXPECT_EQ(c.p, Point3f(4, 5, 6));
    EXPECT_EQ(c.time, Float(2));
    EXPECT_EQ(c.wo, Vector3f(0, 0, 0));
    EXPECT_FALSE(c.IsSurfaceInteraction());
}

TEST(Interaction, ZeroOutgoingDirectionStaysZero) {
    Interaction a(Point3f(1, 2, 3), Normal3f(0, 1, 0), Vector3f(),
                  Vector3f(0, 0, 0), 0);
    EXPECT_EQ(a.wo, Vector3f(0, 0, 0));
    EXPECT_FALSE(a.wo.HasNaNs());
    Interaction b(Point3f(1, 2, 3), Vector3f(0, 0, 0), 0);
    EXPECT_FALSE(b.wo.HasNaNs());
}

// ---------------------------------------------------------------------------
// SurfaceInteraction

TEST(SurfaceInteraction, DefaultMembers) {
    SurfaceInteraction si;
    EXPECT_EQ(si.shape, nullptr);
    EXPECT_EQ(si.primitive, nullptr);
    EXPECT_EQ(si.faceIndex, 0);
    EXPECT_FALSE(si.flipNormal);
    EXPECT_FALSE(si.IsSurfaceInteraction());
}

TEST(SurfaceInteraction, ConstructorComputesUnitNormalFromTangents) {
    constexpr int kCases = 3000;
    std::mt19937_64 rng(601);
    for (int c = 0; c < kCases; ++c) {
        ConstructorArgs a = RandomConstructorArgs(rng);
        SurfaceInteraction si(a.p, a.pError, a.uv, a.wo, a.dpdu, a.dpdv,
                              a.dndu, a.dndv, 0.75, false, 7);
        // n is the normalized cross product, computed independently.
        V3 cr = CrossLD(a.dpdu, a.dpdv);
        LD cl = std::sqrt(cr.x * cr.x + cr.y * cr.y + cr.z * cr.z);
        ASSERT_NEAR(si.n.x, double(cr.x / cl), 4 * kEps) << c;
        ASSERT_NEAR(si.n.y, double(cr.y / cl), 4 * kEps) << c;
        ASSERT_NEAR(si.n.z, double(cr.z / cl), 4 * kEps) << c;
        ASSERT_NEAR(double(LengthLD(si.n)), 1, 4 * kEps);
        ASSERT_TRUE(si.IsSurfaceInteraction());
        // Everything else is stored; shading geometry starts as a copy.
        ASSERT_EQ(si.p, a.p);
        ASSERT_EQ(si.pError, a.pError);
        ASSERT_EQ(si.uv, a.uv);
        ASSERT_EQ(si.time, Float(0.75));
        ASSERT_EQ(si.dpdu, a.dpdu);
        ASSERT_EQ(si.dpdv, a.dpdv);
        ASSERT_EQ(si.dndu, a.dndu);
        ASSERT_EQ(si.dndv, a.dndv);
        ASSERT_EQ(si.faceIndex, 7);
        ASSERT_FALSE(si.flipNormal);
        ASSERT_EQ(si.shading.n, si.n);
        ASSERT_EQ(si.shading.dpdu, a.dpdu);
        ASSERT_EQ(si.shading.dpdv, a.dpdv);
        ASSERT_EQ(si.shading.dndu, a.dndu);
        ASSERT_EQ(si.shading.dndv, a.dndv);
        ASSERT_EQ(si.shape, nullptr);
        ASSERT_EQ(si.primitive, nullptr);
        ASSERT_NEAR(double(LengthLD(si.wo)), 1, 4 * kEps);
        ASSERT_NEAR(double(CosLD(si.wo, a.wo)), 1, 4 * kEps);
    }
}

// The constructor that takes the normal uses it as given (negated when
// flipNormal is set) and stores everything else exactly as the one that
// computes the normal from the tangents does.
TEST(SurfaceInteraction, ConstructorWithNormalUsesTheGivenNormal) {
    constexpr int kCases = 2000;
    std::mt19937_64 rng(607);
    for (int c = 0; c < kCases; ++c) {
        ConstructorArgs a = RandomConstructorArgs(rng);
        // A unit normal unrelated to the tangents, so that a constructor
        // that recomputed it from them would be caught.
        Normal3f given = Normalize(RandomNormal(rng));
        bool flip = c % 2 == 1;
        SurfaceInteraction si(a.p, a.pError, a.uv, a.wo, a.dpdu, a.dpdv,
                              a.dndu, a.dndv, given, 0.25, flip, 11);
        Normal3f expected = flip ? -given : given;
        ASSERT_EQ(si.n, expected) << c;
        ASSERT_EQ(si.shading.n, expected) << c;
        ASSERT_EQ(si.flipNormal, flip);
        // The other members match the tangent constructor's.
        SurfaceInteraction ref(a.p, a.pError, a.uv, a.wo, a.dpdu, a.dpdv,
                               a.dndu, a.dndv, 0.25, flip, 11);
        ASSERT_EQ(si.p, ref.p);
        ASSERT_EQ(si.pError, ref.pError);
        ASSERT_EQ(si.wo, ref.wo);
        ASSERT_EQ(si.time, ref.time);
        ASSERT_EQ(si.uv, ref.uv);
        ASSERT_EQ(si.dpdu, ref.dpdu);
        ASSERT_EQ(si.dpdv, ref.dpdv);
        ASSERT_EQ(si.dndu, ref.dndu);
        ASSERT_EQ(si.dndv, ref.dndv);
        ASSERT_EQ(si.shading.dpdu, ref.shading.dpdu);
        ASSERT_EQ(si.shading.dpdv, ref.shading.dpdv);
        ASSERT_EQ(si.shading.dndu, ref.shading.dndu);
        ASSERT_EQ(si.shading.dndv, ref.shading.dndv);
        ASSERT_EQ(si.faceIndex, 11);
        ASSERT_EQ(si.shape, nullptr);
        ASSERT_EQ(si.primitive, nullptr);
        // Given the normal that the tangent constructor computes, the two
        // constructors agree on the normals too.
        SurfaceInteraction same(a.p, a.pError, a.uv, a.wo, a.dpdu, a.dpdv,
                                a.dndu, a.dndv,
                                Normal3f(Normalize(Cross(a.dpdu, a.dpdv))),
                                0.25, flip, 11);
        ASSERT_EQ(same.n, ref.n);
        ASSERT_EQ(same.shading.n, ref.shading.n);
    }
}

TEST(SurfaceInteraction, FlipNormalFlipsBothNormals) {
    constexpr int kCases = 1000;
    std::mt19937_64 rng(602);
    for (int c = 0; c < kCases; ++c) {
        Vector3f dpdu, dpdv;
        RandomTangents(rng, &dpdu, &dpdv);
        Point3f p = RandomPoint(rng, -5, 5);
        SurfaceInteraction a(p, Vector3f(), Point2f(), Vector3f(0, 0, 1),
                             dpdu, dpdv, Normal3f(), Normal3f(), 0, false);
        SurfaceInteraction b(p, Vector3f(), Point2f(), Vector3f(0, 0, 1),
                             dpdu, dpdv, Normal3f(), Normal3f(), 0, true);
        ASSERT_EQ(b.n, -a.n);
        ASSERT_EQ(b.shading.n, -a.shading.n);
        ASSERT_TRUE(b.flipNormal);
        // The flipped normal points against the cross product.
        ASSERT_LT(DotLD(b.n, Cross(dpdu, dpdv)), 0);
        ASSERT_GT(DotLD(a.n, Cross(dpdu, dpdv)), 0);
    }
}

TEST(SurfaceInteraction, SetShadingGeometryWhenShadingIsAuthoritative) {
    Vector3f dpdu(1, 0, 0), dpdv(0, 1, 0);
    SurfaceInteraction si(Point3f(), Vector3f(), Point2f(), Vector3f(0, 0, 1),
                          dpdu, dpdv, Normal3f(), Normal3f(), 0, false);
    EXPECT_EQ(si.n, Normal3f(0, 0, 1));
    // Shading tangents whose cross product points to the other side: the
    // true normal follows the shading normal.
    Vector3f dpdus(0, 1, 0.2f), dpdvs(1, 0, 0.1f);
    Normal3f dndus(1, 2, 3), dndvs(4, 5, 6);
    si.SetShadingGeometry(dpdus, dpdvs, dndus, dndvs, true);
    Vector3f cr = Normalize(Cross(dpdus, dpdvs));
    EXPECT_NEAR(si.shading.n.x, cr.x, 2 * kEps);
    EXPECT_NEAR(si.shading.n.y, cr.y, 2 * kEps);
    EXPECT_NEAR(si.shading.n.z, cr.z, 2 * kEps);
    EXPECT_LT(si.shading.n.z, 0);
    EXPECT_EQ(si.n, Normal3f(0, 0, -1));
    EXPECT_EQ(si.shading.dpdu, dpdus);
    EXPECT_EQ(si.shading.dpdv, dpdvs);
    EXPECT_EQ(si.shading.dndu, dndus);
    EXPECT_EQ(si.shading.dndv, dndvs);
    // The true geometry's tangents are not touched.
    EXPECT_EQ(si.dpdu, dpdu);
    EXPECT_EQ(si.dpdv, dpdv);

    // Shading normal on the same side: nothing flips.
    SurfaceInteraction s2(Point3f(), Vector3f(), Point2f(), Vector3f(0, 0, 1),
                          dpdu, dpdv, Normal3f(), Normal3f(), 0, false);
    s2.SetShadingGeometry(dpdvs, dpdus, dndus, dndvs, true);
    EXPECT_EQ(s2.n, Normal3f(0, 0, 1));
    EXPECT_GT(s2.shading.n.z, 0);
}

TEST(SurfaceInteraction, SetShadingGeometryWhenGeometryIsAuthoritative) {
    Vector3f dpdu(1, 0, 0), dpdv(0, 1, 0);
    SurfaceInteraction si(Point3f(), Vector3f(), Point2f(), Vector3f(0, 0, 1),
                          dpdu, dpdv, Normal3f(), Normal3f(), 0, false);
    Vector3f dpdus(0, 1, 0.2f), dpdvs(1, 0, 0.1f);
    si.SetShadingGeometry(dpdus, dpdvs, Normal3f(), Normal3f(), false);
    // The shading normal is flipped to the true normal's side.
    EXPECT_EQ(si.n, Normal3f(0, 0, 1));
    Vector3f cr = Normalize(Cross(dpdus, dpdvs));
    EXPECT_NEAR(si.shading.n.x, -cr.x, 2 * kEps);
    EXPECT_NEAR(si.shading.n.y, -cr.y, 2 * kEps);
    EXPECT_NEAR(si.shading.n.z, -cr.z, 2 * kEps);
    EXPECT_GT(si.shading.n.z, 0);
}

TEST(SurfaceInteraction, SetShadingGeometryAppliesFlipNormal) {
    Vector3f dpdu(1, 0, 0), dpdv(0, 1, 0);
    // With flipNormal the true normal is -z; shading tangents equal to the
    // true ones must give the same, flipped, shading normal, whichever side
    // is authoritative.
    for (bool authoritative : {false, true}) {
        SurfaceInteraction si(Point3f(), Vector3f(), Point2f(),
                              Vector3f(0, 0, 1), dpdu, dpdv, Normal3f(),
                              Normal3f(), 0, true);
        EXPECT_EQ(si.n, Normal3f(0, 0, -1));
        si.SetShadingGeometry(dpdu, dpdv, Normal3f(), Normal3f(),
                              authoritative);
        EXPECT_EQ(si.shading.n, Normal3f(0, 0, -1));
        EXPECT_EQ(si.n, Normal3f(0, 0, -1));
    }
    // With flipNormal and an authoritative shading frame, the true normal
    // follows the flipped cross product of the shading tangents.
    SurfaceInteraction si(Point3f(), Vector3f(), Point2f(), Vector3f(0, 0, 1),
                          dpdu, dpdv, Normal3f(), Normal3f(), 0, true);
    si.SetShadingGeometry(dpdv, dpdu, Normal3f(), Normal3f(), true);
    EXPECT_EQ(si.shading.n, Normal3f(0, 0, 1));
    EXPECT_EQ(si.n, Normal3f(0, 0, 1));
}

TEST(SurfaceInteraction, SetShadingGeometryRandomHemispheres) {
    constexpr int kCases = 3000;
    std::mt19937_64 rng(603);
    for (int c = 0; c < kCases; ++c) {
        bool flip = c % 2, authoritative = (c / 2) % 2;
        SurfaceInteraction si = RandomSurfaceInteraction(rng, flip);
        Normal3f n0 = si.n;
        Vector3f dpdus, dpdvs;
        RandomTangents(rng, &dpdus, &dpdvs);
        si.SetShadingGeometry(dpdus, dpdvs, Normal3f(), Normal3f(),
                              authoritative);
        ASSERT_GE(Dot(si.n, si.shading.n), 0) << c;
        ASSERT_NEAR(double(LengthLD(si.shading.n)), 1, 4 * kEps);
        // shading.n is +-normalize(dpdus x dpdvs).
        ASSERT_NEAR(double(std::fabs(CosLD(si.shading.n,
                                           Cross(dpdus, dpdvs)))),
                    1, 4 * kEps);
        if (authoritative) {
            // The shading normal keeps the sign given by flipNormal.
            LD s = DotLD(si.shading.n, Cross(dpdus, dpdvs));
            ASSERT_EQ(s < 0, flip) << c;
            ASSERT_TRUE(si.n == n0 || si.n == -n0);
        } else {
            ASSERT_EQ(si.n, n0) << c;
        }
    }
}

// ---------------------------------------------------------------------------
// Transforming a SurfaceInteraction

EXERCISE_TEST(Ex2_13_SurfaceInteraction, TransformKeepsGeometryConsistent) {
    constexpr int kCases = 3000;
    std::mt19937_64 rng(calls::Seed(604));
    for (int c = 0; c < kCases; ++c) {
        bool mirror = c % 2, flip = (c / 2) % 2;
        Transform t = RandomTransform(rng, mirror);
        ASSERT_EQ(t.SwapsHandedness(), mirror);
        SurfaceInteraction si = RandomSurfaceInteraction(rng, flip);
        // Give the shading geometry its own tangents.
        Vector3f dpdus, dpdvs;
        RandomTangents(rng, &dpdus, &dpdvs);
        si.SetShadingGeometry(dpdus, dpdvs, RandomNormal(rng),
                              RandomNormal(rng), false);
        // Addresses that stay the same when the judge runs the test again.
        static const int dummyShape = 0, dummyPrimitive = 0;
        si.shape = reinterpret_cast<const Shape *>(&dummyShape);
        si.primitive = reinterpret_cast<const Primitive *>(&dummyPrimitive);

        SurfaceInteraction ts = ex::Apply(t, si);
        // n is unit length and perpendicular to the transformed tangents.
        ASSERT_NEAR(double(LengthLD(ts.n)), 1, 4 * kEps);
        ASSERT_LE(std::fabs(CosLD(ts.n, ts.dpdu)), 256 * kEps) << c;
        ASSERT_LE(std::fabs(CosLD(ts.n, ts.dpdv)), 256 * kEps) << c;
        ASSERT_EQ(ts.dpdu, t(si.dpdu));
        ASSERT_EQ(ts.dpdv, t(si.dpdv));
        ASSERT_EQ(ts.dndu, ex::Apply(t, si.dndu));
        ASSERT_EQ(ts.dndv, ex::Apply(t, si.dndv));
        // The shading frame likewise, and shading.n faces n.
        ASSERT_NEAR(double(LengthLD(ts.shading.n)), 1, 4 * kEps);
        ASSERT_LE(std::fabs(CosLD(ts.shading.n, ts.shading.dpdu)),
                  256 * kEps);
        ASSERT_LE(std::fabs(CosLD(ts.shading.n, ts.shading.dpdv)),
                  256 * kEps);
        ASSERT_GE(Dot(ts.shading.n, ts.n), 0) << c;
        ASSERT_EQ(ts.shading.dpdu, t(si.shading.dpdu));
        ASSERT_EQ(ts.shading.dndv, ex::Apply(t, si.shading.dndv));
        // Orientation: by the cross-product identity the transformed normal
        // agrees with the cross product of the transformed tangents up to
        // the sign of the determinant (and the flip), and the transformed
        // flag records exactly that.
        LD side = DotLD(ts.n, Cross(ts.dpdu, ts.dpdv));
        ASSERT_EQ(side < 0, mirror != flip) << c;
        ASSERT_EQ(ts.flipNormal, mirror != flip) << c;
        // The point and its error bound: the exact image of any point in
        // the original error box lies in the new one.
        const Matrix4x4 &m = t.GetMatrix();
        for (int k = 0; k < 8; ++k) {
            LD q[3] = {LD(si.p.x) + ((k & 1) ? si.pError.x : -si.pError.x),
                       LD(si.p.y) + ((k & 2) ? si.pError.y : -si.pError.y),
                       LD(si.p.z) + ((k & 4) ? si.pError.z : -si.pError.z)};
            for (int i = 0; i < 3; ++i) {
                LD e = m.m[i][0] * q[0] + m.m[i][1] * q[1] +
                       m.m[i][2] * q[2] + m.m[i][3];
                ASSERT_LE(std::fabs(e - ts.p[i]), LD(ts.pError[i])) << c;
            }
        }
        // Direction, parameters and bookkeeping.
        ASSERT_NEAR(double(LengthLD(ts.wo)), 1, 4 * kEps);
        ASSERT_NEAR(double(CosLD(ts.wo, t(si.wo))), 1, 4 * kEps);
        ASSERT_EQ(ts.uv, si.uv);
        ASSERT_EQ(ts.time, si.time);
        ASSERT_EQ(ts.faceIndex, si.faceIndex);
        ASSERT_EQ(ts.shape, si.shape);
        ASSERT_EQ(ts.primitive, si.primitive);
    }
}

EXERCISE_TEST(Ex2_13_SurfaceInteraction, FlipNormalTracksTheCrossProductThroughTransforms) {
    // flipNormal is true exactly when n is the negated cross product of the
    // interaction's own dpdu and dpdv, also after any chain of
    // transformations, mirrors included.
    constexpr int kCases = 2000;
    std::mt19937_64 rng(calls::Seed(605));
    for (int c = 0; c < kCases; ++c) {
        SurfaceInteraction si = RandomSurfaceInteraction(rng, c % 2);
        int steps = 1 + c % 3;
        for (int k = 0; k < steps; ++k) {
            Transform t = RandomTransform(rng, Uniform(rng, 0, 1) < 0.5);
            si = ex::Apply(t, si);
            LD side = DotLD(si.n, Cross(si.dpdu, si.dpdv));
            ASSERT_EQ(side < 0, si.flipNormal) << c << " step " << k;
            ASSERT_GE(Dot(si.shading.n, si.n), 0);
        }
        // SetShadingGeometry with the true tangents then reproduces n.
        Normal3f n = si.n;
        si.SetShadingGeometry(si.dpdu, si.dpdv, Normal3f(), Normal3f(), true);
        ASSERT_GT(DotLD(si.shading.n, Vector3f(n)), 0.99) << c;
        ASSERT_EQ(si.n, n);
    }
}

EXERCISE_TEST(Ex2_13_SurfaceInteraction, OutwardNormalsStayOutwardUnderMirrors) {
    // A point on a sphere with tangents whose cross product points outward.
    // Built in object space (flip = reverseOrientation) and transformed, or
    // built from world-space tangents (flip = reverseOrientation ^
    // SwapsHandedness), the world-space normal points outward unless the
    // orientation is reversed.
    constexpr int kCases = 2000;
    std::mt19937_64 rng(calls::Seed(606));
    for (int c = 0; c < kCases; ++c) {
        bool mirror = c % 2, reverse = (c / 2) % 2;
        Transform objectToWorld = RandomTransform(rng, mirror);
        Vector3f u = RandomVector(rng, -1, 1);
        if (u.Length() < 0.1) continue;
        u = Normalize(u);
        Vector3f t1, t2;
        RandomTangents(rng, &t1, &t2);
        Vector3f dpdu = Normalize(Cross(u, t1));
        Vector3f dpdv = Cross(u, dpdu);  // dpdu x dpdv points along u
        Point3f center = RandomPoint(rng, -2, 2);
        Point3f p = center + 2 * u;
        LD expected = reverse ? -1 : 1;

        SurfaceInteraction obj(p, Vector3f(), Point2f(), -u, dpdu, dpdv,
                               Normal3f(), Normal3f(), 0, reverse);
        SurfaceInteraction w1 = ex::Apply(objectToWorld, obj);
        Vector3f out = objectToWorld(p) - objectToWorld(center);
        ASSERT_GT(expected * DotLD(w1.n, out), 0) << c;

        SurfaceInteraction w2(objectToWorld(p), Vector3f(), Point2f(),
                              objectToWorld(-u), objectToWorld(dpdu),
                              objectToWorld(dpdv), Normal3f(), Normal3f(), 0,
                              reverse != objectToWorld.SwapsHandedness());
        ASSERT_GT(expected * DotLD(w2.n, out), 0) << c;
        ASSERT_EQ(w1.flipNormal, w2.flipNormal) << c;
    }
}

EXERCISE_TEST(Ex2_13_SurfaceInteraction, TransformByIdentityAndZeroDirection) {
    std::mt19937_64 rng(calls::Seed(607));
    SurfaceInteraction si = RandomSurfaceInteraction(rng, false);
    SurfaceInteraction ts = ex::Apply(Transform(), si);
    EXPECT_EQ(ts.p, si.p);
    EXPECT_EQ(ts.dpdu, si.dpdu);
    EXPECT_EQ(ts.dndv, si.dndv);
    EXPECT_NEAR(ts.n.x, si.n.x, 2 * kEps);
    EXPECT_NEAR(ts.n.y, si.n.y, 2 * kEps);
    EXPECT_NEAR(ts.n.z, si.n.z, 2 * kEps);
    // The identity adds only the rounding bound of its own evaluation.
    EXPECT_GE(ts.pError.x, si.pError.x);
    EXPECT_LE(ts.pError.x, si.pError.x * (1 + 2 * gamma(3)) +
                               gamma(3) * (std::fabs(si.p.x) + 1));
    // An interaction without an outgoing direction keeps none.
    si.wo = Vector3f(0, 0, 0);
    SurfaceInteraction t2 = ex::Apply(RotateX(30), si);
    EXPECT_EQ(t2.wo, Vector3f(0, 0, 0));
}
