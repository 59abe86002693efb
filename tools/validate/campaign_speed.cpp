// The speed campaign (issue 7): runs the Google Benchmark programs built next to rayq-validate
// and keeps the median of repetitions (or rounds: Program::rounds) per benchmark, with ratios
// taken inside the same run (timings are never comparable across runs on a shared machine).
// Not deterministic: shard/merge identity excludes it. A program that is not built (rayq-bench-embree without Embree 3, all of
// them without Google Benchmark) shows as skipped, and gates on its metrics are skipped.
//
// rayq-bench-embree also answers the oracle campaign's float sphere cases with Embree's native
// sphere; those answers and rayq's three policies on the same cases are measured against the
// exact oracle here, so Embree's point on the run-time-against-error plot is measured, not assumed.
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <map>
#include <optional>
#include <sstream>
#include <unistd.h>

#include <rayq/oracle/fixtures.hpp>
#include <rayq/oracle/harness.hpp>
#include <rayq/stats/histogram.hpp>

#include "campaign.hpp"
#include "process.hpp"

namespace rayq::report {

namespace {

struct Program {
    const char* item;
    const char* binary;        // in the tools build directory (RAYQ_TOOLS_BINARY_DIR), relative
    const char* quick_filter;  // --benchmark_filter under --quick ("" = everything)
    const char* filter;        // otherwise
    const char* needs;         // what building it takes (the reason shown when it is absent)
    std::vector<std::string> metrics;  // prefixes of the metrics its results give
    bool sphere_answers = false;       // also answers the oracle's float sphere cases (Embree)
    // 0: one run, five repetitions of every benchmark in random order, medians. N: N runs
    // ("rounds") of one repetition each in registration order, where the rows a ratio compares run
    // back to back; each ratio is the median of its N same-round ratios (reduce()).
    int rounds = 0;
    // Its -march=native copy (tools/CMakeLists.txt), run instead when built: binary_of().
    const char* native_binary = nullptr;
    bool targets = false;  // its rows are read by the issue-7 targets alone (targets_section())
};
const std::vector<Program> programs = {
    // The gated ratios (accurate and stable over fast) by rounds: rayq-bench registers a primitive's
    // three policies one after the other. With five interleaved repetitions of all 96 benchmarks,
    // a ratio's two medians were sampled up to minutes apart, and one report failed the gate on
    // noise: the open double cylinder at 1.30 where runs of that pair alone gave 1.17-1.18.
    {"policies", "rayq-bench", "", "", "Google Benchmark", {"speed.stable_over_fast.", "speed.accurate_over_fast."}, false, 5},
    // One ray against 16 and 1,024 primitives: scalar loop, compile-time scene, runtime variant.
    {"scene", "rayq-bench-scene", "sphere/float/fast/(loop|scene)/16$", "/(16|1024)$", "Google Benchmark",
     {"speed.scene_over_loop.", "speed.variant_over_loop."}},
    // Embree's native spheres, rayq inside Embree and rayq's compile-time scene on 1 … 100,000
    // spheres; the scalar loops at N = 1 are the like-for-like reference of the Pareto plot.
    {"embree", "rayq-bench-embree", "^sphere/(embree_points|rayq_embree_stable|rayq_scene_fast|rayq_loop_(fast|stable|accurate))/",
     "^sphere/(embree_points|rayq_embree_(stable|accurate)|rayq_scene_(fast|stable|accurate)|rayq_loop_(fast|stable|accurate))/",
     "Embree 3 (libembree-dev) and Google Benchmark", {"speed.embree."}, true},
    // The issue-7 targets (targets[] below), from the -march=native copies tools/report.sh builds:
    // Embree runs its widest ISA whatever rayq was compiled for, and the targets were set for
    // -march=native builds. In rounds, so a ratio's two rows run back to back.
    {"targets_embree", "rayq-bench-embree",
     "^(sphere/(embree_points|rayq_scene_fast_shading)/(1|16)|cylinder/(embree_cone_curve|rayq_scene_fast_shading)/1)$",
     "^(sphere/(embree_points|rayq_scene_fast_shading)/(1|16|1000)|cylinder/(embree_cone_curve|rayq_scene_fast_shading)/(1|16)|"
     "sphere/(embree_points|rayq_embree_(stable|accurate))/100000)$",
     "Embree 3 (libembree-dev) and Google Benchmark", {"speed.targets.", "speed.target_margins."}, false, 5,
     "rayq-bench-embree-native", true},
    {"targets_scene", "rayq-bench-scene", "^(closest|any)/sphere/float/fast/scene/1024$",
     "^(closest|any)/(sphere/(float|double)/fast|cylinder/float/stable|cone/float/accurate)/scene/1024$", "Google Benchmark",
     {"speed.targets.", "speed.target_margins."}, false, 5, "rayq-bench-scene-native", true},
};

const Program& program_named(const std::string& item)
{
    for (const Program& p : programs)
        if (item == p.item) return p;
    throw std::runtime_error("speed campaign: unknown program " + item);
}

// Embree's accuracy is measured on the first oracle_cases float sphere cases of the oracle
// campaign (same generator, same seed), at most this many: the speed campaign runs each program
// as one work item, and the full preset's 10^6 would keep it busy for an hour.
constexpr std::size_t max_sphere_answers = 10000;

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

// A note's title about program p: its binary, and for the targets items which use it.
std::string note_title(const Program& p, const char* what)
{
    return std::string(p.binary) + (p.targets ? " (issue-7 targets)" : "") + ": " + what;
}

// The binary a program runs, and whether it was compiled with -march=native: its native copy when
// it has one and that is built, else the plain one (native too when the tools are: RAYQ_NATIVE).
std::pair<std::string, bool> binary_of(const Program& p)
{
#ifdef RAYQ_TOOLS_NATIVE
    return {p.binary, true};
#else
    if (p.native_binary && std::filesystem::exists(tools_binary(p.native_binary))) return {p.native_binary, true};
    return {p.binary, false};
#endif
}

std::vector<Item> plan(const Settings& s)
{
    std::vector<Item> items;
    for (const Program& p : programs) {
        // "built" and "native" are part of the spec so that a resumed run does not reuse a skipped
        // result once the program has been built, nor a portable one once its native copy has.
        const auto [binary, native] = binary_of(p);
        json spec = {{"binary", binary}, {"native", native}, {"filter", s.preset == "quick" ? p.quick_filter : p.filter},
                     {"built", std::filesystem::exists(tools_binary(binary))}};
        if (p.sphere_answers) spec["sphere_cases"] = std::min(s.oracle_cases, max_sphere_answers);
        items.push_back({p.item, spec});
    }
    return items;
}

// The median of a run's values (0 for none): a benchmark's rounds, a ratio's same-round ratios.
double median(std::vector<double> v)
{
    std::sort(v.begin(), v.end());
    const std::size_t n = v.size();
    return n == 0 ? 0.0 : n % 2 ? v[n / 2] : (v[n / 2 - 1] + v[n / 2]) / 2;
}

// Round by round, `over`'s time divided by `under`'s (rounds where `under` has a time): the
// same-round ratios a ratio's median and range are read from.
std::vector<double> same_round_ratios(const std::vector<double>& over, const std::vector<double>& under)
{
    std::vector<double> r;
    for (std::size_t i = 0; i < over.size() && i < under.size(); ++i)
        if (under[i] > 0) r.push_back(over[i] / under[i]);
    return r;
}

// A case as rayq-bench-embree --answers_in reads it (its write_answers has the format).
std::string answer_input_line(const oracle::Input<Sphere<float>>& c)
{
    std::string line;
    for (const float v : {c.ray.origin.x, c.ray.origin.y, c.ray.origin.z, c.ray.direction.x, c.ray.direction.y,
                          c.ray.direction.z, c.ray.tmin, c.ray.tmax, c.prim.center.x, c.prim.center.y, c.prim.center.z,
                          c.prim.radius}) {
        char buf[48];
        std::snprintf(buf, sizeof buf, "%s%a", line.empty() ? "" : " ", double(v));  // %a writes inf as "inf"
        line += buf;
    }
    return line + "\n";
}

// One answer line ("miss" or "hit t Ng.x Ng.y Ng.z") as the hit record the oracle measures:
// Embree's geometric normal, normalized and turned to face the ray; it certifies nothing, so
// t_error and point_error are infinite (never a bound violation, never "bounded").
std::optional<Hit<float>> embree_hit(const std::string& line, const Ray<float>& ray)
{
    std::istringstream words(line);
    std::string word;
    words >> word;
    if (word == "miss") return std::nullopt;
    float v[4];  // t, Ng (hex floats: istream cannot read them)
    const bool hit = word == "hit";
    for (float& x : v) {
        char* end = nullptr;
        if (hit && words >> word) x = std::strtof(word.c_str(), &end);
        if (!end || *end) throw std::runtime_error("rayq-bench-embree: unexpected answer '" + line + "'");
    }
    constexpr float inf = std::numeric_limits<float>::infinity();
    const Vec3<float> ng{v[1], v[2], v[3]};
    const bool front = dot(ng, ray.direction) < 0;
    Hit<float> h;
    h.t = v[0];
    h.point = ray.origin + ray.direction * h.t;
    h.normal = normalize(front ? ng : ng * -1.0f);
    h.front_face = front;
    h.part = Part::surface;
    h.t_error = inf;
    h.point_error = {inf, inf, inf};
    return h;
}

// Embree's answers and rayq's three policies on the same cases, against the exact oracle.
json sphere_accuracy(const std::vector<oracle::Fixture>& cases, const std::vector<std::string>& answers)
{
    if (answers.size() != cases.size())
        throw std::runtime_error("rayq-bench-embree answered " + std::to_string(answers.size()) + " of " +
                                 std::to_string(cases.size()) + " cases");
    std::vector<std::pair<std::string, oracle::Tally>> variants = {{"embree_points", {}}};
    for (oracle::Policy p : oracle::all_policies) variants.push_back({oracle::policy_name(p), {}});
    for (std::size_t i = 0; i < cases.size(); ++i) {
        const auto& c = std::get<oracle::Input<Sphere<float>>>(cases[i].input);
        const oracle::Truth truth = oracle::truth_of(cases[i].input);
        variants[0].second.add(truth.measure(embree_hit(answers[i], c.ray)));
        const auto rayq_answers = oracle::measure_all_policies(truth, cases[i].input);
        for (std::size_t p = 0; p < rayq_answers.size(); ++p) variants[1 + p].second.add(rayq_answers[p]);
    }
    json rows = json::array();
    for (const auto& [variant, t] : variants) {
        // Quantiles as the oracle campaign reads them (bin upper edges): the Pareto plot puts
        // these next to its points.
        stats::LogHistogram ulps;
        for (double u : t.ulps) ulps.add(u);
        rows.push_back({{"variant", variant}, {"cases", t.cases}, {"hit_agree_pct", percent(t.hit_agree, t.cases)},
                        {"both_hit", t.both_hit}, {"front_agree_pct", percent(t.front_agree, t.both_hit)},
                        {"faithful_pct", percent(t.faithful, t.both_hit)}, {"median_ulp", ulps.quantile(0.5)},
                        {"p99_ulp", ulps.quantile(0.99)}, {"max_ulp", ulps.max()}});
    }
    return rows;
}

json run(const Settings& s, const Item& item, std::string& csv)
{
    const Program& program = program_named(item.id);
    const std::string binary = tools_binary(item.spec.at("binary").get<std::string>());
    if (!item.spec.at("built").get<bool>())
        return {{"program", item.id}, {"skipped", binary + " is not built (it needs " + program.needs + ")"}, {"rows", json::array()}};
    const std::filesystem::path out = temporary_path("bench.json");
    char min_time[64];
    std::snprintf(min_time, sizeof min_time, "--benchmark_min_time=%g", s.bench_min_time);
    std::vector<std::string> args = {binary, min_time, "--benchmark_format=json", "--benchmark_out_format=json", "--benchmark_out=" + out.string()};
    if (program.rounds == 0) {
        // Repetitions in random order across the program's benchmarks: on a shared machine whose
        // speed drifts for minutes at a time, five repetitions of `fast` followed by five of
        // `accurate` put the drift into their ratio (the same binary's float capped cylinder: 0.98,
        // 1.02 and 1.35 in three runs); interleaved, both medians sample the same stretch of time
        // (0.99, 1.05, 1.02).
        for (const char* a : {"--benchmark_repetitions=5", "--benchmark_enable_random_interleaving=true", "--benchmark_report_aggregates_only=true"})
            args.push_back(a);
    } else {
        args.push_back("--benchmark_repetitions=1");  // in registration order (Program::rounds)
        // Each round is a new process: without a warm-up, the first benchmark's first iteration
        // runs on cold caches and pages (Embree's one-sphere row, native, 0.01 s: 20 ms against 5).
        char warmup[64];
        std::snprintf(warmup, sizeof warmup, "--benchmark_min_warmup_time=%g", s.bench_min_time);
        args.push_back(warmup);
    }
    if (const std::string filter = item.spec.value("filter", ""); !filter.empty()) args.push_back("--benchmark_filter=" + filter);
    std::vector<oracle::Fixture> cases;
    const std::filesystem::path answers_in = temporary_path("answers.in"), answers_out = temporary_path("answers.out");
    std::vector<std::string> answer_args;
    if (item.spec.contains("sphere_cases")) {
        cases = oracle::generate_cases("sphere", oracle::Scalar::f32, item.spec.at("sphere_cases"), s.seed);
        std::string text;
        for (const oracle::Fixture& f : cases) text += answer_input_line(std::get<oracle::Input<Sphere<float>>>(f.input));
        std::ofstream(answers_in) << text;
        answer_args = {"--answers_in=" + answers_in.string(), "--answers_out=" + answers_out.string()};
    }
    // Per benchmark, in the order of the program's output: the median's JSON object (rounds == 0),
    // or each round's time and counters.
    std::vector<std::string> order;
    std::map<std::string, json> median_of;
    std::map<std::string, std::vector<double>> round_ns;
    std::map<std::string, std::map<std::string, std::vector<double>>> round_counters;
    std::map<std::string, std::string> unit_of;
    json context;
    const int runs = program.rounds == 0 ? 1 : program.rounds;
    for (int run = 0; run < runs; ++run) {
        std::vector<std::string> run_args = args;
        if (run == 0) run_args.insert(run_args.end(), answer_args.begin(), answer_args.end());  // answered once
        const int status = run_program(run_args, /*quiet=*/true);
        if (status != 0) throw std::runtime_error(binary + " exited with status " + std::to_string(status));
        std::ifstream in(out);
        const json j = json::parse(strict_json(std::string(std::istreambuf_iterator<char>(in), {})));
        in.close();
        std::filesystem::remove(out);
        if (run == 0) context = j.at("context");
        for (const json& b : j.at("benchmarks")) {
            const std::string name = b.at("run_name");
            if (program.rounds == 0 ? b.value("aggregate_name", "") != "median" : b.value("run_type", "iteration") != "iteration") continue;
            if (!unit_of.count(name)) order.push_back(name), unit_of[name] = b.at("time_unit");
            if (program.rounds == 0) {
                median_of[name] = b;
                continue;
            }
            round_ns[name].push_back(b.at("real_time").get<double>());
            for (const auto& [k, v] : b.items())
                if (v.is_number()) round_counters[name][k].push_back(v.get<double>());
        }
    }
    std::vector<std::string> answers;
    if (!cases.empty()) {
        std::ifstream answers_file(answers_out);
        for (std::string line; std::getline(answers_file, line);) answers.push_back(line);
        std::filesystem::remove(answers_in);
        std::filesystem::remove(answers_out);
    }
    const auto is_counter = [](const std::string& k) {
        return k != "real_time" && k != "cpu_time" && k != "iterations" && k != "repetitions" && k != "repetition_index" &&
               k != "threads" && k != "family_index" && k != "per_family_instance_index";
    };
    json rows = json::array();
    for (const std::string& name : order) {
        double ns = 0;
        json counters = json::object();
        json row = {{"name", name}, {"program", item.id}};
        if (program.rounds == 0) {
            const json& b = median_of.at(name);
            ns = b.at("real_time").get<double>();
            for (const auto& [k, v] : b.items())
                if (v.is_number() && is_counter(k)) counters[k] = v;
        } else {
            ns = median(round_ns.at(name));
            row["rounds"] = round_ns.at(name);
            for (const auto& [k, values] : round_counters.at(name))
                if (is_counter(k)) counters[k] = median(values);
        }
        row["ns"] = ns;
        row["time_unit"] = unit_of.at(name);
        row["counters"] = counters;
        csv += item.id + "," + name + "," + json(ns).dump() + "," + unit_of.at(name) + "\n";
        rows.push_back(row);
    }
    json result = {{"program", item.id}, {"binary", item.spec.at("binary")}, {"native", item.spec.value("native", false)},
                   {"context", context}, {"rows", rows}};
    if (!cases.empty()) result["sphere_accuracy"] = sphere_accuracy(cases, answers);
    return result;
}

// rayq-bench-embree names its benchmarks sphere/<variant>/<N>. Its section: M rays/s per variant
// and N with each rayq variant's speed over Embree's native spheres in the same run (metrics
// speed.embree.<variant>_over_points.<N>), the accuracy on the oracle's float sphere cases
// (speed.embree.accuracy.<variant>.<measure>), and the Pareto plot's like-for-like points.
const char* const embree_variants[] = {"embree_points", "rayq_embree_stable", "rayq_embree_accurate",
                                       "rayq_scene_fast", "rayq_scene_stable", "rayq_scene_accurate"};

json embree_section(const json& result, json& metrics, json& tables)
{
    std::map<int, std::map<std::string, double>> mrays;  // N -> variant -> M rays/s
    std::map<std::string, double> time_at_1;            // variant -> median time per batch of rays at N = 1
    for (const json& row : result.at("rows")) {
        const std::string name = row.at("name");
        const auto first = name.find('/'), last = name.rfind('/');
        if (name.compare(0, first, "sphere") != 0 || last == first) continue;
        const std::string variant = name.substr(first + 1, last - first - 1);
        const int n = std::atoi(name.c_str() + last + 1);
        if (const auto rate = row.at("counters").find("rays_per_second"); rate != row.at("counters").end() && rate->is_number())
            mrays[n][variant] = rate->get<double>() / 1e6;
        if (n == 1) time_at_1[variant] = row.at("ns");
    }
    json speed_rows = json::array();
    for (const auto& [n, by_variant] : mrays) {
        json row = {n};
        const auto points = by_variant.find("embree_points");
        for (const char* v : embree_variants) {
            const auto it = by_variant.find(v);
            row.push_back(it == by_variant.end() ? json(nullptr) : json(it->second));
            if (it == by_variant.end() || points == by_variant.end() || it == points || points->second <= 0) continue;
            metrics["speed.embree." + std::string(v) + "_over_points." + std::to_string(n)] = it->second / points->second;
        }
        for (const char* v : {"rayq_embree_stable", "rayq_scene_fast"}) {
            const auto it = by_variant.find(v);
            row.push_back(it == by_variant.end() || points == by_variant.end() || points->second <= 0 ? json(nullptr)
                                                                                                   : json(it->second / points->second));
        }
        speed_rows.push_back(row);
    }
    tables.push_back({{"title", "Embree (rayq-bench-embree): M rays/s, closest hit with hit record, one thread, same run"},
                      {"columns", {"spheres", "Embree points", "rayq in Embree (stable)", "rayq in Embree (accurate)",
                                   "Scene (fast)", "Scene (stable)", "Scene (accurate)", "rayq in Embree (stable) / Embree",
                                   "Scene (fast) / Embree"}},
                      {"rows", speed_rows}});

    // The accuracy rows; each variant's time at N = 1 relative to rayq fast's scalar loop (Embree's
    // includes its BVH traversal: the cost of a sphere as a renderer meets it).
    json accuracy_rows = json::array(), pareto = json::array();
    const auto fast_loop = time_at_1.find("rayq_loop_fast");
    for (const json& a : result.value("sphere_accuracy", json::array())) {
        const std::string variant = a.at("variant");
        const std::string m = "speed.embree.accuracy." + variant + ".";
        for (const char* k : {"hit_agree_pct", "p99_ulp", "max_ulp"}) metrics[m + k] = a.at(k);
        accuracy_rows.push_back({variant == "embree_points" ? "Embree points" : "rayq " + variant, a["cases"], a["hit_agree_pct"],
                                 a["front_agree_pct"], a["faithful_pct"], a["median_ulp"], a["p99_ulp"], a["max_ulp"]});
        const auto t = time_at_1.find(variant == "embree_points" ? variant : "rayq_loop_" + variant);
        if (t != time_at_1.end() && fast_loop != time_at_1.end() && fast_loop->second > 0)
            pareto.push_back({{"variant", variant}, {"time_over_fast", t->second / fast_loop->second}, {"p99_ulp", a.at("p99_ulp")}});
    }
    if (!accuracy_rows.empty())
        tables.push_back({{"title", "The same float sphere cases against the exact oracle: Embree's native sphere and rayq's "
                                    "policies (the oracle campaign's first cases, same seed)"},
                          {"columns", {"variant", "cases", "hit/miss agree %", "front agree %", "faithful %", "median ulp",
                                       "p99 ulp", "max ulp"}},
                          {"rows", accuracy_rows}});
    return {{"sphere_accuracy", result.value("sphere_accuracy", json::array())}, {"pareto", pareto}};
}

// Issue 7's targets, each read from one row of a targets_* program: its rays/s over a reference
// row's in the same round (Embree's native spheres or cone curves, or the closest-hit query on the
// same scene: any hit must cost less), or its primitive tests per second (items_per_second).
struct Target {
    const char* key;        // speed.targets.<key>; speed.target_margins.<key> = value / at_least
    const char* text;       // the target as the table states it
    const char* row;
    const char* reference;  // nullptr: the row's throughput in G tests/s
    double at_least;
};
const Target targets[] = {
    {"sphere_1_over_embree", "1 sphere: rayq's Scene (fast, point and normal) >= 5x Embree's rays/s", "sphere/rayq_scene_fast_shading/1",
     "sphere/embree_points/1", 5},
    {"sphere_16_over_embree", "16 spheres: >= 5x Embree", "sphere/rayq_scene_fast_shading/16", "sphere/embree_points/16", 5},
    {"capped_cylinder_1_over_embree", "1 capped cylinder: >= 5x Embree's cone curve", "cylinder/rayq_scene_fast_shading/1",
     "cylinder/embree_cone_curve/1", 5},
    {"capped_cylinder_16_over_embree", "16 capped cylinders: >= 5x Embree", "cylinder/rayq_scene_fast_shading/16",
     "cylinder/embree_cone_curve/16", 5},
    {"sphere_1000_over_embree", "1,000 spheres: a compile-time Scene at least matches Embree", "sphere/rayq_scene_fast_shading/1000",
     "sphere/embree_points/1000", 1},
    {"rayq_in_embree_stable_100000", "100,000 spheres: rayq in Embree (stable, full record) >= 0.7x Embree native",
     "sphere/rayq_embree_stable/100000", "sphere/embree_points/100000", 0.7},
    {"rayq_in_embree_accurate_100000", "100,000 spheres: rayq in Embree (accurate, full record) >= 0.7x Embree native",
     "sphere/rayq_embree_accurate/100000", "sphere/embree_points/100000", 0.7},
    {"sphere_float_fast_gtests", "float spheres, fast, closest hit, N = 1,024: >= 3 G tests/s", "closest/sphere/float/fast/scene/1024", nullptr, 3},
    {"sphere_double_fast_gtests", "double spheres, fast: >= 1.5 G tests/s", "closest/sphere/double/fast/scene/1024", nullptr, 1.5},
    {"capped_cylinder_float_stable_gtests", "float capped cylinders, stable: >= 0.8 G tests/s", "closest/cylinder/float/stable/scene/1024",
     nullptr, 0.8},
    {"cone_float_accurate_gtests", "float capped cones, accurate (stable has no batch filter): >= 0.8 G tests/s",
     "closest/cone/float/accurate/scene/1024", nullptr, 0.8},
    {"any_over_closest.sphere_float_fast", "any hit costs less than closest hit: float spheres, fast (closest's time / any's)",
     "any/sphere/float/fast/scene/1024", "closest/sphere/float/fast/scene/1024", 1},
    {"any_over_closest.sphere_double_fast", "... double spheres, fast", "any/sphere/double/fast/scene/1024",
     "closest/sphere/double/fast/scene/1024", 1},
    {"any_over_closest.capped_cylinder_float_stable", "... float capped cylinders, stable", "any/cylinder/float/stable/scene/1024",
     "closest/cylinder/float/stable/scene/1024", 1},
    {"any_over_closest.cone_float_accurate", "... float capped cones, accurate", "any/cone/float/accurate/scene/1024",
     "closest/cone/float/accurate/scene/1024", 1},
};

// The targets whose rows ran: value = the median of the same-round values, with their range; met
// when the median reaches the target. Reported, not gated (gates.txt): they were set for a CPU with
// AVX-512 (an AVX2 CPU's 8 float lanes do not reach 5x at 16 primitives) and move by 10-30% in a
// shared machine's slow phases; gate them on a known machine with speed.target_margins.* >= 1.
json targets_section(const std::vector<json>& results, json& metrics, json& tables, json& notes)
{
    std::map<std::string, const json*> row_of;
    std::map<std::string, bool> native_of;  // program -> built with -march=native
    std::string binaries;
    for (const json& r : results) {
        if (!program_named(r.at("program")).targets || r.contains("skipped")) continue;
        native_of[r.at("program")] = r.value("native", false);
        binaries += (binaries.empty() ? "" : ", ") + r.at("binary").get<std::string>();
        for (const json& row : r.at("rows")) row_of[row.at("name").get<std::string>()] = &row;
    }
    json out = json::array(), table = json::array();
    for (const Target& t : targets) {
        const auto row = row_of.find(t.row);
        const auto ref = t.reference ? row_of.find(t.reference) : row_of.end();
        if (row == row_of.end() || (t.reference && ref == row_of.end())) continue;
        std::vector<double> values;
        if (t.reference) {  // the same rays per iteration: the reference's time over the row's is rays/s over rays/s
            values = same_round_ratios(ref->second->at("rounds").get<std::vector<double>>(), row->second->at("rounds").get<std::vector<double>>());
        } else if (const auto rate = row->second->at("counters").find("items_per_second"); rate != row->second->at("counters").end()) {
            // Each round's rate from its time (the same tests per iteration every round): the
            // counter holds the median of the rounds' rates, which belongs to the median time.
            const double ns = row->second->at("ns");
            for (const double t : row->second->at("rounds").get<std::vector<double>>())
                if (t > 0) values.push_back(rate->get<double>() / 1e9 * ns / t);
        }
        if (values.empty()) continue;
        const double value = median(values);
        const auto [lo, hi] = std::minmax_element(values.begin(), values.end());
        const bool met = value >= t.at_least;
        const bool native = native_of.at(row->second->at("program"));
        metrics["speed.targets." + std::string(t.key)] = value;
        metrics["speed.target_margins." + std::string(t.key)] = value / t.at_least;
        out.push_back({{"key", t.key}, {"target", t.text}, {"at_least", t.at_least}, {"value", value}, {"min", *lo}, {"max", *hi},
                       {"met", met}, {"native", native}});
        table.push_back({t.text, value, *lo, *hi, t.at_least, met ? "yes" : "no", native ? "-march=native" : "portable"});
    }
    if (!table.empty())
        tables.push_back({{"title", "Issue-7 targets (" + binaries + "; medians of 5 rounds' values, each round's ratio from the same "
                                    "round; reported, not gated)"},
                          {"columns", {"target", "measured", "min", "max", "at least", "met", "rayq built"}},
                          {"rows", table}});
    for (const auto& [program, native] : native_of)
        if (!native)
            notes.push_back({{"title", note_title(program_named(program), "portable build")},
                             {"text", "The issue-7 targets were measured with the portable build of rayq (no -march=native: SSE2 on "
                                      "x86-64), while Embree runs its widest ISA. The targets were set for -march=native builds: "
                                      "tools/report.sh builds those copies (cmake --build <dir> --target rayq-bench-native).\n"}});
    return out;
}

// rayq-bench names its benchmarks intersect/<primitive>/<type>/<policy>; time is per batch of rays,
// so ratios between policies of the same primitive and type are what we report.
json reduce(const Settings&, const std::vector<json>& results)
{
    json metrics = json::object(), rows = json::array(), notes = json::array(), skipped_metrics = json::array();
    std::map<std::string, double> ns;  // run_name -> median
    std::map<std::string, std::vector<double>> rounds;  // run_name -> time per round (Program::rounds)
    for (const json& r : results)
        for (const json& row : r.at("rows")) {
            rows.push_back(row);
            if (program_named(r.at("program")).targets) continue;  // the same names as other programs' rows: read apart
            ns[row.at("name").get<std::string>()] = row.at("ns").get<double>();
            if (row.contains("rounds")) rounds[row.at("name").get<std::string>()] = row.at("rounds").get<std::vector<double>>();
        }
    // other's time over base's: the median of their same-round ratios when both ran in rounds,
    // else the ratio of their medians (from the same run).
    const auto ratio_of = [&](const std::string& other, const std::string& base) {
        const auto a = rounds.find(other), b = rounds.find(base);
        if (a == rounds.end() || b == rounds.end() || a->second.size() != b->second.size() || a->second.empty())
            return ns.at(other) / ns.at(base);
        return median(same_round_ratios(a->second, b->second));
    };
    json ratios = json::array();
    for (const auto& [name, t] : ns) {
        const auto slash = name.rfind('/');
        if (name.compare(0, 10, "intersect/") != 0 || name.substr(slash + 1) != "fast") continue;
        const std::string stem = name.substr(0, slash);
        for (const char* policy : {"stable", "accurate"}) {
            const auto other = ns.find(stem + "/" + policy);
            if (other == ns.end() || t <= 0) continue;
            const std::string variant = stem.substr(10);  // "<primitive>/<type>"
            const double ratio = ratio_of(other->first, name);
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
    json embree_tables = json::array(), embree = nullptr;
    for (const json& r : results) {
        const Program& program = program_named(r.at("program"));
        if (r.contains("skipped")) {
            for (const std::string& prefix : program.metrics) skipped_metrics.push_back({{"prefix", prefix}, {"reason", r.at("skipped")}});
            notes.push_back({{"title", note_title(program, "skipped")}, {"text", r.at("skipped").get<std::string>() + "\n"}});
        } else if (program.sphere_answers) {
            embree = embree_section(r, metrics, embree_tables);
        }
    }
    json targets_tables = json::array();
    const json target_rows = targets_section(results, metrics, targets_tables, notes);
    json bench_table = json::array(), ratio_table = json::array();
    for (const json& r : rows) bench_table.push_back({r["program"], r["name"], r["ns"], r["time_unit"], r["counters"].dump()});
    for (const json& r : ratios) ratio_table.push_back({r["variant"], r["policy"], r["over_fast"]});
    json tables = json::array(
        {{{"title", "Cost relative to fast (median of 5 rounds' ratios: each round runs the three policies back to back)"},
          {"columns", {"primitive/type", "policy", "time / fast"}},
          {"rows", ratio_table}},
         {{"title", "One ray against N primitives: speed-up over the scalar loop (same run)"},
          {"columns", {"query/primitive/type/policy", "N", "Scene<...>", "std::variant"}},
          {"rows", scene_table}},
         {{"title", "Benchmarks (median of 5 repetitions or of 5 rounds)"}, {"columns", {"program", "benchmark", "median time", "unit", "counters"}},
          {"rows", bench_table}}});
    tables.insert(tables.begin() + 2, embree_tables.begin(), embree_tables.end());
    tables.insert(tables.begin(), targets_tables.begin(), targets_tables.end());
    return {{"metrics", metrics}, {"rows", rows}, {"ratios", ratios}, {"embree", embree}, {"targets", target_rows}, {"tables", tables},
            {"notes", notes}, {"skipped_metrics", skipped_metrics}};
}

// Run time against error. One point per (policy, type): x = median over primitives of the time per
// ray relative to fast (rayq-bench), y = the oracle campaign's worst p99 ulp error of that policy
// and type. And, like for like, float spheres only: Embree's native sphere and rayq's policies on
// the same cases (rayq-bench-embree: time at N = 1 relative to rayq fast's scalar loop, p99 ulp
// error against the exact oracle).
std::vector<Plot> plots(const json& sections)
{
    const json& speed = sections.at("speed");
    Plot p;
    p.name = "speed_vs_error";
    p.title = "Run time against error: cost relative to fast (same run) vs p99 ulp error from the exact oracle";
    std::string data;
    if (sections.contains("oracle")) {
        std::map<std::string, std::vector<double>> cost;  // "policy/type" -> ratios over primitives
        for (const json& r : speed.at("ratios")) {
            const std::string variant = r.at("variant");
            const std::string type = variant.substr(variant.find('/') + 1);
            cost[r.at("policy").get<std::string>() + "/" + type].push_back(r.at("over_fast"));
        }
        for (const char* type : {"float", "double"}) cost[std::string("fast/") + type].push_back(1.0);
        std::map<std::string, double> p99;  // worst over primitives
        for (const json& row : sections.at("oracle").at("rows")) {
            const std::string k = row.at("policy").get<std::string>() + "/" + row.at("type").get<std::string>();
            p99[k] = std::max(p99[k], row.at("p99_ulp").get<double>());
        }
        for (auto& [k, v] : cost) {
            if (!p99.count(k)) continue;
            std::sort(v.begin(), v.end());
            char line[128];
            std::snprintf(line, sizeof line, "%.6g %.6g \"%s\"\n", v[v.size() / 2], std::max(p99[k], 1e-3), k.c_str());
            data += line;
        }
    }
    // The like-for-like points each get a key entry rather than a label: they lie close together.
    std::string spheres, sphere_plots;
    if (speed.at("embree").is_object()) {
        const int point_types[] = {6, 4, 8, 12};  // open circle, square, triangle, diamond
        int k = 0;
        for (const json& q : speed.at("embree").at("pareto")) {
            const std::string variant = q.at("variant");
            char line[128];
            std::snprintf(line, sizeof line, "%.6g %.6g\n", q.at("time_over_fast").get<double>(), std::max(q.at("p99_ulp").get<double>(), 1e-3));
            spheres += line;
            sphere_plots += ", '<dir>/speed_vs_error_spheres.dat' every ::" + std::to_string(k) + "::" + std::to_string(k) +
                            " using 1:2 with points ps 1.5 lt " + std::to_string(2 + k) + " pt " + std::to_string(point_types[k % 4]) + " title '" +
                            (variant == "embree_points" ? "Embree" : variant) + ", float spheres'";
            ++k;
        }
    }
    if (data.empty() && spheres.empty()) return {};
    p.script = "set logscale y\nset xlabel 'time per ray relative to fast (rayq: median over primitives; "
               "float spheres: at N = 1, over the fast scalar loop)'\nset ylabel 'p99 ulp error of t'\nset grid\n"
               "set offsets 0.3, 0.6, 0, 0\nset key outside right top\nplot ";
    if (!data.empty()) {
        p.data.emplace_back("speed_vs_error.dat", data);
        p.script += "'<dir>/speed_vs_error.dat' using 1:2 with points pt 7 ps 1.5 lt 1 title 'rayq: worst over primitives', "
                    "'' using 1:2:3 with labels offset 0,1 notitle";
    }
    if (!spheres.empty()) {
        p.data.emplace_back("speed_vs_error_spheres.dat", spheres);
        p.script += data.empty() ? sphere_plots.substr(2) : sphere_plots;
    }
    p.script += "\n";
    return {p};
}

}  // namespace

Campaign speed_campaign()
{
    Campaign c;
    c.name = "speed";
    c.title = "Speed (Google Benchmark, medians of 5 repetitions or rounds, ratios from the same run)";
    c.deterministic = false;
    c.plan = plan;
    c.run = run;
    c.csv_header = "program,benchmark,median_time,time_unit";
    c.reduce = reduce;
    c.plots = plots;
    return c;
}

}  // namespace rayq::report
