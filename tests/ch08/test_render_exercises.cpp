// Public tests of chapter 8's graded exercises: ex-8.9 (the sRGB encoding),
// ex-8.10 (the pinhole camera's rays) and ex-8.11 (where shadow rays start).
// They reach the exercises' code only through the exercise calls
// (exercise_calls.h). Oracles: the standard's sRGB formula in long double;
// the camera's geometry from an orthonormal basis in double, and the
// analytic silhouette, brightness and depths of a sphere; the error boxes of
// hit points found by the book's shapes, and the exact shadow of a disk on a
// floor.

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

namespace {

// The tolerance of a Float computation of the curve at v.
double SRGBTolerance(double v) {
    long double e = SRGB(v);
    // In the linear piece, a subnormal result is rounded to a multiple of
    // the smallest subnormal.
    return v <= 0.0031308
               ? 2 * kEps * std::abs(double(e)) +
                     double(std::numeric_limits<Float>::denorm_min())
               : 8 * kEps * (double(e) + 0.06);
}

}  // namespace

EXERCISE_TEST(Ex8_9_SRGB, MatchesTheStandardFormula) {
    std::vector<Float> values;
    for (int i = 0; i <= 1000; ++i) values.push_back(Float(i / 1000.0));
    // Both sides of the threshold between the pieces, the smallest values,
    // and values that a caller may pass outside [0, 1].
    Float th = Float(0.0031308);
    for (Float v = th, k = 0; k < 6; ++k, v = std::nextafter(v, Float(0)))
        values.push_back(v);
    for (Float v = th, k = 0; k < 6; ++k, v = std::nextafter(v, Float(1)))
        values.push_back(v);
    for (Float v : {Float(1e-30), Float(1e-6), Float(-0.25), Float(1.5),
                    std::numeric_limits<Float>::denorm_min()})
        values.push_back(v);
    auto got = ex::EncodeSRGB(values);
    ASSERT_EQ(got.encoded.size(), values.size());
    ASSERT_EQ(got.bytes.size(), values.size());
    int bytesChecked = 0;
    for (size_t i = 0; i < values.size(); ++i) {
        double v = values[i];
        double want = double(SRGB(v));
        EXPECT_NEAR(got.encoded[i], want, SRGBTolerance(v)) << "v = " << v;
        if (v <= 0 || v >= 1) continue;
        double scaled = 255 * want;
        if (std::abs(scaled - std::floor(scaled) - 0.5) < 1e-4) continue;
        ++bytesChecked;
        EXPECT_EQ(int(got.bytes[i]), int(std::floor(scaled + 0.5)))
            << "v = " << v;
    }
    EXPECT_GT(bytesChecked, 990);
}

EXERCISE_TEST(Ex8_9_SRGB, EveryByteDecodedEncodesToItself) {
    // The linear value of byte b, and values whose encodings lie 0.4 of a
    // code below and above it: rounding, not truncation, gives b for all.
    std::vector<Float> values;
    for (int b = 0; b < 256; ++b)
        for (double off : {0.0, -0.4, 0.4})
            values.push_back(Float(InverseSRGB((b + off) / 255.0L)));
    auto got = ex::EncodeSRGB(values);
    ASSERT_EQ(got.bytes.size(), values.size());
    for (int b = 0; b < 256; ++b)
        for (int k = 0; k < 3; ++k) {
            Float v = values[3 * b + k];
            if (v <= 0 || v >= 1) continue;  // the clamps, not the exercise
            EXPECT_EQ(int(got.bytes[3 * b + k]), b)
                << "byte " << b << ", v = " << v;
        }
}

EXERCISE_TEST(Ex8_9_SRGB, GrowsWithTheLightAndIsContinuous) {
    std::vector<Float> values;
    for (int i = 0; i <= 4000; ++i)
        values.push_back(Float(std::pow(10.0, -6 + 6.0 * i / 4000)));
    auto got = ex::EncodeSRGB(values);
    ASSERT_EQ(got.encoded.size(), values.size());
    ASSERT_EQ(got.bytes.size(), values.size());
    for (size_t i = 1; i < values.size(); ++i) {
        EXPECT_GE(got.encoded[i], got.encoded[i - 1]) << values[i];
        EXPECT_GE(got.bytes[i], got.bytes[i - 1]) << values[i];
    }
    // The two pieces meet at the threshold: the jump there is no larger
    // than rounding.
    Float th = Float(0.0031308);
    auto at = ex::EncodeSRGB(std::vector<Float>{th, std::nextafter(th, Float(1))});
    ASSERT_EQ(at.encoded.size(), 2u);
    EXPECT_NEAR(at.encoded[0], at.encoded[1], 1e-6);
    EXPECT_NEAR(at.encoded[0], 0.0404500, 1e-6);
}

