// Chapter 6's exercise calls (tests/calls/calls.h): the tests of ex-6.5,
// ex-6.6 and ex-6.7 reach BVHAccel's builders and traversal, and the Morton
// code functions, only through these.
//
// A test describes its scene as values (a SceneValue), from which the worker
// makes primitives of its own. BuildBVH builds an accelerator over them,
// keeps it, and answers with its tree (BVHAccel's nodes), the order of its
// primitives as indices into the scene, and its statistics. TraceRay traces
// a ray through a kept accelerator and answers with the hit, its distance,
// the index of the primitive hit and, if asked, the indices of the
// primitives tested, in order.
//
// This is the end of the calls that runs them: the worker compiles it alone
// (tools/grading/build.py, LRT_CALLS_HEADER); the judge runs it too, with the
// book's code, to speculate (tests/calls/judge.cpp). The tests' end, which
// turns the answers back into a Primitive with lrt::BVHAccel's accessors, is
// remote_bvh.h.

#ifndef LRT_TESTS_CH06_EXERCISE_CALLS_H
#define LRT_TESTS_CH06_EXERCISE_CALLS_H

#include "lrt/accelerators/bvh.h"
#include "lrt/core/slabtest.h"
#include "lrt/shapes/sphere.h"
#include "lrt/shapes/disk.h"
#include "lrt/shapes/cylinder.h"
#include "lrt/shapes/cone.h"
#include "lrt/shapes/paraboloid.h"
#include "lrt/shapes/hyperboloid.h"
#include "lrt/shapes/triangle.h"
#include "calls/calls.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <memory>
#include <stdexcept>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

namespace lrt {

// ---------------------------------------------------------------------------
// Primitives of test scenes, made alike by the tests and by the worker

namespace ex {

// A primitive of a test that keeps note of the tests of it (in a log, in a
// count). When the worker's traversal tests its copy of the primitive, the
// adapters below note the test here.
class NotesTests {
  public:
    virtual ~NotesTests() = default;
    virtual bool KeepsNotes() const = 0;
    virtual void NoteTest() const = 0;
};

// A box as a primitive. A solid box is hit where the ray enters it (a ray that
// starts inside misses it); a hollow one is never hit. With a log, every call
// of Intersect() or IntersectP() appends the box's id to it.
class BoxPrimitive : public Primitive, public NotesTests {
  public:
    explicit BoxPrimitive(const Bounds3f &b, bool solid = true,
                          std::vector<int> *log = nullptr, int id = 0)
        : b(b), solid(solid), log(log), id(id) {}
    Bounds3f WorldBound() const override { return b; }
    bool Intersect(const Ray &r, SurfaceInteraction *isect) const override {
        Float t;
        if (!Hit(r, &t)) return false;
        r.tMax = t;
        isect->primitive = this;
        return true;
    }
    bool IntersectP(const Ray &r) const override {
        Float t;
        return Hit(r, &t);
    }
    bool KeepsNotes() const override { return log != nullptr; }
    void NoteTest() const override {
        if (log) log->push_back(id);
    }

  private:
    bool Hit(const Ray &r, Float *t) const {
        NoteTest();
        Float t0, t1;
        if (!solid || !b.IntersectP(r, &t0, &t1)) return false;
        *t = t0;
        return t0 > 0 && t0 < r.tMax;
    }
    Bounds3f b;
    bool solid;
    std::vector<int> *log;
    int id;
};

// A primitive whose bounds are whatever the test says (NaN, infinite,
// empty), and which every ray with tMax >= 1 hits at t = 1: an accelerator
// that leaves it out must never report it.
class OddBoundsPrimitive : public Primitive {
  public:
    explicit OddBoundsPrimitive(const Bounds3f &b) : b(b) {}
    Bounds3f WorldBound() const override { return b; }
    bool Intersect(const Ray &r, SurfaceInteraction *isect) const override {
        if (r.tMax < 1) return false;
        r.tMax = 1;
        isect->primitive = this;
        return true;
    }
    bool IntersectP(const Ray &r) const override { return r.tMax >= 1; }

