// Hidden tests of chapter 8's graded exercises (docs/exercises.md): they run
// at grading time only and never ship to students. The public tests of the
// same exercises are the suites Ex8_9_*, Ex8_10_* and Ex8_11_* in
// tests/ch08/test_render_exercises.cpp.
//
// Their cases are drawn anew for each grading (calls::Seed): random values
// for the sRGB curve, random cameras of every shape and field of view, and
// random hit points on spheres and disks at scales from 1e-4 to 1e5.

#include "ch08/render_oracles.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <vector>

using namespace lrt;
using namespace lrt::oracle;

// ---------------------------------------------------------------- ex-8.9

EXERCISE_TEST(Ex8_9_SRGBHidden, RandomValuesMatchTheFormula) {
    std::mt19937_64 rng(calls::Seed(8901));
    std::uniform_real_distribution<double> u01(0, 1), logu(-9, 0),
        nearTh(-1e-4, 1e-4);
    std::vector<Float> values;
    int n = calls::Cases(30000, 6000);
    for (int i = 0; i < n; ++i) {
        switch (i % 3) {
        case 0: values.push_back(Float(u01(rng))); break;
        case 1: values.push_back(Float(std::pow(10.0, logu(rng)))); break;
        default: values.push_back(Float(0.0031308 + nearTh(rng))); break;
        }
    }
    auto got = ex::EncodeSRGB(values);
    ASSERT_EQ(got.encoded.size(), values.size());
    ASSERT_EQ(got.bytes.size(), values.size());
    int wrong = 0, bytesWrong = 0;
    for (size_t i = 0; i < values.size(); ++i) {
        long double v = values[i];
        long double want = SRGB(v);
        double tol =
            v <= 0.0031308L
                ? 2 * kEps * double(want) +
                      double(std::numeric_limits<Float>::denorm_min())
                : 8 * kEps * (double(want) + 0.06);
        if (std::abs(got.encoded[i] - double(want)) > tol && wrong++ < 5)
            ADD_FAILURE() << "GammaCorrect(" << double(v) << ") = "
                          << got.encoded[i] << ", the standard gives "
                          << double(want);
        if (v <= 0 || v >= 1) continue;
        long double scaled = 255 * want;
        if (std::abs(scaled - std::floor(scaled) - 0.5L) < 1e-4L) continue;
        int b = int(std::floor(scaled + 0.5L));
        if (got.bytes[i] != b && bytesWrong++ < 5)
            ADD_FAILURE() << "EncodeSRGB8(" << double(v) << ") = "
                          << int(got.bytes[i]) << ", not " << b;
    }
    EXPECT_EQ(wrong, 0);
    EXPECT_EQ(bytesWrong, 0);
}

EXERCISE_TEST(Ex8_9_SRGBHidden, HalfwayBetweenCodesRoundsToTheNearer) {
    // Values whose encodings lie just below and just above b + 1/2 codes.
    std::vector<Float> values;
    for (int b = 0; b < 255; ++b)
        for (double off : {0.47, 0.53})
            values.push_back(Float(InverseSRGB((b + off) / 255.0L)));
    auto got = ex::EncodeSRGB(values);
    ASSERT_EQ(got.bytes.size(), values.size());
    for (int b = 0; b < 255; ++b) {
        if (values[2 * b] > 0) {
            EXPECT_EQ(int(got.bytes[2 * b]), b);
        }
        EXPECT_EQ(int(got.bytes[2 * b + 1]), b + 1);
    }
}

// ---------------------------------------------------------------- ex-8.10

