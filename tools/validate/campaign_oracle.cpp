// The exact-oracle campaign (issue 4): generated cases of every family for every primitive and
// number type, each measured under the three policies against rayq::oracle; plus the curated
// fixture files. Per (primitive, policy, type, family class): integer counts and log histograms
// of the ulp error and of the bound/actual-error ratio, so shards merge exactly.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <set>
#include <tuple>

#include <rayq/detail/exact.hpp>
#include <rayq/oracle/fixtures.hpp>
#include <rayq/oracle/harness.hpp>
#include <rayq/stats/histogram.hpp>

#include "campaign.hpp"

namespace rayq::report {

namespace {

using oracle::Policy;
using stats::LogHistogram;

// The primitives the accurate contract covers in full (issue 4); quadrics and transformed
// instances only require certified bounds.
const std::set<std::string> contract_scope = {"sphere", "plane", "disk", "parallelogram", "triangle", "cylinder", "cone"};

struct Cell {
    std::uint64_t cases = 0, hit_agree = 0, both_hit = 0, part_agree = 0, front_agree = 0, faithful = 0;
    std::uint64_t kernel_hits = 0, bounded = 0, violations = 0, uncertified = 0, other_crossing = 0;
    std::uint64_t fallback_cases = 0;  // cases where the kernel's exact fallback ran (accurate)
    double max_angle = 0;
    LogHistogram ulps;         // among both_hit
    LogHistogram bound_ratio;  // t_error / |t − t_exact| among both_hit with a finite bound (inf when exact)