// ---------------------------------------------------------------- ex-8.10

EXERCISE_TEST(Ex8_10_CameraRays, PassThroughTheFilmPlaneOfTheFieldOfView) {
    // A camera placed anywhere: in camera space the ray through raster point
    // (xr, yr) has the direction of the film point, with z = 1.
    Point3f eye(3, -2, 5), look(-1, 4, 2);
    for (auto [w, h] : {std::pair<int, int>{64, 48}, {30, 90}, {7, 7}}) {
        Camera cam(D(eye), D(look), V3{0, 0, 1}, 50, w, h);
        std::vector<Point2f> raster;
        for (auto [xr, yr] : {std::pair<double, double>{0, 0}, {w, h},
                              {w / 2.0, h / 2.0}, {0.25 * w, 0.9 * h},
                              {w, 0}, {0.5, h - 0.5}})
            raster.push_back(Point2f(Float(xr), Float(yr)));
        std::vector<Ray> rays = ex::GenerateRays(
            cam.Value(eye, look, Vector3f(0, 0, 1), 50), raster);
        ASSERT_EQ(rays.size(), raster.size());
        for (size_t i = 0; i < rays.size(); ++i) {
            const Ray &r = rays[i];
            EXPECT_LT(Norm(D(r.o) - D(eye)), 16 * kEps * 6);
            V3 dc = cam.ToCamera(cam.eye + D(r.d));
            V3 want = cam.ToCamera(cam.eye + cam.Direction(raster[i].x,
                                                            raster[i].y));
            EXPECT_NEAR(dc.z, 1, 16 * kEps) << w << "x" << h << " " << i;
            EXPECT_NEAR(dc.x, want.x, 16 * kEps) << w << "x" << h << " " << i;
            EXPECT_NEAR(dc.y, want.y, 16 * kEps) << w << "x" << h << " " << i;
            EXPECT_EQ(r.tMax, Infinity);
        }
        // The image center looks at the look-at point.
        V3 c = Unit(D(rays[2].d));
        EXPECT_NEAR(Dot(c, cam.forward), 1, 16 * kEps);
    }
}

EXERCISE_TEST(Ex8_10_CameraRays, PixelCentersProjectBackToTheirPixels) {
    // A tall and a wide camera, looking obliquely: the far point of the ray
    // through each pixel's center projects back to that center.
    struct Setup {
        Point3f eye, look;
        Float fov;
        int w, h;
    } setups[] = {{Point3f(-4, 7, 1), Point3f(2, -1, 3), 65, 40, 25},
                  {Point3f(10, 10, -10), Point3f(0, 0, 0), 20, 16, 33}};
    for (const Setup &s : setups) {
        Camera cam(D(s.eye), D(s.look), V3{0, 0, 1}, s.fov, s.w, s.h);
        std::vector<Point2f> centers;
        for (int y = 0; y < s.h; ++y)
            for (int x = 0; x < s.w; ++x)
                centers.push_back(Point2f(x + Float(0.5), y + Float(0.5)));
        std::vector<Ray> rays = ex::GenerateRays(
            cam.Value(s.eye, s.look, Vector3f(0, 0, 1), s.fov), centers);
        ASSERT_EQ(rays.size(), centers.size());
        for (size_t i = 0; i < rays.size(); ++i) {
            double xr, yr;
            cam.Project(D(rays[i].o) + 100 * D(rays[i].d), &xr, &yr);
            EXPECT_NEAR(xr, centers[i].x, 1e-3) << i;
            EXPECT_NEAR(yr, centers[i].y, 1e-3) << i;
        }
    }
}

