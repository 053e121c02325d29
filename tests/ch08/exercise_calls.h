// Chapter 8's exercise calls (tests/calls/calls.h): the tests of ex-8.9
// (the sRGB encoding), ex-8.10 (PinholeCamera::GenerateRay) and ex-8.11 (the
// shadow ray of Shade()) reach that code only through these.
//
// A test describes its scene, camera and options as values, from which the
// worker makes the library's objects of its own: RenderImage renders them
// with Render(), RenderHeatMap with RenderNodeVisits(), ShadeRays intersects
// and shades rays that the test chose (no camera ray involved), and
// SpawnShadowRays hands Shade() single hit points and reports the shadow rays it
// asks the scene about.

#ifndef LRT_TESTS_CH08_EXERCISE_CALLS_H
#define LRT_TESTS_CH08_EXERCISE_CALLS_H

#include "lrt/render/renderer.h"
#include "lrt/render/bvhvisits.h"
#include "lrt/accelerators/bvh.h"
#include "lrt/shapes/sphere.h"
#include "lrt/shapes/disk.h"
#include "calls/calls.h"

#include <array>
#include <cstdint>
#include <memory>
#include <stdexcept>
#include <vector>

namespace lrt {

// ---------------------------------------------------------------------------
// Values

// The kinds of shapes of a scene.
enum RenderShape : uint8_t { kSphereShape, kDiskShape };

// A full sphere or disk with its color. args: a sphere's radius, zMin, zMax
// and phiMax, or a disk's height, radius, innerRadius and phiMax.
struct ShapeValue {
    uint8_t kind;
    Transform objectToWorld;
    std::array<Float, 4> args;
    RGB albedo;
    LRT_FIELDS(kind, objectToWorld, args, albedo)
};

// PinholeCamera's constructor arguments.
struct CameraValue {
    Transform cameraToWorld;
    Float fov;
    int width, height;
    Float zNear, zFar;
    LRT_FIELDS(cameraToWorld, fov, width, height, zNear, zFar)
};

// RenderOptions, member by member.
struct OptionsValue {
    Float headlight = 1;
    Falloff falloff = Falloff::InverseDistance;
    RGB background;
    std::vector<PointLight> lights;
    ShadowRays shadowRays = ShadowRays::ErrorBounds;
    Float shadowEpsilon = Float(1e-4);
    LRT_FIELDS(headlight, falloff, background, lights, shadowRays,
               shadowEpsilon)
};

// An image and, for RenderImage, its depth buffer; for RenderHeatMap, the
// counts of node visits.
struct RenderedImage {
    int width, height;
    std::vector<RGB> pixels;
    std::vector<Float> depth;
    std::vector<int> visits;
    LRT_FIELDS(width, height, pixels, depth, visits)
    const RGB &operator()(int x, int y) const {
        return pixels.at(size_t(y) * size_t(width) + size_t(x));
    }
};

// What ShadeRays answers for one ray: whether it hit and the color Shade()
// gave the hit (the options' background if none).
struct ShadedRay {
    bool hit;
    RGB color;
    LRT_FIELDS(hit, color)
};

// One hit point for SpawnShadowRays: the camera ray with its tMax at the hit, the
// interaction's point, error bounds and normal, the eye and the light.
struct ShadowCase {
    Ray ray;
    Point3f p;
    Vector3f pError;
    Normal3f n;
    Point3f eye, pLight;
    ShadowRays method;
    Float epsilon;
    LRT_FIELDS(ray, p, pError, n, eye, pLight, method, epsilon)
};

// What Shade() did at a ShadowCase: the shadow rays it asked the scene about
// (none if the light is behind the surface, one otherwise) and the color it
// returned, with the light unobstructed.
struct ShadowAnswer {
    std::vector<Ray> rays;
    RGB color;
    LRT_FIELDS(rays, color)
};

namespace calls {

inline void Put(Writer &w, const RGB &c) { Put(w, c.r), Put(w, c.g), Put(w, c.b); }
inline void Get(Reader &r, RGB &c) { Get(r, c.r), Get(r, c.g), Get(r, c.b); }
inline void Put(Writer &w, const PointLight &l) { Put(w, l.pLight), Put(w, l.I); }
inline void Get(Reader &r, PointLight &l) { Get(r, l.pLight), Get(r, l.I); }

}  // namespace calls

// ---------------------------------------------------------------------------
// The worker's side: the library's objects made of the values

namespace ex {

// A primitive that no ray hits and that notes every ray IntersectP() is
// asked about: Shade()'s shadow rays.
class ShadowRayLog : public Primitive {
  public:
    explicit ShadowRayLog(std::vector<Ray> *log) : log(log) {}
    Bounds3f WorldBound() const override { return Bounds3f(); }
    bool Intersect(const Ray &, SurfaceInteraction *) const override {
        return false;
    }
    bool IntersectP(const Ray &r) const override {
        log->push_back(r);
        return false;
    }

