#include "test_support.hpp"

namespace rayq::test::quadric_test {
namespace {

template <class C>
class QuadricTest : public ::testing::Test {};
TYPED_TEST_SUITE(QuadricTest, AllConfigs, ConfigNames);

TYPED_TEST(QuadricTest, EllipsoidAxisHits)
{
    using T = typename TypeParam::T;
    const auto e = Quadric<T>::ellipsoid(v3<T>(1, 1, 1), v3<T>(1, 2, 4));
    auto h = checked_intersect(TypeParam::policy, ray(v3<T>(1, 1, -9), v3<T>(0, 0, 1)), e);
    ASSERT_TRUE(h);
    EXPECT_NEAR(h->t, T(6), tol<T>(10));
    EXPECT_NEAR(h->normal.z, T(-1), tol<T>(4));
    EXPECT_TRUE(h->front_face);
    h = checked_intersect(TypeParam::policy, ray(v3<T>(1, 9, 1), v3<T>(0, -2, 0)), e);
    ASSERT_TRUE(h);
    EXPECT_NEAR(h->t, T(3), tol<T>(10));
    // From the center outward along x: exits at 1.
    h = checked_intersect(TypeParam::policy, ray(v3<T>(1, 1, 1), v3<T>(1, 0, 0)), e);
    ASSERT_TRUE(h);
    EXPECT_NEAR(h->t, T(1), tol<T>(4));
    EXPECT_FALSE(h->front_face);
}

TYPED_TEST(QuadricTest, RotatedEllipsoid)
{
    using T = typename TypeParam::T;
    // Semi-axis 3 along (1, 1, 0)/√2, 1 along (−1, 1, 0)/√2, 2 along z.
    const auto e = Quadric<T>::ellipsoid(v3<T>(0, 0, 0), v3<T>(3, 1, 2), v3<T>(1, 1, 0), v3<T>(-1, 1, 0));
    const T s = T(1) / std::sqrt(T(2));
    auto h = checked_intersect(TypeParam::policy, ray(Vec3<T>{-10 * s, -10 * s, T(0)}, Vec3<T>{s, s, T(0)}), e);
    ASSERT_TRUE(h);
    EXPECT_NEAR(h->t, T(7), tol<T>(20));
    h = checked_intersect(TypeParam::policy, ray(Vec3<T>{10 * s, -10 * s, T(0)}, Vec3<T>{-s, s, T(0)}), e);
    ASSERT_TRUE(h);
    EXPECT_NEAR(h->t, T(9), tol<T>(20));
}

TYPED_TEST(QuadricTest, ParaboloidAxisAndClip)
{
    using T = typename TypeParam::T;
    // x² + y² = z (a = b = c = 1), vertex at the origin, clipped at height 4.
    const auto p = Quadric<T>::elliptic_paraboloid(v3<T>(0, 0, 0), T(1), T(1), T(1), T(4));
    auto h = checked_intersect(TypeParam::policy, ray(v3<T>(0, 0, -3), v3<T>(0, 0, 1)), p);
    ASSERT_TRUE(h);
    EXPECT_NEAR(h->t, T(3), tol<T>(4));  // the vertex
    EXPECT_TRUE(h->front_face);
    // A horizontal ray at z = 1 meets the bowl at x = ±1.
    h = checked_intersect(TypeParam::policy, ray(v3<T>(-3, 0, 1), v3<T>(1, 0, 0)), p);
    ASSERT_TRUE(h);
    EXPECT_NEAR(h->t, T(2), tol<T>(4));
    // At z = 9 the surface is at x = ±3 but above the clip box: no hit.
    EXPECT_FALSE(checked_intersect(TypeParam::policy, ray(v3<T>(-5, 0, 9), v3<T>(1, 0, 0)), p));
}

TYPED_TEST(QuadricTest, ClipBoxFallsBackToTheFarRoot)
{
    using T = typename TypeParam::T;
    // Unit sphere as a quadric, clipped to x >= 0: a ray along +x from −5 skips the near root at x = −1.
    auto q = Quadric<T>::ellipsoid(v3<T>(0, 0, 0), v3<T>(1, 1, 1));
    q.clip = {v3<T>(0, -2, -2), v3<T>(2, 2, 2)};
    const auto h = checked_intersect(TypeParam::policy, ray(v3<T>(-5, 0, 0), v3<T>(1, 0, 0)), q);
    ASSERT_TRUE(h);
    EXPECT_NEAR(h->t, T(6), tol<T>(8));
    EXPECT_FALSE(h->front_face);
}

TYPED_TEST(QuadricTest, HyperboloidsAndCone)
{
    using T = typename TypeParam::T;
    // One sheet: x² + y² − z² = 1; a ray along x at z = 0 meets the waist at x = ±1 from outside.
    const auto h1 = Quadric<T>::hyperboloid_one_sheet(v3<T>(0, 0, 0), T(1), T(1), T(1), T(3));
    auto h = checked_intersect(TypeParam::policy, ray(v3<T>(-4, 0, 0), v3<T>(1, 0, 0)), h1);
    ASSERT_TRUE(h);
    EXPECT_NEAR(h->t, T(3), tol<T>(4));
    EXPECT_TRUE(h->front_face);
    // At z = 2 the radius is √5.
    h = checked_intersect(TypeParam::policy, ray(v3<T>(-4, 0, 2), v3<T>(1, 0, 0)), h1);
    ASSERT_TRUE(h);
    EXPECT_NEAR(h->t, T(4) - std::sqrt(T(5)), tol<T>(8));
    // Along the axis the one-sheet hyperboloid is never met.
    EXPECT_FALSE(checked_intersect(TypeParam::policy, ray(v3<T>(0, 0, -2), v3<T>(0, 0, 1)), h1));

    // Two sheets: z² − x² − y² = 1 (scaled c = 2: z²/4 − … = 1, vertices at z = ±2).
    const auto h2 = Quadric<T>::hyperboloid_two_sheets(v3<T>(0, 0, 0), T(1), T(1), T(2), T(5));
    h = checked_intersect(TypeParam::policy, ray(v3<T>(0, 0, 0), v3<T>(0, 0, 1)), h2);
    ASSERT_TRUE(h);
    EXPECT_NEAR(h->t, T(2), tol<T>(4));
    EXPECT_TRUE(h->front_face);  // from between the sheets (outside) into the upper bowl

    // Elliptic double cone x² + y² = z²/4: a ray along x at z = 2 meets it at x = ±1.
    const auto k = Quadric<T>::elliptic_cone(v3<T>(0, 0, 0), T(1), T(1), T(2), T(4));
    h = checked_intersect(TypeParam::policy, ray(v3<T>(-3, 0, 2), v3<T>(1, 0, 0)), k);
    ASSERT_TRUE(h);
    EXPECT_NEAR(h->t, T(2), tol<T>(4));
}

TYPED_TEST(QuadricTest, LinearDegenerateIsAPlane)
{
    using T = typename TypeParam::T;
    // Only G and J: x − 2 = 0, outside toward +x.
    const Quadric<T> plane{T(0), T(0), T(0), T(0), T(0), T(0), T(1), T(0), T(0), T(-2)};
    auto h = checked_intersect(TypeParam::policy, ray(v3<T>(5, 1, 1), v3<T>(-1, 0, 0)), plane);
    ASSERT_TRUE(h);
    EXPECT_NEAR(h->t, T(3), tol<T>(4));
    EXPECT_TRUE(h->front_face);
    EXPECT_NEAR(h->normal.x, T(1), tol<T>());
    EXPECT_FALSE(checked_intersect(TypeParam::policy, ray(v3<T>(5, 1, 1), v3<T>(0, 1, 0)), plane));
    // A quadric that is linear along this ray (a = 0): the paraboloid x² = z hit along z.
    const Quadric<T> bowl{T(1), T(0), T(0), T(0), T(0), T(0), T(0), T(0), T(-1), T(0)};
    h = checked_intersect(TypeParam::policy, ray(v3<T>(2, 0, 10), v3<T>(0, 0, -1)), bowl);
    ASSERT_TRUE(h);
    EXPECT_NEAR(h->t, T(6), tol<T>(10));
}

TYPED_TEST(QuadricTest, Validate)
{
    using T = typename TypeParam::T;
    EXPECT_FALSE(validate(Quadric<T>{}));
    EXPECT_EQ(validate(Quadric<T>{}).defect, Defect::degenerate);
    Quadric<T> q = Quadric<T>::ellipsoid(v3<T>(0, 0, 0), v3<T>(1, 1, 1));
    EXPECT_TRUE(validate(q));
    q.E = std::numeric_limits<T>::quiet_NaN();
    EXPECT_EQ(validate(q).defect, Defect::non_finite);
    const Quadric<T> constant{T(0), T(0), T(0), T(0), T(0), T(0), T(0), T(0), T(0), T(1)};
    EXPECT_EQ(validate(constant).defect, Defect::degenerate);
    Quadric<T> empty_box = Quadric<T>::ellipsoid(v3<T>(0, 0, 0), v3<T>(1, 1, 1));
    empty_box.clip = {v3<T>(1, 0, 0), v3<T>(0, 1, 1)};
    EXPECT_EQ(validate(empty_box).defect, Defect::degenerate);
    EXPECT_FALSE(intersect(TypeParam::policy, ray(v3<T>(-5, 0, 0), v3<T>(1, 0, 0)), empty_box));
}

}  // namespace
}  // namespace rayq::test::quadric_test
