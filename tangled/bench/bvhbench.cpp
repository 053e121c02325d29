// bench/bvhbench.cpp: tangled from chapters/09-bvh-benchmark.md. Edit the chapter, not this file.
#include "lrt/lrt.h"

#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <functional>
#include <iostream>
#include <map>
#include <memory>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <unordered_map>
#include <vector>

using namespace lrt;
using SplitMethod = BVHAccel::SplitMethod;

// BVH Benchmark Declarations
struct BenchMesh {
    std::string name;
    Transform identity;
    std::vector<std::shared_ptr<Primitive>> prims;
    PlyMesh ply;
};

struct RaySet {
    std::string name;
    std::vector<float> data;  // ox oy oz dx dy dz for each ray
    size_t Count() const { return data.size() / 6; }
    Ray Get(size_t i) const {
        const float *r = &data[6 * i];
        return Ray(Point3f(r[0], r[1], r[2]), Vector3f(r[3], r[4], r[5]));
    }
};
struct BenchOptions {
    std::string dataDir = "build/bench-data";
    std::string baseMesh = "data/bunny.ply";
    std::vector<std::string> meshFiles, rayFiles;
    std::vector<SplitMethod> methods = {SplitMethod::SAH, SplitMethod::HLBVH,
                                        SplitMethod::Middle,
                                        SplitMethod::EqualCounts};
    int passes = 5, buildRepetitions = 3;
    int firstLeafSize = 4, finalLeafSize = 8;
    std::string jsonFile = "build/bvhbench.json";
};

// The last is the peer of the next section, measured only if it is built in.
const char *versionNames[] = {"first", "adopted", "final", "embree"};
struct Agreement {
    std::string mesh, rays;
    size_t count = 0, lrtHits = 0, peerHits = 0, differ = 0;
    size_t firstRay = 0;                 // the first ray that differs
    double firstLrt = 0, firstPeer = 0;  // its distances; infinite: a miss
};
struct Column {
    const char *counter;
    int width, precision;
};
const Column treeColumns[] = {{"nodes", 9, 0}, {"leaves", 8, 0},
                              {"leaf_size", 5, 2}, {"sah_cost", 7, 2},
                              {"depth", 5, 0}};
const char *comparedTo[] = {"first", "embree"};

struct Ratio {
    double median, min, max;
};
std::string FormatRatio(const Ratio &r) {
    char text[64];
    std::snprintf(text, sizeof text, "%.2fx [%.2f, %.2f]", r.median, r.min,
                  r.max);
    return text;
}
// BVH Benchmark Data Generation
void SubdivideMesh(PlyMesh *m) {
    std::unordered_map<uint64_t, int> midpoints;
    auto midpoint = [&](int a, int b) {
        uint64_t key = (uint64_t(std::min(a, b)) << 32) |
                       uint64_t(std::max(a, b));
        auto it = midpoints.find(key);
        if (it != midpoints.end()) return it->second;
        const Point3f &p = m->p[a], &q = m->p[b];
        m->p.push_back(Point3f(float(0.5 * (double(p.x) + double(q.x))),
                               float(0.5 * (double(p.y) + double(q.y))),
                               float(0.5 * (double(p.z) + double(q.z)))));
        int index = int(m->p.size()) - 1;
        midpoints[key] = index;
        return index;
    };
    std::vector<int> out;
    out.reserve(4 * m->vertexIndices.size());
    for (size_t t = 0; t < m->vertexIndices.size(); t += 3) {
        int a = m->vertexIndices[t], b = m->vertexIndices[t + 1],
            c = m->vertexIndices[t + 2];
        int ab = midpoint(a, b), bc = midpoint(b, c), ca = midpoint(c, a);
        for (int v : {a, ab, ca, ab, b, bc, ca, bc, c, ab, bc, ca})
            out.push_back(v);
    }
    m->vertexIndices.swap(out);
}
struct Vec3d {
    double x, y, z;
};

Vec3d Normalized(const Vec3d &v) {
    double l = std::sqrt(v.x * v.x + v.y * v.y + v.z * v.z);
    return {v.x / l, v.y / l, v.z / l};
}

Vec3d CrossD(const Vec3d &a, const Vec3d &b) {
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z,
            a.x * b.y - a.y * b.x};
}

