// rayq — parallelogram: corner + α·edge0 + β·edge1 for α, β in [0, 1]; the front side is the
// one edge0 × edge1 points to (the design notes' square and rectangle).
#pragma once

#include "detail/exact_crossings.hpp"
#include "detail/flat.hpp"
#include "query.hpp"
#include "validation.hpp"

namespace rayq {

template <class T>
struct Parallelogram {
    using scalar_type = T;
    Vec3<T> corner;
    Vec3<T> edge0, edge1;
};

template <class T>
struct is_primitive<Parallelogram<T>> : std::true_type {};

template <class T>
inline Validation validate(const Parallelogram<T>& p)
{
    return detail::Validator{}
        .finite(p.corner, "Parallelogram: corner is NaN or infinite")
        .finite(p.edge0, "Parallelogram: edge0 is NaN or infinite")
        .finite(p.edge1, "Parallelogram: edge1 is NaN or infinite")
        .nonzero(cross(p.edge0, p.edge1), "Parallelogram: edges are parallel or zero (no area)",
                 "Parallelogram: edges are too long for the number type", Defect::degenerate)
        .result();
}

template <class Policy, class T>
inline Crossings<T> crossings(Policy policy, const Ray<T>& ray, const Parallelogram<T>& p)
{
    const auto pc = detail::planar_coordinates(policy, ray, p.corner, p.edge0, p.edge1);
    return detail::flat_crossing(pc, detail::within(pc.alpha, pc.det, true) && detail::within(pc.beta, pc.det, true));
}

// The supporting plane, with certified bounds (for Hit::t_error).
// Inside: p − corner = u·e0 + v·e1 with u, v in [0, 1]; U = ((p − corner) × e1)·n = u|n|² and
// V = (e0 × (p − corner))·n = v|n|², n = e0 × e1, so the margins need no division.
template <class T, class N>
inline detail::Margins<N> trim_margins(const Parallelogram<T>& pg, const Vec3<N>& o, const Vec3<N>& d, N t, Part)
{
    const Vec3<N> e0 = detail::lift<N>(pg.edge0), e1 = detail::lift<N>(pg.edge1), n = cross(e0, e1);
    const Vec3<N> q = o + t * d - detail::lift<N>(pg.corner);
    const N u = dot(cross(q, e1), n), v = dot(cross(e0, q), n), nn = dot(n, n);
    detail::Margins<N> m;
    m.add(u);
    m.add(nn - u);
    m.add(v);
    m.add(nn - v);
    return m;
}

template <class N, class T>
inline detail::Residual<N> residual(const Parallelogram<T>& p, const Vec3<N>& o, const Vec3<N>& d, N t, Part)
{
    return detail::plane_residual(p.corner, cross(detail::lift<N>(p.edge0), detail::lift<N>(p.edge1)), o, d, t);
}

namespace detail {
// The frame (corner, edge0, edge1) in any number type, for the exact and the quick planar tests.
template <class T>
inline auto planar_frame(const Parallelogram<T>& p)
{
    return [&p](auto zero) {
        using N = decltype(zero);
        return PlanarFrame<N>{lift<N>(p.corner), lift<N>(p.edge0), lift<N>(p.edge1)};
    };
}
// The quick lane's plane and trim (exact_crossings.hpp, QuickFlat).
template <class T>
inline QuickFlat quick_flat(const Ray<T>& ray, const Parallelogram<T>& p)
{
    return quick_planar(ray, planar_frame(p), false, all_within_static_range(p.corner, p.edge0, p.edge1));
}
}  // namespace detail

// Accurate: exact decisions, correctly rounded t (detail/exact_crossings.hpp).
template <class T>
inline Crossings<T> crossings(accurate_policy, const Ray<T>& ray, const Parallelogram<T>& p)
{
    // det = e0·(d × e1) = −d·n, so its sign is minus the plane's slope along the ray.
    return detail::exact_flat_crossing(
        ray, p, [&](const auto& plane) { return detail::exact_planar_inside(ray, detail::planar_frame(p), -plane.sign_b(), false); },
        [&] { return detail::quick_flat(ray, p); });
}

template <class T>
inline Vec3<T> outward_normal(const Parallelogram<T>& p, const Vec3<T>&, Part) { return cross(p.edge0, p.edge1); }

}  // namespace rayq
