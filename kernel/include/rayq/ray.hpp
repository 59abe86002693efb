// rayq — rays: point(t) = origin + t·direction, hits count for tmin < t < tmax.
#pragma once

#include <limits>

#include "vec3.hpp"

namespace rayq {

template <class T>
struct Ray {
    Vec3<T> origin;
    Vec3<T> direction;  // need not be unit length; t is measured in units of it
    T tmin = T(0);
    T tmax = std::numeric_limits<T>::infinity();
};

template <class U, class T>
constexpr Ray<U> scalar_cast(const Ray<T>& ray)
{
    return {scalar_cast<U>(ray.origin), scalar_cast<U>(ray.direction), U(ray.tmin), U(ray.tmax)};
}

template <class T>
constexpr Vec3<T> point_at(const Ray<T>& ray, T t) { return ray.origin + t * ray.direction; }

// A ray can hit something only when its origin and direction are finite, |direction|² is a
// normal number (zero-length and underflowing directions carry no usable direction), and the
// window (tmin, tmax) is a non-empty interval (NaN bounds fail the comparison).
template <class T>
inline bool usable(const Ray<T>& ray)
{
    // One comparison per test instead of one per component (scenes pay this once per ray):
    // x − x is 0 for finite x and NaN for ±inf or NaN, so the sum is 0 exactly when the origin is
    // finite; |d|² is NaN or +inf when a component of d is (or when it overflows).
    const Vec3<T>& o = ray.origin;
    const T origin_defect = (o.x - o.x) + (o.y - o.y) + (o.z - o.z);
    const T dd = length_squared(ray.direction);
    return origin_defect == T(0) && dd >= std::numeric_limits<T>::min() && dd <= std::numeric_limits<T>::max() &&
           ray.tmin < ray.tmax;
}

}  // namespace rayq
