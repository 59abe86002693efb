// rayq-validate — gates: thresholds on the summary's metrics, read from a checked-in text file.
//
//   # comment
//   <metric pattern>  <op>  <threshold>      op: <= < >= > ==
//
// A pattern may contain '*' (any run of characters, dots included); every metric it matches must
// pass. A gate whose campaign did not run (skipped, incomplete) is "skipped", never "pass"; so is
// a gate that matches no metric and names a part of a campaign that did not run (the section's
// "skipped_metrics" prefixes, e.g. rayq-bench-embree not built). A gate whose campaign ran but
// which matches no metric otherwise fails (it would measure nothing).
#pragma once

#include <string>
#include <vector>

#include "campaign.hpp"

namespace rayq::report {

struct Gate {
    std::string pattern, op;
    double threshold = 0;
    std::string file;
    int line = 0;
};

// Throws std::runtime_error "file:line: expected …" on malformed lines.
std::vector<Gate> parse_gates(const std::string& text, const std::string& file_name);
std::vector<Gate> load_gates(const std::string& path);

// Evaluates the gates against summary["campaigns"]; returns the "gates" object of the summary:
// {"file", "results": [...], "passed", "failed", "skipped"}.
json evaluate_gates(const std::vector<Gate>& gates, const json& campaigns, const std::string& file);

}  // namespace rayq::report
