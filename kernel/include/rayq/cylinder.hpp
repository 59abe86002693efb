// rayq — cylinder: points within `radius` of the axis segment p0→p1; open, or closed by the
// disks cap0 (at p0) and cap1 (at p1).
#pragma once

#include <type_traits>

#include "batch/filter_core.hpp"
#include "detail/bounded.hpp"
#include "detail/exact_crossings.hpp"
#include "detail/policy_ops.hpp"
#include "detail/spans.hpp"
#include "quadratic.hpp"
#include "query.hpp"
#include "validation.hpp"

namespace rayq {

enum class Caps : unsigned char { none, both };

template <class T>
struct Cylinder {
    using scalar_type = T;
    Vec3<T> p0, p1;
    T radius;
    Caps caps = Caps::none;

    // The design notes' form: centred at `center`, axis direction `axis` (any length),
    // extending half_height along it each way.
    static Cylinder from_center(const Vec3<T>& center, const Vec3<T>& axis, T radius, T half_height, Caps caps = Caps::none)
    {
        const Vec3<T> h = detail::unit(axis) * half_height;
        return {center - h, center + h, radius, caps};
    }
};

// The same cylinder in another scalar type (exact when widening, float → double).
template <class U, class T>
constexpr Cylinder<U> scalar_cast(const Cylinder<T>& c) { return {scalar_cast<U>(c.p0), scalar_cast<U>(c.p1), U(c.radius), c.caps}; }

template <class T>
struct is_primitive<Cylinder<T>> : std::true_type {};

template <class T>
inline Validation validate(const Cylinder<T>& c)
{
    return detail::Validator{}
        .finite(c.p0, "Cylinder: p0 is NaN or infinite")
        .finite(c.p1, "Cylinder: p1 is NaN or infinite")
        .finite(c.radius, "Cylinder: radius is NaN or infinite")
        .positive(c.radius, "Cylinder: radius is zero or negative")
        .nonzero(c.p1 - c.p0, "Cylinder: axis p1 - p0 has zero length (or its squared length underflows the number type)", "Cylinder: axis p1 - p0 is too long for the number type")
        .require(c.caps == Caps::none || c.caps == Caps::both, Defect::degenerate, "Cylinder: caps is not a Caps value")
        .result();
}

namespace detail {
// The infinite side's form F(t) = |u + t·v|² − r²|A|². `fast`: the textbook coefficients, with
// r²|A|² formed as it reads, so no square root for |A| (a one-capped-cylinder scene: 15.7 -> 14.1
// ns per ray, standalone loop, SSE2); the other policies keep the norm form (w = r|A|) that their
// discriminants are built on.
template <class Policy, class T>
RAYQ_INLINE auto cylinder_side(Policy, const Vec3<T>& u, const Vec3<T>& v, T radius, const Vec3<T>& axis)
{
    if constexpr (std::is_same_v<Policy, fast_policy>)
        return CoefficientQuadratic<T>{dot(v, v), dot(u, v), dot(u, u) - radius * radius * dot(axis, axis)};
    else
        return NormQuadratic<T>{u, v, radius * length(axis), T(0)};
}
}  // namespace detail

// Infinite side: |(o + t·d − p0) × A|² = r²|A|², the norm form with u = (o − p0) × A,
// v = d × A, w = r|A| (`fast` takes its coefficients: cylinder_side): cross products take out
// the axial component without dividing by |A|².
// Forced inline: GCC left it out of line in large translation units, and a one-cylinder scene
// under `fast` ran 10-20% slower (rayq-bench-embree: 46 -> 51-54 M rays/s SSE2, 54 -> 63-65 native).
template <class Policy, class T>
RAYQ_INLINE Crossings<T> crossings(Policy policy, const Ray<T>& ray, const Cylinder<T>& cyl)
{
    const Vec3<T> axis = cyl.p1 - cyl.p0;
    const Vec3<T> u = detail::cross(policy, ray.origin - cyl.p0, axis), v = detail::cross(policy, ray.direction, axis);
    const Spans<T> side = solve_quadratic(policy, detail::cylinder_side(policy, u, v, cyl.radius, axis));
    return detail::axial_crossings(policy, ray, side, cyl.p0, cyl.p1, axis, cyl.caps == Caps::both);
}

// The side |(q + t·d) × A|² − r²|A|², or the cap's plane, with certified bounds (for Hit::t_error).
// The side between the end planes: 0 <= (p − p0)·A <= |A|², A = p1 − p0; a cap within the radius:
// r²|A|² − |(p − p_end) × A|² >= 0.
template <class T, class N>
inline detail::Margins<N> trim_margins(const Cylinder<T>& cyl, const Vec3<N>& o, const Vec3<N>& d, N t, Part part)
{
    return detail::axial_trim_margins(detail::lift<N>(cyl.p0), detail::lift<N>(cyl.p1), N{cyl.radius}, N{cyl.radius}, o, d, t, part);
}

template <class N, class T>
RAYQ_INLINE detail::Residual<N> residual(const Cylinder<T>& cyl, const Vec3<N>& o, const Vec3<N>& d, N t, Part part)
{
    using B = N;
    const Vec3<B> axis = detail::lift<N>(cyl.p1) - detail::lift<N>(cyl.p0);
    if (part != Part::surface) return detail::plane_residual(part == Part::cap0 ? cyl.p0 : cyl.p1, axis, o, d, t);
    const Vec3<B> qa = cross(o - detail::lift<N>(cyl.p0) + t * d, axis), da = cross(d, axis);
    const B r{cyl.radius};
    return {dot(qa, qa) - r * r * dot(axis, axis), B{T(2)} * dot(qa, da), dot(da, da)};
}

// Accurate: exact decisions, correctly rounded t (detail/exact_crossings.hpp), after the certain
// misses of the tube around the axis and of the bounding sphere (batch::exactly_missed_axial).
template <class T>
inline Crossings<T> crossings(accurate_policy, const Ray<T>& ray, const Cylinder<T>& cyl, int limit = 2)
{
    if (batch::exactly_missed_axial(ray, cyl.p0, cyl.p1, cyl.radius, cyl.radius)) return {};
    return detail::exact_curved_crossings(ray, cyl, true, cyl.caps == Caps::both, {true, true}, limit);
}

// Every point and radius of the cylinder, for the exact path's rescaling (detail/exact_crossings.hpp).
template <class S, class F, std::enable_if_t<detail::is_instance_v<S, Cylinder>, int> = 0>
inline void each_length(S& c, F&& f)
{
    f(c.p0), f(c.p1), f(c.radius);
}

namespace detail {
// The side's radial normal or a cap's ±A, picked by bit masks: cap or side is a coin toss per hit,
// which GCC compiled as jumps (16 capped cylinders, `fast`, point and normal, rays that hit, ns per
// ray, medians of 16 alternated runs: 66.2 -> 64.1).
template <class T>
RAYQ_INLINE Vec3<T> side_or_cap(Part part, const Vec3<T>& radial, const Vec3<T>& axis)
{
    return pick(part == Part::surface, radial, pick(part == Part::cap0, -axis, axis));
}
}  // namespace detail

// Forced inline: see detail::unit().
template <class T>
RAYQ_INLINE Vec3<T> outward_normal(const Cylinder<T>& cyl, const Vec3<T>& p, Part part)
{
    const Vec3<T> axis = cyl.p1 - cyl.p0;
    const Vec3<T> q = detail::offset_from_nearer_end(p, cyl.p0, cyl.p1);
    return detail::side_or_cap(part, q - (dot(q, axis) / dot(axis, axis)) * axis, axis);
}

// The same at the ray's point t, from t rather than the point: q × A is linear in t, q = o − p0 +
// t·d, and A × (q × A) = |A|²·(q's radial component). From t that is one multiply-add and a cross
// product, where the point form waits for the point, its nearer end, a dot product and a division
// (16 capped cylinders, `fast`, point and normal, ns per ray, medians of 16 alternated runs: rays
// that hit 64.1 -> 61.9, all rays 25.6 -> 24.9). Its rounding, ~ε·|o − p0|·|A|² against a result
// of r·|A|², is of the order of the rounded point's own (ε·|p| against r: pbrt-v4, "Managing
// Rounding Error"). Where |A|²·r leaves unit()'s direct range (huge or tiny cylinders, or an
// overflow on the way), the point form.
template <class T>
RAYQ_INLINE Vec3<T> outward_normal_on_ray(const Cylinder<T>& cyl, const Ray<T>& ray, T t, const Vec3<T>& p, Part part)
{
    const Vec3<T> axis = cyl.p1 - cyl.p0;
    const Vec3<T> radial = cross(axis, cross(ray.origin - cyl.p0, axis) + t * cross(ray.direction, axis));
    if (!detail::unscaled_unit(dot(radial, radial))) return outward_normal(cyl, p, part);
    return detail::side_or_cap(part, radial, axis);
}

}  // namespace rayq
