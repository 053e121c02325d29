// lrt/accelerators/fastbvh.cpp: tangled from chapters/07-fast-bvh.md. Edit the chapter, not this file.
#include "lrt/accelerators/fastbvh.h"
#include "lrt/core/platform.h"

#include <algorithm>
#include <limits>
#include <new>
#include <stdexcept>
#include <string>
#include <typeinfo>

namespace lrt {

// Triangle Utility Functions
static inline Float MaxAbs(Float a, Float b, Float c) {
    return std::max(std::abs(a), std::max(std::abs(b), std::abs(c)));
}
// FastBVHAccel Local Declarations
struct FastBVHBuildPrim {
    Float lo[4], hi[4];
    int index;
    bool isTriangle;
    uint8_t bin;
    Float Centroid(int dim) const {
        return lo[dim] * Float(0.5) + hi[dim] * Float(0.5);
    }
};
struct FastBox {
    Float lo[4], hi[4];
    static FastBox Empty() {
        return {{Infinity, Infinity, Infinity, Infinity},
                {-Infinity, -Infinity, -Infinity, -Infinity}};
    }
    void Grow(const Float l[4], const Float h[4]) {
        for (int a = 0; a < 4; ++a) lo[a] = l[a] < lo[a] ? l[a] : lo[a];
        for (int a = 0; a < 4; ++a) hi[a] = h[a] > hi[a] ? h[a] : hi[a];
    }
    void Grow(const FastBox &b) { Grow(b.lo, b.hi); }
    Float HalfArea() const {
        Float dx = hi[0] - lo[0], dy = hi[1] - lo[1], dz = hi[2] - lo[2];
        if (!(dx >= 0 && dy >= 0 && dz >= 0)) return 0;
        return dx * dy + dy * dz + dz * dx;
    }
    int MaximumExtent() const {
        Float dx = hi[0] - lo[0], dy = hi[1] - lo[1], dz = hi[2] - lo[2];
        return (dx > dy && dx > dz) ? 0 : (dy > dz ? 1 : 2);
    }
};
class SAHBinaryTree {
  public:
    struct Node {
        FastBox box;
        int start, end, depth, mid;
        FastBox childBox[2];
        FastBVHChild leaf;
    };
    SAHBinaryTree(std::vector<FastBVHBuildPrim> *prims, int maxPrimsInNode)
        : prims(*prims), maxPrimsInNode(maxPrimsInNode) {}
    Node Root(const FastBox &box) {
        Node root;
        MakeNode(&root, 0, int(prims.size()), box, 0);
        return root;
    }
    bool IsLeaf(const Node &node) const { return node.mid < 0; }
    FastBVHChild Leaf(const Node &node) const { return node.leaf; }
    FastBox Box(const Node &node) const { return node.box; }
    void Open(const Node &node, Node child[2]) {
        int depth = node.depth + 1;
        MakeNode(&child[0], node.start, node.mid, node.childBox[0], depth);
        MakeNode(&child[1], node.mid, node.end, node.childBox[1], depth);
    }

