// Chapter 2's exercise calls (tests/calls/calls.h): the tests of ex-2.12,
// ex-2.13 and ex-2.14 reach CoordinateSystem(), the transformation of
// normals (alone or inside a SurfaceInteraction) and the union and
// intersection of boxes only through these.

#ifndef LRT_TESTS_CH02_EXERCISE_CALLS_H
#define LRT_TESTS_CH02_EXERCISE_CALLS_H

#include "lrt/core/interaction.h"
#include "lrt/core/transform.h"
#include "calls/calls.h"

#include <cstdint>

namespace lrt {

// The two vectors that CoordinateSystem() writes.
struct Frame {
    Vector3f v2, v3;
    LRT_FIELDS(v2, v3)
};

// A SurfaceInteraction as values. Its shape and primitive pointers travel as
// numbers: the transformation copies them and never follows them.
struct InteractionRecord {
    Point3f p;
    Float time;
    Vector3f pError, wo;
    Normal3f n;
    Point2f uv;
    Vector3f dpdu, dpdv;
    Normal3f dndu, dndv;
    Normal3f shadingN;
    Vector3f shadingDpdu, shadingDpdv;
    Normal3f shadingDndu, shadingDndv;
    uint64_t shape, primitive;
    int faceIndex;
    bool flipNormal;
    LRT_FIELDS(p, time, pError, wo, n, uv, dpdu, dpdv, dndu, dndv, shadingN,
               shadingDpdu, shadingDpdv, shadingDndu, shadingDndv, shape,
               primitive, faceIndex, flipNormal)

    static InteractionRecord Of(const SurfaceInteraction &si) {
        return {si.p,
                si.time,
                si.pError,
                si.wo,
                si.n,
                si.uv,
                si.dpdu,
                si.dpdv,
                si.dndu,
                si.dndv,
                si.shading.n,
                si.shading.dpdu,
                si.shading.dpdv,
                si.shading.dndu,
                si.shading.dndv,
                uint64_t(reinterpret_cast<uintptr_t>(si.shape)),
                uint64_t(reinterpret_cast<uintptr_t>(si.primitive)),
                si.faceIndex,
                si.flipNormal};
    }
    SurfaceInteraction ToInteraction() const {
        SurfaceInteraction si;
        si.p = p;
        si.time = time;
        si.pError = pError;
        si.wo = wo;
        si.n = n;
        si.uv = uv;
        si.dpdu = dpdu;
        si.dpdv = dpdv;
        si.dndu = dndu;
        si.dndv = dndv;
        si.shading.n = shadingN;
        si.shading.dpdu = shadingDpdu;
        si.shading.dpdv = shadingDpdv;
        si.shading.dndu = shadingDndu;
        si.shading.dndv = shadingDndv;
        si.shape = reinterpret_cast<const Shape *>(uintptr_t(shape));
        si.primitive =
            reinterpret_cast<const Primitive *>(uintptr_t(primitive));
        si.faceIndex = faceIndex;
        si.flipNormal = flipNormal;
        return si;
    }
};

namespace direct {

// CoordinateSystem(v1, &v2, &v3), with v2 and v3 holding the given values
// before the call (the function must overwrite both).
inline Frame CompleteFrame(Vector3f v1, Vector3f v2, Vector3f v3) {
    Frame f{v2, v3};
    CoordinateSystem(v1, &f.v2, &f.v3);
    return f;
}

// t(n) for a normal.
inline Normal3f NormalTransformed(Transform t, Normal3f n) { return t(n); }

// t(si): the interaction's normals are transformed as normals.
inline InteractionRecord InteractionTransformed(Transform t,
                                                InteractionRecord si) {
    return InteractionRecord::Of(t(si.ToInteraction()));
}

// Union() and Intersect() of two boxes, of Float and of int coordinates.
inline Bounds3f BoxUnion(Bounds3f a, Bounds3f b) { return Union(a, b); }
inline Bounds3i IntBoxUnion(Bounds3i a, Bounds3i b) { return Union(a, b); }
inline Bounds3f BoxIntersect(Bounds3f a, Bounds3f b) { return Intersect(a, b); }
inline Bounds3i IntBoxIntersect(Bounds3i a, Bounds3i b) {
    return Intersect(a, b);
}

// The same for rectangles, whose Union() and Intersect() are the same
// fragments.
inline Bounds2f RectUnion(Bounds2f a, Bounds2f b) { return Union(a, b); }
inline Bounds2f RectIntersect(Bounds2f a, Bounds2f b) { return Intersect(a, b); }

}  // namespace direct
}  // namespace lrt

LRT_EXERCISE_CALL(CompleteFrame)
LRT_EXERCISE_CALL(NormalTransformed)
LRT_EXERCISE_CALL(InteractionTransformed)
LRT_EXERCISE_CALL(BoxUnion)
LRT_EXERCISE_CALL(IntBoxUnion)
LRT_EXERCISE_CALL(BoxIntersect)
LRT_EXERCISE_CALL(IntBoxIntersect)
LRT_EXERCISE_CALL(RectUnion)
LRT_EXERCISE_CALL(RectIntersect)

namespace lrt {
namespace ex {

// The library's signatures, for the tests; ex::Apply(t, x) stands for t(x).
inline void CoordinateSystem(const Vector3f &v1, Vector3f *v2, Vector3f *v3) {
    Frame f = CompleteFrame(v1, *v2, *v3);
    *v2 = f.v2;
    *v3 = f.v3;
}
inline Normal3f Apply(const Transform &t, const Normal3f &n) {
    return NormalTransformed(t, n);
}
inline SurfaceInteraction Apply(const Transform &t,
                                const SurfaceInteraction &si) {
    return InteractionTransformed(t, InteractionRecord::Of(si))
        .ToInteraction();
}
inline Bounds3f Union(const Bounds3f &a, const Bounds3f &b) {
    return BoxUnion(a, b);
}
inline Bounds3i Union(const Bounds3i &a, const Bounds3i &b) {
    return IntBoxUnion(a, b);
}
inline Bounds3f Intersect(const Bounds3f &a, const Bounds3f &b) {
    return BoxIntersect(a, b);
}
inline Bounds3i Intersect(const Bounds3i &a, const Bounds3i &b) {
    return IntBoxIntersect(a, b);
}
inline Bounds2f Union(const Bounds2f &a, const Bounds2f &b) {
    return RectUnion(a, b);
}
inline Bounds2f Intersect(const Bounds2f &a, const Bounds2f &b) {
    return RectIntersect(a, b);
}

}  // namespace ex
}  // namespace lrt

#endif  // LRT_TESTS_CH02_EXERCISE_CALLS_H
