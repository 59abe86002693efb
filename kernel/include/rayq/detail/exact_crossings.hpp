// rayq — the accurate policy's crossings: every decision (hit or miss, which part, inside the
// window) made exactly on the float inputs, and every t rounded correctly from the exact root.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <optional>
#include <type_traits>
#include <utility>

#include "../hit.hpp"
#include "../query.hpp"
#include "../ray.hpp"
#include "exact.hpp"
#include "magnitude.hpp"
#include "spans.hpp"
#include "ulp.hpp"

namespace rayq::detail {

// One part's implicit function along the ray as coefficients at t = 0, in any number type: the
// primitive's own residual(), so the exact path evaluates the same formulation as t_error.
template <class Prim>
struct PartCoefficients {
    const Prim* prim;
    const Ray<scalar_t<Prim>>* ray;
    Part part;

    template <class N>
    Residual<N> at(N t) const
    {
        return residual(*prim, lift<N>(ray->origin), lift<N>(ray->direction), t, part);
    }
    template <class N>
    Residual<N> operator()(N zero) const
    {
        if constexpr (is_magnitude<N>::value) return first_at_zero(zero);
        else return at(zero);
    }
    // The static filter's coefficients (magnitude.hpp), with the primitive's residual inlined: its
    // rounding counts are then constants the compiler folds away.
    template <class N>
    RAYQ_FLATTEN Residual<N> first_at_zero(N zero) const { return at(zero); }
};

// Ends of spans, symbolically: ±infinity, a root of the side's quadratic, or a cap plane's t.
enum class EndKind : unsigned char { neg_inf, pos_inf, root, cap0, cap1 };
struct End {
    EndKind kind;
    int which = 0;  // for roots: 0 smaller, 1 larger
    constexpr bool finite() const { return kind != EndKind::neg_inf && kind != EndKind::pos_inf; }
};

// t kept strictly inside the ray's window, where the exact value it stands for lies: a value
// rounded onto (or, after unscaling, past) an end moves to the neighbouring float inside. An exact
// root of zero is +0 whichever stage rounded it (a closest hit once reported −0 where all passages
// reported +0, from the origin on a sphere of radius 2^-511: sphere libFuzzer harness).
template <class T>
inline T inside_window(const Ray<T>& ray, T t)
{
    if (!(t > ray.tmin)) t = next_up(ray.tmin);
    if (!(t < ray.tmax)) t = next_down(ray.tmax);
    return t + T(0);  // −0 + 0 = +0 in round-to-nearest; every other t is unchanged
}

// The same ray with the window (tmin, tmax): the narrowed queries that settle a rounding.
template <class T>
inline Ray<T> with_window(Ray<T> ray, T tmin, T tmax)
{
    ray.tmin = tmin, ray.tmax = tmax;
    return ray;
}

// The side solid's spans (where its implicit function is negative), ascending, from the signs of
// its quadratic (a side of ExactQuadratic's interface: sign_a, sign_b, sign_c, sign_disc).
template <class Quadratic>
inline int side_spans_of(const Quadratic& side, End (&enter)[2], End (&exit)[2])
{
    const End lo{EndKind::neg_inf}, hi{EndKind::pos_inf}, r0{EndKind::root, 0}, r1{EndKind::root, 1};
    int n = 0;
    const auto add = [&](End a, End b) { enter[n] = a, exit[n] = b, ++n; };
    if (side.sign_a() == 0) {
        if (side.sign_b() == 0) {
            if (side.sign_c() < 0) add(lo, hi);
        } else if (side.sign_b() < 0) {
            add(r0, hi);
        } else {
            add(lo, r0);
        }
    } else if (side.sign_disc() < 0 || (side.sign_disc() == 0 && side.sign_a() < 0)) {
        if (side.sign_a() < 0) add(lo, hi);  // inside everywhere (touching once, at an apex)
    } else if (side.sign_a() > 0) {
        add(r0, r1);
    } else {
        add(lo, r0);
        add(r1, hi);
    }
    return n;
}

// The slab between the cap planes; false when the ray runs parallel to them outside it.
template <class Quadratic>
inline bool slab_of(const Quadratic& cap0, const Quadratic& cap1, End& enter, End& exit)
{
    const int dg = cap0.sign_b();  // d·A, shared by both planes
    if (dg == 0) {
        enter = {EndKind::neg_inf};
        exit = {EndKind::pos_inf};
        return cap0.sign_c() >= 0 && cap1.sign_c() <= 0;  // (o − p0)·A >= 0, (o − p1)·A <= 0
    }
    enter = {dg > 0 ? EndKind::cap0 : EndKind::cap1};
    exit = {dg > 0 ? EndKind::cap1 : EndKind::cap0};
    return true;
}

// A curved primitive's side quadratic and, for axial primitives, its two cap planes, with exact
// comparisons between any two span ends and against floats.
template <class Prim>
class ExactSolid {
    using T = scalar_t<Prim>;
    using Coef = PartCoefficients<Prim>;
    using Quadratic = ExactQuadratic<T, Coef>;

public:
    ExactSolid(const Ray<T>& ray, const Prim& prim, bool axial) : ray_(ray), prim_(prim), side_(coef(Part::surface))
    {
        if (axial) {
            cap0_.emplace(coef(Part::cap0));
            cap1_.emplace(coef(Part::cap1));
        }
    }

    int side_spans(End (&enter)[2], End (&exit)[2]) const { return side_spans_of(side_, enter, exit); }
    bool slab(End& enter, End& exit) const { return slab_of(*cap0_, *cap1_, enter, exit); }

    // sign(x − y).
    int compare(End x, End y) const
    {
        if (x.kind == y.kind && !x.finite()) return 0;
        if (x.kind == EndKind::neg_inf || y.kind == EndKind::pos_inf) return -1;
        if (x.kind == EndKind::pos_inf || y.kind == EndKind::neg_inf) return 1;
        // Filters, cheapest first: disjoint certified intervals (no exact rounding needed; only
        // where rounding runs in double-word arithmetic — for float inputs it runs in hardware
        // double and costs no more than the enclosure: measured 5% more instructions with it,
        // 27% fewer for double), then rounded values two or more ulps apart (each exact end lies
        // strictly between the neighbours of its rounded value).
        if constexpr (std::is_same_v<wide_t<T>, DoubleWord<T>>) {
            if (const auto bx = enclosure(x), by = enclosure(y); bx && by) {
                if (bx->second < by->first) return -1;
                if (by->second < bx->first) return 1;
            }
        }
        if (const int s = separated(rounded(x), rounded(y))) return s;
        if (x.kind == EndKind::root && y.kind == EndKind::root)
            return side_.sign_disc() == 0 || x.which == y.which ? 0 : (x.which < y.which ? -1 : 1);
        if (x.kind == EndKind::root) return -side_.compare(x.which, coef(part_of(y.kind)));
        if (y.kind == EndKind::root) return side_.compare(y.which, coef(part_of(x.kind)));
        if (x.kind == y.kind) return 0;
        // t_cap0 − t_cap1 = ((o − p1)·A − (o − p0)·A)/(d·A) = −|A|²/(d·A).
        const int t0_minus_t1 = -cap0_->sign_b();
        return x.kind == EndKind::cap0 ? t0_minus_t1 : -t0_minus_t1;
    }

    // sign(e − x) for a float x (a window bound; ±infinity allowed).
    int compare(End e, T x) const
    {
        constexpr T inf = std::numeric_limits<T>::infinity();
        if (e.kind == EndKind::neg_inf) return x == -inf ? 0 : -1;
        if (e.kind == EndKind::pos_inf) return x == inf ? 0 : 1;
        if (!std::isfinite(x)) return x > T(0) ? -1 : 1;
        const T r = rounded(e);
        if (next_down(r) >= x) return 1;
        if (next_up(r) <= x) return -1;
        const FloatLine<T> at{-x, T(1)};
        return -quadratic(e).compare(e.which, at);
    }

    bool in_window(End e) const { return compare(e, ray_.tmin) > 0 && compare(e, ray_.tmax) < 0; }

    // The end's t correctly rounded (memoized), kept strictly inside the window (where the exact value is).
    T value(End e) const
    {
        return inside_window(ray_, rounded(e));
    }

private:
    T rounded(End e) const
    {
        const int slot = e.kind == EndKind::root ? e.which : (e.kind == EndKind::cap0 ? 2 : 3);
        if (!cache_[slot]) {
            const Quadratic& q = quadratic(e);
            cache_[slot] = q.round(e.which);
        }
        return *cache_[slot];
    }

    // A certified interval around the end (memoized): its rounded value's neighbours when that is
    // already known, else the quadratic's cheap enclosure.
    std::optional<std::pair<T, T>> enclosure(End e) const
    {
        const int slot = e.kind == EndKind::root ? e.which : (e.kind == EndKind::cap0 ? 2 : 3);
        if (cache_[slot]) return std::pair<T, T>{next_down(*cache_[slot]), next_up(*cache_[slot])};
        if (!enclosed_[slot]) enclosed_[slot] = quadratic(e).enclose(e.which);
        return *enclosed_[slot];
    }
    // sign(x − y) when x and y are at least two ulps apart, else 0.
    static int separated(T x, T y)
    {
        if (next_up(next_up(x)) <= y) return -1;
        if (next_up(next_up(y)) <= x) return 1;
        return 0;
    }

    static Part part_of(EndKind k) { return k == EndKind::cap0 ? Part::cap0 : Part::cap1; }
    Coef coef(Part p) const { return {&prim_, &ray_, p}; }
    const Quadratic& quadratic(End e) const
    {
        return e.kind == EndKind::root ? side_ : (e.kind == EndKind::cap0 ? *cap0_ : *cap1_);
    }

