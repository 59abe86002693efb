// rayq::oracle harness — the kernel under rayq::fast for every input type (one TU per policy).
#include "harness_policy.hpp"

namespace rayq::oracle::harness {
KernelAnswer run_fast(const AnyInput& input) { return run(rayq::fast, input); }
}  // namespace rayq::oracle::harness
