// The tests' end of chapter 6's exercise calls (exercise_calls.h): the
// BVHAccel that the worker builds and keeps, seen from a test as a
// Primitive with the accessors of lrt::BVHAccel, so that the tests read as
// they would with the library's class.
//
// A test describes its scene with an ex::Scene, which holds the test's own
// primitives (for its oracles) and their description (a SceneValue), which
// travels to the worker. ex::BVHAccel maps the indices of the worker's answers
// back to the test's own primitives, and refuses (throws on) an answer whose
// indices do not describe a tree over the scene.
//
// Included by chapter 6's tests (tests/ch06/, tests/hidden/ch06/), in
// `make test` and in the judge; never by the worker, which runs the calls'
// end only.

#ifndef LRT_TESTS_CH06_REMOTE_BVH_H
#define LRT_TESTS_CH06_REMOTE_BVH_H

#include "exercise_calls.h"

#include <memory>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace lrt {
namespace ex {

// A test's scene: its own primitives, for the test's oracles, and their
// description, from which the worker makes its copies. Primitive k of
// `prims` is primitive k of the description. A test may replace a primitive
// of `prims` by one that wraps it (to count its tests, say).
class Scene {
  public:
    std::vector<std::shared_ptr<Primitive>> prims;
    Bounds3f bounds;  // of the primitives with a finite box
    SceneValue value;

    void AddBox(const Bounds3f &b, bool solid = true,
                std::vector<int> *log = nullptr, int id = 0) {
        value.items.push_back(kBoxItem);
        value.boxes.push_back({b, solid});
        Add(std::make_shared<BoxPrimitive>(b, solid, log, id));
    }
    void AddSphere(const Transform &objectToWorld,
                   const Transform &worldToObject, bool reverseOrientation,
                   Float radius, Float zMin, Float zMax, Float phiMax) {
        QuadricArgs args = {radius, zMin, zMax, phiMax};
        AddQuadric(kSphereItem,
                   {objectToWorld, worldToObject, reverseOrientation, args});
    }
    void AddDisk(const Transform &objectToWorld, const Transform &worldToObject,
                 bool reverseOrientation, Float height, Float radius,
                 Float innerRadius, Float phiMax) {
        QuadricArgs args = {height, radius, innerRadius, phiMax};
        AddQuadric(kDiskItem,
                   {objectToWorld, worldToObject, reverseOrientation, args});
    }
    void AddCylinder(const Transform &objectToWorld,
                     const Transform &worldToObject, bool reverseOrientation,
                     Float radius, Float zMin, Float zMax, Float phiMax) {
        QuadricArgs args = {radius, zMin, zMax, phiMax};
        AddQuadric(kCylinderItem,
                   {objectToWorld, worldToObject, reverseOrientation, args});
    }
    void AddCone(const Transform &objectToWorld, const Transform &worldToObject,
                 bool reverseOrientation, Float height, Float radius,
                 Float phiMax) {
        QuadricArgs args = {height, radius, phiMax};
        AddQuadric(kConeItem,
                   {objectToWorld, worldToObject, reverseOrientation, args});
    }
    void AddParaboloid(const Transform &objectToWorld,
                       const Transform &worldToObject, bool reverseOrientation,
                       Float radius, Float z0, Float z1, Float phiMax) {
        QuadricArgs args = {radius, z0, z1, phiMax};
        AddQuadric(kParaboloidItem,
                   {objectToWorld, worldToObject, reverseOrientation, args});
    }
    void AddHyperboloid(const Transform &objectToWorld,
                        const Transform &worldToObject,
                        bool reverseOrientation, const Point3f &point1,
                        const Point3f &point2, Float phiMax) {
        QuadricArgs args = {point1.x, point1.y, point1.z, point2.x,
                            point2.y, point2.z, phiMax};
        AddQuadric(kHyperboloidItem,
                   {objectToWorld, worldToObject, reverseOrientation, args});
    }
    void AddTriangles(const std::vector<Point3f> &p,
                      const std::vector<int> &indices) {
        value.items.push_back(kMeshItem);
        value.meshes.push_back({p, indices});
        for (auto &prim : direct::MakeMesh(value.meshes.back(), &transforms))
            Add(prim);
    }
    void AddOddBounds(const Bounds3f &b) {
        value.items.push_back(kOddBoundsItem);
        value.oddBounds.push_back(b);
        Add(std::make_shared<OddBoundsPrimitive>(b));
    }
    void AddEmptyAggregate() {
        value.items.push_back(kEmptyAggregateItem);
        Add(std::make_shared<lrt::BVHAccel>(
            std::vector<std::shared_ptr<Primitive>>()));
    }

