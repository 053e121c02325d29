// render/figures.cpp: tangled from chapters/08-rendering.md. Edit the chapter, not this file.
#include "lrt/lrt.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

using namespace lrt;

namespace {

// Figure Program Helpers
PinholeCamera LookAtCamera(const Point3f &eye, const Point3f &look,
                           Float fov, int width, int height,
                           Float zNear = 0, Float zFar = Infinity) {
    Transform worldToCamera = LookAt(eye, look, Vector3f(0, 0, 1));
    return PinholeCamera(Inverse(worldToCamera), fov, width, height, zNear,
                         zFar);
}

void AddSphere(RenderScene *scene, const Transform &objectToWorld,
               Float radius, Float zMin, Float zMax, Float phiMax,
               const RGB &albedo) {
    const Transform *o2w = scene->AddTransform(objectToWorld);
    const Transform *w2o = scene->AddTransform(Inverse(objectToWorld));
    scene->AddShape(std::make_shared<Sphere>(o2w, w2o, false, radius, zMin,
                                             zMax, phiMax),
                    albedo);
}

void AddDisk(RenderScene *scene, const Transform &objectToWorld,
             Float height, Float radius, Float innerRadius, Float phiMax,
             const RGB &albedo) {
    const Transform *o2w = scene->AddTransform(objectToWorld);
    const Transform *w2o = scene->AddTransform(Inverse(objectToWorld));
    scene->AddShape(std::make_shared<Disk>(o2w, w2o, false, height, radius,
                                           innerRadius, phiMax),
                    albedo);
}
template <typename QuadricShape, typename... Parameters>
void AddQuadric(RenderScene *scene, const Transform &objectToWorld,
                const RGB &albedo, Parameters... parameters) {
    const Transform *o2w = scene->AddTransform(objectToWorld);
    const Transform *w2o = scene->AddTransform(Inverse(objectToWorld));
    scene->AddShape(
        std::make_shared<QuadricShape>(o2w, w2o, false, parameters...),
        albedo);
}
std::string dataDir = "data";

std::vector<std::shared_ptr<Primitive>> BunnyPrimitives(
    RenderScene *scene) {
    PlyMesh m = ReadPly(dataDir + "/bunny.ply");
    const Transform *o2w = scene->AddTransform(RotateX(90));
    const Transform *w2o = scene->AddTransform(Inverse(*o2w));
    auto shapes = CreateTriangleMesh(o2w, w2o, false, m.nTriangles(),
                                     m.vertexIndices.data(), m.nVertices(),
                                     m.p.data(), nullptr, nullptr, nullptr);
    std::vector<std::shared_ptr<Primitive>> prims;
    for (const auto &s : shapes)
        prims.push_back(std::make_shared<GeometricPrimitive>(s));
    return prims;
}
Image Tile(const std::vector<Image> &panels, int columns, int gap = 20) {
    int w = panels[0].Width(), h = panels[0].Height();
    int rows = (int(panels.size()) + columns - 1) / columns;
    Image out(columns * w + (columns - 1) * gap, rows * h + (rows - 1) * gap,
              RGB(1, 1, 1));
    for (size_t i = 0; i < panels.size(); ++i) {
        if (panels[i].Width() != w || panels[i].Height() != h)
            throw std::logic_error("Tile: panels differ in size");
        int x0 = int(i) % columns * (w + gap);
        int y0 = int(i) / columns * (h + gap);
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) out(x0 + x, y0 + y) = panels[i](x, y);
    }
    return out;
}

// Figure Scenes
const RGB kFloor(0.55, 0.55, 0.55);
const RGB kRed(0.75, 0.22, 0.18), kBlue(0.22, 0.45, 0.75);
const RGB kGreen(0.30, 0.62, 0.30), kOrange(0.85, 0.60, 0.18);
const RGB kWhite(1, 1, 1);

