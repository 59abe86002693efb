// rayq-fuzz — fuzz rayq's edge cases for a given time or number of runs, without libFuzzer
// (issue 9). Random byte strings go through the same structured decoder and invariants as the
// libFuzzer harnesses (validation/fuzz/include/rayq/fuzz); each violation is printed as a
// ready-to-paste fixture line (fixtures/README.md) with the input's bytes in hex.
//
//   rayq-fuzz --harness sphere --seconds 60          fuzz one family for a minute
//   rayq-fuzz --harness all --runs 100000 --seed 7  a fixed number of cases per family
//   rayq-fuzz --harness flat --replay FILE...        check stored inputs (e.g. libFuzzer crashes)
//   rayq-fuzz --harness axial --write-seeds DIR      write a small covering seed corpus (one passing
//                                                    input per number type, primitive and construction)
// --report-known also reports the known open issues (validation/fuzz/include/rayq/fuzz/
// known_issues.hpp); --strict, in addition, runs rayq::accurate where it is known to hang. Exit status: 0 nothing found, 1 findings,
// 2 bad usage.
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>
#include <set>
#include <string>
#include <vector>

#include "fuzz_driver.hpp"

namespace {

using namespace rayq::fuzz;

int usage(const char* why)
{
    std::fprintf(stderr,
                 "rayq-fuzz: %s\nusage: rayq-fuzz --harness flat|sphere|axial|quadric|transformed|all\n"
                 "                 [--seconds S | --runs N] [--seed S] [--max-findings N] [--report-known | --strict]\n"
                 "                 [--replay FILE... | --write-seeds DIR]\n",
                 why);
    return 2;
}

struct Run {
    Options options;
    std::size_t cases = 0, findings = 0, hits = 0;
};

// Checks one input; prints a finding. Returns whether it passed; `key` names its kind
// (primitive-type-construction).
bool run_one(Harness h, const std::vector<std::uint8_t>& bytes, Run& run, std::string* key = nullptr)
{
    const InputCheck c = check_input(h, bytes, run.options);
    ++run.cases;
    run.hits += std::size_t(c.checked.hits);
    if (key) {  // the fixture line's primitive and type words
        const std::size_t from = c.line.find(' ') + 1, to = c.line.find(' ', c.line.find(' ', from) + 1);
        *key = c.line.substr(from, to - from) + "-" + c.construction;
        for (char& ch : *key)
            if (ch == ' ') ch = '-';
    }
    if (c.checked.violations.empty()) return true;
    ++run.findings;
    std::fputs(finding_text(h, bytes, c).c_str(), stdout);
    std::fflush(stdout);
    return false;
}

}  // namespace

int main(int argc, char** argv)
{
    std::vector<Harness> harnesses;
    double seconds = 0;
    std::size_t runs = 0, max_findings = 20;
    std::uint64_t seed = 1;
    bool strict = false, report_known = false;
    std::vector<std::string> replay;
    std::string seeds_dir;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        const auto value = [&]() -> std::string { return i + 1 < argc ? argv[++i] : ""; };
        if (a == "--harness") {
            const std::string v = value();
            for (Harness h : all_harnesses)
                if (v == "all" || v == harness_name(h)) harnesses.push_back(h);
            if (harnesses.empty()) return usage(("unknown harness '" + v + "'").c_str());
        } else if (a == "--seconds") seconds = std::atof(value().c_str());
        else if (a == "--runs") runs = std::strtoull(value().c_str(), nullptr, 10);
        else if (a == "--seed") seed = std::strtoull(value().c_str(), nullptr, 10);
        else if (a == "--max-findings") max_findings = std::strtoull(value().c_str(), nullptr, 10);
        else if (a == "--strict") strict = true;
        else if (a == "--report-known") report_known = true;
        else if (a == "--write-seeds") seeds_dir = value();
        else if (a == "--replay") {
            while (i + 1 < argc && std::strncmp(argv[i + 1], "--", 2) != 0) replay.push_back(argv[++i]);
        } else if (a == "--help" || a == "-h") {
            usage("help");
            return 0;
        } else return usage(("unknown option '" + a + "'").c_str());
    }
    if (harnesses.empty()) return usage("--harness is required");
    if (seconds <= 0 && runs == 0 && replay.empty() && seeds_dir.empty()) runs = 10000;

    Run run;
    if (strict) run.options.skip_known = run.options.skip_known_hangs = false;
    if (report_known) run.options.skip_known = false;

    if (!replay.empty()) {
        for (const auto& file : replay) {
            std::ifstream in(file, std::ios::binary);
            if (!in) return usage(("cannot read '" + file + "'").c_str());
            const std::vector<std::uint8_t> bytes{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
            for (Harness h : harnesses) run_one(h, bytes, run);
        }
        std::printf("rayq-fuzz: replayed %zu input(s), %zu finding(s)\n", replay.size(), run.findings);
        return run.findings ? 1 : 0;
    }

    std::mt19937_64 rng(seed);
    const auto random_bytes = [&] { return random_input(rng); };

    if (!seeds_dir.empty()) {
        // One passing input per (primitive, number type, construction), at most 40 per family, from a
        // bounded search: small corpora that reach every construction.
        for (Harness h : harnesses) {
            const auto dir = std::filesystem::path(seeds_dir) / harness_name(h);
            std::filesystem::create_directories(dir);
            std::set<std::string> seen;
            for (int i = 0; i < 4000 && seen.size() < 40; ++i) {
                const auto bytes = random_bytes();
                std::string key;
                if (!run_one(h, bytes, run, &key) || !seen.insert(key).second) continue;
                std::ofstream(dir / ("seed-" + key), std::ios::binary).write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
            }
            std::printf("rayq-fuzz: %s: %zu seeds in %s\n", harness_name(h), seen.size(), dir.string().c_str());
        }
        return run.findings ? 1 : 0;
    }

    for (Harness h : harnesses) {
        const auto start = std::chrono::steady_clock::now();
        const std::size_t before = run.cases, findings_before = run.findings;
        for (std::size_t i = 0;; ++i) {
            if (runs && i >= runs) break;
            if (seconds > 0 && std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() >= seconds) break;
            if (run.findings - findings_before >= max_findings) break;
            run_one(h, random_bytes(), run);
        }
        const double took = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        std::printf("rayq-fuzz: %s: %zu cases in %.1f s (%.0f/s), %zu finding(s)\n", harness_name(h), run.cases - before, took,
                    double(run.cases - before) / std::max(took, 1e-9), run.findings - findings_before);
    }
    return run.findings ? 1 : 0;
}
