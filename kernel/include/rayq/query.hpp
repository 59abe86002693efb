// rayq — the queries every primitive answers: intersect (closest hit), occluded (any hit),
// intersect_all (every crossing).
//
// A primitive header supplies three things, found by argument-dependent lookup:
//   crossings(policy, ray, prim)        the surface crossings along the ray's line, ascending,
//                                       each with its part and whether the ray enters the solid
//                                       (optionally with a trailing limit: at most that many, the
//                                       first ones in the window — for closest and any hit);
//   outward_normal(prim, point, part)   the outward normal (any length) at a hit point;
//   outward_normal_on_ray(prim, ray, t, point, part)
//                                       optional: the same at the ray's point t (point, rounded),
//                                       where a form in t is shorter than one from the point;
//   validate(prim)                      whether the primitive is usable;
// and specializes is_primitive. The queries below are written once for all of them: the
// cheap core (crossings) is shared, and only intersect() builds the full hit record.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <type_traits>

#include "detail/bounded.hpp"
#include "detail/magnitude.hpp"
#include "detail/policy_ops.hpp"
#include "detail/ulp.hpp"
#include "hit.hpp"
#include "policy.hpp"
#include "ray.hpp"
#include "validation.hpp"
#include "vec3.hpp"

namespace rayq {

template <class Prim>
struct is_primitive : std::false_type {};
template <class Prim>
inline constexpr bool is_primitive_v = is_primitive<Prim>::value;

template <class Prim>
using scalar_t = typename Prim::scalar_type;

namespace detail {
// Whether S is P<T> or const P<T>: lets one each_length serve the walks that read a primitive's
// lengths and the one that scales a copy of them.
template <class S, template <class> class P>
struct is_instance : std::false_type {};
template <class T, template <class> class P>
struct is_instance<P<T>, P> : std::true_type {};
template <class S, template <class> class P>
inline constexpr bool is_instance_v = is_instance<std::remove_const_t<S>, P>::value;
}  // namespace detail

template <class T>
struct Crossing {
    T t;
    Part part;
    bool entering;         // the ray passes from outside to inside here
    bool rounded = false;  // t is the exact root correctly rounded (or the float next to the window's
                           // end it lies within an ulp of), certified by running error bounds: accurate
};

// At most two: every primitive is a convex solid, a quadric surface or a flat piece.
// Only the first `count` items are set. Zeroing the others can make GCC keep the record in memory
// and read it back across the stores: a loop over a one-sphere scene that used the hit's t ran at
// 58-65 M rays/s zeroed and 93-120 unzeroed (-O3 -march=native); rayq-bench-embree's loop ran at
// the same speed either way. In a union they are copied as bytes, so an unset item is never read as
// a value.
template <class T>
struct Crossings {
    int count = 0;
    union {
        Crossing<T> item[2];
    };
    Crossings() {}  // leaves the union unset (Crossing's default member initializer would set it)