  private:
    void AddQuadric(uint8_t kind, const QuadricValue &q) {
        value.items.push_back(kind);
        value.quadrics.push_back(q);
        Add(direct::MakeQuadric(kind, q, &transforms));
    }
    void Add(std::shared_ptr<Primitive> p) {
        Bounds3f b = p->WorldBound();
        if (IsFiniteBox(b)) bounds = Union(bounds, b);
        prims.push_back(std::move(p));
    }
    std::vector<std::shared_ptr<Transform>> transforms;
};

// Whether the worker is to log the tests of its primitives: if some primitive
// of the test keeps notes of its tests.
inline bool KeepsNotes(const Scene &scene) {
    for (const auto &p : scene.prims) {
        auto notes = dynamic_cast<const NotesTests *>(p.get());
        if (notes && notes->KeepsNotes()) return true;
    }
    return false;
}

// An accelerator that the worker keeps, seen from the test: its handle and
// the test's primitives in the scene's order.
class KeptInWorker {
  public:
    KeptInWorker(calls::Handle handle,
                 const std::vector<std::shared_ptr<Primitive>> &scene, bool log)
        : handle(std::move(handle)), scene(scene), log(log) {}
    // The test's primitive of the worker's index k in a tree's order, where
    // every entry must name one.
    const std::shared_ptr<Primitive> &Listed(int k) const {
        if (k == -1)
            throw std::runtime_error("the worker lists no primitive (-1) in "
                                     "its tree's order");
        return At(k);
    }
    // The test's primitive of the worker's index k (nullptr for -1).
    const std::shared_ptr<Primitive> &At(int k) const {
        static const std::shared_ptr<Primitive> none;
        if (k == -1) return none;
        if (k < 0 || k >= int(scene.size()))
            throw std::runtime_error("the worker names primitive " +
                                     std::to_string(k) + " of a scene of " +
                                     std::to_string(scene.size()));
        return scene[k];
    }
    // Intersect() (isect given) or IntersectP() in the worker; notes the
    // tests of the test's primitives that keep notes.
    bool Trace(const Ray &ray, SurfaceInteraction *isect) const {
        TraceResult r = ex::TraceRay(handle, ray, !isect, log);
        for (int k : r.tested) {
            auto notes = dynamic_cast<const NotesTests *>(At(k).get());
            if (notes) notes->NoteTest();
        }
        if (isect) {
            ray.tMax = r.tMax;
            if (r.hit) isect->primitive = At(r.primitive).get();
        }
        return r.hit;
    }

  private:
    calls::Handle handle;
    std::vector<std::shared_ptr<Primitive>> scene;
    bool log;
};

// Counts the primitives a leaf holds, each of which must be in exactly one
// leaf: trees whose leaves overlap would let the checks that walk them do
// the work of every leaf for every primitive (a reply of a few megabytes
// could make the judge check billions of pairs).
class LeafCover {
  public:
    explicit LeafCover(size_t nPrimitives) : held(nPrimitives, 0) {}
    // False if a primitive of [offset, offset + n) is already in a leaf.
    bool Add(size_t offset, size_t n) {
        for (size_t k = offset; k < offset + n; ++k)
            if (held[k]++) return false;
        return true;
    }
    bool Complete() const {
        for (char h : held)
            if (!h) return false;
        return true;
    }

