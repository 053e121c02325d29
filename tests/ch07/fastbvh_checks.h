// Checks of FastBVHAccel's trees for chapter 7's exercise tests, public and
// hidden (the hidden tests include this file as "../../ch07/fastbvh_checks.h"),
// and for chapter 8's tests of the book's FastBVHAccel. The exercise tests'
// trees are the worker's (ex::FastBVHAccel, remote_fastbvh.h), already
// checked there to be trees.
//
//   CheckStructure      boxes, leaves and counts of a four-wide tree;
//   EntersBox           the box test's answer for one box, in double
//                       precision: surely entered, surely not, or too close
//                       to call for the test's rounding;
//   CheckLeavesTested   the primitives IntersectP() tests, against the
//                       leaves whose boxes the ray enters;
//   CheckCollapse       each four-wide node of a tree adopted from a BVHAccel
//                       against the greedy rule of chapter 7's "Four
//                       Children per Node", as properties of the binary
//                       tree;
//   CheckSAHDecisions   every decision of the binned SAH, recovered from the
//                       order of the primitives in the leaves, against the
//                       cost model evaluated in double precision;
//   CheckEveryOctant    rays in every octant, zeros of either sign, against
//                       brute force;
//   RaysWithNaNAndInfinity, ExpectSameAnswers
//                       rays that pass every box test (a NaN rejects
//                       nothing) or have infinite components, and the
//                       agreement of several trees on them;
//   RandomBoxScene      scenes of boxes as primitives, for CheckLeavesTested,
//                       CheckCollapse and CheckSAHDecisions.
//
// Chapter 8's tests of FastBVHAccel as the book writes it (lrt::FastBVHAccel)
// use the helpers that take either kind of tree or any Primitive.

#pragma once

#include "remote_fastbvh.h"
#include "ch06/bvh_scenes.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <map>
#include <memory>
#include <random>
#include <set>
#include <string>
#include <vector>