EXERCISE_TEST(Ex8_10_CameraRays, NearPlaneMovesTheOriginAndFarPlaneBoundsTheRay) {
    Point3f eye(1, 2, 3), look(4, -2, 3);
    for (auto [zNear, zFar] : {std::pair<double, double>{2, 7}, {0.5, HUGE_VAL},
                               {0, 3}}) {
        Camera cam(D(eye), D(look), V3{0, 0, 1}, 60, 11, 9, zNear, zFar);
        std::vector<Point2f> raster = {Point2f(0, 0), Point2f(5.5, 4.5),
                                       Point2f(11, 2), Point2f(3, 9)};
        std::vector<Ray> rays = ex::GenerateRays(
            cam.Value(eye, look, Vector3f(0, 0, 1), 60), raster);
        ASSERT_EQ(rays.size(), raster.size());
        for (const Ray &r : rays) {
            EXPECT_NEAR(cam.ToCamera(D(r.o)).z, zNear, 16 * kEps * 8);
            if (std::isinf(zFar)) {
                EXPECT_EQ(r.tMax, Infinity);
                continue;
            }
            EXPECT_NEAR(r.tMax, zFar - zNear, 8 * kEps * zFar);
            EXPECT_NEAR(cam.ToCamera(D(r(r.tMax))).z, zFar, 32 * kEps * zFar);
        }
    }
}

EXERCISE_TEST(Ex8_10_Render, SphereSilhouetteHasTheAnalyticRadius) {
    // A sphere of radius r at distance D on the axis: a ray with film point
    // (xc, yc) hits it iff xc^2 + yc^2 < tan^2(asin(r / D)) = r^2/(D^2 - r^2).
    const int W = 161, H = 121;
    const double fov = 30;
    for (double D : {4.0, 9.0, 25.0}) {
        const double r = 1;
        RenderedImage im = ex::RenderImage(
            std::vector<ShapeValue>{SphereShape(Translate(Vector3f(0, 0, Float(D))), Float(r),
                         RGB(1, 1, 1))},
            AxisCamera(Float(fov), W, H), OptionsValue());
        ASSERT_EQ(im.depth.size(), size_t(W * H));
        double R = r / std::sqrt(D * D - r * r);
        int checked = 0, hits = 0, centerRow = 0;
        for (int y = 0; y < H; ++y)
            for (int x = 0; x < W; ++x) {
                double xc, yc;
                FilmPoint(fov, W, H, x, y, &xc, &yc);
                double rho = std::sqrt(xc * xc + yc * yc);
                bool hit = std::isfinite(im.depth[y * W + x]);
                if (y == H / 2) centerRow += hit;
                if (std::abs(rho - R) < 1e-4 * R) continue;
                ++checked;
                hits += hit;
                EXPECT_EQ(hit, rho < R) << "D " << D << " pixel " << x << ","
                                        << y;
            }
        EXPECT_GT(checked, W * H * 0.99);
        // The silhouette's radius in pixels, R / sy * H / 2, seen along the
        // middle row.
        double radiusPixels = R / std::tan(fov * M_PI / 360) * H / 2;
        EXPECT_NEAR(centerRow, 2 * radiusPixels, 1.01) << D;
        EXPECT_NEAR(hits, M_PI * radiusPixels * radiusPixels,
                    4 * 2 * M_PI * radiusPixels) << D;
    }
}

EXERCISE_TEST(Ex8_10_Render, HeadlightBrightnessFollowsTheFalloff) {
    // The center pixel of an odd-sized image looks along the axis and hits
    // the sphere head on at distance D - r, with cos = 1: L = rho I f(D - r).
    // Every other pixel: L = rho I f(dist) cos, from the analytic hit.
    const int W = 41, H = 41;
    const double fov = 40, r = 1.5;
    const RGB albedo(0.8, 0.5, 0.25);
    for (Falloff f : {Falloff::None, Falloff::InverseDistance,
                      Falloff::InverseSquare}) {
        for (double D : {5.0, 12.0}) {
            // Rotated so that the ray along the axis does not meet the
            // sphere at a pole, where Sphere nudges the hit point by 1e-5 r
            // (Chapter 3), which double precision would notice.
            OptionsValue opt;
            opt.headlight = 7;
            opt.falloff = f;
            opt.background = RGB(0.125, 0.25, 0.5);
            RenderedImage im = ex::RenderImage(
                std::vector<ShapeValue>{SphereShape(Translate(Vector3f(0, 0, Float(D))) * RotateX(90),
                             Float(r), albedo)},
                AxisCamera(Float(fov), W, H), opt);
            ASSERT_EQ(im.pixels.size(), size_t(W * H));
            int k = f == Falloff::None ? 0 : f == Falloff::InverseDistance ? 1 : 2;
            double center = 7 / std::pow(D - r, k);
            EXPECT_NEAR(im(W / 2, H / 2).r, 0.8 * center, 8 * kEps * center);
            EXPECT_NEAR(im(W / 2, H / 2).b, 0.25 * center, 8 * kEps * center);
            for (int y = 0; y < H; ++y)
                for (int x = 0; x < W; ++x) {
                    double xc, yc, t0, t1;
                    FilmPoint(fov, W, H, x, y, &xc, &yc);
                    if (!SphereDepths(xc, yc, D, r, &t0, &t1)) {
                        EXPECT_EQ(im(x, y), opt.background);
                        continue;
                    }
                    double px = t0 * xc, py = t0 * yc, pz = t0;
                    double dist = std::sqrt(px * px + py * py + pz * pz);
                    double cosT = ((px) * -px + py * -py + (pz - D) * -pz) /
                                  (r * dist);
                    double want = 0.5 * 7 / std::pow(dist, k) * cosT;
                    EXPECT_NEAR(im(x, y).g, want,
                                1e-3 * 7 / std::pow(D - r, k))
                        << x << "," << y;
                }
        }
    }
}