  private:
    std::vector<Ray> *log;
};

inline void AddShapes(RenderScene *scene,
                      const std::vector<ShapeValue> &shapes) {
    for (const ShapeValue &s : shapes) {
        const Transform *o2w = scene->AddTransform(s.objectToWorld);
        const Transform *w2o = scene->AddTransform(Inverse(s.objectToWorld));
        const std::array<Float, 4> &a = s.args;
        if (s.kind == kSphereShape)
            scene->AddShape(std::make_shared<Sphere>(o2w, w2o, false, a[0],
                                                     a[1], a[2], a[3]),
                            s.albedo);
        else if (s.kind == kDiskShape)
            scene->AddShape(std::make_shared<Disk>(o2w, w2o, false, a[0],
                                                   a[1], a[2], a[3]),
                            s.albedo);
        else
            throw std::invalid_argument("unknown shape kind");
    }
}

inline PinholeCamera MakeCamera(const CameraValue &c) {
    return PinholeCamera(c.cameraToWorld, c.fov, c.width, c.height, c.zNear,
                         c.zFar);
}

inline RenderOptions MakeOptions(const OptionsValue &o) {
    RenderOptions r;
    r.headlight = o.headlight;
    r.falloff = o.falloff;
    r.background = o.background;
    r.lights = o.lights;
    r.shadowRays = o.shadowRays;
    r.shadowEpsilon = o.shadowEpsilon;
    return r;
}

}  // namespace ex

namespace direct {

// GammaCorrect(v) and EncodeSRGB8(v) of each value, in order.
struct SRGBAnswer {
    std::vector<Float> encoded;
    std::vector<uint8_t> bytes;
    LRT_FIELDS(encoded, bytes)
};
inline SRGBAnswer EncodeSRGB(std::vector<Float> values) {
    SRGBAnswer a;
    for (Float v : values) {
        a.encoded.push_back(GammaCorrect(v));
        a.bytes.push_back(EncodeSRGB8(v));
    }
    return a;
}

// The camera's rays through the raster positions, in order.
inline std::vector<Ray> GenerateRays(CameraValue camera,
                                     std::vector<Point2f> pRaster) {
    PinholeCamera c = ex::MakeCamera(camera);
    std::vector<Ray> rays;
    for (const Point2f &p : pRaster) rays.push_back(c.GenerateRay(p));
    return rays;
}

// Render() of the scene, with its depth buffer.
inline RenderedImage RenderImage(std::vector<ShapeValue> shapes,
                                 CameraValue camera, OptionsValue options) {
    RenderScene scene;
    ex::AddShapes(&scene, shapes);
    PinholeCamera c = ex::MakeCamera(camera);
    RenderedImage r{c.width, c.height, {}, {}, {}};
    Image image = Render(scene, c, ex::MakeOptions(options), &r.depth);
    for (int y = 0; y < image.Height(); ++y)
        for (int x = 0; x < image.Width(); ++x) r.pixels.push_back(image(x, y));
    return r;
}

// RenderNodeVisits() over a BVHAccel (split by the middle, at most
// maxPrimsInNode primitives in a leaf) of the scene's shapes.
inline RenderedImage RenderHeatMap(std::vector<ShapeValue> shapes,
                                   int maxPrimsInNode, CameraValue camera,
                                   int maxVisits) {
    RenderScene scene;
    ex::AddShapes(&scene, shapes);
    std::vector<std::shared_ptr<Primitive>> prims;
    for (const SceneObject &o : scene.Objects()) prims.push_back(o.primitive);
    BVHAccel bvh(prims, maxPrimsInNode, BVHAccel::SplitMethod::Middle);
    PinholeCamera c = ex::MakeCamera(camera);
    RenderedImage r{c.width, c.height, {}, {}, {}};
    Image image = RenderNodeVisits(bvh, c, maxVisits, &r.visits);
    for (int y = 0; y < image.Height(); ++y)
        for (int x = 0; x < image.Width(); ++x) r.pixels.push_back(image(x, y));
    return r;
}

// Each ray intersected with the scene and, where it hits, shaded by Shade()
// as Render() shades a camera ray, with the headlight at `eye`.
inline std::vector<ShadedRay> ShadeRays(std::vector<ShapeValue> shapes,
                                        Point3f eye, OptionsValue options,
                                        std::vector<Ray> rays) {
    RenderScene scene;
    ex::AddShapes(&scene, shapes);
    PinholeCamera camera(Translate(Vector3f(eye)), 60, 1, 1);
    RenderOptions o = ex::MakeOptions(options);
    std::vector<ShadedRay> shaded;
    for (Ray ray : rays) {
        SurfaceInteraction isect;
        const SceneObject *object = nullptr;
        if (!scene.Intersect(ray, &isect, &object))
            shaded.push_back({false, o.background});
        else
            shaded.push_back(
                {true, Shade(ray, isect, *object, scene, camera, o)});
    }
    return shaded;
}

// Shade() at each hit point, in a scene with nothing in it but a primitive
// that notes the shadow rays; an albedo of 1, a light of intensity 1, no
// headlight and no falloff.
inline std::vector<ShadowAnswer> SpawnShadowRays(std::vector<ShadowCase> cases) {
    std::vector<ShadowAnswer> answers;
    for (const ShadowCase &c : cases) {
        ShadowAnswer a;
        RenderScene scene;
        scene.Add(std::make_shared<ex::ShadowRayLog>(&a.rays), RGB(1, 1, 1));
        PinholeCamera camera(Translate(Vector3f(c.eye)), 60, 1, 1);
        RenderOptions o;
        o.headlight = 0;
        o.falloff = Falloff::None;
        o.lights.push_back({c.pLight, RGB(1, 1, 1)});
        o.shadowRays = c.method;
        o.shadowEpsilon = c.epsilon;
        SurfaceInteraction isect;
        isect.p = c.p;
        isect.pError = c.pError;
        isect.n = c.n;
        SceneObject object{nullptr, RGB(1, 1, 1)};
        a.color = Shade(c.ray, isect, object, scene, camera, o);
        answers.push_back(a);
    }
    return answers;
}

}  // namespace direct
}  // namespace lrt

LRT_EXERCISE_CALL(EncodeSRGB)
LRT_EXERCISE_CALL(GenerateRays)
LRT_EXERCISE_CALL(RenderImage)
LRT_EXERCISE_CALL(RenderHeatMap)
LRT_EXERCISE_CALL(ShadeRays)
LRT_EXERCISE_CALL(SpawnShadowRays)

#endif  // LRT_TESTS_CH08_EXERCISE_CALLS_H
