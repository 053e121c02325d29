// lrt/core/interaction.cpp: tangled from chapters/02-geometry.md. Edit the chapter, not this file.
// interaction.cpp includes
#include "lrt/core/interaction.h"

namespace lrt {

// Interaction Method Definitions
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
