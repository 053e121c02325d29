// lrt/render/camera.cpp: tangled from chapters/08-rendering.md. Edit the chapter, not this file.
#include "lrt/render/camera.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace lrt {

// PinholeCamera Method Definitions
PinholeCamera::PinholeCamera(const Transform &CameraToWorld, Float fov,
                             int width, int height, Float zNear, Float zFar)
    : CameraToWorld(CameraToWorld), WorldToCamera(Inverse(CameraToWorld)),
      fov(fov), width(width), height(height), zNear(zNear), zFar(zFar) {
    if (!(fov > 0 && fov < 180))
        throw std::invalid_argument("PinholeCamera: field of view " +
                                    std::to_string(fov) +
                                    " is not between 0 and 180 degrees");
    if (width <= 0 || height <= 0)
        throw std::invalid_argument("PinholeCamera: invalid image size");
    if (!(zNear >= 0 && zNear < zFar))
        throw std::invalid_argument(
            "PinholeCamera: need 0 <= zNear < zFar, got zNear = " +
            std::to_string(zNear) + ", zFar = " + std::to_string(zFar));
    // Compute the film's half-widths sx and sy
    Float tanHalf = std::tan(Radians(fov) / 2);
    if (width >= height) {
        sy = tanHalf;
        sx = tanHalf * Float(width) / Float(height);
    } else {
        sx = tanHalf;
        sy = tanHalf * Float(height) / Float(width);
    }
    eye = CameraToWorld(Point3f(0, 0, 0));
}
Ray PinholeCamera::GenerateRay(const Point2f &pRaster) const {
    // Compute the ray through pRaster between the clipping planes
    Vector3f dCamera((2 * pRaster.x / Float(width) - 1) * sx,
                     (1 - 2 * pRaster.y / Float(height)) * sy, 1);
    Vector3f d = CameraToWorld(dCamera);
    Point3f o = zNear > 0 ? eye + zNear * d : eye;
    return Ray(o, d, zFar - zNear);
}

}  // namespace lrt
