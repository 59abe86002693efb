// rayq — exact decisions for the accurate policy: signs of polynomials in the inputs, filtered
// first (a certified-error estimate, as in Shewchuk's adaptive predicates) and decided by
// expansion arithmetic only when the filter cannot; roots of a primitive's quadratic located
// against floats and rationals exactly, and rounded correctly.
#pragma once

#include <atomic>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <algorithm>
#include <array>
#include <limits>
#include <optional>
#include <type_traits>
#include <utility>

#include "bounded.hpp"
#include "double_word.hpp"
#include "dyadic.hpp"
#include "expansion.hpp"
#include "ulp.hpp"

namespace rayq {

// Decisions the accurate policy's filters could not make and handed to exact arithmetic
// (process-wide; relaxed increments, read it between runs).
inline std::atomic<unsigned long long> exact_fallbacks{0};

namespace detail {

// The components of the exact fallback's expansions. An expansion is exact only while no product
// under- or overflows; float inputs are exact in double, whose exponent range keeps products of
// up to eight float factors in range (float's own did not: a cone near 2^-30 underflowed and a
// root was rounded 2 ulps off; kernel test AccurateRegression.TinyFloatConeMissIsExact).
template <class T> struct ExactComponent { using type = T; };
template <> struct ExactComponent<float> { using type = double; };

// The accurate policy's first filter precision: T's own, except for float, whose first filter is
// hardware double (wide_t<float>): in scalar code it costs what float does, and its bounds are
// 2^29 times tighter, tight enough to round most roots correctly without a Newton step
// (ExactQuadratic::interval_round). (A primitive's common case first takes the cheaper static
// filter of magnitude.hpp: exact_crossings.hpp, quick_curved_crossings and quick_flat_crossing.)
template <class T> struct First { using type = Bounded<T>; };
template <> struct First<float> { using type = Bounded<double>; };
template <class T>
using first_t = typename First<T>::type;

// The sign of expr(N) for the exact inputs: expr is generic over the number type and is called
// with a zero of first_t<T> (working precision), then wide_t<T> (about twice the precision),
// and only if neither can decide, of Expansion (exact within the component's range), and if a
// product left that range on the way, of Dyadic (exact, unbounded exponent).
template <class T, class Expr>
inline int adaptive_sign(const Expr& expr)
{
    const auto b = expr(first_t<T>{T(0)});
    if (b.v == 0 && b.e == 0) return 0;  // exactly zero (e.g. a plane's leading coefficient)
    if (b.v > b.e) return 1;
    if (-b.v > b.e) return -1;
    if constexpr (!std::is_same_v<first_t<T>, wide_t<T>>)
        if (const int s = certain_sign(expr(wide_t<T>{T(0)}))) return s;
    exact_fallbacks.fetch_add(1, std::memory_order_relaxed);
    const auto x = expr(Expansion<typename ExactComponent<T>::type>{});
    if (x.exact()) return x.sign();
    const auto y = expr(Dyadic{});
    return y.finite() ? y.sign() : x.sign();  // an infinite input (a window end) means what it did
}

// A point on the ray's parameter line is given exactly as the root t = −g/dg of a linear
// function g + dg·t (dg ≠ 0), by a callable N -> Residual<N> with f = g, df = dg (a unused).
// A float x is {−x, 1}; the midpoint of floats x, y is {−x − y, 2}; a cap plane is its residual.
template <class T>
struct FloatLine {
    T g, dg;
    template <class N>
    Residual<N> operator()(N) const { return {N{g}, N{dg}, N{T(0)}}; }
};

// The midpoint of two floats, t = (a + b)/2 exactly: g = −a − b (summed in N), dg = 2.
template <class T>
struct MidpointLine {
    T a, b;
    template <class N>
    Residual<N> operator()(N) const { return {N{-a} + N{-b}, N{T(2)}, N{T(0)}}; }
};

// sign(F(x)) for a quadratic F given by coefficients at t = 0, at x = −g/dg: sign(c·dg² − b·g·dg + a·g²).
template <class T, class Coef, class Line>
inline int quadratic_sign_at(const Coef& coef, const Line& x)
{
    return adaptive_sign<T>([&](auto zero) {
        const auto& r = coef(zero);
        const auto l = x(zero);
        return r.f * l.df * l.df - r.df * l.f * l.df + r.a * l.f * l.f;
    });
}

// x/y for y certainly nonzero: |X/Y − x/y| <= (e_x + |x/y|·e_y)/(|y| − e_y), plus the rounding.
template <class B>
RAYQ_INLINE B quotient(const B& x, const B& y)
{
    using W = decltype(x.v / y.v);
    const W v = x.v / y.v, y_min = lower(y);
    if (!(y_min > W(0))) return {v, std::numeric_limits<W>::infinity()};
    return {v, grow(grow(x.e + grow(std::abs(v) * y.e)) / y_min + unit_roundoff<W> * std::abs(v))};
}

// q = −(b + sign(b)·√d)/2 for the discriminant d = b² − 4ac > 0 (certain), with its running error
// bound (pbrt-v4 "Managing Rounding Error"): the cancellation-free form whose roots are q/a and
// c/q (Ray Tracing Gems ch. 7). The sign is that of b's computed value; the roots are q/a and c/q
// whichever sign b has exactly.
template <class W>
RAYQ_INLINE Bounded<W> cancellation_free_q(const Bounded<W>& b, const Bounded<W>& disc)
{
    using B = Bounded<W>;
    const W s = std::sqrt(disc.v);
    // |√D − √d| = |D − d|/(√D + √d) <= e/√d; s itself is one rounding from √d.
    const B sq{s, grow(grow(disc.e / s) + unit_roundoff<W> * s)};
    return B{W(-0.5)} * (b.v >= W(0) ? b + sq : b - sq);
}
// Whether a and d are certainly nonzero and positive: the roots are then real and distinct.
template <class W>
RAYQ_INLINE bool two_certain_roots(const Bounded<W>& a, const Bounded<W>& disc)
{
    return std::abs(a.v) > a.e && disc.v > W(0) && lower(disc) > W(0);
}

// Both roots of a·t² + b·t + c from bounded coefficients and discriminant d = b² − 4ac, each with
// a certified interval, ascending; none unless a ≠ 0 and d > 0 are certain and the intervals are
// disjoint (they must say which root is which).
template <class W>
RAYQ_INLINE std::optional<std::array<Bounded<W>, 2>> root_intervals(const Bounded<W>& a, const Bounded<W>& b, const Bounded<W>& c,
                                                               const Bounded<W>& disc)
{
    using B = Bounded<W>;
    const W margin = W(1) - W(2) * unit_roundoff<W>;  // a difference of two W, rounded once
    if (!two_certain_roots(a, disc)) return std::nullopt;
    const B q = cancellation_free_q(b, disc);
    if (!(std::abs(q.v) > q.e)) return std::nullopt;
    B r0 = quotient(q, a), r1 = quotient(c, q);
    if (r1.v < r0.v) std::swap(r0, r1);
    if (!((r1.v - r0.v) * margin > grow(r0.e + r1.e))) return std::nullopt;
    return std::array<B, 2>{r0, r1};
}

// One root (which: 0 smaller, 1 larger) with its certified interval, from q (cancellation_free_q),
// for a caller that needs only one: one quotient instead of two. q/a = −(b + s·√d)/(2a) is the
// smaller root exactly when s, the sign q took from b's computed value, is a's sign (the roots
// differ: d > 0 is certain). Requires two_certain_roots; none where c/q is asked for and q is not
// certainly nonzero.
template <class W>
RAYQ_INLINE std::optional<Bounded<W>> root_interval(const Bounded<W>& a, const Bounded<W>& b, const Bounded<W>& c, const Bounded<W>& q,
                                                    int which)
{
    if ((b.v >= W(0)) == (a.v > W(0)) ? which == 0 : which == 1) return quotient(q, a);
    if (!(std::abs(q.v) > q.e)) return std::nullopt;
    return quotient(c, q);
}

// The midpoints between t and its two neighbours in T, exact in W (W has at least one more bit).
template <class W, class T>
RAYQ_INLINE std::pair<W, W> midpoints_around(T t)
{
    if constexpr (std::is_same_v<T, float> && std::is_same_v<W, double>) {
        // Half the spacing from t's exponent bits (the hot case, inline and without branches on
        // the neighbours): 2^(E − 24) away from zero, and half that toward zero when |t| is a
        // power of two above FLT_MIN. Subnormal t (exponent bits 0) takes the general form below.
        const std::uint32_t bits = bits_of(t);
        const std::uint32_t exponent = bits & 0x7f800000u;
        if (exponent != 0) {
            const float power = from_bits<float>(exponent);  // 2^E, |t| in [2^E, 2^(E+1))
            const double away = double(power) * 0x1p-24;
            const double toward = (bits & 0x007fffffu) == 0 && exponent > 0x00800000u ? away * 0.5 : away;  // FLT_MIN's lower neighbour is as close as its upper
            const bool positive = t > 0.0f;
            return {double(t) - (positive ? toward : away), double(t) + (positive ? away : toward)};
        }
    }
    return {(W(next_down(t)) + W(t)) / W(2), (W(t) + W(next_up(t))) / W(2)};
}

// The T nearest to a root known to lie in [v − e, v + e] (W at least as precise as T), when that
// interval lies strictly between the midpoints around it: then it is the correctly rounded root.
// For float roots computed in double the interval is ~2^-50 of the root against float's 2^-24
// spacing, so this decides nearly every root.
template <class T, class W>
RAYQ_INLINE std::optional<T> rounded_between_midpoints(const Bounded<W>& root)
{
    const W margin = W(1) - W(2) * unit_roundoff<W>;
    const T t = static_cast<T>(root.v);
    if (!std::isfinite(t) || t == T(0) || !std::isfinite(root.e)) return std::nullopt;
    const auto [below, above] = midpoints_around<W>(t);
    if ((root.v - below) * margin > root.e && (above - root.v) * margin > root.e) return t;
    return std::nullopt;
}

// A double with an exponent of its own, m·2^e, for estimates at magnitudes beyond double's range:
// products and quotients act on m and e apart, so nothing under- or overflows before the result
// is rounded to T once (std::ldexp, correctly rounded into T's subnormals).
struct ScaledDouble {
    double m = 0;  // |m| in [1/4, 4) after a few operations, or 0
    long e = 0;
    ScaledDouble() = default;
    ScaledDouble(double m_, long e_) : m(m_), e(e_) {}
    explicit ScaledDouble(const Dyadic& x)  // truncated to 53 bits
    {
        const auto [mantissa, exponent] = x.frexp();
        m = mantissa;
        e = exponent;
    }
    friend ScaledDouble operator-(ScaledDouble x) { return {-x.m, x.e}; }
    friend ScaledDouble operator/(const ScaledDouble& x, const ScaledDouble& y) { return {x.m / y.m, x.e - y.e}; }
    ScaledDouble sqrt() const  // of a non-negative value
    {
        const bool odd = (e % 2) != 0;
        return {std::sqrt(odd ? 2 * m : m), (odd ? e - 1 : e) / 2};
    }
    static ScaledDouble sum_of_magnitudes(const ScaledDouble& x, const ScaledDouble& y)
    {
        if (x.m == 0 || y.m == 0) return {std::abs(x.m) + std::abs(y.m), x.m == 0 ? y.e : x.e};
        const long top = std::max(x.e, y.e);
        const auto aligned = [top](const ScaledDouble& z) { return std::ldexp(std::abs(z.m), int(std::max(z.e - top, -2000L))); };
        return {aligned(x) + aligned(y), top};
    }
    template <class T>
    T to() const
    {
        if (m == 0) return T(0);
        constexpr long beyond = 4 * std::numeric_limits<double>::max_exponent;  // past every T's range
        const double x = std::ldexp(m, int(std::clamp(e, -beyond, beyond)));
        constexpr double largest = std::numeric_limits<T>::max();  // a search starts from a finite float
        return static_cast<T>(std::clamp(x, -largest, largest));
    }
};

// Root `which` of a quadratic (sign_a: a's sign, 0 when linear), rounded to nearest from a guess t
// by one Newton step t + δ, δ = −F(t)/F'(t), given F(t), F'(t) and a with certified bounds; none
// when the step cannot certify it.
// With x = 4·|a|·|F|/F'² <= 1/2 the nearest root lies within |δ|·x/2 of t + δ (the quadratic's
// root 2F/(F' ± √(F'² − 4aF)) against its linearization), plus the bounds' effect on δ. If no
// rounding boundary of T lies within that, fl(t + δ) is correctly rounded.
// F must be far more precise than T (about u², a double word); F' and a need not be: they scale the
// step and bound its curvature, and a relative error ~u in them moves δ by ~u·|δ|, far below the
// half ulp the step resolves.
template <class T>
inline std::optional<T> newton_step(const Estimate<T>& f, const Estimate<T>& df, const Estimate<T>& a, int sign_a, int which, T t)
{
    const T u = unit_roundoff<T>;
    const T fv = f.v, dv = df.v, f_err = f.e, d_err = df.e;
    const T d_min = lower(dv, d_err);
    if (!(d_min > T(0))) return std::nullopt;
    // The nearest root is the requested one: F' has the sign of an entry (−sign a) at the smaller root.
    if (sign_a != 0 && (dv > T(0) ? 1 : -1) * sign_a != (which == 0 ? -1 : 1)) return std::nullopt;
    const T f_max = upper(fv, f_err), a_max = upper(a.v, a.e);
    // One reciprocal of F''s lower bound, rounded up (grow), scales every bound: the chain to the
    // rounding test then waits on one division, not two in turn (pt.cpp, SSE2, min of 31 runs,
    // accurate double hits with their records: capped cylinder 222 -> 216 ns, sphere 119 -> 117).
    // A d_min so small that 1/d_min overflows gives an infinite or NaN bound: the step declines.
    // F's quotient before the product with a: grow() covers one underflow's absolute error, which
    // a later scaling by 1/F' would magnify (a float sphere near 2^-60 was rounded 1 ulp off).
    // A linear residual (a exactly 0: flat parts) has x = 0, without a subnormal product of floors.
    // The bounds are products of upper bounds, each grown: any grouping is sound. 4|a|/D is formed
    // beside F/D, not after it, so that x waits on F (the last input to arrive: the double word)
    // for one product less; an underflow there only raises the bound to grow()'s floor.
    const T inv = grow(T(1) / d_min);
    const T delta_max = grow(f_max * inv);
    const T x = a_max == T(0) ? T(0) : grow(grow(T(4) * a_max * inv) * delta_max);
    if (!(x <= T(0.5))) return std::nullopt;
    // δ = −F·(1/F'), the reciprocal taken while F is still being evaluated, so that t + δ (which
    // the hit record waits for) is one product after F, not one division: two roundings, within
    // 3u·|δ| of −fv/dv while 1/F' is normal (|F'| < 1/min, checked; a subnormal one errs more).
    // (rayq-bench, SSE2, accurate ÷ fast, double sphere, medians of 5, two alternating runs:
    // 1.30, 1.31 -> 1.27, 1.26, with smaller_half_gap below and quick_residual_f's tree sum.)
    if (!(std::abs(dv) < T(1) / std::numeric_limits<T>::min())) return std::nullopt;
    const T delta = -fv * (T(1) / dv);
    // |δ − fv/dv| over the bounds of F and F': f_err/D + |fv/dv|·d_err/D.
    const T spread = grow(grow(delta_max * x / T(2)) + grow(grow(f_err * inv) + grow(std::abs(delta) * grow(d_err * inv))) +
                          T(3) * u * std::abs(delta));
    const T rounded = t + delta;
    if (!std::isfinite(rounded)) return std::nullopt;
    // Offset of t + δ from `rounded`, exactly up to one rounding: (t − rounded) is a two-sum.
    const Pair<T> gap = two_sum(t, -rounded);
    const T offset = gap.hi + (gap.lo + delta);
    const T slack = grow(spread + T(2) * u * (std::abs(gap.lo) + std::abs(delta) + std::abs(offset)));
    // Within half the smaller gap on either side: rounded is then the nearest float to the root.
    const T half_gap = smaller_half_gap(rounded);
    if (offset + slack < half_gap && offset - slack > -half_gap) return rounded;
    return std::nullopt;
}

// newton_step on the residual along the ray `coef.at`, F, F' and a evaluated in wide_t at t.
template <class T, class Coef>
inline std::optional<T> newton_rounded(const Coef& coef, int sign_a, int which, T t)
{
    if (!std::isfinite(t)) return std::nullopt;
    const Residual<wide_t<T>> r = coef.at(wide_t<T>{t});
    return newton_step(estimate(r.f), estimate(r.df), estimate(r.a), sign_a, which, t);
}

// The quadratic a·t² + b·t + c along the ray, whose coefficients `coef` computes in any number
// type (a primitive's residual at t = 0). Signs of a and of the discriminant are decided once.
template <class T, class Coef>
class ExactQuadratic {
public:
    explicit ExactQuadratic(const Coef& coef) : coef_(coef), first0_(coef(first_t<T>{T(0)}))
    {
        sign_a_ = adaptive_sign<T>([&](auto zero) { return at_zero(zero).a; });
        if (sign_a_ != 0) {
            // The first filter's discriminant is kept: interval_round's roots start from it.
            const auto discriminant = [&](auto zero) {
                const auto& r = at_zero(zero);
                return r.df * r.df - decltype(zero){T(4)} * r.a * r.f;
            };
            disc0_ = discriminant(first_t<T>{T(0)});
            sign_disc_ = certain_sign(disc0_);
            if (sign_disc_ == 0) sign_disc_ = adaptive_sign<T>(discriminant);
            sign_b_ = 0;
        } else {
            sign_b_ = adaptive_sign<T>([&](auto zero) { return at_zero(zero).df; });
            sign_c_ = sign_b_ == 0 ? adaptive_sign<T>([&](auto zero) { return at_zero(zero).f; }) : 0;
        }
    }

