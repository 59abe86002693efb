// rayq-bench-embree: rayq against Embree 3 on the same rays (issue 7), one thread.
//
// Closest hit of 65,536 rays aimed into scenes of N random spheres (N = 1, 16, 1,000, 100,000) or
// capped cylinders (N = 1, 16), radius ~0.25·N^(-1/3) in the cube [-1, 1]³ (the scenes and rays
// of rayq-bench-scene). Variants, named <prim>/<variant>/<N>:
//   embree_points         Embree's native spheres (RTC_GEOMETRY_TYPE_SPHERE_POINT)
//   embree_mesh           Embree on UV-sphere triangle meshes (10 rings × 10 segments: 180 triangles)
//   embree_cone_curve     Embree's RTC_GEOMETRY_TYPE_CONE_LINEAR_CURVE (one segment per cylinder)
//   embree_user_plain     Embree user geometry with the textbook float sphere test as its callback,
//                         on the adapter's boxes and leaf size: the floor under any user-geometry
//                         adapter (no rayq)
//   embree_points_rayq_filter  Embree's native spheres on a padded radius, rayq's `stable` crossing
//                         deciding each candidate in an intersection filter: the design proposed
//                         instead of user geometry, kept to compare with the adapter (not exact in
//                         general: FilteredPoints below)
//   embree_round_curve    Embree's RTC_GEOMETRY_TYPE_ROUND_LINEAR_CURVE (a capsule: round ends,
//                         not the same shape; the speed of Embree's other cylinder-like primitive)
//   rayq_embree_<policy>  rayq in Embree: rayq::embree::Scene (user geometry, Embree's BVH culls)
//                         with rayq's full hit record; _shading: point and normal (below);
//                         _nearest: t and primID only (Scene::nearest)
//   rayq_scene_<policy>   rayq's compile-time scene rayq::Scene<rayq::Sphere<float>> (or
//                         Cylinder<float>): brute force with the SIMD sphere filter (N <= 1,000)
//   rayq_loop_<policy>    the plain scalar loop: rayq::intersect over a std::vector (N <= 16)
//   ..._shading           the same with HitFields::point | normal: the record Embree's native
//                         hits give, without rayq's certified bounds
// Counters: rays_per_second, hits (fraction of rays that hit: equal across variants up to the
// shapes' differences), build_seconds (BVH build or scene set-up, once per benchmark, excluded
// from the timing). Every variant builds its hit record (Embree: tfar, Ng; rayq: the full Hit, or
// for _shading point and normal).
//
// FTZ/DAZ are set for the whole run, as Embree recommends (--ftz=0: off); the rayq adapter switches them off
// for each query (rayq's certified arithmetic needs gradual underflow), which it pays for, and
// the rayq_scene and rayq_loop variants run with them off, as rayq's users must (with DAZ on, the
// certified bounds do not hold; it also hides what subnormal operands cost: see grow() in
// detail/bounded.hpp).
//
// --accuracy_json=FILE (optional) also writes the accuracy side of the Pareto plot: unit spheres
// 10⁴ away, float rays within |δ| ≤ 10⁻⁴ of tangency, hit/miss of Embree's native sphere and of
// rayq's fast/stable (scalar and in Embree) against rayq::accurate (exact on the same float
// inputs), plus the t error of agreeing hits in ulps. The same numbers go into the benchmark
// JSON's context (accuracy.*).
//
// --answers_in=FILE --answers_out=FILE (optional) answer given cases with Embree's native sphere,
// for rayq-validate's speed campaign, which measures the answers against the exact oracle on the
// oracle campaign's own float sphere cases (write_answers below has the format).
//
// --rounds=N (optional, N >= 2) runs the selected benchmarks N times ("rounds", one repetition
// each; add --benchmark_enable_random_interleaving=true to shuffle them within a round) and prints,
// per benchmark, the median time and the median and range of its ratio to Embree's native row of
// the same scene in the same round (rays/s over rays/s: sphere/embree_points/N, or
// cylinder/embree_cone_curve/N; select that row too). This machine's slow phases last from seconds
// to minutes and hurt some rows more than others (README, session 47), so a ratio of two rows
// measured minutes apart, as medians of repetitions may be, can move by 30%; ratios taken round by
// round, then their median, are what the issue-7 table reports.
#include <benchmark/benchmark.h>
#include <rayq/embree.hpp>
#include <rayq/rayq.hpp>
#include <rayq/scene.hpp>

#include <embree3/rtcore.h>
#include <pmmintrin.h>
#include <xmmintrin.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <functional>
#include <map>
#include <memory>
#include <random>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

// 65,536 distinct rays per iteration, not a few thousand: the same 4,096 rays every iteration let
// the branch predictor learn their outcomes (which rays hit, which lane), and a branch-free
// candidate index then looked slower than a loop that the predictor ran ahead of. Measured
// (-march=native, medians, µs per 4,096 rays, 16 float spheres, Embree / rayq `fast` with point
// and normal): 4,096 rays repeated 258 / 48; 65,536 rays 324 / 67; 2^20 rays 333–340 / 71–74. New
// rays are what a renderer traces.
constexpr std::size_t kRays = 1 << 16;
constexpr int kRings = 10, kSegments = 10;  // UV-sphere tessellation: 2·10 + 2·10·8 = 180 triangles

using Sphere = rayq::Sphere<float>;
using Cylinder = rayq::Cylinder<float>;
using Ray = rayq::Ray<float>;

// The scenes and rays of rayq-bench-scene (same seeds, same distributions).
std::vector<Sphere> spheres(std::size_t n)
{
    std::mt19937_64 rng(0x5CE4E000 + n);
    std::uniform_real_distribution<double> u(-1, 1);
    const double r = 0.25 / std::cbrt(double(n));
    std::vector<Sphere> out;
    for (std::size_t i = 0; i < n; ++i) {
        const rayq::Vec3<float> c{float(u(rng)), float(u(rng)), float(u(rng))};
        out.push_back({c, float(r * (0.5 + 0.5 * (u(rng) + 1)))});
    }
    return out;
}

