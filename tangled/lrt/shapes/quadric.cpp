// lrt/shapes/quadric.cpp: tangled from chapters/03-shapes.md. Edit the chapter, not this file.
#include "lrt/shapes/quadric.h"

#include <cmath>
#include <initializer_list>
#include <utility>
#include <stdexcept>
#include <string>

namespace lrt {

// Quadric Method Definitions
QuadricRay::QuadricRay(const Ray &r, const Transform &WorldToObject) {
    Vector3f oErr, dErr;
    ray = Ray(WorldToObject(r.o, &oErr), WorldToObject(r.d, &dErr), r.tMax,
              r.time);
    ox = EFloat(ray.o.x, oErr.x);
    oy = EFloat(ray.o.y, oErr.y);
    oz = EFloat(ray.o.z, oErr.z);
    dx = EFloat(ray.d.x, dErr.x);
    dy = EFloat(ray.d.y, dErr.y);
    dz = EFloat(ray.d.z, dErr.z);
}
bool QuadricOfRevolution::Roots(const QuadricRay &q, EFloat *t0,
                                EFloat *t1) const {
    const EFloat &dx = q.dx, &dy = q.dy, &dz = q.dz;
    // Move the origin to the point of the ray nearest to (0, 0, zc)
    const Vector3f &d = q.ray.d;
    Vector3f oc(q.ray.o.x, q.ray.o.y, q.ray.o.z - (Float)zc);
    Float s = -Dot(oc, d) / Dot(d, d);
    if (!std::isfinite(s)) s = 0;
    EFloat ox = q.ox + s * dx, oy = q.oy + s * dy, oz = q.oz - zc + s * dz;
    // Compute the coefficients of the quadric's quadratic
    EFloat a = dx * dx + dy * dy - alpha * dz * dz;
    EFloat b = 2 * (dx * ox + dy * oy - alpha * dz * oz) - beta * dz;
    EFloat c = ox * ox + oy * oy - alpha * oz * oz - beta * oz - gamma;
    // Compute the quadric's discriminant from the cross product
    EFloat wx = oy * dz - oz * dy, wy = oz * dx - ox * dz,
           wz = ox * dy - oy * dx;
    EFloat halfBetaDz = Float(0.5) * beta * dz;
    EFloat discrim = 4 * (alpha * (wx * wx + wy * wy) - wz * wz +
                          beta * (dx * wy - dy * wx) + halfBetaDz * halfBetaDz +
                          gamma * a);
    // Solve the quadric's quadratic, or its linear equation
    if ((Float)a == 0) {
        if ((Float)b == 0) return false;
        *t0 = *t1 = -c / b;
    } else if (!QuadraticRoots(a, b, c, discrim, t0, t1)) {
        return false;
    } else {
        // Bound the roots again if the moved origin is near a double root
        bool aNonzero = a.LowerBound() > 0 || a.UpperBound() < 0;
        if (aNonzero && !(std::isfinite(t0->LowerBound()) &&
                          std::isfinite(t1->UpperBound()))) {
            EFloat rootDiscrim = sqrt(discrim);
            *t0 = (-b - rootDiscrim) / (2 * a);
            *t1 = (-b + rootDiscrim) / (2 * a);
            if ((Float)*t0 > (Float)*t1) std::swap(*t0, *t1);
        }
    }
    *t0 = *t0 + s;
    *t1 = *t1 + s;
    return true;
}
// Convert phiMax from degrees to radians
static Float PhiMaxRadians(Float phiMaxDegrees) {
    Float deg = Clamp(phiMaxDegrees, 0, 360);
    return (deg >= 360) ? 2 * Pi : Radians(deg);
}

Quadric::Quadric(const char *name, const Transform *ObjectToWorld,
                 const Transform *WorldToObject, bool reverseOrientation,
                 const QuadricOfRevolution &implicit, Float phiMax)
    : Shape(ObjectToWorld, WorldToObject, reverseOrientation),
      implicit(implicit),
      phiMax(PhiMaxRadians(phiMax)) {
    if (!(this->phiMax > 0))
        throw std::invalid_argument(std::string(name) +
                                    ": phiMax must be positive");
}
bool Quadric::FindHit(const QuadricRay &q, QuadricHit *hit) const {
    EFloat t0, t1;
    if (!implicit.Roots(q, &t0, &t1)) return false;
    for (const EFloat &t : {t0, t1}) {
        if (!(t.LowerBound() > 0)) continue;
        if (!((Float)t <= q.ray.tMax)) return false;
        hit->t = t;
        if (LocateHit(q, hit)) return true;
    }
    return false;
}
bool Quadric::Intersect(const Ray &r, Float *tHit, SurfaceInteraction *isect,
                        bool /*testAlphaTexture*/) const {
    QuadricRay q(r, *WorldToObject);
    QuadricHit hit;
    if (!FindHit(q, &hit)) return false;
    *isect = DescribeHit(q, hit);
    *tHit = (Float)hit.t;
    return true;
}

bool Quadric::IntersectP(const Ray &r, bool /*testAlphaTexture*/) const {
    QuadricHit hit;
    return FindHit(QuadricRay(r, *WorldToObject), &hit);
}
SurfaceInteraction Quadric::Interaction(const QuadricRay &q,
                                        const QuadricHit &hit,
                                        const Point3f &pAxis,
                                        const Point2f &uv,
                                        const Vector3f &dpdv,
                                        const Vector3f &d2Pdvv) const {
    Vector3f dpdu(-phiMax * pAxis.y, phiMax * pAxis.x, 0);
    Vector3f d2Pduu(-phiMax * dpdu.y, phiMax * dpdu.x, 0);
    Vector3f d2Pduv(-phiMax * dpdv.y, phiMax * dpdv.x, 0);
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
    if (reverseOrientation) {
        dndu = -dndu;
        dndv = -dndv;
    }
    SurfaceInteraction isect = (*ObjectToWorld)(SurfaceInteraction(
        hit.p, hit.pError, uv, -q.ray.d, dpdu, dpdv, dndu, dndv, q.ray.time,
        reverseOrientation));
    isect.shape = this;
    return isect;
}

}  // namespace lrt
