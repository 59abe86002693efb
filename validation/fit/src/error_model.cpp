// rayq::fit — the power-law and logistic fits (Ceres Solver). See include/rayq/fit/error_model.hpp.
#include <rayq/fit/error_model.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <set>

#include <ceres/ceres.h>

namespace rayq::fit {

namespace {

constexpr double nan = std::numeric_limits<double>::quiet_NaN();

// ---- power law -----------------------------------------------------------------------------------
// θ = (p, a = ln C0, b = ln C1): the logs keep C0 and C1 positive without a bound at 0 (where the
// covariance of a bounded parameter is meaningless) and make the residual's scale uniform.
struct LogPowerLaw {
    double log_s, log_observed;
    template <class J>
    bool operator()(const J* theta, J* residual) const
    {
        const J model = exp(theta[1]) + exp(theta[2] + theta[0] * log_s);
        residual[0] = J(log_observed) - log(model);
        return true;
    }
};

// The single power law C·s^p, θ = (p, c = ln C): the flat case's exponent.
struct LogSinglePowerLaw {
    double log_s, log_observed;
    template <class J>
    bool operator()(const J* theta, J* residual) const
    {
        residual[0] = J(log_observed) - (theta[1] + theta[0] * log_s);  // log(C·s^p), linear in θ
        return true;
    }
};

struct Sample {
    double log_s, log_observed;
};

ceres::LossFunction* make_loss(const PowerLawOptions& o)
{
    // Ceres' losses act on the squared residual; their scale is in residual units.
    if (o.loss == Loss::huber) return new ceres::HuberLoss(o.loss_scale);
    return new ceres::CauchyLoss(o.loss_scale);
}

ceres::Solver::Options solver_options()
{
    ceres::Solver::Options s;
    s.linear_solver_type = ceres::DENSE_QR;  // at most 3 parameters
    s.max_num_iterations = 500;              // converges in tens; room for bad starts
    s.function_tolerance = 1e-12;            // the fits are tiny: solve them to (near) machine precision
    s.gradient_tolerance = 1e-14;
    s.parameter_tolerance = 1e-12;
    s.logging_type = ceres::SILENT;
    return s;
}

// A solved problem with its final cost and parameters.
struct Solved {
    double cost = std::numeric_limits<double>::infinity();
    std::vector<double> theta;
    std::vector<double> covariance;  // row-major, scaled by the residual variance; empty if unavailable
};

// Residual variance from the robust cost (cost = ½·Σρ(r²)), per degree of freedom: Ceres'
// covariance assumes unit-variance residuals, the fit's own scatter sets the real scale.
template <class Functor, int K>
Solved solve(const std::vector<Sample>& samples, const PowerLawOptions& o, std::vector<double> start,
             const std::vector<std::pair<double, double>>& bounds)
{
    Solved out;
    out.theta = std::move(start);
    ceres::Problem problem;
    for (const Sample& s : samples)
        problem.AddResidualBlock(new ceres::AutoDiffCostFunction<Functor, 1, K>(new Functor{s.log_s, s.log_observed}),
                                 make_loss(o), out.theta.data());
    for (int i = 0; i < K; ++i) {
        problem.SetParameterLowerBound(out.theta.data(), i, bounds[i].first);
        problem.SetParameterUpperBound(out.theta.data(), i, bounds[i].second);
    }
    ceres::Solver::Summary summary;
    ceres::Solve(solver_options(), &problem, &summary);
    if (!summary.IsSolutionUsable()) return out;
    out.cost = summary.final_cost;

    ceres::Covariance::Options co;
    co.algorithm_type = ceres::DENSE_SVD;  // tolerates rank deficiency (e.g. C1 → 0 leaves p undetermined)
    co.null_space_rank = -1;               // drop the undetermined directions instead of failing
    ceres::Covariance covariance(co);
    std::vector<std::pair<const double*, const double*>> blocks = {{out.theta.data(), out.theta.data()}};
    if (samples.size() > static_cast<std::size_t>(K) && covariance.Compute(blocks, &problem)) {
        out.covariance.assign(K * K, 0);
        covariance.GetCovarianceBlock(out.theta.data(), out.theta.data(), out.covariance.data());
        const double variance = 2 * summary.final_cost / static_cast<double>(samples.size() - K);
        for (double& c : out.covariance) c *= variance;
    }
    return out;
}

double se_of(const Solved& s, int i, int k)
{
    if (s.covariance.empty()) return nan;
    const double v = s.covariance[static_cast<std::size_t>(i * k + i)];
    return v >= 0 ? std::sqrt(v) : nan;
}

}  // namespace

double PowerLawFit::predict(double x) const
{
    if (!ok || !(x > 0)) return nan;
    const double s = growth == Growth::toward_zero ? 1 / x : x;
    if (flat) return C0.value * std::pow(s, p.value);  // the single power law C·s^p
    return C0.value + C1.value * std::pow(s, p.value);
}

PowerLawFit fit_power_law(const std::vector<ErrorSample>& input, const PowerLawOptions& o)
{
    PowerLawFit fit;
    fit.growth = o.growth;
    fit.floor_ulps = o.floor_ulps;
    if (!(o.floor_ulps > 0)) {
        fit.why = "floor_ulps must be positive (the log of a zero error)";
        return fit;
    }
    std::vector<Sample> samples;
    std::set<double> distinct;
    double min_log_s = std::numeric_limits<double>::infinity();
    double max_log_s = -std::numeric_limits<double>::infinity(), min_err = std::numeric_limits<double>::infinity(), err_at_max = 0;
    for (const ErrorSample& e : input) {
        if (!(e.x > 0) || !std::isfinite(e.x)) {
            fit.why = "x must be positive and finite (got " + std::to_string(e.x) + ")";
            return fit;
        }
        if (!(e.err >= 0) || !std::isfinite(e.err)) {
            fit.why = "errors must be finite and non-negative (got " + std::to_string(e.err) + ")";
            return fit;
        }
        if (e.err >= o.saturation_ulps) {
            ++fit.saturated;
            continue;
        }
        const double log_s = o.growth == Growth::toward_zero ? -std::log(e.x) : std::log(e.x);
        samples.push_back({log_s, std::log(std::max(e.err, o.floor_ulps))});
        distinct.insert(e.x);
        min_err = std::min(min_err, e.err);
        min_log_s = std::min(min_log_s, log_s);
        if (log_s > max_log_s) max_log_s = log_s, err_at_max = e.err;
    }
    fit.points = samples.size();
    if (distinct.size() < 4) {
        fit.why = "needs samples at 4 or more distinct x (3 parameters + 1 for the error scale), got " + std::to_string(distinct.size()) +
                  (fit.saturated ? " below saturation (" + std::to_string(fit.saturated) + " saturated)" : std::string());
        return fit;
    }

    // First the single power law C·s^p (p of either sign): its exponent is the data's overall
    // log–log trend, with a proper standard error even when the data are flat.
    const std::vector<std::pair<double, double>> bounds2 = {{-o.max_exponent, o.max_exponent}, {std::log(1e-6), std::log(1e20)}};
    const Solved single = solve<LogSinglePowerLaw, 2>(samples, o, {0.0, std::log(std::max(min_err, o.floor_ulps))}, bounds2);
    if (!std::isfinite(single.cost)) {
        fit.why = "the solver found no usable solution (single power law)";
        return fit;
    }
    const Estimate slope{single.theta[0], se_of(single, 0, 2)};

    // Bounds, natural logs: C0 from 1e-3 ulp (invisible under the half-ulp floor) to 1e20 ulps
    // (a wrong crossing in double is at most ~1e16 ulps away); C1 from e^-120 ≈ 1e-52 to e^60 ≈ 1e26,
    // wide enough that s^p (up to 1e15^4) never makes a real fit bind.
    const std::vector<std::pair<double, double>> bounds3 = {
        {0.0, o.max_exponent}, {std::log(1e-3), std::log(1e20)}, {-120.0, 60.0}};
    Solved best;
    // Several starting exponents: the log-space cost has a shallow valley along C1·s^p, and a start
    // on the wrong side of it can stall; four starts cost microseconds.
    for (double p0 : {0.1, 0.5, 1.0, 2.0}) {
        if (p0 > o.max_exponent) continue;
        const double a0 = std::log(std::max(min_err, o.floor_ulps));
        const double b0 = std::log(std::max(err_at_max, o.floor_ulps)) - p0 * max_log_s;
        Solved s = solve<LogPowerLaw, 3>(samples, o, {p0, a0, std::clamp(b0, -119.0, 59.0)}, bounds3);
        if (s.cost < best.cost) best = std::move(s);
    }
    if (!std::isfinite(best.cost)) {
        fit.why = "the solver found no usable solution";
        return fit;
    }
    const double p = best.theta[0], C0 = std::exp(best.theta[1]), C1 = std::exp(best.theta[2]);
    // The growth term counts only when all three hold:
    //  * the data have a trend: the single power law's exponent is more than 3 standard errors
    //    from 0 (flat data scattered by ±20% otherwise let C1·s^p chase the noise: measured
    //    exponents up to 0.13 on synthetic flat data without this test);
    //  * it adds at least the floor (half an ulp, the measurement's resolution) over the least
    //    stressed sample at two or more samples: growth seen at a single x — typically the last
    //    one — is an outlier the model can always fit exactly with a steep p, not a trend;
    //  * p is above 1e-3, i.e. not at its bound 0 within solver tolerance (a constant model).
    // Otherwise a tiny C1·s^p with an arbitrary p fits as well as any other, and the reported
    // exponent is the single power law's.
    const bool trend = std::isfinite(slope.se) && std::fabs(slope.value) > 3 * slope.se;
    std::size_t grown = 0;
    for (const Sample& s : samples) grown += C1 * (std::exp(p * s.log_s) - std::exp(p * min_log_s)) >= o.floor_ulps;
    const bool growth_takes_over = trend && p > 1e-3 && grown >= 2;
    if (growth_takes_over) {
        fit.p = {p, se_of(best, 0, 3)};
        fit.C0 = {C0, C0 * se_of(best, 1, 3)};  // delta method through C = e^a
        fit.C1 = {C1, C1 * se_of(best, 2, 3)};
        const double log_s_star = std::log(C0 / C1) / p;
        fit.x_star = o.growth == Growth::toward_zero ? std::exp(-log_s_star) : std::exp(log_s_star);
        fit.x_star_in_data = log_s_star >= min_log_s && log_s_star <= max_log_s;
    } else {
        fit.flat = true;
        const double C = std::exp(single.theta[1]);
        fit.p = slope;
        fit.C0 = {C, C * se_of(single, 1, 2)};
        fit.C1 = {0, 0};
    }
    fit.ok = true;
    double sum = 0;
    for (const ErrorSample& e : input) {
        if (e.err >= o.saturation_ulps) continue;
        const double r = std::log(std::max(e.err, o.floor_ulps)) - std::log(fit.predict(e.x));
        sum += r * r;
    }
    fit.rms_log_residual = std::sqrt(sum / static_cast<double>(samples.size()));
    return fit;
}

// ---- logistic ------------------------------------------------------------------------------------
namespace {

// softplus(z) = log(1 + e^z) without overflow: −log σ(η) = softplus(−η), −log(1 − σ(η)) = softplus(η).
template <class J>
J softplus(const J& z)
{
    if (z > J(0)) return z + log1p(exp(-z));
    return log1p(exp(z));
}

// The binomial negative log-likelihood as a sum of squares: for a point with c correct and w wrong
// answers at u, the residuals √(2c·(−log P)) and √(2w·(−log(1 − P))) square to twice its term, so
// least squares minimizes exactly the likelihood's cost. Both are smooth: −log P > 0 for every
// finite η, and |η| stays below ~400 under the bounds, far from exp's underflow.
struct BinomialTerm {
    double u, count;
    bool correct;
    template <class J>
    bool operator()(const J* theta, J* residual) const
    {
        const J eta = theta[1] * (J(u) - theta[0]);  // θ = (u0, k)
        residual[0] = sqrt(J(2 * count) * softplus(correct ? J(-eta) : eta));
        return true;
    }
};

double sigmoid(double eta) { return eta >= 0 ? 1 / (1 + std::exp(-eta)) : std::exp(eta) / (1 + std::exp(eta)); }

}  // namespace

double LogisticFit::probability(double x) const
{
    if (!ok || !(x > 0)) return nan;
    if (always_correct) return 1;
    if (never_correct) return 0;
    return sigmoid(k.value * (std::log10(x) - u0.value));
}

LogisticFit fit_logistic(const std::vector<CorrectnessSample>& input, const LogisticOptions& o)
{
    LogisticFit fit;
    struct Point {
        double u;
        std::size_t correct, wrong;
    };
    std::vector<Point> points;
    std::set<double> distinct;
    for (const CorrectnessSample& c : input) {
        if (!(c.x > 0) || !std::isfinite(c.x)) {
            fit.why = "x must be positive and finite (got " + std::to_string(c.x) + ")";
            return fit;
        }
        if (c.correct > c.total) {
            fit.why = "more correct answers than cases at x = " + std::to_string(c.x);
            return fit;
        }
        if (c.total == 0) continue;
        points.push_back({std::log10(c.x), c.correct, c.total - c.correct});
        distinct.insert(c.x);
        fit.cases += c.total;
        fit.wrong += c.total - c.correct;
    }
    fit.points = points.size();
    if (distinct.size() < 2) {
        fit.why = "needs cases at 2 or more distinct x, got " + std::to_string(distinct.size());
        return fit;
    }
    fit.ok = true;
    if (fit.wrong == 0) {
        fit.always_correct = true;
        return fit;
    }
    if (fit.wrong == fit.cases) {
        fit.never_correct = true;
        return fit;
    }
    double u_min = points.front().u, u_max = u_min;
    for (const Point& p : points) u_min = std::min(u_min, p.u), u_max = std::max(u_max, p.u);

    // Start at the empirical crossing of 50% (the mean u when it never crosses), both slope signs.
    double u_start = 0;
    {
        double sum_u = 0;
        for (const Point& p : points) sum_u += p.u;
        u_start = sum_u / static_cast<double>(points.size());
    }
    double best_cost = std::numeric_limits<double>::infinity();
    double best[2] = {u_start, 0};
    for (double k0 : {1.0, -1.0}) {
        double theta[2] = {u_start, k0};
        ceres::Problem problem;
        for (const Point& p : points) {
            if (p.correct)
                problem.AddResidualBlock(new ceres::AutoDiffCostFunction<BinomialTerm, 1, 2>(
                                             new BinomialTerm{p.u, static_cast<double>(p.correct), true}),
                                         nullptr, theta);
            if (p.wrong)
                problem.AddResidualBlock(new ceres::AutoDiffCostFunction<BinomialTerm, 1, 2>(
                                             new BinomialTerm{p.u, static_cast<double>(p.wrong), false}),
                                         nullptr, theta);
        }
        problem.SetParameterLowerBound(theta, 0, u_min - o.max_extrapolation_decades);
        problem.SetParameterUpperBound(theta, 0, u_max + o.max_extrapolation_decades);
        problem.SetParameterLowerBound(theta, 1, -o.max_slope);
        problem.SetParameterUpperBound(theta, 1, o.max_slope);
        ceres::Solver::Summary summary;
        ceres::Solve(solver_options(), &problem, &summary);
        if (summary.IsSolutionUsable() && summary.final_cost < best_cost) {
            best_cost = summary.final_cost;
            best[0] = theta[0], best[1] = theta[1];
        }
    }
    if (!std::isfinite(best_cost)) {
        fit.ok = false;
        fit.why = "the solver found no usable solution";
        return fit;
    }
    const double u0 = best[0], k = best[1];
    // Standard errors from the binomial Fisher information Σ n·P(1 − P)·g gᵀ, g = ∂η/∂(u0, k) =
    // (−k, u − u0): the exact curvature of the likelihood, which the least-squares form's JᵀJ is not.
    double i00 = 0, i01 = 0, i11 = 0;
    for (const Point& p : points) {
        const double P = sigmoid(k * (p.u - u0));
        const double w = static_cast<double>(p.correct + p.wrong) * P * (1 - P);
        const double g0 = -k, g1 = p.u - u0;
        i00 += w * g0 * g0, i01 += w * g0 * g1, i11 += w * g1 * g1;
    }
    const double det = i00 * i11 - i01 * i01;
    const bool invertible = det > 0 && std::isfinite(det);
    fit.u0 = {u0, invertible ? std::sqrt(i11 / det) : nan};
    fit.k = {k, invertible ? std::sqrt(i00 / det) : nan};
    fit.step = std::fabs(k) >= 0.999 * o.max_slope;  // at the bound within solver tolerance
    // Within 1e-6 decade of the bound is at the bound (solver tolerance).
    fit.sparse = u0 <= u_min - o.max_extrapolation_decades + 1e-6 || u0 >= u_max + o.max_extrapolation_decades - 1e-6;
    if (k != 0 && !fit.sparse) {
        fit.x50 = std::pow(10.0, u0);
        fit.x99 = std::pow(10.0, u0 + std::log(99.0) / k);  // σ(k(u − u0)) = 0.99
    }
    fit.x50_extrapolated = u0 < u_min || u0 > u_max;
    return fit;
}

double percentile(std::vector<double> values, double q)
{
    if (values.empty()) return 0;
    std::sort(values.begin(), values.end());
    const double rank = std::ceil(q * static_cast<double>(values.size()));
    const std::size_t index = rank < 1 ? 0 : std::min(values.size() - 1, static_cast<std::size_t>(rank) - 1);
    return values[index];
}

}  // namespace rayq::fit
