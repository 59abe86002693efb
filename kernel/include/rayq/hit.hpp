// rayq — the hit record returned by intersect().
#pragma once

#include <limits>

#include "vec3.hpp"

namespace rayq {

// Which piece of a primitive was hit: the surface proper, or the cap at the first/second end of
// an axis (cylinder and cone: cap0 at p0, cap1 at p1).
enum class Part : unsigned char { surface, cap0, cap1 };

template <class T>
struct Hit {
    T t;              // ray parameter of the hit
    Vec3<T> point;    // origin + t·direction, finite (saturated at the largest float)
    Vec3<T> normal;   // unit, facing the incoming ray: dot(normal, direction) <= 0 in T
    bool front_face;  // the ray arrives from outside (the crossing's side; exact under accurate)
    Part part;
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
