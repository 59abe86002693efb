// The precision-sweep campaign (issue 6): rayq::fit's sweeps toward tangency (closeness δ), at
// distance and under translation, one work item per primitive × number type × sweep kind; the
// Ceres fits (error model C0 + C1·s^p, logistic misclassification band) are computed in reduce
// from the items' per-decade statistics, so one run and any merge of shards fit the same data.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <optional>
#include <set>
#include <stdexcept>

#include <rayq/fit/sweep.hpp>

#include "campaign.hpp"

namespace rayq::report {

namespace {

using fit::SweepKind;

// The primitives of the accurate contract (issue 4): accurate decides exactly there, so its
// error must be flat and its hit/miss and part never wrong. Quadrics and transformed instances
// are measured and shown, not gated (accurate is not exact for them: README "Policies").
const std::set<std::string> contract_scope = {"sphere", "plane", "disk", "parallelogram", "triangle", "cylinder", "cone"};

// Cases per decade for each precision preset. quick: enough for a per-decade median and a
// misclassification to show, a few seconds in all (the validate end-to-end test runs it);
// default: the ctest's size ×2 (medians within ~±15%); full: the size of rayq-sweep's table.
std::size_t cases_per_decade(const Settings& s)
{
    if (s.precision_preset == "quick") return 8;
    if (s.precision_preset == "full") return 400;
    return 48;
}

json number(double v) { return std::isfinite(v) ? json(v) : json(nullptr); }  // JSON has no NaN
constexpr double no_value = std::numeric_limits<double>::quiet_NaN();

const SweepKind kinds[] = {SweepKind::closeness, SweepKind::distance, SweepKind::translation};

SweepKind kind_named(const std::string& name)
{
    for (SweepKind k : kinds)
        if (name == fit::sweep_kind_name(k)) return k;
    throw std::runtime_error("sweep campaign: unknown sweep kind " + name);
}

std::vector<Item> plan(const Settings& s)
{
    std::vector<Item> items;
    const std::vector<std::string> primitives = s.oracle_primitives.empty() ? oracle::generated_primitives() : s.oracle_primitives;
    for (const std::string& primitive : primitives)
        for (oracle::Scalar scalar : {oracle::Scalar::f64, oracle::Scalar::f32})
            for (SweepKind kind : kinds) {
                if (fit::sweep_classes(primitive, scalar, kind).empty()) continue;  // e.g. far for transformed-*
                const std::string type = oracle::scalar_name(scalar);
                items.push_back({primitive + "/" + type + "/" + fit::sweep_kind_name(kind),
                                 {{"primitive", primitive}, {"type", type}, {"kind", fit::sweep_kind_name(kind)}}});
            }
    return items;
}

json run(const Settings& s, const Item& item, std::string& csv)
{
    const std::string primitive = item.spec.at("primitive"), type = item.spec.at("type");
    const oracle::Scalar scalar = type == "float" ? oracle::Scalar::f32 : oracle::Scalar::f64;
    fit::SweepOptions options;
    options.cases_per_x = cases_per_decade(s);
    options.seed = s.seed;
    const std::vector<fit::Series> all = fit::run_sweep(primitive, scalar, kind_named(item.spec.at("kind")), options);
    json series = json::array();
    for (const fit::Series& x : all) {
        json points = json::array();
        for (const fit::SweepPoint& p : x.points) {
            points.push_back({{"x", p.x}, {"cases", p.cases}, {"both_hit", p.both_hit}, {"hit_correct", p.hit_correct},
                              {"part_correct", p.part_correct}, {"exact_hits", p.exact_hits}, {"median_ulps", p.median_ulps},
                              {"p99_ulps", p.p99_ulps}, {"max_ulps", p.max_ulps}});
            char line[320];
            std::snprintf(line, sizeof line, "%s,%s,%s,%s,%s,%.17g,%zu,%zu,%zu,%zu,%.17g,%.17g,%.17g\n", primitive.c_str(),
                          type.c_str(), oracle::policy_name(x.policy), fit::sweep_kind_name(x.kind), x.family_class.c_str(), p.x,
                          p.cases, p.both_hit, p.hit_correct, p.part_correct, p.median_ulps, p.p99_ulps, p.max_ulps);
            csv += line;
        }
        series.push_back({{"primitive", primitive}, {"type", type}, {"policy", oracle::policy_name(x.policy)},
                          {"kind", fit::sweep_kind_name(x.kind)}, {"family", x.family_class}, {"points", points}});
    }
    return {{"series", series}};
}

fit::Series series_from_json(const json& j)
{
    fit::Series s;
    s.primitive = j.at("primitive");
    s.family_class = j.at("family");
    s.scalar = j.at("type") == "float" ? oracle::Scalar::f32 : oracle::Scalar::f64;
    const std::string policy = j.at("policy");
    for (oracle::Policy p : oracle::all_policies)
        if (policy == oracle::policy_name(p)) s.policy = p;
    s.kind = kind_named(j.at("kind"));
    for (const json& q : j.at("points")) {
        fit::SweepPoint p;
        p.x = q.at("x"); p.cases = q.at("cases"); p.both_hit = q.at("both_hit"); p.hit_correct = q.at("hit_correct");
        p.part_correct = q.at("part_correct"); p.exact_hits = q.at("exact_hits"); p.median_ulps = q.at("median_ulps");
        p.p99_ulps = q.at("p99_ulps"); p.max_ulps = q.at("max_ulps");
        s.points.push_back(p);
    }
    return s;
}

std::string text(double v, int digits = 3)
{
    char buf[48];
    std::snprintf(buf, sizeof buf, "%.*g", digits, v);
    return buf;
}

json reduce(const Settings&, const std::vector<json>& results)
{
    json metrics = json::object(), rows = json::array(), table = json::array();
    double accurate_max_p = 0;
    std::uint64_t accurate_misclassified = 0, accurate_failed_fits = 0, accurate_fits = 0;
    for (const json& r : results) {
        for (const json& j : r.at("series")) {
            const fit::Series s = series_from_json(j);
            const fit::SeriesFit f = fit::fit_series(s);
            const std::string policy = j.at("policy"), type = j.at("type"), kind = j.at("kind"), family = j.at("family");
            std::size_t cases = 0;
            for (const auto& p : s.points) cases += p.cases;
            const std::string m = "sweep." + policy + "." + type + "." + s.primitive + "." + family + ".";
            if (f.median.ok) metrics[m + "p"] = f.median.p.value;
            if (f.p99.ok) metrics[m + "p99_p"] = f.p99.p.value;
            metrics[m + "misclassified"] = f.misclassified;
            if (policy == "accurate" && contract_scope.count(s.primitive)) {
                accurate_misclassified += f.misclassified;
                for (const fit::PowerLawFit* pf : {&f.median, &f.p99}) {
                    if (!pf->ok) {
                        ++accurate_failed_fits;
                        continue;
                    }
                    ++accurate_fits;
                    accurate_max_p = std::max(accurate_max_p, pf->p.value);
                }
            }
            // The fitted curves at every x, for the plots.
            json fitted = json::array();
            for (const auto& p : s.points)
                fitted.push_back({number(f.median.ok ? f.median.predict(p.x) : no_value), number(f.p99.ok ? f.p99.predict(p.x) : no_value)});
            json row = j;
            row["fitted"] = fitted;
            row["fit"] = {{"ok", f.median.ok}, {"flat", f.median.flat}, {"p", number(f.median.p.value)}, {"p_se", number(f.median.p.se)},
                          {"C0", number(f.median.C0.value)}, {"C1", number(f.median.C1.value)},
                          {"x_star", f.median.x_star ? number(*f.median.x_star) : json(nullptr)},
                          {"p99_p", number(f.p99.ok ? f.p99.p.value : no_value)},
                          {"x50", f.hit.x50 ? number(*f.hit.x50) : json(nullptr)}, {"x99", f.hit.x99 ? number(*f.hit.x99) : json(nullptr)},
                          {"always_correct", f.hit.ok && f.hit.always_correct}, {"misclassified", f.misclassified}, {"cases", cases}};
            rows.push_back(row);
            const auto band = [&](const std::optional<double>& x) -> json {
                if (!f.hit.ok) return "n/a";
                if (f.hit.always_correct) return "none";
                return x ? json(text(*x, 2)) : json("n/a");
            };
            table.push_back({s.primitive, type, policy, kind, family,
                             f.median.ok ? text(f.median.p.value) + " ± " + text(f.median.p.se, 2) + (f.median.flat ? " (flat)" : "")
                                         : std::string("n/a"),
                             f.median.ok ? json(text(f.median.C0.value)) : json("n/a"),
                             f.median.ok ? json(text(f.median.C1.value)) : json("n/a"),
                             f.median.x_star ? json(text(*f.median.x_star, 2)) : json("-"),
                             f.p99.ok ? json(text(f.p99.p.value)) : json("n/a"), band(f.hit.x50), band(f.hit.x99),
                             std::to_string(f.misclassified) + "/" + std::to_string(cases)});
        }
    }
    metrics["sweep.accurate.contract_scope.max_p"] = accurate_max_p;
    metrics["sweep.accurate.contract_scope.misclassified"] = accurate_misclassified;
    metrics["sweep.accurate.contract_scope.fits"] = accurate_fits;
    metrics["sweep.accurate.contract_scope.failed_fits"] = accurate_failed_fits;
    const json tables = json::array(
        {{{"title", "Error-model fits: err = C0 + C1·s^p ulps (s = 1/δ toward tangency, distance/size, translation), "
                    "median per decade; x50/x99 where P(correct hit/miss) falls to 50%/99%"},
          {"columns", {"primitive", "type", "policy", "sweep", "family", "p ± se (median)", "C0", "C1", "x*", "p (p99)", "x50", "x99",
                       "misclassified/cases"}},
          {"rows", table}}});
    return {{"metrics", metrics}, {"rows", rows}, {"tables", tables}};
}

// The misclassification band: the fraction of cases per decade whose hit/miss differs from the
// exact oracle's, against δ toward tangency, one line per policy, with the logistic fit's δ50 and
// δ99 (where P(correct) falls to 50% and 99%) in the key.
std::optional<Plot> misclassification_plot(const json& rows, const std::string& primitive, const std::string& type)
{
    Plot p;
    p.name = "sweep_band_" + primitive + "_" + type;
    p.title = "Misclassification band: wrong hit/miss against δ toward tangency, " + primitive + ", " + type;
    std::string plot;
    double highest = 0;
    int colour = 1;
    for (const json& r : rows) {
        if (r.at("primitive") != primitive || r.at("type") != type || r.at("kind") != "closeness" || r.at("family") == "rim") continue;
        std::string data;
        for (const json& q : r.at("points")) {
            const std::size_t cases = q.at("cases"), correct = q.at("hit_correct");
            if (cases == 0) continue;
            const double wrong = double(cases - correct) / double(cases);
            highest = std::max(highest, wrong);
            char line[64];
            std::snprintf(line, sizeof line, "%.6g %.6g\n", q.at("x").get<double>(), wrong);
            data += line;
        }
        if (data.empty()) continue;
        const std::string policy = r.at("policy");
        const std::string file = p.name + "_" + policy + ".dat";
        p.data.emplace_back(file, data);
        const json& fit = r.at("fit");
        std::string title = policy;
        if (fit.at("always_correct").get<bool>()) title += " (never wrong)";
        else if (!fit.at("x50").is_null() || !fit.at("x99").is_null())
            title += " (logistic fit: δ50 = " + (fit.at("x50").is_null() ? std::string("n/a") : text(fit.at("x50").get<double>(), 2)) +
                     ", δ99 = " + (fit.at("x99").is_null() ? std::string("n/a") : text(fit.at("x99").get<double>(), 2)) + ")";
        plot += std::string(plot.empty() ? "" : ", ") + "'<dir>/" + file + "' using 1:2 with linespoints pt 7 lw 2 lt " +
                std::to_string(colour++) + " title '" + title + "'";
    }
    if (plot.empty()) return std::nullopt;
    char range[64];
    std::snprintf(range, sizeof range, "set yrange [0:%.3g]\n", std::max(0.05, 1.1 * highest));  // all zero: still a visible axis
    p.script = "set logscale x\nset format x '10^{%L}'\nset xlabel 'δ (relative distance to tangency / |d·n|)'\n"
               "set ylabel 'fraction misclassified (hit/miss)'\nset key top left\nset grid\nset xrange [*:*] reverse\n" +
               std::string(range) + "plot " + plot + "\n";
    return p;
}

// Median ulp error against δ toward tangency with the fitted curves, per primitive shown and
// number type: the sphere (the theory's case) and the plane (a flat primitive's 1/(d·n)); then
// the misclassification band of each.
std::vector<Plot> plots(const json& sections)
{
    std::vector<Plot> out;
    const json& rows = sections.at("sweep").at("rows");
    for (const char* primitive : {"sphere", "plane"}) {
        for (const char* type : {"double", "float"}) {
            Plot p;
            p.name = std::string("sweep_") + primitive + "_" + type;
            p.title = std::string("Toward tangency: median ulp error of t against δ, ") + primitive + ", " + type +
                      " (points: data; lines: fitted C0 + C1·δ^-p)";
            p.script = "set logscale xy\nset format x '10^{%L}'\nset format y '10^{%L}'\nset xlabel 'δ (relative distance to tangency / |d·n|)'\n"
                       "set ylabel 'median ulp error (floored at 0.5)'\nset key outside right\nset grid\nset xrange [*:*] reverse\nplot ";
            bool first = true;
            int colour = 1;
            for (const json& r : rows) {
                if (r.at("primitive") != primitive || r.at("type") != type || r.at("kind") != "closeness" || r.at("family") == "rim") continue;
                std::string data;
                const json& points = r.at("points");
                const json& fitted = r.at("fitted");
                for (std::size_t i = 0; i < points.size(); ++i) {
                    if (points[i].at("both_hit").get<std::size_t>() == 0) continue;
                    const double median = std::max(points[i].at("median_ulps").get<double>(), 0.5);
                    const double curve = fitted[i][0].is_null() ? median : fitted[i][0].get<double>();
                    char line[96];
                    std::snprintf(line, sizeof line, "%.6g %.6g %.6g\n", points[i].at("x").get<double>(), median, curve);
                    data += line;
                }
                if (data.empty()) continue;
                const std::string policy = r.at("policy");
                const std::string file = p.name + "_" + policy + ".dat";
                p.data.emplace_back(file, data);
                const json& fit = r.at("fit");
                std::string title = policy;
                if (fit.at("ok").get<bool>() && !fit.at("p").is_null()) title += " (p = " + text(fit.at("p").get<double>(), 2) + ")";
                const std::string lt = " lt " + std::to_string(colour++);
                p.script += std::string(first ? "" : ", ") + "'<dir>/" + file + "' using 1:2 with points pt 7" + lt + " title '" + title +
                            "', '<dir>/" + file + "' using 1:3 with lines lw 2" + lt + " notitle";
                first = false;
            }
            if (first) continue;
            p.script += "\n";
            out.push_back(p);
        }
    }
    for (const char* primitive : {"sphere", "plane"})
        for (const char* type : {"double", "float"})
            if (auto p = misclassification_plot(rows, primitive, type)) out.push_back(*p);
    return out;
}

}  // namespace

Campaign sweep_campaign()
{
    Campaign c;
    c.name = "sweep";
    c.title = "Precision sweeps toward tangency, distance and translation (Ceres error-model fits)";
    c.plan = plan;
    c.run = run;
    c.csv_header = "primitive,type,policy,sweep,family,x,cases,both_hit,hit_correct,part_correct,median_ulps,p99_ulps,max_ulps";
    c.reduce = reduce;
    c.plots = plots;
    return c;
}

}  // namespace rayq::report
