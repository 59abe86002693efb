// rayq::oracle — tallies of measurements and the table every report prints.
#include <rayq/oracle/fixtures.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace rayq::oracle {

void Tally::add(const Measurement& m)
{
    if (!m.defined) return;
    ++cases;
    if (m.hit_agrees) ++hit_agree;
    if (m.exact_fallback) ++exact_fallbacks;
    if (m.kernel_hit) {
        if (m.bounded) ++bounded;
        if (m.bound_violated) ++bound_violations;
        if (m.uncertified) ++uncertified;
    }
    if (!m.both_hit) return;
    ++both_hit;
    if (m.part_agrees) ++part_agree;
    if (m.front_face_agrees) ++front_agree;
    if (m.faithful) ++faithful;
    if (m.other_crossing) ++other_crossing;
    if (!std::isnan(m.normal_angle)) max_angle = std::max(max_angle, m.normal_angle);
    ulps.push_back(m.ulps);
}

double Tally::max_ulps() const
{
    double m = 0;
    for (double u : ulps) m = std::max(m, u);  // NaN-free: ulps are finite or +inf
    return m;
}

double Tally::percentile_ulps(double p) const
{
    if (ulps.empty()) return 0;
    std::vector<double> sorted = ulps;
    std::sort(sorted.begin(), sorted.end());
    const double rank = std::ceil(p / 100.0 * static_cast<double>(sorted.size()));
    const std::size_t i = rank < 1 ? 0 : static_cast<std::size_t>(rank) - 1;
    return sorted[std::min(i, sorted.size() - 1)];
}

namespace {

double pct(std::size_t part, std::size_t whole) { return whole == 0 ? 100.0 : 100.0 * static_cast<double>(part) / static_cast<double>(whole); }

std::string fmt_ulps(double u)
{
    char buf[32];
    if (std::isinf(u)) return "inf";
    if (u < 1e4) std::snprintf(buf, sizeof buf, "%.2f", u);
    else std::snprintf(buf, sizeof buf, "%.2e", u);
    return buf;
}

}  // namespace

std::string table_header()
{
    char buf[256];
    std::snprintf(buf, sizeof buf, "%-20s %-8s %-6s %-10s %6s %8s %8s %8s %9s %9s %9s %12s %6s %6s %9s %9s", "primitive",
                  "policy", "type", "family", "cases", "hit%", "part%", "front%", "max ulp", "p99 ulp", "faithful%",
                  "bound viol", "uncert", "other", "max angle", "fallback%");
    return buf;
}

std::string table_line(const SummaryRow& r)
{
    const Tally& t = r.tally;
    char viol[32];
    std::snprintf(viol, sizeof viol, "%zu/%zu", t.bound_violations, t.bounded);
    char buf[320];
    std::snprintf(buf, sizeof buf, "%-20s %-8s %-6s %-10s %6zu %8.3f %8.3f %8.3f %9s %9s %9.2f %12s %6zu %6zu %9.2e %9.4f",
                  r.primitive.c_str(), r.policy.c_str(), r.type.c_str(), r.family.c_str(), t.cases,
                  pct(t.hit_agree, t.cases), pct(t.part_agree, t.both_hit), pct(t.front_agree, t.both_hit),
                  fmt_ulps(t.max_ulps()).c_str(), fmt_ulps(t.percentile_ulps(99)).c_str(), pct(t.faithful, t.both_hit),
                  viol, t.uncertified, t.other_crossing, t.max_angle, pct(t.exact_fallbacks, t.cases));
    return buf;
}

std::string csv_header()
{
    return "primitive,policy,type,family,cases,hit_agree_pct,both_hit,part_agree_pct,front_agree_pct,max_ulp,p99_ulp,"
           "faithful_pct,bounded,bound_violations,uncertified,other_crossing,max_normal_angle,exact_fallback_pct";
}

std::string csv_line(const SummaryRow& r)
{
    const Tally& t = r.tally;
    char buf[512];
    std::snprintf(buf, sizeof buf, "%s,%s,%s,%s,%zu,%.4f,%zu,%.4f,%.4f,%.6g,%.6g,%.4f,%zu,%zu,%zu,%zu,%.6g,%.6g", r.primitive.c_str(),
                  r.policy.c_str(), r.type.c_str(), r.family.c_str(), t.cases, pct(t.hit_agree, t.cases), t.both_hit,
                  pct(t.part_agree, t.both_hit), pct(t.front_agree, t.both_hit), t.max_ulps(), t.percentile_ulps(99),
                  pct(t.faithful, t.both_hit), t.bounded, t.bound_violations, t.uncertified, t.other_crossing, t.max_angle,
                  pct(t.exact_fallbacks, t.cases));
    return buf;
}

}  // namespace rayq::oracle
