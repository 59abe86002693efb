// The boxes Embree culls with (rayq::embree::embree_bounds) contain every hit point rayq reports,
// for every policy: aimed, grazing and inside rays, near and 10⁴ away. The point is taken on the
// float line Embree traverses, in long double. Also: the padding stays small where it can.
#include <rayq/embree.hpp>

#include <gtest/gtest.h>

#include "test_scenes.hpp"

namespace {

using namespace rayq_embree_test;

// How far (in world units) the point lies outside the box; <= 0 inside.
long double outside_by(const RTCBounds& b, const rayq::Vec3<long double>& p)
{
    const auto axis = [](long double v, float lo, float hi) { return std::max(lo - v, v - hi); };
    return std::max({axis(p.x, b.lower_x, b.upper_x), axis(p.y, b.lower_y, b.upper_y), axis(p.z, b.lower_z, b.upper_z)});
}

template <class Prim, class Policy>
void hits_inside_boxes(Policy policy, double far)
{
    using T = rayq::scalar_t<Prim>;
    const rayq::Vec3<double> offset{far, far, -far};
    const std::vector<Prim> prims = random_primitives<Prim>(64, offset, 0xB0C5);
    std::vector<rayq::Ray<T>> rays = aimed_rays<T>(2000, offset, 1);
    for (const auto& r : grazing_rays(prims, 4000, 2)) rays.push_back(r);
    for (const auto& r : inside_rays(prims, 500, 3)) rays.push_back(r);
    std::size_t hits = 0;
    for (const auto& ray : rays) {
        // Embree's float copy of the ray: where its traversal looks for the hit.
        const rayq::Vec3<long double> o{(long double)(float)ray.origin.x, (long double)(float)ray.origin.y, (long double)(float)ray.origin.z};
        const rayq::Vec3<long double> d{(long double)(float)ray.direction.x, (long double)(float)ray.direction.y,
                                        (long double)(float)ray.direction.z};
        for (const Prim& p : prims) {
            const auto h = rayq::intersect(policy, ray, p);
            if (!h) continue;
            ++hits;
            const RTCBounds box = rayq::embree::embree_bounds<Policy>(p);
            const long double out = outside_by(box, o + (long double)h->t * d);
            ASSERT_LE(out, 0.0L) << "hit at t=" << h->t << " lies " << double(out) << " outside its box; far=" << far;
        }
    }
    EXPECT_GT(hits, 500u);
}

template <class Prim>
void every_policy(double far)
{
    hits_inside_boxes<Prim>(rayq::fast, far);
    hits_inside_boxes<Prim>(rayq::stable, far);
    hits_inside_boxes<Prim>(rayq::accurate, far);
}

TEST(EmbreeBounds, ContainEveryHitSpheres) { every_policy<rayq::Sphere<float>>(0), every_policy<rayq::Sphere<double>>(0); }
TEST(EmbreeBounds, ContainEveryHitCylinders) { every_policy<rayq::Cylinder<float>>(0), every_policy<rayq::Cylinder<double>>(0); }
TEST(EmbreeBounds, ContainEveryHitFarSpheres) { every_policy<rayq::Sphere<float>>(1e4), every_policy<rayq::Sphere<double>>(1e4); }
TEST(EmbreeBounds, ContainEveryHitFarCylinders) { every_policy<rayq::Cylinder<float>>(1e4), every_policy<rayq::Cylinder<double>>(1e4); }

// The padding is ulp-scaled, not a guess: a unit sphere at the origin grows by < 1e-5 under the
// stable and accurate policies; its box is exact-or-larger on every side.
TEST(EmbreeBounds, PaddingIsSmallAndOutward)
{
    const rayq::Sphere<float> s{{0, 0, 0}, 1};
    for (const RTCBounds& b : {rayq::embree::embree_bounds<rayq::stable_policy>(s), rayq::embree::embree_bounds<rayq::accurate_policy>(s)}) {
        EXPECT_LE(b.upper_x, 1.0f + 1e-5f);
        EXPECT_GT(b.upper_x, 1.0f);
        EXPECT_LT(b.lower_y, -1.0f);
        EXPECT_GE(b.lower_y, -1.0f - 1e-5f);
    }
    // A cylinder along z is only as wide as its radius in x and y.
    const rayq::Cylinder<float> c{{0, 0, -2}, {0, 0, 2}, 0.5f, rayq::Caps::both};
    const RTCBounds b = rayq::embree::embree_bounds<rayq::accurate_policy>(c);
    EXPECT_LE(b.upper_x, 0.5f + 1e-5f);
    EXPECT_LE(b.upper_z, 2.0f + 1e-5f);
    EXPECT_GT(b.upper_z, 2.0f);
}

TEST(EmbreeBounds, InvalidPrimitivesGetAnEmptyBox)
{
    const RTCBounds b = rayq::embree::embree_bounds<rayq::stable_policy>(rayq::Sphere<float>{{0, 0, 0}, -1});
    EXPECT_GT(b.lower_x, b.upper_x);
}

}  // namespace
