// rayq — precision policies, passed first like the standard's execution policies:
//   intersect(rayq::fast, ray, prim), intersect(rayq::stable, ...), intersect(rayq::accurate, ...).
#pragma once

#include <type_traits>

namespace rayq {

// Textbook formulas: b² − 4ac discriminant and (−b ± √Δ)/2a roots.
struct fast_policy {};
// Hearn–Baker discriminant (r² − |f − (f·d̂)d̂|²) and the cancellation-free q = −(b + sign(b)√Δ) roots.
struct stable_policy {};
// Exact: hit/miss, part and window decided on the exact value of the float inputs (filtered
// signs falling back to expansion arithmetic) and t correctly rounded, for sphere, plane, disk,
// parallelogram, triangle, cylinder and cone. Quadrics and transformed instances: error-free
// products (difference-of-products discriminant, compensated dot and cross) and stable roots.
struct accurate_policy {};

inline constexpr fast_policy fast{};
inline constexpr stable_policy stable{};
inline constexpr accurate_policy accurate{};

// The policy used by the overloads that take none, chosen by measurement (README, "Policies"):
// `stable` costs the same as `fast` within noise and removes its cancellation; `accurate`
// currently costs 2–5× `fast` in float, 3–8× in double on random rays (README, "Policies").
using default_policy = stable_policy;

// Whether `accurate` decides hit/miss and part exactly for a primitive type: true for the seven
// primitives of its contract; quadric.hpp and transformed.hpp specialize it to false.
template <class Prim>
struct accurate_decides_exactly : std::true_type {};

template <class P>
inline constexpr bool is_policy_v = std::is_same_v<P, fast_policy> || std::is_same_v<P, stable_policy> ||
                                    std::is_same_v<P, accurate_policy>;

}  // namespace rayq
