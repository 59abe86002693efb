// rayq::oracle — the KERNEL side of a measurement, for tests and tools: runs rayq::intersect
// under a policy on any fixture input and hands the answer to the oracle. A separate library
// (rayq::oracle_harness): the oracle itself (rayq::oracle) never calls the kernel. Non-template;
// the 3 policies × 32 input types are instantiated once, in one TU per policy.
#pragma once

#include <array>
#include <optional>

#include <rayq/oracle/fixtures.hpp>

namespace rayq::oracle {

enum class Policy { fast, stable, accurate };
inline constexpr std::array<Policy, 3> all_policies = {Policy::fast, Policy::stable, Policy::accurate};
inline const char* policy_name(Policy p) { return p == Policy::fast ? "fast" : p == Policy::stable ? "stable" : "accurate"; }

// rayq::intersect(policy, ray, prim) for the input's number type (the other one stays empty).
struct KernelAnswer {
    bool is_float = false;
    std::optional<Hit<float>> f;
    std::optional<Hit<double>> d;
    bool exact_fallback = false;  // the call needed the accurate policy's exact arithmetic (rayq::exact_fallbacks moved)

    bool hit() const { return is_float ? f.has_value() : d.has_value(); }
};
KernelAnswer run_kernel(Policy p, const AnyInput& input);

// The kernel's answer measured against a Truth of the same input.
Measurement measure_kernel(const Truth& truth, Policy p, const AnyInput& input);
std::array<Measurement, 3> measure_all_policies(const Truth& truth, const AnyInput& input);

}  // namespace rayq::oracle
