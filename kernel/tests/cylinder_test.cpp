#include "test_support.hpp"

namespace rayq::test::cylinder_test {
namespace {

template <class C>
class CylinderTest : public ::testing::Test {};
TYPED_TEST_SUITE(CylinderTest, AllConfigs, ConfigNames);

// Unit-radius cylinder along z from z = −1 to z = 2.
template <class T>
Cylinder<T> can(Caps caps) { return {v3<T>(0, 0, -1), v3<T>(0, 0, 2), T(1), caps}; }

TYPED_TEST(CylinderTest, SideHitFromOutside)
{
    using T = typename TypeParam::T;
    for (Caps caps : {Caps::none, Caps::both}) {
        const auto h = checked_intersect(TypeParam::policy, ray(v3<T>(-5, 0, 0.5), v3<T>(1, 0, 0)), can<T>(caps));
        ASSERT_TRUE(h);
        EXPECT_NEAR(h->t, T(4), tol<T>(5));
        EXPECT_EQ(h->part, Part::surface);
        EXPECT_TRUE(h->front_face);
        EXPECT_NEAR(h->normal.x, T(-1), tol<T>());
    }
}

TYPED_TEST(CylinderTest, AlongAxisHitsCapOnlyWhenCapped)
{
    using T = typename TypeParam::T;
    const auto up = ray(v3<T>(0.25, 0.5, -4), v3<T>(0, 0, 1));
    auto h = checked_intersect(TypeParam::policy, up, can<T>(Caps::both));
    ASSERT_TRUE(h);
    EXPECT_NEAR(h->t, T(3), tol<T>(4));
    EXPECT_EQ(h->part, Part::cap0);
    EXPECT_TRUE(h->front_face);
    EXPECT_NEAR(h->normal.z, T(-1), tol<T>());
    EXPECT_FALSE(checked_intersect(TypeParam::policy, up, can<T>(Caps::none)));  // straight through the open tube

    const auto down = ray(v3<T>(0.25, 0.5, 6), v3<T>(0, 0, -2));
    h = checked_intersect(TypeParam::policy, down, can<T>(Caps::both));
    ASSERT_TRUE(h);
    EXPECT_NEAR(h->t, T(2), tol<T>(4));
    EXPECT_EQ(h->part, Part::cap1);
    EXPECT_NEAR(h->normal.z, T(1), tol<T>());
}

TYPED_TEST(CylinderTest, FromInside)
{
    using T = typename TypeParam::T;
    // Radially outward from the axis: exits through the side.
    auto h = checked_intersect(TypeParam::policy, ray(v3<T>(0, 0, 0), v3<T>(0, 1, 0)), can<T>(Caps::both));
    ASSERT_TRUE(h);
    EXPECT_NEAR(h->t, T(1), tol<T>());
    EXPECT_EQ(h->part, Part::surface);
    EXPECT_FALSE(h->front_face);
    EXPECT_NEAR(h->normal.y, T(-1), tol<T>());
    // Along the axis from inside: exits through cap1 when capped, nothing when open.
    h = checked_intersect(TypeParam::policy, ray(v3<T>(0, 0, 0), v3<T>(0, 0, 1)), can<T>(Caps::both));
    ASSERT_TRUE(h);
    EXPECT_NEAR(h->t, T(2), tol<T>(2));
    EXPECT_EQ(h->part, Part::cap1);
    EXPECT_FALSE(h->front_face);
    EXPECT_FALSE(checked_intersect(TypeParam::policy, ray(v3<T>(0, 0, 0), v3<T>(0, 0, 1)), can<T>(Caps::none)));
    // Open tube seen from inside at a slant: the inner wall.
    h = checked_intersect(TypeParam::policy, ray(v3<T>(0, 0, 0), v3<T>(1, 0, 1)), can<T>(Caps::none));
    ASSERT_TRUE(h);
    EXPECT_NEAR(h->t, T(1), tol<T>());
    EXPECT_FALSE(h->front_face);
}

TYPED_TEST(CylinderTest, CapsVersusSideSelection)
{
    using T = typename TypeParam::T;
    // A slanted ray entering through cap0 (lands at x = 0.5 on z = −1) and leaving through the side.
    const auto r = ray(v3<T>(-0.5, 0, -2), v3<T>(1, 0, 1));
    auto h = checked_intersect(TypeParam::policy, r, can<T>(Caps::both));
    ASSERT_TRUE(h);
    EXPECT_NEAR(h->t, T(1), tol<T>(2));
    EXPECT_EQ(h->part, Part::cap0);
    // The open tube: the same ray meets only the inside of the side wall at x = 1 (t = 1.5).
    h = checked_intersect(TypeParam::policy, r, can<T>(Caps::none));
    ASSERT_TRUE(h);
    EXPECT_NEAR(h->t, T(1.5), tol<T>(2));
    EXPECT_EQ(h->part, Part::surface);
    EXPECT_FALSE(h->front_face);
    // Above the top: a ray passing over cap1 misses both.
    EXPECT_FALSE(checked_intersect(TypeParam::policy, ray(v3<T>(-5, 0, 2.5), v3<T>(1, 0, 0)), can<T>(Caps::both)));
}

TYPED_TEST(CylinderTest, RimAndTangency)
{
    using T = typename TypeParam::T;
    // Tangent to the side at x = 1 (representable, exact): a grazing hit on the side.
    auto h = checked_intersect(TypeParam::policy, ray(v3<T>(1, -5, 0), v3<T>(0, 1, 0)), can<T>(Caps::none));
    ASSERT_TRUE(h);
    EXPECT_EQ(h->t, T(5));
    // Through the rim of cap1 exactly: (1, 0, 2) reached along −x·z diagonal.
    h = checked_intersect(TypeParam::policy, ray(v3<T>(2, 0, 3), v3<T>(-1, 0, -1)), can<T>(Caps::both));
    ASSERT_TRUE(h);
    EXPECT_NEAR(h->t, T(1), tol<T>(3));
    EXPECT_NEAR(h->point.x, T(1), tol<T>(3));
    EXPECT_NEAR(h->point.z, T(2), tol<T>(3));
}

TYPED_TEST(CylinderTest, RotatedAxisAndFromCenter)
{
    using T = typename TypeParam::T;
    // Axis along (1, 1, 0)/√2 through (1, 2, 3), radius 0.5, half height 2.
    const auto c = Cylinder<T>::from_center(v3<T>(1, 2, 3), v3<T>(3, 3, 0), T(0.5), T(2), Caps::both);
    EXPECT_NEAR(length(c.p1 - c.p0), T(4), tol<T>(4));
    // A ray perpendicular to the axis, in the z direction, through the center: hits at distance 5 − 0.5.
    auto h = checked_intersect(TypeParam::policy, ray(v3<T>(1, 2, -2), v3<T>(0, 0, 1)), c);
    ASSERT_TRUE(h);
    EXPECT_NEAR(h->t, T(4.5), tol<T>(8));
    EXPECT_EQ(h->part, Part::surface);
    // Along the axis from beyond p1's end: hits cap1 at distance 3 − 2 = 1 from the start.
    const T s = T(1) / std::sqrt(T(2));
    const Vec3<T> start = v3<T>(1, 2, 3) + T(3) * Vec3<T>{s, s, T(0)};
    h = checked_intersect(TypeParam::policy, ray(start, Vec3<T>{-s, -s, T(0)}), c);
    ASSERT_TRUE(h);
    EXPECT_NEAR(h->t, T(1), tol<T>(8));
    EXPECT_EQ(h->part, Part::cap1);
    EXPECT_NEAR(h->normal.x, s, tol<T>(2));
}

TYPED_TEST(CylinderTest, ParallelToCapsOutsideSlab)
{
    using T = typename TypeParam::T;
    // Parallel to the cap planes: inside the slab it meets the side, outside it misses.
    EXPECT_TRUE(checked_intersect(TypeParam::policy, ray(v3<T>(-5, 0, 1.5), v3<T>(1, 0, 0)), can<T>(Caps::both)));
    EXPECT_FALSE(checked_intersect(TypeParam::policy, ray(v3<T>(-5, 0, -1.5), v3<T>(1, 0, 0)), can<T>(Caps::both)));
    EXPECT_FALSE(checked_intersect(TypeParam::policy, ray(v3<T>(-5, 0, 2.5), v3<T>(1, 0, 0)), can<T>(Caps::none)));
}

// A side hit's normal is the radial direction at the reported point (computed again in long
// double), at every scale: the record takes it from t (outward_normal_on_ray), and where |A|²·r
// leaves unit()'s direct range (float: the smallest and largest scales here) from the point.
// The bound is the rounding of the point itself, ~ε·(|o| + |t·d| + |p0|) against the distance ρ
// from the axis.
TYPED_TEST(CylinderTest, SideNormalIsRadialAtEveryScale)
{
    using T = typename TypeParam::T;
    using L = long double;
    Random rng(20261204);
    for (const double scale : {1e-12, 1e-6, 1.0, 1e8, 1e15}) {
        int sides = 0;
        for (int i = 0; i < 100; ++i) {
            const Vec3<double> center = scale * Vec3<double>{rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1)};
            const auto cyl = Cylinder<T>::from_center(scalar_cast<T>(center), scalar_cast<T>(rng.unit_vector()), T(0.3 * scale),
                                                      T(0.5 * scale), Caps::both);
            const Vec3<double> aim = center + 0.2 * scale * rng.unit_vector();
            const Vec3<double> origin = center + 4 * scale * rng.unit_vector();
            const auto r = ray(scalar_cast<T>(origin), scalar_cast<T>(normalize(aim - origin)));
            const auto h = checked_intersect(TypeParam::policy, r, cyl);
            if (!h || h->part != Part::surface) continue;
            ++sides;
            const Vec3<L> p0 = scalar_cast<L>(cyl.p0), axis = scalar_cast<L>(cyl.p1) - p0, q = scalar_cast<L>(h->point) - p0;
            Vec3<L> radial = q - (dot(q, axis) / dot(axis, axis)) * axis;
            const L rho = length(radial);
            radial = (h->front_face ? L(1) : L(-1)) / rho * radial;
            const L reach = length(scalar_cast<L>(r.origin)) + length(L(h->t) * scalar_cast<L>(r.direction)) + length(p0) + length(axis);
            const L bound = L(64) * std::numeric_limits<T>::epsilon() * reach / rho;
            EXPECT_LE(length(scalar_cast<L>(h->normal) - radial), bound) << "scale " << scale << ", ray " << i;
        }
        // `fast` and `stable` in float under- or overflow their discriminant's products beyond
        // lengths of ~[1.8e-5, 6.5e4] and may miss (README, "Scenes and batches"): there `accurate` must hit.
        const bool in_range = std::is_same_v<T, double> || std::is_same_v<typename TypeParam::Policy, accurate_policy> || scale == 1.0;
        if (in_range) {
            EXPECT_GT(sides, 20) << "scale " << scale;
        }
    }
}

}  // namespace
}  // namespace rayq::test::cylinder_test
