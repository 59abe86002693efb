// rayq — a static error filter: a polynomial in the inputs evaluated in working precision W
// together with what a forward error bound needs, at about two operations per operation
// (Bounded, the running error bound, costs about eight). As in Shewchuk's and CGAL's static
// filters, the inputs' range is the caller's to guarantee, once, up front; the magnitude is
// computed alongside the value instead of from input bounds known in advance.
//   v  the computed value;
//   m  the same polynomial on |inputs| with every sign +, computed in W;
//   k  the most roundings on a path from an input (products k_a + k_b + 1, sums max + 1);
//   p  the number of products;
//   d  the degree (products d_a + d_b, sums max).
// k, p and d depend only on the expression, so the compiler folds them once the evaluation is
// inlined: an operation costs its value and its magnitude.
// The caller guarantees that every product of nonzero magnitudes stays in W's normal range: float
// inputs in double always do where no monomial has more than six float factors besides constants
// >= 1 (six float magnitudes multiply to [2^-894, 2^768]).
// A product then loses at most η = 2^-1075 <= u·m_j to underflow, and |exact − v| <=
// (k + p + 3)·u·m (bound()): each monomial carries at most k factors (1 + δ), |δ| <= u, so
// |v − E| <= γ_k·M (Higham, "Accuracy and Stability of Numerical Algorithms", §3.1); each
// product's underflow, carried to the result by the other factors, adds at most u·M;
// m >= M·(1 − u)^k; the three extra units absorb γ_k's higher-order terms and the rounding of the
// bound itself while (k + p)·u < 2^-20. A magnitude that overflows makes the bound infinite.
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
    W v = W(0), m = W(0);
    int k = 0, p = 0, d = 0;

    Magnitude() = default;
    // An input (exact).
    RAYQ_INLINE Magnitude(W x) : v(x), m(std::abs(x)), d(1) {}
    RAYQ_INLINE Magnitude(W v_, W m_, int k_, int p_, int d_) : v(v_), m(m_), k(k_), p(p_), d(d_) {}

    // |exact − v| <= bound(), under the caller's guarantee above.
    RAYQ_INLINE W bound() const { return W(k + p + 3) * unit_roundoff<W> * m; }
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
template <class W> RAYQ_INLINE Bounded<W> bounded(const Bounded<W>& x) { return x; }

// Sign of the exact value when the bound decides it, else 0.
template <class W> RAYQ_INLINE int certain_sign(const Magnitude<W>& x)
{
    const W e = x.bound();
    return x.v > e ? 1 : (-x.v > e ? -1 : 0);
}

}  // namespace rayq::detail
