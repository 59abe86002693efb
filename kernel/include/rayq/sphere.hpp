// rayq — sphere: |p − center| = radius.
#pragma once

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
struct Sphere {
    using scalar_type = T;
    Vec3<T> center;
    T radius;
};

// The same sphere in another scalar type (exact when widening, float → double).
template <class U, class T>
constexpr Sphere<U> scalar_cast(const Sphere<T>& s) { return {scalar_cast<U>(s.center), U(s.radius)}; }

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
// Forced inline: once solve_quadratic() was forced inline under `fast`, GCC called this out of
// line from a one-sphere scene's intersect() (callgrind, SSE2: 147 against 127 instructions per ray).
template <class Policy, class T>
RAYQ_INLINE Crossings<T> crossings(Policy policy, const Ray<T>& ray, const Sphere<T>& s)
{
    const NormQuadratic<T> f{ray.origin - s.center, ray.direction, s.radius, T(0)};
    return detail::crossings_of(solve_quadratic(policy, f));
}

// |o + t·d − c|² − r² with certified bounds (for Hit::t_error).
// Untrimmed: every root of the surface is a hit.
template <class T, class N>
inline detail::Margins<N> trim_margins(const Sphere<T>&, const Vec3<N>&, const Vec3<N>&, N, Part)
{
    return {};
}

template <class N, class T>
inline detail::Residual<N> residual(const Sphere<T>& s, const Vec3<N>& o, const Vec3<N>& d, N t, Part)
{
    using B = N;
    const Vec3<B> q = o - detail::lift<N>(s.center) + t * d;
    const B r{s.radius};
    return {dot(q, q) - r * r, B{T(2)} * dot(q, d), dot(d, d)};
}

// Accurate: exact decisions, correctly rounded t (detail/exact_crossings.hpp). A ray whose line
// certainly passes the sphere is answered first (batch::exactly_missed_sphere): ~10× cheaper than
// the exact path's filtered predicates on such misses.
template <class T>
inline Crossings<T> crossings(accurate_policy, const Ray<T>& ray, const Sphere<T>& s, int limit = 2)
{
    if (batch::exactly_missed_sphere(ray, s.center, s.radius)) return {};
    return detail::exact_curved_crossings(ray, s, false, false, {false, false}, limit);
}

template <class T>
inline Vec3<T> outward_normal(const Sphere<T>& s, const Vec3<T>& p, Part) { return p - s.center; }

// Every point and radius of the sphere, for the exact path's rescaling (detail/exact_crossings.hpp).
template <class S, class F, std::enable_if_t<detail::is_instance_v<S, Sphere>, int> = 0>
inline void each_length(S& s, F&& f)
{
    f(s.center), f(s.radius);
}

}  // namespace rayq
