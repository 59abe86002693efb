// rayq — 3-vectors: an aggregate with the arithmetic every intersector needs.
#pragma once

#include <cmath>

#include "detail/inline.hpp"

namespace rayq {

template <class T>
struct Vec3 {
    T x, y, z;
};

template <class T> RAYQ_INLINE constexpr Vec3<T> operator+(const Vec3<T>& a, const Vec3<T>& b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
template <class T> RAYQ_INLINE constexpr Vec3<T> operator-(const Vec3<T>& a, const Vec3<T>& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
template <class T> RAYQ_INLINE constexpr Vec3<T> operator-(const Vec3<T>& a) { return {-a.x, -a.y, -a.z}; }
template <class T> RAYQ_INLINE constexpr Vec3<T> operator*(const Vec3<T>& a, T s) { return {a.x * s, a.y * s, a.z * s}; }
template <class T> RAYQ_INLINE constexpr Vec3<T> operator*(T s, const Vec3<T>& a) { return {s * a.x, s * a.y, s * a.z}; }
template <class T> RAYQ_INLINE constexpr Vec3<T> operator/(const Vec3<T>& a, T s) { return {a.x / s, a.y / s, a.z / s}; }
template <class T> RAYQ_INLINE constexpr Vec3<T>& operator+=(Vec3<T>& a, const Vec3<T>& b) { a = a + b; return a; }
template <class T> RAYQ_INLINE constexpr Vec3<T>& operator-=(Vec3<T>& a, const Vec3<T>& b) { a = a - b; return a; }
template <class T> RAYQ_INLINE constexpr Vec3<T>& operator*=(Vec3<T>& a, T s) { a = a * s; return a; }
template <class T> RAYQ_INLINE constexpr bool operator==(const Vec3<T>& a, const Vec3<T>& b) { return a.x == b.x && a.y == b.y && a.z == b.z; }
template <class T> RAYQ_INLINE constexpr bool operator!=(const Vec3<T>& a, const Vec3<T>& b) { return !(a == b); }

template <class T> RAYQ_INLINE constexpr T dot(const Vec3<T>& a, const Vec3<T>& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
template <class T> RAYQ_INLINE constexpr Vec3<T> cross(const Vec3<T>& a, const Vec3<T>& b)
{
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
template <class T> RAYQ_INLINE constexpr T length_squared(const Vec3<T>& a) { return dot(a, a); }
template <class T> RAYQ_INLINE T length(const Vec3<T>& a) { return std::sqrt(dot(a, a)); }
template <class T> RAYQ_INLINE Vec3<T> normalize(const Vec3<T>& a) { return a / length(a); }

// The same vector in another scalar type (exact when widening, float → double).
template <class U, class T> RAYQ_INLINE constexpr Vec3<U> scalar_cast(const Vec3<T>& a) { return {U(a.x), U(a.y), U(a.z)}; }

template <class T> RAYQ_INLINE bool isfinite(const Vec3<T>& a)
{
    return std::isfinite(a.x) && std::isfinite(a.y) && std::isfinite(a.z);
}

namespace detail {

// |v|₁: a cheap bound on a vector's size (the batch filters' bound on coordinates, the nearer end).
template <class T> RAYQ_INLINE T norm1(const Vec3<T>& v) { return std::abs(v.x) + std::abs(v.y) + std::abs(v.z); }

}  // namespace detail

}  // namespace rayq
