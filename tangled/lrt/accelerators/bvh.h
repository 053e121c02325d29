// lrt/accelerators/bvh.h: tangled from chapters/06-bvh.md. Edit the chapter, not this file.
#pragma once

#include "lrt/core/base.h"
#include "lrt/core/geometry.h"
#include "lrt/core/primitive.h"

#include <cstdint>
#include <memory>
#include <vector>

namespace lrt {

struct BVHBuildNode;
struct BVHBuildArena;
struct BVHPrimitiveInfo;
struct MortonPrimitive;
// BVH Constants and Inline Functions
inline bool IsFiniteBox(const Bounds3f &b) {
    for (int i = 0; i < 3; ++i)
        if (!std::isfinite(b.pMin[i]) || !std::isfinite(b.pMax[i]) ||
            !(b.pMin[i] <= b.pMax[i]))
            return false;
    return true;
}
constexpr int maxBVHDepth = 64;

inline int CeilLog2(int64_t n) {
    return n <= 1 ? 0 : Log2Int(int64_t(n - 1)) + 1;
}
inline uint32_t LeftShift3(uint32_t x) {
    if (x > 1023) x = 1023;
    // Spread the ten bits of x apart
    x = (x | (x << 16)) & 0x030000FF;  // 98 ........ 76543210
    x = (x | (x << 8)) & 0x0300F00F;   // 98 .... 7654 .... 3210
    x = (x | (x << 4)) & 0x030C30C3;   // 98 .. 76 .. 54 .. 32 .. 10
    x = (x | (x << 2)) & 0x09249249;   // 9..8..7..6..5..4..3..2..1..0
    return x;
}
inline uint32_t QuantizeMorton(Float v) {
    if (!(v > 0)) return 0;
    if (v >= 1023) return 1023;
    return uint32_t(v);
}

inline uint32_t EncodeMorton3(const Vector3f &v) {
    // Interleave the quantized coordinates of v
    return (LeftShift3(QuantizeMorton(v.z)) << 2) |
           (LeftShift3(QuantizeMorton(v.y)) << 1) |
           LeftShift3(QuantizeMorton(v.x));
}
// LinearBVHNode Definition
struct alignas(32) LinearBVHNode {
    Bounds3f bounds;
    union {
        int primitivesOffset;   // leaf
        int secondChildOffset;  // interior
    };
    uint16_t nPrimitives;  // 0 -> interior node
    uint8_t axis;          // interior node: xyz
    uint8_t pad[1];        // ensure 32 byte total size
};
static_assert(sizeof(LinearBVHNode) == (sizeof(Float) == 4 ? 32 : 64),
              "LinearBVHNode should fill half a cache line");
// BVHStats Definition
struct BVHStats {
    int64_t interiorNodes = 0, leafNodes = 0, primitives = 0;
    int maxDepth = 0, maxLeafSize = 0;
    double sahCost = 0;
    int64_t TotalNodes() const { return interiorNodes + leafNodes; }
    double AverageLeafSize() const {
        return leafNodes > 0 ? double(primitives) / double(leafNodes) : 0;
    }
};

inline double BoxArea(const Bounds3f &b) {
    if (b.IsEmpty()) return 0;
    double dx = double(b.pMax.x) - double(b.pMin.x);
    double dy = double(b.pMax.y) - double(b.pMin.y);
    double dz = double(b.pMax.z) - double(b.pMin.z);
    return 2 * (dx * dy + dx * dz + dy * dz);
}

inline double HitProbability(double area, double rootArea) {
    return rootArea > 0 && rootArea < Infinity ? area / rootArea : 1;
}
// BVHAccel Declarations
class BVHAccel : public Aggregate {
  public:
    // BVHAccel Public Types
    enum class SplitMethod { SAH, HLBVH, Middle, EqualCounts };
    static const char *SplitMethodName(SplitMethod m) {
        switch (m) {
        case SplitMethod::SAH: return "SAH";
        case SplitMethod::HLBVH: return "HLBVH";
        case SplitMethod::Middle: return "Middle";
        case SplitMethod::EqualCounts: return "EqualCounts";
        }
        return "unknown";
    }
    // BVHAccel Public Methods
    BVHAccel(std::vector<std::shared_ptr<Primitive>> p,
             int maxPrimsInNode = 1, SplitMethod splitMethod = SplitMethod::SAH);
    ~BVHAccel();
    Bounds3f WorldBound() const override;
    bool Intersect(const Ray &ray, SurfaceInteraction *isect) const override;
    bool IntersectP(const Ray &ray) const override;
    const std::vector<LinearBVHNode> &Nodes() const { return nodes; }
    const std::vector<std::shared_ptr<Primitive>> &Primitives() const {
        return primitives;
    }
    int MaxPrimsInNode() const { return maxPrimsInNode; }
    SplitMethod GetSplitMethod() const { return splitMethod; }
    BVHStats Stats() const;
  private:
    // BVHAccel Private Methods
    BVHBuildNode *recursiveBuild(
        BVHBuildArena &arena, std::vector<BVHPrimitiveInfo> &primitiveInfo,
        int start, int end, int depth, int *totalNodes,
        std::vector<std::shared_ptr<Primitive>> &orderedPrims) const;
    BVHBuildNode *HLBVHBuild(
        BVHBuildArena &arena,
        const std::vector<BVHPrimitiveInfo> &primitiveInfo, int *totalNodes,
        std::vector<std::shared_ptr<Primitive>> &orderedPrims) const;
    BVHBuildNode *emitLBVH(
        BVHBuildArena &arena,
        const std::vector<BVHPrimitiveInfo> &primitiveInfo,
        MortonPrimitive *mortonPrims, int nPrimitives, int bitIndex,
        int depth, int *maxDepth, int *totalNodes,
        std::vector<std::shared_ptr<Primitive>> &orderedPrims) const;
    BVHBuildNode *buildUpperSAH(BVHBuildArena &arena,
                                std::vector<BVHBuildNode *> &treeletRoots,
                                int start, int end, int depth,
                                int treeletDepth, int *totalNodes) const;
    int flattenBVHTree(const BVHBuildNode *node, int *offset);
    // BVHAccel Private Data
    const int maxPrimsInNode;
    const SplitMethod splitMethod;
    std::vector<std::shared_ptr<Primitive>> primitives;
    std::vector<LinearBVHNode> nodes;
};

}  // namespace lrt