void AppendRay(RaySet *rays, const Vec3d &o, const Vec3d &d) {
    for (double v : {o.x, o.y, o.z, d.x, d.y, d.z})
        rays->data.push_back(float(v));
}
RaySet MakeCameraRays(const double lo[3], const double hi[3], int res) {
    Vec3d c = {0.5 * (lo[0] + hi[0]), 0.5 * (lo[1] + hi[1]),
               0.5 * (lo[2] + hi[2])};
    double e[3] = {hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]};
    double r = 0.5 * std::sqrt(e[0] * e[0] + e[1] * e[1] + e[2] * e[2]);
    Vec3d view = Normalized({0.35, 0.25, 1.0});
    double dist = 3.0 * r;
    Vec3d eye = {c.x + dist * view.x, c.y + dist * view.y,
                 c.z + dist * view.z};
    Vec3d fwd = {-view.x, -view.y, -view.z};
    Vec3d right = Normalized(CrossD(fwd, {0.0, 1.0, 0.0}));
    Vec3d up = CrossD(right, fwd);
    double tanHalf = std::tan(std::asin(0.8 * r / dist));
    RaySet rays;
    rays.name = "rays_primary (generated)";
    rays.data.reserve(6 * size_t(res) * res);
    for (int y = 0; y < res; ++y) {
        double sy = (1.0 - 2.0 * (y + 0.5) / res) * tanHalf;
        for (int x = 0; x < res; ++x) {
            double sx = (2.0 * (x + 0.5) / res - 1.0) * tanHalf;
            Vec3d d = Normalized({fwd.x + sx * right.x + sy * up.x,
                                  fwd.y + sx * right.y + sy * up.y,
                                  fwd.z + sx * right.z + sy * up.z});
            AppendRay(&rays, eye, d);
        }
    }
    return rays;
}
class PythonRandom {
  public:
    explicit PythonRandom(uint32_t seed) { InitByArray(seed); }
    double Random() {
        uint32_t a = Next() >> 5, b = Next() >> 6;
        return (a * 67108864.0 + b) * (1.0 / 9007199254740992.0);
    }

  private:
    static constexpr int N = 624, M = 397;
    // PythonRandom Private Methods
    void InitGenrand(uint32_t s) {
        mt[0] = s;
        for (int i = 1; i < N; ++i)
            mt[i] = 1812433253u * (mt[i - 1] ^ (mt[i - 1] >> 30)) + uint32_t(i);
        index = N;
    }

    void InitByArray(uint32_t key) {
        InitGenrand(19650218u);
        int i = 1;
        for (int k = N; k > 0; --k) {
            mt[i] = (mt[i] ^ ((mt[i - 1] ^ (mt[i - 1] >> 30)) * 1664525u)) + key;
            if (++i >= N) {
                mt[0] = mt[N - 1];
                i = 1;
            }
        }
        for (int k = N - 1; k > 0; --k) {
            mt[i] = (mt[i] ^ ((mt[i - 1] ^ (mt[i - 1] >> 30)) * 1566083941u)) -
                    uint32_t(i);
            if (++i >= N) {
                mt[0] = mt[N - 1];
                i = 1;
            }
        }
        mt[0] = 0x80000000u;
    }
    uint32_t Next() {
        if (index >= N) {
            for (int i = 0; i < N; ++i) {
                uint32_t y =
                    (mt[i] & 0x80000000u) | (mt[(i + 1) % N] & 0x7fffffffu);
                mt[i] = mt[(i + M) % N] ^ (y >> 1) ^ ((y & 1) ? 0x9908b0dfu : 0u);
            }
            index = 0;
        }
        uint32_t y = mt[index++];
        y ^= y >> 11;
        y ^= (y << 7) & 0x9d2c5680u;
        y ^= (y << 15) & 0xefc60000u;
        y ^= y >> 18;
        return y;
    }
    uint32_t mt[N];
    int index = N;
};
RaySet MakeIncoherentRays(const double lo[3], const double hi[3],
                          size_t count, uint32_t seed) {
    PythonRandom rng(seed);
    Vec3d c = {0.5 * (lo[0] + hi[0]), 0.5 * (lo[1] + hi[1]),
               0.5 * (lo[2] + hi[2])};
    double e[3] = {hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]};
    double R = 1.5 * 0.5 * std::sqrt(e[0] * e[0] + e[1] * e[1] + e[2] * e[2]);
    RaySet rays;
    rays.name = "rays_incoherent (generated)";
    rays.data.reserve(6 * count);
    for (size_t i = 0; i < count; ++i) {
        double z = 1.0 - 2.0 * rng.Random();
        double phi = 2.0 * 3.141592653589793 * rng.Random();
        double s = std::sqrt(std::max(0.0, 1.0 - z * z));
        Vec3d o = {c.x + R * s * std::cos(phi), c.y + R * s * std::sin(phi),
                   c.z + R * z};
        double tx = lo[0] + e[0] * rng.Random();
        double ty = lo[1] + e[1] * rng.Random();
        double tz = lo[2] + e[2] * rng.Random();
        AppendRay(&rays, o, Normalized({tx - o.x, ty - o.y, tz - o.z}));
    }
    return rays;
}
// BVH Benchmark Input Functions
std::unique_ptr<BenchMesh> MakeBenchMesh(const std::string &name,
                                         const PlyMesh &m) {
    auto bm = std::make_unique<BenchMesh>();
    bm->name = name;
    bm->ply = m;
    auto shapes = CreateTriangleMesh(
        &bm->identity, &bm->identity, false, m.nTriangles(),
        m.vertexIndices.data(), m.nVertices(), m.p.data(), nullptr,
        nullptr, nullptr);
    bm->prims.reserve(shapes.size());
    for (const auto &s : shapes)
        bm->prims.push_back(std::make_shared<GeometricPrimitive>(s));
    return bm;
}
RaySet ReadRays(const std::string &filename) {
    std::ifstream in(filename, std::ios::binary | std::ios::ate);
    if (!in) throw std::runtime_error(filename + ": cannot open");
    std::streamsize bytes = in.tellg();
    if (bytes <= 0 || bytes % (6 * sizeof(float)) != 0)
        throw std::runtime_error(filename + ": not a whole number of rays");
    RaySet rays;
    rays.name = filename.substr(filename.find_last_of('/') + 1);
    rays.data.resize(size_t(bytes) / sizeof(float));
    in.seekg(0);
    in.read(reinterpret_cast<char *>(rays.data.data()), bytes);
    if (!in) throw std::runtime_error(filename + ": read error");
    // Convert the rays from little-endian if this machine is not
    const uint32_t one = 1;
    if (*reinterpret_cast<const unsigned char *>(&one) != 1)
        for (float &f : rays.data) {
            unsigned char *b = reinterpret_cast<unsigned char *>(&f);
            std::swap(b[0], b[3]);
            std::swap(b[1], b[2]);
        }
    return rays;
}
// BVH Benchmark Measurement Functions
struct TraceResult {
    int64_t hits = 0;
    double sumT = 0;
};