    int sign_a() const { return sign_a_; }
    int sign_disc() const { return sign_disc_; }  // quadratic case
    int sign_b() const { return sign_b_; }        // linear case
    int sign_c() const { return sign_c_; }        // constant case

    // sign of the quadratic at x = −g/dg.
    template <class Line>
    int sign_at(const Line& x) const
    {
        return quadratic_sign_at<T>([&](auto zero) -> const auto& { return at_zero(zero); }, x);
    }

    // sign(x − r) for r the smaller (which = 0) or larger (which = 1) real root, x = −g/dg.
    // Requires real roots (sign_disc >= 0) or, when a = 0, b ≠ 0 (then which is ignored).
    template <class Line>
    int compare(int which, const Line& x) const
    {
        if (sign_a_ == 0) {  // root −c/b: sign(−g/dg + c/b) = sign(c·dg − g·b)·sign(b)·sign(dg)
            const int s = adaptive_sign<T>([&](auto zero) {
                const auto& r = at_zero(zero);
                const auto l = x(zero);
                return r.f * l.df - l.f * r.df;
            });
            return s * sign_b_ * line_direction(x);
        }
        // sign(a)·R(x)·dg² = sign(a)·(c·dg² − b·g·dg + a·g²): < 0 strictly between the roots.
        const int inside = sign_a_ * sign_at(x);
        if (inside < 0) return which == 0 ? 1 : -1;
        // Side of the vertex −b/2a: sign(x − vertex) = sign(b·dg − 2a·g)·sign(a)·sign(dg).
        const int side = sign_a_ * line_direction(x) * adaptive_sign<T>([&](auto zero) {
                             const auto& r = at_zero(zero);
                             const auto l = x(zero);
                             return r.df * l.df - decltype(zero){T(2)} * r.a * l.f;
                         });
        if (inside > 0) return side < 0 ? -1 : 1;
        if (sign_disc_ == 0) return 0;  // x is the double root
        if (side < 0) return which == 0 ? 0 : -1;
        return which == 0 ? 1 : 0;
    }

