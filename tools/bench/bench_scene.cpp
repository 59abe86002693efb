// rayq-bench-scene: the two batch patterns.
// One ray against N primitives (N = 1, 16, 1,024), the BVH-leaf pattern, for spheres (every
// policy), capped cylinders (stable: not filtered; accurate: the bounding-sphere filter), cones
// and triangles, float and double:
//   loop     the scalar intersect()/occluded() over an array, keeping the nearest hit;
//   scene    rayq::Scene<...> (compile-time type list, SIMD culling filters, one hit record);
//   variant  a runtime-dispatched scene: std::vector<std::variant<...>> + std::visit;
//   scene_long_d  spheres: the scene on rays whose directions are not unit (target − origin, length ~3–5).
// Names: <query>/<prim>/<type>/<policy>/<variant>/<N>. items_per_second is ray–primitive tests
// per second (rays × N); "hits" the fraction of rays that hit something. Rays start outside the
// scene's box and aim at random points inside it; primitives are random, ~1% of the box each.
// N rays against one primitive, the stream pattern: stream/<prim>/<type>/<policy>/<scalar|batch>/1
// (batch::intersect over a RayStream of the same 1,024 rays; items: ray–primitive tests).
#include <benchmark/benchmark.h>
#include <rayq/rayq.hpp>
#include <rayq/batch/bounding_sphere.hpp>
#include <rayq/scene.hpp>

#include <cmath>
#include <random>
#include <string>
#include <type_traits>
#include <variant>
#include <vector>

