// Chapter 5's exercise calls (tests/calls/calls.h): the tests of ex-5.9,
// ex-5.10 and ex-5.11 reach Bounds3::IntersectP only through these.

#ifndef LRT_TESTS_CH05_EXERCISE_CALLS_H
#define LRT_TESTS_CH05_EXERCISE_CALLS_H

#include "lrt/core/slabtest.h"
#include "calls/calls.h"

#include <array>

namespace lrt {

struct SlabHit {
    bool hit;
    Float t0, t1;
    LRT_FIELDS(hit, t0, t1)
};

namespace direct {

// Bounds3::IntersectP(ray, hitt0, hitt1), each output asked for or not; an
// output that the test does not write keeps the value it came with.
inline SlabHit BoxIntersectP(Bounds3f b, Ray r, bool want0, bool want1,
                             Float t0, Float t1) {
    SlabHit h{false, t0, t1};
    h.hit = b.IntersectP(r, want0 ? &h.t0 : nullptr, want1 ? &h.t1 : nullptr);
    return h;
}

// The form for BVH traversal, with the reciprocal direction and its signs
// precomputed by the caller.
inline bool BoxIntersectPWithInverse(Bounds3f b, Ray r, Vector3f invDir,
                                     std::array<int, 3> dirIsNeg) {
    return b.IntersectP(r, invDir, dirIsNeg.data());
}

}  // namespace direct
}  // namespace lrt

LRT_EXERCISE_CALL(BoxIntersectP)
LRT_EXERCISE_CALL(BoxIntersectPWithInverse)

namespace lrt {
namespace ex {

// The library's signatures, for the tests.
inline bool IntersectP(const Bounds3f &b, const Ray &r, Float *hitt0 = nullptr,
                       Float *hitt1 = nullptr) {
    SlabHit h = BoxIntersectP(b, r, hitt0 != nullptr, hitt1 != nullptr,
                              hitt0 ? *hitt0 : 0, hitt1 ? *hitt1 : 0);
    if (hitt0) *hitt0 = h.t0;
    if (hitt1) *hitt1 = h.t1;
    return h.hit;
}
inline bool IntersectP(const Bounds3f &b, const Ray &r, const Vector3f &invDir,
                       const int dirIsNeg[3]) {
    return BoxIntersectPWithInverse(
        b, r, invDir, std::array<int, 3>{dirIsNeg[0], dirIsNeg[1], dirIsNeg[2]});
}

}  // namespace ex
}  // namespace lrt

#endif  // LRT_TESTS_CH05_EXERCISE_CALLS_H
