// rayq-validate — the partial summary (partial.json): what one run or shard writes and `merge`
// reads back. Parsing checks the whole structure merge relies on, so that a malformed or foreign
// file is rejected up front with its name and what was expected (fuzzed: tools/fuzz/parsers_fuzz_target.cpp).
#pragma once

#include <filesystem>
#include <string>

#include "campaign.hpp"

namespace rayq::report {

// The version of partial.json and summary.json (summary.schema.json): bumped when a field's
// meaning changes or settings gain a field, so results of another version are never merged.
constexpr int format_version = 2;

struct Partial {
    json summary;
    std::filesystem::path dir;
};

// Parses the text of a partial summary. Throws std::runtime_error "<file>: …" naming what was
// expected (JSON syntax errors carry the line and column) when the text is not valid UTF-8 JSON,
// is not a rayq-validate partial of this version, or lacks or mistypes a field merge reads:
// settings (every Settings field), selected (campaign names), shard {index, count}, campaigns
// (for each selected name: planned, a count, and items, an object).
json parse_partial(const std::string& text, const std::string& file);

}  // namespace rayq::report
