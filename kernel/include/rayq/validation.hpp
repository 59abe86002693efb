// rayq — validate(prim): whether a primitive is usable and, if not, why.
#pragma once

#include <cmath>
#include <limits>

#include "vec3.hpp"

namespace rayq {

enum class Defect : unsigned char {
    none,
    non_finite,         // NaN or ±Inf in some field
    nonpositive_radius, // radius <= 0
    zero_vector,        // a normal, axis or edge of zero (or underflowing) length
    degenerate,         // triangle/parallelogram with collinear edges, cone with both radii 0
    out_of_range,       // finite, but squared lengths overflow the number type
};

struct Validation {
    Defect defect = Defect::none;
    const char* reason = "ok";  // a static sentence naming the field and the problem

    constexpr explicit operator bool() const noexcept { return defect == Defect::none; }
};

namespace detail {

// Checks in the order a user would fix them; the first failure is the answer.
class Validator {
public:
    template <class T>
    Validator& finite(T v, const char* reason)
    {
        if (result_ && !std::isfinite(v)) result_ = {Defect::non_finite, reason};
        return *this;
    }
    template <class T>
    Validator& finite(const Vec3<T>& v, const char* reason)
    {
        if (result_ && !isfinite(v)) result_ = {Defect::non_finite, reason};
        return *this;
    }
    template <class T>
    Validator& positive(T v, const char* reason)
    {
        if (result_ && !(v > T(0))) result_ = {Defect::nonpositive_radius, reason};
        return *this;
    }
    // |v|² must be a normal, finite number: zero or underflowing vectors have no direction.
    template <class T>
    Validator& nonzero(const Vec3<T>& v, const char* zero_reason, const char* huge_reason, Defect zero = Defect::zero_vector)
    {
        if (!result_) return *this;
        const T n = rayq::dot(v, v);
        if (!(n <= std::numeric_limits<T>::max())) result_ = {Defect::out_of_range, huge_reason};
        else if (!(n >= std::numeric_limits<T>::min())) result_ = {zero, zero_reason};
        return *this;
    }
    constexpr Validator& require(bool ok, Defect defect, const char* reason)
    {
        if (result_ && !ok) result_ = {defect, reason};
        return *this;
    }
    constexpr Validation result() const { return result_; }

private:
    Validation result_{};
};

}  // namespace detail
}  // namespace rayq