    constexpr void add(T t, Part part, bool entering, bool rounded = false) { item[count++] = {t, part, entering, rounded}; }
    constexpr const Crossing<T>* begin() const { return item; }
    constexpr const Crossing<T>* end() const { return item + count; }
};

namespace detail {

template <class T>
constexpr bool in_window(const Ray<T>& ray, T t) { return ray.tmin < t && t < ray.tmax; }

// write_hit's normal n where dot(n, d) > 0 as computed (see there): reflected across the plane
// perpendicular to d, nudged by an ulp while rounding keeps the sign; flipped at last. Rare, so
// out of line.
template <class T>
inline Vec3<T> facing_ray(Vec3<T> n, const Vec3<T>& direction)
{
    const Vec3<T> u = unit(direction);
    for (int i = 0; i < 3 && dot(n, direction) > T(0); ++i)
        n = unit(n - (T(2) * dot(n, u) + std::numeric_limits<T>::epsilon()) * u);
    if (dot(n, direction) > T(0)) n = -n;
    return n;
}

// write_hit's normal where unit()'s direct path does not apply (direct_unit, whose result is never
// zero): flipped to the crossing's side and, where it is zero, replaced by −d̂: a point rounded onto
// a degenerate spot (the center of a far sphere whose t the fast policy got wrong, a cone's apex) has
// no normal, and the record still promises a unit one facing the ray. Rare, so out of line: the
// zero test on every record's normal, three branches waiting for its division, had cost 20% of a
// hit (scratch program over rayq-bench-embree's 16 float spheres and rays, `fast` with point and
// normal, -march=native, AVX-512, the rays that hit, median of 41 passes: 68.5, 69.0, 67.8 ->
// 55.4, 54.6, 54.3 ns per ray).
template <class T>
inline Vec3<T> unit_facing_side(const Vec3<T>& outward, bool entering, const Vec3<T>& direction)
{
    Vec3<T> n = scaled_unit(outward);
    if (!entering) n = -n;
    if (n.x == T(0) && n.y == T(0) && n.z == T(0)) n = -unit(direction);
    return n;
}

// The record's certified bounds (t_error, point_error) for write_hit, given its point before
// saturation (passed, not computed again: under FP contraction a second o + t·d may round
// differently). Not inlined with it, so that the shading record every renderer asks for stays
// small where it is inlined.
template <class T>
struct HitBounds {
    T t_error;
    Vec3<T> point_error;
};
// Whether a primitive's residual evaluates in the static filter (magnitude.hpp): sums and products only.
template <class Prim, class = void>
struct has_static_residual : std::false_type {};
template <class Prim>
struct has_static_residual<Prim, std::void_t<decltype(residual(std::declval<const Prim&>(), std::declval<const Vec3<Magnitude<double>>&>(),
                                                               std::declval<const Vec3<Magnitude<double>>&>(), Magnitude<double>{},
                                                               Part::surface))>> : std::true_type {};

// A float primitive's certificate runs in double: its inputs are exact there, its residual goes
// through the static filter (magnitude.hpp: float inputs keep every monomial of at most six factors
// normal in double; about a third of the instructions of Bounded<float>, and an evaluation error
// u_double·m instead of u_float·m), its trim margins through Bounded<double>. One precision for
// the whole certificate also keeps float lanes out of registers that hold doubles: clang -O1 packs
// a Bounded<float> into the low half of an xmm register and multiplies all four lanes, and double
// bits left in the upper ones read as subnormal floats (an x86 microcode assist each;
// subnormal_operand_test).
template <class Prim>
constexpr bool certified_in_double = std::is_same_v<scalar_t<Prim>, float> && has_static_residual<Prim>::value;
template <class Prim>
using certificate_scalar_t = std::conditional_t<certified_in_double<Prim>, double, scalar_t<Prim>>;

// Whether the primitive lists every length its residual reads (each_length: sphere, cylinder, cone).
struct AnyLength {
    template <class X>
    void operator()(const X&) const {}
};
template <class Prim, class = void>
struct lists_its_lengths : std::false_type {};
template <class Prim>
struct lists_its_lengths<Prim, std::void_t<decltype(each_length(std::declval<const Prim&>(), AnyLength{}))>> : std::true_type {};

// The residual at t in the static filter, and whether its guarantee holds: every monomial's
// nonzero magnitudes multiply within double's normal range (magnitude.hpp). Float inputs keep six
// factors there; fifteen when every input is zero or within 2^±64 ([2^-960, 2^960]), which a
// primitive listing its lengths can check: the cone's surface residual, |(q × A)|²·|A|² − (r·|A|²)²,
// has degree eight.
template <class Prim>
RAYQ_INLINE bool static_residual(const Ray<scalar_t<Prim>>& ray, const Prim& prim, scalar_t<Prim> t, Part part,
                                 Residual<Magnitude<double>>& r)
{
    using M = Magnitude<double>;
    r = residual(prim, lift<M>(ray.origin), lift<M>(ray.direction), M{double(t)}, part);
    const int degree = std::max(r.f.d, std::max(r.df.d, r.a.d));
    if (degree <= 6) return true;
    if constexpr (lists_its_lengths<Prim>::value) {
        if (degree > 15) return false;
        bool within = all_evaluated(zero_or_within_exact_range(ray.origin), zero_or_within_exact_range(ray.direction),
                                    zero_or_within_exact_range(t));
        each_length(prim, [&](const auto& x) { within = all_evaluated(within, zero_or_within_exact_range(x)); });
        return within;
    }
    return false;
}

// How far the exact root can be from t (certify_root), rounded up to T. Flattened, as are the two
// below: left to GCC -O3, the residual in Magnitude<double> was a call that returned its 96 bytes
// through memory and counted k, p, d at run time (rayq-bench, float sphere under `fast`, full
// record: 10% slower than Bounded<float> despite 12% fewer instructions). The cylinder's, cone's
// and plane_residual's residuals are forced inline besides: GCC called them "not inlinable" there.
template <class Prim>
RAYQ_FLATTEN inline scalar_t<Prim> certified_root_distance(const Ray<scalar_t<Prim>>& ray, const Prim& prim, scalar_t<Prim> t, Part part)
{
    using T = scalar_t<Prim>;
    if constexpr (certified_in_double<Prim>) {
        Residual<Magnitude<double>> r;
        if (static_residual(ray, prim, t, part, r)) {
            const double h = certify_root(Residual<Bounded<double>>{bounded(r.f), bounded(r.df), bounded(r.a)});
            const float hf = float(h);
            return double(hf) < h ? next_up(hf) : hf;
        }
    }
    return certify_root(residual(prim, exact(ray.origin), exact(ray.direction), Bounded<T>{t}, part));
}

// Whether F(t) < 0 for certain: t lies inside the surface.
template <class Prim>
RAYQ_FLATTEN inline bool certainly_inside(const Ray<scalar_t<Prim>>& ray, const Prim& prim, scalar_t<Prim> t)
{
    using T = scalar_t<Prim>;
    if constexpr (certified_in_double<Prim>) {
        Residual<Magnitude<double>> r;
        if (static_residual(ray, prim, t, Part::surface, r)) return certain_sign(r.f) < 0;
    }
    const Bounded<T> f = residual(prim, exact(ray.origin), exact(ray.direction), Bounded<T>{t}, Part::surface).f;
    return f.v < T(0) && lower(f) > T(0);
}

// Whether every root within t_error of t lies on the trimmed part (trim_margins).
template <class Prim>
RAYQ_FLATTEN inline bool certainly_on_part(const Ray<scalar_t<Prim>>& ray, const Prim& prim, scalar_t<Prim> t, scalar_t<Prim> t_error, Part part)
{
    using W = certificate_scalar_t<Prim>;
    using N = Bounded<W>;
    return certainly_within(trim_margins(prim, lift<N>(ray.origin), lift<N>(ray.direction), N{W(t), W(t_error)}, part));
}

template <class Policy, class Prim>
inline HitBounds<scalar_t<Prim>> certify_hit(Policy, const Ray<scalar_t<Prim>>& ray, const Prim& prim, const Crossing<scalar_t<Prim>>& c,
                                             const Vec3<scalar_t<Prim>>& point)
{
    using T = scalar_t<Prim>;
    const bool saturated[3] = {std::isinf(point.x), std::isinf(point.y), std::isinf(point.z)};
    constexpr bool exact_decisions = std::is_same_v<Policy, accurate_policy> && accurate_decides_exactly<Prim>::value;
    T t_error;
    if (exact_decisions && c.rounded) {
        // accurate decided hit, part and window exactly, and certified that t is the exact root
        // correctly rounded (or the float next to the window's end, the root lying within an ulp
        // of it): the root is within one ulp of t. (The exact search is exact at every magnitude
        // since its decisions fall back to Dyadic where expansions leave double's range: before,
        // planes near DBL_MAX were rounded 7 ulps off, and its roots got the a-posteriori bound.)
        t_error = detail::wider_gap(c.t);
    } else {
        // A posteriori, independent of how t was found: bounds on F(t), F'(t) and a certify how
        // far the exact root can be (detail::certify_root).
        t_error = certified_root_distance(ray, prim, c.t, c.part);
    }
    // The point errs by t_error·|d| plus the rounding of o + t·d (at most two roundings:
    // γ(2)·(|o| + |t·d|), pbrt-v4 §6.8.5).
    const T root_error = t_error;  // the crossing's own bound: what the point's error needs
    // The certified root must also provably lie inside the window, or it may not be this hit
    // (decided exactly under exact_decisions).
    if (!exact_decisions && !(c.t - t_error > ray.tmin && c.t + t_error < ray.tmax)) t_error = std::numeric_limits<T>::infinity();
    // ... and on the trimmed part (inside the triangle, within the side's height, the cap's
    // radius, the clip box): a root of the untrimmed surface near a rim may belong to no hit at
    // all. Policies whose trim decisions are exact have nothing to prove here.
    if (!exact_decisions && std::isfinite(t_error) &&
        !certainly_on_part(ray, prim, c.t, t_error, c.part))
        t_error = std::numeric_limits<T>::infinity();
    const T g2 = T(2) * unit_roundoff<T> / (T(1) - T(2) * unit_roundoff<T>);
    // A component the ray does not move along gains nothing from t's error (not ∞·0 = NaN).
    const auto axis_error = [&](T o, T d) {
        return grow((d == T(0) ? T(0) : root_error * std::abs(d)) + g2 * (std::abs(o) + std::abs(c.t * d)));
    };
    constexpr T inf = std::numeric_limits<T>::infinity();
    return {t_error,
            {saturated[0] ? inf : axis_error(ray.origin.x, ray.direction.x), saturated[1] ? inf : axis_error(ray.origin.y, ray.direction.y),
             saturated[2] ? inf : axis_error(ray.origin.z, ray.direction.z)}};
}

// The outward normal at ray(t), whose rounded value is p: a primitive with a shorter form in t
// supplies its own (cylinder.hpp); the others take their normal at p.
template <class Prim, class T>
RAYQ_INLINE Vec3<T> outward_normal_on_ray(const Prim& prim, const Ray<T>&, T, const Vec3<T>& p, Part part)
{
    return outward_normal(prim, p, part);
}

// The hit record of crossing c, with the fields asked for. Forced inline, its rare parts
// (facing_ray, certify_hit) out of line: GCC had called the whole record out of line from a
// scene's closest hit (16 capped cylinders under `fast`, point and normal: 18% of the samples in
// it; standalone loop, -march=native, ns per ray, three alternating runs: 27.3, 27.5, 27.3 ->
// 24.6, 25.2, 24.2 with complete() inlined too; rayq-bench-embree, two runs, µs per 4,096 rays:
// 16 spheres 69.2, 73.6 -> 63.4, 69.8, 16 capped cylinders 116.8, 125.5 -> 115.8, 121.4).
// Written into h, whose fields not asked for keep what they hold (a fresh Hit's defaults), so that a
// caller keeping the record in memory gets it stored there field by field (scene.hpp's
// fill_scene_hit, intersect(), intersect_all()). The bounds come back by value, so h never escapes
// into a call.
template <class Policy, class Prim>
RAYQ_INLINE void write_hit(Policy policy, const Ray<scalar_t<Prim>>& ray, const Prim& prim, const Crossing<scalar_t<Prim>>& c,
                           HitFields fields, Hit<scalar_t<Prim>>& h)
{
    using T = scalar_t<Prim>;
    h.t = c.t;
    h.front_face = c.entering;
    h.part = c.part;
    if (fields == HitFields::t) return;
    const Vec3<T> point = detail::point_at(policy, ray.origin, ray.direction, c.t);
    // A point beyond the largest float (a ray starting near it) saturates to the nearest finite
    // value, as rounding with saturation would; its error bound becomes infinite (certify_hit).
    const auto saturate = [](T x) { return std::isinf(x) ? std::copysign(std::numeric_limits<T>::max(), x) : x; };
    const Vec3<T> p{saturate(point.x), saturate(point.y), saturate(point.z)};
    if (wants(fields, HitFields::point)) h.point = p;
    if (wants(fields, HitFields::normal)) {
        // Face the incoming ray: outward where it enters, inward where it leaves. The side comes from
        // the crossing (the root order; exact under the accurate policy), not from the sign of
        // dot(n, d), which is noise at grazing incidence.
        const Vec3<T> outward = outward_normal_on_ray(prim, ray, c.t, p, c.part);
        Vec3<T> n;
        if (direct_unit(outward, n)) {
            if (!c.entering) n = -n;
        } else {
            n = unit_facing_side(outward, c.entering, ray.direction);
        }
        // The promise is dot(normal, direction) <= 0 as computed in T. Where the side and the rounded
        // normal disagree — grazing incidence, where the exact normal is nearly perpendicular to d, or a
        // point a non-exact policy placed off the surface — the normal is reflected across the plane
        // perpendicular to d (a flip would turn a grazing normal by ~π), nudged by an ulp while
        // rounding keeps the sign; front_face keeps the crossing's side.
        if (dot(n, ray.direction) > T(0)) n = facing_ray(n, ray.direction);
        h.normal = n;
    }
    if (wants(fields, HitFields::bounds)) {
        const HitBounds<T> b = certify_hit(policy, ray, prim, c, point);
        h.t_error = b.t_error;
        h.point_error = b.point_error;
    }
}

// A crossing the window excluded (t <= tmin) whose exact root may nevertheless lie inside it:
// then the exact first hit may be that root, anywhere in (tmin, t of the reported hit), and the
// reported hit's bound must reach back to tmin. Policies with exact decisions have excluded it
// exactly.
template <class Policy, class Prim>
inline bool may_enter_window(Policy, const Ray<scalar_t<Prim>>& ray, const Prim& prim, const Crossing<scalar_t<Prim>>& c)
{
    if (std::is_same_v<Policy, accurate_policy> && accurate_decides_exactly<Prim>::value) return false;
    if (!(c.t <= ray.tmin)) return false;
    return !(c.t + certified_root_distance(ray, prim, c.t, c.part) <= ray.tmin);
}

// The first crossing in the window as a hit, written into a fresh record h (write_hit); its bound
// covers every earlier crossing that may exactly lie in the window.
// Forced inline, as the record was where GCC inlined it (rayq-bench: the accurate double
// plane's intersect() called it out of line once it wrote in place).
template <class Policy, class Prim>
RAYQ_INLINE void write_first_hit(Policy policy, const Ray<scalar_t<Prim>>& ray, const Prim& prim, const Crossing<scalar_t<Prim>>& c,
                                 bool earlier_may_count, HitFields fields, Hit<scalar_t<Prim>>& h)
{
    write_hit(policy, ray, prim, c, fields, h);
    if (!wants(fields, HitFields::bounds)) return;
    // A first hit that leaves the surface says the window starts inside (F(tmin) < 0): if that is
    // not certain, an entering root before it may have been lost (cancellation in the fast
    // formula, a far-away primitive in float).
    if (!(std::is_same_v<Policy, accurate_policy> && accurate_decides_exactly<Prim>::value) && !c.entering &&
        c.part == Part::surface && std::isfinite(ray.tmin)) {
        earlier_may_count = earlier_may_count || !certainly_inside(ray, prim, ray.tmin);
    }
    if (earlier_may_count) h.t_error = std::max(h.t_error, grow(c.t - ray.tmin));
}

// The crossings a closest- or any-hit query needs: the first one in the window. A primitive whose
// crossings() takes a trailing limit (the accurate curved primitives, where every crossing costs an
// exactly rounded root) computes no more than that; the others compute all (at most two).
template <class Policy, class Prim>
RAYQ_INLINE auto crossings_up_to(Policy policy, const Ray<scalar_t<Prim>>& ray, const Prim& prim, int limit, int)
    -> decltype(crossings(policy, ray, prim, limit))
{
    return crossings(policy, ray, prim, limit);
}
template <class Policy, class Prim>
RAYQ_INLINE Crossings<scalar_t<Prim>> crossings_up_to(Policy policy, const Ray<scalar_t<Prim>>& ray, const Prim& prim, int, long)
{
    return crossings(policy, ray, prim);
}
template <class Policy, class Prim>
RAYQ_INLINE Crossings<scalar_t<Prim>> leading_crossings(Policy policy, const Ray<scalar_t<Prim>>& ray, const Prim& prim)
{
    return crossings_up_to(policy, ray, prim, 1, 0);
}

// The first of `cs` inside (tmin, tmax), or null: the cheap core that closest-hit searches over
// many primitives run before building one hit record, as leading_crossings() then this (ray and
// primitive already accepted). A pointer into `cs`, not a std::optional copy: GCC wrote the
// optional's flag as one byte and read it back as four, a store-forwarding stall on every miss (a
// one-capped-cylinder scene's nearest() took 23 ns per ray against occluded()'s 10).
template <class T>
RAYQ_INLINE const Crossing<T>* first_in_window(const Ray<T>& ray, const Crossings<T>& cs)
{
    for (const auto& c : cs)
        if (in_window(ray, c.t)) return &c;
    return nullptr;
}

template <class Prim>
inline bool accepts(const Ray<scalar_t<Prim>>& ray, const Prim& prim)
{
    return usable(ray) && static_cast<bool>(validate(prim));
}

}  // namespace detail

// `fields`: which optional parts of the record to compute (HitFields; all by default).
template <class Policy, class Prim, std::enable_if_t<is_policy_v<Policy> && is_primitive_v<Prim>, int> = 0>
inline std::optional<Hit<scalar_t<Prim>>> intersect(Policy policy, const Ray<scalar_t<Prim>>& ray, const Prim& prim,
                                                    HitFields fields = HitFields::all)
{
    // The record is written where it is returned (every return names `out`: NRVO), not built in a
    // Hit and copied: GCC copied that one in 16-byte loads of fields just stored as 8-, 4- and 2-byte
    // pieces, store-forwarding stalls on every hit (as fill_scene_hit's, scene.hpp).
    std::optional<Hit<scalar_t<Prim>>> out;
    if (!detail::accepts(ray, prim)) return out;
    bool earlier_may_count = false;
    for (const auto& c : detail::leading_crossings(policy, ray, prim)) {
        if (detail::in_window(ray, c.t)) {
            detail::write_first_hit(policy, ray, prim, c, earlier_may_count, fields, out.emplace());
            return out;
        }
        // Only the bound needs to know whether an excluded crossing may exactly lie in the window.
        earlier_may_count = earlier_may_count || (wants(fields, HitFields::bounds) && detail::may_enter_window(policy, ray, prim, c));
    }
    return out;
}

template <class Policy, class Prim, std::enable_if_t<is_policy_v<Policy> && is_primitive_v<Prim>, int> = 0>
inline bool occluded(Policy policy, const Ray<scalar_t<Prim>>& ray, const Prim& prim)
{
    return detail::accepts(ray, prim) && detail::first_in_window(ray, detail::leading_crossings(policy, ray, prim)) != nullptr;
}

// One boundary crossing along the ray: the hit record and whether the ray enters the solid there
// (for flat primitives: whether it meets the front side).
template <class T>
struct Passage {
    Hit<T> hit;
    bool entering;
};

// Every crossing in (tmin, tmax), ascending in t — for CSG, thickness along a ray, volume
// integration. Fixed capacity (no allocation): no primitive has more than two.
template <class T>
struct Passages {
    int count = 0;
    Passage<T> item[2]{};

