// rayq — the few arithmetic operations whose accuracy a precision policy decides.
// Every primitive computes through these, so a policy is a choice made in one place.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>

#include "../policy.hpp"
#include "../vec3.hpp"
#include "eft.hpp"

namespace rayq::detail {

template <class Policy>
inline constexpr bool compensated_v = std::is_same_v<Policy, accurate_policy>;

template <class Policy, class T>
inline T dot(Policy, const Vec3<T>& a, const Vec3<T>& b)
{
    if constexpr (compensated_v<Policy>) return dot_compensated(a, b);
    else return rayq::dot(a, b);
}

template <class Policy, class T>
inline Vec3<T> cross(Policy, const Vec3<T>& a, const Vec3<T>& b)
{
    if constexpr (compensated_v<Policy>) return cross_compensated(a, b);
    else return rayq::cross(a, b);
}

// a·b + c, fused where the hardware fuses (one rounding instead of two), plain elsewhere.
template <class T>
inline T mul_add(T a, T b, T c)
{
#if defined(__FMA__) || defined(__FMA4__) || defined(__aarch64__) || defined(__ARM_FEATURE_FMA)
    return std::fma(a, b, c);
#else
    return a * b + c;
#endif
}

template <class Policy, class T>
inline Vec3<T> point_at(Policy, const Vec3<T>& origin, const Vec3<T>& direction, T t)
{
    if constexpr (compensated_v<Policy>)
        return {mul_add(t, direction.x, origin.x), mul_add(t, direction.y, origin.y), mul_add(t, direction.z, origin.z)};
    else return origin + t * direction;
}

// Whether unit() below takes its direct path for a vector of squared length dd: finite and far
// above the subnormals.
template <class T>
RAYQ_INLINE bool unscaled_unit(T dd)
{
    constexpr T smallest_unscaled = std::numeric_limits<T>::min() / (std::numeric_limits<T>::epsilon() * std::numeric_limits<T>::epsilon());
    return dd >= smallest_unscaled && dd <= std::numeric_limits<T>::max();
}

// unit()'s direct path alone (see unit() below): n = v·(1/|v|) and true where it applies, false (n
// untouched) elsewhere. Where it applies n is never zero: its largest component is about 1/√3 or more.
template <class T>
RAYQ_INLINE bool direct_unit(const Vec3<T>& v, Vec3<T>& n)
{
    const T dd = rayq::dot(v, v);
    if (!unscaled_unit(dd)) return false;
    n = v * (T(1) / std::sqrt(dd));
    return true;
}

// unit()'s other path: v scaled by its largest component first; zero for a zero or non-finite v.
template <class T>
inline Vec3<T> scaled_unit(const Vec3<T>& v)
{
    // Every component checked: std::max skips a NaN that is not first (NaN < x is false).
    if (!(std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z))) return {T(0), T(0), T(0)};
    const T m = std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)});
    if (!(m > T(0))) return {T(0), T(0), T(0)};
    const Vec3<T> s = v / m;
    return s / std::sqrt(rayq::dot(s, s));
}

// Unit vector along v. Returns {0,0,0} for a zero or non-finite v.
// Where |v|² is finite and far above the subnormals (squares too small to count may underflow:
// they lose less than an ulp of |v|²), v times 1/|v|: one division instead of six, and each
// component rounded once after the common factor, which does not turn the vector (float sphere hits
// with the full record, SSE2, fast / accurate: 989 -> 957 / 847 -> 819 instructions, callgrind;
// 79 -> 69 / 97 -> 91 ns, min of 31 runs). Otherwise v is first scaled by its largest component,
// so that neither tiny nor huge vectors under- or overflow in the squared length.
// Forced inline, as the cylinder's outward_normal() is: GCC called both out of line from a scene's
// hit record, 16% of a 16-capped-cylinder scene's samples (rayq-bench-embree, native, `fast` with
// point and normal over Embree, three alternating runs: 16 capped cylinders 4.77, 4.84, 4.80 ->
// 4.86, 4.87, 4.99; 16 spheres 5.17, 5.08, 5.06 -> 5.28, 5.31, 6.03).
// Two entry points for callers that treat the rare path apart (write_hit): direct_unit, scaled_unit.
template <class T>
RAYQ_INLINE Vec3<T> unit(const Vec3<T>& v)
{
    Vec3<T> n;
    if (direct_unit(v, n)) return n;
    return scaled_unit(v);
}

}  // namespace rayq::detail