  private:
    Bounds3f b;
};

}  // namespace ex

// ---------------------------------------------------------------------------
// Scenes as values

// The kinds of items of a scene.
enum SceneItem : uint8_t {
    kBoxItem,             // an ex::BoxPrimitive
    kSphereItem,          // a GeometricPrimitive of a Sphere
    kDiskItem,            // a GeometricPrimitive of a Disk
    kMeshItem,            // GeometricPrimitives of a mesh's Triangles
    kOddBoundsItem,       // an ex::OddBoundsPrimitive
    kEmptyAggregateItem,  // a BVHAccel over no primitives
    kCylinderItem,        // a GeometricPrimitive of a Cylinder
    kConeItem,            // a GeometricPrimitive of a Cone
    kParaboloidItem,      // a GeometricPrimitive of a Paraboloid
    kHyperboloidItem,     // a GeometricPrimitive of a Hyperboloid
};

// The items that are one quadric (a QuadricValue) each.
inline bool IsQuadricItem(uint8_t kind) {
    return kind == kSphereItem || kind == kDiskItem || kind == kCylinderItem ||
           kind == kConeItem || kind == kParaboloidItem ||
           kind == kHyperboloidItem;
}

struct BoxValue {
    Bounds3f bounds;
    bool solid;
    LRT_FIELDS(bounds, solid)
};

// A quadric's constructor arguments after its transformations and
// reverseOrientation, in the constructor's order, the rest zero: a sphere's
// radius, zMin, zMax and phiMax; a disk's height, radius, innerRadius and
// phiMax; a cylinder's radius, zMin, zMax and phiMax; a cone's height,
// radius and phiMax; a paraboloid's radius, z0, z1 and phiMax; a
// hyperboloid's point1 (x, y, z), point2 (x, y, z) and phiMax.
using QuadricArgs = std::array<Float, 7>;
struct QuadricValue {
    Transform objectToWorld, worldToObject;
    bool reverseOrientation;
    QuadricArgs args;
    LRT_FIELDS(objectToWorld, worldToObject, reverseOrientation, args)
};

// A triangle mesh in world space (the identity transformation).
struct MeshValue {
    std::vector<Point3f> p;
    std::vector<int> indices;
    LRT_FIELDS(p, indices)
};

// A scene: its items in order, each taking the next value of its kind (a
// mesh adds all its triangles). Primitive k of the scene is the k-th
// primitive made so.
struct SceneValue {
    std::vector<uint8_t> items;
    std::vector<BoxValue> boxes;
    std::vector<QuadricValue> quadrics;
    std::vector<MeshValue> meshes;
    std::vector<Bounds3f> oddBounds;
    LRT_FIELDS(items, boxes, quadrics, meshes, oddBounds)
};

// What the worker answers about an accelerator it built and keeps.
struct BuiltBVH {
    calls::Handle handle;
    std::vector<LinearBVHNode> nodes;  // BVHAccel's tree
    std::vector<int> order;  // Primitives(), as indices into the scene
    BVHStats stats;
    int maxPrimsInNode;
    Bounds3f worldBound;
    LRT_FIELDS(handle, nodes, order, stats, maxPrimsInNode, worldBound)
};

// What TraceRay answers: for Intersect(), whether the ray hit, its tMax
// afterwards and the index of the primitive hit (-1 if none is named); for
// IntersectP(), whether it hit. `tested`: the primitives tested, in order.
struct TraceResult {
    bool hit;
    Float tMax;
    int primitive;
    std::vector<int> tested;
    LRT_FIELDS(hit, tMax, primitive, tested)
};

namespace calls {

// BVHAccel's node and statistics, member by member.
inline void Put(Writer &w, const LinearBVHNode &n) {
    Put(w, n.bounds), Put(w, n.primitivesOffset), Put(w, n.nPrimitives),
        Put(w, n.axis);
}
inline void Get(Reader &r, LinearBVHNode &n) {
    Get(r, n.bounds), Get(r, n.primitivesOffset), Get(r, n.nPrimitives),
        Get(r, n.axis);
}
inline void Put(Writer &w, const BVHStats &s) {
    Put(w, s.interiorNodes), Put(w, s.leafNodes), Put(w, s.primitives);
    Put(w, s.maxDepth), Put(w, s.maxLeafSize), Put(w, s.sahCost);
}
inline void Get(Reader &r, BVHStats &s) {
    Get(r, s.interiorNodes), Get(r, s.leafNodes), Get(r, s.primitives);
    Get(r, s.maxDepth), Get(r, s.maxLeafSize), Get(r, s.sahCost);
}

}  // namespace calls

namespace direct {

// The primitives of a quadric or a mesh; the transformations they point to
// go into `transforms`.
inline std::shared_ptr<Primitive> MakeQuadric(
    uint8_t kind, const QuadricValue &q,
    std::vector<std::shared_ptr<Transform>> *transforms) {
    transforms->push_back(std::make_shared<Transform>(q.objectToWorld));
    const Transform *toWorld = transforms->back().get();
    transforms->push_back(std::make_shared<Transform>(q.worldToObject));
    const Transform *toObject = transforms->back().get();
    const QuadricArgs &a = q.args;
    const bool ro = q.reverseOrientation;
    std::shared_ptr<Shape> shape;
    switch (kind) {
    case kSphereItem:
        shape = std::make_shared<Sphere>(toWorld, toObject, ro, a[0], a[1],
                                         a[2], a[3]);
        break;
    case kDiskItem:
        shape = std::make_shared<Disk>(toWorld, toObject, ro, a[0], a[1], a[2],
                                       a[3]);
        break;
    case kCylinderItem:
        shape = std::make_shared<Cylinder>(toWorld, toObject, ro, a[0], a[1],
                                           a[2], a[3]);
        break;
    case kConeItem:
        shape = std::make_shared<Cone>(toWorld, toObject, ro, a[0], a[1],
                                       a[2]);
        break;
    case kParaboloidItem:
        shape = std::make_shared<Paraboloid>(toWorld, toObject, ro, a[0],
                                             a[1], a[2], a[3]);
        break;
    case kHyperboloidItem:
        shape = std::make_shared<Hyperboloid>(
            toWorld, toObject, ro, Point3f(a[0], a[1], a[2]),
            Point3f(a[3], a[4], a[5]), a[6]);
        break;
    default:
        throw std::invalid_argument("a scene item that is no quadric");
    }
    return std::make_shared<GeometricPrimitive>(shape);
}
inline std::vector<std::shared_ptr<Primitive>> MakeMesh(
    const MeshValue &m, std::vector<std::shared_ptr<Transform>> *transforms) {
    transforms->push_back(std::make_shared<Transform>());
    const Transform *id = transforms->back().get();
    auto shapes = CreateTriangleMesh(id, id, false, int(m.indices.size() / 3),
                                     m.indices.data(), int(m.p.size()),
                                     m.p.data(), nullptr, nullptr, nullptr);
    std::vector<std::shared_ptr<Primitive>> prims;
    for (auto &s : shapes)
        prims.push_back(std::make_shared<GeometricPrimitive>(s));
    return prims;
}

// A primitive of the worker's scene that writes its index into a log at
// every test (only where the test asks for the log).
class LoggedPrimitive : public Primitive {
  public:
    LoggedPrimitive(std::shared_ptr<Primitive> p, int index,
                    std::vector<int> *log)
        : p(std::move(p)), index(index), log(log) {}
    Bounds3f WorldBound() const override { return p->WorldBound(); }
    bool Intersect(const Ray &r, SurfaceInteraction *isect) const override {
        log->push_back(index);
        return p->Intersect(r, isect);
    }
    bool IntersectP(const Ray &r) const override {
        log->push_back(index);
        return p->IntersectP(r);
    }

