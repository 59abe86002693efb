// rayq — double-word numbers (an unevaluated sum hi + lo of two floats) carrying a certified
// error bound: the accurate policy's second filter, about u² relative instead of u. Algorithms:
// Dekker 1971; bounds after Joldes, Muller, Popescu, "Tight and rigorous error bounds for basic
// building blocks of double-word arithmetic" (ACM TOMS 2017): ≤ 3u² for the sum of two words
// relative to |a| + |b|, ≤ 7u² for the product; we use 4u² and 8u², then inflate as Bounded does.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>

#include "bounded.hpp"
#include "eft.hpp"

namespace rayq::detail {

template <class T>
struct DoubleWord {
    T hi = T(0), lo = T(0);
    T e = T(0);  // |exact − (hi + lo)| <= e

    DoubleWord() = default;
    DoubleWord(T x) : hi(x) {}  // NOLINT(google-explicit-constructor): numbers convert implicitly
    DoubleWord(T h, T l, T err) : hi(h), lo(l), e(err) {}

    T magnitude() const { return std::abs(hi) + std::abs(lo); }
};

template <class T>
RAYQ_INLINE T u2() { return unit_roundoff<T> * unit_roundoff<T>; }

// The sum and product of two double words (DoubleWord's), values only: within 4u²·(|a| + |b|)
// of a + b, and within 8u²·|a|·|b| of a·b, where no product underflows.
template <class T> RAYQ_INLINE Pair<T> double_word_sum(T a_hi, T a_lo, T b_hi, T b_lo)
{
    const Pair<T> s = two_sum(a_hi, b_hi);
    return two_sum(s.hi, s.lo + (a_lo + b_lo));
}
template <class T> RAYQ_INLINE Pair<T> double_word_product(T a_hi, T a_lo, T b_hi, T b_lo)
{
    const Pair<T> p = two_product(a_hi, b_hi);
    // |lo| <= ~3u·|p.hi| (normalized operands), so Fast2Sum renormalizes exactly (Joldes et al.'s
    // DWTimesDW does the same); where a_hi·b_hi underflows, every term is a multiple of the
    // smallest subnormal below 2^-1021, whose sums are exact.
    return fast_two_sum(p.hi, p.lo + (a_hi * b_lo + a_lo * b_hi));
}

template <class T> RAYQ_INLINE DoubleWord<T> operator+(const DoubleWord<T>& a, const DoubleWord<T>& b)
{
    const Pair<T> s = double_word_sum(a.hi, a.lo, b.hi, b.lo);
    // With an exact zero operand the sum is the other one, exactly (it is normalized).
    const T ma = a.magnitude(), mb = b.magnitude();
    return {s.hi, s.lo, grow_exact_operands(a.e + b.e + T(4) * u2<T>() * (ma + mb), ma + a.e, mb + b.e)};
}
template <class T> RAYQ_INLINE DoubleWord<T> operator-(const DoubleWord<T>& a) { return {-a.hi, -a.lo, a.e}; }
template <class T> RAYQ_INLINE DoubleWord<T> operator-(const DoubleWord<T>& a, const DoubleWord<T>& b) { return a + (-b); }
template <class T> RAYQ_INLINE DoubleWord<T> operator*(const DoubleWord<T>& a, const DoubleWord<T>& b)
{
    const Pair<T> p = double_word_product(a.hi, a.lo, b.hi, b.lo);
    const T ma = a.magnitude(), mb = b.magnitude();
    // Where products underflow, Two-Product's error term and the cross products each lose up to
    // half a subnormal (absolute, not relative): grow's floor covers them (Dekker's split too).
    const T size_a = ma + a.e;  // ma·e_b + e_a·e_b as size_a·e_b, as Bounded's product does
    return {p.hi, p.lo, grow_exact_operands(size_a * b.e + mb * a.e + T(8) * u2<T>() * ma * mb, size_a, mb + b.e)};
}
template <class T> RAYQ_INLINE DoubleWord<T>& operator+=(DoubleWord<T>& a, const DoubleWord<T>& b) { return a = a + b; }

// A double word with a static error bound, as Magnitude (magnitude.hpp) is to Bounded: the value,
// the magnitude m (the same polynomial on |inputs| with every sign +, computed in T), c and the
// degree d, and |exact − (hi + lo)| <= (c + 2)·u²·m (bound()). No running bound, and never
// renormalized: hi is the plain floating-point evaluation and lo gathers its first-order errors,
// each rounding's exact error from TwoSum or TwoProduct plus the operands' own lo terms
// (compensated evaluation: Ogita, Rump, Oishi, "Accurate sum and dot product", SIAM J. Sci.
// Comput. 2005; Graillat, Langlois, Louvet, compensated Horner, 2009). hi's chain is then the
// plain one and lo's runs beside it, where the renormalizing double-word operations made each
// operation wait for the last (callgrind, SSE2, accurate double capped-cylinder hits: 2,177 ->
// 2,035 instructions, 236 -> 211 ns per hit). The quick lanes' Newton steps evaluate F in it
// (quick_newton_rounded).
// The caller guarantees that every input is 0 or within 2^±64, and checks d <= 8. Every value is
// then a multiple of 2^-928 (each input of 2^-116, ulp(2^-64); two_sum, two_product and rounding
// keep a value on its operands' grid, a product on the product of theirs), so no product
// underflows, every error-free transformation is exact and m is 0 (the value exact) or above
// 2^-928; and below 2^600 none overflows.
// The bounds, with M the exact magnitude, |hi| <= (1 + θ)·M and |lo| <= l·u·M (1 + θ) (θ: the
// relative effect of at most a few hundred roundings, below 2^-40):
//   a + b: hi + lo = TwoSum(hi_a, hi_b), lo += lo_a + lo_b (two roundings, of at most
//          (1 + 2·max(l_a, l_b))·u²·(M_a + M_b)): c = max(c_a, c_b) + 2·max(l_a, l_b) + 2,
//          l = max(l_a, l_b) + 2;
//   a·b:   hi + lo = TwoProduct(hi_a, hi_b), lo += hi_a·lo_b + lo_a·hi_b (four roundings, of at
//          most (3·(l_a + l_b) + 1)·u²·M_a·M_b), leaving out lo_a·lo_b (l_a·l_b·u²·M_a·M_b) and
//          carrying the operands' errors (c_a + c_b)·u²·M_a·M_b: c = c_a + c_b + l_a·l_b +
//          3·(l_a + l_b) + 2, l = l_a + l_b + 2;
// the last + 1 in each c absorbing the (1 + θ) factors while c, l < 2^20. An input has c = l = 0
// and lo = 0 (`word`): a sum or product of two is exact (c = 0, l = 1), and a term with lo = 0 is
// skipped (c = c_a + 2·l_a + 2 or + l_a + 2 for a product or sum with an input). m's n roundings
// (n <= c + 1: only the exact sums and products of inputs add none to c, and they are leaves)
// leave c·u²·M <= (c + 1)·u²·m (2·c·n·u <= 1), and bound() rounds once more, within the last
// unit: relative u, or where u²·m is subnormal (m >= 2^-928 or 0), absolute 2^-1075, far below
// that unit. c, l, d and `word` are constants once inlined. `Products` forms the products' error
// terms (eft.hpp: as the build targets, or by hardware FMA).
template <class T, class Products = AsBuiltProducts>
struct StaticDoubleWord {
    T hi = T(0), lo = T(0), m = T(0);
    int c = 0, l = 0, d = 0;
    bool word = false;

