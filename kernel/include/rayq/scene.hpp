// rayq — scenes that compile only what they use.
//
//     rayq::Scene<rayq::Sphere<float>, rayq::Cylinder<float>> scene;
//     scene.add(rayq::Sphere<float>{{0, 0, 5}, 1});
//     if (auto h = rayq::intersect(rayq::fast, ray, scene)) ... h->hit, h->type, h->index
//     bool blocked = rayq::occluded(rayq::fast, ray, scene);
//
// Each listed primitive type is stored in its own arrays, and bounded ones also as structure of
// arrays for a SIMD culling filter (spheres: batch/sphere.hpp; disks, parallelograms, triangles,
// cylinders, and cones under `accurate`: their bounding spheres, batch/bounding_sphere.hpp); a
// type not listed is never instantiated. Closest hit
// searches with the cheap core only (the crossing, no hit record) and builds one record, for the
// winner, at the end, with the fields asked for (HitFields); nearest() stops before that.
// Any-hit (occluded) returns at the first hit.
//
// The answers are exactly those of the scalar queries run over every primitive in order
// (types in list order, primitives in insertion order; the first of equal t wins): a test. Exactly,
// that is, where the compiler rounds the same expression the same way in both places: GCC on FMA
// targets (-march=native) contracts a·b + c into fused multiply-adds by default, and differently in
// different inlined contexts, so a `fast` or `stable` crossing near tangency may then differ (5% of
// rayq-bench-scene's rays against 1,024 float spheres); -ffp-contract=off restores equality, and
// every record's bound holds either way (it is certified from the record's own t: complete()).
// Brute force over all primitives: for large scenes use a BVH (adapters/embree).
#pragma once

#include <cstddef>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <tuple>
#include <type_traits>
#include <utility>
#include <vector>

#include "batch/bounding_sphere.hpp"
#include "batch/sphere.hpp"
#include "detail/ulp.hpp"
#include "query.hpp"

namespace rayq {

namespace detail {

template <class Prim, class... List>
inline constexpr int index_in = [] {
    constexpr bool same[] = {std::is_same_v<Prim, List>...};
    for (int i = 0; i < static_cast<int>(sizeof...(List)); ++i)
        if (same[i]) return i;
    return -1;
}();

// The nearest crossing found so far: t (infinite until one is found: a crossing in the window is
// finite), and its part and side packed in one word. Kept as a Crossing (an optional one before
// that), its part and side bytes were stored one by one and read back as one word when the answer
// was built: a store-forwarding stall on every ray (perf, 16 capped cylinders: 5-7% of the time
// on that one load; rayq-bench-embree, -march=native, µs per 4,096 rays with point and normal,
// medians: one sphere 28.9 -> 21.4, 16 spheres 80.4 -> 77.5).
template <class T>
struct NearestSoFar {
    T t = std::numeric_limits<T>::infinity();
    std::uint32_t part_side = 0;  // Part | entering << 8

    RAYQ_INLINE void take(const Crossing<T>& c)
    {
        t = c.t;
        part_side = static_cast<std::uint32_t>(c.part) | static_cast<std::uint32_t>(c.entering) << 8;
    }
    bool found() const { return t < std::numeric_limits<T>::infinity(); }
    Part part() const { return static_cast<Part>(part_side & 0xFFu); }
    bool entering() const { return (part_side >> 8) != 0; }
};

template <class Prim>
struct is_sphere : std::false_type {};
template <class T>
struct is_sphere<Sphere<T>> : std::true_type {};

struct NoBatch {
    template <class Prim>
    void push_back(const Prim&) {}
};

// One primitive type's storage and its closest/any loops. Invalid primitives are kept (indices
// stay the caller's) but never hit, as with the scalar queries.
template <class Prim>
struct SceneStore {
    using T = scalar_t<Prim>;
    static constexpr bool sphere = is_sphere<Prim>::value;
    static constexpr bool bounded = !sphere && batch::has_bounding_sphere_v<Prim>;
    std::vector<Prim> items;
    std::vector<unsigned char> valid;
    std::conditional_t<sphere, batch::SphereSoA<T>, std::conditional_t<bounded, batch::BoundSoA<T>, NoBatch>> soa;

    void add(const Prim& p)
    {
        items.push_back(p);
        valid.push_back(static_cast<bool>(validate(p)));
        soa.push_back(p);
    }

