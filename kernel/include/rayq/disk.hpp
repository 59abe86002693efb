// rayq — disk: the points of the plane through `center` (normal `normal`, any length, pointing
// to the front) within `radius` of the center.
#pragma once

#include "detail/flat.hpp"
#include "query.hpp"
#include "validation.hpp"

namespace rayq {

template <class T>
struct Disk {
    using scalar_type = T;
    Vec3<T> center;
    Vec3<T> normal;
    T radius;
};

template <class T>
struct is_primitive<Disk<T>> : std::true_type {};

template <class T>
inline Validation validate(const Disk<T>& d)
{
    return detail::Validator{}
        .finite(d.center, "Disk: center is NaN or infinite")
        .finite(d.normal, "Disk: normal is NaN or infinite")
        .finite(d.radius, "Disk: radius is NaN or infinite")
        .positive(d.radius, "Disk: radius is zero or negative")
        .nonzero(d.normal, "Disk: normal has zero length", "Disk: normal is too long for the number type")
        .result();
}

template <class Policy, class T>
inline Crossings<T> crossings(Policy policy, const Ray<T>& ray, const Disk<T>& d)
{
    Crossings<T> c = detail::plane_crossing(policy, ray, d.center, d.normal);
    if (c.count == 0) return c;
    // The offset from the center as (o − c) + t·d, so the large coordinates cancel before t scales.
    const Vec3<T> offset = detail::point_at(policy, ray.origin - d.center, ray.direction, c.item[0].t);
    if (!(detail::dot(policy, offset, offset) <= d.radius * d.radius)) c.count = 0;
    return c;
}

// The supporting plane, with certified bounds (for Hit::t_error).
template <class T>
inline detail::Residual<T> residual(const Disk<T>& p, const Vec3<detail::Bounded<T>>& o, const Vec3<detail::Bounded<T>>& d,
                                    detail::Bounded<T> t, Part)
{
    return detail::plane_residual(p.center, detail::exact(p.normal), o, d, t);
}

template <class T>
inline Vec3<T> outward_normal(const Disk<T>& d, const Vec3<T>&, Part) { return d.normal; }

}  // namespace rayq
