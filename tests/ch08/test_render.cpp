// Tests of chapter 8's renderer. Oracles: the analytic silhouette, depth and
// brightness of a sphere seen by a known pinhole camera, computed in double
// precision from the equations of the chapter; exact segment/disk geometry
// for shadows; BVHAccel::Intersect for the counting traversal; and a
// double-precision sRGB formula for the encoding.

#include "lrt/render/renderer.h"
#include "lrt/render/bvhvisits.h"
#include "lrt/shapes/sphere.h"
#include "lrt/shapes/disk.h"
#include "lrt/accelerators/bvh.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <memory>
#include <random>
#include <string>
#include <unistd.h>
#include <vector>

using namespace lrt;

namespace {

const Float kEps = std::numeric_limits<Float>::epsilon();

// A scene that owns its shapes' transformations (RenderScene does).
void AddSphere(RenderScene *scene, const Transform &o2w, Float r,
               const RGB &albedo) {
    const Transform *a = scene->AddTransform(o2w);
    const Transform *b = scene->AddTransform(Inverse(o2w));
    scene->AddShape(std::make_shared<Sphere>(a, b, false, r, -r, r, 360),
                    albedo);
}

void AddDisk(RenderScene *scene, const Transform &o2w, Float height,
             Float radius, const RGB &albedo) {
    const Transform *a = scene->AddTransform(o2w);
    const Transform *b = scene->AddTransform(Inverse(o2w));
    scene->AddShape(
        std::make_shared<Disk>(a, b, false, height, radius, 0, 360), albedo);
}

// The camera of the analytic tests: the eye at the origin looking down +z
// with +y up, so camera space is world space.
PinholeCamera AxisCamera(Float fov, int w, int h, Float zNear = 0,
                         Float zFar = Infinity) {
    Transform w2c = LookAt(Point3f(0, 0, 0), Point3f(0, 0, 1),
                           Vector3f(0, 1, 0));
    return PinholeCamera(Inverse(w2c), fov, w, h, zNear, zFar);
}

// Film-plane position of a pixel center, in double, from the chapter's
// equations (film at z = 1, fov spans the shorter side).
void FilmPoint(double fov, int w, int h, int x, int y, double *xc, double *yc) {
    double t = std::tan(fov * M_PI / 360);
    double sx = w >= h ? t * w / h : t, sy = w >= h ? t : t * h / w;
    *xc = (2 * (x + 0.5) / w - 1) * sx;
    *yc = (1 - 2 * (y + 0.5) / h) * sy;
}

// Roots t0 <= t1 of |t (xc, yc, 1) - (0, 0, D)|^2 = r^2; false if none.
bool SphereDepths(double xc, double yc, double D, double r, double *t0,
                  double *t1) {
    double a = xc * xc + yc * yc + 1, b = -2 * D, c = D * D - r * r;
    double disc = b * b - 4 * a * c;
    if (disc < 0) return false;
    double s = std::sqrt(disc);
    *t0 = (-b - s) / (2 * a);
    *t1 = (-b + s) / (2 * a);
    return true;
}

std::string TempPath(const std::string &name) {
    return "/tmp/lrt-ch08-" + std::to_string(getpid()) + "-" + name;
}

}  // namespace

// ---------------------------------------------------------------- images

TEST(Image, RejectsInvalidSizesAndOutOfRangePixels) {
    EXPECT_THROW(Image(0, 5), std::invalid_argument);
    EXPECT_THROW(Image(5, -1), std::invalid_argument);
    EXPECT_THROW(Image(1 << 15, 1 << 15), std::invalid_argument);
    Image im(4, 3, RGB(0.5, 0.25, 1));
    EXPECT_EQ(im(3, 2), RGB(0.5, 0.25, 1));
    EXPECT_THROW(im(4, 0), std::out_of_range);
    EXPECT_THROW(im(0, 3), std::out_of_range);
    EXPECT_THROW(im(-1, 0), std::out_of_range);
}

