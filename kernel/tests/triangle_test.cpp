#include "test_support.hpp"

namespace rayq::test::triangle_test {
namespace {

template <class C>
class TriangleTest : public ::testing::Test {};
TYPED_TEST_SUITE(TriangleTest, AllConfigs, ConfigNames);

TYPED_TEST(TriangleTest, FrontBackAndOutside)
{
    using T = typename TypeParam::T;
    const Triangle<T> tri{v3<T>(0, 0, 0), v3<T>(4, 0, 0), v3<T>(0, 4, 0)};  // counter-clockwise from +z
    auto h = checked_intersect(TypeParam::policy, ray(v3<T>(1, 1, 3), v3<T>(0, 0, -1)), tri);
    ASSERT_TRUE(h);
    EXPECT_NEAR(h->t, T(3), tol<T>(4));
    EXPECT_TRUE(h->front_face);
    EXPECT_NEAR(h->normal.z, T(1), tol<T>());
    h = checked_intersect(TypeParam::policy, ray(v3<T>(1, 1, -3), v3<T>(0, 0, 1)), tri);
    ASSERT_TRUE(h);
    EXPECT_FALSE(h->front_face);
    EXPECT_NEAR(h->normal.z, T(-1), tol<T>());
    EXPECT_FALSE(checked_intersect(TypeParam::policy, ray(v3<T>(3, 3, 3), v3<T>(0, 0, -1)), tri));  // beyond the hypotenuse
    EXPECT_FALSE(checked_intersect(TypeParam::policy, ray(v3<T>(-1, 1, 3), v3<T>(0, 0, -1)), tri));
    // Edges and vertices are inside.
    EXPECT_TRUE(checked_intersect(TypeParam::policy, ray(v3<T>(2, 2, 3), v3<T>(0, 0, -1)), tri));
    EXPECT_TRUE(checked_intersect(TypeParam::policy, ray(v3<T>(4, 0, 3), v3<T>(0, 0, -1)), tri));
}

TYPED_TEST(TriangleTest, RotatedOblique)
{
    using T = typename TypeParam::T;
    // The triangle on x + y + z = 1 with vertices on the axes; the centroid (1/3, 1/3, 1/3)
    // is reached from the origin along (1, 1, 1) at t = 1/3; the origin is behind (inside).
    const Triangle<T> tri{v3<T>(1, 0, 0), v3<T>(0, 1, 0), v3<T>(0, 0, 1)};
    const auto h = checked_intersect(TypeParam::policy, ray(v3<T>(0, 0, 0), v3<T>(1, 1, 1)), tri);
    ASSERT_TRUE(h);
    EXPECT_NEAR(h->t, T(1) / T(3), tol<T>());
    EXPECT_FALSE(h->front_face);
    const T s = T(1) / std::sqrt(T(3));
    EXPECT_NEAR(h->normal.x, -s, tol<T>());
}

TYPED_TEST(TriangleTest, ParallelAndWindow)
{
    using T = typename TypeParam::T;
    const Triangle<T> tri{v3<T>(0, 0, 0), v3<T>(1, 0, 0), v3<T>(0, 1, 0)};
    EXPECT_FALSE(checked_intersect(TypeParam::policy, ray(v3<T>(-1, 0.2, 0), v3<T>(1, 0, 0)), tri));
    EXPECT_FALSE(checked_intersect(TypeParam::policy, ray(v3<T>(0.2, 0.2, 1), v3<T>(0, 0, -1), T(0), T(1)), tri));
    EXPECT_TRUE(checked_intersect(TypeParam::policy, ray(v3<T>(0.2, 0.2, 1), v3<T>(0, 0, -1), T(0), T(1.5)), tri));
}

}  // namespace
}  // namespace rayq::test::triangle_test