    const Ray<T>& ray_;
    const Prim& prim_;
    Quadratic side_;
    std::optional<Quadratic> cap0_, cap1_;
    mutable std::optional<T> cache_[4];  // rounded values: root 0, root 1, cap0, cap1
    mutable std::optional<std::optional<std::pair<T, T>>> enclosed_[4];  // their enclosures, once tried
};

// Crossings of a sphere-like (no caps) or axial (slab-clipped, open or capped) curved primitive,
// with the same interval logic as the floating-point path but exact comparisons. Only the first
// `limit` crossings inside the window are returned: each one costs a correctly rounded root.
// `Solid` is ExactSolid or the quick lane's QuickSolid. Written into `out` (see
// exact_curved_crossings).
template <class T, class Solid>
inline void solid_crossings(const Solid& solid, bool axial, bool capped, CapEnds ends, int limit, Crossings<T>& out)
{
    out.count = 0;
    End enter[2], exit[2];
    const int spans = solid.side_spans(enter, exit);
    struct Candidate {
        End end;
        Part part;
        bool entering;
    };
    Candidate found[4];
    int n = 0;
    End slab_in{EndKind::neg_inf}, slab_out{EndKind::pos_inf};
    if (axial && !solid.slab(slab_in, slab_out)) return;
    for (int i = 0; i < spans; ++i) {
        if (!axial) {
            found[n++] = {enter[i], Part::surface, true};
            found[n++] = {exit[i], Part::surface, false};
        } else if (capped) {
            // Solid = side ∩ slab; at a tie the cap wins where that end has one.
            const auto cap_part = [](End e) { return e.kind == EndKind::cap0 ? Part::cap0 : Part::cap1; };
            const bool cap_in = solid.compare(slab_in, enter[i]) >= 0, cap_out = solid.compare(slab_out, exit[i]) <= 0;
            const End in = cap_in ? slab_in : enter[i], out = cap_out ? slab_out : exit[i];
            if (solid.compare(in, out) > 0) continue;
            const Part in_part = cap_in && in.finite() && ends.closes(cap_part(in)) ? cap_part(in) : Part::surface;
            const Part out_part = cap_out && out.finite() && ends.closes(cap_part(out)) ? cap_part(out) : Part::surface;
            found[n++] = {in, in_part, true};
            found[n++] = {out, out_part, false};
            break;  // convex: one span survives
        } else {
            for (const auto& [e, entering] : {std::pair{enter[i], true}, std::pair{exit[i], false}})
                if (e.finite() && solid.compare(slab_in, e) <= 0 && solid.compare(e, slab_out) <= 0) found[n++] = {e, Part::surface, entering};
        }
    }
    // The ends are in ascending exact order, so their correctly rounded values are too (before
    // Dyadic, expansions that underflowed broke this: the axial and transformed libFuzzer
    // harnesses' ascending invariant on cones of size 2^-511 and with a 3·2^-1074 apex coordinate).
    for (int i = 0; i < n && out.count < limit; ++i)
        if (found[i].end.finite() && solid.in_window(found[i].end))
            out.add(solid.value(found[i].end), found[i].part, found[i].entering, true);
}

template <class Prim>
inline Crossings<scalar_t<Prim>> exact_curved_crossings_unscaled(const Ray<scalar_t<Prim>>& ray, const Prim& prim, bool axial, bool capped,
                                                                  CapEnds ends, int limit)
{
    Crossings<scalar_t<Prim>> out;
    solid_crossings(ExactSolid<Prim>(ray, prim, axial), axial, capped, ends, limit, out);
    return out;
}

// x·2^k, and whether that is exact (no overflow, no bits lost to underflow).
template <class T>
inline bool scale_exactly(T& x, int k)
{
    const T y = std::ldexp(x, k);
    if (!(std::ldexp(y, -k) == x)) return false;
    x = y;
    return true;
}

// Magnitudes the exact expansions take as they are: a product of up to twelve factors in
// [2^-64, 2^64] stays within double's exponent range (and float's, lifted to double).
template <class T>
constexpr bool within_exact_range(T magnitude) { return magnitude >= T(0x1p-64) && magnitude <= T(0x1p64); }
// zero_or_between, zero_or_within_exact_range and all_evaluated: detail/ulp.hpp.

// Whether the static filter (magnitude.hpp) may take these inputs: each 0 or within 2^±64, so that
// products of up to six of them stay in double's normal range. Float inputs, in double, always may.
template <class T>
RAYQ_INLINE bool within_static_range(T x)
{
    if constexpr (std::is_same_v<T, float>) return true;
    else return zero_or_within_exact_range(x);
}
// within_static_range for many inputs at once: the largest magnitude and the smallest nonzero one
// (less one, as unsigned integers, so that ±0 wraps to the largest), then two comparisons. Same
// decision as each input's zero_or_between; about 7 integer operations per input against 10, and
// the sphere's quick lane took 1.7 ns less per ray (pt.cpp, SSE2, min of 31: 60.1 -> 58.4 ns).
template <class T>
class StaticRange {
public:
    RAYQ_INLINE StaticRange& add(T x)
    {
        if constexpr (!std::is_same_v<T, float>) {
            const std::uint64_t magnitude = magnitude_bits(x);
            largest_ = std::max(largest_, magnitude);
            smallest_less_one_ = std::min(smallest_less_one_, magnitude - 1);
        }
        return *this;
    }
    RAYQ_INLINE StaticRange& add(const Vec3<T>& v) { return add(v.x).add(v.y).add(v.z); }
    // Float inputs, in double, always lie within it (within_static_range).
    RAYQ_INLINE bool holds() const
    {
        if constexpr (std::is_same_v<T, float>) return true;
        else return all_evaluated(largest_ <= bits_of(0x1p64), smallest_less_one_ >= bits_of(0x1p-64) - 1);
    }

private:
    std::uint64_t largest_ = 0, smallest_less_one_ = ~std::uint64_t(0);
};
// A primitive's inputs and the ray's.
template <class Prim>
RAYQ_INLINE bool inputs_within_static_range(const Ray<scalar_t<Prim>>& ray, const Prim& prim)
{
    StaticRange<scalar_t<Prim>> range;
    range.add(ray.origin).add(ray.direction);
    each_length(prim, [&](const auto& x) { range.add(x); });
    return range.holds();
}

template <class X>
struct static_range_scalar {
    using type = X;
};
template <class T>
struct static_range_scalar<Vec3<T>> {
    using type = T;
};
template <class X, class... Rest>
RAYQ_INLINE bool all_within_static_range(const X& x, const Rest&... rest)
{
    StaticRange<typename static_range_scalar<X>::type> range;
    range.add(x);
    (range.add(rest), ...);
    return range.holds();
}

// newton_rounded for the quick lanes, whose inputs are within the static range: F in a double word
// with a static bound (StaticDoubleWord), F' and a in the static filter (magnitude.hpp). Flattened,
// each residual computes only the part it is used for. A double's accurate closest hit took fewer
// instructions than with running bounds (callgrind, -O3, AVX2+FMA / SSE2): sphere 41% / 41%,
// capped cylinder 32% / 36%, cone 33% / 37%, disk 20% / 17%, triangle 8% / 8%.
// A guess t outside the range, or a residual beyond the degrees the range covers, takes the
// running bounds (newton_rounded). Double only: a float root needs no Newton step in the quick lanes.
// A part whose primitive evaluates F itself for the quick lanes' Newton steps: the primitive's
// `quick_residual_f(prim, ray, t, part)`, found by argument-dependent lookup (the sphere's,
// sphere.hpp, with a shorter chain after t than the residual in StaticDoubleWord).
template <class Coef, class = void>
struct has_quick_residual_f : std::false_type {};
template <class Coef>
struct has_quick_residual_f<Coef, std::void_t<decltype(quick_residual_f(*std::declval<const Coef&>().prim, *std::declval<const Coef&>().ray,
                                                                        std::declval<const Coef&>().ray->tmin, Part::surface,
                                                                        AsBuiltProducts{}))>>
    : std::true_type {};

// F(t) in a double word for the Newton step, its products' error terms formed by `Products`.
// Degrees: StaticDoubleWord's grid argument (at most 8; checked by the caller).
template <class T, class Coef, class Products>
RAYQ_INLINE Estimate<T> quick_residual_estimate(const Coef& coef, T t, Products)
{
    if constexpr (has_quick_residual_f<Coef>::value) return quick_residual_f(*coef.prim, *coef.ray, t, coef.part, Products{});
    else return estimate(coef.at(StaticDoubleWord<T, Products>{t}).f);
}

// Hardware FMA where the CPU has one, whatever the build targets: without it (the x86-64
// baseline) a double word's product is Dekker's, 17 operations where FMA takes two, and the Newton
// step's F(t) took most of a double plane's accurate query (callgrind, SSE2: 661 instructions per
// ray against fast's 467; rayq-bench, accurate ÷ fast 1.35). The evaluation runs in a function
// compiled for FMA (GCC and clang's target attribute), called only where the CPU reports FMA and
// the OS its AVX state (__builtin_cpu_supports checks both); elsewhere, and before static
// initialization has probed the CPU, the build's own products. Both are within the same bound,
// and a step that certifies its root gives the correctly rounded one either way. Within that
// function GCC (GNU mode) may contract a·b + c into FMA: one rounding instead of two, which
// StaticDoubleWord's and the sphere's bounds cover (they count roundings as upper bounds; Dekker's
// split, which contraction would break, is not used there).
#if (defined(__x86_64__) || defined(__i386__)) && (defined(__GNUC__) || defined(__clang__)) && !defined(__FMA__)
#define RAYQ_FMA_DISPATCH 1
inline bool cpu_has_fma()
{
    __builtin_cpu_init();  // static initialization may run before libgcc's own
    return __builtin_cpu_supports("fma");
}
// Tests clear it to run the build's own products on a machine with FMA.
inline bool use_fused_products = cpu_has_fma();
template <class T, class Coef>
__attribute__((target("fma"), noinline)) RAYQ_FLATTEN Estimate<T> fused_residual_estimate(const Coef& coef, T t)
{
    return quick_residual_estimate(coef, t, FusedProducts{});
}
#endif
template <class T, class Coef>
RAYQ_INLINE Estimate<T> quick_f_estimate(const Coef& coef, T t)
{
#if defined(RAYQ_FMA_DISPATCH)
    if (use_fused_products) return fused_residual_estimate(coef, t);
#endif
    return quick_residual_estimate(coef, t, AsBuiltProducts{});
}

template <class T, class Coef>
RAYQ_FLATTEN inline std::optional<T> quick_newton_rounded(const Coef& coef, int sign_a, int which, T t)
{
    static_assert(std::is_same_v<T, double>, "the quick lanes round float roots from their intervals");
    if (within_static_range(t)) {
        const Residual<Magnitude<T>> slopes = coef.at(Magnitude<T>{t});
        // Degrees: StaticDoubleWord's grid argument (F's degree, counted as the filter counts it:
        // the sphere's own evaluation needs no check, sphere.hpp); products of at most 15
        // magnitudes in 2^±64 stay normal (magnitude.hpp).
        if ((has_quick_residual_f<Coef>::value || slopes.f.d <= 8) && slopes.df.d <= 15 && slopes.a.d <= 15)
            return newton_step(quick_f_estimate(coef, t), Estimate<T>{slopes.df.v(), slopes.df.bound()},
                               Estimate<T>{slopes.a.v(), slopes.a.bound()}, sign_a, which, t);
    }
    return newton_rounded<T>(coef, sign_a, which, t);
}

// A normal (or any direction whose length does not matter) scaled by a power of two so that its
// largest component is near 1, when it is far from 1 and the scaling is exact: the exact inside
// tests square it (a disk's rim at the plane's root has |n|² in every term), and a component of
// 2^511 made those products overflow (found by the fuzz harnesses' stream invariant: a disk hit
// 8e9 away from its center). Homogeneous in n, so every decision is unchanged.
template <class T>
inline Vec3<T> direction_near_unit(const Vec3<T>& n)
{
    const T largest = std::max({std::abs(n.x), std::abs(n.y), std::abs(n.z)});
    if (!(largest > T(0)) || !std::isfinite(largest) || within_exact_range(largest)) return n;
    const int k = std::ilogb(largest);
    Vec3<T> scaled = n;
    const bool exact = scale_exactly(scaled.x, -k) && scale_exactly(scaled.y, -k) && scale_exactly(scaled.z, -k);
    return exact ? scaled : n;
}

// The ray and the primitive with every point and radius scaled by 2^-kl and the direction by 2^-kd
// (the window follows: t' = t·2^(kd−kl)); none when a scaling is inexact.
template <class Prim>
struct Rescaled {
    Ray<scalar_t<Prim>> ray;
    Prim prim;
};

template <class Prim>
inline std::optional<Rescaled<Prim>> rescaled(const Ray<scalar_t<Prim>>& ray, const Prim& prim, int kl, int kd)
{
    using T = scalar_t<Prim>;
    Rescaled<Prim> out{ray, prim};
    bool exact = true;
    const auto length_unit = [&](auto& x) {
        if constexpr (std::is_same_v<std::decay_t<decltype(x)>, T>)
            exact = exact && scale_exactly(x, -kl);
        else
            exact = exact && scale_exactly(x.x, -kl) && scale_exactly(x.y, -kl) && scale_exactly(x.z, -kl);
    };
    each_length(out.prim, length_unit);
    length_unit(out.ray.origin);
    for (T* x : {&out.ray.direction.x, &out.ray.direction.y, &out.ray.direction.z}) exact = exact && scale_exactly(*x, -kd);
    // A window end that overflows when scaled (tmax = DBL_MAX for a tiny primitive, scaled up by
    // 2^115: found by the fuzz harnesses' scene invariant, where the unscaled fallback underflowed
    // and the scene's narrowed window got another answer) becomes ±inf: it is then at least
    // 2^1024 in the new unit, beyond every root whose scaled value is finite, and the roots that
    // are not finite fall back below.
    const auto scale_end = [&](T& x) {
        const T y = std::ldexp(x, kd - kl);
        if (std::isinf(y) && std::isfinite(x)) x = y;
        else exact = exact && scale_exactly(x, kd - kl);
    };
    scale_end(out.ray.tmin);
    scale_end(out.ray.tmax);
    if (!exact) return std::nullopt;
    return out;
}

// The crossings in the rescaled unit, their t left in it; none when a root is not finite there.
template <class Prim>
inline std::optional<Crossings<scalar_t<Prim>>> scaled_crossings(const std::optional<Rescaled<Prim>>& unit, bool axial, bool capped,
                                                                  CapEnds ends, int limit)
{
    if (!unit) return std::nullopt;
    Crossings<scalar_t<Prim>> out = exact_curved_crossings_unscaled(unit->ray, unit->prim, axial, capped, ends, limit);
    for (const auto& c : out)
        if (!std::isfinite(c.t)) return std::nullopt;
    return out;
}

// A root x rounded to a coarser grid (a smaller unit's subnormals, or float from double) from
// `fine`, its correct rounding on the finer one: rounding twice errs exactly when `fine` is a
// midpoint of the coarse grid (the sphere libFuzzer harness: a float root at 0x1.4523246fp-128,
// rescaled and rounded to 24 bits, came back from ldexp as 0x1.45232p-128, 0.555 ulp off).
// The side of `fine` on which x lies then decides, read from which of the windows
// (fine⁻, fine) and (fine, fine⁺) `crossing_in` finds the crossing in: the exact path decides
// windows exactly.
template <class Coarse, class Fine, class ToCoarse, class ToFine, class CrossingIn>
inline Coarse rounded_once(Fine fine, ToCoarse to_coarse, ToFine to_fine, CrossingIn crossing_in)
{
    const Coarse t = to_coarse(fine);
    if (to_fine(t) == fine) return t;
    const Coarse other = to_fine(t) < fine ? next_up(t) : next_down(t);
    // Both neighbours are on the coarse grid, at least two fine ulps apart, so their sum is exact.
    if (to_fine(t) + to_fine(other) != Fine(2) * fine) return t;
    if (crossing_in(next_down(fine), fine)) return std::min(t, other);
    if (crossing_in(fine, next_up(fine))) return std::max(t, other);
    return t;  // x = fine: a true tie, and to_coarse rounded it to even
}

// Whether `found` holds crossing c's part and direction.
template <class T>
inline bool holds(const Crossings<T>& found, const Crossing<T>& c)
{
    for (const Crossing<T>& x : found)
        if (x.part == c.part && x.entering == c.entering) return true;
    return false;
}

// t'·2^shift rounded to nearest, for a t' that is the exact root correctly rounded in the
// rescaled unit (ldexp rounds a second time when the result is subnormal).
template <class Prim>
inline scalar_t<Prim> unscaled_t(const Crossing<scalar_t<Prim>>& c, int shift, const Rescaled<Prim>& unit, bool axial, bool capped,
                                 CapEnds ends)
{
    using T = scalar_t<Prim>;
    return rounded_once<T>(
        c.t, [&](T x) { return std::ldexp(x, shift); }, [&](T x) { return std::ldexp(x, -shift); },
        [&](T lo, T hi) { return holds(exact_curved_crossings_unscaled(with_window(unit.ray, lo, hi), unit.prim, axial, capped, ends, 2), c); });
}

// The exact path's unit of length: the largest radius or distance from the ray's origin to one of
// the primitive's points (each_length).
template <class Prim>
inline scalar_t<Prim> reach_of(const Ray<scalar_t<Prim>>& ray, const Prim& prim)
{
    using T = scalar_t<Prim>;
    T reach = T(0);
    const auto see = [&](T x) { reach = std::max(reach, std::abs(x)); };
    each_length(prim, [&](const auto& x) {
        if constexpr (std::is_same_v<std::decay_t<decltype(x)>, T>) see(x);
        else see(x.x - ray.origin.x), see(x.y - ray.origin.y), see(x.z - ray.origin.z);
    });
    return reach;
}

// The same, with the inputs' units changed first when their magnitudes are far from 1. Expansions
// are exact only while no product (up to about twelve factors: a discriminant compared with a cap's
// t) under- or overflows, and distances of 2^200 in double made them overflow (and the root search
// run for ever). The products are of differences (o − c, p1 − p0), radii and the direction, so
// the scale comes from those: every point (the origin's and the primitive's) and radius is scaled
// by 2^-kl and the direction by 2^-kd, bringing the largest distance and direction component near
// 1. The residuals are homogeneous, so every sign is unchanged, and t' = t·2^(kd−kl) exactly,
// which is undone on the rounded t.
template <class Prim>
inline Crossings<float> float_crossings_in_double(const Ray<float>& ray, const Prim& prim, bool axial, bool capped, CapEnds ends, int limit);

template <class Prim>
inline Crossings<scalar_t<Prim>> exact_curved_crossings_in_unit(const Ray<scalar_t<Prim>>& ray, const Prim& prim, bool axial, bool capped,
                                                                 CapEnds ends, int limit, scalar_t<Prim> length)
{
    using T = scalar_t<Prim>;
    const T direction = std::max({std::abs(ray.direction.x), std::abs(ray.direction.y), std::abs(ray.direction.z)});
    const bool in_range = zero_or_within_exact_range(length) && within_exact_range(direction);
    if constexpr (std::is_same_v<T, float>) {
        // Float inputs are solved in double's unit instead: every float scaled by the powers of
        // two the unit needs stays exact in double (a float difference that overflows, too), and a
        // float problem's roots then land inside double's normal range, so the rescaled roots lose
        // no bits and one rounding to float remains (rounded_once). Rescaling within float's
        // range could not lift every root above float's subnormals: a float sphere of radius 2^127
        // with its root at 0x1.7081d7a5p-129 got 2^-24 (found by the sphere libFuzzer harness).
        if (!in_range && direction > T(0) && std::isfinite(direction)) return float_crossings_in_double(ray, prim, axial, capped, ends, limit);
    }
    // A zero, infinite or NaN magnitude (a degenerate ray mapped into a Transformed's object
    // space) has no unit to change.
    const bool scalable = std::isfinite(length) && direction > T(0) && std::isfinite(direction);
    if (in_range || !scalable) return exact_curved_crossings_unscaled(ray, prim, axial, capped, ends, limit);
    const int kl = length == T(0) ? 0 : std::ilogb(length), kd = std::ilogb(direction);
    // Only double inputs come here (float ones are widened above); the findings cited below were
    // float inputs before they were, and double's extremes give the same shapes 2^900 further out.
    // The rescaled problem's roots are t·2^(kd−kl), rounded in T: one that falls below T's normal
    // range there loses bits that unscaling cannot restore (a float sphere of radius 2^101 with
    // the origin 2^-102 outside it, seen along 2^-13: t = 2^-89 became 2^-203, rounded to 0 and
    // reported as 2^-35; found by the sphere libFuzzer harness). Such roots are solved again with
    // the lengths' unit lowered and the direction's raised by 2^63 each (the largest length and
    // direction component stay within the exact range), which lifts them by 2^126: as far as the
    // exact range allows (a float sphere of radius FLT_MAX crossed at t = 2^-114 along 2^-10
    // needed 2^125; found by the sphere libFuzzer harness). So is a window whose end cannot be scaled
    // exactly (tmax narrowed to such a root: a scene of copies does that; the sphere and axial
    // harnesses found answers that changed with the window, kernel tests SubnormalGapTo*).
    int shift = kl - kd;  // t = t'·2^shift
    std::optional<Rescaled<Prim>> unit = rescaled(ray, prim, kl, kd);
    std::optional<Crossings<T>> out = scaled_crossings(unit, axial, capped, ends, limit);
    const auto lost_bits = [](const Crossings<T>& c) {
        for (const Crossing<T>& x : c)
            if (std::abs(x.t) < std::numeric_limits<T>::min()) return true;
        return false;
    };
    // The direction's unit is raised by less where a small direction component cannot take all of
    // 2^63 exactly (a float direction (2^48, -1.75, -2^-52) toward a sphere of radius 2^101, root
    // 2^-146: found by the sphere libFuzzer harness), and not at all where one is subnormal
    // (0x1.5807bp-128 beside 2^-13, same sphere, root 2^-89): the lengths' unit is then lowered by
    // 2^80, which keeps products of twelve lengths below 2^972.
    if (!out || lost_bits(*out)) {
        for (const auto& [lower, raise] : {std::pair{63, 63}, std::pair{63, 31}, std::pair{63, 15}, std::pair{80, 0}}) {
            std::optional<Rescaled<Prim>> lifted_unit = rescaled(ray, prim, kl - lower, kd + raise);
            if (auto lifted = scaled_crossings(lifted_unit, axial, capped, ends, limit); lifted && !lost_bits(*lifted)) {
                out = lifted, unit = lifted_unit, shift -= lower + raise;
                break;
            }
        }
    }
    // Where no unit holds every root above T's subnormals (a sphere of radius 2^900 with the origin
    // 2^-301 outside it: t' = 2^-1201), the inputs are solved as they are: their decisions then
    // leave the expansions' range and are made in Dyadic (adaptive_sign), slower but exact.
    if (!out || lost_bits(*out)) return exact_curved_crossings_unscaled(ray, prim, axial, capped, ends, limit);
    for (Crossing<T>& c : out->item) {
        c.t = inside_window(ray, unscaled_t(c, shift, *unit, axial, capped, ends));  // exact unless subnormal or beyond the largest float
    }
    return *out;
}

template <class Prim>
inline Crossings<float> float_crossings_in_double(const Ray<float>& ray, const Prim& prim, bool axial, bool capped, CapEnds ends, int limit)
{
    const Ray<double> wide_ray = scalar_cast<double>(ray);
    const auto wide = scalar_cast<double>(prim);
    const double reach = reach_of(wide_ray, wide);
    Crossings<float> out;
    for (const Crossing<double>& c : exact_curved_crossings_in_unit(wide_ray, wide, axial, capped, ends, limit, reach)) {
        const float t = rounded_once<float>(
            c.t, [](double x) { return float(x); }, [](float x) { return double(x); },
            [&](double lo, double hi) { return holds(exact_curved_crossings_in_unit(with_window(wide_ray, lo, hi), wide, axial, capped, ends, 2, reach), c); });
        out.add(inside_window(ray, t), c.part, c.entering, c.rounded);
    }
    return out;
}

// An estimate of root `which` (0 the smaller) of a·t² + b·t + c, a of sign sign_a ≠ 0 and
// d = b² − 4ac, for a Newton step (which checks that the root it rounds is `which`): the
// cancellation-free q-form (Ray Tracing Gems ch. 7), q = −(b + sign(b)·√d)/2 and the roots q/a and
// c/q, of which only the one asked for is divided out. q/a = −(b + s·√d)/(2a) is the smaller
// exactly when s, the sign q takes from b's sign bit, is a's sign (as in root_interval).
template <class T>
RAYQ_INLINE T root_estimate(T a, T b, T c, T d, int sign_a, int which)
{
    const T q = T(-0.5) * (b + std::copysign(std::sqrt(std::max(d, T(0))), b));
    const bool q_over_a_smaller = std::signbit(b) == (sign_a < 0);
    return q_over_a_smaller == (which == 0) ? q / a : c / q;
}

// One part of a curved primitive (the side's quadratic, or a cap's plane) for the quick lane:
// ExactQuadratic's signs and roots decided by the static filter (magnitude.hpp) alone. A sign is
// certain when the filter's bound decides it, or zero when the magnitude is (every monomial
// vanishes). A float root is its certified interval's correctly rounded float (root_intervals or
// quotient, rounded_between_midpoints); a double root, whose interval in double spans ulps, is
// rounded by one certified double-word Newton step from the filter's estimate (newton_rounded).
// Whatever cannot be decided sets the shared `undecided` flag, and the lane's answer is then
// discarded. `coef` is the part's residual along the ray (PartCoefficients).
template <class T, class Coef, class F = Magnitude<double>>
class QuickQuadratic {
    static constexpr bool static_filter = is_magnitude<F>::value;

public:
    // Flattened: GCC left the part's coefficients (first_at_zero) out of line here, past its
    // inlining limit, so their rounding counts reached the filter's bounds as runtime values
    // (rayq-bench, SSE2, accurate frustum float 597 -> 525 us per 4,096 rays, open cylinder
    // double 1,078 -> 989; cylinder_test.cpp under clang ASan compiled 7% longer).
    RAYQ_FLATTEN QuickQuadratic(const Coef& coef, bool& undecided) : coef_(coef), r_(coef(t_zero())), undecided_(&undecided)
    {
        // Every product of nonzero magnitudes must stay normal (magnitude.hpp): the coefficients
        // have at most six input factors per monomial (b also the constant 2; double inputs are
        // within 2^±64, quick_solid_crossings) and, for the
        // discriminant's products and root_intervals' running-error steps, magnitudes within
        // 2^±400 or exactly zero. (An infinite or NaN input fails here too.)
        // (Running error bounds, the second try, need no such guarantee: they cover underflow,
        // and an overflow leaves a bound that decides nothing.)
        const Residual<F>& r = r_;
        if constexpr (static_filter) {
            const auto moderate = [](const F& x) { return zero_or_between(x.m(), 0x1p-400, 0x1p400); };
            if (!(r.a.d <= 6 && r.f.d <= 6 && r.df.d <= 7 && all_evaluated(moderate(r.a), moderate(r.df), moderate(r.f)))) undecided = true;
        }
        a_ = sign_of(r.a);
        if (a_.sign != 0) {
            // The discriminant by running error bounds on the filter's coefficients (pbrt-v4
            // "Managing Rounding Error"): its bound scales with |b|, |a|, |c| rather than with
            // their magnitudes. For rays passing close by a cylinder, the ones a scene's
            // bounding-sphere filter keeps, m(b)² + 4·m(a)·m(c) reached ~10^8 times b² − 4ac, the
            // roots' intervals grew wider than half a float ulp, and the lane declined half of them.
            disc_ = bounded(r.df) * bounded(r.df) - Bounded<double>{4.0} * bounded(r.a) * bounded(r.f);
            // Certainly zero when every monomial of b² and of a·c vanishes.
            if (vanishes(r.df) && (vanishes(r.a) || vanishes(r.f))) sign_disc_ = {0, true};
            else if (const int s = certain_sign(disc_)) sign_disc_ = {s, true};
            else sign_disc_ = {0, false};
        }
    }

