// Chapter 3's exercise calls (tests/calls/calls.h): the tests of ex-3.22
// (OffsetRayOrigin(), and the Interaction methods that spawn rays with it),
// ex-3.23 (Triangle::Intersect() and IntersectP(), whose ray coordinate
// system the exercise builds), ex-3.24 (ReadPly(), whose header parser the
// exercise writes) and ex-3.25 (the quadrics' Intersect() and IntersectP(),
// whose quadratic the exercise sets up) reach that code only through these.
//
// Calls take values: a triangle mesh travels as its vertex data (MeshSpec)
// and is built where the call runs; a PLY file travels as its bytes and is
// written to a file of its own in the temporary directory, since the code
// under test may run where the tests' files are not.

#ifndef LRT_TESTS_CH03_EXERCISE_CALLS_H
#define LRT_TESTS_CH03_EXERCISE_CALLS_H

#include "lrt/shapes/sphere.h"
#include "lrt/shapes/disk.h"
#include "lrt/shapes/triangle.h"
#include "lrt/shapes/plyreader.h"
#include "lrt/shapes/cylinder.h"
#include "lrt/shapes/cone.h"
#include "lrt/shapes/paraboloid.h"
#include "lrt/shapes/hyperboloid.h"
#include "calls/calls.h"
#include "calls/memory_files.h"

#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace lrt {

// ---------------------------------------------------------------------------
// ex-3.22: spawning rays

// The parts of an Interaction that its SpawnRay*() methods use.
struct SpawnPoint {
    Point3f p;
    Vector3f pError;
    Normal3f n;
    Float time = 0;
    LRT_FIELDS(p, pError, n, time)
};

// ---------------------------------------------------------------------------
// ex-3.23: triangles

// The arguments of CreateTriangleMesh(), as values: WorldToObject is the
// inverse of objectToWorld; empty vectors stand for absent data.
struct MeshSpec {
    std::vector<Point3f> p;
    std::vector<int> indices;
    Transform objectToWorld;
    bool reverseOrientation = false;
    std::vector<Normal3f> n;
    std::vector<Vector3f> s;
    std::vector<Point2f> uv;
    std::vector<int> faceIndices;
    LRT_FIELDS(p, indices, objectToWorld, reverseOrientation, n, s, uv,
               faceIndices)
};

// The parts of a SurfaceInteraction that the tests check. The shape is
// given by its triangle's number in the mesh (-1: some other pointer).
struct SurfaceHit {
    Point3f p;
    Vector3f pError, wo;
    Point2f uv;
    Float time = 0;
    Normal3f n;
    Vector3f dpdu, dpdv;
    Normal3f dndu, dndv;
    Normal3f shadingN;
    Vector3f shadingDpdu, shadingDpdv;
    Normal3f shadingDndu, shadingDndv;
    int faceIndex = 0;
    int shapeIndex = -1;
    LRT_FIELDS(p, pError, wo, uv, time, n, dpdu, dpdv, dndu, dndv, shadingN,
               shadingDpdu, shadingDpdv, shadingDndu, shadingDndv, faceIndex,
               shapeIndex)
};

// Calls f(h.part, si.part) for each part of a SurfaceInteraction si that a
// SurfaceHit h holds (all but the shape), to copy them either way.
template <typename Hit, typename Interaction, typename F>
void ForEachPart(Hit &h, Interaction &si, F f) {
    f(h.p, si.p);
    f(h.pError, si.pError);
    f(h.wo, si.wo);
    f(h.uv, si.uv);
    f(h.time, si.time);
    f(h.n, si.n);
    f(h.dpdu, si.dpdu);
    f(h.dpdv, si.dpdv);
    f(h.dndu, si.dndu);
    f(h.dndv, si.dndv);
    f(h.shadingN, si.shading.n);
    f(h.shadingDpdu, si.shading.dpdu);
    f(h.shadingDpdv, si.shading.dpdv);
    f(h.shadingDndu, si.shading.dndu);
    f(h.shadingDndv, si.shading.dndv);
    f(h.faceIndex, si.faceIndex);
}

