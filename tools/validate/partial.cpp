#include "partial.hpp"

#include <limits>
#include <stdexcept>

namespace rayq::report {

namespace {

// Typed field access with a message naming the field and the type expected. nlohmann's own
// get<T>() converts a float or a negative number to an unsigned type with a plain cast, which is
// undefined behaviour out of range.
const json& field(const json& j, const char* key, const std::string& where)
{
    if (!j.is_object()) throw std::invalid_argument("expected " + where + " to be an object");
    const auto it = j.find(key);
    if (it == j.end()) throw std::invalid_argument("expected a \"" + std::string(key) + "\" field in " + where);
    return *it;
}

template <class Unsigned>
Unsigned unsigned_field(const json& j, const char* key, const std::string& where)
{
    const json& v = field(j, key, where);
    if (!v.is_number_unsigned() || v.get<std::uint64_t>() > std::numeric_limits<Unsigned>::max())
        throw std::invalid_argument("expected " + where + "." + key + " to be a count (a non-negative integer), got " + v.dump());
    return v.get<Unsigned>();
}

int int_field(const json& j, const char* key, const std::string& where)
{
    const json& v = field(j, key, where);
    if (!v.is_number_integer() || v.get<std::int64_t>() < std::numeric_limits<int>::min() ||
        v.get<std::int64_t>() > std::numeric_limits<int>::max())
        throw std::invalid_argument("expected " + where + "." + key + " to be an integer, got " + v.dump());
    return v.get<int>();
}

double number_field(const json& j, const char* key, const std::string& where)
{
    const json& v = field(j, key, where);
    if (!v.is_number()) throw std::invalid_argument("expected " + where + "." + key + " to be a number, got " + v.dump());
    return v.get<double>();
}

std::string string_field(const json& j, const char* key, const std::string& where)
{
    const json& v = field(j, key, where);
    if (!v.is_string()) throw std::invalid_argument("expected " + where + "." + key + " to be a string, got " + v.dump());
    return v.get<std::string>();
}

std::vector<std::string> strings_field(const json& j, const char* key, const std::string& where)
{
    const json& v = field(j, key, where);
    std::vector<std::string> out;
    if (v.is_array())
        for (const json& e : v)
            if (e.is_string()) out.push_back(e.get<std::string>());
    if (!v.is_array() || out.size() != v.size())
        throw std::invalid_argument("expected " + where + "." + key + " to be an array of strings, got " + v.dump());
    return out;
}

}  // namespace

json Settings::to_json() const
{
    return {{"preset", preset}, {"seed", seed}, {"oracle_cases", oracle_cases}, {"oracle_chunk", oracle_chunk},
            {"oracle_csv_cases", oracle_csv_cases}, {"oracle_primitives", oracle_primitives},
            {"mesh_rays", mesh_rays}, {"mesh_max_n", mesh_max_n}, {"precision_preset", precision_preset},
            {"bench_min_time", bench_min_time}, {"fixtures_dir", fixtures_dir}, {"fuzz_cases", fuzz_cases},
            {"fuzz_chunk", fuzz_chunk}, {"fuzz_corpus_dir", fuzz_corpus_dir}};
}

// Throws std::invalid_argument "expected settings.<field> to be …".
Settings Settings::from_json(const json& j)
{
    const std::string w = "settings";
    Settings s;
    s.preset = string_field(j, "preset", w);
    s.seed = unsigned_field<std::uint64_t>(j, "seed", w);
    s.oracle_cases = unsigned_field<std::size_t>(j, "oracle_cases", w);
    s.oracle_chunk = unsigned_field<std::size_t>(j, "oracle_chunk", w);
    s.oracle_csv_cases = unsigned_field<std::size_t>(j, "oracle_csv_cases", w);
    s.oracle_primitives = strings_field(j, "oracle_primitives", w);
    s.mesh_rays = int_field(j, "mesh_rays", w);
    s.mesh_max_n = int_field(j, "mesh_max_n", w);
    s.precision_preset = string_field(j, "precision_preset", w);
    s.bench_min_time = number_field(j, "bench_min_time", w);
    s.fixtures_dir = string_field(j, "fixtures_dir", w);
    s.fuzz_cases = unsigned_field<std::size_t>(j, "fuzz_cases", w);
    s.fuzz_chunk = unsigned_field<std::size_t>(j, "fuzz_chunk", w);
    s.fuzz_corpus_dir = string_field(j, "fuzz_corpus_dir", w);
    return s;
}

json parse_partial(const std::string& text, const std::string& file)
{
    json j;
    try {
        j = json::parse(text);
    } catch (const json::exception& e) {  // parse_error: position, line and column; invalid UTF-8 included
        throw std::runtime_error(file + ": not valid JSON (" + e.what() + ")");
    }
    try {
        if (!j.is_object() || j.value("schema", json()) != "rayq-validate-partial" || j.value("version", json()) != format_version)
            throw std::invalid_argument("expected a rayq-validate partial summary (schema rayq-validate-partial, version " +
                                        std::to_string(format_version) +
                                        "; shards made by another version are rerun, not merged)");
        (void)Settings::from_json(field(j, "settings", "the partial summary"));
        const std::vector<std::string> selected = strings_field(j, "selected", "the partial summary");
        const json& shard = field(j, "shard", "the partial summary");
        (void)int_field(shard, "index", "shard");
        (void)int_field(shard, "count", "shard");
        const json& campaigns = field(j, "campaigns", "the partial summary");
        for (const std::string& name : selected) {
            const json& c = field(campaigns, name.c_str(), "campaigns");
            (void)unsigned_field<std::size_t>(c, "planned", "campaigns." + name);
            if (!field(c, "items", "campaigns." + name).is_object())
                throw std::invalid_argument("expected campaigns." + name + ".items to be an object (item id -> result)");
        }
    } catch (const std::exception& e) {
        throw std::runtime_error(file + ": " + e.what());
    }
    return j;
}

}  // namespace rayq::report