  private:
    std::shared_ptr<Primitive> p;
    int index;
    std::vector<int> *log;
};

// An accelerator that the worker keeps, with the scene it was built over.
struct KeptAccelerator {
    std::vector<std::shared_ptr<Transform>> transforms;
    std::vector<std::shared_ptr<Primitive>> prims;  // in the scene's order
    std::unordered_map<const Primitive *, int> index;
    std::vector<int> tested;  // the log of the current query
    std::shared_ptr<lrt::BVHAccel> bvh;

    int IndexOf(const Primitive *p) const {
        auto it = index.find(p);
        return it == index.end() ? -1 : it->second;
    }
};

// Makes the scene's primitives (logged, if `log`) into `kept`.
inline void MakeScene(const SceneValue &scene, bool log,
                      KeptAccelerator *kept) {
    size_t box = 0, quadric = 0, mesh = 0, odd = 0;  // the next value of each
    auto next = [](size_t *i, size_t n) {
        if (*i >= n)
            throw std::invalid_argument("a scene item without a value");
        return (*i)++;
    };
    std::vector<std::shared_ptr<Primitive>> made;
    for (uint8_t kind : scene.items) {
        if (kind == kBoxItem) {
            const BoxValue &b = scene.boxes[next(&box, scene.boxes.size())];
            made.push_back(
                std::make_shared<ex::BoxPrimitive>(b.bounds, b.solid));
        } else if (IsQuadricItem(kind)) {
            made.push_back(MakeQuadric(
                kind, scene.quadrics[next(&quadric, scene.quadrics.size())],
                &kept->transforms));
        } else if (kind == kMeshItem) {
            for (auto &p :
                 MakeMesh(scene.meshes[next(&mesh, scene.meshes.size())],
                          &kept->transforms))
                made.push_back(p);
        } else if (kind == kOddBoundsItem) {
            made.push_back(std::make_shared<ex::OddBoundsPrimitive>(
                scene.oddBounds[next(&odd, scene.oddBounds.size())]));
        } else if (kind == kEmptyAggregateItem) {
            made.push_back(std::make_shared<lrt::BVHAccel>(
                std::vector<std::shared_ptr<Primitive>>()));
        } else {
            throw std::invalid_argument("a scene item of unknown kind");
        }
    }
    for (size_t k = 0; k < made.size(); ++k) {
        kept->index[made[k].get()] = int(k);
        if (log) {
            made[k] = std::make_shared<LoggedPrimitive>(made[k], int(k),
                                                        &kept->tested);
            kept->index[made[k].get()] = int(k);
        }
        kept->prims.push_back(made[k]);
    }
}

// Builds a BVHAccel over the scene and keeps it.
inline BuiltBVH BuildBVH(SceneValue scene, int maxPrimsInNode,
                         lrt::BVHAccel::SplitMethod method, bool log) {
    auto kept = std::make_shared<KeptAccelerator>();
    MakeScene(scene, log, kept.get());
    BuiltBVH built;
    kept->bvh =
        std::make_shared<lrt::BVHAccel>(kept->prims, maxPrimsInNode, method);
    built.nodes = kept->bvh->Nodes();
    built.stats = kept->bvh->Stats();
    built.maxPrimsInNode = kept->bvh->MaxPrimsInNode();
    built.worldBound = kept->bvh->WorldBound();
    for (const auto &p : kept->bvh->Primitives())
        built.order.push_back(kept->IndexOf(p.get()));
    built.handle = calls::Keep(kept);
    return built;
}

// Intersect() (or, with anyHit, IntersectP()) of `accel`, an accelerator
// over kept.prims, answered with indices into the scene; chapter 7's calls
// trace their FastBVHAccel with it too.
inline TraceResult TraceKept(KeptAccelerator &kept, const Primitive &accel,
                             Ray ray, bool anyHit, bool log) {
    kept.tested.clear();
    TraceResult result{false, ray.tMax, -1, {}};
    if (anyHit) {
        result.hit = accel.IntersectP(ray);
    } else {
        SurfaceInteraction si;
        result.hit = accel.Intersect(ray, &si);
        result.tMax = ray.tMax;
        if (result.hit) result.primitive = kept.IndexOf(si.primitive);
    }
    if (log) result.tested = kept.tested;
    return result;
}

// Intersect() (or, with anyHit, IntersectP()) of a kept BVHAccel.
inline TraceResult TraceRay(calls::Handle accelerator, Ray ray, bool anyHit,
                            bool log) {
    KeptAccelerator &kept = calls::Find<KeptAccelerator>(accelerator);
    return TraceKept(kept, *kept.bvh, ray, anyHit, log);
}

// The Morton code functions of Section 6.5.
inline uint32_t LeftShift3(uint32_t x) { return lrt::LeftShift3(x); }
inline uint32_t EncodeMorton3(Vector3f v) { return lrt::EncodeMorton3(v); }

}  // namespace direct
}  // namespace lrt

LRT_EXERCISE_CALL(BuildBVH)
LRT_EXERCISE_CALL(TraceRay)
LRT_EXERCISE_CALL(LeftShift3)
LRT_EXERCISE_CALL(EncodeMorton3)

#endif  // LRT_TESTS_CH06_EXERCISE_CALLS_H
