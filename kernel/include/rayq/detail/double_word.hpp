// rayq — double-word numbers (an unevaluated sum hi + lo of two floats) carrying a certified
// error bound: the accurate policy's second filter, about u² relative instead of u. Algorithms:
// Dekker 1971; bounds after Joldes, Muller, Popescu, "Tight and rigorous error bounds for basic
// building blocks of double-word arithmetic" (ACM TOMS 2017): ≤ 3u² for the sum of two words
// relative to |a| + |b|, ≤ 7u² for the product; we use 4u² and 8u², then inflate as Bounded does.
#pragma once

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
RAYQ_INLINE DoubleWord<T> renormalize(T hi, T lo, T e)
{
    const Pair<T> s = two_sum(hi, lo);
    return {s.hi, s.lo, e};
}

template <class T>
RAYQ_INLINE T u2() { return unit_roundoff<T> * unit_roundoff<T>; }

template <class T> RAYQ_INLINE DoubleWord<T> operator+(const DoubleWord<T>& a, const DoubleWord<T>& b)
{
    const Pair<T> s = two_sum(a.hi, b.hi);
    const T lo = s.lo + (a.lo + b.lo);
    // With an exact zero operand the sum is the other one, exactly (it is normalized).
    const T ma = a.magnitude(), mb = b.magnitude();
    return renormalize(s.hi, lo, grow_exact_operands(a.e + b.e + T(4) * u2<T>() * (ma + mb), ma + a.e, mb + b.e));
}
template <class T> RAYQ_INLINE DoubleWord<T> operator-(const DoubleWord<T>& a) { return {-a.hi, -a.lo, a.e}; }
template <class T> RAYQ_INLINE DoubleWord<T> operator-(const DoubleWord<T>& a, const DoubleWord<T>& b) { return a + (-b); }
template <class T> RAYQ_INLINE DoubleWord<T> operator*(const DoubleWord<T>& a, const DoubleWord<T>& b)
{
    const Pair<T> p = two_product(a.hi, b.hi);
    const T lo = p.lo + (a.hi * b.lo + a.lo * b.hi);
    const T ma = a.magnitude(), mb = b.magnitude();
    // Where products underflow, Two-Product's error term and the cross products each lose up to
    // half a subnormal (absolute, not relative): grow's floor covers them (Dekker's split too).
    const T size_a = ma + a.e;  // ma·e_b + e_a·e_b as size_a·e_b, as Bounded's product does
    return renormalize(p.hi, lo, grow_exact_operands(size_a * b.e + mb * a.e + T(8) * u2<T>() * ma * mb, size_a, mb + b.e));
}
template <class T> RAYQ_INLINE DoubleWord<T>& operator+=(DoubleWord<T>& a, const DoubleWord<T>& b) { return a = a + b; }

// Certain sign of the exact value, or 0 when the bound straddles zero.
template <class T>
inline int certain_sign(const DoubleWord<T>& x)
{
    const T v = x.hi + x.lo;  // |v − (hi + lo)| <= u·|v|
    const T slack = grow(x.e + unit_roundoff<T> * std::abs(v));
    return v > slack ? 1 : (-v > slack ? -1 : 0);
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
template <class T>
RAYQ_INLINE Estimate<T> estimate(const DoubleWord<T>& x)
{
    const T v = x.hi + x.lo;
    return {v, grow_inexact(x.e + unit_roundoff<T> * std::abs(v))};
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
    return x.v > x.e ? 1 : (-x.v > x.e ? -1 : 0);
}

}  // namespace rayq::detail
