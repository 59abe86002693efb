// The static filter (detail/magnitude.hpp) and the accurate policy's quick lane for float spheres
// (detail/exact_crossings.hpp, quick_side_crossings): the filter's bound holds against exact
// expansion arithmetic, and the quick lane answers exactly what the full exact path does.
#include "test_support.hpp"

#include <cmath>
#include <random>

#include <rayq/detail/expansion.hpp>
#include <rayq/detail/magnitude.hpp>

namespace rayq::test {
namespace {

using detail::Expansion;
using detail::Magnitude;

// A float with a random sign, significand and exponent in [lo, hi].
float random_float(std::mt19937_64& rng, int lo, int hi)
{
    std::uniform_real_distribution<double> m(1, 2);
    std::uniform_int_distribution<int> e(lo, hi);
    const float x = float(std::ldexp(m(rng), e(rng)));
    return rng() & 1 ? -x : x;
}

// |exact − v| <= bound, decided exactly: bound − |v − E| >= 0 as expansions.
bool bound_holds(const Magnitude<double>& x, const Expansion<double>& exact)
{
    const Expansion<double> diff = Expansion<double>(x.v) - exact;
    const Expansion<double> b(x.bound());
    return (b - diff).sign() >= 0 && (b + diff).sign() >= 0;
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
        Sphere<float> s{{random_float(rng, -spread, spread), random_float(rng, -spread, spread), random_float(rng, -spread, spread)},
                        std::abs(random_float(rng, -spread, spread))};
        Ray<float> r{{random_float(rng, -spread, spread), random_float(rng, -spread, spread), random_float(rng, -spread, spread)},
                     {random_float(rng, -spread, spread), random_float(rng, -spread, spread), random_float(rng, -spread, spread)}};
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

// The quick lane, where it answers, gives the full exact path's crossings (count, t bit for bit,
// part, direction, certification), for the closest crossing and for both; and it answers on nearly
// every generic ray.
TEST(MagnitudeFilter, QuickLaneAgreesWithTheExactPath)
{
    std::mt19937_64 rng(0x5E7);
    std::uniform_real_distribution<double> u(-1, 1), lg(-3, 3);
    int rays = 0, answered = 0;
    for (int i = 0; i < 20000; ++i) {
        // Mostly ordinary scales; every fourth query far from 1 (2^±60), where the quick lane
        // still answers as long as the coefficients stay within 2^±400.
        const double scale = i % 4 == 3 ? std::ldexp(1.0, int(60 * u(rng))) : std::pow(10.0, lg(rng));
        const Sphere<float> s{{float(scale * u(rng)), float(scale * u(rng)), float(scale * u(rng))}, float(scale * (0.1 + std::abs(u(rng))))};
        const Vec3<float> o{float(4 * scale * u(rng)), float(4 * scale * u(rng)), float(4 * scale * u(rng))};
        const Vec3<float> aim{float(s.center.x + 1.2 * s.radius * u(rng)), float(s.center.y + 1.2 * s.radius * u(rng)),
                              float(s.center.z + 1.2 * s.radius * u(rng))};
        Ray<float> r{o, aim - o};
        if (i % 4 == 1) r.tmin = float(std::abs(u(rng))), r.tmax = float(1 + std::abs(u(rng)));  // windows that cut the roots
        const float reach = detail::length_profile(r, s).reach;
        for (const int limit : {1, 2}) {
            ++rays;
            const auto quick = detail::quick_side_crossings(r, s, limit);
            if (!quick) continue;
            ++answered;
            const auto exact = detail::exact_curved_crossings_in_unit(r, s, false, false, {false, false}, limit, reach);
            ASSERT_EQ(quick->count, exact.count) << i;
            for (int k = 0; k < exact.count; ++k) {
                EXPECT_EQ(quick->item[k].t, exact.item[k].t) << i << " crossing " << k;
                EXPECT_EQ(quick->item[k].part, exact.item[k].part) << i;
                EXPECT_EQ(quick->item[k].entering, exact.item[k].entering) << i;
            }
        }
    }
    EXPECT_GT(answered, rays * 95 / 100);
}

// Non-finite inputs, and coefficients beyond 2^±400, leave the quick lane to the rescaled exact
// path; large spheres whose coefficients stay within it do not.
TEST(MagnitudeFilter, QuickLaneDeclinesOutOfRange)
{
    const Ray<float> r{{0.0f, 0.0f, -4.0f}, {0.0f, 0.0f, 1.0f}};
    const float inf = std::numeric_limits<float>::infinity(), nan = std::numeric_limits<float>::quiet_NaN();
    EXPECT_TRUE(detail::quick_side_crossings(r, Sphere<float>{{0.0f, 0.0f, 0.0f}, 1.0f}, 2));
    EXPECT_TRUE(detail::quick_side_crossings(r, Sphere<float>{{0.0f, 0.0f, 0.0f}, 0x1p81f}, 2));
    EXPECT_TRUE(detail::quick_side_crossings(r, Sphere<float>{{0.0f, 0.0f, 0.0f}, 0x1p120f}, 2));
    // From 2^120 away along a direction of length 2^100: b² ~ 2^442.
    EXPECT_FALSE(detail::quick_side_crossings(Ray<float>{{0.0f, 0.0f, -0x1p120f}, {0.0f, 0.0f, 0x1p100f}}, Sphere<float>{{0.0f, 0.0f, 0.0f}, 1.0f}, 2));
    EXPECT_FALSE(detail::quick_side_crossings(r, Sphere<float>{{0.0f, 0.0f, 0.0f}, inf}, 2));
    EXPECT_FALSE(detail::quick_side_crossings(r, Sphere<float>{{nan, 0.0f, 0.0f}, 1.0f}, 2));
    EXPECT_FALSE(detail::quick_side_crossings(Ray<float>{{0.0f, 0.0f, -4.0f}, {0.0f, 0.0f, inf}}, Sphere<float>{{0.0f, 0.0f, 0.0f}, 1.0f}, 2));
}

// The closest hit and all crossings take the same lane: with a direction component 2^-63 beside
// 1 the exact path's certificates do not hold (t_error is the a-posteriori bound), and the quick
// lane once answered the closest hit alone (t_error one ulp), so intersect and intersect_all's
// first passage differed (sphere libFuzzer harness).
TEST(MagnitudeFilter, ClosestHitAndAllCrossingsAgreeInEveryField)
{
    const Ray<float> r{{0.0f, 0x1p-63f, -0x1.a24e54p+44f}, {0.0f, 0.0f, 1.0f}};
    const Sphere<float> s{{-0x1.490764p-43f, 0x1p-63f, -0x1.509p-1f}, 0x1.a24e54p+43f};
    const auto hit = intersect(accurate, r, s);
    const auto all = intersect_all(accurate, r, s);
    ASSERT_TRUE(hit);
    ASSERT_GE(all.size(), 1);
    EXPECT_EQ(all[0].hit.t, hit->t);
    EXPECT_EQ(all[0].hit.t_error, hit->t_error);
}

}  // namespace
}  // namespace rayq::test