    int sign_a() const { return use(a_); }
    int sign_b() const { return use(sign_of(r_.df)); }
    int sign_c() const { return use(sign_of(r_.f)); }
    int sign_disc() const { return use(sign_disc_); }

    // The root `which` (0 smaller, 1 larger; a line's only root when a vanishes), correctly rounded.
    // A float's both roots at once, from one pair of intervals (a solid's span logic orders both);
    // a double's each by one Newton step, only when asked for.
    T rounded(int which) const
    {
        if constexpr (std::is_same_v<T, float>) {
            if (!rounded_) {
                rounded_ = true;
                std::optional<float> t[2];
                if (a_.sign == 0) {
                    if (sign_b() != 0) t[0] = t[1] = rounded_between_midpoints<float>(line_root());
                } else if (const auto roots = root_intervals(bounded(r_.a), bounded(r_.df), bounded(r_.f), disc_)) {
                    t[0] = rounded_between_midpoints<float>((*roots)[0]), t[1] = rounded_between_midpoints<float>((*roots)[1]);
                }
                if (!t[0] || !t[1]) *undecided_ = true;
                root_[0] = t[0].value_or(0.0f), root_[1] = t[1].value_or(0.0f);
            }
        } else if (!done_[which]) {
            done_[which] = true;
            const std::optional<T> t = newton_from_estimate(which);
            if (!t) *undecided_ = true;
            root_[which] = t.value_or(T(0));
        }
        return root_[which];
    }
    // The same for a caller that asks for each root at most once and may need only one (a sphere's
    // closest hit): a float's root from its own interval alone (root_interval, one quotient).
    // Callgrind, SSE2, accurate float sphere hits: 946 -> 845 instructions.
    T rounded_alone(int which) const
    {
        if constexpr (std::is_same_v<T, float>) {
            std::optional<float> t;
            if (a_.sign == 0) {
                if (sign_b() != 0) t = rounded_between_midpoints<float>(line_root());
            } else if (two_certain_roots(bounded(r_.a), disc_)) {
                const auto root = root_interval(bounded(r_.a), bounded(r_.df), bounded(r_.f), cancellation_free_q(bounded(r_.df), disc_), which);
                if (root) t = rounded_between_midpoints<float>(*root);
            }
            if (!t) *undecided_ = true;
            return t.value_or(0.0f);
        } else {
            return rounded(which);
        }
    }

