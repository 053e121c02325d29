// lrt/shapes/triangle.cpp: tangled from chapters/03-shapes.md. Edit the chapter, not this file.
#include "lrt/shapes/triangle.h"

#include <algorithm>
#include <cmath>
#include <new>
#include <stdexcept>
#include <string>

namespace lrt {

// Triangle Utility Functions
static inline Float MaxAbs(Float a, Float b, Float c) {
    return std::max(std::abs(a), std::max(std::abs(b), std::abs(c)));
}

// TriangleMesh Method Definitions
TriangleMesh::TriangleMesh(const Transform &ObjectToWorld,
                           bool reverseOrientation, int nTriangles,
                           const int *vertexIndices, int nVertices,
                           const Point3f *P, const Vector3f *S,
                           const Normal3f *N, const Point2f *UV,
                           const int *faceIndices)
    : nTriangles(nTriangles), nVertices(nVertices) {
    // Check the arguments of the TriangleMesh constructor
    if (nTriangles < 0 || nVertices < 0)
        throw std::invalid_argument("TriangleMesh: negative number of "
                                    "triangles or vertices");
    if ((nTriangles > 0 && !vertexIndices) || (nVertices > 0 && !P))
        throw std::invalid_argument("TriangleMesh: vertex indices or "
                                    "positions missing");
    for (size_t i = 0; i < 3 * size_t(nTriangles); ++i)
        if (vertexIndices[i] < 0 || vertexIndices[i] >= nVertices)
            throw std::out_of_range(
                "TriangleMesh: triangle " + std::to_string(i / 3) +
                " has vertex index " + std::to_string(vertexIndices[i]) +
                ", outside the range [0, " + std::to_string(nVertices) + ")");
    this->vertexIndices.assign(vertexIndices,
                               vertexIndices + 3 * size_t(nTriangles));
    // Transform mesh vertices to world space
    p.resize(nVertices);
    for (int i = 0; i < nVertices; ++i) {
        p[i] = ObjectToWorld(P[i]);
        if (!std::isfinite(p[i].x) || !std::isfinite(p[i].y) ||
            !std::isfinite(p[i].z))
            throw std::invalid_argument("TriangleMesh: vertex " +
                                        std::to_string(i) +
                                        " is not finite in world space");
    }
    // Copy normals, tangents, uv and face indices, if present
    if (N) {
        n.resize(nVertices);
        for (int i = 0; i < nVertices; ++i) {
            n[i] = ObjectToWorld(N[i]);
            if (reverseOrientation) n[i] = -n[i];
        }
    }
    if (S) {
        s.resize(nVertices);
        for (int i = 0; i < nVertices; ++i) s[i] = ObjectToWorld(S[i]);
    }
    if (UV) uv.assign(UV, UV + nVertices);
    if (faceIndices)
        this->faceIndices.assign(faceIndices, faceIndices + nTriangles);
}

// Triangle Method Definitions
Bounds3f Triangle::ObjectBound() const {
    // Get triangle vertices in p0, p1, and p2
    const Point3f &p0 = mesh->p[v[0]];
    const Point3f &p1 = mesh->p[v[1]];
    const Point3f &p2 = mesh->p[v[2]];
    return Union(Bounds3f((*WorldToObject)(p0), (*WorldToObject)(p1)),
                 (*WorldToObject)(p2));
}

Bounds3f Triangle::WorldBound() const {
    // Get triangle vertices in p0, p1, and p2
    const Point3f &p0 = mesh->p[v[0]];
    const Point3f &p1 = mesh->p[v[1]];
    const Point3f &p2 = mesh->p[v[2]];
    return Union(Bounds3f(p0, p1), p2);
}
bool Triangle::IntersectP(const Ray &ray, bool) const {
    // Get triangle vertices in p0, p1, and p2
    const Point3f &p0 = mesh->p[v[0]];
    const Point3f &p1 = mesh->p[v[1]];
    const Point3f &p2 = mesh->p[v[2]];
    // Perform ray-triangle intersection test
    // Transform triangle vertices to ray coordinate space
    // Translate vertices based on ray origin
    Point3f p0t = p0 - Vector3f(ray.o);
    Point3f p1t = p1 - Vector3f(ray.o);
    Point3f p2t = p2 - Vector3f(ray.o);
    // Permute components of triangle vertices and ray direction
    // Choose the ray's permuted axes kx, ky, kz and direction d
    int kz = MaxDimension(Abs(ray.d));
    int kx = kz + 1;
    if (kx == 3) kx = 0;
    int ky = kx + 1;
    if (ky == 3) ky = 0;
    Vector3f d = Permute(ray.d, kx, ky, kz);
    p0t = Permute(p0t, kx, ky, kz);
    p1t = Permute(p1t, kx, ky, kz);
    p2t = Permute(p2t, kx, ky, kz);
    // Apply shear transformation to translated vertex positions
    // Compute the ray's shear coefficients Sx, Sy, Sz
    Float Sx = -d.x / d.z;
    Float Sy = -d.y / d.z;
    Float Sz = 1 / d.z;
    // Shear the translated vertices into x0, y0, x1, y1, x2, y2
    Float x0 = p0t.x + Sx * p0t.z, y0 = p0t.y + Sy * p0t.z;
    Float x1 = p1t.x + Sx * p1t.z, y1 = p1t.y + Sy * p1t.z;
    Float x2 = p2t.x + Sx * p2t.z, y2 = p2t.y + Sy * p2t.z;
    // Compute edge function coefficients e0, e1, and e2
    Float e0 = x1 * y2 - y1 * x2;
    Float e1 = x2 * y0 - y2 * x0;
    Float e2 = x0 * y1 - y0 * x1;
    // Fall back to double-precision test at triangle edges
    if (sizeof(Float) == sizeof(float) && (e0 == 0 || e1 == 0 || e2 == 0)) {
        e0 = Float(double(x1) * double(y2) - double(y1) * double(x2));
        e1 = Float(double(x2) * double(y0) - double(y2) * double(x0));
        e2 = Float(double(x0) * double(y1) - double(y0) * double(x1));
    }
    // Perform triangle edge and determinant tests
    if ((e0 < 0 || e1 < 0 || e2 < 0) && (e0 > 0 || e1 > 0 || e2 > 0))
        return false;
    Float det = e0 + e1 + e2;
    if (det == 0) return false;
    // Compute scaled hit distance to triangle and test against ray t range
    Float z0 = Sz * p0t.z, z1 = Sz * p1t.z, z2 = Sz * p2t.z;
    Float tScaled = e0 * z0 + e1 * z1 + e2 * z2;
    Float tMaxScaled = ray.tMax * det * (1 + 2 * gamma(3));
    bool inRange = det > 0 ? (tScaled > 0 && tScaled <= tMaxScaled)
                           : (tScaled < 0 && tScaled >= tMaxScaled);
    if (!inRange) return false;
    // Compute t for the triangle hit
    Float invDet = 1 / det;
    Float t = tScaled * invDet;
    if (!(t <= ray.tMax)) return false;
    // Ensure that computed triangle t is conservatively greater than zero
    // Compute delta_z term for triangle t error bounds
    Float maxZs = MaxAbs(z0, z1, z2);
    Float deltaZ = gamma(3) * maxZs;
    // Compute delta_x and delta_y terms for triangle t error bounds
    Float maxZt = MaxAbs(p0t.z, p1t.z, p2t.z);
    Float deltaX = gamma(5) * (MaxAbs(p0t.x, p1t.x, p2t.x) + maxZt);
    Float deltaY = gamma(5) * (MaxAbs(p0t.y, p1t.y, p2t.y) + maxZt);
    // Compute delta_e term for triangle t error bounds
    Float maxXs = MaxAbs(x0, x1, x2), maxYs = MaxAbs(y0, y1, y2);
    Float deltaE =
        2 * (gamma(2) * maxXs * maxYs + deltaY * maxXs + deltaX * maxYs);
    // Compute delta_t term for triangle t error bounds and check t
    Float maxE = MaxAbs(e0, e1, e2);
    Float deltaT = 3 *
                   (gamma(3) * maxE * maxZs + deltaE * maxZs + deltaZ * maxE) *
                   std::abs(invDet);
    if (!(t > deltaT)) return false;
    // Reject degenerate triangles
    Vector3f dp02 = p0 - p2, dp12 = p1 - p2;
    Vector3f ng = Cross(dp02, dp12);
    if (ng.LengthSquared() == 0) return false;
    return true;
}
bool Triangle::Intersect(const Ray &ray, Float *tHit,
                         SurfaceInteraction *isect, bool) const {
    // Get triangle vertices in p0, p1, and p2
    const Point3f &p0 = mesh->p[v[0]];
    const Point3f &p1 = mesh->p[v[1]];
    const Point3f &p2 = mesh->p[v[2]];
    // Perform ray-triangle intersection test
    // Transform triangle vertices to ray coordinate space
    // Translate vertices based on ray origin
    Point3f p0t = p0 - Vector3f(ray.o);
    Point3f p1t = p1 - Vector3f(ray.o);
    Point3f p2t = p2 - Vector3f(ray.o);
    // Permute components of triangle vertices and ray direction
    // Choose the ray's permuted axes kx, ky, kz and direction d
    int kz = MaxDimension(Abs(ray.d));
    int kx = kz + 1;
    if (kx == 3) kx = 0;
    int ky = kx + 1;
    if (ky == 3) ky = 0;
    Vector3f d = Permute(ray.d, kx, ky, kz);
    p0t = Permute(p0t, kx, ky, kz);
    p1t = Permute(p1t, kx, ky, kz);
    p2t = Permute(p2t, kx, ky, kz);
    // Apply shear transformation to translated vertex positions
    // Compute the ray's shear coefficients Sx, Sy, Sz
    Float Sx = -d.x / d.z;
    Float Sy = -d.y / d.z;
    Float Sz = 1 / d.z;
    // Shear the translated vertices into x0, y0, x1, y1, x2, y2
    Float x0 = p0t.x + Sx * p0t.z, y0 = p0t.y + Sy * p0t.z;
    Float x1 = p1t.x + Sx * p1t.z, y1 = p1t.y + Sy * p1t.z;
    Float x2 = p2t.x + Sx * p2t.z, y2 = p2t.y + Sy * p2t.z;
    // Compute edge function coefficients e0, e1, and e2
    Float e0 = x1 * y2 - y1 * x2;
    Float e1 = x2 * y0 - y2 * x0;
    Float e2 = x0 * y1 - y0 * x1;
    // Fall back to double-precision test at triangle edges
    if (sizeof(Float) == sizeof(float) && (e0 == 0 || e1 == 0 || e2 == 0)) {
        e0 = Float(double(x1) * double(y2) - double(y1) * double(x2));
        e1 = Float(double(x2) * double(y0) - double(y2) * double(x0));
        e2 = Float(double(x0) * double(y1) - double(y0) * double(x1));
    }
    // Perform triangle edge and determinant tests
    if ((e0 < 0 || e1 < 0 || e2 < 0) && (e0 > 0 || e1 > 0 || e2 > 0))
        return false;
    Float det = e0 + e1 + e2;
    if (det == 0) return false;
    // Compute scaled hit distance to triangle and test against ray t range
    Float z0 = Sz * p0t.z, z1 = Sz * p1t.z, z2 = Sz * p2t.z;
    Float tScaled = e0 * z0 + e1 * z1 + e2 * z2;
    Float tMaxScaled = ray.tMax * det * (1 + 2 * gamma(3));
    bool inRange = det > 0 ? (tScaled > 0 && tScaled <= tMaxScaled)
                           : (tScaled < 0 && tScaled >= tMaxScaled);
    if (!inRange) return false;
    // Compute t for the triangle hit
    Float invDet = 1 / det;
    Float t = tScaled * invDet;
    if (!(t <= ray.tMax)) return false;
    // Ensure that computed triangle t is conservatively greater than zero
    // Compute delta_z term for triangle t error bounds
    Float maxZs = MaxAbs(z0, z1, z2);
    Float deltaZ = gamma(3) * maxZs;
    // Compute delta_x and delta_y terms for triangle t error bounds
    Float maxZt = MaxAbs(p0t.z, p1t.z, p2t.z);
    Float deltaX = gamma(5) * (MaxAbs(p0t.x, p1t.x, p2t.x) + maxZt);
    Float deltaY = gamma(5) * (MaxAbs(p0t.y, p1t.y, p2t.y) + maxZt);
    // Compute delta_e term for triangle t error bounds
    Float maxXs = MaxAbs(x0, x1, x2), maxYs = MaxAbs(y0, y1, y2);
    Float deltaE =
        2 * (gamma(2) * maxXs * maxYs + deltaY * maxXs + deltaX * maxYs);
    // Compute delta_t term for triangle t error bounds and check t
    Float maxE = MaxAbs(e0, e1, e2);
    Float deltaT = 3 *
                   (gamma(3) * maxE * maxZs + deltaE * maxZs + deltaZ * maxE) *
                   std::abs(invDet);
    if (!(t > deltaT)) return false;
    // Reject degenerate triangles
    Vector3f dp02 = p0 - p2, dp12 = p1 - p2;
    Vector3f ng = Cross(dp02, dp12);
    if (ng.LengthSquared() == 0) return false;
    // Compute barycentric coordinates of the triangle hit
    Float b0 = e0 * invDet, b1 = e1 * invDet, b2 = e2 * invDet;
    // Compute triangle partial derivatives
    Point2f uv[3];
    GetUVs(uv);
    // Compute triangle partial derivatives from uv
    Vector2f duv02 = uv[0] - uv[2], duv12 = uv[1] - uv[2];
    Float determinant = duv02[0] * duv12[1] - duv02[1] * duv12[0];
    bool degenerateUV = std::abs(determinant) < 1e-8;
    Vector3f dpdu, dpdv;
    if (!degenerateUV) {
        Float invdet = 1 / determinant;
        dpdu = (duv12[1] * dp02 - duv02[1] * dp12) * invdet;
        dpdv = (duv02[0] * dp12 - duv12[0] * dp02) * invdet;
    }
    // Handle degenerate uv parameterization or partial derivatives
    if (degenerateUV || Cross(dpdu, dpdv).LengthSquared() == 0)
        CoordinateSystem(Normalize(ng), &dpdu, &dpdv);
    // Compute error bounds for triangle intersection
    Float xAbsSum = std::abs(b0 * p0.x) + std::abs(b1 * p1.x) +
                    std::abs(b2 * p2.x);
    Float yAbsSum = std::abs(b0 * p0.y) + std::abs(b1 * p1.y) +
                    std::abs(b2 * p2.y);
    Float zAbsSum = std::abs(b0 * p0.z) + std::abs(b1 * p1.z) +
                    std::abs(b2 * p2.z);
    Vector3f pError = gamma(7) * Vector3f(xAbsSum, yAbsSum, zAbsSum);
    // Interpolate (u,v) parametric coordinates and hit point
    Point3f pHit = b0 * p0 + b1 * p1 + b2 * p2;
    Point2f uvHit = b0 * uv[0] + b1 * uv[1] + b2 * uv[2];
    // Fill in SurfaceInteraction from triangle hit
    bool flip = FlipsNormal();
    // Construct the SurfaceInteraction of the triangle hit
    new (isect) SurfaceInteraction(pHit, pError, uvHit, -ray.d, dpdu, dpdv,
                                   Normal3f(0, 0, 0), Normal3f(0, 0, 0),
                                   Normal3f(Normalize(ng)), ray.time, flip,
                                   faceIndex);
    isect->shape = this;
    if (!mesh->n.empty() || !mesh->s.empty()) {
        // Initialize Triangle shading geometry
        // Compute shading normal ns for triangle
        Normal3f ns = isect->n;
        if (!mesh->n.empty()) {
            Normal3f nInterp =
                b0 * mesh->n[v[0]] + b1 * mesh->n[v[1]] + b2 * mesh->n[v[2]];
            if (nInterp.LengthSquared() > 0) ns = Normalize(nInterp);
        }
        // Compute shading tangent ss for triangle
        Vector3f ss = Normalize(isect->dpdu);
        if (!mesh->s.empty()) {
            Vector3f sInterp =
                b0 * mesh->s[v[0]] + b1 * mesh->s[v[1]] + b2 * mesh->s[v[2]];
            if (sInterp.LengthSquared() > 0) ss = Normalize(sInterp);
        }
        // Compute shading bitangent ts for triangle and adjust ss
        Vector3f ts = Cross(Vector3f(ns), ss);
        if (ts.LengthSquared() > 0) {
            ts = Normalize(ts);
            ss = Cross(ts, Vector3f(ns));
        } else
            CoordinateSystem(Vector3f(ns), &ss, &ts);
        if (flip) ts = -ts;
        // Compute dndu and dndv for triangle shading geometry
        Normal3f dndu(0, 0, 0), dndv(0, 0, 0);
        if (!mesh->n.empty()) {
            if (degenerateUV) {
                duv02 = Vector2f(Dot(dp02, dpdu), Dot(dp02, dpdv));
                duv12 = Vector2f(Dot(dp12, dpdu), Dot(dp12, dpdv));
                determinant = duv02[0] * duv12[1] - duv02[1] * duv12[0];
            }
            if (determinant != 0) {
                Normal3f dn02 = mesh->n[v[0]] - mesh->n[v[2]];
                Normal3f dn12 = mesh->n[v[1]] - mesh->n[v[2]];
                Float invdet = 1 / determinant;
                dndu = (duv12[1] * dn02 - duv02[1] * dn12) * invdet;
                dndv = (duv02[0] * dn12 - duv12[0] * dn02) * invdet;
            }
        }
        isect->SetShadingGeometry(ss, ts, dndu, dndv, true);
    }
    *tHit = t;
    return true;
}
Float Triangle::Area() const {
    // Get triangle vertices in p0, p1, and p2
    const Point3f &p0 = mesh->p[v[0]];
    const Point3f &p1 = mesh->p[v[1]];
    const Point3f &p2 = mesh->p[v[2]];
    // Compute the area from the edges in double precision
    double ax = double(p1.x) - p0.x, ay = double(p1.y) - p0.y,
           az = double(p1.z) - p0.z;
    double bx = double(p2.x) - p0.x, by = double(p2.y) - p0.y,
           bz = double(p2.z) - p0.z;
    double cx = ay * bz - az * by, cy = az * bx - ax * bz,
           cz = ax * by - ay * bx;
    return Float(0.5 * std::sqrt(cx * cx + cy * cy + cz * cz));
}
bool Triangle::CompleteIntersection(const Ray &ray, const Point3f &p0,
                                    const Point3f &p1, const Point3f &p2,
                                    Float e0, Float e1, Float e2,
                                    Float invDet,
                                    SurfaceInteraction *isect) const {
    // Reject degenerate triangles
    Vector3f dp02 = p0 - p2, dp12 = p1 - p2;
    Vector3f ng = Cross(dp02, dp12);
    if (ng.LengthSquared() == 0) return false;
    // Compute barycentric coordinates of the triangle hit
    Float b0 = e0 * invDet, b1 = e1 * invDet, b2 = e2 * invDet;
    // Compute triangle partial derivatives
    Point2f uv[3];
    GetUVs(uv);
    // Compute triangle partial derivatives from uv
    Vector2f duv02 = uv[0] - uv[2], duv12 = uv[1] - uv[2];
    Float determinant = duv02[0] * duv12[1] - duv02[1] * duv12[0];
    bool degenerateUV = std::abs(determinant) < 1e-8;
    Vector3f dpdu, dpdv;
    if (!degenerateUV) {
        Float invdet = 1 / determinant;
        dpdu = (duv12[1] * dp02 - duv02[1] * dp12) * invdet;
        dpdv = (duv02[0] * dp12 - duv12[0] * dp02) * invdet;
    }
    // Handle degenerate uv parameterization or partial derivatives
    if (degenerateUV || Cross(dpdu, dpdv).LengthSquared() == 0)
        CoordinateSystem(Normalize(ng), &dpdu, &dpdv);
    // Compute error bounds for triangle intersection
    Float xAbsSum = std::abs(b0 * p0.x) + std::abs(b1 * p1.x) +
                    std::abs(b2 * p2.x);
    Float yAbsSum = std::abs(b0 * p0.y) + std::abs(b1 * p1.y) +
                    std::abs(b2 * p2.y);
    Float zAbsSum = std::abs(b0 * p0.z) + std::abs(b1 * p1.z) +
                    std::abs(b2 * p2.z);
    Vector3f pError = gamma(7) * Vector3f(xAbsSum, yAbsSum, zAbsSum);
    // Interpolate (u,v) parametric coordinates and hit point
    Point3f pHit = b0 * p0 + b1 * p1 + b2 * p2;
    Point2f uvHit = b0 * uv[0] + b1 * uv[1] + b2 * uv[2];
    // Fill in SurfaceInteraction from triangle hit
    bool flip = FlipsNormal();
    // Construct the SurfaceInteraction of the triangle hit
    new (isect) SurfaceInteraction(pHit, pError, uvHit, -ray.d, dpdu, dpdv,
                                   Normal3f(0, 0, 0), Normal3f(0, 0, 0),
                                   Normal3f(Normalize(ng)), ray.time, flip,
                                   faceIndex);
    isect->shape = this;
    if (!mesh->n.empty() || !mesh->s.empty()) {
        // Initialize Triangle shading geometry
        // Compute shading normal ns for triangle
        Normal3f ns = isect->n;
        if (!mesh->n.empty()) {
            Normal3f nInterp =
                b0 * mesh->n[v[0]] + b1 * mesh->n[v[1]] + b2 * mesh->n[v[2]];
            if (nInterp.LengthSquared() > 0) ns = Normalize(nInterp);
        }
        // Compute shading tangent ss for triangle
        Vector3f ss = Normalize(isect->dpdu);
        if (!mesh->s.empty()) {
            Vector3f sInterp =
                b0 * mesh->s[v[0]] + b1 * mesh->s[v[1]] + b2 * mesh->s[v[2]];
            if (sInterp.LengthSquared() > 0) ss = Normalize(sInterp);
        }
        // Compute shading bitangent ts for triangle and adjust ss
        Vector3f ts = Cross(Vector3f(ns), ss);
        if (ts.LengthSquared() > 0) {
            ts = Normalize(ts);
            ss = Cross(ts, Vector3f(ns));
        } else
            CoordinateSystem(Vector3f(ns), &ss, &ts);
        if (flip) ts = -ts;
        // Compute dndu and dndv for triangle shading geometry
        Normal3f dndu(0, 0, 0), dndv(0, 0, 0);
        if (!mesh->n.empty()) {
            if (degenerateUV) {
                duv02 = Vector2f(Dot(dp02, dpdu), Dot(dp02, dpdv));
                duv12 = Vector2f(Dot(dp12, dpdu), Dot(dp12, dpdv));
                determinant = duv02[0] * duv12[1] - duv02[1] * duv12[0];
            }
            if (determinant != 0) {
                Normal3f dn02 = mesh->n[v[0]] - mesh->n[v[2]];
                Normal3f dn12 = mesh->n[v[1]] - mesh->n[v[2]];
                Float invdet = 1 / determinant;
                dndu = (duv12[1] * dn02 - duv02[1] * dn12) * invdet;
                dndv = (duv02[0] * dn12 - duv12[0] * dn02) * invdet;
            }
        }
        isect->SetShadingGeometry(ss, ts, dndu, dndv, true);
    }
    return true;
}

// Triangle Function Definitions
std::vector<std::shared_ptr<Shape>> CreateTriangleMesh(
    const Transform *ObjectToWorld, const Transform *WorldToObject,
    bool reverseOrientation, int nTriangles, const int *vertexIndices,
    int nVertices, const Point3f *p, const Vector3f *s, const Normal3f *n,
    const Point2f *uv, const int *faceIndices) {
    if (!ObjectToWorld || !WorldToObject)
        throw std::invalid_argument("CreateTriangleMesh: missing "
                                    "transformation");
    std::shared_ptr<TriangleMesh> mesh = std::make_shared<TriangleMesh>(
        *ObjectToWorld, reverseOrientation, nTriangles, vertexIndices,
        nVertices, p, s, n, uv, faceIndices);
    std::vector<std::shared_ptr<Shape>> tris;
    tris.reserve(nTriangles);
    for (int i = 0; i < nTriangles; ++i)
        tris.push_back(std::make_shared<Triangle>(
            ObjectToWorld, WorldToObject, reverseOrientation, mesh, i));
    return tris;
}

}  // namespace lrt
