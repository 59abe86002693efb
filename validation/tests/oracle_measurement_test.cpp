// The kernel measured against the exact oracle on every checked-in fixture (fixtures/oracle/),
// under all three policies, float and double. Prints one summary line per primitive × policy ×
// type. Asserts the oracle's own consistency; that on the generic (non-grazing) family every
// policy agrees with the oracle on hit/miss in double; the accurate contract (issue 4) on the
// primitives in scope; and certified bounds for every policy and primitive.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <set>
#include <tuple>
#include <type_traits>

#include <rayq/oracle/harness.hpp>

namespace {

using namespace rayq;
using namespace rayq::oracle;

const std::vector<Fixture>& fixtures()
{
    static const std::vector<Fixture> all = load_fixture_directory(RAYQ_ORACLE_FIXTURES);
    return all;
}

TEST(OracleMeasurement, OracleIsSelfConsistentOnEveryFixture)
{
    for (const Fixture& f : fixtures()) {
        SCOPED_TRACE(format_fixture(f));
        const Truth truth = truth_of(f.input);
        const ExactHit& h = truth.first_hit();
        ASSERT_TRUE(h.defined);
        // Deterministic: a second Truth says the same.
        EXPECT_EQ(truth_of(f.input).first_hit().t_exact, h.t_exact);
        for (std::size_t k = 1; k < h.crossings.size(); ++k) EXPECT_LE(h.crossings[k - 1], h.crossings[k]);
        if (!h.hit) continue;
        std::visit(
            [&](const auto& in) {
                // The hit lies in the window, is one of the line's crossings, and rounds consistently.
                EXPECT_GT(h.t_long, static_cast<long double>(in.ray.tmin));
                EXPECT_LT(h.t_long, static_cast<long double>(in.ray.tmax));
                EXPECT_NE(std::find(h.crossings.begin(), h.crossings.end(), h.t_long), h.crossings.end());
                const long double ulp_d = std::nextafter(std::fabs(h.t_double), INFINITY) - std::fabs(h.t_double);
                EXPECT_LE(std::fabs(h.t_long - h.t_double), 0.5L * ulp_d * (1 + 1e-6L));
                const long double ulp_f = std::nextafter(std::fabs(h.t_float), INFINITY) - std::fabs(h.t_float);
                EXPECT_LE(std::fabs(h.t_long - h.t_float), 0.5L * ulp_f * (1 + 1e-6L));
                if (h.normal_defined) {
                    const Vec3<double>& n = h.facing_normal;
                    EXPECT_NEAR(n.x * n.x + n.y * n.y + n.z * n.z, 1.0, 1e-14);
                    const double dn = n.x * in.ray.direction.x + n.y * in.ray.direction.y + n.z * in.ray.direction.z;
                    const double dd = std::sqrt(double(in.ray.direction.x) * in.ray.direction.x +
                                                double(in.ray.direction.y) * in.ray.direction.y +
                                                double(in.ray.direction.z) * in.ray.direction.z);
                    EXPECT_LE(dn, 1e-12 * dd);  // faces the ray (up to the normal's rounding)
                }
                // The exact answer, rounded, measured as a kernel answer: at most half an ulp, faithful.
                using T = std::decay_t<decltype(in.ray.tmin)>;
                Hit<T> exact{};
                exact.t = std::is_same_v<T, float> ? T(h.t_float) : T(h.t_double);
                exact.normal = {T(h.facing_normal.x), T(h.facing_normal.y), T(h.facing_normal.z)};
                exact.front_face = h.entering;
                exact.part = h.part;
                const Measurement m = truth.measure(std::optional<Hit<T>>(exact));
                EXPECT_TRUE(m.hit_agrees && m.part_agrees && m.front_face_agrees && m.faithful);
                EXPECT_LE(m.ulps, 0.5);
                EXPECT_FALSE(m.other_crossing);
            },
            f.input);
    }
}

// Issue 4's contract for rayq::accurate on the primitives in scope, on every checked-in fixture
// family, float and double: hit/miss, part and front face agree with the exact oracle; t is
// within 1 ulp (faithful; the kernel rounds correctly, so within half an ulp); no certified
// bound is violated.
TEST(OracleMeasurement, AccurateContractOnEveryFixture)
{
    const std::set<std::string> in_scope = {"sphere", "plane", "disk", "parallelogram", "triangle", "cylinder", "cone"};
    std::size_t checked = 0, hits = 0;
    for (const Fixture& f : fixtures()) {
        if (!in_scope.count(primitive_name(f.input))) continue;
        const Measurement m = measure_all_policies(truth_of(f.input), f.input)[2];
        ASSERT_TRUE(m.defined) << format_fixture(f);
        ++checked;
        EXPECT_TRUE(m.hit_agrees) << "accurate disagrees on hit/miss:\n" << format_fixture(f);
        EXPECT_FALSE(m.bound_violated) << "accurate's t_error is violated:\n" << format_fixture(f);
        if (!m.both_hit) continue;
        ++hits;
        EXPECT_TRUE(m.part_agrees) << format_fixture(f);
        EXPECT_TRUE(m.front_face_agrees) << format_fixture(f);
        EXPECT_TRUE(m.faithful) << format_fixture(f);
        EXPECT_LE(m.ulps, 0.5) << format_fixture(f);
    }
    EXPECT_GT(checked, 200u);
    EXPECT_GT(hits, 100u);
}

// Issue 4: every policy's t_error holds — the exact first hit lies within [t − t_error, t + t_error]
// for every hit (a false hit's finite bound is a violation) — on every checked-in fixture, every
// reproducer that once broke it, and freshly generated cases of every family, all primitives.
TEST(OracleMeasurement, CertifiedBoundsHoldForEveryPolicyAndPrimitive)
{
    std::vector<Fixture> cases = fixtures();
    for (const Fixture& f : load_fixture_directory(RAYQ_ORACLE_REPRODUCERS)) cases.push_back(f);
    for (const std::string& primitive : generated_primitives())
        for (Scalar s : {Scalar::f32, Scalar::f64})
            for (const Fixture& f : generate_cases(primitive, s, 300, 20261122)) cases.push_back(f);
    std::size_t bounded = 0;
    for (const Fixture& f : cases) {
        const auto m = measure_all_policies(truth_of(f.input), f.input);
        for (int i = 0; i < 3; ++i) {
            if (!m[i].defined) continue;
            EXPECT_FALSE(m[i].bound_violated) << policy_name(all_policies[i]) << "'s t_error misses the exact first hit:\n"
                                              << format_fixture(f);
            bounded += m[i].bounded;
        }
    }
    EXPECT_GT(bounded, cases.size());  // most hits carry a finite bound: the test is not vacuous
}

TEST(OracleMeasurement, KernelAgainstOracleOnEveryFixture)
{
    // primitive, policy, type → tally; and the generic-family hit/miss check.
    std::map<std::tuple<std::string, int, int>, Tally> tallies;
    std::size_t generic_double = 0;
    for (const Fixture& f : fixtures()) {
        const Truth truth = truth_of(f.input);
        const auto m = measure_all_policies(truth, f.input);
        const Scalar s = scalar_of(f.input);
        for (int i = 0; i < 3; ++i) {
            tallies[{primitive_name(f.input), i, s == Scalar::f64 ? 0 : 1}].add(m[i]);
            if (family_class(f.family) == "generic" && s == Scalar::f64) {
                EXPECT_TRUE(m[i].hit_agrees) << policy_name(all_policies[i]) << " disagrees with the oracle on hit/miss:\n"
                                             << format_fixture(f);
            }
        }
        if (family_class(f.family) == "generic" && s == Scalar::f64) ++generic_double;
    }
    EXPECT_GT(generic_double, 30u);

    std::printf("\nrayq kernel vs exact oracle, %zu checked-in fixtures (%s)\n", fixtures().size(), RAYQ_ORACLE_FIXTURES);
    std::printf("%s\n", table_header().c_str());
    for (const std::string& primitive : generated_primitives())
        for (int policy = 0; policy < 3; ++policy)
            for (int type = 0; type < 2; ++type) {
                const auto it = tallies.find({primitive, policy, type});
                if (it == tallies.end()) continue;
                const SummaryRow row{primitive, policy_name(all_policies[policy]), type == 0 ? "double" : "float", "all", it->second};
                std::printf("%s\n", table_line(row).c_str());
            }
    std::fflush(stdout);
}

}  // namespace