    // A certified interval around root `which` from the filter alone (root_intervals, quotient),
    // without rounding it; none when the filter cannot give one. Orders most ends of a double
    // solid without their Newton steps (QuickSolid::interval_order).
    std::optional<Bounded<double>> interval(int which) const
    {
        if (!intervals_) {
            intervals_ = true;
            if (a_.known && a_.sign == 0) {
                const Sign b = sign_of(r_.df);
                if (b.known && b.sign != 0) iv_[0] = iv_[1] = line_root(), has_iv_ = true;
            } else if (a_.known && sign_disc_.known && sign_disc_.sign > 0) {
                if (const auto roots = root_intervals(bounded(r_.a), bounded(r_.df), bounded(r_.f), disc_))
                    iv_[0] = (*roots)[0], iv_[1] = (*roots)[1], has_iv_ = true;
            }
        }
        if (!has_iv_) return std::nullopt;
        return iv_[which];
    }

private:
    // A line's only root, -c/b, as a certified interval (a vanishes, b's sign is certain).
    Bounded<double> line_root() const { return quotient(-bounded(r_.f), bounded(r_.df)); }
    std::optional<T> newton_from_estimate(int which) const
    {
        if (a_.sign == 0) return sign_b() != 0 ? newton(0, -value_of(r_.f) / value_of(r_.df)) : std::nullopt;
        if (!(sign_disc_.known && sign_disc_.sign > 0)) return std::nullopt;
        return newton(which, root_estimate<T>(value_of(r_.a), value_of(r_.df), value_of(r_.f), disc_.v, a_.sign, which));
    }
    // The static filter's inputs are within the static range (quick_solid_crossings checks them).
    std::optional<T> newton(int which, T t) const
    {
        if constexpr (static_filter) return quick_newton_rounded<T>(coef_, a_.sign, which, t);
        else return newton_rounded<T>(coef_, a_.sign, which, t);
    }