  private:
    void MakeNode(Node *node, int start, int end, const FastBox &box,
                  int depth);
    void MakeLeaf(Node *node);
    std::vector<FastBVHBuildPrim> &prims;
    int maxPrimsInNode;
};
constexpr int fastBVHBins = 16;
constexpr Float fastBVHTraversalCost = 3;
constexpr Float fastBVHIntersectionCost = 1;

struct FastBVHBin {
    FastBox box;
    int count;
};
struct FastRay {
    explicit FastRay(const Ray &ray) {
        ox = ray.o.x;
        oy = ray.o.y;
        oz = ray.o.z;
        ix = 1 / ray.d.x;
        iy = 1 / ray.d.y;
        iz = 1 / ray.d.z;
        octant = (ix < 0) | (iy < 0) << 1 | (iz < 0) << 2;
        o[0] = ox;
        o[1] = oy;
        o[2] = oz;
        // Compute the ray's permutation and shear for triangle tests
        {
            // Choose the ray's permuted axes kx, ky, kz and direction d
            int kz = MaxDimension(Abs(ray.d));
            int kx = kz + 1;
            if (kx == 3) kx = 0;
            int ky = kx + 1;
            if (ky == 3) ky = 0;
            Vector3f d = Permute(ray.d, kx, ky, kz);
            // Compute the ray's shear coefficients Sx, Sy, Sz
            Float Sx = -d.x / d.z;
            Float Sy = -d.y / d.z;
            Float Sz = 1 / d.z;
            this->kx = kx;
            this->ky = ky;
            this->kz = kz;
            this->Sx = Sx;
            this->Sy = Sy;
            this->Sz = Sz;
        }
    }
    Float ox, oy, oz, ix, iy, iz;
    int octant;
    Float o[3];
    int kx, ky, kz;
    Float Sx, Sy, Sz;
};
struct FastTriangleHit {
    Float t, e0, e1, e2, invDet;
};
constexpr int8_t lowestSetBit[16] = {0, 0, 1, 0, 2, 0, 1, 0,
                                     3, 0, 1, 0, 2, 0, 1, 0};
// FastBVHAccel Utility Functions
static void SetChildBox(FastBVHNode *node, int c, const Float lo[3],
                        const Float hi[3]) {
    for (int a = 0; a < 3; ++a) {
        node->bounds[a][0][c] = lo[a];
        node->bounds[a][1][c] = hi[a];
    }
}

static Bounds3f GetChildBox(const FastBVHNode &node, int c) {
    Bounds3f b;
    b.pMin = Point3f(node.bounds[0][0][c], node.bounds[1][0][c],
                     node.bounds[2][0][c]);
    b.pMax = Point3f(node.bounds[0][1][c], node.bounds[1][1][c],
                     node.bounds[2][1][c]);
    return b;
}
static bool PassesDegenerateTest(const Point3f &p0, const Point3f &p1,
                                 const Point3f &p2) {
    // Reject degenerate triangles
    Vector3f dp02 = p0 - p2, dp12 = p1 - p2;
    Vector3f ng = Cross(dp02, dp12);
    if (ng.LengthSquared() == 0) return false;
    return true;
}

static const Triangle *GetTriangle(const Primitive *p) {
    if (typeid(*p) != typeid(GeometricPrimitive)) return nullptr;
    const Shape *s = static_cast<const GeometricPrimitive *>(p)->GetShape();
    if (typeid(*s) != typeid(Triangle)) return nullptr;
    return static_cast<const Triangle *>(s);
}

static void DefaultUVDerivatives(const Vector3f &dp02, const Vector3f &dp12,
                                 Vector3f *dpdu, Vector3f *dpdv);

static bool StoreTriangle(FastTriangle *ft, FastTriangleInfo *info,
                          const Triangle *tri) {
    Point3f q[3];
    tri->GetVertices(&q[0], &q[1], &q[2]);
    if (!PassesDegenerateTest(q[0], q[1], q[2])) return false;
    for (int a = 0; a < 3; ++a) {
        for (int i = 0; i < 3; ++i) ft->c[a][i] = q[i][a];
        ft->c[a][3] = 0;
    }
    *info = {tri, tri->FaceIndex(), tri->FlipsNormal(),
             !tri->HasVertexAttributes(), false, Normal3f(0, 0, 0)};
    if (info->plain) {
        Vector3f dp02 = q[0] - q[2], dp12 = q[1] - q[2];
        info->n = Normal3f(Normalize(Cross(dp02, dp12)));
        Vector3f dpdu, dpdv;
        DefaultUVDerivatives(dp02, dp12, &dpdu, &dpdv);
        info->parallelDerivatives = Cross(dpdu, dpdv).LengthSquared() == 0;
    }
    return true;
}
static inline int BinIndex(Float c, Float cMin, Float scale, int nBins) {
    Float f = (c - cMin) * scale;
    if (!(f > 0)) return 0;
    if (f >= nBins) return nBins - 1;
    return int(f);
}
static FastBox ToFastBox(const Bounds3f &b) {
    return {{b.pMin.x, b.pMin.y, b.pMin.z, b.pMin.z},
            {b.pMax.x, b.pMax.y, b.pMax.z, b.pMax.z}};
}

static const FastBVHNode &EmptyNode() {
    static const FastBVHNode emptyNode = [] {
        FastBVHNode node;
        FastBox empty = FastBox::Empty();
        for (int c = 0; c < fastBVHWidth; ++c) {
            SetChildBox(&node, c, empty.lo, empty.hi);
            node.child[c] = {0, 0, 0};
        }
        return node;
    }();
    return emptyNode;
}
template <typename BinaryTree>
static FastBVHChild BuildWide(BinaryTree &tree,
                              const typename BinaryTree::Node &node,
                              LargeArray<FastBVHNode> *nodes) {
    if (tree.IsLeaf(node)) return tree.Leaf(node);
    // Gather up to four children by opening the largest interior ones
    typename BinaryTree::Node child[fastBVHWidth];
    tree.Open(node, child);
    int n = 2;
    while (n < fastBVHWidth) {
        int open = -1;
        Float largest = -1;
        for (int k = 0; k < n; ++k) {
            if (tree.IsLeaf(child[k])) continue;
            Float area = tree.Box(child[k]).HalfArea();
            if (area > largest) {
                largest = area;
                open = k;
            }
        }
        if (open < 0) break;
        typename BinaryTree::Node opened[2];
        tree.Open(child[open], opened);
        child[open] = opened[0];
        child[n++] = opened[1];
    }
    int nodeIndex = int(nodes->size());
    nodes->push_back(EmptyNode());
    for (int k = 0; k < n; ++k) {
        FastBox box = tree.Box(child[k]);
        SetChildBox(&(*nodes)[nodeIndex], k, box.lo, box.hi);
    }
    for (int k = 0; k < n; ++k) {
        FastBVHChild wide = BuildWide(tree, child[k], nodes);
        (*nodes)[nodeIndex].child[k] = wide;
    }
    return {uint32_t(nodeIndex), fastBVHInterior, 0};
}
class AdoptedBinaryTree {
  public:
    struct Node {
        int index;
    };
    AdoptedBinaryTree(const BVHAccel &bvh,
                      std::vector<std::shared_ptr<Primitive>> *primitives,
                      LargeArray<FastTriangle> *triangles,
                      LargeArray<FastTriangleInfo> *triangleInfo)
        : bvh(bvh), primitives(*primitives), triangles(*triangles),
          triangleInfo(*triangleInfo) {}
    bool IsLeaf(const Node &node) const {
        return bvh.Nodes()[node.index].nPrimitives > 0;
    }
    FastBVHChild Leaf(const Node &node);
    FastBox Box(const Node &node) const {
        return ToFastBox(bvh.Nodes()[node.index].bounds);
    }
    void Open(const Node &node, Node child[2]) const {
        child[0] = {node.index + 1};
        child[1] = {bvh.Nodes()[node.index].secondChildOffset};
    }

