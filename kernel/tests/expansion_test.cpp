// Shewchuk expansions (detail/expansion.hpp), the exact arithmetic under every accurate decision,
// against integer arithmetic: on dyadic inputs whose exact sums and products fit a 128-bit integer
// once scaled by a power of two, the components must add up to exactly the integer result, stay
// ordered and nonoverlapping, and give its sign. Sums of terms 2^±900 apart take the components
// past their inline storage onto the heap, and must cancel to exactly zero.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include <rayq/detail/expansion.hpp>

namespace rayq::detail::expansion_test {
namespace {

__extension__ typedef __int128 Int;  // NOLINT: GCC and clang's 128-bit integer, exact up to 2^127

// x·2^shift as an integer; x must be a multiple of 2^-shift with |x·2^shift| < 2^126.
Int scaled(double x, int shift)
{
    const double y = std::ldexp(x, shift);
    EXPECT_EQ(y, std::floor(y)) << x;
    return Int(y);
}

int sign(Int x) { return x > 0 ? 1 : (x < 0 ? -1 : 0); }

// The values of x's highest and lowest set bits.
double highest_bit(double x)
{
    int e;
    std::frexp(x, &e);
    return std::ldexp(1.0, e - 1);
}
double lowest_bit(double x)
{
    int e;
    const double m = std::frexp(std::abs(x), &e);
    const auto bits = static_cast<unsigned long long>(std::ldexp(m, 53));
    return std::ldexp(1.0, e - 53 + __builtin_ctzll(bits));
}

// Components increasing and nonoverlapping: each one's highest bit below the next one's lowest.
void expect_nonoverlapping(const Expansion<double>& e)
{
    double previous = 0;
    for (double c : e) {
        ASSERT_NE(c, 0.0);
        if (previous != 0) {
            EXPECT_LT(highest_bit(previous), lowest_bit(c)) << previous << " then " << c;
        }
        previous = c;
    }
}

// The value, ordering and sign of e against the exact integer (scaled by 2^shift).
void expect_exact(const Expansion<double>& e, Int exact, int shift)
{
    expect_nonoverlapping(e);
    Int sum = 0;
    for (double c : e) sum += scaled(c, shift);
    EXPECT_TRUE(sum == exact);
    EXPECT_EQ(e.sign(), sign(exact));
}

// ±m·2^k with a random odd m < 2^bits.
double dyadic(std::mt19937_64& rng, int bits, int lo, int hi)
{
    const double m = double((rng() >> (64 - bits)) | 1);
    const double x = std::ldexp(m, std::uniform_int_distribution<int>(lo, hi)(rng));
    return rng() & 1 ? -x : x;
}

TEST(Expansion, SumsAreExact)
{
    std::mt19937_64 rng(0xE4);
    for (int round = 0; round < 500; ++round) {
        Expansion<double> e;
        Int exact = 0;
        for (int i = 0; i < 40; ++i) {
            const double x = dyadic(rng, 8, -60, 40);  // |x| < 2^48, a multiple of 2^-60
            if (i % 3 == 2) e = e - Expansion<double>(x), exact -= scaled(x, 64);
            else e += Expansion<double>(x), exact += scaled(x, 64);
        }
        expect_exact(e, exact, 64);
        expect_exact(-e, -exact, 64);
    }
}

// Terms 2^±900 apart need dozens of components (more than the 16 stored inline); subtracting
// them again in another order must leave exactly zero.
TEST(Expansion, WideSumsSpillToTheHeapAndCancelExactly)
{
    std::mt19937_64 rng(0xE6);
    std::size_t largest = 0;
    for (int round = 0; round < 200; ++round) {
        std::vector<double> terms;
        Expansion<double> e;
        for (int i = 0; i < 40; ++i) {
            terms.push_back(dyadic(rng, 8, -900, 900));
            e += Expansion<double>(terms.back());
            largest = std::max(largest, e.size());
            expect_nonoverlapping(e);
        }
        std::shuffle(terms.begin(), terms.end(), rng);
        for (double x : terms) e = e - Expansion<double>(x);
        EXPECT_EQ(e.size(), 0u);
        EXPECT_EQ(e.sign(), 0);
    }
    EXPECT_GT(largest, 16u);
}

TEST(Expansion, ProductsAndDifferencesOfProductsAreExact)
{
    std::mt19937_64 rng(0xE5);
    for (int round = 0; round < 2000; ++round) {
        // Four monomials a·b·c with a, b, c = m·2^k, m < 2^20, |k| <= 10: each a multiple of 2^-30
        // below 2^90, so their sum scaled by 2^30 stays below 2^122.
        Expansion<double> e;
        Int exact = 0;
        for (int term = 0; term < 4; ++term) {
            const double a = dyadic(rng, 20, -10, 10), b = dyadic(rng, 20, -10, 10), c = dyadic(rng, 20, -10, 10);
            const Expansion<double> product = Expansion<double>(a) * Expansion<double>(b) * Expansion<double>(c);
            expect_exact(product, scaled(a, 10) * scaled(b, 10) * scaled(c, 10), 30);
            if (term % 2) e = e - product, exact -= scaled(a, 10) * scaled(b, 10) * scaled(c, 10);
            else e += product, exact += scaled(a, 10) * scaled(b, 10) * scaled(c, 10);
        }
        expect_exact(e, exact, 30);
        // Cancellation to exactly zero, and a product of two multi-component expansions.
        expect_exact(e - e, 0, 30);
        const double x = dyadic(rng, 12, -10, 0);  // (x + x·2^-40)² is a multiple of 2^-100 below 2^24
        Expansion<double> wide = Expansion<double>(x) + Expansion<double>(std::ldexp(x, -40));
        expect_exact(wide * wide, (scaled(x, 50) + scaled(std::ldexp(x, -40), 50)) * (scaled(x, 50) + scaled(std::ldexp(x, -40), 50)), 100);
    }
}

}  // namespace
}  // namespace rayq::detail::expansion_test
