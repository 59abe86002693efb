// Error-free transformations: checked against long double / exact rational reasoning.
#include "test_support.hpp"

#include <algorithm>
#include <cstring>
#include <random>

#include <rayq/detail/exact.hpp>
#include <rayq/detail/ulp.hpp>

namespace rayq::test::eft_test {
namespace {

__extension__ typedef __float128 quad;  // GCC/Clang binary128: the exact reference

// next_up/next_down equal std::nextafter toward ±inf on random bit patterns and the specials, and
// the gaps to the neighbours (wider_gap, smaller_half_gap) equal the nextafter differences.
template <class T, class Bits>
void check_neighbours()
{
    std::mt19937_64 rng(0x0E1F);
    constexpr T inf = std::numeric_limits<T>::infinity();
    std::vector<T> xs = {T(0), -T(0), inf, -inf, std::numeric_limits<T>::max(), -std::numeric_limits<T>::max(),
                         std::numeric_limits<T>::min(), -std::numeric_limits<T>::min(), std::numeric_limits<T>::denorm_min(),
                         -std::numeric_limits<T>::denorm_min(), T(1), T(-1)};
    for (int i = 0; i < 100000; ++i) {
        const Bits b = static_cast<Bits>(rng());
        T x;
        std::memcpy(&x, &b, sizeof x);
        xs.push_back(x);
    }
    for (T x : xs) {
        const T up = detail::next_up(x), down = detail::next_down(x), ref_up = std::nextafter(x, inf), ref_down = std::nextafter(x, -inf);
        if (std::isnan(x)) {
            EXPECT_TRUE(std::isnan(up) && std::isnan(down));
            continue;
        }
        EXPECT_EQ(std::memcmp(&up, &ref_up, sizeof x), 0) << x;
        EXPECT_EQ(std::memcmp(&down, &ref_down, sizeof x), 0) << x;
        // wider_gap: the farther neighbour's distance (the one above |x| at a power of two; inf at ±max).
        if (std::isfinite(x)) {
            EXPECT_EQ(detail::wider_gap(x), std::max(ref_up - x, x - ref_down)) << x;
        }
        // smaller_half_gap: half the nearer neighbour's distance (the one below |x| at a power of two).
        if (x == T(0)) {
            EXPECT_TRUE(std::isnan(detail::smaller_half_gap(x)));
        } else if (std::isfinite(x)) {
            EXPECT_EQ(detail::smaller_half_gap(x), std::min(ref_up - x, x - ref_down) / T(2)) << x;
        }
    }
}

TEST(ErrorFreeTransformations, NextUpDownAndTheGapsEqualNextafters)
{
    check_neighbours<float, std::uint32_t>();
    check_neighbours<double, std::uint64_t>();
}

// rounded_between_midpoints (exact.hpp) accepts a root interval exactly when it lies strictly
// between the midpoints from t to its neighbours: both sides, at powers of two (where the lower
// neighbour is closer), FLT_MIN, FLT_MAX, subnormals and random floats of either sign.
TEST(ErrorFreeTransformations, RoundingBetweenMidpointsUsesTheNeighbours)
{
    std::mt19937 rng(0x3107);
    const float max = std::numeric_limits<float>::max(), min = std::numeric_limits<float>::min();
    std::vector<float> ts = {1.0f, 2.0f, 0.5f, 1.5f, max, min, 2 * min, 1.5f * min, std::numeric_limits<float>::denorm_min(), 0x1p-140f,
                             0x1.8p-130f, 0x1p100f, std::nextafter(1.0f, 2.0f), std::nextafter(1.0f, 0.0f)};
    for (int i = 0; i < 50000; ++i) {
        const std::uint32_t b = static_cast<std::uint32_t>(rng());
        float x;
        std::memcpy(&x, &b, sizeof x);
        if (std::isfinite(x) && x != 0.0f) ts.push_back(x);
    }
    const std::size_t n = ts.size();
    for (std::size_t i = 0; i < n; ++i) ts.push_back(-ts[i]);
    for (const float t : ts) {
        const double down = detail::next_down(t), up = detail::next_up(t);
        // ±FLT_MAX's outer midpoint is the overflow threshold, half an ulp beyond it.
        const double lo = std::isinf(down) ? double(t) - (up - double(t)) / 2 : (down + t) / 2;
        const double hi = std::isinf(up) ? double(t) + (double(t) - down) / 2 : (double(t) + up) / 2;
        for (const double s : {(double(t) - lo) / 2, -(hi - double(t)) / 2}) {  // an interval near each midpoint
            const double v = s > 0 ? lo + s : hi + s, e = std::abs(s);
            const auto inside = detail::rounded_between_midpoints<float>(detail::Bounded<double>{v, e * (1 - 0x1p-20)});
            ASSERT_TRUE(inside.has_value()) << t << ' ' << s;
            EXPECT_EQ(*inside, t);
            EXPECT_FALSE(detail::rounded_between_midpoints<float>(detail::Bounded<double>{v, e * (1 + 0x1p-20)}).has_value()) << t << ' ' << s;
        }
    }
}

TEST(ErrorFreeTransformations, TwoProductIsExact)
{
    std::mt19937_64 rng(20261122);
    std::uniform_real_distribution<double> u(-1e3, 1e3);
    for (int i = 0; i < 10000; ++i) {
        const float a = float(u(rng)), b = float(u(rng));
        const auto p = detail::two_product(a, b);
        EXPECT_EQ((double)p.hi + (double)p.lo, (double)a * (double)b);  // float products are exact in double
        const double x = u(rng), y = u(rng);
        const auto q = detail::two_product(x, y);
        EXPECT_EQ(q.hi, x * y);
        EXPECT_EQ(q.lo, std::fma(x, y, -q.hi));  // libm's fma is exact; the kernel may use Dekker's split instead
    }
}

TEST(ErrorFreeTransformations, TwoSumIsExact)
{
    const auto s = detail::two_sum(1.0, 1e-20);
    EXPECT_EQ(s.hi, 1.0);
    EXPECT_EQ(s.lo, 1e-20);
    const auto f = detail::two_sum(16777216.0f, 1.0f);
    EXPECT_EQ(f.hi, 16777216.0f);
    EXPECT_EQ(f.lo, 1.0f);
}

TEST(ErrorFreeTransformations, DifferenceOfProductsBeatsNaive)
{
    // a·b = 1 + 2^-11 + 2^-24 needs 25 bits; c·d = 1 + 2^-11. The difference is 2^-24.
    const float a = 1.0f + 0x1p-12f, b = a, c = 1.0f + 0x1p-11f, d = 1.0f;
    const double exact = double(a) * b - double(c) * d;  // float products are exact in double
    EXPECT_EQ(detail::difference_of_products(a, b, c, d), float(exact));
    EXPECT_NE(a * b - c * d, float(exact));  // the naive form rounds a·b to 1 first
    // Antisymmetric, exactly.
    EXPECT_EQ(detail::difference_of_products(c, d, a, b), -detail::difference_of_products(a, b, c, d));
}

// Dot2's bound (Ogita, Rump, Oishi 2005, Prop. 5.5): |dot2 − exact| <= u·|exact| + γ(n)²·Σ|aᵢbᵢ|,
// with u = 2^-24 and γ(n) = n·u/(1 − n·u): as if computed in twice the precision, then rounded.
TEST(ErrorFreeTransformations, CompensatedDotMeetsTwicePrecisionBound)
{
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> u(-1, 1);
    const double unit = 0x1p-24, g3 = 3 * unit / (1 - 3 * unit);
    int naive_outside = 0;
    for (int i = 0; i < 20000; ++i) {
        // Nearly orthogonal vectors: heavy cancellation.
        const Vec3<float> a{float(u(rng)), float(u(rng)), float(u(rng))};
        Vec3<float> b{float(u(rng)), float(u(rng)), 0.0f};
        b.z = a.z != 0 ? float(-(double(a.x) * b.x + double(a.y) * b.y) / a.z) : 0.0f;
        // Float products are exact in double; their sum is exact in binary128.
        const quad exact = quad(double(a.x) * b.x) + quad(double(a.y) * b.y) + quad(double(a.z) * b.z);
        const double magnitude = std::fabs(double(a.x) * b.x) + std::fabs(double(a.y) * b.y) + std::fabs(double(a.z) * b.z);
        const double bound = unit * std::fabs(double(exact)) + g3 * g3 * magnitude;
        const float got = detail::dot_compensated(a, b);
        EXPECT_LE(std::fabs(double(quad(got) - exact)), bound) << got << " vs " << double(exact);
        naive_outside += std::fabs(double(quad(dot(a, b)) - exact)) > bound;
    }
    EXPECT_GT(naive_outside, 1000);  // the case the compensated form exists for
}

}  // namespace
}  // namespace rayq::test::eft_test
