// Tests of chapter 8's renderer that no graded exercise's code takes part
// in: images and PNG files, the decoding of sRGB bytes, the camera's argument
// checks, the scene's nearest hit and the BVH traversal counter. The tests of
// the encoding, the camera's rays, rendering and shadows are the exercise
// tests of test_render_exercises.cpp. Oracles: a double-precision sRGB
// formula, exact counts on a tree of known shape, and BVHAccel::Intersect.

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

TEST(Image, SRGBDecodingMatchesTheStandardAndEncodingClamps) {
    for (int i = 0; i <= 1000; ++i) {
        double e = i / 1000.0;
        double ref = e <= 0.04045 ? e / 12.92
                                  : std::pow((e + 0.055) / 1.055, 2.4);
        EXPECT_NEAR(InverseGammaCorrect(Float(e)), ref, 16 * kEps * ref + 1e-9)
            << e;
    }
    for (int b = 0; b < 256; ++b) {
        double e = b / 255.0;
        double ref = e <= 0.04045 ? e / 12.92
                                  : std::pow((e + 0.055) / 1.055, 2.4);
        EXPECT_NEAR(DecodeSRGB8(uint8_t(b)), ref, 16 * kEps * ref) << b;
    }
    // Outside (0, 1) the encoding clamps, before any curve is evaluated.
    EXPECT_EQ(EncodeSRGB8(0), 0);
    EXPECT_EQ(EncodeSRGB8(-1), 0);
    EXPECT_EQ(EncodeSRGB8(1), 255);
    EXPECT_EQ(EncodeSRGB8(7), 255);
    EXPECT_EQ(EncodeSRGB8(std::numeric_limits<Float>::quiet_NaN()), 0);
    EXPECT_EQ(EncodeSRGB8(Infinity), 255);
}

// The bytes of the file are those of the image. The pixels are black or
// white in each channel, at random, so that the test needs no more of the
// encoding than its clamps (the curve between them is Exercise 8.9's, and
// its tests check every byte).
TEST(Image, PNGRoundTripKeepsEveryByte) {
    std::mt19937_64 rng(7001);
    std::uniform_int_distribution<int> u(0, 3);
    const Float levels[4] = {-Float(0.1), 0, 1, Float(1.1)};
    Image im(37, 23);
    for (int y = 0; y < im.Height(); ++y)
        for (int x = 0; x < im.Width(); ++x)
            im(x, y) = RGB(levels[u(rng)], levels[u(rng)], levels[u(rng)]);
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
    std::vector<uint8_t> bytes = im.EncodeSRGB8();
    EXPECT_EQ(back.EncodeSRGB8(), bytes);
    int white = 0;
    for (uint8_t b : bytes) white += b == 255;
    EXPECT_GT(white, 37 * 23 * 3 / 3);
    EXPECT_LT(white, 37 * 23 * 3 * 2 / 3);
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
