// lrt/core/primitive.cpp: tangled from chapters/06-bvh.md. Edit the chapter, not this file.
#include "lrt/core/primitive.h"

#include <stdexcept>

namespace lrt {

// Primitive Method Definitions
Primitive::~Primitive() {}
GeometricPrimitive::GeometricPrimitive(const std::shared_ptr<Shape> &shape)
    : shape(shape) {
    if (!shape)
        throw std::invalid_argument("GeometricPrimitive: null shape");
}

Bounds3f GeometricPrimitive::WorldBound() const {
    return shape->WorldBound();
}
bool GeometricPrimitive::Intersect(const Ray &r,
                                   SurfaceInteraction *isect) const {
    Float tHit;
    if (!shape->Intersect(r, &tHit, isect)) return false;
    r.tMax = tHit;
    isect->primitive = this;
    return true;
}

bool GeometricPrimitive::IntersectP(const Ray &r) const {
    return shape->IntersectP(r);
}
TransformedPrimitive::TransformedPrimitive(
    const std::shared_ptr<Primitive> &primitive,
    const Transform &PrimitiveToWorld)
    : primitive(primitive),
      PrimitiveToWorld(PrimitiveToWorld),
      WorldToPrimitive(Inverse(PrimitiveToWorld)) {
    if (!primitive)
        throw std::invalid_argument("TransformedPrimitive: null primitive");
}

Bounds3f TransformedPrimitive::WorldBound() const {
    return PrimitiveToWorld(primitive->WorldBound());
}
bool TransformedPrimitive::Intersect(const Ray &r,
                                     SurfaceInteraction *isect) const {
    Ray ray(WorldToPrimitive(r.o), WorldToPrimitive(r.d), r.tMax, r.time);
    if (!primitive->Intersect(ray, isect)) return false;
    r.tMax = ray.tMax;
    if (!PrimitiveToWorld.IsIdentity()) *isect = PrimitiveToWorld(*isect);
    return true;
}

bool TransformedPrimitive::IntersectP(const Ray &r) const {
    Ray ray(WorldToPrimitive(r.o), WorldToPrimitive(r.d), r.tMax, r.time);
    return primitive->IntersectP(ray);
}

}  // namespace lrt