std::vector<Cylinder> cylinders(std::size_t n)
{
    std::mt19937_64 rng(0x5CE4E000 + n);
    std::uniform_real_distribution<double> u(-1, 1);
    std::normal_distribution<double> g;
    const double r = 0.25 / std::cbrt(double(n));
    std::vector<Cylinder> out;
    for (std::size_t i = 0; i < n; ++i) {
        const rayq::Vec3<float> c{float(u(rng)), float(u(rng)), float(u(rng))};
        const rayq::Vec3<float> axis{float(g(rng)), float(g(rng)), float(g(rng))};
        out.push_back(Cylinder::from_center(c, axis, float(r), float(r), rayq::Caps::both));
    }
    return out;
}

std::vector<Ray> rays()
{
    std::mt19937_64 rng(0xA11CE);
    std::uniform_real_distribution<double> u(-1, 1);
    std::normal_distribution<double> g;
    std::vector<Ray> out;
    for (std::size_t i = 0; i < kRays; ++i) {
        rayq::Vec3<double> o{g(rng), g(rng), g(rng)};
        o = o * (4.0 / rayq::length(o));
        const rayq::Vec3<double> target{u(rng), u(rng), u(rng)}, d = rayq::normalize(target - o);
        out.push_back({{float(o.x), float(o.y), float(o.z)}, {float(d.x), float(d.y), float(d.z)}});
    }
    return out;
}

RTCRayHit embree_ray(const Ray& r)
{
    RTCRayHit rh;
    rh.ray.org_x = r.origin.x, rh.ray.org_y = r.origin.y, rh.ray.org_z = r.origin.z;
    rh.ray.dir_x = r.direction.x, rh.ray.dir_y = r.direction.y, rh.ray.dir_z = r.direction.z;
    rh.ray.tnear = r.tmin, rh.ray.tfar = r.tmax, rh.ray.time = 0;
    rh.ray.mask = ~0u;  // Debian's Embree has ray masks on: 0 would hit nothing
    rh.ray.id = 0, rh.ray.flags = 0;
    rh.hit.geomID = rh.hit.primID = rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    return rh;
}

// One Embree device for the native variants, one thread (also for the BVH build).
RTCDevice device()
{
    static RTCDevice d = [] {
        RTCDevice dev = rtcNewDevice("threads=1");
        if (!dev) throw std::runtime_error("rtcNewDevice failed");
        return dev;
    }();
    return d;
}

struct NativeScene {
    RTCScene scene = rtcNewScene(device());
    NativeScene() = default;
    NativeScene(const NativeScene&) = delete;
    NativeScene& operator=(const NativeScene&) = delete;
    ~NativeScene() { rtcReleaseScene(scene); }
    void add(RTCGeometry g)
    {
        rtcCommitGeometry(g);
        rtcAttachGeometry(scene, g);
        rtcReleaseGeometry(g);
    }
    void commit()
    {
        rtcCommitScene(scene);
        if (rtcGetDeviceError(device()) != RTC_ERROR_NONE) throw std::runtime_error("Embree: building the scene failed");
    }
};

// Vertex buffers get one spare float past the end: Embree may read 16 bytes at the last FLOAT3.
std::unique_ptr<NativeScene> native_points(const std::vector<Sphere>& prims)
{
    auto s = std::make_unique<NativeScene>();
    RTCGeometry g = rtcNewGeometry(device(), RTC_GEOMETRY_TYPE_SPHERE_POINT);
    auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT4, 4 * sizeof(float), prims.size()));
    for (const Sphere& p : prims) *v++ = p.center.x, *v++ = p.center.y, *v++ = p.center.z, *v++ = p.radius;
    s->add(g);
    s->commit();
    return s;
}

std::unique_ptr<NativeScene> native_mesh(const std::vector<Sphere>& prims)
{
    const std::size_t verts_per = 2 + std::size_t(kRings - 1) * kSegments, tris_per = 2 * std::size_t(kSegments) * (kRings - 1);
    auto s = std::make_unique<NativeScene>();
    RTCGeometry g = rtcNewGeometry(device(), RTC_GEOMETRY_TYPE_TRIANGLE);
    // One spare vertex at the end (Embree's 16-byte loads of FLOAT3 vertices).
    auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float),
                                                          prims.size() * verts_per + 1));
    auto* idx = static_cast<unsigned*>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned),
                                                               prims.size() * tris_per));
    const double pi = std::acos(-1.0);
    for (std::size_t k = 0; k < prims.size(); ++k) {
        const Sphere& p = prims[k];
        const unsigned base = static_cast<unsigned>(k * verts_per);
        const auto put = [&](double x, double y, double z) {
            *v++ = float(p.center.x + p.radius * x), *v++ = float(p.center.y + p.radius * y), *v++ = float(p.center.z + p.radius * z);
        };
        put(0, 0, 1);  // north pole: vertex 0
        for (int ring = 1; ring < kRings; ++ring)
            for (int seg = 0; seg < kSegments; ++seg) {
                const double th = pi * ring / kRings, ph = 2 * pi * seg / kSegments;
                put(std::sin(th) * std::cos(ph), std::sin(th) * std::sin(ph), std::cos(th));
            }
        put(0, 0, -1);  // south pole: vertex verts_per − 1
        const auto ring_vertex = [&](int ring, int seg) { return base + 1 + unsigned((ring - 1) * kSegments + (seg % kSegments)); };
        const unsigned south = base + unsigned(verts_per - 1);
        for (int seg = 0; seg < kSegments; ++seg) {
            *idx++ = base, *idx++ = ring_vertex(1, seg), *idx++ = ring_vertex(1, seg + 1);
            *idx++ = south, *idx++ = ring_vertex(kRings - 1, seg + 1), *idx++ = ring_vertex(kRings - 1, seg);
            for (int ring = 1; ring < kRings - 1; ++ring) {
                const unsigned a = ring_vertex(ring, seg), b = ring_vertex(ring, seg + 1), c = ring_vertex(ring + 1, seg),
                               d = ring_vertex(ring + 1, seg + 1);
                *idx++ = a, *idx++ = c, *idx++ = b;
                *idx++ = b, *idx++ = c, *idx++ = d;
            }
        }
    }
    *v++ = 0, *v++ = 0, *v++ = 0;
    s->add(g);
    s->commit();
    return s;
}