EXERCISE_TEST(Ex8_10_Render, ClippingPlanesCutTheSphereAtTheirDepth) {
    // Depth buffer against the analytic depths: the visible surface is the
    // first root of the ray/sphere equation within [zNear, zFar], where the
    // ray parameter of direction (xc, yc, 1) is the depth z.
    const int W = 121, H = 91;
    const double fov = 28, D = 5, r = 1;
    struct Planes {
        double zNear, zFar;
    } cases[] = {{0, 1e30}, {4.5, 1e30}, {0, 4.5}, {4.3, 5.6}, {5.2, 8}};
    for (const Planes &c : cases) {
        Float zFar = c.zFar > 1e29 ? Infinity : Float(c.zFar);
        RenderedImage im = ex::RenderImage(
            std::vector<ShapeValue>{SphereShape(Translate(Vector3f(0, 0, Float(D))) * RotateX(90),
                         Float(r), RGB(1, 1, 1))},
            AxisCamera(Float(fov), W, H, Float(c.zNear), zFar),
            OptionsValue());
        ASSERT_EQ(im.depth.size(), size_t(W * H));
        int visible = 0, zOnly = 0;
        for (int y = 0; y < H; ++y)
            for (int x = 0; x < W; ++x) {
                double xc, yc, t0, t1;
                FilmPoint(fov, W, H, x, y, &xc, &yc);
                Float got = im.depth[y * W + x];
                if (!SphereDepths(xc, yc, D, r, &t0, &t1)) {
                    EXPECT_EQ(got, Infinity);
                    continue;
                }
                const double m = 1e-4;
                if (t1 - t0 < m || std::abs(t0 - c.zNear) < m ||
                    std::abs(t1 - c.zNear) < m || std::abs(t0 - c.zFar) < m ||
                    std::abs(t1 - c.zFar) < m)
                    continue;
                double want = std::numeric_limits<double>::infinity();
                if (t0 >= c.zNear && t0 <= c.zFar) want = t0;
                else if (t1 >= c.zNear && t1 <= c.zFar) want = t1;
                if (std::isinf(want)) {
                    EXPECT_EQ(got, Infinity) << x << "," << y;
                    continue;
                }
                ++visible;
                EXPECT_NEAR(got, want, 64 * kEps * want) << x << "," << y;
                // Pixels that a clip by distance along the ray would have
                // removed, but the clip by depth keeps.
                double len = std::sqrt(xc * xc + yc * yc + 1);
                if (want * len > c.zFar) ++zOnly;
            }
        EXPECT_GT(visible, 100);
        if (c.zFar == 4.5) {
            EXPECT_GT(zOnly, 10);
        }
    }
}