namespace {

constexpr std::size_t kRays = 16384;

template <class T> constexpr const char* type_name() { return sizeof(T) == 4 ? "float" : "double"; }
constexpr const char* policy_name(rayq::fast_policy) { return "fast"; }
constexpr const char* policy_name(rayq::stable_policy) { return "stable"; }
constexpr const char* policy_name(rayq::accurate_policy) { return "accurate"; }

template <class Prim>
struct Setup {
    using T = rayq::scalar_t<Prim>;
    std::vector<Prim> prims;
    std::vector<rayq::Ray<T>> rays;
};

template <class T>
rayq::Vec3<T> v3(std::mt19937_64& rng, std::normal_distribution<double>& g)
{
    return {T(g(rng)), T(g(rng)), T(g(rng))};
}

// A primitive of size ~r at c (spheres, capped cylinders and cones, triangles).
template <class T>
void make(rayq::Sphere<T>& s, const rayq::Vec3<T>& c, double r, std::mt19937_64& rng, std::normal_distribution<double>&)
{
    s = {c, T(r * (0.5 + 0.5 * std::uniform_real_distribution<double>(0, 2)(rng)))};
}
template <class T>
void make(rayq::Cylinder<T>& s, const rayq::Vec3<T>& c, double r, std::mt19937_64& rng, std::normal_distribution<double>& g)
{
    s = rayq::Cylinder<T>::from_center(c, v3<T>(rng, g), T(r), T(r), rayq::Caps::both);
}
template <class T>
void make(rayq::Cone<T>& s, const rayq::Vec3<T>& c, double r, std::mt19937_64& rng, std::normal_distribution<double>& g)
{
    const rayq::Vec3<T> half = rayq::normalize(v3<T>(rng, g)) * T(r);
    s = {c - half, T(r), c + half, T(r / 3), rayq::Caps::both};
}
template <class T>
void make(rayq::Triangle<T>& s, const rayq::Vec3<T>& c, double r, std::mt19937_64& rng, std::normal_distribution<double>& g)
{
    const auto corner = [&] { return c + rayq::normalize(v3<T>(rng, g)) * T(1.5 * r); };
    s = {corner(), corner(), corner()};
}

// N primitives in the cube [-1, 1]³ with size ~ N^(-1/3)/4 (so rays meet a few of them at every
// N), rays from a sphere of radius 4 at points of the cube.
template <class Prim>
Setup<Prim> setup(std::size_t n, bool long_directions = false)
{
    using T = rayq::scalar_t<Prim>;
    std::mt19937_64 rng(0x5CE4E000 + n);
    std::uniform_real_distribution<double> u(-1, 1);
    std::normal_distribution<double> g;
    Setup<Prim> s;
    const double r = 0.25 / std::cbrt(double(n));
    for (std::size_t i = 0; i < n; ++i) {
        const rayq::Vec3<T> c{T(u(rng)), T(u(rng)), T(u(rng))};
        Prim prim;
        make(prim, c, r, rng, g);
        s.prims.push_back(prim);
    }
    for (std::size_t i = 0; i < kRays; ++i) {
        rayq::Vec3<double> o{g(rng), g(rng), g(rng)};
        o = o * (4.0 / rayq::length(o));
        const rayq::Vec3<double> target{u(rng), u(rng), u(rng)};
        const rayq::Vec3<double> d = long_directions ? target - o : rayq::normalize(target - o);
        s.rays.push_back({{T(o.x), T(o.y), T(o.z)}, {T(d.x), T(d.y), T(d.z)}});
    }
    return s;
}

template <class Policy, class T, class Prim>
bool loop_closest(Policy p, const rayq::Ray<T>& ray, const std::vector<Prim>& prims, std::size_t& index)
{
    std::optional<rayq::Hit<T>> best;
    for (std::size_t i = 0; i < prims.size(); ++i)
        if (auto h = rayq::intersect(p, ray, prims[i]); h && (!best || h->t < best->t)) best = h, index = i;
    return best.has_value();
}

template <class Policy, class T, class Prim>
bool loop_any(Policy p, const rayq::Ray<T>& ray, const std::vector<Prim>& prims)
{
    for (const Prim& prim : prims)
        if (rayq::occluded(p, ray, prim)) return true;
    return false;
}

// scene_long_d: the scene on the same rays with directions target − origin (length ~3–5, as
// callers who do not normalize pass them) instead of unit ones.
enum class Variant { loop, scene, variant, scene_long_d };
constexpr const char* variant_name(Variant v)
{
    return v == Variant::loop ? "loop" : v == Variant::scene ? "scene" : v == Variant::variant ? "variant" : "scene_long_d";
}

template <class T, class Policy, class Prim>
void run(benchmark::State& state, Policy p, Variant v, bool closest, std::size_t n)
{
    const Setup<Prim> s = setup<Prim>(n, v == Variant::scene_long_d);
    const std::vector<Prim>& prims = s.prims;
    rayq::Scene<rayq::Sphere<T>, rayq::Cylinder<T>, rayq::Cone<T>, rayq::Triangle<T>> scene;
    std::vector<std::variant<rayq::Sphere<T>, rayq::Cylinder<T>, rayq::Cone<T>, rayq::Triangle<T>>> dynamic;
    for (const Prim& prim : prims) scene.add(prim), dynamic.emplace_back(prim);
    std::size_t hits = 0;
    for (auto _ : state) {
        hits = 0;
        for (const rayq::Ray<T>& ray : s.rays) {
            bool hit = false;
            std::size_t index = 0;
            if (v == Variant::loop) {
                hit = closest ? loop_closest(p, ray, prims, index) : loop_any(p, ray, prims);
            } else if (v == Variant::scene || v == Variant::scene_long_d) {
                if (closest) {
                    const auto h = rayq::intersect(p, ray, scene);
                    hit = h.has_value();
                    if (hit) benchmark::DoNotOptimize(h->hit.t);
                } else {
                    hit = rayq::occluded(p, ray, scene);
                }
            } else {
                std::optional<rayq::Hit<T>> best;
                for (const auto& prim : dynamic) {
                    if (closest) {
                        const auto h = std::visit([&](const auto& q) { return rayq::intersect(p, ray, q); }, prim);
                        if (h && (!best || h->t < best->t)) best = h;
                    } else if (std::visit([&](const auto& q) { return rayq::occluded(p, ray, q); }, prim)) {
                        hit = true;
                        break;
                    }
                }
                if (closest) hit = best.has_value();
            }
            hits += hit;
            benchmark::DoNotOptimize(index);
        }
    }
    state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * s.rays.size() * n));
    state.counters["hits"] = double(hits) / double(s.rays.size());
    state.counters["rays_per_second"] = benchmark::Counter(double(s.rays.size()), benchmark::Counter::kIsIterationInvariantRate);
}

