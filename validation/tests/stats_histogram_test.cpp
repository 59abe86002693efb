// rayq::stats::LogHistogram: merging shards gives the histogram of the whole, quantiles are
// conservative and within one bin of the exact nearest-rank quantile, JSON round-trips.
#include <rayq/stats/histogram.hpp>

#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

using rayq::stats::LogHistogram;

namespace {

std::vector<double> log_uniform_values(std::size_t n, unsigned seed)
{
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> exponent(-8.0, 32.0);  // beyond both ends of the bins
    std::vector<double> v(n);
    for (auto& x : v) x = std::pow(10.0, exponent(rng));
    return v;
}

double nearest_rank(std::vector<double> v, double q)
{
    std::sort(v.begin(), v.end());
    const auto rank = static_cast<std::size_t>(std::ceil(q * static_cast<double>(v.size())));
    return v[rank - 1];
}

}  // namespace

TEST(LogHistogram, MergingShardsEqualsTheWhole)
{
    const auto values = log_uniform_values(10000, 7);
    LogHistogram whole;
    std::vector<LogHistogram> shards(4);
    for (std::size_t i = 0; i < values.size(); ++i) {
        whole.add(values[i]);
        shards[(i * 2654435761u) % shards.size()].add(values[i]);
    }
    LogHistogram merged;
    for (auto it = shards.rbegin(); it != shards.rend(); ++it) merged.merge(*it);  // any order
    EXPECT_EQ(merged, whole);
    EXPECT_EQ(merged.count(), values.size());
    EXPECT_EQ(merged.max(), *std::max_element(values.begin(), values.end()));
}

TEST(LogHistogram, QuantilesAreConservativeAndWithinOneBin)
{
    std::mt19937_64 rng(3);
    std::uniform_real_distribution<double> exponent(-3.0, 12.0);
    std::vector<double> values(5001);
    for (auto& x : values) x = std::pow(10.0, exponent(rng));
    LogHistogram h;
    for (double x : values) h.add(x);
    const double bin_ratio = std::pow(10.0, 1.0 / LogHistogram::bins_per_decade);
    for (double q : {0.01, 0.5, 0.9, 0.99, 0.999, 1.0}) {
        const double exact = nearest_rank(values, q);
        const double got = h.quantile(q);
        EXPECT_GE(got, exact) << "q = " << q;
        EXPECT_LE(got, exact * bin_ratio * (1 + 1e-12)) << "q = " << q;
    }
    EXPECT_EQ(h.quantile(1.0), *std::max_element(values.begin(), values.end()));
}

TEST(LogHistogram, EdgesZeroInfinityAndNaN)
{
    for (int k = 1; k < 200; ++k) {
        EXPECT_EQ(LogHistogram::index_of(LogHistogram::lower_edge(k)), k) << k;
        EXPECT_EQ(LogHistogram::index_of(std::nextafter(LogHistogram::upper_edge(k), 0.0)), k) << k;
    }
    LogHistogram h;
    h.add(0.0);
    h.add(0.5);
    h.add(HUGE_VAL);
    h.add(std::nan(""));
    EXPECT_EQ(h.finite(), 2u);
    EXPECT_EQ(h.infinite(), 1u);
    EXPECT_EQ(h.nan(), 1u);
    EXPECT_EQ(h.max(), 0.5);
    EXPECT_EQ(h.quantile(0.5), LogHistogram::upper_edge(0));
    EXPECT_EQ(h.quantile(1.0), 0.5);  // capped at the exact maximum
    EXPECT_EQ(h.count_above(0.1), 1u);
    EXPECT_EQ(h.count_above(1.0), 0u);
}

TEST(LogHistogram, JsonRoundTripAndRejection)
{
    LogHistogram h;
    for (double x : log_uniform_values(500, 11)) h.add(x);
    h.add(HUGE_VAL);
    const auto text = h.to_json().dump();
    EXPECT_EQ(LogHistogram::from_json(nlohmann::json::parse(text)), h);

    auto broken = h.to_json();
    broken["finite"] = h.finite() + 1;
    EXPECT_THROW(LogHistogram::from_json(broken), std::runtime_error);
    auto bad_key = h.to_json();
    bad_key["bins"]["x7"] = 1;
    EXPECT_THROW(LogHistogram::from_json(bad_key), std::runtime_error);
    EXPECT_THROW(LogHistogram::from_json(nlohmann::json::parse(R"({"bins": {}})")), std::runtime_error);
}
