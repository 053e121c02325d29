// The tests' end of chapter 7's exercise calls (exercise_calls.h): the
// FastBVHAccel that the worker builds and keeps, seen from a test as a
// Primitive with the accessors of lrt::FastBVHAccel, as ex::BVHAccel
// (ch06/remote_bvh.h) shows a BVHAccel.
//
// Included by chapter 7's exercise tests (tests/ch07/, tests/hidden/ch07/),
// in `make test` and in the judge; never by the worker.

#ifndef LRT_TESTS_CH07_REMOTE_FASTBVH_H
#define LRT_TESTS_CH07_REMOTE_FASTBVH_H

#include "exercise_calls.h"
#include "ch06/remote_bvh.h"

#include <memory>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace lrt {
namespace ex {

// Checks that the worker's four-wide nodes form a tree under `root`: every
// node reached once, at most maxBVHDepth levels, leaves within the
// primitives and each primitive in one leaf (LeafCover, ch06/remote_bvh.h),
// and an empty leaf as the root of a tree of no primitives. Throws if not,
// so that no check ever follows an index out of the arrays or around a
// cycle, or walks overlapping leaves.
inline void CheckIsWideTree(const std::vector<FastBVHNode> &nodes,
                            FastBVHChild root, size_t nPrimitives) {
    auto refuse = [](const std::string &why) {
        throw std::runtime_error("the worker's FastBVHAccel is not a tree: " +
                                 why);
    };
    std::vector<char> reached(nodes.size(), 0);
    LeafCover cover(nPrimitives);
    std::vector<std::pair<FastBVHChild, int>> pending;  // child, depth
    if (nPrimitives == 0 && !(root.IsLeaf() && root.NPrimitives() == 0))
        refuse("a tree of no primitives has a root that is not an empty leaf");
    pending.push_back({root, 0});
    while (!pending.empty()) {
        auto [c, depth] = pending.back();
        pending.pop_back();
        if (depth > maxBVHDepth) refuse("it is deeper than maxBVHDepth");
        if (c.IsLeaf()) {
            if (size_t(c.offset) + c.NPrimitives() > nPrimitives)
                refuse("a leaf holds primitives outside the array");
            if (!cover.Add(c.offset, size_t(c.NPrimitives())))
                refuse("two leaves hold the same primitive");
            continue;
        }
        if (c.offset >= nodes.size())
            refuse("node " + std::to_string(c.offset) +
                   " is outside the array");
        if (reached[c.offset]++)
            refuse("node " + std::to_string(c.offset) + " is reached twice");
        for (const FastBVHChild &child : nodes[c.offset].child)
            pending.push_back({child, depth + 1});
    }
    for (size_t i = 0; i < nodes.size(); ++i)
        if (!reached[i])
            refuse("node " + std::to_string(i) +
                   " is not reached from the root");
    if (!cover.Complete()) refuse("a primitive is in no leaf");
}

// The worker's FastBVHAccel over a scene, with lrt::FastBVHAccel's
// interface: Primitives() are the test's own, in the tree's order. With
// `adopt`, the worker builds a BVHAccel with the split method and the
// FastBVHAccel adopts its tree; AdoptedNodes() and AdoptedPrimitives() are
// that BVHAccel's.
class FastBVHAccel : public Primitive {
  public:
    using SplitMethod = lrt::BVHAccel::SplitMethod;
    explicit FastBVHAccel(const Scene &scene, int maxPrimsInNode = 8,
                          SplitMethod splitMethod = SplitMethod::SAH,
                          bool adopt = false)
        : built(ex::BuildFastBVH(scene.value, maxPrimsInNode, splitMethod,
                                 adopt, KeepsNotes(scene))),
          log(KeepsNotes(scene)),
          kept(std::make_shared<KeptInWorker>(built.handle, scene.prims, log)) {
        for (int k : built.order) primitives.push_back(kept->Listed(k));
        for (int k : built.adoptedOrder)
            adoptedPrimitives.push_back(kept->Listed(k));
        CheckIsWideTree(built.nodes, built.root, primitives.size());
        if (built.triangles.size() != primitives.size())
            throw std::runtime_error("the worker's FastBVHAccel has " +
                                     std::to_string(built.triangles.size()) +
                                     " triangle records for " +
                                     std::to_string(primitives.size()) +
                                     " primitives");
        if (adopt) CheckIsTree(built.adoptedNodes, adoptedPrimitives.size());
    }
    Bounds3f WorldBound() const override { return built.worldBound; }
    bool Intersect(const Ray &ray, SurfaceInteraction *isect) const override {
        return Trace(ray, isect);
    }
    bool IntersectP(const Ray &ray) const override {
        return Trace(ray, nullptr);
    }
    const std::vector<FastBVHNode> &Nodes() const { return built.nodes; }
    FastBVHChild Root() const { return built.root; }
    const std::vector<std::shared_ptr<Primitive>> &Primitives() const {
        return primitives;
    }
    const std::vector<FastTriangle> &Triangles() const {
        return built.triangles;
    }
    int MaxPrimsInNode() const { return built.maxPrimsInNode; }
    BVHStats Stats() const { return built.stats; }
    const std::vector<LinearBVHNode> &AdoptedNodes() const {
        return built.adoptedNodes;
    }
    const std::vector<std::shared_ptr<Primitive>> &AdoptedPrimitives() const {
        return adoptedPrimitives;
    }

  private:
    // As KeptInWorker::Trace(), through TraceFastRay.
    bool Trace(const Ray &ray, SurfaceInteraction *isect) const {
        TraceResult r = ex::TraceFastRay(built.handle, ray, !isect, log);
        for (int k : r.tested) {
            auto notes = dynamic_cast<const NotesTests *>(kept->At(k).get());
            if (notes) notes->NoteTest();
        }
        if (isect) {
            ray.tMax = r.tMax;
            if (r.hit) isect->primitive = kept->At(r.primitive).get();
        }
        return r.hit;
    }
    BuiltFastBVH built;
    bool log;
    std::shared_ptr<const KeptInWorker> kept;
    std::vector<std::shared_ptr<Primitive>> primitives, adoptedPrimitives;
};

}  // namespace ex
}  // namespace lrt

#endif  // LRT_TESTS_CH07_REMOTE_FASTBVH_H
