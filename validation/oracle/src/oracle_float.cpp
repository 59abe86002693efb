// rayq::oracle — the public overloads for float inputs.
#include <limits>

#include "entry_points.hpp"

namespace rayq::oracle {
RAYQ_ORACLE_ENTRY_POINTS(float, true)
}  // namespace rayq::oracle
