// lrt/shapes/triangle.h: tangled from chapters/03-shapes.md. Edit the chapter, not this file.
#pragma once

#include "lrt/core/geometry.h"
#include "lrt/core/interaction.h"
#include "lrt/core/shape.h"
#include "lrt/core/transform.h"

#include <memory>
#include <vector>

namespace lrt {

// TriangleMesh Declarations
struct TriangleMesh {
    // TriangleMesh Public Methods
    TriangleMesh(const Transform &ObjectToWorld, bool reverseOrientation,
                 int nTriangles, const int *vertexIndices, int nVertices,
                 const Point3f *P, const Vector3f *S, const Normal3f *N,
                 const Point2f *UV, const int *faceIndices = nullptr);
    // TriangleMesh Data
    const int nTriangles, nVertices;
    std::vector<int> vertexIndices;
    std::vector<Point3f> p;
    std::vector<Normal3f> n;
    std::vector<Vector3f> s;
    std::vector<Point2f> uv;
    std::vector<int> faceIndices;
};

// Triangle Declarations
class Triangle : public Shape {
  public:
    // Triangle Public Methods
    Triangle(const Transform *ObjectToWorld, const Transform *WorldToObject,
             bool reverseOrientation, const std::shared_ptr<TriangleMesh> &mesh,
             int triNumber)
        : Shape(ObjectToWorld, WorldToObject, reverseOrientation), mesh(mesh) {
        v = &mesh->vertexIndices[3 * size_t(triNumber)];
        faceIndex = mesh->faceIndices.empty() ? 0
                                              : mesh->faceIndices[triNumber];
    }
    Bounds3f ObjectBound() const override;
    Bounds3f WorldBound() const override;
    static void GetDefaultUVs(Point2f uv[3]) {
        uv[0] = Point2f(0, 0);
        uv[1] = Point2f(1, 0);
        uv[2] = Point2f(1, 1);
    }
    bool Intersect(const Ray &ray, Float *tHit, SurfaceInteraction *isect,
                   bool testAlphaTexture = true) const override;
    bool IntersectP(const Ray &ray,
                    bool testAlphaTexture = true) const override;
    bool FlipsNormal() const {
        return reverseOrientation ^ transformSwapsHandedness;
    }
    Float Area() const override;
    void GetVertices(Point3f *q0, Point3f *q1, Point3f *q2) const {
        // Get triangle vertices in p0, p1, and p2
        const Point3f &p0 = mesh->p[v[0]];
        const Point3f &p1 = mesh->p[v[1]];
        const Point3f &p2 = mesh->p[v[2]];
        *q0 = p0;
        *q1 = p1;
        *q2 = p2;
    }
    bool CompleteIntersection(const Ray &ray, const Point3f &p0,
                              const Point3f &p1, const Point3f &p2, Float e0,
                              Float e1, Float e2, Float invDet,
                              SurfaceInteraction *isect) const;
    int FaceIndex() const { return faceIndex; }
    bool HasVertexAttributes() const {
        return !mesh->n.empty() || !mesh->s.empty() || !mesh->uv.empty();
    }

  private:
    // Triangle Private Methods
    void GetUVs(Point2f uv[3]) const {
        if (!mesh->uv.empty()) {
            uv[0] = mesh->uv[v[0]];
            uv[1] = mesh->uv[v[1]];
            uv[2] = mesh->uv[v[2]];
        } else {
            GetDefaultUVs(uv);
        }
    }
    // Triangle Private Data
    std::shared_ptr<TriangleMesh> mesh;
    const int *v;
    int faceIndex;
};

// Triangle Function Declarations
std::vector<std::shared_ptr<Shape>> CreateTriangleMesh(
    const Transform *ObjectToWorld, const Transform *WorldToObject,
    bool reverseOrientation, int nTriangles, const int *vertexIndices,
    int nVertices, const Point3f *p, const Vector3f *s, const Normal3f *n,
    const Point2f *uv, const int *faceIndices = nullptr);

}  // namespace lrt
