// rayq — sphere: |p − center| = radius.
#pragma once

#include "detail/policy_ops.hpp"
#include "detail/spans.hpp"
#include "quadratic.hpp"
#include "query.hpp"
#include "validation.hpp"

namespace rayq {

template <class T>
struct Sphere {
    using scalar_type = T;
    Vec3<T> center;
    T radius;
};

template <class T>
struct is_primitive<Sphere<T>> : std::true_type {};

template <class T>
inline Validation validate(const Sphere<T>& s)
{
    return detail::Validator{}
        .finite(s.center, "Sphere: center is NaN or infinite")
        .finite(s.radius, "Sphere: radius is NaN or infinite")
        .positive(s.radius, "Sphere: radius is zero or negative")
        .result();
}

// |o + t·d − c|² = r²: the norm form with u = o − c, v = d, w = r.
template <class Policy, class T>
inline Crossings<T> crossings(Policy policy, const Ray<T>& ray, const Sphere<T>& s)
{
    const NormQuadratic<T> f{ray.origin - s.center, ray.direction, s.radius, T(0)};
    return detail::crossings_of(solve_quadratic(policy, f));
}

template <class T>
inline Vec3<T> outward_normal(const Sphere<T>& s, const Vec3<T>& p, Part) { return p - s.center; }

}  // namespace rayq
