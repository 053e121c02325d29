// Checks of BVHAccel's trees for chapter 6's tests, public and hidden (the
// hidden tests include this file as "../../ch06/bvh_checks.h"). The trees
// are lrt::BVHAccel's or, in the exercises' tests, ex::BVHAccel's: the nodes
// that the worker built (remote_bvh.h), checked there to be a tree.
//
//   TreeWalker         traces a BVHAccel's tree without BVHAccel's own
//                      traversal, so that the trees built by the SAH and
//                      HLBVH can be checked against brute force whatever
//                      state the traversal is in, or, visiting the nearer
//                      child first, to count the primitives tested;
//   CountingPrimitive  counts the tests of a primitive;
//   CheckSAHChoices    the cost model of Section 6.4 evaluated in double
//                      precision at every node where the SAH decided;
//   CheckMortonOrder   the order of an HLBVH tree's primitives along the
//                      Morton curve, from codes interleaved bit by bit;
//   BoxPrimitive       a box as a primitive, which can log the tests of it
//                      (in exercise_calls.h, which the worker shares);
//   ClosedMesh         a subdivided octahedron on the unit sphere.

#pragma once

#include "remote_bvh.h"
#include "lrt/accelerators/bvh.h"
#include "lrt/core/slabtest.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <map>
#include <memory>
#include <random>
#include <utility>
#include <vector>

namespace lrt_test {

using namespace lrt;

// A uniform random number in [a, b).
inline double U(std::mt19937_64 &rng, double a, double b) {
    return std::uniform_real_distribution<double>(a, b)(rng);
}

// A uniformly distributed unit vector (a normalized Gaussian vector).
inline Vector3f RandomDirection(std::mt19937_64 &rng) {
    std::normal_distribution<double> n(0, 1);
    for (;;) {
        double x = n(rng), y = n(rng), z = n(rng);
        double l = std::sqrt(x * x + y * y + z * z);
        if (l > 1e-3)
            return Vector3f(Float(x / l), Float(y / l), Float(z / l));
    }
}

// Traces the tree of a BVHAccel from its nodes and ordered primitives: a
// stack of node indices, both children of every node whose box the ray
// enters. Any visiting order finds the same closest hit, so this checks a
// tree independently of BVHAccel::Intersect(). In index order, the first
// child is visited first; in distance order, the child whose box the ray
// enters first, which makes a yardstick for the number of primitives a
// traversal tests.
class TreeWalker : public Primitive {
  public:
    enum class Order { Index, Distance };
    // BVH: lrt::BVHAccel or ex::BVHAccel.
    template <typename BVH>
    explicit TreeWalker(std::shared_ptr<BVH> bvh, Order order = Order::Index)
        : nodes(bvh->Nodes()), prims(bvh->Primitives()),
          bounds(bvh->WorldBound()), bvh(std::move(bvh)), order(order) {}
    Bounds3f WorldBound() const override { return bounds; }
    bool Intersect(const Ray &ray, SurfaceInteraction *isect) const override {
        return Walk(ray, isect);
    }
    bool IntersectP(const Ray &ray) const override {
        return Walk(ray, nullptr);
    }

  private:
    static Float Entry(const Bounds3f &b, const Ray &ray) {
        Float t0, t1;
        return b.IntersectP(ray, &t0, &t1) ? t0 : Infinity;
    }
    bool Walk(const Ray &ray, SurfaceInteraction *isect) const {
        if (nodes.empty()) return false;
        Vector3f inv(1 / ray.d.x, 1 / ray.d.y, 1 / ray.d.z);
        const int neg[3] = {inv.x < 0, inv.y < 0, inv.z < 0};
        std::vector<int> pending(1, 0);
        bool found = false;
        while (!pending.empty()) {
            int index = pending.back();
            pending.pop_back();
            const LinearBVHNode &node = nodes[index];
            if (!node.bounds.IntersectP(ray, inv, neg)) continue;
            if (node.nPrimitives == 0) {
                int later = node.secondChildOffset, sooner = index + 1;
                if (order == Order::Distance &&
                    Entry(nodes[later].bounds, ray) <
                        Entry(nodes[sooner].bounds, ray))
                    std::swap(later, sooner);
                pending.push_back(later);
                pending.push_back(sooner);
                continue;
            }
            for (int k = node.primitivesOffset;
                 k < node.primitivesOffset + node.nPrimitives; ++k) {
                if (!isect) {
                    if (prims[k]->IntersectP(ray)) return true;
                } else if (prims[k]->Intersect(ray, isect)) {
                    found = true;
                }
            }
        }
        return found;
    }
    const std::vector<LinearBVHNode> &nodes;
    const std::vector<std::shared_ptr<Primitive>> &prims;
    Bounds3f bounds;
    std::shared_ptr<const void> bvh;  // which holds the two above
    Order order;
};

// A primitive that counts the tests of it (and, in an ex::BVHAccel, the
// worker's tests of its copy).
class CountingPrimitive : public Primitive, public ex::NotesTests {
  public:
    CountingPrimitive(std::shared_ptr<Primitive> p, int64_t *count)
        : p(std::move(p)), count(count) {}
    Bounds3f WorldBound() const override { return p->WorldBound(); }
    bool Intersect(const Ray &r, SurfaceInteraction *isect) const override {
        ++*count;
        return p->Intersect(r, isect);
    }
    bool IntersectP(const Ray &r) const override {
        ++*count;
        return p->IntersectP(r);
    }
    bool KeepsNotes() const override { return true; }
    void NoteTest() const override { ++*count; }

