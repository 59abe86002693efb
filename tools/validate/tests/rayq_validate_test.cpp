// rayq-validate end to end (issue 8): the --quick report, its schema, gates and the exit status,
// shard/merge identity, resume, bad input, the fuzz campaign, Embree in the speed campaign (or its
// absence), and the page in headless Chromium. Runs the real program; nothing is mocked.
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <sys/wait.h>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

namespace fs = std::filesystem;
using json = nlohmann::json;

namespace {

const std::string program = RAYQ_VALIDATE_BINARY;
// The running suite's own directory under RAYQ_TEST_WORK_DIR: ctest runs the two suites below as
// two processes at once (validate.quick_report and validate.standalone_runs).
fs::path work;

struct Result {
    int status;
    std::string output;  // stdout and stderr
};

Result run(const std::string& args)
{
    const std::string command = program + " " + args + " 2>&1";
    FILE* pipe = popen(command.c_str(), "r");
    std::string output;
    char buf[4096];
    while (std::size_t n = std::fread(buf, 1, sizeof buf, pipe)) output.append(buf, n);
    const int status = pclose(pipe);
    return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, output};
}

json read_json(const fs::path& p)
{
    std::ifstream in(p);
    return json::parse(in);
}

std::string read_text(const fs::path& p)
{
    std::ifstream in(p);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

// A small JSON Schema validator: the subset summary.schema.json uses (type, const, enum,
// required, properties, additionalProperties, items). Returns the first violation, "" if none.
std::string violation(const json& schema, const json& v, const std::string& at)
{
    if (schema.contains("const") && v != schema["const"]) return at + ": expected " + schema["const"].dump();
    if (schema.contains("enum")) {
        bool found = false;
        for (const json& e : schema["enum"]) found |= e == v;
        if (!found) return at + ": " + v.dump() + " not in " + schema["enum"].dump();
    }
    if (schema.contains("type")) {
        const std::string t = schema["type"];
        const bool ok = (t == "object" && v.is_object()) || (t == "array" && v.is_array()) ||
                        (t == "string" && v.is_string()) || (t == "boolean" && v.is_boolean()) ||
                        (t == "integer" && v.is_number_integer()) || (t == "number" && v.is_number());
        if (!ok) return at + ": expected " + t + ", got " + v.dump().substr(0, 60);
    }
    if (v.is_object()) {
        for (const json& r : schema.value("required", json::array()))
            if (!v.contains(r.get<std::string>())) return at + ": missing \"" + r.get<std::string>() + "\"";
        for (const auto& [k, sub] : v.items()) {
            if (schema.contains("properties") && schema["properties"].contains(k)) {
                if (auto e = violation(schema["properties"][k], sub, at + "." + k); !e.empty()) return e;
            } else if (schema.contains("additionalProperties") && schema["additionalProperties"].is_object()) {
                if (auto e = violation(schema["additionalProperties"], sub, at + "." + k); !e.empty()) return e;
            }
        }
    }
    if (v.is_array() && schema.contains("items"))
        for (std::size_t i = 0; i < v.size(); ++i)
            if (auto e = violation(schema["items"], v[i], at + "[" + std::to_string(i) + "]"); !e.empty()) return e;
    return "";
}

// The deterministic part of a summary: what one run and merged shards must share.
json results_of(json summary)
{
    summary.erase("run");
    summary.erase("shards");
    for (auto it = summary["campaigns"].begin(); it != summary["campaigns"].end(); ++it)
        if (!(*it)["deterministic"].get<bool>()) it->erase("section");
    return summary;
}

const std::string small = "--only oracle --only mesh --oracle-cases 120 --mesh-rays 120 --mesh-max-n 16 --seed 5";
const char* const harnesses[] = {"flat", "sphere", "axial", "quadric", "transformed"};
// Gates both of which pass when their campaigns run; the second is on the mesh campaign.
const char* const passing_gates = "oracle.accurate.contract_scope.max_ulp <= 1\nmesh.disagreements == 0\n";

void use_fresh_work_directory(const char* suite)
{
    work = fs::path(RAYQ_TEST_WORK_DIR) / suite;
    fs::remove_all(work);
    fs::create_directories(work);
}

// The tests that read one shared --quick run.
class RayqValidate : public ::testing::Test {
protected:
    static void SetUpTestSuite()
    {
        use_fresh_work_directory("quick_report");
        quick_ = new Result(run("--quick --out " + (work / "quick").string()));
    }
    static void TearDownTestSuite() { delete quick_; }
    static Result* quick_;
};
Result* RayqValidate::quick_ = nullptr;

// The tests that make their own runs.
class RayqValidateStandalone : public ::testing::Test {
protected:
    static void SetUpTestSuite() { use_fresh_work_directory("standalone_runs"); }
};

}  // namespace