std::unique_ptr<NativeScene> native_curves(const std::vector<Cylinder>& prims, RTCGeometryType type)
{
    auto s = std::make_unique<NativeScene>();
    RTCGeometry g = rtcNewGeometry(device(), type);
    auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT4, 4 * sizeof(float), 2 * prims.size()));
    auto* idx = static_cast<unsigned*>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT, sizeof(unsigned), prims.size()));
    for (std::size_t k = 0; k < prims.size(); ++k) {
        const Cylinder& c = prims[k];
        *v++ = c.p0.x, *v++ = c.p0.y, *v++ = c.p0.z, *v++ = c.radius;
        *v++ = c.p1.x, *v++ = c.p1.y, *v++ = c.p1.z, *v++ = c.radius;
        idx[k] = static_cast<unsigned>(2 * k);  // segment k: vertices 2k, 2k + 1 (no neighbours: both ends capped)
    }
    s->add(g);
    s->commit();
    return s;
}

// The last scene built, kept across a benchmark's repetitions (which run back to back), so the
// 100,000-primitive BVHs are built once; build_seconds is that build's time.
struct Cache {
    std::string key;
    std::shared_ptr<void> value;
    double build_seconds = 0;
};

template <class Built>
Built& cached(const std::string& key, const std::function<std::shared_ptr<Built>()>& make, double& build_seconds)
{
    static Cache cache;
    if (cache.key != key) {
        cache.value.reset();  // free the previous scene before building the next
        const auto t0 = std::chrono::steady_clock::now();
        cache.value = make();
        cache.build_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        cache.key = key;
    }
    build_seconds = cache.build_seconds;
    return *static_cast<Built*>(cache.value.get());
}

const std::vector<Ray>& the_rays()
{
    static const std::vector<Ray> r = rays();
    return r;
}

void finish(benchmark::State& state, std::size_t hits, double build_seconds)
{
    state.counters["rays_per_second"] = benchmark::Counter(double(kRays), benchmark::Counter::kIsIterationInvariantRate);
    state.counters["hits"] = double(hits) / double(kRays);
    state.counters["build_seconds"] = build_seconds;
    state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * kRays));
}

// Embree user geometry whose callback is the textbook float sphere test (no rayq), on the rayq
// adapter's boxes and leaf size: what Embree's callbacks and object BVH cost by themselves, the
// floor under any user-geometry adapter (rayq_embree_* against it: what rayq's decisions add).
struct PlainUserSpheres {
    RTCDevice device = nullptr;
    RTCScene scene = nullptr;
    std::vector<Sphere> spheres;
    std::vector<RTCBounds> boxes;

    explicit PlainUserSpheres(const std::vector<Sphere>& prims) : spheres(prims)
    {
        for (const Sphere& p : spheres) boxes.push_back(rayq::embree::embree_bounds<rayq::stable_policy>(p, 0));
        const std::string config = "threads=1,object_accel_max_leaf_size=" + std::to_string(rayq::embree::automatic_max_leaf_size(prims.size()));
        device = rtcNewDevice(config.c_str());
        if (!device) throw std::runtime_error("rtcNewDevice failed");
        scene = rtcNewScene(device);
        RTCGeometry g = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_USER);
        rtcSetGeometryUserPrimitiveCount(g, static_cast<unsigned>(spheres.size()));
        rtcSetGeometryUserData(g, this);
        rtcSetGeometryBoundsFunction(g, [](const RTCBoundsFunctionArguments* a) {
            *a->bounds_o = static_cast<const PlainUserSpheres*>(a->geometryUserPtr)->boxes[a->primID];
        }, nullptr);
        rtcSetGeometryIntersectFunction(g, [](const RTCIntersectFunctionNArguments* a) {
            const Sphere& s = static_cast<const PlainUserSpheres*>(a->geometryUserPtr)->spheres[a->primID];
            RTCRayHit& rh = *reinterpret_cast<RTCRayHit*>(a->rayhit);
            const rayq::Vec3<float> o{rh.ray.org_x, rh.ray.org_y, rh.ray.org_z}, d{rh.ray.dir_x, rh.ray.dir_y, rh.ray.dir_z};
            const rayq::Vec3<float> u = o - s.center;
            const float a2 = rayq::dot(d, d), b = rayq::dot(u, d), disc = b * b - a2 * (rayq::dot(u, u) - s.radius * s.radius);
            if (!(disc >= 0)) return;
            const float root = std::sqrt(disc), t0 = (-b - root) / a2, t = t0 > rh.ray.tnear ? t0 : (-b + root) / a2;
            if (!(t > rh.ray.tnear && t < rh.ray.tfar)) return;
            const rayq::Vec3<float> n = u + t * d;
            rh.ray.tfar = t;
            rh.hit.Ng_x = n.x, rh.hit.Ng_y = n.y, rh.hit.Ng_z = n.z;
            rh.hit.u = rh.hit.v = 0;
            rh.hit.primID = a->primID, rh.hit.geomID = a->geomID, rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
        });
        rtcCommitGeometry(g);
        rtcAttachGeometry(scene, g);
        rtcReleaseGeometry(g);
        rtcCommitScene(scene);
        if (rtcGetDeviceError(device) != RTC_ERROR_NONE) throw std::runtime_error("Embree: building the scene failed");
    }
    PlainUserSpheres(const PlainUserSpheres&) = delete;
    PlainUserSpheres& operator=(const PlainUserSpheres&) = delete;
    ~PlainUserSpheres()
    {
        rtcReleaseScene(scene);
        rtcReleaseDevice(device);
    }
};