TEST(Image, SRGBEncodingMatchesTheStandardAndRoundTrips) {
    for (int i = 0; i <= 1000; ++i) {
        double v = i / 1000.0;
        double ref = v <= 0.0031308 ? 12.92 * v
                                    : 1.055 * std::pow(v, 1 / 2.4) - 0.055;
        EXPECT_NEAR(GammaCorrect(Float(v)), ref, 8 * kEps) << v;
        EXPECT_NEAR(InverseGammaCorrect(GammaCorrect(Float(v))), v,
                    64 * kEps + 1e-6 * v) << v;
        EXPECT_EQ(EncodeSRGB8(Float(v)), int(std::floor(255 * ref + 0.5)))
            << v;
    }
    // Every byte survives decoding and encoding again.
    for (int b = 0; b < 256; ++b)
        EXPECT_EQ(EncodeSRGB8(DecodeSRGB8(uint8_t(b))), b);
    EXPECT_EQ(EncodeSRGB8(-1), 0);
    EXPECT_EQ(EncodeSRGB8(7), 255);
    EXPECT_EQ(EncodeSRGB8(std::numeric_limits<Float>::quiet_NaN()), 0);
    EXPECT_EQ(EncodeSRGB8(Infinity), 255);
}

TEST(Image, PNGRoundTripKeepsEveryByte) {
    std::mt19937_64 rng(7001);
    std::uniform_real_distribution<double> u(-0.1, 1.1);
    Image im(37, 23);
    for (int y = 0; y < im.Height(); ++y)
        for (int x = 0; x < im.Width(); ++x)
            im(x, y) = RGB(Float(u(rng)), Float(u(rng)), Float(u(rng)));
    std::string file = TempPath("roundtrip.png");
    im.WritePNG(file);
    std::ifstream in(file, std::ios::binary);
    char sig[8] = {};
    in.read(sig, 8);
    EXPECT_EQ(std::string(sig + 1, 3), "PNG");
    Image back = Image::ReadPNG(file);
    std::remove(file.c_str());
    ASSERT_EQ(back.Width(), 37);
    ASSERT_EQ(back.Height(), 23);
    EXPECT_EQ(back.EncodeSRGB8(), im.EncodeSRGB8());
}

TEST(Image, WritePNGToABadPathThrowsNamingTheFile) {
    Image im(2, 2);
    const std::string bad = "/nonexistent-lrt-dir/figure.png";
    try {
        im.WritePNG(bad);
        FAIL() << "no exception";
    } catch (const std::runtime_error &e) {
        EXPECT_NE(std::string(e.what()).find(bad), std::string::npos)
            << e.what();
        EXPECT_NE(std::string(e.what()).find("WritePNG"), std::string::npos);
    }
    // A directory is not a file either.
    EXPECT_THROW(im.WritePNG("/tmp"), std::runtime_error);
    // A full disk shows only when the data is flushed.
    if (std::ifstream("/dev/full")) {
        try {
            im.WritePNG("/dev/full");
            FAIL() << "no exception writing to /dev/full";
        } catch (const std::runtime_error &e) {
            EXPECT_NE(std::string(e.what()).find("/dev/full"),
                      std::string::npos);
        }
    }
    EXPECT_THROW(Image().WritePNG(TempPath("empty.png")),
                 std::invalid_argument);
}

TEST(Image, ReadPNGOfAMissingOrBadFileThrowsNamingTheFile) {
    const std::string missing = TempPath("missing.png");
    try {
        Image::ReadPNG(missing);
        FAIL() << "no exception";
    } catch (const std::runtime_error &e) {
        EXPECT_NE(std::string(e.what()).find(missing), std::string::npos);
    }
    std::string notPng = TempPath("text.png");
    std::ofstream(notPng) << "not an image\n";
    EXPECT_THROW(Image::ReadPNG(notPng), std::runtime_error);
    std::remove(notPng.c_str());
}

// ---------------------------------------------------------------- camera