    struct Sign {
        int sign;
        bool known;
    };
    // t = 0, a constant rather than an input (the static filter counts input factors).
    static F t_zero()
    {
        if constexpr (static_filter) return F{0.0, 0.0, 0, 0, 0};
        else return F{0.0};
    }
    // Certain when the filter's bound decides it, or zero when the magnitude is (every monomial
    // vanishes; with running bounds, an exact zero).
    static bool vanishes(const F& x)
    {
        if constexpr (static_filter) return x.m() == 0.0;
        else return exact_zero(x);
    }
    static Sign sign_of(const F& x)
    {
        if (vanishes(x)) return {0, true};
        const int s = certain_sign(x);
        return {s, s != 0};
    }
    int use(Sign s) const
    {
        if (!s.known) *undecided_ = true;
        return s.sign;
    }

    // Only a double's Newton steps use the residual again.
    struct Unused {
        explicit Unused(const Coef&) {}
    };
    std::conditional_t<std::is_same_v<T, float>, Unused, Coef> coef_;
    Residual<F> r_;
    Bounded<double> disc_{0.0};
    Sign a_, sign_disc_{0, true};
    bool* undecided_;
    mutable bool rounded_ = false, done_[2] = {false, false}, intervals_ = false, has_iv_ = false;
    mutable T root_[2] = {};
    mutable Bounded<double> iv_[2] = {};
};

// The crossings of a solid between two roots (a sphere: a > 0), from `root(which)`, each root
// correctly rounded or none, written into `out`; false when a root is needed and not given, or
// equals a window end (a float ≠ x on one side of x puts the exact root on that side, past its
// midpoint). The exit is rounded only when it can count (a double's costs a Newton step).
// Not forced inline: twice here GCC 12 left calls inside a forced-inline callee of a flattened
// function out of line. Forced, it left quick_newton_rounded out of line in a double sphere's lane
// (1,255 against 1,179 instructions per hit, callgrind), and forcing that inline in turn left a
// double plane's residual and Newton step out of line in rayq-bench (accurate 264 -> 347 us).
// Written into the caller's object, the one the query reads (exact_curved_crossings): a local
// Crossings copied out at the end was read back by 16-byte loads across its narrower stores, a
// failed store-to-load forwarding that took 6% of a double sphere's hit samples (perf;
// rayq-bench, SSE2, accurate ÷ fast double sphere, three alternating runs: 1.277, 1.159, 1.239 ->
// 1.214, 1.220, 1.231); an optional returned in place was still copied once by its callers.
template <class T, class Root>
inline bool two_root_crossings(const Ray<T>& ray, int limit, Root root, Crossings<T>& out)
{
    out.count = 0;
    const std::optional<T> t0 = root(0);
    if (!t0 || *t0 == ray.tmin || *t0 == ray.tmax) return false;
    if (ray.tmin < *t0 && *t0 < ray.tmax) out.add(*t0, Part::surface, true, true);
    if (out.count == limit || !(*t0 < ray.tmax)) return true;
    const std::optional<T> t1 = root(1);
    if (!t1 || *t1 == ray.tmin || *t1 == ray.tmax) return false;
    if (ray.tmin < *t1 && *t1 < ray.tmax) out.add(*t1, Part::surface, false, true);
    return true;
}

// The sign of a residual F at every point of [t − h, t + h], from r, its value at t in the static
// filter, or 0 when that cannot decide it: F(t) must clear its bound plus what F can move there,
// |F'(t)|·h + |a|·h² (Taylor, exact for a quadratic). The inputs and t must be within the static
// range (magnitude.hpp).
template <class T>
RAYQ_INLINE int sign_over_span(const Residual<Magnitude<T>>& r, T h)
{
    // h·(|F'| + |a|·h), without a's term for a plane (a = 0): a bound floored by grow() and then
    // multiplied by h would be subnormal, which costs x86 a microcode assist (bounded.hpp).
    const T slope = grow(std::abs(r.df.v()) + r.df.bound());
    const T drift = r.a.m() == T(0) ? slope : grow(slope + grow(grow(std::abs(r.a.v()) + r.a.bound()) * h));
    const T reach = grow(r.f.bound() + grow(drift * h));
    return sign_beyond(r.f.v(), reach);
}
// How far the root of a linear residual G = f + df·t (a plane along the ray, from the static
// filter) can lie from t: |G(t)|/|df|, |G(t)| at most the computed |f + df·t| (two roundings of
// at most u·(|f| + |df·t|) each, an underflow's absolute error within grow's floor) plus f's
// bound and |t| times df's, |df| at least its value less its bound. Infinite where df's sign is
// uncertain. The inputs and t within the static range.
template <class T>
RAYQ_INLINE T linear_root_reach(const Residual<Magnitude<T>>& g, T t)
{
    const T u = unit_roundoff<T>, fv = g.f.v(), dv = g.df.v(), slope = dv * t;
    const T d_min = lower(dv, g.df.bound());
    if (!(d_min > T(0))) return std::numeric_limits<T>::infinity();
    const T g_max = grow(grow(std::abs(fv + slope) + T(2) * u * (std::abs(fv) + std::abs(slope))) +
                         grow(g.f.bound() + grow(g.df.bound() * std::abs(t))));
    return grow(g_max / d_min);
}
// ... over the cell of floats that round to `t` (where a certified Newton step puts an exact
// root): h = one ulp above |t|, at least the distance to either edge of the cell.
template <class T>
RAYQ_INLINE int sign_over_cell(const Residual<Magnitude<T>>& r, T t)
{
    return sign_over_span(r, wider_gap(t));
}

// An axial primitive: its axis runs from p0 to p1 (a sphere's lane, compiled with `axial` false
// only, is never asked for one).
template <class Prim, class = void>
struct has_axis_ends : std::false_type {};
template <class Prim>
struct has_axis_ends<Prim, std::void_t<decltype(std::declval<const Prim&>().p1 - std::declval<const Prim&>().p0)>> : std::true_type {};

// Where the floats that round to t lie against an axial primitive's slab: the signs of
// G0 = (p − p0)·A (cap0's residual, positive inside) and G1 = (p − p1)·A (cap1's, negative
// inside) over t's cell (slab_of), A = p1 − p0, and d·A, which orders the planes (each 0 when
// uncertain). G1 is G0 − |A|² exactly: one evaluation serves both planes. Inputs and t within the
// static range.
struct SlabCell {
    int g0, g1, rising;
    bool inside() const { return g0 > 0 && g1 < 0; }
    // Certainly past the exit plane (at or beyond it by the exact root's cell).
    bool past() const { return rising != 0 && (rising > 0 ? g1 > 0 : g0 < 0); }
};
template <class Prim, class T = scalar_t<Prim>>
RAYQ_INLINE SlabCell slab_cell(const Ray<T>& ray, const Prim& prim, T t)
{
    Residual<Magnitude<T>> g = PartCoefficients<Prim>{&prim, &ray, Part::cap0}.at(Magnitude<T>{t});
    const int g0 = sign_over_cell(g, t);
    const Vec3<Magnitude<T>> axis = lift<Magnitude<T>>(prim.p1) - lift<Magnitude<T>>(prim.p0);
    g.f = g.f - dot(axis, axis);
    return {g0, sign_over_cell(g, t), certain_sign(g.df)};
}

// A double axial primitive's closest crossing, without the quick lane's filter, where the ray
// enters through its side (about four hits in five on random rays aimed at a cylinder or
// frustum) or through an end of its slab. Plain estimates pick the case to certify (a wrong pick
// costs time, never the answer):
//   The side: its smaller root τ0 from plain coefficients and one certified Newton step (as a
//   double sphere's lane), then the cap planes' signs over τ0's cell. With a > 0 (a certain
//   sign) the side's inside is the span (τ0, τ1), so every crossing of the solid, capped or open,
//   is at or after τ0 (solid_crossings). τ0 strictly between the planes: τ0, entering; τ0 past
//   the slab's exit plane: none.
//   An end: the slab's entry plane t_c, where the side is certainly negative. Capped, t_c by its
//   own Newton step, the side negative over its cell: the solid (side ∩ slab) starts there,
//   through that cap, and no crossing comes before it. Open, the side negative over an interval
//   that holds the exact t_c (no crossing, so never rounded): with a > 0, τ0 < t_c < τ1, τ0 is
//   outside the slab, so the first crossing is τ1, leaving through the side, when τ1 lies within
//   the slab (its own Newton step), and none when τ1 lies past it.
// Every crossing lies within the slab, so none when its entry (t_c) or the first root is beyond
// the window's end. True with the crossing (or none) in `out`; false where any of this is not
// certain, where the first crossing is at or behind the window's start, or for more than one
// crossing: the quick lane then decides. Inputs within the static range.
template <class Prim, class T = scalar_t<Prim>>
inline bool axial_first_crossing(const Ray<T>& ray, const Prim& prim, bool capped, CapEnds ends, int limit, Crossings<T>& out)
{
    if (limit != 1) return false;
    const PartCoefficients<Prim> side{&prim, &ray, Part::surface}, cap0{&prim, &ray, Part::cap0};
    const Magnitude<T> zero{T(0), T(0), 0, 0, 0};
    out.count = 0;
    const auto first = [&](T t, Part part, bool entering) {
        if (t == ray.tmin || t == ray.tmax) return false;
        if (t > ray.tmax) return true;
        if (!(ray.tmin < t)) return false;
        out.add(t, part, entering, true);
        return true;
    };
    // A root of the side, certified, with a > 0 certain.
    const Residual<T> r = side.at(T(0));
    const T d = r.df * r.df - T(4) * r.a * r.f;
    const bool two_roots = r.a > T(0) && d > T(0);
    const auto side_root = [&](int which, T estimate) -> std::optional<T> {
        if (certain_sign(side(zero).a) <= 0) return std::nullopt;
        const std::optional<T> t = quick_newton_rounded<T>(side, 1, which, estimate);
        if (!t || !within_static_range(*t)) return std::nullopt;
        return t;
    };
    if (two_roots) {
        const T estimate = root_estimate(r.a, r.df, r.f, d, 1, 0);
        const T height = cap0.at(estimate).f;  // (p − p0)·A: the slab is 0 < height < |A|²
        const Vec3<T> axis = prim.p1 - prim.p0;
        if (height > T(0) && height < dot(axis, axis)) {
            const std::optional<T> t0 = side_root(0, estimate);
            if (!t0) return false;
            const SlabCell cell = slab_cell(ray, prim, *t0);
            if (cell.inside()) return first(*t0, Part::surface, true);
            if (cell.past()) return true;
            return false;
        }
    }
    const Residual<T> rise = cap0.at(T(0));  // d·A
    if (!(rise.df != T(0))) return false;
    const Part entry = rise.df > T(0) ? Part::cap0 : Part::cap1;
    // An end no cap closes (a cone's apex) is a point: the side is never certainly negative over
    // its plane's cell below, so this only saves the plane's Newton step.
    if (capped && !ends.closes(entry)) return false;
    const PartCoefficients<Prim> plane{&prim, &ray, entry};
    const Residual<T> e = entry == Part::cap0 ? rise : plane.at(T(0));
    const T plane_estimate = -e.f / e.df;
    if (!(side.at(plane_estimate).f < T(0))) return false;  // the estimate misses the end's disk
    if (certain_sign(cap0(zero).df) != (rise.df > T(0) ? 1 : -1)) return false;
    if (capped) {
        const std::optional<T> tc = quick_newton_rounded<T>(plane, 0, 0, plane_estimate);
        if (!tc || !within_static_range(*tc) || sign_over_cell(side.at(Magnitude<T>{*tc}), *tc) >= 0) return false;
        return first(*tc, entry, true);
    }
    if (!two_roots) return false;  // open: the answer is the side's larger root τ1
    // Open, t_c is no crossing: the side certainly negative over an interval that holds it is
    // enough, without rounding it (pt.cpp, SSE2, accurate open-cylinder hits: 2,439 -> 2,344
    // instructions by callgrind, 244 -> 233 ns; hits and misses 134 -> 130 ns per ray, fast's 103).
    if (!within_static_range(plane_estimate)) return false;
    const T reach = linear_root_reach(plane(zero), plane_estimate);
    if (sign_over_span(side.at(Magnitude<T>{plane_estimate}), reach) >= 0) return false;
    const std::optional<T> t1 = side_root(1, root_estimate(r.a, r.df, r.f, d, 1, 1));
    if (!t1) return false;
    const SlabCell cell = slab_cell(ray, prim, *t1);
    if (cell.inside()) return first(*t1, Part::surface, false);
    if (cell.past()) return true;
    return false;
}

// ExactSolid's interface for the quick lane, on QuickQuadratic parts. Its ends are compared
// through their correctly rounded floats: two different floats order their exact ends (each lies
// strictly between its float's midpoints); equal ones leave the comparison undecided.
template <class Prim, class F>
class QuickSolid {
    using T = scalar_t<Prim>;
    using Coef = PartCoefficients<Prim>;
    using Quadratic = QuickQuadratic<T, Coef, F>;

public:
    QuickSolid(const Ray<T>& ray, const Prim& prim, bool axial, bool& undecided)
        : ray_(ray), prim_(prim), undecided_(undecided), side_(part(Part::surface))
    {
        // Constructed in place: each part is a few hundred bytes, and a moved temporary was copied whole.
        if (axial) cap0_.emplace(Coef{&prim_, &ray_, Part::cap0}, undecided_), cap1_.emplace(Coef{&prim_, &ray_, Part::cap1}, undecided_);
    }

