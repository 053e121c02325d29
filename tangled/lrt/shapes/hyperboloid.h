// lrt/shapes/hyperboloid.h: tangled from chapters/03-shapes.md. Edit the chapter, not this file.
#pragma once

#include "lrt/shapes/quadric.h"

namespace lrt {

// Hyperboloid Declarations
class Hyperboloid : public Quadric {
  public:
    // Hyperboloid Public Methods
    Hyperboloid(const Transform *ObjectToWorld, const Transform *WorldToObject,
                bool reverseOrientation, const Point3f &point1,
                const Point3f &point2, Float phiMax);
    Bounds3f ObjectBound() const override {
        return Bounds3f(Point3f(-rMax, -rMax, zMin), Point3f(rMax, rMax, zMax));
    }
    Float Area() const override;
  protected:
    bool LocateHit(const QuadricRay &q, QuadricHit *hit) const override;
    SurfaceInteraction DescribeHit(const QuadricRay &q,
                                   const QuadricHit &hit) const override;
  private:
    static QuadricOfRevolution ImplicitForm(const Point3f &p1,
                                            const Point3f &p2);
    const Point3f p1, p2;
    const Float zMin, zMax, rMax;
};

}  // namespace lrt
