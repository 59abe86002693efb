// The fixture format (fixtures/README.md): exact round trips, the checked-in files, the README's
// example, and malformed lines rejected with "file:line: expected …".
#include <gtest/gtest.h>

#include <fstream>
#include <set>
#include <sstream>
#include <string>

#include <rayq/oracle/fixtures.hpp>

namespace {

using namespace rayq;
using namespace rayq::oracle;

std::vector<Fixture> parse(const std::string& text, const std::string& name = "test.txt")
{
    std::istringstream in(text);
    return parse_fixtures(in, name);
}

TEST(OracleFixtures, EveryGeneratedCaseRoundTripsExactly)
{
    for (const std::string& p : generated_primitives())
        for (Scalar s : {Scalar::f64, Scalar::f32}) {
            const std::vector<Fixture> cases = generate_cases(p, s, 60, 5);
            std::ostringstream out;
            write_fixtures(out, cases);
            const std::vector<Fixture> back = parse(out.str());
            ASSERT_EQ(back.size(), cases.size());
            for (std::size_t i = 0; i < cases.size(); ++i) {
                EXPECT_EQ(format_fixture(back[i]), format_fixture(cases[i]));
                EXPECT_EQ(back[i].input.index(), cases[i].input.index());
                EXPECT_EQ(primitive_name(back[i].input), p);
                EXPECT_EQ(scalar_of(back[i].input), s);
                // Same bits, same truth.
                EXPECT_EQ(truth_of(back[i].input).first_hit().t_exact, truth_of(cases[i].input).first_hit().t_exact);
            }
        }
}

TEST(OracleFixtures, GenerationIsDeterministic)
{
    for (const std::string& p : generated_primitives())
        EXPECT_EQ(format_fixture(generate(p, Scalar::f64, "generic", 42, 3)), format_fixture(generate(p, Scalar::f64, "generic", 42, 3)));
    EXPECT_NE(format_fixture(generate("sphere", Scalar::f64, "generic", 42, 3)), format_fixture(generate("sphere", Scalar::f64, "generic", 42, 4)));
}

TEST(OracleFixtures, CheckedInFilesParseAndCoverEveryFamily)
{
    const std::vector<Fixture> all = load_fixture_directory(RAYQ_ORACLE_FIXTURES);
    EXPECT_GT(all.size(), 300u);
    EXPECT_LT(all.size(), 1000u);
    std::set<std::string> primitives, classes;
    for (const Fixture& f : all) {
        primitives.insert(primitive_name(f.input));
        classes.insert(family_class(f.family));
        EXPECT_TRUE(truth_of(f.input).first_hit().defined) << format_fixture(f);
    }
    for (const std::string& p : generated_primitives()) EXPECT_TRUE(primitives.count(p)) << p;
    for (const char* c : {"generic", "grazing", "parallel", "rim", "axial", "apex", "far", "translated", "inside", "surface", "clip"})
        EXPECT_TRUE(classes.count(c)) << c;
}

TEST(OracleFixtures, TheReadmeExampleMeansWhatItSays)
{
    std::ifstream readme(RAYQ_FIXTURES_README);
    ASSERT_TRUE(readme);
    std::string line, example;
    while (std::getline(readme, line))
        if (line.rfind("generic sphere double", 0) == 0) example = line;
    ASSERT_FALSE(example.empty());
    const std::vector<Fixture> f = parse(example);
    ASSERT_EQ(f.size(), 1u);
    const ExactHit h = truth_of(f[0].input).first_hit();
    EXPECT_TRUE(h.hit);
    EXPECT_EQ(h.t_double, 4.0);
    EXPECT_EQ(format_fixture(f[0]), example);
}

TEST(OracleFixtures, CommentsBlankLinesAndSpecialValues)
{
    const std::vector<Fixture> f = parse(
        "# a comment\n"
        "\n"
        "   \t\n"
        "mine.k03 cylinder float 0x0p+0 0x0p+0 -0x1p+1 0x0p+0 0x0p+0 0x1p+0 -inf inf "
        "0x0p+0 0x0p+0 0x0p+0 0x0p+0 0x0p+0 0x1p+1 0x1p+0 both  # trailing comment\n"
        "x transformed-disk double 0x0p+0 0x0p+0 0x1p+0 0x0p+0 0x0p+0 -0x1p+0 0x0p+0 inf 0x0p+0 0x0p+0 0x0p+0 0x0p+0 0x0p+0 0x1p+0 0x1p+0 "
        "0x1p+0 0x0p+0 0x0p+0 0x0p+0 0x0p+0 0x1p+0 0x0p+0 0x0p+0 0x0p+0 0x0p+0 0x1p+0 0x0p+0 "
        "0x1p+0 0x0p+0 0x0p+0 0x0p+0 0x0p+0 0x1p+0 0x0p+0 0x0p+0 0x0p+0 0x0p+0 0x1p+0 0x0p+0\n");
    ASSERT_EQ(f.size(), 2u);
    EXPECT_EQ(f[0].family, "mine.k03");
    EXPECT_EQ(family_class(f[0].family), "mine");
    const auto& cyl = std::get<Input<Cylinder<float>>>(f[0].input);
    EXPECT_EQ(cyl.prim.caps, Caps::both);
    EXPECT_EQ(cyl.ray.tmin, -std::numeric_limits<float>::infinity());
    EXPECT_EQ(cyl.prim.p1.z, 2.0f);
    const ExactHit h = truth_of(f[0].input).first_hit();
    EXPECT_EQ(h.t_double, 2.0);  // enters cap0 at z = 0
    EXPECT_EQ(h.part, Part::cap0);
    const auto& disk = std::get<Input<Transformed<Disk<double>>>>(f[1].input);
    EXPECT_EQ(disk.prim.object.radius, 1.0);
    EXPECT_EQ(disk.prim.to_object.m[2][2], 1.0);
    EXPECT_EQ(truth_of(f[1].input).first_hit().t_double, 1.0);
}

// A malformed line names the file and the line and says what was expected.
void expect_rejected(const std::string& text, std::size_t line, const std::string& expected_fragment)
{
    try {
        parse(text, "bad.txt");
        ADD_FAILURE() << "accepted: " << text;
    } catch (const ParseError& e) {
        const std::string what = e.what();
        EXPECT_EQ(e.file(), "bad.txt");
        EXPECT_EQ(e.line(), line) << what;
        EXPECT_EQ(what.rfind("bad.txt:" + std::to_string(line) + ": expected ", 0), 0u) << what;
        EXPECT_NE(what.find(expected_fragment), std::string::npos) << what;
    }
}

TEST(OracleFixtures, MalformedLinesAreRejectedWithFileAndLine)
{
    const std::string ray = " 0x0p+0 0x0p+0 -0x1.4p+2 0x0p+0 0x0p+0 0x1p+0 0x0p+0 inf";
    const std::string good = "generic sphere double" + ray + " 0x0p+0 0x0p+0 0x0p+0 0x1p+0\n";
    EXPECT_EQ(parse(good).size(), 1u);
    const std::string prefix = "# header\n" + good + "\n";  // the bad line is line 4
    expect_rejected(prefix + "generic sphere double" + ray + " 0x0p+0 0x0p+0 0x0p+0 1.5\n", 4, "C99 hex float");
    expect_rejected(prefix + "generic sphere double" + ray + " 0x0p+0 0x0p+0 0x0p+0\n", 4, "field 'radius'");
    expect_rejected(prefix + "generic sphere double" + ray + " 0x0p+0 0x0p+0 0x0p+0 0x1p+0 0x1p+0\n", 4, "end of line");
    expect_rejected(prefix + "generic torus double" + ray + "\n", 4, "primitive name");
    expect_rejected(prefix + "generic sphere half" + ray + "\n", 4, "'float' or 'double'");
    expect_rejected(prefix + "generic sphere\n", 4, "number type");
    expect_rejected(prefix + "gen/eric sphere double" + ray + " 0x0p+0 0x0p+0 0x0p+0 0x1p+0\n", 4, "family name");
    expect_rejected(prefix + "generic sphere float" + ray + " 0x0p+0 0x0p+0 0x0p+0 0x1.0000001p+0\n", 4, "exactly representable as float");
    expect_rejected(prefix + "generic sphere double" + ray + " 0x0p+0 0x0p+0 0x0p+0 0x1.8\n", 4, "C99 hex float");
    expect_rejected(prefix + "generic sphere double" + ray + " 0x0p+0 0x0p+0 0x0p+0 0x1p+0x\n", 4, "C99 hex float");
    expect_rejected(prefix + "generic cylinder double" + ray + " 0x0p+0 0x0p+0 0x0p+0 0x0p+0 0x0p+0 0x1p+0 0x1p+0 maybe\n", 4,
                    "'none' or 'both'");
    expect_rejected("generic sphere double 0x0p+0 0x0p+0\n", 1, "field 'ray.origin.z'");
    try {
        load_fixtures("/nonexistent/fixtures.txt");
        ADD_FAILURE() << "a missing file was accepted";
    } catch (const ParseError& e) {
        EXPECT_NE(std::string(e.what()).find("/nonexistent/fixtures.txt:0: expected a readable file"), std::string::npos);
    }
}

}  // namespace
