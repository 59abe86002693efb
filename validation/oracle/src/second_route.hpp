// rayq::oracle — private: what the second-route TUs share (the oracle's answer to compare with).
#pragma once

#include <sstream>
#include <string>

#include "convert.hpp"

namespace rayq::oracle::second_route {

// The oracle's own answer, exactly.
template <class T, class Prim>
exact::Solution oracle_answer(const Ray<T>& ray, const Prim& prim)
{
    return exact::solve(exact::to_problem(ray, prim));
}

inline Agreement agree() { return {true, {}}; }
inline Agreement disagree(const std::string& why) { return {false, why}; }

}  // namespace rayq::oracle::second_route
