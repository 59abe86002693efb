// rayq-validate — rayq's main job (issue 8): runs the validation campaigns and writes a
// self-contained HTML report, a JSON summary and the raw data; exits non-zero when a gate fails.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <fstream>
#include <iostream>
#include <set>
#include <sys/utsname.h>
#include <thread>
#include <unistd.h>

#include <rayq/oracle/fixtures.hpp>

#include "gates.hpp"
#include "report.hpp"
#include "runner.hpp"

using namespace rayq::report;

namespace {

const char* usage =
    "usage: rayq-validate [--quick | --full | --preset NAME] [options]        run, then write the report\n"
    "       rayq-validate --shard I/N [options]                             run one shard (partial results only)\n"
    "       rayq-validate merge --out DIR [--gates FILE] SHARD_DIR...        report from shards' partial results\n"
    "       rayq-validate --list                                            list the campaigns\n"
    "options:\n"
    "  --quick | --full | --preset quick|default|full   sizes (default: about 10 minutes on 2 cores)\n"
    "  --seed S              seed of every generated case (default 1); same seed, same results\n"
    "  --only C / --skip C   run only / skip campaign C (repeatable; see --list)\n"
    "  --oracle-cases N      generated oracle cases per primitive and number type\n"
    "  --primitive P         oracle campaign on these primitives only (repeatable; default all)\n"
    "  --mesh-rays N --mesh-max-n N   mesh cross-check size\n"
    "  --fuzz-cases N        generated fuzz inputs per harness\n"
    "  --bench-min-time S    seconds per benchmark repetition\n"
    "  --fixtures DIR        curated oracle fixture files measured too (default: the checked-in ones)\n"
    "  --fuzz-corpus DIR     stored fuzz inputs replayed too: DIR/<harness>, DIR/open/<harness>\n"
    "                        (default: the checked-in fixtures/fuzz)\n"
    "  --no-fixtures         generated cases only: no curated oracle fixtures, no stored fuzz inputs\n"
    "  --out DIR             output directory (default rayq-report)\n"
    "  --gates FILE          gates file (default: the checked-in tools/validate/gates.txt)\n"
    "  --fresh               do not reuse finished work items from an interrupted run in DIR\n"
    "exit status: 0 all gates pass, 1 a gate failed, 2 bad usage or input, 3 a run-time failure\n";

struct UsageError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

std::string cpu_model()
{
    std::ifstream in("/proc/cpuinfo");
    for (std::string line; std::getline(in, line);)
        if (line.rfind("model name", 0) == 0) return line.substr(line.find(':') + 2);
    return "unknown";
}

json environment(int argc, char** argv)
{
    std::string command;
    for (int i = 0; i < argc; ++i) command += (i ? " " : "") + std::string(argv[i]);
    utsname u{};
    uname(&u);
    char date[64];
    const std::time_t now = std::time(nullptr);
    std::strftime(date, sizeof date, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&now));
    char cwd[4096] = "";
    if (!getcwd(cwd, sizeof cwd)) cwd[0] = 0;
    return {{"command", command}, {"working_directory", cwd}, {"date", date},
            {"compiler", RAYQ_COMPILER}, {"flags", RAYQ_CXX_FLAGS}, {"build_type", RAYQ_BUILD_TYPE},
            {"git_commit", RAYQ_GIT_COMMIT}, {"cpu", cpu_model()},
            {"hardware_threads", std::thread::hardware_concurrency()},
            {"system", std::string(u.sysname) + " " + u.release + " " + u.machine}, {"host", u.nodename}};
}

std::string need(int& i, int argc, char** argv)
{
    if (i + 1 >= argc) throw UsageError(std::string(argv[i]) + " needs a value");
    return argv[++i];
}

std::uint64_t number(const std::string& option, const std::string& v)
{
    std::size_t used = 0;
    unsigned long long n = 0;
    try {
        n = std::stoull(v, &used);
    } catch (const std::exception&) {
        used = 0;
    }
    if (used != v.size() || v.empty() || v[0] == '-') throw UsageError(option + ": expected a non-negative integer, got '" + v + "'");
    return n;
}

