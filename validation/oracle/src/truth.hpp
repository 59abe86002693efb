// rayq::oracle — private: what a Truth holds, shared by the float and double TUs.
#pragma once

#include <rayq/oracle/oracle.hpp>

#include "exact.hpp"

namespace rayq::oracle {

struct Truth::Impl {
    bool is_float = false;
    exact::Solution solution;
    ExactHit hit;
    long double facing[3] = {0, 0, 0};  // the exact facing unit normal, to 64 bits
    bool facing_ambiguous = false;      // exactly d·n = 0: either orientation faces the ray
};

std::unique_ptr<Truth::Impl> make_truth(const exact::Problem& problem, bool is_float);

}  // namespace rayq::oracle