TEST_F(RayqValidate, QuickRunWritesACompleteReportMatchingTheSchema)
{
    const fs::path out = work / "quick";
    ASSERT_TRUE(fs::exists(out / "summary.json")) << quick_->output;
    const json summary = read_json(out / "summary.json");
    const json schema = read_json(RAYQ_SUMMARY_SCHEMA);
    EXPECT_EQ(violation(schema, summary, "summary"), "");
    // Every campaign ran with all its items.
    for (const auto& [name, c] : summary["campaigns"].items()) {
        EXPECT_EQ(c["status"], "ran") << name;
        EXPECT_EQ(c["items_done"], c["items_planned"]) << name;
        EXPECT_FALSE(c["section"]["metrics"].empty()) << name;
        const std::string csv = read_text(out / "data" / (name + ".csv"));
        EXPECT_GT(std::count(csv.begin(), csv.end(), '\n'), 1) << name << ": raw data has rows";
    }
    // The exit status is the gates' verdict.
    EXPECT_EQ(quick_->status, summary["gates"]["failed"].get<int>() > 0 ? 1 : 0) << quick_->output;
    // No temporary file left behind; the page embeds every plot it announces.
    for (const auto& e : fs::recursive_directory_iterator(out))
        EXPECT_EQ(e.path().string().find(".tmp"), std::string::npos) << e.path();
    const std::string html = read_text(out / "index.html");
    std::smatch m;
    ASSERT_TRUE(std::regex_search(html, m, std::regex("data-plots=\"([0-9]+)\"")));
    const int plots = std::stoi(m[1]);
    EXPECT_GE(plots, 8);
    std::size_t svgs = 0;
    for (std::size_t at = 0; (at = html.find("<svg", at)) != std::string::npos; ++at) ++svgs;
    EXPECT_EQ(svgs, static_cast<std::size_t>(plots));
    EXPECT_NE(html.find(summary["run"]["command"].get<std::string>()), std::string::npos) << "the command line is on the page";
}

TEST_F(RayqValidate, GatesDecideTheExitStatus)
{
    const fs::path quick = work / "quick";
    ASSERT_TRUE(fs::exists(quick / "partial.json"));
    std::ofstream(work / "failing.txt") << "oracle.accurate.contract_scope.max_ulp <= 0.25   # deliberately impossible: correct rounding is 0.5\n";
    std::ofstream(work / "passing.txt") << passing_gates;
    std::ofstream(work / "nomatch.txt") << "oracle.accurate.no_such_metric <= 1\n";

    Result r = run("merge --out " + (work / "regated").string() + " --gates " + (work / "failing.txt").string() + " " + quick.string());
    EXPECT_EQ(r.status, 1) << r.output;
    EXPECT_NE(r.output.find("FAIL oracle.accurate.contract_scope.max_ulp"), std::string::npos) << r.output;
    r = run("merge --out " + (work / "regated").string() + " --gates " + (work / "passing.txt").string() + " " + quick.string());
    EXPECT_EQ(r.status, 0) << r.output;
    r = run("merge --out " + (work / "regated").string() + " --gates " + (work / "nomatch.txt").string() + " " + quick.string());
    EXPECT_EQ(r.status, 1) << "a gate that matches nothing fails: " << r.output;
}

TEST_F(RayqValidateStandalone, AGateOnACampaignThatDidNotRunIsSkippedNeverPassed)
{
    // A run without the mesh campaign: its gate is skipped, not passed.
    std::ofstream(work / "passing.txt") << passing_gates;
    const Result r = run(small + " --skip mesh --out " + (work / "nomesh").string() + " --gates " + (work / "passing.txt").string());
    ASSERT_TRUE(fs::exists(work / "nomesh" / "summary.json")) << r.output;
    const json s = read_json(work / "nomesh" / "summary.json");
    EXPECT_EQ(s["campaigns"]["mesh"]["status"], "skipped");
    EXPECT_EQ(s["gates"]["results"][1]["status"], "skipped");
    EXPECT_EQ(s["gates"]["skipped"], 1);
}

