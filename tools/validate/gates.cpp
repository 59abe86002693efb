#include "gates.hpp"

#include <cmath>
#include <fnmatch.h>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace rayq::report {

std::vector<Gate> parse_gates(const std::string& text, const std::string& file)
{
    std::vector<Gate> gates;
    std::istringstream in(text);
    std::string line;
    int number = 0;
    while (std::getline(in, line)) {
        ++number;
        if (const auto hash = line.find('#'); hash != std::string::npos) line.erase(hash);
        std::istringstream words(line);
        Gate g;
        g.file = file;
        g.line = number;
        std::string threshold, extra;
        if (!(words >> g.pattern)) continue;  // blank or comment
        auto fail = [&](const std::string& expected) {
            throw std::runtime_error(file + ":" + std::to_string(number) + ": expected " + expected);
        };
        if (!(words >> g.op)) fail("an operator (<=, <, >=, >, ==) after the metric");
        if (g.op != "<=" && g.op != "<" && g.op != ">=" && g.op != ">" && g.op != "==")
            fail("an operator (<=, <, >=, >, ==), got '" + g.op + "'");
        if (!(words >> threshold)) fail("a number after the operator");
        std::size_t used = 0;
        try {
            g.threshold = std::stod(threshold, &used);
        } catch (const std::exception&) {
            used = 0;
        }
        if (used != threshold.size() || !std::isfinite(g.threshold)) fail("a finite number, got '" + threshold + "'");
        if (words >> extra) fail("end of line after the threshold, got '" + extra + "'");
        // Printable ASCII only: the pattern is written into summary.json, and a byte that is not
        // UTF-8 made writing it throw after the whole run (found by the parsers' fuzz harness,
        // fixtures/fuzz/parsers/crash-gates-invalid-utf8-pattern).
        for (const char ch : g.pattern)
            if (ch < '!' || ch > '~') fail("a metric pattern of printable ASCII characters (letters, digits, '.', '_', '*', ...)");
        if (g.pattern.find('.') == std::string::npos) fail("a metric of the form <campaign>.<name>, got '" + g.pattern + "'");
        gates.push_back(g);
    }
    return gates;
}

std::vector<Gate> load_gates(const std::string& path)
{
    std::ifstream in(path);
    if (!in) throw std::runtime_error(path + ": cannot open the gates file");
    std::ostringstream s;
    s << in.rdbuf();
    return parse_gates(s.str(), path);
}

namespace {
bool holds(double v, const std::string& op, double t)
{
    if (std::isnan(v)) return false;
    if (op == "<=") return v <= t;
    if (op == "<") return v < t;
    if (op == ">=") return v >= t;
    if (op == ">") return v > t;
    return v == t;
}
}  // namespace

json evaluate_gates(const std::vector<Gate>& gates, const json& campaigns, const std::string& file)
{
    json results = json::array();
    int passed = 0, failed = 0, skipped = 0;
    for (const Gate& g : gates) {
        json r = {{"metric", g.pattern}, {"op", g.op}, {"threshold", g.threshold},
                  {"where", g.file + ":" + std::to_string(g.line)}};
        const std::string campaign = g.pattern.substr(0, g.pattern.find('.'));
        const auto c = campaigns.find(campaign);
        if (c == campaigns.end()) {
            r["status"] = "fail";
            r["reason"] = "no campaign named '" + campaign + "'";
        } else if (c->at("status") != "ran") {
            r["status"] = "skipped";
            r["reason"] = "campaign " + campaign + " " + c->at("status").get<std::string>();
        } else {
            json values = json::array();
            bool ok = true;
            for (const auto& [name, value] : c->at("section").at("metrics").items()) {
                if (fnmatch(g.pattern.c_str(), name.c_str(), 0) != 0) continue;
                const double v = value.is_number() ? value.get<double>() : NAN;
                const bool pass = holds(v, g.op, g.threshold);
                ok &= pass;
                values.push_back({{"metric", name}, {"value", value}, {"pass", pass}});
            }
            r["values"] = values;
            // A gate on the metrics of a part that did not run (e.g. a benchmark program that is not
            // built) is skipped like a campaign that did not run; matching nothing otherwise fails.
            std::string skipped_because;
            for (const json& part : c->at("section").value("skipped_metrics", json::array()))
                if (g.pattern.rfind(part.at("prefix").get<std::string>(), 0) == 0) skipped_because = part.at("reason");
            if (values.empty() && !skipped_because.empty()) {
                r["status"] = "skipped";
                r["reason"] = skipped_because;
            } else if (values.empty()) {
                r["status"] = "fail";
                r["reason"] = "no metric matches";
            } else {
                r["status"] = ok ? "pass" : "fail";
            }
        }
        const std::string s = r["status"];
        (s == "pass" ? passed : s == "fail" ? failed : skipped)++;
        results.push_back(r);
    }
    return {{"file", file}, {"results", results}, {"passed", passed}, {"failed", failed}, {"skipped", skipped}};
}

}  // namespace rayq::report
