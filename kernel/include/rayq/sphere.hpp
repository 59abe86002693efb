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

// F(t) = |q|² − r², q = o − c + t·d, to about u² of its magnitude, for the quick lanes' Newton
// steps (detail::quick_newton_rounded; inputs and t each 0 or within 2^±64, so that no product
// below underflows: StaticDoubleWord's grid argument, degree 2). Shorter after t than the residual
// in StaticDoubleWord (callgrind, SSE2, accurate double sphere hits: 1,193 -> 1,060 instructions,
// 133 -> 109 ns per hit, fast's 75, against its renormalizing form; 1,166 -> 1,060 and 113 -> 109
// against its compensated one, which evaluates F much as this does but with q as a full double
// word and without the cascade's grouping): q's components rounded once, q̃ = fl(u_hi + t·d), with the
// exact remainder E = q − q̃ from the two-sums and the two-product (computed e within 4.01u²·M of
// E, M = |u_hi| + |t·d|); F = (Σq̃² − r²) + 2q̃·E + E², the first sum error-free (two-products,
// a two-sum cascade: Ogita, Rump, Oishi's Dot2) with its low parts, 2q̃·e, and E² (≤ 4.01u²·M²)
// left out. The bound, per m = ΣM² + r²: the low parts' and 2q̃·e's sum (eight terms, their
// magnitudes within 8.02u·m: γ7) 56.2u²·m, 2q̃·e's own rounding 12.1u²·m, e's error 8.01u²·m, E²
// 4.01u²·m: 81u²·m, taken as 128u²·m (m's own rounding is far inside that).
// `Products` forms the products' error terms (detail::AsBuiltProducts or FusedProducts).
template <class T, class Products>
RAYQ_INLINE detail::Estimate<T> quick_residual_f(const Sphere<T>& s, const Ray<T>& ray, T t, Part, Products)
{
    using detail::Pair, detail::two_sum;
    const auto two_product = [](T a, T b) RAYQ_INLINE_LAMBDA { return Products::two_product(a, b); };
    const T o[3] = {ray.origin.x, ray.origin.y, ray.origin.z}, c[3] = {s.center.x, s.center.y, s.center.z};
    const T d[3] = {ray.direction.x, ray.direction.y, ray.direction.z};
    Pair<T> sq[3];
    T qe[3], m = s.radius * s.radius;
    for (int i = 0; i < 3; ++i) {
        const Pair<T> u = two_sum(o[i], -c[i]), p = two_product(t, d[i]), q = two_sum(u.hi, p.hi);
        const T e = (q.lo + u.lo) + p.lo;  // q − q.hi, within 4.01u²·M
        const T size = std::abs(u.hi) + std::abs(p.hi);
        m += size * size;
        sq[i] = two_product(q.hi, q.hi);
        qe[i] = q.hi * e;
    }
    const T cross = (qe[0] + qe[1]) + qe[2];  // a tree: one addition less after the last e than a running sum from 0
    const Pair<T> rr = two_product(s.radius, s.radius);
    const Pair<T> a1 = two_sum(sq[0].hi, sq[1].hi), a2 = two_sum(a1.hi, sq[2].hi), a3 = two_sum(a2.hi, -rr.hi);
    const T lo = ((a1.lo + a2.lo) + (a3.lo + (sq[0].lo + sq[1].lo))) + ((sq[2].lo - rr.lo) + T(2) * cross);
    return detail::estimate_of(a3.hi, lo, T(128) * detail::u2<T>() * m);
}

// Accurate: exact decisions, correctly rounded t (detail/exact_crossings.hpp). A ray whose line
// certainly passes the sphere is answered by batch::exactly_missed_sphere: ~10× cheaper than the
// exact path's filtered predicates on such misses. A double ray whose plain discriminant is
// positive, nearly always a hit, skips that test and goes straight to the sphere's quick lane
// (quick_sphere_crossings; pt.cpp, SSE2, min of 31 runs, measured before that lane left
// quick_solid_crossings: hits 117 -> 114 ns, misses 7.3 -> 8.1).
template <class T>
inline Crossings<T> crossings(accurate_policy, const Ray<T>& ray, const Sphere<T>& s, int limit = 2)
{
    // Every return names `out` (NRVO): written where the query reads it (exact_curved_crossings).
    Crossings<T> out;
    if constexpr (std::is_same_v<T, double>) {
        const detail::PlainQuadratic q = detail::plain_quadratic(ray, s);
        if (q.d > T(0)) {
            if (detail::quick_sphere_crossings(ray, s, q, limit, out)) return out;
        } else if (batch::exactly_missed_sphere(ray, s.center, s.radius)) {
            return out;
        }
    } else if (batch::exactly_missed_sphere(ray, s.center, s.radius)) {
        return out;
    }
    detail::exact_curved_crossings(ray, s, false, false, {false, false}, limit, out);
    return out;
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