// Embree's native spheres with rayq deciding each candidate in an intersection filter (row
// embree_points_rayq_filter): the design proposed in session 47 instead of user geometry, measured
// in session 48 and not adopted (README). Embree tests a radius padded by r·2⁻¹⁰ + 10⁻⁵, ample for
// these rays but with no proof that Embree's float sphere test on it never drops a hit rayq's
// policy finds (its source is not in Debian's package), so not exact in general. Each vertex holds
// rayq's own radius after Embree's four floats (a 32-byte stride: the cache line Embree has just
// read; read from a separate array, the filter paid a cache miss per call and ran at 0.83× Embree
// against 0.92× this way). The filter decides with rayq's `stable` crossing on the query's ray in
// (tmin, best t so far) and writes rayq's t into the ray's tfar, which Embree keeps once the hit is
// accepted (the final tfar and primID equal rayq's: the counter "disagree" checks it). A rejected
// first candidate may be presented again as the sphere's far root: rejected again, as it must be.
struct FilteredPoints {
    static constexpr int stride = 8;  // floats per vertex: x, y, z, Embree's radius, rayq's radius
    NativeScene native;
    RTCScene scene = native.scene;
    const float* vertices = nullptr;

    // The query, found again from the context Embree hands the filter (its first member).
    struct Query {
        RTCIntersectContext embree;
        Ray ray;
        float best_t;
        unsigned prim;
        unsigned calls;
    };

    explicit FilteredPoints(const std::vector<Sphere>& prims)
    {
        RTCGeometry g = rtcNewGeometry(device(), RTC_GEOMETRY_TYPE_SPHERE_POINT);
        auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT4, stride * sizeof(float), prims.size()));
        vertices = v;
        for (const Sphere& p : prims) {
            v[0] = p.center.x, v[1] = p.center.y, v[2] = p.center.z, v[3] = p.radius * (1 + 0x1p-10f) + 1e-5f, v[4] = p.radius;
            v += stride;
        }
        rtcSetGeometryUserData(g, this);
        rtcSetGeometryIntersectFilterFunction(g, &FilteredPoints::filter);
        native.add(g);
        native.commit();
    }

    static void filter(const RTCFilterFunctionNArguments* a)
    {
        const auto* self = static_cast<const FilteredPoints*>(a->geometryUserPtr);
        auto* q = reinterpret_cast<Query*>(const_cast<RTCIntersectContext*>(a->context));
        const unsigned prim = RTCHitN_primID(a->hit, a->N, 0);
        ++q->calls;
        const float* e = self->vertices + std::size_t(stride) * prim;
        const Sphere s{{e[0], e[1], e[2]}, e[4]};
        const Ray window{q->ray.origin, q->ray.direction, q->ray.tmin, q->best_t};
        const auto cs = rayq::detail::leading_crossings(rayq::stable, window, s);
        const rayq::Crossing<float>* c = rayq::detail::first_in_window(window, cs);
        if (!c) {
            a->valid[0] = 0;
            return;
        }
        q->best_t = c->t;
        q->prim = prim;
        RTCRayN_tfar(a->ray, a->N, 0) = c->t;
    }
};

void run_filtered_points(benchmark::State& state, const std::string& key, const std::vector<Sphere>& prims)
{
    double build = 0;
    const FilteredPoints& scene = cached<FilteredPoints>(key, [&] { return std::make_shared<FilteredPoints>(prims); }, build);
    const rayq::embree::detail::IeeeArithmetic ieee;  // rayq decides in the filter (header)
    std::size_t hits = 0, disagree = 0, calls = 0;
    for (auto _ : state) {
        hits = disagree = calls = 0;
        for (const Ray& r : the_rays()) {
            FilteredPoints::Query q{{}, r, r.tmax, RTC_INVALID_GEOMETRY_ID, 0};
            rtcInitIntersectContext(&q.embree);
            RTCRayHit rh = embree_ray(r);
            rtcIntersect1(scene.scene, &q.embree, &rh);
            const bool hit = rh.hit.geomID != RTC_INVALID_GEOMETRY_ID;
            hits += hit;
            disagree += hit != (q.prim != RTC_INVALID_GEOMETRY_ID) || (hit && (rh.ray.tfar != q.best_t || rh.hit.primID != q.prim));
            calls += q.calls;
            benchmark::DoNotOptimize(rh);
        }
    }
    state.counters["disagree"] = double(disagree);
    state.counters["filter_calls"] = double(calls) / double(the_rays().size());
    finish(state, hits, build);
}

// make: returns a std::shared_ptr to a NativeScene, or to anything else with an Embree `scene`.
template <class Make>
void run_native(benchmark::State& state, const std::string& key, const Make& make)
{
    using Built = typename decltype(make())::element_type;
    double build = 0;
    Built& scene = cached<Built>(key, make, build);
    RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    std::size_t hits = 0;
    for (auto _ : state) {
        hits = 0;
        for (const Ray& r : the_rays()) {
            RTCRayHit rh = embree_ray(r);
            rtcIntersect1(scene.scene, &ctx, &rh);
            hits += rh.hit.geomID != RTC_INVALID_GEOMETRY_ID;
            benchmark::DoNotOptimize(rh);
        }
    }
    finish(state, hits, build);
}

template <class Prim, class Policy>
void run_adapter(benchmark::State& state, const std::string& key, const std::vector<Prim>& prims, Policy policy, bool record = true,
                 rayq::HitFields fields = rayq::HitFields::all)
{
    using Adapter = rayq::embree::Scene<Prim, Policy>;
    double build = 0;
    const Adapter& scene = cached<Adapter>(key, [&] {
        rayq::embree::Options options;
        options.device_config = "threads=1";
        return std::make_shared<Adapter>(prims, policy, options);
    }, build);
    std::size_t hits = 0;
    for (auto _ : state) {
        hits = 0;
        if (record) {
            for (const Ray& r : the_rays()) {
                const auto h = scene.intersect(r, fields);
                hits += h.has_value();
                benchmark::DoNotOptimize(h);
            }
        } else {
            for (const Ray& r : the_rays()) {
                const auto h = scene.nearest(r);
                hits += h.has_value();
                benchmark::DoNotOptimize(h);
            }
        }
    }
    finish(state, hits, scene.build_seconds());
    (void)build;
}