    int side_spans(End (&enter)[2], End (&exit)[2]) const { return side_spans_of(side_, enter, exit); }
    bool slab(End& enter, End& exit) const { return slab_of(*cap0_, *cap1_, enter, exit); }

    // sign(x − y).
    int compare(End x, End y) const
    {
        if (x.kind == y.kind && (!x.finite() || x.which == y.which)) return 0;
        if (x.kind == EndKind::neg_inf || y.kind == EndKind::pos_inf) return -1;
        if (x.kind == EndKind::pos_inf || y.kind == EndKind::neg_inf) return 1;
        if constexpr (!std::is_same_v<T, float>)
            if (const int s = interval_order(x, y)) return s;
        return order(value(x), value(y));
    }
    // sign(e − x) for a float x (a window bound; ±infinity allowed).
    int compare(End e, T x) const
    {
        constexpr T inf = std::numeric_limits<T>::infinity();
        if (e.kind == EndKind::neg_inf) return x == -inf ? 0 : -1;
        if (e.kind == EndKind::pos_inf) return x == inf ? 0 : 1;
        return order(value(e), x);
    }
    bool in_window(End e) const { return compare(e, ray_.tmin) > 0 && compare(e, ray_.tmax) < 0; }
    const Quadratic& side() const { return side_; }

