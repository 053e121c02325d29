// lrt/core/slabtest.h: tangled from chapters/05-slab-test.md. Edit the chapter, not this file.
#pragma once

#include "lrt/core/geometry.h"

#include <algorithm>

namespace lrt {

// Slab Test Functions
template <typename T>
inline bool Bounds3<T>::IntersectP(const Ray &ray, Float *hitt0,
                                   Float *hitt1) const {
    const Bounds3<T> &b = *this;
    // Initialize parametric interval to the ray's extent
    Float t0 = 0, t1 = ray.tMax;
    // Widen the ray's extent to cover rounding error
    t1 *= 1 + 2 * gamma(3);
    for (int i = 0; i < 3; ++i) {
        // Compute the reciprocal direction and its sign on axis i
        Float invD = 1 / ray.d[i];
        int isNeg = invD < 0;
        // Clip the parametric interval to slab i
        Float tNear = (b[isNeg][i] - ray.o[i]) * invD;
        Float tFar = (b[1 - isNeg][i] - ray.o[i]) * invD;
        // Widen tFar to cover rounding error
        tFar *= 1 + 2 * gamma(3);
        if (tNear > t0) t0 = tNear;
        if (tFar < t1) t1 = tFar;
        if (t0 > t1) return false;
    }
    // Reject a box that the ray reaches only at infinite t
    if (t0 == Infinity) return false;
    // Report the parametric interval of the hit
    if (hitt0) *hitt0 = std::min(t0, ray.tMax);
    if (hitt1) *hitt1 = std::min(t1, ray.tMax);
    return true;
}
template <typename T>
inline bool Bounds3<T>::IntersectP(const Ray &ray, const Vector3f &invDir,
                                   const int dirIsNeg[3]) const {
    const Bounds3<T> &b = *this;
    // Initialize parametric interval to the ray's extent
    Float t0 = 0, t1 = ray.tMax;
    // Widen the ray's extent to cover rounding error
    t1 *= 1 + 2 * gamma(3);
    for (int i = 0; i < 3; ++i) {
        // Look up the reciprocal direction and its sign on axis i
        Float invD = invDir[i];
        int isNeg = dirIsNeg[i];
        // Clip the parametric interval to slab i
        Float tNear = (b[isNeg][i] - ray.o[i]) * invD;
        Float tFar = (b[1 - isNeg][i] - ray.o[i]) * invD;
        // Widen tFar to cover rounding error
        tFar *= 1 + 2 * gamma(3);
        if (tNear > t0) t0 = tNear;
        if (tFar < t1) t1 = tFar;
        if (t0 > t1) return false;
    }
    // Reject a box that the ray reaches only at infinite t
    if (t0 == Infinity) return false;
    return true;
}

}  // namespace lrt
