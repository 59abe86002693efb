// rayq-bench: what each precision policy costs. For every primitive × scalar type × policy it
// times closest-hit intersect() and any-hit occluded() over a fixed array of random rays
// (kRays of them, fixed seed, exactly half hitting by the double/accurate reference, in random
// order) against one primitive, read in order (kRays: why that many).
//
// Names are query/primitive/type/policy, e.g. intersect/sphere/double/accurate. One iteration
// is the whole ray array; items_per_second is ray tests per second (ns/test = 1e9 / it), and
// the "hits" counter is the fraction of the array the benchmarked policy reports as hit, and
// "exact_fallbacks_per_ray" how often the accurate policy needed exact expansion arithmetic.
#include <benchmark/benchmark.h>
#include <rayq/rayq.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <deque>
#include <random>
#include <string>
#include <vector>

namespace {

// 65,536 distinct rays, not 4,096 repeated: the branch predictor learns a few thousand rays'
// outcomes over the iterations and flatters branchy code (rayq-bench-embree, session 33). Here it
// had flattered `accurate` (SSE2 release, accurate ÷ fast, medians of 5 interleaved, three runs,
// 4,096 / 16,384 / 65,536 rays): double plane 0.96–0.98 / 1.14–1.18 / 1.27–1.29, double sphere
// 1.02–1.25 / 1.26–1.31 / 1.28–1.31, float plane 0.69–0.71 / 0.79–0.91 / 0.99–1.00; float sphere
// 1.15 throughout. The array (4 MB of double rays) is read in order, which the prefetcher follows.
constexpr std::size_t kRays = 65536;
constexpr std::uint64_t kSeed = 0x5eed'2a7f'0001ULL;

using rayq::Vec3;

struct Intersect {
    static constexpr const char* name = "intersect";
    template <class Policy, class T, class Prim>
    static auto run(Policy policy, const rayq::Ray<T>& ray, const Prim& prim) { return rayq::intersect(policy, ray, prim); }
    template <class R>
    static bool hit(const R& r) { return r.has_value(); }
};

struct Occluded {
    static constexpr const char* name = "occluded";
    template <class Policy, class T, class Prim>
    static bool run(Policy policy, const rayq::Ray<T>& ray, const Prim& prim) { return rayq::occluded(policy, ray, prim); }
    static bool hit(bool r) { return r; }
};

template <class T> constexpr const char* type_name() { return sizeof(T) == 4 ? "float" : "double"; }
constexpr const char* policy_name(rayq::fast_policy) { return "fast"; }
constexpr const char* policy_name(rayq::stable_policy) { return "stable"; }
constexpr const char* policy_name(rayq::accurate_policy) { return "accurate"; }

template <class T, class U>
rayq::Vec3<T> to(const Vec3<U>& v) { return {T(v.x), T(v.y), T(v.z)}; }

// The scene: every primitive of size ~1 around `c`, tilted off the coordinate axes so that no
// component is conveniently zero. make<T>() converts the double geometry to T.
const Vec3<double> c{0.3, -0.2, 0.1};
const Vec3<double> tilt{0.2, 0.3, 0.93};

template <class T> rayq::Sphere<T> sphere() { return {to<T>(c), T(1)}; }
template <class T> rayq::Plane<T> plane() { return {to<T>(c), to<T>(tilt)}; }
template <class T> rayq::Disk<T> disk() { return {to<T>(c), to<T>(tilt), T(1)}; }
template <class T> rayq::Parallelogram<T> parallelogram()
{
    return {to<T>(c + Vec3<double>{-0.7, -0.6, 0.1}), {T(1.6), T(0.3), T(-0.2)}, {T(-0.25), T(1.2), T(0.4)}};
}
template <class T> rayq::Triangle<T> triangle()
{
    return {to<T>(c + Vec3<double>{-1.0, -0.8, 0.1}), to<T>(c + Vec3<double>{1.1, -0.5, -0.2}),
            to<T>(c + Vec3<double>{-0.2, 1.2, 0.3})};
}
// A capped frustum about the same axis as the cylinder, radii 0.9 and 0.4.
template <class T> rayq::Cone<T> frustum()
{
    const Vec3<double> half{0.3 * 1.2, 0.4 * 1.2, 0.87 * 1.2};
    return {to<T>(c - half), T(0.9), to<T>(c + half), T(0.4), rayq::Caps::both};
}
template <class T> rayq::Cylinder<T> cylinder(rayq::Caps caps)
{
    return rayq::Cylinder<T>::from_center(to<T>(c), {T(0.3), T(0.4), T(0.87)}, T(0.7), T(1.2), caps);
}

// Origins on a sphere of radius 4 about the scene, aimed at random points of the cube
// c ± 1.5, unit directions. Candidates are kept until half the array hits and half misses
// (by the double/accurate reference), then shuffled so hits and misses do not come in runs.
template <class PrimD>
std::vector<rayq::Ray<double>> make_rays(const PrimD& prim)
{
    std::mt19937_64 rng(kSeed);
    std::normal_distribution<double> gauss(0.0, 1.0);
    std::uniform_real_distribution<double> box(-1.5, 1.5);
    std::vector<rayq::Ray<double>> hits, misses;
    while (hits.size() < kRays / 2 || misses.size() < kRays / 2) {
        const Vec3<double> g{gauss(rng), gauss(rng), gauss(rng)};
        const Vec3<double> origin = c + (4.0 / rayq::length(g)) * g;
        const Vec3<double> target = c + Vec3<double>{box(rng), box(rng), box(rng)};
        const rayq::Ray<double> ray{origin, rayq::normalize(target - origin)};
        auto& bin = rayq::occluded(rayq::accurate, ray, prim) ? hits : misses;
        if (bin.size() < kRays / 2) bin.push_back(ray);
    }
    hits.insert(hits.end(), misses.begin(), misses.end());
    std::shuffle(hits.begin(), hits.end(), rng);
    return hits;
}

template <class T>
std::vector<rayq::Ray<T>> convert(const std::vector<rayq::Ray<double>>& rays)
{
    std::vector<rayq::Ray<T>> out;
    out.reserve(rays.size());
    for (const auto& r : rays) out.push_back({to<T>(r.origin), to<T>(r.direction)});
    return out;
}

template <class Query, class Policy, class Prim>
void run(benchmark::State& state, const Prim& prim_in, const std::vector<rayq::Ray<rayq::scalar_t<Prim>>>& rays)
{
    Prim prim = prim_in;
    benchmark::DoNotOptimize(prim);  // the primitive is opaque: no constant folding of validate()

    std::size_t hits = 0;
    const unsigned long long fallbacks_before = rayq::exact_fallbacks.load();
    for (const auto& r : rays) hits += Query::hit(Query::run(Policy{}, r, prim));
    // Decisions the accurate policy's filters left to exact arithmetic, per ray (issue 7: <= 0.1%).
    const double fallbacks = double(rayq::exact_fallbacks.load() - fallbacks_before) / double(rays.size());

    for (auto _ : state) {
        for (const auto& r : rays) {
            auto result = Query::run(Policy{}, r, prim);
            benchmark::DoNotOptimize(result);
        }
    }
    state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()) * static_cast<std::int64_t>(rays.size()));
    state.counters["hits"] = double(hits) / double(rays.size());
    state.counters["exact_fallbacks_per_ray"] = fallbacks;
}