    // Calls visit(i) for every primitive the ray may hit in its window, in index order, until
    // visit returns true. Bounded types: the SIMD filter skips lanes the ray certainly misses;
    // the window is re-read per lane group, so a nearer hit narrows what the sphere filter and
    // the exact policies' bounding-sphere filter keep.
    // One or two primitives: their scalar queries cost less than the filter's set-up and one
    // lane group (callgrind, one float sphere under fast: 167 of the scene's 364 instructions
    // per ray were filter and bookkeeping, against 197 for the scalar query; accurate answers
    // certain misses with batch::exactly_missed_sphere at about the filter's cost). Both loops are
    // forced inline: clang left the whole scan out of line, and a one-sphere scene's nearest() ran
    // at 34 M rays/s against 68 M inlined. The filtered loop was kept out of line while inlining it
    // cost 17% at 16 spheres; since the line tests need no square root (SphereFilterRay), inlined
    // it keeps the window, the nearest crossing and the ray's lanes in registers rather than behind
    // the call's references (rayq-bench-embree, -march=native, µs per 4,096 rays with point and
    // normal: 16 spheres 78 -> 55, 16 capped cylinders 111 -> 91, 1,000 spheres 917 -> 871; one
    // sphere 26 -> 31), once the scene's intersect() is forced inline too (GCC had then called it
    // out of line, the answer returned through memory: one sphere took 57).
    // Bounded types (not spheres) whose filter has a line test still test each of those one or two
    // primitives' bounds first, in scalar arithmetic: for a capped cylinder the line test is a
    // third of the scalar query's arithmetic and its outcome far more predictable (of the rays of
    // rayq-bench-embree's one-cylinder scene, 9% pass within the bound, 25% within the infinite
    // side's radius, the branch the query took first). rayq-bench-embree, one capped cylinder,
    // -march=native, M rays/s, medians of 5, two runs each: `fast` with point and normal 58.7, 60.1
    // -> 71.1, 63.5 (Embree's cone curve 12.2–12.8 in the same runs); `stable` 33.6, 34.2 -> 44.4,
    // 44.5. The line test compares ℓ²·|d|², so it waits for no square root (BoundFilterRay).
    // `line`: the query's ray as the caller holds it, whose origin and direction the filter reads;
    // `window`: the same line with the window narrowed so far (nearest()'s copy). Not the copy's
    // origin and direction: GCC copies a Ray in one 32-byte store and the filter then reads
    // direction x and y (bytes 12-19, across its 16-byte halves) back in one 8-byte load, which
    // store forwarding cannot serve (perf, 16 capped cylinders under `fast`, Xeon with AVX-512:
    // 11% of the samples on that load).
    template <class Policy, class Visit>
    RAYQ_INLINE bool scan(const Ray<T>& line, const Ray<T>& window, Visit visit) const
    {
        constexpr std::size_t direct_up_to = 2;
        if constexpr (filtered<Policy>)
            if (items.size() > direct_up_to) return scan_filtered<Policy>(line, window, visit);
        if constexpr (bounded && filtered<Policy> && batch::bound_test_v<Policy, Prim> != batch::BoundTest::line) {
            const auto f = filter_ray<Policy>(line);
            for (std::size_t i = 0, n = items.size(); i < n; ++i)
                if (valid[i] && !batch::line_passes_bound<batch::bound_test_v<Policy, Prim>>(f, soa, i) && visit(i)) return true;
            return false;
        }
        for (std::size_t i = 0, n = items.size(); i < n; ++i)
            if (valid[i] && visit(i)) return true;
        return false;
    }

    template <class Policy>
    static constexpr bool filtered = sphere || batch::bound_filter_exact_v<Policy, Prim>;

    // The filter's side of the ray (the direction range check only where the exact test needs it).
    template <class Policy>
    RAYQ_INLINE static auto filter_ray(const Ray<T>& ray)
    {
        if constexpr (sphere) return batch::SphereFilterRay<T>(ray);
        else return batch::BoundFilterRay<T>(ray, batch::bound_test_v<Policy, Prim> == batch::BoundTest::exact);
    }

