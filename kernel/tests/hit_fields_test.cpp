// HitFields: a query asked for fewer fields computes the same t, part and side, the same values in
// the fields asked for, and leaves the others at their documented defaults — for every primitive
// kind, policy and type, through intersect, intersect_all and a scene.
#include <random>

#include <rayq/scene.hpp>

#include "test_support.hpp"

namespace rayq::test::hit_fields_test {
namespace {

template <class C>
class HitFieldsTest : public ::testing::Test {};
TYPED_TEST_SUITE(HitFieldsTest, AllConfigs, ConfigNames);

constexpr HitFields kSubsets[] = {HitFields::t,
                                  HitFields::point,
                                  HitFields::normal,
                                  HitFields::bounds,
                                  HitFields::point | HitFields::normal,
                                  HitFields::point | HitFields::bounds,
                                  HitFields::normal | HitFields::bounds,
                                  HitFields::all};

std::string name(HitFields f)
{
    std::string s = "fields";
    if (wants(f, HitFields::point)) s += " point";
    if (wants(f, HitFields::normal)) s += " normal";
    if (wants(f, HitFields::bounds)) s += " bounds";
    return s;
}

template <class T>
void expect_subset(const Hit<T>& got, const Hit<T>& full, HitFields f)
{
    SCOPED_TRACE(name(f));
    constexpr T inf = std::numeric_limits<T>::infinity();
    EXPECT_TRUE(same_bits(got.t, full.t));
    EXPECT_EQ(got.part, full.part);
    EXPECT_EQ(got.front_face, full.front_face);
    const Vec3<T> zero{0, 0, 0};
    EXPECT_EQ(got.point, wants(f, HitFields::point) ? full.point : zero);
    EXPECT_EQ(got.normal, wants(f, HitFields::normal) ? full.normal : zero);
    if (wants(f, HitFields::bounds)) {
        EXPECT_TRUE(same_bits(got.t_error, full.t_error));
        EXPECT_TRUE(same_bits(got.point_error, full.point_error));
    } else {
        EXPECT_EQ(got.t_error, inf);
        EXPECT_EQ(got.point_error, (Vec3<T>{inf, inf, inf}));
    }
}

template <class Policy, class Prim>
void check_prim(Policy p, const Prim& prim, std::mt19937_64& rng, int& hits)
{
    using T = scalar_t<Prim>;
    std::uniform_real_distribution<double> u(-3, 3);
    Scene<Prim> scene;
    scene.add(prim);
    for (int k = 0; k < 300; ++k) {
        // From around the primitive (some rays start inside the solids) toward points near it.
        const Vec3<T> o{T(u(rng)), T(u(rng)), T(u(rng))};
        const Vec3<T> aim{T(u(rng) / 3), T(u(rng) / 3), T(u(rng) / 3)};
        Ray<T> r{o, aim - o};
        if (k % 5 == 0) r.tmin = T(0.5);  // crossings before the window: the bounds must look back
        const auto full = intersect(p, r, prim);
        const auto all_full = intersect_all(p, r, prim);
        hits += full.has_value();
        for (const HitFields f : kSubsets) {
            const auto got = intersect(p, r, prim, f);
            ASSERT_EQ(got.has_value(), full.has_value());
            if (got) expect_subset(*got, *full, f);
            const auto all = intersect_all(p, r, prim, f);
            ASSERT_EQ(all.size(), all_full.size());
            for (int i = 0; i < all.size(); ++i) {
                expect_subset(all[i].hit, all_full[i].hit, f);
                EXPECT_EQ(all[i].entering, all_full[i].entering);
            }
            const auto in_scene = intersect(p, r, scene, f);
            ASSERT_EQ(in_scene.has_value(), full.has_value());
            if (in_scene) expect_subset(in_scene->hit, *full, f);
        }
    }
}

TYPED_TEST(HitFieldsTest, FewerFieldsSameValues)
{
    using T = typename TypeParam::T;
    const auto p = TypeParam::policy;
    std::mt19937_64 rng(0xF1E1D5 + sizeof(T));
    const Vec3<T> o = v3<T>(0.1, -0.2, 0.3);
    int hits = 0;
    check_prim(p, Sphere<T>{o, T(1)}, rng, hits);
    check_prim(p, Plane<T>{o, v3<T>(0.2, 1, -0.3)}, rng, hits);
    check_prim(p, Disk<T>{o, v3<T>(1, 0.5, 0.1), T(1.2)}, rng, hits);
    check_prim(p, Parallelogram<T>{o, v3<T>(1.5, 0, 0.2), v3<T>(0.1, 1.4, 0)}, rng, hits);
    check_prim(p, Triangle<T>{v3<T>(-1, -1, 0), v3<T>(1.5, -0.5, 0.2), v3<T>(0, 1.5, -0.1)}, rng, hits);
    check_prim(p, Cylinder<T>::from_center(o, v3<T>(0.3, 1, 0.2), T(0.8), T(1), Caps::both), rng, hits);
    check_prim(p, Cylinder<T>::from_center(o, v3<T>(1, 0, 0.2), T(0.7), T(1.5), Caps::none), rng, hits);
    check_prim(p, Cone<T>{v3<T>(0, -1, 0), T(1), v3<T>(0.2, 1, 0.1), T(0.3), Caps::both}, rng, hits);
    check_prim(p, Quadric<T>::ellipsoid(o, v3<T>(1.5, 1, 0.6), v3<T>(1, 0, 0), v3<T>(0, 1, 0)), rng, hits);
    check_prim(p, transformed(Sphere<T>{v3<T>(0, 0, 0), T(1)}, Affine3<T>::scaling(v3<T>(1.5, 0.7, 1))), rng, hits);
    // The rays aim near the primitives: most of the 3,000 hit something.
    EXPECT_GT(hits, 1000);
}

}  // namespace
}  // namespace rayq::test::hit_fields_test
