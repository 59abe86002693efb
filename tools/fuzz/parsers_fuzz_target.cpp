// The libFuzzer harness for rayq's file parsers (issue 9): every public entry that reads a file a
// user may hand it. The first byte picks the parser, the rest is the file's text:
//   'f' (or byte % 4 == 0)  a fixture file   rayq::oracle::parse_fixtures (validation/oracle)
//   'g' (or byte % 4 == 1)  a gates file     rayq::report::parse_gates    (tools/validate)
//   'p' (or byte % 4 == 2)  a partial.json   rayq::report::parse_partial  (tools/validate)
//   'm' (or byte % 4 == 3)  a mesh file      rayq::mesh::parse_mesh_text  (validation/mesh, what
//                           read_mesh reads OFF/OBJ/PLY with); the second byte picks the format:
//                           'o' OFF, 'j' OBJ, 'y' PLY (or byte % 3 in that order)
// Invariants: the parser returns or throws its own error, never anything else, never a sanitizer
// report; an error names the file and, for the line formats, a line that exists, then says what
// was expected; what a line format accepts is written back (format_fixture, an OFF text for a
// mesh) to text that parses to the same again; an accepted partial holds every field merge reads,
// with its type; an accepted mesh has finite coordinates, one normal per point or none, and faces
// of at least three distinct existing vertices.
// Seed corpus and reproducers: fixtures/fuzz/parsers/. Built by tools/sanitize (clang, ASan + UBSan).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <string>

#include <rayq/mesh/text_formats.hpp>
#include <rayq/oracle/fixtures.hpp>

#include "gates.hpp"
#include "partial.hpp"

namespace {

[[noreturn]] void finding(const std::string& what, const std::string& text)
{
    std::fprintf(stderr, "rayq parser fuzz: %s\ninput (%zu bytes):\n%s\n", what.c_str(), text.size(), text.c_str());
    std::abort();  // libFuzzer keeps the input as crash-<sha1>
}

std::size_t lines_in(const std::string& text)
{
    std::size_t n = 0;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);) ++n;
    return n;
}

// "<file>:<line>: expected …" with 1 <= line <= the number of lines (line 1 for an empty input).
void check_line_error(const std::string& message, const std::string& file, const std::string& text)
{
    const std::string prefix = file + ":";
    if (message.compare(0, prefix.size(), prefix) != 0) finding("the error does not start with the file name: " + message, text);
    std::size_t used = 0;
    unsigned long line = 0;
    try {
        line = std::stoul(message.substr(prefix.size()), &used);
    } catch (const std::exception&) {
        finding("the error names no line: " + message, text);
    }
    if (line < 1 || line > std::max<std::size_t>(1, lines_in(text))) finding("the error names a line the input does not have: " + message, text);
    if (message.compare(prefix.size() + used, 11, ": expected ") != 0) finding("the error does not say what was expected: " + message, text);
}

void fixtures(const std::string& text)
{
    const std::string file = "fuzz.txt";
    std::vector<rayq::oracle::Fixture> parsed;
    try {
        std::istringstream in(text);
        parsed = rayq::oracle::parse_fixtures(in, file);
    } catch (const rayq::oracle::ParseError& e) {
        check_line_error(e.what(), file, text);
        if (e.file() != file || e.line() < 1) finding("ParseError's file()/line() disagree with its message", text);
        return;
    }
    for (const rayq::oracle::Fixture& f : parsed) {
        const std::string line = rayq::oracle::format_fixture(f);
        std::istringstream again(line);
        std::vector<rayq::oracle::Fixture> back;
        try {
            back = rayq::oracle::parse_fixtures(again, "written");
        } catch (const std::exception& e) {
            finding(std::string("an accepted fixture, written back, does not parse: ") + e.what() + "\nwritten: " + line, text);
        }
        if (back.size() != 1 || rayq::oracle::format_fixture(back[0]) != line)
            finding("an accepted fixture does not survive writing and reading: " + line, text);
    }
}

void gates(const std::string& text)
{
    const std::string file = "fuzz-gates.txt";
    std::vector<rayq::report::Gate> parsed;
    try {
        parsed = rayq::report::parse_gates(text, file);
    } catch (const std::runtime_error& e) {
        check_line_error(e.what(), file, text);
        return;
    }
    const std::size_t lines = lines_in(text);
    for (const rayq::report::Gate& g : parsed) {
        if (g.op != "<=" && g.op != "<" && g.op != ">=" && g.op != ">" && g.op != "==") finding("accepted operator " + g.op, text);
        if (!(g.threshold == g.threshold) || g.threshold - g.threshold != 0) finding("accepted a non-finite threshold", text);
        if (g.line < 1 || std::size_t(g.line) > lines) finding("a gate on a line the input does not have", text);
    }
    // Evaluating them against a small summary exercises the pattern matching on fuzzed patterns.
    const rayq::report::json campaigns = {
        {"oracle", {{"status", "ran"}, {"section", {{"metrics", {{"oracle.accurate.max_ulp", 0.5}, {"oracle.fast.hit_pct", 99.0}}}}}}},
        {"mesh", {{"status", "skipped"}}}};
    // The results go into summary.json: they must serialize (dump() throws on invalid UTF-8).
    try {
        (void)rayq::report::evaluate_gates(parsed, campaigns, file).dump();
    } catch (const std::exception& e) {
        finding(std::string("accepted gates whose results cannot be written: ") + e.what(), text);
    }
}

