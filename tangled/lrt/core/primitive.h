// lrt/core/primitive.h: tangled from chapters/06-bvh.md. Edit the chapter, not this file.
#pragma once

#include "lrt/core/geometry.h"
#include "lrt/core/interaction.h"
#include "lrt/core/shape.h"
#include "lrt/core/transform.h"

#include <memory>

namespace lrt {

// Primitive Declarations
class Primitive {
  public:
    virtual ~Primitive();
    virtual Bounds3f WorldBound() const = 0;
    virtual bool Intersect(const Ray &r,
                           SurfaceInteraction *isect) const = 0;
    virtual bool IntersectP(const Ray &r) const = 0;
};
class GeometricPrimitive : public Primitive {
  public:
    // GeometricPrimitive Public Methods
    explicit GeometricPrimitive(const std::shared_ptr<Shape> &shape);
    Bounds3f WorldBound() const override;
    bool Intersect(const Ray &r, SurfaceInteraction *isect) const override;
    bool IntersectP(const Ray &r) const override;
    const Shape *GetShape() const { return shape.get(); }
  private:
    std::shared_ptr<Shape> shape;
};
class TransformedPrimitive : public Primitive {
  public:
    // TransformedPrimitive Public Methods
    TransformedPrimitive(const std::shared_ptr<Primitive> &primitive,
                         const Transform &PrimitiveToWorld);
    Bounds3f WorldBound() const override;
    bool Intersect(const Ray &r, SurfaceInteraction *isect) const override;
    bool IntersectP(const Ray &r) const override;
  private:
    std::shared_ptr<Primitive> primitive;
    const Transform PrimitiveToWorld, WorldToPrimitive;
};
class Aggregate : public Primitive {};

}  // namespace lrt
