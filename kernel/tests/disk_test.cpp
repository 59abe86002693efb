#include "test_support.hpp"

namespace rayq::test::disk_test {
namespace {

template <class C>
class DiskTest : public ::testing::Test {};
TYPED_TEST_SUITE(DiskTest, AllConfigs, ConfigNames);

TYPED_TEST(DiskTest, InsideAndOutsideRadius)
{
    using T = typename TypeParam::T;
    const Disk<T> d{v3<T>(1, 1, 1), v3<T>(0, 0, 1), T(2)};
    auto h = checked_intersect(TypeParam::policy, ray(v3<T>(2.5, 1, 4), v3<T>(0, 0, -1)), d);
    ASSERT_TRUE(h);
    EXPECT_NEAR(h->t, T(3), tol<T>(4));
    EXPECT_TRUE(h->front_face);
    EXPECT_NEAR(h->normal.z, T(1), tol<T>());
    EXPECT_FALSE(checked_intersect(TypeParam::policy, ray(v3<T>(3.5, 1, 4), v3<T>(0, 0, -1)), d));
    // From below: the back face.
    h = checked_intersect(TypeParam::policy, ray(v3<T>(1, 2, -1), v3<T>(0, 0, 1)), d);
    ASSERT_TRUE(h);
    EXPECT_FALSE(h->front_face);
    EXPECT_NEAR(h->normal.z, T(-1), tol<T>());
}

TYPED_TEST(DiskTest, RimIsInsideAndTiltedDisk)
{
    using T = typename TypeParam::T;
    const Disk<T> d{v3<T>(0, 0, 0), v3<T>(0, 0, 1), T(2)};
    EXPECT_TRUE(checked_intersect(TypeParam::policy, ray(v3<T>(2, 0, 1), v3<T>(0, 0, -1)), d));  // exactly on the rim
    // Disk tilted: normal (0, 1, 1); the ray along −y through (0, 0, 0) hits the center at t = 5.
    const Disk<T> tilted{v3<T>(0, 0, 0), v3<T>(0, 1, 1), T(1)};
    const auto h = checked_intersect(TypeParam::policy, ray(v3<T>(0, 5, 0), v3<T>(0, -1, 0)), tilted);
    ASSERT_TRUE(h);
    EXPECT_NEAR(h->t, T(5), tol<T>(5));
    EXPECT_NEAR(h->normal.y, T(1) / std::sqrt(T(2)), tol<T>());
    // Same line displaced along x by 1.5: outside the unit disk.
    EXPECT_FALSE(checked_intersect(TypeParam::policy, ray(v3<T>(1.5, 5, 0), v3<T>(0, -1, 0)), tilted));
}

TYPED_TEST(DiskTest, ParallelRayMisses)
{
    using T = typename TypeParam::T;
    const Disk<T> d{v3<T>(0, 0, 0), v3<T>(0, 0, 1), T(1)};
    EXPECT_FALSE(checked_intersect(TypeParam::policy, ray(v3<T>(-5, 0, 0), v3<T>(1, 0, 0)), d));
    EXPECT_FALSE(checked_intersect(TypeParam::policy, ray(v3<T>(-5, 0, 0.5), v3<T>(1, 0, 0)), d));
}

}  // namespace
}  // namespace rayq::test::disk_test
