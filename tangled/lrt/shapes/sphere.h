// lrt/shapes/sphere.h: tangled from chapters/03-shapes.md. Edit the chapter, not this file.
#pragma once

#include "lrt/core/shape.h"

namespace lrt {

// Sphere Declarations
class Sphere : public Shape {
  public:
    // Sphere Public Methods
    Sphere(const Transform *ObjectToWorld, const Transform *WorldToObject,
           bool reverseOrientation, Float radius, Float zMin, Float zMax,
           Float phiMax);
    Bounds3f ObjectBound() const override;
    bool Intersect(const Ray &ray, Float *tHit, SurfaceInteraction *isect,
                   bool testAlphaTexture = true) const override;
    bool IntersectP(const Ray &ray,
                    bool testAlphaTexture = true) const override;
    Float Area() const override;
  private:
    // Sphere Private Methods
    bool IsClipped(const Point3f &pHit, Float phi) const {
        return (zMin > -radius && pHit.z < zMin) ||
               (zMax < radius && pHit.z > zMax) || phi > phiMax;
    }
    // Sphere Private Data
    const Float radius;
    const Float zMin, zMax;
    const Float thetaMin, thetaMax, phiMax;
};

}  // namespace lrt
