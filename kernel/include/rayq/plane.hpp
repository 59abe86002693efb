// rayq — plane through `point`; `normal` (any length) points to the outside.
#pragma once

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
        .nonzero(p.normal, "Plane: normal has zero length", "Plane: normal is too long for the number type")
        .result();
}

template <class Policy, class T>
inline Crossings<T> crossings(Policy policy, const Ray<T>& ray, const Plane<T>& p)
{
    return detail::plane_crossing(policy, ray, p.point, p.normal);
}

// The supporting plane, with certified bounds (for Hit::t_error).
template <class T>
inline detail::Residual<T> residual(const Plane<T>& p, const Vec3<detail::Bounded<T>>& o, const Vec3<detail::Bounded<T>>& d,
                                    detail::Bounded<T> t, Part)
{
    return detail::plane_residual(p.point, detail::exact(p.normal), o, d, t);
}

template <class T>
inline Vec3<T> outward_normal(const Plane<T>& p, const Vec3<T>&, Part) { return p.normal; }

}  // namespace rayq
