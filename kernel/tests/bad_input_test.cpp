// Bad input never hits and never invokes undefined behaviour (run under UBSan/ASan too).
#include "test_support.hpp"

#include <vector>

namespace rayq::test::bad_input_test {
namespace {

template <class C>
class BadInputTest : public ::testing::Test {};
TYPED_TEST_SUITE(BadInputTest, AllConfigs, ConfigNames);

// One valid instance of every primitive, all straddling the z axis near the origin so that the
// good ray below hits each of them.
template <class T, class F>
void for_each_primitive(F&& f)
{
    f(Sphere<T>{v3<T>(0, 0, 0), T(1)});
    f(Plane<T>{v3<T>(0, 0, 0), v3<T>(0, 0, 1)});
    f(Disk<T>{v3<T>(0, 0, 0), v3<T>(0, 0, 1), T(1)});
    f(Parallelogram<T>{v3<T>(-1, -1, 0), v3<T>(2, 0, 0), v3<T>(0, 2, 0)});
    f(Triangle<T>{v3<T>(-1, -1, 0), v3<T>(2, -1, 0), v3<T>(-1, 2, 0)});
    f(Cylinder<T>{v3<T>(0, 0, -1), v3<T>(0, 0, 1), T(1), Caps::both});
    f(Cylinder<T>{v3<T>(-2, 0, 0), v3<T>(2, 0, 0), T(1), Caps::none});
}

TYPED_TEST(BadInputTest, GoodRayHitsEveryPrimitive)
{
    using T = typename TypeParam::T;
    for_each_primitive<T>([](const auto& prim) {
        EXPECT_TRUE(validate(prim));
        EXPECT_TRUE(checked_intersect(TypeParam::policy, ray(v3<T>(0.25, 0.25, 5), v3<T>(0, 0, -1)), prim));
    });
}

TYPED_TEST(BadInputTest, NonFiniteOrEmptyRaysNeverHit)
{
    using T = typename TypeParam::T;
    constexpr T nan = std::numeric_limits<T>::quiet_NaN(), inf = std::numeric_limits<T>::infinity();
    const T tiny = std::numeric_limits<T>::denorm_min();
    const auto o = v3<T>(0.25, 0.25, 5), d = v3<T>(0, 0, -1);
    const std::vector<Ray<T>> bad = {
        ray(Vec3<T>{nan, T(0), T(5)}, d),
        ray(Vec3<T>{T(0), inf, T(5)}, d),
        ray(o, Vec3<T>{T(0), T(0), nan}),
        ray(o, Vec3<T>{T(0), T(0), -inf}),
        ray(o, Vec3<T>{T(0), T(0), T(0)}),           // zero-length direction
        ray(o, Vec3<T>{T(0), T(0), -tiny}),          // |d|² underflows: no usable direction
        ray(o, d, T(3), T(3)),                       // empty window
        ray(o, d, T(6), T(2)),                       // reversed window
        ray(o, d, nan, T(10)),
        ray(o, d, T(0), nan),
    };
    for_each_primitive<T>([&](const auto& prim) {
        for (const auto& r : bad) {
            EXPECT_FALSE(intersect(TypeParam::policy, r, prim));
            EXPECT_FALSE(occluded(TypeParam::policy, r, prim));
        }
    });
}

TYPED_TEST(BadInputTest, InvalidPrimitivesNeverHit)
{
    using T = typename TypeParam::T;
    constexpr T nan = std::numeric_limits<T>::quiet_NaN(), inf = std::numeric_limits<T>::infinity();
    const auto r = ray(v3<T>(0.25, 0.25, 5), v3<T>(0, 0, -1));
    const auto z = v3<T>(0, 0, 0);
    const auto expect_no_hit = [&](const auto& prim) {
        EXPECT_FALSE(validate(prim));
        EXPECT_FALSE(intersect(TypeParam::policy, r, prim));
        EXPECT_FALSE(occluded(TypeParam::policy, r, prim));
    };
    expect_no_hit(Sphere<T>{z, T(0)});
    expect_no_hit(Sphere<T>{z, T(-1)});
    expect_no_hit(Sphere<T>{z, nan});
    expect_no_hit(Sphere<T>{Vec3<T>{nan, T(0), T(0)}, T(1)});
    expect_no_hit(Plane<T>{z, z});
    expect_no_hit(Plane<T>{z, Vec3<T>{T(0), T(0), inf}});
    expect_no_hit(Disk<T>{z, v3<T>(0, 0, 1), T(-2)});
    expect_no_hit(Disk<T>{z, z, T(1)});
    expect_no_hit(Parallelogram<T>{v3<T>(-1, -1, 0), v3<T>(2, 0, 0), v3<T>(4, 0, 0)});  // collinear edges
    expect_no_hit(Triangle<T>{v3<T>(-1, -1, 0), v3<T>(1, 1, 0), v3<T>(3, 3, 0)});        // collinear vertices
    expect_no_hit(Triangle<T>{v3<T>(-1, -1, 0), v3<T>(-1, -1, 0), v3<T>(3, 3, 0)});      // repeated vertex
    expect_no_hit(Cylinder<T>{v3<T>(0, 0, 1), v3<T>(0, 0, 1), T(1), Caps::both});          // zero axis
    expect_no_hit(Cylinder<T>{v3<T>(0, 0, -1), v3<T>(0, 0, 1), T(0), Caps::both});
    expect_no_hit(Cylinder<T>{v3<T>(0, 0, -1), v3<T>(0, 0, nan), T(1), Caps::both});
}

TYPED_TEST(BadInputTest, HugeButFiniteInputsGiveFiniteAnswersOrNone)
{
    using T = typename TypeParam::T;
    const T big = std::numeric_limits<T>::max() / T(4);
    const auto r = ray(Vec3<T>{big, -big, big}, Vec3<T>{-big, big, -big});
    for_each_primitive<T>([&](const auto& prim) {
        if (const auto h = intersect(TypeParam::policy, r, prim)) expect_well_formed(r, *h);
    });
    const Sphere<T> huge{Vec3<T>{T(0), T(0), T(0)}, big};
    const auto from_center = ray(v3<T>(0, 0, 0), v3<T>(1, 0, 0));
    if (const auto h = intersect(TypeParam::policy, from_center, huge)) expect_well_formed(from_center, *h);
}

// Found by fuzzing (rayq-fuzz --harness transformed): a float ray starting near FLT_MAX meets a
// transformed plane where o + t·d rounds beyond the largest float. The point saturates; its
// error bound is infinite.
TEST(BadInput, HitPointNearTheLargestFloatSaturates)
{
    const Ray<float> r{{0x1.f3e59cp+123f, 0x1.4429f6p+127f, 0x1.8b139ep+127f}, {0.0f, 0.0f, 1.0f}, 0.0f,
                       std::numeric_limits<float>::infinity()};
    const Plane<float> plane{{-0x1.59p-1f, 0x1.4af8p+0f, 0x1.fffffep+127f}, {-0x1.94bcp+1f, 0x1.c448p+1f, 0x1.db5ffep+1f}};
    const Affine3<float> to_world{{{0x1.e90b16p-1f, 0x1.28ad9ap-2f, 0x1.f3e59ep-5f, 0x1.a9ee16p+13f},
                                   {-0x1.0bb66ep-2f, 0x1.75053ap-1f, 0x1.4429f8p-1f, -0x1.60c88p+7f},
                                   {0x1.1c9f6p-3f, -0x1.3dcc2cp-1f, 0x1.8b13ap-1f, -0x1.b310f4p+13f}}};
    const Affine3<float> to_object{{{0x1.e90b18p-1f, -0x1.0bb67p-2f, 0x1.1c9f64p-3f, -0x1.5bcf54p+13f},
                                    {0x1.28ad9ap-2f, 0x1.75053ap-1f, -0x1.3dcc2ep-1f, -0x1.856e7p+13f},
                                    {0x1.f3e5ap-5f, 0x1.4429f8p-1f, 0x1.8b13a6p-1f, 0x1.3935ecp+13f}}};
    const Transformed<Plane<float>> x{plane, to_world, to_object};
    const auto check = [&](auto policy) {
        const auto h = checked_intersect(policy, r, x);
        if (!h) return;
        EXPECT_EQ(h->point.z, std::numeric_limits<float>::max());
        EXPECT_EQ(h->point_error.z, std::numeric_limits<float>::infinity());
    };
    check(fast);
    check(stable);
    check(accurate);
    // Its object-space origin overflows to infinity (z), where accurate's exact signs once took
    // infinite expansions at face value and hit at FLT_MAX; no policy hits it now. A plain plane
    // at z = FLT_MAX, reached along z = 1.0036…, still reaches the overflow: t·d rounds past
    // FLT_MAX.
    const Ray<float> along{{0.0f, 0.0f, 0.0f}, {0.0f, 0.0f, 0x1.003adp+0f}, 0.0f, std::numeric_limits<float>::infinity()};
    const Plane<float> top{{0.0f, 0.0f, std::numeric_limits<float>::max()}, {0.0f, 0.0f, 1.0f}};
    const auto h = checked_intersect(accurate, along, top);
    ASSERT_TRUE(h);
    EXPECT_FALSE(h->t * along.direction.z <= std::numeric_limits<float>::max()) << "the reproducer no longer reaches the overflow";
    EXPECT_EQ(h->point.z, std::numeric_limits<float>::max());
    EXPECT_EQ(h->point_error.z, std::numeric_limits<float>::infinity());
}

}  // namespace
}  // namespace rayq::test::bad_input_test
