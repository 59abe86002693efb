// rayq — disk: the points of the plane through `center` (normal `normal`, any length, pointing
// to the front) within `radius` of the center.
#pragma once

#include <tuple>

#include "detail/exact_crossings.hpp"
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
        .nonzero(d.normal, "Disk: normal has zero length (or its squared length underflows the number type)", "Disk: normal is too long for the number type")
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
// On the disk: r² − |p − c|² >= 0 at the exact point.
template <class T, class N>
inline detail::Margins<N> trim_margins(const Disk<T>& disk, const Vec3<N>& o, const Vec3<N>& d, N t, Part)
{
    const Vec3<N> q = o + t * d - detail::lift<N>(disk.center);
    const N r{disk.radius};
    detail::Margins<N> m;
    m.add(r * r - dot(q, q));
    return m;
}

template <class N, class T>
inline detail::Residual<N> residual(const Disk<T>& p, const Vec3<N>& o, const Vec3<N>& d, N t, Part)
{
    return detail::plane_residual(p.center, detail::lift<N>(p.normal), o, d, t);
}

namespace detail {
// The quick lane's plane and trim (exact_crossings.hpp, QuickFlat): with w = (d·n)·(o + t·d − c)
// at the root t = −f/(d·n), |w|² − r²·(d·n)² has the rim's sign and six float factors per
// monomial.
template <class T>
inline QuickFlat quick_flat(const Ray<T>& ray, const Disk<T>& disk)
{
    using M = Magnitude<double>;
    // Out of range, computed and discarded, as quick_planar's (the counts stay constants).
    const Residual<M> plane = quick_plane(ray, disk);
    const Vec3<M> q = lift<M>(ray.origin) - lift<M>(disk.center), d = lift<M>(ray.direction);
    const Vec3<M> w = plane.df * q - plane.f * d;
    const M r{disk.radius};
    return {plane.f, plane.df, -certain_sign(dot(w, w) - r * r * (plane.df * plane.df)),
            all_within_static_range(disk.center, disk.normal, disk.radius)};
}
}  // namespace detail

// Accurate: exact decisions, correctly rounded t. Inside: |o + t·d − c|² − r² <= 0 at the
// plane's root, evaluated exactly (detail/exact_crossings.hpp).
template <class T>
inline Crossings<T> crossings(accurate_policy, const Ray<T>& ray, const Disk<T>& disk_in)
{
    const Disk<T> disk{disk_in.center, detail::direction_near_unit(disk_in.normal), disk_in.radius};
    const auto rim = [&](auto zero) {
        using N = decltype(zero);
        const Vec3<N> q = detail::lift<N>(ray.origin) - detail::lift<N>(disk.center), d = detail::lift<N>(ray.direction);
        const N r{disk.radius};
        return detail::Residual<N>{dot(q, q) - r * r, N{T(2)} * dot(q, d), dot(d, d)};
    };
    const detail::PartCoefficients<Disk<T>> plane{&disk, &ray, Part::surface};
    return detail::exact_flat_crossing(
        ray, disk, [&](const auto&) { return detail::quadratic_sign_at<T>(rim, plane) <= 0; },
        [&] { return detail::quick_flat(ray, disk); });
}

template <class T>
inline Vec3<T> outward_normal(const Disk<T>& d, const Vec3<T>&, Part) { return d.normal; }

}  // namespace rayq
