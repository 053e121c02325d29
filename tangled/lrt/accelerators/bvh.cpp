// lrt/accelerators/bvh.cpp: tangled from chapters/06-bvh.md. Edit the chapter, not this file.
#include "lrt/accelerators/bvh.h"
#include "lrt/core/slabtest.h"

#include <algorithm>
#include <deque>
#include <limits>
#include <stdexcept>
#include <string>

namespace lrt {

// BVHAccel Local Declarations
struct BVHPrimitiveInfo {
    BVHPrimitiveInfo() {}
    BVHPrimitiveInfo(size_t primitiveNumber, const Bounds3f &bounds)
        : primitiveNumber(primitiveNumber),
          bounds(bounds),
          centroid(bounds.pMin * Float(0.5) + bounds.pMax * Float(0.5)) {}
    size_t primitiveNumber;
    Bounds3f bounds;
    Point3f centroid;
};
struct BVHBuildNode {
    void InitLeaf(int first, int n, const Bounds3f &b) {
        firstPrimOffset = first;
        nPrimitives = n;
        bounds = b;
        children[0] = children[1] = nullptr;
    }
    void InitInterior(int axis, BVHBuildNode *c0, BVHBuildNode *c1) {
        children[0] = c0;
        children[1] = c1;
        bounds = Union(c0->bounds, c1->bounds);
        splitAxis = axis;
        nPrimitives = 0;
    }
    Bounds3f bounds;
    BVHBuildNode *children[2];
    int splitAxis = 0, firstPrimOffset = 0, nPrimitives = 0;
};
struct BVHBuildArena {
    BVHBuildNode *Alloc() {
        nodes.emplace_back();
        return &nodes.back();
    }
    std::deque<BVHBuildNode> nodes;
};
struct MortonPrimitive {
    int primitiveIndex;
    uint32_t mortonCode;
};
struct LBVHTreelet {
    int startIndex, nPrimitives;
    BVHBuildNode *root;
};
// BVHAccel Utility Functions
static int BucketIndex(const Bounds3f &centroidBounds, const Point3f &c,
                       int dim, int nBuckets) {
    Float f = nBuckets * centroidBounds.Offset(c)[dim];
    if (!(f > 0)) return 0;
    if (f >= nBuckets) return nBuckets - 1;
    return int(f);
}
static void RadixSort(std::vector<MortonPrimitive> *v) {
    std::vector<MortonPrimitive> tempVector(v->size());
    constexpr int bitsPerPass = 6;
    constexpr int nBits = 30;
    constexpr int nPasses = nBits / bitsPerPass;
    for (int pass = 0; pass < nPasses; ++pass) {
        // Perform one pass of radix sort, sorting bitsPerPass bits
        int lowBit = pass * bitsPerPass;
        std::vector<MortonPrimitive> &in = (pass & 1) ? tempVector : *v;
        std::vector<MortonPrimitive> &out = (pass & 1) ? *v : tempVector;
        constexpr int nBuckets = 1 << bitsPerPass;
        constexpr uint32_t bitMask = (1 << bitsPerPass) - 1;
        int bucketCount[nBuckets] = {0};
        for (const MortonPrimitive &mp : in)
            bucketCount[(mp.mortonCode >> lowBit) & bitMask]++;
        int outIndex[nBuckets];
        outIndex[0] = 0;
        for (int i = 1; i < nBuckets; ++i)
            outIndex[i] = outIndex[i - 1] + bucketCount[i - 1];
        for (const MortonPrimitive &mp : in) {
            int bucket = (mp.mortonCode >> lowBit) & bitMask;
            out[outIndex[bucket]++] = mp;
        }
    }
    // Copy final result from tempVector, if needed
    if (nPasses & 1) std::swap(*v, tempVector);
}
// BVHAccel Method Definitions
BVHAccel::BVHAccel(std::vector<std::shared_ptr<Primitive>> p,
                   int maxPrimsInNode, SplitMethod splitMethod)
    : maxPrimsInNode(Clamp(maxPrimsInNode, 1, 255)),
      splitMethod(splitMethod),
      primitives(std::move(p)) {
    // Check BVHAccel's arguments
    if (primitives.size() >
        size_t(std::numeric_limits<int>::max() / 2))
        throw std::length_error("BVHAccel: too many primitives");
    if (splitMethod != SplitMethod::SAH && splitMethod != SplitMethod::HLBVH &&
        splitMethod != SplitMethod::Middle &&
        splitMethod != SplitMethod::EqualCounts)
        throw std::invalid_argument("BVHAccel: unknown split method");
    // Initialize primitiveInfo array for primitives
    std::vector<BVHPrimitiveInfo> primitiveInfo;
    primitiveInfo.reserve(primitives.size());
    for (size_t i = 0; i < primitives.size(); ++i) {
        if (!primitives[i])
            throw std::invalid_argument("BVHAccel: primitive " +
                                        std::to_string(i) + " is null");
        Bounds3f b = primitives[i]->WorldBound();
        if (IsFiniteBox(b)) primitiveInfo.push_back(BVHPrimitiveInfo(i, b));
    }
    if (primitiveInfo.empty()) {
        primitives.clear();
        return;
    }
    // Build BVH tree for primitives using primitiveInfo
    BVHBuildArena arena;
    int totalNodes = 0;
    std::vector<std::shared_ptr<Primitive>> orderedPrims;
    orderedPrims.reserve(primitiveInfo.size());
    BVHBuildNode *root;
    if (splitMethod == SplitMethod::HLBVH)
        root = HLBVHBuild(arena, primitiveInfo, &totalNodes, orderedPrims);
    else
        root = recursiveBuild(arena, primitiveInfo, 0,
                              int(primitiveInfo.size()), 0, &totalNodes,
                              orderedPrims);
    primitives.swap(orderedPrims);
    // Compute representation of depth-first traversal of BVH tree
    nodes.resize(totalNodes);
    int offset = 0;
    flattenBVHTree(root, &offset);
}

BVHAccel::~BVHAccel() {}
BVHBuildNode *BVHAccel::recursiveBuild(
    BVHBuildArena &arena, std::vector<BVHPrimitiveInfo> &primitiveInfo,
    int start, int end, int depth, int *totalNodes,
    std::vector<std::shared_ptr<Primitive>> &orderedPrims) const {
    BVHBuildNode *node = arena.Alloc();
    (*totalNodes)++;
    // Compute bounds of all primitives in BVH node
    Bounds3f bounds;
    for (int i = start; i < end; ++i)
        bounds = Union(bounds, primitiveInfo[i].bounds);
    int nPrimitives = end - start;
    if (nPrimitives == 1) {
        // Create leaf BVHBuildNode
        int firstPrimOffset = int(orderedPrims.size());
        for (int i = start; i < end; ++i) {
            size_t primNum = primitiveInfo[i].primitiveNumber;
            orderedPrims.push_back(primitives[primNum]);
        }
        node->InitLeaf(firstPrimOffset, nPrimitives, bounds);
        return node;
    }
    // Compute bound of primitive centroids, choose split dimension dim
    Bounds3f centroidBounds;
    for (int i = start; i < end; ++i)
        centroidBounds = Union(centroidBounds, primitiveInfo[i].centroid);
    int dim = centroidBounds.MaximumExtent();
    // Partition primitives into two sets and build children
    int mid = (start + end) / 2;
    if (centroidBounds.pMax[dim] == centroidBounds.pMin[dim]) {
        if (nPrimitives <= maxPrimsInNode) {
            // Create leaf BVHBuildNode
            int firstPrimOffset = int(orderedPrims.size());
            for (int i = start; i < end; ++i) {
                size_t primNum = primitiveInfo[i].primitiveNumber;
                orderedPrims.push_back(primitives[primNum]);
            }
            node->InitLeaf(firstPrimOffset, nPrimitives, bounds);
            return node;
        }
    } else if (depth + CeilLog2(nPrimitives) >= maxBVHDepth) {
        // Partition primitives into equally sized subsets
        mid = (start + end) / 2;
        std::nth_element(primitiveInfo.begin() + start, primitiveInfo.begin() + mid,
                         primitiveInfo.begin() + end,
                         [dim](const BVHPrimitiveInfo &a,
                               const BVHPrimitiveInfo &b) {
                             return a.centroid[dim] < b.centroid[dim];
                         });
    } else {
        // Partition primitives according to splitMethod
        bool split = false;
        if (splitMethod == SplitMethod::Middle) {
            // Partition primitives through node's midpoint
            Float pmid = (centroidBounds.pMin[dim] + centroidBounds.pMax[dim]) / 2;
            auto midIter = std::partition(
                primitiveInfo.begin() + start, primitiveInfo.begin() + end,
                [dim, pmid](const BVHPrimitiveInfo &pi) {
                    return pi.centroid[dim] < pmid;
                });
            mid = int(midIter - primitiveInfo.begin());
            split = (mid != start && mid != end);
        } else if (splitMethod == SplitMethod::SAH) {
            // Partition primitives using approximate SAH
            if (nPrimitives > 2) {
                // Allocate BucketInfo for SAH partition buckets
                constexpr int nBuckets = 12;
                struct BucketInfo {
                    int count = 0;
                    Bounds3f bounds;
                };
                BucketInfo buckets[nBuckets];
                // Initialize BucketInfo for SAH partition buckets
                for (int i = start; i < end; ++i) {
                    int b = BucketIndex(centroidBounds, primitiveInfo[i].centroid, dim,
                                        nBuckets);
                    buckets[b].count++;
                    buckets[b].bounds = Union(buckets[b].bounds, primitiveInfo[i].bounds);
                }
                // Compute costs for splitting after each bucket
                const Float traversalCost = Float(1) / 8;
                Float area = bounds.SurfaceArea();
                Float invArea = area > 0 ? 1 / area : 0;
                Float cost[nBuckets - 1];
                for (int i = 0; i < nBuckets - 1; ++i) {
                    Bounds3f b0, b1;
                    int count0 = 0, count1 = 0;
                    for (int j = 0; j <= i; ++j) {
                        b0 = Union(b0, buckets[j].bounds);
                        count0 += buckets[j].count;
                    }
                    for (int j = i + 1; j < nBuckets; ++j) {
                        b1 = Union(b1, buckets[j].bounds);
                        count1 += buckets[j].count;
                    }
                    cost[i] = traversalCost +
                              (count0 * b0.SurfaceArea() + count1 * b1.SurfaceArea()) *
                                  invArea;
                }
                // Find bucket to split at that minimizes SAH metric
                Float minCost = cost[0];
                int minCostSplitBucket = 0;
                for (int i = 1; i < nBuckets - 1; ++i) {
                    if (cost[i] < minCost) {
                        minCost = cost[i];
                        minCostSplitBucket = i;
                    }
                }
                // Either create leaf or split primitives at selected SAH bucket
                // Decide whether to split at the selected SAH bucket
                Float leafCost = Float(nPrimitives);
                bool splitHere = nPrimitives > maxPrimsInNode || minCost < leafCost;
                if (splitHere) {
                    auto midIter = std::partition(
                        primitiveInfo.begin() + start, primitiveInfo.begin() + end,
                        [=](const BVHPrimitiveInfo &pi) {
                            return BucketIndex(centroidBounds, pi.centroid, dim,
                                               nBuckets) <= minCostSplitBucket;
                        });
                    mid = int(midIter - primitiveInfo.begin());
                    split = (mid != start && mid != end);
                } else {
                    // Create leaf BVHBuildNode
                    int firstPrimOffset = int(orderedPrims.size());
                    for (int i = start; i < end; ++i) {
                        size_t primNum = primitiveInfo[i].primitiveNumber;
                        orderedPrims.push_back(primitives[primNum]);
                    }
                    node->InitLeaf(firstPrimOffset, nPrimitives, bounds);
                    return node;
                }
            }
        }
        if (!split) {
            // Partition primitives into equally sized subsets
            mid = (start + end) / 2;
            std::nth_element(primitiveInfo.begin() + start, primitiveInfo.begin() + mid,
                             primitiveInfo.begin() + end,
                             [dim](const BVHPrimitiveInfo &a,
                                   const BVHPrimitiveInfo &b) {
                                 return a.centroid[dim] < b.centroid[dim];
                             });
        }
    }
    // The first child is built first, so its primitives come first in
    // orderedPrims; as two arguments of one call, the builds would run in an
    // order each compiler chooses for itself (GCC's is the second first)
    BVHBuildNode *c0 = recursiveBuild(arena, primitiveInfo, start, mid,
                                      depth + 1, totalNodes, orderedPrims);
    BVHBuildNode *c1 = recursiveBuild(arena, primitiveInfo, mid, end,
                                      depth + 1, totalNodes, orderedPrims);
    node->InitInterior(dim, c0, c1);
    return node;
}
BVHBuildNode *BVHAccel::HLBVHBuild(
    BVHBuildArena &arena,
    const std::vector<BVHPrimitiveInfo> &primitiveInfo, int *totalNodes,
    std::vector<std::shared_ptr<Primitive>> &orderedPrims) const {
    // Compute bounding box of all primitive centroids
    Bounds3f bounds;
    for (const BVHPrimitiveInfo &pi : primitiveInfo)
        bounds = Union(bounds, pi.centroid);
    // Compute Morton indices of primitives
    constexpr int mortonBits = 10;
    constexpr int mortonScale = 1 << mortonBits;
    std::vector<MortonPrimitive> mortonPrims(primitiveInfo.size());
    for (size_t i = 0; i < primitiveInfo.size(); ++i) {
        mortonPrims[i].primitiveIndex = int(i);
        Vector3f centroidOffset = bounds.Offset(primitiveInfo[i].centroid);
        mortonPrims[i].mortonCode = EncodeMorton3(centroidOffset * mortonScale);
    }
    // Radix sort primitive Morton indices
    RadixSort(&mortonPrims);
    // Create LBVH treelets at bottom of BVH
    std::vector<LBVHTreelet> treeletsToBuild;
    constexpr uint32_t treeletMask = 0x3FFC0000;  // bits 18 to 29
    for (int start = 0, end = 1; end <= int(mortonPrims.size()); ++end) {
        if (end == int(mortonPrims.size()) ||
            (mortonPrims[start].mortonCode & treeletMask) !=
                (mortonPrims[end].mortonCode & treeletMask)) {
            treeletsToBuild.push_back({start, end - start, nullptr});
            start = end;
        }
    }
    // Build the LBVH treelets
    int treeletDepth = 0;
    for (LBVHTreelet &tr : treeletsToBuild) {
        constexpr int firstBitIndex = 29 - 12;
        tr.root = emitLBVH(arena, primitiveInfo, &mortonPrims[tr.startIndex],
                           tr.nPrimitives, firstBitIndex, 0, &treeletDepth,
                           totalNodes, orderedPrims);
    }
    // Create and return SAH BVH from LBVH treelets
    std::vector<BVHBuildNode *> finishedTreelets;
    finishedTreelets.reserve(treeletsToBuild.size());
    for (LBVHTreelet &treelet : treeletsToBuild)
        finishedTreelets.push_back(treelet.root);
    return buildUpperSAH(arena, finishedTreelets, 0,
                         int(finishedTreelets.size()), 0, treeletDepth,
                         totalNodes);
}
BVHBuildNode *BVHAccel::emitLBVH(
    BVHBuildArena &arena,
    const std::vector<BVHPrimitiveInfo> &primitiveInfo,
    MortonPrimitive *mortonPrims, int nPrimitives, int bitIndex,
    int depth, int *maxDepth, int *totalNodes,
    std::vector<std::shared_ptr<Primitive>> &orderedPrims) const {
    if (nPrimitives <= maxPrimsInNode) {
        // Create and return leaf node of LBVH treelet
        (*totalNodes)++;
        BVHBuildNode *node = arena.Alloc();
        Bounds3f bounds;
        int firstPrimOffset = int(orderedPrims.size());
        for (int i = 0; i < nPrimitives; ++i) {
            const BVHPrimitiveInfo &pi = primitiveInfo[mortonPrims[i].primitiveIndex];
            orderedPrims.push_back(primitives[pi.primitiveNumber]);
            bounds = Union(bounds, pi.bounds);
        }
        node->InitLeaf(firstPrimOffset, nPrimitives, bounds);
        *maxDepth = std::max(*maxDepth, depth);
        return node;
    }
    int splitOffset = nPrimitives / 2, axis = 0;
    if (bitIndex >= 0) {
        uint32_t mask = uint32_t(1) << bitIndex;
        // Advance to next subtree level if there is no LBVH split for this bit
        if ((mortonPrims[0].mortonCode & mask) ==
            (mortonPrims[nPrimitives - 1].mortonCode & mask))
            return emitLBVH(arena, primitiveInfo, mortonPrims, nPrimitives,
                            bitIndex - 1, depth, maxDepth, totalNodes,
                            orderedPrims);
        // Find LBVH split point for this dimension
        int searchStart = 0, searchEnd = nPrimitives - 1;
        while (searchStart + 1 != searchEnd) {
            int mid = (searchStart + searchEnd) / 2;
            if ((mortonPrims[searchStart].mortonCode & mask) ==
                (mortonPrims[mid].mortonCode & mask))
                searchStart = mid;
            else
                searchEnd = mid;
        }
        splitOffset = searchEnd;
        axis = bitIndex % 3;
    }
    // Create and return interior LBVH node
    (*totalNodes)++;
    BVHBuildNode *node = arena.Alloc();
    int nextBit = std::max(bitIndex - 1, -1);
    BVHBuildNode *c0 = emitLBVH(arena, primitiveInfo, mortonPrims, splitOffset,
                                nextBit, depth + 1, maxDepth, totalNodes,
                                orderedPrims);
    BVHBuildNode *c1 = emitLBVH(arena, primitiveInfo, &mortonPrims[splitOffset],
                                nPrimitives - splitOffset, nextBit, depth + 1,
                                maxDepth, totalNodes, orderedPrims);
    node->InitInterior(axis, c0, c1);
    return node;
}
BVHBuildNode *BVHAccel::buildUpperSAH(
    BVHBuildArena &arena, std::vector<BVHBuildNode *> &treeletRoots,
    int start, int end, int depth, int treeletDepth,
    int *totalNodes) const {
    int nNodes = end - start;
    if (nNodes == 1) return treeletRoots[start];
    (*totalNodes)++;
    BVHBuildNode *node = arena.Alloc();
    // Compute bounds of all nodes under this HLBVH node
    Bounds3f bounds;
    for (int i = start; i < end; ++i)
        bounds = Union(bounds, treeletRoots[i]->bounds);
    // Compute bound of HLBVH node centroids, choose split dimension dim
    auto centroidOf = [](const BVHBuildNode *n) {
        return n->bounds.pMin * Float(0.5) + n->bounds.pMax * Float(0.5);
    };
    Bounds3f centroidBounds;
    for (int i = start; i < end; ++i)
        centroidBounds = Union(centroidBounds, centroidOf(treeletRoots[i]));
    int dim = centroidBounds.MaximumExtent();
    int mid = (start + end) / 2;
    if (centroidBounds.pMax[dim] > centroidBounds.pMin[dim] &&
        depth + CeilLog2(nNodes) + treeletDepth < maxBVHDepth) {
        // Partition the HLBVH nodes at the SAH bucket of least cost
        constexpr int nBuckets = 12;
        struct BucketInfo {
            int count = 0;
            Bounds3f bounds;
        };
        BucketInfo buckets[nBuckets];
        for (int i = start; i < end; ++i) {
            int b = BucketIndex(centroidBounds, centroidOf(treeletRoots[i]), dim,
                                nBuckets);
            buckets[b].count++;
            buckets[b].bounds = Union(buckets[b].bounds, treeletRoots[i]->bounds);
        }
        // Compute costs for splitting after each bucket
        const Float traversalCost = Float(1) / 8;
        Float area = bounds.SurfaceArea();
        Float invArea = area > 0 ? 1 / area : 0;
        Float cost[nBuckets - 1];
        for (int i = 0; i < nBuckets - 1; ++i) {
            Bounds3f b0, b1;
            int count0 = 0, count1 = 0;
            for (int j = 0; j <= i; ++j) {
                b0 = Union(b0, buckets[j].bounds);
                count0 += buckets[j].count;
            }
            for (int j = i + 1; j < nBuckets; ++j) {
                b1 = Union(b1, buckets[j].bounds);
                count1 += buckets[j].count;
            }
            cost[i] = traversalCost +
                      (count0 * b0.SurfaceArea() + count1 * b1.SurfaceArea()) *
                          invArea;
        }
        // Find bucket to split at that minimizes SAH metric
        Float minCost = cost[0];
        int minCostSplitBucket = 0;
        for (int i = 1; i < nBuckets - 1; ++i) {
            if (cost[i] < minCost) {
                minCost = cost[i];
                minCostSplitBucket = i;
            }
        }
        auto midIter = std::partition(
            treeletRoots.begin() + start, treeletRoots.begin() + end,
            [=](const BVHBuildNode *n) {
                return BucketIndex(centroidBounds, centroidOf(n), dim, nBuckets) <=
                       minCostSplitBucket;
            });
        int splitAt = int(midIter - treeletRoots.begin());
        if (splitAt != start && splitAt != end) mid = splitAt;
    }
    node->InitInterior(
        dim,
        buildUpperSAH(arena, treeletRoots, start, mid, depth + 1,
                      treeletDepth, totalNodes),
        buildUpperSAH(arena, treeletRoots, mid, end, depth + 1,
                      treeletDepth, totalNodes));
    return node;
}
int BVHAccel::flattenBVHTree(const BVHBuildNode *node, int *offset) {
    LinearBVHNode *linearNode = &nodes[*offset];
    linearNode->bounds = node->bounds;
    int myOffset = (*offset)++;
    if (node->nPrimitives > 0) {
        linearNode->primitivesOffset = node->firstPrimOffset;
        linearNode->nPrimitives = uint16_t(node->nPrimitives);
        linearNode->axis = 0;
    } else {
        linearNode->axis = uint8_t(node->splitAxis);
        linearNode->nPrimitives = 0;
        flattenBVHTree(node->children[0], offset);
        int second = flattenBVHTree(node->children[1], offset);
        nodes[myOffset].secondChildOffset = second;
    }
    return myOffset;
}
Bounds3f BVHAccel::WorldBound() const {
    return nodes.empty() ? Bounds3f() : nodes[0].bounds;
}
bool BVHAccel::Intersect(const Ray &ray, SurfaceInteraction *isect) const {
    if (nodes.empty()) return false;
    bool hit = false;
    Vector3f invDir(1 / ray.d.x, 1 / ray.d.y, 1 / ray.d.z);
    int dirIsNeg[3] = {invDir.x < 0, invDir.y < 0, invDir.z < 0};
    // Follow ray through BVH nodes to find primitive intersections
    int toVisitOffset = 0, currentNodeIndex = 0;
    int nodesToVisit[maxBVHDepth];
    while (true) {
        const LinearBVHNode *node = &nodes[currentNodeIndex];
        if (node->bounds.IntersectP(ray, invDir, dirIsNeg)) {
            if (node->nPrimitives > 0) {
                // Intersect ray with primitives in leaf BVH node
                for (int i = 0; i < node->nPrimitives; ++i)
                    if (primitives[node->primitivesOffset + i]->Intersect(ray, isect))
                        hit = true;
                if (toVisitOffset == 0) break;
                currentNodeIndex = nodesToVisit[--toVisitOffset];
            } else {
                // Put far BVH node on nodesToVisit stack, advance to near node
                if (dirIsNeg[node->axis]) {
                    nodesToVisit[toVisitOffset++] = currentNodeIndex + 1;
                    currentNodeIndex = node->secondChildOffset;
                } else {
                    nodesToVisit[toVisitOffset++] = node->secondChildOffset;
                    currentNodeIndex = currentNodeIndex + 1;
                }
            }
        } else {
            if (toVisitOffset == 0) break;
            currentNodeIndex = nodesToVisit[--toVisitOffset];
        }
    }
    return hit;
}
bool BVHAccel::IntersectP(const Ray &ray) const {
    if (nodes.empty()) return false;
    Vector3f invDir(1 / ray.d.x, 1 / ray.d.y, 1 / ray.d.z);
    int dirIsNeg[3] = {invDir.x < 0, invDir.y < 0, invDir.z < 0};
    int nodesToVisit[maxBVHDepth];
    int toVisitOffset = 0, currentNodeIndex = 0;
    while (true) {
        const LinearBVHNode *node = &nodes[currentNodeIndex];
        if (node->bounds.IntersectP(ray, invDir, dirIsNeg)) {
            if (node->nPrimitives > 0) {
                for (int i = 0; i < node->nPrimitives; ++i)
                    if (primitives[node->primitivesOffset + i]->IntersectP(
                            ray))
                        return true;
                if (toVisitOffset == 0) break;
                currentNodeIndex = nodesToVisit[--toVisitOffset];
            } else {
                // Put far BVH node on nodesToVisit stack, advance to near node
                if (dirIsNeg[node->axis]) {
                    nodesToVisit[toVisitOffset++] = currentNodeIndex + 1;
                    currentNodeIndex = node->secondChildOffset;
                } else {
                    nodesToVisit[toVisitOffset++] = node->secondChildOffset;
                    currentNodeIndex = currentNodeIndex + 1;
                }
            }
        } else {
            if (toVisitOffset == 0) break;
            currentNodeIndex = nodesToVisit[--toVisitOffset];
        }
    }
    return false;
}
BVHStats BVHAccel::Stats() const {
    BVHStats s;
    if (nodes.empty()) return s;
    double rootArea = BoxArea(nodes[0].bounds);
    std::vector<std::pair<int, int>> todo = {{0, 0}};
    while (!todo.empty()) {
        auto [index, depth] = todo.back();
        todo.pop_back();
        const LinearBVHNode &node = nodes[index];
        double p = HitProbability(BoxArea(node.bounds), rootArea);
        s.maxDepth = std::max(s.maxDepth, depth);
        if (node.nPrimitives > 0) {
            s.leafNodes++;
            s.primitives += node.nPrimitives;
            s.maxLeafSize = std::max(s.maxLeafSize, int(node.nPrimitives));
            s.sahCost += p * node.nPrimitives;
        } else {
            s.interiorNodes++;
            s.sahCost += p;
            todo.push_back({index + 1, depth + 1});
            todo.push_back({node.secondChildOffset, depth + 1});
        }
    }
    return s;
}

}  // namespace lrt
