// rayq::oracle — the exact hit record and the measurement of a kernel answer against it.
#include "truth.hpp"

#include <rayq/oracle/fixtures.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <variant>

#include "convert.hpp"
#include "numeric.hpp"

namespace rayq::oracle {

using exact::Alg;
using exact::Mp;
using exact::Q;

std::unique_ptr<Truth::Impl> make_truth(const exact::Problem& problem, bool is_float)
{
    auto impl = std::make_unique<Truth::Impl>();
    impl->is_float = is_float;
    impl->solution = exact::solve(problem);
    const exact::Solution& s = impl->solution;
    ExactHit& h = impl->hit;
    h.defined = s.defined;
    for (const exact::Crossing& x : s.crossings) {
        Mp v;
        exact::approximate(v.v, x.t, s.D);
        h.crossings.push_back(mpfr_get_ld(v.v, MPFR_RNDN));
    }
    if (!s.first) return impl;

    const exact::Crossing& c = s.crossings[*s.first];
    h.hit = true;
    h.part = c.part;
    h.entering = c.entering;
    h.tangent = c.tangent;
    h.t_float = exact::round_nearest<float>(c.t, s.D);
    h.t_double = exact::round_nearest<double>(c.t, s.D);
    {
        Mp v;
        exact::approximate(v.v, c.t, s.D);
        h.t_long = mpfr_get_ld(v.v, MPFR_RNDN);
    }
    h.t_exact = exact::to_string(c.t, s.D);

    h.normal_defined = s.normal_defined;
    if (s.normal_defined) {
        const Alg* comp[3] = {&s.normal.x, &s.normal.y, &s.normal.z};
        Mp n[3], len, sq;
        mpfr_set_zero(len.v, 1);
        for (int i = 0; i < 3; ++i) {
            exact::approximate(n[i].v, *comp[i], s.D);
            mpfr_sqr(sq.v, n[i].v, MPFR_RNDN);
            mpfr_add(len.v, len.v, sq.v, MPFR_RNDN);
        }
        mpfr_sqrt(len.v, len.v, MPFR_RNDN);
        double out[3];
        long double out_ld[3];
        for (int i = 0; i < 3; ++i) {
            mpfr_div(n[i].v, n[i].v, len.v, MPFR_RNDN);
            out[i] = mpfr_get_d(n[i].v, MPFR_RNDN);
            out_ld[i] = mpfr_get_ld(n[i].v, MPFR_RNDN);
        }
        h.outward_normal = {out[0], out[1], out[2]};
        const int facing = exact::sign(exact::dot(s.normal, s.direction), s.D);
        const double f = facing > 0 ? -1.0 : 1.0;
        h.facing_normal = {f * out[0], f * out[1], f * out[2]};
        for (int i = 0; i < 3; ++i) impl->facing[i] = static_cast<long double>(f) * out_ld[i];
        impl->facing_ambiguous = facing == 0;
    }
    return impl;
}

namespace {

long double angle_between(const long double a[3], const long double b[3])
{
    const long double cx = a[1] * b[2] - a[2] * b[1], cy = a[2] * b[0] - a[0] * b[2], cz = a[0] * b[1] - a[1] * b[0];
    const long double d = a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    return std::atan2(std::sqrt(cx * cx + cy * cy + cz * cz), d);
}

template <class T>
Measurement measure_impl(const Truth::Impl& impl, const std::optional<Hit<T>>& kernel)
{
    constexpr double nan = std::numeric_limits<double>::quiet_NaN();
    Measurement m;
    m.ulps = m.rel_error = m.normal_angle = nan;
    const exact::Solution& s = impl.solution;
    m.defined = s.defined;
    if (!m.defined) return m;
    m.exact_hit = impl.hit.hit;
    m.kernel_hit = kernel.has_value();
    m.hit_agrees = m.exact_hit == m.kernel_hit;
    m.tangent = impl.hit.tangent;
    m.both_hit = m.exact_hit && m.kernel_hit;
    if (m.kernel_hit && !m.exact_hit) {
        // A false hit certifies a crossing that the window does not hold: its bound is violated
        // unless some crossing of the line (outside the window, or clipped) lies within it.
        const T t = kernel->t, e = kernel->t_error;
        m.bounded = std::isfinite(e);
        if (std::isfinite(t) && (m.bounded || std::isnan(e) || e < T(0))) {
            bool within = false;
            if (m.bounded && e >= T(0)) {
                const Q lo = Q(static_cast<double>(t)) - Q(static_cast<double>(e)), hi = Q(static_cast<double>(t)) + Q(static_cast<double>(e));
                for (const exact::Crossing& x : s.crossings)
                    within = within || (exact::compare(x.t, lo, s.D) >= 0 && exact::compare(x.t, hi, s.D) <= 0);
            }
            m.bound_violated = m.uncertified = !within;
        }
    }
    if (!m.both_hit) return m;

    const Hit<T>& k = *kernel;
    const exact::Crossing& c = s.crossings[*s.first];
    m.part_agrees = k.part == c.part;
    m.front_face_agrees = k.front_face == c.entering;

    if (!std::isfinite(k.t)) {
        m.ulps = m.rel_error = std::numeric_limits<double>::infinity();
        m.bounded = std::isfinite(k.t_error);
        m.bound_violated = true;
    } else {
        const Q tk(static_cast<double>(k.t));
        const Alg diff{tk - c.t.a, -c.t.b};  // t_kernel − t_exact
        Mp err, scale;
        exact::approximate(err.v, diff, s.D);
        mpfr_abs(err.v, err.v, MPFR_RNDN);
        const Q ulp = exact::ulp_at<T>(c.t, s.D);
        mpfr_set_q(scale.v, ulp.get_mpq_t(), MPFR_RNDN);
        Mp q;
        mpfr_div(q.v, err.v, scale.v, MPFR_RNDN);
        m.ulps = mpfr_get_d(q.v, MPFR_RNDN);
        if (exact::sign(c.t, s.D) == 0) {
            m.rel_error = mpfr_zero_p(err.v) ? 0.0 : std::numeric_limits<double>::infinity();
        } else {
            exact::approximate(scale.v, c.t, s.D);
            mpfr_abs(scale.v, scale.v, MPFR_RNDN);
            mpfr_div(q.v, err.v, scale.v, MPFR_RNDN);
            m.rel_error = mpfr_get_d(q.v, MPFR_RNDN);
        }
        T down, up;
        exact::brackets<T>(c.t, s.D, down, up);
        m.faithful = k.t == down || k.t == up;

        const T e = k.t_error;
        m.bounded = std::isfinite(e);
        if (std::isnan(e) || e < T(0)) m.bound_violated = m.uncertified = true;
        else if (m.bounded) {
            const Q eq(static_cast<double>(e));
            const Q lo = tk - eq, hi = tk + eq;
            const auto within = [&](const Alg& x) { return exact::compare(x, lo, s.D) >= 0 && exact::compare(x, hi, s.D) <= 0; };
            m.bound_violated = !within(c.t);
            m.uncertified = m.bound_violated && std::none_of(s.crossings.begin(), s.crossings.end(),
                                                             [&](const exact::Crossing& x) { return within(x.t); });
        }
        // Not a rounding of the first hit, and nearer another crossing:
        // |tk − x| < |tk − first| ⇔ (first − x)·(2tk − x − first) < 0.
        for (const exact::Crossing& x : m.faithful ? std::vector<exact::Crossing>{} : s.crossings) {
            const int apart = exact::compare(c.t, x.t, s.D);
            if (apart == 0) continue;
            const Alg twice_tk_minus{2 * tk - x.t.a - c.t.a, -x.t.b - c.t.b};
            if (apart * exact::sign(twice_tk_minus, s.D) < 0) m.other_crossing = true;
        }
    }

    if (impl.hit.normal_defined) {
        const long double kn[3] = {k.normal.x, k.normal.y, k.normal.z};
        long double a = angle_between(kn, impl.facing);
        if (impl.facing_ambiguous) {
            const long double flipped[3] = {-impl.facing[0], -impl.facing[1], -impl.facing[2]};
            a = std::min(a, angle_between(kn, flipped));
        }
        m.normal_angle = static_cast<double>(a);
    }
    return m;
}

}  // namespace

// Here, not in fixtures.cpp: the text format's parser then links without the exact arithmetic
// (the parser fuzz harness builds it alone, tools/fuzz/parsers_fuzz_target.cpp).
Truth truth_of(const AnyInput& input)
{
    return std::visit([](const auto& in) { return Truth(in.ray, in.prim); }, input);
}

Truth::Truth(Truth&&) noexcept = default;
Truth& Truth::operator=(Truth&&) noexcept = default;
Truth::~Truth() = default;

const ExactHit& Truth::first_hit() const { return impl_->hit; }
bool Truth::is_float() const { return impl_->is_float; }

Measurement Truth::measure(const std::optional<Hit<float>>& kernel) const
{
    if (!impl_->is_float) throw std::logic_error("rayq::oracle::Truth::measure: a float hit for double inputs");
    return measure_impl<float>(*impl_, kernel);
}

Measurement Truth::measure(const std::optional<Hit<double>>& kernel) const
{
    if (impl_->is_float) throw std::logic_error("rayq::oracle::Truth::measure: a double hit for float inputs");
    return measure_impl<double>(*impl_, kernel);
}

}  // namespace rayq::oracle