TEST_F(RayqValidateStandalone, FourShardsMergedEqualOneRun)
{
    const std::string sharded = small + " --only fuzz --fuzz-cases 40";  // the fuzz campaign shards too
    Result one = run(sharded + " --out " + (work / "one").string());
    ASSERT_TRUE(one.status == 0 || one.status == 1) << one.output;
    std::string dirs;
    for (int i = 0; i < 4; ++i) {
        const fs::path d = work / ("shard" + std::to_string(i));
        Result r = run(sharded + " --shard " + std::to_string(i) + "/4 --out " + d.string());
        ASSERT_EQ(r.status, 0) << r.output;
        EXPECT_FALSE(fs::exists(d / "summary.json")) << "a shard writes partial results only";
        dirs += " " + d.string();
    }
    Result merged = run("merge --out " + (work / "merged").string() + dirs);
    EXPECT_EQ(merged.status, one.status) << merged.output;
    const json a = results_of(read_json(work / "one" / "summary.json"));
    const json b = results_of(read_json(work / "merged" / "summary.json"));
    EXPECT_EQ(a, b) << "one run and four merged shards differ";
    EXPECT_EQ(read_text(work / "one" / "data" / "oracle.csv"), read_text(work / "merged" / "data" / "oracle.csv"));
    EXPECT_EQ(read_text(work / "one" / "data" / "fuzz.csv"), read_text(work / "merged" / "data" / "fuzz.csv"));
    EXPECT_EQ(a["campaigns"]["fuzz"]["status"], "ran");

    // Three of four shards: the campaigns are incomplete and their gates skipped, never passed.
    run("merge --out " + (work / "three").string() + " " + (work / "shard0").string() + " " +
                         (work / "shard1").string() + " " + (work / "shard2").string());
    const json t = read_json(work / "three" / "summary.json");
    EXPECT_EQ(t["campaigns"]["oracle"]["status"], "incomplete");
    for (const json& g : t["gates"]["results"]) {
        if (g["metric"].get<std::string>().rfind("oracle.", 0) == 0) {
            EXPECT_EQ(g["status"], "skipped") << g.dump();
        }
    }
}

TEST_F(RayqValidateStandalone, AnInterruptedRunResumesWithoutRedoingFinishedItems)
{
    const fs::path d = work / "resume";
    Result first = run(small + " --only oracle --skip mesh --out " + d.string());
    ASSERT_TRUE(fs::exists(d / "summary.json")) << first.output;
    const json before = results_of(read_json(d / "summary.json"));
    // Lose one item's result, as if the run had stopped before it finished.
    const fs::path items = d / "items" / "oracle";
    const fs::path victim = fs::directory_iterator(items)->path();
    const fs::path json_file = victim.extension() == ".json" ? victim : fs::path(victim).replace_extension(".json");
    fs::remove(json_file);
    Result second = run(small + " --only oracle --skip mesh --out " + d.string());
    auto occurrences = [](const std::string& text, const std::string& word) {
        std::size_t n = 0;
        for (std::size_t at = 0; (at = text.find(word, at)) != std::string::npos; at += word.size()) ++n;
        return n;
    };
    const std::size_t planned = read_json(d / "summary.json")["campaigns"]["oracle"]["items_planned"];
    EXPECT_EQ(occurrences(first.output, "(resumed)"), 0u) << first.output;
    EXPECT_EQ(occurrences(second.output, "(resumed)"), planned - 1) << "every finished item is reused, the lost one redone:\n"
                                                                   << second.output;
    EXPECT_EQ(results_of(read_json(d / "summary.json")), before);
}