    template <class Policy, class Visit>
    RAYQ_INLINE bool scan_filtered(const Ray<T>& line, const Ray<T>& window, Visit& visit) const
    {
        const auto f = filter_ray<Policy>(line);
        const auto candidates = [&](std::size_t g) RAYQ_INLINE_LAMBDA {
            if constexpr (sphere) return batch::sphere_candidates(f, window.tmin, window.tmax, soa, g);
            else return batch::bound_candidates<Policy, batch::bound_test_v<Policy, Prim>>(f, window.tmin, window.tmax, soa, g);
        };
        // Most groups have no candidate: the ray's line passes every bound in them. They are
        // skipped by that test alone (line_passes_group) in a loop of its own, which calls no
        // visit, so the compiler keeps the ray's broadcast lanes in registers across it; in one
        // loop with the visit it reloaded them per group (callgrind per ray, 1,000 float spheres,
        // fast: AVX2 5,032 -> 3,088 instructions, SSE2 15,801 -> 10,850; 2,712 and 9,878 with the
        // stored reach², ccc313a). A kept group's line test runs again inside candidates(): the
        // price of a loop that carries nothing, measured as a win at 16 and 1,000 primitives (the
        // stopped group's line terms carried on into candidates() instead: rayq-bench-embree,
        // -march=native, `fast` with point and normal, µs per 4,096 rays, 16 spheres 62-63 -> 77-82,
        // 1,000 spheres 604-617 -> 745-783). The group tests are forced inline: GCC called them out
        // of line under AVX-512, which halved the rays/s of a 16-sphere scene.
        const std::size_t groups = soa.groups();
        const auto passed = [&](std::size_t g) RAYQ_INLINE_LAMBDA {
            if constexpr (sphere) return batch::line_passes_group(f, soa, g);
            else return batch::line_passes_group<batch::bound_test_v<Policy, Prim>>(f, soa, g);
        };
        // One lane group (up to 16 float primitives under AVX-512): visit_group alone, whose line
        // mask is the skip, with no separate line_passes_group first, so a kept group's line test is
        // not computed twice (the compiler shares it between line_candidates() and candidates(), both
        // inline in one body; rayq-bench-embree, -march=native, `fast` with point and normal, µs per
        // 4,096 rays, three alternating runs, when candidates() held the skip: 16 capped cylinders
        // 116, 114, 129 -> 111, 106, 108; 16 spheres 65, 64, 69 -> 72, 59, 61).
        // The lanes are walked in the line test's mask and each checked against the window test's
        // (candidates(), a subset): the walk, and the scalar crossing of the first lane, no longer
        // wait for the window test, whose verdict is a predictable branch (a ray whose line meets a
        // primitive mostly has it in its window). The same lanes are visited. rayq-bench-embree,
        // -march=native, Xeon with AVX-512, `fast` with point and normal, `--rounds=3`, pinned, ms
        // per 65,536 rays: 16 capped cylinders 2.07 -> 1.62 (3.96x -> 5.01x Embree's cone curves),
        // 16 spheres 1.09 -> 0.98 (4.48x -> 4.96x); a ray with a candidate had waited for the window
        // test's ~15 lane operations before its first crossing (scratch program, 16 spheres, rays
        // with a candidate: 72.5 -> 61.8 ns; 16 capped cylinders 93.3 -> 77.2 ns).
        // Triangles and parallelograms under `fast` and `stable` have no window test apart (their
        // plane test follows the line test): candidates() is their walk and their mask at once.
        constexpr bool window_apart = sphere || batch::bound_test_v<Policy, Prim> != batch::BoundTest::line;
        const auto line_candidates = [&](std::size_t g) RAYQ_INLINE_LAMBDA {
            if constexpr (sphere) return batch::sphere_line_candidates(f, soa, g);
            else if constexpr (window_apart) return batch::bound_line_candidates<batch::bound_test_v<Policy, Prim>>(f, soa, g);
            else return candidates(g);
        };
        const auto visit_group = [&](std::size_t g) RAYQ_INLINE_LAMBDA {
            std::uint32_t m = line_candidates(g);
            if (m == 0) return false;
            const std::uint32_t keep = window_apart ? candidates(g) : m;
            for (; m != 0; m &= m - 1) {
                const unsigned lane = static_cast<unsigned>(lowest_bit(m));
                if (!(keep >> lane & 1u)) continue;
                const std::size_t i = g * decltype(soa)::width + lane;
                if (valid[i] && visit(i)) return true;
            }
            return false;
        };
        if (groups == 1) return visit_group(0);
        // Spheres in many groups: tested against d/|d| (UnitLineRay), whose square root the many
        // groups repay, two groups per trip of the skip loop (half its loop and branch overhead; a
        // kept second group has its first tested twice). rayq-bench-embree, -march=native, AVX2,
        // `fast` with point and normal, ms per 65,536 rays, minimum of 15: 1,000 spheres 19.1 ->
        // 17.1 (d/|d|) -> 16.5 (pairs). Pairs lost where the groups are few (16 capped cylinders,
        // two groups: 2.25 -> 2.36) and were not clearly ahead for bounds in many groups (1,024
        // cylinders and cones, rayq-bench-scene: within the noise, some rows 5-7% behind).
        constexpr std::size_t few_groups = 3;
        const auto skip_and_visit = [&](auto line_passes, bool pairs) RAYQ_INLINE_LAMBDA {
            for (std::size_t g = 0; g < groups; ++g) {
                if (pairs)
                    while (g + 1 < groups && line_passes(g) && line_passes(g + 1)) g += 2;
                while (g < groups && line_passes(g)) ++g;
                if (g == groups) break;
                if (visit_group(g)) return true;
            }
            return false;
        };
        if constexpr (sphere) {
            if (groups > few_groups) {
                const batch::UnitLineRay<T> unit(line.direction, f.dd);
                return skip_and_visit([&](std::size_t g) RAYQ_INLINE_LAMBDA { return batch::line_passes_group(f, unit, soa, g); }, true);
            }
        }
        return skip_and_visit(passed, false);
    }

