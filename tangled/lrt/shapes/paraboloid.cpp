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
    return hit->p.z >= zMin && hit->p.z <= zMax && hit->phi <= phiMax;
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
    double r2 = double(radius) * radius, k = 4 * double(zMax) / r2;
    return Float(phiMax * r2 * r2 / (12 * double(zMax) * zMax) *
                 (std::pow(k * zMax + 1, 1.5) - std::pow(k * zMin + 1, 1.5)));
}

}  // namespace lrt
