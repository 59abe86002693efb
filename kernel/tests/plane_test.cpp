#include "test_support.hpp"

namespace rayq::test::plane_test {
namespace {

template <class C>
class PlaneTest : public ::testing::Test {};
TYPED_TEST_SUITE(PlaneTest, AllConfigs, ConfigNames);

TYPED_TEST(PlaneTest, FrontAndBack)
{
    using T = typename TypeParam::T;
    const Plane<T> p{v3<T>(0, 0, 1), v3<T>(0, 0, 2)};  // z = 1, outside is +z; normal not unit
    auto h = checked_intersect(TypeParam::policy, ray(v3<T>(3, 4, 5), v3<T>(0, 0, -2)), p);
    ASSERT_TRUE(h);
    EXPECT_NEAR(h->t, T(2), tol<T>(4));
    EXPECT_TRUE(h->front_face);
    EXPECT_NEAR(h->normal.z, T(1), tol<T>());
    h = checked_intersect(TypeParam::policy, ray(v3<T>(3, 4, -1), v3<T>(0, 0, 1)), p);
    ASSERT_TRUE(h);
    EXPECT_NEAR(h->t, T(2), tol<T>(4));
    EXPECT_FALSE(h->front_face);
    EXPECT_NEAR(h->normal.z, T(-1), tol<T>());
}

TYPED_TEST(PlaneTest, RotatedPlane)
{
    using T = typename TypeParam::T;
    // x + y + z = 3, through (1, 1, 1); the ray from the origin along (1, 1, 1) meets it at t = 1.
    const Plane<T> p{v3<T>(1, 1, 1), v3<T>(1, 1, 1)};
    const auto h = checked_intersect(TypeParam::policy, ray(v3<T>(0, 0, 0), v3<T>(1, 1, 1)), p);
    ASSERT_TRUE(h);
    EXPECT_NEAR(h->t, T(1), tol<T>(3));
    EXPECT_FALSE(h->front_face);  // origin is on the inside (behind the normal)
    // Oblique: from (3, 0, 0) along (−1, 0, 0): 3 − t = 3 → t = 0, excluded by tmin; from (4, 0, 0) → t = 1.
    const auto g = checked_intersect(TypeParam::policy, ray(v3<T>(4, 0, 0), v3<T>(-1, 0, 0)), p);
    ASSERT_TRUE(g);
    EXPECT_NEAR(g->t, T(1), tol<T>(4));
    EXPECT_TRUE(g->front_face);
}

TYPED_TEST(PlaneTest, ParallelBehindAndWindow)
{
    using T = typename TypeParam::T;
    const Plane<T> p{v3<T>(0, 0, 0), v3<T>(0, 1, 0)};
    EXPECT_FALSE(checked_intersect(TypeParam::policy, ray(v3<T>(0, 1, 0), v3<T>(1, 0, 0)), p));  // parallel above
    EXPECT_FALSE(checked_intersect(TypeParam::policy, ray(v3<T>(0, 0, 0), v3<T>(1, 0, 0)), p));  // lying in it
    EXPECT_FALSE(checked_intersect(TypeParam::policy, ray(v3<T>(0, 1, 0), v3<T>(0, 1, 0)), p));  // moving away
    EXPECT_FALSE(checked_intersect(TypeParam::policy, ray(v3<T>(0, 1, 0), v3<T>(0, -1, 0), T(0), T(0.5)), p));
    EXPECT_TRUE(checked_intersect(TypeParam::policy, ray(v3<T>(0, 1, 0), v3<T>(0, -1, 0), T(0.5), T(1.5)), p));
}

}  // namespace
}  // namespace rayq::test::plane_test
