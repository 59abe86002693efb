// rayq::stats — summaries that merge exactly. A campaign split into shards must produce the same
// report as one run (issue 8), so everything a campaign keeps is an integer count, an exact
// maximum, or a histogram with fixed bins: merging adds counts, and quantiles are read from the
// merged bins. Floating-point sums (means) are deliberately absent: their value depends on order.
#pragma once

#include <cstdint>
#include <map>
#include <string>

#include <nlohmann/json_fwd.hpp>

namespace rayq::stats {

// Non-negative values (ulp errors, relative errors, ratios) in log-spaced bins: bins_per_decade
// bins per power of ten from 10^min_decade to 10^max_decade; smaller values (and 0) go to the
// zero bin, larger finite ones to the top bin, +inf and NaN are counted apart.
class LogHistogram {
public:
    static constexpr int bins_per_decade = 20;
    static constexpr int min_decade = -6;
    static constexpr int max_decade = 30;

    void add(double value);
    void merge(const LogHistogram& other);

    std::uint64_t count() const { return finite_ + infinite_; }  // NaN excluded
    std::uint64_t finite() const { return finite_; }
    std::uint64_t infinite() const { return infinite_; }
    std::uint64_t nan() const { return nan_; }
    double max() const { return max_; }  // exact largest finite value added (0 when none)
    const std::map<int, std::uint64_t>& bins() const { return bins_; }  // index -> count, ascending

    // The q-quantile (0 < q <= 1) of the finite values, rounded up to its bin's upper edge and
    // capped at the exact maximum: a conservative figure (never below the true quantile).
    double quantile(double q) const;
    // Number of finite values strictly greater than the upper edge of the bin holding `threshold`
    // (exact when threshold is a bin edge; conservative, i.e. never more, otherwise).
    std::uint64_t count_above(double threshold) const;

    // {"bins": {"<index>": count, ...}, "zero": n, "inf": n, "nan": n, "max": x} — sparse.
    nlohmann::json to_json() const;
    static LogHistogram from_json(const nlohmann::json& j);  // throws std::runtime_error on bad input

    // The bin's range [lower, upper); index 0 is the zero bin [0, 10^min_decade).
    static double lower_edge(int index);
    static double upper_edge(int index);
    static int index_of(double finite_nonnegative);

    friend bool operator==(const LogHistogram& a, const LogHistogram& b);
    friend bool operator!=(const LogHistogram& a, const LogHistogram& b) { return !(a == b); }

private:
    std::map<int, std::uint64_t> bins_;  // sparse: most campaigns touch few bins
    std::uint64_t finite_ = 0, infinite_ = 0, nan_ = 0;
    double max_ = 0;
};

}  // namespace rayq::stats
