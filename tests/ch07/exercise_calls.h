// Chapter 7's exercise calls (tests/calls/calls.h): the tests of ex-7.8,
// ex-7.9 and ex-7.10 reach FastBVHAccel's build and traversal only through
// these.
//
// The scenes are chapter 6's (a SceneValue, from which the worker makes
// primitives of its own; ch06/exercise_calls.h, whose calls the worker of
// chapter 7 serves too). BuildFastBVH builds a FastBVHAccel over a scene,
// with its own SAH builder or by adopting the tree of a BVHAccel that it
// builds first, keeps it, and answers with its four-wide tree (nodes, the
// reference to the root, the triangles' vertices), the order of its
// primitives as indices into the scene and its statistics; an adopted tree
// comes with the BVHAccel's nodes and order. TraceFastRay traces a ray
// through a kept FastBVHAccel and answers as chapter 6's TraceRay does.
//
// The worker compiles this end alone (tools/grading/build.py); the tests'
// end, which shows the answers as a Primitive with the accessors of
// lrt::FastBVHAccel, is remote_fastbvh.h.

#ifndef LRT_TESTS_CH07_EXERCISE_CALLS_H
#define LRT_TESTS_CH07_EXERCISE_CALLS_H

#include "ch06/exercise_calls.h"
#include "lrt/accelerators/fastbvh.h"

#include <memory>
#include <vector>

namespace lrt {

// What the worker answers about a FastBVHAccel it built and keeps.
struct BuiltFastBVH {
    calls::Handle handle;
    std::vector<FastBVHNode> nodes;
    FastBVHChild root;
    std::vector<FastTriangle> triangles;
    std::vector<int> order;  // Primitives(), as indices into the scene
    BVHStats stats;
    int maxPrimsInNode;
    Bounds3f worldBound;
    // For a tree adopted from a BVHAccel: that BVHAccel's nodes and the
    // order of its primitives (indices into the scene); empty otherwise.
    std::vector<LinearBVHNode> adoptedNodes;
    std::vector<int> adoptedOrder;
    LRT_FIELDS(handle, nodes, root, triangles, order, stats, maxPrimsInNode,
               worldBound, adoptedNodes, adoptedOrder)
};

namespace calls {

// FastBVHAccel's node types, member by member.
inline void Put(Writer &w, const FastBVHChild &c) {
    Put(w, c.offset), Put(w, c.nTriangles), Put(w, c.nOthers);
}
inline void Get(Reader &r, FastBVHChild &c) {
    Get(r, c.offset), Get(r, c.nTriangles), Get(r, c.nOthers);
}
inline void Put(Writer &w, const FastBVHNode &n) {
    for (const auto &axis : n.bounds)
        for (const auto &side : axis)
            for (Float v : side) Put(w, v);
    for (const FastBVHChild &c : n.child) Put(w, c);
}
inline void Get(Reader &r, FastBVHNode &n) {
    for (auto &axis : n.bounds)
        for (auto &side : axis)
            for (Float &v : side) Get(r, v);
    for (FastBVHChild &c : n.child) Get(r, c);
}
inline void Put(Writer &w, const FastTriangle &t) {
    for (const auto &axis : t.c)
        for (Float v : axis) Put(w, v);
}
inline void Get(Reader &r, FastTriangle &t) {
    for (auto &axis : t.c)
        for (Float &v : axis) Get(r, v);
}

}  // namespace calls

namespace direct {

// A FastBVHAccel that the worker keeps, with the scene it was built over.
struct KeptFastAccelerator : KeptAccelerator {
    std::shared_ptr<FastBVHAccel> fast;
};

// Builds a FastBVHAccel over the scene (adopting a BVHAccel's tree built
// with `method`, if `adopt`) and keeps it.
inline BuiltFastBVH BuildFastBVH(SceneValue scene, int maxPrimsInNode,
                                 lrt::BVHAccel::SplitMethod method, bool adopt,
                                 bool log) {
    auto kept = std::make_shared<KeptFastAccelerator>();
    MakeScene(scene, log, kept.get());
    BuiltFastBVH built;
    if (adopt) {
        lrt::BVHAccel bvh(kept->prims, maxPrimsInNode, method);
        built.adoptedNodes = bvh.Nodes();
        for (const auto &p : bvh.Primitives())
            built.adoptedOrder.push_back(kept->IndexOf(p.get()));
        kept->fast = std::make_shared<FastBVHAccel>(bvh);
    } else {
        kept->fast =
            std::make_shared<FastBVHAccel>(kept->prims, maxPrimsInNode, method);
    }
    const FastBVHAccel &fast = *kept->fast;
    built.nodes.assign(fast.Nodes().begin(), fast.Nodes().end());
    built.root = fast.Root();
    built.triangles.assign(fast.Triangles().begin(), fast.Triangles().end());
    for (const auto &p : fast.Primitives())
        built.order.push_back(kept->IndexOf(p.get()));
    built.stats = fast.Stats();
    built.maxPrimsInNode = fast.MaxPrimsInNode();
    built.worldBound = fast.WorldBound();
    built.handle = calls::Keep(kept);
    return built;
}

// Intersect() (or, with anyHit, IntersectP()) of a kept FastBVHAccel.
inline TraceResult TraceFastRay(calls::Handle accelerator, Ray ray,
                                bool anyHit, bool log) {
    KeptFastAccelerator &kept = calls::Find<KeptFastAccelerator>(accelerator);
    return TraceKept(kept, *kept.fast, ray, anyHit, log);
}

}  // namespace direct
}  // namespace lrt

LRT_EXERCISE_CALL(BuildFastBVH)
LRT_EXERCISE_CALL(TraceFastRay)

#endif  // LRT_TESTS_CH07_EXERCISE_CALLS_H
