// lrt/shapes/disk.cpp: tangled from chapters/03-shapes.md. Edit the chapter, not this file.
#include "lrt/shapes/disk.h"

#include "lrt/core/efloat.h"

#include <cmath>
#include <stdexcept>

namespace lrt {

// Disk Method Definitions
// Convert phiMax from degrees to radians
static Float PhiMaxRadians(Float phiMaxDegrees) {
    Float deg = Clamp(phiMaxDegrees, 0, 360);
    return (deg >= 360) ? 2 * Pi : Radians(deg);
}

Disk::Disk(const Transform *ObjectToWorld, const Transform *WorldToObject,
           bool reverseOrientation, Float height, Float radius,
           Float innerRadius, Float phiMax)
    : Shape(ObjectToWorld, WorldToObject, reverseOrientation),
      height(height),
      radius(radius),
      innerRadius(innerRadius),
      phiMax(PhiMaxRadians(phiMax)) {
    // Reject disk parameters that describe no surface
    if (!(radius > 0 && radius < Infinity))
        throw std::invalid_argument("Disk: radius must be positive and finite");
    if (!(innerRadius >= 0 && innerRadius < radius))
        throw std::invalid_argument(
            "Disk: innerRadius must be at least 0 and less than radius");
    if (!std::isfinite(height))
        throw std::invalid_argument("Disk: height must be finite");
    if (!(this->phiMax > 0))
        throw std::invalid_argument("Disk: phiMax must be positive");
}
Bounds3f Disk::ObjectBound() const {
    return Bounds3f(Point3f(-radius, -radius, height),
                    Point3f(radius, radius, height));
}
bool Disk::Intersect(const Ray &r, Float *tHit, SurfaceInteraction *isect,
                     bool /*testAlphaTexture*/) const {
    // Transform Ray to object space
    Vector3f oErr, dErr;
    Ray ray((*WorldToObject)(r.o, &oErr), (*WorldToObject)(r.d, &dErr), r.tMax,
            r.time);
    // Compute plane intersection for disk
    if (ray.d.z == 0) return false;
    EFloat tShapeHit = (EFloat(height) - EFloat(ray.o.z, oErr.z)) /
                       EFloat(ray.d.z, dErr.z);
    if (!(tShapeHit.LowerBound() > 0 && (Float)tShapeHit <= ray.tMax))
        return false;
    // See if hit point is inside disk radii and phiMax
    Point3f pHit = ray((Float)tShapeHit);
    Float dist2 = pHit.x * pHit.x + pHit.y * pHit.y;
    if (!(dist2 <= radius * radius && dist2 >= innerRadius * innerRadius))
        return false;
    Float phi = std::atan2(pHit.y, pHit.x);
    if (phi < 0) phi += 2 * Pi;
    if (phi > phiMax) return false;
    // Refine disk intersection point
    pHit.z = height;
    if (pHit.x == 0 && pHit.y == 0) pHit.x = Float(1e-5) * radius;
    // Find parametric representation of disk hit
    Float u = phi / phiMax;
    Float rHit = std::sqrt(pHit.x * pHit.x + pHit.y * pHit.y);
    Float v = (radius - rHit) / (radius - innerRadius);
    Vector3f dpdu(-phiMax * pHit.y, phiMax * pHit.x, 0);
    Vector3f dpdv = Vector3f(pHit.x, pHit.y, 0) * (innerRadius - radius) / rHit;
    Normal3f dndu(0, 0, 0), dndv(0, 0, 0);
    // Compute error bounds for disk intersection
    Vector3f pError(0, 0, 0);
    // Initialize SurfaceInteraction from parametric information
    if (reverseOrientation) {
        dndu = -dndu;
        dndv = -dndv;
    }
    *isect = (*ObjectToWorld)(SurfaceInteraction(pHit, pError, Point2f(u, v),
                                                 -ray.d, dpdu, dpdv, dndu, dndv,
                                                 ray.time, reverseOrientation));
    isect->shape = this;
    // Update tHit for quadric intersection
    *tHit = (Float)tShapeHit;
    return true;
}
bool Disk::IntersectP(const Ray &r, bool /*testAlphaTexture*/) const {
    // Transform Ray to object space
    Vector3f oErr, dErr;
    Ray ray((*WorldToObject)(r.o, &oErr), (*WorldToObject)(r.d, &dErr), r.tMax,
            r.time);
    // Compute plane intersection for disk
    if (ray.d.z == 0) return false;
    EFloat tShapeHit = (EFloat(height) - EFloat(ray.o.z, oErr.z)) /
                       EFloat(ray.d.z, dErr.z);
    if (!(tShapeHit.LowerBound() > 0 && (Float)tShapeHit <= ray.tMax))
        return false;
    // See if hit point is inside disk radii and phiMax
    Point3f pHit = ray((Float)tShapeHit);
    Float dist2 = pHit.x * pHit.x + pHit.y * pHit.y;
    if (!(dist2 <= radius * radius && dist2 >= innerRadius * innerRadius))
        return false;
    Float phi = std::atan2(pHit.y, pHit.x);
    if (phi < 0) phi += 2 * Pi;
    if (phi > phiMax) return false;
    return true;
}
Float Disk::Area() const {
    // Compute the area of the partial ring
    return Float(0.5) * phiMax * (radius - innerRadius) *
           (radius + innerRadius);
}

}  // namespace lrt
