// lrt/shapes/sphere.cpp: tangled from chapters/03-shapes.md. Edit the chapter, not this file.
#include "lrt/shapes/sphere.h"

#include "lrt/core/efloat.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace lrt {

// Sphere Method Definitions
// Convert phiMax from degrees to radians
static Float PhiMaxRadians(Float phiMaxDegrees) {
    Float deg = Clamp(phiMaxDegrees, 0, 360);
    return (deg >= 360) ? 2 * Pi : Radians(deg);
}

Sphere::Sphere(const Transform *ObjectToWorld, const Transform *WorldToObject,
               bool reverseOrientation, Float radius, Float zMin, Float zMax,
               Float phiMax)
    : Shape(ObjectToWorld, WorldToObject, reverseOrientation),
      radius(radius),
      zMin(Clamp(std::min(zMin, zMax), -radius, radius)),
      zMax(Clamp(std::max(zMin, zMax), -radius, radius)),
      thetaMin(std::acos(Clamp(std::min(zMin, zMax) / radius, -1, 1))),
      thetaMax(std::acos(Clamp(std::max(zMin, zMax) / radius, -1, 1))),
      phiMax(PhiMaxRadians(phiMax)) {
    // Reject sphere parameters that describe no surface
    if (!(radius > 0 && radius < Infinity))
        throw std::invalid_argument("Sphere: radius must be positive and finite");
    if (!(this->zMin < this->zMax))
        throw std::invalid_argument("Sphere: zMin and zMax leave no surface");
    if (!(this->phiMax > 0))
        throw std::invalid_argument("Sphere: phiMax must be positive");
}
Bounds3f Sphere::ObjectBound() const {
    return Bounds3f(Point3f(-radius, -radius, zMin),
                    Point3f(radius, radius, zMax));
}
bool Sphere::Intersect(const Ray &r, Float *tHit, SurfaceInteraction *isect,
                       bool /*testAlphaTexture*/) const {
    Float phi;
    Point3f pHit;
    // Transform Ray to object space
    Vector3f oErr, dErr;
    Ray ray((*WorldToObject)(r.o, &oErr), (*WorldToObject)(r.d, &dErr), r.tMax,
            r.time);
    // Compute quadratic sphere coefficients
    EFloat ox(ray.o.x, oErr.x), oy(ray.o.y, oErr.y), oz(ray.o.z, oErr.z);
    EFloat dx(ray.d.x, dErr.x), dy(ray.d.y, dErr.y), dz(ray.d.z, dErr.z);
    EFloat a = dx * dx + dy * dy + dz * dz;
    EFloat b = 2 * (dx * ox + dy * oy + dz * oz);
    EFloat c = ox * ox + oy * oy + oz * oz - EFloat(radius) * EFloat(radius);
    // Compute the sphere's discriminant from the closest point
    EFloat s = b / (2 * a);
    EFloat fx = ox - s * dx, fy = oy - s * dy, fz = oz - s * dz;
    EFloat fLength = sqrt(fx * fx + fy * fy + fz * fz);
    EFloat discrim =
        4 * a * (EFloat(radius) - fLength) * (EFloat(radius) + fLength);
    // Solve quadratic equation for t values
    EFloat t0, t1;
    if (!QuadraticRoots(a, b, c, discrim, &t0, &t1)) return false;
    // Check quadric shape t0 and t1 for nearest intersection
    if (!((Float)t0 <= ray.tMax) || !(t1.LowerBound() > 0)) return false;
    EFloat tShapeHit = t0;
    bool usingFarRoot = false;
    if (!(tShapeHit.LowerBound() > 0)) {
        tShapeHit = t1;
        usingFarRoot = true;
        if (!((Float)tShapeHit <= ray.tMax)) return false;
    }
    // Compute sphere hit position and phi
    pHit = ray((Float)tShapeHit);
    // Refine sphere intersection point
    if (pHit.x == 0 && pHit.y == 0) pHit.x = Float(1e-5) * radius;
    pHit *= radius / Distance(pHit, Point3f(0, 0, 0));
    phi = std::atan2(pHit.y, pHit.x);
    if (phi < 0) phi += 2 * Pi;
    // Test sphere intersection against clipping parameters
    if (IsClipped(pHit, phi)) {
        if (usingFarRoot) return false;
        if (!((Float)t1 <= ray.tMax)) return false;
        tShapeHit = t1;
        // Compute sphere hit position and phi
        pHit = ray((Float)tShapeHit);
        // Refine sphere intersection point
        if (pHit.x == 0 && pHit.y == 0) pHit.x = Float(1e-5) * radius;
        pHit *= radius / Distance(pHit, Point3f(0, 0, 0));
        phi = std::atan2(pHit.y, pHit.x);
        if (phi < 0) phi += 2 * Pi;
        if (IsClipped(pHit, phi)) return false;
    }
    // Find parametric representation of sphere hit
    Float u = phi / phiMax;
    Float cosTheta = pHit.z / radius;
    Float theta = std::acos(Clamp(cosTheta, -1, 1));
    Float v = (theta - thetaMin) / (thetaMax - thetaMin);
    // Compute sphere dpdu and dpdv
    Float zRadius = std::sqrt(pHit.x * pHit.x + pHit.y * pHit.y);
    Float cosPhi = pHit.x / zRadius, sinPhi = pHit.y / zRadius;
    Float sinTheta = zRadius / radius;
    Vector3f dpdu(-phiMax * pHit.y, phiMax * pHit.x, 0);
    Vector3f dpdv = (thetaMax - thetaMin) *
                    Vector3f(pHit.z * cosPhi, pHit.z * sinPhi, -radius * sinTheta);
    // Compute sphere dndu and dndv
    Vector3f d2Pduu = -phiMax * phiMax * Vector3f(pHit.x, pHit.y, 0);
    Vector3f d2Pduv = (thetaMax - thetaMin) * pHit.z * phiMax *
                      Vector3f(-sinPhi, cosPhi, 0);
    Vector3f d2Pdvv = -(thetaMax - thetaMin) * (thetaMax - thetaMin) *
                      Vector3f(pHit.x, pHit.y, pHit.z);
    // Compute coefficients for fundamental forms
    Float E = Dot(dpdu, dpdu), F = Dot(dpdu, dpdv), G = Dot(dpdv, dpdv);
    Vector3f N = Normalize(Cross(dpdu, dpdv));
    Float e = Dot(N, d2Pduu), f = Dot(N, d2Pduv), g = Dot(N, d2Pdvv);
    // Compute dndu and dndv from fundamental form coefficients
    Float invEGF2 = 1 / (E * G - F * F);
    Normal3f dndu = Normal3f((f * F - e * G) * invEGF2 * dpdu +
                             (e * F - f * E) * invEGF2 * dpdv);
    Normal3f dndv = Normal3f((g * F - f * G) * invEGF2 * dpdu +
                             (f * F - g * E) * invEGF2 * dpdv);
    // Compute error bounds for sphere intersection
    Vector3f pError = gamma(5) * Abs((Vector3f)pHit);
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
bool Sphere::IntersectP(const Ray &r, bool /*testAlphaTexture*/) const {
    Float phi;
    Point3f pHit;
    // Transform Ray to object space
    Vector3f oErr, dErr;
    Ray ray((*WorldToObject)(r.o, &oErr), (*WorldToObject)(r.d, &dErr), r.tMax,
            r.time);
    // Compute quadratic sphere coefficients
    EFloat ox(ray.o.x, oErr.x), oy(ray.o.y, oErr.y), oz(ray.o.z, oErr.z);
    EFloat dx(ray.d.x, dErr.x), dy(ray.d.y, dErr.y), dz(ray.d.z, dErr.z);
    EFloat a = dx * dx + dy * dy + dz * dz;
    EFloat b = 2 * (dx * ox + dy * oy + dz * oz);
    EFloat c = ox * ox + oy * oy + oz * oz - EFloat(radius) * EFloat(radius);
    // Compute the sphere's discriminant from the closest point
    EFloat s = b / (2 * a);
    EFloat fx = ox - s * dx, fy = oy - s * dy, fz = oz - s * dz;
    EFloat fLength = sqrt(fx * fx + fy * fy + fz * fz);
    EFloat discrim =
        4 * a * (EFloat(radius) - fLength) * (EFloat(radius) + fLength);
    // Solve quadratic equation for t values
    EFloat t0, t1;
    if (!QuadraticRoots(a, b, c, discrim, &t0, &t1)) return false;
    // Check quadric shape t0 and t1 for nearest intersection
    if (!((Float)t0 <= ray.tMax) || !(t1.LowerBound() > 0)) return false;
    EFloat tShapeHit = t0;
    bool usingFarRoot = false;
    if (!(tShapeHit.LowerBound() > 0)) {
        tShapeHit = t1;
        usingFarRoot = true;
        if (!((Float)tShapeHit <= ray.tMax)) return false;
    }
    // Compute sphere hit position and phi
    pHit = ray((Float)tShapeHit);
    // Refine sphere intersection point
    if (pHit.x == 0 && pHit.y == 0) pHit.x = Float(1e-5) * radius;
    pHit *= radius / Distance(pHit, Point3f(0, 0, 0));
    phi = std::atan2(pHit.y, pHit.x);
    if (phi < 0) phi += 2 * Pi;
    // Test sphere intersection against clipping parameters
    if (IsClipped(pHit, phi)) {
        if (usingFarRoot) return false;
        if (!((Float)t1 <= ray.tMax)) return false;
        tShapeHit = t1;
        // Compute sphere hit position and phi
        pHit = ray((Float)tShapeHit);
        // Refine sphere intersection point
        if (pHit.x == 0 && pHit.y == 0) pHit.x = Float(1e-5) * radius;
        pHit *= radius / Distance(pHit, Point3f(0, 0, 0));
        phi = std::atan2(pHit.y, pHit.x);
        if (phi < 0) phi += 2 * Pi;
        if (IsClipped(pHit, phi)) return false;
    }
    return true;
}
Float Sphere::Area() const {
    // Compute the area of the partial sphere
    return phiMax * radius * (zMax - zMin);
}

}  // namespace lrt
