// rayq-oracle-campaign — measures the kernel against the exact oracle: N generated cases per
// primitive and number type (round-robin over issue 4's families), every policy, one table row
// per primitive × policy × type (and per family class with --by-family).
#include <rayq/oracle/harness.hpp>

#include <chrono>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <map>
#include <set>
#include <string>
#include <vector>

namespace {

using namespace rayq::oracle;

const char* usage =
    "usage: rayq-oracle-campaign [--cases N] [--seed S] [--primitive P]... [--type float|double|both]\n"
    "                            [--policies L] [--exclude-family C]... [--by-family] [--csv FILE]\n"
    "                            [--failures FILE] [--fixtures DIR] [--explain FILE]\n"
    "  --cases N      cases per primitive and type (default 10000), round-robin over the families\n"
    "  --seed S       generator seed (default 1)\n"
    "  --primitive P  only these primitives (default: all generated ones; see rayq-fixtures --list)\n"
    "  --by-family    also one row per family class (generic, grazing, rim, ...)\n"
    "  --csv FILE     the table as CSV too\n"
    "  --failures FILE  write the cases with a bound violation, or with a hit/part/front-face\n"
    "                 disagreement in a non-grazing family (generic, inside, far, translated, clip),\n"
    "                 as fixture lines (hex-float reproducers) preceded by a comment\n"
    "  --fixtures DIR measure the fixture files in DIR instead of generated cases\n"
    "  --policies L   a comma-separated subset of fast,stable,accurate (default: all three)\n"
    "  --exclude-family C  skip the family class C (generic, grazing, parallel, ...); repeatable\n"
    "  --explain FILE for each case in the fixture file FILE: the exact answer and every policy's\n";

// One case in full: what the oracle says and what each policy returned.
void explain(const Fixture& f, const bool use_policy[3])
{
    const Truth truth = truth_of(f.input);
    const ExactHit& h = truth.first_hit();
    std::printf("%s\n  exact: ", format_fixture(f).c_str());
    if (!h.defined) std::printf("outside the oracle's domain\n");
    else if (!h.hit) std::printf("miss\n");
    else
        std::printf("t = %a (%.17g; float %a), part %d, front_face %d, tangent %d, normal (%.17g, %.17g, %.17g)\n         t = %s\n",
                    h.t_double, h.t_double, static_cast<double>(h.t_float), static_cast<int>(h.part), h.entering, h.tangent,
                    h.facing_normal.x, h.facing_normal.y, h.facing_normal.z, h.t_exact.c_str());
    if (h.defined) {
        std::printf("  exact crossings of the line:");
        for (long double x : h.crossings) std::printf(" %.17Lg", x);
        std::printf("\n");
    }
    for (Policy p : all_policies) {
        if (!use_policy[static_cast<int>(p)]) continue;
        const KernelAnswer a = run_kernel(p, f.input);
        const Measurement m = a.is_float ? truth.measure(a.f) : truth.measure(a.d);
        std::printf("  %-8s ", policy_name(p));
        if (!a.hit()) {
            std::printf("miss%s\n", m.hit_agrees ? "" : "   <-- disagrees");
            continue;
        }
        const auto show = [&](const auto& k) {
            std::printf("t = %a (%.17g), t_error %a, part %d, front_face %d, normal (%.17g, %.17g, %.17g)\n"
                        "           %.3g ulps, faithful %d, bound violated %d (uncertified %d), other crossing %d, normal angle %.3g%s\n",
                        static_cast<double>(k.t), static_cast<double>(k.t), static_cast<double>(k.t_error), static_cast<int>(k.part),
                        k.front_face, static_cast<double>(k.normal.x), static_cast<double>(k.normal.y), static_cast<double>(k.normal.z),
                        m.ulps, m.faithful, m.bound_violated, m.uncertified, m.other_crossing, m.normal_angle,
                        m.hit_agrees ? "" : "   <-- disagrees");
        };
        if (a.is_float) show(*a.f);
        else show(*a.d);
    }
}

// Families where the answer is not decided within a few ulps of a boundary by construction.
bool robust_family(const std::string& cls)
{
    return cls == "generic" || cls == "inside" || cls == "far" || cls == "translated" || cls == "clip";
}

struct Rows {
    SummaryRow policy[3];
};

}  // namespace