#if defined(__GNUC__) || defined(__clang__)
__attribute__((noinline))
#endif
TraceResult TracePass(const Primitive &accel, const RaySet &rays) {
    TraceResult r;
    for (size_t i = 0; i < rays.Count(); ++i) {
        Ray ray = rays.Get(i);
        SurfaceInteraction isect;
        if (accel.Intersect(ray, &isect)) {
            ++r.hits;
            r.sumT += ray.tMax;
        }
    }
    return r;
}
template <typename Accel>
using AccelSlot = std::shared_ptr<std::unique_ptr<Accel>>;

template <typename Accel>
void CountTree(benchmark::State &state, const Accel &accel) {
    BVHStats s = accel.Stats();
    state.counters["nodes"] = double(s.TotalNodes());
    state.counters["leaves"] = double(s.leafNodes);
    state.counters["leaf_size"] = s.AverageLeafSize();
    state.counters["sah_cost"] = s.sahCost;
    state.counters["depth"] = s.maxDepth;
}

template <typename Accel, typename Make>
void RegisterBuild(const std::string &name, AccelSlot<Accel> slot, Make make,
                   const char *whyNoTree = "the build made no tree") {
    benchmark::RegisterBenchmark(
        name.c_str(),
        [slot, make, whyNoTree](benchmark::State &state) {
            slot->reset();
            for (auto _ : state) *slot = make();
            if (!*slot) {
                state.SkipWithError(whyNoTree);
                return;
            }
            CountTree(state, **slot);
        })
        ->Iterations(1)
        ->Unit(benchmark::kMillisecond);
}
template <typename Accel>
void RegisterTrace(const std::string &name, AccelSlot<Accel> slot,
                   const RaySet &rays) {
    benchmark::RegisterBenchmark(
        name.c_str(),
        [slot, &rays](benchmark::State &state) {
            if (!*slot) {
                state.SkipWithError("the accelerator was not built");
                return;
            }
            TraceResult r;
            for (auto _ : state) r = TracePass(**slot, rays);
            state.counters["Mrays/s"] = benchmark::Counter(
                double(rays.Count()) * 1e-6, benchmark::Counter::kIsRate);
            state.counters["hits"] = double(r.hits);
            state.counters["sum_t"] = r.sumT;
        })
        ->Iterations(1)
        ->Unit(benchmark::kMillisecond);
}
const char *MethodName(SplitMethod m) { return BVHAccel::SplitMethodName(m); }

std::string BenchName(const BenchMesh &mesh, SplitMethod method,
                      const std::string &version, const std::string &what) {
    return mesh.name + "/" + MethodName(method) + "/" + version + "/" + what;
}

const char roundTag[] = "/round:";

std::string RoundName(const std::string &name, int round) {
    return name + roundTag + std::to_string(round + 1);
}
struct Version {
    const char *name;
    std::function<void(const std::string &)> registerBuild;
    std::function<void(const std::string &, const RaySet &)> registerTrace;
};

template <typename Accel, typename Make>
Version MakeVersion(const char *name, AccelSlot<Accel> slot, Make make,
                    const char *whyNoTree = "the build made no tree") {
    return {name,
            [=](const std::string &n) {
                RegisterBuild(n, slot, make, whyNoTree);
            },
            [=](const std::string &n, const RaySet &rays) {
                RegisterTrace(n, slot, rays);
            }};
}

void RunRegistered(benchmark::BenchmarkReporter *reporter) {
    benchmark::RunSpecifiedBenchmarks(reporter);
    benchmark::ClearRegisteredBenchmarks();
}
// BVH Benchmark Peer
#if defined(LRT_BENCH_EMBREE)
#include <embree3/rtcore.h>

