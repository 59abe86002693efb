// Every tessellator: manifold, expected topology, outward orientation, vertices on the surface and
// analytic normals that match the kernel's own outward_normal().
#include <cmath>
#include <set>
#include <string>

#include <gtest/gtest.h>

#include <rayq/mesh/compare.hpp>
#include <rayq/mesh/mesh.hpp>

namespace {

using namespace rayq;
using namespace rayq::mesh;

struct Expected {
    const char* name;
    long euler;
    std::size_t loops;  // boundary loops
};

// Disk-like patches have χ = 1 and one boundary loop, tubes χ = 0 and two, closed solids χ = 2
// and none; a two-sheet hyperboloid and a double cone are two disks (χ = 2, two loops).
constexpr Expected topologies[] = {
    {"sphere", 2, 0},
    {"disk", 1, 1},
    {"parallelogram", 1, 1},
    {"triangle", 1, 1},
    {"cylinder_open", 0, 2},
    {"cylinder_capped", 2, 0},
    {"frustum_open", 0, 2},
    {"frustum_capped", 2, 0},
    {"cone_open", 1, 1},
    {"cone_capped", 2, 0},
    {"ellipsoid", 2, 0},
    {"ellipsoid_cut", 1, 1},
    {"hyperboloid_one_sheet", 0, 2},
    {"hyperboloid_two_sheets", 2, 2},
    {"paraboloid", 1, 1},
    {"elliptic_cone", 2, 2},
    {"transformed_sphere", 2, 0},
    {"transformed_cylinder_mirror", 2, 0},
    {"transformed_cone_shear", 2, 0},
    {"transformed_hyperboloid", 0, 2},
    {"transformed_disk_mirror", 1, 1},
};

const std::vector<Case>& cases()
{
    static const std::vector<Case> all = standard_cases();
    return all;
}

double angle(const Vec3d& a, const Vec3d& b) { return std::atan2(length(cross(a, b)), dot(a, b)); }

class Tessellator : public ::testing::TestWithParam<std::size_t> {};

TEST(TessellatorList, EveryCaseHasAnExpectedTopology)
{
    ASSERT_EQ(cases().size(), std::size(topologies));
    for (std::size_t i = 0; i < cases().size(); ++i) EXPECT_EQ(cases()[i].name, topologies[i].name);
}

TEST_P(Tessellator, ManifoldWithTheExpectedTopology)
{
    const Case& c = cases()[GetParam()];
    const Expected& want = topologies[GetParam()];
    for (const int n : {3, 8, 13, 32}) {
        SCOPED_TRACE(c.name + ", n = " + std::to_string(n));
        const Tessellation t = c.tessellate(n);
        const Topology topo = topology(t.mesh);
        EXPECT_EQ(t.part.size(), t.mesh.n_faces());
        EXPECT_EQ(topo.nonmanifold_vertices, 0u);
        EXPECT_EQ(topo.degenerate_faces, 0u);
        EXPECT_EQ(topo.euler(), want.euler);
        EXPECT_EQ(topo.boundary_loops, want.loops);
        EXPECT_EQ(t.closed, c.closed);
        if (c.closed) {
            EXPECT_EQ(topo.boundary_edges, 0u);
            EXPECT_EQ(topo.euler(), 2);
        }
    }
}

TEST_P(Tessellator, FacesOutward)
{
    const Case& c = cases()[GetParam()];
    for (const int n : {3, 8, 13, 32}) {
        SCOPED_TRACE(c.name + ", n = " + std::to_string(n));
        const Tessellation t = c.tessellate(n);
        if (c.closed) {
            EXPECT_GT(signed_volume(t.mesh), 0);
        }
        int against = 0, steep = 0;
        for (const auto f : t.mesh.faces()) {
            const Part part = t.part[static_cast<std::size_t>(f.idx())];
            const Vec3d nf = face_normal(t.mesh, f.idx());
            const Vec3d g = c.outward_normal(centroid(t.mesh, f.idx()), part);
            if (!(dot(nf, g) > 0)) ++against;
            // From n = 8 on, each face is within 45° of the surface it approximates.
            if (n >= 8 && !(angle(nf, g) < 0.25 * 3.14159265358979)) ++steep;
        }
        EXPECT_EQ(against, 0) << "faces against the kernel's outward normal at their centroid";
        EXPECT_EQ(steep, 0) << "faces more than 45° off the kernel's outward normal at their centroid";
    }
}

// A vertex whose corner normals (within a part) all agree is a smooth point of that part; an apex
// has corner normals along different generators.
bool apex(const TriMesh& m, TriMesh::VertexHandle v, const std::vector<Part>& parts)
{
    for (const auto h : m.vih_range(v)) {
        if (m.is_boundary(h)) continue;
        for (const auto g : m.vih_range(v)) {
            if (m.is_boundary(g)) continue;
            if (parts[static_cast<std::size_t>(m.face_handle(h).idx())] == parts[static_cast<std::size_t>(m.face_handle(g).idx())] &&
                m.normal(h) != m.normal(g))
                return true;
        }
    }
    return false;
}

TEST_P(Tessellator, VerticesOnTheSurfaceAndNormalsMatchTheKernel)
{
    const Case& c = cases()[GetParam()];
    for (const int n : {8, 13, 32}) {
        SCOPED_TRACE(c.name + ", n = " + std::to_string(n));
        const Tessellation t = c.tessellate(n);
        const TriMesh& m = t.mesh;
        double worst_residual = 0, worst_kernel_t = 0, worst_corner = 0, worst_vertex = 0;
        int kernel_misses = 0, probed = 0;
        for (const auto v : m.vertices()) {
            const Vec3d p = to_vec(m.point(v));
            const bool is_apex = apex(m, v, t.part);
            bool crease = false;
            std::set<int> parts;
            for (const auto h : m.vih_range(v)) {
                if (m.is_boundary(h)) continue;
                const Part part = t.part[static_cast<std::size_t>(m.face_handle(h).idx())];
                parts.insert(static_cast<int>(part));
                // The implicit function of each incident part vanishes at the vertex (to rounding).
                const Implicit im = t.implicit(p, part);
                worst_residual = std::max(worst_residual, std::abs(im.value) / length(im.gradient));
                // Corner normals: the kernel's outward normal of that part (apexes excepted).
                if (!is_apex) worst_corner = std::max(worst_corner, angle(to_vec(m.normal(h)), c.outward_normal(p, part)));
            }
            crease = parts.size() > 1;
            if (is_apex || crease || m.is_boundary(v)) continue;
            // Smooth interior vertex: the vertex normal is the kernel's, and a ray from just outside
            // along −normal meets the kernel's surface at the vertex.
            const Vec3d nv = to_vec(m.normal(v));
            const Part part = static_cast<Part>(*parts.begin());
            worst_vertex = std::max(worst_vertex, angle(nv, c.outward_normal(p, part)));
            const double s = 1e-3;
            const auto hit = c.intersect(Ray<double>{p + s * nv, -nv});
            ++probed;
            if (!hit) ++kernel_misses;
            else worst_kernel_t = std::max(worst_kernel_t, std::abs(hit->t - s));
        }
        EXPECT_LE(worst_residual, 1e-14) << "a vertex off the surface (Sampson distance)";
        EXPECT_EQ(kernel_misses, 0) << "of " << probed << " probes at smooth vertices";
        EXPECT_LE(worst_kernel_t, 1e-14) << "kernel t of a probe at a vertex";
        EXPECT_LE(worst_vertex, 1e-13) << "vertex normal vs the kernel's outward normal (radians)";
        EXPECT_LE(worst_corner, 1e-13) << "corner normal vs the kernel's outward normal of the face's part (radians)";
    }
}

TEST_P(Tessellator, DeviationShrinksQuadratically)
{
    const Case& c = cases()[GetParam()];
    const double d32 = c.tessellate(32).deviation, d64 = c.tessellate(64).deviation;
    if (c.flat && c.name.find("disk") == std::string::npos) {
        EXPECT_LE(d32, 1e-14);  // polygons are their own mesh
        return;
    }
    ASSERT_GT(d64, 0);
    EXPECT_NEAR(d32 / d64, 4.0, 0.5) << c.name;
}

std::string case_name(const ::testing::TestParamInfo<std::size_t>& info) { return cases()[info.param].name; }

INSTANTIATE_TEST_SUITE_P(Mesh, Tessellator, ::testing::Range<std::size_t>(0, std::size(topologies)), case_name);

TEST(Tessellate, RejectsWhatItCannotMesh)
{
    EXPECT_THROW(tessellate(Sphere<double>{{0, 0, 0}, 1}, 2), std::invalid_argument);
    EXPECT_THROW(tessellate(Sphere<double>{{0, 0, 0}, -1}, 8), std::invalid_argument);
    // Unbounded: a hyperboloid without its z clip, a paraboloid open upward.
    Quadric<double> h = Quadric<double>::hyperboloid_one_sheet({0, 0, 0}, 1, 1, 1, 1);
    h.clip = Box<double>::everything();
    EXPECT_THROW(tessellate(h, 8), std::invalid_argument);
    // A rotated hyperboloid is for Transformed; a rotated ellipsoid cut by its clip box is not supported.
    Quadric<double> e = Quadric<double>::ellipsoid({0, 0, 0}, {1, 2, 3}, {1, 1, 0}, {-1, 1, 0});
    e.clip.hi.z = 0.5;
    EXPECT_THROW(tessellate(e, 8), std::invalid_argument);
}

TEST(Tessellate, AMirrorKeepsFacesOutward)
{
    const Sphere<double> s{{0, 0, 0}, 1};
    const Tessellation t = tessellate(transformed(s, Affine3<double>::scaling({-1, 1, 1})), 16);
    EXPECT_GT(signed_volume(t.mesh), 0);
}

}  // namespace
