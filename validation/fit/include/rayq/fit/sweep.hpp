// rayq::fit — the precision sweeps of issue 6: the kernel under each policy against the exact
// oracle on the generated families that approach an ill-conditioned configuration one decade at
// a time, summarized per decade and fitted (error_model.hpp). Non-template; target rayq::sweep.
//
//   kind        families (rayq::oracle::family_names)              x
//   closeness   grazing.{in,out}.kNN (curved, transformed curved),  δ = 10^-k: relative distance to
//               parallel.kNN and rim.{in,out}.kNN (flat; rim also   tangency, |d̂·n̂|, or to the rim
//               for cylinder and cone caps)                         (k = 1..15 double, 1..7 float)
//   distance    far.eNN (not for transformed-*)                     distance/size = 10^e (e = 1..8)
//   translation translated.eNN                                      translation magnitude 10^e
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <rayq/fit/error_model.hpp>
#include <rayq/oracle/harness.hpp>

namespace rayq::fit {

enum class SweepKind { closeness, distance, translation };
const char* sweep_kind_name(SweepKind k);  // "closeness", "distance", "translation"

// One x value of one series: every case generated at that x (both sides of the boundary for the
// in/out families, alternating).
struct SweepPoint {
    double x = 0;
    std::size_t cases = 0;         // cases inside the oracle's domain
    std::size_t both_hit = 0;      // cases with an ulp error (kernel and oracle both hit)
    std::size_t hit_correct = 0;   // kernel hit/miss agrees with the oracle
    std::size_t part_correct = 0;  // among both_hit: the part (surface, cap0, cap1) agrees
    std::size_t exact_hits = 0;    // the oracle says hit
    double median_ulps = 0, p99_ulps = 0, max_ulps = 0;  // among both_hit (nearest rank); 0 if none
};

struct Series {
    std::string primitive;     // "sphere", …, "transformed-quadric"
    std::string family_class;  // "grazing", "parallel", "rim", "far", "translated"
    oracle::Scalar scalar = oracle::Scalar::f64;
    oracle::Policy policy = oracle::Policy::fast;
    SweepKind kind = SweepKind::closeness;
    std::vector<SweepPoint> points;  // in the families' order (k or e ascending)
};

struct SeriesFit {
    PowerLawFit median, p99;  // on the per-x median and 99th-percentile ulp errors
    LogisticFit hit;          // P(hit/miss correct) against log10 x
    std::size_t misclassified = 0;  // hit/miss or part disagreements, all x
};

// The error grows as x → 0 for closeness, as x → ∞ otherwise.
Growth growth_of(SweepKind kind);
SeriesFit fit_series(const Series& s, const PowerLawOptions& base = {});

struct SweepOptions {
    std::size_t cases_per_x = 24;
    std::uint64_t seed = 1;
    std::vector<oracle::Policy> policies{oracle::all_policies.begin(), oracle::all_policies.end()};
    int max_k = 0;  // closeness: only k <= max_k when > 0 (a CI-sized subset)
};

// The family classes a primitive has for a sweep kind (empty: none, e.g. far for transformed-*).
std::vector<std::string> sweep_classes(const std::string& primitive, oracle::Scalar s, SweepKind kind);

// Every series of one primitive and number type for one kind: one per family class × policy.
// The exact answer of each case is computed once and measured against every policy.
std::vector<Series> run_sweep(const std::string& primitive, oracle::Scalar s, SweepKind kind, const SweepOptions& options);

}  // namespace rayq::fit
