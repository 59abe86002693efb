// How rayq-fuzz drives the fuzz harnesses' decoder and invariants (validation/fuzz/include/rayq/fuzz)
// without libFuzzer: how a random input is drawn, how one input is decoded and checked, and how a
// finding is written. Shared with rayq-validate's fuzz campaign (tools/validate/campaign_fuzz.cpp),
// so that a finding in the report is the text rayq-fuzz prints and replays with --replay.
// Header-only; needs validation/fuzz/include and kernel/tests (the binary128 reference) on the
// include path.
#pragma once

#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

#include <rayq/fuzz/decoder.hpp>
#include <rayq/fuzz/fixture_line.hpp>
#include <rayq/fuzz/checks.hpp>

namespace rayq::fuzz {

// A random input: 0 to 192 random bytes (long enough for every construction's numbers; shorter
// ones read zeros past their end, which the decoder turns into special values).
template <class Rng>
std::vector<std::uint8_t> random_input(Rng& rng)
{
    std::vector<std::uint8_t> bytes(rng() % 193);
    for (auto& b : bytes) b = std::uint8_t(rng());
    return bytes;
}

inline std::string hex(const std::vector<std::uint8_t>& bytes)
{
    std::string s;
    for (auto b : bytes) {
        char buf[3];
        std::snprintf(buf, sizeof buf, "%02x", b);
        s += buf;
    }
    return s;
}

// One input decoded and checked.
struct InputCheck {
    Checked checked;
    std::string construction;
    std::string line;  // the case as a fixture line (fixtures/README.md), family fuzz.<harness>.<construction>
};

template <class Prim>
void describe_case(Harness h, const Case<Prim>& c, InputCheck& out)
{
    out.construction = c.construction;
    out.line = fixture_line(std::string("fuzz.") + harness_name(h) + "." + c.construction, c.ray, c.prim);
}

// The input's construction and fixture line, unchecked (for an input whose check never returns).
inline InputCheck decode_input(Harness h, const std::vector<std::uint8_t>& bytes)
{
    InputCheck out;
    decode(h, bytes.data(), bytes.size(), [&](const auto& c) { describe_case(h, c, out); });
    return out;
}

// Decodes and checks one input as the libFuzzer harnesses do (validation/fuzz/src/fuzz_target.cpp):
// the input's last byte also sets how many copies of a sphere the scene check holds, so that the
// SIMD filter's lanes and tails are exercised.
inline InputCheck check_input(Harness h, const std::vector<std::uint8_t>& bytes, Options options)
{
    InputCheck out;
    options.scene_copies = scene_copies_for(bytes.data(), bytes.size());
    decode(h, bytes.data(), bytes.size(), [&](const auto& c) {
        out.checked = check(c.ray, c.prim, options);
        describe_case(h, c, out);
    });
    return out;
}

// A finding, ready to paste into a fixture file: comments naming the harness, the construction and
// the input's bytes (write them to a file for rayq-fuzz --replay or a libFuzzer corpus) and the
// violated invariants, then the fixture line.
inline std::string finding_text(Harness h, const std::vector<std::uint8_t>& bytes, const InputCheck& c)
{
    std::string s = "# " + std::string(harness_name(h)) + ": " + c.construction + " input " + hex(bytes) + "\n";
    for (const Violation& v : c.checked.violations) s += "#   [" + v.invariant + "] " + v.detail + "\n";
    return s + c.line + "\n";
}

}  // namespace rayq::fuzz
