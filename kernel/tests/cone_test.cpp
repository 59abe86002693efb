#include "test_support.hpp"

namespace rayq::test::cone_test {
namespace {

template <class C>
class ConeTest : public ::testing::Test {};
TYPED_TEST_SUITE(ConeTest, AllConfigs, ConfigNames);

// Base radius 2 at z = 0 narrowing to an apex at z = 4: r(z) = 2 − z/2.
template <class T>
Cone<T> spike(Caps caps) { return {v3<T>(0, 0, 0), T(2), v3<T>(0, 0, 4), T(0), caps}; }
// Frustum: radius 1 at z = 0, radius 3 at z = 2 (r(z) = 1 + z).
template <class T>
Cone<T> funnel(Caps caps) { return {v3<T>(0, 0, 0), T(1), v3<T>(0, 0, 2), T(3), caps}; }

TYPED_TEST(ConeTest, SideFromOutside)
{
    using T = typename TypeParam::T;
    // At z = 1 the spike's radius is 1.5: a ray along +x from x = −5 hits at x = −1.5.
    const auto h = checked_intersect(TypeParam::policy, ray(v3<T>(-5, 0, 1), v3<T>(1, 0, 0)), spike<T>(Caps::both));
    ASSERT_TRUE(h);
    EXPECT_NEAR(h->t, T(3.5), tol<T>(5));
    EXPECT_EQ(h->part, Part::surface);
    EXPECT_TRUE(h->front_face);
    // Outward normal of r = 2 − z/2 on the −x side: (−1, 0, 1/2)/|·|.
    const T n = T(1) / std::sqrt(T(1.25));
    EXPECT_NEAR(h->normal.x, -n, tol<T>(2));
    EXPECT_NEAR(h->normal.z, T(0.5) * n, tol<T>(2));
}

TYPED_TEST(ConeTest, SideFromInside)
{
    using T = typename TypeParam::T;
    // From the axis at z = 1 of the funnel (radius 2) along +y: exits at y = 2.
    const auto h = checked_intersect(TypeParam::policy, ray(v3<T>(0, 0, 1), v3<T>(0, 1, 0)), funnel<T>(Caps::none));
    ASSERT_TRUE(h);
    EXPECT_NEAR(h->t, T(2), tol<T>(3));
    EXPECT_FALSE(h->front_face);
    EXPECT_EQ(h->part, Part::surface);
}

TYPED_TEST(ConeTest, BothCapsOfAFrustum)
{
    using T = typename TypeParam::T;
    auto h = checked_intersect(TypeParam::policy, ray(v3<T>(0.5, 0, -3), v3<T>(0, 0, 1)), funnel<T>(Caps::both));
    ASSERT_TRUE(h);
    EXPECT_NEAR(h->t, T(3), tol<T>(4));
    EXPECT_EQ(h->part, Part::cap0);
    EXPECT_NEAR(h->normal.z, T(-1), tol<T>());
    h = checked_intersect(TypeParam::policy, ray(v3<T>(2.5, 0, 7), v3<T>(0, 0, -1)), funnel<T>(Caps::both));
    ASSERT_TRUE(h);
    EXPECT_NEAR(h->t, T(5), tol<T>(8));
    EXPECT_EQ(h->part, Part::cap1);
    // Open funnel: the same ray passes cap1's plane inside the rim and meets the wall where 1 + z = 2.5.
    h = checked_intersect(TypeParam::policy, ray(v3<T>(2.5, 0, 7), v3<T>(0, 0, -1)), funnel<T>(Caps::none));
    ASSERT_TRUE(h);
    EXPECT_NEAR(h->t, T(5.5), tol<T>(8));
    EXPECT_FALSE(h->front_face);
}

TYPED_TEST(ConeTest, ApexHasNoCapAndNoNaN)
{
    using T = typename TypeParam::T;
    // Straight down the axis onto the apex: the apex is a surface hit, not a cap.
    auto h = checked_intersect(TypeParam::policy, ray(v3<T>(0, 0, 9), v3<T>(0, 0, -1)), spike<T>(Caps::both));
    ASSERT_TRUE(h);
    EXPECT_NEAR(h->t, T(5), tol<T>(10));
    EXPECT_EQ(h->part, Part::surface);
    // Through the apex from below (inside), leaving at the apex.
    h = checked_intersect(TypeParam::policy, ray(v3<T>(0, 0, 1), v3<T>(0, 0, 1)), spike<T>(Caps::both));
    ASSERT_TRUE(h);
    EXPECT_NEAR(h->t, T(3), tol<T>(4));
    EXPECT_EQ(h->part, Part::surface);
    EXPECT_FALSE(h->front_face);
    // A slanted line through the apex point.
    h = checked_intersect(TypeParam::policy, ray(v3<T>(-3, 0, 7), v3<T>(1, 0, -1)), spike<T>(Caps::none));
    if (h) {
        EXPECT_NEAR(h->t, T(3), T(1e-2));  // touching only the apex: a hit there, or none
    }
    // Exiting the open spike through its base plane from inside: no hit when open, cap0 when capped.
    EXPECT_FALSE(checked_intersect(TypeParam::policy, ray(v3<T>(0, 0, 1), v3<T>(0, 0, -1)), spike<T>(Caps::none)));
    h = checked_intersect(TypeParam::policy, ray(v3<T>(0, 0, 1), v3<T>(0, 0, -1)), spike<T>(Caps::both));
    ASSERT_TRUE(h);
    EXPECT_EQ(h->part, Part::cap0);
}

TYPED_TEST(ConeTest, ParallelToGeneratorIsLinear)
{
    using T = typename TypeParam::T;
    // (−1, 0, 2) is parallel to the generator from (2, 0, 0) to the apex (0, 0, 4), so the leading
    // coefficient vanishes: the ray enters through the base plane and leaves the side once, at (−1, 0, 2).
    const auto h = checked_intersect(TypeParam::policy, ray(v3<T>(0.5, 0, -1), v3<T>(-1, 0, 2)), spike<T>(Caps::none));
    ASSERT_TRUE(h);
    EXPECT_NEAR(h->t, T(1.5), tol<T>(4));
    EXPECT_NEAR(h->point.x, T(-1), tol<T>(4));
    EXPECT_FALSE(h->front_face);
}

// A cone whose slope (r1 − r0)/L overflows T: its normal is still the gradient's direction, nearly
// the axis, and finite (it was NaN, and the hit record fell back to the ray's reversed direction).
template <class T>
void expect_flat_cone_normal(T r0, T length)
{
    const Cone<T> flat{v3<T>(0, 0, 0), r0, v3<T>(0, 0, length), T(0), Caps::none};
    const Vec3<T> n = detail::unit(outward_normal(flat, v3<T>(0.5, 0, 0), Part::surface));
    EXPECT_NEAR(n.x, T(0), T(1e-6));
    EXPECT_NEAR(n.y, T(0), T(1e-6));
    EXPECT_NEAR(n.z, T(1), T(1e-6));
}

TEST(ConeNormal, FiniteWhereTheSlopeOverflows)
{
    expect_flat_cone_normal(1e30f, 1e-10f);
    expect_flat_cone_normal(0x1p1000, 0x1p-100);
}

}  // namespace
}  // namespace rayq::test::cone_test
