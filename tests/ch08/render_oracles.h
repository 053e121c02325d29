// Oracles and scenes of chapter 8's exercise tests (public and hidden): the
// pinhole camera's geometry written out in double precision from an
// orthonormal basis (not from Transform), the analytic depths of a sphere on
// the axis, the sRGB formula in long double, and the hit points on spheres
// and disks that the shadow-ray tests hand to Shade().

#ifndef LRT_TESTS_CH08_RENDER_ORACLES_H
#define LRT_TESTS_CH08_RENDER_ORACLES_H

#include "ch08/exercise_calls.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <vector>

namespace lrt {
namespace oracle {

const Float kEps = std::numeric_limits<Float>::epsilon();

// The standard's sRGB curve and its inverse, in long double.
inline long double SRGB(long double v) {
    return v <= 0.0031308L ? 12.92L * v
                           : 1.055L * std::pow(v, 1 / 2.4L) - 0.055L;
}
inline long double InverseSRGB(long double e) {
    return e <= 0.04045L ? e / 12.92L
                         : std::pow((e + 0.055L) / 1.055L, 2.4L);
}

struct V3 {
    double x, y, z;
};
inline V3 operator+(V3 a, V3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
inline V3 operator-(V3 a, V3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
inline V3 operator*(double s, V3 a) { return {s * a.x, s * a.y, s * a.z}; }
inline double Dot(V3 a, V3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline double Norm(V3 a) { return std::sqrt(Dot(a, a)); }
inline V3 Unit(V3 a) { return (1 / Norm(a)) * a; }
inline V3 Cross(V3 a, V3 b) {
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z,
            a.x * b.y - a.y * b.x};
}
template <typename P>
V3 D(const P &p) {
    return {double(p.x), double(p.y), double(p.z)};
}

// A pinhole camera as the chapter describes it, in double: the eye, the unit
// vectors of camera space's x (right), y (up) and z (the view direction) in
// world space, and the film's half-widths.
struct Camera {
    V3 eye, right, up, forward;
    double sx, sy;
    int width, height;
    double zNear, zFar;

    // The camera of LookAt(eye, look, up), as the book's tests make it.
    Camera(V3 e, V3 look, V3 upHint, double fov, int w, int h,
           double zNear = 0, double zFar = HUGE_VAL)
        : eye(e), width(w), height(h), zNear(zNear), zFar(zFar) {
        forward = Unit(look - e);
        right = Unit(Cross(Unit(upHint), forward));
        up = Cross(forward, right);
        double t = std::tan(fov * M_PI / 360);
        sx = w >= h ? t * w / h : t;
        sy = w >= h ? t : t * h / w;
    }
    CameraValue Value(const Point3f &e, const Point3f &look,
                      const Vector3f &upHint, Float fov) const {
        return {Inverse(LookAt(e, look, upHint)), fov, width, height,
                Float(zNear), std::isinf(zFar) ? Infinity : Float(zFar)};
    }
    // The world-space direction of the film point of a raster position.
    V3 Direction(double xr, double yr) const {
        double xc = (2 * xr / width - 1) * sx, yc = (1 - 2 * yr / height) * sy;
        return forward + xc * right + yc * up;
    }
    // A world-space point in camera space.
    V3 ToCamera(V3 p) const {
        V3 q = p - eye;
        return {Dot(q, right), Dot(q, up), Dot(q, forward)};
    }
    // The raster position that a world-space point projects to.
    void Project(V3 p, double *xr, double *yr) const {
        V3 c = ToCamera(p);
        *xr = (c.x / c.z / sx + 1) * width / 2;
        *yr = (1 - c.y / c.z / sy) * height / 2;
    }
    // The ray through a raster position, from the eye, made in double and
    // rounded to Float once.
    Ray RayThrough(double xr, double yr) const {
        V3 d = Direction(xr, yr);
        return Ray(Point3f(Float(eye.x), Float(eye.y), Float(eye.z)),
                   Vector3f(Float(d.x), Float(d.y), Float(d.z)));
    }
};

// Film-plane position of a pixel center for the camera on the axis.
inline void FilmPoint(double fov, int w, int h, int x, int y, double *xc,
                      double *yc) {
    double t = std::tan(fov * M_PI / 360);
    double sx = w >= h ? t * w / h : t, sy = w >= h ? t : t * h / w;
    *xc = (2 * (x + 0.5) / w - 1) * sx;
    *yc = (1 - 2 * (y + 0.5) / h) * sy;
}

// Roots t0 <= t1 of |t (xc, yc, 1) - (0, 0, D)|^2 = r^2; false if none.
inline bool SphereDepths(double xc, double yc, double D, double r, double *t0,
                         double *t1) {
    double a = xc * xc + yc * yc + 1, b = -2 * D, c = D * D - r * r;
    double disc = b * b - 4 * a * c;
    if (disc < 0) return false;
    double s = std::sqrt(disc);
    *t0 = (-b - s) / (2 * a);
    *t1 = (-b + s) / (2 * a);
    return true;
}

inline ShapeValue SphereShape(const Transform &o2w, Float r,
                              const RGB &albedo) {
    return {kSphereShape, o2w, {r, -r, r, 360}, albedo};
}
inline ShapeValue DiskShape(const Transform &o2w, Float height, Float radius,
                            const RGB &albedo) {
    return {kDiskShape, o2w, {height, radius, 0, 360}, albedo};
}

// The camera on the axis: the eye at the origin looking down +z with +y up,
// so camera space is world space.
inline CameraValue AxisCamera(Float fov, int w, int h, Float zNear = 0,
                              Float zFar = Infinity) {
    Transform w2c = LookAt(Point3f(0, 0, 0), Point3f(0, 0, 1),
                           Vector3f(0, 1, 0));
    return {Inverse(w2c), fov, w, h, zNear, zFar};
}

// A hit point of a ray from a random eye on a random sphere or disk of size
// `scale`, found by the book's shapes, with a light on the side of the
// normal that faces the eye. `shape` keeps the shape, to test the shadow ray
// against it.
struct ShadowHit {
    ShadowCase c;
    std::shared_ptr<Shape> shape;
    std::shared_ptr<Transform> o2w, w2o;
    V3 towardLight;  // the normal on the light's side, unit
};

inline bool RandomShadowHit(std::mt19937_64 &rng, double scale, bool disk,
                            ShadowHit *h) {
    std::uniform_real_distribution<double> u(-1, 1), u01(0, 1);
    V3 center{scale * 10 * u(rng), scale * 10 * u(rng), scale * 10 * u(rng)};
    Float r = Float(scale * (0.5 + u01(rng)));
    h->o2w = std::make_shared<Transform>(
        Translate(Vector3f(Float(center.x), Float(center.y),
                           Float(center.z))) *
        Rotate(Float(360 * u01(rng)),
               Vector3f(Float(u(rng)), Float(u(rng)), Float(u(rng)) + 2)));
    h->w2o = std::make_shared<Transform>(Inverse(*h->o2w));
    if (disk)
        h->shape = std::make_shared<Disk>(h->o2w.get(), h->w2o.get(), false,
                                          0, r, 0, 360);
    else
        h->shape = std::make_shared<Sphere>(h->o2w.get(), h->w2o.get(), false,
                                            r, -r, r, 360);
    // A ray from an eye some 5 to 40 sizes away toward a random point near
    // the shape's center.
    V3 dir = Unit(V3{u(rng), u(rng), u(rng)});
    V3 eye = center + (scale * (5 + 35 * u01(rng))) * dir;
    V3 target = center + (0.4 * double(r)) * V3{u(rng), u(rng), u(rng)};
    Ray ray(Point3f(Float(eye.x), Float(eye.y), Float(eye.z)),
            Vector3f(Float(target.x - eye.x), Float(target.y - eye.y),
                     Float(target.z - eye.z)));
    Float tHit;
    SurfaceInteraction isect;
    if (!h->shape->Intersect(ray, &tHit, &isect)) return false;
    ray.tMax = tHit;
    V3 n = D(isect.n), p = D(isect.p);
    V3 toEye = D(ray.o) - p;
    if (Dot(n, toEye) < 0) n = -1 * n;
    // A light in the half-space in front of the surface, 2 to 20 sizes away.
    V3 w = Unit(V3{u(rng), u(rng), u(rng)});
    if (Dot(w, n) < 0) w = w - 2 * Dot(w, n) * n;
    if (Dot(w, n) < 0.05) return false;
    V3 light = p + (scale * (2 + 18 * u01(rng))) * w;
    h->towardLight = Unit(n);
    h->c = {ray,
            isect.p,
            isect.pError,
            isect.n,
            ray.o,
            Point3f(Float(light.x), Float(light.y), Float(light.z)),
            ShadowRays::ErrorBounds,
            Float(1e-4)};
    return true;
}

// True, after a failure, once five more cases have been checked: a test of
// hundreds of cases shows the first failures, not all of them.
inline bool StopAfterFailures(size_t i) {
    static size_t first = 0;
    static const ::testing::TestInfo *test = nullptr;
    const ::testing::TestInfo *now =
        ::testing::UnitTest::GetInstance()->current_test_info();
    if (!::testing::Test::HasFailure()) {
        test = nullptr;
        return false;
    }
    if (test != now) test = now, first = i;
    if (i < first + 5) return false;
    ADD_FAILURE() << "stopped after the failures above (case " << i << ")";
    return true;
}

// The distance from one Float to the next, at x.
inline double Ulp(Float x) {
    x = std::abs(x);
    return double(std::nextafter(x, Infinity)) - double(x);
}

// Checks the end of a shadow ray s for case c: o + d is the light, and the
// ray stops just short of it.
inline void CheckEndsShortOfTheLight(const ShadowCase &c, const Ray &s,
                                     const std::string &what) {
    V3 end = D(s.o) + D(s.d), light = D(c.pLight);
    double scale = Norm(light) + Norm(D(s.o));
    EXPECT_LT(Norm(end - light), 4 * kEps * scale) << what;
    EXPECT_LT(s.tMax, 1) << what;
    EXPECT_GT(s.tMax, 0.999) << what;
}

// Checks a shadow ray s spawned with the fixed offset for case c: it starts
// at the ray equation's point o + t d moved by c.epsilon along n, the unit
// normal turned toward the eye, and ends just short of the light.
inline void CheckFixedEpsilonRay(const ShadowCase &c, V3 n, const Ray &s,
                                 const std::string &what) {
    V3 q = D(c.ray.o) + double(c.ray.tMax) * D(c.ray.d);
    V3 want = q + double(c.epsilon) * n;
    double tol = 8 * kEps * (Norm(D(c.ray.o)) + Norm(q) + double(c.epsilon));
    EXPECT_LT(Norm(D(s.o) - want), tol)
        << what << ": the origin is " << Norm(D(s.o) - want)
        << " from o + t d + epsilon n";
    CheckEndsShortOfTheLight(c, s, what);
}

// Checks a shadow ray spawned with the error bounds at hit h: it starts
// outside the error box of the hit point, on the light's side, no farther
// than the box requires; it ends just short of the light; and it does not
// find the surface it leaves.
inline void CheckErrorBoundsRay(const ShadowHit &h, const Ray &s, const char *what) {
    const ShadowCase &c = h.c;
    V3 p = D(c.p), o = D(s.o), n = h.towardLight;
    // The error box's extent along the normal.
    double support = std::abs(n.x) * c.pError.x + std::abs(n.y) * c.pError.y +
                     std::abs(n.z) * c.pError.z;
    double along = Dot(o - p, n);
    EXPECT_GE(along, support * (1 - 16 * kEps)) << what << ": below the box";
    double fromP[3] = {o.x - p.x, o.y - p.y, o.z - p.z};
    double nn[3] = {n.x, n.y, n.z};
    Float pc[3] = {c.p.x, c.p.y, c.p.z}, oc[3] = {s.o.x, s.o.y, s.o.z};
    for (int i = 0; i < 3; ++i)
        EXPECT_LE(std::abs(fromP[i]), support * std::abs(nn[i]) * 1.001 +
                                          3 * std::max(Ulp(pc[i]), Ulp(oc[i])))
            << what << ": too far on axis " << i;
    CheckEndsShortOfTheLight(c, s, what);
    EXPECT_FALSE(h.shape->IntersectP(s)) << what << ": hits its own surface";
}

}  // namespace oracle
}  // namespace lrt

#endif  // LRT_TESTS_CH08_RENDER_ORACLES_H
