// rayq::oracle — the public overloads for double inputs.
#include <limits>

#include "entry_points.hpp"

namespace rayq::oracle {
RAYQ_ORACLE_ENTRY_POINTS(double, false)
}  // namespace rayq::oracle
