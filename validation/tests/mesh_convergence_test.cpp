// The kernel (rayq::accurate, double) against meshes of every bounded primitive, n = 8 … 128, on a
// CI-sized set of rays: no hit/miss, part, front-face or t disagreement outside the band, and the
// median t error and normal error converging as O(n⁻²) (log–log slope within [−2.2, −1.8]). The
// full sweep (n = 8 … 512, more rays) is rayq-mesh-sweep.
#include <cmath>
#include <string>

#include <gtest/gtest.h>

#include <rayq/mesh/compare.hpp>

namespace {

using namespace rayq;
using namespace rayq::mesh;

const std::vector<Case>& cases()
{
    static const std::vector<Case> all = standard_cases();
    return all;
}

SweepOptions ci_options()
{
    SweepOptions o;
    o.resolutions = {8, 16, 32, 64, 128};
    o.rays = 1500;
    o.seed = 1;
    o.max_examples = 4;
    return o;
}

class AgainstMesh : public ::testing::TestWithParam<std::size_t> {};

TEST_P(AgainstMesh, AgreesOutsideTheBandAndConvergesQuadratically)
{
    const Case& c = cases()[GetParam()];
    const CaseResult r = run_case(c, ci_options());
    for (const Disagreement& d : r.examples) ADD_FAILURE() << d.kind << " at n = " << d.n << ": " << d.detail;
    for (const Level& l : r.levels) {
        SCOPED_TRACE(c.name + ", n = " + std::to_string(l.n));
        EXPECT_EQ(l.hit_miss, 0u);
        EXPECT_EQ(l.part, 0u);
        EXPECT_EQ(l.front, 0u);
        EXPECT_EQ(l.t_outliers, 0u);
        // Enough of the rays are compared (at n = 8 the band takes out up to 40%), from outside and inside.
        EXPECT_GT(l.compared_hits, l.rays / 20);
        EXPECT_GT(l.inside_origins, 0u);
        // Flat parts (polygons, disks, caps): the mesh is the surface, t errs by rounding only.
        EXPECT_LE(l.t_flat.max, 1e-12);
        EXPECT_LE(l.normal_flat.max, 1e-12);
        if (c.flat) {
            EXPECT_EQ(l.t_curved.count, 0u);
        }
    }
    std::string table;
    for (const Level& l : r.levels)
        table += "n=" + std::to_string(l.n) + " common=" + std::to_string(l.t_common.count) + " t=" + std::to_string(l.t_common.median) +
                 " normal=" + std::to_string(l.normal_common.median) + "; ";
    if (c.flat) {
        EXPECT_TRUE(std::isnan(r.slope_t));
        return;
    }
    EXPECT_GE(r.levels.front().t_common.count, 100u) << table;
    // The expected rate for t: O(n⁻²).
    EXPECT_GE(r.slope_t, -2.2) << table;
    EXPECT_LE(r.slope_t, -1.8) << table;
    // Interpolated normals: O(n⁻²) as well (at an apex the corner normals differ by O(1/n), but
    // those fan triangles cover O(n⁻²) of the surface and do not move the median).
    EXPECT_GE(r.slope_normal, -2.2) << table;
    EXPECT_LE(r.slope_normal, -1.8) << table;
    std::printf("[ %s ] slope t %.3f, slope normal %.3f; %s\n", c.name.c_str(), r.slope_t, r.slope_normal, table.c_str());
}

std::string case_name(const ::testing::TestParamInfo<std::size_t>& info) { return cases()[info.param].name; }

INSTANTIATE_TEST_SUITE_P(Mesh, AgainstMesh, ::testing::Range<std::size_t>(0, standard_cases().size()), case_name);

TEST(Slope, LeastSquaresInLogLog)
{
    EXPECT_NEAR(loglog_slope({8, 16, 32}, {1.0 / 64, 1.0 / 256, 1.0 / 1024}), -2.0, 1e-12);
    EXPECT_NEAR(loglog_slope({1, 2, 4, 8}, {3, 6, 12, 24}), 1.0, 1e-12);
    EXPECT_TRUE(std::isnan(loglog_slope({8, 16}, {1.0, 0.0})));
    EXPECT_TRUE(std::isnan(loglog_slope({8}, {1.0})));
}

}  // namespace
