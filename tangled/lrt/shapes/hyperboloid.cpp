// lrt/shapes/hyperboloid.cpp: tangled from chapters/03-shapes.md. Edit the chapter, not this file.
#include "lrt/shapes/hyperboloid.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace lrt {

// Hyperboloid Method Definitions
Hyperboloid::Hyperboloid(const Transform *ObjectToWorld,
                         const Transform *WorldToObject,
                         bool reverseOrientation, const Point3f &point1,
                         const Point3f &point2, Float phiMax)
    : Quadric("Hyperboloid", ObjectToWorld, WorldToObject, reverseOrientation,
              ImplicitForm(point1, point2), phiMax),
      p1(point1),
      p2(point2),
      zMin(std::min(point1.z, point2.z)),
      zMax(std::max(point1.z, point2.z)),
      rMax(std::max(std::sqrt(point1.x * point1.x + point1.y * point1.y),
                    std::sqrt(point2.x * point2.x + point2.y * point2.y))) {
    for (int i = 0; i < 3; ++i)
        if (!std::isfinite(p1[i]) || !std::isfinite(p2[i]))
            throw std::invalid_argument(
                "Hyperboloid: point1 and point2 must be finite");
    if (p1.z == p2.z)
        throw std::invalid_argument(
            "Hyperboloid: point1 and point2 must differ in z");
    if (!(rMax > 0))
        throw std::invalid_argument(
            "Hyperboloid: the segment lies on the z axis");
}
QuadricOfRevolution Hyperboloid::ImplicitForm(const Point3f &p1,
                                              const Point3f &p2) {
    EFloat x1(p1.x), y1(p1.y), z1(p1.z);
    EFloat dx = EFloat(p2.x) - x1, dy = EFloat(p2.y) - y1,
           dz = EFloat(p2.z) - z1;
    if ((Float)dx == 0 && (Float)dy == 0) return {0, 0, 0, x1 * x1 + y1 * y1};
    EFloat dxy2 = dx * dx + dy * dy;
    EFloat vWaist = -(x1 * dx + y1 * dy) / dxy2;
    EFloat cross = x1 * dy - y1 * dx;
    return {z1 + vWaist * dz, dxy2 / (dz * dz), 0, cross * cross / dxy2};
}
bool Hyperboloid::LocateHit(const QuadricRay &q, QuadricHit *hit) const {
    q.PointAt(hit->t, &hit->p, &hit->pError);
    const Point3f &p = hit->p;
    Float v = (p.z - p1.z) / (p2.z - p1.z);
    Point3f pr = (1 - v) * p1 + v * p2;
    hit->phi = Azimuth(pr.x * p.x + pr.y * p.y, pr.x * p.y - pr.y * p.x);
    return p.z >= zMin && p.z <= zMax && hit->phi <= phiMax;
}
SurfaceInteraction Hyperboloid::DescribeHit(const QuadricRay &q,
                                            const QuadricHit &hit) const {
    Point2f uv(hit.phi / phiMax, (hit.p.z - p1.z) / (p2.z - p1.z));
    Float cosPhi = std::cos(hit.phi), sinPhi = std::sin(hit.phi);
    Vector3f delta = p2 - p1;
    Vector3f dpdv(delta.x * cosPhi - delta.y * sinPhi,
                  delta.x * sinPhi + delta.y * cosPhi, delta.z);
    Vector3f d2Pdvv(0, 0, 0);
    return Interaction(q, hit, OffAxis(hit.p, rMax), uv, dpdv, d2Pdvv);
}
// S(x) = arsinh(x) / x for x >= 0, with its limits: 1 at 0 (the cylinder),
// 0 at infinity, where a tiny waist makes mu t / rho0 overflow (the cone).
static Float ArsinhRatio(Float x) {
    if (x == 0) return 1;
    if (std::isinf(x)) return 0;
    return std::asinh(x) / x;
}

Float Hyperboloid::Area() const {
    // Find the waist and the slope of the hyperboloid's profile
    Vector3f d = p2 - p1;
    Float dxy2 = d.x * d.x + d.y * d.y;
    Float height = std::abs(d.z);
    Float rho0, mu, t0;
    if (dxy2 == 0) {
        // A vertical segment sweeps a cylinder: its waist is its radius, and
        // since mu = 0 any height may serve as the waist's.
        rho0 = std::sqrt(p1.x * p1.x + p1.y * p1.y);
        mu = 0;
        t0 = 0;
    } else {
        Float dxy = std::sqrt(dxy2);
        rho0 = std::abs(p1.x * d.y - p1.y * d.x) / dxy;
        Float kappa = dxy / height;
        mu = kappa * std::hypot(Float(1), kappa);
        const Point3f &lower = (d.z > 0) ? p1 : p2;
        t0 = d.z * ((lower.x * d.x + lower.y * d.y) / dxy2);
    }
    Float t1 = t0 + height;
    // Integrate the hyperboloid's profile between its heights
    auto w = [&](Float t) { return std::hypot(rho0, mu * t); };
    if (t0 < 0 && t1 > 0) {
        // The waist lies inside the band: G(t1) + G(-t0), no cancellation.
        auto G = [&](Float t) {
            Float second = (rho0 > 0) ? rho0 * ArsinhRatio(mu * t / rho0) : 0;
            return Float(0.5) * t * (w(t) + second);
        };
        return phiMax * (G(t1) + G(-t0));
    }
    // Both heights on one side of the waist: mirror them to 0 <= t0 < t1.
    if (t1 <= 0) {
        Float t = -t1;
        t1 = -t0;
        t0 = t;
    }
    // The first difference, with numerator and denominator divided by w1 >=
    // rho0, mu t1, mu t0, so that no square overflows.
    Float w0 = w(t0), w1 = w(t1);
    Float first = height * (t1 + t0) *
                  (rho0 * (rho0 / w1) + mu * t0 * (mu * t0 / w1) +
                   mu * t1 * (mu * t1 / w1)) /
                  (t1 + t0 * (w0 / w1));
    Float second = 0;
    if (rho0 > 0 && std::isfinite(mu * t1 / rho0)) {
        Float c0 = std::hypot(Float(1), mu * t0 / rho0);
        Float c1 = std::hypot(Float(1), mu * t1 / rho0);
        Float R = (t1 + t0) / (t1 * c0 + t0 * c1);
        second = rho0 * height * R * ArsinhRatio(mu * height * R / rho0);
    }
    return phiMax * Float(0.5) * (first + second);
}

}  // namespace lrt
