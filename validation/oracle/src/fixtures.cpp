// rayq::oracle — the fixture text format (fixtures/README.md): parser and writer. One schema per
// primitive lists its fields once; the parser and the writer both walk it.
#include <rayq/oracle/fixtures.hpp>

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <dirent.h>
#include <fstream>
#include <istream>
#include <ostream>
#include <sstream>
#include <utility>

namespace rayq::oracle {

namespace {

constexpr std::size_t kinds = 16;  // primitives per number type, in AnyInput's order
const std::array<const char*, kinds> kind_names = {
    "sphere", "plane", "disk", "parallelogram", "triangle", "cylinder", "cone", "quadric",
    "transformed-sphere", "transformed-plane", "transformed-disk", "transformed-parallelogram",
    "transformed-triangle", "transformed-cylinder", "transformed-cone", "transformed-quadric"};

// ---- the schema: every field of every input, in file order ---------------------------------------
template <class V, class T>
void vec_fields(V& v, const char* name, Vec3<T>& x)
{
    const std::string n(name);
    v.num(n + ".x", x.x);
    v.num(n + ".y", x.y);
    v.num(n + ".z", x.z);
}

template <class V, class T>
void fields(V& v, Sphere<T>& s)
{
    vec_fields(v, "center", s.center);
    v.num("radius", s.radius);
}
template <class V, class T>
void fields(V& v, Plane<T>& p)
{
    vec_fields(v, "point", p.point);
    vec_fields(v, "normal", p.normal);
}
template <class V, class T>
void fields(V& v, Disk<T>& d)
{
    vec_fields(v, "center", d.center);
    vec_fields(v, "normal", d.normal);
    v.num("radius", d.radius);
}
template <class V, class T>
void fields(V& v, Parallelogram<T>& p)
{
    vec_fields(v, "corner", p.corner);
    vec_fields(v, "edge0", p.edge0);
    vec_fields(v, "edge1", p.edge1);
}
template <class V, class T>
void fields(V& v, Triangle<T>& t)
{
    vec_fields(v, "a", t.a);
    vec_fields(v, "b", t.b);
    vec_fields(v, "c", t.c);
}
template <class V, class T>
void fields(V& v, Cylinder<T>& c)
{
    vec_fields(v, "p0", c.p0);
    vec_fields(v, "p1", c.p1);
    v.num("radius", c.radius);
    v.caps("caps", c.caps);
}
template <class V, class T>
void fields(V& v, Cone<T>& c)
{
    vec_fields(v, "p0", c.p0);
    v.num("r0", c.r0);
    vec_fields(v, "p1", c.p1);
    v.num("r1", c.r1);
    v.caps("caps", c.caps);
}
template <class V, class T>
void fields(V& v, Quadric<T>& q)
{
    v.num("A", q.A), v.num("B", q.B), v.num("C", q.C), v.num("D", q.D), v.num("E", q.E);
    v.num("F", q.F), v.num("G", q.G), v.num("H", q.H), v.num("I", q.I), v.num("J", q.J);
    vec_fields(v, "clip.lo", q.clip.lo);
    vec_fields(v, "clip.hi", q.clip.hi);
}
template <class V, class T>
void affine_fields(V& v, const char* name, Affine3<T>& a)
{
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 4; ++j) v.num(std::string(name) + "[" + std::to_string(i) + "][" + std::to_string(j) + "]", a.m[i][j]);
}
template <class V, class Prim>
void fields(V& v, Transformed<Prim>& x)
{
    fields(v, x.object);
    affine_fields(v, "to_world", x.to_world);
    affine_fields(v, "to_object", x.to_object);
}
template <class V, class T>
void ray_fields(V& v, Ray<T>& r)
{
    vec_fields(v, "ray.origin", r.origin);
    vec_fields(v, "ray.direction", r.direction);
    v.num("ray.tmin", r.tmin);
    v.num("ray.tmax", r.tmax);
}

// ---- numbers -----------------------------------------------------------------------------------
bool is_hex(char c) { return std::isxdigit(static_cast<unsigned char>(c)) != 0; }

// C99 hex floats ([+-]0x<hex>[.<hex>]p[+-]<dec>), inf and nan (as printf %a writes them).
bool parse_hex_float(const std::string& s, double& out)
{
    std::size_t i = 0;
    const bool negative = !s.empty() && s[0] == '-';
    if (!s.empty() && (s[0] == '+' || s[0] == '-')) i = 1;
    const std::string rest = s.substr(i);
    if (rest == "inf" || rest == "infinity") {
        out = negative ? -HUGE_VAL : HUGE_VAL;
        return true;
    }
    if (rest == "nan") {
        out = negative ? -std::nan("") : std::nan("");
        return true;
    }
    if (s.size() < i + 2 || s[i] != '0' || (s[i + 1] != 'x' && s[i + 1] != 'X')) return false;
    i += 2;
    std::size_t digits = 0;
    while (i < s.size() && is_hex(s[i])) ++i, ++digits;
    if (i < s.size() && s[i] == '.') {
        ++i;
        while (i < s.size() && is_hex(s[i])) ++i, ++digits;
    }
    if (digits == 0 || i >= s.size() || (s[i] != 'p' && s[i] != 'P')) return false;
    ++i;
    if (i < s.size() && (s[i] == '+' || s[i] == '-')) ++i;
    std::size_t exp_digits = 0;
    while (i < s.size() && std::isdigit(static_cast<unsigned char>(s[i]))) ++i, ++exp_digits;
    if (exp_digits == 0 || i != s.size()) return false;
    char* end = nullptr;
    out = std::strtod(s.c_str(), &end);
    return end == s.c_str() + s.size();
}

std::string hex(double x)
{
    if (std::isnan(x)) return std::signbit(x) ? "-nan" : "nan";
    if (std::isinf(x)) return x > 0 ? "inf" : "-inf";
    char buf[64];
    std::snprintf(buf, sizeof buf, "%a", x);
    return buf;
}

// ---- the parser's visitor ----------------------------------------------------------------------
struct Reader {
    const std::vector<std::string>& tokens;
    std::size_t next;
    const std::string& file;
    std::size_t line;
    const std::string& primitive;

