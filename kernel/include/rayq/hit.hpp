// rayq — the hit record returned by intersect().
#pragma once

#include <limits>

#include "vec3.hpp"

namespace rayq {

// Which piece of a primitive was hit: the surface proper, or the cap at the first/second end of
// an axis (cylinder and cone: cap0 at p0, cap1 at p1).
enum class Part : unsigned char { surface, cap0, cap1 };

// Which optional fields of a hit record a query computes (t, part and front_face always): ask
// for less when you need less, as pbrt-v4 and Mitsuba 3 split the cheap intersection from the
// surface record. Visibility needs t alone, shading point and normal, spawn() everything.
// A field not asked for keeps its default: point and normal {0, 0, 0}, t_error and point_error
// +∞ ("not certified", which is always safe to read).
enum class HitFields : unsigned char {
    t = 0,       // t, part, front_face only
    point = 1,   // point
    normal = 2,  // normal
    bounds = 4,  // t_error and point_error
    all = 7,
};
constexpr HitFields operator|(HitFields a, HitFields b)
{
    return static_cast<HitFields>(static_cast<unsigned char>(a) | static_cast<unsigned char>(b));
}
// Whether `set` includes every field of `f`.
constexpr bool wants(HitFields set, HitFields f)
{
    return (static_cast<unsigned char>(set) & static_cast<unsigned char>(f)) == static_cast<unsigned char>(f);
}

template <class T>
struct Hit {
    T t;                     // ray parameter of the hit
    Vec3<T> point{0, 0, 0};  // origin + t·direction, finite (saturated at the largest float)
    Vec3<T> normal{0, 0, 0}; // unit, facing the incoming ray: dot(normal, direction) <= 0 in T
    bool front_face = false;  // the ray arrives from outside (the crossing's side; exact under accurate)
    Part part = Part::surface;
    // Certified: the exact first hit of the (exactly represented) inputs lies in
    // [t − t_error, t + t_error]; infinite when that cannot be proven (near a rim, an edge, the
    // window's start, tangency).
    T t_error = std::numeric_limits<T>::infinity();
    // Certified, per component: |point − exact point|, the exact point being where the line meets
    // the exact surface of `part` near t (so spawn() can leave that surface even when t_error,
    // which also certifies that this crossing is the first hit, is infinite).
    Vec3<T> point_error = {std::numeric_limits<T>::infinity(), std::numeric_limits<T>::infinity(),
                           std::numeric_limits<T>::infinity()};
};

}  // namespace rayq