    // A float estimate of the root from the coefficients in precision N (stable q-form).
    template <class N = wide_t<T>>
    T guess(int which) const
    {
        const Residual<N> r = at_zero(N{T(0)});
        const auto value = [](const auto& x) -> T {
            if constexpr (std::is_same_v<N, Bounded<T>>) return x.v;
            else return estimate(x).v;
        };
        const T a = value(r.a), b = value(r.df), c = value(r.f);
        if (sign_a_ == 0) return -c / b;
        const T disc = std::max(b * b - T(4) * a * c, T(0));
        const T q = T(-0.5) * (b + std::copysign(std::sqrt(disc), b));
        T t0 = q / a, t1 = q == T(0) ? t0 : c / q;
        if (t1 < t0) std::swap(t0, t1);
        return which == 0 ? t0 : t1;
    }
    // A certified interval around the root, from a working-precision guess and the root-location
    // bound of certify_root on its residual (running error bounds, pbrt-v4 "Managing Rounding
    // Error"): enough to order ends that are far apart without rounding either exactly. Empty when
    // the bound cannot be given or cannot tell this root from the other one.
    std::optional<std::pair<T, T>> enclose(int which) const
    {
        const T t = guess<Bounded<T>>(which);
        if (!std::isfinite(t)) return std::nullopt;
        const Residual<Bounded<T>> r = coef_.at(Bounded<T>{t});
        // The nearest root lies within h of t ...
        const T h = near_root_distance(r);
        if (!(h < std::numeric_limits<T>::infinity())) return std::nullopt;
        // ... and it is the requested one: F' has the sign of an entry (−sign a) at the smaller root.
        if (sign_a_ != 0 && (r.df.v > T(0) ? 1 : -1) * sign_a_ != (which == 0 ? -1 : 1)) return std::nullopt;
        const T lo = next_down(t - h), hi = next_up(t + h);  // t ∓ h rounded outward
        if (!(std::isfinite(lo) && std::isfinite(hi))) return std::nullopt;
        return std::pair<T, T>{lo, hi};
    }
    // The root rounded to nearest (ties to even) in T: a certified Newton step in double-word
    // arithmetic from a working-precision guess (enough for most rays), else from a double-word
    // guess (cancellation in the coefficients: far away, near tangency), else an exact search.
    T round(int which) const
    {
        if constexpr (std::is_same_v<first_t<T>, Bounded<T>>) {
            if (const auto quick = newton_round(which, guess<Bounded<T>>(which))) return *quick;
        } else {
            if (const auto quick = interval_round(which)) return *quick;
        }
        const T careful = guess<wide_t<T>>(which);
        if (const auto quick = newton_round(which, careful)) return *quick;
        return search_round(which, exact_guess(which, careful));
    }
    // The root from the exact coefficients and discriminant, each rounded to 53 bits with its
    // exponent kept apart (ScaledDouble), through the stable q-form: within a few ulps at any
    // magnitude, where the double-word guess under- or overflows (a root below 2^-1000 guessed as
    // 0 cost the exact search ~30 comparisons in Dyadic; fuzz harness rate 745/s on spheres).
    // `fallback` when a coefficient is not finite.
    T exact_guess(int which, T fallback) const
    {
        const Residual<Dyadic>& r = at_zero(Dyadic{});
        if (!(r.a.finite() && r.df.finite() && r.f.finite())) return fallback;
        const ScaledDouble a{r.a}, b{r.df}, c{r.f};
        if (sign_a_ == 0) return b.m == 0 ? fallback : (-c / b).template to<T>();
        const Dyadic disc = r.df * r.df - Dyadic(4.0) * r.a * r.f;
        // q = −(b + sign(b)·√disc)/2: |q| = (|b| + √disc)/2, no cancellation.
        ScaledDouble q = ScaledDouble::sum_of_magnitudes(b, disc.sign() > 0 ? ScaledDouble{disc}.sqrt() : ScaledDouble{});
        q.e -= 1;
        if (b.m >= 0) q.m = -q.m;
        if (q.m == 0) return T(0);  // b = disc = 0: the double root 0
        T t0 = (q / a).template to<T>(), t1 = (c / q).template to<T>();
        if (t1 < t0) std::swap(t0, t1);
        return which == 0 ? t0 : t1;
    }
    // The root from the first filter's coefficients with a certified interval (root_intervals),
    // rounded when that interval decides it (rounded_between_midpoints).
    std::optional<T> interval_round(int which) const
    {
        const first_t<T>& a = first0_.a, &b = first0_.df, &c = first0_.f;
        if (sign_a_ == 0) {
            if (!(std::abs(b.v) > b.e)) return std::nullopt;
            return rounded_between_midpoints<T>(quotient(-c, b));
        }
        if (sign_disc_ <= 0) return std::nullopt;
        const auto roots = root_intervals(a, b, c, disc0_);
        if (!roots) return std::nullopt;
        return rounded_between_midpoints<T>((*roots)[which]);
    }

