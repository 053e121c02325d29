// lrt/shapes/quadric.h: tangled from chapters/03-shapes.md. Edit the chapter, not this file.
#pragma once

#include "lrt/core/efloat.h"
#include "lrt/core/shape.h"

namespace lrt {

// Quadric Declarations
struct QuadricRay {
    QuadricRay(const Ray &r, const Transform &WorldToObject);
    // QuadricRay Public Methods
    void PointAt(const EFloat &t, Point3f *p, Vector3f *pError) const {
        EFloat px = ox + t * dx, py = oy + t * dy, pz = oz + t * dz;
        *p = Point3f((Float)px, (Float)py, (Float)pz);
        *pError = Vector3f(px.GetAbsoluteError(), py.GetAbsoluteError(),
                           pz.GetAbsoluteError());
    }
    Ray ray;
    EFloat ox, oy, oz, dx, dy, dz;
};
struct QuadricOfRevolution {
    EFloat zc, alpha, beta, gamma;
    bool Roots(const QuadricRay &q, EFloat *t0, EFloat *t1) const;
};
struct QuadricHit {
    EFloat t;
    Point3f p;
    Vector3f pError;
    Float phi;
};

class Quadric : public Shape {
  public:
    // Quadric Public Methods
    bool Intersect(const Ray &ray, Float *tHit, SurfaceInteraction *isect,
                   bool testAlphaTexture = true) const override;
    bool IntersectP(const Ray &ray,
                    bool testAlphaTexture = true) const override;
  protected:
    // Quadric Protected Methods
    Quadric(const char *name, const Transform *ObjectToWorld,
            const Transform *WorldToObject, bool reverseOrientation,
            const QuadricOfRevolution &implicit, Float phiMax);
    virtual bool LocateHit(const QuadricRay &q, QuadricHit *hit) const = 0;
    virtual SurfaceInteraction DescribeHit(const QuadricRay &q,
                                           const QuadricHit &hit) const = 0;
    SurfaceInteraction Interaction(const QuadricRay &q, const QuadricHit &hit,
                                   const Point3f &pAxis, const Point2f &uv,
                                   const Vector3f &dpdv,
                                   const Vector3f &d2Pdvv) const;
    // Quadric Protected Data
    const QuadricOfRevolution implicit;
    const Float phiMax;
  private:
    bool FindHit(const QuadricRay &q, QuadricHit *hit) const;
};
inline Float Azimuth(Float x, Float y) {
    Float phi = std::atan2(y, x);
    return (phi < 0) ? phi + 2 * Pi : phi;
}
inline Point3f OffAxis(const Point3f &p, Float radius) {
    if (p.x != 0 || p.y != 0) return p;
    return Point3f(Float(1e-5) * radius, 0, p.z);
}

}  // namespace lrt