  private:
    std::vector<char> held;
};

// Checks that the worker's nodes are a tree over its primitives, laid out as
// BVHAccel lays it out (Section 6.3.5): every node reached once from the root,
// a first child right after its parent and a second child after that, leaves
// within the primitives and each primitive in one leaf, at most maxBVHDepth
// levels. Throws if not, so that no check ever follows an index out of the
// arrays or around a cycle.
inline void CheckIsTree(const std::vector<LinearBVHNode> &nodes,
                        size_t nPrimitives) {
    auto refuse = [](int i, const std::string &why) {
        throw std::runtime_error("the worker's BVH is not a tree: node " +
                                 std::to_string(i) + " " + why);
    };
    std::vector<char> reached(nodes.size(), 0);
    LeafCover cover(nPrimitives);
    std::vector<std::pair<int, int>> pending;  // node, depth
    if (!nodes.empty()) pending.push_back({0, 0});
    while (!pending.empty()) {
        auto [i, depth] = pending.back();
        pending.pop_back();
        if (reached[i]++) refuse(i, "is reached twice");
        if (depth > maxBVHDepth) refuse(i, "is deeper than maxBVHDepth");
        const LinearBVHNode &n = nodes[i];
        if (n.nPrimitives > 0) {
            if (n.primitivesOffset < 0 ||
                size_t(n.primitivesOffset) + n.nPrimitives > nPrimitives)
                refuse(i, "has primitives outside the array");
            if (!cover.Add(size_t(n.primitivesOffset), size_t(n.nPrimitives)))
                refuse(i, "holds a primitive that another leaf holds");
            continue;
        }
        if (n.axis > 2)
            refuse(i, "splits along axis " + std::to_string(n.axis));
        if (i + 1 >= int(nodes.size()) || n.secondChildOffset <= i + 1 ||
            n.secondChildOffset >= int(nodes.size()))
            refuse(i, "has children outside the array or out of order");
        pending.push_back({i + 1, depth + 1});
        pending.push_back({n.secondChildOffset, depth + 1});
    }
    for (size_t i = 0; i < nodes.size(); ++i)
        if (!reached[i]) refuse(int(i), "is not reached from the root");
    if (!cover.Complete())
        throw std::runtime_error("the worker's BVH is not a tree: a primitive "
                                 "is in no leaf");
}

// The worker's BVHAccel over a scene, with lrt::BVHAccel's interface:
// Primitives() are the test's own, in the tree's order. The scene may go
// out of scope; its primitives stay.
class BVHAccel : public Primitive {
  public:
    using SplitMethod = lrt::BVHAccel::SplitMethod;
    explicit BVHAccel(const Scene &scene, int maxPrimsInNode = 1,
                      SplitMethod splitMethod = SplitMethod::SAH)
        : built(ex::BuildBVH(scene.value, maxPrimsInNode, splitMethod,
                             KeepsNotes(scene))),
          kept(std::make_shared<KeptInWorker>(built.handle, scene.prims,
                                              KeepsNotes(scene))) {
        for (int k : built.order) primitives.push_back(kept->Listed(k));
        CheckIsTree(built.nodes, primitives.size());
    }
    Bounds3f WorldBound() const override { return built.worldBound; }
    bool Intersect(const Ray &ray, SurfaceInteraction *isect) const override {
        return kept->Trace(ray, isect);
    }
    bool IntersectP(const Ray &ray) const override {
        return kept->Trace(ray, nullptr);
    }
    const std::vector<LinearBVHNode> &Nodes() const { return built.nodes; }
    const std::vector<std::shared_ptr<Primitive>> &Primitives() const {
        return primitives;
    }
    int MaxPrimsInNode() const { return built.maxPrimsInNode; }
    BVHStats Stats() const { return built.stats; }

  private:
    BuiltBVH built;
    std::shared_ptr<const KeptInWorker> kept;
    std::vector<std::shared_ptr<Primitive>> primitives;
};

}  // namespace ex
}  // namespace lrt

#endif  // LRT_TESTS_CH06_REMOTE_BVH_H
