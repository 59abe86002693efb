// The shared solver on its own: spans for each sign structure, and the roots' accuracy where the
// textbook formula cancels.
#include "test_support.hpp"

namespace rayq::test::quadratic_test {
namespace {

template <class C>
class QuadraticTest : public ::testing::Test {};
TYPED_TEST_SUITE(QuadraticTest, AllConfigs, ConfigNames);

TYPED_TEST(QuadraticTest, TwoRootsOneSpan)
{
    using T = typename TypeParam::T;
    // (t − 1)(t − 3) = t² − 4t + 3: a = 1, b = −2, c = 3.
    const auto s = solve_quadratic(TypeParam::policy, CoefficientQuadratic<T>{T(1), T(-2), T(3)});
    ASSERT_EQ(s.count, 1);
    EXPECT_EQ(s.span[0].enter, T(1));
    EXPECT_EQ(s.span[0].exit, T(3));
}

TYPED_TEST(QuadraticTest, NegativeLeadingCoefficientGivesTwoUnboundedSpans)
{
    using T = typename TypeParam::T;
    // −(t − 1)(t − 3) < 0 outside [1, 3].
    const auto s = solve_quadratic(TypeParam::policy, CoefficientQuadratic<T>{T(-1), T(2), T(-3)});
    ASSERT_EQ(s.count, 2);
    EXPECT_EQ(s.span[0].enter, -std::numeric_limits<T>::infinity());
    EXPECT_EQ(s.span[0].exit, T(1));
    EXPECT_EQ(s.span[1].enter, T(3));
    EXPECT_EQ(s.span[1].exit, std::numeric_limits<T>::infinity());
}

TYPED_TEST(QuadraticTest, NoRealRoots)
{
    using T = typename TypeParam::T;
    EXPECT_EQ(solve_quadratic(TypeParam::policy, CoefficientQuadratic<T>{T(1), T(0), T(1)}).count, 0);  // always outside
    const auto all = solve_quadratic(TypeParam::policy, CoefficientQuadratic<T>{T(-1), T(0), T(-1)});  // always inside
    ASSERT_EQ(all.count, 1);
    EXPECT_EQ(all.span[0].enter, -std::numeric_limits<T>::infinity());
    EXPECT_EQ(all.span[0].exit, std::numeric_limits<T>::infinity());
}

TYPED_TEST(QuadraticTest, LinearAndConstant)
{
    using T = typename TypeParam::T;
    // 2·b·t + c with b = 1, c = −4: root t = 2, inside for t < 2.
    auto s = solve_quadratic(TypeParam::policy, CoefficientQuadratic<T>{T(0), T(1), T(-4)});
    ASSERT_EQ(s.count, 1);
    EXPECT_EQ(s.span[0].enter, -std::numeric_limits<T>::infinity());
    EXPECT_EQ(s.span[0].exit, T(2));
    s = solve_quadratic(TypeParam::policy, CoefficientQuadratic<T>{T(0), T(-1), T(4)});
    ASSERT_EQ(s.count, 1);
    EXPECT_EQ(s.span[0].enter, T(2));
    EXPECT_EQ(s.span[0].exit, std::numeric_limits<T>::infinity());
    EXPECT_EQ(solve_quadratic(TypeParam::policy, CoefficientQuadratic<T>{T(0), T(0), T(1)}).count, 0);
    EXPECT_EQ(solve_quadratic(TypeParam::policy, CoefficientQuadratic<T>{T(0), T(0), T(-1)}).count, 1);
}

TYPED_TEST(QuadraticTest, DoubleRoot)
{
    using T = typename TypeParam::T;
    const auto s = solve_quadratic(TypeParam::policy, CoefficientQuadratic<T>{T(1), T(-3), T(9)});  // (t − 3)²
    ASSERT_EQ(s.count, 1);
    EXPECT_EQ(s.span[0].enter, T(3));
    EXPECT_EQ(s.span[0].exit, T(3));
}

TYPED_TEST(QuadraticTest, NaNCoefficientsGiveNothing)
{
    using T = typename TypeParam::T;
    const T nan = std::numeric_limits<T>::quiet_NaN();
    EXPECT_EQ(solve_quadratic(TypeParam::policy, CoefficientQuadratic<T>{nan, T(1), T(1)}).count, 0);
    EXPECT_EQ(solve_quadratic(TypeParam::policy, CoefficientQuadratic<T>{T(1), nan, T(-1)}).count, 0);
    EXPECT_EQ(solve_quadratic(TypeParam::policy, CoefficientQuadratic<T>{T(0), T(1), nan}).count, 0);
}

// Roots of very different size: t² − 2·10⁴·t + 1 = 0 has roots ≈ 2·10⁴ and 5·10⁻⁵. The textbook
// formula loses the small root to cancellation; the q-form keeps it to a few ulps.
TEST(QuadraticAccuracy, SmallRootSurvivesCancellationExceptWithFast)
{
    const auto exact_small = 1.0L / (1e4L + std::sqrt(1e8L - 1.0L));
    for (auto policy_is_fast : {true, false}) {
        const CoefficientQuadratic<float> q{1.0f, -1e4f, 1.0f};
        const auto s = policy_is_fast ? solve_quadratic(fast, q) : solve_quadratic(stable, q);
        ASSERT_EQ(s.count, 1);
        const long double rel = std::fabs((s.span[0].enter - exact_small) / exact_small);
        if (policy_is_fast) EXPECT_GT(rel, 1e-2L);  // the reason `stable` exists
        else EXPECT_LT(rel, 4 * std::numeric_limits<float>::epsilon());
    }
    const auto s = solve_quadratic(accurate, CoefficientQuadratic<float>{1.0f, -1e4f, 1.0f});
    EXPECT_LT(std::fabs((s.span[0].enter - exact_small) / exact_small), 4 * std::numeric_limits<float>::epsilon());
}

// A far, small sphere: the Hearn–Baker and compensated discriminants keep a grazing ray's hit,
// which the textbook discriminant loses to cancellation of two ~10⁸-sized products.
TEST(QuadraticAccuracy, FarSphereDiscriminant)
{
    // Unit sphere at distance 1e4 in float; the ray passes at 0.999 of the radius (a hit).
    const NormQuadratic<float> q{{0.999f, 0.0f, -1e4f}, {0.0f, 0.0f, 1.0f}, 1.0f, 0.0f};
    EXPECT_EQ(solve_quadratic(stable, q).count, 1);
    EXPECT_EQ(solve_quadratic(accurate, q).count, 1);
    const auto exact = std::sqrt(1.0L - 0.999L * 0.999L);  // half chord
    for (auto s : {solve_quadratic(stable, q), solve_quadratic(accurate, q)}) {
        const long double chord = (long double)s.span[0].exit - s.span[0].enter;
        EXPECT_NEAR(double(chord / 2), double(exact), 2e-3);  // limited by ulp(1e4) in float, not by the formula
    }
}

}  // namespace
}  // namespace rayq::test::quadratic_test
