// lrt/shapes/cone.cpp: tangled from chapters/03-shapes.md. Edit the chapter, not this file.
#include "lrt/shapes/cone.h"

#include <cmath>
#include <stdexcept>

namespace lrt {

// Cone Method Definitions
Cone::Cone(const Transform *ObjectToWorld, const Transform *WorldToObject,
           bool reverseOrientation, Float height, Float radius, Float phiMax)
    : Quadric("Cone", ObjectToWorld, WorldToObject, reverseOrientation,
              {EFloat(height),
               (EFloat(radius) / EFloat(height)) *
                   (EFloat(radius) / EFloat(height)),
               0, 0},
              phiMax),
      height(height),
      radius(radius) {
    if (!(radius > 0 && radius < Infinity))
        throw std::invalid_argument("Cone: radius must be positive and finite");
    if (!(height > 0 && height < Infinity))
        throw std::invalid_argument("Cone: height must be positive and finite");
}

bool Cone::LocateHit(const QuadricRay &q, QuadricHit *hit) const {
    q.PointAt(hit->t, &hit->p, &hit->pError);
    hit->phi = Azimuth(hit->p.x, hit->p.y);
    return hit->p.z >= 0 && hit->p.z <= height && hit->phi <= phiMax;
}
SurfaceInteraction Cone::DescribeHit(const QuadricRay &q,
                                     const QuadricHit &hit) const {
    Point2f uv(hit.phi / phiMax, hit.p.z / height);
    Float cosPhi = std::cos(hit.phi), sinPhi = std::sin(hit.phi);
    Vector3f dpdv(-radius * cosPhi, -radius * sinPhi, height);
    Vector3f d2Pdvv(0, 0, 0);
    return Interaction(q, hit, OffAxis(hit.p, radius), uv, dpdv, d2Pdvv);
}
Float Cone::Area() const {
    // Compute the area of the partial cone
    return Float(0.5) * phiMax * radius * std::hypot(height, radius);
}

}  // namespace lrt