void partial(const std::string& text)
{
    const std::string file = "fuzz/partial.json";
    rayq::report::json j;
    try {
        j = rayq::report::parse_partial(text, file);
    } catch (const std::runtime_error& e) {
        const std::string message = e.what();
        if (message.compare(0, file.size() + 2, file + ": ") != 0) finding("the error does not start with the file name: " + message, text);
        return;
    }
    // What merge reads, read here the way merge reads it: nothing may throw.
    try {
        const auto settings = rayq::report::Settings::from_json(j.at("settings"));
        (void)settings;
        for (const auto& name : j.at("selected")) {
            const auto& c = j.at("campaigns").at(name.get<std::string>());
            (void)c.at("planned").get<std::size_t>();
            for (const auto& item : c.at("items").items()) (void)item.key();
        }
        (void)j.at("shard").dump();
        (void)j.dump();
    } catch (const std::exception& e) {
        finding(std::string("an accepted partial summary throws when read: ") + e.what(), text);
    }
}

std::string off_text(const rayq::mesh::Polygons& m)
{
    std::string out = m.normals.empty() ? "OFF\n" : "NOFF\n";
    out += std::to_string(m.points.size()) + " " + std::to_string(m.faces.size()) + " 0\n";
    char number[40];
    for (std::size_t i = 0; i < m.points.size(); ++i) {
        for (int k = 0; k < (m.normals.empty() ? 3 : 6); ++k) {
            const double x = k < 3 ? m.points[i][std::size_t(k)] : m.normals[i][std::size_t(k - 3)];
            std::snprintf(number, sizeof number, "%.17g", x);
            out += (k ? " " : "") + std::string(number);
        }
        out += "\n";
    }
    for (const auto& f : m.faces) {
        out += std::to_string(f.vertices.size());
        for (const std::size_t v : f.vertices) out += " " + std::to_string(v);
        out += "\n";
    }
    return out;
}

void mesh(const std::string& text, rayq::mesh::TextFormat format)
{
    const std::string file = "fuzz.mesh";
    rayq::mesh::Polygons m;
    try {
        m = rayq::mesh::parse_mesh_text(text, format, file);
    } catch (const rayq::mesh::MeshFormatError& e) {
        check_line_error(e.what(), file, text);
        if (e.file() != file || e.line() < 1) finding("MeshFormatError's file()/line() disagree with its message", text);
        return;
    }
    if (!m.normals.empty() && m.normals.size() != m.points.size()) finding("normals for some points only", text);
    const auto finite = [](const std::array<double, 3>& v) { return std::isfinite(v[0]) && std::isfinite(v[1]) && std::isfinite(v[2]); };
    if (!std::all_of(m.points.begin(), m.points.end(), finite) || !std::all_of(m.normals.begin(), m.normals.end(), finite))
        finding("accepted a coordinate that is not finite", text);
    const std::size_t lines = lines_in(text);
    for (const auto& f : m.faces) {
        if (f.vertices.size() < 3) finding("accepted a face with fewer than 3 vertices", text);
        if (f.line < 1 || f.line > lines) finding("a face on a line the input does not have", text);
        for (std::size_t i = 0; i < f.vertices.size(); ++i) {
            if (f.vertices[i] >= m.points.size()) finding("accepted a face naming a vertex that does not exist", text);
            if (std::count(f.vertices.begin(), f.vertices.end(), f.vertices[i]) != 1) finding("accepted a face with a repeated vertex", text);
        }
    }
    // Written as OFF and read again: the same points, normals and faces.
    const std::string written = off_text(m);
    rayq::mesh::Polygons back;
    try {
        back = rayq::mesh::parse_mesh_text(written, rayq::mesh::TextFormat::off, "written.off");
    } catch (const std::exception& e) {
        finding(std::string("an accepted mesh, written as OFF, does not parse: ") + e.what() + "\nwritten:\n" + written, text);
    }
    if (off_text(back) != written) finding("an accepted mesh does not survive writing as OFF and reading:\n" + written, text);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    if (size == 0) return 0;
    const std::string text(reinterpret_cast<const char*>(data) + 1, size - 1);
    const std::uint8_t which = data[0];
    const auto is = [which](char letter, int rest) {
        return which == letter || (which != 'f' && which != 'g' && which != 'p' && which != 'm' && which % 4 == rest);
    };
    if (is('f', 0)) fixtures(text);
    else if (is('g', 1)) gates(text);
    else if (is('p', 2)) partial(text);
    else if (!text.empty()) {
        const std::uint8_t f = static_cast<std::uint8_t>(text[0]);
        using rayq::mesh::TextFormat;
        const TextFormat format = f == 'o' ? TextFormat::off : f == 'j' ? TextFormat::obj : f == 'y' ? TextFormat::ply
                                 : f % 3 == 0 ? TextFormat::off : f % 3 == 1 ? TextFormat::obj : TextFormat::ply;
        mesh(text.substr(1), format);
    }
    return 0;
}
