// lrt/shapes/cylinder.h: tangled from chapters/03-shapes.md. Edit the chapter, not this file.
#pragma once

#include "lrt/shapes/quadric.h"

namespace lrt {

// Cylinder Declarations
class Cylinder : public Quadric {
  public:
    // Cylinder Public Methods
    Cylinder(const Transform *ObjectToWorld, const Transform *WorldToObject,
             bool reverseOrientation, Float radius, Float zMin, Float zMax,
             Float phiMax);
    Bounds3f ObjectBound() const override {
        return Bounds3f(Point3f(-radius, -radius, zMin),
                        Point3f(radius, radius, zMax));
    }
    Float Area() const override;
  protected:
    bool LocateHit(const QuadricRay &q, QuadricHit *hit) const override;
    SurfaceInteraction DescribeHit(const QuadricRay &q,
                                   const QuadricHit &hit) const override;
  private:
    const Float radius, zMin, zMax;
};

}  // namespace lrt
