// lrt/shapes/cylinder.cpp: tangled from chapters/03-shapes.md. Edit the chapter, not this file.
#include "lrt/shapes/cylinder.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace lrt {

// Cylinder Method Definitions
Cylinder::Cylinder(const Transform *ObjectToWorld,
                   const Transform *WorldToObject, bool reverseOrientation,
                   Float radius, Float zMin, Float zMax, Float phiMax)
    : Quadric("Cylinder", ObjectToWorld, WorldToObject, reverseOrientation,
              {0, 0, 0, EFloat(radius) * EFloat(radius)}, phiMax),
      radius(radius),
      zMin(std::min(zMin, zMax)),
      zMax(std::max(zMin, zMax)) {
    if (!(radius > 0 && radius < Infinity))
        throw std::invalid_argument(
            "Cylinder: radius must be positive and finite");
    if (!(std::isfinite(zMin) && std::isfinite(zMax) && zMin != zMax))
        throw std::invalid_argument(
            "Cylinder: zMin and zMax must be finite and differ");
}
bool Cylinder::LocateHit(const QuadricRay &q, QuadricHit *hit) const {
    Point3f p = q.ray((Float)hit->t);
    Float hitRadius = std::sqrt(p.x * p.x + p.y * p.y);
    if (!(hitRadius > 0)) return false;
    p.x *= radius / hitRadius;
    p.y *= radius / hitRadius;
    hit->p = p;
    hit->pError = gamma(4) * Abs(Vector3f(p.x, p.y, 0));
    hit->phi = Azimuth(p.x, p.y);
    return p.z >= zMin && p.z <= zMax && hit->phi <= phiMax;
}
SurfaceInteraction Cylinder::DescribeHit(const QuadricRay &q,
                                         const QuadricHit &hit) const {
    Point2f uv(hit.phi / phiMax, (hit.p.z - zMin) / (zMax - zMin));
    Vector3f dpdv(0, 0, zMax - zMin), d2Pdvv(0, 0, 0);
    return Interaction(q, hit, hit.p, uv, dpdv, d2Pdvv);
}
Float Cylinder::Area() const {
    // Compute the area of the partial cylinder
    return phiMax * radius * (zMax - zMin);
}

}  // namespace lrt