  private:
    const BVHAccel &bvh;
    std::vector<std::shared_ptr<Primitive>> &primitives;
    LargeArray<FastTriangle> &triangles;
    LargeArray<FastTriangleInfo> &triangleInfo;
    std::vector<int> others;
};
static LRT_ALWAYS_INLINE bool IntersectTriangle(const FastTriangle &tri,
                                                const FastRay &fr,
                                                const Ray &ray,
                                                FastTriangleHit *hit) {
#if defined(__SSE2__) && !defined(LRT_FLOAT_AS_DOUBLE)
    // Compute the edge functions with SSE2 and reject a miss
    __m128 px = _mm_sub_ps(_mm_load_ps(tri.c[fr.kx]), _mm_set1_ps(fr.o[fr.kx]));
    __m128 py = _mm_sub_ps(_mm_load_ps(tri.c[fr.ky]), _mm_set1_ps(fr.o[fr.ky]));
    __m128 pz = _mm_sub_ps(_mm_load_ps(tri.c[fr.kz]), _mm_set1_ps(fr.o[fr.kz]));
    __m128 xs = _mm_add_ps(px, _mm_mul_ps(_mm_set1_ps(fr.Sx), pz));
    __m128 ys = _mm_add_ps(py, _mm_mul_ps(_mm_set1_ps(fr.Sy), pz));
    // Lane i of next holds vertex i + 1 (modulo 3), and lane i of es holds
    // x_i y_{i+1} - y_i x_{i+1}, which is e_{i+2}: e2, e0, e1
    __m128 xNext = _mm_shuffle_ps(xs, xs, _MM_SHUFFLE(3, 0, 2, 1));
    __m128 yNext = _mm_shuffle_ps(ys, ys, _MM_SHUFFLE(3, 0, 2, 1));
    __m128 es = _mm_sub_ps(_mm_mul_ps(xs, yNext), _mm_mul_ps(ys, xNext));
    // The sign bits are the signs where the squares are greater than zero
    // (not zero, NaN or tiny); reject if all three are and the signs differ
    __m128 nonzeroLanes = _mm_cmpgt_ps(_mm_mul_ps(es, es), _mm_setzero_ps());
    unsigned nonzero = unsigned(_mm_movemask_ps(nonzeroLanes)) & 7u;
    unsigned negative = unsigned(_mm_movemask_ps(es)) & 7u;
    if (nonzero == 7u && negative != 0 && negative != 7u) return false;
    // Unpack the vector lanes into the scalar test's variables
    alignas(16) float lane[6][4];
    _mm_store_ps(lane[0], px);
    _mm_store_ps(lane[1], py);
    _mm_store_ps(lane[2], pz);
    _mm_store_ps(lane[3], xs);
    _mm_store_ps(lane[4], ys);
    _mm_store_ps(lane[5], es);
    Point3f p0t(lane[0][0], lane[1][0], lane[2][0]);
    Point3f p1t(lane[0][1], lane[1][1], lane[2][1]);
    Point3f p2t(lane[0][2], lane[1][2], lane[2][2]);
    Float x0 = lane[3][0], x1 = lane[3][1], x2 = lane[3][2];
    Float y0 = lane[4][0], y1 = lane[4][1], y2 = lane[4][2];
    Float e0 = lane[5][1], e1 = lane[5][2], e2 = lane[5][0];
    const Float Sz = fr.Sz;
    const bool signsTested = nonzero == 7u;
#else
    // Translate and permute the vertices with the ray's axes
    const int kx = fr.kx, ky = fr.ky, kz = fr.kz;
    Point3f p0t(tri.c[kx][0] - fr.o[kx], tri.c[ky][0] - fr.o[ky],
                tri.c[kz][0] - fr.o[kz]);
    Point3f p1t(tri.c[kx][1] - fr.o[kx], tri.c[ky][1] - fr.o[ky],
                tri.c[kz][1] - fr.o[kz]);
    Point3f p2t(tri.c[kx][2] - fr.o[kx], tri.c[ky][2] - fr.o[ky],
                tri.c[kz][2] - fr.o[kz]);
    // Shear the vertices with the ray's coefficients
    const Float Sx = fr.Sx, Sy = fr.Sy, Sz = fr.Sz;
    // Shear the translated vertices into x0, y0, x1, y1, x2, y2
    Float x0 = p0t.x + Sx * p0t.z, y0 = p0t.y + Sy * p0t.z;
    Float x1 = p1t.x + Sx * p1t.z, y1 = p1t.y + Sy * p1t.z;
    Float x2 = p2t.x + Sx * p2t.z, y2 = p2t.y + Sy * p2t.z;
    // Compute edge function coefficients e0, e1, and e2
    Float e0 = x1 * y2 - y1 * x2;
    Float e1 = x2 * y0 - y2 * x0;
    Float e2 = x0 * y1 - y0 * x1;
    const bool signsTested = false;
#endif
    if (!signsTested) {
        // Test the signs of the edge functions with few branches
        if (sizeof(Float) == sizeof(float) && ((e0 == 0) | (e1 == 0) | (e2 == 0))) {
            e0 = Float(double(x1) * double(y2) - double(y1) * double(x2));
            e1 = Float(double(x2) * double(y0) - double(y2) * double(x0));
            e2 = Float(double(x0) * double(y1) - double(y0) * double(x1));
        }
        if (((e0 < 0) | (e1 < 0) | (e2 < 0)) & ((e0 > 0) | (e1 > 0) | (e2 > 0)))
            return false;
    }
    Float det = e0 + e1 + e2;
    if (det == 0) return false;
    // Compute scaled hit distance to triangle and test against ray t range
    Float z0 = Sz * p0t.z, z1 = Sz * p1t.z, z2 = Sz * p2t.z;
    Float tScaled = e0 * z0 + e1 * z1 + e2 * z2;
    Float tMaxScaled = ray.tMax * det * (1 + 2 * gamma(3));
    bool inRange = det > 0 ? (tScaled > 0 && tScaled <= tMaxScaled)
                           : (tScaled < 0 && tScaled >= tMaxScaled);
    if (!inRange) return false;
    // Compute t for the triangle hit
    Float invDet = 1 / det;
    Float t = tScaled * invDet;
    if (!(t <= ray.tMax)) return false;
    // Ensure that computed triangle t is conservatively greater than zero
    // Compute delta_z term for triangle t error bounds
    Float maxZs = MaxAbs(z0, z1, z2);
    Float deltaZ = gamma(3) * maxZs;
    // Compute delta_x and delta_y terms for triangle t error bounds
    Float maxZt = MaxAbs(p0t.z, p1t.z, p2t.z);
    Float deltaX = gamma(5) * (MaxAbs(p0t.x, p1t.x, p2t.x) + maxZt);
    Float deltaY = gamma(5) * (MaxAbs(p0t.y, p1t.y, p2t.y) + maxZt);
    // Compute delta_e term for triangle t error bounds
    Float maxXs = MaxAbs(x0, x1, x2), maxYs = MaxAbs(y0, y1, y2);
    Float deltaE =
        2 * (gamma(2) * maxXs * maxYs + deltaY * maxXs + deltaX * maxYs);
    // Compute delta_t term for triangle t error bounds and check t
    Float maxE = MaxAbs(e0, e1, e2);
    Float deltaT = 3 *
                   (gamma(3) * maxE * maxZs + deltaE * maxZs + deltaZ * maxE) *
                   std::abs(invDet);
    if (!(t > deltaT)) return false;
    *hit = {t, e0, e1, e2, invDet};
    return true;
}
static void DefaultUVDerivatives(const Vector3f &dp02, const Vector3f &dp12,
                                 Vector3f *dpdu, Vector3f *dpdv) {
    Point2f uv[3];
    Triangle::GetDefaultUVs(uv);
    Vector2f duv02 = uv[0] - uv[2], duv12 = uv[1] - uv[2];
    Float invdet = 1 / (duv02[0] * duv12[1] - duv02[1] * duv12[0]);
    *dpdu = (duv12[1] * dp02 - duv02[1] * dp12) * invdet;
    *dpdv = (duv02[0] * dp12 - duv12[0] * dp02) * invdet;
}

static inline void CompletePlainTriangle(const Ray &ray, const Point3f &p0,
                                         const Point3f &p1,
                                         const Point3f &p2,
                                         const FastTriangleHit &hit,
                                         const FastTriangleInfo &info,
                                         SurfaceInteraction *isect) {
    Float e0 = hit.e0, e1 = hit.e1, e2 = hit.e2, invDet = hit.invDet;
    Vector3f dp02 = p0 - p2, dp12 = p1 - p2;
    // Compute barycentric coordinates of the triangle hit
    Float b0 = e0 * invDet, b1 = e1 * invDet, b2 = e2 * invDet;
    Point2f uv[3];
    Triangle::GetDefaultUVs(uv);
    Vector3f dpdu, dpdv;
    DefaultUVDerivatives(dp02, dp12, &dpdu, &dpdv);
    if (info.parallelDerivatives)
        CoordinateSystem(Vector3f(info.n), &dpdu, &dpdv);
    // Compute error bounds for triangle intersection
    Float xAbsSum = std::abs(b0 * p0.x) + std::abs(b1 * p1.x) +
                    std::abs(b2 * p2.x);
    Float yAbsSum = std::abs(b0 * p0.y) + std::abs(b1 * p1.y) +
                    std::abs(b2 * p2.y);
    Float zAbsSum = std::abs(b0 * p0.z) + std::abs(b1 * p1.z) +
                    std::abs(b2 * p2.z);
    Vector3f pError = gamma(7) * Vector3f(xAbsSum, yAbsSum, zAbsSum);
    // Interpolate (u,v) parametric coordinates and hit point
    Point3f pHit = b0 * p0 + b1 * p1 + b2 * p2;
    Point2f uvHit = b0 * uv[0] + b1 * uv[1] + b2 * uv[2];
    new (isect) SurfaceInteraction(pHit, pError, uvHit, -ray.d, dpdu, dpdv,
                                   Normal3f(0, 0, 0), Normal3f(0, 0, 0),
                                   info.n, ray.time, info.flipNormal,
                                   info.faceIndex);
    isect->shape = info.triangle;
}
// FastBVHAccel Traversal Function
struct FastStackEntry {
    FastBVHChild child;
    Float tEntry;
};

// Define DescendIntoNearerOfTwo()
template <int c, int d>
static LRT_ALWAYS_INLINE FastBVHChild DescendIntoNearerOfTwo(
    const FastBVHNode &node, const Float t[], FastStackEntry stack[],
    int &stackSize, const FastBVHNode *nodes, const FastTriangle *triangles) {
    if (t[d] < t[c]) {
        stack[stackSize++] = {node.child[c], t[c]};
        // Prefetch the data of the next child on the stack
        const FastBVHChild &next = stack[stackSize - 1].child;
        const void *nextData = &nodes[next.offset];
        if (next.IsLeaf()) nextData = &triangles[next.offset];
        LRT_PREFETCH(nextData);
        LRT_PREFETCH(static_cast<const char *>(nextData) + 64);
        return node.child[d];
    }
    stack[stackSize++] = {node.child[d], t[d]};
    // Prefetch the data of the next child on the stack
    const FastBVHChild &next = stack[stackSize - 1].child;
    const void *nextData = &nodes[next.offset];
    if (next.IsLeaf()) nextData = &triangles[next.offset];
    LRT_PREFETCH(nextData);
    LRT_PREFETCH(static_cast<const char *>(nextData) + 64);
    return node.child[c];
}

template <int octant, typename LeafVisitor>
static void TraverseFastBVHOctant(const FastBVHNode *nodes,
                                  const FastTriangle *triangles,
                                  FastBVHChild root,
                                  const FastBVHNode &rootNode,
                                  const Ray &ray, const FastRay &fr,
                                  LeafVisitor &visitLeaf) {
    const FastRay r = fr;
    // Compute the offsets of the near and far planes in a node
    constexpr int w = fastBVHWidth;
    constexpr int nearX = (octant & 1) * w, farX = w - nearX;
    constexpr int nearY = (2 + (octant >> 1 & 1)) * w, farY = 5 * w - nearY;
    constexpr int nearZ = (4 + (octant >> 2 & 1)) * w, farZ = 9 * w - nearZ;
#if defined(__SSE2__) && !defined(LRT_FLOAT_AS_DOUBLE)
    // Copy the ray's values for the box test into SSE2 registers
    const __m128 ox = _mm_set1_ps(r.ox), oy = _mm_set1_ps(r.oy),
                 oz = _mm_set1_ps(r.oz);
    const __m128 ix = _mm_set1_ps(r.ix), iy = _mm_set1_ps(r.iy),
                 iz = _mm_set1_ps(r.iz);
    const __m128 widen = _mm_set1_ps(1 + 2 * gamma(3));
    __m128 tMaxLanes;
#endif
    Float tMaxWidened;
    // Copy the ray's tMax into the traversal's variables
    tMaxWidened = ray.tMax * (1 + 2 * gamma(3));
    #if defined(__SSE2__) && !defined(LRT_FLOAT_AS_DOUBLE)
    tMaxLanes = _mm_set1_ps(ray.tMax);
    #endif
    if (root.IsLeaf()) {
        const FastBVHNode &node = rootNode;
        // Intersect the ray with the child boxes of node
        Float t[fastBVHWidth];
        unsigned mask = 0;
        {
            const Float *b = &node.bounds[0][0][0];
            Float t1[fastBVHWidth];
        #if defined(__SSE2__) && !defined(LRT_FLOAT_AS_DOUBLE)
            // Test the four boxes in the lanes of SSE2 registers
            auto tx0 = _mm_mul_ps(_mm_sub_ps(_mm_load_ps(b + nearX), ox), ix);
            auto tx1 = _mm_mul_ps(_mm_sub_ps(_mm_load_ps(b + farX), ox), ix);
            auto ty0 = _mm_mul_ps(_mm_sub_ps(_mm_load_ps(b + nearY), oy), iy);
            auto ty1 = _mm_mul_ps(_mm_sub_ps(_mm_load_ps(b + farY), oy), iy);
            auto tz0 = _mm_mul_ps(_mm_sub_ps(_mm_load_ps(b + nearZ), oz), iz);
            auto tz1 = _mm_mul_ps(_mm_sub_ps(_mm_load_ps(b + farZ), oz), iz);
            // _mm_max_ps(x, m) is std::max(m, x) in every lane, NaNs included, and
            // _mm_min_ps(x, m) is std::min(m, x): the operand order matters
            auto tNear = _mm_max_ps(tx0, _mm_setzero_ps());
            tNear = _mm_max_ps(ty0, tNear);
            tNear = _mm_max_ps(tz0, tNear);
            auto tFar = _mm_min_ps(tx1, tMaxLanes);
            tFar = _mm_min_ps(ty1, tFar);
            tFar = _mm_min_ps(tz1, tFar);
            _mm_storeu_ps(t, tNear);
            _mm_storeu_ps(t1, _mm_mul_ps(tFar, widen));
        #else
            for (int c = 0; c < fastBVHWidth; ++c) {
                Float tx0 = (b[nearX + c] - r.ox) * r.ix;
                Float tx1 = (b[farX + c] - r.ox) * r.ix;
                Float ty0 = (b[nearY + c] - r.oy) * r.iy;
                Float ty1 = (b[farY + c] - r.oy) * r.iy;
                Float tz0 = (b[nearZ + c] - r.oz) * r.iz;
                Float tz1 = (b[farZ + c] - r.oz) * r.iz;
                t[c] = std::max(std::max(std::max(Float(0), tx0), ty0), tz0);
                t1[c] = std::min(std::min(std::min(ray.tMax, tx1), ty1), tz1) *
                        (1 + 2 * gamma(3));
            }
        #endif
            mask = EnteredChildren(t, t1);
        }
        (void)t;
        if (!(mask & 1)) return;
    }
    FastStackEntry stack[(fastBVHWidth - 1) * maxBVHDepth + fastBVHWidth];
    int stackSize = 0;
    FastBVHChild current = root;
    while (true) {
        if (!current.IsLeaf()) {
            // Test the children's boxes and descend into the nearest
            const FastBVHNode &node = nodes[current.offset];
            // Intersect the ray with the child boxes of node
            Float t[fastBVHWidth];
            unsigned mask = 0;
            {
                const Float *b = &node.bounds[0][0][0];
                Float t1[fastBVHWidth];
            #if defined(__SSE2__) && !defined(LRT_FLOAT_AS_DOUBLE)
                // Test the four boxes in the lanes of SSE2 registers
                auto tx0 = _mm_mul_ps(_mm_sub_ps(_mm_load_ps(b + nearX), ox), ix);
                auto tx1 = _mm_mul_ps(_mm_sub_ps(_mm_load_ps(b + farX), ox), ix);
                auto ty0 = _mm_mul_ps(_mm_sub_ps(_mm_load_ps(b + nearY), oy), iy);
                auto ty1 = _mm_mul_ps(_mm_sub_ps(_mm_load_ps(b + farY), oy), iy);
                auto tz0 = _mm_mul_ps(_mm_sub_ps(_mm_load_ps(b + nearZ), oz), iz);
                auto tz1 = _mm_mul_ps(_mm_sub_ps(_mm_load_ps(b + farZ), oz), iz);
                // _mm_max_ps(x, m) is std::max(m, x) in every lane, NaNs included, and
                // _mm_min_ps(x, m) is std::min(m, x): the operand order matters
                auto tNear = _mm_max_ps(tx0, _mm_setzero_ps());
                tNear = _mm_max_ps(ty0, tNear);
                tNear = _mm_max_ps(tz0, tNear);
                auto tFar = _mm_min_ps(tx1, tMaxLanes);
                tFar = _mm_min_ps(ty1, tFar);
                tFar = _mm_min_ps(tz1, tFar);
                _mm_storeu_ps(t, tNear);
                _mm_storeu_ps(t1, _mm_mul_ps(tFar, widen));
            #else
                for (int c = 0; c < fastBVHWidth; ++c) {
                    Float tx0 = (b[nearX + c] - r.ox) * r.ix;
                    Float tx1 = (b[farX + c] - r.ox) * r.ix;
                    Float ty0 = (b[nearY + c] - r.oy) * r.iy;
                    Float ty1 = (b[farY + c] - r.oy) * r.iy;
                    Float tz0 = (b[nearZ + c] - r.oz) * r.iz;
                    Float tz1 = (b[farZ + c] - r.oz) * r.iz;
                    t[c] = std::max(std::max(std::max(Float(0), tx0), ty0), tz0);
                    t1[c] = std::min(std::min(std::min(ray.tMax, tx1), ty1), tz1) *
                            (1 + 2 * gamma(3));
                }
            #endif
                mask = EnteredChildren(t, t1);
            }
            if (mask == 1) {
                current = node.child[0];
                continue;
            }
            if (mask == 2) {
                current = node.child[1];
                continue;
            }
            if (mask == 4) {
                current = node.child[2];
                continue;
            }
            if (mask == 8) {
                current = node.child[3];
                continue;
            }
            switch (mask) {
            case 0:
                break;
            case 3:
                current = DescendIntoNearerOfTwo<0, 1>(node, t, stack, stackSize, nodes,
                                                       triangles);
                continue;
            case 5:
                current = DescendIntoNearerOfTwo<0, 2>(node, t, stack, stackSize, nodes,
                                                       triangles);
                continue;
            case 6:
                current = DescendIntoNearerOfTwo<1, 2>(node, t, stack, stackSize, nodes,
                                                       triangles);
                continue;
            case 9:
                current = DescendIntoNearerOfTwo<0, 3>(node, t, stack, stackSize, nodes,
                                                       triangles);
                continue;
            case 10:
                current = DescendIntoNearerOfTwo<1, 3>(node, t, stack, stackSize, nodes,
                                                       triangles);
                continue;
            case 12:
                current = DescendIntoNearerOfTwo<2, 3>(node, t, stack, stackSize, nodes,
                                                       triangles);
                continue;
            default: {
                int c = lowestSetBit[mask];
                mask &= mask - 1;
                int d = lowestSetBit[mask];
                mask &= mask - 1;
                // Push three or four children, sort them, descend into the nearest
                int first = stackSize;
                stack[stackSize++] = {node.child[c], t[c]};
                stack[stackSize++] = {node.child[d], t[d]};
                do {
                    int e = lowestSetBit[mask];
                    mask &= mask - 1;
                    stack[stackSize++] = {node.child[e], t[e]};
                } while (mask != 0);
                // Sort the pushed children, the nearest on top
                for (int i = first + 1; i < stackSize; ++i) {
                    FastStackEntry e = stack[i];
                    int j = i;
                    for (; j > first && stack[j - 1].tEntry < e.tEntry; --j)
                        stack[j] = stack[j - 1];
                    stack[j] = e;
                }
                current = stack[--stackSize].child;
                // Prefetch the data of the next child on the stack
                const FastBVHChild &next = stack[stackSize - 1].child;
                const void *nextData = &nodes[next.offset];
                if (next.IsLeaf()) nextData = &triangles[next.offset];
                LRT_PREFETCH(nextData);
                LRT_PREFETCH(static_cast<const char *>(nextData) + 64);
                continue;
            }
            }
        } else {
            if (visitLeaf(current)) return;
            // Copy the ray's tMax into the traversal's variables
            tMaxWidened = ray.tMax * (1 + 2 * gamma(3));
            #if defined(__SSE2__) && !defined(LRT_FLOAT_AS_DOUBLE)
            tMaxLanes = _mm_set1_ps(ray.tMax);
            #endif
        }
        // Pop the next child that the ray may still reach, or return
        do {
            if (stackSize == 0) return;
            --stackSize;
        } while (stack[stackSize].tEntry > tMaxWidened);
        current = stack[stackSize].child;
    }
}
template <typename LeafVisitor>
static void TraverseFastBVH(const FastBVHNode *nodes,
                            const FastTriangle *triangles,
                            FastBVHChild root, const FastBVHNode &rootNode,
                            const Ray &ray, const FastRay &fr,
                            LeafVisitor visitLeaf) {
    using Instance = void (*)(const FastBVHNode *, const FastTriangle *,
                              FastBVHChild, const FastBVHNode &, const Ray &,
                              const FastRay &, LeafVisitor &);
    static constexpr Instance instances[8] = {
        TraverseFastBVHOctant<0, LeafVisitor>,
        TraverseFastBVHOctant<1, LeafVisitor>,
        TraverseFastBVHOctant<2, LeafVisitor>,
        TraverseFastBVHOctant<3, LeafVisitor>,
        TraverseFastBVHOctant<4, LeafVisitor>,
        TraverseFastBVHOctant<5, LeafVisitor>,
        TraverseFastBVHOctant<6, LeafVisitor>,
        TraverseFastBVHOctant<7, LeafVisitor>};
    instances[fr.octant](nodes, triangles, root, rootNode, ray, fr,
                         visitLeaf);
}
// FastBVHAccel Method Definitions
FastBVHAccel::FastBVHAccel(std::vector<std::shared_ptr<Primitive>> p,
                           int maxPrimsInNode, SplitMethod splitMethod)
    : maxPrimsInNode(Clamp(maxPrimsInNode, 1, 255)) {
    if (splitMethod != SplitMethod::SAH) {
        BVHAccel bvh(std::move(p), this->maxPrimsInNode, splitMethod);
        CopyTree(bvh);
        return;
    }
    if (p.size() > size_t(std::numeric_limits<int>::max() / 2))
        throw std::length_error("FastBVHAccel: too many primitives");
    // Compute build records of the valid primitives
    std::vector<FastBVHBuildPrim> prims;
    prims.reserve(p.size());
    std::vector<FastTriangle> inputTriangles(p.size());
    std::vector<FastTriangleInfo> inputInfo(p.size());
    FastBox box = FastBox::Empty();
    for (size_t i = 0; i < p.size(); ++i) {
        if (!p[i])
            throw std::invalid_argument("FastBVHAccel: primitive " +
                                        std::to_string(i) + " is null");
        Bounds3f b = p[i]->WorldBound();
        if (!IsFiniteBox(b)) continue;
        FastBVHBuildPrim bp = {{b.pMin.x, b.pMin.y, b.pMin.z, b.pMin.z},
                               {b.pMax.x, b.pMax.y, b.pMax.z, b.pMax.z},
                               int(i), false, 0};
        const Triangle *tri = GetTriangle(p[i].get());
        bp.isTriangle =
            tri && StoreTriangle(&inputTriangles[i], &inputInfo[i], tri);
        prims.push_back(bp);
        box.Grow(bp.lo, bp.hi);
    }
    if (prims.empty()) return;
    // Build the tree with the binned SAH
    SAHBinaryTree binary(&prims, maxPrimsInNode);
    nodes.reserve(prims.size());
    SetRoot(box, BuildWide(binary, binary.Root(box), &nodes));
    // Store the primitives and their triangles in leaf order
    primitives.reserve(prims.size());
    triangles.reserve(prims.size());
    triangleInfo.reserve(prims.size());
    for (const FastBVHBuildPrim &bp : prims) {
        triangles.push_back(inputTriangles[bp.index]);
        triangleInfo.push_back(inputInfo[bp.index]);
        primitives.push_back(std::move(p[bp.index]));
    }
}
void SAHBinaryTree::MakeNode(Node *node, int start, int end,
                             const FastBox &box, int depth) {
    *node = {box, start, end, depth, -1,
             {FastBox::Empty(), FastBox::Empty()}, {0, 0, 0}};
    int n = end - start;
    if (n == 1) return MakeLeaf(node);
    int dim = box.MaximumExtent();
    if (depth + CeilLog2(n) < maxBVHDepth) {
        // Bin the build primitives by centroid
        int nBins = std::min(n, fastBVHBins);
        FastBVHBin bins[2][fastBVHBins];
        for (int b = 0; b < nBins; ++b)
            bins[0][b] = bins[1][b] = {FastBox::Empty(), 0};
        Float bMin = box.lo[dim];
        Float scale = nBins / (box.hi[dim] - bMin);
        for (int i = start; i < end; ++i) {
            FastBVHBuildPrim &bp = prims[i];
            int b = BinIndex(bp.Centroid(dim), bMin, scale, nBins);
            bp.bin = uint8_t(b);
            FastBVHBin &bin = bins[i & 1][b];
            bin.count++;
            bin.box.Grow(bp.lo, bp.hi);
        }
        for (int b = 0; b < nBins; ++b) {
            bins[0][b].count += bins[1][b].count;
            bins[0][b].box.Grow(bins[1][b].box);
        }
        // Find the cheapest bin boundary, or return a leaf
        Float rightArea[fastBVHBins];
        int rightCount[fastBVHBins];
        FastBox acc = FastBox::Empty();
        int count = 0;
        for (int b = nBins - 1; b > 0; --b) {
            acc.Grow(bins[0][b].box);
            count += bins[0][b].count;
            rightArea[b] = acc.HalfArea();
            rightCount[b] = count;
        }
        acc = FastBox::Empty();
        count = 0;
        Float bestCost = Infinity;
        int bestSplit = -1;
        for (int b = 0; b < nBins - 1; ++b) {
            acc.Grow(bins[0][b].box);
            count += bins[0][b].count;
            if (count == 0 || rightCount[b + 1] == 0) continue;
            Float cost = count * acc.HalfArea() + rightCount[b + 1] * rightArea[b + 1];
            if (cost < bestCost) {
                bestCost = cost;
                bestSplit = b;
            }
        }
        Float area = box.HalfArea();
        Float leafCost = fastBVHIntersectionCost * n * area;
        Float splitCost = fastBVHTraversalCost * area +
                          fastBVHIntersectionCost * bestCost;
        if (n <= maxPrimsInNode && !(splitCost < leafCost))
            return MakeLeaf(node);
        // Partition the build primitives at the chosen bin boundary
        if (bestSplit >= 0) {
            auto midIter = std::partition(
                prims.begin() + start, prims.begin() + end,
                [=](const FastBVHBuildPrim &bp) { return bp.bin <= bestSplit; });
            node->mid = int(midIter - prims.begin());
            for (int b = 0; b < nBins; ++b)
                node->childBox[b <= bestSplit ? 0 : 1].Grow(bins[0][b].box);
        }
    }
    if (node->mid < 0) {
        // Split the build primitives into two halves
        node->mid = (start + end) / 2;
        std::nth_element(prims.begin() + start, prims.begin() + node->mid,
                         prims.begin() + end,
                         [dim](const FastBVHBuildPrim &a, const FastBVHBuildPrim &b) {
                             return a.Centroid(dim) < b.Centroid(dim);
                         });
        for (int i = start; i < end; ++i)
            node->childBox[i < node->mid ? 0 : 1].Grow(prims[i].lo, prims[i].hi);
    }
}
void SAHBinaryTree::MakeLeaf(Node *node) {
    auto first = prims.begin() + node->start, last = prims.begin() + node->end;
    auto firstOther = std::partition(
        first, last, [](const FastBVHBuildPrim &bp) { return bp.isTriangle; });
    int nTriangles = int(firstOther - first);
    node->leaf = {uint32_t(node->start), uint16_t(nTriangles),
                  uint16_t(node->end - node->start - nTriangles)};
}
void FastBVHAccel::SetRoot(const FastBox &box, FastBVHChild child) {
    rootNode = EmptyNode();
    SetChildBox(&rootNode, 0, box.lo, box.hi);
    root = child;
}
FastBVHAccel::FastBVHAccel(const BVHAccel &bvh)
    : maxPrimsInNode(bvh.MaxPrimsInNode()) {
    CopyTree(bvh);
}
FastBVHChild AdoptedBinaryTree::Leaf(const Node &node) {
    const LinearBVHNode &bvhNode = bvh.Nodes()[node.index];
    const std::shared_ptr<Primitive> *prims =
        &bvh.Primitives()[bvhNode.primitivesOffset];
    FastBVHChild leaf = {uint32_t(primitives.size()), 0, 0};
    others.clear();
    for (int i = 0; i < bvhNode.nPrimitives; ++i) {
        FastTriangle ft;
        FastTriangleInfo info;
        const Triangle *tri = GetTriangle(prims[i].get());
        if (tri && StoreTriangle(&ft, &info, tri)) {
            primitives.push_back(prims[i]);
            triangles.push_back(ft);
            triangleInfo.push_back(info);
            leaf.nTriangles++;
        } else {
            others.push_back(i);
        }
    }
    for (int i : others) {
        primitives.push_back(prims[i]);
        triangles.emplace_back();
        triangleInfo.emplace_back();
        leaf.nOthers++;
    }
    return leaf;
}
void FastBVHAccel::CopyTree(const BVHAccel &bvh) {
    if (bvh.Nodes().empty()) return;
    size_t n = bvh.Primitives().size();
    primitives.reserve(n);
    triangles.reserve(n);
    triangleInfo.reserve(n);
    nodes.reserve(n);
    AdoptedBinaryTree binary(bvh, &primitives, &triangles, &triangleInfo);
    AdoptedBinaryTree::Node binaryRoot = {0};
    SetRoot(ToFastBox(bvh.Nodes()[0].bounds),
            BuildWide(binary, binaryRoot, &nodes));
}
bool FastBVHAccel::Intersect(const Ray &ray,
                             SurfaceInteraction *isect) const {
    if (primitives.empty()) return false;
    FastRay fr(ray);
    int64_t hitTriangle = -1;
    FastTriangleHit closest = {0, 0, 0, 0, 0};
    bool hitOther = false;
    const FastTriangle *tris = triangles.data();
    TraverseFastBVH(nodes.data(), tris, root, rootNode, ray, fr,
                    [&](FastBVHChild leaf) LRT_ALWAYS_INLINE_LAMBDA {
        // Find the closest hit among a fast leaf's primitives
        const FastTriangle *end = tris + leaf.offset + leaf.nTriangles;
        for (const FastTriangle *tri = tris + leaf.offset; tri != end; ++tri) {
            FastTriangleHit hit;
            if (IntersectTriangle(*tri, fr, ray, &hit)) {
                ray.tMax = hit.t;
                closest = hit;
                hitTriangle = tri - tris;
                LRT_PREFETCH(&triangleInfo[hitTriangle]);
                LRT_PREFETCH(&primitives[hitTriangle]);
            }
        }
        for (int i = 0; i < leaf.nOthers; ++i) {
            size_t k = size_t(leaf.offset) + leaf.nTriangles + i;
            if (primitives[k]->Intersect(ray, isect)) {
                hitTriangle = -1;
                hitOther = true;
            }
        }
        return false;
    });
    if (hitTriangle >= 0) {
        // Complete the interaction for the closest triangle hit
        const FastTriangle &ft = triangles[hitTriangle];
        const FastTriangleInfo &info = triangleInfo[hitTriangle];
        Point3f p0 = ft.Vertex(0), p1 = ft.Vertex(1), p2 = ft.Vertex(2);
        bool completed = true;
        if (info.plain)
            CompletePlainTriangle(ray, p0, p1, p2, closest, info, isect);
        else
            completed = info.triangle->CompleteIntersection(ray, p0, p1, p2, closest.e0,
                                                            closest.e1, closest.e2,
                                                            closest.invDet, isect);
        if (!completed)
            throw std::logic_error("FastBVHAccel::Intersect: the fast triangle "
                                   "test accepted a degenerate triangle");
        isect->primitive = primitives[hitTriangle].get();
    }
    return hitOther || hitTriangle >= 0;
}
bool FastBVHAccel::IntersectP(const Ray &ray) const {
    if (primitives.empty()) return false;
    FastRay fr(ray);
    bool hit = false;
    const FastTriangle *tris = triangles.data();
    TraverseFastBVH(nodes.data(), tris, root, rootNode, ray, fr,
                    [&](FastBVHChild leaf) {
        for (int i = 0; i < leaf.nTriangles; ++i) {
            FastTriangleHit h;
            if (IntersectTriangle(tris[leaf.offset + i], fr, ray, &h))
                return hit = true;
        }
        for (int i = 0; i < leaf.nOthers; ++i) {
            size_t k = size_t(leaf.offset) + leaf.nTriangles + i;
            if (primitives[k]->IntersectP(ray)) return hit = true;
        }
        return false;
    });
    return hit;
}
Bounds3f FastBVHAccel::WorldBound() const {
    if (primitives.empty()) return Bounds3f();
    return GetChildBox(rootNode, 0);
}
BVHStats FastBVHAccel::Stats() const {
    BVHStats s;
    if (primitives.empty()) return s;
    double rootArea = BoxArea(GetChildBox(rootNode, 0));
    struct Item {
        FastBVHChild child;
        double area;
        int depth;
    };
    std::vector<Item> todo = {{root, rootArea, 0}};
    while (!todo.empty()) {
        Item item = todo.back();
        todo.pop_back();
        double p = HitProbability(item.area, rootArea);
        s.maxDepth = std::max(s.maxDepth, item.depth);
        if (item.child.IsLeaf()) {
            int n = item.child.NPrimitives();
            s.leafNodes++;
            s.primitives += n;
            s.maxLeafSize = std::max(s.maxLeafSize, n);
            s.sahCost += p * n;
        } else {
            s.interiorNodes++;
            s.sahCost += p;
            const FastBVHNode &node = nodes[item.child.offset];
            for (int c = 0; c < fastBVHWidth; ++c)
                if (!node.child[c].IsEmpty())
                    todo.push_back({node.child[c],
                                    BoxArea(GetChildBox(node, c)),
                                    item.depth + 1});
        }
    }
    return s;
}

}  // namespace lrt
