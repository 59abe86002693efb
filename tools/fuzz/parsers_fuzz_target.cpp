// The libFuzzer harness for rayq's file parsers (issue 9): every public entry that reads a file a
// user may hand it. The first byte picks the parser, the rest is the file's text:
//   'f' (or byte % 3 == 0)  a fixture file   rayq::oracle::parse_fixtures (validation/oracle)
//   'g' (or byte % 3 == 1)  a gates file     rayq::report::parse_gates    (tools/validate)
//   'p' (or byte % 3 == 2)  a partial.json   rayq::report::parse_partial  (tools/validate)
// Invariants: the parser returns or throws its own error, never anything else, never a sanitizer
// report; an error names the file and, for the line formats, a line that exists, then says what
// was expected; what a line format accepts is written back (format_fixture) to text that parses
// to the same text again; an accepted partial holds every field merge reads, with its type.
// Seed corpus and reproducers: fixtures/fuzz/parsers/. Built by tools/sanitize (clang, ASan + UBSan).
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <string>

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

// "<file>:<line>: expected …" with 1 <= line <= the number of lines.
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
    if (line < 1 || line > lines_in(text)) finding("the error names a line the input does not have: " + message, text);
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

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    if (size == 0) return 0;
    const std::string text(reinterpret_cast<const char*>(data) + 1, size - 1);
    const std::uint8_t which = data[0];
    if (which == 'f' || (which != 'g' && which != 'p' && which % 3 == 0)) fixtures(text);
    else if (which == 'g' || (which != 'p' && which % 3 == 1)) gates(text);
    else partial(text);
    return 0;
}
