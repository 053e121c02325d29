// lrt/shapes/disk.h: tangled from chapters/03-shapes.md. Edit the chapter, not this file.
#pragma once

#include "lrt/core/shape.h"

namespace lrt {

// Disk Declarations
class Disk : public Shape {
  public:
    // Disk Public Methods
    Disk(const Transform *ObjectToWorld, const Transform *WorldToObject,
         bool reverseOrientation, Float height, Float radius, Float innerRadius,
         Float phiMax);
    Bounds3f ObjectBound() const override;
    bool Intersect(const Ray &ray, Float *tHit, SurfaceInteraction *isect,
                   bool testAlphaTexture = true) const override;
    bool IntersectP(const Ray &ray,
                    bool testAlphaTexture = true) const override;
    Float Area() const override;
  private:
    // Disk Private Data
    const Float height, radius, innerRadius, phiMax;
};

}  // namespace lrt