TEST_F(RayqValidate, BadInputGetsAClearMessageAndExitStatus2)
{
    Result r = run("--bogus");
    EXPECT_EQ(r.status, 2);
    EXPECT_NE(r.output.find("unknown option '--bogus'"), std::string::npos) << r.output;

    r = run("--quick --out /proc/rayq-cannot-write-here");
    EXPECT_EQ(r.status, 2);
    EXPECT_NE(r.output.find("cannot write the output directory"), std::string::npos) << r.output;

    std::ofstream(work / "bad_gates.txt") << "# fine\noracle.accurate.contract_scope.max_ulp <= 1\nmesh.disagreements =< 0\n";
    r = run(small + " --out " + (work / "x").string() + " --gates " + (work / "bad_gates.txt").string());
    EXPECT_EQ(r.status, 2);
    EXPECT_NE(r.output.find("bad_gates.txt:3: expected an operator"), std::string::npos) << r.output;

    fs::create_directories(work / "bad_fixtures");
    std::ofstream(work / "bad_fixtures" / "sphere.txt") << "# a comment\nsphere double generic 0x1p+0\n";
    r = run(small + " --out " + (work / "x").string() + " --fixtures " + (work / "bad_fixtures").string());
    EXPECT_EQ(r.status, 2);
    EXPECT_NE(r.output.find("sphere.txt:2: expected"), std::string::npos) << r.output;

    fs::create_directories(work / "not_a_shard");
    std::ofstream(work / "not_a_shard" / "partial.json") << "{\"schema\": \"something-else\"}";
    r = run("merge --out " + (work / "x").string() + " " + (work / "not_a_shard").string());
    EXPECT_EQ(r.status, 2);
    EXPECT_NE(r.output.find("partial.json: expected a rayq-validate partial summary"), std::string::npos) << r.output;

    // A partial of the right schema whose fields do not hold what merge reads: named, not a crash.
    const fs::path quick = work / "quick";
    ASSERT_TRUE(fs::exists(quick / "partial.json"));
    json mistyped = read_json(quick / "partial.json");
    mistyped["settings"]["seed"] = -1;
    std::ofstream(work / "not_a_shard" / "partial.json") << mistyped.dump();
    r = run("merge --out " + (work / "x").string() + " " + (work / "not_a_shard").string());
    EXPECT_EQ(r.status, 2);
    EXPECT_NE(r.output.find("partial.json: expected settings.seed to be a count (a non-negative integer), got -1"), std::string::npos) << r.output;
    mistyped = read_json(quick / "partial.json");
    mistyped["campaigns"].erase("oracle");
    std::ofstream(work / "not_a_shard" / "partial.json") << mistyped.dump();
    r = run("merge --out " + (work / "x").string() + " " + (work / "not_a_shard").string());
    EXPECT_EQ(r.status, 2);
    EXPECT_NE(r.output.find("partial.json: expected a \"oracle\" field in campaigns"), std::string::npos) << r.output;

    r = run("--shard 4/4 --out " + (work / "x").string());
    EXPECT_EQ(r.status, 2) << r.output;
}

TEST_F(RayqValidate, TheFuzzCampaignReportsEveryHarnessAndIsGated)
{
    const fs::path out = work / "quick";
    ASSERT_TRUE(fs::exists(out / "summary.json")) << quick_->output;
    const json summary = read_json(out / "summary.json");
    const json& fuzz = summary["campaigns"]["fuzz"];
    ASSERT_EQ(fuzz["status"], "ran");
    const json& metrics = fuzz["section"]["metrics"];
    for (const char* h : harnesses) {
        const std::string m = std::string("fuzz.") + h + ".";
        for (const char* k : {"cases", "findings", "known_open", "accurate_skipped"})
            EXPECT_TRUE(metrics.contains(m + k)) << m + k;
        // the preset's generated cases plus the stored corpus
        EXPECT_GT(metrics.value(m + "cases", 0), summary["settings"]["fuzz_cases"].get<int>()) << h;
    }
    bool gated = false;
    for (const json& g : summary["gates"]["results"])
        if (g["metric"] == "fuzz.*.findings") {
            gated = true;
            EXPECT_NE(g["status"], "skipped");
            EXPECT_EQ(g["values"].size(), 5u);
        }
    EXPECT_TRUE(gated) << "gates.txt gates fuzz.*.findings";
    const std::string html = read_text(out / "index.html");
    for (const char* h : harnesses) EXPECT_NE(html.find(std::string("Harness ") + h + " ("), std::string::npos) << h;
    EXPECT_NE(html.find("First findings"), std::string::npos);
    // Every finding shown is a ready-to-paste fixture line after its comments.
    const std::string notes = fuzz["section"]["notes"][0]["text"];
    std::istringstream lines(notes);
    for (std::string line; std::getline(lines, line);) {
        if (!line.empty() && line[0] != '#' && line.rfind("None", 0) != 0) {
            EXPECT_EQ(line.rfind("fuzz.", 0), 0u) << line;
        }
    }
}