RTCDevice EmbreeDevice() {
    static RTCDevice device = rtcNewDevice("threads=1");
    if (!device)
        throw std::runtime_error("Embree: cannot create a device (error " +
                                 std::to_string(rtcGetDeviceError(nullptr)) +
                                 ")");
    return device;
}
// Embree Geometry and Scene
class EmbreeGeometry {
  public:
    explicit EmbreeGeometry(const PlyMesh &m)
        : geometry(rtcNewGeometry(EmbreeDevice(),
                                  RTC_GEOMETRY_TYPE_TRIANGLE)) {
        auto *p = static_cast<float *>(rtcSetNewGeometryBuffer(
            geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
            3 * sizeof(float), m.p.size()));
        auto *v = static_cast<unsigned *>(rtcSetNewGeometryBuffer(
            geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
            3 * sizeof(unsigned), size_t(m.nTriangles())));
        if (!p || !v)
            throw std::runtime_error("Embree: cannot allocate the buffers");
        for (size_t i = 0; i < m.p.size(); ++i)
            for (int a = 0; a < 3; ++a) p[3 * i + a] = float(m.p[i][a]);
        std::copy(m.vertexIndices.begin(), m.vertexIndices.end(), v);
        rtcCommitGeometry(geometry);
    }
    ~EmbreeGeometry() { rtcReleaseGeometry(geometry); }
    EmbreeGeometry(const EmbreeGeometry &) = delete;
    EmbreeGeometry &operator=(const EmbreeGeometry &) = delete;

    RTCGeometry geometry;
};
class EmbreeScene {
  public:
    explicit EmbreeScene(const EmbreeGeometry &g)
        : scene(rtcNewScene(EmbreeDevice())) {
        rtcAttachGeometry(scene, g.geometry);
        rtcCommitScene(scene);
    }
    ~EmbreeScene() { rtcReleaseScene(scene); }
    EmbreeScene(const EmbreeScene &) = delete;
    EmbreeScene &operator=(const EmbreeScene &) = delete;

    RTCScene scene;
};

void CountTree(benchmark::State &, const EmbreeScene &) {}
// Trace a ray with Embree
inline bool EmbreeHit(const EmbreeScene &peer, const RaySet &rays, size_t i,
                      float *t) {
    const float *r = &rays.data[6 * i];
    RTCRayHit rh;
    rh.ray.org_x = r[0];
    rh.ray.org_y = r[1];
    rh.ray.org_z = r[2];
    rh.ray.dir_x = r[3];
    rh.ray.dir_y = r[4];
    rh.ray.dir_z = r[5];
    rh.ray.tnear = 0;
    rh.ray.tfar = std::numeric_limits<float>::infinity();
    rh.ray.time = 0;
    rh.ray.mask = unsigned(-1);
    rh.ray.id = 0;
    rh.ray.flags = 0;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    rtcIntersect1(peer.scene, &context, &rh);
    *t = rh.ray.tfar;
    // Inject a fault into the peer's hits, for the tests only
    #if defined(LRT_BENCH_EMBREE_FAULT)
    if (i % LRT_BENCH_EMBREE_FAULT == 0) return false;
    #endif
    return rh.hit.geomID != RTC_INVALID_GEOMETRY_ID;
}
// Embree Tracing Pass
#if defined(__GNUC__) || defined(__clang__)
__attribute__((noinline))
#endif
TraceResult TracePass(const EmbreeScene &peer, const RaySet &rays) {
    TraceResult r;
    for (size_t i = 0; i < rays.Count(); ++i) {
        float t;
        if (EmbreeHit(peer, rays, i, &t)) {
            ++r.hits;
            r.sumT += t;
        }
    }
    return r;
}
// Compare lrt's hits with the peer's
bool SameHit(double tLrt, double tPeer) {
    if (tLrt == Infinity || tPeer == Infinity) return tLrt == tPeer;
    return std::abs(tLrt - tPeer) <= 1e-4 * tLrt;
}

