// rayq::oracle — correct rounding of elements of Q(√D) to float and double.
#include "numeric.hpp"

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>

namespace rayq::oracle::exact {

void approximate(mpfr_t out, const Alg& x, const Q& D)
{
    const int sa = sgn(x.a);
    const int sb = sgn(D) == 0 ? 0 : sgn(x.b);
    if (sb == 0) {
        mpfr_set_q(out, x.a.get_mpq_t(), MPFR_RNDN);
        return;
    }
    Mp root;
    mpfr_set_q(root.v, D.get_mpq_t(), MPFR_RNDN);
    mpfr_sqrt(root.v, root.v, MPFR_RNDN);
    if (sa == 0 || sa == sb) {  // a + b√D, both terms of one sign
        mpfr_mul_q(root.v, root.v, x.b.get_mpq_t(), MPFR_RNDN);
        Mp a;
        mpfr_set_q(a.v, x.a.get_mpq_t(), MPFR_RNDN);
        mpfr_add(out, a.v, root.v, MPFR_RNDN);
        return;
    }
    // (a² − b²D) / (a − b√D): the denominator adds two terms of the sign of a.
    const Q nb = -x.b;
    mpfr_mul_q(root.v, root.v, nb.get_mpq_t(), MPFR_RNDN);
    Mp den;
    mpfr_set_q(den.v, x.a.get_mpq_t(), MPFR_RNDN);
    mpfr_add(den.v, den.v, root.v, MPFR_RNDN);
    const Q num = x.a * x.a - x.b * x.b * D;
    mpfr_set_q(out, num.get_mpq_t(), MPFR_RNDN);
    mpfr_div(out, out, den.v, MPFR_RNDN);
}

namespace {

template <class T>
T from_mpfr(const mpfr_t v);
template <>
float from_mpfr<float>(const mpfr_t v) { return mpfr_get_flt(v, MPFR_RNDN); }
template <>
double from_mpfr<double>(const mpfr_t v) { return mpfr_get_d(v, MPFR_RNDN); }

template <class T>
bool even(T x)
{
    if constexpr (sizeof(T) == 4) {
        std::uint32_t b;
        std::memcpy(&b, &x, 4);
        return (b & 1u) == 0;
    } else {
        std::uint64_t b;
        std::memcpy(&b, &x, 8);
        return (b & 1u) == 0;
    }
}

template <class T>
Q exact_of(T x) { return Q(static_cast<double>(x)); }

// The neighbours of a finite T as rationals; beyond ±max, the value the exponent range would
// give next (so that midpoints above max are defined).
template <class T>
Q succ(T x)
{
    const T n = std::nextafter(x, std::numeric_limits<T>::infinity());
    if (std::isinf(n)) return exact_of(x) + (exact_of(x) - exact_of(std::nextafter(x, T(0))));
    return exact_of(n);
}
template <class T>
Q pred(T x) { return -succ<T>(-x); }

}  // namespace

template <class T>
T round_nearest(const Alg& x, const Q& D)
{
    constexpr T inf = std::numeric_limits<T>::infinity();
    Mp v;
    approximate(v.v, x, D);
    T c = from_mpfr<T>(v.v);
    for (int guard = 0; guard < 64 && std::isfinite(c); ++guard) {
        const Q cq = exact_of(c);
        const Q lo_mid = (cq + pred(c)) / 2, hi_mid = (cq + succ(c)) / 2;
        const int sl = compare(x, lo_mid, D);
        if (sl < 0) {
            c = std::nextafter(c, -inf);
            continue;
        }
        const int sh = compare(x, hi_mid, D);
        if (sh > 0) {
            c = std::nextafter(c, inf);
            continue;
        }
        if (sl == 0 && !even(c)) c = std::nextafter(c, -inf);
        else if (sh == 0 && !even(c)) c = std::nextafter(c, inf);
        return c;
    }
    return c;  // overflow: ±inf
}

template <class T>
void brackets(const Alg& x, const Q& D, T& down, T& up)
{
    constexpr T inf = std::numeric_limits<T>::infinity();
    const T c = round_nearest<T>(x, D);
    if (!std::isfinite(c)) {  // beyond the largest T: between it and the infinity of its sign
        const T max = std::numeric_limits<T>::max();
        if (c > 0) down = max, up = c;
        else down = c, up = -max;
        return;
    }
    const int s = compare(x, exact_of(c), D);
    if (s == 0) down = up = c;
    else if (s > 0) down = c, up = std::nextafter(c, inf);
    else up = c, down = std::nextafter(c, -inf);
}

template <class T>
Q ulp_at(const Alg& x, const Q& D)
{
    T down, up;
    brackets<T>(x, D, down, up);
    const T toward_zero = std::fabs(sign(x, D) >= 0 ? down : up);  // finite: brackets beyond the range end at ±max
    return succ(toward_zero) - exact_of(toward_zero);
}

template float round_nearest<float>(const Alg&, const Q&);
template double round_nearest<double>(const Alg&, const Q&);
template void brackets<float>(const Alg&, const Q&, float&, float&);
template void brackets<double>(const Alg&, const Q&, double&, double&);
template Q ulp_at<float>(const Alg&, const Q&);
template Q ulp_at<double>(const Alg&, const Q&);

}  // namespace rayq::oracle::exact