  private:
    std::shared_ptr<Primitive> p;
    int64_t *count;
};

inline Point3f CentroidOf(const Bounds3f &b) {
    return b.pMin * Float(0.5) + b.pMax * Float(0.5);
}

// The bucket of a centroid, computed as the builder computes it (Section
// 6.4.3), so that the oracle below sees the same buckets.
constexpr int kSAHBuckets = 12;
inline int OracleBucket(const Bounds3f &centroidBounds, const Point3f &c,
                        int dim) {
    Float f = kSAHBuckets * centroidBounds.Offset(c)[dim];
    if (!(f > 0)) return 0;
    if (f >= kSAHBuckets) return kSAHBuckets - 1;
    return int(f);
}

// What CheckSAHChoices() saw.
struct SAHCheck {
    int decisions = 0;  // nodes at which the builder consulted the SAH
    int leaves = 0;     // ... and made a leaf
    int failures = 0;
};

// The SAH decisions of a BVHAccel built with SplitMethod::SAH, checked
// against the cost model in double precision. The nodes checked are those
// where the builder consults the SAH: three or more primitives whose
// centroids are not all equal along the split axis, below the depth bound
// of Section 6.3.4, and (since the builder computes in Float) a box whose
// area is finite and either zero or far from the subnormal range. There,
// the cost of splitting after each of the 11 bucket boundaries is
// c_T + (N_A S(A) + N_B S(B)) / S(node), with c_T = 1/8 and no area term if
// the node's area is zero. An interior node's children must be separated by
// a bucket boundary whose cost is the least, and the node must be a leaf
// exactly when a leaf, which costs N, is no more expensive and
// N <= maxPrimsInNode. Costs that agree to a relative 1e-5 count as equal,
// so a float computation that rounds differently may choose either.
template <typename BVH>
SAHCheck CheckSAHChoices(const BVH &bvh, const char *what = "SAH tree") {
    SAHCheck check;
    const std::vector<LinearBVHNode> &nodes = bvh.Nodes();
    const auto &prims = bvh.Primitives();
    if (nodes.empty()) return check;
    std::vector<Bounds3f> boxes;
    for (const auto &p : prims) boxes.push_back(p->WorldBound());
    // Counts every failure; reports the first few.
    auto failed = [&]() { return ++check.failures <= 10; };
    // Returns the range of ordered primitives below node `index`: the
    // builder appends the primitives of each subtree's leaves one after the
    // other, so it is contiguous.
    std::function<std::pair<int, int>(int, int)> visit =
        [&](int index, int depth) -> std::pair<int, int> {
        const LinearBVHNode &node = nodes[index];
        std::pair<int, int> range, first, second;
        if (node.nPrimitives > 0) {
            range = {node.primitivesOffset,
                     node.primitivesOffset + node.nPrimitives};
        } else {
            if (node.secondChildOffset <= index + 1 ||
                node.secondChildOffset >= int(nodes.size())) {
                if (failed())
                    ADD_FAILURE() << what << ": bad child offset at " << index;
                return {0, 0};
            }
            first = visit(index + 1, depth + 1);
            second = visit(node.secondChildOffset, depth + 1);
            // (The builder may create the second child's leaves first: the
            // order in which a call's arguments are evaluated is not
            // specified.)
            if (first.second == second.first) {
                range = {first.first, second.second};
            } else if (second.second == first.first) {
                range = {second.first, first.second};
            } else {
                if (failed())
                    ADD_FAILURE() << what << ": the primitives below node "
                                  << index << " are not contiguous";
                return {0, 0};
            }
        }
        int n = range.second - range.first;
        if (n < 3) return range;
        Bounds3f centroidBounds, nodeBox;
        for (int k = range.first; k < range.second; ++k) {
            centroidBounds = Union(centroidBounds, CentroidOf(boxes[k]));
            nodeBox = Union(nodeBox, boxes[k]);
        }
        int dim = centroidBounds.MaximumExtent();
        if (!(centroidBounds.pMax[dim] > centroidBounds.pMin[dim]))
            return range;
        if (depth + CeilLog2(n) >= maxBVHDepth) return range;
        // The builder computes in Float: a cost that overflows, or areas so
        // small that their products are subnormal, decide nothing.
        Float area = nodeBox.SurfaceArea();
        if (!std::isfinite(area * Float(n))) return range;
        const Float tiny = std::numeric_limits<Float>::min() * Float(1e13);
        if (area > 0 && area < tiny) return range;
        // Counts and boxes of the buckets, and of the buckets up to and
        // from each one.
        int count[kSAHBuckets] = {};
        Bounds3f box[kSAHBuckets];
        for (int k = range.first; k < range.second; ++k) {
            int b = OracleBucket(centroidBounds, CentroidOf(boxes[k]), dim);
            count[b] += 1;
            box[b] = Union(box[b], boxes[k]);
        }
        Bounds3f upTo[kSAHBuckets], from[kSAHBuckets];
        int nUpTo[kSAHBuckets], nFrom[kSAHBuckets];
        for (int b = 0; b < kSAHBuckets; ++b) {
            upTo[b] = b == 0 ? box[0] : Union(upTo[b - 1], box[b]);
            nUpTo[b] = count[b] + (b == 0 ? 0 : nUpTo[b - 1]);
        }
        for (int b = kSAHBuckets - 1; b >= 0; --b) {
            bool last = b == kSAHBuckets - 1;
            from[b] = last ? box[b] : Union(from[b + 1], box[b]);
            nFrom[b] = count[b] + (last ? 0 : nFrom[b + 1]);
        }
        double scale = area > 0 ? 1 / BoxArea(nodeBox) : 0;
        double planeCost[kSAHBuckets - 1];
        double best = std::numeric_limits<double>::infinity();
        for (int b = 0; b + 1 < kSAHBuckets; ++b) {
            planeCost[b] = 0.125 + (nUpTo[b] * BoxArea(upTo[b]) +
                                    nFrom[b + 1] * BoxArea(from[b + 1])) *
                                       scale;
            best = std::min(best, planeCost[b]);
        }
        double tol = 1e-5 * best;
        ++check.decisions;
        bool fits = n <= bvh.MaxPrimsInNode();
        if (node.nPrimitives > 0) {
            ++check.leaves;
            if (!fits) {
                if (failed())
                    ADD_FAILURE() << what << ": node " << index << " is a "
                                  << "leaf of " << n << " primitives, more "
                                  << "than " << bvh.MaxPrimsInNode();
            } else if (best < n - tol) {
                if (failed())
                    ADD_FAILURE() << what << ": node " << index << " is a "
                                  << "leaf of " << n << " primitives (cost "
                                  << n << "), but the cheapest split costs "
                                  << best;
            }
            return range;
        }
        if (fits && best > n + tol && failed())
            ADD_FAILURE() << what << ": node " << index << " of " << n
                          << " primitives is split, but the cheapest split "
                          << "costs " << best << ", more than a leaf, " << n;
        int lastFirst = -1, firstSecond = kSAHBuckets;
        for (int k = first.first; k < first.second; ++k)
            lastFirst = std::max(
                lastFirst,
                OracleBucket(centroidBounds, CentroidOf(boxes[k]), dim));
        for (int k = second.first; k < second.second; ++k)
            firstSecond = std::min(
                firstSecond,
                OracleBucket(centroidBounds, CentroidOf(boxes[k]), dim));
        if (lastFirst < 0 || firstSecond <= lastFirst ||
            lastFirst >= kSAHBuckets - 1) {
            if (failed())
                ADD_FAILURE() << what << ": the children of node " << index
                              << " are not separated by a bucket boundary "
                              << "(first child up to bucket " << lastFirst
                              << ", second from " << firstSecond << ")";
        } else if (planeCost[lastFirst] > best + tol && failed()) {
            ADD_FAILURE() << what << ": node " << index << " of " << n
                          << " primitives is split after bucket "
                          << lastFirst << " at cost "
                          << planeCost[lastFirst]
                          << ", but the cheapest split costs " << best;
        }
        return range;
    };
    visit(0, 0);
    EXPECT_EQ(check.failures, 0)
        << what << ": decisions that contradict the cost model";
    return check;
}

// The Morton code of a point scaled to [0, 1024]^3, interleaved bit by
// bit: bit b of coordinate a becomes bit 3b + a.
inline uint32_t ReferenceMortonCode(const Vector3f &v) {
    uint32_t code = 0;
    for (int a = 0; a < 3; ++a) {
        uint32_t q = QuantizeMorton(v[a]);
        for (int b = 0; b < 10; ++b)
            if (q & (uint32_t(1) << b)) code |= uint32_t(1) << (3 * b + a);
    }
    return code;
}

// The HLBVH build stores its primitives in the order of their Morton codes
// (Section 6.5): the treelets are built one after the other from the sorted
// codes, and the upper levels rearrange nodes, not primitives. Checks that
// the codes of bvh.Primitives(), computed here from the primitives' boxes
// as the build computes them, never decrease; returns how many distinct
// codes there are.
template <typename BVH>
int CheckMortonOrder(const BVH &bvh, const char *what = "HLBVH tree") {
    const auto &prims = bvh.Primitives();
    std::vector<Point3f> centroids;
    Bounds3f centroidBounds;
    for (const auto &p : prims) {
        centroids.push_back(CentroidOf(p->WorldBound()));
        centroidBounds = Union(centroidBounds, centroids.back());
    }
    int distinct = 0, failures = 0;
    uint32_t previous = 0;
    for (size_t i = 0; i < centroids.size(); ++i) {
        uint32_t code = ReferenceMortonCode(
            centroidBounds.Offset(centroids[i]) * Float(1024));
        if (i > 0 && code < previous && failures++ < 5)
            ADD_FAILURE() << what << ": primitive " << i << " of "
                          << prims.size() << " has Morton code " << code
                          << ", smaller than the one before it, " << previous
                          << ": the primitives are not sorted by their codes";
        distinct += (i == 0 || code != previous);
        previous = code;
    }
    EXPECT_EQ(failures, 0) << what;
    return distinct;
}

using BoxPrimitive = ex::BoxPrimitive;

// A closed mesh, for the public and the hidden tests: an octahedron
// subdivided `levels` times (1-to-4), with its vertices on the unit
// sphere.
inline void ClosedMesh(int levels, std::vector<Point3f> *pOut,
                       std::vector<int> *idxOut) {
    std::vector<Point3f> p = {Point3f(1, 0, 0),  Point3f(-1, 0, 0),
                              Point3f(0, 1, 0),  Point3f(0, -1, 0),
                              Point3f(0, 0, 1),  Point3f(0, 0, -1)};
    std::vector<int> idx = {0, 2, 4, 2, 1, 4, 1, 3, 4, 3, 0, 4,
                            2, 0, 5, 1, 2, 5, 3, 1, 5, 0, 3, 5};
    for (int level = 0; level < levels; ++level) {  // 1-to-4 subdivision
        std::vector<int> next;
        std::map<std::pair<int, int>, int> mid;
        auto midpoint = [&](int a, int b) {
            auto key = std::make_pair(std::min(a, b), std::max(a, b));
            auto it = mid.find(key);
            if (it != mid.end()) return it->second;
            Vector3f m =
                Vector3f(p[a]) * Float(0.5) + Vector3f(p[b]) * Float(0.5);
            p.push_back(Point3f(Normalize(m)));
            return mid[key] = int(p.size()) - 1;
        };
        for (size_t t = 0; t < idx.size(); t += 3) {
            int a = idx[t], b = idx[t + 1], c = idx[t + 2];
            int ab = midpoint(a, b), bc = midpoint(b, c), ca = midpoint(c, a);
            next.insert(next.end(), {a, ab, ca, ab, b, bc, ca, bc, c, ab, bc,
                                     ca});
        }
        idx = next;
    }
    *pOut = p;
    *idxOut = idx;
}

}  // namespace lrt_test
