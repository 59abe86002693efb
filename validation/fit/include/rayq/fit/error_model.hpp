// rayq::fit — error-model fits for the precision sweeps of issue 6 (Ceres Solver inside the
// library's .cpp; this header is non-template and includes no Ceres).
//
// Two models, both over a "stress" variable x > 0 (the relative distance to tangency δ, a
// distance/radius ratio, a translation magnitude):
//
//   * power law: err(x) = C0 + C1·s^p in ulps, s = 1/x when the error grows as x → 0 (δ) and
//     s = x when it grows as x → ∞ (distance, translation). The issue writes ε·(C0 + C1·δ^−p);
//     errors here are already in ulps of t, i.e. divided by ε. Fitted in log space with a robust
//     loss on per-x statistics (median or 99th percentile), standard errors from ceres::Covariance.
//   * logistic: P(correct | x) = 1 / (1 + exp(−k·(u − u0))), u = log10 x, fitted by maximum
//     likelihood to per-x counts of correct and wrong hit/miss answers.
#pragma once

#include <cstddef>
#include <limits>
#include <optional>
#include <string>
#include <vector>

namespace rayq::fit {

// Which way the error grows.
enum class Growth {
    toward_zero,      // err ∝ x^−p: x is a closeness such as δ (10^−1 … 10^−15)
    toward_infinity,  // err ∝ x^p: x is a distance/radius or a translation magnitude (10^1 … 10^8)
};

struct Estimate {
    double value = 0;
    double se = 0;  // standard error; NaN when the covariance could not be computed
};

// ---- power law ---------------------------------------------------------------------------------
struct ErrorSample {
    double x = 0;    // > 0
    double err = 0;  // >= 0, in ulps (a per-x median or 99th percentile)
};

enum class Loss { cauchy, huber };

struct PowerLawOptions {
    Growth growth = Growth::toward_zero;
    // Errors enter as log(max(err, floor_ulps)), zeros included. Half an ulp is the measurement's
    // own resolution: a correctly rounded t lies anywhere in [0, 0.5] ulp depending only on where
    // the exact root falls between two floats (0 when it is a float), so differences below it say
    // nothing about the kernel. Flooring with max makes every correctly rounded answer the same
    // number, so an exact kernel fits exactly flat. (log(err + floor) was tried first: it keeps
    // the sub-half-ulp scatter, and per-decade medians hopping between 0.1 and 0.3 ulp — the share
    // of exactly representable roots varies — gave spurious exponents of ±0.06 for accurate on
    // the translation sweeps.) The floor applies to the data only: the model C0 + C1·s^p stays
    // smooth in its parameters, and C0 settles at the floor where the data sit on it.
    double floor_ulps = 0.5;
    Loss loss = Loss::cauchy;
    // Robust-loss scale, in natural-log units of the error: 0.5 is a factor e^0.5 ≈ 1.65.
    // Per-x medians of a few dozen random orientations scatter by less than that; a point further
    // off (a different mechanism, e.g. a wrong crossing) is down-weighted rather than followed.
    double loss_scale = 0.5;
    // Upper bound on p. A simple root's condition number grows as δ^−1/2 and a flat primitive's
    // 1/(d·n) as δ^−1; 4 leaves room for anything worse without letting s^p overflow (s <= 1e15).
    double max_exponent = 4;
    // Samples at or above this error are left out (counted in PowerLawFit::saturated): an error
    // cannot grow past ~|t| itself, so once t has lost its leading digits the error plateaus and
    // measures the saturation, not the growth law. Default: no limit; rayq::fit::fit_series sets
    // it per number type.
    double saturation_ulps = std::numeric_limits<double>::infinity();
};

struct PowerLawFit {
    bool ok = false;
    std::string why;  // when !ok: what was wrong with the data
    // No growth: the best single power law C·s^p has an exponent within 3 standard errors of 0,
    // or the growth term adds the floor (half an ulp) or more at fewer than two samples (a
    // single grown point is an outlier, not a trend), or p sits at its lower bound 0. The
    // three-parameter p is then unidentifiable (any p with a small enough C1 fits), so p is
    // instead the single power law's exponent, ≈ 0 for flat data and with a proper standard
    // error; C0 = C, C1 = 0, no crossover.
    bool flat = false;
    Estimate p, C0, C1;
    std::optional<double> x_star;  // where C1·s^p = C0 (δ* for Growth::toward_zero); none when flat
    // x_star lies within the sampled x: otherwise the growth dominates (or stays below C0) at
    // every measured x and C0 (or C1) rests on little data — x_star is then an extrapolation.
    bool x_star_in_data = false;
    std::size_t points = 0;        // samples used
    std::size_t saturated = 0;     // samples left out at or above saturation_ulps
    double rms_log_residual = 0;   // of log(max(err, floor)), over all samples (no robust weighting)
    Growth growth = Growth::toward_zero;
    double floor_ulps = 0.5;

    double predict(double x) const;  // C0 + C1·s^p (ulps); flat: C0·s^p, the single power law; NaN when !ok
};

// Needs at least 4 samples at distinct x below saturation (3 parameters and one degree of freedom
// for the error scale); fewer, or non-positive/non-finite x, or negative/NaN errors, give
// ok = false and `why`.
PowerLawFit fit_power_law(const std::vector<ErrorSample>& samples, const PowerLawOptions& options = {});

// ---- logistic ----------------------------------------------------------------------------------
struct CorrectnessSample {
    double x = 0;            // > 0
    std::size_t correct = 0;
    std::size_t total = 0;   // >= correct
};

struct LogisticOptions {
    // Bound on |k| (per decade of x). The sweeps step x by one decade; a transition steeper than
    // 20/decade (1% to 99% within 0.46 decade) cannot be told from a step with such data, and the
    // bound keeps the maximum-likelihood estimate finite on perfectly separated data.
    double max_slope = 20;
    // u0 may lie at most this many decades outside the data (an extrapolated 50% point further
    // out than that is a guess, not a measurement).
    double max_extrapolation_decades = 5;
};

struct LogisticFit {
    bool ok = false;
    std::string why;
    bool always_correct = false;  // not a single wrong answer: no band (δ50, δ99 empty)
    bool never_correct = false;   // not a single right answer
    bool step = false;            // |k| reached max_slope: the data are (nearly) separated
    Estimate u0, k;               // midpoint (log10 x) and slope per decade
    std::optional<double> x50, x99;  // x where P(correct) = 50% and 99% (δ50, δ99)
    bool x50_extrapolated = false;   // x50 lies outside the measured x range
    // u0 ran into its extrapolation bound: the wrong answers show no trend the model can place
    // (e.g. a few scattered over the whole range); x50 and x99 are then empty.
    bool sparse = false;
    std::size_t points = 0, cases = 0, wrong = 0;

    double probability(double x) const;  // fitted P(correct); 1 when always_correct
};

LogisticFit fit_logistic(const std::vector<CorrectnessSample>& samples, const LogisticOptions& options = {});

// Nearest-rank percentile (q in [0, 1]) of a copy of `values`; 0 for an empty set.
double percentile(std::vector<double> values, double q);

}  // namespace rayq::fit