RenderOptions TwoLights(Float headlight, const Point3f &pLight, Float I) {
    RenderOptions options;
    options.headlight = headlight;
    options.background = kWhite;
    options.lights.push_back({pLight, RGB(I, I, I)});
    return options;
}
Image PartialSpheres() {
    RenderScene scene;
    AddDisk(&scene, Transform(), 0, 14, 0, 360, kFloor);
    struct {
        Float x, zMin, zMax, phiMax, rotateZ;
        RGB albedo;
    } spheres[] = {{3.3, -1, 1, 360, 0, kRed},
                   {1.1, -0.6, 0.5, 360, 0, kBlue},
                   {-1.1, -1, 1, 270, -45, kGreen},
                   {-3.3, -0.7, 0.8, 220, -20, kOrange}};
    for (const auto &s : spheres)
        AddSphere(&scene,
                  Translate(Vector3f(s.x, 0, 1.15)) * RotateZ(s.rotateZ), 1,
                  s.zMin, s.zMax, s.phiMax, s.albedo);
    PinholeCamera camera = LookAtCamera(Point3f(0, -10, 5), Point3f(0, 0, 0.8),
                                        22, 1872, 728);
    return Render(scene, camera, TwoLights(5, Point3f(7, -5, 11), 12));
}
Image Disks() {
    RenderScene scene;
    AddDisk(&scene, Transform(), 0, 14, 0, 360, kFloor);
    AddDisk(&scene, Translate(Vector3f(1.3, 0, 1.4)) * RotateX(55), 0, 1,
            0.45, 360, kBlue);
    AddDisk(&scene,
            Translate(Vector3f(-1.3, 0, 1.4)) * RotateX(55) * RotateZ(-45), 0,
            1, 0.3, 270, kOrange);
    PinholeCamera camera = LookAtCamera(Point3f(0, -7, 4.2), Point3f(0, 0, 1),
                                        28, 1512, 810);
    return Render(scene, camera, TwoLights(3.5, Point3f(5, -4, 9), 8));
}
Image Quadrics() {
    RenderScene scene;
    AddDisk(&scene, Transform(), 0, 30, 0, 360, kFloor);
    AddSphere(&scene, Translate(Vector3f(2.8, -1.6, 0.9)), 0.9, -0.9, 0.9,
              360, kRed);
    AddDisk(&scene, Translate(Vector3f(0, -1.6, 1)) * RotateX(35), 0, 0.9,
            0.35, 360, kGreen);
    AddQuadric<Paraboloid>(&scene, Translate(Vector3f(-2.8, -1.6, -0.25)),
                           kBlue, 0.9, 0.25, 1.8, 360);
    AddQuadric<Cylinder>(&scene,
                         Translate(Vector3f(2.8, 1.8, 0)) * RotateZ(-45),
                         kOrange, 0.8, 0, 1.7, 270);
    AddQuadric<Cone>(&scene, Translate(Vector3f(0, 1.8, 0)) * RotateZ(-60),
                     kBlue, 1.8, 0.9, 300);
    AddQuadric<Hyperboloid>(&scene,
                            Translate(Vector3f(-2.8, 1.8, 0)) * RotateZ(-45),
                            kGreen, Point3f(0.55, -0.75, 0),
                            Point3f(0.55, 0.75, 1.8), 270);
    PinholeCamera camera = LookAtCamera(
        Point3f(0, -10, 9), Point3f(-0.3, 0.3, 0.7), 28, 1872, 1000);
    return Render(scene, camera, TwoLights(6, Point3f(7, -5, 11), 12));
}
Image Bunny() {
    RenderScene scene;
    AddDisk(&scene, Transform(), 0, 80, 0, 360, kFloor);
    scene.Add(std::make_shared<FastBVHAccel>(BunnyPrimitives(&scene)),
              RGB(0.80, 0.72, 0.60));
    PinholeCamera camera = LookAtCamera(Point3f(10, -26, 12),
                                        Point3f(0, 0, 4.3), 25, 1152, 960);
    return Render(scene, camera, TwoLights(14, Point3f(14, -18, 26), 30));
}
const Point3f kRowEye(0, 0, 4.5);

void AddSphereRow(RenderScene *scene) {
    AddDisk(scene, Transform(), 0, 60, 0, 360, kFloor);
    const RGB colors[5] = {kRed, kBlue, kGreen, kOrange, kRed};
    for (int i = 0; i < 5; ++i)
        AddSphere(scene, Translate(Vector3f(i % 2 ? -1.6 : 1.6, 6 + 4 * i, 1)),
                  1, -1, 1, 360, colors[i]);
}

PinholeCamera RowCamera(int width, int height, Float zNear = 0,
                        Float zFar = Infinity) {
    return LookAtCamera(kRowEye, Point3f(0, 13, 0.5), 32, width, height,
                        zNear, zFar);
}