    void merge(const Cell& o)
    {
        cases += o.cases; hit_agree += o.hit_agree; both_hit += o.both_hit; part_agree += o.part_agree;
        front_agree += o.front_agree; faithful += o.faithful; kernel_hits += o.kernel_hits; bounded += o.bounded;
        violations += o.violations; uncertified += o.uncertified; other_crossing += o.other_crossing;
        fallback_cases += o.fallback_cases;
        max_angle = std::max(max_angle, o.max_angle);
        ulps.merge(o.ulps);
        bound_ratio.merge(o.bound_ratio);
    }
    json to_json() const
    {
        return {{"cases", cases}, {"hit_agree", hit_agree}, {"both_hit", both_hit}, {"part_agree", part_agree},
                {"front_agree", front_agree}, {"faithful", faithful}, {"kernel_hits", kernel_hits},
                {"bounded", bounded}, {"violations", violations}, {"uncertified", uncertified},
                {"other_crossing", other_crossing}, {"fallback_cases", fallback_cases}, {"max_angle", max_angle},
                {"ulps", ulps.to_json()}, {"bound_ratio", bound_ratio.to_json()}};
    }
    static Cell from_json(const json& j)
    {
        Cell c;
        c.cases = j.at("cases"); c.hit_agree = j.at("hit_agree"); c.both_hit = j.at("both_hit");
        c.part_agree = j.at("part_agree"); c.front_agree = j.at("front_agree"); c.faithful = j.at("faithful");
        c.kernel_hits = j.at("kernel_hits"); c.bounded = j.at("bounded"); c.violations = j.at("violations");
        c.uncertified = j.at("uncertified"); c.other_crossing = j.at("other_crossing");
        c.fallback_cases = j.at("fallback_cases"); c.max_angle = j.at("max_angle");
        c.ulps = LogHistogram::from_json(j.at("ulps"));
        c.bound_ratio = LogHistogram::from_json(j.at("bound_ratio"));
        return c;
    }
};

// (primitive, policy, type, family class)
using Key = std::tuple<std::string, std::string, std::string, std::string>;

std::string key_text(const Key& k)
{
    return std::get<0>(k) + "|" + std::get<1>(k) + "|" + std::get<2>(k) + "|" + std::get<3>(k);
}

template <class T>
double t_error_of(const std::optional<Hit<T>>& h) { return h ? static_cast<double>(h->t_error) : 0.0; }

void measure_case(const oracle::Fixture& f, std::map<Key, Cell>& cells, std::string* csv_or_null)
{
    std::string ignored;
    std::string& csv = csv_or_null ? *csv_or_null : ignored;
    const oracle::Truth truth = oracle::truth_of(f.input);
    const oracle::ExactHit& exact = truth.first_hit();
    if (!exact.defined) return;
    const std::string primitive = oracle::primitive_name(f.input);
    const std::string type = oracle::scalar_name(oracle::scalar_of(f.input));
    const std::string cls = oracle::family_class(f.family);
    char buf[160];
    std::snprintf(buf, sizeof buf, "%s,%s,%s,%d,%.17Lg", primitive.c_str(), type.c_str(), f.family.c_str(),
                  exact.hit ? 1 : 0, exact.hit ? exact.t_long : 0.0L);
    csv += buf;
    for (Policy p : oracle::all_policies) {
        const oracle::KernelAnswer a = oracle::run_kernel(p, f.input);
        const bool fell_back = a.exact_fallback;
        const oracle::Measurement m = a.is_float ? truth.measure(a.f) : truth.measure(a.d);
        const double t_error = a.is_float ? t_error_of(a.f) : t_error_of(a.d);
        Cell& c = cells[Key{primitive, oracle::policy_name(p), type, cls}];
        ++c.cases;
        c.hit_agree += m.hit_agrees;
        c.fallback_cases += fell_back;
        if (m.kernel_hit) {
            ++c.kernel_hits;
            c.bounded += m.bounded;
            c.violations += m.bound_violated;
            c.uncertified += m.uncertified;
        }
        if (m.both_hit) {
            ++c.both_hit;
            c.part_agree += m.part_agrees;
            c.front_agree += m.front_face_agrees;
            c.faithful += m.faithful;
            c.other_crossing += m.other_crossing;
            if (!std::isnan(m.normal_angle)) c.max_angle = std::max(c.max_angle, m.normal_angle);
            c.ulps.add(m.ulps);
            if (m.bounded) {
                const double actual = m.rel_error * std::fabs(static_cast<double>(exact.t_long));
                c.bound_ratio.add(actual > 0 ? t_error / actual : HUGE_VAL);
            }
        }
        std::snprintf(buf, sizeof buf, ",%d,%.6g,%.6g,%d,%d", m.kernel_hit ? 1 : 0, m.both_hit ? m.ulps : 0.0, t_error,
                      m.bound_violated ? 1 : 0, fell_back ? 1 : 0);
        csv += buf;
    }
    csv += '\n';
}

oracle::Scalar scalar_named(const std::string& s) { return s == "float" ? oracle::Scalar::f32 : oracle::Scalar::f64; }

std::vector<Item> plan(const Settings& s)
{
    std::vector<Item> items;
    for (const std::string& prim : oracle::generated_primitives())
        if (s.oracle_primitives.empty() ||
            std::find(s.oracle_primitives.begin(), s.oracle_primitives.end(), prim) != s.oracle_primitives.end())
        for (const char* type : {"float", "double"})
            for (std::size_t first = 0; first < s.oracle_cases; first += s.oracle_chunk) {
                const std::size_t count = std::min(s.oracle_chunk, s.oracle_cases - first);
                char id[160];
                std::snprintf(id, sizeof id, "%s/%s/%06zu", prim.c_str(), type, first / s.oracle_chunk);
                items.push_back({id, {{"primitive", prim}, {"type", type}, {"first", first}, {"count", count}}});
            }
    if (!s.fixtures_dir.empty()) {
        std::vector<std::string> files;
        for (const auto& e : std::filesystem::directory_iterator(s.fixtures_dir))
            if (e.path().extension() == ".txt") files.push_back(e.path().filename().string());
        std::sort(files.begin(), files.end());
        for (const auto& f : files) items.push_back({"fixtures/" + f, {{"file", s.fixtures_dir + "/" + f}}});
    }
    return items;
}

json run(const Settings& s, const Item& item, std::string& csv)
{
    std::map<Key, Cell> cells;
    if (item.spec.contains("file")) {
        for (const auto& f : oracle::load_fixtures(item.spec.at("file").get<std::string>())) measure_case(f, cells, &csv);
    } else {
        const std::string prim = item.spec.at("primitive");
        const oracle::Scalar type = scalar_named(item.spec.at("type"));
        const std::vector<std::string> families = oracle::family_names(prim, type);
        const std::size_t first = item.spec.at("first"), count = item.spec.at("count");
        // The same case sequence as oracle::generate_cases(prim, type, N, seed): round robin.
        for (std::size_t i = first; i < first + count; ++i)
            measure_case(oracle::generate(prim, type, families[i % families.size()], s.seed, i / families.size()),
                         cells, i < s.oracle_csv_cases ? &csv : nullptr);
    }
    json out = json::object();
    for (const auto& [k, c] : cells) out[key_text(k)] = c.to_json();
    return out;
}

struct Totals {
    std::map<Key, Cell> by_primitive;  // family class "all"
    std::map<Key, Cell> by_class;      // primitive "all"
};

json row_json(const Key& k, const Cell& c)
{
    return {{"primitive", std::get<0>(k)}, {"policy", std::get<1>(k)}, {"type", std::get<2>(k)},
            {"family", std::get<3>(k)}, {"cases", c.cases}, {"hit_agree_pct", percent(c.hit_agree, c.cases)},
            {"part_agree_pct", percent(c.part_agree, c.both_hit)}, {"front_agree_pct", percent(c.front_agree, c.both_hit)},
            {"faithful_pct", percent(c.faithful, c.both_hit)}, {"max_ulp", c.ulps.max()},
            {"p99_ulp", c.ulps.quantile(0.99)}, {"median_ulp", c.ulps.quantile(0.5)},
            {"kernel_hits", c.kernel_hits}, {"bounded_pct", percent(c.bounded, c.kernel_hits)},
            {"bound_violations", c.violations}, {"uncertified", c.uncertified},
            {"bound_ratio_median", c.bound_ratio.quantile(0.5)}, {"bound_ratio_p99", c.bound_ratio.quantile(0.99)},
            {"fallback_pct", percent(c.fallback_cases, c.cases)}, {"max_angle", c.max_angle},
            {"ulps", c.ulps.to_json()}};
}

json reduce(const Settings&, const std::vector<json>& results)
{
    std::map<Key, Cell> cells;
    for (const json& r : results)
        for (const auto& [text, cj] : r.items()) {
            Key k;
            std::string parts[4];
            std::size_t at = 0;
            for (int i = 0; i < 4; ++i) {
                const std::size_t bar = i < 3 ? text.find('|', at) : text.size();
                parts[i] = text.substr(at, bar - at);
                at = bar + 1;
            }
            const Cell c = Cell::from_json(cj);
            cells[Key{parts[0], parts[1], parts[2], "all"}].merge(c);
            cells[Key{"all", parts[1], parts[2], parts[3]}].merge(c);
        }

    json rows = json::array(), family_rows = json::array(), metrics = json::object();
    std::map<std::string, Cell> per_policy, contract;  // over everything; accurate over the contract's scope
    for (const auto& [k, c] : cells) {
        const auto& [prim, policy, type, cls] = k;
        if (prim == "all") { family_rows.push_back(row_json(k, c)); continue; }
        rows.push_back(row_json(k, c));
        per_policy[policy].merge(c);
        if (contract_scope.count(prim)) contract[policy].merge(c);
        const std::string m = "oracle." + policy + "." + type + "." + prim + ".";
        metrics[m + "hit_agree_pct"] = percent(c.hit_agree, c.cases);
        metrics[m + "part_agree_pct"] = percent(c.part_agree, c.both_hit);
        metrics[m + "max_ulp"] = c.ulps.max();
        metrics[m + "bound_violations"] = c.violations;
    }
    for (const auto& [policy, c] : per_policy) {
        metrics["oracle." + policy + ".bound_violations"] = c.violations;
        metrics["oracle." + policy + ".cases"] = c.cases;
        metrics["oracle." + policy + ".fallback_pct"] = percent(c.fallback_cases, c.cases);
    }
    for (const auto& [policy, c] : contract) {
        const std::string m = "oracle." + policy + ".contract_scope.";
        metrics[m + "hit_agree_pct"] = percent(c.hit_agree, c.cases);
        metrics[m + "part_agree_pct"] = percent(c.part_agree, c.both_hit);
        metrics[m + "max_ulp"] = c.ulps.max();
        metrics[m + "cases"] = c.cases;
    }
    const json columns = {"primitive", "policy", "type", "family", "cases", "hit %", "part %", "front %", "faithful %",
                          "max ulp", "p99 ulp", "bound violations / hits", "finite bound %", "bound/actual median", "bound/actual p99",
                          "fallback %"};
    auto table_rows = [](const json& source) {
        json out = json::array();
        for (const json& r : source)
            out.push_back({r["primitive"], r["policy"], r["type"], r["family"], r["cases"], r["hit_agree_pct"],
                           r["part_agree_pct"], r["front_agree_pct"], r["faithful_pct"], r["max_ulp"], r["p99_ulp"],
                           r["bound_violations"].dump() + " / " + r["kernel_hits"].dump(), r["bounded_pct"], r["bound_ratio_median"],
                           r["bound_ratio_p99"], r["fallback_pct"]});
        return out;
    };
    const json tables = json::array(
        {{{"title", "Per primitive, policy and number type"}, {"columns", columns}, {"rows", table_rows(rows)}},
         {{"title", "Per family class (all primitives)"}, {"columns", columns}, {"rows", table_rows(family_rows)}}});
    return {{"metrics", metrics}, {"rows", rows}, {"family_rows", family_rows}, {"tables", tables},
            {"contract_scope", std::vector<std::string>(contract_scope.begin(), contract_scope.end())}};
}

// One plot per policy and type: the cumulative distribution of the ulp error of t over the
// both-hit cases (read from the merged histograms), one line per primitive.
std::vector<Plot> plots(const json& sections)
{
    const json& section = sections.at("oracle");
    std::vector<Plot> out;
    for (const char* policy : {"fast", "stable", "accurate"})
        for (const char* type : {"float", "double"}) {
            Plot p;
            p.name = std::string("oracle_ulps_") + policy + "_" + type;
            p.title = std::string("Error of t, ") + policy + " policy, " + type +
                      ": fraction of both-hit cases with error <= x ulps";
            std::string script = "set logscale x\nset format x '10^{%L}'\nset xlabel 'ulp error of t'\n"
                                 "set ylabel 'cumulative fraction'\nset yrange [0:1.02]\nset key outside right\n"
                                 "set grid\nplot ";
            bool first = true;
            int line_type = 0;
            for (const json& row : section.at("rows")) {
                if (row.at("policy") != policy || row.at("type") != type) continue;
                const LogHistogram h = LogHistogram::from_json(row.at("ulps"));
                ++line_type;
                if (h.finite() == 0) continue;
                const std::string file = p.name + "_" + row.at("primitive").get<std::string>() + ".dat";
                std::string data;
                std::uint64_t seen = 0;
                for (const auto& [idx, n] : h.bins()) {
                    seen += n;
                    char line[96];
                    std::snprintf(line, sizeof line, "%.6g %.6g\n", std::max(LogHistogram::upper_edge(idx), 1e-3),
                                  static_cast<double>(seen) / static_cast<double>(h.finite()));
                    data += line;
                }
                p.data.emplace_back(file, data);
                script += std::string(first ? "" : ", ") + "'<dir>/" + file + "' using 1:2 with steps lw 2 lt " +
                          std::to_string(line_type) + " title '" + row.at("primitive").get<std::string>() + "'";
                first = false;
            }
            if (first) continue;
            p.script = script + "\n";
            out.push_back(p);
        }
    return out;
}

}  // namespace

Campaign oracle_campaign()
{
    Campaign c;
    c.name = "oracle";
    c.title = "Exact oracle agreement and certified bounds";
    c.plan = plan;
    c.run = run;
    c.csv_header = "primitive,type,family,exact_hit,t_exact,"
                   "fast_hit,fast_ulps,fast_t_error,fast_bound_violated,fast_fallback,"
                   "stable_hit,stable_ulps,stable_t_error,stable_bound_violated,stable_fallback,"
                   "accurate_hit,accurate_ulps,accurate_t_error,accurate_bound_violated,accurate_fallback";
    c.reduce = reduce;
    c.plots = plots;
    return c;
}

}  // namespace rayq::report
