// check() for the quadric family's primitives (see rayq/fuzz/checks.hpp).
#include <rayq/fuzz/checks.hpp>

namespace rayq::fuzz {
RAYQ_FUZZ_QUADRIC_PRIMITIVES(RAYQ_FUZZ_CHECK_INSTANTIATE, float)
RAYQ_FUZZ_QUADRIC_PRIMITIVES(RAYQ_FUZZ_CHECK_INSTANTIATE, double)
}  // namespace rayq::fuzz
