// rayq::oracle harness — the kernel under rayq::stable for every input type (one TU per policy).
#include "harness_policy.hpp"

namespace rayq::oracle::harness {
KernelAnswer run_stable(const AnyInput& input) { return run(rayq::stable, input); }
}  // namespace rayq::oracle::harness