EXERCISE_TEST(Ex8_10_Render, HeatMapPixelsCountTheRaysThroughTheirCenters) {
    // RenderNodeVisits() traces the camera's ray through each pixel's
    // center: its counts must be those of CountNodeVisits() for the rays
    // that the camera gives for the centers, and its colors those of the
    // counts.
    std::mt19937_64 rng(5);
    std::uniform_real_distribution<double> u(-10, 10), ur(0.2, 1.0);
    std::vector<ShapeValue> shapes;
    std::vector<std::shared_ptr<Transform>> keep;
    std::vector<std::shared_ptr<Primitive>> prims;
    for (int i = 0; i < 100; ++i) {
        Transform t = Translate(
            Vector3f(Float(u(rng)), Float(u(rng)), Float(u(rng))));
        Float r = Float(ur(rng));
        shapes.push_back(SphereShape(t, r, RGB(1, 1, 1)));
        keep.push_back(std::make_shared<Transform>(t));
        keep.push_back(std::make_shared<Transform>(Inverse(t)));
        prims.push_back(std::make_shared<GeometricPrimitive>(
            std::make_shared<Sphere>(keep[keep.size() - 2].get(),
                                     keep.back().get(), false, r, -r, r,
                                     360)));
    }
    BVHAccel bvh(prims, 2, BVHAccel::SplitMethod::Middle);
    Point3f eye(0, -40, 5), look(0, 0, 0);
    Camera cam(D(eye), D(look), V3{0, 0, 1}, 40, 48, 32);
    CameraValue camera = cam.Value(eye, look, Vector3f(0, 0, 1), 40);
    RenderedImage im = ex::RenderHeatMap(shapes, 2, camera, 50);
    std::vector<Point2f> centers;
    for (int y = 0; y < 32; ++y)
        for (int x = 0; x < 48; ++x)
            centers.push_back(Point2f(x + Float(0.5), y + Float(0.5)));
    std::vector<Ray> rays = ex::GenerateRays(camera, centers);
    ASSERT_EQ(im.visits.size(), size_t(48 * 32));
    ASSERT_EQ(im.pixels.size(), size_t(48 * 32));
    ASSERT_EQ(rays.size(), size_t(48 * 32));
    int most = 0;
    for (int i = 0; i < 48 * 32; ++i) {
        double xr, yr;
        cam.Project(D(rays[i].o) + 100 * D(rays[i].d), &xr, &yr);
        ASSERT_NEAR(xr, centers[i].x, 1e-3) << i;
        ASSERT_NEAR(yr, centers[i].y, 1e-3) << i;
        SurfaceInteraction isect;
        bool hit;
        int v = CountNodeVisits(bvh, rays[i], &isect, &hit);
        EXPECT_EQ(im.visits[i], v) << i;
        EXPECT_EQ(im.pixels[i], HeatColor(Float(v) / 50)) << i;
        most = std::max(most, v);
    }
    EXPECT_GT(most, 10);
}

// ---------------------------------------------------------------- ex-8.11

EXERCISE_TEST(Ex8_11_ShadowRays, ErrorBoundsStartOutsideTheErrorBox) {
    std::mt19937_64 rng(calls::Seed(8011));
    std::vector<ShadowHit> hits;
    for (double scale : {1e-4, 1e-2, 1.0, 1e3, 1e5})
        for (bool disk : {false, true})
            for (int found = 0, tries = 0; found < 25 && tries < 400;
                 ++tries) {
                ShadowHit h;
                if (RandomShadowHit(rng, scale, disk, &h))
                    hits.push_back(h), ++found;
            }
    std::vector<ShadowCase> cases;
    for (const ShadowHit &h : hits) cases.push_back(h.c);
    std::vector<ShadowAnswer> got = ex::SpawnShadowRays(cases);
    ASSERT_EQ(got.size(), cases.size());
    ASSERT_GT(cases.size(), 200u);
    for (size_t i = 0; i < cases.size(); ++i) {
        ASSERT_EQ(got[i].rays.size(), 1u) << i;
        CheckErrorBoundsRay(hits[i], got[i].rays[0], "error bounds");
        if (StopAfterFailures(i)) break;
        // With nothing in the way, the light arrives at the cosine.
        V3 toLight = Unit(D(cases[i].pLight) - D(cases[i].p));
        EXPECT_NEAR(got[i].color.g, Dot(toLight, hits[i].towardLight), 1e-4)
            << i;
    }
}