namespace lrt_test {

using namespace lrt;

// A child's box in a FastBVHNode: bounds[axis][min or max][child].
inline Bounds3f BoxOf(const FastBVHNode &n, int c) {
    Bounds3f r;
    r.pMin = Point3f(n.bounds[0][0][c], n.bounds[1][0][c], n.bounds[2][0][c]);
    r.pMax = Point3f(n.bounds[0][1][c], n.bounds[1][1][c], n.bounds[2][1][c]);
    return r;
}

// A triangle whose geometric normal, computed as Triangle::Intersect()
// computes it, is zero: no ray can hit it.
inline bool IsDegenerate(const Triangle &tri) {
    Point3f p0, p1, p2;
    tri.GetVertices(&p0, &p1, &p2);
    return Cross(p0 - p2, p1 - p2).LengthSquared() == 0;
}

// The structure of a FastBVHAccel (lrt::FastBVHAccel, or the worker's
// ex::FastBVHAccel), as CheckStructure() checks a BVHAccel's
// (bvh_scenes.h): its boxes are stored in the parents, whose nodes have two
// to four children (unused slots hold an empty box and an empty leaf), and
// whose leaves put triangles, with their vertices copied, first. (For a tree
// over the test's own primitives: not over the worker's logged copies, which
// are no triangles.) The worker's trees were checked to be trees when they
// arrived; the book's are checked here, so that no index leaves the arrays.
template <typename FastBVH>
void CheckFastStructure(const FastBVH &bvh,
                        const std::vector<std::shared_ptr<Primitive>> &input) {
    const auto &nodes = bvh.Nodes();
    const auto &prims = bvh.Primitives();
    const auto &tris = bvh.Triangles();
    std::multiset<const Primitive *> got;
    for (const auto &p : prims) got.insert(p.get());
    ASSERT_EQ(got, ValidPrimitives(input));
    ASSERT_EQ(tris.size(), prims.size());
    BVHStats s = bvh.Stats();
    if (prims.empty()) {
        EXPECT_TRUE(nodes.empty());
        EXPECT_EQ(s.TotalNodes(), 0);
        EXPECT_TRUE(bvh.WorldBound().IsEmpty());
        return;
    }
    std::vector<int> visited(nodes.size(), 0), covered(prims.size(), 0);
    int maxDepth = 0, leaves = 0;
    int64_t children = 0;
    std::function<Bounds3f(FastBVHChild, int)> visit =
        [&](FastBVHChild c, int depth) -> Bounds3f {
        maxDepth = std::max(maxDepth, depth);
        Bounds3f b;
        if (c.IsLeaf()) {
            ++leaves;
            EXPECT_LE(c.NPrimitives(), bvh.MaxPrimsInNode());
            EXPECT_LE(size_t(c.offset) + c.NPrimitives(), prims.size());
            for (int i = 0; i < c.NPrimitives() &&
                            size_t(c.offset) + i < prims.size();
                 ++i) {
                size_t k = c.offset + i;
                covered[k]++;
                b = Union(b, prims[k]->WorldBound());
                const Triangle *tri = AsTriangle(prims[k].get());
                if (tri && IsDegenerate(*tri)) tri = nullptr;
                EXPECT_EQ(tri != nullptr, i < c.nTriangles) << k;
                if (tri) {
                    Point3f q[3];
                    tri->GetVertices(&q[0], &q[1], &q[2]);
                    for (int a = 0; a < 3; ++a) {
                        for (int j = 0; j < 3; ++j)
                            EXPECT_EQ(tris[k].c[a][j], q[j][a]);
                        EXPECT_EQ(tris[k].c[a][3], 0);
                    }
                }
            }
            return b;
        }
        if (c.offset >= nodes.size() || depth > maxBVHDepth) {
            ADD_FAILURE() << "bad node index " << c.offset << " at depth "
                          << depth;
            return b;
        }
        visited[c.offset]++;
        const FastBVHNode &n = nodes[c.offset];
        int used = 0;
        for (int k = 0; k < fastBVHWidth; ++k) {
            if (n.child[k].IsEmpty()) {
                // An unused slot: no box a ray could enter, nothing to visit.
                EXPECT_TRUE(n.child[k].IsLeaf());
                Bounds3f bk = BoxOf(n, k);
                for (int a = 0; a < 3; ++a) {
                    EXPECT_EQ(bk.pMin[a], Infinity) << "node " << c.offset;
                    EXPECT_EQ(bk.pMax[a], -Infinity) << "node " << c.offset;
                }
                continue;
            }
            // Used slots come first.
            EXPECT_EQ(k, used) << "node " << c.offset;
            ++used;
            Bounds3f bk = visit(n.child[k], depth + 1);
            EXPECT_EQ(BoxOf(n, k), bk) << "node " << c.offset;
            b = Union(b, bk);
        }
        EXPECT_GE(used, 2) << "node " << c.offset;
        children += used;
        return b;
    };
    EXPECT_EQ(visit(bvh.Root(), 0), bvh.WorldBound());
    for (size_t i = 0; i < visited.size(); ++i)
        ASSERT_EQ(visited[i], 1) << "node " << i;
    for (size_t i = 0; i < covered.size(); ++i)
        ASSERT_EQ(covered[i], 1) << "primitive " << i;
    EXPECT_LE(maxDepth, maxBVHDepth);
    EXPECT_EQ(s.interiorNodes, int64_t(nodes.size()));
    EXPECT_EQ(s.leafNodes, leaves);
    // Every node but the root is the child of exactly one interior node.
    EXPECT_EQ(children + 1, s.TotalNodes());
    EXPECT_EQ(s.primitives, int64_t(prims.size()));
    EXPECT_EQ(s.maxDepth, maxDepth);
}

// CheckStructure() for both kinds of FastBVHAccel, beside chapter 6's
// template for the BVHAccels (an exact match is chosen over the template).
inline void CheckStructure(
    const ex::FastBVHAccel &bvh,
    const std::vector<std::shared_ptr<Primitive>> &input) {
    CheckFastStructure(bvh, input);
}
inline void CheckStructure(
    const lrt::FastBVHAccel &bvh,
    const std::vector<std::shared_ptr<Primitive>> &input) {
    CheckFastStructure(bvh, input);
}

// ---------------------------------------------------------------------------
// The box test, one box at a time

enum class Entered { kSurely, kMaybe, kNot };

// Whether the four-wide box test, which computes in Float and widens the
// exit distance by 1 + 2 gamma(3), enters box `b`. Computed here in double
// precision, in which the distances are exact to far better than Float's
// rounding: a box whose entry is not beyond its exit is surely entered
// (the widening is there to make sure of it), one whose entry is beyond its
// exit by more than the widening and the rounding of a few operations is
// surely not, and between them the answer is the rounding's. A NaN distance
// (a ray in the plane of a slab) leaves the interval as it is, and a box
// reached only at infinite t counts as entered, as in chapter 7's "Four
// Boxes at Once".
inline Entered EntersBox(const Bounds3f &b, const Ray &ray) {
    double tEnter = 0, tExit = ray.tMax;
    for (int a = 0; a < 3; ++a) {
        double inv = 1.0 / double(ray.d[a]);
        double lo = (double(b.pMin[a]) - double(ray.o[a])) * inv;
        double hi = (double(b.pMax[a]) - double(ray.o[a])) * inv;
        double tIn = std::signbit(inv) ? hi : lo;
        double tOut = std::signbit(inv) ? lo : hi;
        if (tIn > tEnter) tEnter = tIn;
        if (tOut < tExit) tExit = tOut;
    }
    if (tEnter <= tExit) return Entered::kSurely;
    if (tEnter > tExit * (1 + 1e-5) + 1e-30) return Entered::kNot;
    return Entered::kMaybe;
}

struct LeavesTested {
    int rays = 0, surelyTested = 0, maybe = 0;
};

// Where each primitive of the scene stands in the tree's order, to turn the
// log of a scene's primitives into indices of bvh.Primitives().
inline std::map<const Primitive *, int> Positions(
    const ex::FastBVHAccel &bvh) {
    std::map<const Primitive *, int> at;
    for (size_t k = 0; k < bvh.Primitives().size(); ++k)
        at[bvh.Primitives()[k].get()] = int(k);
    return at;
}

// The primitives that IntersectP() tested, in `tested` (their indices in
// bvh.Primitives(), in order), for a ray that hits none of them: every
// primitive in a leaf whose boxes, from the root's down, the ray surely
// enters must be tested, none in a leaf whose boxes it surely misses, and
// none twice.
inline void CheckLeavesTested(const ex::FastBVHAccel &bvh, const Ray &ray,
                              const std::vector<int> &tested,
                              LeavesTested *count, int *failures,
                              const std::string &name) {
    const auto &prims = bvh.Primitives();
    std::vector<int> expected(prims.size(), 0);  // 0 not, 1 maybe, 2 surely
    std::function<void(FastBVHChild, Entered)> visit = [&](FastBVHChild c,
                                                            Entered e) {
        if (c.IsLeaf()) {
            for (int i = 0; i < c.NPrimitives(); ++i)
                expected[c.offset + i] = e == Entered::kSurely ? 2 : 1;
            return;
        }
        const FastBVHNode &n = bvh.Nodes()[c.offset];
        for (int k = 0; k < fastBVHWidth; ++k) {
            if (n.child[k].IsEmpty()) continue;
            Entered ek = EntersBox(BoxOf(n, k), ray);
            if (ek == Entered::kNot) continue;
            visit(n.child[k], e == Entered::kSurely ? ek : Entered::kMaybe);
        }
    };
    if (!prims.empty()) {
        // The root's own box is tested only if the root is a leaf.
        Entered e = bvh.Root().IsLeaf() ? EntersBox(bvh.WorldBound(), ray)
                                        : Entered::kSurely;
        if (e != Entered::kNot) visit(bvh.Root(), e);
    }
    std::vector<int> times(prims.size(), 0);
    for (int k : tested) times[k]++;
    ++count->rays;
    for (size_t k = 0; k < prims.size(); ++k) {
        count->surelyTested += expected[k] == 2;
        count->maybe += expected[k] == 1;
        bool ok = times[k] <= 1 && (times[k] == 1 || expected[k] != 2) &&
                  (times[k] == 0 || expected[k] != 0);
        if (!ok && (*failures)++ < kMaxFailuresReported)
            ADD_FAILURE() << name << ", ray " << ray << ": primitive " << k
                          << " was tested " << times[k]
                          << " times, but the ray "
                          << (expected[k] == 2   ? "enters"
                              : expected[k] == 1 ? "may enter"
                                                 : "misses")
                          << " the boxes above its leaf";
    }
}

// ---------------------------------------------------------------------------
// The collapse into four-wide nodes

// The surface area of a box, halved, as a number to compare.
inline double HalfAreaOf(const Bounds3f &b) {
    double dx = double(b.pMax.x) - b.pMin.x, dy = double(b.pMax.y) - b.pMin.y,
           dz = double(b.pMax.z) - b.pMin.z;
    if (!(dx >= 0 && dy >= 0 && dz >= 0)) return 0;
    return dx * dy + dy * dz + dz * dx;
}

struct CollapseCount {
    int nodes = 0, opened = 0, full = 0;
};

// Each node of a FastBVHAccel that adopted a BVHAccel's tree (its nodes
// and order: bvh.AdoptedNodes(), bvh.AdoptedPrimitives()) against the rule
// of the collapse: its children are binary nodes below the binary node it
// stands for, which together hold that node's primitives, each once (a cut
// of its subtree); the binary nodes above the cut (the ones opened) are
// interior; there are four children unless all of them are leaves; and no
// interior child has a larger area than any node that was opened, since
// the largest is opened first. Areas that agree to rounding count as equal.
inline void CheckCollapse(const ex::FastBVHAccel &bvh, CollapseCount *count,
                          const std::string &name) {
    const std::vector<LinearBVHNode> &binary = bvh.AdoptedNodes();
    const auto &binaryPrims = bvh.AdoptedPrimitives();
    if (binary.empty()) return;
    // The primitives under each binary node, sorted, and its parent.
    std::vector<std::vector<const Primitive *>> under(binary.size());
    std::vector<int> parent(binary.size(), -1);
    std::function<void(int)> gather = [&](int i) {
        const LinearBVHNode &n = binary[i];
        if (n.nPrimitives > 0) {
            for (int k = 0; k < n.nPrimitives; ++k)
                under[i].push_back(binaryPrims[n.primitivesOffset + k].get());
        } else {
            int kids[2] = {i + 1, n.secondChildOffset};
            for (int c : kids) {
                parent[c] = i;
                gather(c);
                under[i].insert(under[i].end(), under[c].begin(),
                                under[c].end());
            }
        }
        std::sort(under[i].begin(), under[i].end());
    };
    gather(0);
    std::map<std::vector<const Primitive *>, int> nodeOf;
    for (size_t i = 0; i < binary.size(); ++i) nodeOf[under[i]] = int(i);
    auto isLeaf = [&](int i) { return binary[i].nPrimitives > 0; };
    // The primitives under a child of the four-wide tree, sorted.
    std::function<void(FastBVHChild, std::vector<const Primitive *> *)>
        wideUnder = [&](FastBVHChild c, std::vector<const Primitive *> *out) {
            if (c.IsLeaf()) {
                for (int k = 0; k < c.NPrimitives(); ++k)
                    out->push_back(bvh.Primitives()[c.offset + k].get());
                return;
            }
            for (const FastBVHChild &child : bvh.Nodes()[c.offset].child)
                wideUnder(child, out);
        };
    int failures = 0;
    auto fail = [&](int i, const std::string &why) {
        if (failures++ < kMaxFailuresReported)
            ADD_FAILURE() << name << ": binary node " << i << ": " << why;
    };
    // Binary node i stands for four-wide child w.
    std::function<void(int, FastBVHChild)> match = [&](int i, FastBVHChild w) {
        if (isLeaf(i)) {
            if (!w.IsLeaf()) fail(i, "a leaf became an interior node");
            return;
        }
        if (w.IsLeaf()) return fail(i, "an interior node became a leaf");
        const FastBVHNode &node = bvh.Nodes()[w.offset];
        ++count->nodes;
        std::vector<int> cut;
        std::vector<const Primitive *> all;
        for (int k = 0; k < fastBVHWidth; ++k) {
            if (node.child[k].IsEmpty()) continue;
            std::vector<const Primitive *> s;
            wideUnder(node.child[k], &s);
            std::sort(s.begin(), s.end());
            auto it = nodeOf.find(s);
            if (it == nodeOf.end())
                return fail(i, "child " + std::to_string(k) +
                                   " holds the primitives of no binary node");
            int d = it->second;
            int up = d;
            while (up >= 0 && up != i) up = parent[up];
            if (up != i || d == i)
                return fail(i, "child " + std::to_string(k) +
                                   " is not below the node");
            if (!(BoxOf(node, k) == binary[d].bounds))
                fail(i, "child " + std::to_string(k) +
                            " has a box not its own");
            cut.push_back(d);
            all.insert(all.end(), s.begin(), s.end());
        }
        std::sort(all.begin(), all.end());
        if (all != under[i] ||
            std::adjacent_find(all.begin(), all.end()) != all.end())
            return fail(i, "the children do not hold the node's primitives "
                           "once each");
        // The opened nodes: those strictly between i and the cut.
        std::set<int> opened;
        for (int d : cut)
            for (int up = parent[d]; up != i; up = parent[up])
                opened.insert(up);
        count->opened += int(opened.size());
        if (cut.size() != 2 + opened.size())
            return fail(i, "the children are not a cut of its subtree");
        bool allLeaves = true;
        for (int d : cut) allLeaves = allLeaves && isLeaf(d);
        if (cut.size() < size_t(fastBVHWidth) && !allLeaves)
            fail(i, std::to_string(cut.size()) +
                        " children, and one of them could be opened");
        count->full += cut.size() == size_t(fastBVHWidth);
        double smallestOpened = Infinity;
        for (int o : opened)
            smallestOpened =
                std::min(smallestOpened, HalfAreaOf(binary[o].bounds));
        for (int d : cut)
            if (!isLeaf(d) &&
                HalfAreaOf(binary[d].bounds) > smallestOpened * (1 + 1e-5))
                fail(i, "a child of area " +
                            std::to_string(HalfAreaOf(binary[d].bounds)) +
                            " stayed closed where one of area " +
                            std::to_string(smallestOpened) + " was opened");
        for (size_t k = 0; k < cut.size(); ++k) match(cut[k], node.child[k]);
    };
    match(0, bvh.Root());
}

// The worker's FastBVHAccel adopting the tree of a BVHAccel built with
// method m over `scene`: its structure, and the collapse of every node.
// `name` names the scene in failures.
inline void CheckAdoptedTree(const Scene &scene, SplitMethod m, int leafSize,
                             CollapseCount *count, const std::string &name) {
    ex::FastBVHAccel bvh(scene, leafSize, m, true);
    CheckStructure(bvh, scene.prims);
    CheckCollapse(bvh, count,
                  name + ", " + MethodName(m) + "(" +
                      std::to_string(leafSize) + ")");
}

// ---------------------------------------------------------------------------
// The binned SAH

struct SAHCount {
    int decisions = 0, leaves = 0, near = 0;
};

// The binned SAH of chapter 7's "Building with Binned SAH", in the order in
// which the build makes its decisions: the binary tree is never stored, but
// every node of it holds a range of the primitives in their final order (the
// partitions keep each node's records together, and the leaves store them in
// that order), so the decisions can be recovered from bvh.Primitives() and
// the ranges of the leaves. At each range, the binning is the book's (the
// axis of the box's largest extent, min(n, 16) bins, a primitive's bin from
// its centroid, in Float as the build computes it); the cost of every bin
// boundary and of a leaf are evaluated here in double precision, with c_T = 3
// and c_I = 1. The tree must make a leaf where that is cheapest and split at
// a cheapest boundary otherwise (where two costs agree to rounding, either
// will do), and where no boundary has primitives on both sides, split a range
// too large for a leaf into halves by centroid.
inline void CheckSAHDecisions(const ex::FastBVHAccel &bvh, SAHCount *count,
                              const std::string &name) {
    const auto &prims = bvh.Primitives();
    const int maxPrims = bvh.MaxPrimsInNode();
    std::map<uint32_t, int> leafAt;  // the leaves' ranges: offset, count
    std::function<void(FastBVHChild)> leaves = [&](FastBVHChild c) {
        if (c.IsLeaf()) {
            if (!c.IsEmpty()) leafAt[c.offset] = c.NPrimitives();
            return;
        }
        for (const FastBVHChild &child : bvh.Nodes()[c.offset].child)
            leaves(child);
    };
    if (prims.empty()) return;
    leaves(bvh.Root());
    const double tol = 1e-5;
    int failures = 0;
    auto fail = [&](int s, int e, const std::string &why) {
        if (failures++ < kMaxFailuresReported)
            ADD_FAILURE() << name << ": primitives " << s << " to " << e - 1
                          << ": " << why;
    };
    std::function<void(int, int, int)> check = [&](int s, int e, int depth) {
        int n = e - s;
        auto isLeaf = [&] {
            auto it = leafAt.find(uint32_t(s));
            return it != leafAt.end() && it->second == n;
        };
        if (n == 1) {
            if (!isLeaf()) fail(s, e, "one primitive, not in a leaf");
            return;
        }
        Float lo[3] = {Infinity, Infinity, Infinity},
              hi[3] = {-Infinity, -Infinity, -Infinity};
        std::vector<Bounds3f> boxes;
        for (int k = s; k < e; ++k) {
            Bounds3f b = prims[k]->WorldBound();
            boxes.push_back(b);
            for (int a = 0; a < 3; ++a) {
                lo[a] = std::min(lo[a], b.pMin[a]);
                hi[a] = std::max(hi[a], b.pMax[a]);
            }
        }
        Float dx = hi[0] - lo[0], dy = hi[1] - lo[1], dz = hi[2] - lo[2];
        int dim = (dx > dy && dx > dz) ? 0 : (dy > dz ? 1 : 2);
        auto centroid = [&](const Bounds3f &b) {
            return b.pMin[dim] * Float(0.5) + b.pMax[dim] * Float(0.5);
        };
        auto halves = [&] {
            int mid = (s + e) / 2;
            Float leftMax = -Infinity, rightMin = Infinity;
            for (int k = 0; k < n; ++k) {
                Float c = centroid(boxes[k]);
                if (s + k < mid) leftMax = std::max(leftMax, c);
                else rightMin = std::min(rightMin, c);
            }
            if (isLeaf() || leftMax > rightMin)
                return fail(s, e, "not split into halves by centroid");
            check(s, mid, depth + 1);
            check(mid, e, depth + 1);
        };
        if (depth + CeilLog2(n) >= maxBVHDepth) return halves();
        int nBins = std::min(n, 16);
        Float scale = Float(nBins) / (hi[dim] - lo[dim]);
        std::vector<int> bin(n), binCount(nBins, 0);
        std::vector<Bounds3f> binBox(nBins);
        for (int k = 0; k < n; ++k) {
            Float f = (centroid(boxes[k]) - lo[dim]) * scale;
            bin[k] = !(f > 0) ? 0 : (f >= nBins ? nBins - 1 : int(f));
            binCount[bin[k]]++;
            binBox[bin[k]] = Union(binBox[bin[k]], boxes[k]);
        }
        // The cost of splitting after each bin, in units of c_I.
        std::vector<double> cost(nBins - 1, Infinity);
        double best = Infinity;
        for (int b = 0; b + 1 < nBins; ++b) {
            Bounds3f left, right;
            int nl = 0, nr = 0;
            for (int j = 0; j < nBins; ++j) {
                if (j <= b) left = Union(left, binBox[j]), nl += binCount[j];
                else right = Union(right, binBox[j]), nr += binCount[j];
            }
            if (nl == 0 || nr == 0) continue;
            cost[b] = nl * HalfAreaOf(left) + nr * HalfAreaOf(right);
            best = std::min(best, cost[b]);
        }
        Bounds3f all(Point3f(lo[0], lo[1], lo[2]),
                     Point3f(hi[0], hi[1], hi[2]));
        double area = HalfAreaOf(all);
        double leafCost = n * area, splitCost = 3 * area + best;
        bool leafAllowed = n <= maxPrims && splitCost >= leafCost * (1 - tol);
        bool splitAllowed = n > maxPrims || splitCost <= leafCost * (1 + tol);
        ++count->decisions;
        count->near += leafAllowed && splitAllowed && best < Infinity;
        if (isLeaf()) {
            ++count->leaves;
            if (!leafAllowed)
                fail(s, e, n > maxPrims ? "a leaf of more than maxPrimsInNode"
                                        : "a leaf where a split is cheaper");
            return;
        }
        if (best == Infinity) {
            if (n <= maxPrims)
                return fail(s, e, "a split where no bin boundary divides "
                                  "the primitives and a leaf is possible");
            return halves();
        }
        if (!splitAllowed) return fail(s, e, "a split where a leaf is cheaper");
        // The boundary the tree split at: the primitives of the bins up to it
        // come first.
        for (int b = 0; b + 1 < nBins; ++b) {
            if (!(cost[b] <= best * (1 + tol))) continue;
            int nl = 0;
            for (int j = 0; j <= b; ++j) nl += binCount[j];
            bool split = true;
            for (int k = 0; k < nl; ++k) split = split && bin[k] <= b;
            if (!split) continue;
            check(s, s + nl, depth + 1);
            check(s + nl, e, depth + 1);
            return;
        }
        fail(s, e, "split at no bin boundary of least cost");
    };
    check(0, int(prims.size()), 0);
}

// The worker's FastBVHAccel built with the SAH over `scene`, a scene of
// boxes: its structure, and every decision of the build. `name` names the
// scene in failures.
inline void CheckSAHTree(const Scene &scene, int leafSize, SAHCount *count,
                         const std::string &name) {
    ex::FastBVHAccel bvh(scene, leafSize, SplitMethod::SAH);
    CheckStructure(bvh, scene.prims);
    CheckSAHDecisions(bvh, count,
                      name + ", " + std::to_string(scene.prims.size()) +
                          " boxes, maxPrimsInNode " + std::to_string(leafSize));
}

// ---------------------------------------------------------------------------
// Rays in every octant, and rays with NaN and infinite components

// Traces rays in every octant of direction through each of `accels`, built
// over `scene`, against brute force: directions whose components are 0,
// 0.25 or 1 in magnitude, zeros signed as the octant says (the reciprocal
// turns the sign of a zero into that of an infinity, which picks the
// octant's planes), with lines through the middle of the scene. Counts in
// hitsPerOctant[octant] the rays that brute force finds a hit for.
inline void CheckEveryOctant(std::mt19937_64 &rng, const Scene &scene,
                             const std::vector<const Primitive *> &accels,
                             int hitsPerOctant[8]) {
    const Float magnitudes[] = {0, Float(0.25), 1};
    Point3f c = scene.bounds.pMin * Float(0.5) + scene.bounds.pMax * Float(0.5);
    double r = scene.bounds.Diagonal().Length() / 2;
    for (int octant = 0; octant < 8; ++octant)
        for (Float mx : magnitudes)
            for (Float my : magnitudes)
                for (Float mz : magnitudes) {
                    if (mx == 0 && my == 0 && mz == 0) continue;
                    Vector3f d(octant & 1 ? -mx : mx, octant & 2 ? -my : my,
                               octant & 4 ? -mz : mz);
                    Ray ray(RandomPoint(rng, c, 0.4 * r) -
                                Normalize(d) * Float(U(rng, 0, 3 * r)),
                            d);
                    Oracle o = BruteForce(scene.prims, ray);
                    if (!o.hits.empty()) ++hitsPerOctant[octant];
                    for (const Primitive *a : accels) {
                        std::string e = Compare(*a, ray, o);
                        EXPECT_TRUE(e.empty()) << "octant " << octant
                                               << ", ray " << ray << ": " << e;
                    }
                }
}

// 300 small triangles at random near the origin.
inline Scene SmallTriangles(std::mt19937_64 &rng) {
    Scene scene;
    for (int i = 0; i < 300; ++i) {
        Point3f a = RandomPoint(rng, Point3f(0, 0, 0), 2);
        scene.AddTriangles({a, a + RandomDirection(rng) * Float(0.3),
                            a + RandomDirection(rng) * Float(0.3)},
                           {0, 1, 2});
    }
    return scene;
}

// Rays that are NaN in every component, in the origin or the direction
// alone, or on one axis; rays with an infinite component; and n more rays
// near SmallTriangles(), NaN on one axis of the origin or the direction.
inline std::vector<Ray> RaysWithNaNAndInfinity(std::mt19937_64 &rng, int n) {
    const Float nan = std::numeric_limits<Float>::quiet_NaN();
    const Float inf = Infinity;
    std::vector<Ray> rays;
    rays.push_back(Ray(Point3f(nan, nan, nan), Vector3f(nan, nan, nan)));
    rays.push_back(Ray(Point3f(0, 0, 0), Vector3f(nan, nan, nan)));
    rays.push_back(Ray(Point3f(nan, nan, nan), Vector3f(0, 0, 1)));
    rays.push_back(Ray(Point3f(-5, 0, 0), Vector3f(1, nan, 0)));
    rays.push_back(Ray(Point3f(-5, 0.1f, 0.2f), Vector3f(inf, 0, 0)));
    rays.push_back(Ray(Point3f(-inf, 0, 0), Vector3f(1, 0, 0)));
    for (int i = 0; i < n; ++i) {
        Point3f o = RandomPoint(rng, Point3f(0, 0, 0), 4);
        Vector3f d = RandomDirection(rng);
        int axis = i % 3;
        if (i % 2) d[axis] = nan;
        else o[axis] = nan;
        rays.push_back(Ray(o, d));
    }
    return rays;
}

// Every ray ends, and gets from each of `accels` the answer of the first:
// whether Intersect() and IntersectP() hit, and where (two NaN distances
// count as the same).
inline void ExpectSameAnswers(const std::vector<const Primitive *> &accels,
                              const std::vector<Ray> &rays) {
    for (const Ray &ray : rays) {
        Ray r0 = ray;
        SurfaceInteraction si0;
        bool h0 = accels[0]->Intersect(r0, &si0);
        bool p0 = accels[0]->IntersectP(ray);
        for (size_t k = 1; k < accels.size(); ++k) {
            Ray r = ray;
            SurfaceInteraction si;
            bool h = accels[k]->Intersect(r, &si);
            EXPECT_EQ(h0, h) << "accelerator " << k << ", ray " << ray;
            EXPECT_EQ(p0, accels[k]->IntersectP(ray))
                << "accelerator " << k << ", ray " << ray;
            if (h0 && h) {
                EXPECT_TRUE(r0.tMax == r.tMax ||
                            (std::isnan(r0.tMax) && std::isnan(r.tMax)))
                    << "accelerator " << k << ", ray " << ray;
            }
        }
    }
}

// ---------------------------------------------------------------------------
// Scenes of boxes

// n boxes as primitives: in a cube, in clusters, flat in z, on a line
// (segments along x, of zero area), repeated copies of a few, on a grid of
// equal cubes (whose nodes have equal areas), or large boxes around nearly
// the same center; sizes over several orders of magnitude. Hollow boxes are
// never hit.
inline Scene RandomBoxScene(std::mt19937_64 &rng, int n, bool solid = true,
                            std::vector<int> *log = nullptr) {
    Scene scene;
    int kind = int(rng() % 7);
    int nCenters = 1 + int(rng() % 4);
    std::vector<Point3f> centers;
    for (int i = 0; i < nCenters; ++i)
        centers.push_back(RandomPoint(rng, Point3f(0, 0, 0), 50));
    std::vector<Bounds3f> few;
    int side = 1 + int(std::cbrt(double(n)));
    while (int(scene.prims.size()) < n) {
        int i = int(scene.prims.size());
        Point3f c = RandomPoint(rng, Point3f(0, 0, 0), 50);
        if (kind == 1)
            c = RandomPoint(rng, centers[rng() % nCenters], U(rng, 0.5, 5));
        Vector3f half(Float(std::pow(10.0, U(rng, -2, 1))),
                      Float(std::pow(10.0, U(rng, -2, 1))),
                      Float(std::pow(10.0, U(rng, -2, 1))));
        if (kind == 2) c.z = 0, half.z = 0;
        if (kind == 3) c.y = c.z = 0, half.y = half.z = 0;
        Bounds3f b(c - half, c + half);
        if (kind == 4) {
            if (few.size() < 3) few.push_back(b);
            b = few[rng() % few.size()];
        }
        if (kind == 5) {
            Point3f corner(Float(2 * (i % side)), Float(2 * (i / side % side)),
                           Float(2 * (i / side / side)));
            b = Bounds3f(corner, corner + Vector3f(1, 1, 1));
        }
        if (kind == 6) {
            c = RandomPoint(rng, centers[0], 0.2);
            b = Bounds3f(c - Vector3f(3, 2, 1), c + Vector3f(3, 2, 1));
        }
        scene.AddBox(b, solid, log, i);
    }
    return scene;
}

}  // namespace lrt_test
