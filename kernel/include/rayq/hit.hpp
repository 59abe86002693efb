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
    Vec3<T> point;    // origin + t·direction
    Vec3<T> normal;   // unit, facing the incoming ray: dot(normal, direction) <= 0
    bool front_face;  // the ray arrives from outside (the side the outward normal points to)
    Part part;
    // Certified: the exact intersection parameter of the (exactly represented) inputs lies in
    // [t − t_error, t + t_error].
    T t_error = std::numeric_limits<T>::infinity();
    // Certified, per component: |point − exact point| (the exact point at the exact t).
    Vec3<T> point_error = {std::numeric_limits<T>::infinity(), std::numeric_limits<T>::infinity(),
                           std::numeric_limits<T>::infinity()};
};

}  // namespace rayq