EXERCISE_TEST(Ex8_11_ShadowRays, FixedEpsilonStartsOffTheRayEquationsPoint) {
    // The fixed offset starts from o + t d, not from the interaction's
    // point (here deliberately a little off it), and moves along the normal
    // turned toward the eye (here the interaction's normal faces away from
    // the eye in half of the cases).
    std::mt19937_64 rng(calls::Seed(8012));
    std::uniform_real_distribution<double> u(-1, 1);
    std::vector<ShadowCase> cases;
    std::vector<V3> turned;
    for (double scale : {1e-3, 1.0, 1e4})
        for (int i = 0; i < 30; ++i) {
            V3 eye = scale * V3{10 * u(rng), 10 * u(rng), 10 + u(rng)};
            V3 q = scale * V3{u(rng), u(rng), u(rng)};
            V3 n = Unit(V3{0.3 * u(rng), 0.3 * u(rng), 1});
            if (Dot(n, eye - q) < 0) n = -1 * n;
            V3 nInteraction = i % 2 ? -1 * n : n;
            Ray ray(Point3f(Float(eye.x), Float(eye.y), Float(eye.z)),
                    Vector3f(Float(q.x - eye.x), Float(q.y - eye.y),
                             Float(q.z - eye.z)),
                    1);
            V3 off = (1e-3 * scale) * V3{u(rng), u(rng), u(rng)};
            V3 p = q + off;
            V3 light = q + (5 * scale) * Unit(n + V3{u(rng), u(rng), 0});
            ShadowCase c{ray,
                         Point3f(Float(p.x), Float(p.y), Float(p.z)),
                         Vector3f(0, 0, 0),
                         Normal3f(Float(nInteraction.x), Float(nInteraction.y),
                                  Float(nInteraction.z)),
                         ray.o,
                         Point3f(Float(light.x), Float(light.y), Float(light.z)),
                         ShadowRays::FixedEpsilon,
                         Float(1e-4 * scale)};
            cases.push_back(c);
            turned.push_back(n);
        }
    std::vector<ShadowAnswer> got = ex::SpawnShadowRays(cases);
    ASSERT_EQ(got.size(), cases.size());
    for (size_t i = 0; i < cases.size(); ++i) {
        const ShadowCase &c = cases[i];
        ASSERT_EQ(got[i].rays.size(), 1u) << i;
        const Ray &s = got[i].rays[0];
        V3 nf = D(Normal3f(Float(turned[i].x), Float(turned[i].y),
                           Float(turned[i].z)));
        CheckFixedEpsilonRay(c, nf, s, std::to_string(i));
        if (StopAfterFailures(i)) break;
    }
}

namespace {

// A floor (a disk of radius 4s at z = 0) and a slab (a disk of radius s at
// height h) centered on the z axis, lit by one light at pLight, without a
// headlight, seen from a camera of 80 x 60 pixels whose rays the test makes
// itself. Returns whether each pixel is lit and, per pixel, the exact
// verdict: -1 skip, 0 floor in shadow, 1 floor lit, 2 slab or background.
std::vector<bool> SlabScene(Float s, Float h, const Point3f &pLight,
                            ShadowRays method, std::vector<int> *verdict) {
    std::vector<ShapeValue> shapes = {
        DiskShape(Transform(), 0, 4 * s, RGB(0.5, 0.5, 0.5)),
        DiskShape(Transform(), h, s, RGB(0.5, 0.5, 0.5))};
    Point3f eye(0, -5 * s, 5 * s);
    Camera cam(D(eye), V3{-double(s), 0, 0}, V3{0, 0, 1}, 40, 80, 60);
    OptionsValue opt;
    opt.headlight = 0;
    opt.lights.push_back({pLight, RGB(s, s, s)});
    opt.shadowRays = method;
    opt.shadowEpsilon = Float(1e-4);
    verdict->assign(80 * 60, 2);
    std::vector<Ray> rays;
    for (int y = 0; y < 60; ++y)
        for (int x = 0; x < 80; ++x) {
            Ray r = cam.RayThrough(x + 0.5, y + 0.5);
            rays.push_back(r);
            double o[3] = {r.o.x, r.o.y, r.o.z}, d[3] = {r.d.x, r.d.y, r.d.z};
            double ts = (h - o[2]) / d[2], tf = -o[2] / d[2];
            double sx = o[0] + ts * d[0], sy = o[1] + ts * d[1];
            double rs = std::hypot(sx, sy);
            int &v = (*verdict)[y * 80 + x];
            if (std::abs(rs - s) < 0.02 * s) { v = -1; continue; }
            if (ts > 0 && rs < s) continue;  // the slab
            double fx = o[0] + tf * d[0], fy = o[1] + tf * d[1];
            if (!(tf > 0) || std::hypot(fx, fy) > 3.9 * s) continue;
            // The segment from the floor point to the light crosses z = h at
            // the fraction u = h / pLight.z of its length.
            double u = h / pLight.z;
            double qx = fx + u * (pLight.x - fx), qy = fy + u * (pLight.y - fy);
            double rq = std::hypot(qx, qy);
            if (std::abs(rq - s) < 0.02 * s) { v = -1; continue; }
            v = rq < s ? 0 : 1;
        }
    std::vector<ShadedRay> shaded = ex::ShadeRays(shapes, eye, opt, rays);
    if (shaded.size() != rays.size())
        throw std::runtime_error("ShadeRays answered " +
                                 std::to_string(shaded.size()) + " rays of " +
                                 std::to_string(rays.size()));
    std::vector<bool> lit;
    for (const ShadedRay &r : shaded) lit.push_back(r.hit && r.color.r > 0);
    return lit;
}

struct ShadowCount {
    int shadowPixels = 0, litPixels = 0, wrong = 0, leaks = 0, acne = 0;
};

ShadowCount CountShadows(const std::vector<bool> &lit,
                         const std::vector<int> &verdict) {
    ShadowCount c;
    for (int i = 0; i < int(verdict.size()); ++i) {
        if (verdict[i] != 0 && verdict[i] != 1) continue;
        if (verdict[i] == 0) {
            ++c.shadowPixels;
            if (lit[i]) ++c.leaks, ++c.wrong;
        } else {
            ++c.litPixels;
            if (!lit[i]) ++c.acne, ++c.wrong;
        }
    }
    return c;
}

}  // namespace

