// The static filter (detail/magnitude.hpp) and the accurate policy's quick lanes for float spheres
// and flat primitives (detail/exact_crossings.hpp, quick_curved_crossings, quick_flat_crossing): the
// filter's bound holds against exact expansion arithmetic, and the quick lanes answer exactly what
// the full exact paths do.
#include "test_support.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <random>
#include <vector>

#include <rayq/detail/expansion.hpp>
#include <rayq/detail/double_word.hpp>
#include <rayq/detail/magnitude.hpp>

namespace rayq::test::magnitude_filter_test {
namespace {

using detail::Expansion;
using detail::Magnitude;

// The quick lanes write into a Crossings and say whether they decided; here as an optional, none
// where a lane declines.
template <class T, class Lane>
std::optional<Crossings<T>> lane_answer(Lane&& lane)
{
    Crossings<T> out;
    if (lane(out)) return out;
    return std::nullopt;
}
template <class Prim, class T = scalar_t<Prim>>
std::optional<Crossings<T>> quick_curved(const Ray<T>& r, const Prim& p, bool axial, bool capped, detail::CapEnds ends, int limit)
{
    return lane_answer<T>([&](Crossings<T>& out) { return detail::quick_curved_crossings(r, p, axial, capped, ends, limit, out); });
}
template <class Prim, class T = scalar_t<Prim>>
std::optional<Crossings<T>> running_bound(const Ray<T>& r, const Prim& p, bool axial, bool capped, detail::CapEnds ends, int limit)
{
    return lane_answer<T>([&](Crossings<T>& out) { return detail::running_bound_crossings(r, p, axial, capped, ends, limit, out); });
}
template <class Prim, class T = scalar_t<Prim>>
std::optional<Crossings<T>> axial_first(const Ray<T>& r, const Prim& p, bool capped, detail::CapEnds ends, int limit)
{
    return lane_answer<T>([&](Crossings<T>& out) { return detail::axial_first_crossing(r, p, capped, ends, limit, out); });
}
template <class Prim>
std::optional<Crossings<double>> quick_sphere(const Ray<double>& r, const Prim& p, const detail::PlainQuadratic& q, int limit)
{
    return lane_answer<double>([&](Crossings<double>& out) { return detail::quick_sphere_crossings(r, p, q, limit, out); });
}
template <class T, class Quick, class Coef>
std::optional<Crossings<T>> quick_flat_lane(const Ray<T>& r, const Quick& quick, const Coef& coef)
{
    return lane_answer<T>([&](Crossings<T>& out) { return detail::quick_flat_crossing(r, quick, coef, out); });
}

// A T with a random sign, full significand and exponent in [lo, hi]; 0 one time in `zeros`.
template <class T>
T random_number(std::mt19937_64& rng, int lo, int hi, int zeros = 0)
{
    if (zeros > 0 && rng() % zeros == 0) return T(0);
    constexpr int fraction_bits = std::numeric_limits<T>::digits - 1;
    const T significand = T(1) + std::ldexp(T(rng() >> (64 - fraction_bits)), -fraction_bits);
    const T x = std::ldexp(significand, std::uniform_int_distribution<int>(lo, hi)(rng));
    return rng() & 1 ? -x : x;
}

// |exact − value| <= bound, decided exactly: bound − |value − exact| >= 0 as expansions.
bool bound_holds(const Expansion<double>& value, double bound, const Expansion<double>& exact)
{
    const Expansion<double> diff = value - exact;
    const Expansion<double> b(bound);
    return (b - diff).sign() >= 0 && (b + diff).sign() >= 0;
}
bool bound_holds(const Magnitude<double>& x, const Expansion<double>& exact)
{
    return bound_holds(Expansion<double>(x.v()), x.bound(), exact);
}
bool bound_holds(const detail::StaticDoubleWord<double>& x, const Expansion<double>& exact)
{
    return bound_holds(Expansion<double>(x.hi) + Expansion<double>(x.lo), x.bound(), exact);
}

// The value lane takes exactly the scalar operations and the magnitude lane those on |inputs|
// with every difference a sum, bit for bit, whichever pair type carries them (the compiler's
// two-lane vector, or PortablePair where there is none); k, p and d count as documented.
TEST(MagnitudeFilter, ValueAndMagnitudeLanesAreTheScalarEvaluations)
{
    std::mt19937_64 rng(0x7E1);
    const auto portable = [](double v, double m) { return detail::PortablePair<double>{{v, m}}; };
    for (int i = 0; i < 10000; ++i) {
        const double a = random_number<double>(rng, -60, 60, 8), b = random_number<double>(rng, -60, 60, 8),
                     c = random_number<double>(rng, -60, 60, 8);
        const Magnitude<double> x = (Magnitude<double>{a} - Magnitude<double>{b}) * Magnitude<double>{c} + -(Magnitude<double>{a} * Magnitude<double>{a});
        const double value = (a - b) * c + -(a * a);
        const double magnitude = (std::abs(a) + std::abs(b)) * std::abs(c) + std::abs(a) * std::abs(a);
        ASSERT_EQ(std::signbit(x.v()), std::signbit(value)) << a << ' ' << b << ' ' << c;
        ASSERT_EQ(x.v(), value) << a << ' ' << b << ' ' << c;
        ASSERT_EQ(x.m(), magnitude) << a << ' ' << b << ' ' << c;
        ASSERT_EQ(x.k, 3);
        ASSERT_EQ(x.p, 2);
        ASSERT_EQ(x.d, 2);
        const auto y = (portable(a, std::abs(a)) + detail::negated_value<double>(portable(b, std::abs(b)))) * portable(c, std::abs(c));
        ASSERT_EQ(y[0], (a - b) * c);
        ASSERT_EQ(y[1], (std::abs(a) + std::abs(b)) * std::abs(c));
    }
}

// The range the quick lanes and the exact expansions take inputs in, decided on the bits: zero
// or a magnitude in [2^-64, 2^64], both ends included; NaN, infinities and subnormals out.
template <class T>
void expect_exact_range_boundaries()
{
    using detail::next_down;
    using detail::next_up;
    using detail::zero_or_within_exact_range;
    const T lo = T(0x1p-64), hi = T(0x1p64), inf = std::numeric_limits<T>::infinity();
    for (const T sign : {T(1), T(-1)}) {
        EXPECT_TRUE(zero_or_within_exact_range(sign * T(0)));
        EXPECT_TRUE(zero_or_within_exact_range(sign * lo));
        EXPECT_TRUE(zero_or_within_exact_range(sign * hi));
        EXPECT_TRUE(zero_or_within_exact_range(sign * next_up(lo)));
        EXPECT_TRUE(zero_or_within_exact_range(sign * next_down(hi)));
        EXPECT_TRUE(zero_or_within_exact_range(sign * T(1)));
        EXPECT_FALSE(zero_or_within_exact_range(sign * next_down(lo)));
        EXPECT_FALSE(zero_or_within_exact_range(sign * next_up(hi)));
        EXPECT_FALSE(zero_or_within_exact_range(sign * std::numeric_limits<T>::denorm_min()));
        EXPECT_FALSE(zero_or_within_exact_range(sign * std::numeric_limits<T>::min()));
        EXPECT_FALSE(zero_or_within_exact_range(sign * std::numeric_limits<T>::max()));
        EXPECT_FALSE(zero_or_within_exact_range(sign * inf));
    }
    EXPECT_FALSE(zero_or_within_exact_range(std::numeric_limits<T>::quiet_NaN()));
    EXPECT_FALSE(zero_or_within_exact_range(-std::numeric_limits<T>::quiet_NaN()));
    EXPECT_TRUE(zero_or_within_exact_range(Vec3<T>{T(0), lo, -hi}));
    EXPECT_FALSE(zero_or_within_exact_range(Vec3<T>{T(1), T(1), next_up(hi)}));
    EXPECT_FALSE(zero_or_within_exact_range(Vec3<T>{next_down(lo), T(1), T(1)}));
}
TEST(MagnitudeFilter, ExactRangeIncludesZeroAndBothEnds)
{
    expect_exact_range_boundaries<float>();
    expect_exact_range_boundaries<double>();
}

// StaticRange (all_within_static_range), which decides many double inputs at once from their largest
// and smallest nonzero magnitudes, gives the same answer as each input's own test, for every triple
// of boundary values (zeros of both signs, both ends and their neighbours, subnormals, NaN,
// infinities) in every order; float inputs always lie within it.
TEST(MagnitudeFilter, StaticRangeDecidesAsEachInputDoes)
{
    using detail::next_down;
    using detail::next_up;
    const double lo = 0x1p-64, hi = 0x1p64, inf = std::numeric_limits<double>::infinity();
    std::vector<double> values;
    for (const double x : {0.0, lo, hi, next_up(lo), next_down(hi), 1.0, next_down(lo), next_up(hi), std::numeric_limits<double>::denorm_min(),
                           std::numeric_limits<double>::min(), std::numeric_limits<double>::max(), inf, std::numeric_limits<double>::quiet_NaN()})
        values.push_back(x), values.push_back(-x);
    int in = 0, out = 0;
    for (const double a : values)
        for (const double b : values)
            for (const double c : values) {
                const bool each = detail::zero_or_within_exact_range(a) && detail::zero_or_within_exact_range(b) && detail::zero_or_within_exact_range(c);
                ASSERT_EQ(detail::all_within_static_range(a, b, c), each) << a << " " << b << " " << c;
                ASSERT_EQ(detail::all_within_static_range(Vec3<double>{a, b, c}), each) << a << " " << b << " " << c;
                ASSERT_EQ(detail::all_within_static_range(Vec3<double>{a, 1.0, -1.0}, Vec3<double>{0.0, b, 2.0}, c), each);
                ++(each ? in : out);
            }
    EXPECT_GT(in, 1000);
    EXPECT_GT(out, 1000);
    EXPECT_TRUE(detail::all_within_static_range(Vec3<float>{0.0f, 1e-40f, std::numeric_limits<float>::max()}, 1e30f));
}

// One root's interval (root_interval, for a caller that needs one) is the one root_intervals gives
// for it among both, whatever the signs of a and b: the smaller root is q/a exactly when q took a's
// sign from b.
TEST(MagnitudeFilter, OneRootIntervalIsThatRootAmongBoth)
{
    using B = detail::Bounded<double>;
    std::mt19937_64 rng(0x0A1);
    int compared = 0, signs[2][2] = {};
    for (int i = 0; i < 20000; ++i) {
        const double av = random_number<double>(rng, -20, 20), bv = random_number<double>(rng, -20, 20),
                     cv = random_number<double>(rng, -20, 20);
        const B a{av, std::abs(av) * 0x1p-50}, b{bv, std::abs(bv) * 0x1p-50}, c{cv, std::abs(cv) * 0x1p-50};
        const B disc = b * b - B{4.0} * a * c;
        const auto both = detail::root_intervals(a, b, c, disc);
        if (!both) continue;
        ASSERT_TRUE(detail::two_certain_roots(a, disc));
        const B q = detail::cancellation_free_q(b, disc);
        for (int which = 0; which < 2; ++which) {
            const auto one = detail::root_interval(a, b, c, q, which);
            ASSERT_TRUE(one) << i;
            EXPECT_EQ(one->v, (*both)[which].v) << i << " which " << which;
            EXPECT_EQ(one->e, (*both)[which].e) << i << " which " << which;
        }
        ++compared, ++signs[av > 0][bv >= 0];
    }
    EXPECT_GT(compared, 5000);
    for (const auto& row : signs)
        for (const int n : row) EXPECT_GT(n, 1000);
}

// The sphere's coefficients at t = 0 and their discriminant, as the quick lane computes them, on
// float inputs across 2^±40 and across float's whole range, and on near-tangent rays
// (cancellation).
TEST(MagnitudeFilter, BoundHoldsOnSphereCoefficientsAndDiscriminant)
{
    std::mt19937_64 rng(0x3A6);
    int checked = 0, decided = 0;
    for (int i = 0; i < 20000; ++i) {
        const int spread = i % 3 == 0 ? 40 : (i % 3 == 1 ? 4 : 126);
        const auto x = [&] { return random_number<float>(rng, -spread, spread); };
        Sphere<float> s{{x(), x(), x()}, std::abs(x())};
        Ray<float> r{{x(), x(), x()}, {x(), x(), x()}};
        if (i % 2 == 1) {  // aim along an axis at the rim: the discriminant nearly cancels
            r.origin = {s.center.x - 4 * s.radius, s.center.y + s.radius * (1 - 1e-6f * float(i % 7)), s.center.z};
            r.direction = {1.0f, 0.0f, 0.0f};
            if (!isfinite(r.origin)) continue;  // 4·radius beyond the largest float
        }
        const detail::PartCoefficients<Sphere<float>> coef{&s, &r, Part::surface};
        const auto m = coef(Magnitude<double>{0.0});
        const auto e = coef(Expansion<double>{});
        const Magnitude<double> disc = m.df * m.df - Magnitude<double>{4.0} * m.a * m.f;
        const Expansion<double> exact_disc = e.df * e.df - Expansion<double>{4.0} * e.a * e.f;
        EXPECT_TRUE(bound_holds(m.a, e.a)) << i;
        EXPECT_TRUE(bound_holds(m.df, e.df)) << i;
        EXPECT_TRUE(bound_holds(m.f, e.f)) << i;
        EXPECT_TRUE(bound_holds(disc, exact_disc)) << i;
        ++checked;
        if (detail::certain_sign(disc) != 0) {
            ++decided;
            EXPECT_EQ(detail::certain_sign(disc), exact_disc.sign()) << i;
        }
    }
    // The filter is useful: it decides most discriminants, but not the near-tangent ones.
    EXPECT_GT(decided, checked / 2);
    EXPECT_LT(decided, checked);
}

// The quick lanes' Newton step evaluates F in StaticDoubleWord (quick_newton_rounded): its static
// bound holds against exact expansions on every primitive's residual, at the edges of the range it
// is promised (inputs and t of 0 or within 2^±64, down to 2^-64 with full significands: the grid
// argument), at ordinary scales, near a root (t from the exact path), where F cancels, and where
// an intermediate cancels; and
// every residual stays within the degree the argument covers (8: the cone's).
TEST(MagnitudeFilter, StaticDoubleWordBoundHoldsOnEveryResidual)
{
    std::mt19937_64 rng(0x5D3);
    int checked = 0, max_degree = 0;
    const auto check = [&](const auto& prim, const Ray<double>& r, Part part, double t, int i) {
        using Prim = std::decay_t<decltype(prim)>;
        const detail::PartCoefficients<Prim> coef{&prim, &r, part};
        const auto f = coef.at(detail::StaticDoubleWord<double>{t}).f;
        const auto exact = coef.at(Expansion<double>{t}).f;
        ASSERT_TRUE(exact.exact()) << i;
        EXPECT_TRUE(bound_holds(f, exact)) << i << " part " << int(part) << " t " << t;
        // The Newton step's estimate, as the query takes it (hardware FMA where the CPU has one).
        const detail::Estimate<double> step_f = detail::quick_f_estimate(coef, t);
        EXPECT_TRUE(bound_holds(Expansion<double>(step_f.v), step_f.e, exact)) << i << " part " << int(part) << " t " << t;
        EXPECT_LE(f.d, 8) << i;
        max_degree = std::max(max_degree, f.d);
        ++checked;
    };
    for (int i = 0; i < 6000; ++i) {
        const int lo = i % 3 == 0 ? -64 : (i % 3 == 1 ? -2 : -30), hi = i % 3 == 0 ? 63 : (i % 3 == 1 ? 2 : 30);
        const auto x = [&] { return random_number<double>(rng, lo, hi, 8); };
        const auto v = [&] { return Vec3<double>{x(), x(), x()}; };
        const Ray<double> r{v(), v()};
        const Vec3<double> p0 = v(), p1 = v();
        const double r0 = std::abs(x()), r1 = std::abs(x());
        const Sphere<double> sphere{p0, r0};
        const Cylinder<double> cylinder{p0, p1, r0, Caps::both};
        const Cone<double> cone{p0, r0, p1, r1, Caps::both};
        const Triangle<double> triangle{p0, p1, v()};
        const Parallelogram<double> parallelogram{p0, p1, v()};
        const Disk<double> disk{p0, p1, r0};
        // t: random, the exact path's roots, where F nearly vanishes, and the point of the line
        // nearest p0, where q = o − p0 + t·d cancels before the products take it (hi and lo of an
        // operand then have comparable sizes: the compensated form's bound must not assume lo ≪ hi).
        std::vector<double> ts{x(), 0.0, dot(p0 - r.origin, r.direction) / dot(r.direction, r.direction)};
        for (const auto& c : detail::exact_curved_crossings(r, cylinder, true, true, {true, true}, 2)) ts.push_back(c.t);
        for (const auto& c : detail::exact_curved_crossings(r, sphere, false, false, {false, false}, 2)) ts.push_back(c.t);
        for (const double t : ts) {
            if (!(t == 0.0 || (std::abs(t) >= 0x1p-64 && std::abs(t) <= 0x1p64))) continue;
            check(sphere, r, Part::surface, t, i);
            for (const Part part : {Part::surface, Part::cap0, Part::cap1}) check(cylinder, r, part, t, i), check(cone, r, part, t, i);
            check(triangle, r, Part::surface, t, i);
            check(parallelogram, r, Part::surface, t, i);
            check(disk, r, Part::surface, t, i);
        }
    }
    EXPECT_GT(checked, 6000 * 2 * 10);
    EXPECT_EQ(max_degree, 8);
}

// An open axial primitive's end route takes the side's sign over an interval around the plane's
// plain root estimate instead of rounding the plane's root (axial_first_crossing): that interval,
// linear_root_reach, holds the exact root, decided exactly (|G(t)| <= reach·|df| in expansions),
// at t̂ = −f/df, a few ulps off it and anywhere, across the static range's scales; and it is finite
// (df's sign certain) on nearly every plane.
TEST(MagnitudeFilter, LinearRootReachHoldsThePlanesRoot)
{
    std::mt19937_64 rng(0x11AE);
    int checked = 0, finite = 0;
    const Magnitude<double> zero{0.0, 0.0, 0, 0, 0};
    for (int i = 0; i < 20000; ++i) {
        const int lo = i % 3 == 0 ? -64 : (i % 3 == 1 ? -2 : -30), hi = i % 3 == 0 ? 63 : (i % 3 == 1 ? 2 : 30);
        const auto x = [&] { return random_number<double>(rng, lo, hi, 8); };
        const auto v = [&] { return Vec3<double>{x(), x(), x()}; };
        const Ray<double> r{v(), v()};
        const Cylinder<double> cylinder{v(), v(), std::abs(x()), Caps::none};
        const detail::PartCoefficients<Cylinder<double>> plane{&cylinder, &r, i % 2 ? Part::cap0 : Part::cap1};
        const detail::Residual<Magnitude<double>> g = plane(zero);
        const double estimate = -g.f.v() / g.df.v();
        const double ulp = std::nextafter(std::abs(estimate), 1e300) - std::abs(estimate);
        for (const double t : {estimate, estimate + 3 * ulp, estimate - 7 * ulp, x()}) {
            if (!std::isfinite(t) || !(t == 0.0 || (std::abs(t) >= 0x1p-64 && std::abs(t) <= 0x1p64))) continue;
            const double reach = detail::linear_root_reach(g, t);
            ++checked;
            if (!std::isfinite(reach)) continue;
            ++finite;
            const Expansion<double> at_t = plane.at(Expansion<double>{t}).f, slope = plane.at(Expansion<double>{0.0}).df;
            const Expansion<double> room = slope.sign() < 0 ? -(Expansion<double>(reach) * slope) : Expansion<double>(reach) * slope;
            EXPECT_GE((room - at_t).sign(), 0) << i << " t " << t << " reach " << reach;
            EXPECT_GE((room + at_t).sign(), 0) << i << " t " << t << " reach " << reach;
        }
    }
    EXPECT_GT(checked, 20000);
    EXPECT_GT(finite, checked * 9 / 10);
}

// The sphere's quick lane against the full exact path on one query: where the lane answers, the
// same crossings (count, t bit for bit, part, direction). The number of crossings, or none when
// the lane declined.
template <class T>
std::optional<int> sphere_lane_answer(const Ray<T>& r, const Sphere<T>& s, int limit, int i)
{
    const auto exact = detail::exact_curved_crossings_in_unit(r, s, false, false, {false, false}, limit, detail::reach_of(r, s));
    const auto expect_exact = [&](const Crossings<T>& quick, const char* lane) {
        EXPECT_EQ(quick.count, exact.count) << lane << " " << i << " limit " << limit;
        for (int k = 0; k < std::min(quick.count, exact.count); ++k) {
            EXPECT_EQ(quick.item[k].t, exact.item[k].t) << lane << " " << i << " limit " << limit << " crossing " << k;
            EXPECT_EQ(quick.item[k].part, exact.item[k].part) << lane << " " << i;
            EXPECT_EQ(quick.item[k].entering, exact.item[k].entering) << lane << " " << i;
        }
    };
    // A double sphere's own lane (from plain coefficients, as crossings(accurate) calls it where
    // the plain discriminant is positive), and the filter's lane, each checked where it answers.
    bool answered = false;
    if constexpr (std::is_same_v<T, double>) {
        const detail::PlainQuadratic q = detail::plain_quadratic(r, s);
        if (q.d > 0.0)
            if (const auto own = quick_sphere(r, s, q, limit)) expect_exact(*own, "sphere lane"), answered = true;
    }
    if (const auto quick = quick_curved(r, s, false, false, {false, false}, limit)) expect_exact(*quick, "filter lane"), answered = true;
    if (!answered) return std::nullopt;
    return exact.count;
}

// The quick lane, where it answers, gives the full exact path's crossings (count, t bit for bit,
// part, direction, certification), for the closest crossing and for both; and it answers on nearly
// every generic ray.
template <class T>
void expect_sphere_lane_agrees()
{
    std::mt19937_64 rng(0x5E7);
    std::uniform_real_distribution<double> u(-1, 1), lg(-3, 3);
    int rays = 0, answered = 0;
    for (int i = 0; i < 20000; ++i) {
        // Mostly ordinary scales; every fourth query far from 1 (2^±60), where the quick lane
        // still answers as long as the coefficients stay within 2^±400.
        const double scale = i % 4 == 3 ? std::ldexp(1.0, int(60 * u(rng))) : std::pow(10.0, lg(rng));
        const Sphere<T> s{{T(scale * u(rng)), T(scale * u(rng)), T(scale * u(rng))}, T(scale * (0.1 + std::abs(u(rng))))};
        const Vec3<T> o{T(4 * scale * u(rng)), T(4 * scale * u(rng)), T(4 * scale * u(rng))};
        const Vec3<T> aim{T(s.center.x + 1.2 * s.radius * u(rng)), T(s.center.y + 1.2 * s.radius * u(rng)),
                          T(s.center.z + 1.2 * s.radius * u(rng))};
        Ray<T> r{o, aim - o};
        if (i % 4 == 1) r.tmin = T(std::abs(u(rng))), r.tmax = T(1 + std::abs(u(rng)));  // windows that cut the roots
        for (const int limit : {1, 2}) {
            ++rays;
            answered += sphere_lane_answer(r, s, limit, i).has_value();
        }
    }
    EXPECT_GT(answered, rays * 95 / 100);
}

TEST(MagnitudeFilter, QuickLaneAgreesWithTheExactPath) { expect_sphere_lane_agrees<float>(); }
// Double spheres within 2^±64 (every fourth one reaches 2^±60) take the lane as well, their roots
// rounded by a double-word Newton step.
TEST(MagnitudeFilter, DoubleQuickLaneAgreesWithTheExactPath) { expect_sphere_lane_agrees<double>(); }

// Double rays grazing a sphere, their lines 2^-52 to 2^-8 of the radius inside or outside
// tangency, from in front and from a point on the line's closest approach (inside the sphere when
// the line crosses it): the lane takes a double sphere's roots straight from plain coefficients,
// each certified by its Newton step, which must decline where the plain discriminant's sign is
// wrong. Where the lane answers, it answers what the exact path does: hit or miss, every crossing
// bit for bit.
TEST(MagnitudeFilter, DoubleSphereLaneAgreesNearTangency)
{
    std::mt19937_64 rng(0x7A26);
    std::uniform_real_distribution<double> u(-1, 1);
    int rays = 0, answered = 0, hits = 0, misses = 0;
    for (int i = 0; i < 20000; ++i) {
        const double radius = std::ldexp(1.0 + std::abs(u(rng)), int(8 * u(rng)));
        const Sphere<double> s{{u(rng), u(rng), u(rng)}, radius};
        const Vec3<double> d = normalize(Vec3<double>{u(rng), u(rng), u(rng)});
        const Vec3<double> n = normalize(cross(d, Vec3<double>{u(rng), u(rng), u(rng)}));
        const double eps = (rng() & 1 ? 1.0 : -1.0) * std::ldexp(1.0, -8 - int(rng() % 45));
        const Vec3<double> closest = s.center + (radius * (1 + eps)) * n;
        const Ray<double> r{closest - (i % 3 == 0 ? 0.0 : 3 * radius) * d, d};
        for (const int limit : {1, 2}) {
            ++rays;
            const std::optional<int> count = sphere_lane_answer(r, s, limit, i);
            if (!count) continue;
            ++answered;
            (*count > 0 ? hits : misses) += 1;
        }
    }
    // Both answers are exercised, and the lane answers most of these rays (two thirds at writing).
    EXPECT_GT(hits, rays / 8);
    EXPECT_GT(misses, rays / 8);
    EXPECT_GT(answered, rays / 2);
}

// The sphere's own F for the quick lanes' Newton steps (quick_residual_f) holds its bound: the
// exact F (expansions) lies within e of v, at roots (where F cancels to nothing), a few ulps off
// them, and far from them, over spheres and rays across the static range's scales; and the bound
// is u²-sized (within 2^-98 of F's magnitude, plus the rounding of v itself).
TEST(MagnitudeFilter, SphereResidualForNewtonStepsHoldsItsBound)
{
    std::mt19937_64 rng(0x5F0F);
    std::uniform_real_distribution<double> u(-1, 1);
    int checked = 0, near_roots = 0;
    for (int i = 0; i < 20000; ++i) {
        const int scale = int(40 * u(rng));
        const double radius = std::ldexp(0.5 + std::abs(u(rng)), scale);
        const Sphere<double> s{Vec3<double>{u(rng), u(rng), u(rng)} * std::ldexp(1.0, scale), radius};
        const Vec3<double> d = normalize(Vec3<double>{u(rng), u(rng), u(rng)}) * std::ldexp(1.0, int(8 * u(rng)));
        const Ray<double> r{s.center + Vec3<double>{u(rng), u(rng), u(rng)} * (0.6 * radius) - (4 * radius / length(d)) * d, d};
        // t: a root when there is one, moved by up to a few ulps, or anywhere along the ray.
        const auto roots = detail::exact_curved_crossings_in_unit(r, s, false, false, {false, false}, 2, detail::reach_of(r, s));
        double t = std::ldexp(std::abs(u(rng)), int(10 * u(rng))) * radius / length(d);
        if (roots.count > 0 && i % 4 != 0) {
            t = roots.item[rng() % roots.count].t;
            for (int k = int(rng() % 5); k > 0; --k) t = rng() & 1 ? std::nextafter(t, 1e300) : std::nextafter(t, -1e300);
            ++near_roots;
        }
        if (!detail::all_within_static_range(r.origin, r.direction, s.center, s.radius, t)) continue;
        const detail::Estimate<double> f = quick_residual_f(s, r, t, Part::surface, detail::AsBuiltProducts{});
        using E = Expansion<double>;
        const E exact = residual(s, detail::lift<E>(r.origin), detail::lift<E>(r.direction), E{t}, Part::surface).f;
        ASSERT_TRUE(exact.exact());
        EXPECT_GE((exact - E{f.v} + E{f.e}).sign(), 0) << i;
        EXPECT_LE((exact - E{f.v} - E{f.e}).sign(), 0) << i;
        // As the query takes it: hardware FMA where the CPU has one (quick_f_estimate).
        const detail::Estimate<double> g = detail::quick_f_estimate(detail::PartCoefficients<Sphere<double>>{&s, &r, Part::surface}, t);
        EXPECT_GE((exact - E{g.v} + E{g.e}).sign(), 0) << i;
        EXPECT_LE((exact - E{g.v} - E{g.e}).sign(), 0) << i;
        EXPECT_LT(g.e, 1.01 * f.e) << i;  // the same bound, up to its own roundings
        double m = radius * radius;  // F's magnitude: Σ(|o − c| + |t·d|)² + r², per component
        for (int a = 0; a < 3; ++a) {
            const double size = std::abs((&r.origin.x)[a] - (&s.center.x)[a]) + std::abs(t * (&r.direction.x)[a]);
            m += size * size;
        }
        EXPECT_LT(f.e, 0x1p-98 * m + 0x1p-52 * std::abs(f.v)) << i;  // u²-sized, plus v's own rounding
        ++checked;
    }
    EXPECT_GT(checked, 15000);
    EXPECT_GT(near_roots, 5000);
}

// Non-finite inputs, and coefficients beyond 2^±400, leave the quick lane to the rescaled exact
// path; large spheres whose coefficients stay within it do not.
TEST(MagnitudeFilter, QuickLaneDeclinesOutOfRange)
{
    const Ray<float> r{{0.0f, 0.0f, -4.0f}, {0.0f, 0.0f, 1.0f}};
    const float inf = std::numeric_limits<float>::infinity(), nan = std::numeric_limits<float>::quiet_NaN();
    EXPECT_TRUE(quick_curved(r, Sphere<float>{{0.0f, 0.0f, 0.0f}, 1.0f}, false, false, {false, false}, 2));
    EXPECT_TRUE(quick_curved(r, Sphere<float>{{0.0f, 0.0f, 0.0f}, 0x1p81f}, false, false, {false, false}, 2));
    EXPECT_TRUE(quick_curved(r, Sphere<float>{{0.0f, 0.0f, 0.0f}, 0x1p120f}, false, false, {false, false}, 2));
    // From 2^120 away along a direction of length 2^100: b² ~ 2^442.
    EXPECT_FALSE(quick_curved(Ray<float>{{0.0f, 0.0f, -0x1p120f}, {0.0f, 0.0f, 0x1p100f}}, Sphere<float>{{0.0f, 0.0f, 0.0f}, 1.0f}, false, false, {false, false}, 2));
    EXPECT_FALSE(quick_curved(r, Sphere<float>{{0.0f, 0.0f, 0.0f}, inf}, false, false, {false, false}, 2));
    EXPECT_FALSE(quick_curved(r, Sphere<float>{{nan, 0.0f, 0.0f}, 1.0f}, false, false, {false, false}, 2));
    EXPECT_FALSE(quick_curved(Ray<float>{{0.0f, 0.0f, -4.0f}, {0.0f, 0.0f, inf}}, Sphere<float>{{0.0f, 0.0f, 0.0f}, 1.0f}, false, false, {false, false}, 2));
}

// The closest hit and all crossings take the same lane: with a direction component 2^-63 beside
// 1 the exact path's certificates were not trusted then (t_error was the a-posteriori bound), and
// the quick lane once answered the closest hit alone (t_error one ulp), so intersect and
// intersect_all's first passage differed (sphere libFuzzer harness).
TEST(MagnitudeFilter, ClosestHitAndAllCrossingsAgreeInEveryField)
{
    const Ray<float> r{{0.0f, 0x1p-63f, -0x1.a24e54p+44f}, {0.0f, 0.0f, 1.0f}};
    const Sphere<float> s{{-0x1.490764p-43f, 0x1p-63f, -0x1.509p-1f}, 0x1.a24e54p+43f};
    expect_first_passage_is_closest_hit(r, s);
}

// The flat primitives' quick lane against the double exact path on the same (widened) inputs,
// which never takes it: the same decisions, and each float t the correctly rounded root. The
// double t is the root rounded to double; rounding it again to float gives the same float unless
// it lies exactly on a float midpoint. Scales as above, with windows that cut the root and rays
// nearly parallel to the plane (cancellation in d·n).
template <class T>
Vec3<T> widened(const Vec3<float>& v)
{
    return {T(v.x), T(v.y), T(v.z)};
}

template <class FloatPrim, class DoublePrim, class Quick>
void expect_flat_lane_agrees(const char* what, const Ray<float>& r, const FloatPrim& prim, const DoublePrim& wide, const Quick& quick,
                             int& answered, int i)
{
    const Ray<double> wide_ray{widened<double>(r.origin), widened<double>(r.direction), double(r.tmin), double(r.tmax)};
    const Crossings<double> reference = crossings(accurate, wide_ray, wide);
    const Crossings<float> full = crossings(accurate, r, prim);
    const std::optional<Crossings<float>> lane =
        quick_flat_lane(r, quick, detail::PartCoefficients<FloatPrim>{&prim, &r, Part::surface});
    answered += lane.has_value();
    for (const Crossings<float>* c : {&full, lane ? &*lane : nullptr}) {
        if (!c) continue;
        ASSERT_EQ(c->count, reference.count) << what << ' ' << i << (c == &full ? " (accurate)" : " (quick lane)");
        if (reference.count == 0) continue;
        const float t = c->item[0].t;
        const double exact_t = reference.item[0].t;
        if (float(exact_t) != t) {
            const float other = float(exact_t);
            EXPECT_EQ(exact_t, (double(t) + double(other)) / 2) << what << ' ' << i << ": " << t << " vs " << exact_t;
        }
        EXPECT_EQ(c->item[0].entering, reference.item[0].entering) << what << ' ' << i;
    }
}

// A random flat scene in T: a point c, normal n and edges e0, e1 at `scale`, a radius, and a ray
// aimed near c, every eighth nearly in the plane (slope `parallel` against 1), every fourth with a
// window that cuts the root.
template <class T>
struct FlatScene {
    Vec3<T> c, n, e0, e1;
    T radius;
    Ray<T> ray;
};
template <class T>
FlatScene<T> random_flat_scene(std::mt19937_64& rng, int i, int spread, double parallel)
{
    std::uniform_real_distribution<double> u(-1, 1), lg(-3, 3);
    const double scale = i % 4 == 3 ? std::ldexp(1.0, int(spread * u(rng))) : std::pow(10.0, lg(rng));
    const auto point = [&](double k) { return Vec3<T>{T(k * u(rng)), T(k * u(rng)), T(k * u(rng))}; };
    FlatScene<T> f;
    f.c = point(scale), f.n = point(1 + std::abs(u(rng))), f.e0 = point(scale), f.e1 = point(scale);
    f.radius = T(scale * (0.1 + std::abs(u(rng))));
    f.ray = {point(4 * scale), {}};
    f.ray.direction = f.c + point(1.2 * scale) - f.ray.origin;
    if (i % 8 == 5) f.ray.direction = cross(f.n, point(1)) + Vec3<T>{T(parallel * u(rng)), T(0), T(0)};
    if (i % 4 == 1) f.ray.tmin = T(std::abs(u(rng))), f.ray.tmax = T(1 + std::abs(u(rng)));
    return f;
}

TEST(MagnitudeFilter, FlatQuickLaneAgreesWithTheDoublePath)
{
    std::mt19937_64 rng(0xF1A7);
    int rays = 0, answered = 0;
    for (int i = 0; i < 8000; ++i) {
        const FlatScene<float> f = random_flat_scene<float>(rng, i, 60, 0x1p-20);
        const auto &c = f.c, &n = f.n, &e0 = f.e0, &e1 = f.e1;
        const auto& radius = f.radius;
        const auto& r = f.ray;
        const Plane<float> plane{c, n};
        const Disk<float> disk{c, n, radius};
        const Triangle<float> tri{c, c + e0, c + e1};
        const Parallelogram<float> quad{c, e0, e1};
        rays += 4;
        expect_flat_lane_agrees("plane", r, plane, Plane<double>{widened<double>(c), widened<double>(n)},
                                [&] { return detail::quick_flat(r, plane); }, answered, i);
        expect_flat_lane_agrees("disk", r, disk, Disk<double>{widened<double>(c), widened<double>(n), double(radius)},
                                [&] { return detail::quick_flat(r, disk); }, answered, i);
        expect_flat_lane_agrees("triangle", r, tri, Triangle<double>{widened<double>(tri.a), widened<double>(tri.b), widened<double>(tri.c)},
                                [&] { return detail::quick_flat(r, tri); }, answered, i);
        expect_flat_lane_agrees("parallelogram", r, quad, Parallelogram<double>{widened<double>(c), widened<double>(e0), widened<double>(e1)},
                                [&] { return detail::quick_flat(r, quad); }, answered, i);
    }
    EXPECT_GT(answered, rays * 90 / 100);
}

// The flat lane on double inputs (a double-word Newton step for t) against the double exact path,
// reached by the same inputs with every length scaled by 2^200: beyond the static filter's range,
// where the lane declines. Scaling lengths scales the exact root by 2^200 and commutes with
// rounding, so the answers must be equal bit for bit.
template <class Prim>
Prim scaled_lengths(const Prim& p, double s);
template <>
Plane<double> scaled_lengths(const Plane<double>& p, double s) { return {s * p.point, p.normal}; }
template <>
Disk<double> scaled_lengths(const Disk<double>& p, double s) { return {s * p.center, p.normal, s * p.radius}; }
template <>
Triangle<double> scaled_lengths(const Triangle<double>& p, double s) { return {s * p.a, s * p.b, s * p.c}; }
template <>
Parallelogram<double> scaled_lengths(const Parallelogram<double>& p, double s) { return {s * p.corner, s * p.edge0, s * p.edge1}; }

template <class Prim>
void expect_double_lane_agrees(const char* what, const Ray<double>& r, const Prim& prim, int& answered, int i)
{
    constexpr double s = 0x1p200;
    const Ray<double> far{s * r.origin, r.direction, s * r.tmin, s * r.tmax};
    const Crossings<double> reference = crossings(accurate, far, scaled_lengths(prim, s));
    ASSERT_TRUE(!quick_flat_lane(far, [&] { return detail::quick_flat(far, scaled_lengths(prim, s)); },
                                             detail::PartCoefficients<Prim>{&prim, &far, Part::surface}))
        << "the reference took the lane";
    const std::optional<Crossings<double>> lane =
        quick_flat_lane(r, [&] { return detail::quick_flat(r, prim); }, detail::PartCoefficients<Prim>{&prim, &r, Part::surface});
    answered += lane.has_value();
    const Crossings<double> full = crossings(accurate, r, prim);
    for (const Crossings<double>* c : {&full, lane ? &*lane : nullptr}) {
        if (!c) continue;
        ASSERT_EQ(c->count, reference.count) << what << ' ' << i << (c == &full ? " (accurate)" : " (quick lane)");
        if (reference.count == 0) continue;
        EXPECT_EQ(c->item[0].t, reference.item[0].t / s) << what << ' ' << i;
        EXPECT_EQ(c->item[0].entering, reference.item[0].entering) << what << ' ' << i;
    }
}

// A ray through a point exactly on a triangle's or parallelogram's edge, or on a disk's rim: the
// trim's exact value is 0 (inside) with nonzero magnitude, which no filter can decide. The lane
// must decline, never report a miss, and accurate finds the hit at t = 2.
template <class T>
void expect_lane_declines_on_the_boundary()
{
    const Vec3<T> a{T(0.25), T(0.125), T(0.25)}, d{T(0.125), T(0.25), T(-1)};
    const Vec3<T> on_edge{T(0.75), T(0.125), T(0.25)};  // on the edge from a along x
    const Ray<T> r{on_edge - T(2) * d, d};
    const Triangle<T> tri{a, a + Vec3<T>{T(1), T(0), T(0)}, a + Vec3<T>{T(0), T(1), T(0.5)}};
    const Parallelogram<T> quad{a, {T(1), T(0), T(0)}, {T(0), T(1), T(0.5)}};
    const Disk<T> disk{a, {T(0), T(0), T(1)}, T(0.5)};
    const auto check = [&](const char* what, const auto& prim) {
        using Prim = std::decay_t<decltype(prim)>;
        const auto lane = quick_flat_lane(r, [&] { return detail::quick_flat(r, prim); },
                                                      detail::PartCoefficients<Prim>{&prim, &r, Part::surface});
        EXPECT_FALSE(lane.has_value()) << what;
        const Crossings<T> c = crossings(accurate, r, prim);
        ASSERT_EQ(c.count, 1) << what;
        EXPECT_EQ(c.item[0].t, T(2)) << what;
    };
    check("triangle", tri);
    check("parallelogram", quad);
    check("disk", disk);
}

TEST(MagnitudeFilter, FlatQuickLaneDeclinesOnTheBoundary)
{
    expect_lane_declines_on_the_boundary<float>();
    expect_lane_declines_on_the_boundary<double>();
}

TEST(MagnitudeFilter, FlatQuickLaneInDoubleAgreesWithTheExactPath)
{
    std::mt19937_64 rng(0xD0B1E);
    int rays = 0, answered = 0;
    for (int i = 0; i < 6000; ++i) {
        const FlatScene<double> f = random_flat_scene<double>(rng, i, 40, 0x1p-40);
        rays += 4;
        expect_double_lane_agrees("plane", f.ray, Plane<double>{f.c, f.n}, answered, i);
        expect_double_lane_agrees("disk", f.ray, Disk<double>{f.c, f.n, f.radius}, answered, i);
        expect_double_lane_agrees("triangle", f.ray, Triangle<double>{f.c, f.c + f.e0, f.c + f.e1}, answered, i);
        expect_double_lane_agrees("parallelogram", f.ray, Parallelogram<double>{f.c, f.e0, f.e1}, answered, i);
    }
    EXPECT_GT(answered, rays * 90 / 100);
}

// The same lanes on axial primitives (open and capped cylinders, cones and frustums; for float,
// the static filter's lane and then the running bounds' where it declines): the exact
// path's span logic on certified signs and correctly rounded ends (QuickSolid) against the exact
// path itself. Rays aim at the primitive's bounding box, some along the axis's direction (the
// slab's comparisons with the side's roots), with windows that cut the crossings.
template <class T>
void expect_axial_lane_agrees()
{
    std::mt19937_64 rng(0xA71A);
    std::uniform_real_distribution<double> u(-1, 1), lg(-3, 3);
    int rays = 0, answered = 0, crossings_seen = 0, caps_seen = 0, asked[2] = {0, 0}, decided[2] = {0, 0};
    for (int i = 0; i < 16000; ++i) {
        const double scale = i % 4 == 3 ? std::ldexp(1.0, int(60 * u(rng))) : std::pow(10.0, lg(rng));
        const auto point = [&](double s) { return Vec3<T>{T(s * u(rng)), T(s * u(rng)), T(s * u(rng))}; };
        const Vec3<T> p0 = point(scale), p1 = p0 + point(scale);
        const T r0 = T(scale * (0.1 + std::abs(u(rng)))), r1 = i % 3 == 0 ? T(0) : T(scale * (0.1 + std::abs(u(rng))));
        const Caps caps = i % 2 == 0 ? Caps::both : Caps::none;
        Ray<T> r{point(4 * scale), {}};
        r.direction = p0 + point(1.5 * scale) - r.origin;
        if (i % 8 == 5) r.direction = (p1 - p0) + point(0.01 * scale);  // nearly along the axis
        if (i % 4 == 1) r.tmin = T(std::abs(u(rng))), r.tmax = T(1 + std::abs(u(rng)));
        const auto check = [&](const auto& prim, detail::CapEnds ends, const char* what) {
            const T reach = detail::reach_of(r, prim);
            const int type = what[1] == 'y' ? 0 : 1;
            for (const int limit : {1, 2}) {
                ++rays, ++asked[type];
                auto quick = quick_curved(r, prim, true, prim.caps == Caps::both, ends, limit);
                if (!quick) quick = running_bound(r, prim, true, prim.caps == Caps::both, ends, limit);
                if (!quick) continue;
                ++answered, ++decided[type];
                const auto exact = detail::exact_curved_crossings_in_unit(r, prim, true, prim.caps == Caps::both, ends, limit, reach);
                ASSERT_EQ(quick->count, exact.count) << what << ' ' << i << " limit " << limit;
                for (int k = 0; k < exact.count; ++k) {
                    EXPECT_EQ(quick->item[k].t, exact.item[k].t) << what << ' ' << i << " crossing " << k;
                    EXPECT_EQ(quick->item[k].part, exact.item[k].part) << what << ' ' << i << " crossing " << k;
                    EXPECT_EQ(quick->item[k].entering, exact.item[k].entering) << what << ' ' << i << " crossing " << k;
                    crossings_seen += 1;
                    caps_seen += exact.item[k].part != Part::surface;
                }
            }
        };
        check(Cylinder<T>{p0, p1, r0, caps}, detail::CapEnds{true, true}, "cylinder");
        check(Cone<T>{p0, r0, p1, r1, caps}, detail::CapEnds{r0 > T(0), r1 > T(0)}, "cone");
    }
    // The lanes answer nearly every ray, cones included (every float ray here; double 99.93%).
    // Their coefficients cancel (magnitudes up to 10^6 times the values). While the
    // discriminant's bound came from the magnitudes, float roots' intervals were often wider
    // than half an ulp: 97% of cylinders and 83% of cones were answered; with its own running
    // bound, 99.8% and 99.7%; with the float lane's second try on running bounds, all.
    EXPECT_GT(decided[0], asked[0] * 999 / 1000) << "cylinders";
    EXPECT_GT(decided[1], asked[1] * 999 / 1000) << "cones";
    EXPECT_GT(crossings_seen, rays / 8);
    EXPECT_GT(caps_seen, crossings_seen / 10);
}

TEST(MagnitudeFilter, AxialQuickLaneAgreesWithTheExactPath) { expect_axial_lane_agrees<float>(); }
TEST(MagnitudeFilter, DoubleAxialQuickLaneAgreesWithTheExactPath) { expect_axial_lane_agrees<double>(); }

// A double axial primitive's first crossing straight from plain estimates and Newton steps
// (axial_first_crossing), where it is hardest to certify: rays through points off a rim (2^-52
// to 2^-8 of the size radially, 2^-67 to 2^-8 or 0 along the axis), where the side meets a cap
// plane, so that the side's root and the cap's lie ulps apart, and rays whose lines pass that
// close to tangency with the side; cylinders, frustums and cones with an apex (an end no cap
// closes). Where the lane answers, it answers what the exact path does: hit or miss, the crossing
// bit for bit, its part and direction. Each of its answers is exercised (about 60% of these rays
// answered at writing): entering through the side or a cap, leaving an open one through its side
// after entering through an open end, and none (some windows end short of the surface).
TEST(MagnitudeFilter, DoubleAxialLaneAgreesNearRimsAndTangency)
{
    std::mt19937_64 rng(0xA7E5);
    std::uniform_real_distribution<double> u(-1, 1);
    int answered = 0, sides = 0, caps = 0, exits = 0, misses = 0, rays = 0;
    for (int i = 0; i < 12000; ++i) {
        const Vec3<double> p0{u(rng), u(rng), u(rng)};
        const Vec3<double> axis = normalize(Vec3<double>{u(rng), u(rng), u(rng)}) * (0.5 + std::abs(u(rng)));
        const Vec3<double> p1 = p0 + axis;
        const double r0 = 0.2 + std::abs(u(rng)), r1 = i % 3 == 0 ? r0 : 0.2 + std::abs(u(rng));
        const Caps capped = i % 4 == 0 ? Caps::none : Caps::both;
        const Vec3<double> radial = normalize(cross(axis, Vec3<double>{u(rng), u(rng), u(rng)}));
        const double eps = (rng() & 1 ? 1.0 : -1.0) * std::ldexp(1.0, -8 - int(rng() % 45));
        const double along = i % 6 == 0 ? 0.0 : (rng() & 1 ? 1.0 : -1.0) * std::ldexp(1.0, -8 - int(rng() % 60));
        Vec3<double> through, d;
        if (i % 2 == 0) {
            // Near a rim, from any direction.
            const bool far_end = rng() & 1;
            through = (far_end ? p1 : p0) + ((far_end ? r1 : r0) * (1 + eps)) * radial + along * axis;
            d = normalize(Vec3<double>{u(rng), u(rng), u(rng)});
        } else {
            // Grazing the side: the line's closest approach to the axis near the surface.
            const double h = std::abs(u(rng));
            through = p0 + h * axis + ((r0 + h * (r1 - r0)) * (1 + eps)) * radial;
            d = normalize(cross(radial, axis) + 0.3 * u(rng) * axis);
        }
        Ray<double> r{through - 3.0 * d, d};
        if (i % 5 == 1) r.tmax = 2.9;  // ending short of the point near the surface: often no crossing
        const auto check = [&](const auto& prim, detail::CapEnds ends) {
            ++rays;
            const auto lane = axial_first(r, prim, prim.caps == Caps::both, ends, 1);
            if (!lane) return;
            ++answered;
            const auto exact = detail::exact_curved_crossings_in_unit(r, prim, true, prim.caps == Caps::both, ends, 1, detail::reach_of(r, prim));
            ASSERT_EQ(lane->count, exact.count) << i;
            if (exact.count == 0) {
                ++misses;
                return;
            }
            EXPECT_EQ(lane->item[0].t, exact.item[0].t) << i;
            EXPECT_EQ(lane->item[0].part, exact.item[0].part) << i;
            EXPECT_EQ(lane->item[0].entering, exact.item[0].entering) << i;
            (exact.item[0].part == Part::surface ? sides : caps) += 1;
            exits += !exact.item[0].entering;
        };
        check(Cylinder<double>{p0, p1, r0, capped}, detail::CapEnds{true, true});
        check(Cone<double>{p0, r0, p1, r1, capped}, detail::CapEnds{true, true});
        check(Cone<double>{p0, r0, p1, 0.0, capped}, detail::CapEnds{true, false});
    }
    EXPECT_GT(answered, rays / 3);
    EXPECT_GT(sides, rays / 20);
    EXPECT_GT(caps, rays / 20);
    EXPECT_GT(misses, rays / 50);
    EXPECT_GT(exits, rays / 100);
}

// The Newton steps' F(t) by hardware FMA (where the CPU has one, whatever the build targets) and
// by the build's own products: every accurate record the same, bit for bit, on random rays at
// every primitive with a double quick lane (the correctly rounded root is unique; a step that
// cannot certify it leaves it to the exact path either way).
TEST(MagnitudeFilter, FusedAndBuiltProductsGiveTheSameRecords)
{
#if defined(RAYQ_FMA_DISPATCH)
    if (!detail::cpu_has_fma()) GTEST_SKIP() << "this CPU has no FMA";
    std::mt19937_64 rng(0xF3A);
    std::uniform_real_distribution<double> u(-1, 1);
    const auto v = [&] { return Vec3<double>{u(rng), u(rng), u(rng)}; };
    int hits = 0, rays = 0;
    const auto same = [&](const auto& prim, const Ray<double>& r) {
        detail::use_fused_products = true;
        const auto fused = intersect(accurate, r, prim);
        detail::use_fused_products = false;
        const auto built = intersect(accurate, r, prim);
        detail::use_fused_products = true;
        ++rays;
        ASSERT_EQ(fused.has_value(), built.has_value()) << rays;
        if (!fused) return;
        ++hits;
        EXPECT_EQ(fused->t, built->t) << rays;
        EXPECT_EQ(fused->t_error, built->t_error) << rays;
        EXPECT_EQ(fused->part, built->part) << rays;
        EXPECT_EQ(fused->front_face, built->front_face) << rays;
        for (int k = 0; k < 3; ++k) {
            EXPECT_EQ((&fused->point.x)[k], (&built->point.x)[k]) << rays;
            EXPECT_EQ((&fused->normal.x)[k], (&built->normal.x)[k]) << rays;
            EXPECT_EQ((&fused->point_error.x)[k], (&built->point_error.x)[k]) << rays;
        }
    };
    for (int i = 0; i < 3000; ++i) {
        const Vec3<double> c = v(), a = normalize(v()), o = c + 4.0 * normalize(v());
        const Ray<double> r{o, normalize(c + 0.8 * v() - o)};
        same(Plane<double>{c, a}, r);
        same(Disk<double>{c, a, 0.7}, r);
        same(Triangle<double>{c, c + v(), c + v()}, r);
        same(Parallelogram<double>{c, v(), v()}, r);
        same(Sphere<double>{c, 0.8}, r);
        same(Cylinder<double>{c - 0.5 * a, c + 0.5 * a, 0.6, Caps::both}, r);
        same(Cone<double>{c - 0.5 * a, 0.7, c + 0.5 * a, 0.3, Caps::both}, r);
    }
    detail::use_fused_products = detail::cpu_has_fma();
    EXPECT_GT(hits, rays / 4);
#else
    GTEST_SKIP() << "the build targets FMA, or is not GCC or clang on x86: no run-time choice";
#endif
}

}  // namespace
}  // namespace rayq::test::magnitude_filter_test