// One ray against one triangle: Intersect() (with the tHit it was given,
// which a miss must leave alone) and IntersectP().
struct TriangleHit {
    bool hit = false, hitP = false;
    Float tHit = 0;
    SurfaceHit isect;
    LRT_FIELDS(hit, hitP, tHit, isect)
};

// Whether Intersect() and IntersectP() report a hit.
struct TriangleVerdict {
    bool hit = false, hitP = false;
    LRT_FIELDS(hit, hitP)
};

// The nearest hit of a ray among all the triangles of a mesh (Intersect()):
// the triangle's number, or -1 if none is hit.
struct MeshHit {
    int triangle = -1;
    Float tHit = 0;
    SurfaceHit isect;
    LRT_FIELDS(triangle, tHit, isect)
};

// ---------------------------------------------------------------------------
// ex-3.24: PLY files

// A PlyMesh's data.
struct PlyValues {
    std::vector<Point3f> p;
    std::vector<Normal3f> n;
    std::vector<Point2f> uv;
    std::vector<int> vertexIndices;
    LRT_FIELDS(p, n, uv, vertexIndices)
};

// The triangles that CreatePLYMesh() makes of a file, as their world bounds,
// and the nearest hit of a ray among them.
struct PlyShapes {
    std::vector<Bounds3f> worldBounds;
    MeshHit nearest;
    LRT_FIELDS(worldBounds, nearest)
};

// ---------------------------------------------------------------------------
// ex-3.25: the quadrics

// A cylinder, cone, paraboloid or hyperboloid, as the arguments of its
// constructor (WorldToObject is the inverse of objectToWorld). The
// paraboloid's z0 and z1 are zMin and zMax.
enum QuadricKind { kCylinder, kCone, kParaboloid, kHyperboloid };
struct QuadricSpec {
    int kind = kCylinder;
    Float radius = 1, zMin = -1, zMax = 1, height = 1, phiMax = 360;
    Point3f p1, p2;
    Transform objectToWorld;
    bool reverseOrientation = false;
    LRT_FIELDS(kind, radius, zMin, zMax, height, phiMax, p1, p2,
               objectToWorld, reverseOrientation)
};

// One ray against one shape: Intersect() (with the tHit it was given, which
// a miss must leave alone) and IntersectP(). isect.shapeIndex is 0 if the
// interaction names the shape.
struct ShapeHit {
    bool hit = false, hitP = false;
    Float tHit = 0;
    SurfaceHit isect;
    LRT_FIELDS(hit, hitP, tHit, isect)
};