    // Finds a hit nearer than `best` (the nearest so far, over every store), updating `best`
    // and narrowing `window` to it (`line`: the query's own ray, see scan). The window stays one
    // ulp past `best`: the accurate policy decides the window exactly and may report a root just
    // inside an end as the float next to it, so ties are settled by comparing t, never by the
    // window's exclusive end.
    template <class Policy>
    RAYQ_INLINE bool closest(Policy policy, const Ray<T>& line, Ray<T>& window, NearestSoFar<T>& best, std::size_t& index) const
    {
        bool found = false;
        scan<Policy>(line, window, [&](std::size_t i) RAYQ_INLINE_LAMBDA {
            const auto crossings = leading_crossings(policy, window, items[i]);
            const Crossing<T>* c = first_in_window(window, crossings);
            if (c && c->t < best.t) {
                best.take(*c);
                window.tmax = next_up(c->t);
                index = i;
                found = true;
            }
            return false;
        });
        return found;
    }

    template <class Policy>
    RAYQ_INLINE bool any(Policy policy, const Ray<T>& ray) const
    {
        return scan<Policy>(ray, ray, [&](std::size_t i) RAYQ_INLINE_LAMBDA {
            return first_in_window(ray, leading_crossings(policy, ray, items[i])) != nullptr;
        });
    }

};

// Calls visit(store, type) for each store in list order until one returns true; returns whether
// one did. Not std::apply: its std::__invoke_impl is not forced inline, and GCC left it out of
// line once the search inside grew (a one-sphere scene's intersect(): 133 -> 150 instructions per
// ray, callgrind).
template <class... Stores, class Visit, std::size_t... I>
RAYQ_INLINE bool visit_stores(const std::tuple<Stores...>& stores, Visit&& visit, std::index_sequence<I...>)
{
    return (visit(std::get<I>(stores), static_cast<int>(I)) || ...);
}
template <class... Stores, class Visit>
RAYQ_INLINE bool visit_stores(const std::tuple<Stores...>& stores, Visit&& visit)
{
    return visit_stores(stores, visit, std::index_sequence_for<Stores...>{});
}

template <class T, class... Prims>
inline constexpr bool same_scalar_v = (std::is_same_v<T, scalar_t<Prims>> && ...);

}  // namespace detail

template <class... Prims>
class Scene {
    static_assert(sizeof...(Prims) > 0, "rayq::Scene: list at least one primitive type");
    static_assert((is_primitive_v<Prims> && ...), "rayq::Scene: every listed type must be a rayq primitive");

public:
    using scalar_type = scalar_t<std::tuple_element_t<0, std::tuple<Prims...>>>;
    static_assert(detail::same_scalar_v<scalar_type, Prims...>, "rayq::Scene: all primitives share one scalar type");

    // Position of Prim in the list (the `type` of a SceneHit).
    template <class Prim>
    static constexpr int type_index = detail::index_in<Prim, Prims...>;

    // Adds a primitive and returns its index within its type. Invalid primitives are kept (so
    // indices stay predictable) and never hit; rayq::validate(prim) says why.
    template <class Prim>
    std::size_t add(const Prim& prim)
    {
        static_assert(type_index<Prim> >= 0, "rayq::Scene::add: this primitive type is not in the scene's list");
        auto& store = std::get<type_index<Prim>>(stores_);
        store.add(prim);
        return store.items.size() - 1;
    }

