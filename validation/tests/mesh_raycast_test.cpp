// The ray–mesh closest hit (CGAL AABB tree): t, barycentric point, interpolated normal, front side,
// the ray's window, and no ray slipping through a shared edge or vertex.
#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include <rayq/mesh/raycast.hpp>

namespace {

using namespace rayq;
using namespace rayq::mesh;

TEST(Raycast, FlatFaceAgreesWithTheKernel)
{
    const Parallelogram<double> p{{-1.0, -0.5, 0.2}, {2.0, 0.3, 0.1}, {0.4, 1.5, -0.3}};
    const Tessellation t = tessellate(p, 8);
    const Raycaster caster(t.mesh);
    EXPECT_EQ(caster.size(), t.mesh.n_faces());
    const Vec3d nrm = normalize(cross(p.edge0, p.edge1));
    for (const double side : {1.0, -1.0}) {
        const Ray<double> ray{p.corner + 0.3 * p.edge0 + 0.6 * p.edge1 + 2.0 * side * nrm + Vec3d{0.1, -0.2, 0.05}, -side * nrm};
        const auto m = caster.closest_hit(ray);
        const auto k = intersect(accurate, ray, p);
        ASSERT_TRUE(m && k);
        EXPECT_NEAR(m->t, k->t, 1e-14);
        EXPECT_EQ(m->front, k->front_face);
        EXPECT_EQ(m->front, side > 0);
        EXPECT_FALSE(m->coplanar);
        EXPECT_NEAR(m->bary[0] + m->bary[1] + m->bary[2], 1.0, 1e-15);
        for (const double b : m->bary) EXPECT_GE(b, 0.0);
        const Vec3d expected = point_at(ray, m->t);
        EXPECT_NEAR(length(m->point - expected), 0.0, 1e-14);
        EXPECT_NEAR(length(m->normal - nrm), 0.0, 1e-15);  // outward, whichever side the ray comes from
    }
}

TEST(Raycast, NoRaySlipsThroughAnEdgeOrAVertex)
{
    // A 4×4 grid of squares (32 triangles): aim at every vertex and every edge midpoint.
    const Parallelogram<double> p{{0.0, 0.0, 0.0}, {1.0, 0.0, 0.0}, {0.0, 1.0, 0.0}};
    const Tessellation t = tessellate(p, 32);
    const Raycaster caster(t.mesh);
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    int misses = 0, shots = 0;
    for (const auto e : t.mesh.edges()) {
        const auto h = t.mesh.halfedge_handle(e, 0);
        const Vec3d a = to_vec(t.mesh.point(t.mesh.from_vertex_handle(h))), b = to_vec(t.mesh.point(t.mesh.to_vertex_handle(h)));
        for (const Vec3d& target : {a, 0.5 * (a + b)}) {
            for (int i = 0; i < 8; ++i) {
                const Vec3d from{u(rng), u(rng), 0.5 + u(rng) * 0.4 + (i % 2 ? -2.0 : 0.0)};
                ++shots;
                const auto m = caster.closest_hit({from, target - from});
                if (!m) ++misses;
                else EXPECT_NEAR(m->t, 1.0, 1e-14);
            }
        }
    }
    EXPECT_EQ(misses, 0) << "of " << shots;
}

TEST(Raycast, ClosedMeshFrontBackAndWindow)
{
    const Sphere<double> s{{0.0, 0.0, 0.0}, 1.0};
    const Tessellation t = tessellate(s, 32);
    const Raycaster caster(t.mesh);
    const Ray<double> outside{{-3.0, 0.01, 0.02}, {1.0, 0.0, 0.0}};
    const auto in = caster.closest_hit(outside);
    ASSERT_TRUE(in);
    EXPECT_TRUE(in->front);
    EXPECT_NEAR(in->t, 2.0, 2 * t.deviation);
    EXPECT_EQ(in->candidates, 2);  // enters and leaves
    EXPECT_LT(dot(in->normal, outside.direction), 0);  // outward at the near side
    // Past the near side (tmin), the far side from within.
    const auto out = caster.closest_hit({outside.origin, outside.direction, in->t + 0.5});
    ASSERT_TRUE(out);
    EXPECT_FALSE(out->front);
    EXPECT_NEAR(out->t, 4.0, 2 * t.deviation);
    EXPECT_GT(dot(out->normal, outside.direction), 0);
    // A window that ends before the sphere.
    EXPECT_FALSE(caster.closest_hit({outside.origin, outside.direction, 0.0, 1.5}));
    // From the center: every direction leaves through a back face.
    const auto center = caster.closest_hit({{0.0, 0.0, 0.0}, {0.3, -0.4, 0.5}});
    ASSERT_TRUE(center);
    EXPECT_FALSE(center->front);
    EXPECT_FALSE(caster.closest_hit({{0.0, 0.0, 0.0}, {0.0, 0.0, 0.0}}));  // unusable ray
}

TEST(Raycast, CornerNormalsFollowTheHitPart)
{
    const Cylinder<double> cyl{{0.0, 0.0, -1.0}, {0.0, 0.0, 1.0}, 1.0, Caps::both};
    const Tessellation t = tessellate(cyl, 64);
    const Raycaster caster(t.mesh);
    // Near the rim, on the cap: the cap's normal exactly, though the face's vertices include rim vertices.
    const auto cap = caster.closest_hit({{0.9, 0.0, 3.0}, {0.0, 0.0, -1.0}});
    ASSERT_TRUE(cap);
    EXPECT_EQ(t.part[static_cast<std::size_t>(cap->face)], Part::cap1);
    EXPECT_EQ(cap->normal.z, 1.0);
    // On the side, just below the rim: radial.
    const auto side = caster.closest_hit({{3.0, 0.01, 0.99}, {-1.0, 0.0, 0.0}});
    ASSERT_TRUE(side);
    EXPECT_EQ(t.part[static_cast<std::size_t>(side->face)], Part::surface);
    EXPECT_NEAR(side->normal.x, 1.0, 1e-3);
    EXPECT_NEAR(side->normal.z, 0.0, 1e-15);
}

TEST(Raycast, OriginInAFacePlaneIsFlagged)
{
    const Disk<double> d{{0.0, 0.0, 0.0}, {0.0, 0.0, 1.0}, 1.0};
    const Raycaster caster(tessellate(d, 16).mesh);
    // Starting on the disk's plane, leaving it: no hit at t > 0.
    EXPECT_FALSE(caster.closest_hit({{0.2, 0.1, 0.0}, {0.0, 0.0, 1.0}}));
    // Inside the plane, along it: met edge-on (the whole disk lies along the ray) — degenerate, not a hit.
    const auto along = caster.closest_hit({{-2.0, 0.1, 0.0}, {1.0, 0.0, 0.0}});
    EXPECT_FALSE(along.has_value());
}

}  // namespace
