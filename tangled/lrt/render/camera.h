// lrt/render/camera.h: tangled from chapters/08-rendering.md. Edit the chapter, not this file.
#pragma once

#include "lrt/core/geometry.h"
#include "lrt/core/transform.h"

namespace lrt {

// PinholeCamera Declarations
class PinholeCamera {
  public:
    PinholeCamera(const Transform &CameraToWorld, Float fov, int width,
                  int height, Float zNear = 0, Float zFar = Infinity);
    Ray GenerateRay(const Point2f &pRaster) const;
    Point3f Position() const { return eye; }
    Float Depth(const Point3f &p) const { return WorldToCamera(p).z; }
    const Transform CameraToWorld, WorldToCamera;
    const Float fov;
    const int width, height;
    const Float zNear, zFar;

  private:
    Float sx, sy;
    Point3f eye;
};

}  // namespace lrt
