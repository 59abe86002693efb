// spawn(): secondary rays never re-hit the surface they leave. From each hit, rays spawned into
// the outward hemisphere of a convex solid (or the front/back half-space of a flat primitive)
// can meet nothing; rays spawned into a sphere must meet its far side, a whole chord away.
#include "test_support.hpp"

namespace rayq::test::spawn_test {
namespace {

template <class C>
class SpawnTest : public ::testing::Test {};
TYPED_TEST_SUITE(SpawnTest, AllConfigs, ConfigNames);

// `spawns` secondary rays from hits of random primary rays; returns the number of false re-hits.
template <class Policy, class Prim>
int false_self_hits(Policy policy, const Prim& prim, int spawns, std::uint64_t seed, bool check_inward_chord, bool flat = false)
{
    using T = scalar_t<Prim>;
    Random random(seed);
    int made = 0, bad = 0;
    while (made < spawns) {
        const Vec3<T> o = T(4) * scalar_cast<T>(random.unit_vector());
        const Vec3<T> aim{T(random.uniform(-1, 1)), T(random.uniform(-1, 1)), T(random.uniform(-1, 1))};  // braces: drawn in order
        const auto h = intersect(policy, Ray<T>{o, aim - o}, prim);
        if (!h) continue;
        for (int k = 0; k < 8 && made < spawns; ++k, ++made) {
            Vec3<T> w = scalar_cast<T>(random.unit_vector());
            const T scale = T(std::pow(10.0, random.uniform(-3, 3)));  // direction length must not matter
            // Away from the surface, on the side the primary ray came from (outward for a convex solid hit from outside).
            if (dot(w, h->normal) < T(0)) w = -w;
            const Ray<T> out = spawn(*h, scale * w);
            if ((h->front_face || flat) && occluded(policy, out, prim)) ++bad;  // flat: either side
            if (check_inward_chord) {
                // Into the solid: the next hit is the far side, 2·r·|cos θ| away (unit sphere), not the start.
                const Ray<T> in = spawn(*h, -scale * w);
                const auto far = intersect(policy, in, prim);
                const T chord = T(2) * std::abs(dot(h->normal, w));
                if (h->front_face && chord > T(1e-2) && (!far || far->t * scale < T(0.5) * chord)) ++bad;
            }
        }
    }
    return bad;
}

// 10^6 spawns per primitive and number type under the default policy; 10^5 under fast, and 2·10^4
// under accurate, whose exact arithmetic decides most of these near-surface origins (slow path).
template <class Policy>
int spawn_count()
{
    if (std::is_same_v<Policy, default_policy>) return 1000000;
    return std::is_same_v<Policy, accurate_policy> ? 20000 : 100000;
}

TYPED_TEST(SpawnTest, NoFalseSelfIntersections)
{
    using T = typename TypeParam::T;
    const auto p = TypeParam::policy;
    const int n = spawn_count<typename TypeParam::Policy>();
    EXPECT_EQ(false_self_hits(p, Sphere<T>{v3<T>(0.1, -0.2, 0.3), T(1)}, n, 1, true), 0);
    EXPECT_EQ(false_self_hits(p, Plane<T>{v3<T>(0.1, 0.2, 0.3), v3<T>(0.3, -1, 0.7)}, n, 2, false, true), 0);
    EXPECT_EQ(false_self_hits(p, Disk<T>{v3<T>(0.1, 0.2, 0.3), v3<T>(0.3, -1, 0.7), T(1.1)}, n, 3, false, true), 0);
    EXPECT_EQ(false_self_hits(p, Parallelogram<T>{v3<T>(-1, -0.9, 0.1), v3<T>(2, 0.3, 0.1), v3<T>(0.2, 1.8, -0.4)}, n, 4, false, true), 0);
    EXPECT_EQ(false_self_hits(p, Triangle<T>{v3<T>(-1, -0.9, 0.1), v3<T>(1.3, -0.2, 0.3), v3<T>(0.2, 1.4, -0.4)}, n, 5, false, true), 0);
    EXPECT_EQ(false_self_hits(p, Cylinder<T>{v3<T>(-0.3, -0.6, -0.9), v3<T>(0.5, 0.4, 0.8), T(0.7), Caps::both}, n, 6, false), 0);
    EXPECT_EQ(false_self_hits(p, Cone<T>{v3<T>(-0.3, -0.6, -0.9), T(0.9), v3<T>(0.5, 0.4, 0.8), T(0.2), Caps::both}, n, 7, false), 0);
    EXPECT_EQ(false_self_hits(p, Quadric<T>::ellipsoid(v3<T>(0.1, 0, -0.1), v3<T>(1.2, 0.7, 0.9), v3<T>(1, 1, 0), v3<T>(-1, 1, 0.5)), n, 8,
                              false),
              0);
    EXPECT_EQ(false_self_hits(p, transformed(Sphere<T>{v3<T>(0, 0, 0), T(1)}, Affine3<T>::rotation(v3<T>(1, 2, 3), T(0.3), v3<T>(0.1, 0.2, 0.3)) *
                                                                                 Affine3<T>::scaling(v3<T>(1.1, 0.6, 0.9))),
                              n, 9, false),
              0);
}

TEST(Spawn, FarAwaySphereAndUncertifiedFallback)
{
    // A unit sphere 1e4 away in float: the offset scales with the coordinates, not the radius.
    const Sphere<float> s{{6000, 8000, 0}, 1};
    const auto h = intersect(Ray<float>{{0, 0, 0}, {0.6f, 0.8f, 0}}, s);
    ASSERT_TRUE(h);
    EXPECT_TRUE(std::isfinite(h->t_error));
    EXPECT_FALSE(occluded(spawn(*h, Vec3<float>{-0.6f, -0.8f, 0}), s));
    // A hit without a certificate still spawns a finite origin.
    Hit<float> raw = *h;
    raw.point_error = {INFINITY, INFINITY, INFINITY};
    const Ray<float> r = spawn(raw, Vec3<float>{-0.6f, -0.8f, 0});
    EXPECT_TRUE(isfinite(r.origin));
    EXPECT_FALSE(occluded(r, s));
}

}  // namespace
}  // namespace rayq::test::spawn_test
