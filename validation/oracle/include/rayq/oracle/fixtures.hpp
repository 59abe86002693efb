// rayq::oracle — fixtures: (ray, primitive) cases in the exact text format of fixtures/README.md,
// the families of issue 4 that generate them, and the measurement table. Non-template API
// (the small Input<Prim> aggregate only pairs a ray with a primitive).
#pragma once

#include <cstddef>
#include <cstdint>
#include <iosfwd>
#include <stdexcept>
#include <string>
#include <variant>
#include <vector>

#include <rayq/oracle/oracle.hpp>

namespace rayq::oracle {

template <class Prim>
struct Input {
    Ray<typename Prim::scalar_type> ray;
    Prim prim;
};

#define RAYQ_ORACLE_INPUTS(T)                                                                                     \
    Input<Sphere<T>>, Input<Plane<T>>, Input<Disk<T>>, Input<Parallelogram<T>>, Input<Triangle<T>>,             \
        Input<Cylinder<T>>, Input<Cone<T>>, Input<Quadric<T>>, Input<Transformed<Sphere<T>>>,                   \
        Input<Transformed<Plane<T>>>, Input<Transformed<Disk<T>>>, Input<Transformed<Parallelogram<T>>>,         \
        Input<Transformed<Triangle<T>>>, Input<Transformed<Cylinder<T>>>, Input<Transformed<Cone<T>>>,          \
        Input<Transformed<Quadric<T>>>
using AnyInput = std::variant<RAYQ_ORACLE_INPUTS(float), RAYQ_ORACLE_INPUTS(double)>;
#undef RAYQ_ORACLE_INPUTS

enum class Scalar { f32, f64 };

struct Fixture {
    std::string family;  // e.g. "generic", "grazing.in.k07"; the class is the text before the first '.'
    AnyInput input;
};

std::string primitive_name(const AnyInput& input);  // "sphere", …, "quadric", "transformed-cone"
Scalar scalar_of(const AnyInput& input);
const char* scalar_name(Scalar s);                   // "float", "double"
std::string family_class(const std::string& family); // "grazing" for "grazing.in.k07"
Truth truth_of(const AnyInput& input);

// ---- the text format ----------------------------------------------------------------------------
// A malformed line: what() is "file:line: expected …".
class ParseError : public std::runtime_error {
public:
    ParseError(const std::string& file, std::size_t line, const std::string& expected);
    const std::string& file() const { return file_; }
    std::size_t line() const { return line_; }

private:
    std::string file_;
    std::size_t line_;
};

std::vector<Fixture> parse_fixtures(std::istream& in, const std::string& file_name);
std::vector<Fixture> load_fixtures(const std::string& path);           // one file
std::vector<Fixture> load_fixture_directory(const std::string& dir);   // every *.txt in it, sorted by name
std::string format_fixture(const Fixture& f);                          // one line, no newline
void write_fixtures(std::ostream& out, const std::vector<Fixture>& fixtures);

// ---- the generated families (issue 4) -------------------------------------------------------------
// Primitive names the generator knows: sphere plane disk parallelogram triangle cylinder cone
// quadric transformed-sphere transformed-cylinder transformed-cone transformed-quadric
// transformed-triangle.
const std::vector<std::string>& generated_primitives();
// Every family (with its parameter) generated for a primitive in a number type, e.g.
// generic, grazing.in.k01 … grazing.out.k15 (k up to 15 for double, 7 for float), parallel.k03,
// rim.in.k05, axial.k04, apex.out.k06, far.e08, translated.e08, inside, surface.in, clip.
std::vector<std::string> family_names(const std::string& primitive, Scalar s);
// One case, a pure function of its arguments (fixed seeds: same arguments, same bits).
Fixture generate(const std::string& primitive, Scalar s, const std::string& family, std::uint64_t seed,
                 std::uint64_t index);
// `count` cases, round-robin over family_names(primitive, s).
std::vector<Fixture> generate_cases(const std::string& primitive, Scalar s, std::size_t count, std::uint64_t seed);
// The small curated selection checked in under fixtures/oracle/<primitive>.txt (both types).
std::vector<Fixture> curated_fixtures(const std::string& primitive);
constexpr std::uint64_t curated_seed = 20240404;

// ---- the measurement table ----------------------------------------------------------------------
struct Tally {
    std::size_t cases = 0;            // measured (defined) cases
    std::size_t hit_agree = 0;
    std::size_t both_hit = 0;
    std::size_t part_agree = 0;       // among both_hit
    std::size_t front_agree = 0;      // among both_hit
    std::size_t faithful = 0;         // among both_hit
    std::size_t bounded = 0;          // kernel hits with a finite t_error
    std::size_t bound_violations = 0; // kernel hits whose bound misses the exact first hit (false hits: every crossing)
    std::size_t uncertified = 0;      // violations with no exact crossing of the line within the bound
    std::size_t other_crossing = 0;   // among both_hit: the kernel reported a different crossing
    std::size_t exact_fallbacks = 0;  // cases whose kernel call needed exact arithmetic (accurate)
    double max_angle = 0;             // radians, over both_hit with a defined normal
    std::vector<double> ulps;         // among both_hit

    void add(const Measurement& m);
    double max_ulps() const;
    double percentile_ulps(double p) const;  // nearest rank; 0 when empty
};

struct SummaryRow {
    std::string primitive, policy, type, family = "all";
    Tally tally;
};

std::string table_header();
std::string table_line(const SummaryRow& row);
std::string csv_header();
std::string csv_line(const SummaryRow& row);

}  // namespace rayq::oracle