    [[noreturn]] void fail(const std::string& expected) const { throw ParseError(file, line, expected); }

    const std::string& take(const std::string& field, const char* what)
    {
        if (next >= tokens.size()) fail(primitive + " field '" + field + "' (" + what + "), got end of line");
        return tokens[next++];
    }
    template <class T>
    void num(const std::string& field, T& x)
    {
        const std::string& tok = take(field, "a C99 hex float");
        double v;
        if (!parse_hex_float(tok, v))
            fail("a C99 hex float (printf %a, e.g. 0x1.8p+1) for " + primitive + " field '" + field + "', got '" + tok + "'");
        if constexpr (sizeof(T) == sizeof(float)) {
            if (!std::isnan(v) && static_cast<double>(static_cast<float>(v)) != v)
                fail("a value exactly representable as float for " + primitive + " field '" + field + "', got '" + tok + "'");
        }
        x = static_cast<T>(v);
    }
    void caps(const std::string& field, Caps& c)
    {
        const std::string& tok = take(field, "none or both");
        if (tok == "none") c = Caps::none;
        else if (tok == "both") c = Caps::both;
        else fail("'none' or 'both' for " + primitive + " field '" + field + "', got '" + tok + "'");
    }
};

// ---- the writer's visitor ----------------------------------------------------------------------
struct Writer {
    std::string out;
    template <class T>
    void num(const std::string&, T& x)
    {
        out += ' ';
        out += hex(static_cast<double>(x));
    }
    void caps(const std::string&, Caps& c) { out += c == Caps::both ? " both" : " none"; }
};

// A default-constructed alternative by run-time index.
template <std::size_t... I>
AnyInput make_input(std::size_t index, std::index_sequence<I...>)
{
    static const std::array<AnyInput (*)(), sizeof...(I)> makers = {
        +[]() -> AnyInput { return AnyInput(std::in_place_index<I>); }...};
    return makers[index]();
}

bool valid_family(const std::string& f)
{
    if (f.empty()) return false;
    return std::all_of(f.begin(), f.end(), [](char c) {
        return std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '_' || c == '-';
    });
}

std::vector<std::string> tokens_of(const std::string& line)
{
    std::istringstream in(line.substr(0, line.find('#')));
    std::vector<std::string> out;
    for (std::string t; in >> t;) out.push_back(t);
    return out;
}

}  // namespace

