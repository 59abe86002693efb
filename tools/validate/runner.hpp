// rayq-validate — running campaigns (whole or one shard), merging partial results, and building
// the summary (issue 8).
#pragma once

#include <filesystem>
#include <set>
#include <string>
#include <vector>

#include "campaign.hpp"
#include "partial.hpp"

namespace rayq::report {

struct RunOptions {
    Settings settings;
    std::set<std::string> selected;  // campaign names to run; the others are reported as skipped
    int shard = 0, shards = 1;       // this run does the items i with i mod shards == shard
    std::filesystem::path out;       // item results go to out/items/, the partial summary to out/partial.json
    bool resume = true;              // reuse item results already in out/items/ (made with the same settings)
};

// Runs this shard's items of the selected campaigns and writes out/partial.json (atomically).
// Progress goes to stderr. Returns the partial summary.
json run_shard(const RunOptions& options);

// Combines partial summaries (each with the directory it was written in, for the raw CSV) into
// the summary: every campaign's section reduced from the union of item results. Throws
// std::runtime_error when the partials disagree on settings or on an item's result.
json merge(const std::vector<Partial>& partials, const std::filesystem::path& out);

// Reads <dir>/partial.json (parse_partial) with a clear error naming the file.
Partial read_partial(const std::filesystem::path& dir);

// Writes text to path through a temporary file and a rename: never a half-written file.
void write_file_atomically(const std::filesystem::path& path, const std::string& text);

}  // namespace rayq::report