size_t AllowedToDiffer(size_t rays) { return 1 + rays / 10000; }
Agreement CompareHits(const BenchMesh &mesh, const Primitive &accel,
                      const EmbreeScene &peer, const RaySet &rays) {
    Agreement a;
    a.mesh = mesh.name;
    a.rays = rays.name;
    a.count = rays.Count();
    for (size_t i = 0; i < rays.Count(); ++i) {
        Ray ray = rays.Get(i);
        SurfaceInteraction isect;
        double tLrt = accel.Intersect(ray, &isect) ? double(ray.tMax)
                                                   : Infinity;
        float t;
        double tPeer = EmbreeHit(peer, rays, i, &t) ? double(t) : Infinity;
        a.lrtHits += tLrt < Infinity;
        a.peerHits += tPeer < Infinity;
        if (!SameHit(tLrt, tPeer) && a.differ++ == 0) {
            a.firstRay = i;
            a.firstLrt = tLrt;
            a.firstPeer = tPeer;
        }
    }
    return a;
}
void CheckAgreement(const Agreement &a) {
    if (a.differ <= AllowedToDiffer(a.count)) return;
    auto hit = [](double t) {
        return t < Infinity ? "a hit at t = " + std::to_string(t)
                            : std::string("a miss");
    };
    throw std::runtime_error(
        "lrt and embree disagree on " + a.mesh + " with " + a.rays + ": " +
        std::to_string(a.differ) + " of " + std::to_string(a.count) +
        " rays differ (at most " + std::to_string(AllowedToDiffer(a.count)) +
        " may), with " + std::to_string(a.lrtHits) + " and " +
        std::to_string(a.peerHits) + " hits; the first is ray " +
        std::to_string(a.firstRay) + ": lrt finds " + hit(a.firstLrt) +
        ", embree " + hit(a.firstPeer));
}
#endif
// BVH Benchmark Groups
void RunGroup(const BenchMesh &mesh, SplitMethod method,
              const std::vector<RaySet> &raySets, const BenchOptions &opt,
              benchmark::BenchmarkReporter *reporter,
              std::vector<Agreement> *agreements) {
    auto first = std::make_shared<std::unique_ptr<BVHAccel>>();
    auto final = std::make_shared<std::unique_ptr<FastBVHAccel>>();
    int finalLeafSize = method == SplitMethod::SAH ? opt.finalLeafSize
                                                   : opt.firstLeafSize;
    std::vector<Version> versions = {
        MakeVersion("first", first, [&] {
            return std::make_unique<BVHAccel>(mesh.prims, opt.firstLeafSize,
                                              method);
        }),
        MakeVersion(
            "adopted", std::make_shared<std::unique_ptr<FastBVHAccel>>(),
            [=]() -> std::unique_ptr<FastBVHAccel> {
                if (!*first) return nullptr;
                return std::make_unique<FastBVHAccel>(**first);
            },
            "the adopted version copies the first version's tree, which "
            "was not built: let --benchmark_filter select the first "
            "version's builds too"),
        MakeVersion("final", final, [=, &mesh] {
            return std::make_unique<FastBVHAccel>(mesh.prims, finalLeafSize,
                                                  method);
        })};
#if defined(LRT_BENCH_EMBREE)
    // Add the Embree peer to the SAH group
    auto peer = std::make_shared<std::unique_ptr<EmbreeScene>>();
    if (method == SplitMethod::SAH) {
        auto geometry = std::make_shared<EmbreeGeometry>(mesh.ply);
        versions.push_back(MakeVersion(
            "embree", peer,
            [geometry]() -> std::unique_ptr<EmbreeScene> {
                auto scene = std::make_unique<EmbreeScene>(*geometry);
                if (rtcGetDeviceError(EmbreeDevice()) != RTC_ERROR_NONE)
                    return nullptr;
                return scene;
            },
            "Embree could not build the scene"));
    }
#endif
    for (int r = 0; r < opt.buildRepetitions; ++r)
        for (const Version &v : versions)
            v.registerBuild(
                RoundName(BenchName(mesh, method, v.name, "build"), r));
    RunRegistered(reporter);
#if defined(LRT_BENCH_EMBREE)
    // Check that lrt's final version and the peer agree on every ray
    if (method == SplitMethod::SAH) {
        if (!*final || !*peer)
            std::printf("agreement of lrt and embree not checked on %s: "
                        "a filter left out a build\n", mesh.name.c_str());
        else
            for (const RaySet &rays : raySets) {
                agreements->push_back(CompareHits(mesh, **final, **peer, rays));
                CheckAgreement(agreements->back());
            }
    }
#else
    (void)agreements;
#endif
    size_t n = versions.size();
    for (const RaySet &rays : raySets)
        for (int r = 0; r < opt.passes; ++r)
            for (size_t k = 0; k < n; ++k) {
                const Version &v = versions[(size_t(r) + k) % n];
                v.registerTrace(
                    RoundName(BenchName(mesh, method, v.name, rays.name), r),
                    rays);
            }
    RunRegistered(reporter);
}
// BVH Benchmark Reporter
struct Rounds {
    std::vector<double> cpuMs;
    std::map<std::string, std::vector<double>> counters;
};

class BenchReporter : public benchmark::ConsoleReporter {
  public:
    bool ReportContext(const Context &context) override {
        if (contextShown) return true;
        contextShown = true;
        return ConsoleReporter::ReportContext(context);
    }
    void ReportRuns(const std::vector<Run> &runs) override {
        ConsoleReporter::ReportRuns(runs);
        for (const Run &run : runs) {
            if (run.run_type != Run::RT_Iteration || run.error_occurred)
                continue;
            std::string name = run.run_name.function_name;
            name = name.substr(0, name.rfind(roundTag));
            Rounds &r = rounds[name];
            r.cpuMs.push_back(run.GetAdjustedCPUTime());
            for (const auto &c : run.counters)
                r.counters[c.first].push_back(c.second);
        }
    }
    // BenchReporter Summaries
    struct Median {
        double cpuMs = 0;
        std::map<std::string, double> counters;
    };

