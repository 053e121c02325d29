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
Float Hyperboloid::Area() const {
    // Compute the area of the partial hyperboloid
    double dx = double(p2.x) - p1.x, dy = double(p2.y) - p1.y,
           dz = double(p2.z) - p1.z;
    double x1 = p1.x, y1 = p1.y;
    double dxy2 = dx * dx + dy * dy, cross = x1 * dy - y1 * dx;
    double A = dxy2 * (dxy2 + dz * dz);
    double B = (dxy2 > 0) ? cross * cross * dz * dz / dxy2 : 0;
    double vWaist = (dxy2 > 0) ? -(x1 * dx + y1 * dy) / dxy2 : 0;
    auto F = [&](double s) {
        if (A == 0) return std::sqrt(x1 * x1 + y1 * y1) * std::abs(dz) * s;
        if (B == 0) return 0.5 * std::sqrt(A) * s * std::abs(s);
        return 0.5 * (s * std::sqrt(A * s * s + B) +
                      B / std::sqrt(A) *
                          std::asinh(std::sqrt(A) * s / std::sqrt(B)));
    };
    return Float(phiMax * (F(1 - vWaist) - F(-vWaist)));
}

}  // namespace lrt
