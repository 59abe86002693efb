// rayq — secondary rays that do not re-hit the surface they leave.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>

#include "hit.hpp"
#include "ray.hpp"
#include "vec3.hpp"

namespace rayq {

// A ray leaving `hit` along `direction` (reflected, refracted, shadow), its origin pushed off the
// surface along the normal, to the side `direction` goes, by the hit point's certified error
// projected on the normal, then rounded one ulp further away (pbrt-v4 OffsetRayOrigin, §6.8.6):
// the origin is on the intended side of the exact surface, so no hit near t = 0 is spurious.
// Without a finite certificate (a grazing hit the bound could not certify) the offset falls back
// to 64 ulps of the point's largest coordinate.
template <class T>
inline Ray<T> spawn(const Hit<T>& hit, const Vec3<T>& direction)
{
    const Vec3<T>& n = hit.normal;
    const Vec3<T>& e = hit.point_error;
    T distance = std::abs(n.x) * e.x + std::abs(n.y) * e.y + std::abs(n.z) * e.z;
    if (!std::isfinite(distance)) {
        const T largest = std::max({std::abs(hit.point.x), std::abs(hit.point.y), std::abs(hit.point.z), T(1)});
        distance = T(64) * std::numeric_limits<T>::epsilon() * largest;
    }
    distance *= T(1) + T(4) * std::numeric_limits<T>::epsilon();  // the sum above rounds, too
    Vec3<T> offset = distance * n;
    if (dot(direction, n) < T(0)) offset = -offset;
    Vec3<T> o = hit.point + offset;
    const auto away = [](T& coordinate, T push) {
        if (push > T(0)) coordinate = std::nextafter(coordinate, std::numeric_limits<T>::infinity());
        else if (push < T(0)) coordinate = std::nextafter(coordinate, -std::numeric_limits<T>::infinity());
    };
    away(o.x, offset.x);
    away(o.y, offset.y);
    away(o.z, offset.z);
    return {o, direction};
}

}  // namespace rayq
