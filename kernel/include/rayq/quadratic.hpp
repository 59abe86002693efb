// rayq — the one quadratic solver. Every curved primitive reduces its ray equation to
//     F(t) = a·t² + 2·b·t + c,   F < 0 inside the solid,
// and asks this file where along the ray F < 0. The precision policy decides how the
// coefficients and the discriminant b² − a·c are computed and which root formula is used.
#pragma once

#include <cmath>
#include <limits>
#include <utility>

#include "detail/eft.hpp"
#include "detail/inline.hpp"
#include "detail/policy_ops.hpp"
#include "policy.hpp"
#include "vec3.hpp"

namespace rayq {

// F(t) = |u + t·v|² − (w + t·s)². The sphere is u = o − c, v = d, w = r, s = 0; cylinders and
// cones use the components of the ray perpendicular to their axis (s ≠ 0 for a cone).
// Keeping the form geometric, instead of expanding it to a, b, c at once, is what lets the
// stable and accurate policies avoid cancellation in the discriminant.
template <class T>
struct NormQuadratic {
    using scalar_type = T;
    Vec3<T> u, v;
    T w, s;
};

// F(t) = a·t² + 2·b·t + c given directly (general quadrics).
template <class T>
struct CoefficientQuadratic {
    using scalar_type = T;
    T a, b, c;
};

template <class T>
struct QuadraticTerms {
    T a, b, c;  // F(t) = a·t² + 2·b·t + c
    T disc;     // b² − a·c (a quarter of the textbook discriminant)
};

// An interval of t where the ray is inside the solid; ends may be ±infinity.
template <class T>
struct Span {
    T enter, exit;
};

// Where F(t) < 0, as at most two disjoint spans in ascending order (two when a < 0 and
// the ray passes both nappes of a cone or both sheets of a hyperboloid).
// Only the first `count` spans are set (see Crossings for why the rest stay unset).
template <class T>
struct Spans {
    int count = 0;
    union {
        Span<T> span[2];
    };
};

namespace detail {

// Textbook: the coefficients and b² − ac as written.
template <class T>
inline QuadraticTerms<T> terms(fast_policy, const NormQuadratic<T>& q)
{
    const T a = rayq::dot(q.v, q.v) - q.s * q.s;
    const T b = rayq::dot(q.u, q.v) - q.w * q.s;
    const T c = rayq::dot(q.u, q.u) - q.w * q.w;
    return {a, b, c, b * b - a * c};
}

// Hearn & Baker's discriminant, as analysed in Ray Tracing Gems ch. 7 ("Precision Improvements
// for Ray/Sphere Intersection", Haines et al. 2019):
// b² − ac = |v|²·(w² − |l|²) + s·(s|u|² − 2w·u·v) with l = u − (u·v̂)v̂ the ray's closest approach.
// |l|² is computed from a short vector instead of as the difference of two large products,
// so a ray far from a small sphere keeps its discriminant (for s = 0 the last term vanishes).
template <class T>
inline QuadraticTerms<T> terms(stable_policy, const NormQuadratic<T>& q)
{
    const T vv = rayq::dot(q.v, q.v), uv = rayq::dot(q.u, q.v), uu = rayq::dot(q.u, q.u);
    const T a = vv - q.s * q.s;
    const T b = uv - q.w * q.s;
    const T c = uu - q.w * q.w;
    const Vec3<T> l = vv > T(0) ? q.u - (uv / vv) * q.v : q.u;
    const T ll = vv > T(0) ? rayq::dot(l, l) : T(0);
    const T disc = vv * (q.w * q.w - ll) + (q.s == T(0) ? T(0) : q.s * (q.s * uu - T(2) * q.w * uv));
    return {a, b, c, disc};
}

// Error-free products throughout: a, b, c by Dot2 (as if in twice the precision), and
// b² − ac = |s·u − w·v|² − |u × v|² (Lagrange's identity) factored as (X − Y)(X + Y) with
// X, Y computed from difference-of-products components, so no squared large term cancels.
template <class T>
inline QuadraticTerms<T> terms(accurate_policy, const NormQuadratic<T>& q)
{
    const T ns = -q.s, nw = -q.w;
    const T vs[4] = {q.v.x, q.v.y, q.v.z, q.s}, vns[4] = {q.v.x, q.v.y, q.v.z, ns};
    const T uw[4] = {q.u.x, q.u.y, q.u.z, q.w}, unw[4] = {q.u.x, q.u.y, q.u.z, nw};
    const T a = dot2(vs, vns);
    const T b = dot2(uw, vns);
    const T c = dot2(uw, unw);
    const Vec3<T> su_wv{difference_of_products(q.s, q.u.x, q.w, q.v.x), difference_of_products(q.s, q.u.y, q.w, q.v.y),
                        difference_of_products(q.s, q.u.z, q.w, q.v.z)};
    const T x = rayq::length(su_wv);
    const T y = rayq::length(cross_compensated(q.u, q.v));
    return {a, b, c, (x - y) * (x + y)};
}

template <class Policy, class T>
inline QuadraticTerms<T> terms(Policy, const CoefficientQuadratic<T>& q)
{
    if constexpr (compensated_v<Policy>) return {q.a, q.b, q.c, difference_of_products(q.b, q.b, q.a, q.c)};
    else return {q.a, q.b, q.c, q.b * q.b - q.a * q.c};
}

// The body of solve_quadratic() below, shared by its two entry points.
template <class Policy, class Form>
RAYQ_INLINE Spans<typename Form::scalar_type> solve_quadratic_body(Policy policy, const Form& form)
{
    using T = typename Form::scalar_type;
    constexpr T inf = std::numeric_limits<T>::infinity();
    const QuadraticTerms<T> k = detail::terms(policy, form);
    Spans<T> out;
    const auto everywhere = [&] { out.count = 1; out.span[0] = {-inf, inf}; return out; };

    if (k.a == T(0)) {  // linear: a ray parallel to a cone's generator, a degenerate quadric
        if (k.b == T(0)) return k.c < T(0) ? everywhere() : out;
        const T t = -k.c / (T(2) * k.b);
        if (std::isnan(t)) return out;
        out.count = 1;
        out.span[0] = k.b < T(0) ? Span<T>{t, inf} : Span<T>{-inf, t};
        return out;
    }
    if (!(k.disc >= T(0))) return (k.a < T(0) && k.disc < T(0)) ? everywhere() : out;  // NaN: no roots
    // a < 0 with a double root: F <= 0 everywhere, touching 0 once (a line through a cone's apex
    // along a direction inside it): one unbounded span, not two that meet.
    if (k.a < T(0) && k.disc == T(0)) return everywhere();

    const T root = std::sqrt(k.disc);
    T t0, t1;
    if constexpr (std::is_same_v<Policy, fast_policy>) {
        t0 = (-k.b - root) / k.a;
        t1 = (-k.b + root) / k.a;
    } else {
        // q = −(b + sign(b)·√Δ) adds quantities of equal sign, so neither root suffers the
        // cancellation of −b ± √Δ (Press et al., Numerical Recipes §5.6; pbrt-v4 Quadratic()).
        const T q = -(k.b + std::copysign(root, k.b));
        t0 = q / k.a;
        t1 = q == T(0) ? t0 : k.c / q;  // q = 0 only when b = Δ = 0, i.e. c = 0: a double root at 0
    }
    if (std::isnan(t0) || std::isnan(t1)) return out;
    if (t1 < t0) std::swap(t0, t1);
    if (k.a > T(0)) {
        out.count = 1;
        out.span[0] = {t0, t1};
    } else {  // inside outside the roots: both nappes/sheets
        out.count = 2;
        out.span[0] = {-inf, t0};
        out.span[1] = {t1, inf};
    }
    return out;
}

}  // namespace detail

// The spans of t where F(t) < 0. Roots are closed ends, so a tangent ray yields [t, t].
// Forced inline under `fast` only: GCC called it out of line from a one-capped-cylinder scene's
// search, 60 of its ~300 instructions per ray; forcing it for every policy made the kernel tests
// compile 17% longer (certified_bound_test.cpp, g++ -O1: 33.8 -> 39.7 s), for `fast` alone not.
template <class Form>
RAYQ_INLINE Spans<typename Form::scalar_type> solve_quadratic(fast_policy policy, const Form& form)
{
    return detail::solve_quadratic_body(policy, form);
}
template <class Policy, class Form>
inline Spans<typename Form::scalar_type> solve_quadratic(Policy policy, const Form& form)
{
    return detail::solve_quadratic_body(policy, form);
}

}  // namespace rayq
