// rayq::fit — the precision sweeps (see include/rayq/fit/sweep.hpp).
#include <rayq/fit/sweep.hpp>

#include <cmath>
#include <limits>
#include <map>
#include <stdexcept>

namespace rayq::fit {

namespace {

using oracle::Policy;

// The parameter of a family name: "grazing.in.k07" → class "grazing", letter 'k', value 7.
struct Parsed {
    std::string cls;
    char letter = 0;  // 'k' or 'e'
    int value = 0;
};

Parsed parse(const std::string& family)
{
    Parsed p;
    p.cls = oracle::family_class(family);
    const std::size_t last = family.rfind('.');
    if (last == std::string::npos || last + 2 > family.size()) return p;
    const char letter = family[last + 1];
    if (letter != 'k' && letter != 'e') return p;
    // "apex.exact" has no parameter: the letter must be followed by digits only.
    if (family.find_first_not_of("0123456789", last + 2) != std::string::npos) return p;
    p.letter = letter;
    p.value = std::stoi(family.substr(last + 2));
    return p;
}

bool class_in_kind(const std::string& cls, SweepKind kind)
{
    switch (kind) {
    case SweepKind::closeness: return cls == "grazing" || cls == "parallel" || cls == "rim";
    case SweepKind::distance: return cls == "far";
    case SweepKind::translation: return cls == "translated";
    }
    return false;
}

}  // namespace

const char* sweep_kind_name(SweepKind k)
{
    return k == SweepKind::closeness ? "closeness" : k == SweepKind::distance ? "distance" : "translation";
}

Growth growth_of(SweepKind kind) { return kind == SweepKind::closeness ? Growth::toward_zero : Growth::toward_infinity; }

std::vector<std::string> sweep_classes(const std::string& primitive, oracle::Scalar s, SweepKind kind)
{
    std::vector<std::string> out;
    for (const std::string& f : oracle::family_names(primitive, s)) {
        const Parsed p = parse(f);
        if (p.letter == 0 || !class_in_kind(p.cls, kind)) continue;
        bool seen = false;
        for (const std::string& c : out) seen = seen || c == p.cls;
        if (!seen) out.push_back(p.cls);
    }
    return out;
}

SeriesFit fit_series(const Series& s, const PowerLawOptions& base)
{
    SeriesFit out;
    PowerLawOptions o = base;
    o.growth = growth_of(s.kind);
    // Saturation at a relative error of 1/16: 2^(m−1−4) ulps for an m-bit significand (float 2^19
    // ≈ 5e5, double 2^48 ≈ 3e14). Beyond it t keeps at most 3 correct bits; the float quadric
    // translated by 10^4 and more, e.g., plateaus at 1e6–1e7 ulps (relative error ~1).
    if (base.saturation_ulps == std::numeric_limits<double>::infinity())
        o.saturation_ulps = s.scalar == oracle::Scalar::f32 ? 0x1p19 : 0x1p48;
    std::vector<ErrorSample> median, p99;
    std::vector<CorrectnessSample> hit;
    for (const SweepPoint& p : s.points) {
        if (p.both_hit > 0) {
            median.push_back({p.x, p.median_ulps});
            p99.push_back({p.x, p.p99_ulps});
        }
        hit.push_back({p.x, p.hit_correct, p.cases});
        out.misclassified += (p.cases - p.hit_correct) + (p.both_hit - p.part_correct);
    }
    out.median = fit_power_law(median, o);
    out.p99 = fit_power_law(p99, o);
    out.hit = fit_logistic(hit);
    return out;
}

std::vector<Series> run_sweep(const std::string& primitive, oracle::Scalar scalar, SweepKind kind, const SweepOptions& options)
{
    if (options.cases_per_x == 0) throw std::invalid_argument("rayq::fit: cases_per_x must be positive");
    std::vector<Series> out;
    for (const std::string& cls : sweep_classes(primitive, scalar, kind)) {
        // x value → the families at it (one, or the in/out pair).
        std::map<int, std::vector<std::string>> at;
        for (const std::string& f : oracle::family_names(primitive, scalar)) {
            const Parsed p = parse(f);
            if (p.cls != cls || p.letter == 0) continue;
            if (kind == SweepKind::closeness && options.max_k > 0 && p.value > options.max_k) continue;
            at[p.value].push_back(f);
        }
        const std::size_t first = out.size();
        for (Policy policy : options.policies) {
            Series s;
            s.primitive = primitive, s.family_class = cls, s.scalar = scalar, s.policy = policy, s.kind = kind;
            out.push_back(s);
        }
        for (const auto& [value, families] : at) {
            const double x = std::pow(10.0, kind == SweepKind::closeness ? -value : value);
            std::vector<std::vector<double>> ulps(options.policies.size());
            std::vector<SweepPoint> points(options.policies.size());
            for (std::size_t i = 0; i < options.cases_per_x; ++i) {
                // Alternate the sides; each side's cases are indexed 0, 1, 2, … so that a larger
                // cases_per_x extends a smaller run.
                const std::string& family = families[i % families.size()];
                const oracle::Fixture f = oracle::generate(primitive, scalar, family, options.seed, i / families.size());
                const oracle::Truth truth = oracle::truth_of(f.input);
                if (!truth.first_hit().defined) continue;
                for (std::size_t j = 0; j < options.policies.size(); ++j) {
                    const oracle::Measurement m = oracle::measure_kernel(truth, options.policies[j], f.input);
                    SweepPoint& p = points[j];
                    ++p.cases;
                    p.exact_hits += m.exact_hit;
                    p.hit_correct += m.hit_agrees;
                    if (m.both_hit) {
                        ++p.both_hit;
                        p.part_correct += m.part_agrees;
                        ulps[j].push_back(m.ulps);
                    }
                }
            }
            for (std::size_t j = 0; j < options.policies.size(); ++j) {
                SweepPoint& p = points[j];
                p.x = x;
                p.median_ulps = percentile(ulps[j], 0.5);
                p.p99_ulps = percentile(ulps[j], 0.99);
                p.max_ulps = percentile(ulps[j], 1.0);
                out[first + j].points.push_back(p);
            }
        }
    }
    return out;
}

}  // namespace rayq::fit
