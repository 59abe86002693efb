// rayq — numbers that carry a certified bound on their distance from the exact value:
// |exact − v| <= e. Running error analysis in the style of pbrt-v4 "Managing Rounding Error"
// (§6.8: conservative bounds propagated through each operation), evaluated in the working
// precision: each bound is computed with round-to-nearest, then inflated by 8 unit roundoffs, which
// covers the rounding of the bound's own arithmetic (≤ 4 roundings per operation), and raised to a
// floor of 16 times the smallest normal number, which covers gradual underflow (grow).
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>

#include "../vec3.hpp"

namespace rayq::detail {

template <class T>
struct Bounded {
    T v;      // the computed value
    T e = 0;  // |exact − v| <= e
};

template <class T>
inline constexpr T unit_roundoff = std::numeric_limits<T>::epsilon() / 2;

// Products that underflow err absolutely, by up to denorm_min/2 each: at most 4·denorm_min per
// operation (five products in Bounded's, eight in DoubleWord's). Where the inflated bound g is at
// least F − 4·denorm_min, the spare ~3u·g of the 8u inflation covers that (3u·F = 24·denorm_min,
// as u·min = denorm_min/2); below, the floor F = 16·min adds at least 4·denorm_min to g.
// A floor, not an added denorm_min as before: a subnormal operand costs x86 a microcode assist
// per instruction unless DAZ is set (rayq needs gradual underflow, so users must leave it off).
// With the added denorm_min, -march=native builds ran accurate scenes 2–3× slower (one float
// sphere: 26 against 51 M rays/s now) and every policy's full hit record up to 17× slower
// (rayq-bench); the MXCSR denormal flag showed it on every hit. NaN stays NaN.
template <class T>
inline constexpr T bound_floor = T(16) * std::numeric_limits<T>::min();

template <class T>
RAYQ_INLINE T grow(T bound)
{
    const T inflated = bound * (T(1) + T(8) * unit_roundoff<T>);
    return inflated < bound_floor<T> ? bound_floor<T> : inflated;
}

// The bound of a result that is certainly exact stays zero rather than rising to the floor: a
// product of a floor with a small value would be subnormal, the operand grow() avoids (the MXCSR
// flag showed it on flat parts' hit records, where a = 0 exactly, on quadrics with zero
// coefficients, and on CAD-like inputs: axis-aligned normals, edges and rays, whose zero
// components enter as exact zero factors and differences). A sum or difference whose bound terms
// are all zero is exact: its operands are, and u·|v| = 0 puts |v| below 2·min, where every sum of
// two floats is representable (grow_inexact). A sum or product with an exact zero operand, one
// whose size |v| + e is zero, is exact when the other operand is, that is when its bound terms
// are all zero (grow_exact_operands).
template <class T>
RAYQ_INLINE T grow_inexact(T bound)
{
    return bound == T(0) ? T(0) : grow(bound);
}
template <class T>
RAYQ_INLINE T grow_exact_operands(T bound, T size_a, T size_b)
{
    // A branch, rarely taken on ordinary rays, costs them least: the same test as a select cost
    // the full hit record up to 31% (rayq-bench, SSE2); the branch, with the products' bounds
    // reusing the sizes, nothing on average (geometric mean 0.999) and at most 8% (double
    // frustum, accurate).
    if (RAYQ_UNLIKELY(bound == T(0)) && std::min(size_a, size_b) == T(0)) return T(0);
    return grow(bound);
}
template <class T>
RAYQ_INLINE bool exact_zero(Bounded<T> a)
{
    return a.v == T(0) && a.e == T(0);
}

template <class T> RAYQ_INLINE Bounded<T> operator+(Bounded<T> a, Bounded<T> b)
{
    const T v = a.v + b.v;
    return {v, grow_inexact(a.e + b.e + unit_roundoff<T> * std::abs(v))};
}
template <class T> RAYQ_INLINE Bounded<T> operator-(Bounded<T> a, Bounded<T> b)
{
    const T v = a.v - b.v;
    return {v, grow_inexact(a.e + b.e + unit_roundoff<T> * std::abs(v))};
}
template <class T> RAYQ_INLINE Bounded<T> operator-(Bounded<T> a) { return {-a.v, a.e}; }
template <class T> RAYQ_INLINE Bounded<T> operator*(Bounded<T> a, Bounded<T> b)
{
    // |a·b − v| <= |a|·e_b + |b|·e_a + e_a·e_b + u·|v|, the first and third terms as
    // (|a| + e_a)·e_b: a's size, which the exact-zero test needs anyway (at most four roundings
    // on any path, as before).
    const T v = a.v * b.v, size_a = std::abs(a.v) + a.e, size_b = std::abs(b.v) + b.e;
    return {v, grow_exact_operands(size_a * b.e + std::abs(b.v) * a.e + unit_roundoff<T> * std::abs(v), size_a, size_b)};
}
template <class T> RAYQ_INLINE Bounded<T>& operator+=(Bounded<T>& a, Bounded<T> b) { return a = a + b; }

// The sign of an exact value known to lie within `slack` of v: ±1 when v clears the slack, else 0
// (also for NaN). Without branches: where the sign is a coin flip (a plane's f and df on random
// rays), nested conditionals became two branches that mispredicted (perf: 14% of an accurate
// double plane's hit samples; per ray, -O3 SSE2, min of 15 runs over 32,768: hits 93 -> 82 ns,
// misses 37 -> 28, fast's 63 and 37).
template <class T> RAYQ_INLINE int sign_beyond(T v, T slack) { return int(v > slack) - int(-v > slack); }

// Bounds of |x| over the values x may take (|v| + e rounds only when e is not zero).
template <class T> RAYQ_INLINE T upper(T v, T e) { return e == T(0) ? std::abs(v) : grow(std::abs(v) + e); }
template <class T> RAYQ_INLINE T upper(Bounded<T> a) { return upper(a.v, a.e); }
// (|v| − e) rounded toward zero: one rounding of relative size <= u, removed by (1 − 2u).
template <class T> RAYQ_INLINE T lower(T v, T e) { return (std::abs(v) - e) * (T(1) - T(2) * unit_roundoff<T>); }
template <class T> RAYQ_INLINE T lower(Bounded<T> a) { return lower(a.v, grow_inexact(a.e)); }

// An input vector as numbers of type N (Bounded<T>: exact, error 0; Expansion<T>: one component).
template <class N, class T> RAYQ_INLINE Vec3<N> lift(const Vec3<T>& v) { return {N{v.x}, N{v.y}, N{v.z}}; }
template <class T> RAYQ_INLINE Vec3<Bounded<T>> exact(const Vec3<T>& v) { return lift<Bounded<T>>(v); }

// F(t), F'(t) and the leading coefficient a of a primitive's implicit function along the ray, in
// any number type N: with Bounded<T> each carries its bound (what certify_root needs); with
// Expansion<T> they are exact (what the accurate policy's decisions fall back to).
template <class N>
struct Residual {
    N f, df, a;
};

// The plane through `point` with normal n: F = (o + t·d − point)·n, linear.
template <class N, class T>
RAYQ_INLINE Residual<N> plane_residual(const Vec3<T>& point, const Vec3<N>& n, const Vec3<N>& o, const Vec3<N>& d, N t)
{
    return {dot(o - lift<N>(point) + t * d, n), dot(d, n), N{T(0)}};
}

// The conditions an exact hit point must meet to lie on the trimmed part, each as a number that
// must be >= 0: the edges of a flat primitive, the height range of an axial side, a cap's radius,
// a quadric's clip box (at most six). A posteriori, like the residual: evaluated at t with t's own
// bound, so they speak for the exact root, not only for the computed point.
template <class N>
struct Margins {
    int count = 0;
    N m[6];
    void add(N v) { m[count++] = v; }
};

// Every margin certainly >= 0: its value minus its bound, rounded toward zero, still > 0 (or the
// margin is exactly zero with no error: a point exactly on the trim line is on the part).
template <class T>
inline bool certainly_within(const Margins<Bounded<T>>& ms)
{
    for (int i = 0; i < ms.count; ++i) {
        const Bounded<T>& m = ms.m[i];
        if (!exact_zero(m) && !(m.v > T(0) && lower(m) > T(0))) return false;
    }
    return true;
}

// A certified distance from t to a root of the exact quadratic
//   a·h² + F'(t)·h + F(t) = 0,   h = root − t,
// given only bounds on the three exact coefficients; finite only when a real root provably exists.
// If |F'| >= D > 0 and D² >= 4·|a|max·|F|max, a root exists with |h| <= 2|F|max/D (the smaller root
// of the quadratic in h, in the cancellation-free form 2F/(F' ± √…)). Otherwise, if a·F <= 0 is
// certain (so the discriminant F'² − 4aF >= 0) and |a| >= A > 0, every root has
// |h| <= |F'|max/A + √(|F|max/A) (Cauchy's bound). Otherwise (near tangency, where the exact
// discriminant may be negative and the ray miss) no bound: +infinity. near_root_distance is the
// first case alone, which also says that the root found is the one nearest t.
template <class T>
inline T near_root_distance(const Residual<Bounded<T>>& r)
{
    const T f_max = upper(r.f), a_max = upper(r.a), d_min = lower(r.df);
    if (d_min > T(0) && d_min * d_min * (T(1) - T(4) * unit_roundoff<T>) >= grow(T(4) * a_max * f_max)) {
        const T h = grow(T(2) * f_max / d_min);
        if (h >= T(0)) return h;  // not NaN: overflowed bounds (inf/inf) certify nothing
    }
    return std::numeric_limits<T>::infinity();
}

template <class T>
inline T certify_root(const Residual<Bounded<T>>& r)
{
    if (const T h = near_root_distance(r); h < std::numeric_limits<T>::infinity()) return h;
    const T f_max = upper(r.f), a_min = lower(r.a), f_min = lower(r.f);
    const bool opposite = f_min > T(0) && (r.a.v > T(0)) != (r.f.v > T(0));
    if (a_min > T(0) && (opposite || exact_zero(r.f))) {
        const T h = grow(grow(upper(r.df) / a_min) + grow(std::sqrt(grow(f_max / a_min))));
        if (h >= T(0)) return h;
    }
    return std::numeric_limits<T>::infinity();
}

}  // namespace rayq::detail
