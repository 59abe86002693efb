// The precision sweeps of issue 6 on the kernel, against the exact oracle, fitted with rayq::fit
// (whose own tests, fit_error_model_test.cpp, establish that the fits recover known parameters).
// CI-sized: a few dozen cases per decade; `rayq-sweep` runs the full sweeps.
//
// What is asserted, and why it is true:
//  * accurate, on the primitives where it decides exactly (sphere, plane, disk, parallelogram,
//    triangle, cylinder, cone — README "Policies"): the fitted exponent p <= 0.05 toward tangency
//    (and toward the flat primitives' parallel and rim limits), at distance and under
//    translation, and no hit/miss or part misclassification at all.
//  * fast on the sphere: p = 0.5 ± 0.1 (the textbook discriminant b² − 4ac cancels: its error
//    ~ε·b² against a value ~δ·b² near tangency, so √Δ and t carry ε/√δ).
//  * stable on the sphere: the same exponent, a smaller constant (Hearn–Baker's r² − |f⊥|²).
//  * accurate on quadrics and transformed instances is NOT exact (README: error-free products and
//    stable roots; a transformed primitive also stores a rounded to_object): there it grows like
//    stable, and the test says so instead of asserting a flatness that does not hold.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <rayq/fit/sweep.hpp>

namespace {

using namespace rayq;
using namespace rayq::fit;
using oracle::Policy;
using oracle::Scalar;

const std::vector<std::string> exact_scope = {"sphere", "plane", "disk", "parallelogram", "triangle", "cylinder", "cone"};

// 24 cases per decade: 12 on each side of tangency (or of the rim). Enough for a per-decade
// median within ~±20% and for a misclassification to show. The whole file measured 12.8 s of
// CPU (6.4 s wall with ctest -j2) on a loaded 2-core machine; the oracle is the cost.
constexpr std::size_t ci_cases = 24;

std::string label(const Series& s)
{
    return s.primitive + " " + oracle::scalar_name(s.scalar) + " " + oracle::policy_name(s.policy) + " " + sweep_kind_name(s.kind) +
           " " + s.family_class;
}

void print(const Series& s, const SeriesFit& f)
{
    std::printf("%-55s p(median) %s%.3f ± %.3f  C0 %.3g  C1 %.3g | p(p99) %.3f ± %.3f | misclassified %zu\n", label(s).c_str(),
                f.median.flat ? "flat " : "", f.median.p.value, f.median.p.se, f.median.C0.value, f.median.C1.value, f.p99.p.value,
                f.p99.p.se, f.misclassified);
}

std::vector<Series> sweep(const std::string& primitive, Scalar scalar, SweepKind kind, std::vector<Policy> policies,
                          std::size_t cases = ci_cases)
{
    SweepOptions o;
    o.cases_per_x = cases;
    o.seed = 6;  // issue 6; any seed must do
    o.policies = std::move(policies);
    return run_sweep(primitive, scalar, kind, o);
}

// accurate where it is exact: flat and never wrong, for every sweep kind.
void expect_accurate_flat_and_correct(SweepKind kind, std::size_t cases)
{
    for (const std::string& primitive : exact_scope) {
        for (Scalar scalar : {Scalar::f64, Scalar::f32}) {
            const std::vector<Series> all = sweep(primitive, scalar, kind, {Policy::accurate}, cases);
            ASSERT_FALSE(all.empty()) << primitive << " has no " << sweep_kind_name(kind) << " families";
            for (const Series& s : all) {
                const SeriesFit f = fit_series(s);
                print(s, f);
                ASSERT_TRUE(f.median.ok) << label(s) << ": " << f.median.why;
                ASSERT_TRUE(f.p99.ok) << label(s) << ": " << f.p99.why;
                EXPECT_LE(f.median.p.value, 0.05) << label(s) << ": accurate's median error grows";
                EXPECT_LE(f.p99.p.value, 0.05) << label(s) << ": accurate's 99th-percentile error grows";
                EXPECT_EQ(f.misclassified, 0u) << label(s) << ": accurate decides hit/miss and part exactly here";
                EXPECT_TRUE(f.hit.ok && f.hit.always_correct) << label(s);
                // Correctly rounded: every error within half an ulp.
                for (const SweepPoint& p : s.points) EXPECT_LE(p.max_ulps, 0.5) << label(s) << " at x = " << p.x;
            }
        }
    }
}

TEST(PrecisionSweep, AccurateIsFlatAndNeverMisclassifiesTowardTangency)
{
    expect_accurate_flat_and_correct(SweepKind::closeness, ci_cases);
}

TEST(PrecisionSweep, AccurateIsFlatAndNeverMisclassifiesAtDistanceAndUnderTranslation)
{
    // The translated family aims generic rays around the primitive: for a small triangle or
    // parallelogram most miss, and a decade needs ~100 cases for a few dozen ulp errors and a
    // median steady enough that the flat fit's standard error falls well below 0.05 (at 24 cases
    // it was ±0.08, and some decades had no hit at all). The far family is the same size for
    // symmetry; both are cheap (8 decades).
    expect_accurate_flat_and_correct(SweepKind::distance, 4 * ci_cases);
    expect_accurate_flat_and_correct(SweepKind::translation, 4 * ci_cases);
}

// Fits of fast and stable grazing a sphere, in one sweep (the exact answers are shared).
struct SphereFits {
    SeriesFit fast, stable;
};
SphereFits sphere_grazing(Scalar scalar, std::size_t cases)
{
    SphereFits out;
    for (const Series& s : sweep("sphere", scalar, SweepKind::closeness, {Policy::fast, Policy::stable}, cases)) {
        const SeriesFit f = fit_series(s);
        print(s, f);
        (s.policy == Policy::fast ? out.fast : out.stable) = f;
    }
    return out;
}

TEST(PrecisionSweep, FastOnTheSphereGrowsAsInverseSquareRootOfDelta)
{
    // Double: 15 decades pin p well. Float: only 7 decades, so more cases per decade (the sphere
    // is the cheapest primitive to decide) keep the median steady enough for ±0.1. Measured over
    // seeds 1–8 at these sizes: double 0.489–0.515, float 0.457–0.489.
    const struct {
        Scalar scalar;
        std::size_t cases;
    } runs[] = {{Scalar::f64, 48}, {Scalar::f32, 96}};
    for (const auto& run : runs) {
        const SphereFits f = sphere_grazing(run.scalar, run.cases);
        ASSERT_TRUE(f.fast.median.ok) << f.fast.median.why;
        EXPECT_FALSE(f.fast.median.flat) << oracle::scalar_name(run.scalar) << ": fast showed no growth toward tangency";
        EXPECT_NEAR(f.fast.median.p.value, 0.5, 0.1)
            << oracle::scalar_name(run.scalar) << ": the theory says fast's error grows as δ^-1/2 near tangency";
    }
}

TEST(PrecisionSweep, StableKeepsTheExponentAndShrinksTheConstant)
{
    // The theory (issue 6): Hearn–Baker keeps the exponent and divides the constant by about
    // distance/radius. The grazing family starts its rays 1.5 to 5 radii away, so the constant
    // must shrink by more than the smallest distance/radius in it, 1.5. (The family mixes
    // distances, so it cannot tell distance/radius from its square: rayq-sweep prints the ratio.)
    const SphereFits f = sphere_grazing(Scalar::f64, 48);
    ASSERT_TRUE(f.fast.median.ok && f.stable.median.ok);
    ASSERT_FALSE(f.stable.median.flat) << "stable showed no growth toward tangency";
    EXPECT_NEAR(f.stable.median.p.value, f.fast.median.p.value, 0.1) << "stable's exponent differs from fast's";
    EXPECT_GT(f.fast.median.C1.value / f.stable.median.C1.value, 1.5) << "stable's growth constant is not smaller than fast's";
    std::printf("sphere double: C1 fast / C1 stable = %.3g\n", f.fast.median.C1.value / f.stable.median.C1.value);
}

TEST(PrecisionSweep, AccurateOutsideItsExactScopeGrowsLikeStable)
{
    // Quadrics and transformed instances: accurate uses error-free products and stable roots, not
    // exact decisions (README "Policies"), and a Transformed stores a rounded to_object while the
    // oracle inverts to_world exactly. So toward tangency accurate's error grows with the exponent
    // of a root computed from rounded coefficients — 1/2 for curved surfaces, 1 for the transformed
    // triangle's 1/(d·n) — and it can misclassify. If p drops here, accurate became exact for the
    // primitive: move it to exact_scope above, where flatness is asserted.
    const struct {
        const char* primitive;
        double p;
    } cases[] = {{"quadric", 0.5}, {"transformed-sphere", 0.5}, {"transformed-cylinder", 0.5}, {"transformed-cone", 0.5},
                 {"transformed-quadric", 0.5}, {"transformed-triangle", 1.0}};
    for (const auto& c : cases) {
        for (const Series& s : sweep(c.primitive, Scalar::f64, SweepKind::closeness, {Policy::accurate})) {
            if (s.family_class == "rim") continue;  // t at a rim is well conditioned; only the decision is hard
            const SeriesFit f = fit_series(s);
            print(s, f);
            ASSERT_TRUE(f.median.ok) << label(s) << ": " << f.median.why;
            EXPECT_FALSE(f.median.flat) << label(s) << ": accurate became flat — move " << c.primitive << " to exact_scope";
            EXPECT_NEAR(f.median.p.value, c.p, 0.1) << label(s) << ": accurate is not exact here and grows as δ^-" << c.p
                                                    << " (rounded coefficients)";
        }
    }
}

}  // namespace