namespace direct {

// Helpers of the calls below; they are not calls themselves.
namespace detail {

// An interaction at the point, for its SpawnRay*() methods.
inline Interaction At(const SpawnPoint &p) {
    return Interaction(p.p, p.n, p.pError, Vector3f(0, 0, 0), p.time);
}

inline SurfaceHit Values(const SurfaceInteraction &si,
                         const std::vector<std::shared_ptr<Shape>> &shapes) {
    SurfaceHit h;
    ForEachPart(h, si, [](auto &part, const auto &from) { part = from; });
    for (size_t k = 0; k < shapes.size(); ++k)
        if (si.shape == shapes[k].get()) h.shapeIndex = int(k);
    return h;
}

// A mesh's triangles with the transformations they point to.
struct BuiltMesh {
    explicit BuiltMesh(const MeshSpec &m)
        : objectToWorld(m.objectToWorld),
          worldToObject(Inverse(m.objectToWorld)) {
        auto data = [](const auto &v) {
            return v.empty() ? nullptr : v.data();
        };
        triangles = CreateTriangleMesh(
            &objectToWorld, &worldToObject, m.reverseOrientation,
            int(m.indices.size() / 3), data(m.indices), int(m.p.size()),
            data(m.p), data(m.s), data(m.n), data(m.uv), data(m.faceIndices));
    }
    BuiltMesh(const BuiltMesh &) = delete;
    BuiltMesh &operator=(const BuiltMesh &) = delete;
    const Transform objectToWorld, worldToObject;
    std::vector<std::shared_ptr<Shape>> triangles;
};

inline const Shape &TriangleOf(const BuiltMesh &m, int k) {
    if (k < 0 || size_t(k) >= m.triangles.size())
        throw std::out_of_range("the mesh has no triangle " +
                                std::to_string(k));
    return *m.triangles[size_t(k)];
}

inline TriangleHit Hit(const BuiltMesh &m, int k, const Ray &ray, Float tHit) {
    TriangleHit h;
    SurfaceInteraction si;
    h.tHit = tHit;
    h.hit = TriangleOf(m, k).Intersect(ray, &h.tHit, &si);
    h.hitP = TriangleOf(m, k).IntersectP(ray);
    if (h.hit) h.isect = Values(si, m.triangles);
    return h;
}

inline MeshHit Nearest(const std::vector<std::shared_ptr<Shape>> &shapes,
                       const Ray &ray) {
    MeshHit best;
    for (size_t k = 0; k < shapes.size(); ++k) {
        Float t;
        SurfaceInteraction si;
        if (shapes[k]->Intersect(ray, &t, &si) &&
            (best.triangle < 0 || t < best.tHit)) {
            best.triangle = int(k);
            best.tHit = t;
            best.isect = Values(si, shapes);
        }
    }
    return best;
}

// The quadric that a spec describes, with the transformations it points to.
struct BuiltQuadric {
    explicit BuiltQuadric(const QuadricSpec &q)
        : objectToWorld(q.objectToWorld),
          worldToObject(Inverse(q.objectToWorld)) {
        const Transform *o2w = &objectToWorld, *w2o = &worldToObject;
        bool ro = q.reverseOrientation;
        switch (q.kind) {
        case kCylinder:
            shape = std::make_shared<Cylinder>(o2w, w2o, ro, q.radius, q.zMin,
                                               q.zMax, q.phiMax);
            break;
        case kCone:
            shape = std::make_shared<Cone>(o2w, w2o, ro, q.height, q.radius,
                                           q.phiMax);
            break;
        case kParaboloid:
            shape = std::make_shared<Paraboloid>(o2w, w2o, ro, q.radius,
                                                 q.zMin, q.zMax, q.phiMax);
            break;
        case kHyperboloid:
            shape = std::make_shared<Hyperboloid>(o2w, w2o, ro, q.p1, q.p2,
                                                  q.phiMax);
            break;
        default:
            throw std::invalid_argument("no quadric of kind " +
                                        std::to_string(q.kind));
        }
    }
    BuiltQuadric(const BuiltQuadric &) = delete;
    BuiltQuadric &operator=(const BuiltQuadric &) = delete;
    const Transform objectToWorld, worldToObject;
    std::shared_ptr<Shape> shape;
};

// Writes `bytes` to a file called `name` in a new directory of the
// temporary directory, passes its path to `use`, and removes both. In the
// worker, which may open no file, the file is one in memory
// (calls::MemoryFiles()) that fopen() finds by its path.
template <typename F>
auto WithFile(const std::string &name, const std::string &bytes, F &&use) {
    if (name.empty() || name.find('/') != std::string::npos || name == "." ||
        name == "..")
        throw std::invalid_argument("not a plain file name: \"" + name + "\"");
#ifdef LRT_WORKER
    struct Forget {
        std::string path;
        ~Forget() { calls::MemoryFiles().erase(path); }
    } forget{"/lrt-ply-memory/" + name};
    calls::MemoryFiles()[forget.path] = bytes;
    return use(forget.path);
#else
    const char *tmp = std::getenv("TMPDIR");
    std::string pattern =
        std::string(tmp && *tmp ? tmp : "/tmp") + "/lrt-ply-XXXXXX";
    if (!mkdtemp(&pattern[0]))
        throw std::runtime_error("cannot make a directory in " + pattern);
    const std::string path = pattern + "/" + name;
    struct Remove {
        std::string dir, path;
        ~Remove() {
            std::remove(path.c_str());
            rmdir(dir.c_str());
        }
    } remove{pattern, path};
    std::FILE *f = std::fopen(path.c_str(), "wb");
    bool ok =
        f && std::fwrite(bytes.data(), 1, bytes.size(), f) == bytes.size();
    if (f && std::fclose(f) != 0) ok = false;
    if (!ok) throw std::runtime_error("cannot write " + path);
    return use(path);
#endif
}

}  // namespace detail

// ex-3.22 ------------------------------------------------------------------

inline Point3f OffsetRayOrigin(Point3f p, Vector3f pError, Normal3f n,
                               Vector3f w) {
    return ::lrt::OffsetRayOrigin(p, pError, n, w);
}

inline Ray SpawnRayFrom(SpawnPoint from, Vector3f d) {
    return detail::At(from).SpawnRay(d);
}

inline Ray SpawnRayToPoint(SpawnPoint from, Point3f to) {
    return detail::At(from).SpawnRayTo(to);
}

inline Ray SpawnRayBetween(SpawnPoint from, SpawnPoint to) {
    return detail::At(from).SpawnRayTo(detail::At(to));
}

// ex-3.23 ------------------------------------------------------------------

// Builds the mesh and keeps it for the calls below.
inline calls::Handle MakeMesh(MeshSpec m) {
    return calls::Keep(std::make_shared<detail::BuiltMesh>(m));
}

// Triangle k of a kept mesh against a ray.
inline TriangleHit IntersectTriangle(calls::Handle mesh, int k, Ray ray,
                                     Float tHit) {
    return detail::Hit(calls::Find<detail::BuiltMesh>(mesh), k, ray, tHit);
}

// The same for a mesh built for this one ray.
inline TriangleHit IntersectTriangleOf(MeshSpec m, int k, Ray ray, Float tHit) {
    return detail::Hit(detail::BuiltMesh(m), k, ray, tHit);
}

// Triangles `which` of a kept mesh against one ray.
inline std::vector<TriangleVerdict> IntersectTriangles(calls::Handle mesh,
                                                       std::vector<int> which,
                                                       Ray ray) {
    const detail::BuiltMesh &m = calls::Find<detail::BuiltMesh>(mesh);
    std::vector<TriangleVerdict> verdicts;
    for (int k : which) {
        TriangleHit h = detail::Hit(m, k, ray, 0);
        verdicts.push_back(TriangleVerdict{h.hit, h.hitP});
    }
    return verdicts;
}

// The nearest hit among all the triangles of a kept mesh.
inline MeshHit IntersectMesh(calls::Handle mesh, Ray ray) {
    return detail::Nearest(calls::Find<detail::BuiltMesh>(mesh).triangles, ray);
}

// Whether IntersectP() says that the ray hits some triangle of a kept mesh.
inline bool HitsMesh(calls::Handle mesh, Ray ray) {
    for (const auto &t : calls::Find<detail::BuiltMesh>(mesh).triangles)
        if (t->IntersectP(ray)) return true;
    return false;
}

// ex-3.24 ------------------------------------------------------------------

// ReadPly() of a file called `name` that holds `bytes`.
inline PlyValues ReadPlyFile(std::string name, std::string bytes) {
    return detail::WithFile(name, bytes, [](const std::string &path) {
        PlyMesh m = ReadPly(path);
        return PlyValues{m.p, m.n, m.uv, m.vertexIndices};
    });
}

// CreatePLYMesh() of such a file, and a ray shot at its triangles.
inline PlyShapes CreatePLYMeshFile(std::string name, std::string bytes,
                                   Transform objectToWorld,
                                   bool reverseOrientation, Ray ray) {
    return detail::WithFile(name, bytes, [&](const std::string &path) {
        const Transform worldToObject = Inverse(objectToWorld);
        auto shapes = CreatePLYMesh(&objectToWorld, &worldToObject,
                                    reverseOrientation, path);
        PlyShapes r;
        for (const auto &s : shapes) r.worldBounds.push_back(s->WorldBound());
        r.nearest = detail::Nearest(shapes, ray);
        return r;
    });
}

// ex-3.25 ------------------------------------------------------------------

// A quadric built for this one ray, against it.
inline ShapeHit IntersectQuadric(QuadricSpec q, Ray ray, Float tHit) {
    detail::BuiltQuadric b(q);
    ShapeHit h;
    SurfaceInteraction si;
    h.tHit = tHit;
    h.hit = b.shape->Intersect(ray, &h.tHit, &si);
    h.hitP = b.shape->IntersectP(ray);
    if (h.hit) h.isect = detail::Values(si, {b.shape});
    return h;
}

}  // namespace direct
}  // namespace lrt