template <class Prim, class Policy>
void run_scene(benchmark::State& state, const std::string& key, const std::vector<Prim>& prims, Policy policy,
               rayq::HitFields fields = rayq::HitFields::all)
{
    using CompileTime = rayq::Scene<Prim>;
    double build = 0;
    const CompileTime& scene = cached<CompileTime>(key, [&] {
        auto s = std::make_shared<CompileTime>();
        for (const Prim& p : prims) s->add(p);
        return s;
    }, build);
    const rayq::embree::detail::IeeeArithmetic ieee;  // the mode rayq requires (header)
    std::size_t hits = 0;
    for (auto _ : state) {
        hits = 0;
        for (const Ray& r : the_rays()) {
            const auto h = rayq::intersect(policy, r, scene, fields);
            hits += h.has_value();
            benchmark::DoNotOptimize(h);
        }
    }
    finish(state, hits, build);
}

// The plain scalar loop: rayq::intersect over the array, the nearest kept (first of equal t).
template <class Prim, class Policy>
void run_loop(benchmark::State& state, const std::vector<Prim>& prims, Policy policy, rayq::HitFields fields = rayq::HitFields::all)
{
    const rayq::embree::detail::IeeeArithmetic ieee;
    std::size_t hits = 0;
    for (auto _ : state) {
        hits = 0;
        for (const Ray& r : the_rays()) {
            std::optional<rayq::Hit<float>> best;
            for (const Prim& p : prims)
                if (auto h = rayq::intersect(policy, r, p, fields); h && (!best || h->t < best->t)) best = h;
            hits += best.has_value();
            benchmark::DoNotOptimize(best);
        }
    }
    finish(state, hits, 0);
}

template <class Policy>
const char* policy_name(Policy)
{
    return std::is_same_v<Policy, rayq::fast_policy> ? "fast" : std::is_same_v<Policy, rayq::stable_policy> ? "stable" : "accurate";
}

void reg(const std::string& name, std::function<void(benchmark::State&)> fn)
{
    benchmark::RegisterBenchmark(name.c_str(), [name, fn](benchmark::State& st) { fn(st); })->Unit(benchmark::kMillisecond);
}

// A scene asked for the record Embree's native hits give (point and normal, no certified
// bounds): rayq_scene_<policy>_shading.
template <class Prim, class Policy>
void shading_scene(Policy policy, const char* prim, const std::shared_ptr<std::vector<Prim>>& prims, const std::string& tail)
{
    const std::string name = std::string(prim) + "/rayq_scene_" + policy_name(policy) + "_shading" + tail;
    reg(name, [=](benchmark::State& st) { run_scene(st, name, *prims, policy, rayq::HitFields::point | rayq::HitFields::normal); });
}

void register_all()
{
    for (std::size_t n : {std::size_t(1), std::size_t(16), std::size_t(1000), std::size_t(100000)}) {
        const std::string tail = "/" + std::to_string(n);
        const auto prims = std::make_shared<std::vector<Sphere>>(spheres(n));
        reg("sphere/embree_points" + tail, [=](benchmark::State& st) {
            run_native(st, "points" + tail, [=] { return std::shared_ptr<NativeScene>(native_points(*prims)); });
        });
        reg("sphere/embree_mesh" + tail, [=](benchmark::State& st) {
            run_native(st, "mesh" + tail, [=] { return std::shared_ptr<NativeScene>(native_mesh(*prims)); });
        });
        reg("sphere/embree_points_rayq_filter" + tail,
            [=](benchmark::State& st) { run_filtered_points(st, "points_rayq_filter" + tail, *prims); });
        reg("sphere/embree_user_plain" + tail, [=](benchmark::State& st) {
            run_native(st, "user_plain" + tail, [=] { return std::make_shared<PlainUserSpheres>(*prims); });
        });
        const auto adapter = [&](auto policy) {
            const std::string name = std::string("sphere/rayq_embree_") + policy_name(policy) + tail;
            reg(name, [=](benchmark::State& st) { run_adapter(st, name, *prims, policy); });
        };
        adapter(rayq::stable), adapter(rayq::accurate);
        // Point and normal, no certified bounds: the record Embree's native hits give.
        const std::string shading_name = "sphere/rayq_embree_stable_shading" + tail;
        reg(shading_name, [=](benchmark::State& st) {
            run_adapter(st, shading_name, *prims, rayq::stable, true, rayq::HitFields::point | rayq::HitFields::normal);
        });
        // t and primID only (no normal, no certified bound).
        const std::string nearest_name = "sphere/rayq_embree_stable_nearest" + tail;
        reg(nearest_name, [=](benchmark::State& st) { run_adapter(st, nearest_name, *prims, rayq::stable, false); });
        if (n <= 1000) {
            const auto scene = [&](auto policy) {
                const std::string name = std::string("sphere/rayq_scene_") + policy_name(policy) + tail;
                reg(name, [=](benchmark::State& st) { run_scene(st, name, *prims, policy); });
            };
            scene(rayq::fast), scene(rayq::stable), scene(rayq::accurate);
            shading_scene(rayq::fast, "sphere", prims, tail), shading_scene(rayq::stable, "sphere", prims, tail);
        }
        if (n <= 16) {
            const auto loop = [&](auto policy) {
                reg(std::string("sphere/rayq_loop_") + policy_name(policy) + tail, [=](benchmark::State& st) { run_loop(st, *prims, policy); });
            };
            loop(rayq::fast), loop(rayq::stable), loop(rayq::accurate);
            reg("sphere/rayq_loop_fast_shading" + tail,
                [=](benchmark::State& st) { run_loop(st, *prims, rayq::fast, rayq::HitFields::point | rayq::HitFields::normal); });
        }
    }
    for (std::size_t n : {std::size_t(1), std::size_t(16)}) {
        const std::string tail = "/" + std::to_string(n);
        const auto prims = std::make_shared<std::vector<Cylinder>>(cylinders(n));
        reg("cylinder/embree_cone_curve" + tail, [=](benchmark::State& st) {
            run_native(st, "cone" + tail, [=] { return std::shared_ptr<NativeScene>(native_curves(*prims, RTC_GEOMETRY_TYPE_CONE_LINEAR_CURVE)); });
        });
        reg("cylinder/embree_round_curve" + tail, [=](benchmark::State& st) {
            run_native(st, "round" + tail, [=] { return std::shared_ptr<NativeScene>(native_curves(*prims, RTC_GEOMETRY_TYPE_ROUND_LINEAR_CURVE)); });
        });
        const auto adapter = [&](auto policy) {
            const std::string name = std::string("cylinder/rayq_embree_") + policy_name(policy) + tail;
            reg(name, [=](benchmark::State& st) { run_adapter(st, name, *prims, policy); });
        };
        adapter(rayq::stable), adapter(rayq::accurate);
        const auto scene = [&](auto policy) {
            const std::string name = std::string("cylinder/rayq_scene_") + policy_name(policy) + tail;
            reg(name, [=](benchmark::State& st) { run_scene(st, name, *prims, policy); });
        };
        scene(rayq::fast), scene(rayq::stable), scene(rayq::accurate);
        shading_scene(rayq::fast, "cylinder", prims, tail), shading_scene(rayq::stable, "cylinder", prims, tail);
        const auto loop = [&](auto policy) {
            reg(std::string("cylinder/rayq_loop_") + policy_name(policy) + tail, [=](benchmark::State& st) { run_loop(st, *prims, policy); });
        };
        loop(rayq::fast), loop(rayq::stable), loop(rayq::accurate);
    }
}