    // The end's t correctly rounded.
    T value(End e) const { return part_of(e).rounded(e.kind == EndKind::root ? e.which : 0); }

private:
    Quadratic part(Part p) const { return {Coef{&prim_, &ray_, p}, undecided_}; }
    const Quadratic& part_of(End e) const { return e.kind == EndKind::root ? side_ : (e.kind == EndKind::cap0 ? *cap0_ : *cap1_); }
    // sign(x − y) when the filter's intervals around both ends are disjoint, else 0 (a double's
    // rounding costs a Newton step; ends that become crossings are rounded all the same, and
    // window bounds are compared with rounded ends, as the exact path's inside_window needs).
    int interval_order(End x, End y) const
    {
        const auto ix = part_of(x).interval(x.which), iy = part_of(y).interval(y.which);
        if (!ix || !iy) return 0;
        const double margin = 1 - 2 * unit_roundoff<double>, gap = grow(ix->e + iy->e);  // as root_intervals
        if ((iy->v - ix->v) * margin > gap) return -1;
        if ((ix->v - iy->v) * margin > gap) return 1;
        return 0;
    }
    int order(T x, T y) const
    {
        if (x != y) return x < y ? -1 : 1;
        undecided_ = true;
        return 0;
    }

    const Ray<T>& ray_;
    const Prim& prim_;
    bool& undecided_;
    Quadratic side_;
    std::optional<Quadratic> cap0_, cap1_;
};

// The common case of a curved primitive, settled by the quick lane: the exact path's span logic
// (solid_crossings) on QuickSolid. None when anything is undecided: the exact path then decides,
// and since its decisions are exact and a correctly rounded root is unique, both give the same
// answer. Its filter is the static one of magnitude.hpp (about a third of Bounded's cost), and
// everything is inlined (flatten) so that the filter's counts fold to constants. Double inputs
// must lie within its range (within_static_range); float ones always do.
template <bool axial, class Prim, class F = Magnitude<double>, class T = scalar_t<Prim>>
RAYQ_FLATTEN inline bool quick_solid_crossings(const Ray<T>& ray, const Prim& prim, bool capped, CapEnds ends, int limit,
                                               Crossings<T>& out)
{
    if constexpr (!std::is_same_v<T, float> && is_magnitude<F>::value) {
        if (!inputs_within_static_range(ray, prim)) return false;
    }
    bool undecided = false;
    const QuickSolid<Prim, F> solid(ray, prim, axial, undecided);
    if (undecided) return false;
    if constexpr (!axial) {
        // A sphere's side has a > 0: no crossing, or the one span between the roots. Written out,
        // this common case takes 11% fewer instructions per float sphere ray (callgrind) than
        // solid_crossings' general span logic.
        const auto& side = solid.side();
        const int a = side.sign_a();
        if (undecided) return false;
        if (a > 0) {
            const int disc = side.sign_disc();
            if (undecided) return false;
            if (disc < 0) {
                out.count = 0;
                return true;
            }
            const bool settled = two_root_crossings(ray, limit, [&](int which) -> std::optional<T> {
                const T t = side.rounded_alone(which);
                if (undecided) return std::nullopt;
                return t;
            }, out);
            return settled && !undecided;
        }
        // a = |d|² is 0 only for a zero direction, or a non-sphere: the exact path decides (and
        // the general span logic below is not compiled into a sphere's lane).
        return false;
    } else {
        // Only the crossings asked for: a closest hit rounds no exit (a double's costs a Newton
        // step). The lane may then answer a closest hit whose exit it could not have decided;
        // the exact path gives the same record (every accurate crossing is the exact root
        // correctly rounded, its t_error one ulp), so the closest hit and all crossings still
        // agree (MagnitudeFilter.ClosestHitAndAllCrossingsAgreeInEveryField, IntersectAllTest). Until the exact path
        // was exact at every magnitude they did not: the lane decided both ends whatever the limit.
        solid_crossings(solid, axial, capped, ends, limit, out);
        return !undecided;
    }
}

// A double sphere's roots straight from its plain coefficients at t = 0 and d = b² − 4ac > 0,
// each certified by its Newton step alone, without the filter's coefficients, discriminant and
// signs: a step that certifies a root also proves the roots real (x <= 1/2 in newton_step makes
// F'² − 4aF, the discriminant, positive) and that it is root `which` (F''s sign). a = |d|² is a sum
// of squares of inputs within the static range: positive exactly when its computed value is.
// None when a step declines (then quick_solid_crossings and the exact path decide).
// Callgrind, SSE2, accurate double sphere hits: 1,477 -> 1,179 instructions against the filter's
// lane; ns per ray over hits and misses (min of 31 runs) 69 -> 63, fast's 44.
// Its own function, called by the sphere (sphere.hpp) before the rest of the quick lane, not a
// branch inside quick_solid_crossings: that flattened function spills much of its state on entry,
// which every hit paid (pt.cpp, SSE2, min of 31 runs, with the sphere's miss test moved behind
// the plain discriminant and StaticRange: 117 -> 106 ns per hit; per ray over hits and misses
// 63.3 -> 59.2, fast's 47.4).
struct PlainQuadratic {
    Residual<double> r;  // F(0), F'(0), a
    double d;            // F'(0)² − 4·a·F(0)
};
template <class Prim>
RAYQ_INLINE PlainQuadratic plain_quadratic(const Ray<double>& ray, const Prim& prim)
{
    const Residual<double> r = PartCoefficients<Prim>{&prim, &ray, Part::surface}.at(0.0);
    return {r, r.df * r.df - 4.0 * r.a * r.f};
}
template <class Prim>
RAYQ_FLATTEN inline bool quick_sphere_crossings(const Ray<double>& ray, const Prim& prim, const PlainQuadratic& q, int limit,
                                                Crossings<double>& out)
{
    const Residual<double>& r = q.r;
    const double d = q.d;
    if (!inputs_within_static_range(ray, prim) || !(r.a > 0.0 && d > 0.0)) return false;
    const PartCoefficients<Prim> coef{&prim, &ray, Part::surface};
    return two_root_crossings(ray, limit, [&](int which) {
        return quick_newton_rounded<double>(coef, 1, which, root_estimate(r.a, r.df, r.f, d, 1, which));
    }, out);
}

// A double axial primitive's closest crossing by axial_first_crossing, flattened on its own before
// the rest of the quick lane (as the sphere's, quick_sphere_crossings): inside quick_solid_crossings,
// whose entry spills much of its state, every hit paid for that function (pt.cpp, SSE2, min of
// 31 runs, accurate double, ns per ray over hits and misses: capped cylinder 117.3 -> 108.1, open
// 129.0 -> 118.8, frustum 150.9 -> 139.0; fast's 90.6, 102.3, 117.3).
template <class Prim>
RAYQ_FLATTEN inline bool quick_axial_crossing(const Ray<double>& ray, const Prim& prim, bool capped, CapEnds ends, int limit,
                                              Crossings<double>& out)
{
    return inputs_within_static_range(ray, prim) && axial_first_crossing(ray, prim, capped, ends, limit, out);
}

// (Axial as a constant, so that a sphere's lane carries no cap logic.)
template <class Prim>
inline bool quick_curved_crossings(const Ray<scalar_t<Prim>>& ray, const Prim& prim, bool axial, bool capped, CapEnds ends, int limit,
                                   Crossings<scalar_t<Prim>>& out)
{
    if constexpr (has_axis_ends<Prim>::value && std::is_same_v<scalar_t<Prim>, double>) {
        if (axial && quick_axial_crossing(ray, prim, capped, ends, limit, out)) return true;
    }
    return axial ? quick_solid_crossings<true>(ray, prim, capped, ends, limit, out)
                 : quick_solid_crossings<false>(ray, prim, capped, ends, limit, out);
}

// The quick lane again on coefficients in running error bounds (pbrt-v4 "Managing Rounding
// Error"), for float inputs the static filter left undecided, before the exact path. Those bounds
// follow the intermediate values where the filter's follow the monomials' magnitudes: a cone's
// coefficients cancel to 10^-5–10^-6 of their magnitudes, and for rays passing close by the
// filter's root intervals were wider than half a float ulp (6% of float cones aimed near their
// surface; 0.002% after this try). Double inputs go straight to the exact path (their lane rounds
// by a Newton step, which interval widths do not stop). None when this lane declines too.
template <class Prim>
inline bool running_bound_crossings(const Ray<scalar_t<Prim>>& ray, const Prim& prim, bool axial, bool capped, CapEnds ends, int limit,
                                    Crossings<scalar_t<Prim>>& out)
{
    if constexpr (std::is_same_v<scalar_t<Prim>, float>) {
        using BD = Bounded<double>;
        return axial ? quick_solid_crossings<true, Prim, BD>(ray, prim, capped, ends, limit, out)
                     : quick_solid_crossings<false, Prim, BD>(ray, prim, capped, ends, limit, out);
    }
    return false;
}

// What the static filter's lane declined: the running bounds' lane, then the exact path. Out of
// line, so the common case's code is as it was without the second lane.
template <class Prim>
RAYQ_NOINLINE void declined_curved_crossings(const Ray<scalar_t<Prim>>& ray, const Prim& prim, bool axial, bool capped, CapEnds ends,
                                             int limit, Crossings<scalar_t<Prim>>& out)
{
    if (running_bound_crossings(ray, prim, axial, capped, ends, limit, out)) return;
    out = exact_curved_crossings_in_unit(ray, prim, axial, capped, ends, limit, reach_of(ray, prim));
}

// Written into `out`, the object the query reads (a primitive's crossings() returns it by NRVO),
// so that no Crossings is built elsewhere and copied: GCC copied the quick lane's returned
// optional in 16-byte loads of fields just stored as 4- and 1-byte pieces, a store-forwarding
// stall on every query (as intersect()'s record, query.hpp).
template <class Prim>
inline void exact_curved_crossings(const Ray<scalar_t<Prim>>& ray, const Prim& prim, bool axial, bool capped, CapEnds ends, int limit,
                                   Crossings<scalar_t<Prim>>& out)
{
    if (!quick_curved_crossings(ray, prim, axial, capped, ends, limit, out)) declined_curved_crossings(ray, prim, axial, capped, ends, limit, out);
}
template <class Prim>
inline Crossings<scalar_t<Prim>> exact_curved_crossings(const Ray<scalar_t<Prim>>& ray, const Prim& prim, bool axial, bool capped,
                                                         CapEnds ends, int limit)
{
    Crossings<scalar_t<Prim>> out;
    exact_curved_crossings(ray, prim, axial, capped, ends, limit, out);
    return out;
}

}  // namespace rayq::detail

