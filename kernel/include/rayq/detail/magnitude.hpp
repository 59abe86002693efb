// rayq — a static error filter: a polynomial in the inputs evaluated in working precision W
// together with what a forward error bound needs, at about two operations per operation
// (Bounded, the running error bound, costs about eight). As in Shewchuk's and CGAL's static
// filters, the inputs' range is checked once, up front (in_range), and the magnitude is computed
// alongside the value instead of from input bounds known in advance.
//   v  the computed value;
//   m  the same polynomial on |inputs| with every sign +, computed in W;
//   k  the most roundings on a path from an input (products k_a + k_b + 1, sums max + 1);
//   p  the number of products;
//   d  the degree (products d_a + d_b, sums max).
// k, p and d depend only on the expression, so the compiler folds them once the evaluation is
// inlined: an operation costs its value and its magnitude.
// With every nonzero input in [2^-80, 2^80] (the caller's check) and degree <= 12, every
// product's magnitude lies in [2^-960, 2^960], inside double's normal range, so a product loses at
// most η = 2^-1075 <= u·m_j to underflow. Then |exact − v| <= (k + p + 3)·u·m (bound()): each
// monomial carries at most k factors (1 + δ), |δ| <= u, so |v − E| <= γ_k·M (Higham, "Accuracy and
// Stability of Numerical Algorithms", §3.1); each product's underflow, carried to the result by
// the other factors, adds at most u·M; m >= M·(1 − u)^k; the three extra units absorb γ_k's
// higher-order terms and the rounding of the bound itself while (k + p)·u < 2^-20.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>
#include <type_traits>

#include "bounded.hpp"
#include "inline.hpp"

namespace rayq::detail {

template <class W>
struct Magnitude {
    static_assert(std::numeric_limits<W>::min_exponent < -960, "products of twelve factors in 2^±80 must stay normal");
    W v = W(0), m = W(0);
    int k = 0, p = 0, d = 0;

    Magnitude() = default;
    // An input (exact), which the caller has checked with in_range.
    RAYQ_INLINE Magnitude(W x) : v(x), m(std::abs(x)), d(1) {}
    RAYQ_INLINE Magnitude(W v_, W m_, int k_, int p_, int d_) : v(v_), m(m_), k(k_), p(p_), d(d_) {}

    // Whether x may be an input (branch-free: it runs on every input of the filter).
    template <class T>
    static RAYQ_INLINE bool in_range(T x)
    {
        return (x == T(0)) | ((std::abs(x) >= T(0x1p-80)) & (std::abs(x) <= T(0x1p80)));
    }

    // |exact − v| <= bound(), or +infinity beyond the degree the analysis above covers.
    RAYQ_INLINE W bound() const { return d > 12 ? std::numeric_limits<W>::infinity() : W(k + p + 3) * unit_roundoff<W> * m; }
};

template <class W> RAYQ_INLINE Magnitude<W> operator+(const Magnitude<W>& a, const Magnitude<W>& b)
{
    return {a.v + b.v, a.m + b.m, std::max(a.k, b.k) + 1, a.p + b.p, std::max(a.d, b.d)};
}
template <class W> RAYQ_INLINE Magnitude<W> operator-(const Magnitude<W>& a, const Magnitude<W>& b)
{
    return {a.v - b.v, a.m + b.m, std::max(a.k, b.k) + 1, a.p + b.p, std::max(a.d, b.d)};
}
template <class W> RAYQ_INLINE Magnitude<W> operator-(const Magnitude<W>& a) { return {-a.v, a.m, a.k, a.p, a.d}; }
template <class W> RAYQ_INLINE Magnitude<W> operator*(const Magnitude<W>& a, const Magnitude<W>& b)
{
    return {a.v * b.v, a.m * b.m, a.k + b.k + 1, a.p + b.p + 1, a.d + b.d};
}
template <class W> RAYQ_INLINE Magnitude<W>& operator+=(Magnitude<W>& a, const Magnitude<W>& b) { return a = a + b; }

template <class N> struct is_magnitude : std::false_type {};
template <class W> struct is_magnitude<Magnitude<W>> : std::true_type {};

// The same as a running error bound, for arithmetic that continues in Bounded.
template <class W> RAYQ_INLINE Bounded<W> bounded(const Magnitude<W>& x) { return {x.v, x.bound()}; }

// Sign of the exact value when the bound decides it, else 0.
template <class W> RAYQ_INLINE int certain_sign(const Magnitude<W>& x)
{
    const W e = x.bound();
    return x.v > e ? 1 : (-x.v > e ? -1 : 0);
}

}  // namespace rayq::detail