Image FalloffComparison() {
    RenderScene scene;
    AddSphereRow(&scene);
    Float t0 = Distance(kRowEye, Point3f(1.6, 6, 1)) - 1;
    std::vector<Image> panels;
    int k = 0;
    for (Falloff f : {Falloff::None, Falloff::InverseDistance,
                      Falloff::InverseSquare}) {
        RenderOptions options;
        options.falloff = f;
        options.background = kWhite;
        options.headlight = Float(0.9) * std::pow(t0, Float(k++));
        panels.push_back(Render(scene, RowCamera(612, 459), options));
    }
    return Tile(panels, 3);
}
Image Clipping() {
    RenderScene scene;
    AddSphereRow(&scene);
    RenderOptions options = TwoLights(5, Point3f(8, 2, 12), 10);
    PinholeCamera plain = RowCamera(936, 702);
    Float zNear = plain.Depth(Point3f(1.6, 6, 1));
    Float zFar = plain.Depth(Point3f(-1.6, 18, 1));
    return Tile({Render(scene, plain, options),
                 Render(scene, RowCamera(936, 702, zNear, zFar), options)},
                2);
}
Image BiasPanel(Float s, ShadowRays shadowRays) {
    RenderScene scene;
    AddDisk(&scene, Transform(), 0, 8 * s, 0, 360, kFloor);
    AddSphere(&scene, Translate(Vector3f(-1.3 * s, 1.6 * s, s)), s, -s, s,
              360, kRed);
    AddDisk(&scene, Translate(Vector3f(1.4 * s, -0.8 * s, 0)), 0.08 * s,
            1.1 * s, 0, 360, kBlue);
    PinholeCamera camera = LookAtCamera(Point3f(0, -9 * s, 5.5 * s),
                                        Point3f(0, 0.2 * s, 0.3 * s), 34, 920,
                                        598);
    RenderOptions options = TwoLights(3 * s, Point3f(12 * s, 2 * s, 2.6 * s),
                                      16 * s);
    options.shadowRays = shadowRays;
    options.shadowEpsilon = Float(1e-4);
    return Render(scene, camera, options);
}

Image ShadowBias() {
    std::vector<Image> panels;
    for (Float s : {Float(1e-3), Float(1e4)})
        for (ShadowRays r : {ShadowRays::FixedEpsilon, ShadowRays::ErrorBounds})
            panels.push_back(BiasPanel(s, r));
    return Tile(panels, 2);
}
Image HeatMaps() {
    RenderScene scene;
    auto prims = BunnyPrimitives(&scene);
    PinholeCamera camera = LookAtCamera(Point3f(10, -26, 12),
                                        Point3f(0, 0, 4.6), 24, 690, 690);
    const int maxVisits = 120;
    std::vector<Image> panels;
    using SM = BVHAccel::SplitMethod;
    for (SM m : {SM::SAH, SM::HLBVH, SM::Middle, SM::EqualCounts}) {
        BVHAccel bvh(prims, 4, m);
        std::vector<int> visits;
        panels.push_back(RenderNodeVisits(bvh, camera, maxVisits, &visits));
        double sum = 0;
        int most = 0;
        for (int v : visits) sum += v, most = std::max(most, v);
        std::printf("  %-12s %6.1f node visits per pixel on average, "
                    "at most %d\n", BVHAccel::SplitMethodName(m),
                    sum / visits.size(), most);
    }
    // Append a color bar to the tiled heat maps
    Image maps = Tile(panels, 2);
    const int gap = 20, barHeight = 40;
    Image out(maps.Width(), maps.Height() + gap + barHeight, kWhite);
    for (int y = 0; y < maps.Height(); ++y)
        for (int x = 0; x < maps.Width(); ++x) out(x, y) = maps(x, y);
    for (int y = 0; y < barHeight; ++y)
        for (int x = 0; x < maps.Width(); ++x)
            out(x, maps.Height() + gap + y) =
                HeatColor(Float(x) / Float(maps.Width() - 1));
    return out;
}

// Figure List
struct Figure {
    std::string name;
    std::function<Image()> render;
};

