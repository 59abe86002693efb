#include <rayq/stats/histogram.hpp>

#include <cmath>
#include <stdexcept>

#include <nlohmann/json.hpp>

namespace rayq::stats {

namespace {
constexpr int top_index = (LogHistogram::max_decade - LogHistogram::min_decade) * LogHistogram::bins_per_decade;
}

int LogHistogram::index_of(double v)
{
    if (!(v >= std::pow(10.0, min_decade))) return 0;
    // Bin k >= 1 covers [10^(min + (k-1)/b), 10^(min + k/b)); the pow() comparisons below fix
    // the log10() rounding so a value exactly on an edge lands in the bin it starts.
    int k = 1 + static_cast<int>(std::floor((std::log10(v) - min_decade) * bins_per_decade));
    if (k > top_index) return top_index;
    if (k > 1 && v < lower_edge(k)) --k;
    else if (k < top_index && v >= upper_edge(k)) ++k;
    return k;
}

double LogHistogram::lower_edge(int index)
{
    if (index <= 0) return 0.0;
    return std::pow(10.0, min_decade + static_cast<double>(index - 1) / bins_per_decade);
}

double LogHistogram::upper_edge(int index)
{
    if (index >= top_index) return HUGE_VAL;
    return std::pow(10.0, min_decade + static_cast<double>(index) / bins_per_decade);
}

void LogHistogram::add(double v)
{
    if (std::isnan(v)) { ++nan_; return; }
    if (std::isinf(v)) { ++infinite_; return; }
    if (v < 0) v = -v;
    ++bins_[index_of(v)];
    ++finite_;
    if (v > max_) max_ = v;
}

void LogHistogram::merge(const LogHistogram& o)
{
    for (const auto& [k, n] : o.bins_) bins_[k] += n;
    finite_ += o.finite_;
    infinite_ += o.infinite_;
    nan_ += o.nan_;
    if (o.max_ > max_) max_ = o.max_;
}

double LogHistogram::quantile(double q) const
{
    if (finite_ == 0) return 0.0;
    // The rank of the q-quantile among finite values, 1-based, rounded up (nearest-rank method).
    const auto rank = static_cast<std::uint64_t>(std::ceil(q * static_cast<double>(finite_)));
    std::uint64_t seen = 0;
    for (const auto& [k, n] : bins_) {
        seen += n;
        if (seen >= rank) return std::fmin(upper_edge(k), max_);
    }
    return max_;
}

std::uint64_t LogHistogram::count_above(double threshold) const
{
    const int t = index_of(threshold < 0 ? -threshold : threshold);
    std::uint64_t n = 0;
    for (auto it = bins_.upper_bound(t); it != bins_.end(); ++it) n += it->second;
    return n;
}

nlohmann::json LogHistogram::to_json() const
{
    nlohmann::json bins = nlohmann::json::object();
    for (const auto& [k, n] : bins_) bins[std::to_string(k)] = n;
    return {{"bins", bins}, {"finite", finite_}, {"inf", infinite_}, {"nan", nan_}, {"max", max_}};
}

LogHistogram LogHistogram::from_json(const nlohmann::json& j)
{
    try {
        LogHistogram h;
        for (const auto& [key, n] : j.at("bins").items()) {
            std::size_t used = 0;
            const int k = std::stoi(key, &used);
            if (used != key.size() || k < 0 || k > top_index) throw std::runtime_error("bin index " + key + " out of range");
            h.bins_[k] = n.get<std::uint64_t>();
        }
        h.finite_ = j.at("finite").get<std::uint64_t>();
        h.infinite_ = j.at("inf").get<std::uint64_t>();
        h.nan_ = j.at("nan").get<std::uint64_t>();
        h.max_ = j.at("max").get<double>();
        std::uint64_t total = 0;
        for (const auto& [k, n] : h.bins_) total += n;
        if (total != h.finite_) throw std::runtime_error("bin counts do not add up to 'finite'");
        return h;
    } catch (const nlohmann::json::exception& e) {
        throw std::runtime_error(std::string("log histogram: ") + e.what());
    } catch (const std::logic_error& e) {  // std::stoi
        throw std::runtime_error(std::string("log histogram: ") + e.what());
    }
}

bool operator==(const LogHistogram& a, const LogHistogram& b)
{
    return a.bins_ == b.bins_ && a.finite_ == b.finite_ && a.infinite_ == b.infinite_ && a.nan_ == b.nan_ &&
           a.max_ == b.max_;
}

}  // namespace rayq::stats
