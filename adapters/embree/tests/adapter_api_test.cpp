// The adapter's interface: hit mapping (Embree's tfar/geomID/primID/Ng and rayq's Hit), rays
// Embree cannot take, invalid primitives, FTZ/DAZ, the low-level UserGeometry in an Embree scene
// of one's own next to native Embree geometry, and other primitive types.
#include <rayq/embree.hpp>

#include <gtest/gtest.h>

#include <xmmintrin.h>

#include <limits>
#include <vector>

namespace {

using rayq::Ray;
using rayq::Sphere;

TEST(EmbreeApi, HitMapsEmbreeAndRayqFields)
{
    const std::vector<rayq::Cylinder<double>> cans{rayq::Cylinder<double>::from_center({0, 0, 0}, {0, 0, 1}, 1.0, 2.0, rayq::Caps::both),
                                                   rayq::Cylinder<double>::from_center({0, 0, 10}, {0, 0, 1}, 1.0, 2.0, rayq::Caps::both)};
    const rayq::embree::Scene<rayq::Cylinder<double>, rayq::accurate_policy> scene(cans);
    const Ray<double> ray{{0.25, 0, 20}, {0, 0, -1}};
    const auto hit = scene.intersect(ray);
    ASSERT_TRUE(hit.has_value());
    EXPECT_EQ(hit->primID, 1u);
    EXPECT_EQ(hit->geomID, 0u);
    EXPECT_EQ(hit->hit.t, 8.0);
    EXPECT_EQ(hit->tfar, 8.0f);
    EXPECT_EQ(hit->hit.part, rayq::Part::cap1);
    EXPECT_TRUE(hit->hit.front_face);
    EXPECT_EQ(hit->hit.normal.z, 1.0);
    EXPECT_TRUE(std::isfinite(hit->hit.t_error));
    EXPECT_TRUE(scene.occluded(ray));
    EXPECT_FALSE(scene.occluded({{0.25, 0, 20}, {0, 0, -1}, 0, 7.9}));  // the window ends before the first cap
    EXPECT_FALSE(scene.intersect({{5, 0, 20}, {0, 0, -1}}).has_value());
}

// Embree's segments start at t >= 0; a window starting before 0 is answered by the scalar loop.
TEST(EmbreeApi, NegativeTminFallsBackToTheScalarLoop)
{
    const std::vector<Sphere<float>> spheres{{{0, 0, -5}, 1}, {{0, 0, 5}, 1}};
    const rayq::embree::Scene<Sphere<float>> scene(spheres);
    const auto hit = scene.intersect({{0, 0, 0}, {0, 0, 1}, -10.0f});
    ASSERT_TRUE(hit.has_value());
    EXPECT_EQ(hit->primID, 0u);
    EXPECT_EQ(hit->hit.t, -6.0f);
    EXPECT_TRUE(scene.occluded({{0, 0, 0}, {0, 0, 1}, -10.0f, -5.5f}));
}

TEST(EmbreeApi, BadRaysAndInvalidPrimitivesNeverHit)
{
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const std::vector<Sphere<float>> spheres{{{0, 0, 5}, -1}, {{0, 0, 8}, nan}, {{0, 0, 12}, 1}};
    const rayq::embree::Scene<Sphere<float>> scene(spheres);
    const auto hit = scene.intersect({{0, 0, 0}, {0, 0, 1}});
    ASSERT_TRUE(hit.has_value());
    EXPECT_EQ(hit->primID, 2u);
    EXPECT_FALSE(scene.intersect({{nan, 0, 0}, {0, 0, 1}}).has_value());
    EXPECT_FALSE(scene.intersect({{0, 0, 0}, {0, 0, 0}}).has_value());
    EXPECT_FALSE(scene.occluded({{0, 0, 0}, {0, 0, 1}, 5, 5}));
    // Beyond Embree's range: a primitive past ±1e18 (its box becomes the whole range), a ray whose
    // float copy overflows, an origin past 5e17 (both answered without Embree): as the scalar query.
    const std::vector<Sphere<double>> far{{{0, 0, 1e30}, 1e29}, {{0, 0, 0}, 1}};
    const rayq::embree::Scene<Sphere<double>> far_scene(far);
    const auto expect_scalar = [&](const Ray<double>& ray, std::size_t index) {
        const auto hit = far_scene.intersect(ray);
        ASSERT_TRUE(hit.has_value());
        EXPECT_EQ(hit->primID, index);
        EXPECT_EQ(hit->hit.t, rayq::intersect(ray, far[index])->t);
    };
    expect_scalar({{0, 0, 5}, {0, 0, 1}}, 0);
    expect_scalar({{0, 0, -1e40}, {0, 0, 1}}, 1);
    expect_scalar({{0, 0, -1e18}, {0, 0, 1}}, 1);
}

// With FTZ/DAZ on (as Embree recommends) the callbacks still decide in IEEE arithmetic, and the
// caller's mode is restored.
TEST(EmbreeApi, FtzDazIsOffInsideCallbacksAndRestored)
{
    const std::vector<Sphere<float>> spheres{{{0, 0, 5}, 1}};
    const rayq::embree::Scene<Sphere<float>, rayq::accurate_policy> scene(spheres);
    const unsigned saved = _mm_getcsr();
    _mm_setcsr(saved | 0x8040u);
    const auto hit = scene.intersect({{0, 0, 0}, {0, 0, 1}});
    const unsigned during = _mm_getcsr();
    _mm_setcsr(saved);
    ASSERT_TRUE(hit.has_value());
    EXPECT_EQ(hit->hit.t, 4.0f);
    EXPECT_EQ(during & 0x8040u, 0x8040u);
}

// The record is built in IEEE arithmetic too, not only the callbacks' decisions: a hit whose point
// has a subnormal coordinate (DAZ would read it as 0) gets the normal rayq computes with gradual
// underflow. And a QueryContext keeps FTZ/DAZ off while it lives, restoring the caller's mode.
TEST(EmbreeApi, FtzDazIsOffForTheWholeQueryRecordIncluded)
{
    const Sphere<float> tiny{{0, 0, 0}, 2e-38f};
    const Ray<float> ray{{1e-39f, 0, -1e-37f}, {0, 0, 1}};  // x subnormal: the normal's x is about 0.05
    const auto expected = rayq::intersect(rayq::accurate, ray, tiny);
    ASSERT_TRUE(expected.has_value());
    ASSERT_GT(expected->normal.x, 0.01f);
    ASSERT_LT(expected->normal.x, 0.1f);
    const rayq::embree::Scene<Sphere<float>, rayq::accurate_policy> scene({tiny});
    const unsigned saved = _mm_getcsr();
    _mm_setcsr(saved | 0x8040u);
    const auto hit = scene.intersect(ray);
    unsigned inside = 0;
    {
        rayq::embree::QueryContext<float> ctx(ray);
        inside = _mm_getcsr();
    }
    const unsigned after = _mm_getcsr();
    _mm_setcsr(saved);
    ASSERT_TRUE(hit.has_value());
    EXPECT_EQ(hit->hit.t, expected->t);
    EXPECT_EQ(hit->hit.normal.x, expected->normal.x);
    EXPECT_EQ(hit->hit.normal.z, expected->normal.z);
    EXPECT_EQ(hit->hit.t_error, expected->t_error);
    EXPECT_EQ(inside & 0x8040u, 0u);
    EXPECT_EQ(after & 0x8040u, 0x8040u);
    // The record asked for directly, outside any query, under the caller's FTZ/DAZ.
    _mm_setcsr(saved | 0x8040u);
    const auto direct = scene.geometry().hit_record(ray, 0);
    _mm_setcsr(saved);
    ASSERT_TRUE(direct.has_value());
    EXPECT_EQ(direct->normal.x, expected->normal.x);
    EXPECT_EQ(direct->t_error, expected->t_error);
}

// A user's own Embree scene: a rayq geometry next to a native Embree triangle, one context.
TEST(EmbreeApi, UserGeometryInAnEmbreeSceneWithNativeGeometry)
{
    RTCDevice device = rtcNewDevice("threads=1");
    ASSERT_NE(device, nullptr);
    RTCScene scene = rtcNewScene(device);
    rayq::embree::UserGeometry<Sphere<double>, rayq::accurate_policy> balls(device, {{{0, 0, 10}, 1}, {{0, 0, 20}, 1}});
    const unsigned balls_id = balls.attach(scene);
    // A native triangle at z = 15 spanning the axis.
    RTCGeometry tri = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
    auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(tri, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), 4));
    const float verts[12] = {-5, -5, 15, 5, -5, 15, 0, 5, 15, 0, 0, 0};  // one spare vertex: Embree reads past the last
    std::copy(verts, verts + 12, v);
    auto* idx = static_cast<unsigned*>(rtcSetNewGeometryBuffer(tri, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), 1));
    idx[0] = 0, idx[1] = 1, idx[2] = 2;
    rtcCommitGeometry(tri);
    const unsigned tri_id = rtcAttachGeometry(scene, tri);
    rtcReleaseGeometry(tri);
    rtcCommitScene(scene);

    const auto trace = [&](rayq::embree::QueryContext<double>& ctx) {
        RTCRayHit rh = *ctx.embree_ray();
        rtcIntersect1(scene, ctx.context(), &rh);
        return rh;
    };
    {   // From below: the sphere at z = 10 is nearer than the triangle.
        const Ray<double> ray{{0, 0, 0}, {0, 0, 1}};
        rayq::embree::QueryContext<double> ctx(ray);
        const RTCRayHit rh = trace(ctx);
        EXPECT_EQ(rh.hit.geomID, balls_id);
        EXPECT_EQ(rh.hit.primID, 0u);
        EXPECT_EQ(rh.ray.tfar, 9.0f);
        EXPECT_EQ(ctx.t, 9.0);
        EXPECT_LT(rh.hit.Ng_z, 0.0f);  // outward normal at the sphere's bottom
        EXPECT_EQ(balls.hit_record(ray, rh.hit.primID)->t, 9.0);
        const auto kept = balls.hit_record(ctx);  // from the crossing the callback kept: the same record
        ASSERT_TRUE(kept.has_value());
        EXPECT_EQ(kept->t, 9.0);
        EXPECT_EQ(kept->t_error, balls.hit_record(ray, rh.hit.primID)->t_error);
        EXPECT_EQ(kept->normal.z, balls.hit_record(ray, rh.hit.primID)->normal.z);
    }
    {   // From z = 12 upwards: the triangle (t = 3) is nearer than the sphere at 20 (t = 7).
        const Ray<double> ray{{0, 0, 12}, {0, 0, 1}};
        rayq::embree::QueryContext<double> ctx(ray);
        const RTCRayHit rh = trace(ctx);
        EXPECT_EQ(rh.hit.geomID, tri_id);
        EXPECT_EQ(rh.ray.tfar, 3.0f);
        // The context may still hold the sphere's farther hit (t = 7) if Embree met it first.
        if (ctx.found()) {
            EXPECT_EQ(ctx.t, 7.0);
        }
    }
    {   // A miss: no record from the context.
        const Ray<double> ray{{0, 0, 0}, {0, 0, -1}};
        rayq::embree::QueryContext<double> ctx(ray);
        const RTCRayHit rh = trace(ctx);
        EXPECT_EQ(rh.hit.geomID, RTC_INVALID_GEOMETRY_ID);
        EXPECT_FALSE(balls.hit_record(ctx).has_value());
    }
    {   // A plain context (no QueryContext): Embree's float ray decides, the hit fields are Embree's.
        RTCIntersectContext plain;
        rtcInitIntersectContext(&plain);
        RTCRayHit rh{};
        rh.ray.org_z = 0, rh.ray.dir_z = 1, rh.ray.tnear = 0, rh.ray.tfar = std::numeric_limits<float>::infinity(), rh.ray.mask = ~0u;
        rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
        rtcIntersect1(scene, &plain, &rh);
        EXPECT_EQ(rh.hit.geomID, balls_id);
        EXPECT_EQ(rh.ray.tfar, 9.0f);
        RTCRay shadow = rh.ray;
        shadow.tfar = 8.5f;
        rtcOccluded1(scene, &plain, &shadow);
        EXPECT_EQ(shadow.tfar, 8.5f);  // not occluded before the sphere
        shadow.tfar = 9.5f;
        rtcOccluded1(scene, &plain, &shadow);
        EXPECT_EQ(shadow.tfar, -std::numeric_limits<float>::infinity());
    }
    rtcReleaseScene(scene);
    rtcReleaseDevice(device);
}

