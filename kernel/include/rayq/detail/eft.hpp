// rayq — error-free transformations and the compensated operations built on them.
//
// Sources: Ogita, Rump, Oishi, "Accurate sum and dot product" (SIAM J. Sci. Comput. 2005) for
// TwoSum/TwoProduct/Dot2; Dekker 1971 / Veltkamp splitting where no hardware FMA exists;
// pbrt-v4 "Managing Rounding Error" (DifferenceOfProducts) for why the discriminant needs them.
#pragma once

#include <cmath>

#include "../vec3.hpp"

namespace rayq::detail {

// x + y = s + e exactly (Knuth's TwoSum: no precondition on magnitudes).
template <class T>
struct Pair {
    T hi, lo;
};

template <class T>
RAYQ_INLINE Pair<T> two_sum(T a, T b)
{
    const T s = a + b;
    const T bb = s - a;
    const T e = (a - (s - bb)) + (b - bb);
    return {s, e};
}

// a + b = s + e exactly when |a| >= |b| or a = 0 (Dekker's Fast2Sum: half TwoSum's operations).
template <class T>
RAYQ_INLINE Pair<T> fast_two_sum(T a, T b)
{
    const T s = a + b;
    return {s, b - (s - a)};
}

// a·b = p + e exactly by the hardware FMA: one fused operation for the error term. Where the
// build does not target FMA, only inside code compiled for it (FusedProducts below).
template <class T>
RAYQ_INLINE Pair<T> fused_two_product(T a, T b)
{
    const T p = a * b;
    return {p, std::fma(a, b, -p)};
}

// a·b = p + e exactly (barring overflow/underflow). With a hardware FMA the error term is one
// fused operation; without one (the x86-64 baseline), std::fma is a slow library call, so we use
// Dekker's product with Veltkamp splitting instead.
template <class T>
RAYQ_INLINE Pair<T> two_product(T a, T b)
{
#if defined(__FMA__) || defined(__FMA4__) || defined(__aarch64__) || defined(__ARM_FEATURE_FMA)
    return fused_two_product(a, b);
#else
    const T p = a * b;
    constexpr T splitter = sizeof(T) == 4 ? T(4097) : T(134217729);  // 2^ceil(digits/2) + 1
    const T ca = splitter * a, cb = splitter * b;
    const T ah = ca - (ca - a), al = a - ah;
    const T bh = cb - (cb - b), bl = b - bh;
    return {p, ((ah * bh - p) + ah * bl + al * bh) + al * bl};
#endif
}

// How a double-word evaluation forms its products' error terms: two_product as the build targets
// it (AsBuilt), or the hardware FMA (Fused), for code compiled for FMA inside a function that
// only runs where the CPU has one (quick_f_estimate, exact_crossings.hpp). Both error terms are
// exact.
struct AsBuiltProducts {
    template <class T>
    static RAYQ_INLINE Pair<T> two_product(T a, T b) { return detail::two_product(a, b); }
};
struct FusedProducts {
    template <class T>
    static RAYQ_INLINE Pair<T> two_product(T a, T b) { return fused_two_product(a, b); }
};

// a·b − c·d with both products error-free, so the subtraction — where cancellation lives —
// sees exact operands (pbrt-v4 DifferenceOfProducts; this form is exactly antisymmetric:
// dop(a,b,c,d) == −dop(c,d,a,b), which keeps shared triangle edges watertight).
template <class T>
inline T difference_of_products(T a, T b, T c, T d)
{
    const Pair<T> ab = two_product(a, b);
    const Pair<T> cd = two_product(c, d);
    return (ab.hi - cd.hi) + (ab.lo - cd.lo);
}

// Σ aᵢ·bᵢ as if computed in twice the working precision, then rounded (Ogita–Rump–Oishi Dot2).
template <class T, int N>
inline T dot2(const T (&a)[N], const T (&b)[N])
{
    Pair<T> acc = two_product(a[0], b[0]);
    T err = acc.lo;
    for (int i = 1; i < N; ++i) {
        const Pair<T> p = two_product(a[i], b[i]);
        const Pair<T> s = two_sum(acc.hi, p.hi);
        acc.hi = s.hi;
        err += p.lo + s.lo;
    }
    return acc.hi + err;
}

template <class T>
inline T dot_compensated(const Vec3<T>& a, const Vec3<T>& b)
{
    const T x[3] = {a.x, a.y, a.z};
    const T y[3] = {b.x, b.y, b.z};
    return dot2(x, y);
}

template <class T>
inline Vec3<T> cross_compensated(const Vec3<T>& a, const Vec3<T>& b)
{
    return {difference_of_products(a.y, b.z, a.z, b.y), difference_of_products(a.z, b.x, a.x, b.z),
            difference_of_products(a.x, b.y, a.y, b.x)};
}

}  // namespace rayq::detail