    // One certified Newton step from t (newton_rounded, above).
    std::optional<T> newton_round(int which, T t) const { return newton_rounded(coef_, sign_a_, which, t); }

    // Exact: gallop from `guess` in ulps until the root is bracketed, bisect, then settle the
    // last ulp against the midpoint.
    T search_round(int which, T guess) const
    {
        if (!std::isfinite(guess)) guess = T(0);
        const auto at = [&](T x) { return compare(which, FloatLine<T>{-x, T(1)}); };
        int c = at(guess);
        if (c == 0) return guess;
        // Gallop away from guess in ulps until the root is bracketed, then bisect on the ordered bits.
        std::int64_t lo = key(guess), hi = lo;
        std::uint64_t step = 1;
        const int toward = -c;  // +1: root above guess
        constexpr T inf = std::numeric_limits<T>::infinity();
        const std::int64_t last = key(toward > 0 ? inf : -inf);  // never step past ±infinity
        for (;;) {
            // Saturating: lo ± step must not overflow (a root beyond the largest float gallops all
            // the way across the keys; found by the report's fuzz campaign on a triangle at 2^177).
            // (Unsigned: the keys of two floats can be 2^64 apart.)
            const std::uint64_t room = toward > 0 ? std::uint64_t(last) - std::uint64_t(lo) : std::uint64_t(lo) - std::uint64_t(last);
            const std::int64_t next =
                step >= room ? last : std::int64_t(toward > 0 ? std::uint64_t(lo) + step : std::uint64_t(lo) - step);
            const T y = value(next);
            const int cy = std::isfinite(y) ? at(y) : toward;
            if (cy == 0) return y;
            if (cy != c) {
                hi = next;
                break;
            }
            lo = next;
            if (step < room) step *= 2;
        }
        if (lo > hi) std::swap(lo, hi);
        while (hi - lo > 1) {  // invariant: the root lies strictly between value(lo) and value(hi)
            const std::int64_t mid = lo + (hi - lo) / 2;
            const int cm = at(value(mid));
            if (cm == 0) return value(mid);
            (cm < 0 ? lo : hi) = mid;
        }
        const T a = value(lo), b = value(hi);
        const int cm = compare(which, MidpointLine<T>{a, b});
        if (cm < 0) return b;  // midpoint below the root
        if (cm > 0) return a;
        return (key(a) & 1) == 0 ? a : b;
    }

private:
    // The coefficients at t = 0, computed once per quadratic in each number type (every sign and
    // comparison starts from them; the exact search compares dozens of floats with the root, and
    // recomputing a cone's exact coefficients for each was most of its cost).
    template <class N>
    const Residual<N>& at_zero(N zero) const
    {
        if constexpr (std::is_same_v<N, first_t<T>>) {
            return first0_;
        } else if constexpr (std::is_same_v<N, wide_t<T>>) {
            if (!wide0_) wide0_ = coef_(zero);
            return *wide0_;
        } else if constexpr (std::is_same_v<N, Dyadic>) {
            if (!dyadic0_) dyadic0_ = coef_(zero);
            return *dyadic0_;
        } else {
            if (!exact0_) exact0_ = coef_(zero);
            return *exact0_;
        }
    }