// Any rayq primitive with a box: triangles, disks, cones, transformed instances.
TEST(EmbreeApi, OtherPrimitiveTypes)
{
    const rayq::embree::Scene<rayq::Triangle<float>> tris(std::vector<rayq::Triangle<float>>{{{-1, -1, 5}, {1, -1, 5}, {0, 1, 5}}});
    EXPECT_EQ(tris.intersect({{0, 0, 0}, {0, 0, 1}})->hit.t, 5.0f);
    const rayq::embree::Scene<rayq::Cone<double>, rayq::accurate_policy> cones(
        std::vector<rayq::Cone<double>>{{{0, 0, 3}, 1.0, {0, 0, 6}, 0.0, rayq::Caps::both}});
    EXPECT_EQ(cones.intersect({{0, 0, 0}, {0, 0, 1}})->hit.t, 3.0);
    using Moved = rayq::Transformed<Sphere<double>>;
    const rayq::embree::Scene<Moved> moved(std::vector<Moved>{rayq::transformed(Sphere<double>{{0, 0, 0}, 1}, rayq::Affine3<double>::translation({0, 0, 7}))});
    EXPECT_NEAR(moved.intersect({{0, 0, 0}, {0, 0, 1}})->hit.t, 6.0, 1e-12);
    EXPECT_FALSE(moved.intersect({{0, 2, 0}, {0, 0, 1}}).has_value());
}

}  // namespace
