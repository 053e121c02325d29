// Exercise calls for the lrt library: the framework (core.h) and the
// encoding of the library's geometry (points, vectors, normals, boxes, rays,
// matrices and transforms), member by member, bit for bit. Included by each
// of the book's tests/chNN/exercise_calls.h.

#ifndef LRT_TESTS_CALLS_H
#define LRT_TESTS_CALLS_H

#include "lrt/core/transform.h"

#include "calls/core.h"

namespace lrt {
namespace calls {

template <typename T>
void Put(Writer &w, const Vector2<T> &v) { Put(w, v.x), Put(w, v.y); }
template <typename T>
void Get(Reader &r, Vector2<T> &v) { Get(r, v.x), Get(r, v.y); }
template <typename T>
void Put(Writer &w, const Point2<T> &v) { Put(w, v.x), Put(w, v.y); }
template <typename T>
void Get(Reader &r, Point2<T> &v) { Get(r, v.x), Get(r, v.y); }
template <typename T>
void Put(Writer &w, const Vector3<T> &v) {
    Put(w, v.x), Put(w, v.y), Put(w, v.z);
}
template <typename T>
void Get(Reader &r, Vector3<T> &v) { Get(r, v.x), Get(r, v.y), Get(r, v.z); }
template <typename T>
void Put(Writer &w, const Point3<T> &v) {
    Put(w, v.x), Put(w, v.y), Put(w, v.z);
}
template <typename T>
void Get(Reader &r, Point3<T> &v) { Get(r, v.x), Get(r, v.y), Get(r, v.z); }
template <typename T>
void Put(Writer &w, const Normal3<T> &v) {
    Put(w, v.x), Put(w, v.y), Put(w, v.z);
}
template <typename T>
void Get(Reader &r, Normal3<T> &v) { Get(r, v.x), Get(r, v.y), Get(r, v.z); }
template <typename T>
void Put(Writer &w, const Bounds3<T> &b) { Put(w, b.pMin), Put(w, b.pMax); }
template <typename T>
void Get(Reader &r, Bounds3<T> &b) { Get(r, b.pMin), Get(r, b.pMax); }
template <typename T>
void Put(Writer &w, const Bounds2<T> &b) { Put(w, b.pMin), Put(w, b.pMax); }
template <typename T>
void Get(Reader &r, Bounds2<T> &b) { Get(r, b.pMin), Get(r, b.pMax); }
inline void Put(Writer &w, const Ray &ray) {
    Put(w, ray.o), Put(w, ray.d), Put(w, ray.tMax), Put(w, ray.time);
}
inline void Get(Reader &r, Ray &ray) {
    Get(r, ray.o), Get(r, ray.d), Get(r, ray.tMax), Get(r, ray.time);
}
inline void Put(Writer &w, const Matrix4x4 &m) {
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) Put(w, m.m[i][j]);
}
inline void Get(Reader &r, Matrix4x4 &m) {
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) Get(r, m.m[i][j]);
}
inline void Put(Writer &w, const Transform &t) {
    Put(w, t.GetMatrix()), Put(w, t.GetInverseMatrix());
}
inline void Get(Reader &r, Transform &t) {
    Matrix4x4 m, mInv;
    Get(r, m), Get(r, mInv);
    t = Transform(m, mInv);
}

}  // namespace calls
}  // namespace lrt

#endif  // LRT_TESTS_CALLS_H