// ---- accuracy: far-away near-tangent rays, hit/miss against rayq::accurate ----

struct Verdicts {
    std::string variant;
    std::size_t true_hits = 0, true_misses = 0, missed = 0, spurious = 0, agreeing_hits = 0;
    double max_ulps = 0;  // |t − t_accurate| in ulps of t_accurate, over hits both report
    double ns_per_ray = 0;  // the variant's answers for all cases, timed once (wall clock)
    std::vector<double> ulps;
};

double ulps_between(float a, float b)
{
    const double ulp = std::nextafter(std::abs(b), INFINITY) - std::abs(b);
    return std::abs(double(a) - double(b)) / ulp;
}

std::string accuracy_json(std::size_t cases, std::uint64_t seed, bool offset_origins)
{
    // A unit sphere at distance 10⁴ in a random direction; a ray from the origin aimed at
    // c + (1 + δ)·r·p̂ (p̂ ⟂ the line of sight), δ uniform in [−10⁻⁴, 10⁻⁴]: half graze inside, half
    // outside, all within float's resolution of tangency at that distance. Rounded to float; the
    // exact answer for those float inputs is rayq::accurate's.
    std::mt19937_64 rng(seed);
    std::normal_distribution<double> g;
    std::uniform_real_distribution<double> delta(-1e-4, 1e-4);
    std::vector<Sphere> prims;
    std::vector<Ray> rays_;
    std::uniform_real_distribution<double> u(-1, 1);
    for (std::size_t i = 0; i < cases; ++i) {
        const rayq::Vec3<double> origin = offset_origins ? rayq::Vec3<double>{u(rng), u(rng), u(rng)} : rayq::Vec3<double>{0, 0, 0};
        const rayq::Vec3<double> dir = rayq::normalize(rayq::Vec3<double>{g(rng), g(rng), g(rng)});
        const rayq::Vec3<double> c = origin + dir * 1e4;
        const rayq::Vec3<double> p = rayq::normalize(rayq::cross(dir, rayq::Vec3<double>{g(rng), g(rng), g(rng)}));
        const rayq::Vec3<double> aim = c + p * (1.0 + delta(rng));
        const rayq::Vec3<double> d = rayq::normalize(aim - origin);
        prims.push_back({{float(c.x), float(c.y), float(c.z)}, 1.0f});
        rays_.push_back({{float(origin.x), float(origin.y), float(origin.z)}, {float(d.x), float(d.y), float(d.z)}});
    }
    // Every variant answers on the same window around its own sphere, so no other sphere of the
    // family (10⁴ away in other directions) can interfere; rayq's answers then equal the adapter's.
    const auto window = [&](std::size_t i) {
        Ray r = rays_[i];
        r.tmin = 1e4f - 2, r.tmax = 1e4f + 2;
        return r;
    };
    std::vector<Verdicts> out;
    std::vector<std::optional<rayq::Hit<float>>> exact(cases);
    for (std::size_t i = 0; i < cases; ++i) exact[i] = rayq::intersect(rayq::accurate, window(i), prims[i]);
    const auto judge = [&](const std::string& name, const std::function<std::optional<float>(std::size_t)>& t_of) {
        Verdicts v;
        v.variant = name;
        std::vector<std::optional<float>> answers(cases);
        const auto t0 = std::chrono::steady_clock::now();
        for (std::size_t i = 0; i < cases; ++i) answers[i] = t_of(i);
        v.ns_per_ray = std::chrono::duration<double, std::nano>(std::chrono::steady_clock::now() - t0).count() / double(cases);
        for (std::size_t i = 0; i < cases; ++i) {
            const std::optional<float>& t = answers[i];
            exact[i] ? ++v.true_hits : ++v.true_misses;
            if (exact[i] && !t) ++v.missed;
            if (!exact[i] && t) ++v.spurious;
            if (exact[i] && t) {
                ++v.agreeing_hits;
                v.ulps.push_back(ulps_between(*t, exact[i]->t));
                v.max_ulps = std::max(v.max_ulps, v.ulps.back());
            }
        }
        out.push_back(std::move(v));
    };
    // Embree's native sphere: one scene per case would be slow to build; all spheres in one
    // scene, each ray's window limited to its own sphere's neighbourhood (|c| ± 2) so no other
    // sphere can answer (they are 10⁴ away in other directions... or closer: check the primID).
    {
        auto scene = native_points(prims);
        RTCIntersectContext ctx;
        rtcInitIntersectContext(&ctx);
        judge("embree_points", [&](std::size_t i) -> std::optional<float> {
            const Ray r = window(i);
            RTCRayHit rh = embree_ray(r);
            rtcIntersect1(scene->scene, &ctx, &rh);
            if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return std::nullopt;
            if (rh.hit.primID != i) {  // another sphere in the window: ask this one alone
                auto alone = native_points({prims[i]});
                RTCRayHit again = embree_ray(r);
                rtcIntersect1(alone->scene, &ctx, &again);
                return again.hit.geomID == RTC_INVALID_GEOMETRY_ID ? std::nullopt : std::optional<float>(again.ray.tfar);
            }
            return rh.ray.tfar;
        });
    }
    const auto scalar = [&](auto policy) {
        judge(std::string("rayq_") + policy_name(policy), [&](std::size_t i) -> std::optional<float> {
            const auto h = rayq::intersect(policy, window(i), prims[i]);
            return h ? std::optional<float>(h->t) : std::nullopt;
        });
    };
    scalar(rayq::fast), scalar(rayq::stable), scalar(rayq::accurate);
    const auto in_embree = [&](auto policy) {
        rayq::embree::Options options;
        options.device_config = "threads=1";
        const rayq::embree::Scene<Sphere, decltype(policy)> scene(prims, policy, options);
        judge(std::string("rayq_embree_") + policy_name(policy), [&](std::size_t i) -> std::optional<float> {
            const Ray r = window(i);
            const auto h = scene.intersect(r);
            if (!h) return std::nullopt;
            if (h->primID != i) {
                const auto alone = rayq::intersect(policy, r, prims[i]);
                return alone ? std::optional<float>(alone->t) : std::nullopt;
            }
            return h->hit.t;
        });
    };
    in_embree(rayq::fast), in_embree(rayq::stable), in_embree(rayq::accurate);

    std::ostringstream js;
    js << "{\"family\": \"" << (offset_origins ? "far_near_tangent_sphere_offset_origin" : "far_near_tangent_sphere") << "\", \"distance\": 1e4, \"radius\": 1, \"max_abs_delta\": 1e-4, \"type\": \"float\", "
       << "\"cases\": " << cases << ", \"seed\": " << seed << ", \"reference\": \"rayq_accurate\", \"rows\": [";
    for (std::size_t k = 0; k < out.size(); ++k) {
        Verdicts& v = out[k];
        std::sort(v.ulps.begin(), v.ulps.end());
        const double p99 = v.ulps.empty() ? 0 : v.ulps[std::min(v.ulps.size() - 1, std::size_t(0.99 * double(v.ulps.size())))];
        const double median = v.ulps.empty() ? 0 : v.ulps[v.ulps.size() / 2];
        js << (k ? ", " : "") << "{\"variant\": \"" << v.variant << "\", \"true_hits\": " << v.true_hits << ", \"true_misses\": " << v.true_misses
           << ", \"missed\": " << v.missed << ", \"spurious\": " << v.spurious
           << ", \"missed_fraction_of_true_hits\": " << (v.true_hits ? double(v.missed) / double(v.true_hits) : 0)
           << ", \"spurious_fraction_of_true_misses\": " << (v.true_misses ? double(v.spurious) / double(v.true_misses) : 0)
           << ", \"wrong_fraction_of_rays\": " << double(v.missed + v.spurious) / double(cases)
           << ", \"ns_per_ray\": " << v.ns_per_ray << ", \"t_ulps_median\": " << median << ", \"t_ulps_p99\": " << p99 << ", \"t_ulps_max\": " << v.max_ulps << "}";
    }
    js << "]}";
    return js.str();
}

