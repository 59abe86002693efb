// Issue 9: the deterministic edge-case generator and the replay of fixtures/fuzz/.
//
// The same decoder and invariants as the libFuzzer harnesses (validation/fuzz/include/rayq/fuzz),
// on a fixed set of random byte strings per primitive family, in every CI run and without
// libFuzzer: every policy, float and double, scalar and scene paths, t_error against the binary128
// reference. In the g++ build (RAYQ_EDGE_CASE_ORACLE) every 50th valid case of the primitives the
// accurate policy decides exactly is also measured against the exact oracle: hit/miss, part, and
// t within 1 ulp (beyond T's range: the largest T). The sanitizer build (tools/sanitize/CMakeLists.txt) runs it without the oracle.
//
// RAYQ_EDGE_CASES=N sets the byte strings per family (default 20,000: a few seconds in all with
// g++ -O2; the sanitizer build runs 4,000); the replay
// test reads every file under fixtures/fuzz/<harness>/ (the seed corpus and every input that
// ever failed) and fixtures/fuzz/open/<harness>/ (reproducers of open kernel issues, which must
// fail nothing but the known issues of known_issues.hpp).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include <rayq/fuzz/decoder.hpp>
#include <rayq/fuzz/fixture_line.hpp>
#include <rayq/fuzz/checks.hpp>

#ifdef RAYQ_EDGE_CASE_ORACLE
#include <rayq/oracle/fixtures.hpp>
#include <rayq/oracle/harness.hpp>
#endif

