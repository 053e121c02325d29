// lrt/core/transform.h: tangled from chapters/02-geometry.md. Edit the chapter, not this file.
#pragma once

// transform.h includes
#include "lrt/core/geometry.h"

#include <cmath>
#include <limits>
#include <stdexcept>

namespace lrt {

// Matrix4x4 Declarations
struct Matrix4x4 {
    // Matrix4x4 Public Methods
    Matrix4x4() {
        for (int i = 0; i < 4; ++i)
            for (int j = 0; j < 4; ++j)
                m[i][j] = (i == j) ? 1 : 0;
    }
    Matrix4x4(const Float mat[4][4]) {
        for (int i = 0; i < 4; ++i)
            for (int j = 0; j < 4; ++j)
                m[i][j] = mat[i][j];
    }
    Matrix4x4(Float t00, Float t01, Float t02, Float t03,
              Float t10, Float t11, Float t12, Float t13,
              Float t20, Float t21, Float t22, Float t23,
              Float t30, Float t31, Float t32, Float t33) {
        Float *row[4] = {m[0], m[1], m[2], m[3]};
        row[0][0] = t00; row[0][1] = t01; row[0][2] = t02; row[0][3] = t03;
        row[1][0] = t10; row[1][1] = t11; row[1][2] = t12; row[1][3] = t13;
        row[2][0] = t20; row[2][1] = t21; row[2][2] = t22; row[2][3] = t23;
        row[3][0] = t30; row[3][1] = t31; row[3][2] = t32; row[3][3] = t33;
    }
    bool operator==(const Matrix4x4 &m2) const {
        for (int i = 0; i < 4; ++i)
            for (int j = 0; j < 4; ++j)
                if (m[i][j] != m2.m[i][j]) return false;
        return true;
    }
    bool operator!=(const Matrix4x4 &m2) const { return !(*this == m2); }
    friend Matrix4x4 Transpose(const Matrix4x4 &m);
    static Matrix4x4 Mul(const Matrix4x4 &m1, const Matrix4x4 &m2) {
        Matrix4x4 r;
        for (int i = 0; i < 4; ++i)
            for (int j = 0; j < 4; ++j)
                r.m[i][j] = m1.m[i][0] * m2.m[0][j] + m1.m[i][1] * m2.m[1][j] +
                            m1.m[i][2] * m2.m[2][j] + m1.m[i][3] * m2.m[3][j];
        return r;
    }
    friend Matrix4x4 Inverse(const Matrix4x4 &m);
    Float m[4][4];
};

// Transform Declarations
class Transform {
  public:
    // Transform Public Methods
    Transform() {}
    Transform(const Float mat[4][4]) : m(mat), mInv(Inverse(m)) {}
    Transform(const Matrix4x4 &m) : m(m), mInv(Inverse(m)) {}
    Transform(const Matrix4x4 &m, const Matrix4x4 &mInv) : m(m), mInv(mInv) {}
    friend Transform Inverse(const Transform &t) {
        return Transform(t.mInv, t.m);
    }
    friend Transform Transpose(const Transform &t) {
        return Transform(Transpose(t.m), Transpose(t.mInv));
    }
    bool operator==(const Transform &t) const {
        return t.m == m && t.mInv == mInv;
    }
    bool operator!=(const Transform &t) const { return !(*this == t); }
    bool operator<(const Transform &t2) const {
        for (int i = 0; i < 4; ++i)
            for (int j = 0; j < 4; ++j) {
                if (m.m[i][j] < t2.m.m[i][j]) return true;
                if (m.m[i][j] > t2.m.m[i][j]) return false;
            }
        return false;
    }
    bool IsIdentity() const { return m == Matrix4x4(); }
    const Matrix4x4 &GetMatrix() const { return m; }
    const Matrix4x4 &GetInverseMatrix() const { return mInv; }
    bool HasScale() const {
        Float la2 = (*this)(Vector3f(1, 0, 0)).LengthSquared();
        Float lb2 = (*this)(Vector3f(0, 1, 0)).LengthSquared();
        Float lc2 = (*this)(Vector3f(0, 0, 1)).LengthSquared();
        auto notOne = [](Float l2) {
            return l2 < Float(0.999) || l2 > Float(1.001);
        };
        return notOne(la2) || notOne(lb2) || notOne(lc2);
    }
    template <typename T>
    Point3<T> operator()(const Point3<T> &p) const;
    template <typename T>
    Vector3<T> operator()(const Vector3<T> &v) const;
    template <typename T>
    Normal3<T> operator()(const Normal3<T> &n) const;
    Ray operator()(const Ray &r) const;
    Bounds3f operator()(const Bounds3f &b) const;
    Transform operator*(const Transform &t2) const;
    bool SwapsHandedness() const;
    template <typename T>
    Point3<T> operator()(const Point3<T> &p, Vector3<T> *pError) const;
    template <typename T>
    Point3<T> operator()(const Point3<T> &p, const Vector3<T> &pError,
                         Vector3<T> *pTransError) const;
    template <typename T>
    Vector3<T> operator()(const Vector3<T> &v, Vector3<T> *vTransError) const;
    template <typename T>
    Vector3<T> operator()(const Vector3<T> &v, const Vector3<T> &vError,
                          Vector3<T> *vTransError) const;
    Ray operator()(const Ray &r, Vector3f *oError, Vector3f *dError) const;
    bool IsAffine() const {
        return m.m[3][0] == 0 && m.m[3][1] == 0 && m.m[3][2] == 0 &&
               m.m[3][3] == 1;
    }
    SurfaceInteraction operator()(const SurfaceInteraction &si) const;

