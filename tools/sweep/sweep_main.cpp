// rayq-sweep — the precision sweeps of issue 6: per primitive × policy × type, the kernel against
// the exact oracle one decade at a time toward tangency (closeness δ), distance and translation,
// with Ceres fits of the error model err = C0 + C1·s^p (s = 1/δ or distance or translation) and
// of the logistic misclassification band. Prints the fit table; writes the per-decade data as CSV.
#include <rayq/fit/sweep.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

namespace {

using namespace rayq;
using fit::SweepKind;

const char* usage =
    "usage: rayq-sweep [--cases-per-delta N] [--seed S] [--csv FILE] [--out DIR] [--primitive P]...\n"
    "                  [--type float|double|both] [--kind closeness|distance|translation|all] [--max-k K]\n"
    "  --cases-per-delta N  cases per decade of the stress variable (default 24), both sides of the\n"
    "                       boundary alternating for the in/out families\n"
    "  --seed S             generator seed (default 1)\n"
    "  --csv FILE           the per-decade data (one row per series and x, with the fitted curves)\n"
    "  --out DIR            writes DIR/sweep.csv (as --csv), DIR/fits.csv and DIR/fits.txt (the table)\n"
    "  --primitive P        only these primitives (default: every generated one); repeatable\n"
    "  --type T             float, double or both (default both)\n"
    "  --kind K             which sweeps (default all)\n"
    "  --max-k K            closeness: only δ >= 10^-K\n"
    "Table: p ± se, C0, C1 (ulps) and x* (where C1·s^p = C0) of the median-error fit, p of the p99 fit,\n"
    "x50/x99 where P(correct hit/miss) falls to 50% / 99% ('-' = always correct), and the\n"
    "number of hit/miss or part misclassifications. 'flat': the growth term never takes over; p is\n"
    "then the slope of a single power law. x* ending in '~': outside the measured range (an extrapolation).\n"
    "Decades whose error reaches a relative 1/16 (float 2^19, double 2^48 ulps) are saturated and left out of\n"
    "the error fits ('n/a (saturated)' when fewer than 4 remain).\n";

std::string number(double v, int digits = 3)
{
    if (std::isnan(v)) return "n/a";
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.*g", digits, v);
    return buf;
}

std::string estimate(const fit::Estimate& e) { return number(e.value, 3) + "±" + number(e.se, 2); }

std::string power_text(const fit::PowerLawFit& f)
{
    if (!f.ok) return f.saturated ? "n/a (saturated)" : "n/a";
    return estimate(f.p) + (f.flat ? " flat" : "");
}

std::string band_text(const fit::LogisticFit& f, bool fifty)
{
    if (!f.ok) return "n/a";
    if (f.always_correct) return "-";
    if (f.never_correct) return "never";
    if (f.sparse) return "sparse";
    const auto& x = fifty ? f.x50 : f.x99;
    if (!x) return "n/a";
    return number(*x, 2) + (fifty && f.x50_extrapolated ? "*" : "") + (f.step ? "^" : "");
}

const char* stress_name(SweepKind k) { return k == SweepKind::closeness ? "delta" : k == SweepKind::distance ? "distance" : "translation"; }

}  // namespace