EXERCISE_TEST(Ex8_10_CameraHidden, RandomCamerasProjectBackAndClip) {
    std::mt19937_64 rng(calls::Seed(8101));
    std::uniform_real_distribution<double> u(-1, 1), u01(0, 1);
    std::uniform_int_distribution<int> size(1, 60);
    int cameras = calls::Cases(200, 60);
    for (int k = 0; k < cameras; ++k) {
        Point3f eye(Float(20 * u(rng)), Float(20 * u(rng)), Float(20 * u(rng)));
        Point3f look(Float(20 * u(rng)), Float(20 * u(rng)), Float(20 * u(rng)));
        Vector3f upHint(Float(u(rng)), Float(u(rng)), 1);
        Float fov = Float(5 + 150 * u01(rng));
        int w = size(rng), h = size(rng);
        double zNear = k % 3 == 0 ? 0 : 5 * u01(rng);
        double zFar = k % 4 == 0 ? HUGE_VAL : double(Float(zNear + 0.5 + 50 * u01(rng)));
        zNear = double(Float(zNear));
        Camera cam(D(eye), D(look), D(upHint), fov, w, h, zNear, zFar);
        std::vector<Point2f> raster;
        for (int i = 0; i < 20; ++i)
            raster.push_back(Point2f(Float(w * u01(rng)), Float(h * u01(rng))));
        raster.push_back(Point2f(0, 0));
        raster.push_back(Point2f(Float(w), Float(h)));
        std::vector<Ray> rays =
            ex::GenerateRays(cam.Value(eye, look, upHint, fov), raster);
        ASSERT_EQ(rays.size(), raster.size());
        for (size_t i = 0; i < rays.size(); ++i) {
            const Ray &r = rays[i];
            V3 o = D(r.o), d = D(r.d);
            // The direction's depth component is 1: the parameter is depth.
            // (The camera's Float transformation rounds the direction, whose
            // length grows with the field of view and the aspect ratio.)
            V3 dc = cam.ToCamera(cam.eye + d);
            ASSERT_NEAR(dc.z, 1, 64 * kEps * (1 + Norm(d)))
                << "camera " << k << ", ray " << i;
            double xr, yr;
            cam.Project(o + d, &xr, &yr);
            double scale = 1e-4 * (w + h) * (1 + 1 / std::tan(fov * M_PI / 360));
            ASSERT_NEAR(xr, raster[i].x, scale) << "camera " << k << ", ray " << i;
            ASSERT_NEAR(yr, raster[i].y, scale) << "camera " << k << ", ray " << i;
            // The origin on the near plane, the end of the ray on the far one.
            double reach = Norm(cam.eye) + 60 * Norm(d);
            ASSERT_NEAR(cam.ToCamera(o).z, zNear, 1e-5 * reach)
                << "camera " << k << ", ray " << i;
            if (std::isinf(zFar)) {
                ASSERT_EQ(r.tMax, Infinity);
            } else {
                ASSERT_NEAR(r.tMax, zFar - zNear, 1e-5 * zFar);
                ASSERT_NEAR(cam.ToCamera(o + double(r.tMax) * d).z, zFar,
                            1e-5 * reach);
            }
        }
    }
}

EXERCISE_TEST(Ex8_10_CameraHidden, TheShorterSideSpansTheFieldOfView) {
    // The rays through the midpoints of the two edges of the shorter side
    // make the angle fov; those of the longer side the angle that the aspect
    // ratio gives, 2 atan(aspect tan(fov / 2)).
    std::mt19937_64 rng(calls::Seed(8102));
    std::uniform_real_distribution<double> u01(0, 1);
    std::uniform_int_distribution<int> size(1, 4000);
    for (int k = 0; k < 40; ++k) {
        int w = size(rng), h = size(rng);
        Float fov = Float(1 + 170 * u01(rng));
        Point3f eye(1, 2, 3), look(Float(u01(rng)), 5, Float(u01(rng)));
        Camera cam(D(eye), D(look), V3{0, 0, 1}, fov, w, h);
        std::vector<Point2f> raster = {
            Point2f(0, Float(h / 2.0)), Point2f(Float(w), Float(h / 2.0)),
            Point2f(Float(w / 2.0), 0), Point2f(Float(w / 2.0), Float(h))};
        std::vector<Ray> rays =
            ex::GenerateRays(cam.Value(eye, look, Vector3f(0, 0, 1), fov), raster);
        ASSERT_EQ(rays.size(), 4u);
        auto angle = [](const Ray &a, const Ray &b) {
            double c = Dot(Unit(D(a.d)), Unit(D(b.d)));
            return std::acos(std::max(-1.0, std::min(1.0, c))) * 180 / M_PI;
        };
        double t = std::tan(double(fov) * M_PI / 360);
        double across = 2 * std::atan(t * w / std::min(w, h)) * 180 / M_PI;
        double down = 2 * std::atan(t * h / std::min(w, h)) * 180 / M_PI;
        EXPECT_NEAR(angle(rays[0], rays[1]), across, 1e-2)
            << w << "x" << h << ", fov " << fov;
        EXPECT_NEAR(angle(rays[2], rays[3]), down, 1e-2)
            << w << "x" << h << ", fov " << fov;
        // Left is left and up is up: the left edge's ray is on the camera's
        // -x side, the top edge's on its +y side.
        EXPECT_LT(cam.ToCamera(cam.eye + D(rays[0].d)).x, 0);
        EXPECT_GT(cam.ToCamera(cam.eye + D(rays[2].d)).y, 0);
    }
}

