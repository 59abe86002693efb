// rayq-validate — the campaign model (issue 8). A campaign is planned as a deterministic list of
// work items; each item is a pure function of (settings, item) and its result is JSON. Shards run
// disjoint subsets of items (item i goes to shard i mod n); merging is the union of item results;
// a campaign's section of the summary is reduced from all its item results taken in plan order.
// So one run and any set of merged shards give the same summary, and a resumed run can reuse
// finished items.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace rayq::report {

using json = nlohmann::json;

// Everything that determines the results (part of every partial summary: merging refuses
// partials made with different settings).
struct Settings {
    std::string preset = "default";   // quick | default | full
    std::uint64_t seed = 1;
    std::size_t oracle_cases = 0;     // generated cases per primitive and number type
    std::size_t oracle_chunk = 0;     // cases per work item
    std::size_t oracle_csv_cases = 0; // per-case CSV rows for the first this many cases of each primitive and type
    std::vector<std::string> oracle_primitives;  // empty: every primitive the generator knows
    int mesh_rays = 0;
    int mesh_max_n = 0;
    std::string precision_preset;     // the precision sweeps' own preset name
    double bench_min_time = 0;        // seconds per benchmark (Google Benchmark --benchmark_min_time)
    std::string fixtures_dir;         // curated oracle fixtures measured too ("" = none)
    std::size_t fuzz_cases = 0;       // generated fuzz inputs per harness
    std::size_t fuzz_chunk = 0;       // inputs per work item
    std::string fuzz_corpus_dir;      // stored fuzz inputs replayed too: <dir>/<harness>, <dir>/open/<harness> ("" = none)

    static Settings preset_named(const std::string& name);  // throws std::invalid_argument
    json to_json() const;
    static Settings from_json(const json& j);
};

struct Item {
    std::string id;  // unique within the campaign, e.g. "sphere/double/003"
    json spec;       // what run() needs
};

// A table row for the page; the summary carries tables too, so a merged report can be rendered
// without the items.
struct Plot {
    std::string name;     // file stem: plots/<name>.svg
    std::string title;
    std::string script;   // gnuplot commands; data files referenced as "<dir>/<file>"
    std::vector<std::pair<std::string, std::string>> data;  // (file name, contents)
};

struct Campaign {
    std::string name;   // "oracle", "mesh", ...
    std::string title;
    bool deterministic = true;  // false: timings (excluded from shard/merge identity)
    std::function<std::vector<Item>(const Settings&)> plan;
    // The result of one item. `csv` receives raw per-case rows (header written by the caller
    // once, from csv_header).
    std::function<json(const Settings&, const Item&, std::string& csv)> run;
    std::string csv_header;
    // The campaign's summary section from every item's result, in plan order. Must contain
    // "metrics": a flat object of numbers that gates refer to, and "tables"; may contain "notes"
    // (titled preformatted text for the page) and "skipped_metrics" (metric name prefixes whose
    // producer did not run, e.g. a benchmark program that is not built: gates on them are skipped).
    std::function<json(const Settings&, const std::vector<json>&)> reduce;
    // Plots drawn from the reduced sections of every campaign that ran (keyed by name; this
    // campaign's own is always there): run time against error needs the oracle's errors.
    std::function<std::vector<Plot>(const json& sections)> plots;
};

const std::vector<Campaign>& all_campaigns();

// Shared by the campaigns: a percentage with no division by zero (100 when there is nothing).
double percent(std::uint64_t part, std::uint64_t whole);

}  // namespace rayq::report
