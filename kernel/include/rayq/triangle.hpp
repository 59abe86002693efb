// rayq — triangle a, b, c; the front side is the one (b − a) × (c − a) points to
// (counter-clockwise seen from the front, the right-hand rule).
#pragma once

#include "detail/exact_crossings.hpp"
#include "detail/flat.hpp"
#include "query.hpp"
#include "validation.hpp"

namespace rayq {

template <class T>
struct Triangle {
    using scalar_type = T;
    Vec3<T> a, b, c;
};

template <class T>
struct is_primitive<Triangle<T>> : std::true_type {};

template <class T>
inline Validation validate(const Triangle<T>& tri)
{
    return detail::Validator{}
        .finite(tri.a, "Triangle: vertex a is NaN or infinite")
        .finite(tri.b, "Triangle: vertex b is NaN or infinite")
        .finite(tri.c, "Triangle: vertex c is NaN or infinite")
        .nonzero(cross(tri.b - tri.a, tri.c - tri.a), "Triangle: vertices are collinear or coincide (no area)",
                 "Triangle: edges are too long for the number type", Defect::degenerate)
        .result();
}

template <class Policy, class T>
inline Crossings<T> crossings(Policy policy, const Ray<T>& ray, const Triangle<T>& tri)
{
    const auto pc = detail::planar_coordinates(policy, ray, tri.a, tri.b - tri.a, tri.c - tri.a);
    const bool inside = detail::within(pc.alpha, pc.det, false) && detail::within(pc.beta, pc.det, false) &&
                        detail::within(pc.alpha + pc.beta, pc.det, true);
    return detail::flat_crossing(pc, inside);
}

// The supporting plane, with certified bounds (for Hit::t_error).
// Inside the triangle: each edge function ((v_{i+1} − v_i) × (p − v_i))·n >= 0, n = (b − a) × (c − a)
// (twice the signed sub-triangle areas times |n|: the barycentrics without a division).
template <class T, class N>
inline detail::Margins<N> trim_margins(const Triangle<T>& tri, const Vec3<N>& o, const Vec3<N>& d, N t, Part)
{
    const Vec3<N> a = detail::lift<N>(tri.a), b = detail::lift<N>(tri.b), c = detail::lift<N>(tri.c);
    const Vec3<N> p = o + t * d, n = cross(b - a, c - a);
    detail::Margins<N> m;
    m.add(dot(cross(b - a, p - a), n));
    m.add(dot(cross(c - b, p - b), n));
    m.add(dot(cross(a - c, p - c), n));
    return m;
}

template <class N, class T>
inline detail::Residual<N> residual(const Triangle<T>& p, const Vec3<N>& o, const Vec3<N>& d, N t, Part)
{
    return detail::plane_residual(p.a, cross(detail::lift<N>(p.b) - detail::lift<N>(p.a), detail::lift<N>(p.c) - detail::lift<N>(p.a)), o, d, t);
}

namespace detail {
// The frame (a, b − a, c − a) in any number type, for the exact and the quick planar tests.
template <class T>
inline auto planar_frame(const Triangle<T>& tri)
{
    return [&tri](auto zero) {
        using N = decltype(zero);
        const Vec3<N> a = lift<N>(tri.a);
        return PlanarFrame<N>{a, lift<N>(tri.b) - a, lift<N>(tri.c) - a};
    };
}
// The quick lane's plane and trim (exact_crossings.hpp, QuickFlat).
template <class T>
inline QuickFlat quick_flat(const Ray<T>& ray, const Triangle<T>& tri)
{
    return quick_planar(ray, planar_frame(tri), true, all_within_static_range(tri.a, tri.b, tri.c));
}
}  // namespace detail

// Accurate: exact decisions, correctly rounded t (detail/exact_crossings.hpp).
template <class T>
inline Crossings<T> crossings(accurate_policy, const Ray<T>& ray, const Triangle<T>& tri)
{
    return detail::exact_flat_crossing(
        ray, tri, [&](const auto& plane) { return detail::exact_planar_inside(ray, detail::planar_frame(tri), -plane.sign_b(), true); },
        [&] { return detail::quick_flat(ray, tri); });
}

template <class T>
inline Vec3<T> outward_normal(const Triangle<T>& tri, const Vec3<T>&, Part) { return cross(tri.b - tri.a, tri.c - tri.a); }

}  // namespace rayq
