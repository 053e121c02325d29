// lrt/core/transform.cpp: tangled from chapters/02-geometry.md. Edit the chapter, not this file.
// transform.cpp includes
#include "lrt/core/transform.h"
#include "lrt/core/interaction.h"

#include <cmath>
#include <stdexcept>

namespace lrt {

// Matrix4x4 Method Definitions
Matrix4x4 Transpose(const Matrix4x4 &m) {
    Matrix4x4 r;
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j)
            r.m[i][j] = m.m[j][i];
    return r;
}
Matrix4x4 Inverse(const Matrix4x4 &m) {
    // Reject matrices with non-finite entries
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j)
            if (!std::isfinite(m.m[i][j]))
                throw std::domain_error(
                    "Matrix4x4::Inverse: matrix has a non-finite entry");
    Float a[4][4], e[4][4];
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) {
            a[i][j] = m.m[i][j];
            e[i][j] = (i == j) ? 1 : 0;
        }
    bool rowUsed[4] = {false, false, false, false};
    bool colUsed[4] = {false, false, false, false};
    int pivotColumn[4] = {0, 0, 0, 0};
    for (int step = 0; step < 4; ++step) {
        // Choose the largest remaining entry as pivot a[pr][pc]
        int pr = -1, pc = -1;
        Float big = 0;
        for (int i = 0; i < 4; ++i) {
            if (rowUsed[i]) continue;
            for (int j = 0; j < 4; ++j) {
                if (colUsed[j]) continue;
                if (std::abs(a[i][j]) > big) {
                    big = std::abs(a[i][j]);
                    pr = i;
                    pc = j;
                }
            }
        }
        if (pr < 0)
            throw std::domain_error("Matrix4x4::Inverse: singular matrix");
        rowUsed[pr] = colUsed[pc] = true;
        pivotColumn[pr] = pc;
        // Eliminate column pc from all other rows
        for (int i = 0; i < 4; ++i) {
            if (i == pr || a[i][pc] == 0) continue;
            Float f = a[i][pc] / a[pr][pc];
            for (int j = 0; j < 4; ++j) {
                a[i][j] -= f * a[pr][j];
                e[i][j] -= f * e[pr][j];
            }
            a[i][pc] = 0;
        }
        // Divide the pivot row by the pivot
        Float pivot = a[pr][pc];
        for (int j = 0; j < 4; ++j) {
            a[pr][j] /= pivot;
            e[pr][j] /= pivot;
        }
        a[pr][pc] = 1;
    }
    // Permute the rows of e into the inverse and check it
    Matrix4x4 inv;
    for (int r = 0; r < 4; ++r)
        for (int j = 0; j < 4; ++j) {
            inv.m[pivotColumn[r]][j] = e[r][j];
            if (!std::isfinite(e[r][j]))
                throw std::domain_error("Matrix4x4::Inverse: singular matrix");
        }
    return inv;
}

// Transform Method Definitions
Bounds3f Transform::operator()(const Bounds3f &b) const {
    if (b.IsEmpty()) return Bounds3f();
    const Transform &M = *this;
    Bounds3f ret(M(b.Corner(0)));
    for (int i = 1; i < 8; ++i)
        ret = Union(ret, M(b.Corner(i)));
    return ret;
}
Transform Transform::operator*(const Transform &t2) const {
    return Transform(Matrix4x4::Mul(m, t2.m), Matrix4x4::Mul(t2.mInv, mInv));
}
bool Transform::SwapsHandedness() const {
    Float det =
        m.m[0][0] * (m.m[1][1] * m.m[2][2] - m.m[1][2] * m.m[2][1]) -
        m.m[0][1] * (m.m[1][0] * m.m[2][2] - m.m[1][2] * m.m[2][0]) +
        m.m[0][2] * (m.m[1][0] * m.m[2][1] - m.m[1][1] * m.m[2][0]);
    return det < 0;
}
SurfaceInteraction Transform::operator()(const SurfaceInteraction &si) const {
    const Transform &t = *this;
    SurfaceInteraction ret;
    ret.p = t(si.p, si.pError, &ret.pError);
    ret.time = si.time;
    ret.wo = Interaction::NormalizeDirection(t(si.wo));
    ret.n = Normalize(t(si.n));
    ret.uv = si.uv;
    ret.dpdu = t(si.dpdu);
    ret.dpdv = t(si.dpdv);
    ret.dndu = t(si.dndu);
    ret.dndv = t(si.dndv);
    ret.shape = si.shape;
    ret.shading.n = Normalize(t(si.shading.n));
    ret.shading.dpdu = t(si.shading.dpdu);
    ret.shading.dpdv = t(si.shading.dpdv);
    ret.shading.dndu = t(si.shading.dndu);
    ret.shading.dndv = t(si.shading.dndv);
    ret.primitive = si.primitive;
    ret.faceIndex = si.faceIndex;
    ret.flipNormal = si.flipNormal ^ SwapsHandedness();
    ret.shading.n = Faceforward(ret.shading.n, ret.n);
    return ret;
}