    template <class Line>
    static int line_direction(const Line& x)
    {
        return adaptive_sign<T>([&](auto zero) { return x(zero).df; });
    }
    // Floats ordered as integers: the key of the next float up is key + 1.
    static std::int64_t key(T x)
    {
        if constexpr (sizeof(T) == 8) {
            std::int64_t i;
            std::memcpy(&i, &x, 8);
            return i < 0 ? std::numeric_limits<std::int64_t>::min() - i : i;
        } else {
            std::int32_t i;
            std::memcpy(&i, &x, 4);
            return i < 0 ? std::int64_t(std::numeric_limits<std::int32_t>::min()) - i : i;
        }
    }
    static T value(std::int64_t k)
    {
        T x;
        if constexpr (sizeof(T) == 8) {
            const std::int64_t i = k < 0 ? std::numeric_limits<std::int64_t>::min() - k : k;
            std::memcpy(&x, &i, 8);
        } else {
            const std::int32_t i = std::int32_t(k < 0 ? std::int64_t(std::numeric_limits<std::int32_t>::min()) - k : k);
            std::memcpy(&x, &i, 4);
        }
        return x;
    }

    Coef coef_;
    Residual<first_t<T>> first0_;
    first_t<T> disc0_{T(0)};  // F'(0)² − 4·a·F(0) in the first filter (quadratic case)
    mutable std::optional<Residual<wide_t<T>>> wide0_;
    mutable std::optional<Residual<Expansion<typename ExactComponent<T>::type>>> exact0_;
    mutable std::optional<Residual<Dyadic>> dyadic0_;
    int sign_a_ = 0, sign_disc_ = 0, sign_b_ = 0, sign_c_ = 0;
};

}  // namespace detail
}  // namespace rayq