    std::optional<Median> Find(const std::string &name) const {
        auto it = rounds.find(name);
        if (it == rounds.end()) return std::nullopt;
        Median m;
        m.cpuMs = MedianOf(it->second.cpuMs);
        for (const auto &c : it->second.counters)
            m.counters[c.first] = MedianOf(c.second);
        return m;
    }

    std::optional<Ratio> PairedRatio(const std::string &numerator,
                                      const std::string &denominator,
                                      const std::string &counter) const {
        auto a = rounds.find(numerator), b = rounds.find(denominator);
        if (a == rounds.end() || b == rounds.end()) return std::nullopt;
        const std::vector<double> &x = counter.empty()
                                           ? a->second.cpuMs
                                           : a->second.counters.at(counter);
        const std::vector<double> &y = counter.empty()
                                           ? b->second.cpuMs
                                           : b->second.counters.at(counter);
        std::vector<double> ratios;
        for (size_t i = 0; i < std::min(x.size(), y.size()); ++i)
            ratios.push_back(x[i] / y[i]);
        if (ratios.empty()) return std::nullopt;
        auto [lo, hi] = std::minmax_element(ratios.begin(), ratios.end());
        return Ratio{MedianOf(ratios), *lo, *hi};
    }

    static double MedianOf(std::vector<double> v) {
        std::sort(v.begin(), v.end());
        size_t n = v.size();
        return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
    }

  private:
    bool contextShown = false;
    std::map<std::string, Rounds> rounds;
};
// BVH Benchmark Output Functions
struct BuildConfiguration {
    std::string compiler, command, flags;
};

BuildConfiguration ThisBuild() {
    BuildConfiguration b;
#if defined(__clang__)
    b.compiler = "Clang " __clang_version__;
#elif defined(__GNUC__)
    b.compiler = "GCC " __VERSION__;
#else
    b.compiler = "unknown compiler";
#endif
#if defined(LRT_BENCH_CXX) && defined(LRT_BENCH_CXXFLAGS)
    b.command = LRT_BENCH_CXX;
    b.flags = LRT_BENCH_CXXFLAGS;
#else
    b.command = b.flags = "not recorded";
#endif
    while (!b.compiler.empty() && b.compiler.back() == ' ')
        b.compiler.pop_back();
    return b;
}

