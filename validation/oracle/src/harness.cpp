// rayq::oracle harness — dispatch by policy, and the measurement of the kernel's answers.
#include "harness_policy.hpp"

namespace rayq::oracle {

namespace {

KernelAnswer dispatch(Policy p, const AnyInput& input)
{
    switch (p) {
    case Policy::fast: return harness::run_fast(input);
    case Policy::stable: return harness::run_stable(input);
    default: return scalar_of(input) == Scalar::f32 ? harness::run_accurate_float(input) : harness::run_accurate_double(input);
    }
}

}  // namespace

KernelAnswer run_kernel(Policy p, const AnyInput& input)
{
    const auto before = rayq::exact_fallbacks.load(std::memory_order_relaxed);
    KernelAnswer a = dispatch(p, input);
    a.exact_fallback = rayq::exact_fallbacks.load(std::memory_order_relaxed) != before;
    return a;
}

Measurement measure_kernel(const Truth& truth, Policy p, const AnyInput& input)
{
    const KernelAnswer a = run_kernel(p, input);
    Measurement m = a.is_float ? truth.measure(a.f) : truth.measure(a.d);
    m.exact_fallback = a.exact_fallback;
    return m;
}

std::array<Measurement, 3> measure_all_policies(const Truth& truth, const AnyInput& input)
{
    return {measure_kernel(truth, Policy::fast, input), measure_kernel(truth, Policy::stable, input),
            measure_kernel(truth, Policy::accurate, input)};
}

}  // namespace rayq::oracle