// ---------------------------------------------------------------- ex-8.11

EXERCISE_TEST(Ex8_11_ShadowHidden, RandomHitsAtEveryScale) {
    std::mt19937_64 rng(calls::Seed(8111));
    std::vector<ShadowHit> hits;
    int perScale = calls::Cases(40, 12);
    for (int e = -4; e <= 5; ++e)
        for (bool disk : {false, true})
            for (int found = 0, tries = 0; found < perScale && tries < 2000;
                 ++tries) {
                ShadowHit h;
                if (RandomShadowHit(rng, std::pow(10.0, e), disk, &h))
                    hits.push_back(h), ++found;
            }
    std::vector<ShadowCase> cases;
    for (const ShadowHit &h : hits) cases.push_back(h.c);
    std::vector<ShadowAnswer> got = ex::SpawnShadowRays(cases);
    ASSERT_EQ(got.size(), cases.size());
    for (size_t i = 0; i < cases.size(); ++i) {
        ASSERT_EQ(got[i].rays.size(), 1u) << i;
        CheckErrorBoundsRay(hits[i], got[i].rays[0], "hidden error bounds");
        if (StopAfterFailures(i)) break;
    }
}

EXERCISE_TEST(Ex8_11_ShadowHidden, FixedOffsetAndLightsBehindTheSurface) {
    // Hit points of spheres and disks with the fixed offset: the origin is
    // o + t d moved by epsilon along the normal that faces the eye. A light
    // behind the surface gets no shadow ray at all.
    std::mt19937_64 rng(calls::Seed(8112));
    std::vector<ShadowHit> hits;
    std::vector<bool> behind;
    for (int e = -3; e <= 4; ++e)
        for (bool disk : {false, true})
            for (int found = 0, tries = 0; found < 10 && tries < 1000;
                 ++tries) {
                ShadowHit h;
                if (!RandomShadowHit(rng, std::pow(10.0, e), disk, &h)) continue;
                h.c.method = ShadowRays::FixedEpsilon;
                h.c.epsilon = Float(1e-4 * std::pow(10.0, e));
                // The interaction's point a little off o + t d, which is
                // where the fixed offset starts.
                std::uniform_real_distribution<double> u(-1, 1);
                double off = 1e-3 * std::pow(10.0, e);
                h.c.p = Point3f(Float(h.c.p.x + off * u(rng)),
                                Float(h.c.p.y + off * u(rng)),
                                Float(h.c.p.z + off * u(rng)));
                bool back = found % 3 == 2;
                if (back) {
                    // The light mirrored through the tangent plane.
                    V3 p = D(h.c.p), l = D(h.c.pLight), n = h.towardLight;
                    V3 m = l - 2 * Dot(l - p, n) * n;
                    h.c.pLight = Point3f(Float(m.x), Float(m.y), Float(m.z));
                }
                hits.push_back(h);
                behind.push_back(back);
                ++found;
            }
    std::vector<ShadowCase> cases;
    for (const ShadowHit &h : hits) cases.push_back(h.c);
    std::vector<ShadowAnswer> got = ex::SpawnShadowRays(cases);
    ASSERT_EQ(got.size(), cases.size());
    for (size_t i = 0; i < cases.size(); ++i) {
        const ShadowCase &c = cases[i];
        if (behind[i]) {
            EXPECT_EQ(got[i].rays.size(), 0u) << i;
            continue;
        }
        ASSERT_EQ(got[i].rays.size(), 1u) << i;
        const Ray &s = got[i].rays[0];
        V3 n = D(c.n);
        if (Dot(n, D(c.ray.o) - D(c.p)) < 0) n = -1 * n;
        CheckFixedEpsilonRay(c, n, s, std::to_string(i));
        if (StopAfterFailures(i)) break;
    }
}
