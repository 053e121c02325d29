// The Stanford bunny of data/bunny.ply, subdivided once in code (4 x 3,674
// triangles), with camera and incoherent rays and brute force's closest hit
// of each, made once per test program; Check() traces the rays with an
// accelerator and compares. Shared by chapter 6's tests of BVHAccel and
// chapter 7's of FastBVHAccel (which include it as "ch06/bvh_bunny.h").

#pragma once

#include "remote_bvh.h"
#include "lrt/accelerators/bvh.h"
#include "lrt/shapes/plyreader.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <map>
#include <random>
#include <string>
#include <vector>

namespace lrt_test {

using namespace lrt;

// A 40 x 40 image and as many incoherent rays; graded, where every ray
// crosses to the worker, a 20 x 20 image and 400.
inline const int kCameraResolution = calls::Cases(40, 20);
inline const int kIncoherentRays = calls::Cases(1600, 400);
inline const Float kTieTolerance = 256 * std::numeric_limits<Float>::epsilon();

// The tests run from the repository root; LRT_DATA_DIR overrides.
inline std::string FindBunny() {
    std::vector<std::string> dirs;
    if (const char *env = std::getenv("LRT_DATA_DIR")) dirs.push_back(env);
    for (std::string up = ""; up.size() < 16; up += "../")
        dirs.push_back(up + "data");
    for (const std::string &d : dirs) {
        std::ifstream f(d + "/bunny.ply");
        if (f) return d + "/bunny.ply";
    }
    return "";
}

// One round of 1-to-4 midpoint subdivision with shared edge midpoints, as
// the benchmark's data generator does it.
inline void Subdivide(PlyMesh *m) {
    std::map<std::pair<int, int>, int> mid;
    auto midpoint = [&](int a, int b) {
        auto key = std::make_pair(std::min(a, b), std::max(a, b));
        auto it = mid.find(key);
        if (it != mid.end()) return it->second;
        const Point3f &p = m->p[a], &q = m->p[b];
        m->p.push_back(Point3f(Float(0.5 * (double(p.x) + double(q.x))),
                               Float(0.5 * (double(p.y) + double(q.y))),
                               Float(0.5 * (double(p.z) + double(q.z)))));
        return mid[key] = int(m->p.size()) - 1;
    };
    std::vector<int> out;
    const std::vector<int> &v = m->vertexIndices;
    for (size_t t = 0; t < v.size(); t += 3) {
        int a = v[t], b = v[t + 1], c = v[t + 2];
        int ab = midpoint(a, b), bc = midpoint(b, c), ca = midpoint(c, a);
        out.insert(out.end(), {a, ab, ca, ab, b, bc, ca, bc, c, ab, bc, ca});
    }
    m->vertexIndices = out;
}

inline std::vector<Ray> MakeRays(const Bounds3f &b) {
    std::vector<Ray> rays;
    Point3f c = b.pMin * Float(0.5) + b.pMax * Float(0.5);
    double r = 0.5 * b.Diagonal().Length();
    // A pinhole camera in front of the bunny, as in the benchmark.
    Vector3f view = Normalize(Vector3f(0.35f, 0.25f, 1));
    Point3f eye = c + view * Float(3 * r);
    Vector3f fwd = -view;
    Vector3f right = Normalize(Cross(fwd, Vector3f(0, 1, 0)));
    Vector3f up = Cross(right, fwd);
    double tanHalf = std::tan(std::asin(0.8 / 3));
    int res = kCameraResolution;
    for (int y = 0; y < res; ++y)
        for (int x = 0; x < res; ++x) {
            Float sx = Float((2 * (x + 0.5) / res - 1) * tanHalf);
            Float sy = Float((1 - 2 * (y + 0.5) / res) * tanHalf);
            rays.push_back(Ray(eye, Normalize(fwd + right * sx + up * sy)));
        }
    // Incoherent rays: from a sphere around the bunny to random points in
    // its box.
    std::mt19937_64 rng(calls::Seed(621));
    std::uniform_real_distribution<double> u(0, 1);
    for (int i = 0; i < kIncoherentRays; ++i) {
        double z = 1 - 2 * u(rng), phi = 2 * Pi * u(rng);
        double s = std::sqrt(std::max(0.0, 1 - z * z));
        Point3f o = c + Vector3f(Float(s * std::cos(phi)),
                                 Float(s * std::sin(phi)), Float(z)) *
                            Float(1.5 * r);
        Point3f t(Float(b.pMin.x + u(rng) * (b.pMax.x - b.pMin.x)),
                  Float(b.pMin.y + u(rng) * (b.pMax.y - b.pMin.y)),
                  Float(b.pMin.z + u(rng) * (b.pMax.z - b.pMin.z)));
        rays.push_back(Ray(o, Normalize(t - o)));
    }
    return rays;
}

// The subdivided bunny, its rays, and brute force's closest hit of each
// ray, made once (they depend on no exercise); null if data/bunny.ply is
// not found.
struct Bunny {
    int baseTriangles;
    ex::Scene scene;
    std::vector<Ray> rays;
    std::vector<Float> oracleT;
};

const Bunny *TheBunny() {
    static const Bunny *bunny = [] {
        std::string path = FindBunny();
        if (path.empty()) return static_cast<Bunny *>(nullptr);
        PlyMesh m = ReadPly(path);
        Bunny *b = new Bunny;
        b->baseTriangles = m.nTriangles();
        Subdivide(&m);
        b->scene.AddTriangles(m.p, m.vertexIndices);
        b->rays = MakeRays(b->scene.bounds);
        // Brute force: every triangle, each with the ray's full extent.
        for (const Ray &ray : b->rays) {
            Float tMin = Infinity;
            for (auto &p : b->scene.prims) {
                Ray r = ray;
                SurfaceInteraction si;
                if (p->Intersect(r, &si)) tMin = std::min(tMin, r.tMax);
            }
            b->oracleT.push_back(tMin);
        }
        return b;
    }();
    return bunny;
}

#define ASSERT_BUNNY(bunny)                                             \
    ASSERT_NE(bunny, nullptr) << "data/bunny.ply not found (set "       \
                                 "LRT_DATA_DIR to the data directory)"

// Traces the bunny's rays with an accelerator and compares with brute
// force.
inline void Check(const Bunny &bunny, const Primitive &accel, const char *name) {
    int hits = 0, oracleHits = 0, failures = 0;
    for (size_t i = 0; i < bunny.rays.size(); ++i) {
        Ray ray = bunny.rays[i];
        SurfaceInteraction si;
        bool hit = accel.Intersect(ray, &si);
        Float t = bunny.oracleT[i];
        hits += hit;
        oracleHits += t < Infinity;
        bool ok = hit == (t < Infinity) &&
                  accel.IntersectP(bunny.rays[i]) == hit;
        if (ok && hit) {
            Ray r = bunny.rays[i];
            SurfaceInteraction s2;
            // The primitive reported is hit at the distance reported,
            // which is the closest, up to ties.
            ok = si.primitive && si.primitive->Intersect(r, &s2) &&
                 r.tMax == ray.tMax && ray.tMax >= t &&
                 ray.tMax <= t * (1 + kTieTolerance);
        }
        if (!ok && failures++ < 10)
            ADD_FAILURE() << name << ": ray " << i << " " << bunny.rays[i]
                          << " hit " << hit << " t " << ray.tMax
                          << ", brute force t " << t;
    }
    EXPECT_EQ(failures, 0) << name;
    EXPECT_EQ(hits, oracleHits) << name;
    // The camera sees the bunny, and incoherent rays aimed into its box hit
    // it about half of the time.
    EXPECT_GT(hits, int(bunny.rays.size()) / 4) << name;
}

}  // namespace lrt_test
