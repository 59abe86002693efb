// The speed campaign (issue 7): runs the Google Benchmark programs built next to rayq-validate
// and keeps the median of repetitions per benchmark, with ratios taken inside the same run
// (timings are never comparable across runs on a shared machine). Not deterministic: shard/merge
// identity excludes it.
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <sstream>
#include <unistd.h>

#include "campaign.hpp"
#include "process.hpp"

namespace rayq::report {

namespace {

struct Program {
    const char* item;
    const char* binary;  // in the tools build directory (RAYQ_TOOLS_BINARY_DIR), relative
    const char* quick_filter;  // --benchmark_filter under --quick ("" = everything)
    const char* filter;        // otherwise
};
const Program programs[] = {
    {"policies", "rayq-bench", "", ""},
    // One ray against 16 and 1,024 primitives: scalar loop, compile-time scene, runtime variant.
    {"scene", "rayq-bench-scene", "sphere/float/fast/(loop|scene)/16$", "/(16|1024)$"},
};

// Google Benchmark writes NaN and Infinity bare (e.g. the "cv" aggregate of a counter that is 0 in
// every repetition is 0/0), which strict JSON does not allow: they become null.
std::string strict_json(std::string text)
{
    for (const char* bare : {"-NaN", "NaN", "-Infinity", "Infinity"}) {
        const std::string needle = std::string(": ") + bare;
        for (std::size_t at = text.find(needle); at != std::string::npos; at = text.find(needle, at))
            text.replace(at, needle.size(), ": null");
    }
    return text;
}

std::vector<Item> plan(const Settings& s)
{
    std::vector<Item> items;
    for (const Program& p : programs)
        items.push_back({p.item, {{"binary", p.binary}, {"filter", s.preset == "quick" ? p.quick_filter : p.filter}}});
    return items;
}

json run(const Settings& s, const Item& item, std::string& csv)
{
    const std::string binary = tools_binary(item.spec.at("binary").get<std::string>());
    const std::filesystem::path out = temporary_path("bench.json");
    char min_time[64];
    std::snprintf(min_time, sizeof min_time, "--benchmark_min_time=%g", s.bench_min_time);
    std::vector<std::string> args = {binary, min_time, "--benchmark_repetitions=5", "--benchmark_report_aggregates_only=true",
                                     "--benchmark_format=json", "--benchmark_out_format=json", "--benchmark_out=" + out.string()};
    if (const std::string filter = item.spec.value("filter", ""); !filter.empty()) args.push_back("--benchmark_filter=" + filter);
    const int status = run_program(args, /*quiet=*/true);
    if (status != 0) throw std::runtime_error(binary + " exited with status " + std::to_string(status));
    std::ifstream in(out);
    const json j = json::parse(strict_json(std::string(std::istreambuf_iterator<char>(in), {})));
    std::filesystem::remove(out);
    json rows = json::array();
    for (const json& b : j.at("benchmarks")) {
        if (b.value("aggregate_name", "") != "median") continue;
        json row = {{"name", b.at("run_name")}, {"ns", b.at("real_time")}, {"time_unit", b.at("time_unit")}};
        json counters = json::object();
        for (const auto& [k, v] : b.items())
            if (v.is_number() && k != "real_time" && k != "cpu_time" && k != "iterations" && k != "repetitions" &&
                k != "repetition_index" && k != "threads" && k != "family_index" && k != "per_family_instance_index")
                counters[k] = v;
        row["counters"] = counters;
        csv += item.id + "," + b.at("run_name").get<std::string>() + "," + b.at("real_time").dump() + "," +
               b.at("time_unit").get<std::string>() + "\n";
        rows.push_back(row);
    }
    return {{"program", item.id}, {"context", j.at("context")}, {"rows", rows}};
}

// rayq-bench names its benchmarks intersect/<primitive>/<type>/<policy>; time is per batch of rays,
// so ratios between policies of the same primitive and type are what we report.
json reduce(const Settings&, const std::vector<json>& results)
{
    json metrics = json::object(), rows = json::array();
    std::map<std::string, double> ns;  // run_name -> median
    for (const json& r : results)
        for (const json& row : r.at("rows")) {
            rows.push_back(row);
            ns[row.at("name").get<std::string>()] = row.at("ns").get<double>();
        }
    json ratios = json::array();
    for (const auto& [name, t] : ns) {
        const auto slash = name.rfind('/');
        if (name.compare(0, 10, "intersect/") != 0 || name.substr(slash + 1) != "fast") continue;
        const std::string stem = name.substr(0, slash);
        for (const char* policy : {"stable", "accurate"}) {
            const auto other = ns.find(stem + "/" + policy);
            if (other == ns.end() || t <= 0) continue;
            const std::string variant = stem.substr(10);  // "<primitive>/<type>"
            const double ratio = other->second / t;
            ratios.push_back({{"variant", variant}, {"policy", policy}, {"over_fast", ratio}});
            std::string key = variant;
            for (char& ch : key) if (ch == '/') ch = '.';
            metrics["speed." + std::string(policy) + "_over_fast." + key] = ratio;
        }
    }
    // rayq-bench-scene: <query>/<prim>/<type>/<policy>/<loop|scene|variant>/<N>; the scene's and the
    // variant's speed-up over the scalar loop, same run.
    json scene_table = json::array();
    for (const auto& [name, t] : ns) {
        const std::string tail = "/loop/";
        const auto at = name.find(tail);
        if (at == std::string::npos || t <= 0) continue;
        const std::string stem = name.substr(0, at), n = name.substr(at + tail.size());
        json row = {stem, n};
        for (const char* v : {"scene", "variant"}) {
            const auto other = ns.find(stem + "/" + v + "/" + n);
            const double speedup = other == ns.end() || other->second <= 0 ? 0.0 : t / other->second;
            row.push_back(speedup);
            std::string key = stem + "." + n;
            for (char& ch : key) if (ch == '/') ch = '.';
            if (speedup > 0) metrics["speed." + std::string(v) + "_over_loop." + key] = speedup;
        }
        scene_table.push_back(row);
    }
    json bench_table = json::array(), ratio_table = json::array();
    for (const json& r : rows) bench_table.push_back({r["name"], r["ns"], r["time_unit"], r["counters"].dump()});
    for (const json& r : ratios) ratio_table.push_back({r["variant"], r["policy"], r["over_fast"]});
    const json tables = json::array(
        {{{"title", "Cost relative to fast (same run)"}, {"columns", {"primitive/type", "policy", "time / fast"}},
          {"rows", ratio_table}},
         {{"title", "One ray against N primitives: speed-up over the scalar loop (same run)"},
          {"columns", {"query/primitive/type/policy", "N", "Scene<...>", "std::variant"}},
          {"rows", scene_table}},
         {{"title", "Benchmarks (median of 5 repetitions)"}, {"columns", {"benchmark", "median time", "unit", "counters"}},
          {"rows", bench_table}}});
    return {{"metrics", metrics}, {"rows", rows}, {"ratios", ratios}, {"tables", tables}};
}

// Run time against error: one point per (policy, type), x = median over primitives of the time
// per ray relative to fast, y = the oracle's worst p99 ulp error of that policy and type.
std::vector<Plot> plots(const json& sections)
{
    const json& speed = sections.at("speed");
    Plot p;
    p.name = "speed_vs_error";
    p.title = "Run time against error: cost relative to fast (same run) vs p99 ulp error from the exact oracle";
    std::map<std::string, std::vector<double>> cost;  // "policy/type" -> ratios over primitives
    for (const json& r : speed.at("ratios")) {
        const std::string variant = r.at("variant");
        const std::string type = variant.substr(variant.find('/') + 1);
        cost[r.at("policy").get<std::string>() + "/" + type].push_back(r.at("over_fast"));
    }
    for (const char* type : {"float", "double"}) cost[std::string("fast/") + type].push_back(1.0);
    if (!sections.contains("oracle")) return {};
    std::map<std::string, double> p99;  // worst over primitives
    for (const json& row : sections.at("oracle").at("rows")) {
        const std::string k = row.at("policy").get<std::string>() + "/" + row.at("type").get<std::string>();
        p99[k] = std::max(p99[k], row.at("p99_ulp").get<double>());
    }
    std::string data;
    for (auto& [k, v] : cost) {
        if (!p99.count(k)) continue;
        std::sort(v.begin(), v.end());
        char line[128];
        std::snprintf(line, sizeof line, "%.6g %.6g \"%s\"\n", v[v.size() / 2], std::max(p99[k], 1e-3), k.c_str());
        data += line;
    }
    p.data.emplace_back("speed_vs_error.dat", data);
    p.script = "set logscale y\nset xlabel 'time per ray relative to fast (median over primitives)'\n"
               "set ylabel 'worst p99 ulp error of t'\nset grid\nset offsets 0.3, 0.6, 0, 0\n"
               "plot '<dir>/speed_vs_error.dat' using 1:2 with points pt 7 ps 1.5 notitle, "
               "'' using 1:2:3 with labels offset 0,1 notitle\n";
    return {p};
}

}  // namespace

Campaign speed_campaign()
{
    Campaign c;
    c.name = "speed";
    c.title = "Speed (Google Benchmark, medians of 5 repetitions, ratios from the same run)";
    c.deterministic = false;
    c.plan = plan;
    c.run = run;
    c.csv_header = "program,benchmark,median_time,time_unit";
    c.reduce = reduce;
    c.plots = plots;
    return c;
}

}  // namespace rayq::report
