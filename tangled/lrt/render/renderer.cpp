// lrt/render/renderer.cpp: tangled from chapters/08-rendering.md. Edit the chapter, not this file.
#include "lrt/render/renderer.h"

#include <cmath>
#include <stdexcept>

namespace lrt {

// Renderer Method Definitions
void RenderScene::Add(const std::shared_ptr<Primitive> &primitive,
                      const RGB &albedo) {
    if (!primitive)
        throw std::invalid_argument("RenderScene::Add: null primitive");
    objects.push_back({primitive, albedo});
}
bool RenderScene::Intersect(const Ray &ray, SurfaceInteraction *isect,
                            const SceneObject **object) const {
    bool hit = false;
    for (const SceneObject &o : objects)
        if (o.primitive->Intersect(ray, isect)) {
            hit = true;
            *object = &o;
        }
    return hit;
}

bool RenderScene::IntersectP(const Ray &ray) const {
    for (const SceneObject &o : objects)
        if (o.primitive->IntersectP(ray)) return true;
    return false;
}
Image Render(const RenderScene &scene, const PinholeCamera &camera,
             const RenderOptions &options, std::vector<Float> *depth) {
    Image image(camera.width, camera.height, options.background);
    if (depth) depth->assign(size_t(camera.width) * camera.height, Infinity);
    for (int y = 0; y < camera.height; ++y)
        for (int x = 0; x < camera.width; ++x) {
            Point2f pRaster(x + Float(0.5), y + Float(0.5));
            Ray ray = camera.GenerateRay(pRaster);
            SurfaceInteraction isect;
            const SceneObject *object = nullptr;
            if (!scene.Intersect(ray, &isect, &object)) continue;
            if (depth)
                (*depth)[size_t(y) * camera.width + x] = camera.Depth(isect.p);
            image(x, y) = Shade(ray, isect, *object, scene, camera, options);
        }
    return image;
}
RGB Shade(const Ray &ray, const SurfaceInteraction &isect,
          const SceneObject &object, const RenderScene &scene,
          const PinholeCamera &camera, const RenderOptions &options) {
    RGB L;
    // Turn the normal toward the eye and add the headlight's light
    Vector3f toEye = camera.Position() - isect.p;
    Float tEye = toEye.Length();
    Vector3f n(isect.n);
    if (Dot(n, toEye) < 0) n = -n;
    if (tEye > 0)
        L = object.albedo * (options.headlight *
                             FalloffFactor(options.falloff, tEye) *
                             (Dot(n, toEye) / tEye));
    for (const PointLight &light : options.lights) {
        // Add the light of light if it reaches the hit point
        Vector3f toLight = light.pLight - isect.p;
        Float tLight = toLight.Length();
        Float cosLight = tLight > 0 ? Dot(n, toLight) / tLight : 0;
        if (cosLight > 0) {
            Ray shadowRay;
            // Make the shadow ray from the hit point toward the light
            if (options.shadowRays == ShadowRays::FixedEpsilon) {
                Point3f p = ray(ray.tMax);
                Point3f o = p + options.shadowEpsilon * n;
                shadowRay = Ray(o, light.pLight - o, 1 - ShadowEpsilon);
            } else {
                shadowRay = isect.SpawnRayTo(light.pLight);
            }
            if (!scene.IntersectP(shadowRay))
                L = L + object.albedo * light.I *
                            (FalloffFactor(options.falloff, tLight) * cosLight);
        }
    }
    return L;
}

}  // namespace lrt
