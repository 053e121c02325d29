// lrt/render/renderer.h: tangled from chapters/08-rendering.md. Edit the chapter, not this file.
#pragma once

#include "lrt/core/geometry.h"
#include "lrt/core/interaction.h"
#include "lrt/core/primitive.h"
#include "lrt/core/shape.h"
#include "lrt/core/transform.h"
#include "lrt/render/camera.h"
#include "lrt/render/image.h"

#include <deque>
#include <memory>
#include <vector>

namespace lrt {

// Renderer Declarations
struct SceneObject {
    std::shared_ptr<Primitive> primitive;
    RGB albedo;
};

class RenderScene {
  public:
    RenderScene() {}
    RenderScene(const RenderScene &) = delete;
    RenderScene &operator=(const RenderScene &) = delete;
    // RenderScene Public Methods
    const Transform *AddTransform(const Transform &t) {
        transforms.push_back(t);
        return &transforms.back();
    }
    void Add(const std::shared_ptr<Primitive> &primitive, const RGB &albedo);
    void AddShape(const std::shared_ptr<Shape> &shape, const RGB &albedo) {
        Add(std::make_shared<GeometricPrimitive>(shape), albedo);
    }
    const std::vector<SceneObject> &Objects() const { return objects; }
    bool Intersect(const Ray &ray, SurfaceInteraction *isect,
                   const SceneObject **object) const;
    bool IntersectP(const Ray &ray) const;

  private:
    std::vector<SceneObject> objects;
    std::deque<Transform> transforms;
};
enum class Falloff { None, InverseDistance, InverseSquare };

inline Float FalloffFactor(Falloff falloff, Float t) {
    switch (falloff) {
    case Falloff::InverseDistance: return 1 / t;
    case Falloff::InverseSquare: return 1 / (t * t);
    default: return 1;
    }
}
struct PointLight {
    Point3f pLight;
    RGB I;
};

enum class ShadowRays { FixedEpsilon, ErrorBounds };

struct RenderOptions {
    Float headlight = 1;
    Falloff falloff = Falloff::InverseDistance;
    RGB background;
    std::vector<PointLight> lights;
    ShadowRays shadowRays = ShadowRays::ErrorBounds;
    Float shadowEpsilon = Float(1e-4);
};

Image Render(const RenderScene &scene, const PinholeCamera &camera,
             const RenderOptions &options,
             std::vector<Float> *depth = nullptr);
RGB Shade(const Ray &ray, const SurfaceInteraction &isect,
          const SceneObject &object, const RenderScene &scene,
          const PinholeCamera &camera, const RenderOptions &options);

}  // namespace lrt