// ---- answers: Embree's native sphere on cases given in a file ----

// Input: one case per line, 12 numbers, each exactly a float, as C99 hex literals (printf %a) or
// inf/-inf: origin.xyz direction.xyz tmin tmax center.xyz radius. Output: one line per case, "miss"
// or "hit t Ng.x Ng.y Ng.z" (%a; Ng as Embree returns it: not normalized, outward). Each case is
// answered by a scene holding its sphere alone, in the run's floating-point mode (FTZ/DAZ as set
// for the benchmarks). Throws on an unreadable or malformed file.
void write_answers(const std::string& in_path, const std::string& out_path)
{
    std::ifstream in(in_path);
    if (!in) throw std::runtime_error("cannot read " + in_path);
    std::ofstream out(out_path);
    NativeScene scene;
    RTCGeometry g = rtcNewGeometry(device(), RTC_GEOMETRY_TYPE_SPHERE_POINT);
    auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT4, 4 * sizeof(float), 1));
    rtcCommitGeometry(g);
    rtcAttachGeometry(scene.scene, g);
    RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    std::size_t line_number = 0;
    for (std::string line; std::getline(in, line);) {
        ++line_number;
        std::istringstream words(line);
        float x[12];
        for (float& f : x) {
            std::string w;
            char* end = nullptr;
            if (words >> w) f = std::strtof(w.c_str(), &end);
            if (!end || *end != 0) throw std::runtime_error(in_path + ":" + std::to_string(line_number) + ": expected 12 numbers");
        }
        const Ray ray{{x[0], x[1], x[2]}, {x[3], x[4], x[5]}, x[6], x[7]};
        v[0] = x[8], v[1] = x[9], v[2] = x[10], v[3] = x[11];
        rtcUpdateGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0);
        rtcCommitGeometry(g);
        scene.commit();
        RTCRayHit rh = embree_ray(ray);
        rtcIntersect1(scene.scene, &ctx, &rh);
        char buf[160] = "miss";
        if (rh.hit.geomID != RTC_INVALID_GEOMETRY_ID)
            std::snprintf(buf, sizeof buf, "hit %a %a %a %a", double(rh.ray.tfar), double(rh.hit.Ng_x), double(rh.hit.Ng_y), double(rh.hit.Ng_z));
        out << buf << "\n";
    }
    rtcReleaseGeometry(g);
    out.close();
    if (!out) throw std::runtime_error("cannot write " + out_path);
}

