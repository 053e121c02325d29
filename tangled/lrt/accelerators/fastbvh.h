// lrt/accelerators/fastbvh.h: tangled from chapters/07-fast-bvh.md. Edit the chapter, not this file.
#pragma once

#include "lrt/accelerators/bvh.h"
#include "lrt/core/base.h"
#include "lrt/core/geometry.h"
#include "lrt/core/platform.h"
#include "lrt/core/primitive.h"
#include "lrt/shapes/triangle.h"

#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>
#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace lrt {

struct FastBox;
// FastBVHAccel Node Types
constexpr int fastBVHWidth = 4;
constexpr uint16_t fastBVHInterior = 0xffff;

struct FastBVHChild {
    uint32_t offset;
    uint16_t nTriangles, nOthers;
    bool IsLeaf() const { return nTriangles != fastBVHInterior; }
    bool IsEmpty() const { return nTriangles == 0 && nOthers == 0; }
    int NPrimitives() const { return IsLeaf() ? nTriangles + nOthers : 0; }
};

struct alignas(64) FastBVHNode {
    Float bounds[3][2][fastBVHWidth];
    FastBVHChild child[fastBVHWidth];
};
static_assert(sizeof(FastBVHNode) == (sizeof(Float) == 4 ? 128 : 256),
              "FastBVHNode should fill two cache lines");
struct alignas(16) FastTriangle {
    Float c[3][4];  // c[axis][vertex]; c[axis][3] is zero
    Point3f Vertex(int i) const { return Point3f(c[0][i], c[1][i], c[2][i]); }
};
struct FastTriangleInfo {
    const Triangle *triangle;
    int faceIndex;
    bool flipNormal;
    bool plain;  // the mesh has no normals, tangents or (u,v) per vertex
    bool parallelDerivatives;  // plain: the default (u,v) give no frame
    Normal3f n;  // the geometric normal, for plain triangles
};
// FastBVHAccel Inline Functions
template <typename T>
inline unsigned EnteredChildren(const T tNear[fastBVHWidth],
                                const T tFar[fastBVHWidth]) {
    static_assert(fastBVHWidth == 4, "the mask is built for four children");
    int hit[fastBVHWidth];
    for (int c = 0; c < fastBVHWidth; ++c) hit[c] = !(tNear[c] > tFar[c]);
    return unsigned(hit[0] | hit[1] << 1 | hit[2] << 2 | hit[3] << 3);
}

#if defined(__SSE2__)
template <>
inline unsigned EnteredChildren(const float tNear[fastBVHWidth],
                                const float tFar[fastBVHWidth]) {
    __m128 entered = _mm_cmpngt_ps(_mm_loadu_ps(tNear), _mm_loadu_ps(tFar));
    return unsigned(_mm_movemask_ps(entered));
}
#endif
// FastBVHAccel Declarations
class FastBVHAccel : public Aggregate {
  public:
    using SplitMethod = BVHAccel::SplitMethod;
    // FastBVHAccel Public Methods
    FastBVHAccel(std::vector<std::shared_ptr<Primitive>> p,
                 int maxPrimsInNode = 8,
                 SplitMethod splitMethod = SplitMethod::SAH);
    explicit FastBVHAccel(const BVHAccel &bvh);
    Bounds3f WorldBound() const override;
    bool Intersect(const Ray &ray, SurfaceInteraction *isect) const override;
    bool IntersectP(const Ray &ray) const override;
    const LargeArray<FastBVHNode> &Nodes() const { return nodes; }
    FastBVHChild Root() const { return root; }
    const std::vector<std::shared_ptr<Primitive>> &Primitives() const {
        return primitives;
    }
    const LargeArray<FastTriangle> &Triangles() const { return triangles; }
    int MaxPrimsInNode() const { return maxPrimsInNode; }
    BVHStats Stats() const;
  private:
    // FastBVHAccel Private Methods
    void SetRoot(const FastBox &box, FastBVHChild child);
    void CopyTree(const BVHAccel &bvh);
    // FastBVHAccel Private Data
    int maxPrimsInNode;
    std::vector<std::shared_ptr<Primitive>> primitives;
    LargeArray<FastTriangle> triangles;
    LargeArray<FastTriangleInfo> triangleInfo;
    LargeArray<FastBVHNode> nodes;
    FastBVHChild root = {0, 0, 0};
    FastBVHNode rootNode = {};
};

}  // namespace lrt