EXERCISE_TEST(Ex8_11_ShadowScenes, ErrorBoundsAreRightAtEveryScale) {
    // The light low on the +x side, so the slab's shadow falls beside it on
    // the floor, where the camera sees it.
    for (double s : {1e-3, 1.0, 1e4}) {
        std::vector<int> verdict;
        Float S = Float(s);
        std::vector<bool> lit =
            SlabScene(S, Float(0.05) * S, Point3f(10 * S, 0, 1 * S),
                      ShadowRays::ErrorBounds, &verdict);
        ShadowCount c = CountShadows(lit, verdict);
        EXPECT_GT(c.shadowPixels, 50) << s;
        EXPECT_GT(c.litPixels, 1000) << s;
        EXPECT_EQ(c.wrong, 0) << "scale " << s;
        // The same scene shaded again gives the same pixels.
        std::vector<int> again;
        EXPECT_EQ(SlabScene(S, Float(0.05) * S, Point3f(10 * S, 0, 1 * S),
                            ShadowRays::ErrorBounds, &again),
                  lit);
    }
}

EXERCISE_TEST(Ex8_11_ShadowScenes, FixedEpsilonLeaksLightUnderAThinSlab) {
    // At scale 1e-3 the slab hovers 5e-5 above the floor, less than epsilon:
    // every shadow ray starts above it.
    std::vector<int> verdict;
    std::vector<bool> lit =
        SlabScene(Float(1e-3), Float(5e-5), Point3f(1e-2f, 0, 1e-3f),
                  ShadowRays::FixedEpsilon, &verdict);
    ShadowCount c = CountShadows(lit, verdict);
    EXPECT_GT(c.shadowPixels, 50);
    EXPECT_EQ(c.leaks, c.shadowPixels);
    // At scale 1 the same slab is 0.05 above the floor and epsilon works.
    lit = SlabScene(1, Float(0.05), Point3f(10, 0, 1), ShadowRays::FixedEpsilon,
                    &verdict);
    c = CountShadows(lit, verdict);
    EXPECT_GT(c.shadowPixels, 50);
    EXPECT_EQ(c.wrong, 0);
}

EXERCISE_TEST(Ex8_11_ShadowScenes, FixedEpsilonGivesAcneAtALargeScale) {
    // Where the spacing of floating-point numbers exceeds epsilon many times,
    // the hit point o + t d falls below the floor for a good part of the
    // pixels and their shadow rays hit the floor itself.
    double s = sizeof(Float) == 4 ? 1e4 : 1e14;
    std::vector<int> verdict;
    Float S = Float(s);
    std::vector<bool> lit =
        SlabScene(S, Float(0.05) * S, Point3f(10 * S, 0, S),
                  ShadowRays::FixedEpsilon, &verdict);
    ShadowCount c = CountShadows(lit, verdict);
    EXPECT_GT(c.acne, c.litPixels / 20) << c.acne << " of " << c.litPixels;
}