template <class Query, class T, class Prim>
void register_policies(const char* prim_name, const Prim& prim, const std::vector<rayq::Ray<T>>& rays)
{
    const auto one = [&](auto policy) {
        using Policy = decltype(policy);
        const std::string name =
            std::string(Query::name) + "/" + prim_name + "/" + type_name<T>() + "/" + policy_name(policy);
        benchmark::RegisterBenchmark(name.c_str(), [prim, &rays](benchmark::State& state) {
            run<Query, Policy>(state, prim, rays);
        });
    };
    one(rayq::fast);
    one(rayq::stable);
    one(rayq::accurate);
}

// The ray arrays live for the whole run (the benchmarks refer to them).
template <class T>
std::deque<std::vector<rayq::Ray<T>>>& storage()
{
    static std::deque<std::vector<rayq::Ray<T>>> s;  // push_back keeps references valid
    return s;
}

template <class Query, class MakeD, class MakeF>
void register_primitive(const char* prim_name, MakeD make_double, MakeF make_float)
{
    const auto rays_d = make_rays(make_double());
    auto& d = storage<double>();
    auto& f = storage<float>();
    d.push_back(rays_d);
    f.push_back(convert<float>(rays_d));
    register_policies<Query, float>(prim_name, make_float(), f.back());
    register_policies<Query, double>(prim_name, make_double(), d.back());
}

template <class Query>
void register_query()
{
    register_primitive<Query>("sphere", sphere<double>, sphere<float>);
    register_primitive<Query>("plane", plane<double>, plane<float>);
    register_primitive<Query>("disk", disk<double>, disk<float>);
    register_primitive<Query>("parallelogram", parallelogram<double>, parallelogram<float>);
    register_primitive<Query>("triangle", triangle<double>, triangle<float>);
    register_primitive<Query>(
        "cylinder", [] { return cylinder<double>(rayq::Caps::none); }, [] { return cylinder<float>(rayq::Caps::none); });
    register_primitive<Query>(
        "capped_cylinder", [] { return cylinder<double>(rayq::Caps::both); },
        [] { return cylinder<float>(rayq::Caps::both); });
    register_primitive<Query>("frustum", frustum<double>, frustum<float>);
}

}  // namespace

int main(int argc, char** argv)
{
    benchmark::Initialize(&argc, argv);
    if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;

#ifdef RAYQ_BENCH_NATIVE
    benchmark::AddCustomContext("rayq_native", "-march=native");
#else
    benchmark::AddCustomContext("rayq_native", "off");
#endif
#if defined(__FMA__) || defined(__FMA4__) || defined(__aarch64__) || defined(__ARM_FEATURE_FMA)
    benchmark::AddCustomContext("rayq_two_product", "hardware fma");
#else
    benchmark::AddCustomContext("rayq_two_product", "Dekker/Veltkamp split");
#endif
    benchmark::AddCustomContext("rayq_rays_per_iteration", std::to_string(kRays));

    register_query<Intersect>();
    register_query<Occluded>();

    benchmark::RunSpecifiedBenchmarks();
    benchmark::Shutdown();
    return 0;
}