TEST_F(RayqValidateStandalone, ASkippedFuzzCampaignShowsAsSkipped)
{
    std::ofstream(work / "fuzz_gate.txt") << "fuzz.*.findings == 0\n";
    const fs::path out = work / "nofuzz";
    const Result r = run("--only mesh --mesh-rays 20 --mesh-max-n 8 --out " + out.string() + " --gates " + (work / "fuzz_gate.txt").string());
    EXPECT_EQ(r.status, 0) << "a skipped gate neither passes nor fails the run: " << r.output;
    const json s = read_json(out / "summary.json");
    EXPECT_EQ(s["campaigns"]["fuzz"]["status"], "skipped");
    EXPECT_FALSE(s["campaigns"]["fuzz"].contains("section"));
    EXPECT_EQ(s["gates"]["results"][0]["status"], "skipped");
    EXPECT_EQ(s["gates"]["passed"], 0);
    const std::string html = read_text(out / "index.html");
    EXPECT_NE(html.find("<h2 id=\"fuzz\">"), std::string::npos);
    EXPECT_NE(html.find("skipped</small>", html.find("<h2 id=\"fuzz\">")), std::string::npos);
}

// Embree in the speed campaign: measured against the exact oracle when rayq-bench-embree is built;
// otherwise its part shows as skipped and gates on it are skipped, never passed.
TEST_F(RayqValidate, EmbreeIsMeasuredOrShownAsSkipped)
{
    const json summary = read_json(work / "quick" / "summary.json");
    const json& speed = summary["campaigns"]["speed"]["section"];
    const std::string html = read_text(work / "quick" / "index.html");
    bool embree_skipped = false;
    for (const json& part : speed.value("skipped_metrics", json::array())) embree_skipped |= part["prefix"] == "speed.embree.";
    if (embree_skipped) {
        EXPECT_NE(html.find("rayq-bench-embree: skipped"), std::string::npos);
    } else {
        for (const char* k : {"embree_points", "fast", "stable", "accurate"})
            EXPECT_TRUE(speed["metrics"].contains(std::string("speed.embree.accuracy.") + k + ".p99_ulp")) << k;
        EXPECT_TRUE(speed["metrics"].contains("speed.embree.rayq_embree_stable_over_points.100000"));
        EXPECT_NE(html.find("Embree (rayq-bench-embree): M rays/s"), std::string::npos);
        EXPECT_EQ(speed["embree"]["pareto"].size(), 4u) << "Embree and rayq's policies on the Pareto plot";
    }
}

// The issue-7 targets: each reads the same-round values of a targets_* program (its -march=native
// copy when built, else the portable program, which a note says); "met" is the median reaching the
// target, and speed.target_margins.* is the value over the target.
TEST_F(RayqValidate, IssueSevenTargetsAreReported)
{
    const json summary = read_json(work / "quick" / "summary.json");
    const json& speed = summary["campaigns"]["speed"]["section"];
    const std::string html = read_text(work / "quick" / "index.html");
    std::set<std::string> note_titles;
    for (const json& note : speed.value("notes", json::array())) note_titles.insert(note["title"].get<std::string>());
    std::set<std::string> keys;
    for (const json& t : speed.at("targets")) {
        const std::string key = t["key"];
        keys.insert(key);
        const double value = t["value"], lo = t["min"], hi = t["max"], at_least = t["at_least"];
        EXPECT_GT(lo, 0) << key;
        EXPECT_LE(lo, value) << key;
        EXPECT_LE(value, hi) << key;
        EXPECT_EQ(t["met"].get<bool>(), value >= at_least) << key;
        EXPECT_DOUBLE_EQ(speed["metrics"].value("speed.targets." + key, 0.0), value) << key;
        EXPECT_DOUBLE_EQ(speed["metrics"].value("speed.target_margins." + key, 0.0), value / at_least) << key;
    }
    const bool scene_ran = !note_titles.count("rayq-bench-scene (issue-7 targets): skipped");
    const bool embree_ran = !note_titles.count("rayq-bench-embree (issue-7 targets): skipped");
    if (scene_ran) {
        EXPECT_TRUE(keys.count("sphere_float_fast_gtests"));
        EXPECT_TRUE(keys.count("any_over_closest.sphere_float_fast"));
    }
    if (embree_ran) {
        ASSERT_TRUE(keys.count("sphere_16_over_embree"));
        // Recomputed from the rows: Embree's time over rayq's, round by round, then the median.
        std::map<std::string, std::vector<double>> rounds;
        for (const json& row : speed["rows"])
            if (row["program"] == "targets_embree") rounds[row["name"]] = row["rounds"].get<std::vector<double>>();
        const auto& embree = rounds.at("sphere/embree_points/16");
        const auto& rayq = rounds.at("sphere/rayq_scene_fast_shading/16");
        ASSERT_EQ(embree.size(), 5u);
        ASSERT_EQ(rayq.size(), 5u);
        std::vector<double> ratio;
        for (std::size_t i = 0; i < 5; ++i) ratio.push_back(embree[i] / rayq[i]);
        std::sort(ratio.begin(), ratio.end());
        EXPECT_DOUBLE_EQ(speed["metrics"]["speed.targets.sphere_16_over_embree"].get<double>(), ratio[2]);
    }
    if (scene_ran || embree_ran) {
        EXPECT_NE(html.find("Issue-7 targets ("), std::string::npos);
        for (const json& t : speed["targets"])
            if (!t["native"].get<bool>()) {
                bool noted = false;
                for (const std::string& title : note_titles) noted |= title.find(": portable build") != std::string::npos;
                EXPECT_TRUE(noted) << "a target measured on the portable build says so";
            }
    }
}

