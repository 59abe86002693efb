// rayq::oracle harness — the kernel under rayq::accurate for every float input (the heaviest
// instantiations, one TU per number type).
#include "harness_policy.hpp"

namespace rayq::oracle::harness {
KernelAnswer run_accurate_float(const AnyInput& input) { return run<float>(rayq::accurate, input); }
}  // namespace rayq::oracle::harness
