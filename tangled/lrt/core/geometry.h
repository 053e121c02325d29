// lrt/core/geometry.h: tangled from chapters/02-geometry.md. Edit the chapter, not this file.
#pragma once

// geometry.h includes
#include <algorithm>
#include <cmath>
#include <limits>
#include <ostream>
#include <stdexcept>

#include "lrt/core/base.h"

namespace lrt {

// Geometry Forward Declarations
template <typename T> class Vector2;
template <typename T> class Vector3;
template <typename T> class Point2;
template <typename T> class Point3;
template <typename T> class Normal3;
template <typename T> class Bounds2;
template <typename T> class Bounds3;
class Ray;
// Vector Declarations
template <typename T>
class Vector3 {
  public:
    // Vector3 Public Methods
    Vector3() : x(0), y(0), z(0) {}
    Vector3(T x, T y, T z) : x(x), y(y), z(z) {}
    bool HasNaNs() const {
        return std::isnan(x) || std::isnan(y) || std::isnan(z);
    }
    T operator[](int i) const {
        if (i == 0) return x;
        if (i == 1) return y;
        if (i == 2) return z;
        throw std::out_of_range("Vector3::operator[]: index out of range");
    }
    T &operator[](int i) {
        if (i == 0) return x;
        if (i == 1) return y;
        if (i == 2) return z;
        throw std::out_of_range("Vector3::operator[]: index out of range");
    }
    Vector3<T> operator+(const Vector3<T> &v) const {
        return Vector3<T>(x + v.x, y + v.y, z + v.z);
    }
    Vector3<T> &operator+=(const Vector3<T> &v) {
        x += v.x;
        y += v.y;
        z += v.z;
        return *this;
    }
    Vector3<T> operator-(const Vector3<T> &v) const {
        return Vector3<T>(x - v.x, y - v.y, z - v.z);
    }
    Vector3<T> &operator-=(const Vector3<T> &v) {
        x -= v.x;
        y -= v.y;
        z -= v.z;
        return *this;
    }
    bool operator==(const Vector3<T> &v) const {
        return x == v.x && y == v.y && z == v.z;
    }
    bool operator!=(const Vector3<T> &v) const { return !(*this == v); }
    template <typename U>
    Vector3<T> operator*(U s) const {
        return Vector3<T>(s * x, s * y, s * z);
    }
    template <typename U>
    Vector3<T> &operator*=(U s) {
        x *= s;
        y *= s;
        z *= s;
        return *this;
    }
    Vector3<T> operator-() const { return Vector3<T>(-x, -y, -z); }
    template <typename U>
    Vector3<T> operator/(U f) const {
        Float inv = Float(1) / f;
        return Vector3<T>(x * inv, y * inv, z * inv);
    }
    template <typename U>
    Vector3<T> &operator/=(U f) {
        Float inv = Float(1) / f;
        x *= inv;
        y *= inv;
        z *= inv;
        return *this;
    }
    Float LengthSquared() const { return x * x + y * y + z * z; }
    Float Length() const { return std::sqrt(LengthSquared()); }
    explicit Vector3(const Point3<T> &p) : x(p.x), y(p.y), z(p.z) {}
    explicit Vector3(const Normal3<T> &n) : x(n.x), y(n.y), z(n.z) {}
    // Vector3 Public Data
    T x, y, z;
};

typedef Vector3<Float> Vector3f;
typedef Vector3<int> Vector3i;
template <typename T>
class Vector2 {
  public:
    // Vector2 Public Methods
    Vector2() : x(0), y(0) {}
    Vector2(T x, T y) : x(x), y(y) {}
    bool HasNaNs() const { return std::isnan(x) || std::isnan(y); }
    T operator[](int i) const {
        if (i == 0) return x;
        if (i == 1) return y;
        throw std::out_of_range("Vector2::operator[]: index out of range");
    }
    T &operator[](int i) {
        if (i == 0) return x;
        if (i == 1) return y;
        throw std::out_of_range("Vector2::operator[]: index out of range");
    }
    Vector2<T> operator+(const Vector2<T> &v) const {
        return Vector2<T>(x + v.x, y + v.y);
    }
    Vector2<T> &operator+=(const Vector2<T> &v) {
        x += v.x;
        y += v.y;
        return *this;
    }
    Vector2<T> operator-(const Vector2<T> &v) const {
        return Vector2<T>(x - v.x, y - v.y);
    }
    Vector2<T> &operator-=(const Vector2<T> &v) {
        x -= v.x;
        y -= v.y;
        return *this;
    }
    bool operator==(const Vector2<T> &v) const { return x == v.x && y == v.y; }
    bool operator!=(const Vector2<T> &v) const { return !(*this == v); }
    template <typename U>
    Vector2<T> operator*(U s) const {
        return Vector2<T>(s * x, s * y);
    }
    template <typename U>
    Vector2<T> &operator*=(U s) {
        x *= s;
        y *= s;
        return *this;
    }
    template <typename U>
    Vector2<T> operator/(U f) const {
        Float inv = Float(1) / f;
        return Vector2<T>(x * inv, y * inv);
    }
    template <typename U>
    Vector2<T> &operator/=(U f) {
        Float inv = Float(1) / f;
        x *= inv;
        y *= inv;
        return *this;
    }
    Vector2<T> operator-() const { return Vector2<T>(-x, -y); }
    Float LengthSquared() const { return x * x + y * y; }
    Float Length() const { return std::sqrt(LengthSquared()); }
    explicit Vector2(const Point2<T> &p) : x(p.x), y(p.y) {}
    explicit Vector2(const Point3<T> &p) : x(p.x), y(p.y) {}
    T x, y;
};

typedef Vector2<Float> Vector2f;
typedef Vector2<int> Vector2i;
// Point Declarations
template <typename T>
class Point3 {
  public:
    // Point3 Public Methods
    Point3() : x(0), y(0), z(0) {}
    Point3(T x, T y, T z) : x(x), y(y), z(z) {}
    bool HasNaNs() const {
        return std::isnan(x) || std::isnan(y) || std::isnan(z);
    }
    T operator[](int i) const {
        if (i == 0) return x;
        if (i == 1) return y;
        if (i == 2) return z;
        throw std::out_of_range("Point3::operator[]: index out of range");
    }
    T &operator[](int i) {
        if (i == 0) return x;
        if (i == 1) return y;
        if (i == 2) return z;
        throw std::out_of_range("Point3::operator[]: index out of range");
    }
    bool operator==(const Point3<T> &p) const {
        return x == p.x && y == p.y && z == p.z;
    }
    bool operator!=(const Point3<T> &p) const { return !(*this == p); }
    template <typename U>
    explicit Point3(const Point3<U> &p) : x(T(p.x)), y(T(p.y)), z(T(p.z)) {}
    template <typename U>
    explicit operator Vector3<U>() const {
        return Vector3<U>(U(x), U(y), U(z));
    }
    template <typename U>
    explicit Point3(const Vector3<U> &v) : x(T(v.x)), y(T(v.y)), z(T(v.z)) {}
    Point3<T> operator+(const Vector3<T> &v) const {
        return Point3<T>(x + v.x, y + v.y, z + v.z);
    }
    Point3<T> &operator+=(const Vector3<T> &v) {
        x += v.x;
        y += v.y;
        z += v.z;
        return *this;
    }
    Vector3<T> operator-(const Point3<T> &p) const {
        return Vector3<T>(x - p.x, y - p.y, z - p.z);
    }
    Point3<T> operator-(const Vector3<T> &v) const {
        return Point3<T>(x - v.x, y - v.y, z - v.z);
    }
    Point3<T> &operator-=(const Vector3<T> &v) {
        x -= v.x;
        y -= v.y;
        z -= v.z;
        return *this;
    }
    Point3<T> operator+(const Point3<T> &p) const {
        return Point3<T>(x + p.x, y + p.y, z + p.z);
    }
    Point3<T> &operator+=(const Point3<T> &p) {
        x += p.x;
        y += p.y;
        z += p.z;
        return *this;
    }
    template <typename U>
    Point3<T> operator*(U f) const {
        return Point3<T>(f * x, f * y, f * z);
    }
    template <typename U>
    Point3<T> &operator*=(U f) {
        x *= f;
        y *= f;
        z *= f;
        return *this;
    }
    template <typename U>
    Point3<T> operator/(U f) const {
        Float inv = Float(1) / f;
        return Point3<T>(inv * x, inv * y, inv * z);
    }
    template <typename U>
    Point3<T> &operator/=(U f) {
        Float inv = Float(1) / f;
        x *= inv;
        y *= inv;
        z *= inv;
        return *this;
    }
    Point3<T> operator-() const { return Point3<T>(-x, -y, -z); }
    // Point3 Public Data
    T x, y, z;
};

typedef Point3<Float> Point3f;
typedef Point3<int> Point3i;
template <typename T>
class Point2 {
  public:
    // Point2 Public Methods
    Point2() : x(0), y(0) {}
    Point2(T x, T y) : x(x), y(y) {}
    explicit Point2(const Point3<T> &p) : x(p.x), y(p.y) {}
    template <typename U>
    explicit Point2(const Point2<U> &p) : x(T(p.x)), y(T(p.y)) {}
    template <typename U>
    explicit Point2(const Vector2<U> &v) : x(T(v.x)), y(T(v.y)) {}
    template <typename U>
    explicit operator Vector2<U>() const {
        return Vector2<U>(U(x), U(y));
    }
    bool HasNaNs() const { return std::isnan(x) || std::isnan(y); }
    T operator[](int i) const {
        if (i == 0) return x;
        if (i == 1) return y;
        throw std::out_of_range("Point2::operator[]: index out of range");
    }
    T &operator[](int i) {
        if (i == 0) return x;
        if (i == 1) return y;
        throw std::out_of_range("Point2::operator[]: index out of range");
    }
    bool operator==(const Point2<T> &p) const { return x == p.x && y == p.y; }
    bool operator!=(const Point2<T> &p) const { return !(*this == p); }
    Point2<T> operator+(const Vector2<T> &v) const {
        return Point2<T>(x + v.x, y + v.y);
    }
    Point2<T> &operator+=(const Vector2<T> &v) {
        x += v.x;
        y += v.y;
        return *this;
    }
    Vector2<T> operator-(const Point2<T> &p) const {
        return Vector2<T>(x - p.x, y - p.y);
    }
    Point2<T> operator-(const Vector2<T> &v) const {
        return Point2<T>(x - v.x, y - v.y);
    }
    Point2<T> &operator-=(const Vector2<T> &v) {
        x -= v.x;
        y -= v.y;
        return *this;
    }
    Point2<T> operator+(const Point2<T> &p) const {
        return Point2<T>(x + p.x, y + p.y);
    }
    Point2<T> &operator+=(const Point2<T> &p) {
        x += p.x;
        y += p.y;
        return *this;
    }
    template <typename U>
    Point2<T> operator*(U f) const {
        return Point2<T>(f * x, f * y);
    }
    template <typename U>
    Point2<T> &operator*=(U f) {
        x *= f;
        y *= f;
        return *this;
    }
    template <typename U>
    Point2<T> operator/(U f) const {
        Float inv = Float(1) / f;
        return Point2<T>(inv * x, inv * y);
    }
    template <typename U>
    Point2<T> &operator/=(U f) {
        Float inv = Float(1) / f;
        x *= inv;
        y *= inv;
        return *this;
    }
    Point2<T> operator-() const { return Point2<T>(-x, -y); }
    T x, y;
};

typedef Point2<Float> Point2f;
typedef Point2<int> Point2i;
// Normal Declarations
template <typename T>
class Normal3 {
  public:
    // Normal3 Public Methods
    Normal3() : x(0), y(0), z(0) {}
    Normal3(T x, T y, T z) : x(x), y(y), z(z) {}
    bool HasNaNs() const {
        return std::isnan(x) || std::isnan(y) || std::isnan(z);
    }
    T operator[](int i) const {
        if (i == 0) return x;
        if (i == 1) return y;
        if (i == 2) return z;
        throw std::out_of_range("Normal3::operator[]: index out of range");
    }
    T &operator[](int i) {
        if (i == 0) return x;
        if (i == 1) return y;
        if (i == 2) return z;
        throw std::out_of_range("Normal3::operator[]: index out of range");
    }
    bool operator==(const Normal3<T> &n) const {
        return x == n.x && y == n.y && z == n.z;
    }
    bool operator!=(const Normal3<T> &n) const { return !(*this == n); }
    Float LengthSquared() const { return x * x + y * y + z * z; }
    Float Length() const { return std::sqrt(LengthSquared()); }
    Normal3<T> operator+(const Normal3<T> &n) const {
        return Normal3<T>(x + n.x, y + n.y, z + n.z);
    }
    Normal3<T> &operator+=(const Normal3<T> &n) {
        x += n.x;
        y += n.y;
        z += n.z;
        return *this;
    }
    Normal3<T> operator-(const Normal3<T> &n) const {
        return Normal3<T>(x - n.x, y - n.y, z - n.z);
    }
    Normal3<T> &operator-=(const Normal3<T> &n) {
        x -= n.x;
        y -= n.y;
        z -= n.z;
        return *this;
    }
    template <typename U>
    Normal3<T> operator*(U f) const {
        return Normal3<T>(f * x, f * y, f * z);
    }
    template <typename U>
    Normal3<T> &operator*=(U f) {
        x *= f;
        y *= f;
        z *= f;
        return *this;
    }
    template <typename U>
    Normal3<T> operator/(U f) const {
        Float inv = Float(1) / f;
        return Normal3<T>(x * inv, y * inv, z * inv);
    }
    template <typename U>
    Normal3<T> &operator/=(U f) {
        Float inv = Float(1) / f;
        x *= inv;
        y *= inv;
        z *= inv;
        return *this;
    }
    Normal3<T> operator-() const { return Normal3<T>(-x, -y, -z); }
    explicit Normal3(const Vector3<T> &v) : x(v.x), y(v.y), z(v.z) {}
    T x, y, z;
};

typedef Normal3<Float> Normal3f;
// Ray Declarations
class Ray {
  public:
    // Ray Public Methods
    Ray() : tMax(Infinity), time(0) {}
    Ray(const Point3f &o, const Vector3f &d, Float tMax = Infinity,
        Float time = 0.f)
        : o(o), d(d), tMax(tMax), time(time) {}
    Point3f operator()(Float t) const { return o + d * t; }
    bool HasNaNs() const {
        return o.HasNaNs() || d.HasNaNs() || std::isnan(tMax);
    }
    // Ray Public Data
    Point3f o;
    Vector3f d;
    mutable Float tMax;
    Float time;
};
// Bounds Declarations
template <typename T>
class Bounds3 {
  public:
    // Bounds3 Public Methods
    Bounds3() {
        T minNum = std::numeric_limits<T>::lowest();
        T maxNum = std::numeric_limits<T>::max();
        pMin = Point3<T>(maxNum, maxNum, maxNum);
        pMax = Point3<T>(minNum, minNum, minNum);
    }
    bool IsEmpty() const {
        return pMin.x > pMax.x || pMin.y > pMax.y || pMin.z > pMax.z;
    }
    bool IsDegenerate() const {
        return !IsEmpty() &&
               (pMin.x == pMax.x || pMin.y == pMax.y || pMin.z == pMax.z);
    }
    explicit Bounds3(const Point3<T> &p) : pMin(p), pMax(p) {}
    Bounds3(const Point3<T> &p1, const Point3<T> &p2)
        : pMin(std::min(p1.x, p2.x), std::min(p1.y, p2.y),
               std::min(p1.z, p2.z)),
          pMax(std::max(p1.x, p2.x), std::max(p1.y, p2.y),
               std::max(p1.z, p2.z)) {}
    template <typename U>
    explicit operator Bounds3<U>() const {
        if (IsEmpty()) return Bounds3<U>();
        return Bounds3<U>(Point3<U>(pMin), Point3<U>(pMax));
    }
    const Point3<T> &operator[](int i) const {
        if (i == 0) return pMin;
        if (i == 1) return pMax;
        throw std::out_of_range("Bounds3::operator[]: index out of range");
    }
    Point3<T> &operator[](int i) {
        if (i == 0) return pMin;
        if (i == 1) return pMax;
        throw std::out_of_range("Bounds3::operator[]: index out of range");
    }
    bool operator==(const Bounds3<T> &b) const {
        return b.pMin == pMin && b.pMax == pMax;
    }
    bool operator!=(const Bounds3<T> &b) const { return !(*this == b); }
    Point3<T> Corner(int corner) const {
        if (corner < 0 || corner > 7)
            throw std::out_of_range("Bounds3::Corner: corner must be 0 to 7");
        return Point3<T>((*this)[corner & 1].x,
                         (*this)[(corner & 2) ? 1 : 0].y,
                         (*this)[(corner & 4) ? 1 : 0].z);
    }
    Vector3<T> Diagonal() const { return pMax - pMin; }
    T SurfaceArea() const {
        if (IsEmpty()) return T(0);
        Vector3<T> d = Diagonal();
        return 2 * (d.x * d.y + d.x * d.z + d.y * d.z);
    }
    T Volume() const {
        if (IsEmpty()) return T(0);
        Vector3<T> d = Diagonal();
        return d.x * d.y * d.z;
    }
    int MaximumExtent() const {
        Vector3<T> d = Diagonal();
        if (d.x > d.y && d.x > d.z) return 0;
        if (d.y > d.z) return 1;
        return 2;
    }
    Point3<T> Lerp(const Point3f &t) const {
        return Point3<T>(lrt::Lerp(t.x, pMin.x, pMax.x),
                         lrt::Lerp(t.y, pMin.y, pMax.y),
                         lrt::Lerp(t.z, pMin.z, pMax.z));
    }
    Vector3<T> Offset(const Point3<T> &p) const {
        Vector3<T> o = p - pMin;
        if (pMax.x > pMin.x) o.x /= pMax.x - pMin.x;
        if (pMax.y > pMin.y) o.y /= pMax.y - pMin.y;
        if (pMax.z > pMin.z) o.z /= pMax.z - pMin.z;
        return o;
    }
    void BoundingSphere(Point3<T> *center, Float *radius) const {
        *center = (pMin + pMax) / 2;
        *radius = Inside(*center, *this) ? Distance(*center, pMax) : 0;
    }
    bool IntersectP(const Ray &ray, Float *hitt0 = nullptr,
                    Float *hitt1 = nullptr) const;
    inline bool IntersectP(const Ray &ray, const Vector3f &invDir,
                           const int dirIsNeg[3]) const;
    // Bounds3 Public Data
    Point3<T> pMin, pMax;
};

typedef Bounds3<Float> Bounds3f;
typedef Bounds3<int> Bounds3i;
template <typename T>
class Bounds2 {
  public:
    // Bounds2 Public Methods
    Bounds2() {
        T minNum = std::numeric_limits<T>::lowest();
        T maxNum = std::numeric_limits<T>::max();
        pMin = Point2<T>(maxNum, maxNum);
        pMax = Point2<T>(minNum, minNum);
    }
    explicit Bounds2(const Point2<T> &p) : pMin(p), pMax(p) {}
    Bounds2(const Point2<T> &p1, const Point2<T> &p2)
        : pMin(std::min(p1.x, p2.x), std::min(p1.y, p2.y)),
          pMax(std::max(p1.x, p2.x), std::max(p1.y, p2.y)) {}
    template <typename U>
    explicit operator Bounds2<U>() const {
        if (IsEmpty()) return Bounds2<U>();
        return Bounds2<U>(Point2<U>(pMin), Point2<U>(pMax));
    }
    bool IsEmpty() const { return pMin.x > pMax.x || pMin.y > pMax.y; }
    bool IsDegenerate() const {
        return !IsEmpty() && (pMin.x == pMax.x || pMin.y == pMax.y);
    }
    const Point2<T> &operator[](int i) const {
        if (i == 0) return pMin;
        if (i == 1) return pMax;
        throw std::out_of_range("Bounds2::operator[]: index out of range");
    }
    Point2<T> &operator[](int i) {
        if (i == 0) return pMin;
        if (i == 1) return pMax;
        throw std::out_of_range("Bounds2::operator[]: index out of range");
    }
    bool operator==(const Bounds2<T> &b) const {
        return b.pMin == pMin && b.pMax == pMax;
    }
    bool operator!=(const Bounds2<T> &b) const { return !(*this == b); }
    Vector2<T> Diagonal() const { return pMax - pMin; }
    T Area() const {
        if (IsEmpty()) return T(0);
        Vector2<T> d = pMax - pMin;
        return d.x * d.y;
    }
    int MaximumExtent() const {
        Vector2<T> diag = Diagonal();
        return (diag.x > diag.y) ? 0 : 1;
    }
    Point2<T> Lerp(const Point2f &t) const {
        return Point2<T>(lrt::Lerp(t.x, pMin.x, pMax.x),
                         lrt::Lerp(t.y, pMin.y, pMax.y));
    }
    Vector2<T> Offset(const Point2<T> &p) const {
        Vector2<T> o = p - pMin;
        if (pMax.x > pMin.x) o.x /= pMax.x - pMin.x;
        if (pMax.y > pMin.y) o.y /= pMax.y - pMin.y;
        return o;
    }
    void BoundingSphere(Point2<T> *center, Float *radius) const {
        *center = (pMin + pMax) / 2;
        *radius = Inside(*center, *this) ? Distance(*center, pMax) : 0;
    }
    Point2<T> pMin, pMax;
};

typedef Bounds2<Float> Bounds2f;
typedef Bounds2<int> Bounds2i;
// Geometry Inline Functions
template <typename T, typename U>
inline Vector3<T> operator*(U s, const Vector3<T> &v) {
    return v * s;
}
template <typename T>
inline Vector3<T> Abs(const Vector3<T> &v) {
    return Vector3<T>(std::abs(v.x), std::abs(v.y), std::abs(v.z));
}
template <typename T>
inline std::ostream &operator<<(std::ostream &os, const Vector3<T> &v) {
    os << "[ " << v.x << ", " << v.y << ", " << v.z << " ]";
    return os;
}
template <typename T>
inline T Dot(const Vector3<T> &v1, const Vector3<T> &v2) {
    return v1.x * v2.x + v1.y * v2.y + v1.z * v2.z;
}
template <typename T>
inline T AbsDot(const Vector3<T> &v1, const Vector3<T> &v2) {
    return std::abs(Dot(v1, v2));
}
template <typename T>
inline Vector3<T> Cross(const Vector3<T> &v1, const Vector3<T> &v2) {
    double v1x = v1.x, v1y = v1.y, v1z = v1.z;
    double v2x = v2.x, v2y = v2.y, v2z = v2.z;
    return Vector3<T>(T(v1y * v2z - v1z * v2y),
                      T(v1z * v2x - v1x * v2z),
                      T(v1x * v2y - v1y * v2x));
}
template <typename T>
inline Vector3<T> Normalize(const Vector3<T> &v) {
    return v / v.Length();
}
template <typename T>
inline T MinComponent(const Vector3<T> &v) {
    return std::min(v.x, std::min(v.y, v.z));
}
template <typename T>
inline T MaxComponent(const Vector3<T> &v) {
    return std::max(v.x, std::max(v.y, v.z));
}
template <typename T>
inline int MaxDimension(const Vector3<T> &v) {
    return (v.x > v.y) ? ((v.x > v.z) ? 0 : 2) : ((v.y > v.z) ? 1 : 2);
}
template <typename T>
inline Vector3<T> Min(const Vector3<T> &v1, const Vector3<T> &v2) {
    return Vector3<T>(std::min(v1.x, v2.x), std::min(v1.y, v2.y),
                      std::min(v1.z, v2.z));
}
template <typename T>
inline Vector3<T> Max(const Vector3<T> &v1, const Vector3<T> &v2) {
    return Vector3<T>(std::max(v1.x, v2.x), std::max(v1.y, v2.y),
                      std::max(v1.z, v2.z));
}
template <typename T>
inline Vector3<T> Permute(const Vector3<T> &v, int x, int y, int z) {
    return Vector3<T>(v[x], v[y], v[z]);
}
template <typename T>
inline void CoordinateSystem(const Vector3<T> &v1, Vector3<T> *v2,
                             Vector3<T> *v3) {
    // Complete v1 to an orthonormal frame
    if (std::abs(v1.x) > std::abs(v1.y))
        *v2 = Vector3<T>(-v1.z, 0, v1.x) /
              std::sqrt(v1.x * v1.x + v1.z * v1.z);
    else
        *v2 = Vector3<T>(0, v1.z, -v1.y) /
              std::sqrt(v1.y * v1.y + v1.z * v1.z);
    *v3 = Cross(v1, *v2);
}
template <typename T, typename U>
inline Vector2<T> operator*(U s, const Vector2<T> &v) {
    return v * s;
}
template <typename T>
inline Vector2<T> Abs(const Vector2<T> &v) {
    return Vector2<T>(std::abs(v.x), std::abs(v.y));
}
template <typename T>
inline T Dot(const Vector2<T> &v1, const Vector2<T> &v2) {
    return v1.x * v2.x + v1.y * v2.y;
}
template <typename T>
inline T AbsDot(const Vector2<T> &v1, const Vector2<T> &v2) {
    return std::abs(Dot(v1, v2));
}
template <typename T>
inline Vector2<T> Normalize(const Vector2<T> &v) {
    return v / v.Length();
}
template <typename T>
inline std::ostream &operator<<(std::ostream &os, const Vector2<T> &v) {
    os << "[ " << v.x << ", " << v.y << " ]";
    return os;
}
template <typename T, typename U>
inline Point3<T> operator*(U f, const Point3<T> &p) {
    return p * f;
}
template <typename T>
inline std::ostream &operator<<(std::ostream &os, const Point3<T> &p) {
    os << "[ " << p.x << ", " << p.y << ", " << p.z << " ]";
    return os;
}
template <typename T>
inline Float Distance(const Point3<T> &p1, const Point3<T> &p2) {
    return (p1 - p2).Length();
}
template <typename T>
inline Float DistanceSquared(const Point3<T> &p1, const Point3<T> &p2) {
    return (p1 - p2).LengthSquared();
}
template <typename T>
inline Point3<T> Lerp(Float t, const Point3<T> &p0, const Point3<T> &p1) {
    return (1 - t) * p0 + t * p1;
}
template <typename T>
inline Point3<T> Min(const Point3<T> &p1, const Point3<T> &p2) {
    return Point3<T>(std::min(p1.x, p2.x), std::min(p1.y, p2.y),
                     std::min(p1.z, p2.z));
}
template <typename T>
inline Point3<T> Max(const Point3<T> &p1, const Point3<T> &p2) {
    return Point3<T>(std::max(p1.x, p2.x), std::max(p1.y, p2.y),
                     std::max(p1.z, p2.z));
}
template <typename T>
inline Point3<T> Floor(const Point3<T> &p) {
    return Point3<T>(std::floor(p.x), std::floor(p.y), std::floor(p.z));
}
template <typename T>
inline Point3<T> Ceil(const Point3<T> &p) {
    return Point3<T>(std::ceil(p.x), std::ceil(p.y), std::ceil(p.z));
}
template <typename T>
inline Point3<T> Abs(const Point3<T> &p) {
    return Point3<T>(std::abs(p.x), std::abs(p.y), std::abs(p.z));
}
template <typename T>
inline Point3<T> Permute(const Point3<T> &p, int x, int y, int z) {
    return Point3<T>(p[x], p[y], p[z]);
}
template <typename T, typename U>
inline Point2<T> operator*(U f, const Point2<T> &p) {
    return p * f;
}
template <typename T>
inline Float Distance(const Point2<T> &p1, const Point2<T> &p2) {
    return (p1 - p2).Length();
}
template <typename T>
inline Float DistanceSquared(const Point2<T> &p1, const Point2<T> &p2) {
    return (p1 - p2).LengthSquared();
}
template <typename T>
inline Point2<T> Lerp(Float t, const Point2<T> &p0, const Point2<T> &p1) {
    return (1 - t) * p0 + t * p1;
}
template <typename T>
inline Point2<T> Min(const Point2<T> &p1, const Point2<T> &p2) {
    return Point2<T>(std::min(p1.x, p2.x), std::min(p1.y, p2.y));
}
template <typename T>
inline Point2<T> Max(const Point2<T> &p1, const Point2<T> &p2) {
    return Point2<T>(std::max(p1.x, p2.x), std::max(p1.y, p2.y));
}
template <typename T>
inline Point2<T> Floor(const Point2<T> &p) {
    return Point2<T>(std::floor(p.x), std::floor(p.y));
}
template <typename T>
inline Point2<T> Ceil(const Point2<T> &p) {
    return Point2<T>(std::ceil(p.x), std::ceil(p.y));
}
template <typename T>
inline std::ostream &operator<<(std::ostream &os, const Point2<T> &p) {
    os << "[ " << p.x << ", " << p.y << " ]";
    return os;
}
template <typename T>
inline T Dot(const Normal3<T> &n, const Vector3<T> &v) {
    return n.x * v.x + n.y * v.y + n.z * v.z;
}
template <typename T>
inline T Dot(const Vector3<T> &v, const Normal3<T> &n) {
    return v.x * n.x + v.y * n.y + v.z * n.z;
}
template <typename T>
inline T Dot(const Normal3<T> &n1, const Normal3<T> &n2) {
    return n1.x * n2.x + n1.y * n2.y + n1.z * n2.z;
}
template <typename T>
inline T AbsDot(const Normal3<T> &n, const Vector3<T> &v) {
    return std::abs(Dot(n, v));
}
template <typename T>
inline T AbsDot(const Vector3<T> &v, const Normal3<T> &n) {
    return std::abs(Dot(v, n));
}
template <typename T>
inline T AbsDot(const Normal3<T> &n1, const Normal3<T> &n2) {
    return std::abs(Dot(n1, n2));
}
template <typename T>
inline Vector3<T> Cross(const Vector3<T> &v, const Normal3<T> &n) {
    return Cross(v, Vector3<T>(n));
}
template <typename T>
inline Vector3<T> Cross(const Normal3<T> &n, const Vector3<T> &v) {
    return Cross(Vector3<T>(n), v);
}
template <typename T, typename U>
inline Normal3<T> operator*(U f, const Normal3<T> &n) {
    return n * f;
}
template <typename T>
inline Normal3<T> Normalize(const Normal3<T> &n) {
    return n / n.Length();
}
template <typename T>
inline Normal3<T> Abs(const Normal3<T> &n) {
    return Normal3<T>(std::abs(n.x), std::abs(n.y), std::abs(n.z));
}
template <typename T>
inline std::ostream &operator<<(std::ostream &os, const Normal3<T> &n) {
    os << "[ " << n.x << ", " << n.y << ", " << n.z << " ]";
    return os;
}
template <typename T>
inline Normal3<T> Faceforward(const Normal3<T> &n, const Vector3<T> &v) {
    return (Dot(n, v) < 0) ? -n : n;
}
template <typename T>
inline Normal3<T> Faceforward(const Normal3<T> &n, const Normal3<T> &n2) {
    return (Dot(n, n2) < 0) ? -n : n;
}
template <typename T>
inline Vector3<T> Faceforward(const Vector3<T> &v, const Vector3<T> &v2) {
    return (Dot(v, v2) < 0) ? -v : v;
}
template <typename T>
inline Vector3<T> Faceforward(const Vector3<T> &v, const Normal3<T> &n2) {
    return (Dot(v, n2) < 0) ? -v : v;
}
inline std::ostream &operator<<(std::ostream &os, const Ray &r) {
    os << "[o=" << r.o << ", d=" << r.d << ", tMax=" << r.tMax
       << ", time=" << r.time << "]";
    return os;
}
template <typename T>
inline Bounds3<T> Union(const Bounds3<T> &b, const Point3<T> &p) {
    Bounds3<T> ret;
    ret.pMin = Min(b.pMin, p);
    ret.pMax = Max(b.pMax, p);
    return ret;
}
template <typename T>
inline Bounds3<T> Union(const Bounds3<T> &b1, const Bounds3<T> &b2) {
    using Box = Bounds3<T>;
    // Compute the union of two boxes
    Box ret;
    ret.pMin = Min(b1.pMin, b2.pMin);
    ret.pMax = Max(b1.pMax, b2.pMax);
    return ret;
}
template <typename T>
inline Bounds3<T> Intersect(const Bounds3<T> &b1, const Bounds3<T> &b2) {
    using Box = Bounds3<T>;
    // Compute the intersection of two boxes
    Box ret;
    ret.pMin = Max(b1.pMin, b2.pMin);
    ret.pMax = Min(b1.pMax, b2.pMax);
    return ret.IsEmpty() ? Box() : ret;
}
template <typename T>
inline bool Overlaps(const Bounds3<T> &b1, const Bounds3<T> &b2) {
    bool x = std::max(b1.pMin.x, b2.pMin.x) <= std::min(b1.pMax.x, b2.pMax.x);
    bool y = std::max(b1.pMin.y, b2.pMin.y) <= std::min(b1.pMax.y, b2.pMax.y);
    bool z = std::max(b1.pMin.z, b2.pMin.z) <= std::min(b1.pMax.z, b2.pMax.z);
    return x && y && z;
}
template <typename T>
inline bool Inside(const Point3<T> &p, const Bounds3<T> &b) {
    return p.x >= b.pMin.x && p.x <= b.pMax.x && p.y >= b.pMin.y &&
           p.y <= b.pMax.y && p.z >= b.pMin.z && p.z <= b.pMax.z;
}
template <typename T>
inline bool InsideExclusive(const Point3<T> &p, const Bounds3<T> &b) {
    return p.x >= b.pMin.x && p.x < b.pMax.x && p.y >= b.pMin.y &&
           p.y < b.pMax.y && p.z >= b.pMin.z && p.z < b.pMax.z;
}
template <typename T, typename U>
inline Bounds3<T> Expand(const Bounds3<T> &b, U delta) {
    if (b.IsEmpty()) return Bounds3<T>();
    Bounds3<T> ret;
    ret.pMin = b.pMin - Vector3<T>(delta, delta, delta);
    ret.pMax = b.pMax + Vector3<T>(delta, delta, delta);
    return ret.IsEmpty() ? Bounds3<T>() : ret;
}
template <typename T, typename U>
inline Float DistanceSquared(const Point3<T> &p, const Bounds3<U> &b) {
    Float dx = std::max({Float(0), Float(b.pMin.x - p.x),
                         Float(p.x - b.pMax.x)});
    Float dy = std::max({Float(0), Float(b.pMin.y - p.y),
                         Float(p.y - b.pMax.y)});
    Float dz = std::max({Float(0), Float(b.pMin.z - p.z),
                         Float(p.z - b.pMax.z)});
    return dx * dx + dy * dy + dz * dz;
}
template <typename T, typename U>
inline Float Distance(const Point3<T> &p, const Bounds3<U> &b) {
    return std::sqrt(DistanceSquared(p, b));
}
template <typename T>
inline std::ostream &operator<<(std::ostream &os, const Bounds3<T> &b) {
    os << "[ " << b.pMin << " - " << b.pMax << " ]";
    return os;
}
template <typename T>
inline Bounds2<T> Union(const Bounds2<T> &b, const Point2<T> &p) {
    Bounds2<T> ret;
    ret.pMin = Min(b.pMin, p);
    ret.pMax = Max(b.pMax, p);
    return ret;
}
template <typename T>
inline Bounds2<T> Union(const Bounds2<T> &b1, const Bounds2<T> &b2) {
    using Box = Bounds2<T>;
    // Compute the union of two boxes
    Box ret;
    ret.pMin = Min(b1.pMin, b2.pMin);
    ret.pMax = Max(b1.pMax, b2.pMax);
    return ret;
}
template <typename T>
inline Bounds2<T> Intersect(const Bounds2<T> &b1, const Bounds2<T> &b2) {
    using Box = Bounds2<T>;
    // Compute the intersection of two boxes
    Box ret;
    ret.pMin = Max(b1.pMin, b2.pMin);
    ret.pMax = Min(b1.pMax, b2.pMax);
    return ret.IsEmpty() ? Box() : ret;
}
template <typename T>
inline bool Overlaps(const Bounds2<T> &b1, const Bounds2<T> &b2) {
    bool x = std::max(b1.pMin.x, b2.pMin.x) <= std::min(b1.pMax.x, b2.pMax.x);
    bool y = std::max(b1.pMin.y, b2.pMin.y) <= std::min(b1.pMax.y, b2.pMax.y);
    return x && y;
}
template <typename T>
inline bool Inside(const Point2<T> &p, const Bounds2<T> &b) {
    return p.x >= b.pMin.x && p.x <= b.pMax.x && p.y >= b.pMin.y &&
           p.y <= b.pMax.y;
}
template <typename T>
inline bool InsideExclusive(const Point2<T> &p, const Bounds2<T> &b) {
    return p.x >= b.pMin.x && p.x < b.pMax.x && p.y >= b.pMin.y &&
           p.y < b.pMax.y;
}
template <typename T, typename U>
inline Bounds2<T> Expand(const Bounds2<T> &b, U delta) {
    if (b.IsEmpty()) return Bounds2<T>();
    Bounds2<T> ret;
    ret.pMin = b.pMin - Vector2<T>(delta, delta);
    ret.pMax = b.pMax + Vector2<T>(delta, delta);
    return ret.IsEmpty() ? Bounds2<T>() : ret;
}
template <typename T>
inline std::ostream &operator<<(std::ostream &os, const Bounds2<T> &b) {
    os << "[ " << b.pMin << " - " << b.pMax << " ]";
    return os;
}
inline Point3f OffsetRayOrigin(const Point3f &p, const Vector3f &pError,
                               const Normal3f &n, const Vector3f &w) {
    // Offset p along n to the side of w
    Float d = Dot(Abs(n), pError);
    Vector3f offset = d * Vector3f(n);
    if (Dot(w, n) < 0) offset = -offset;
    Point3f po = p + offset;
    // Round offset point po away from p
    for (int i = 0; i < 3; ++i) {
        if (offset[i] > 0)
            po[i] = NextFloatUp(po[i]);
        else if (offset[i] < 0)
            po[i] = NextFloatDown(po[i]);
    }
    return po;
}

}  // namespace lrt