    constexpr int size() const { return count; }
    constexpr bool empty() const { return count == 0; }
    constexpr const Passage<T>& operator[](int i) const { return item[i]; }
    constexpr const Passage<T>* begin() const { return item; }
    constexpr const Passage<T>* end() const { return item + count; }
};

template <class Policy, class Prim, std::enable_if_t<is_policy_v<Policy> && is_primitive_v<Prim>, int> = 0>
inline Passages<scalar_t<Prim>> intersect_all(Policy policy, const Ray<scalar_t<Prim>>& ray, const Prim& prim,
                                              HitFields fields = HitFields::all)
{
    Passages<scalar_t<Prim>> out;
    if (!detail::accepts(ray, prim)) return out;
    bool earlier_may_count = false;
    for (const auto& c : crossings(policy, ray, prim)) {
        if (detail::in_window(ray, c.t)) {
            // Written in place, as intersect()'s record (a Hit built and copied in is read back
            // through failed store forwarding); out.item[] starts as fresh records.
            Passage<scalar_t<Prim>>& p = out.item[out.count++];
            p.entering = c.entering;
            if (out.count == 1) detail::write_first_hit(policy, ray, prim, c, earlier_may_count, fields, p.hit);
            else detail::write_hit(policy, ray, prim, c, fields, p.hit);
        } else {
            earlier_may_count = earlier_may_count || (wants(fields, HitFields::bounds) && detail::may_enter_window(policy, ray, prim, c));
        }
    }
    return out;
}

template <class Prim, std::enable_if_t<is_primitive_v<Prim>, int> = 0>
inline Passages<scalar_t<Prim>> intersect_all(const Ray<scalar_t<Prim>>& ray, const Prim& prim, HitFields fields = HitFields::all)
{
    return intersect_all(default_policy{}, ray, prim, fields);
}

template <class Prim, std::enable_if_t<is_primitive_v<Prim>, int> = 0>
inline std::optional<Hit<scalar_t<Prim>>> intersect(const Ray<scalar_t<Prim>>& ray, const Prim& prim, HitFields fields = HitFields::all)
{
    return intersect(default_policy{}, ray, prim, fields);
}

template <class Prim, std::enable_if_t<is_primitive_v<Prim>, int> = 0>
inline bool occluded(const Ray<scalar_t<Prim>>& ray, const Prim& prim)
{
    return occluded(default_policy{}, ray, prim);
}

}  // namespace rayq
