// The fuzz campaign (issue 9 in the report): rayq-fuzz's deterministic edge-case generator —
// random byte strings through the fuzz harnesses' structured decoder, every invariant under every
// policy (validation/fuzz/include/rayq/fuzz, driven as rayq-fuzz drives it: tools/fuzz/
// fuzz_driver.hpp) — for N cases per harness, and the replay of the stored inputs under
// fixtures/fuzz/<harness>/ and fixtures/fuzz/open/<harness>/. Work items: chunks of generated cases
// and one per stored directory; each holds counts and its first findings, so shards merge exactly.
// An input whose check does not return in time, or kills the process, is a finding too (as
// libFuzzer's -timeout and crash reports make it one): the inputs run in a watched child process.
#include <algorithm>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <new>
#include <random>
#include <set>
#include <stdexcept>
#include <sys/mman.h>
#include <sys/wait.h>
#include <thread>
#include <unistd.h>

#include "campaign.hpp"
#include "fuzz_driver.hpp"
#include "process.hpp"

namespace rayq::report {

namespace {

using fuzz::Harness;

// Findings kept per work item and shown per harness: enough to start debugging, and a report that
// stays readable when something breaks everywhere.
constexpr std::size_t findings_kept = 5;

// An input whose check runs longer than this is a hang. A check takes well under a millisecond;
// rayq::accurate has not returned for minutes, in exact expansions, on extreme coordinates.
constexpr double hang_seconds = 10;

const char* harness_contents(Harness h)
{
    switch (h) {
    case Harness::flat: return "plane, disk, parallelogram, triangle";
    case Harness::sphere: return "sphere";
    case Harness::axial: return "cylinder, cone";
    case Harness::quadric: return "general quadric";
    case Harness::transformed: return "every primitive under an affine map";
    }
    return "";
}

Harness harness_named(const std::string& name)
{
    for (Harness h : fuzz::all_harnesses)
        if (name == fuzz::harness_name(h)) return h;
    throw std::runtime_error("fuzz campaign: unknown harness " + name);
}

// Case i of a harness is a pure function of (seed, harness, i), not of how the cases are chunked
// into items: any preset's or --fuzz-cases' first N cases are the same N cases (splitmix64 mixing).
std::uint64_t case_seed(std::uint64_t seed, Harness h, std::uint64_t i)
{
    std::uint64_t z = seed;
    for (const std::uint64_t v : {std::uint64_t(h), i}) {
        z += 0x9e3779b97f4a7c15ull + v;
        z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
        z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
        z ^= z >> 31;
    }
    return z;
}

struct Tally {
    std::uint64_t cases = 0, usable = 0, hits = 0, certified = 0, uncertain = 0, accurate_skipped = 0, known_open = 0,
                  findings = 0;
    std::map<std::string, std::uint64_t> violated;  // new violations by invariant
    std::vector<std::string> examples;              // the first findings, as finding_text

