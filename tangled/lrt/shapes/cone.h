// lrt/shapes/cone.h: tangled from chapters/03-shapes.md. Edit the chapter, not this file.
#pragma once

#include "lrt/shapes/quadric.h"

namespace lrt {

// Cone Declarations
class Cone : public Quadric {
  public:
    // Cone Public Methods
    Cone(const Transform *ObjectToWorld, const Transform *WorldToObject,
         bool reverseOrientation, Float height, Float radius, Float phiMax);
    Bounds3f ObjectBound() const override {
        return Bounds3f(Point3f(-radius, -radius, 0),
                        Point3f(radius, radius, height));
    }
    Float Area() const override;
  protected:
    bool LocateHit(const QuadricRay &q, QuadricHit *hit) const override;
    SurfaceInteraction DescribeHit(const QuadricRay &q,
                                   const QuadricHit &hit) const override;
  private:
    const Float height, radius;
};

}  // namespace lrt