TEST(PinholeCamera, RejectsBadArguments) {
    Transform id;
    EXPECT_THROW(PinholeCamera(id, 0, 10, 10), std::invalid_argument);
    EXPECT_THROW(PinholeCamera(id, 180, 10, 10), std::invalid_argument);
    EXPECT_THROW(PinholeCamera(id, std::nan(""), 10, 10),
                 std::invalid_argument);
    EXPECT_THROW(PinholeCamera(id, 40, 0, 10), std::invalid_argument);
    EXPECT_THROW(PinholeCamera(id, 40, 10, 10, -1, 5), std::invalid_argument);
    EXPECT_THROW(PinholeCamera(id, 40, 10, 10, 5, 5), std::invalid_argument);
    EXPECT_NO_THROW(PinholeCamera(id, 40, 10, 10, 0, Infinity));
}

TEST(PinholeCamera, RaysPassThroughTheFilmPlaneOfTheFieldOfView) {
    // A camera placed anywhere: in camera space the ray through raster point
    // (xr, yr) has the direction of the film point, with z = 1.
    Point3f eye(3, -2, 5), look(-1, 4, 2);
    Transform w2c = LookAt(eye, look, Vector3f(0, 0, 1));
    for (auto [w, h] : {std::pair<int, int>{64, 48}, {30, 90}}) {
        PinholeCamera cam(Inverse(w2c), 50, w, h);
        double t = std::tan(50 * M_PI / 360);
        double sx = w >= h ? t * w / h : t, sy = w >= h ? t : t * h / w;
        for (auto [xr, yr] : {std::pair<double, double>{0, 0}, {w, h},
                              {w / 2.0, h / 2.0}, {0.25 * w, 0.9 * h}}) {
            Ray r = cam.GenerateRay(Point2f(Float(xr), Float(yr)));
            EXPECT_LT(Distance(r.o, eye), 16 * kEps * 6);
            Vector3f dc = w2c(r.d);
            EXPECT_NEAR(dc.z, 1, 16 * kEps);
            EXPECT_NEAR(dc.x, (2 * xr / w - 1) * sx, 16 * kEps);
            EXPECT_NEAR(dc.y, (1 - 2 * yr / h) * sy, 16 * kEps);
            EXPECT_EQ(r.tMax, Infinity);
        }
        // The image center looks at the look-at point.
        Ray c = cam.GenerateRay(Point2f(w / 2.0f, h / 2.0f));
        Vector3f want = Normalize(look - eye);
        EXPECT_NEAR(Dot(Normalize(c.d), want), 1, 16 * kEps);
    }
}

TEST(PinholeCamera, NearPlaneMovesTheOriginAndFarPlaneBoundsTheRay) {
    PinholeCamera cam = AxisCamera(60, 11, 11, 2, 7);
    Ray r = cam.GenerateRay(Point2f(0, 0));
    EXPECT_NEAR(r.o.z, 2, 4 * kEps);
    EXPECT_NEAR(r.tMax, 5, 4 * kEps);
    EXPECT_NEAR(cam.Depth(r(r.tMax)), 7, 16 * kEps);
}

// ---------------------------------------------------------------- shading