    void add(const fuzz::InputCheck& c, Harness h, const std::vector<std::uint8_t>& bytes)
    {
        const fuzz::Checked& r = c.checked;
        ++cases;
        usable += r.usable_ray && r.valid_primitive;
        hits += std::uint64_t(r.hits);
        certified += std::uint64_t(r.certified);
        uncertain += std::uint64_t(r.reference_uncertain);
        accurate_skipped += r.accurate_skipped;
        known_open += r.known > 0;
        if (r.violations.empty()) return;
        ++findings;
        for (const fuzz::Violation& v : r.violations) ++violated[v.invariant];
        if (examples.size() < findings_kept) examples.push_back(fuzz::finding_text(h, bytes, c));
    }
    void merge(const Tally& o)
    {
        cases += o.cases; usable += o.usable; hits += o.hits; certified += o.certified; uncertain += o.uncertain;
        accurate_skipped += o.accurate_skipped; known_open += o.known_open; findings += o.findings;
        for (const auto& [k, n] : o.violated) violated[k] += n;
        for (const auto& e : o.examples)
            if (examples.size() < findings_kept) examples.push_back(e);
    }
    json to_json() const
    {
        return {{"cases", cases}, {"usable", usable}, {"policy_hits", hits}, {"certified", certified},
                {"reference_uncertain", uncertain}, {"accurate_skipped", accurate_skipped}, {"known_open", known_open},
                {"findings", findings}, {"violated", violated}, {"examples", examples}};
    }
    static Tally from_json(const json& j)
    {
        Tally t;
        t.cases = j.at("cases"); t.usable = j.at("usable"); t.hits = j.at("policy_hits"); t.certified = j.at("certified");
        t.uncertain = j.at("reference_uncertain"); t.accurate_skipped = j.at("accurate_skipped");
        t.known_open = j.at("known_open"); t.findings = j.at("findings");
        t.violated = j.at("violated").get<std::map<std::string, std::uint64_t>>();
        t.examples = j.at("examples").get<std::vector<std::string>>();
        return t;
    }
};

// One raw row (the columns of the campaign's csv_header).
void csv_row(std::string& csv, Harness h, const std::string& source, const std::string& input,
             const std::vector<std::uint8_t>& bytes, const fuzz::InputCheck& c)
{
    const fuzz::Checked& r = c.checked;
    std::string invariants;
    for (const fuzz::Violation& v : r.violations) invariants += (invariants.empty() ? "" : ";") + v.invariant;
    csv += std::string(fuzz::harness_name(h)) + "," + source + "," + input + "," + c.construction + "," +
           std::to_string(int(r.usable_ray && r.valid_primitive)) + "," + std::to_string(r.hits) + "," +
           std::to_string(r.certified) + "," + std::to_string(r.reference_uncertain) + "," + std::to_string(int(r.accurate_skipped)) +
           "," + std::to_string(r.known) + "," + invariants + "," + fuzz::hex(bytes) + "," + c.line + "\n";
}

fuzz::Options check_options()
{
    fuzz::Options o;
    // Fixed rather than from RAYQ_FUZZ_STRICT: an item's result must not depend on the environment.
    // Known open violations are counted apart (known_open); accurate is not run where it is known
    // to hang, which would stall the campaign.
    o.skip_known = o.skip_known_hangs = true;
    return o;
}

std::vector<Item> plan(const Settings& s)
{
    std::vector<Item> items;
    for (Harness h : fuzz::all_harnesses) {
        const std::string name = fuzz::harness_name(h);
        for (std::size_t first = 0; first < s.fuzz_cases; first += s.fuzz_chunk) {
            char id[96];
            std::snprintf(id, sizeof id, "%s/generated/%06zu", name.c_str(), first / s.fuzz_chunk);
            items.push_back({id, {{"harness", name}, {"first", first}, {"count", std::min(s.fuzz_chunk, s.fuzz_cases - first)}}});
        }
        if (s.fuzz_corpus_dir.empty()) continue;
        for (const auto& [source, dir] : {std::pair<std::string, std::filesystem::path>{"corpus", s.fuzz_corpus_dir + "/" + name},
                                          {"open", s.fuzz_corpus_dir + "/open/" + name}})
            if (std::filesystem::is_directory(dir))
                items.push_back({name + "/" + source, {{"harness", name}, {"source", source}, {"dir", dir.string()}}});
    }
    return items;
}

struct Input {
    std::string name;  // the case index, or the stored file's name
    std::vector<std::uint8_t> bytes;
};

std::vector<Input> inputs_of(const Settings& s, const Item& item, Harness h)
{
    std::vector<Input> inputs;
    if (item.spec.contains("dir")) {
        std::vector<std::filesystem::path> files;
        for (const auto& e : std::filesystem::directory_iterator(item.spec.at("dir").get<std::string>()))
            if (e.is_regular_file()) files.push_back(e.path());
        std::sort(files.begin(), files.end());
        for (const auto& file : files) {
            std::ifstream in(file, std::ios::binary);
            if (!in) throw std::runtime_error("cannot read " + file.string());
            inputs.push_back({file.filename().string(), {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()}});
        }
    } else {
        const std::size_t first = item.spec.at("first"), count = item.spec.at("count");
        for (std::size_t i = first; i < first + count; ++i) {
            std::mt19937_64 rng(case_seed(s.seed, h, i));
            inputs.push_back({std::to_string(i), fuzz::random_input(rng)});
        }
    }
    return inputs;
}

// Checks the inputs, except those in `excluded`, into tally and csv. Generated inputs get a raw
// row only when they are not clean (a finding, a known open violation, accurate skipped).
void check_inputs(Harness h, const std::string& source, const std::vector<Input>& inputs, const std::set<std::size_t>& excluded,
                  std::atomic<std::uint64_t>* started, Tally& tally, std::string& csv)
{
    const fuzz::Options options = check_options();
    for (std::size_t k = 0; k < inputs.size(); ++k) {
        if (excluded.count(k)) continue;
        started->store(k + 1);
        const fuzz::InputCheck c = fuzz::check_input(h, inputs[k].bytes, options);
        tally.add(c, h, inputs[k].bytes);
        if (source != "generated" || !c.checked.violations.empty() || c.checked.known > 0 || c.checked.accurate_skipped)
            csv_row(csv, h, source, inputs[k].name, inputs[k].bytes, c);
    }
}

// Runs check_inputs in a child process, watched: when one input runs longer than hang_seconds the
// child is killed; when a signal kills it, it is gone. Either way that input becomes a finding of
// its own and the child starts over without it (its counts died with it; hangs and crashes are
// rare, and starting over keeps the result a pure function of the inputs).
json run(const Settings& s, const Item& item, std::string& csv)
{
    const Harness h = harness_named(item.spec.at("harness"));
    const std::string source = item.spec.value("source", "generated");
    const std::vector<Input> inputs = inputs_of(s, item, h);
    void* shared = mmap(nullptr, sizeof(std::atomic<std::uint64_t>), PROT_READ | PROT_WRITE, MAP_SHARED | MAP_ANONYMOUS, -1, 0);
    if (shared == MAP_FAILED) throw std::runtime_error("mmap: " + std::string(std::strerror(errno)));
    auto* started = new (shared) std::atomic<std::uint64_t>(0);  // 1 + the input being checked; 0 before the first
    std::map<std::size_t, fuzz::Violation> failed;                 // inputs that hung or crashed
    std::set<std::size_t> excluded;
    json done;
    while (done.is_null()) {
        const std::filesystem::path out = temporary_path("fuzz.json");
        started->store(0);
        std::fflush(nullptr);  // nothing buffered may be written twice
        const pid_t pid = fork();
        if (pid < 0) throw std::runtime_error("fork: " + std::string(std::strerror(errno)));
        if (pid == 0) {
            Tally tally;
            std::string rows;
            check_inputs(h, source, inputs, excluded, started, tally, rows);
            std::ofstream file(out);
            file << json{{"tally", tally.to_json()}, {"csv", rows}}.dump();
            file.close();
            _exit(file ? 0 : 2);
        }
        int status = 0;
        bool hung = false;
        std::uint64_t seen = 0;
        auto since = std::chrono::steady_clock::now();
        while (waitpid(pid, &status, WNOHANG) == 0) {
            std::this_thread::sleep_for(std::chrono::milliseconds(20));
            if (const std::uint64_t now = started->load(); now != seen) {
                seen = now;
                since = std::chrono::steady_clock::now();
            } else if (std::chrono::duration<double>(std::chrono::steady_clock::now() - since).count() > hang_seconds) {
                kill(pid, SIGKILL);
                waitpid(pid, &status, 0);
                hung = true;
                break;
            }
        }
        const std::uint64_t at = started->load();
        if (!hung && WIFEXITED(status)) {
            if (WEXITSTATUS(status) != 0) throw std::runtime_error("the fuzz worker process could not write " + out.string());
            std::ifstream in(out);
            done = json::parse(in);
        } else if (at == 0) {
            throw std::runtime_error("the fuzz worker process failed before checking an input");
        } else {
            failed[at - 1] = hung ? fuzz::Violation{"hang", "no answer within " + std::to_string(int(hang_seconds)) + " s (killed)"}
                                  : fuzz::Violation{"crash", "the check died of signal " + std::to_string(WTERMSIG(status)) + " (" +
                                                                 strsignal(WTERMSIG(status)) + ")"};
            excluded.insert(at - 1);
        }
        std::filesystem::remove(out);
    }
    munmap(shared, sizeof(std::atomic<std::uint64_t>));
    // Hangs and crashes first: they matter most among the findings shown.
    Tally tally;
    for (const auto& [k, violation] : failed) {
        fuzz::InputCheck c = fuzz::decode_input(h, inputs[k].bytes);
        c.checked.violations.push_back(violation);
        tally.add(c, h, inputs[k].bytes);
        csv_row(csv, h, source, inputs[k].name, inputs[k].bytes, c);
    }
    tally.merge(Tally::from_json(done.at("tally")));
    csv += done.at("csv").get<std::string>();
    return {{"harness", fuzz::harness_name(h)}, {"source", source}, {"tally", tally.to_json()}};
}

json reduce(const Settings& s, const std::vector<json>& results)
{
    // (harness, source) in plan order; the sources of a harness: generated, corpus, open.
    std::map<std::string, std::vector<std::pair<std::string, Tally>>> by_harness;
    for (const json& r : results) {
        auto& sources = by_harness[r.at("harness").get<std::string>()];
        const std::string source = r.at("source");
        const Tally t = Tally::from_json(r.at("tally"));
        const auto it = std::find_if(sources.begin(), sources.end(), [&](const auto& p) { return p.first == source; });
        if (it == sources.end()) sources.emplace_back(source, t);
        else it->second.merge(t);
    }
    json metrics = json::object(), rows = json::array(), tables = json::array();
    std::string findings;
    for (Harness h : fuzz::all_harnesses) {
        const std::string name = fuzz::harness_name(h);
        const auto found = by_harness.find(name);
        if (found == by_harness.end()) continue;  // an incomplete merge
        Tally total;
        json table_rows = json::array();
        const auto table_row = [&](const std::string& label, const Tally& t) {
            std::string violated;
            for (const auto& [invariant, n] : t.violated) violated += (violated.empty() ? "" : ", ") + invariant + " ×" + std::to_string(n);
            table_rows.push_back({label, t.cases, t.usable, t.hits, t.certified, t.uncertain, t.accurate_skipped, t.known_open,
                                  t.findings, violated.empty() ? "–" : violated});
        };
        for (const auto& [source, t] : found->second) {
            total.merge(t);
            json row = t.to_json();
            row.erase("examples");
            row["harness"] = name;
            row["source"] = source;
            rows.push_back(row);
            table_row(source == "generated" ? "generated (seed " + std::to_string(s.seed) + ")"
                                            : "fixtures/fuzz/" + std::string(source == "open" ? "open/" : "") + name,
                      t);
        }
        table_row("all", total);
        const std::string m = "fuzz." + name + ".";
        metrics[m + "cases"] = total.cases;
        metrics[m + "findings"] = total.findings;
        metrics[m + "known_open"] = total.known_open;
        metrics[m + "accurate_skipped"] = total.accurate_skipped;
        tables.push_back({{"title", "Harness " + name + " (" + harness_contents(h) + ")"},
                          {"columns", {"source", "cases", "usable", "policy hits", "t_error confirmed", "reference undecided",
                                       "accurate skipped (known hang)", "known open", "findings", "new violations by invariant"}},
                          {"rows", table_rows}});
        for (const auto& e : total.examples) findings += e;
    }
    const json notes = json::array(
        {{{"title", "First findings (up to " + std::to_string(findings_kept) + " per harness), ready to paste into a fixture file"},
          {"text", findings.empty() ? "None: every invariant held on every input (known open issues aside, counted as known open).\n"
                                    : findings}}});
    return {{"metrics", metrics}, {"rows", rows}, {"tables", tables}, {"notes", notes}};
}

}  // namespace

Campaign fuzz_campaign()
{
    Campaign c;
    c.name = "fuzz";
    c.title = "Edge-case fuzzing: structured random inputs and the stored corpora, every invariant under every policy";
    c.plan = plan;
    c.run = run;
    c.csv_header = "harness,source,input,construction,usable,policy_hits,certified,reference_uncertain,accurate_skipped,"
                   "known_open,violations,bytes,fixture_line";
    c.reduce = reduce;
    c.plots = [](const json&) { return std::vector<Plot>{}; };
    return c;
}

}  // namespace rayq::report
