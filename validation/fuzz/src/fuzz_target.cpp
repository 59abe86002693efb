// One libFuzzer harness per primitive family (RAYQ_FUZZ_HARNESS = flat, sphere, axial, quadric,
// transformed): decode the bytes into a (ray, primitive) pair (decoder.hpp), check every invariant
// under every policy (invariants.hpp), and crash on a violation so that libFuzzer keeps the input.
// Built only with clang's -fsanitize=fuzzer (tools/sanitize/CMakeLists.txt), together with ASan
// and UBSan: a sanitizer report is a finding too.
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include <rayq/fuzz/decoder.hpp>
#include <rayq/fuzz/fixture_line.hpp>
#include <rayq/fuzz/checks.hpp>

#ifndef RAYQ_FUZZ_HARNESS
#error "define RAYQ_FUZZ_HARNESS (flat, sphere, axial, quadric or transformed)"
#endif

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    constexpr rayq::fuzz::Harness harness = rayq::fuzz::Harness::RAYQ_FUZZ_HARNESS;
    rayq::fuzz::decode<harness>(data, size, [&](const auto& c) {
        rayq::fuzz::Options options;
        options.scene_copies = rayq::fuzz::scene_copies_for(data, size);
        const rayq::fuzz::Checked checked = rayq::fuzz::check(c.ray, c.prim, options);
        if (checked.violations.empty()) return;
        std::fprintf(stderr, "rayq-fuzz: %zu invariant(s) violated (%s, construction %s):\n%s",
                     checked.violations.size(), rayq::fuzz::harness_name(harness), c.construction.c_str(),
                     rayq::fuzz::to_string(checked.violations).c_str());
        std::fprintf(stderr, "fixture line:\n%s\n",
                     rayq::fuzz::fixture_line(std::string("fuzz.") + rayq::fuzz::harness_name(harness) + "." + c.construction, c.ray, c.prim)
                         .c_str());
        std::abort();  // libFuzzer writes the input as crash-<sha1>
    });
    return 0;
}
