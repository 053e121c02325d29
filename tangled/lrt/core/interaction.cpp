// lrt/core/interaction.cpp: tangled from chapters/02-geometry.md. Edit the chapter, not this file.
// interaction.cpp includes
#include "lrt/core/interaction.h"

namespace lrt {

// Interaction Method Definitions
SurfaceInteraction::SurfaceInteraction(
    const Point3f &p, const Vector3f &pError, const Point2f &uv,
    const Vector3f &wo, const Vector3f &dpdu, const Vector3f &dpdv,
    const Normal3f &dndu, const Normal3f &dndv, Float time, bool flipNormal,
    int faceIndex)
    : SurfaceInteraction(p, pError, uv, wo, dpdu, dpdv, dndu, dndv,
                         Normal3f(Normalize(Cross(dpdu, dpdv))), time,
                         flipNormal, faceIndex) {}
void SurfaceInteraction::SetShadingGeometry(const Vector3f &dpdus,
                                            const Vector3f &dpdvs,
                                            const Normal3f &dndus,
                                            const Normal3f &dndvs,
                                            bool orientationIsAuthoritative) {
    // Compute shading.n for SurfaceInteraction
    shading.n = Normalize(Normal3f(Cross(dpdus, dpdvs)));
    if (flipNormal) shading.n = -shading.n;
    if (orientationIsAuthoritative)
        n = Faceforward(n, shading.n);
    else
        shading.n = Faceforward(shading.n, n);
    shading.dpdu = dpdus;
    shading.dpdv = dpdvs;
    shading.dndu = dndus;
    shading.dndv = dndvs;
}

}  // namespace lrt
