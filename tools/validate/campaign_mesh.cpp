// The mesh cross-check campaign (issue 5): every standard case of rayq::mesh at resolutions
// 8, 16, … up to the preset's maximum; one work item per primitive case.
#include <cmath>
#include <cstdio>

#include <rayq/mesh/compare.hpp>

#include "campaign.hpp"

namespace rayq::report {

namespace {

json number(double v) { return std::isfinite(v) ? json(v) : json(nullptr); }  // JSON has no NaN

std::vector<Item> plan(const Settings&)
{
    std::vector<Item> items;
    const auto cases = mesh::standard_cases();
    for (std::size_t i = 0; i < cases.size(); ++i) items.push_back({cases[i].name, {{"index", i}}});
    return items;
}

json run(const Settings& s, const Item& item, std::string& csv)
{
    const auto cases = mesh::standard_cases();
    const std::size_t index = item.spec.at("index");
    if (index >= cases.size() || cases[index].name != item.id)
        throw std::runtime_error("mesh campaign: case list changed since planning (" + item.id + ")");
    mesh::SweepOptions options;
    options.resolutions.clear();
    for (int n = 8; n <= s.mesh_max_n; n *= 2) options.resolutions.push_back(n);
    options.rays = s.mesh_rays;
    options.seed = s.seed;
    const mesh::CaseResult r = mesh::run_case(cases[index], options);

    json levels = json::array();
    for (const mesh::Level& l : r.levels) {
        levels.push_back({{"n", l.n}, {"faces", l.faces}, {"deviation", l.deviation}, {"rays", l.rays},
                          {"band", l.band}, {"compared_hits", l.compared_hits}, {"compared_misses", l.compared_misses},
                          {"hit_miss", l.hit_miss}, {"part", l.part}, {"front", l.front}, {"t_outliers", l.t_outliers},
                          {"t_common_median", number(l.t_common.median)},
                          {"normal_common_median", number(l.normal_common.median)},
                          {"t_curved_max", number(l.t_curved.max)}, {"t_flat_max", number(l.t_flat.max)}});
        char line[256];
        std::snprintf(line, sizeof line, "%s,%d,%zu,%.6g,%zu,%zu,%zu,%.6g,%.6g\n", r.name.c_str(), l.n, l.faces,
                      l.deviation, l.rays, l.band, l.disagreements(), l.t_common.median, l.normal_common.median);
        csv += line;
    }
    json examples = json::array();
    for (const auto& e : r.examples) examples.push_back({{"kind", e.kind}, {"n", e.n}, {"detail", e.detail}});
    return {{"name", r.name}, {"flat", r.flat}, {"apex", r.apex}, {"levels", levels},
            {"slope_t", number(r.slope_t)}, {"slope_normal", number(r.slope_normal)},
            {"disagreements", r.disagreements()}, {"examples", examples}};
}

json reduce(const Settings&, const std::vector<json>& results)
{
    json metrics = json::object(), rows = json::array();
    std::uint64_t disagreements = 0;
    for (const json& r : results) {
        const std::string m = "mesh." + r.at("name").get<std::string>() + ".";
        if (!r.at("slope_t").is_null()) metrics[m + "slope_t"] = r.at("slope_t");
        if (!r.at("slope_normal").is_null()) metrics[m + "slope_normal"] = r.at("slope_normal");
        metrics[m + "disagreements"] = r.at("disagreements");
        disagreements += r.at("disagreements").get<std::uint64_t>();
        rows.push_back(r);
    }
    metrics["mesh.disagreements"] = disagreements;
    json table = json::array();
    for (const json& r : rows) {
        const json& last = r.at("levels").back();
        table.push_back({r["name"], r["slope_t"], r["slope_normal"], r["disagreements"], last["n"], last["rays"],
                         last["band"], last["t_common_median"], last["t_flat_max"]});
    }
    const json tables = json::array({{{"title", "Convergence per case (least-squares log-log slopes over n)"},
                                      {"columns", {"case", "slope t", "slope normal", "disagreements", "max n", "rays",
                                                   "band (max n)", "median t error (max n)", "max flat t error (max n)"}},
                                      {"rows", table}}});
    return {{"metrics", metrics}, {"rows", rows}, {"tables", tables}};
}

// Median t error (curved parts, the fit's common rays) against n, log–log, one line per case.
std::vector<Plot> plots(const json& sections)
{
    const json& section = sections.at("mesh");
    Plot p;
    p.name = "mesh_convergence";
    p.title = "Mesh convergence: median |t_mesh - t_kernel| on curved parts against resolution n";
    p.script = "set logscale xy\nset format y '10^{%L}'\nset xlabel 'n (segments around)'\nset ylabel 'median t error'\n"
               "set key outside right\nset grid\nplot ";
    bool first = true;
    for (const json& r : section.at("rows")) {
        if (r.at("slope_t").is_null()) continue;
        std::string data;
        for (const json& l : r.at("levels")) {
            if (l.at("t_common_median").is_null() || l.at("t_common_median").get<double>() <= 0) continue;
            char line[64];
            std::snprintf(line, sizeof line, "%d %.6g\n", l.at("n").get<int>(), l.at("t_common_median").get<double>());
            data += line;
        }
        const std::string name = r.at("name");
        const std::string file = "mesh_" + name + ".dat";
        p.data.emplace_back(file, data);
        char title[128];
        std::snprintf(title, sizeof title, "%s (slope %.2f)", name.c_str(), r.at("slope_t").get<double>());
        p.script += std::string(first ? "" : ", ") + "'<dir>/" + file + "' using 1:2 with linespoints title '" + title + "'";
        first = false;
    }
    if (first) return {};
    p.script += "\n";
    return {p};
}

}  // namespace

Campaign mesh_campaign()
{
    Campaign c;
    c.name = "mesh";
    c.title = "Mesh cross-check (OpenMesh tessellations, CGAL AABB tree)";
    c.plan = plan;
    c.run = run;
    c.csv_header = "case,n,faces,deviation,rays,band,disagreements,t_common_median,normal_common_median";
    c.reduce = reduce;
    c.plots = plots;
    return c;
}

}  // namespace rayq::report
