// rayq — the shared core of the flat primitives (plane, disk, parallelogram, triangle).
#pragma once

#include "../hit.hpp"
#include "../query.hpp"
#include "../ray.hpp"
#include "bounded.hpp"
#include "policy_ops.hpp"

namespace rayq::detail {

// Where the ray's line meets the plane through `point` with normal n: t = ((point − o)·n)/(d·n).
// No crossing when d·n = 0 (the ray is parallel, or lies in the plane). The ray enters the
// half-space behind n — the solid — when d·n < 0.
template <class Policy, class T>
inline Crossings<T> plane_crossing(Policy policy, const Ray<T>& ray, const Vec3<T>& point, const Vec3<T>& n)
{
    Crossings<T> out;
    const T dn = detail::dot(policy, ray.direction, n);
    if (dn == T(0)) return out;
    const T t = detail::dot(policy, point - ray.origin, n) / dn;
    if (std::isfinite(t)) out.add(t, Part::surface, dn < T(0));
    return out;
}

// The ray's line against the plane point corner + α·e0 + β·e1, solved by Cramer's rule as in
// Möller–Trumbore: o + t·d = corner + α·e0 + β·e1 with determinant D = d·(e0 × e1). The
// numerators are kept undivided so that inside tests compare them with D, which does not round.
template <class T>
struct PlanarCoordinates {
    T det, alpha, beta, t;  // α = alpha/det, β = beta/det, t = t/det
};

template <class Policy, class T>
inline PlanarCoordinates<T> planar_coordinates(Policy policy, const Ray<T>& ray, const Vec3<T>& corner,
                                               const Vec3<T>& e0, const Vec3<T>& e1)
{
    const Vec3<T> q = ray.origin - corner;
    const Vec3<T> p = detail::cross(policy, ray.direction, e1);
    const Vec3<T> r = detail::cross(policy, q, e0);
    return {detail::dot(policy, e0, p), detail::dot(policy, q, p), detail::dot(policy, ray.direction, r),
            detail::dot(policy, e1, r)};
}

// lo·det <= x <= hi·det, for either sign of det (lo, hi ∈ {0, 1}).
template <class T>
constexpr bool within(T x, T det, bool upper_bound)
{
    if (det > T(0)) return x >= T(0) && (!upper_bound || x <= det);
    return x <= T(0) && (!upper_bound || x >= det);
}

// A crossing from planar coordinates; entering when the ray meets the front (e0 × e1) side.
template <class T>
inline Crossings<T> flat_crossing(const PlanarCoordinates<T>& pc, bool inside)
{
    Crossings<T> out;
    if (!inside || pc.det == T(0)) return out;
    const T t = pc.t / pc.det;
    // det = e0·(d × e1) = −d·(e0 × e1): det > 0 is d·n < 0, the ray meeting the front side.
    if (std::isfinite(t)) out.add(t, Part::surface, pc.det > T(0));
    return out;
}

}  // namespace rayq::detail