int main(int argc, char** argv)
{
    std::vector<std::string> args(argv + 1, argv + argc);
    fit::SweepOptions options;
    std::vector<std::string> primitives;
    std::string type = "both", kind_text = "all", csv_path, out_dir;
    try {
        for (std::size_t i = 0; i < args.size(); ++i) {
            const std::string& a = args[i];
            const auto value = [&]() -> const std::string& {
                if (i + 1 >= args.size()) throw std::invalid_argument(a + " needs a value");
                return args[++i];
            };
            if (a == "--cases-per-delta") options.cases_per_x = std::stoul(value());
            else if (a == "--seed") options.seed = std::stoull(value());
            else if (a == "--csv") csv_path = value();
            else if (a == "--out") out_dir = value();
            else if (a == "--primitive") primitives.push_back(value());
            else if (a == "--type") type = value();
            else if (a == "--kind") kind_text = value();
            else if (a == "--max-k") options.max_k = std::stoi(value());
            else if (a == "--help" || a == "-h") {
                std::cout << usage;
                return 0;
            } else throw std::invalid_argument("unknown option " + a);
        }
        if (type != "float" && type != "double" && type != "both") throw std::invalid_argument("--type is float, double or both");
        if (kind_text != "all" && kind_text != "closeness" && kind_text != "distance" && kind_text != "translation")
            throw std::invalid_argument("--kind is closeness, distance, translation or all");
        if (options.cases_per_x == 0) throw std::invalid_argument("--cases-per-delta must be positive");
        const auto& known = oracle::generated_primitives();
        for (const std::string& p : primitives)
            if (std::find(known.begin(), known.end(), p) == known.end()) throw std::invalid_argument("unknown primitive " + p);
    } catch (const std::exception& e) {
        std::cerr << "rayq-sweep: " << e.what() << "\n" << usage;
        return 2;
    }
    if (primitives.empty()) primitives = oracle::generated_primitives();
    std::vector<oracle::Scalar> scalars;
    if (type != "float") scalars.push_back(oracle::Scalar::f64);
    if (type != "double") scalars.push_back(oracle::Scalar::f32);
    std::vector<SweepKind> kinds;
    for (SweepKind k : {SweepKind::closeness, SweepKind::distance, SweepKind::translation})
        if (kind_text == "all" || kind_text == fit::sweep_kind_name(k)) kinds.push_back(k);

    std::ofstream csv, fits_csv, fits_txt;
    const auto open = [](std::ofstream& f, const std::string& path) {
        f.open(path);
        if (!f) throw std::runtime_error("cannot write " + path);
    };
    try {
        if (!out_dir.empty()) {
            std::filesystem::create_directories(out_dir);
            if (csv_path.empty()) csv_path = out_dir + "/sweep.csv";
            open(fits_csv, out_dir + "/fits.csv");
            open(fits_txt, out_dir + "/fits.txt");
        }
        if (!csv_path.empty()) open(csv, csv_path);
    } catch (const std::exception& e) {
        std::cerr << "rayq-sweep: " << e.what() << "\n";
        return 2;
    }
    if (csv.is_open())
        csv << "primitive,type,policy,sweep,family,x,cases,both_hit,hit_correct,part_correct,exact_hits,median_ulps,p99_ulps,"
               "max_ulps,fit_median_ulps,fit_p99_ulps,fit_p_correct\n";
    if (fits_csv.is_open())
        fits_csv << "primitive,type,policy,sweep,family,flat,p,p_se,C0,C0_se,C1,C1_se,x_star,p99_flat,p99_p,p99_p_se,p99_C0,p99_C1,"
                    "x50,x99,logistic_u0,logistic_u0_se,logistic_k,logistic_k_se,cases,misclassified,saturated\n";

    std::ostringstream header;
    char line[512];
    std::snprintf(line, sizeof line, "%-20s %-6s %-8s %-11s %-8s | %-17s %-9s %-9s %-9s | %-17s | %-10s %-10s | %s", "primitive", "type",
                  "policy", "sweep", "family", "p (median)", "C0", "C1", "x*", "p (p99)", "x50", "x99", "miscls/cases");
    header << line << "\n";
    std::cout << "rayq-sweep: " << options.cases_per_x << " cases per decade, seed " << options.seed << "\n" << header.str();
    if (fits_txt.is_open()) fits_txt << header.str();

    const auto start = std::chrono::steady_clock::now();
    std::size_t series_count = 0;
    for (const std::string& primitive : primitives) {
        for (oracle::Scalar scalar : scalars) {
            for (SweepKind kind : kinds) {
                std::vector<fit::Series> all;
                try {
                    all = fit::run_sweep(primitive, scalar, kind, options);
                } catch (const std::exception& e) {
                    std::cerr << "rayq-sweep: " << primitive << ": " << e.what() << "\n";
                    return 3;
                }
                for (const fit::Series& s : all) {
                    const fit::SeriesFit f = fit::fit_series(s);
                    ++series_count;
                    std::size_t cases = 0;
                    for (const auto& p : s.points) cases += p.cases;
                    const char* policy = oracle::policy_name(s.policy);
                    const char* type_name = oracle::scalar_name(scalar);
                    std::snprintf(line, sizeof line, "%-20s %-6s %-8s %-11s %-8s | %-17s %-9s %-9s %-9s | %-17s | %-10s %-10s | %zu/%zu",
                                  primitive.c_str(), type_name, policy, stress_name(kind), s.family_class.c_str(),
                                  power_text(f.median).c_str(), f.median.ok ? number(f.median.C0.value).c_str() : "-",
                                  f.median.ok ? number(f.median.C1.value).c_str() : "-",
                                  f.median.x_star ? (number(*f.median.x_star, 2) + (f.median.x_star_in_data ? "" : "~")).c_str() : "-",
                                  power_text(f.p99).c_str(),
                                  band_text(f.hit, true).c_str(), band_text(f.hit, false).c_str(), f.misclassified, cases);
                    std::cout << line << "\n";
                    if (fits_txt.is_open()) fits_txt << line << "\n";
                    if (fits_csv.is_open()) {
                        const auto opt = [](const std::optional<double>& v) { return v ? number(*v, 17) : std::string(); };
                        fits_csv << primitive << ',' << type_name << ',' << policy << ',' << stress_name(kind) << ',' << s.family_class
                                 << ',' << (f.median.ok ? (f.median.flat ? "1" : "0") : "") << ',' << number(f.median.p.value, 17) << ','
                                 << number(f.median.p.se, 17) << ',' << number(f.median.C0.value, 17) << ','
                                 << number(f.median.C0.se, 17) << ',' << number(f.median.C1.value, 17) << ','
                                 << number(f.median.C1.se, 17) << ',' << opt(f.median.x_star) << ','
                                 << (f.p99.ok ? (f.p99.flat ? "1" : "0") : "") << ',' << number(f.p99.p.value, 17) << ','
                                 << number(f.p99.p.se, 17) << ',' << number(f.p99.C0.value, 17) << ',' << number(f.p99.C1.value, 17)
                                 << ',' << opt(f.hit.x50) << ',' << opt(f.hit.x99) << ',' << number(f.hit.u0.value, 17) << ','
                                 << number(f.hit.u0.se, 17) << ',' << number(f.hit.k.value, 17) << ',' << number(f.hit.k.se, 17)
                                 << ',' << cases << ',' << f.misclassified << ',' << f.median.saturated << "\n";
                    }
                    if (csv.is_open())
                        for (const fit::SweepPoint& p : s.points)
                            csv << primitive << ',' << type_name << ',' << policy << ',' << stress_name(kind) << ',' << s.family_class
                                << ',' << number(p.x, 17) << ',' << p.cases << ',' << p.both_hit << ',' << p.hit_correct << ','
                                << p.part_correct << ',' << p.exact_hits << ',' << number(p.median_ulps, 17) << ','
                                << number(p.p99_ulps, 17) << ',' << number(p.max_ulps, 17) << ','
                                << (f.median.ok ? number(f.median.predict(p.x), 17) : "") << ','
                                << (f.p99.ok ? number(f.p99.predict(p.x), 17) : "") << ','
                                << (f.hit.ok ? number(f.hit.probability(p.x), 17) : "") << "\n";
                }
                std::cout.flush();
            }
        }
    }
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::cout << "rayq-sweep: " << series_count << " series in " << number(seconds, 3) << " s"
              << "  (~ = x* outside the data, * = x50 extrapolated beyond the data, ^ = step: steeper than the fit resolves, sparse = wrong answers with no trend)\n";
    return 0;
}