TEST_F(RayqValidateStandalone, WithoutBenchmarkProgramsTheSpeedCampaignShowsThemSkipped)
{
    // No benchmark program at all (RAYQ_TOOLS_DIR names an empty directory): the speed campaign
    // still runs, every program shows as skipped, and a gate on Embree's metrics is skipped.
    fs::create_directories(work / "no_tools");
    std::ofstream(work / "embree_gate.txt") << "speed.embree.rayq_embree_stable_over_points.* >= 0.7\n";
    const fs::path out = work / "no_embree";
    const std::string command = "RAYQ_TOOLS_DIR=" + (work / "no_tools").string() + " " + program + " --quick --only speed --out " +
                                out.string() + " --gates " + (work / "embree_gate.txt").string() + " 2>&1";
    ASSERT_EQ(std::system(command.c_str()), 0);
    const json s = read_json(out / "summary.json");
    EXPECT_EQ(s["campaigns"]["speed"]["status"], "ran");
    EXPECT_EQ(s["gates"]["results"][0]["status"], "skipped");
    EXPECT_NE(s["gates"]["results"][0]["reason"].get<std::string>().find("rayq-bench-embree is not built"), std::string::npos);
    EXPECT_NE(read_text(out / "index.html").find("rayq-bench-embree: skipped"), std::string::npos);
}

TEST_F(RayqValidate, TheSweepCampaignPlotsTheMisclassificationBand)
{
    const json summary = read_json(work / "quick" / "summary.json");
    if (!summary["campaigns"].contains("sweep")) GTEST_SKIP() << "built without the sweep campaign (Ceres)";
    const std::string html = read_text(work / "quick" / "index.html");
    for (const char* type : {"double", "float"})
        EXPECT_NE(html.find(std::string("Misclassification band: wrong hit/miss against δ toward tangency, sphere, ") + type),
                  std::string::npos) << type;
}

TEST_F(RayqValidate, ThePageRendersEveryPlotInHeadlessChromium)
{
    const fs::path page = work / "quick" / "index.html";
    ASSERT_TRUE(fs::exists(page));
    const std::string chromium = "chromium --headless --no-sandbox --disable-gpu --hide-scrollbars --virtual-time-budget=5000 ";
    FILE* pipe = popen((chromium + "--dump-dom file://" + page.string() + " 2>/dev/null").c_str(), "r");
    std::string dom;
    char buf[65536];
    while (std::size_t n = std::fread(buf, 1, sizeof buf, pipe)) dom.append(buf, n);
    ASSERT_EQ(pclose(pipe), 0) << "chromium failed";
    std::smatch expected, rendered;
    ASSERT_TRUE(std::regex_search(dom, expected, std::regex("data-plots-expected=\"([0-9]+)\""))) << "the page's check script did not run";
    ASSERT_TRUE(std::regex_search(dom, rendered, std::regex("data-plots-rendered=\"([0-9]+)\"")));
    EXPECT_EQ(rendered[1], expected[1]) << "plots with an empty box";
    EXPECT_GE(std::stoi(rendered[1]), 8);

    const fs::path shot = work / "screenshot.png";
    fs::remove(shot);
    const int status = std::system((chromium + "--window-size=1280,4000 --screenshot=" + shot.string() + " file://" +
                                    page.string() + " >/dev/null 2>&1").c_str());
    EXPECT_EQ(status, 0);
    ASSERT_TRUE(fs::exists(shot));
    EXPECT_GT(fs::file_size(shot), 50000u) << "a blank page would compress to almost nothing";
}