int main(int argc, char** argv)
{
    std::vector<std::string> args(argv + 1, argv + argc);
    std::size_t cases = 10000;
    std::uint64_t seed = 1;
    std::vector<std::string> primitives;
    std::string type = "both", csv_path, failures_path, fixture_dir, explain_path;
    bool by_family = false;
    bool use_policy[3] = {true, true, true};
    std::set<std::string> excluded;
    try {
        for (std::size_t i = 0; i < args.size(); ++i) {
            const std::string& a = args[i];
            const auto value = [&]() -> const std::string& {
                if (i + 1 >= args.size()) throw std::invalid_argument(a + " needs a value");
                return args[++i];
            };
            if (a == "--cases") cases = std::stoul(value());
            else if (a == "--seed") seed = std::stoull(value());
            else if (a == "--primitive") primitives.push_back(value());
            else if (a == "--type") type = value();
            else if (a == "--by-family") by_family = true;
            else if (a == "--csv") csv_path = value();
            else if (a == "--failures") failures_path = value();
            else if (a == "--fixtures") fixture_dir = value();
            else if (a == "--explain") explain_path = value();
            else if (a == "--exclude-family") excluded.insert(value());
            else if (a == "--policies") {
                const std::string list = "," + value() + ",";
                for (int i = 0; i < 3; ++i) use_policy[i] = list.find(std::string(",") + policy_name(all_policies[i]) + ",") != std::string::npos;
                if (!use_policy[0] && !use_policy[1] && !use_policy[2]) throw std::invalid_argument("--policies names none of fast, stable, accurate");
            }
            else if (a == "--help" || a == "-h") {
                std::cout << usage;
                return 0;
            } else throw std::invalid_argument("unknown option " + a);
        }
        if (type != "float" && type != "double" && type != "both") throw std::invalid_argument("--type is float, double or both");
    } catch (const std::exception& e) {
        std::cerr << "rayq-oracle-campaign: " << e.what() << "\n" << usage;
        return 2;
    }
    if (!explain_path.empty()) {
        try {
            for (const Fixture& f : load_fixtures(explain_path)) explain(f, use_policy);
        } catch (const std::exception& e) {
            std::cerr << "rayq-oracle-campaign: " << e.what() << "\n";
            return 2;
        }
        return 0;
    }
    std::vector<Fixture> from_files;
    if (!fixture_dir.empty()) {
        try {
            from_files = load_fixture_directory(fixture_dir);
        } catch (const std::exception& e) {
            std::cerr << "rayq-oracle-campaign: " << e.what() << "\n";
            return 2;
        }
    }
    if (primitives.empty()) {
        if (fixture_dir.empty()) primitives = generated_primitives();
        else {
            std::set<std::string> seen;
            for (const Fixture& f : from_files)
                if (seen.insert(primitive_name(f.input)).second) primitives.push_back(primitive_name(f.input));
        }
    }
    std::vector<Scalar> scalars;
    if (type != "float") scalars.push_back(Scalar::f64);
    if (type != "double") scalars.push_back(Scalar::f32);

    std::ofstream csv, failures;
    if (!csv_path.empty()) {
        csv.open(csv_path);
        if (!csv) return std::cerr << "rayq-oracle-campaign: cannot write " << csv_path << "\n", 2;
        csv << csv_header() << "\n";
    }
    if (!failures_path.empty()) {
        failures.open(failures_path);
        if (!failures) return std::cerr << "rayq-oracle-campaign: cannot write " << failures_path << "\n", 2;
        failures << "# rayq-oracle-campaign failures (seed " << seed << "); format: fixtures/README.md\n";
    }

    if (fixture_dir.empty())
        std::cout << "rayq-oracle-campaign: " << cases << " cases per primitive and type, seed " << seed << "\n";
    else std::cout << "rayq-oracle-campaign: the fixtures in " << fixture_dir << "\n";
    std::cout << table_header() << "\n";
    const auto start = std::chrono::steady_clock::now();
    std::size_t total = 0, undefined = 0, written = 0;
    for (const std::string& primitive : primitives) {
        for (Scalar scalar : scalars) {
            std::vector<Fixture> batch;
            if (fixture_dir.empty()) {
                try {
                    batch = generate_cases(primitive, scalar, cases, seed);
                } catch (const std::exception& e) {
                    std::cerr << "rayq-oracle-campaign: " << e.what() << "\n";
                    return 2;
                }
            } else {
                for (const Fixture& f : from_files)
                    if (primitive_name(f.input) == primitive && scalar_of(f.input) == scalar) batch.push_back(f);
                if (batch.empty()) continue;
            }
            Rows all;
            std::map<std::string, Rows> per_family;
            for (const Fixture& f : batch) {
                const std::string cls = family_class(f.family);
                if (excluded.count(cls)) continue;
                const Truth truth = truth_of(f.input);
                ++total;
                if (!truth.first_hit().defined) {
                    ++undefined;
                    continue;
                }
                Measurement m[3];
                for (int i = 0; i < 3; ++i)
                    if (use_policy[i]) m[i] = measure_kernel(truth, all_policies[i], f.input);
                std::string trouble;
                for (int i = 0; i < 3; ++i) {
                    if (!use_policy[i]) continue;
                    all.policy[i].tally.add(m[i]);
                    if (by_family) per_family[cls].policy[i].tally.add(m[i]);
                    const char* p = policy_name(all_policies[i]);
                    if (m[i].bound_violated) trouble += std::string(" ") + p + (m[i].uncertified ? ":uncertified" : ":bound-violated");
                    if (robust_family(cls)) {
                        if (!m[i].hit_agrees) trouble += std::string(" ") + p + (m[i].exact_hit ? ":missed" : ":false-hit");
                        else if (m[i].both_hit && !m[i].part_agrees) trouble += std::string(" ") + p + ":part";
                        else if (m[i].both_hit && !m[i].front_face_agrees) trouble += std::string(" ") + p + ":front-face";
                    }
                }
                if (failures.is_open() && !trouble.empty()) {
                    const ExactHit& h = truth.first_hit();
                    failures << "#" << trouble << " | exact: " << (h.hit ? "t = " + h.t_exact : std::string("miss")) << "\n"
                             << format_fixture(f) << "\n";
                    ++written;
                }
            }
            const auto emit = [&](Rows& rows, const std::string& family) {
                for (int i = 0; i < 3; ++i) {
                    if (!use_policy[i]) continue;
                    SummaryRow& r = rows.policy[i];
                    r.primitive = primitive;
                    r.policy = policy_name(all_policies[i]);
                    r.type = scalar_name(scalar);
                    r.family = family;
                    std::cout << table_line(r) << "\n";
                    if (csv.is_open()) csv << csv_line(r) << "\n";
                }
            };
            emit(all, "all");
            for (auto& [cls, rows] : per_family) emit(rows, cls);
            std::cout.flush();
        }
    }
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::cout << "rayq-oracle-campaign: " << total << " cases (" << undefined << " outside the oracle's domain) in " << seconds
              << " s";
    if (failures.is_open()) std::cout << "; " << written << " written to " << failures_path;
    std::cout << "\n";
    return 0;
}
