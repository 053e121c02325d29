// Scenes, oracles and checks shared by the tests of BVHAccel (chapter 6)
// and of FastBVHAccel (chapter 7, which includes this file as
// "ch06/bvh_scenes.h"): random scenes of spheres, disks and triangles, and
// of every shape of chapter 3 (the other quadrics too), as ex::Scene values; random rays; brute force over the primitives as the
// oracle of the closest hit; the structure of a BVHAccel's tree; and the
// degenerate scenes, each run with a set of accelerators (an AccelSet) that
// the test chooses.

#pragma once

#include "bvh_checks.h"
#include "remote_bvh.h"
#include "lrt/accelerators/bvh.h"
#include "lrt/shapes/cone.h"
#include "lrt/shapes/cylinder.h"
#include "lrt/shapes/disk.h"
#include "lrt/shapes/hyperboloid.h"
#include "lrt/shapes/paraboloid.h"
#include "lrt/shapes/sphere.h"
#include "lrt/shapes/triangle.h"

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
#include <sstream>
#include <string>
#include <typeinfo>
#include <utility>
#include <vector>

namespace lrt_test {

using namespace lrt;
using SplitMethod = BVHAccel::SplitMethod;

constexpr int kRandomScenes = 1200;
// The exercises' random scenes: here, and when graded (where every build and
// every ray crosses to the worker, whose code is not optimized).
inline const int kExerciseRandomScenes = calls::Cases(300, 60);
constexpr int kRaysPerScene = 32;
constexpr int kMaxFailuresReported = 10;
const SplitMethod kMethods[] = {SplitMethod::SAH, SplitMethod::HLBVH,
                                SplitMethod::Middle,
                                SplitMethod::EqualCounts};
const int kLeafSizes[] = {1, 2, 4, 7, 255};
// Two primitives hit at nearly the same distance may be reported in either
// order when their error bounds overlap; the distance reported may then
// exceed the smallest one by this relative amount.
const Float kTieTolerance = 256 * std::numeric_limits<Float>::epsilon();

inline const char *MethodName(SplitMethod m) { return BVHAccel::SplitMethodName(m); }

// A scene: its primitives (scene.prims), and their description, from which
// the worker makes its own for the exercises' accelerators.
using Scene = ex::Scene;

inline Point3f RandomPoint(std::mt19937_64 &rng, const Point3f &c, double r) {
    return Point3f(Float(c.x + U(rng, -r, r)), Float(c.y + U(rng, -r, r)),
                   Float(c.z + U(rng, -r, r)));
}

// What a random scene holds: spheres, disks and triangles, or every shape of
// chapter 3 (cylinders, cones, paraboloids and hyperboloids too). The first
// draws exactly the scenes it always drew, so that the seeds of the tests
// keep their scenes.
enum class Shapes { SpheresDisksTriangles, All };

// An object-to-world transformation at c: a random rotation, sometimes with
// a scale that differs along the object's axes.
inline Transform RandomPlacement(std::mt19937_64 &rng, const Point3f &c) {
    Transform o2w = Translate(Vector3f(c)) *
                    Rotate(Float(U(rng, 0, 360)), RandomDirection(rng));
    if (rng() % 3 == 0)
        o2w = o2w * Scale(Float(U(rng, 0.3, 2)), Float(U(rng, 0.3, 2)),
                          Float(U(rng, 0.3, 2)));
    return o2w;
}

// phiMax in degrees: the whole circle, or, with probability `partial`, part
// of it (now and then more than 360, which the constructors clamp).
inline Float RandomPhiMax(std::mt19937_64 &rng, double partial) {
    if (U(rng, 0, 1) >= partial) return 360;
    return rng() % 16 == 0 ? Float(U(rng, 360, 400)) : Float(U(rng, 20, 350));
}

// One of the four quadrics of "Other Quadrics" in chapter 3, of about the
// given size, placed by a random transformation at c: with partial phiMax
// half the time, z ranges that cut it, the ends given in either order, and
// the special cases of the hyperboloid (its segment parallel to the axis, a
// cylinder; or meeting the axis, a cone).
inline void AddRandomQuadric(std::mt19937_64 &rng, Scene *scene, int kind,
                             const Point3f &c, double size) {
    Transform o2w = RandomPlacement(rng, c);
    bool ro = rng() % 4 == 0;
    Float phiMax = RandomPhiMax(rng, 0.5);
    auto s = [&](double lo, double hi) { return Float(size * U(rng, lo, hi)); };
    if (kind == 0) {
        Float zMin = s(-1, 0.3), zMax = s(0.4, 1.5);
        if (rng() % 2) std::swap(zMin, zMax);
        scene->AddCylinder(o2w, Inverse(o2w), ro, s(0.2, 1), zMin, zMax,
                           phiMax);
    } else if (kind == 1) {
        scene->AddCone(o2w, Inverse(o2w), ro, s(0.3, 2), s(0.2, 1.2), phiMax);
    } else if (kind == 2) {
        // z0 < 0 is clamped to 0, the paraboloid's tip.
        Float z0 = rng() % 3 == 0 ? 0 : s(-0.5, 0.6), z1 = s(0.7, 2);
        if (rng() % 2) std::swap(z0, z1);
        scene->AddParaboloid(o2w, Inverse(o2w), ro, s(0.2, 1.2), z0, z1,
                             phiMax);
    } else {
        Point3f p1(s(-1, 1), s(-1, 1), s(-1, -0.1));
        Point3f p2(s(-1, 1), s(-1, 1), s(0.1, 1));
        int special = int(rng() % 6);
        if (special == 0) p2.x = p1.x, p2.y = p1.y;  // a cylinder
        if (special == 1) p2.x = p2.y = 0;           // a cone, apex at p2
        if (rng() % 2) std::swap(p1, p2);
        scene->AddHyperboloid(o2w, Inverse(o2w), ro, p1, p2, phiMax);
    }
}

// A random scene: clusters of small primitives and a few large ones, so
// that the split methods produce trees of varied shapes.
inline Scene RandomScene(std::mt19937_64 &rng,
                         Shapes shapes = Shapes::SpheresDisksTriangles) {
    const bool all = shapes == Shapes::All;
    Scene scene;
    int n = 1 + int(rng() % 40);
    if (rng() % 8 == 0) n += int(rng() % 160);
    int nClusters = 1 + int(rng() % 3);
    std::vector<Point3f> centers;
    for (int i = 0; i < nClusters; ++i)
        centers.push_back(RandomPoint(rng, Point3f(0, 0, 0), 8));
    while (int(scene.prims.size()) < n) {
        Point3f c = RandomPoint(rng, centers[rng() % nClusters], 3);
        double size = rng() % 10 == 0 ? U(rng, 1, 4) : U(rng, 0.05, 1);
        int kind = int(rng() % (all ? 7 : 3));
        if (kind >= 3) {
            AddRandomQuadric(rng, &scene, kind - 3, c, size);
        } else if (kind == 0) {
            Transform o2w = RandomPlacement(rng, c);
            Float r = Float(size);
            Float zMin = -r, zMax = r, phiMax = 360;
            if (rng() % (all ? 2 : 4) == 0) {
                zMin = Float(U(rng, -1, 0.2)) * r;
                zMax = Float(U(rng, 0.3, 1)) * r;
                phiMax = Float(U(rng, 30, 360));
            }
            scene.AddSphere(o2w, Inverse(o2w), rng() % 2 == 0, r, zMin, zMax,
                            phiMax);
        } else if (kind == 1) {
            Transform o2w = Translate(Vector3f(c));
            if (rng() % 3 != 0)  // else: axis-aligned, with a flat box
                o2w = o2w * Rotate(Float(U(rng, 0, 360)), RandomDirection(rng));
            Float r = Float(size);
            Float ri = rng() % 3 == 0 ? Float(U(rng, 0, 0.8)) * r : 0;
            Float phiMax = rng() % 3 == 0 ? Float(U(rng, 30, 360)) : 360;
            scene.AddDisk(o2w, Inverse(o2w), false, Float(U(rng, -1, 1)), r, ri,
                          phiMax);
        } else {
            // A small strip of triangles sharing edges; sometimes flat in z.
            int nt = 1 + int(rng() % 4);
            bool flat = rng() % 4 == 0;
            std::vector<Point3f> p;
            std::vector<int> idx;
            for (int i = 0; i < nt + 2; ++i) {
                Point3f q = RandomPoint(rng, c, size);
                if (flat) q.z = c.z;
                p.push_back(q);
            }
            for (int i = 0; i < nt; ++i) {
                idx.push_back(i);
                idx.push_back(i + 1);
                idx.push_back(i + 2);
            }
            scene.AddTriangles(p, idx);
        }
    }
    return scene;
}

// Rays start inside the scene's box (and so inside many nodes' boxes) or
// outside it; some are parallel to coordinate planes, some have a finite
// tMax. With `fromInsideShapes`, a quarter of them start near the middle of
// a random primitive's box, inside the shape if it is a sphere, a cylinder,
// a cone or a paraboloid whose cuts leave it closed enough, where the far
// root of a quadric decides.
inline Ray RandomRay(std::mt19937_64 &rng, const Bounds3f &b,
              const std::vector<std::shared_ptr<Primitive>> *prims = nullptr,
              bool fromInsideShapes = false) {
    Vector3f diag = b.Diagonal();
    double r = 0.5 * std::max(diag.x, std::max(diag.y, diag.z)) + 1;
    Point3f c = b.pMin * Float(0.5) + b.pMax * Float(0.5);
    Point3f o = rng() % 2 ? RandomPoint(rng, c, r * 0.8)
                          : RandomPoint(rng, c, r * 2);
    if (fromInsideShapes && prims && !prims->empty() && rng() % 4 == 0) {
        // Not from a box that is flat on some axis: its middle lies in the
        // plane of the flat triangles or disk inside it, and the distances
        // to them are rounding error.
        Bounds3f pb = (*prims)[rng() % prims->size()]->WorldBound();
        Vector3f extent = pb.Diagonal();
        if (IsFiniteBox(pb) && extent.x > 0 && extent.y > 0 && extent.z > 0) {
            Float f[3];
            for (Float &x : f) x = Float(U(rng, 0.3, 0.7));
            o = Point3f(Lerp(f[0], pb.pMin.x, pb.pMax.x),
                        Lerp(f[1], pb.pMin.y, pb.pMax.y),
                        Lerp(f[2], pb.pMin.z, pb.pMax.z));
        }
    }
    Vector3f d;
    if (prims && !prims->empty() && rng() % 4 != 0) {
        // Aim at a point in a random primitive's box: many such rays hit.
        Bounds3f pb = (*prims)[rng() % prims->size()]->WorldBound();
        Point3f target(Float(U(rng, pb.pMin.x, pb.pMax.x)),
                       Float(U(rng, pb.pMin.y, pb.pMax.y)),
                       Float(U(rng, pb.pMin.z, pb.pMax.z)));
        d = target - o;
        if (d.LengthSquared() == 0) d = Vector3f(1, 0, 0);
        d = Normalize(d);
    } else if (rng() % 2) {
        d = Normalize(RandomPoint(rng, c, r * 0.7) - o);
    } else {
        d = RandomDirection(rng);
    }
    if (rng() % 8 == 0) {
        int axis = int(rng() % 3);
        d[axis] = rng() % 2 ? Float(0) : -Float(0);
        if (d.LengthSquared() == 0) d[(axis + 1) % 3] = 1;
        d = Normalize(d);
    }
    Float tMax = Infinity;
    if (rng() % 2) tMax = Float(U(rng, 0, 3 * r));
    return Ray(o, d, tMax);
}

struct OracleHit {
    const Primitive *prim;
    Float t;
};

struct Oracle {
    std::vector<OracleHit> hits;  // every primitive hit, at its distance
    bool anyP = false;            // some primitive's IntersectP is true
    Float tMin = Infinity;
};

inline Oracle BruteForce(const std::vector<std::shared_ptr<Primitive>> &prims,
                  const Ray &ray) {
    Oracle o;
    for (const auto &p : prims) {
        if (!IsFiniteBox(p->WorldBound())) continue;
        Ray r(ray.o, ray.d, ray.tMax, ray.time);
        SurfaceInteraction si;
        if (p->Intersect(r, &si)) {
            o.hits.push_back({p.get(), r.tMax});
            o.tMin = std::min(o.tMin, r.tMax);
        }
        if (p->IntersectP(ray)) o.anyP = true;
    }
    return o;
}

// A primitive hit at the closest distance.
inline const Primitive *ClosestPrimitive(const Oracle &o) {
    for (const OracleHit &h : o.hits)
        if (h.t == o.tMin) return h.prim;
    return nullptr;
}

// The name of the shape of a primitive (a GeometricPrimitive's), for the
// counts of hits per shape.
inline std::string ShapeName(const Primitive *p) {
    auto gp = dynamic_cast<const GeometricPrimitive *>(p);
    const Shape *s = gp ? gp->GetShape() : nullptr;
    if (!s) return "other";
    if (dynamic_cast<const Sphere *>(s)) return "Sphere";
    if (dynamic_cast<const Disk *>(s)) return "Disk";
    if (dynamic_cast<const Triangle *>(s)) return "Triangle";
    if (dynamic_cast<const Cylinder *>(s)) return "Cylinder";
    if (dynamic_cast<const Cone *>(s)) return "Cone";
    if (dynamic_cast<const Paraboloid *>(s)) return "Paraboloid";
    if (dynamic_cast<const Hyperboloid *>(s)) return "Hyperboloid";
    return "other";
}

// Returns an empty string if the accelerator agrees with the oracle. The
// primitive reported must report the same distance to brute force. That
// distance must be the closest, within kTieTolerance, or, if `exact`, the
// closest exactly: a primitive hit nearer than the reported hit, even by
// the last bit, must have been found (a shape accepts a hit nearer than
// tMax, so the order in which an accelerator tests them cannot matter).
inline std::string Compare(const Primitive &accel, const Ray &ray0,
                    const Oracle &o, bool exact = false) {
    std::ostringstream err;
    Ray ray = ray0;
    SurfaceInteraction si;
    bool hit = accel.Intersect(ray, &si);
    if (hit != !o.hits.empty()) {
        err << "Intersect() says " << hit << ", brute force found "
            << o.hits.size() << " hits";
        return err.str();
    }
    if (hit) {
        const OracleHit *h = nullptr;
        for (const OracleHit &oh : o.hits)
            if (oh.prim == si.primitive) h = &oh;
        if (!h)
            err << "reported primitive is not one that the ray hits";
        else if (h->t != ray.tMax)
            err << "t = " << ray.tMax << " but the primitive reports "
                << h->t;
        else if (exact ? ray.tMax != o.tMin
                       : ray.tMax > o.tMin * (1 + kTieTolerance))
            err << "t = " << ray.tMax << " on a " << ShapeName(h->prim)
                << " but the closest hit is at " << o.tMin << " on a "
                << ShapeName(ClosestPrimitive(o));
    } else if (!(ray.tMax == ray0.tMax) &&
               !(std::isnan(ray.tMax) && std::isnan(ray0.tMax))) {
        err << "a miss changed tMax";
    }
    if (accel.IntersectP(ray0) != o.anyP)
        err << " IntersectP() says " << !o.anyP << ", brute force "
            << o.anyP;
    return err.str();
}

inline std::multiset<const Primitive *> ValidPrimitives(
    const std::vector<std::shared_ptr<Primitive>> &input) {
    std::multiset<const Primitive *> s;
    for (const auto &p : input)
        if (IsFiniteBox(p->WorldBound())) s.insert(p.get());
    return s;
}

inline const Triangle *AsTriangle(const Primitive *p) {
    auto gp = dynamic_cast<const GeometricPrimitive *>(p);
    return gp ? dynamic_cast<const Triangle *>(gp->GetShape()) : nullptr;
}

// Structure of a BVHAccel (lrt::BVHAccel or the worker's ex::BVHAccel):
// depth-first layout, boxes equal to the union of what is below them, leaf
// sizes within the limit, every valid primitive in exactly one leaf, node
// counts consistent with Stats().
template <typename BVH>
void CheckStructure(const BVH &bvh,
                    const std::vector<std::shared_ptr<Primitive>> &input) {
    const std::vector<LinearBVHNode> &nodes = bvh.Nodes();
    const auto &prims = bvh.Primitives();
    std::multiset<const Primitive *> got;
    for (const auto &p : prims) got.insert(p.get());
    ASSERT_EQ(got, ValidPrimitives(input));
    BVHStats s = bvh.Stats();
    if (nodes.empty()) {
        EXPECT_TRUE(prims.empty());
        EXPECT_EQ(s.TotalNodes(), 0);
        EXPECT_TRUE(bvh.WorldBound().IsEmpty());
        return;
    }
    std::vector<int> visited(nodes.size(), 0), covered(prims.size(), 0);
    int maxDepth = 0, leaves = 0;
    std::function<Bounds3f(int, int)> visit = [&](int i,
                                                  int depth) -> Bounds3f {
        maxDepth = std::max(maxDepth, depth);
        visited[i]++;
        const LinearBVHNode &n = nodes[i];
        Bounds3f b;
        if (n.nPrimitives > 0) {
            ++leaves;
            EXPECT_LE(n.nPrimitives, bvh.MaxPrimsInNode());
            EXPECT_GE(n.primitivesOffset, 0);
            EXPECT_LE(n.primitivesOffset + n.nPrimitives, int(prims.size()));
            for (int k = std::max(n.primitivesOffset, 0);
                 k < n.primitivesOffset + n.nPrimitives &&
                 k < int(prims.size());
                 ++k) {
                covered[k]++;
                b = Union(b, prims[k]->WorldBound());
            }
        } else {
            EXPECT_LT(n.axis, 3);
            if (i + 1 >= int(nodes.size()) || n.secondChildOffset <= i + 1 ||
                n.secondChildOffset >= int(nodes.size()) ||
                depth >= maxBVHDepth) {
                ADD_FAILURE() << "bad child offsets at node " << i;
                return n.bounds;
            }
            b = Union(visit(i + 1, depth + 1),
                      visit(n.secondChildOffset, depth + 1));
        }
        EXPECT_EQ(n.bounds, b) << "node " << i;
        return n.bounds;
    };
    EXPECT_EQ(visit(0, 0), bvh.WorldBound());
    for (size_t i = 0; i < visited.size(); ++i)
        ASSERT_EQ(visited[i], 1) << "node " << i;
    for (size_t i = 0; i < covered.size(); ++i)
        ASSERT_EQ(covered[i], 1) << "primitive " << i;
    EXPECT_LE(maxDepth, maxBVHDepth);
    EXPECT_EQ(s.TotalNodes(), int64_t(nodes.size()));
    EXPECT_EQ(s.leafNodes, leaves);
    EXPECT_EQ(2 * s.leafNodes - 1, s.TotalNodes());
    EXPECT_EQ(s.primitives, int64_t(prims.size()));
    EXPECT_EQ(s.maxDepth, maxDepth);
    EXPECT_GE(s.sahCost, 1);
}

inline std::shared_ptr<Primitive> UnitSphereAt(Scene &scene, const Point3f &c,
                                        Float r = 1) {
    scene.AddSphere(Translate(Vector3f(c)), Translate(-Vector3f(c)), false, r,
                    -r, r, 360.f);
    return scene.prims.back();
}

// An accelerator under test, with a name for its failures.
struct Accel {
    std::string name;
    std::unique_ptr<Primitive> accel;
};
using Prims = std::vector<std::shared_ptr<Primitive>>;
using AccelSet = std::function<std::vector<Accel>(const Scene &, int)>;

inline std::string Label(const std::string &kind, SplitMethod m, int leafSize) {
    return kind + " " + MethodName(m) + "(" + std::to_string(leafSize) + ")";
}

// Builds the set's accelerators over random scenes with several leaf sizes
// and compares each with brute force on random rays. The seed is fixed, also
// when graded: on a few rays of some random scenes of spheres, brute force
// and every accelerator disagree on the closest hit (a sphere's error bound
// rejects its nearer hit once tMax has shrunk to a farther one's, a defect
// of Sphere::Intersect() whatever the code under test), and these seeds'
// scenes have none. With Shapes::All, the scenes hold every shape, a quarter of
// the rays start inside shapes, the closest distance must be found exactly,
// and each shape must be the closest hit of many rays.
inline void RunRandomScenes(const AccelSet &set, uint64_t seed, int nScenes,
                            Shapes shapes = Shapes::SpheresDisksTriangles) {
    std::mt19937_64 rng(seed);
    int failures = 0;
    int64_t rays = 0, hits = 0;
    std::map<std::string, int64_t> closest;  // rays whose closest hit is of
                                             // the shape
    const bool all = shapes == Shapes::All;
    for (int sceneIndex = 0; sceneIndex < nScenes; ++sceneIndex) {
        Scene scene = RandomScene(rng, shapes);
        std::vector<Accel> accels;
        for (int leafSize : kLeafSizes)
            for (Accel &a : set(scene, leafSize))
                accels.push_back(std::move(a));
        if (::testing::Test::HasFatalFailure()) return;
        for (int r = 0; r < kRaysPerScene; ++r) {
            Ray ray = RandomRay(rng, scene.bounds, &scene.prims, all);
            Oracle o = BruteForce(scene.prims, ray);
            ++rays;
            hits += !o.hits.empty();
            if (!o.hits.empty()) ++closest[ShapeName(ClosestPrimitive(o))];
            for (const Accel &a : accels) {
                std::string e = Compare(*a.accel, ray, o, all);
                if (!e.empty() && failures++ < kMaxFailuresReported)
                    ADD_FAILURE() << a.name << ", scene " << sceneIndex
                                  << " (" << scene.prims.size()
                                  << " primitives), ray " << ray << ": " << e;
            }
        }
    }
    EXPECT_EQ(failures, 0);
    // The rays must actually exercise hits, and misses.
    EXPECT_GT(hits, rays / 5);
    EXPECT_LT(hits, rays * 9 / 10);
    if (!all) return;
    std::ostringstream counts;
    for (const auto &[name, n] : closest) counts << " " << name << " " << n;
    ::testing::Test::RecordProperty("closest_hits_per_shape", counts.str());
    ::testing::Test::RecordProperty("rays", std::to_string(rays));
    ::testing::Test::RecordProperty("hits", std::to_string(hits));
    for (const char *name : {"Sphere", "Disk", "Triangle", "Cylinder", "Cone",
                             "Paraboloid", "Hyperboloid"})
        EXPECT_GT(closest[name], rays / 50)
            << name << " is the closest hit of too few of " << rays
            << " rays:" << counts.str();
}

// The degenerate scenes, each checked with the accelerators of a set.

inline void CheckOnePrimitive(const AccelSet &set) {
    Scene scene;
    UnitSphereAt(scene, Point3f(1, 2, 3), 0.5f);
    std::mt19937_64 rng(calls::Seed(611));
    const int rays = calls::Cases(2000, 400);
    for (int leafSize : {1, 4}) {
        std::vector<Accel> accels = set(scene, leafSize);
        for (int i = 0; i < rays; ++i) {
            Ray ray = RandomRay(rng, scene.bounds, &scene.prims);
            Oracle o = BruteForce(scene.prims, ray);
            for (const Accel &a : accels)
                EXPECT_EQ(Compare(*a.accel, ray, o), "") << a.name;
        }
    }
}

// Many primitives with the same centroid: pbrt would make one leaf of all
// of them; ours keeps leaves within the limit, and 70,000 copies of one
// triangle (more than a 16-bit count holds) must work. (Graded, where the
// leaf limit, which is not an exercise's code, is not what is checked, and
// the worker's code is not optimized, 7,000 copies.)
inline void CheckAllCentroidsEqual(const AccelSet &set) {
    Scene scene;
    std::vector<Point3f> p = {Point3f(-1, -1, 0), Point3f(1, -1, 0),
                              Point3f(0, 2, 0)};
    std::vector<int> idx;
    const int copies = calls::Cases(70000, 7000);
    for (int i = 0; i < copies; ++i) idx.insert(idx.end(), {0, 1, 2});
    scene.AddTriangles(p, idx);
    for (int i = 0; i < 50; ++i)  // concentric spheres: equal centroids
        UnitSphereAt(scene, Point3f(0, 0, 0), 3 + Float(i) / 10);
    for (int leafSize : {1, 4}) {
        for (const Accel &acc : set(scene, leafSize)) {
            SCOPED_TRACE(acc.name);
            const Primitive *a = acc.accel.get();
            // From inside all the spheres, down onto the triangle.
            Ray ray(Point3f(0.1f, 0.2f, 1), Vector3f(0, 0, -1));
            SurfaceInteraction si;
            ASSERT_TRUE(a->Intersect(ray, &si));
            EXPECT_EQ(ray.tMax, 1);
            EXPECT_NE(AsTriangle(si.primitive), nullptr);
            // From outside: the largest sphere comes first.
            Ray out(Point3f(0, 0, 20), Vector3f(0, 0, -1));
            ASSERT_TRUE(a->Intersect(out, &si));
            EXPECT_NEAR(out.tMax, 20 - 7.9f, 1e-4f);
            EXPECT_TRUE(a->IntersectP(Ray(Point3f(0.1f, 0.2f, 1),
                                          Vector3f(0, 0, -1), 1.5f)));
            EXPECT_FALSE(a->IntersectP(Ray(Point3f(0.1f, 0.2f, 1),
                                           Vector3f(0, 0, -1), 0.5f)));
        }
    }
}

// Boxes of zero extent in one or more dimensions: flat triangles and disks
// in coordinate planes, rays lying in those planes, and triangles that
// collapse to a point (which no ray can hit).
inline void CheckZeroExtentBoxes(const AccelSet &set) {
    Scene scene;
    std::vector<Point3f> p;
    std::vector<int> idx;
    for (int i = 0; i < 40; ++i) {
        Float x = Float(i % 8), y = Float(i / 8);
        p.insert(p.end(), {Point3f(x, y, 0), Point3f(x + 1, y, 0),
                           Point3f(x, y + 1, 0)});
        idx.insert(idx.end(), {3 * i, 3 * i + 1, 3 * i + 2});
    }
    for (int i = 0; i < 10; ++i) {  // points
        int base = int(p.size());
        Point3f q(Float(i), 3.5f, 2);
        p.insert(p.end(), {q, q, q});
        idx.insert(idx.end(), {base, base + 1, base + 2});
    }
    scene.AddTriangles(p, idx);
    for (int i = 0; i < 10; ++i)
        scene.AddDisk(Translate(Vector3f(Float(i), 7, 0)),
                      Translate(Vector3f(-Float(i), -7, 0)), false, 1.f, 0.4f,
                      0.f, 360.f);
    std::mt19937_64 rng(calls::Seed(612));
    const int rays = calls::Cases(3000, 600);
    int failures = 0;
    for (int leafSize : {1, 3, 16}) {
        std::vector<Accel> accels = set(scene, leafSize);
        for (int i = 0; i < rays; ++i) {
            Ray ray = RandomRay(rng, scene.bounds, &scene.prims);
            if (i % 3 == 0) {  // in the plane z = 0 or z = 1
                ray.o.z = Float(i % 2);
                ray.d.z = i % 6 == 0 ? Float(0) : -Float(0);
                if (ray.d.LengthSquared() == 0) ray.d.x = 1;
            }
            Oracle o = BruteForce(scene.prims, ray);
            for (const Accel &a : accels) {
                std::string e = Compare(*a.accel, ray, o);
                if (!e.empty() && failures++ < kMaxFailuresReported)
                    ADD_FAILURE() << a.name << " " << ray << ": " << e;
            }
        }
        // Straight down onto each flat triangle and disk.
        for (const Accel &acc : accels) {
            SCOPED_TRACE(acc.name);
            Ray down(Point3f(3.25f, 2.25f, 5), Vector3f(0, 0, -1));
            SurfaceInteraction si;
            ASSERT_TRUE(acc.accel->Intersect(down, &si));
            EXPECT_EQ(down.tMax, 5);
            Ray disk(Point3f(4.1f, 7.1f, 5), Vector3f(0, 0, -1));
            ASSERT_TRUE(acc.accel->Intersect(disk, &si));
            EXPECT_NEAR(disk.tMax, 4, 1e-5f);
        }
    }
}

// A primitive that reports a NaN, infinite or empty box (an empty
// aggregate, for one) is left out of the tree and never hit; a finite box at
// the limits of the range is kept, and its centroid must not overflow.
inline void CheckNaNAndInfiniteBounds(const AccelSet &set) {
    Scene prims;
    UnitSphereAt(prims, Point3f(0, 0, 5));
    UnitSphereAt(prims, Point3f(3, 0, 5));
    const Float nan = std::numeric_limits<Float>::quiet_NaN();
    Bounds3f nanBox(Point3f(0, 0, 0), Point3f(1, 1, 1));
    nanBox.pMax.y = nan;
    Bounds3f infBox(Point3f(0, 0, 0), Point3f(Infinity, 1, 1));
    Bounds3f hugeBox(Point3f(-MaxFloat, -MaxFloat, -MaxFloat),
                     Point3f(MaxFloat, MaxFloat, MaxFloat));
    prims.AddOddBounds(nanBox);
    prims.AddOddBounds(infBox);
    prims.AddOddBounds(Bounds3f());
    prims.AddEmptyAggregate();
    Scene withHuge = prims;
    withHuge.AddOddBounds(hugeBox);
    std::shared_ptr<Primitive> huge = withHuge.prims.back();
    for (int leafSize : {1, 4}) {
        for (const Accel &acc : set(prims, leafSize)) {
            SCOPED_TRACE(acc.name);
            Ray ray(Point3f(0, 0, 0), Vector3f(0, 0, 1));
            SurfaceInteraction si;
            ASSERT_TRUE(acc.accel->Intersect(ray, &si));
            EXPECT_NEAR(ray.tMax, 4, 1e-5f);  // the sphere, not t = 1
            EXPECT_FALSE(acc.accel->IntersectP(
                Ray(Point3f(0, 0, 0), Vector3f(0, 0, 1), 2)));
        }
        for (const Accel &acc : set(withHuge, leafSize)) {
            SCOPED_TRACE(acc.name);
            Ray ray(Point3f(0, 0, 0), Vector3f(0, 0, 1));
            SurfaceInteraction si;
            ASSERT_TRUE(acc.accel->Intersect(ray, &si));
            EXPECT_EQ(ray.tMax, 1);
            EXPECT_EQ(si.primitive, huge.get());
        }
    }
}

// Centroids at 1, 1/2, 1/4, ...: Middle and the SAH split off one
// primitive per level, which would make a chain far deeper than the
// traversal stack. The depth bound keeps every tree within it (which
// CheckStructure() checks).
inline void CheckExponentiallySpacedCentroids(const AccelSet &set) {
    Scene scene;
    std::vector<Point3f> p;
    std::vector<int> idx;
    int n = sizeof(Float) == 4 ? 140 : 1000;
    for (int i = 0; i < n; ++i) {
        Float x = std::ldexp(Float(1), -i);
        Float h = x / 4;
        int base = int(p.size());
        p.insert(p.end(), {Point3f(x - h, -1, 0), Point3f(x + h, -1, 0),
                           Point3f(x, 1, 0)});
        idx.insert(idx.end(), {base, base + 1, base + 2});
    }
    scene.AddTriangles(p, idx);
    std::mt19937_64 rng(calls::Seed(613));
    const int rays = calls::Cases(2000, 400);
    int failures = 0;
    for (int leafSize : {1, 2}) {
        std::vector<Accel> accels = set(scene, leafSize);
        for (int i = 0; i < rays; ++i) {
            Ray ray(Point3f(std::ldexp(Float(1), -int(rng() % n)) *
                                Float(U(rng, 0.8, 1.2)),
                            Float(U(rng, -1, 1)), 1),
                    Vector3f(0, 0, -1));
            Oracle o = BruteForce(scene.prims, ray);
            for (const Accel &a : accels) {
                std::string e = Compare(*a.accel, ray, o);
                if (!e.empty() && failures++ < kMaxFailuresReported)
                    ADD_FAILURE() << a.name << " " << ray << ": " << e;
            }
        }
    }
}

// Random boxes for the tests of the SAH and HLBVH trees: in a cube, in
// clusters, on a plane (boxes flat in z), on a line (segments along x, of
// zero area), many copies of a few, or large boxes around nearly the same

// The degenerate scenes above that take a set, each with the set's
// accelerators.
inline void CheckDegenerateScenes(const AccelSet &set) {
    CheckAllCentroidsEqual(set);
    CheckZeroExtentBoxes(set);
    CheckNaNAndInfiniteBounds(set);
    CheckExponentiallySpacedCentroids(set);
}

// A closed mesh, a subdivided octahedron (ClosedMesh() of bvh_checks.h).
inline Scene ClosedMeshScene(int levels) {
    std::vector<Point3f> p;
    std::vector<int> idx;
    ClosedMesh(levels, &p, &idx);
    Scene scene;
    scene.AddTriangles(p, idx);
    return scene;
}

// Two accelerators over a closed mesh around the origin agree bit for bit
// on rays aimed near the origin and rays in every direction: the same hits,
// at the same distances, and IntersectP() agrees with Intersect().
inline void ExpectSameHitsOnAClosedMesh(const Primitive &a, const Primitive &b,
                                        std::mt19937_64 &rng, int rays) {
    int hits = 0;
    for (int i = 0; i < rays; ++i) {
        Point3f o = RandomPoint(rng, Point3f(0, 0, 0), 3);
        Ray ray(o, RandomPoint(rng, Point3f(0, 0, 0), 0.5) - o);
        if (i % 3 == 0) ray.d = RandomDirection(rng);
        Ray r1 = ray, r2 = ray;
        SurfaceInteraction s1, s2;
        bool h1 = a.Intersect(r1, &s1), h2 = b.Intersect(r2, &s2);
        ASSERT_EQ(h1, h2) << ray;
        EXPECT_EQ(a.IntersectP(ray), h1);
        EXPECT_EQ(b.IntersectP(ray), h2);
        if (h1) {
            ++hits;
            EXPECT_EQ(r1.tMax, r2.tMax) << ray;
        }
    }
    // Rays aimed near the origin hit, unless they start inside.
    EXPECT_GT(hits, rays / 2);
}

}  // namespace lrt_test
