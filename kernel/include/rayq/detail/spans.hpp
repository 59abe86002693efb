// rayq — turning solid spans into surface crossings, and clipping axial solids by their end planes
// (Embree's cylinder/cone intersectors do the same interval logic: caps and side combine as
// intervals, not as special cases).
#pragma once

#include <cmath>
#include <limits>

#include "../hit.hpp"
#include "../query.hpp"
#include "../quadratic.hpp"
#include "../ray.hpp"
#include "policy_ops.hpp"
#include "ulp.hpp"

namespace rayq::detail {

// The trims of an axial solid (cylinder, cone) as margins >= 0 (see Margins): the side between the
// end planes, 0 <= (p − p0)·A <= |A|² with A = p1 − p0; a cap within its radius,
// r_end²·|A|² − |(p − p_end) × A|² >= 0 (the squared distance from the axis, scaled by |A|²).
template <class N>
inline Margins<N> axial_trim_margins(const Vec3<N>& p0, const Vec3<N>& p1, N r0, N r1, const Vec3<N>& o, const Vec3<N>& d,
                                     N t, Part part)
{
    const Vec3<N> axis = p1 - p0, p = o + t * d;
    const N aa = dot(axis, axis);
    Margins<N> m;
    if (part == Part::surface) {
        const N h = dot(p - p0, axis);
        m.add(h);
        m.add(aa - h);
    } else {
        const bool first = part == Part::cap0;
        const Vec3<N> radial = cross(p - (first ? p0 : p1), axis);
        const N r = first ? r0 : r1;
        m.add(r * r * aa - dot(radial, radial));
    }
    return m;
}

// p − p0 or p − p1, whichever is shorter: an axial normal's radial part, q − (q·Â)Â, errs by
// ~ε·|q|, which near an end (a cone's apex above all) would swamp it. Both give the same radial
// part exactly (p1 − p0 is along the axis). A point 1e-28 from the apex of a cone of size 0.02
// got a normal 56° off from p − p0 (axial libFuzzer harness; CGAL's normal).
// Forced inline: GCC called it out of line from a scene's inlined hit record. Picked by bit masks:
// which end is nearer is a coin toss per hit.
template <class T>
RAYQ_INLINE Vec3<T> offset_from_nearer_end(const Vec3<T>& p, const Vec3<T>& p0, const Vec3<T>& p1)
{
    const Vec3<T> q0 = p - p0, q1 = p - p1;
    return pick(norm1(q1) < norm1(q0), q1, q0);
}

// Every finite end of every span is a crossing of the surface.
template <class T>
inline Crossings<T> crossings_of(const Spans<T>& spans, Part part = Part::surface)
{
    Crossings<T> out;
    for (int i = 0; i < spans.count; ++i) {
        if (std::isfinite(spans.span[i].enter)) out.add(spans.span[i].enter, part, true);
        if (std::isfinite(spans.span[i].exit)) out.add(spans.span[i].exit, part, false);
    }
    return out;
}

// The slab between the planes through p0 and p1 perpendicular to the axis A = p1 − p0,
// as the span of t where 0 <= (o + t·d − p0)·A <= |A|², with the cap each end belongs to.
template <class T>
struct Slab {
    Span<T> span;
    Part enter_part, exit_part;
    bool empty;
};

// Which ends are closed by a cap (a cone's zero-radius end is an apex, not a cap).
struct CapEnds {
    bool cap0, cap1;
    constexpr bool closes(Part end) const { return end == Part::cap0 ? cap0 : cap1; }
};

template <class Policy, class T>
inline Slab<T> axial_slab(Policy policy, const Ray<T>& ray, const Vec3<T>& p0, const Vec3<T>& p1, const Vec3<T>& axis)
{
    constexpr T inf = std::numeric_limits<T>::infinity();
    // Each plane's distance is measured from its own point, so neither end inherits the
    // rounding of the other (instead of |A|² − (o − p0)·A for the far plane).
    const T h0 = detail::dot(policy, p0 - ray.origin, axis);  // > 0: origin below the p0 plane
    const T h1 = detail::dot(policy, p1 - ray.origin, axis);  // < 0: origin above the p1 plane
    const T da = detail::dot(policy, ray.direction, axis);
    if (da == T(0)) {
        const bool inside = h0 <= T(0) && h1 >= T(0);
        return {{-inf, inf}, Part::cap0, Part::cap1, !inside};
    }
    const T t0 = h0 / da, t1 = h1 / da;
    if (da > T(0)) return {{t0, t1}, Part::cap0, Part::cap1, false};
    return {{t1, t0}, Part::cap1, Part::cap0, false};
}

// Open surface: the side's crossings that fall within the slab (rim included).
template <class T>
inline Crossings<T> side_crossings_within(const Spans<T>& side, const Slab<T>& slab)
{
    Crossings<T> out;
    if (slab.empty) return out;
    for (const auto& c : crossings_of(side))
        if (slab.span.enter <= c.t && c.t <= slab.span.exit) out.add(c.t, c.part, c.entering);
    return out;
}

// Closed solid: side solid ∩ slab. At a tie the cap wins (the point is on the rim either way),
// unless that end has no cap (an apex), where the point belongs to the side.
template <class T>
inline Crossings<T> capped_crossings(const Spans<T>& side, const Slab<T>& slab, CapEnds ends = {true, true})
{
    Crossings<T> out;
    if (slab.empty) return out;
    for (int i = 0; i < side.count; ++i) {
        const Span<T>& s = side.span[i];
        const bool cap_in = slab.span.enter >= s.enter, cap_out = slab.span.exit <= s.exit;
        const T enter = cap_in ? slab.span.enter : s.enter;
        const T exit = cap_out ? slab.span.exit : s.exit;
        if (!(enter <= exit)) continue;
        const Part in = cap_in && ends.closes(slab.enter_part) ? slab.enter_part : Part::surface;
        const Part out_part = cap_out && ends.closes(slab.exit_part) ? slab.exit_part : Part::surface;
        if (std::isfinite(enter)) out.add(enter, in, true);
        if (std::isfinite(exit)) out.add(exit, out_part, false);
        break;  // the solid is convex: one span at most survives the slab
    }
    return out;
}

// An axial primitive's crossings: its side's solid trimmed by the slab between its end planes,
// closed by caps where `capped` (at the ends `ends` names). The slab only trims the side's solid:
// a ray that misses the side misses the primitive, and skipping the slab's two divisions then made
// one-cylinder scenes 16% faster (most rays miss).
template <class Policy, class T>
inline Crossings<T> axial_crossings(Policy policy, const Ray<T>& ray, const Spans<T>& side, const Vec3<T>& p0, const Vec3<T>& p1,
                                    const Vec3<T>& axis, bool capped, CapEnds ends = {true, true})
{
    if (side.count == 0) return {};
    const Slab<T> slab = axial_slab(policy, ray, p0, p1, axis);
    return capped ? capped_crossings(side, slab, ends) : side_crossings_within(side, slab);
}

}  // namespace rayq::detail
