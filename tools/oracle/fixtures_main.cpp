// rayq-fixtures — writes (or checks) the curated oracle fixtures under fixtures/oracle/, or prints
// generated cases of any family. Fixed seeds: the same command writes the same bits.
#include <rayq/oracle/fixtures.hpp>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

namespace {

using namespace rayq::oracle;

const char* usage =
    "usage: rayq-fixtures --out DIR        write the curated set, DIR/<primitive>.txt\n"
    "       rayq-fixtures --check DIR      exit 1 unless DIR holds exactly what --out would write\n"
    "       rayq-fixtures --list           primitives and their families\n"
    "       rayq-fixtures --primitive P [--type float|double] [--family F] [--cases N] [--seed S]\n"
    "                                      print generated cases (default: all families, double, 1 each)\n";

std::string curated_text(const std::string& primitive)
{
    std::ostringstream out;
    out << "# rayq oracle fixtures: " << primitive << " (curated; written by rayq-fixtures --out, seed " << curated_seed
        << ")\n# Format: fixtures/README.md. One case per line: family primitive type ray(8) primitive fields.\n";
    write_fixtures(out, curated_fixtures(primitive));
    return out.str();
}

int fail(const std::string& message)
{
    std::cerr << "rayq-fixtures: " << message << "\n" << usage;
    return 2;
}

}  // namespace

int main(int argc, char** argv)
{
    std::vector<std::string> args(argv + 1, argv + argc);
    std::string out_dir, check_dir, primitive, family, type = "double";
    std::size_t cases = 1;
    std::uint64_t seed = curated_seed;
    bool list = false;
    try {
        for (std::size_t i = 0; i < args.size(); ++i) {
            const std::string& a = args[i];
            const auto value = [&]() -> const std::string& {
                if (i + 1 >= args.size()) throw std::invalid_argument(a + " needs a value");
                return args[++i];
            };
            if (a == "--out") out_dir = value();
            else if (a == "--check") check_dir = value();
            else if (a == "--list") list = true;
            else if (a == "--primitive") primitive = value();
            else if (a == "--family") family = value();
            else if (a == "--type") type = value();
            else if (a == "--cases") cases = std::stoul(value());
            else if (a == "--seed") seed = std::stoull(value());
            else if (a == "--help" || a == "-h") {
                std::cout << usage;
                return 0;
            } else throw std::invalid_argument("unknown option " + a);
        }
        if (type != "float" && type != "double") throw std::invalid_argument("--type is float or double");
    } catch (const std::exception& e) {
        return fail(e.what());
    }
    const Scalar scalar = type == "float" ? Scalar::f32 : Scalar::f64;

    if (list) {
        for (const std::string& p : generated_primitives()) {
            std::cout << p << ":";
            for (const std::string& f : family_names(p, Scalar::f64)) std::cout << ' ' << f;
            std::cout << "\n";
        }
        return 0;
    }
    if (!out_dir.empty()) {
        std::size_t lines = 0;
        for (const std::string& p : generated_primitives()) {
            const std::string path = out_dir + "/" + p + ".txt";
            std::ofstream f(path);
            if (!f) return fail("cannot write " + path);
            f << curated_text(p);
            lines += curated_fixtures(p).size();
        }
        std::cout << "rayq-fixtures: wrote " << lines << " cases to " << out_dir << "\n";
        return 0;
    }
    if (!check_dir.empty()) {
        int stale = 0;
        for (const std::string& p : generated_primitives()) {
            const std::string path = check_dir + "/" + p + ".txt";
            std::ifstream f(path);
            std::stringstream have;
            have << f.rdbuf();
            if (!f || have.str() != curated_text(p)) {
                std::cerr << "rayq-fixtures: " << path << " differs from what rayq-fixtures --out writes\n";
                ++stale;
            }
        }
        if (stale == 0) std::cout << "rayq-fixtures: " << check_dir << " is up to date\n";
        return stale == 0 ? 0 : 1;
    }
    if (!primitive.empty()) {
        try {
            const std::vector<std::string> families = family.empty() ? family_names(primitive, scalar) : std::vector<std::string>{family};
            std::vector<Fixture> out;
            for (const std::string& f : families)
                for (std::size_t i = 0; i < cases; ++i) out.push_back(generate(primitive, scalar, f, seed, i));
            write_fixtures(std::cout, out);
        } catch (const std::exception& e) {
            return fail(e.what());
        }
        return 0;
    }
    return fail("nothing to do");
}