ParseError::ParseError(const std::string& file, std::size_t line, const std::string& expected)
    : std::runtime_error(file + ":" + std::to_string(line) + ": expected " + expected), file_(file), line_(line)
{
}

std::string primitive_name(const AnyInput& input) { return kind_names[input.index() % kinds]; }
Scalar scalar_of(const AnyInput& input) { return input.index() < kinds ? Scalar::f32 : Scalar::f64; }
const char* scalar_name(Scalar s) { return s == Scalar::f32 ? "float" : "double"; }
std::string family_class(const std::string& family) { return family.substr(0, family.find('.')); }

std::vector<Fixture> parse_fixtures(std::istream& in, const std::string& file_name)
{
    std::vector<Fixture> out;
    std::string text;
    for (std::size_t line = 1; std::getline(in, text); ++line) {
        const std::vector<std::string> tok = tokens_of(text);
        if (tok.empty()) continue;
        const auto fail = [&](const std::string& expected) { throw ParseError(file_name, line, expected); };
        if (!valid_family(tok[0])) fail("a family name (letters, digits, '.', '_', '-'), got '" + tok[0] + "'");
        if (tok.size() < 2) fail("a primitive name after the family, got end of line");
        const auto kind = std::find(kind_names.begin(), kind_names.end(), tok[1]);
        if (kind == kind_names.end())
            fail("a primitive name (sphere, plane, disk, parallelogram, triangle, cylinder, cone, quadric, or "
                 "transformed-<one of those>), got '" + tok[1] + "'");
        if (tok.size() < 3) fail("a number type 'float' or 'double' after the primitive, got end of line");
        if (tok[2] != "float" && tok[2] != "double") fail("a number type 'float' or 'double', got '" + tok[2] + "'");
        const std::size_t index = static_cast<std::size_t>(kind - kind_names.begin()) + (tok[2] == "double" ? kinds : 0);
        Fixture f{tok[0], make_input(index, std::make_index_sequence<2 * kinds>{})};
        Reader reader{tok, 3, file_name, line, tok[1]};
        std::visit(
            [&](auto& input) {
                ray_fields(reader, input.ray);
                fields(reader, input.prim);
            },
            f.input);
        if (reader.next != tok.size())
            fail("end of line after the " + tok[1] + " fields, got '" + tok[reader.next] + "'");
        out.push_back(std::move(f));
    }
    return out;
}

std::vector<Fixture> load_fixtures(const std::string& path)
{
    std::ifstream in(path);
    if (!in) throw ParseError(path, 0, "a readable file");
    return parse_fixtures(in, path);
}

std::vector<Fixture> load_fixture_directory(const std::string& dir)
{
    std::vector<std::string> names;
    if (DIR* d = opendir(dir.c_str())) {
        while (const dirent* e = readdir(d)) {
            const std::string n = e->d_name;
            if (n.size() > 4 && n.compare(n.size() - 4, 4, ".txt") == 0) names.push_back(n);
        }
        closedir(d);
    } else {
        throw ParseError(dir, 0, "a readable directory");
    }
    std::sort(names.begin(), names.end());
    std::vector<Fixture> out;
    for (const std::string& n : names) {
        std::vector<Fixture> part = load_fixtures(dir + "/" + n);
        out.insert(out.end(), std::make_move_iterator(part.begin()), std::make_move_iterator(part.end()));
    }
    return out;
}

std::string format_fixture(const Fixture& f)
{
    Writer w;
    w.out = f.family + " " + primitive_name(f.input) + " " + scalar_name(scalar_of(f.input));
    AnyInput copy = f.input;
    std::visit(
        [&](auto& input) {
            ray_fields(w, input.ray);
            fields(w, input.prim);
        },
        copy);
    return w.out;
}

void write_fixtures(std::ostream& out, const std::vector<Fixture>& fixtures)
{
    for (const Fixture& f : fixtures) out << format_fixture(f) << '\n';
}

}  // namespace rayq::oracle
