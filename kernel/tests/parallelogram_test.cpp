#include "test_support.hpp"

namespace rayq::test::parallelogram_test {
namespace {

template <class C>
class ParallelogramTest : public ::testing::Test {};
TYPED_TEST_SUITE(ParallelogramTest, AllConfigs, ConfigNames);

TYPED_TEST(ParallelogramTest, RectangleInsideOutside)
{
    using T = typename TypeParam::T;
    // 2 × 1 rectangle in z = 0 from (1, 1): front side +z (x × y).
    const Parallelogram<T> p{v3<T>(1, 1, 0), v3<T>(2, 0, 0), v3<T>(0, 1, 0)};
    auto h = checked_intersect(TypeParam::policy, ray(v3<T>(2.5, 1.5, 2), v3<T>(0, 0, -1)), p);
    ASSERT_TRUE(h);
    EXPECT_NEAR(h->t, T(2), tol<T>(3));
    EXPECT_TRUE(h->front_face);
    EXPECT_NEAR(h->normal.z, T(1), tol<T>());
    EXPECT_NEAR(h->point.x, T(2.5), tol<T>(3));
    for (auto [x, y] : {std::pair{0.5, 1.5}, {3.5, 1.5}, {2.0, 0.5}, {2.0, 2.5}})
        EXPECT_FALSE(checked_intersect(TypeParam::policy, ray(v3<T>(x, y, 2), v3<T>(0, 0, -1)), p)) << x << "," << y;
    // Corners and edges belong to it.
    EXPECT_TRUE(checked_intersect(TypeParam::policy, ray(v3<T>(3, 2, 2), v3<T>(0, 0, -1)), p));
    EXPECT_TRUE(checked_intersect(TypeParam::policy, ray(v3<T>(1, 1.5, 2), v3<T>(0, 0, -1)), p));
    // Back face.
    h = checked_intersect(TypeParam::policy, ray(v3<T>(2, 1.5, -3), v3<T>(0, 0, 1)), p);
    ASSERT_TRUE(h);
    EXPECT_FALSE(h->front_face);
    EXPECT_NEAR(h->normal.z, T(-1), tol<T>());
}

TYPED_TEST(ParallelogramTest, SkewedAndRotated)
{
    using T = typename TypeParam::T;
    // A rhombus in the plane x = 0 with edges (0, 2, 0) and (0, 1, 1): contains (0, 2, 0.5), not (0, 0.2, 0.8).
    const Parallelogram<T> p{v3<T>(0, 0, 0), v3<T>(0, 2, 0), v3<T>(0, 1, 1)};
    auto h = checked_intersect(TypeParam::policy, ray(v3<T>(-4, 2, 0.5), v3<T>(2, 0, 0)), p);
    ASSERT_TRUE(h);
    EXPECT_NEAR(h->t, T(2), tol<T>(4));
    EXPECT_FALSE(h->front_face);  // edge0 × edge1 = (2, 0, 0): the ray travels along the normal
    EXPECT_NEAR(h->normal.x, T(-1), tol<T>());
    EXPECT_FALSE(checked_intersect(TypeParam::policy, ray(v3<T>(-4, 0.2, 0.8), v3<T>(2, 0, 0)), p));
}

TYPED_TEST(ParallelogramTest, ParallelRay)
{
    using T = typename TypeParam::T;
    const Parallelogram<T> p{v3<T>(0, 0, 0), v3<T>(1, 0, 0), v3<T>(0, 1, 0)};
    EXPECT_FALSE(checked_intersect(TypeParam::policy, ray(v3<T>(-1, 0.5, 0), v3<T>(1, 0, 0)), p));
    EXPECT_FALSE(checked_intersect(TypeParam::policy, ray(v3<T>(-1, 0.5, 0.1), v3<T>(1, 0, 0)), p));
}

}  // namespace
}  // namespace rayq::test::parallelogram_test
