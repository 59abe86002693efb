// rayq::oracle harness — private: rayq::intersect under one policy for every input type.
#pragma once

#include <type_traits>
#include <variant>

#include <rayq/rayq.hpp>
#include <rayq/oracle/harness.hpp>

namespace rayq::oracle::harness {

// Only the inputs whose number type is Only (float or double; void: both) are run; others give
// an empty answer. Lets the heavy accurate policy split into a float TU and a double TU.
template <class Only = void, class PolicyTag>
KernelAnswer run(PolicyTag policy, const AnyInput& input)
{
    return std::visit(
        [&](const auto& in) {
            using T = std::decay_t<decltype(in.ray.tmin)>;
            KernelAnswer a;
            a.is_float = std::is_same_v<T, float>;
            if constexpr (std::is_void_v<Only> || std::is_same_v<Only, T>) {
                const auto hit = rayq::intersect(policy, in.ray, in.prim);
                if constexpr (std::is_same_v<T, float>) a.f = hit;
                else a.d = hit;
            }
            return a;
        },
        input);
}

KernelAnswer run_fast(const AnyInput& input);
KernelAnswer run_stable(const AnyInput& input);
KernelAnswer run_accurate_float(const AnyInput& input);
KernelAnswer run_accurate_double(const AnyInput& input);

}  // namespace rayq::oracle::harness