TEST(Render, SphereSilhouetteHasTheAnalyticRadius) {
    // A sphere of radius r at distance D on the axis: a ray with film point
    // (xc, yc) hits it iff xc^2 + yc^2 < tan^2(asin(r / D)) = r^2/(D^2 - r^2).
    const int W = 161, H = 121;
    const double fov = 30;
    for (double D : {4.0, 9.0, 25.0}) {
        const double r = 1;
        RenderScene scene;
        AddSphere(&scene, Translate(Vector3f(0, 0, Float(D))), Float(r),
                  RGB(1, 1, 1));
        std::vector<Float> depth;
        Render(scene, AxisCamera(Float(fov), W, H), RenderOptions(), &depth);
        double R = r / std::sqrt(D * D - r * r);
        int checked = 0, hits = 0, centerRow = 0;
        for (int y = 0; y < H; ++y)
            for (int x = 0; x < W; ++x) {
                double xc, yc;
                FilmPoint(fov, W, H, x, y, &xc, &yc);
                double rho = std::sqrt(xc * xc + yc * yc);
                bool hit = std::isfinite(depth[y * W + x]);
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

TEST(Render, HeadlightBrightnessFollowsTheFalloff) {
    // The center pixel of an odd-sized image looks along the axis and hits
    // the sphere head on at distance D - r, with cos = 1: L = rho I f(D - r).
    // Every other pixel: L = rho I f(dist) cos, from the analytic hit.
    const int W = 41, H = 41;
    const double fov = 40, r = 1.5;
    const RGB albedo(0.8, 0.5, 0.25);
    for (Falloff f : {Falloff::None, Falloff::InverseDistance,
                      Falloff::InverseSquare}) {
        for (double D : {5.0, 12.0}) {
            RenderScene scene;
            // Rotated so that the ray along the axis does not meet the
            // sphere at a pole, where Sphere nudges the hit point by 1e-5 r
            // (Chapter 3), which double precision would notice.
            AddSphere(&scene,
                      Translate(Vector3f(0, 0, Float(D))) * RotateX(90),
                      Float(r), albedo);
            RenderOptions opt;
            opt.headlight = 7;
            opt.falloff = f;
            opt.background = RGB(0.125, 0.25, 0.5);
            Image im = Render(scene, AxisCamera(Float(fov), W, H), opt);
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

TEST(Render, ClippingPlanesCutTheSphereAtTheirDepth) {
    // Depth buffer against the analytic depths: the visible surface is the
    // first root of the ray/sphere equation within [zNear, zFar], where the
    // ray parameter of direction (xc, yc, 1) is the depth z.
    const int W = 121, H = 91;
    const double fov = 28, D = 5, r = 1;
    struct Planes {
        double zNear, zFar;
    } cases[] = {{0, 1e30}, {4.5, 1e30}, {0, 4.5}, {4.3, 5.6}, {5.2, 8}};
    for (const Planes &c : cases) {
        RenderScene scene;
        AddSphere(&scene, Translate(Vector3f(0, 0, Float(D))) * RotateX(90),
                  Float(r), RGB(1, 1, 1));
        Float zFar = c.zFar > 1e29 ? Infinity : Float(c.zFar);
        std::vector<Float> depth;
        Render(scene, AxisCamera(Float(fov), W, H, Float(c.zNear), zFar),
               RenderOptions(), &depth);
        int visible = 0, zOnly = 0;
        for (int y = 0; y < H; ++y)
            for (int x = 0; x < W; ++x) {
                double xc, yc, t0, t1;
                FilmPoint(fov, W, H, x, y, &xc, &yc);
                Float got = depth[y * W + x];
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

TEST(Render, IsDeterministic) {
    auto render = [] {
        RenderScene scene;
        AddDisk(&scene, Transform(), 0, 10, RGB(0.5, 0.5, 0.5));
        std::mt19937_64 rng(17);
        std::uniform_real_distribution<double> u(-3, 3);
        for (int i = 0; i < 6; ++i)
            AddSphere(&scene,
                      Translate(Vector3f(Float(u(rng)), Float(u(rng)), 1)),
                      Float(0.4 + 0.1 * i), RGB(0.9, 0.3, 0.2));
        Transform w2c = LookAt(Point3f(1, -9, 5), Point3f(0, 0, 0.5),
                               Vector3f(0, 0, 1));
        RenderOptions opt;
        opt.lights.push_back({Point3f(-5, -3, 9), RGB(6, 6, 6)});
        return Render(scene, PinholeCamera(Inverse(w2c), 35, 96, 64), opt);
    };
    Image a = render(), b = render();
    int lit = 0;
    for (int y = 0; y < a.Height(); ++y)
        for (int x = 0; x < a.Width(); ++x) {
            ASSERT_EQ(a(x, y), b(x, y)) << x << "," << y;
            lit += a(x, y).r > 0;
        }
    EXPECT_GT(lit, 1000);
}

TEST(RenderScene, ReportsTheNearestObjectAndRejectsNull) {
    RenderScene scene;
    EXPECT_THROW(scene.Add(nullptr, RGB()), std::invalid_argument);
    AddSphere(&scene, Translate(Vector3f(0, 0, 9)), 1, RGB(1, 0, 0));
    AddSphere(&scene, Translate(Vector3f(0, 0, 5)), 1, RGB(0, 1, 0));
    AddSphere(&scene, Translate(Vector3f(0, 0, 7)), 1, RGB(0, 0, 1));
    Ray ray(Point3f(0, 0, 0), Vector3f(0, 0, 1));
    SurfaceInteraction isect;
    const SceneObject *hit = nullptr;
    ASSERT_TRUE(scene.Intersect(ray, &isect, &hit));
    EXPECT_EQ(hit->albedo, RGB(0, 1, 0));
    EXPECT_NEAR(ray.tMax, 4, 8 * kEps);
    EXPECT_TRUE(scene.IntersectP(Ray(Point3f(0, 0, 0), Vector3f(0, 0, 1))));
    EXPECT_FALSE(scene.IntersectP(Ray(Point3f(0, 0, 0), Vector3f(0, 1, 0))));
}

// ---------------------------------------------------------------- shadows

namespace {

// A floor disk (radius 4s at z = 0) and a slab disk (radius s at height h)
// centered on the z axis, lit by one light at pLight; no headlight. Returns
// the image and, per pixel, the exact verdict: -1 skip, 0 floor in shadow,
// 1 floor lit, 2 slab or background.
Image SlabScene(Float s, Float h, const Point3f &pLight, ShadowRays method,
                std::vector<int> *verdict) {
    RenderScene scene;
    AddDisk(&scene, Transform(), 0, 4 * s, RGB(0.5, 0.5, 0.5));
    AddDisk(&scene, Transform(), h, s, RGB(0.5, 0.5, 0.5));
    Transform w2c = LookAt(Point3f(0, -5 * s, 5 * s), Point3f(-s, 0, 0),
                           Vector3f(0, 0, 1));
    PinholeCamera cam(Inverse(w2c), 40, 80, 60);
    RenderOptions opt;
    opt.headlight = 0;
    opt.lights.push_back({pLight, RGB(s, s, s)});
    opt.shadowRays = method;
    opt.shadowEpsilon = Float(1e-4);
    verdict->assign(80 * 60, 2);
    for (int y = 0; y < 60; ++y)
        for (int x = 0; x < 80; ++x) {
            Ray r = cam.GenerateRay(Point2f(x + 0.5f, y + 0.5f));
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
    return Render(scene, cam, opt);
}

struct ShadowCount {
    int shadowPixels = 0, litPixels = 0, wrong = 0, leaks = 0, acne = 0;
};

ShadowCount CountShadows(const Image &im, const std::vector<int> &verdict) {
    ShadowCount c;
    for (int i = 0; i < int(verdict.size()); ++i) {
        if (verdict[i] != 0 && verdict[i] != 1) continue;
        bool lit = im(i % 80, i / 80).r > 0;
        if (verdict[i] == 0) {
            ++c.shadowPixels;
            if (lit) ++c.leaks, ++c.wrong;
        } else {
            ++c.litPixels;
            if (!lit) ++c.acne, ++c.wrong;
        }
    }
    return c;
}

}  // namespace

TEST(Shadows, ErrorBoundsAreRightAtEveryScale) {
    // The light low on the +x side, so the slab's shadow falls beside it on
    // the floor, where the camera sees it.
    for (double s : {1e-3, 1.0, 1e4}) {
        std::vector<int> verdict;
        Float S = Float(s);
        Image im = SlabScene(S, Float(0.05) * S, Point3f(10 * S, 0, 1 * S),
                             ShadowRays::ErrorBounds, &verdict);
        ShadowCount c = CountShadows(im, verdict);
        EXPECT_GT(c.shadowPixels, 50) << s;
        EXPECT_GT(c.litPixels, 1000) << s;
        EXPECT_EQ(c.wrong, 0) << "scale " << s;
    }
}

TEST(Shadows, FixedEpsilonLeaksLightUnderAThinSlab) {
    // At scale 1e-3 the slab hovers 5e-5 above the floor, less than epsilon:
    // every shadow ray starts above it.
    std::vector<int> verdict;
    Image im = SlabScene(Float(1e-3), Float(5e-5), Point3f(1e-2f, 0, 1e-3f),
                         ShadowRays::FixedEpsilon, &verdict);
    ShadowCount c = CountShadows(im, verdict);
    EXPECT_GT(c.shadowPixels, 50);
    EXPECT_EQ(c.leaks, c.shadowPixels);
    // At scale 1 the same slab is 0.05 above the floor and epsilon works.
    im = SlabScene(1, Float(0.05), Point3f(10, 0, 1), ShadowRays::FixedEpsilon,
                   &verdict);
    c = CountShadows(im, verdict);
    EXPECT_EQ(c.wrong, 0);
}

TEST(Shadows, FixedEpsilonGivesAcneAtALargeScale) {
    // Where the spacing of floating-point numbers exceeds epsilon many times,
    // the hit point o + t d falls below the floor for a good part of the
    // pixels and their shadow rays hit the floor itself.
    double s = sizeof(Float) == 4 ? 1e4 : 1e14;
    std::vector<int> verdict;
    Float S = Float(s);
    Image im = SlabScene(S, Float(0.05) * S, Point3f(10 * S, 0, S),
                         ShadowRays::FixedEpsilon, &verdict);
    ShadowCount c = CountShadows(im, verdict);
    EXPECT_GT(c.acne, c.litPixels / 20) << c.acne << " of " << c.litPixels;
}

// ---------------------------------------------------------------- BVH visits

namespace {

std::vector<std::shared_ptr<Primitive>> RandomSpheres(
    std::vector<std::unique_ptr<Transform>> *keep, int n, uint64_t seed) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> u(-10, 10), ur(0.2, 1.0);
    std::vector<std::shared_ptr<Primitive>> prims;
    for (int i = 0; i < n; ++i) {
        keep->push_back(std::make_unique<Transform>(Translate(
            Vector3f(Float(u(rng)), Float(u(rng)), Float(u(rng))))));
        const Transform *a = keep->back().get();
        keep->push_back(std::make_unique<Transform>(Inverse(*a)));
        Float r = Float(ur(rng));
        prims.push_back(std::make_shared<GeometricPrimitive>(
            std::make_shared<Sphere>(a, keep->back().get(), false, r, -r, r,
                                     360)));
    }
    return prims;
}

}  // namespace

TEST(BVHVisits, CountingTraversalFindsWhatIntersectFinds) {
    std::vector<std::unique_ptr<Transform>> keep;
    auto prims = RandomSpheres(&keep, 300, 77);
    std::mt19937_64 rng(78);
    std::uniform_real_distribution<double> u(-14, 14);
    using SM = BVHAccel::SplitMethod;
    for (SM m : {SM::SAH, SM::HLBVH, SM::Middle, SM::EqualCounts}) {
        BVHAccel bvh(prims, 4, m);
        int total = int(bvh.Nodes().size()), hits = 0;
        for (int i = 0; i < 2000; ++i) {
            Point3f o(Float(u(rng)), Float(u(rng)), Float(u(rng)));
            Point3f t(Float(u(rng)), Float(u(rng)), Float(u(rng)));
            Ray a(o, t - o), b(o, t - o);
            SurfaceInteraction ia, ib;
            bool hitA = bvh.Intersect(a, &ia), hitB;
            int visits = CountNodeVisits(bvh, b, &ib, &hitB);
            ASSERT_EQ(hitA, hitB);
            EXPECT_GE(visits, 1);
            EXPECT_LE(visits, total);
            if (hitA) {
                ++hits;
                EXPECT_EQ(a.tMax, b.tMax);
                EXPECT_EQ(ia.primitive, ib.primitive);
            }
        }
        EXPECT_GT(hits, 200);
    }
}

TEST(BVHVisits, ExactCountsOnATwoLeafTree) {
    // Two unit spheres at x = -5 and x = 5, one primitive per leaf: a root
    // and two leaves. A ray that misses the root's box costs one visit; one
    // that enters it costs three, whichever leaves it hits.
    std::vector<std::unique_ptr<Transform>> keep;
    std::vector<std::shared_ptr<Primitive>> prims;
    for (Float x : {Float(-5), Float(5)}) {
        keep.push_back(
            std::make_unique<Transform>(Translate(Vector3f(x, 0, 0))));
        const Transform *a = keep.back().get();
        keep.push_back(std::make_unique<Transform>(Inverse(*a)));
        prims.push_back(std::make_shared<GeometricPrimitive>(
            std::make_shared<Sphere>(a, keep.back().get(), false, 1, -1, 1,
                                     360)));
    }
    BVHAccel bvh(prims, 1, BVHAccel::SplitMethod::SAH);
    ASSERT_EQ(bvh.Nodes().size(), 3u);
    SurfaceInteraction isect;
    bool hit = true;
    EXPECT_EQ(CountNodeVisits(bvh, Ray(Point3f(0, 10, 0), Vector3f(1, 0, 0)),
                              &isect, &hit), 1);
    EXPECT_FALSE(hit);
    // Too short to reach the root's box.
    EXPECT_EQ(CountNodeVisits(bvh, Ray(Point3f(-5, 0, 10), Vector3f(0, 0, -1),
                                       5), &isect, &hit), 1);
    EXPECT_FALSE(hit);
    // Between the spheres: inside the root's box, outside both leaves'.
    EXPECT_EQ(CountNodeVisits(bvh, Ray(Point3f(0, 0, 10), Vector3f(0, 0, -1)),
                              &isect, &hit), 3);
    EXPECT_FALSE(hit);
    Ray down(Point3f(-5, 0, 10), Vector3f(0, 0, -1));
    EXPECT_EQ(CountNodeVisits(bvh, down, &isect, &hit), 3);
    EXPECT_TRUE(hit);
    EXPECT_NEAR(down.tMax, 9, 16 * kEps * 9);
    Ray along(Point3f(-20, 0, 0), Vector3f(1, 0, 0));
    EXPECT_EQ(CountNodeVisits(bvh, along, &isect, &hit), 3);
    EXPECT_TRUE(hit);
    EXPECT_NEAR(along.tMax, 14, 16 * kEps * 14);
    BVHAccel empty({}, 1);
    EXPECT_EQ(CountNodeVisits(empty, along, &isect, &hit), 0);
    EXPECT_FALSE(hit);
}

TEST(BVHVisits, HeatColorGrowsLighterAndClamps) {
    auto luminance = [](const RGB &c) {
        return 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b;
    };
    double last = -1;
    for (int i = 0; i <= 400; ++i) {
        double l = luminance(HeatColor(Float(i) / 400));
        EXPECT_GT(l, last) << i;
        last = l;
    }
    EXPECT_EQ(HeatColor(-3), HeatColor(0));
    EXPECT_EQ(HeatColor(5), HeatColor(1));
    EXPECT_EQ(HeatColor(std::numeric_limits<Float>::quiet_NaN()), HeatColor(0));
}

TEST(BVHVisits, HeatMapColorsEachPixelByItsCount) {
    std::vector<std::unique_ptr<Transform>> keep;
    auto prims = RandomSpheres(&keep, 100, 5);
    BVHAccel bvh(prims, 2, BVHAccel::SplitMethod::Middle);
    Transform w2c = LookAt(Point3f(0, -40, 5), Point3f(0, 0, 0),
                           Vector3f(0, 0, 1));
    PinholeCamera cam(Inverse(w2c), 40, 48, 32);
    std::vector<int> visits;
    Image im = RenderNodeVisits(bvh, cam, 50, &visits);
    ASSERT_EQ(visits.size(), size_t(48 * 32));
    int most = 0;
    for (int y = 0; y < 32; ++y)
        for (int x = 0; x < 48; ++x) {
            Ray r = cam.GenerateRay(Point2f(x + 0.5f, y + 0.5f));
            SurfaceInteraction isect;
            bool hit;
            int v = CountNodeVisits(bvh, r, &isect, &hit);
            EXPECT_EQ(visits[y * 48 + x], v);
            EXPECT_EQ(im(x, y), HeatColor(Float(v) / 50));
            most = std::max(most, v);
        }
    EXPECT_GT(most, 10);
}
