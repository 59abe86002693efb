// rayq-validate — the report: gnuplot SVG plots embedded in one self-contained index.html.
#pragma once

#include <filesystem>

#include "campaign.hpp"

namespace rayq::report {

// Draws every plot of the campaigns that ran (data and scripts kept under out/plots/) and writes
// out/index.html atomically. Returns the number of plots embedded. Throws when gnuplot fails.
int write_report(const json& summary, const std::filesystem::path& out);

}  // namespace rayq::report