std::vector<Figure> Figures() {
    return {{"shapes-partial-spheres", PartialSpheres},
            {"shapes-disks", Disks},
            {"shapes-quadrics", Quadrics},
            {"shapes-bunny", Bunny},
            {"render-falloff", FalloffComparison},
            {"render-clipping", Clipping},
            {"render-shadow-bias", ShadowBias},
            {"bvh-heat-maps", HeatMaps}};
}

// Figure Comparison
struct ImageDifference {
    int maxDifference = 0;
    double meanDifference = 0, fractionLarge = 0;
    bool Acceptable() const {
        return meanDifference <= 0.5 && fractionLarge <= 0.002;
    }
};

ImageDifference Compare(const Image &a, const Image &b) {
    std::vector<uint8_t> x = a.EncodeSRGB8(), y = b.EncodeSRGB8();
    ImageDifference d;
    double sum = 0;
    size_t large = 0;
    for (size_t i = 0; i < x.size(); i += 3) {
        int pixelMax = 0;
        for (size_t c = i; c < i + 3; ++c) {
            int diff = std::abs(int(x[c]) - int(y[c]));
            sum += diff;
            pixelMax = std::max(pixelMax, diff);
        }
        d.maxDifference = std::max(d.maxDifference, pixelMax);
        if (pixelMax > 16) ++large;
    }
    d.meanDifference = sum / double(x.size());
    d.fractionLarge = double(large) / double(x.size() / 3);
    return d;
}

}  // namespace

// Figure Program Main
int main(int argc, char **argv) {
    std::string outDir, checkDir;
    std::vector<std::string> only;
    try {
        // Parse the figure program's command line
        for (int i = 1; i < argc; ++i) {
            std::string arg = argv[i];
            auto value = [&]() -> std::string {
                if (i + 1 >= argc) throw std::invalid_argument(arg + " needs a value");
                return argv[++i];
            };
            if (arg == "--out") outDir = value();
            else if (arg == "--check") checkDir = value();
            else if (arg == "--data") dataDir = value();
            else if (arg.compare(0, 1, "-") == 0)
                throw std::invalid_argument("unknown option " + arg +
                                            "; see render/figures.cpp");
            else only.push_back(arg);
        }
        if (outDir.empty() == checkDir.empty())
            throw std::invalid_argument("give either --out DIR or --check DIR");
        int failures = 0, done = 0;
        for (const Figure &f : Figures()) {
            if (!only.empty() &&
                std::find(only.begin(), only.end(), f.name) == only.end())
                continue;
            auto start = std::chrono::steady_clock::now();
            Image image = f.render();
            std::chrono::duration<double, std::milli> ms =
                std::chrono::steady_clock::now() - start;
            // Write the image or compare it with the stored one
            if (!outDir.empty()) {
                std::string file = outDir + "/" + f.name + ".png";
                image.WritePNG(file);
                std::printf("%-24s %4dx%-4d %7.0f ms  wrote %s\n", f.name.c_str(),
                            image.Width(), image.Height(), ms.count(), file.c_str());
            } else {
                std::string file = checkDir + "/" + f.name + ".png";
                Image stored = Image::ReadPNG(file);
                if (stored.Width() != image.Width() ||
                    stored.Height() != image.Height()) {
                    std::printf("%-24s DIFFERS: %s is %dx%d, the rendering %dx%d\n",
                                f.name.c_str(), file.c_str(), stored.Width(),
                                stored.Height(), image.Width(), image.Height());
                    ++failures;
                } else {
                    ImageDifference d = Compare(image, stored);
                    std::printf("%-24s %s: max %d, mean %.3f, %.3f%% of pixels > 16 "
                                "(%.0f ms)\n", f.name.c_str(),
                                d.Acceptable() ? "ok" : "DIFFERS", d.maxDifference,
                                d.meanDifference, 100 * d.fractionLarge, ms.count());
                    if (!d.Acceptable()) ++failures;
                }
            }
            ++done;
        }
        if (done != int(only.empty() ? Figures().size() : only.size()))
            throw std::invalid_argument("unknown figure name; the figures are "
                                        "listed in render/figures.cpp");
        if (failures > 0) {
            std::fprintf(stderr, "figures: %d figure(s) differ from the "
                         "images in %s, in size or by more than the "
                         "tolerance\n", failures, checkDir.c_str());
            return 1;
        }
    } catch (const std::exception &e) {
        std::fprintf(stderr, "figures: %s\n", e.what());
        return 1;
    }
    return 0;
}