  private:
    // Transform Private Methods
    template <typename T>
    static Point3<T> DivideWithError(T xp, T yp, T zp, T wp, T wError,
                                     Vector3<T> *error);
    Matrix4x4 m, mInv;
};

// Transform Inline Method Definitions
template <typename T>
inline Point3<T> Transform::operator()(const Point3<T> &p) const {
    T x = p.x, y = p.y, z = p.z;
    // Compute transformed coordinates from point (x, y, z)
    T xp = (m.m[0][0] * x + m.m[0][1] * y) + (m.m[0][2] * z + m.m[0][3]);
    T yp = (m.m[1][0] * x + m.m[1][1] * y) + (m.m[1][2] * z + m.m[1][3]);
    T zp = (m.m[2][0] * x + m.m[2][1] * y) + (m.m[2][2] * z + m.m[2][3]);
    T wp = (m.m[3][0] * x + m.m[3][1] * y) + (m.m[3][2] * z + m.m[3][3]);
    if (wp == 1)
        return Point3<T>(xp, yp, zp);
    return Point3<T>(xp / wp, yp / wp, zp / wp);
}
template <typename T>
inline Vector3<T> Transform::operator()(const Vector3<T> &v) const {
    T x = v.x, y = v.y, z = v.z;
    return Vector3<T>(m.m[0][0] * x + m.m[0][1] * y + m.m[0][2] * z,
                      m.m[1][0] * x + m.m[1][1] * y + m.m[1][2] * z,
                      m.m[2][0] * x + m.m[2][1] * y + m.m[2][2] * z);
}
template <typename T>
inline Normal3<T> Transform::operator()(const Normal3<T> &n) const {
    // Transform n by the inverse transpose
    T x = n.x, y = n.y, z = n.z;
    return Normal3<T>(mInv.m[0][0] * x + mInv.m[1][0] * y + mInv.m[2][0] * z,
                      mInv.m[0][1] * x + mInv.m[1][1] * y + mInv.m[2][1] * z,
                      mInv.m[0][2] * x + mInv.m[1][2] * y + mInv.m[2][2] * z);
}
inline Ray Transform::operator()(const Ray &r) const {
    Vector3f oError, dError;
    return (*this)(r, &oError, &dError);
}
template <typename T>
inline Point3<T> Transform::operator()(const Point3<T> &p,
                                       Vector3<T> *pError) const {
    T x = p.x, y = p.y, z = p.z;
    // Compute transformed coordinates from point (x, y, z)
    T xp = (m.m[0][0] * x + m.m[0][1] * y) + (m.m[0][2] * z + m.m[0][3]);
    T yp = (m.m[1][0] * x + m.m[1][1] * y) + (m.m[1][2] * z + m.m[1][3]);
    T zp = (m.m[2][0] * x + m.m[2][1] * y) + (m.m[2][2] * z + m.m[2][3]);
    T wp = (m.m[3][0] * x + m.m[3][1] * y) + (m.m[3][2] * z + m.m[3][3]);
    // Compute absolute error for transformed point
    T xAbsSum = (std::abs(m.m[0][0] * x) + std::abs(m.m[0][1] * y) +
                 std::abs(m.m[0][2] * z) + std::abs(m.m[0][3]));
    T yAbsSum = (std::abs(m.m[1][0] * x) + std::abs(m.m[1][1] * y) +
                 std::abs(m.m[1][2] * z) + std::abs(m.m[1][3]));
    T zAbsSum = (std::abs(m.m[2][0] * x) + std::abs(m.m[2][1] * y) +
                 std::abs(m.m[2][2] * z) + std::abs(m.m[2][3]));
    *pError = Vector3<T>(gamma(3) * xAbsSum, gamma(3) * yAbsSum,
                         gamma(3) * zAbsSum);
    if (IsAffine())
        return Point3<T>(xp, yp, zp);
    T wError = gamma(3) * (std::abs(m.m[3][0] * x) + std::abs(m.m[3][1] * y) +
                           std::abs(m.m[3][2] * z) + std::abs(m.m[3][3]));
    return DivideWithError(xp, yp, zp, wp, wError, pError);
}
template <typename T>
inline Point3<T> Transform::DivideWithError(T xp, T yp, T zp, T wp,
                                            T wError, Vector3<T> *error) {
    Point3<T> q(xp / wp, yp / wp, zp / wp);
    T denom = std::abs(wp) - wError;
    if (!(denom > 0)) {
        T inf = std::numeric_limits<T>::infinity();
        *error = Vector3<T>(inf, inf, inf);
        return q;
    }
    T g = 1 + gamma(1);
    *error = Vector3<T>(
        (error->x + g * std::abs(q.x) * wError) / denom +
            gamma(1) * std::abs(q.x),
        (error->y + g * std::abs(q.y) * wError) / denom +
            gamma(1) * std::abs(q.y),
        (error->z + g * std::abs(q.z) * wError) / denom +
            gamma(1) * std::abs(q.z));
    return q;
}
template <typename T>
inline Point3<T> Transform::operator()(const Point3<T> &p,
                                       const Vector3<T> &pError,
                                       Vector3<T> *pTransError) const {
    T x = p.x, y = p.y, z = p.z;
    // Compute transformed coordinates from point (x, y, z)
    T xp = (m.m[0][0] * x + m.m[0][1] * y) + (m.m[0][2] * z + m.m[0][3]);
    T yp = (m.m[1][0] * x + m.m[1][1] * y) + (m.m[1][2] * z + m.m[1][3]);
    T zp = (m.m[2][0] * x + m.m[2][1] * y) + (m.m[2][2] * z + m.m[2][3]);
    T wp = (m.m[3][0] * x + m.m[3][1] * y) + (m.m[3][2] * z + m.m[3][3]);
    // Compute absolute error for transformed point
    T xAbsSum = (std::abs(m.m[0][0] * x) + std::abs(m.m[0][1] * y) +
                 std::abs(m.m[0][2] * z) + std::abs(m.m[0][3]));
    T yAbsSum = (std::abs(m.m[1][0] * x) + std::abs(m.m[1][1] * y) +
                 std::abs(m.m[1][2] * z) + std::abs(m.m[1][3]));
    T zAbsSum = (std::abs(m.m[2][0] * x) + std::abs(m.m[2][1] * y) +
                 std::abs(m.m[2][2] * z) + std::abs(m.m[2][3]));
    T g = gamma(3) + 1;
    *pTransError = Vector3<T>(
        gamma(3) * xAbsSum + g * (std::abs(m.m[0][0]) * pError.x +
                                  std::abs(m.m[0][1]) * pError.y +
                                  std::abs(m.m[0][2]) * pError.z),
        gamma(3) * yAbsSum + g * (std::abs(m.m[1][0]) * pError.x +
                                  std::abs(m.m[1][1]) * pError.y +
                                  std::abs(m.m[1][2]) * pError.z),
        gamma(3) * zAbsSum + g * (std::abs(m.m[2][0]) * pError.x +
                                  std::abs(m.m[2][1]) * pError.y +
                                  std::abs(m.m[2][2]) * pError.z));
    if (IsAffine())
        return Point3<T>(xp, yp, zp);
    T wError = gamma(3) * (std::abs(m.m[3][0] * x) + std::abs(m.m[3][1] * y) +
                           std::abs(m.m[3][2] * z) + std::abs(m.m[3][3])) +
               g * (std::abs(m.m[3][0]) * pError.x +
                    std::abs(m.m[3][1]) * pError.y +
                    std::abs(m.m[3][2]) * pError.z);
    return DivideWithError(xp, yp, zp, wp, wError, pTransError);
}
template <typename T>
inline Vector3<T> Transform::operator()(const Vector3<T> &v,
                                        Vector3<T> *vTransError) const {
    T x = v.x, y = v.y, z = v.z;
    *vTransError = Vector3<T>(
        gamma(3) * (std::abs(m.m[0][0] * x) + std::abs(m.m[0][1] * y) +
                    std::abs(m.m[0][2] * z)),
        gamma(3) * (std::abs(m.m[1][0] * x) + std::abs(m.m[1][1] * y) +
                    std::abs(m.m[1][2] * z)),
        gamma(3) * (std::abs(m.m[2][0] * x) + std::abs(m.m[2][1] * y) +
                    std::abs(m.m[2][2] * z)));
    return (*this)(v);
}

template <typename T>
inline Vector3<T> Transform::operator()(const Vector3<T> &v,
                                        const Vector3<T> &vError,
                                        Vector3<T> *vTransError) const {
    T x = v.x, y = v.y, z = v.z;
    T g = gamma(3) + 1;
    *vTransError = Vector3<T>(
        g * (std::abs(m.m[0][0]) * vError.x + std::abs(m.m[0][1]) * vError.y +
             std::abs(m.m[0][2]) * vError.z) +
            gamma(3) * (std::abs(m.m[0][0] * x) + std::abs(m.m[0][1] * y) +
                        std::abs(m.m[0][2] * z)),
        g * (std::abs(m.m[1][0]) * vError.x + std::abs(m.m[1][1]) * vError.y +
             std::abs(m.m[1][2]) * vError.z) +
            gamma(3) * (std::abs(m.m[1][0] * x) + std::abs(m.m[1][1] * y) +
                        std::abs(m.m[1][2] * z)),
        g * (std::abs(m.m[2][0]) * vError.x + std::abs(m.m[2][1]) * vError.y +
             std::abs(m.m[2][2]) * vError.z) +
            gamma(3) * (std::abs(m.m[2][0] * x) + std::abs(m.m[2][1] * y) +
                        std::abs(m.m[2][2] * z)));
    return (*this)(v);
}
inline Ray Transform::operator()(const Ray &r, Vector3f *oError,
                                 Vector3f *dError) const {
    Point3f o = (*this)(r.o, oError);
    Vector3f d = (*this)(r.d, dError);
    // Offset ray origin to edge of error bounds and compute tMax
    Float lengthSquared = d.LengthSquared();
    Float tMax = r.tMax;
    if (lengthSquared > 0) {
        Float dt = Dot(Abs(d), *oError) / lengthSquared;
        o += d * dt;
        tMax -= dt;
    }
    return Ray(o, d, tMax, r.time);
}

// Transform Function Declarations
Transform Translate(const Vector3f &delta);
Transform Scale(Float x, Float y, Float z);
Transform RotateX(Float theta);
Transform RotateY(Float theta);
Transform RotateZ(Float theta);
Transform Rotate(Float theta, const Vector3f &axis);
Transform LookAt(const Point3f &pos, const Point3f &look,
                 const Vector3f &up);
Transform Orthographic(Float zNear, Float zFar);
Transform Perspective(Float fov, Float zNear, Float zFar);

}  // namespace lrt
