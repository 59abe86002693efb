// rayq — plane through `point`; `normal` (any length) points to the outside.
#pragma once

#include <tuple>

#include "detail/exact_crossings.hpp"
#include "detail/flat.hpp"
#include "query.hpp"
#include "validation.hpp"

namespace rayq {

template <class T>
struct Plane {
    using scalar_type = T;
    Vec3<T> point;
    Vec3<T> normal;
};

template <class T>
struct is_primitive<Plane<T>> : std::true_type {};

template <class T>
inline Validation validate(const Plane<T>& p)
{
    return detail::Validator{}
        .finite(p.point, "Plane: point is NaN or infinite")
        .finite(p.normal, "Plane: normal is NaN or infinite")
        .nonzero(p.normal, "Plane: normal has zero length (or its squared length underflows the number type)", "Plane: normal is too long for the number type")
        .result();
}

template <class Policy, class T>
inline Crossings<T> crossings(Policy policy, const Ray<T>& ray, const Plane<T>& p)
{
    return detail::plane_crossing(policy, ray, p.point, p.normal);
}

// The supporting plane, with certified bounds (for Hit::t_error).
// Untrimmed: every root of the surface is a hit.
template <class T, class N>
inline detail::Margins<N> trim_margins(const Plane<T>&, const Vec3<N>&, const Vec3<N>&, N, Part)
{
    return {};
}

template <class N, class T>
inline detail::Residual<N> residual(const Plane<T>& p, const Vec3<N>& o, const Vec3<N>& d, N t, Part)
{
    return detail::plane_residual(p.point, detail::lift<N>(p.normal), o, d, t);
}

namespace detail {
// The quick lane's plane (exact_crossings.hpp, QuickFlat): no trim, every point of the plane counts.
template <class T>
inline QuickFlat quick_flat(const Ray<T>& ray, const Plane<T>& p)
{
    const auto plane = quick_plane(ray, p);
    return {plane.f, plane.df, 1, all_within_static_range(p.point, p.normal)};
}
}  // namespace detail

// Accurate: exact decisions, correctly rounded t (detail/exact_crossings.hpp).
template <class T>
inline Crossings<T> crossings(accurate_policy, const Ray<T>& ray, const Plane<T>& p)
{
    return detail::exact_flat_crossing(ray, p, [](const auto&) { return true; }, [&] { return detail::quick_flat(ray, p); });
}

template <class T>
inline Vec3<T> outward_normal(const Plane<T>& p, const Vec3<T>&, Part) { return p.normal; }

}  // namespace rayq
