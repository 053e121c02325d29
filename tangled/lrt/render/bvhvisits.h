// lrt/render/bvhvisits.h: tangled from chapters/08-rendering.md. Edit the chapter, not this file.
#pragma once

#include "lrt/accelerators/bvh.h"
#include "lrt/core/geometry.h"
#include "lrt/core/interaction.h"
#include "lrt/render/camera.h"
#include "lrt/render/image.h"

#include <vector>

namespace lrt {

// BVH Visits Declarations
int CountNodeVisits(const BVHAccel &bvh, const Ray &ray,
                    SurfaceInteraction *isect, bool *hit);
RGB HeatColor(Float v);
Image RenderNodeVisits(const BVHAccel &bvh, const PinholeCamera &camera,
                       int maxVisits, std::vector<int> *visits = nullptr);

}  // namespace lrt
