#include "runner.hpp"

#include <chrono>
#include <cstdio>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>
#include <unistd.h>

namespace rayq::report {

Campaign oracle_campaign();
Campaign mesh_campaign();
Campaign speed_campaign();
Campaign fuzz_campaign();
#ifdef RAYQ_VALIDATE_SWEEP
Campaign sweep_campaign();  // campaign_sweep.cpp, built when rayq::sweep (Ceres) is
#endif

const std::vector<Campaign>& all_campaigns()
{
    static const std::vector<Campaign> campaigns = {oracle_campaign(), mesh_campaign(), speed_campaign()
#ifdef RAYQ_VALIDATE_SWEEP
                                                     , sweep_campaign()
#endif
                                                     , fuzz_campaign()
    };
    return campaigns;
}

double percent(std::uint64_t part, std::uint64_t whole)
{
    return whole == 0 ? 100.0 : 100.0 * static_cast<double>(part) / static_cast<double>(whole);
}

// ---- settings -----------------------------------------------------------------------------------

Settings Settings::preset_named(const std::string& name)
{
    Settings s;
    s.preset = name;
    if (name == "quick") {  // about a minute on 2 cores
        s.oracle_cases = 1000; s.oracle_chunk = 1000; s.oracle_csv_cases = 1000; s.mesh_rays = 400; s.mesh_max_n = 32;
        s.precision_preset = "quick"; s.bench_min_time = 0.01; s.fuzz_cases = 5000; s.fuzz_chunk = 5000;
    } else if (name == "default") {  // under 10 minutes on 2 cores
        s.oracle_cases = 10000; s.oracle_chunk = 2500; s.oracle_csv_cases = 10000; s.mesh_rays = 3000; s.mesh_max_n = 128;
        s.precision_preset = "default"; s.bench_min_time = 0.1; s.fuzz_cases = 100000; s.fuzz_chunk = 25000;
    } else if (name == "full") {  // the big campaign: 10^6 cases per primitive and type
        s.oracle_cases = 1000000; s.oracle_chunk = 20000; s.oracle_csv_cases = 10000; s.mesh_rays = 20000; s.mesh_max_n = 512;
        s.precision_preset = "full"; s.bench_min_time = 0.5; s.fuzz_cases = 10000000; s.fuzz_chunk = 200000;
    } else {
        throw std::invalid_argument("unknown preset '" + name + "' (expected quick, default or full)");
    }
    return s;
}

// ---- files --------------------------------------------------------------------------------------

void write_file_atomically(const std::filesystem::path& path, const std::string& text)
{
    const std::filesystem::path tmp = path.string() + ".tmp" + std::to_string(getpid());
    {
        std::ofstream out(tmp, std::ios::binary);
        if (!out) throw std::runtime_error("cannot write " + tmp.string());
        out << text;
        out.close();
        if (!out) throw std::runtime_error("cannot write " + tmp.string() + " (disk full?)");
    }
    std::error_code ec;
    std::filesystem::rename(tmp, path, ec);
    if (ec) throw std::runtime_error("cannot rename " + tmp.string() + " to " + path.string() + ": " + ec.message());
}

namespace {

std::string file_stem(const std::string& item_id)
{
    std::string s = item_id;
    for (char& c : s)
        if (c == '/') c = '~';
    return s;
}

std::filesystem::path item_path(const std::filesystem::path& out, const std::string& campaign, const std::string& id,
                                const char* ext)
{
    return out / "items" / campaign / (file_stem(id) + ext);
}

json read_json(const std::filesystem::path& path)
{
    std::ifstream in(path);
    if (!in) throw std::runtime_error(path.string() + ": cannot open");
    try {
        return json::parse(in);
    } catch (const json::parse_error& e) {
        throw std::runtime_error(path.string() + ": not valid JSON (" + e.what() + ")");
    }
}

std::string read_text(const std::filesystem::path& path)
{
    std::ifstream in(path, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

// Progress on stderr: a bar with rate and ETA on a terminal, plain lines otherwise.
class Progress {
public:
    Progress(std::string name, std::size_t total)
        : name_(std::move(name)), total_(total), tty_(isatty(STDERR_FILENO) != 0), start_(clock::now()) {}

    void item_done(const std::string& id, bool reused)
    {
        ++done_;
        const double elapsed = std::chrono::duration<double>(clock::now() - start_).count();
        const double rate = elapsed > 0 ? static_cast<double>(done_) / elapsed : 0;
        const double eta = rate > 0 ? static_cast<double>(total_ - done_) / rate : 0;
        if (tty_) {
            const int width = 30, filled = total_ ? static_cast<int>(width * done_ / total_) : width;
            std::fprintf(stderr, "\r[%s] [%s%s] %zu/%zu items  %.2f items/s  ETA %d:%02d ", name_.c_str(),
                         std::string(static_cast<std::size_t>(filled), '#').c_str(),
                         std::string(static_cast<std::size_t>(width - filled), '.').c_str(), done_, total_, rate,
                         static_cast<int>(eta) / 60, static_cast<int>(eta) % 60);
            if (done_ == total_) std::fprintf(stderr, "\n");
        } else {
            std::fprintf(stderr, "[%s] %zu/%zu %s%s (%.1f s elapsed, ETA %.0f s)\n", name_.c_str(), done_, total_,
                         id.c_str(), reused ? " (resumed)" : "", elapsed, eta);
        }
        std::fflush(stderr);
    }

private:
    using clock = std::chrono::steady_clock;
    std::string name_;
    std::size_t total_, done_ = 0;
    bool tty_;
    clock::time_point start_;
};

}  // namespace

// ---- one shard ----------------------------------------------------------------------------------

json run_shard(const RunOptions& o)
{
    if (o.shards < 1 || o.shard < 0 || o.shard >= o.shards) throw std::invalid_argument("bad shard");
    const json settings = o.settings.to_json();
    json campaigns = json::object();
    for (const Campaign& c : all_campaigns()) {
        if (!o.selected.count(c.name)) continue;
        const std::vector<Item> items = c.plan(o.settings);
        std::vector<const Item*> mine;
        for (std::size_t i = 0; i < items.size(); ++i)
            if (static_cast<int>(i % static_cast<std::size_t>(o.shards)) == o.shard) mine.push_back(&items[i]);
        std::filesystem::create_directories(o.out / "items" / c.name);
        Progress progress(c.name, mine.size());
        json results = json::object();
        for (const Item* item : mine) {
            const auto result_file = item_path(o.out, c.name, item->id, ".json");
            const auto csv_file = item_path(o.out, c.name, item->id, ".csv");
            bool reused = false;
            if (o.resume && std::filesystem::exists(result_file) && std::filesystem::exists(csv_file)) {
                const json cached = read_json(result_file);
                if (cached.value("settings", json()) == settings && cached.value("spec", json()) == item->spec) {
                    results[item->id] = cached.at("result");
                    reused = true;
                }
            }
            if (!reused) {
                std::string csv;
                json result;
                try {
                    result = c.run(o.settings, *item, csv);
                } catch (const std::exception& e) {
                    throw std::runtime_error(c.name + " item " + item->id + ": " + e.what());
                }
                // The CSV first: an item counts as finished only when its result file exists.
                write_file_atomically(csv_file, csv);
                write_file_atomically(result_file, json{{"settings", settings}, {"spec", item->spec}, {"result", result}}.dump());
                results[item->id] = std::move(result);
            }
            progress.item_done(item->id, reused);
        }
        campaigns[c.name] = {{"planned", items.size()}, {"items", results}};
    }
    json selected = json::array();
    for (const auto& s : o.selected) selected.push_back(s);
    json partial = {{"schema", "rayq-validate-partial"}, {"version", format_version}, {"settings", settings},
                    {"selected", selected}, {"shard", {{"index", o.shard}, {"count", o.shards}}},
                    {"campaigns", campaigns}};
    write_file_atomically(o.out / "partial.json", partial.dump());
    return partial;
}

Partial read_partial(const std::filesystem::path& dir)
{
    const auto file = dir / "partial.json";
    if (!std::ifstream(file)) throw std::runtime_error(file.string() + ": cannot open");
    return {parse_partial(read_text(file), file.string()), dir};
}

// ---- merge --------------------------------------------------------------------------------------

json merge(const std::vector<Partial>& partials, const std::filesystem::path& out)
{
    if (partials.empty()) throw std::runtime_error("nothing to merge");
    const json settings_json = partials.front().summary.at("settings");
    const json selected = partials.front().summary.at("selected");
    for (const Partial& p : partials) {
        if (p.summary.at("settings") != settings_json)
            throw std::runtime_error((p.dir / "partial.json").string() + ": made with other settings than " +
                                     (partials.front().dir / "partial.json").string());
        if (p.summary.at("selected") != selected)
            throw std::runtime_error((p.dir / "partial.json").string() + ": ran other campaigns than " +
                                     (partials.front().dir / "partial.json").string());
    }
    const Settings settings = Settings::from_json(settings_json);
    std::filesystem::create_directories(out / "data");

    json campaigns = json::object(), sections = json::object();
    for (const Campaign& c : all_campaigns()) {
        json entry = {{"title", c.title}, {"deterministic", c.deterministic}};
        bool was_selected = false;
        for (const auto& s : selected) was_selected |= s == c.name;
        if (!was_selected) {
            entry["status"] = "skipped";
            campaigns[c.name] = entry;
            continue;
        }
        const std::vector<Item> items = c.plan(settings);
        std::map<std::string, std::pair<const json*, const Partial*>> found;
        for (const Partial& p : partials) {
            const json& cj = p.summary.at("campaigns").at(c.name);
            if (cj.at("planned").get<std::size_t>() != items.size())
                throw std::runtime_error((p.dir / "partial.json").string() + ": campaign " + c.name + " planned " +
                                         cj.at("planned").dump() + " items, this build plans " + std::to_string(items.size()));
            for (const auto& [id, result] : cj.at("items").items()) {
                auto [it, inserted] = found.emplace(id, std::make_pair(&result, &p));
                if (!inserted && c.deterministic && *it->second.first != result)
                    throw std::runtime_error("campaign " + c.name + ", item " + id + ": shards " + it->second.second->dir.string() +
                                             " and " + p.dir.string() + " disagree");
            }
        }
        std::vector<json> results;
        std::string csv = c.csv_header + "\n";
        for (const Item& item : items) {
            const auto it = found.find(item.id);
            if (it == found.end()) continue;
            results.push_back(*it->second.first);
            csv += read_text(item_path(it->second.second->dir, c.name, item.id, ".csv"));
        }
        write_file_atomically(out / "data" / (c.name + ".csv"), csv);
        entry["items_planned"] = items.size();
        entry["items_done"] = results.size();
        entry["status"] = results.size() == items.size() ? "ran" : "incomplete";
        try {
            entry["section"] = c.reduce(settings, results);
        } catch (const json::exception& e) {  // parse_partial checks the structure, not each campaign's item results
            std::string dirs;
            for (const Partial& p : partials) dirs += " " + (p.dir / "partial.json").string();
            throw std::runtime_error("campaign " + c.name + ": an item result in" + dirs + " is not what this build writes (" + e.what() + ")");
        }
        campaigns[c.name] = entry;
    }
    json shards = json::array();
    for (const Partial& p : partials) shards.push_back(p.summary.at("shard"));
    return {{"schema", "rayq-validate-summary"}, {"version", format_version}, {"settings", settings_json},
            {"campaigns", campaigns}, {"shards", shards}};
}

}  // namespace rayq::report
