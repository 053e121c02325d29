// lrt/core/interaction.h: tangled from chapters/02-geometry.md. Edit the chapter, not this file.
#pragma once

#include "lrt/core/geometry.h"

namespace lrt {

// Interaction Declarations
struct Interaction {
    // Interaction Public Methods
    Interaction() {}
    Interaction(const Point3f &p, const Normal3f &n, const Vector3f &pError,
                const Vector3f &wo, Float time)
        : p(p), time(time), pError(pError), wo(NormalizeDirection(wo)), n(n) {}
    Interaction(const Point3f &p, const Vector3f &wo, Float time)
        : p(p), time(time), wo(NormalizeDirection(wo)) {}
    Interaction(const Point3f &p, Float time) : p(p), time(time) {}
    static Vector3f NormalizeDirection(const Vector3f &w) {
        return w.LengthSquared() > 0 ? Normalize(w) : w;
    }
    bool IsSurfaceInteraction() const { return n != Normal3f(); }
    Ray SpawnRay(const Vector3f &d) const {
        Point3f o = OffsetRayOrigin(p, pError, n, d);
        return Ray(o, d, Infinity, time);
    }
    Ray SpawnRayTo(const Point3f &p2) const {
        Point3f o = OffsetRayOrigin(p, pError, n, p2 - p);
        Vector3f d = p2 - o;
        return Ray(o, d, 1 - ShadowEpsilon, time);
    }
    Ray SpawnRayTo(const Interaction &it) const {
        Point3f o = OffsetRayOrigin(p, pError, n, it.p - p);
        Point3f target = OffsetRayOrigin(it.p, it.pError, it.n, o - it.p);
        Vector3f d = target - o;
        return Ray(o, d, 1 - ShadowEpsilon, time);
    }
    // Interaction Public Data
    Point3f p;
    Float time = 0;
    Vector3f pError;
    Vector3f wo;
    Normal3f n;
};

// SurfaceInteraction Declarations
class SurfaceInteraction : public Interaction {
  public:
    // SurfaceInteraction Public Methods
    SurfaceInteraction() {}
    SurfaceInteraction(const Point3f &p, const Vector3f &pError,
                       const Point2f &uv, const Vector3f &wo,
                       const Vector3f &dpdu, const Vector3f &dpdv,
                       const Normal3f &dndu, const Normal3f &dndv, Float time,
                       bool flipNormal, int faceIndex = 0);
    SurfaceInteraction(const Point3f &p, const Vector3f &pError,
                       const Point2f &uv, const Vector3f &wo,
                       const Vector3f &dpdu, const Vector3f &dpdv,
                       const Normal3f &dndu, const Normal3f &dndv,
                       const Normal3f &normal, Float time, bool flipNormal,
                       int faceIndex);
    void SetShadingGeometry(const Vector3f &dpdus, const Vector3f &dpdvs,
                            const Normal3f &dndus, const Normal3f &dndvs,
                            bool orientationIsAuthoritative);
    // SurfaceInteraction Public Data
    Point2f uv;
    Vector3f dpdu, dpdv;
    Normal3f dndu, dndv;
    const Shape *shape = nullptr;
    struct {
        Normal3f n;
        Vector3f dpdu, dpdv;
        Normal3f dndu, dndv;
    } shading;
    const Primitive *primitive = nullptr;
    int faceIndex = 0;
    bool flipNormal = false;
};

// SurfaceInteraction Inline Definitions
inline SurfaceInteraction::SurfaceInteraction(
    const Point3f &p, const Vector3f &pError, const Point2f &uv,
    const Vector3f &wo, const Vector3f &dpdu, const Vector3f &dpdv,
    const Normal3f &dndu, const Normal3f &dndv, const Normal3f &normal,
    Float time, bool flipNormal, int faceIndex)
    : Interaction(p, normal, pError, wo, time),
      uv(uv), dpdu(dpdu), dpdv(dpdv), dndu(dndu), dndv(dndv),
      faceIndex(faceIndex), flipNormal(flipNormal) {
    shading.n = n;
    shading.dpdu = dpdu;
    shading.dpdv = dpdv;
    shading.dndu = dndu;
    shading.dndv = dndv;
    // Adjust normal based on orientation and handedness
    if (flipNormal) {
        n = -n;
        shading.n = -shading.n;
    }
}

}  // namespace lrt
