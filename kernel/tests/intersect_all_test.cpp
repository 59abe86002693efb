// intersect_all: entry/exit pairs in order for every closed primitive, the first equal to intersect().
#include "test_support.hpp"

#include <random>

namespace rayq::test::intersect_all_test {
namespace {

template <class C>
class IntersectAllTest : public ::testing::Test {};
TYPED_TEST_SUITE(IntersectAllTest, AllConfigs, ConfigNames);

template <class T, class F>
void for_each_closed_solid(F&& f)
{
    f(Sphere<T>{v3<T>(0, 0, 0), T(1)});
    f(Cylinder<T>{v3<T>(0, 0, -1), v3<T>(0, 0, 1), T(1), Caps::both});
    f(Cone<T>{v3<T>(0, 0, -1), T(1), v3<T>(0, 0, 1), T(0), Caps::both});
    f(Cone<T>{v3<T>(0, 0, -1), T(0.5), v3<T>(0, 0, 1), T(1), Caps::both});
    f(Quadric<T>::ellipsoid(v3<T>(0, 0, 0), v3<T>(1, 0.75, 0.5), v3<T>(1, 1, 0), v3<T>(-1, 1, 0)));
    f(transformed(Cylinder<T>{v3<T>(0, 0, 0), v3<T>(0, 0, 1), T(1), Caps::both},
                  Affine3<T>::rotation(v3<T>(1, 0, 0), T(0.5), v3<T>(0, 0, -0.5)) * Affine3<T>::scaling(v3<T>(0.8, 0.6, 1.5))));
}

TYPED_TEST(IntersectAllTest, EntryExitPairsInOrder)
{
    using T = typename TypeParam::T;
    std::mt19937_64 rng(99);
    std::uniform_real_distribution<double> u(-1, 1);
    for_each_closed_solid<T>([&](const auto& solid) {
        int pairs = 0;
        for (int i = 0; i < 2000; ++i) {
            const Vec3<T> o{T(4 * u(rng)), T(4 * u(rng)), T(4 * u(rng))};
            const Vec3<T> aim{T(u(rng)), T(u(rng)), T(u(rng))};
            const Ray<T> r{o, aim - o};
            const auto all = intersect_all(TypeParam::policy, r, solid);
            const auto first = intersect(TypeParam::policy, r, solid);
            ASSERT_EQ(all.empty(), !first.has_value());
            if (all.empty()) continue;
            EXPECT_EQ(all[0].hit.t, first->t);
            EXPECT_EQ(all[0].hit.part, first->part);
            EXPECT_EQ(all[0].entering, first->front_face);
            // The whole record: a closest hit computes no more crossings than it needs (accurate's
            // quick lane rounds no exit for it), and must not differ for that.
            EXPECT_EQ(all[0].hit.t_error, first->t_error);
            EXPECT_EQ(all[0].hit.normal, first->normal);
            for (int k = 1; k < all.size(); ++k) EXPECT_LE(all[k - 1].hit.t, all[k].hit.t);
            for (const auto& p : all) expect_well_formed(r, p.hit);
            // From outside (origin at distance > 4·size from most solids is not guaranteed; use the
            // count): two crossings are an entry then an exit; one crossing from inside is an exit.
            if (all.size() == 2) {
                ++pairs;
                EXPECT_TRUE(all[0].entering);
                EXPECT_FALSE(all[1].entering);
            } else {
                EXPECT_FALSE(all[0].entering) << "a lone crossing must be the exit from inside";
            }
        }
        EXPECT_GT(pairs, 200);
    });
}

TYPED_TEST(IntersectAllTest, WindowCutsTheList)
{
    using T = typename TypeParam::T;
    const Sphere<T> s{v3<T>(0, 0, 0), T(1)};
    const auto r = ray(v3<T>(0, 0, -3), v3<T>(0, 0, 1));
    EXPECT_EQ(intersect_all(TypeParam::policy, r, s).size(), 2);
    EXPECT_EQ(intersect_all(TypeParam::policy, ray(r.origin, r.direction, T(3), T(10)), s).size(), 1);
    EXPECT_EQ(intersect_all(TypeParam::policy, ray(r.origin, r.direction, T(0), T(1)), s).size(), 0);
    EXPECT_EQ(intersect_all(TypeParam::policy, ray(r.origin, Vec3<T>{}), s).size(), 0);
}

}  // namespace
}  // namespace rayq::test::intersect_all_test