template <class T, class Policy, class Prim>
void add(const char* prim_name, Policy p)
{
    for (Variant v : {Variant::loop, Variant::scene, Variant::variant, Variant::scene_long_d})
        for (bool closest : {true, false})
            if (v != Variant::scene_long_d || std::is_same_v<Prim, rayq::Sphere<T>>)  // spheres: enough to compare
            for (std::size_t n : {std::size_t(1), std::size_t(16), std::size_t(1024)}) {
                const std::string name = std::string(closest ? "closest" : "any") + "/" + prim_name + "/" + type_name<T>() + "/" +
                                         policy_name(p) + "/" + variant_name(v) + "/" + std::to_string(n);
                benchmark::RegisterBenchmark(name.c_str(), [=](benchmark::State& st) { run<T, Policy, Prim>(st, p, v, closest, n); });
            }
}

// N = 1,024 rays against one primitive: the scalar queries in a loop, or batch::intersect over a
// RayStream (the bounding-sphere filter in SIMD lanes, then the scalar query on the rays it keeps).
template <class T, class Policy, class Prim>
void run_stream(benchmark::State& state, Policy p, bool batch)
{
    const Setup<Prim> s = setup<Prim>(1);
    rayq::batch::RayStream<T> stream;
    for (const rayq::Ray<T>& ray : s.rays) stream.push_back(ray);
    std::vector<std::optional<rayq::Hit<T>>> out(s.rays.size());
    std::size_t hits = 0;
    for (auto _ : state) {
        if (batch) {
            rayq::batch::intersect(p, stream, s.prims[0], out);
        } else {
            for (std::size_t i = 0; i < s.rays.size(); ++i) out[i] = rayq::intersect(p, s.rays[i], s.prims[0]);
        }
        hits = 0;
        for (const auto& h : out) hits += h.has_value();
        benchmark::DoNotOptimize(hits);
    }
    state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * s.rays.size()));
    state.counters["hits"] = double(hits) / double(s.rays.size());
}

template <class T, class Policy, class Prim>
void add_stream(const char* prim_name, Policy p)
{
    for (bool batch : {false, true}) {
        const std::string name = std::string("stream/") + prim_name + "/" + type_name<T>() + "/" + policy_name(p) + "/" +
                                 (batch ? "batch" : "scalar") + "/1";
        benchmark::RegisterBenchmark(name.c_str(), [=](benchmark::State& st) { run_stream<T, Policy, Prim>(st, p, batch); });
    }
}

template <class T>
void add_all()
{
    add<T, rayq::fast_policy, rayq::Sphere<T>>("sphere", rayq::fast);
    add<T, rayq::stable_policy, rayq::Sphere<T>>("sphere", rayq::stable);
    add<T, rayq::accurate_policy, rayq::Sphere<T>>("sphere", rayq::accurate);
    add<T, rayq::stable_policy, rayq::Cylinder<T>>("cylinder", rayq::stable);
    add<T, rayq::accurate_policy, rayq::Cylinder<T>>("cylinder", rayq::accurate);
    add<T, rayq::accurate_policy, rayq::Cone<T>>("cone", rayq::accurate);
    add<T, rayq::fast_policy, rayq::Triangle<T>>("triangle", rayq::fast);
    add<T, rayq::accurate_policy, rayq::Triangle<T>>("triangle", rayq::accurate);
    add_stream<T, rayq::accurate_policy, rayq::Cylinder<T>>("cylinder", rayq::accurate);
    add_stream<T, rayq::accurate_policy, rayq::Cone<T>>("cone", rayq::accurate);
    add_stream<T, rayq::fast_policy, rayq::Triangle<T>>("triangle", rayq::fast);
    add_stream<T, rayq::accurate_policy, rayq::Triangle<T>>("triangle", rayq::accurate);
}

}  // namespace

int main(int argc, char** argv)
{
    add_all<float>();
    add_all<double>();
    benchmark::Initialize(&argc, argv);
    if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 2;
    benchmark::RunSpecifiedBenchmarks();
    benchmark::Shutdown();
    return 0;
}