namespace rayq::fuzz {
namespace {

std::size_t cases_per_family()
{
    const char* s = std::getenv("RAYQ_EDGE_CASES");
    return s ? std::size_t(std::strtoull(s, nullptr, 10)) : 20000;
}

struct Tally {
    std::size_t cases = 0, usable = 0, hits = 0, certified = 0, uncertain = 0, accurate_skipped = 0, known = 0;
    std::size_t oracle_cases = 0, oracle_failures = 0, failures = 0;
};

template <class Prim>
struct is_exact_primitive : std::false_type {};  // the primitives rayq::accurate decides exactly
template <class T> struct is_exact_primitive<Sphere<T>> : std::true_type {};
template <class T> struct is_exact_primitive<Plane<T>> : std::true_type {};
template <class T> struct is_exact_primitive<Disk<T>> : std::true_type {};
template <class T> struct is_exact_primitive<Parallelogram<T>> : std::true_type {};
template <class T> struct is_exact_primitive<Triangle<T>> : std::true_type {};
template <class T> struct is_exact_primitive<Cylinder<T>> : std::true_type {};
template <class T> struct is_exact_primitive<Cone<T>> : std::true_type {};

#ifdef RAYQ_EDGE_CASE_ORACLE
// accurate against the exact oracle: hit/miss, part, t within 1 ulp. Returns what differed.
template <class Prim>
std::string oracle_disagreement(const Case<Prim>& c)
{
    const oracle::AnyInput input = oracle::Input<Prim>{c.ray, c.prim};
    const oracle::Truth truth = oracle::truth_of(input);
    const oracle::Measurement m = oracle::measure_kernel(truth, oracle::Policy::accurate, input);
    if (!m.defined) return {};
    if (!m.hit_agrees) return std::string("accurate ") + (m.kernel_hit ? "hits" : "misses") + ", the exact oracle " + (m.exact_hit ? "hits" : "misses");
    if (m.both_hit && !m.part_agrees) return "accurate reports another part than the exact oracle";
    // (Faithful also covers a root beyond the largest T, where accurate reports that T.)
    if (m.both_hit && !(m.ulps <= 1 || m.faithful)) return "accurate's t is " + std::to_string(m.ulps) + " ulps from the exact t";
    return {};
}
#endif

// Checks one decoded case; failures are printed with the input's bytes and fixture line.
template <class Prim>
void check_case(const Case<Prim>& c, const std::string& where, unsigned scene_copies, bool oracle_sample, Tally& tally)
{
    Options options;
    options.scene_copies = scene_copies;
    const Checked r = check(c.ray, c.prim, options);
    ++tally.cases;
    tally.usable += r.usable_ray && r.valid_primitive;
    tally.hits += std::size_t(r.hits);
    tally.certified += std::size_t(r.certified);
    tally.uncertain += std::size_t(r.reference_uncertain);
    tally.accurate_skipped += r.accurate_skipped;
    tally.known += std::size_t(r.known);
    const std::string line = fixture_line("fuzz." + c.construction, c.ray, c.prim);
    if (!r.violations.empty()) {
        ++tally.failures;
        ADD_FAILURE() << where << " (construction " << c.construction << "):\n" << to_string(r.violations) << "fixture line:\n" << line;
    }
#ifdef RAYQ_EDGE_CASE_ORACLE
    if constexpr (is_exact_primitive<Prim>::value) {
        if (oracle_sample && r.usable_ray && r.valid_primitive && !r.accurate_skipped &&
            !(options.skip_known && accurate_known_wrong(c.ray, c.prim))) {
            ++tally.oracle_cases;
            const std::string why = oracle_disagreement(c);
            if (!why.empty()) {
                ++tally.oracle_failures;
                ADD_FAILURE() << where << " (construction " << c.construction << "): " << why << "\nfixture line:\n" << line;
            }
        }
    }
#else
    (void)oracle_sample;
#endif
}

std::string hex_bytes(const std::vector<std::uint8_t>& bytes)
{
    static const char* digits = "0123456789abcdef";
    std::string s;
    for (auto b : bytes) {
        s += digits[b >> 4];
        s += digits[b & 15];
    }
    return s;
}

class EdgeCases : public ::testing::TestWithParam<Harness> {};

TEST_P(EdgeCases, InvariantsHoldOnTheFixedSeedSet)
{
    const Harness h = GetParam();
    const std::size_t n = cases_per_family();
    std::mt19937_64 rng(0x9e3779b97f4a7c15ull + std::uint64_t(h));  // fixed: the same cases in every run
    Tally tally;
    std::size_t valid_seen = 0;
    for (std::size_t i = 0; i < n; ++i) {
        std::vector<std::uint8_t> bytes(rng() % 193);
        for (auto& b : bytes) b = std::uint8_t(rng());
        const std::string where = std::string(harness_name(h)) + " case " + std::to_string(i) + " bytes " + hex_bytes(bytes);
        decode(h, bytes.data(), bytes.size(), [&](const auto& c) {
            // every 50th valid case also goes to the oracle (it is slow)
            const bool valid = detail_check::ray_may_hit(c.ray) && static_cast<bool>(validate(c.prim));
            const bool sample = valid && valid_seen++ % 50 == 0;
            check_case(c, where, 1 + unsigned(i % 9), sample, tally);
        });
        if (tally.failures > 20) break;  // enough to read
    }
    std::printf("edge cases %-11s: %zu cases, %zu usable, %zu policy hits, t_error confirmed %zu / undecided %zu, accurate skipped (known hang) %zu, known open violations %zu, oracle samples %zu (disagreements %zu)\n",
                harness_name(h), tally.cases, tally.usable, tally.hits, tally.certified, tally.uncertain, tally.accurate_skipped,
                tally.known, tally.oracle_cases, tally.oracle_failures);
    EXPECT_EQ(tally.failures, 0u);
    // The generator must reach the interesting places: most cases usable, many hits, the
    // reference deciding most of them.
    EXPECT_GT(tally.usable, tally.cases / 2);
    EXPECT_GT(tally.hits, tally.cases / 4);
    EXPECT_GT(tally.certified, tally.hits / 2);
#ifdef RAYQ_EDGE_CASE_ORACLE
    if (h != Harness::quadric && h != Harness::transformed) {
        EXPECT_GT(tally.oracle_cases, n / 100);
    }
#endif
}

INSTANTIATE_TEST_SUITE_P(Families, EdgeCases, ::testing::ValuesIn(all_harnesses),
                         [](const ::testing::TestParamInfo<Harness>& info) { return std::string(harness_name(info.param)); });

std::vector<std::uint8_t> read_bytes(const std::filesystem::path& p)
{
    std::ifstream in(p, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// Every stored input of a harness, in order: fixtures/fuzz/<harness>/ then open/<harness>/, each
// sorted by name.
std::vector<std::filesystem::path> stored_inputs(Harness h)
{
    namespace fs = std::filesystem;
    const fs::path root = RAYQ_FUZZ_FIXTURES;
    std::vector<fs::path> all;
    for (const fs::path& dir : {root / harness_name(h), root / "open" / harness_name(h)}) {
        if (!fs::is_directory(dir)) continue;
        std::vector<fs::path> paths;
        for (const auto& e : fs::directory_iterator(dir))
            if (e.is_regular_file()) paths.push_back(e.path());
        std::sort(paths.begin(), paths.end());
        all.insert(all.end(), paths.begin(), paths.end());
    }
    return all;
}

// Every stored input, forever: the seed corpus, fixed findings, and open reproducers.
TEST(FuzzReplay, EveryStoredInputPasses)
{
    namespace fs = std::filesystem;
    const fs::path root = RAYQ_FUZZ_FIXTURES;
    std::size_t files = 0;
    for (const Harness h : all_harnesses) {
        for (const fs::path& p : stored_inputs(h)) {
            const auto bytes = read_bytes(p);
            Tally tally;
            decode(h, bytes.data(), bytes.size(), [&](const auto& c) { check_case(c, p.string(), scene_copies_for(bytes.data(), bytes.size()), true, tally); });
            ++files;
        }
        EXPECT_TRUE(fs::is_directory(root / harness_name(h))) << "no seed corpus for " << harness_name(h);
    }
    std::printf("replayed %zu stored inputs from %s\n", files, root.string().c_str());
    EXPECT_GT(files, 5u * 10u) << "the seed corpora should hold a few dozen inputs each";
}

// The stored inputs keep their meaning: each decodes to the fixture lines recorded in
// fixtures/fuzz/decoded.txt ("<harness>/<file> <fixture line>", one line per decoded case, in
// decoding order). Recorded from the g++ build and checked under clang in CI, it pins the decoder's
// compiler independence (C++ leaves argument order unspecified, and g++ and clang once read a
// crash input's bytes into different rays) and catches decoder changes that would silently turn
// the corpus and every stored reproducer into other cases. Inputs added later are not listed
// until recorded again: RAYQ_FUZZ_RECORD_DECODED=<path> writes every stored input's lines there.
TEST(FuzzReplay, StoredInputsDecodeAsRecorded)
{
    namespace fs = std::filesystem;
    const fs::path root = RAYQ_FUZZ_FIXTURES;
    const auto lines_of = [&](Harness h, const fs::path& file) {
        const auto bytes = read_bytes(file);
        std::vector<std::string> out;
        decode(h, bytes.data(), bytes.size(), [&](const auto& c) { out.push_back(fixture_line("fuzz." + c.construction, c.ray, c.prim)); });
        return out;
    };
    if (const char* record = std::getenv("RAYQ_FUZZ_RECORD_DECODED")) {
        std::ofstream out(record);
        for (const Harness h : all_harnesses)
            for (const fs::path& p : stored_inputs(h))
                for (const std::string& line : lines_of(h, p)) out << fs::relative(p, root).generic_string() << ' ' << line << '\n';
        GTEST_SKIP() << "recorded to " << record;
    }
    std::ifstream in(root / "decoded.txt");
    ASSERT_TRUE(in) << (root / "decoded.txt") << " is missing";
    std::map<std::string, std::vector<std::string>> recorded;  // input -> its lines, in order
    std::vector<std::string> order;
    for (std::string line; std::getline(in, line);) {
        const auto space = line.find(' ');
        ASSERT_NE(space, std::string::npos) << "decoded.txt: expected '<harness>/<file> <fixture line>', got: " << line;
        const std::string file = line.substr(0, space);
        if (!recorded.count(file)) order.push_back(file);
        recorded[file].push_back(line.substr(space + 1));
    }
    ASSERT_GT(order.size(), 100u);
    for (const std::string& file : order) {
        const fs::path path = root / file;
        const std::string harness = fs::path(file).parent_path().filename().string();
        const auto h = std::find_if(std::begin(all_harnesses), std::end(all_harnesses), [&](Harness x) { return harness == harness_name(x); });
        ASSERT_NE(h, std::end(all_harnesses)) << file;
        ASSERT_TRUE(fs::is_regular_file(path)) << file << " is recorded but missing";
        EXPECT_EQ(lines_of(*h, path), recorded[file]) << file << " decodes to other cases than recorded";
    }
}

// A finding's fixture line is a line of the fixture format (checked against the oracle's parser
// where it is built).
TEST(FuzzReplay, FixtureLinesParse)
{
#ifdef RAYQ_EDGE_CASE_ORACLE
    std::mt19937_64 rng(7);
    for (const Harness h : all_harnesses)
        for (int i = 0; i < 200; ++i) {
            std::vector<std::uint8_t> bytes(rng() % 193);
            for (auto& b : bytes) b = std::uint8_t(rng());
            decode(h, bytes.data(), bytes.size(), [&](const auto& c) {
                const std::string line = fixture_line("fuzz." + c.construction, c.ray, c.prim);
                std::istringstream in(line);
                std::vector<oracle::Fixture> parsed;
                try {
                    parsed = oracle::parse_fixtures(in, "fuzz");
                } catch (const std::exception& e) {
                    ADD_FAILURE() << e.what() << "\n" << line;
                    return;
                }
                ASSERT_EQ(parsed.size(), 1u) << line;
                EXPECT_EQ(oracle::format_fixture(parsed[0]), line);
            });
        }
#else
    GTEST_SKIP() << "needs the oracle's parser (g++ build)";
#endif
}

}  // namespace
}  // namespace rayq::fuzz