// The report for a set of partial results, with gates; returns the exit status.
int finish(const std::vector<Partial>& partials, const std::filesystem::path& out, const std::string& gates_file,
           const json& run_info)
{
    const std::vector<Gate> gates = load_gates(gates_file);  // before any work: a bad gates file is a usage error
    json summary = merge(partials, out);
    summary["gates"] = evaluate_gates(gates, summary.at("campaigns"), gates_file);
    summary["run"] = run_info;
    const int plots = write_report(summary, out);
    // summary.json last: its presence says the report is complete.
    write_file_atomically(out / "summary.json", summary.dump(1));
    const json& g = summary.at("gates");
    std::fprintf(stderr, "rayq-validate: %d gates passed, %d failed, %d skipped; %d plots; report %s\n",
                 g.at("passed").get<int>(), g.at("failed").get<int>(), g.at("skipped").get<int>(), plots,
                 (out / "index.html").c_str());
    for (const json& r : g.at("results"))
        if (r.at("status") == "fail") std::fprintf(stderr, "  FAIL %s %s %g\n", r.at("metric").get<std::string>().c_str(),
                                                  r.at("op").get<std::string>().c_str(), r.at("threshold").get<double>());
    return g.at("failed").get<int>() ? 1 : 0;
}

int main_throwing(int argc, char** argv)
{
    const auto start = std::chrono::steady_clock::now();
    std::string preset = "default", gates_file = RAYQ_DEFAULT_GATES, out = "rayq-report";
    std::string fixtures = RAYQ_DEFAULT_FIXTURES, fuzz_corpus = RAYQ_DEFAULT_FUZZ_CORPUS;
    std::set<std::string> only, skip;
    std::vector<std::string> primitives;
    std::vector<std::pair<std::string, std::string>> overrides;
    int shard = 0, shards = 1;
    bool sharded = false, fresh = false, merging = false;
    std::vector<std::string> shard_dirs;

    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        if (a == "merge" && i == 1) merging = true;
        else if (a == "--help" || a == "-h") { std::fputs(usage, stdout); return 0; }
        else if (a == "--list") {
            for (const Campaign& c : all_campaigns()) std::printf("%-10s %s\n", c.name.c_str(), c.title.c_str());
            return 0;
        }
        else if (a == "--quick") preset = "quick";
        else if (a == "--full") preset = "full";
        else if (a == "--preset") preset = need(i, argc, argv);
        else if (a == "--out") out = need(i, argc, argv);
        else if (a == "--gates") gates_file = need(i, argc, argv);
        else if (a == "--fixtures") fixtures = need(i, argc, argv);
        else if (a == "--fuzz-corpus") fuzz_corpus = need(i, argc, argv);
        else if (a == "--no-fixtures") { fixtures.clear(); fuzz_corpus.clear(); }
        else if (a == "--fresh") fresh = true;
        else if (a == "--only") only.insert(need(i, argc, argv));
        else if (a == "--primitive") primitives.push_back(need(i, argc, argv));
        else if (a == "--skip") skip.insert(need(i, argc, argv));
        else if (a == "--seed" || a == "--oracle-cases" || a == "--mesh-rays" || a == "--mesh-max-n" || a == "--bench-min-time" ||
                 a == "--fuzz-cases")
            overrides.emplace_back(a, need(i, argc, argv));
        else if (a == "--shard") {
            const std::string v = need(i, argc, argv);
            const auto slash = v.find('/');
            if (slash == std::string::npos) throw UsageError("--shard: expected I/N, got '" + v + "'");
            shard = static_cast<int>(number("--shard", v.substr(0, slash)));
            shards = static_cast<int>(number("--shard", v.substr(slash + 1)));
            if (shards < 1 || shard >= shards) throw UsageError("--shard: expected 0 <= I < N, got '" + v + "'");
            sharded = true;
        }
        else if (merging && a[0] != '-') shard_dirs.push_back(a);
        else throw UsageError("unknown option '" + a + "'");
    }
    for (const auto& name : only)
        if (std::none_of(all_campaigns().begin(), all_campaigns().end(), [&](const Campaign& c) { return c.name == name; }))
            throw UsageError("--only: no campaign named '" + name + "' (see --list)");
    for (const auto& name : skip)
        if (std::none_of(all_campaigns().begin(), all_campaigns().end(), [&](const Campaign& c) { return c.name == name; }))
            throw UsageError("--skip: no campaign named '" + name + "' (see --list)");

    const json run_info_base = environment(argc, argv);
    try {
        load_gates(gates_file);
    } catch (const std::runtime_error& e) {
        throw UsageError(e.what());
    }

    std::error_code ec;
    std::filesystem::create_directories(out, ec);
    if (ec || access(out.c_str(), W_OK) != 0)
        throw UsageError("cannot write the output directory '" + out + "'" + (ec ? ": " + ec.message() : ""));

    if (merging) {
        if (shard_dirs.empty()) throw UsageError("merge: name the shard directories to merge");
        std::vector<Partial> partials;
        for (const auto& d : shard_dirs) {
            try {
                partials.push_back(read_partial(d));
            } catch (const std::runtime_error& e) {
                throw UsageError(e.what());
            }
        }
        std::filesystem::remove(std::filesystem::path(out) / "summary.json");
        std::filesystem::remove(std::filesystem::path(out) / "index.html");
        json run_info = run_info_base;
        run_info["merged_from"] = shard_dirs;
        return finish(partials, out, gates_file, run_info);
    }

    RunOptions o;
    try {
        o.settings = Settings::preset_named(preset);
    } catch (const std::invalid_argument& e) {
        throw UsageError(e.what());
    }
    o.settings.fixtures_dir = fixtures;
    if (!fuzz_corpus.empty() && !std::filesystem::is_directory(fuzz_corpus))
        throw UsageError("--fuzz-corpus: '" + fuzz_corpus + "' is not a readable directory");
    o.settings.fuzz_corpus_dir = fuzz_corpus;
    for (const auto& p : primitives)
        if (std::find(rayq::oracle::generated_primitives().begin(), rayq::oracle::generated_primitives().end(), p) ==
            rayq::oracle::generated_primitives().end())
            throw UsageError("--primitive: no primitive named '" + p + "' (sphere, plane, disk, parallelogram, triangle, cylinder, cone, quadric, transformed-…)");
    o.settings.oracle_primitives = primitives;
    if (!fixtures.empty()) {
        if (!std::filesystem::is_directory(fixtures))
            throw UsageError("--fixtures: '" + fixtures + "' is not a readable directory");
        try {
            rayq::oracle::load_fixture_directory(fixtures);  // a malformed line stops us before any work
        } catch (const std::runtime_error& e) {
            throw UsageError(e.what());
        }
    }
    for (const auto& [k, v] : overrides) {
        if (k == "--seed") o.settings.seed = number(k, v);
        else if (k == "--oracle-cases") {
            o.settings.oracle_cases = number(k, v);
            o.settings.oracle_chunk = std::max<std::size_t>(1, std::min<std::size_t>(o.settings.oracle_chunk, o.settings.oracle_cases));
        }
        else if (k == "--mesh-rays") o.settings.mesh_rays = static_cast<int>(number(k, v));
        else if (k == "--mesh-max-n") o.settings.mesh_max_n = static_cast<int>(number(k, v));
        else if (k == "--fuzz-cases") {
            o.settings.fuzz_cases = number(k, v);
            o.settings.fuzz_chunk = std::max<std::size_t>(1, std::min<std::size_t>(o.settings.fuzz_chunk, o.settings.fuzz_cases));
        }
        else {
            char* end = nullptr;
            o.settings.bench_min_time = std::strtod(v.c_str(), &end);
            if (*end || !(o.settings.bench_min_time > 0)) throw UsageError(k + ": expected a positive number of seconds");
        }
    }
    for (const Campaign& c : all_campaigns())
        if ((only.empty() || only.count(c.name)) && !skip.count(c.name)) o.selected.insert(c.name);
    o.shard = shard;
    o.shards = shards;
    o.out = out;
    o.resume = !fresh;
    // An interrupted run must not leave an older, complete-looking report behind.
    std::filesystem::remove(o.out / "summary.json");
    std::filesystem::remove(o.out / "index.html");
    std::filesystem::remove(o.out / "partial.json");
    if (fresh) std::filesystem::remove_all(o.out / "items");

    const json partial = run_shard(o);
    if (sharded) {
        std::fprintf(stderr, "rayq-validate: shard %d/%d written to %s/partial.json; combine with: rayq-validate merge --out DIR SHARD_DIR...\n",
                     shard, shards, out.c_str());
        return 0;
    }
    json run_info = run_info_base;
    run_info["wall_seconds"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return finish({Partial{partial, out}}, out, gates_file, run_info);
}

}  // namespace

int main(int argc, char** argv)
{
    try {
        return main_throwing(argc, argv);
    } catch (const UsageError& e) {
        std::fprintf(stderr, "rayq-validate: %s\n%s", e.what(), usage);
        return 2;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "rayq-validate: %s\n", e.what());
        return 3;
    }
}