std::string JSONString(const std::string &s) {
    std::string quoted = "\"";
    for (char c : s) {
        if (c == '"' || c == '\\') quoted += '\\';
        quoted += c;
    }
    return quoted + '"';
}
const char *ReferenceCheck(const std::string &mesh, const std::string &rays,
                           double hits) {
    if (mesh.compare(0, 7, "bunny_L") != 0 || mesh == "bunny_L0") return "";
    if (rays.compare(0, 12, "rays_primary") == 0)
        return hits == 398701 ? "ok" : "MISMATCH";
    if (rays.compare(0, 15, "rays_incoherent") == 0)
        return hits == 641888 || hits == 641889 ? "ok" : "MISMATCH";
    return "";
}
void PrintSummary(const std::vector<std::unique_ptr<BenchMesh>> &meshes,
                  const std::vector<RaySet> &raySets,
                  const BenchOptions &opt, const BenchReporter &rep,
                  const std::vector<Agreement> &agreements) {
    BuildConfiguration build = ThisBuild();
    std::printf("\nbuilt with %s %s (%s)\n", build.command.c_str(),
                build.flags.c_str(), build.compiler.c_str());
    for (const auto &mesh : meshes) {
        std::printf("\n%s: %zu triangles; medians of %d builds and %d "
                    "passes\n", mesh->name.c_str(), mesh->prims.size(),
                    opt.buildRepetitions, opt.passes);
        std::printf("%-12s %-8s %9s %9s %8s %5s %7s %5s\n", "method",
                    "version", "build ms", "nodes", "leaves", "leaf",
                    "SAH", "depth");
        // Print the tree statistics of every method and version
        for (SplitMethod m : opt.methods)
            for (const char *v : versionNames) {
                auto b = rep.Find(BenchName(*mesh, m, v, "build"));
                if (!b) continue;
                std::printf("%-12s %-8s %9.1f", MethodName(m), v, b->cpuMs);
                for (const Column &k : treeColumns) {
                    auto c = b->counters.find(k.counter);
                    if (c == b->counters.end()) std::printf(" %*s", k.width, "-");
                    else std::printf(" %*.*f", k.width, k.precision, c->second);
                }
                std::printf("\n");
            }
        for (const RaySet &rays : raySets) {
            std::printf("%s (%zu rays)\n", rays.name.c_str(), rays.Count());
            std::printf("%-12s %-8s %9s %9s %14s %6s\n", "method",
                        "version", "Mrays/s", "hits", "sum of t", "check");
            // Print the tracing results of every method and version
            for (SplitMethod m : opt.methods)
                for (const char *v : versionNames) {
                    auto t = rep.Find(BenchName(*mesh, m, v, rays.name));
                    if (!t) continue;
                    auto c = t->counters;
                    std::printf("%-12s %-8s %9.3f %9.0f %14.6e %6s\n", MethodName(m), v,
                                c["Mrays/s"], c["hits"], c["sum_t"],
                                ReferenceCheck(mesh->name, rays.name, c["hits"]));
                }
        }
        // Print the ratios of the final version to the others
        for (const char *other : comparedTo) {
            bool headed = false;
            for (SplitMethod m : opt.methods) {
                std::string line;
                auto add = [&](const std::string &what, const char *counter) {
                    if (auto r = rep.PairedRatio(BenchName(*mesh, m, "final", what),
                                                 BenchName(*mesh, m, other, what),
                                                 counter))
                        line += " " + what + " " + FormatRatio(*r);
                };
                for (const RaySet &rays : raySets) add(rays.name, "Mrays/s");
                add("build", "");
                if (line.empty()) continue;
                if (!headed)
                    std::printf("final / %s: throughput on each ray set; build "
                                "time (median of the rounds' ratios [smallest, "
                                "largest])\n", other);
                headed = true;
                std::printf("%-12s%s\n", MethodName(m), line.c_str());
            }
        }
        // Print the agreement of lrt and the peer
        for (const Agreement &a : agreements)
            if (a.mesh == mesh->name)
                std::printf("lrt and embree on %s: %zu rays, %zu and %zu hits, "
                            "%zu differ\n", a.rays.c_str(), a.count, a.lrtHits,
                            a.peerHits, a.differ);
    }
}
void WriteJSON(const std::string &filename,
               const std::vector<std::unique_ptr<BenchMesh>> &meshes,
               const std::vector<RaySet> &raySets, const BenchOptions &opt,
               const BenchReporter &rep,
               const std::vector<Agreement> &agreements) {
    BuildConfiguration build = ThisBuild();
    std::ostringstream js;
    js << "{\n  \"float\": \"" << (sizeof(Float) == 4 ? "float" : "double")
       << "\",\n  \"compiler\": " << JSONString(build.compiler)
       << ",\n  \"cxx\": " << JSONString(build.command)
       << ",\n  \"cxxflags\": " << JSONString(build.flags)
       << ",\n  \"passes\": " << opt.passes
       << ",\n  \"build_repetitions\": " << opt.buildRepetitions
       << ",\n  \"results\": [";
    const char *sep = "\n";
    for (const auto &mesh : meshes)
        for (SplitMethod m : opt.methods)
            for (const char *v : versionNames) {
                // Write the JSON record of one tree and its ray sets
                auto b = rep.Find(BenchName(*mesh, m, v, "build"));
                if (!b) continue;
                js.precision(10);
                js << sep << "    {\"mesh\": \"" << mesh->name << "\", \"triangles\": "
                   << mesh->prims.size() << ", \"method\": \"" << MethodName(m)
                   << "\", \"version\": \"" << v << "\", \"build_ms\": " << b->cpuMs;
                for (const Column &k : treeColumns)
                    if (auto c = b->counters.find(k.counter); c != b->counters.end())
                        js << ", \"" << k.counter << "\": " << c->second;
                auto first = [&](const std::string &what) {
                    return BenchName(*mesh, m, "first", what);
                };
                if (auto r = rep.PairedRatio(BenchName(*mesh, m, v, "build"),
                                             first("build"), ""))
                    js << ", \"build_ratio\": " << r->median;
                auto versus = [&](const std::string &what, const char *counter) {
                    if (std::string(v) != "final") return;
                    js << ", \"" << (what == "build" ? "build_versus" : "versus")
                       << "\": {";
                    const char *comma = "";
                    for (const char *other : comparedTo)
                        if (auto r = rep.PairedRatio(BenchName(*mesh, m, v, what),
                                                     BenchName(*mesh, m, other, what),
                                                     counter)) {
                            js << comma << "\"" << other << "\": {\"median\": " << r->median
                               << ", \"min\": " << r->min << ", \"max\": " << r->max << "}";
                            comma = ", ";
                        }
                    js << "}";
                };
                versus("build", "");
                js << ", \"rays\": {";
                const char *raySep = "";
                for (const RaySet &rays : raySets) {
                    auto t = rep.Find(BenchName(*mesh, m, v, rays.name));
                    if (!t) continue;
                    js << raySep << "\"" << rays.name << "\": {\"mrays_per_s\": "
                       << t->counters.at("Mrays/s") << ", \"hits\": "
                       << t->counters.at("hits") << ", \"sum_t\": "
                       << t->counters.at("sum_t");
                    if (const char *check = ReferenceCheck(mesh->name, rays.name,
                                                           t->counters.at("hits")); *check)
                        js << ", \"reference\": \"" << check << "\"";
                    if (auto r = rep.PairedRatio(BenchName(*mesh, m, v, rays.name),
                                                 first(rays.name), "Mrays/s"))
                        js << ", \"ratio\": " << r->median;
                    versus(rays.name, "Mrays/s");
                    js << "}";
                    raySep = ", ";
                }
                js << "}}";
                sep = ",\n";
            }
    js << "\n  ],\n  \"agreement\": [";
    sep = "\n";
    for (const Agreement &a : agreements) {
        js << sep << "    {\"mesh\": \"" << a.mesh << "\", \"rays\": \""
           << a.rays << "\", \"count\": " << a.count << ", \"lrt_hits\": "
           << a.lrtHits << ", \"peer_hits\": " << a.peerHits
           << ", \"differ\": " << a.differ << "}";
        sep = ",\n";
    }
    js << "\n  ]\n}\n";
    std::ofstream out(filename);
    out << js.str();
    if (!out) throw std::runtime_error(filename + ": cannot write");
}
// BVH Benchmark Main Function
int main(int argc, char **argv) {
    benchmark::Initialize(&argc, argv);
    BenchOptions opt;
    try {
        // Parse the benchmark's own command-line options
        for (int i = 1; i < argc; ++i) {
            std::string arg = argv[i];
            auto value = [&]() -> std::string {
                if (i + 1 >= argc) throw std::invalid_argument(arg + " needs a value");
                return argv[++i];
            };
            if (arg == "--data") opt.dataDir = value();
            else if (arg == "--base") opt.baseMesh = value();
            else if (arg == "--mesh") opt.meshFiles.push_back(value());
            else if (arg == "--rays") opt.rayFiles.push_back(value());
            else if (arg == "--passes") opt.passes = std::max(1, std::stoi(value()));
            else if (arg == "--builds")
                opt.buildRepetitions = std::max(1, std::stoi(value()));
            else if (arg == "--json") opt.jsonFile = value();
            else if (arg == "--methods") {
                // Parse the list of split methods
                std::istringstream list(value());
                opt.methods.clear();
                for (std::string name; std::getline(list, name, ',');) {
                    if (name == "sah") opt.methods.push_back(SplitMethod::SAH);
                    else if (name == "hlbvh") opt.methods.push_back(SplitMethod::HLBVH);
                    else if (name == "middle") opt.methods.push_back(SplitMethod::Middle);
                    else if (name == "equalcounts")
                        opt.methods.push_back(SplitMethod::EqualCounts);
                    else throw std::invalid_argument("unknown split method " + name);
                }
            } else
                throw std::invalid_argument("unknown option " + arg +
                                            "; see bench/bvhbench.cpp");
        }
        std::vector<std::unique_ptr<BenchMesh>> meshes;
        std::vector<RaySet> raySets;
        // Load or generate the benchmark data
        auto exists = [](const std::string &f) { return bool(std::ifstream(f)); };
        std::string dir = opt.dataDir + "/";
        if (opt.meshFiles.empty() && opt.rayFiles.empty() &&
            exists(dir + "bunny_L2.ply") && exists(dir + "bunny_L4.ply") &&
            exists(dir + "rays_primary.bin") && exists(dir + "rays_incoherent.bin")) {
            opt.meshFiles = {dir + "bunny_L2.ply", dir + "bunny_L4.ply"};
            opt.rayFiles = {dir + "rays_primary.bin", dir + "rays_incoherent.bin"};
        }
        for (const std::string &f : opt.meshFiles) {
            std::string name = f.substr(f.find_last_of('/') + 1);
            name = name.substr(0, name.rfind(".ply"));
            meshes.push_back(MakeBenchMesh(name, ReadPly(f)));
        }
        for (const std::string &f : opt.rayFiles) raySets.push_back(ReadRays(f));
        if (meshes.empty() || raySets.empty()) {
            // Generate the benchmark data from the base mesh
            std::printf("generating the benchmark data from %s\n",
                        opt.baseMesh.c_str());
            PlyMesh m = ReadPly(opt.baseMesh);
            double lo[3] = {Infinity, Infinity, Infinity};
            double hi[3] = {-Infinity, -Infinity, -Infinity};
            for (const Point3f &p : m.p)
                for (int a = 0; a < 3; ++a) {
                    lo[a] = std::min(lo[a], double(p[a]));
                    hi[a] = std::max(hi[a], double(p[a]));
                }
            if (meshes.empty())
                for (int level = 1; level <= 4; ++level) {
                    SubdivideMesh(&m);
                    if (level == 2 || level == 4)
                        meshes.push_back(MakeBenchMesh(
                            "bunny_L" + std::to_string(level), m));
                }
            if (raySets.empty()) {
                raySets.push_back(MakeCameraRays(lo, hi, 1024));
                raySets.push_back(MakeIncoherentRays(lo, hi, size_t(1) << 20, 20240601u));
            }
        }
        BenchReporter reporter;
        std::vector<Agreement> agreements;
        for (const auto &mesh : meshes)
            for (SplitMethod m : opt.methods)
                RunGroup(*mesh, m, raySets, opt, &reporter, &agreements);
        PrintSummary(meshes, raySets, opt, reporter, agreements);
        if (!opt.jsonFile.empty()) {
            WriteJSON(opt.jsonFile, meshes, raySets, opt, reporter,
                      agreements);
            std::printf("\nresults written to %s\n", opt.jsonFile.c_str());
        }
    } catch (const std::exception &e) {
        std::fprintf(stderr, "bvhbench: %s\n", e.what());
        return 1;
    }
    return 0;
}
