// rayq — cone / frustum: radius r0 at p0 growing linearly to r1 at p1; either radius may be 0
// (an apex). Open, or closed by disks at its non-zero ends (cap0 at p0, cap1 at p1).
#pragma once

#include <algorithm>

#include "cylinder.hpp"  // Caps
#include "batch/filter_core.hpp"
#include "detail/bounded.hpp"
#include "detail/exact_crossings.hpp"
#include "detail/policy_ops.hpp"
#include "detail/spans.hpp"
#include "quadratic.hpp"
#include "query.hpp"
#include "validation.hpp"

namespace rayq {

template <class T>
struct Cone {
    using scalar_type = T;
    Vec3<T> p0;
    T r0;
    Vec3<T> p1;
    T r1;
    Caps caps = Caps::none;
};

// The same cone in another scalar type (exact when widening, float → double).
template <class U, class T>
constexpr Cone<U> scalar_cast(const Cone<T>& c) { return {scalar_cast<U>(c.p0), U(c.r0), scalar_cast<U>(c.p1), U(c.r1), c.caps}; }

template <class T>
struct is_primitive<Cone<T>> : std::true_type {};

template <class T>
inline Validation validate(const Cone<T>& c)
{
    return detail::Validator{}
        .finite(c.p0, "Cone: p0 is NaN or infinite")
        .finite(c.p1, "Cone: p1 is NaN or infinite")
        .finite(c.r0, "Cone: r0 is NaN or infinite")
        .finite(c.r1, "Cone: r1 is NaN or infinite")
        .require(c.r0 >= T(0), Defect::nonpositive_radius, "Cone: r0 is negative")
        .require(c.r1 >= T(0), Defect::nonpositive_radius, "Cone: r1 is negative")
        .require(c.r0 > T(0) || c.r1 > T(0), Defect::degenerate, "Cone: r0 and r1 are both zero (a segment)")
        .nonzero(c.p1 - c.p0, "Cone: axis p1 - p0 has zero length (or its squared length underflows the number type)", "Cone: axis p1 - p0 is too long for the number type")
        .require(c.caps == Caps::none || c.caps == Caps::both, Defect::degenerate, "Cone: caps is not a Caps value")
        .result();
}

// The double cone through the frustum: distance to the axis = r(h), with h = (q·A)/|A|² the
// height fraction and r(h) = r0 + (r1 − r0)·h. Scaled by |A| = L, as for the cylinder:
// |(q + t·d) × A|² = (L·r0 + (r1 − r0)(q·A)/L + t·(r1 − r0)(d·A)/L)², the norm form with s ≠ 0.
// Its second nappe has r(h) < 0, so it lies outside the slab 0 <= h <= 1 and the slab removes it.
template <class Policy, class T>
inline Crossings<T> crossings(Policy policy, const Ray<T>& ray, const Cone<T>& cone)
{
    const Vec3<T> axis = cone.p1 - cone.p0;
    const Vec3<T> q = ray.origin - cone.p0;
    const T len = length(axis);
    const T slope = (cone.r1 - cone.r0) / len;
    const NormQuadratic<T> f{detail::cross(policy, q, axis), detail::cross(policy, ray.direction, axis),
                             len * cone.r0 + slope * detail::dot(policy, q, axis), slope * detail::dot(policy, ray.direction, axis)};
    const Spans<T> side = solve_quadratic(policy, f);
    return detail::axial_crossings(policy, ray, side, cone.p0, cone.p1, axis, cone.caps == Caps::both, {cone.r0 > T(0), cone.r1 > T(0)});
}

// The side in rational form |(q + t·d) × A|²·|A|² − (r0·|A|² + (r1 − r0)·(q + t·d)·A)² (no square
// root of |A|²), or the cap's plane, with certified bounds (for Hit::t_error).
// As the cylinder's (detail::axial_trim_margins), with each cap's own radius.
template <class T, class N>
inline detail::Margins<N> trim_margins(const Cone<T>& cone, const Vec3<N>& o, const Vec3<N>& d, N t, Part part)
{
    return detail::axial_trim_margins(detail::lift<N>(cone.p0), detail::lift<N>(cone.p1), N{cone.r0}, N{cone.r1}, o, d, t, part);
}

template <class N, class T>
RAYQ_INLINE detail::Residual<N> residual(const Cone<T>& cone, const Vec3<N>& o, const Vec3<N>& d, N t, Part part)
{
    using B = N;
    const Vec3<B> axis = detail::lift<N>(cone.p1) - detail::lift<N>(cone.p0);
    if (part != Part::surface) return detail::plane_residual(part == Part::cap0 ? cone.p0 : cone.p1, axis, o, d, t);
    const Vec3<B> q = o - detail::lift<N>(cone.p0) + t * d;
    const Vec3<B> qa = cross(q, axis), da = cross(d, axis);
    const B aa = dot(axis, axis), dr = B{cone.r1} - B{cone.r0};
    const B radius = B{cone.r0} * aa + dr * dot(q, axis);  // r(h)·|A|²
    const B slope = dr * dot(d, axis);                     // its derivative in t
    return {dot(qa, qa) * aa - radius * radius, B{T(2)} * (dot(qa, da) * aa - radius * slope), dot(da, da) * aa - slope * slope};
}

// Accurate: exact decisions, correctly rounded t (detail/exact_crossings.hpp).
template <class T>
inline Crossings<T> crossings(accurate_policy, const Ray<T>& ray, const Cone<T>& cone, int limit = 2)
{
    // Certain misses first: the tube around the axis, then the bounding sphere (as for the cylinder).
    if (batch::exactly_missed_axial(ray, cone.p0, cone.p1, cone.r0, cone.r1)) return {};
    return detail::exact_curved_crossings(ray, cone, true, cone.caps == Caps::both, {cone.r0 > T(0), cone.r1 > T(0)}, limit);
}

// Every point and radius of the cone, for the exact path's rescaling (detail/exact_crossings.hpp).
template <class S, class F, std::enable_if_t<detail::is_instance_v<S, Cone>, int> = 0>
inline void each_length(S& c, F&& f)
{
    f(c.p0), f(c.r0), f(c.p1), f(c.r1);
}

template <class T>
inline Vec3<T> outward_normal(const Cone<T>& cone, const Vec3<T>& p, Part part)
{
    const Vec3<T> axis = cone.p1 - cone.p0;
    if (part == Part::cap0) return -axis;
    if (part == Part::cap1) return axis;
    // ∇(|q⊥|² − r(h)²) on the surface is r·(q̂⊥ − (r1 − r0)/L · Â): radial out, tilted by the slope.
    // At the apex q⊥ = 0 and the axial term alone remains, so there is no 0/0. Taken times L and
    // divided by max(L, |r1 − r0|), both weights are <= 1: the slope itself overflows on a flat cone
    // (radius near DBL_MAX over an axis of 2^-11; found by the axial libFuzzer harness, whose hit then
    // got the ray's direction for a normal, 90° off).
    const Vec3<T> q = detail::offset_from_nearer_end(p, cone.p0, cone.p1);
    const T len = length(axis), rise = cone.r1 - cone.r0;
    const T larger = std::max(len, std::abs(rise));
    const Vec3<T> along = axis / len;
    const Vec3<T> radial = detail::unit(q - dot(q, along) * along);
    return (len / larger) * radial - (rise / larger) * along;
}

}  // namespace rayq