namespace rayq::detail {

// What the quick lane below needs of a flat primitive, from the static filter (magnitude.hpp):
// its plane along the ray, F(t) = f + df·t, and its trim at F's root: +1 inside, −1 outside,
// 0 undecided.
// f and df are kept as values with their bounds, made where the filter's counts are constants.
// Kept as Magnitudes, the counts travelled with the copy of this struct: GCC 12 (-O3, SSE2) moved
// them through the stack in 16-byte pieces that missed store forwarding, two stalls on every
// accurate query of a plane before its first branch (same-binary medians, accurate ÷ fast:
// float plane 1.42 -> 1.05, double plane 1.84 -> 1.47).
struct QuickFlat {
    Bounded<double> f, df;
    int inside;
    bool in_range;  // the primitive's inputs are within the filter's range (within_static_range)

    // Degrees beyond six leave the filter's guarantee (magnitude.hpp): out of range too.
    RAYQ_INLINE QuickFlat(const Magnitude<double>& f_, const Magnitude<double>& df_, int inside_, bool in_range_)
        : f(bounded(f_)), df(bounded(df_)), inside(inside_), in_range(in_range_ && f_.d <= 6 && df_.d <= 6)
    {
    }
};

// A flat primitive's plane coefficients for QuickFlat. t = 0 enters as a constant, not as a float
// factor, so the degrees count float factors only: two in a plane's or disk's coefficients, three
// in a triangle's, within the filter's guarantee for any finite float.
template <class Prim>
inline Residual<Magnitude<double>> quick_plane(const Ray<scalar_t<Prim>>& ray, const Prim& prim)
{
    return PartCoefficients<Prim>{&prim, &ray, Part::surface}(Magnitude<double>{0.0, 0.0, 0, 0, 0});
}

// The common case of a flat primitive, settled by the static filter alone, as
// quick_curved_crossings settles a curved one: the plane's slope certainly nonzero, its root −f/df
// correctly rounded on a definite side of both window ends, and the trim certain: true, with the
// crossing (if any) added to `out`. False, `out` untouched, when anything is uncertain:
// exact_flat_crossing then decides, and since the correctly rounded root
// and the exact trim are unique, both give the same answer. `quick()` computes the QuickFlat;
// everything here is inlined (flatten), so the filter's counts fold to constants.
// The root: for float, from the filter's certified interval in double (quotient,
// rounded_between_midpoints), 2^29 times tighter than float's spacing; for double, whose own
// interval spans ulps, by one certified double-word Newton step from −f/df on the plane's residual
// `coef` (newton_rounded), exact for a linear F up to the double-word bounds.
template <class T, class Quick, class Coef>
RAYQ_FLATTEN inline bool quick_flat_crossing(const Ray<T>& ray, const Quick& quick, const Coef& coef, Crossings<T>& out)
{
    if (!all_within_static_range(ray.origin, ray.direction)) return false;
    const QuickFlat plane = quick();
    if (!plane.in_range) return false;
    const int slope = certain_sign(plane.df);
    if (slope == 0) return false;
    // A certain miss of the trim needs no t (most rays that reach a flat primitive's plane miss it;
    // a double t costs a Newton step).
    if (plane.inside < 0) return true;
    // A root certainly behind a window that starts at or after 0 needs no t either: the root −f/df
    // is negative where f and df certainly have one sign (the misses of a plane, rays leaving it,
    // took a double's Newton step: 983 against 643 instructions per miss under `fast`, callgrind,
    // SSE2).
    if (ray.tmin >= T(0) && certain_sign(plane.f) == slope) return true;
    std::optional<T> t;
    if constexpr (std::is_same_v<T, float>) t = rounded_between_midpoints<float>(quotient(-plane.f, plane.df));
    else t = quick_newton_rounded<T>(coef, 0, 0, -plane.f.v / plane.df.v);
    // A float t ≠ x on one side of x puts the exact root on that side: it lies beyond t's midpoint.
    if (!t || *t == ray.tmin || *t == ray.tmax) return false;
    if (!(ray.tmin < *t && *t < ray.tmax)) return true;
    if (plane.inside == 0) return false;
    out.add(*t, Part::surface, slope < 0, true);  // F decreasing along the ray: entering
    return true;
}

// The crossing of a flat primitive's plane, if the exact inside test `inside(plane)` accepts it
// (it receives the plane's exact quadratic, whose root is the crossing). The quick lane comes
// first, on the QuickFlat that `quick()` computes.
template <class Prim, class Inside, class Quick>
inline Crossings<scalar_t<Prim>> exact_flat_crossing(const Ray<scalar_t<Prim>>& ray, const Prim& prim, const Inside& inside,
                                                     const Quick& quick)
{
    using T = scalar_t<Prim>;
    using Coef = PartCoefficients<Prim>;
    const Coef coef{&prim, &ray, Part::surface};
    // Written where it is returned (every return names `out`: NRVO), as intersect()'s record.
    Crossings<T> out;
    if (quick_flat_crossing(ray, quick, coef, out)) return out;
    const ExactQuadratic<T, Coef> plane(coef);
    if (plane.sign_b() == 0) return out;  // parallel to the plane, or in it
    const T t = plane.round(0);
    // The exact root lies strictly between t's neighbours: decide the window from them when they
    // suffice, exactly otherwise.
    const auto after = [&](T x) {
        if (!std::isfinite(x)) return x < T(0);
        if (next_down(t) >= x) return true;
        if (next_up(t) <= x) return false;
        return plane.compare(0, FloatLine<T>{-x, T(1)}) < 0;
    };
    const auto before = [&](T x) {
        if (!std::isfinite(x)) return x > T(0);
        if (next_up(t) <= x) return true;
        if (next_down(t) >= x) return false;
        return plane.compare(0, FloatLine<T>{-x, T(1)}) > 0;
    };
    if (!after(ray.tmin) || !before(ray.tmax) || !inside(plane)) return out;
    out.add(inside_window(ray, t), Part::surface, plane.sign_b() < 0, true);  // F = (o + t·d − p)·n decreasing: entering
    return out;
}

// The ray's line against corner + α·e0 + β·e1 (Möller–Trumbore's numerators over N), with the
// exact test 0 <= α, β and α <= 1, β <= 1 (parallelogram) or α + β <= 1 (triangle).
// A flat primitive's corner and edges, in any number type.
template <class N>
struct PlanarFrame {
    Vec3<N> corner, e0, e1;
};

template <class N>
struct PlanarNumerators {
    N det, alpha, beta, t;  // t only when asked for
};

template <bool with_t, class T, class Edges, class N>
inline PlanarNumerators<N> planar_numerators(const Ray<T>& ray, const Edges& edges, N zero)
{
    const auto [corner, e0, e1] = edges(zero);
    const Vec3<N> q = lift<N>(ray.origin) - corner, d = lift<N>(ray.direction);
    const Vec3<N> p = cross(d, e1), r = cross(q, e0);
    PlanarNumerators<N> out{dot(e0, p), dot(q, p), dot(d, r), zero};
    if constexpr (with_t) out.t = dot(e1, r);
    return out;
}

// The quick lane's plane and trim from the same numerators (three float factors each): t =
// t_num/det is the plane's root (Cramer's rule), so F = t_num − det·t, and inside is the test
// above with the static filter's certain signs.
template <class T, class Edges>
inline QuickFlat quick_planar(const Ray<T>& ray, const Edges& edges, bool triangle, bool in_range)
{
    // Computed even out of range (then discarded), so that the filter's counts stay constants
    // (an early return with zero counts made them runtime values: 11% more instructions per
    // double triangle hit, callgrind).
    const PlanarNumerators<Magnitude<double>> m = planar_numerators<true>(ray, edges, Magnitude<double>{});
    const int sign_det = certain_sign(m.det);
    const int alpha = sign_det * certain_sign(m.alpha), beta = sign_det * certain_sign(m.beta);
    const int upper0 = sign_det * certain_sign(triangle ? m.det - m.alpha - m.beta : m.det - m.alpha);
    const int upper1 = triangle ? 1 : sign_det * certain_sign(m.det - m.beta);
    const bool outside = alpha < 0 || beta < 0 || upper0 < 0 || upper1 < 0;
    return {m.t, -m.det, outside ? -1 : (alpha > 0 && beta > 0 && upper0 > 0 && upper1 > 0 ? 1 : 0), in_range};
}

template <class T, class Edges>
inline bool exact_planar_inside(const Ray<T>& ray, const Edges& edges, int sign_det, bool triangle)
{
    const auto numerators = [&](auto zero) { return planar_numerators<false>(ray, edges, zero); };
    const auto nonneg = [&](auto expr) { return sign_det * adaptive_sign<T>(expr) >= 0; };
    if (!nonneg([&](auto z) { return numerators(z).alpha; }) || !nonneg([&](auto z) { return numerators(z).beta; })) return false;
    if (triangle) return nonneg([&](auto z) { const auto m = numerators(z); return m.det - m.alpha - m.beta; });
    return nonneg([&](auto z) { const auto m = numerators(z); return m.det - m.alpha; }) &&
           nonneg([&](auto z) { const auto m = numerators(z); return m.det - m.beta; });
}

}  // namespace rayq::detail
