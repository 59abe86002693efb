// rayq::oracle — private: from exact values to floating point. Approximations come from MPFR at
// 256 bits evaluated without cancellation; every rounding decision is then checked (and, if
// needed, corrected) by exact comparisons with the candidate's neighbours and midpoints.
#pragma once

#include <mpfr.h>

#include "exact.hpp"

namespace rayq::oracle::exact {

constexpr mpfr_prec_t approx_bits = 256;

// An MPFR number with RAII.
struct Mp {
    mpfr_t v;
    explicit Mp(mpfr_prec_t bits = approx_bits) { mpfr_init2(v, bits); }
    ~Mp() { mpfr_clear(v); }
    Mp(const Mp&) = delete;
    Mp& operator=(const Mp&) = delete;
};

// out ≈ a + b·√D with a relative error below 2^-250 (no cancellation: when a and b·√D have
// opposite signs it is evaluated as (a² − b²D)/(a − b·√D)).
void approximate(mpfr_t out, const Alg& x, const Q& D);

// The T nearest to x (ties to even), decided exactly.
template <class T>
T round_nearest(const Alg& x, const Q& D);

// The largest T <= x and the smallest T >= x (equal when x is a T).
template <class T>
void brackets(const Alg& x, const Q& D, T& down, T& up);

// The spacing of T above the T next to x toward zero: the unit of "ulps" in measurements.
template <class T>
Q ulp_at(const Alg& x, const Q& D);

// An exact rational as a T, correctly rounded.
template <class T>
T round_nearest(const Q& q) { return round_nearest<T>(rational(q), Q(0)); }

}  // namespace rayq::oracle::exact