// Transform Function Definitions
Transform Translate(const Vector3f &delta) {
    Matrix4x4 m(1, 0, 0, delta.x,
                0, 1, 0, delta.y,
                0, 0, 1, delta.z,
                0, 0, 0, 1);
    Matrix4x4 minv(1, 0, 0, -delta.x,
                   0, 1, 0, -delta.y,
                   0, 0, 1, -delta.z,
                   0, 0, 0, 1);
    return Transform(m, minv);
}
Transform Scale(Float x, Float y, Float z) {
    if (x == 0 || y == 0 || z == 0)
        throw std::domain_error("Scale: zero scale factor");
    Matrix4x4 m(x, 0, 0, 0,
                0, y, 0, 0,
                0, 0, z, 0,
                0, 0, 0, 1);
    Matrix4x4 minv(1 / x, 0, 0, 0,
                   0, 1 / y, 0, 0,
                   0, 0, 1 / z, 0,
                   0, 0, 0, 1);
    return Transform(m, minv);
}
Transform RotateX(Float theta) {
    Float sinTheta = std::sin(Radians(theta));
    Float cosTheta = std::cos(Radians(theta));
    Matrix4x4 m(1, 0, 0, 0,
                0, cosTheta, -sinTheta, 0,
                0, sinTheta, cosTheta, 0,
                0, 0, 0, 1);
    return Transform(m, Transpose(m));
}
Transform RotateY(Float theta) {
    Float sinTheta = std::sin(Radians(theta));
    Float cosTheta = std::cos(Radians(theta));
    Matrix4x4 m(cosTheta, 0, sinTheta, 0,
                0, 1, 0, 0,
                -sinTheta, 0, cosTheta, 0,
                0, 0, 0, 1);
    return Transform(m, Transpose(m));
}
Transform RotateZ(Float theta) {
    Float sinTheta = std::sin(Radians(theta));
    Float cosTheta = std::cos(Radians(theta));
    Matrix4x4 m(cosTheta, -sinTheta, 0, 0,
                sinTheta, cosTheta, 0, 0,
                0, 0, 1, 0,
                0, 0, 0, 1);
    return Transform(m, Transpose(m));
}
Transform Rotate(Float theta, const Vector3f &axis) {
    Float len2 = axis.LengthSquared();
    if (!(len2 > 0) || !std::isfinite(len2))
        throw std::domain_error("Rotate: axis must be nonzero and finite");
    Vector3f a = Normalize(axis);
    Float sinTheta = std::sin(Radians(theta));
    Float cosTheta = std::cos(Radians(theta));
    Float c1 = 1 - cosTheta;
    Matrix4x4 m;
    m.m[0][0] = a.x * a.x + (1 - a.x * a.x) * cosTheta;
    m.m[0][1] = a.x * a.y * c1 - a.z * sinTheta;
    m.m[0][2] = a.x * a.z * c1 + a.y * sinTheta;
    m.m[1][0] = a.x * a.y * c1 + a.z * sinTheta;
    m.m[1][1] = a.y * a.y + (1 - a.y * a.y) * cosTheta;
    m.m[1][2] = a.y * a.z * c1 - a.x * sinTheta;
    m.m[2][0] = a.x * a.z * c1 - a.y * sinTheta;
    m.m[2][1] = a.y * a.z * c1 + a.x * sinTheta;
    m.m[2][2] = a.z * a.z + (1 - a.z * a.z) * cosTheta;
    return Transform(m, Transpose(m));
}
Transform LookAt(const Point3f &pos, const Point3f &look,
                 const Vector3f &up) {
    Vector3f dir = look - pos;
    if (dir.LengthSquared() == 0)
        throw std::domain_error("LookAt: eye and look-at points coincide");
    if (up.LengthSquared() == 0)
        throw std::domain_error("LookAt: up vector is zero");
    dir = Normalize(dir);
    Vector3f right = Cross(Normalize(up), dir);
    if (!(right.LengthSquared() > 0))
        throw std::domain_error(
            "LookAt: up vector and viewing direction are parallel");
    right = Normalize(right);
    right = Normalize(right - Dot(right, dir) * dir);
    Vector3f newUp = Cross(dir, right);
    Matrix4x4 cameraToWorld(right.x, newUp.x, dir.x, pos.x,
                            right.y, newUp.y, dir.y, pos.y,
                            right.z, newUp.z, dir.z, pos.z,
                            0, 0, 0, 1);
    return Transform(Inverse(cameraToWorld), cameraToWorld);
}
Transform Orthographic(Float zNear, Float zFar) {
    if (!(zFar > zNear) || !std::isfinite(zFar - zNear))
        throw std::domain_error("Orthographic: need finite zNear < zFar");
    return Scale(1, 1, 1 / (zFar - zNear)) *
           Translate(Vector3f(0, 0, -zNear));
}
Transform Perspective(Float fov, Float n, Float f) {
    if (!(fov > 0 && fov < 180))
        throw std::domain_error(
            "Perspective: field of view must be in (0, 180) degrees");
    if (!(n > 0 && f > n) || !std::isfinite(f))
        throw std::domain_error("Perspective: need 0 < zNear < zFar");
    Matrix4x4 persp(1, 0, 0, 0,
                    0, 1, 0, 0,
                    0, 0, f / (f - n), -f * n / (f - n),
                    0, 0, 1, 0);
    Float invTanAng = 1 / std::tan(Radians(fov) / 2);
    return Scale(invTanAng, invTanAng, 1) * Transform(persp);
}

}  // namespace lrt