// --rounds: collects each round's times (ms per iteration over kRays rays), printing nothing.
class RoundCollector : public benchmark::BenchmarkReporter {
public:
    std::map<std::string, std::vector<double>> ms;  // benchmark -> one time per round

    bool ReportContext(const Context&) override { return true; }
    void ReportRuns(const std::vector<Run>& runs) override
    {
        for (const Run& r : runs)
            if (r.run_type == Run::RT_Iteration && !r.error_occurred)
                ms[r.benchmark_name()].push_back(r.GetAdjustedRealTime() * benchmark::GetTimeUnitMultiplier(benchmark::kMillisecond) /
                                                 benchmark::GetTimeUnitMultiplier(r.time_unit));
    }
};

double median(std::vector<double> v)
{
    std::sort(v.begin(), v.end());
    const std::size_t m = v.size() / 2;
    return v.size() % 2 ? v[m] : (v[m - 1] + v[m]) / 2;
}

// Embree's native row of the scene `name` (<prim>/<variant>/<N>) belongs to, or "" for none.
std::string embree_row_of(const std::string& name)
{
    const auto first = name.find('/'), last = name.rfind('/');
    if (first == std::string::npos || last == first) return "";
    const std::string prim = name.substr(0, first);
    const char* native = prim == "sphere" ? "embree_points" : prim == "cylinder" ? "embree_cone_curve" : nullptr;
    return native ? prim + "/" + native + name.substr(last) : "";
}

int run_rounds(int rounds)
{
    RoundCollector collect;
    for (int r = 0; r < rounds; ++r) benchmark::RunSpecifiedBenchmarks(&collect);
    std::printf("%-48s %10s  %s\n", "benchmark", "median ms", "over Embree's native row, same round: median [min-max]");
    for (const auto& [name, times] : collect.ms) {
        std::printf("%-48s %10.3f", name.c_str(), median(times));
        const auto ref = collect.ms.find(embree_row_of(name));
        if (ref != collect.ms.end() && ref->first != name && ref->second.size() == times.size()) {
            std::vector<double> ratio;
            for (std::size_t i = 0; i < times.size(); ++i) ratio.push_back(ref->second[i] / times[i]);
            std::printf("  %.3fx [%.3f-%.3f]", median(ratio), *std::min_element(ratio.begin(), ratio.end()),
                        *std::max_element(ratio.begin(), ratio.end()));
        }
        std::printf("\n");
    }
    std::printf("(%d rounds)\n", rounds);
    return 0;
}

}  // namespace

int main(int argc, char** argv)
{
    // Embree's recommendation for speed (DEPENDENCIES.md); the rayq adapter restores IEEE mode for
    // each query.
    // --ftz=0 leaves them off (to measure what the adapter's switching costs).
    bool ftz = true;
    std::string accuracy_out, answers_in, answers_out;
    std::size_t accuracy_cases = 20000;
    int rounds = 0;
    std::vector<char*> args;
    for (int i = 0; i < argc; ++i) {
        const std::string a = argv[i];
        if (a.rfind("--accuracy_json=", 0) == 0) accuracy_out = a.substr(16);
        else if (a.rfind("--accuracy_cases=", 0) == 0) accuracy_cases = std::stoul(a.substr(17));
        else if (a.rfind("--answers_in=", 0) == 0) answers_in = a.substr(13);
        else if (a.rfind("--answers_out=", 0) == 0) answers_out = a.substr(14);
        else if (a == "--ftz=0" || a == "--ftz=1") ftz = a == "--ftz=1";
        else if (a.rfind("--rounds=", 0) == 0) {
            char* end = nullptr;
            const long v = std::strtol(a.c_str() + 9, &end, 10);
            if (*end || v < 2 || v > 1000) {
                std::fprintf(stderr, "rayq-bench-embree: --rounds expects a whole number from 2 to 1000, got '%s'\n", a.c_str() + 9);
                return 2;
            }
            rounds = static_cast<int>(v);
        } else args.push_back(argv[i]);
    }
    if (ftz) {
        _MM_SET_FLUSH_ZERO_MODE(_MM_FLUSH_ZERO_ON);
        _MM_SET_DENORMALS_ZERO_MODE(_MM_DENORMALS_ZERO_ON);
    }
    benchmark::AddCustomContext("ftz_daz", ftz ? "on" : "off");
    int n = static_cast<int>(args.size());
    benchmark::Initialize(&n, args.data());
    if (benchmark::ReportUnrecognizedArguments(n, args.data())) return 2;
    if (answers_in.empty() != answers_out.empty()) {
        std::fprintf(stderr, "rayq-bench-embree: --answers_in and --answers_out go together\n");
        return 2;
    }
    if (!answers_in.empty()) {
        try {
            write_answers(answers_in, answers_out);
        } catch (const std::exception& e) {
            std::fprintf(stderr, "rayq-bench-embree: %s\n", e.what());
            return 2;
        }
    }
    if (!accuracy_out.empty()) {
        // Origins at 0 (o − c exact) and at random points of [-1, 1]³ (o − c rounded).
        const std::string js = "{\"tool\": \"rayq-bench-embree\", \"note\": \"ns_per_ray: one wall-clock pass over the cases, same process; "
                               "embree_* and rayq_embree_* include BVH traversal over the family's spheres (one scene)\", \"families\": [" +
                               accuracy_json(accuracy_cases, 0xFA4A, false) + ", " + accuracy_json(accuracy_cases, 0xFA4B, true) + "]}";
        std::ofstream(accuracy_out) << js << "\n";
        benchmark::AddCustomContext("accuracy_json", accuracy_out);
    }
    register_all();
    const int status = rounds > 0 ? run_rounds(rounds) : (benchmark::RunSpecifiedBenchmarks(), 0);
    benchmark::Shutdown();
    return status;
}
