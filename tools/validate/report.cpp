#include "report.hpp"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "process.hpp"
#include "runner.hpp"

namespace rayq::report {

namespace {

std::string escape(const std::string& s)
{
    std::string out;
    for (char c : s) {
        switch (c) {
        case '<': out += "&lt;"; break;
        case '>': out += "&gt;"; break;
        case '&': out += "&amp;"; break;
        case '"': out += "&quot;"; break;
        default: out += c;
        }
    }
    return out;
}

std::string cell(const json& v)
{
    if (v.is_string()) return escape(v.get<std::string>());
    if (v.is_null()) return "–";
    if (v.is_number_float()) {
        const double x = v.get<double>();
        char buf[32];
        if (std::isinf(x)) return x > 0 ? "inf" : "-inf";
        if (x != 0 && (std::fabs(x) >= 1e6 || std::fabs(x) < 1e-3)) std::snprintf(buf, sizeof buf, "%.3g", x);
        else std::snprintf(buf, sizeof buf, "%.4g", x);
        return buf;
    }
    return escape(v.dump());
}

std::string table_html(const json& t)
{
    std::string h = "<h3>" + escape(t.at("title").get<std::string>()) + "</h3>\n<div class=\"scroll\"><table>\n<tr>";
    for (const json& c : t.at("columns")) h += "<th>" + cell(c) + "</th>";
    h += "</tr>\n";
    for (const json& row : t.at("rows")) {
        h += "<tr>";
        for (const json& v : row) h += "<td>" + cell(v) + "</td>";
        h += "</tr>\n";
    }
    return h + "</table></div>\n";
}

std::string read_svg(const std::filesystem::path& file)
{
    std::ifstream in(file);
    std::ostringstream s;
    s << in.rdbuf();
    std::string svg = s.str();
    const auto start = svg.find("<svg");
    if (start == std::string::npos) throw std::runtime_error(file.string() + ": gnuplot wrote no <svg> element");
    return svg.substr(start);
}

// Runs gnuplot on one plot; returns the inline SVG.
std::string draw(const Plot& p, const std::filesystem::path& dir)
{
    const auto data_dir = dir / p.name;
    std::filesystem::create_directories(data_dir);
    for (const auto& [file, text] : p.data) write_file_atomically(data_dir / file, text);
    std::string script = p.script;
    for (std::size_t at; (at = script.find("<dir>")) != std::string::npos;) script.replace(at, 5, data_dir.string());
    const auto svg_file = dir / (p.name + ".svg");
    const std::string full = "set terminal svg size 900,480 dynamic enhanced font 'DejaVu Sans,12' background rgb 'white'\n"
                             "set output '" + svg_file.string() + "'\nset title \"" + p.title + "\" noenhanced\n" +
                             script + "unset output\n";
    write_file_atomically(data_dir / "plot.gp", full);
    const int status = run_program({"gnuplot", (data_dir / "plot.gp").string()}, false);
    if (status != 0) throw std::runtime_error("gnuplot failed on " + (data_dir / "plot.gp").string());
    return read_svg(svg_file);
}

const char* style = R"(
body { font-family: 'DejaVu Sans', Arial, sans-serif; margin: 2em; color: #222; max-width: 1400px; }
h1 { margin-bottom: 0.2em; } h2 { border-bottom: 2px solid #ccc; margin-top: 2em; }
table { border-collapse: collapse; font-size: 0.85em; margin: 0.5em 0 1.5em; }
td, th { border: 1px solid #ccc; padding: 2px 6px; text-align: right; white-space: nowrap; }
th { background: #f0f0f0; } td:first-child, th:first-child { text-align: left; }
.pass { background: #d8f5d8; } .fail { background: #f8d0d0; } .skipped { background: #eee; color: #666; }
.scroll { max-height: 480px; overflow: auto; display: inline-block; }
.plot { margin: 1em 0; } .plot svg { max-width: 100%; height: auto; border: 1px solid #ddd; }
code, pre { background: #f6f6f6; padding: 2px 4px; }
pre.note { max-height: 480px; overflow: auto; }
)";

// After load: count the plots that rendered with a non-empty box; the headless-browser test
// reads the result from the DOM.
const char* check_script = R"(
<script>
window.addEventListener('load', function () {
  var plots = document.querySelectorAll('.plot svg'), ok = 0;
  plots.forEach(function (s) { var b = s.getBoundingClientRect(); if (b.width > 50 && b.height > 50) ok++; });
  document.body.setAttribute('data-plots-expected', document.body.getAttribute('data-plots'));
  document.body.setAttribute('data-plots-rendered', String(ok));
});
</script>
)";

}  // namespace

int write_report(const json& summary, const std::filesystem::path& out)
{
    const auto plot_dir = out / "plots";
    std::filesystem::create_directories(plot_dir);
    const json& campaigns = summary.at("campaigns");
    json sections = json::object();
    for (const auto& [name, c] : campaigns.items())
        if (c.at("status") == "ran") sections[name] = c.at("section");

    std::string body;
    int plots = 0;
    const json& gates = summary.at("gates");
    const int failed = gates.at("failed"), passed = gates.at("passed"), skipped = gates.at("skipped");
    body += std::string("<p class=\"") + (failed ? "fail" : "pass") + "\" style=\"padding:0.5em\"><b>" +
            (failed ? "FAIL" : "PASS") + "</b>: " + std::to_string(passed) + " gates passed, " + std::to_string(failed) +
            " failed, " + std::to_string(skipped) + " skipped (gates file <code>" +
            escape(gates.at("file").get<std::string>()) + "</code>).</p>\n";

    body += "<h2>Gates</h2>\n<table><tr><th>metric</th><th>condition</th><th>status</th><th>worst / failing values</th><th>where</th></tr>\n";
    for (const json& g : gates.at("results")) {
        std::string values;
        if (g.contains("reason")) values = escape(g.at("reason").get<std::string>());
        int shown = 0, failing = 0;
        if (g.contains("values"))
            for (const json& v : g.at("values")) failing += !v.at("pass").get<bool>();
        if (g.contains("values"))
            for (const json& v : g.at("values")) {
                if (failing && v.at("pass").get<bool>()) continue;
                if (shown++ == 6) { values += " …"; break; }
                values += (values.empty() ? "" : "; ") + escape(v.at("metric").get<std::string>()) + " = " + cell(v.at("value"));
            }
        if (failing) values = std::to_string(failing) + " of " + std::to_string(g.at("values").size()) + " fail: " + values;
        const std::string status = g.at("status");
        body += "<tr class=\"" + status + "\"><td>" + escape(g.at("metric").get<std::string>()) + "</td><td>" +
                escape(g.at("op").get<std::string>()) + " " + cell(g.at("threshold")) + "</td><td>" + status +
                "</td><td style=\"text-align:left;white-space:normal\">" + values + "</td><td>" +
                escape(g.at("where").get<std::string>()) + "</td></tr>\n";
    }
    body += "</table>\n";

    for (const Campaign& c : all_campaigns()) {
        const json& entry = campaigns.at(c.name);
        const std::string status = entry.at("status");
        body += "<h2 id=\"" + c.name + "\">" + escape(c.title) + " <small class=\"" + (status == "ran" ? "pass" : "skipped") +
                "\">" + status + "</small></h2>\n";
        if (status == "skipped") { body += "<p>Not run (not selected).</p>\n"; continue; }
        body += "<p>" + entry.at("items_done").dump() + " of " + entry.at("items_planned").dump() +
                " work items. Raw data: <a href=\"data/" + c.name + ".csv\">data/" + c.name + ".csv</a>.</p>\n";
        if (status != "ran") { body += "<p>Incomplete: no gate of this campaign is evaluated.</p>\n"; }
        if (status == "ran")
            for (const Plot& p : c.plots(sections)) {
                body += "<div class=\"plot\"><h3>" + escape(p.title) + "</h3>\n" + draw(p, plot_dir) + "</div>\n";
                ++plots;
            }
        for (const json& t : entry.at("section").value("tables", json::array())) body += table_html(t);
        for (const json& n : entry.at("section").value("notes", json::array()))
            body += "<h3>" + escape(n.at("title").get<std::string>()) + "</h3>\n<pre class=\"note\">" +
                    escape(n.at("text").get<std::string>()) + "</pre>\n";
    }

    const json& run = summary.value("run", json::object());
    body += "<h2>How this report was made</h2>\n<pre>" + escape(run.dump(2)) + "</pre>\n<h3>Settings</h3>\n<pre>" +
            escape(summary.at("settings").dump(2)) + "</pre>\n";

    const std::string html = "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">\n<title>rayq validation report</title>\n<style>" +
                             std::string(style) + "</style></head>\n<body data-plots=\"" + std::to_string(plots) +
                             "\">\n<h1>rayq validation report</h1>\n" + body + check_script + "</body></html>\n";
    write_file_atomically(out / "index.html", html);
    return plots;
}

}  // namespace rayq::report