LRT_EXERCISE_CALL(OffsetRayOrigin)
LRT_EXERCISE_CALL(SpawnRayFrom)
LRT_EXERCISE_CALL(SpawnRayToPoint)
LRT_EXERCISE_CALL(SpawnRayBetween)
LRT_EXERCISE_CALL(MakeMesh)
LRT_EXERCISE_CALL(IntersectTriangle)
LRT_EXERCISE_CALL(IntersectTriangleOf)
LRT_EXERCISE_CALL(IntersectTriangles)
LRT_EXERCISE_CALL(IntersectMesh)
LRT_EXERCISE_CALL(HitsMesh)
LRT_EXERCISE_CALL(ReadPlyFile)
LRT_EXERCISE_CALL(CreatePLYMeshFile)
LRT_EXERCISE_CALL(IntersectQuadric)

namespace lrt {
namespace ex {

// The library's signatures, for the tests.

inline SpawnPoint From(const Interaction &it) {
    return SpawnPoint{it.p, it.pError, it.n, it.time};
}
inline Ray SpawnRay(const Interaction &it, const Vector3f &d) {
    return SpawnRayFrom(From(it), d);
}
inline Ray SpawnRayTo(const Interaction &it, const Point3f &p2) {
    return SpawnRayToPoint(From(it), p2);
}
inline Ray SpawnRayTo(const Interaction &it, const Interaction &it2) {
    return SpawnRayBetween(From(it), From(it2));
}

// A SurfaceInteraction with the parts that a call returns (no shape).
inline SurfaceInteraction ToSurfaceInteraction(const SurfaceHit &h) {
    SurfaceInteraction si;
    ForEachPart(h, si, [](const auto &from, auto &part) { part = from; });
    return si;
}

// ReadPly() of a file called `name` that holds `bytes`.
inline PlyMesh ReadPly(const std::string &name, const std::string &bytes) {
    PlyValues v = ReadPlyFile(name, bytes);
    PlyMesh m;
    m.p = v.p;
    m.n = v.n;
    m.uv = v.uv;
    m.vertexIndices = v.vertexIndices;
    return m;
}

// The message of the std::runtime_error that it throws, or "" if none.
inline std::string ReadPlyError(const std::string &name,
                                const std::string &bytes) {
    try {
        ReadPlyFile(name, bytes);
    } catch (const std::runtime_error &e) {
        return e.what();
    }
    return "";
}

// The length of the start of such a message that names the file,
// `ReadPly: "DIRECTORY/name": `, or 0 if it does not start so. (The
// directory is a new one of the temporary directory each time.)
inline size_t PlyFilePrefix(const std::string &message,
                            const std::string &name) {
    const std::string start = "ReadPly: \"", end = "/" + name + "\": ";
    if (message.compare(0, start.size(), start) != 0) return 0;
    size_t at = message.find(end, start.size());
    if (at == std::string::npos ||
        message.find('"', start.size()) != at + end.size() - 3)
        return 0;
    return at + end.size();
}

}  // namespace ex
}  // namespace lrt

#endif  // LRT_TESTS_CH03_EXERCISE_CALLS_H