    template <class Prim>
    const std::vector<Prim>& primitives() const
    {
        static_assert(type_index<Prim> >= 0, "rayq::Scene::primitives: this primitive type is not in the scene's list");
        return std::get<type_index<Prim>>(stores_).items;
    }

    std::size_t size() const
    {
        return std::apply([](const auto&... s) { return (s.items.size() + ...); }, stores_);
    }

    const std::tuple<detail::SceneStore<Prims>...>& stores() const { return stores_; }

private:
    std::tuple<detail::SceneStore<Prims>...> stores_;
};

// The nearest hit without its record: which primitive, t, and the crossing's part and side.
template <class T>
struct SceneRef {
    T t;
    int type;           // position of the primitive's type in the scene's list
    std::size_t index;  // within that type, in insertion order
    Part part;
    bool entering;      // the hit's front_face
};

template <class T>
struct SceneHit {
    Hit<T> hit;
    int type;
    std::size_t index;
};

// Forced inline: GCC called it out of line from a one-primitive loop once the crossings inside
// grew, and returned the answer through memory (standalone loop, SSE2, intersect() with point and
// normal, ns per ray: one capped cylinder 20.1 -> 15.6, one sphere 6.9 -> 6.3). So is the search
// inside it (SceneStore::scan).
template <class Policy, class... Prims, std::enable_if_t<is_policy_v<Policy>, int> = 0>
RAYQ_INLINE std::optional<SceneRef<typename Scene<Prims...>::scalar_type>> nearest(
    Policy policy, const Ray<typename Scene<Prims...>::scalar_type>& ray, const Scene<Prims...>& scene)
{
    using T = typename Scene<Prims...>::scalar_type;
    if (!usable(ray)) return std::nullopt;
    Ray<T> window = ray;
    detail::NearestSoFar<T> best;
    int best_type = 0;
    std::size_t best_index = 0;
    detail::visit_stores(scene.stores(), [&](const auto& store, int type) RAYQ_INLINE_LAMBDA {
        if (store.closest(policy, ray, window, best, best_index)) best_type = type;
        return false;
    });
    // Built once, here: assembled field by field in the loop, GCC copied the optional with
    // 16-byte loads of just-written bytes (two store-forwarding stalls per ray: a one-sphere
    // scene's nearest() took 18.3 ns per ray against 7.6 ns).
    if (!best.found()) return std::nullopt;
    return SceneRef<T>{best.t, best_type, best_index, best.part(), best.entering()};
}

namespace detail {
// complete()'s record with its bounds, which need the primitive's crossings again (see there):
// out of line, so that complete() stays small where it is inlined; written into `out`, not
// returned (a returned Hit shared its stack slot with write_hit's record: fill_scene_hit).
template <class Policy, class Prim>
inline void certified_scene_hit(Policy policy, const Ray<scalar_t<Prim>>& ray, const Prim& prim, Crossing<scalar_t<Prim>> c,
                                HitFields fields, Hit<scalar_t<Prim>>& out)
{
    bool earlier_may_count = false;
    for (const auto& x : leading_crossings(policy, ray, prim)) {
        if (x.t == c.t && x.part == c.part && x.entering == c.entering) {
            c.rounded = x.rounded;
            break;
        }
        if (!(x.t < c.t)) break;  // ascending: none before it
        earlier_may_count = earlier_may_count || in_window(ray, x.t) || may_enter_window(policy, ray, prim, x);
    }
    write_first_hit(policy, ray, prim, c, earlier_may_count, fields, out);  // out is fresh: fill_scene_hit's callers make it
}

// Writes the record of `ref` into out.hit, out being where the caller keeps it (intersect()'s
// optional), so that no Hit is built elsewhere and copied: GCC copied one in 16-byte loads of fields
// just stored as 8-, 4- and 2-byte pieces, two store-forwarding stalls per hit (rayq-bench-embree,
// -march=native, AVX2, `fast` with point and normal, µs per 4,096 rays, two alternating runs: 16
// capped cylinders 151, 152 -> 140, 139; 16 spheres 93, 94 -> 88, 89; one capped cylinder 72.5, 73 ->
// 69, 69). False when ref names no primitive of this scene.
template <class Policy, class... Prims>
RAYQ_INLINE bool fill_scene_hit(Policy policy, const Ray<typename Scene<Prims...>::scalar_type>& ray, const Scene<Prims...>& scene,
                                const SceneRef<typename Scene<Prims...>::scalar_type>& ref, HitFields fields,
                                SceneHit<typename Scene<Prims...>::scalar_type>& out)
{
    using T = typename Scene<Prims...>::scalar_type;
    return visit_stores(scene.stores(), [&](const auto& store, int type) RAYQ_INLINE_LAMBDA {
        if (type != ref.type) return false;
        const auto& prim = store.items.at(ref.index);
        const Crossing<T> c{ref.t, ref.part, ref.entering};
        if (wants(fields, HitFields::bounds))
            certified_scene_hit(policy, ray, prim, c, fields, out.hit);
        else
            write_hit(policy, ray, prim, c, fields, out.hit);
        return true;
    });
}
}  // namespace detail

// The hit record of a nearest() answer for the same ray and scene, with the fields asked for, built
// from the crossing the search found. The bounds also need the crossings before it (one that lies or
// may exactly lie in the window widens the bound back to tmin, as in intersect()) and, under
// `accurate`, whether t is correctly rounded: both come from that primitive's crossings computed
// again, which are not assumed to name the same crossing (FP contraction: see the top of this file;
// calling intersect() here threw std::bad_optional_access where it found no hit).
// Forced inline, its visit too, as write_hit is: GCC called the visit out of line per hit (16 capped
// cylinders under `fast`, point and normal: ~30 instructions per hit for the call alone).
template <class Policy, class... Prims, std::enable_if_t<is_policy_v<Policy>, int> = 0>
RAYQ_INLINE SceneHit<typename Scene<Prims...>::scalar_type> complete(Policy policy,
                                                                     const Ray<typename Scene<Prims...>::scalar_type>& ray,
                                                                     const Scene<Prims...>& scene,
                                                                     const SceneRef<typename Scene<Prims...>::scalar_type>& ref,
                                                                     HitFields fields = HitFields::all)
{
    using T = typename Scene<Prims...>::scalar_type;
    SceneHit<T> found{Hit<T>{}, ref.type, ref.index};
    if (!detail::fill_scene_hit(policy, ray, scene, ref, fields, found)) throw std::bad_optional_access();
    return found;
}

// Forced inline, as nearest() is: with the filtered search inlined, GCC called it out of line and
// returned the record through memory (rayq-bench-embree, one sphere, point and normal: 26 -> 57 µs).
template <class Policy, class... Prims, std::enable_if_t<is_policy_v<Policy>, int> = 0>
RAYQ_INLINE std::optional<SceneHit<typename Scene<Prims...>::scalar_type>> intersect(
    Policy policy, const Ray<typename Scene<Prims...>::scalar_type>& ray, const Scene<Prims...>& scene,
    HitFields fields = HitFields::all)
{
    using T = typename Scene<Prims...>::scalar_type;
    std::optional<SceneHit<T>> out;
    const auto ref = nearest(policy, ray, scene);
    if (!ref) return out;
    out.emplace(SceneHit<T>{Hit<T>{}, ref->type, ref->index});
    detail::fill_scene_hit(policy, ray, scene, *ref, fields, *out);
    return out;
}

// Forced inline as nearest() is (callgrind, SSE2, instructions per ray: one capped cylinder 209 ->
// 186, one sphere 120 -> 95, 16 spheres 360 -> 340).
template <class Policy, class... Prims, std::enable_if_t<is_policy_v<Policy>, int> = 0>
RAYQ_INLINE bool occluded(Policy policy, const Ray<typename Scene<Prims...>::scalar_type>& ray, const Scene<Prims...>& scene)
{
    if (!usable(ray)) return false;
    return detail::visit_stores(scene.stores(), [&](const auto& store, int) RAYQ_INLINE_LAMBDA { return store.any(policy, ray); });
}

template <class... Prims>
inline std::optional<SceneHit<typename Scene<Prims...>::scalar_type>> intersect(
    const Ray<typename Scene<Prims...>::scalar_type>& ray, const Scene<Prims...>& scene, HitFields fields = HitFields::all)
{
    return intersect(default_policy{}, ray, scene, fields);
}

template <class... Prims>
inline bool occluded(const Ray<typename Scene<Prims...>::scalar_type>& ray, const Scene<Prims...>& scene)
{
    return occluded(default_policy{}, ray, scene);
}

}  // namespace rayq
