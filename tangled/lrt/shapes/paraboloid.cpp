// lrt/shapes/paraboloid.cpp: tangled from chapters/03-shapes.md. Edit the chapter, not this file.
#include "lrt/shapes/paraboloid.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace lrt {

// Paraboloid Method Definitions
Paraboloid::Paraboloid(const Transform *ObjectToWorld,
                       const Transform *WorldToObject,
                       bool reverseOrientation, Float radius, Float z0,
                       Float z1, Float phiMax)
    : Quadric("Paraboloid", ObjectToWorld, WorldToObject, reverseOrientation,
              {0, 0,
               EFloat(radius) * EFloat(radius) / EFloat(std::max(z0, z1)),
               0},
              phiMax),
      radius(radius),
      zMin(std::max(std::min(z0, z1), Float(0))),
      zMax(std::max(z0, z1)) {
    if (!(radius > 0 && radius < Infinity))
        throw std::invalid_argument(
            "Paraboloid: radius must be positive and finite");
    if (!(std::isfinite(z0) && std::isfinite(z1) && zMax > zMin))
        throw std::invalid_argument(
            "Paraboloid: z0 and z1 must be finite and leave a surface above "
            "z = 0");
}
bool Paraboloid::LocateHit(const QuadricRay &q, QuadricHit *hit) const {
    q.PointAt(hit->t, &hit->p, &hit->pError);
    hit->phi = Azimuth(hit->p.x, hit->p.y);
    return (zMin == 0 || hit->p.z >= zMin) && hit->p.z <= zMax &&
           hit->phi <= phiMax;
}
SurfaceInteraction Paraboloid::DescribeHit(const QuadricRay &q,
                                           const QuadricHit &hit) const {
    Point2f uv(hit.phi / phiMax, (hit.p.z - zMin) / (zMax - zMin));
    Point3f p = OffAxis(hit.p, radius);
    Float s = radius * radius / (2 * zMax * (p.x * p.x + p.y * p.y));
    Float height = zMax - zMin;
    Vector3f dpdv = height * Vector3f(s * p.x, s * p.y, 1);
    Vector3f d2Pdvv = -height * height * s * s * Vector3f(p.x, p.y, 0);
    return Interaction(q, hit, p, uv, dpdv, d2Pdvv);
}
Float Paraboloid::Area() const {
    // Compute the area of the partial paraboloid
    Float aHat = std::hypot(radius, 2 * zMax);
    Float bHat = std::hypot(radius, 2 * std::sqrt(zMax) * std::sqrt(zMin));
    return phiMax * radius * ((zMax - zMin) / (3 * zMax)) *
           (aHat + bHat * (bHat / (aHat + bHat)));
}

}  // namespace lrt
