// Dyadic numbers (detail/dyadic.hpp), the accurate policy's last resort when an expansion leaves
// double's range: sums and products of dyadic inputs against 128-bit integers, values far beyond
// double's exponent range held exactly, and adaptive_sign turning to them exactly when an
// expansion says its products under- or overflowed (Expansion::exact()).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <random>

#include <rayq/detail/dyadic.hpp>
#include <rayq/detail/exact.hpp>
#include <rayq/detail/expansion.hpp>

namespace rayq::detail::dyadic_test {
namespace {

__extension__ typedef __int128 Int;  // NOLINT: GCC and clang's 128-bit integer, exact up to 2^127
__extension__ typedef unsigned __int128 UInt;  // NOLINT

int sign(Int x) { return x > 0 ? 1 : (x < 0 ? -1 : 0); }

// x's value as frexp gives it: x = mantissa·2^exponent, mantissa in [1/2, 1).
void expect_value(const Dyadic& x, double mantissa, long exponent)
{
    const auto [m, e] = x.frexp();
    EXPECT_EQ(m, mantissa);
    EXPECT_EQ(e, exponent);
}

TEST(Dyadic, SumsAndProductsOfDyadicInputsMatchIntegers)
{
    std::mt19937_64 rng(13);
    std::uniform_int_distribution<long long> mantissa(-(1LL << 30), 1LL << 30);
    std::uniform_int_distribution<int> shift(0, 20);
    for (int i = 0; i < 20000; ++i) {
        // Inputs k·2^-s with |k| < 2^30, s <= 20: exact as integers once scaled by 2^20 (or 2^40
        // for products), |a·b − c·d + e| < 2^102.
        long long k[5];
        int s[5];
        double x[5];
        for (int j = 0; j < 5; ++j) k[j] = mantissa(rng), s[j] = shift(rng), x[j] = std::ldexp(double(k[j]), -s[j]);
        const auto as_int = [&](int j, int scale) { return Int(k[j]) * (Int(1) << (scale - s[j])); };  // no shift of a negative (UB in C++17)
        const Int exact = as_int(0, 20) * as_int(1, 20) - as_int(2, 20) * as_int(3, 20) + as_int(4, 20) * (Int(1) << 20);
        const Dyadic v = Dyadic(x[0]) * Dyadic(x[1]) - Dyadic(x[2]) * Dyadic(x[3]) + Dyadic(x[4]);
        ASSERT_EQ(v.sign(), sign(exact)) << i;
        // The value itself: the integer's top bits and exponent.
        if (exact != 0) {
            const Int magnitude = exact < 0 ? -exact : exact;
            int bits = 0;
            while ((magnitude >> bits) != 0) ++bits;
            const int drop = bits > 53 ? bits - 53 : 0;
            const double top = std::ldexp(double(magnitude >> drop), -(bits - drop));  // in [1/2, 1), truncated
            const auto [m, e] = v.frexp();
            ASSERT_EQ(std::abs(m), top) << i;
            ASSERT_EQ(e, long(bits) - 40) << i;
        }
    }
}

TEST(Dyadic, HoldsValuesBeyondDoublesRange)
{
    const double max = std::numeric_limits<double>::max(), sub = std::numeric_limits<double>::denorm_min();
    // (max + 2^-1074) − max: a sum spanning 2^2098, exactly the subnormal.
    const Dyadic tiny = (Dyadic(max) + Dyadic(sub)) - Dyadic(max);
    EXPECT_EQ(tiny.sign(), 1);
    expect_value(tiny, 0.5, -1073);
    // Twelve factors of 2^-1074 (as a length of degree twelve would take): 2^-12888, positive.
    Dyadic p(1.0);
    for (int i = 0; i < 12; ++i) p = p * Dyadic(sub);
    expect_value(p, 0.5, -12888 + 1);
    // max² − max² + 2^-1074·2^-1074 is positive: the square of the subnormal survives.
    const Dyadic d = Dyadic(max) * Dyadic(max) - Dyadic(max) * Dyadic(max) + Dyadic(sub) * Dyadic(sub);
    EXPECT_EQ(d.sign(), 1);
    expect_value(d, 0.5, -2147);
    EXPECT_EQ((Dyadic(max) * Dyadic(-max) + Dyadic(max) * Dyadic(max)).sign(), 0);
    // Negation and cancellation in both orders.
    EXPECT_EQ((Dyadic(sub) - Dyadic(2 * sub)).sign(), -1);
    EXPECT_EQ((Dyadic(-0.75f) + Dyadic(0.5) + Dyadic(0.25)).sign(), 0);
}

TEST(Dyadic, LimbProductsAgreeWithThePortableForm)
{
    // multiply_add uses the compiler's 128-bit integer where there is one; the portable form of
    // four 32-bit products must give the same two words, carries at their extremes included.
    const std::uint64_t max = ~std::uint64_t(0);
    const std::uint64_t edges[] = {0, 1, 2, 0xffffffffu, 0x100000000u, max / 2, max - 1, max};
    for (std::uint64_t a : edges)
        for (std::uint64_t b : edges)
            for (std::uint64_t add : edges)
                for (std::uint64_t carry : edges) {
                    const WideProduct p = multiply_add_portable(a, b, add, carry);
                    const WideProduct q = multiply_add(a, b, add, carry);
                    ASSERT_EQ(p.lo, q.lo) << a << ' ' << b << ' ' << add << ' ' << carry;
                    ASSERT_EQ(p.hi, q.hi) << a << ' ' << b << ' ' << add << ' ' << carry;
                    const UInt exact = UInt(a) * b + add + carry;
                    ASSERT_EQ(p.lo, std::uint64_t(exact));
                    ASSERT_EQ(p.hi, std::uint64_t(exact >> 64));
                }
    std::mt19937_64 rng(5);
    for (int i = 0; i < 100000; ++i) {
        const std::uint64_t a = rng(), b = rng(), add = rng(), carry = rng();
        const WideProduct p = multiply_add_portable(a, b, add, carry);
        const UInt exact = UInt(a) * b + add + carry;
        ASSERT_EQ(p.lo, std::uint64_t(exact));
        ASSERT_EQ(p.hi, std::uint64_t(exact >> 64));
    }
}

TEST(Dyadic, ProductsOfLongSumsExpandAsPolynomials)
{
    // Sums of far-apart doubles are integers of many limbs; (a + b)(c + d) must equal the sum of
    // the four products and (a + b)² − (a − b)² = 4ab exactly, whatever the carries across limbs.
    std::mt19937_64 rng(29);
    std::uniform_int_distribution<int> exponent(-1074, 1023);
    std::uniform_real_distribution<double> unit(0.5, 1.0);
    const auto draw = [&] {
        const double x = std::ldexp(unit(rng), exponent(rng));
        return rng() % 2 ? -x : x;
    };
    for (int i = 0; i < 3000; ++i) {
        const Dyadic a = Dyadic(draw()) + Dyadic(draw()), b = Dyadic(draw()) + Dyadic(draw());
        const Dyadic c = Dyadic(draw()) + Dyadic(draw()), d = Dyadic(draw());
        ASSERT_EQ(((a + b) * (c + d) - (a * c + a * d + b * c + b * d)).sign(), 0) << i;
        ASSERT_EQ(((a + b) * (a + b) - (a - b) * (a - b) - Dyadic(4.0) * a * b).sign(), 0) << i;
        const Dyadic square = (a + b) * (a + b);
        ASSERT_EQ(square.sign(), (a + b).sign() == 0 ? 0 : 1) << i;
        // The top 53 bits of a product: those of the factors' product, rounded within 2 ulps.
        const auto [ma, ea] = a.frexp();
        const auto [mc, ec] = c.frexp();
        const auto [mp, ep] = (a * c).frexp();
        const double expected = ma * mc * (std::abs(ma * mc) < 0.5 ? 2.0 : 1.0);
        ASSERT_EQ(ep, ea + ec - (std::abs(ma * mc) < 0.5 ? 1 : 0)) << i;
        ASSERT_LE(std::abs(mp - expected), 0x1p-51) << i;
    }
}

TEST(Dyadic, NonFiniteInputsAreFlagged)
{
    const double inf = std::numeric_limits<double>::infinity();
    EXPECT_FALSE((Dyadic(inf) + Dyadic(1.0)).finite());
    EXPECT_FALSE((Dyadic(1.0) * Dyadic(std::nan(""))).finite());
    EXPECT_TRUE((Dyadic(1.0) * Dyadic(2.0)).finite());
}

TEST(Dyadic, ExpansionsSayWhenTheirProductsLeaveTheRange)
{
    using E = Expansion<double>;
    EXPECT_TRUE((E(0x1p-400) * E(0x1p-500) + E(1.0)).exact());
    EXPECT_FALSE((E(0x1p-600) * E(0x1p-600)).exact());                 // underflows to zero
    EXPECT_FALSE((E(0x1p-500) * E(0x1.0000000000001p-500)).exact());  // its error term would be subnormal
    EXPECT_FALSE((E(0x1p600) * E(0x1p600)).exact());                  // overflows
    EXPECT_FALSE((E(std::numeric_limits<double>::max()) + E(std::numeric_limits<double>::max())).exact());
    EXPECT_FALSE((E(std::numeric_limits<double>::infinity()) * E(1.0)).exact());
    EXPECT_FALSE(((E(0x1p-600) * E(0x1p-600)) + E(1.0)).exact());      // and stays so
}

TEST(Dyadic, AdaptiveSignTurnsToDyadicWhenExpansionsLeaveTheRange)
{
    // 2^-600·2^-600 − 2^-1000·2^-200: the products underflow in every floating-point stage (to zero, or
    // to a bound no filter can decide), so only Dyadic can tell that the value is 0, then 2^-1201 > 0.
    const int s = adaptive_sign<double>([](auto zero) {
        using N = decltype(zero);
        return N{0x1p-600} * N{0x1p-600} - N{0x1p-1000} * N{0x1p-200};
    });
    EXPECT_EQ(s, 0);
    const int positive = adaptive_sign<double>([](auto zero) {
        using N = decltype(zero);
        return N{0x1p-600} * N{0x1.8p-600} - N{0x1p-1000} * N{0x1p-200};
    });
    EXPECT_EQ(positive, 1);
    // 2^600·2^600 − 2^1000·2^200 overflows instead; the exact value is 0, then −2^1199.
    const int zero = adaptive_sign<double>([](auto z) {
        using N = decltype(z);
        return N{0x1p600} * N{0x1p600} - N{0x1p1000} * N{0x1p200};
    });
    EXPECT_EQ(zero, 0);
    const int negative = adaptive_sign<double>([](auto z) {
        using N = decltype(z);
        return N{0x1p600} * N{0x1p599} - N{0x1p1000} * N{0x1p200};
    });
    EXPECT_EQ(negative, -1);
}

// a·t² + b·t + c with fixed double coefficients, as a primitive's residual along a ray.
struct FixedQuadratic {
    double a, b, c;
    template <class N>
    Residual<N> operator()(N) const { return {N{c}, N{b}, N{a}}; }
    template <class N>
    Residual<N> at(N t) const { return {(N{a} * t + N{b}) * t + N{c}, N{2 * a} * t + N{b}, N{a}}; }
};

TEST(Dyadic, ExactGuessHoldsWhereTheDiscriminantUnderflows)
{
    // 2^-600·(t² + t − 2^-470): the discriminant 2^-1200·(1 + 2^-468) underflows to 0 in double and
    // double-word, whose guesses are then −1/2 and 2^-469, each a factor 2 off. The roots are
    // −1 − 2^-470 + … and 2^-470 − 2^-940 + …, which round to −1 and 2^-470.
    const ExactQuadratic<double, FixedQuadratic> q(FixedQuadratic{0x1p-600, 0x1p-600, -0x1p-1070});
    ASSERT_EQ(q.sign_disc(), 1);
    EXPECT_EQ(q.guess(1), 0x1p-469);  // what the search used to start from
    const double nan = std::numeric_limits<double>::quiet_NaN();
    EXPECT_LE(std::abs(q.exact_guess(0, nan) + 1), 0x1p-52);
    EXPECT_LE(std::abs(q.exact_guess(1, nan) - 0x1p-470), 0x1p-522);
    EXPECT_EQ(q.round(0), -1.0);
    EXPECT_EQ(q.round(1), 0x1p-470);
    // A root beyond double's range starts the search from the largest double, not from infinity.
    const ExactQuadratic<double, FixedQuadratic> far(FixedQuadratic{0x1p-600, -0x1p600, 0x1p-600});
    EXPECT_EQ(far.exact_guess(1, nan), std::numeric_limits<double>::max());
}

}  // namespace
}  // namespace rayq::detail::dyadic_test
