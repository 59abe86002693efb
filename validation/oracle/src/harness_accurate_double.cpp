// rayq::oracle harness — the kernel under rayq::accurate for every double input (the heaviest
// instantiations, one TU per number type).
#include "harness_policy.hpp"

namespace rayq::oracle::harness {
KernelAnswer run_accurate_double(const AnyInput& input) { return run<double>(rayq::accurate, input); }
}  // namespace rayq::oracle::harness
