#include "test_support.hpp"

namespace rayq::test::sphere_test {
namespace {

template <class C>
class SphereTest : public ::testing::Test {};
TYPED_TEST_SUITE(SphereTest, AllConfigs, ConfigNames);

TYPED_TEST(SphereTest, AxisHitFromOutside)
{
    using T = typename TypeParam::T;
    const Sphere<T> s{v3<T>(1, 2, 3), T(2)};
    const auto h = checked_intersect(TypeParam::policy, ray(v3<T>(1, 2, -7), v3<T>(0, 0, 1)), s);
    ASSERT_TRUE(h);
    EXPECT_NEAR(h->t, T(8), tol<T>(10));
    EXPECT_TRUE(h->front_face);
    EXPECT_EQ(h->part, Part::surface);
    EXPECT_NEAR(h->normal.z, T(-1), tol<T>());
    EXPECT_NEAR(h->point.z, T(1), tol<T>(10));
}

TYPED_TEST(SphereTest, RotatedDirectionNotUnit)
{
    using T = typename TypeParam::T;
    // Direction (3, 4, 0)·k toward the center from distance 10: hit at distance 10 − r = 7.
    const Sphere<T> s{v3<T>(0, 0, 0), T(3)};
    const T k = T(0.5);
    const auto h = checked_intersect(TypeParam::policy, ray(v3<T>(-6, -8, 0), v3<T>(3 * k, 4 * k, 0)), s);
    ASSERT_TRUE(h);
    EXPECT_NEAR(h->t, T(7) / (5 * k), tol<T>(10));
    EXPECT_NEAR(h->normal.x, T(-0.6), tol<T>());
    EXPECT_NEAR(h->normal.y, T(-0.8), tol<T>());
}

TYPED_TEST(SphereTest, MissAndBehind)
{
    using T = typename TypeParam::T;
    const Sphere<T> s{v3<T>(0, 0, 0), T(1)};
    EXPECT_FALSE(checked_intersect(TypeParam::policy, ray(v3<T>(0, 2, -5), v3<T>(0, 0, 1)), s));
    EXPECT_FALSE(checked_intersect(TypeParam::policy, ray(v3<T>(0, 0, 5), v3<T>(0, 0, 1)), s));  // sphere behind
}

TYPED_TEST(SphereTest, OriginInsideExits)
{
    using T = typename TypeParam::T;
    const Sphere<T> s{v3<T>(0, 0, 0), T(2)};
    const auto h = checked_intersect(TypeParam::policy, ray(v3<T>(0, 0, 0.5), v3<T>(0, 0, -1)), s);
    ASSERT_TRUE(h);
    EXPECT_NEAR(h->t, T(2.5), tol<T>(10));
    EXPECT_FALSE(h->front_face);
    EXPECT_NEAR(h->normal.z, T(1), tol<T>());  // facing the ray: against the direction, i.e. inward
}

TYPED_TEST(SphereTest, ExactTangency)
{
    using T = typename TypeParam::T;
    // The line x = 1, y = 0 touches the unit sphere at (1, 0, 0): representable, discriminant exactly 0.
    const Sphere<T> s{v3<T>(0, 0, 0), T(1)};
    const auto h = checked_intersect(TypeParam::policy, ray(v3<T>(1, 0, -4), v3<T>(0, 0, 1)), s);
    ASSERT_TRUE(h);
    EXPECT_EQ(h->t, T(4));
    EXPECT_NEAR(h->normal.x, T(1), tol<T>());  // the tangent point's normal is perpendicular to the ray
    EXPECT_FALSE(checked_intersect(TypeParam::policy, ray(v3<T>(1.0625, 0, -4), v3<T>(0, 0, 1)), s));
}

TYPED_TEST(SphereTest, Window)
{
    using T = typename TypeParam::T;
    const Sphere<T> s{v3<T>(0, 0, 0), T(1)};
    const auto o = v3<T>(0, 0, -3), d = v3<T>(0, 0, 1);
    // Window excludes the entry: the exit is the closest hit.
    auto h = checked_intersect(TypeParam::policy, ray(o, d, T(2.5), T(10)), s);
    ASSERT_TRUE(h);
    EXPECT_NEAR(h->t, T(4), tol<T>(10));
    EXPECT_FALSE(h->front_face);
    // Window ends before the entry; window between entry and exit; bounds are exclusive.
    EXPECT_FALSE(checked_intersect(TypeParam::policy, ray(o, d, T(0), T(1.5)), s));
    EXPECT_FALSE(checked_intersect(TypeParam::policy, ray(o, d, T(2.1), T(3.9)), s));
    EXPECT_FALSE(checked_intersect(TypeParam::policy, ray(o, d, T(0), T(2)), s));
    EXPECT_FALSE(checked_intersect(TypeParam::policy, ray(o, d, T(4), T(9)), s));
}

TYPED_TEST(SphereTest, FarAwaySmallSphere)
{
    using T = typename TypeParam::T;
    // Radius 1 at distance 1e4 along a skew axis; the ray aims at the center.
    const Vec3<T> c = v3<T>(6000, 8000, 0);
    const Sphere<T> s{c, T(1)};
    const auto h = checked_intersect(TypeParam::policy, ray(v3<T>(0, 0, 0), v3<T>(0.6, 0.8, 0)), s);
    ASSERT_TRUE(h);
    if (std::is_same_v<typename TypeParam::Policy, fast_policy>) {
        // Textbook: c = |o − c|² − r² rounds at ulp(10⁸) and the root moves by up to √(ulp(c)/2)
        // (2 in float) — the error the stable and accurate policies exist to remove.
        EXPECT_NEAR(h->t, T(9999), std::sqrt(T(1e8) * std::numeric_limits<T>::epsilon()));
    } else {
        EXPECT_NEAR(h->t, T(9999), tol<T>(1e4));
    }
}

}  // namespace
}  // namespace rayq::test::sphere_test