    StaticDoubleWord() = default;
    // An input (exact).
    RAYQ_INLINE StaticDoubleWord(T x) : hi(x), m(std::abs(x)), d(1), word(true) {}  // NOLINT(google-explicit-constructor)
    RAYQ_INLINE StaticDoubleWord(T hi_, T lo_, T m_, int c_, int l_, int d_) : hi(hi_), lo(lo_), m(m_), c(c_), l(l_), d(d_) {}

    RAYQ_INLINE T bound() const { return T(c + 2) * m * u2<T>(); }
};

template <class T, class P> RAYQ_INLINE StaticDoubleWord<T, P> operator+(const StaticDoubleWord<T, P>& a, const StaticDoubleWord<T, P>& b)
{
    const Pair<T> s = two_sum(a.hi, b.hi);
    const T m = a.m + b.m;
    const int d = std::max(a.d, b.d), l = std::max(a.l, b.l);
    if (a.word && b.word) return {s.hi, s.lo, m, 0, 1, d};
    if (b.word) return {s.hi, s.lo + a.lo, m, a.c + a.l + 2, a.l + 2, d};
    if (a.word) return {s.hi, s.lo + b.lo, m, b.c + b.l + 2, b.l + 2, d};
    return {s.hi, s.lo + (a.lo + b.lo), m, std::max(a.c, b.c) + 2 * l + 2, l + 2, d};
}
template <class T, class P> RAYQ_INLINE StaticDoubleWord<T, P> operator-(const StaticDoubleWord<T, P>& a)
{
    StaticDoubleWord<T, P> negated = a;
    negated.hi = -a.hi, negated.lo = -a.lo;
    return negated;
}
template <class T, class P> RAYQ_INLINE StaticDoubleWord<T, P> operator-(const StaticDoubleWord<T, P>& a, const StaticDoubleWord<T, P>& b) { return a + (-b); }
template <class T, class P> RAYQ_INLINE StaticDoubleWord<T, P> operator*(const StaticDoubleWord<T, P>& a, const StaticDoubleWord<T, P>& b)
{
    const Pair<T> p = P::two_product(a.hi, b.hi);
    const T m = a.m * b.m;
    const int d = a.d + b.d;
    if (a.word && b.word) return {p.hi, p.lo, m, 0, 1, d};
    if (b.word) return {p.hi, p.lo + a.lo * b.hi, m, a.c + 2 * a.l + 2, a.l + 2, d};
    if (a.word) return {p.hi, p.lo + b.lo * a.hi, m, b.c + 2 * b.l + 2, b.l + 2, d};
    return {p.hi, p.lo + (a.hi * b.lo + a.lo * b.hi), m, a.c + b.c + a.l * b.l + 3 * (a.l + b.l) + 2, a.l + b.l + 2, d};
}
template <class T, class P> RAYQ_INLINE StaticDoubleWord<T, P>& operator+=(StaticDoubleWord<T, P>& a, const StaticDoubleWord<T, P>& b) { return a = a + b; }

// Certain sign of the exact value, or 0 when the bound straddles zero.
template <class T>
inline int certain_sign(const DoubleWord<T>& x)
{
    const T v = x.hi + x.lo;  // |v − (hi + lo)| <= u·|v|
    const T slack = grow(x.e + unit_roundoff<T> * std::abs(v));
    return sign_beyond(v, slack);
}

// The accurate policy's second filter precision. Double-word T in general; for float, hardware
// double: products of floats are exact in it and its unit roundoff 2^-53 is below float's
// double-word bound (u² = 2^-48), at a fraction of the cost of Dekker's arithmetic without FMA.
template <class T>
struct Wide {
    using type = DoubleWord<T>;
};
template <>
struct Wide<float> {
    using type = Bounded<double>;
};
template <class T>
using wide_t = typename Wide<T>::type;

// A wide number as a T with a certified bound: |exact − v| <= e (the rounding to T included).
template <class T>
struct Estimate {
    T v, e;
};
// hi + lo within `bound` of the exact value, rounded to one T.
template <class T>
RAYQ_INLINE Estimate<T> estimate_of(T hi, T lo, T bound)
{
    const T v = hi + lo;
    return {v, grow_inexact(bound + unit_roundoff<T> * std::abs(v))};
}
template <class T>
RAYQ_INLINE Estimate<T> estimate(const DoubleWord<T>& x)
{
    return estimate_of(x.hi, x.lo, x.e);
}
template <class T, class P>
RAYQ_INLINE Estimate<T> estimate(const StaticDoubleWord<T, P>& x)
{
    return estimate_of(x.hi, x.lo, x.bound());
}
// double -> float rounds to nearest: relative error <= u_float; grow() covers converting e. (An
// exact zero stays one; a tiny nonzero x.v may round to a zero v, so the bound alone cannot say.)
RAYQ_INLINE Estimate<float> estimate(const Bounded<double>& x)
{
    if (exact_zero(x)) return {0.0f, 0.0f};
    const float v = static_cast<float>(x.v);
    return {v, grow(static_cast<float>(x.e) + unit_roundoff<float> * std::abs(v))};
}

template <class T>
RAYQ_INLINE int certain_sign(const Bounded<T>& x)
{
    return sign_beyond(x.v, x.e);
}

}  // namespace rayq::detail
