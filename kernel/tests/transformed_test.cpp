// Transformed instances, and the same solid written three ways agreeing on random rays.
#include "test_support.hpp"

#include <random>

namespace rayq::test::transformed_test {
namespace {

template <class C>
class TransformedTest : public ::testing::Test {};
TYPED_TEST_SUITE(TransformedTest, AllConfigs, ConfigNames);

TYPED_TEST(TransformedTest, ScaledAndMovedSphere)
{
    using T = typename TypeParam::T;
    // Unit sphere scaled ×(2, 1, 1) (an ellipsoid with x semi-axis 2) and moved to (5, 0, 0).
    const auto x = transformed(Sphere<T>{v3<T>(0, 0, 0), T(1)},
                               Affine3<T>::translation(v3<T>(5, 0, 0)) * Affine3<T>::scaling(v3<T>(2, 1, 1)));
    ASSERT_TRUE(validate(x));
    auto h = checked_intersect(TypeParam::policy, ray(v3<T>(0, 0, 0), v3<T>(2, 0, 0)), x);  // t in world units of d
    ASSERT_TRUE(h);
    EXPECT_NEAR(h->t, T(1.5), tol<T>(8));
    EXPECT_NEAR(h->point.x, T(3), tol<T>(8));
    EXPECT_NEAR(h->normal.x, T(-1), tol<T>(4));
    // At the top of the ellipsoid, (5, 1, 0), the normal is +y; reached from above.
    h = checked_intersect(TypeParam::policy, ray(v3<T>(5, 4, 0), v3<T>(0, -1, 0)), x);
    ASSERT_TRUE(h);
    EXPECT_NEAR(h->t, T(3), tol<T>(8));
    EXPECT_NEAR(h->normal.y, T(1), tol<T>(4));
    // An oblique point: (5 + 2cosθ, sinθ, 0) has normal ∝ (cosθ/2, sinθ, 0) — the inverse transpose at work.
    const T c = T(0.6), s = T(0.8);
    h = checked_intersect(TypeParam::policy, ray(Vec3<T>{T(5) + 2 * c, s + T(3), T(0)}, v3<T>(0, -1, 0)), x);
    ASSERT_TRUE(h);
    EXPECT_NEAR(h->t, T(3), tol<T>(16));
    const Vec3<T> expected = normalize(Vec3<T>{c / 2, s, T(0)});
    EXPECT_NEAR(h->normal.x, expected.x, tol<T>(16));
    EXPECT_NEAR(h->normal.y, expected.y, tol<T>(16));
}

TYPED_TEST(TransformedTest, MirrorKeepsInsideAndOutside)
{
    using T = typename TypeParam::T;
    const auto x = transformed(Cylinder<T>{v3<T>(0, 0, 0), v3<T>(0, 0, 1), T(1), Caps::both}, Affine3<T>::scaling(v3<T>(-1, 1, -1)));
    ASSERT_TRUE(validate(x));
    // The can now spans z in [−1, 0]: from above, the first hit is object cap0 (z = 0).
    auto h = checked_intersect(TypeParam::policy, ray(v3<T>(0, 0, 3), v3<T>(0, 0, -1)), x);
    ASSERT_TRUE(h);
    EXPECT_NEAR(h->t, T(3), tol<T>(4));
    EXPECT_EQ(h->part, Part::cap0);
    EXPECT_TRUE(h->front_face);
    EXPECT_NEAR(h->normal.z, T(1), tol<T>());
    h = checked_intersect(TypeParam::policy, ray(v3<T>(0.5, 0, -3), v3<T>(0, 0, 1)), x);
    ASSERT_TRUE(h);
    EXPECT_NEAR(h->t, T(2), tol<T>(4));
    EXPECT_TRUE(h->front_face);
    EXPECT_EQ(h->part, Part::cap1);  // object cap1 (z = 1) maps to world z = −1
    EXPECT_NEAR(h->normal.z, T(-1), tol<T>());
}

TYPED_TEST(TransformedTest, SingularMatrixIsRejected)
{
    using T = typename TypeParam::T;
    const auto flat = transformed(Sphere<T>{v3<T>(0, 0, 0), T(1)}, Affine3<T>::scaling(v3<T>(1, 1, 0)));
    EXPECT_FALSE(validate(flat));
    EXPECT_FALSE(intersect(TypeParam::policy, ray(v3<T>(0, 0, 5), v3<T>(0, 0, -1)), flat));
    Affine3<T> nan_map = Affine3<T>::identity();
    nan_map.m[1][3] = std::numeric_limits<T>::quiet_NaN();
    EXPECT_EQ(validate(transformed(Sphere<T>{v3<T>(0, 0, 0), T(1)}, nan_map)).defect, Defect::non_finite);
    EXPECT_EQ(validate(transformed(Sphere<T>{v3<T>(0, 0, 0), T(-1)}, Affine3<T>::identity())).defect,
              Defect::nonpositive_radius);  // the inner primitive's own reason
}

// Random rays aimed near a solid of size ~1 at distance ~5: two descriptions of the same solid must
// agree on hit/miss (except within `graze` of tangency, judged by the hit's incidence) and on t.
template <class Policy, class A, class B>
void expect_same_solid(Policy policy, const A& a, const B& b, typename A::scalar_type t_tolerance, const Vec3<typename A::scalar_type>& center,
                       int n = 3000)
{
    using T = typename A::scalar_type;
    std::mt19937_64 rng(12345);
    std::uniform_real_distribution<double> u(-1, 1);
    const double graze = std::is_same_v<T, float> ? 1e-2 : 1e-5;
    int both = 0;
    for (int i = 0; i < n; ++i) {
        const Vec3<T> o = center + Vec3<T>{T(5 * u(rng)), T(5 * u(rng)), T(5 * u(rng))};
        const Vec3<T> aim = center + Vec3<T>{T(1.5 * u(rng)), T(1.5 * u(rng)), T(1.5 * u(rng))};
        const Ray<T> r{o, aim - o};
        const auto ha = intersect(policy, r, a), hb = intersect(policy, r, b);
        if (ha && hb) {
            ++both;
            EXPECT_NEAR(ha->t, hb->t, t_tolerance) << "ray " << i;
            EXPECT_EQ(ha->front_face, hb->front_face) << "ray " << i;
            EXPECT_NEAR(double(dot(ha->normal, hb->normal)), 1.0, 1e3 * double(t_tolerance)) << "ray " << i;
        } else if (ha || hb) {
            const Hit<T>& h = ha ? *ha : *hb;
            const double incidence = std::fabs(double(dot(h.normal, normalize(r.direction))));
            EXPECT_LT(incidence, graze) << "ray " << i << " hit by only one description, not grazing";
        }
    }
    EXPECT_GT(both, n / 5);
}

// Stated bound for agreement on these rays: 64 ulps of the scale (|o − c| <= ~9, |d| >= ~1e-2 is rare):
// both descriptions are within a few ulps of the truth except near tangency.
template <class T>
T agreement_bound() { return T(64) * std::numeric_limits<T>::epsilon() * T(10); }

TYPED_TEST(TransformedTest, SphereAsQuadricAndAsTransformedAgree)
{
    using T = typename TypeParam::T;
    const Vec3<T> c = v3<T>(0.5, -1.25, 2);
    const Sphere<T> sphere{c, T(1.5)};
    const auto quadric = Quadric<T>::ellipsoid(c, v3<T>(1.5, 1.5, 1.5));
    const auto placed = transformed(Sphere<T>{v3<T>(0, 0, 0), T(1)},
                                    Affine3<T>::translation(c) * Affine3<T>::scaling(v3<T>(1.5, 1.5, 1.5)));
    expect_same_solid(TypeParam::policy, sphere, quadric, agreement_bound<T>(), c);
    expect_same_solid(TypeParam::policy, sphere, placed, agreement_bound<T>(), c);
}

TYPED_TEST(TransformedTest, TransformedCylinderAgreesWithWorldCylinder)
{
    using T = typename TypeParam::T;
    // Object: unit-radius can along z from 0 to 2. World: rotated 0.7 rad about (1, 2, 3), moved to (1, −2, 0.5).
    const Cylinder<T> local{v3<T>(0, 0, 0), v3<T>(0, 0, 2), T(1), Caps::both};
    const Affine3<T> m = Affine3<T>::rotation(v3<T>(1, 2, 3), T(0.7), v3<T>(1, -2, 0.5));
    const auto placed = transformed(local, m);
    const Cylinder<T> world{m.point(local.p0), m.point(local.p1), T(1), Caps::both};
    expect_same_solid(TypeParam::policy, world, placed, agreement_bound<T>(), m.point(v3<T>(0, 0, 1)));
    // Parts survive the transform.
    const Ray<T> down_axis{m.point(v3<T>(0.2, 0.1, 5)), m.linear(v3<T>(0, 0, -1))};
    const auto a = intersect(TypeParam::policy, down_axis, placed), b = intersect(TypeParam::policy, down_axis, world);
    ASSERT_TRUE(a && b);
    EXPECT_EQ(a->part, Part::cap1);
    EXPECT_EQ(b->part, Part::cap1);
}

}  // namespace
}  // namespace rayq::test::transformed_test
