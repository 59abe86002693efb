// Strict readers for OFF, OBJ and ASCII PLY (see text_formats.hpp for what each accepts).
#include "rayq/mesh/text_formats.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <limits>
#include <map>

namespace rayq::mesh {

MeshFormatError::MeshFormatError(const std::string& file, std::size_t line, const std::string& expected)
    : std::runtime_error(file + ":" + std::to_string(line) + ": expected " + expected), file_(file), line_(line)
{
}

std::optional<TextFormat> text_format_of(const std::string& path)
{
    const auto dot = path.find_last_of('.');
    if (dot == std::string::npos) return std::nullopt;
    std::string ext = path.substr(dot + 1);
    for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    if (ext == "off") return TextFormat::off;
    if (ext == "obj") return TextFormat::obj;
    if (ext == "ply") return TextFormat::ply;
    return std::nullopt;
}

namespace {

bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; }

// The file as numbered lines of whitespace-separated words, with a cursor.
class Lines {
public:
    Lines(std::string_view text, const std::string& file) : file_(file)
    {
        std::size_t start = 0;
        while (start < text.size()) {
            const std::size_t end = std::min(text.find('\n', start), text.size());
            lines_.push_back(text.substr(start, end - start));
            start = end + 1;
        }
    }

    // The next line that has words and is not a comment (comment: first word starts with
    // `comment_char`, 0 for none); false at the end of the file.
    bool next(std::vector<std::string_view>& words, char comment_char)
    {
        while (at_ < lines_.size()) {
            split(lines_[at_++], words);
            if (!words.empty() && !(comment_char && words[0][0] == comment_char)) return true;
        }
        return false;
    }
    // The line next() returned last (or the last line, at the end; line 1 for an empty file).
    std::size_t line() const { return std::max<std::size_t>(at_, 1); }
    [[noreturn]] void fail(const std::string& expected) const { throw MeshFormatError(file_, line(), expected); }
    // The next line that has words, or fail with "<what>, got the end of the file".
    void require(std::vector<std::string_view>& words, char comment_char, const std::string& what)
    {
        if (!next(words, comment_char)) fail(what + ", got the end of the file");
    }

private:
    static void split(std::string_view line, std::vector<std::string_view>& words)
    {
        words.clear();
        std::size_t i = 0;
        while (i < line.size()) {
            while (i < line.size() && is_space(line[i])) ++i;
            const std::size_t begin = i;
            while (i < line.size() && !is_space(line[i])) ++i;
            if (i > begin) words.push_back(line.substr(begin, i - begin));
        }
    }

    std::vector<std::string_view> lines_;
    std::size_t at_ = 0;
    const std::string& file_;
};

// Quoted for a message: printable ASCII as is, anything else as \xNN, at most 40 characters.
std::string quoted(std::string_view word)
{
    std::string out = "'";
    for (std::size_t i = 0; i < word.size() && i < 40; ++i) {
        const auto c = static_cast<unsigned char>(word[i]);
        if (c >= 0x20 && c < 0x7f) {
            out += static_cast<char>(c);
        } else {
            static const char hex[] = "0123456789abcdef";
            out += "\\x";
            out += hex[c >> 4];
            out += hex[c & 15];
        }
    }
    return out + (word.size() > 40 ? "…'" : "'");
}

std::optional<double> finite_number(std::string_view word)
{
    if (!word.empty() && word[0] == '+') word.remove_prefix(1);  // from_chars takes no '+'
    double x = 0;
    const auto [end, ec] = std::from_chars(word.data(), word.data() + word.size(), x);
    if (ec != std::errc() || end != word.data() + word.size() || !std::isfinite(x)) return std::nullopt;
    return x;
}

template <class Int>
std::optional<Int> integer(std::string_view word)
{
    if (!word.empty() && word[0] == '+') word.remove_prefix(1);
    Int x = 0;
    const auto [end, ec] = std::from_chars(word.data(), word.data() + word.size(), x);
    if (ec != std::errc() || end != word.data() + word.size()) return std::nullopt;
    return x;
}

double number_at(const Lines& lines, std::string_view word, const char* what)
{
    const auto x = finite_number(word);
    if (!x) lines.fail(std::string(what) + " as a finite number, got " + quoted(word));
    return *x;
}

std::size_t count_at(const Lines& lines, std::string_view word, const char* what)
{
    const auto n = integer<unsigned long long>(word);
    if (!n || *n > std::numeric_limits<std::size_t>::max()) lines.fail(std::string(what) + " as a count, got " + quoted(word));
    return static_cast<std::size_t>(*n);
}

// At least three vertices, each an index below `points`, no vertex twice.
void check_face(const Lines& lines, const PolygonFace& face, std::size_t points)
{
    if (face.vertices.size() < 3) lines.fail("a face with at least 3 vertices, got " + std::to_string(face.vertices.size()));
    for (std::size_t i = 0; i < face.vertices.size(); ++i) {
        if (face.vertices[i] >= points)
            lines.fail("vertex indices below the " + std::to_string(points) + " points, got " + std::to_string(face.vertices[i]));
        for (std::size_t j = 0; j < i; ++j)
            if (face.vertices[j] == face.vertices[i])
                lines.fail("a face's vertices to be distinct, got " + std::to_string(face.vertices[i]) + " twice");
    }
}

// Capacity for `count` items, but never more than the text could hold (a count is only a claim).
template <class V>
void reserve_for(V& v, std::size_t count, std::string_view text)
{
    v.reserve(std::min(count, text.size() / 2 + 1));
}

Polygons parse_off(std::string_view text, const std::string& file)
{
    Lines lines(text, file);
    std::vector<std::string_view> w;
    lines.require(w, '#', "OFF or NOFF");
    const bool normals = w[0] == "NOFF";
    if (w[0] != "OFF" && !normals) lines.fail("OFF or NOFF, got " + quoted(w[0]));
    std::size_t first = 1;  // the counts may follow the keyword on its line
    if (w.size() == 1) {
        lines.require(w, '#', "the counts 'vertices faces edges'");
        first = 0;
    }
    if (w.size() - first != 3) lines.fail("the counts 'vertices faces edges' (3 numbers)");
    const std::size_t nv = count_at(lines, w[first], "the vertex count");
    const std::size_t nf = count_at(lines, w[first + 1], "the face count");
    (void)count_at(lines, w[first + 2], "the edge count");

    Polygons mesh;
    reserve_for(mesh.points, nv, text);
    const std::size_t per_point = normals ? 6 : 3;
    const std::string point_words = normals ? "a point and its normal (6 numbers)" : "a point (3 numbers)";
    for (std::size_t i = 0; i < nv; ++i) {
        lines.require(w, '#', point_words + " for vertex " + std::to_string(i));
        if (w.size() != per_point) lines.fail(point_words + ", got " + std::to_string(w.size()) + " words");
        mesh.points.push_back({number_at(lines, w[0], "x"), number_at(lines, w[1], "y"), number_at(lines, w[2], "z")});
        if (normals) mesh.normals.push_back({number_at(lines, w[3], "nx"), number_at(lines, w[4], "ny"), number_at(lines, w[5], "nz")});
    }
    reserve_for(mesh.faces, nf, text);
    for (std::size_t f = 0; f < nf; ++f) {
        lines.require(w, '#', "face " + std::to_string(f) + " of " + std::to_string(nf));
        const std::size_t n = count_at(lines, w[0], "the face's vertex count");
        const std::size_t colours = w.size() - 1 >= n ? w.size() - 1 - n : std::size_t(-1);
        if (colours != 0 && colours != 3 && colours != 4)
            lines.fail(std::to_string(n) + " vertex indices (and an optional RGB or RGBA colour), got " + std::to_string(w.size() - 1) + " words");
        PolygonFace face{{}, lines.line()};
        for (std::size_t k = 1; k <= n; ++k) face.vertices.push_back(count_at(lines, w[k], "a vertex index"));
        for (std::size_t k = n + 1; k < w.size(); ++k) (void)number_at(lines, w[k], "a colour component");
        check_face(lines, face, nv);
        mesh.faces.push_back(std::move(face));
    }
    if (lines.next(w, '#')) lines.fail("the end of the file after " + std::to_string(nf) + " faces, got " + quoted(w[0]));
    return mesh;
}

Polygons parse_obj(std::string_view text, const std::string& file)
{
    Lines lines(text, file);
    std::vector<std::string_view> w;
    Polygons mesh;
    std::vector<std::array<double, 3>> normals;         // as listed by vn
    std::vector<std::optional<std::size_t>> normal_of;  // per point: the vn its corners name
    bool corners_with_normals = false, corners_without = false;
    std::size_t normal_conflict_line = 0;
    // A 1-based or negative (relative) OBJ index into `size` items, as 0-based.
    const auto index = [&lines](std::string_view word, std::size_t size, const char* what) {
        const auto i = integer<long long>(word);
        if (!i || *i == 0) lines.fail(std::string(what) + " index (1-based, or negative from the end), got " + quoted(word));
        const long long n = static_cast<long long>(std::min<std::size_t>(size, std::numeric_limits<long long>::max()));
        const long long zero_based = *i > 0 ? *i - 1 : n + *i;
        if (zero_based < 0 || zero_based >= n)
            lines.fail(std::string(what) + " index naming one of the " + std::to_string(size) + " listed so far, got " + quoted(word));
        return static_cast<std::size_t>(zero_based);
    };
    const auto triple = [&lines](const std::vector<std::string_view>& w, const char* what) {
        if (w.size() != 4) lines.fail(std::string(what) + ": 3 numbers, got " + std::to_string(w.size() - 1));
        return std::array<double, 3>{number_at(lines, w[1], "x"), number_at(lines, w[2], "y"), number_at(lines, w[3], "z")};
    };
    while (lines.next(w, '#')) {
        const std::string_view key = w[0];
        if (key == "v") {
            mesh.points.push_back(triple(w, "a point after v"));
            normal_of.emplace_back();
        } else if (key == "vn") {
            normals.push_back(triple(w, "a normal after vn"));
        } else if (key == "f") {
            PolygonFace face{{}, lines.line()};
            for (std::size_t k = 1; k < w.size(); ++k) {
                const std::string_view corner = w[k];
                const std::size_t s1 = corner.find('/');
                const std::size_t v = index(corner.substr(0, s1), mesh.points.size(), "a vertex");
                face.vertices.push_back(v);
                std::optional<std::size_t> n;
                if (s1 != std::string_view::npos) {
                    const std::size_t s2 = corner.find('/', s1 + 1);
                    if (s2 != std::string_view::npos) {
                        n = index(corner.substr(s2 + 1), normals.size(), "a normal");
                    }
                    const std::string_view texture = corner.substr(s1 + 1, s2 == std::string_view::npos ? std::string_view::npos : s2 - s1 - 1);
                    if (!texture.empty() && !integer<long long>(texture)) lines.fail("a texture index in corner " + quoted(corner));
                }
                (n ? corners_with_normals : corners_without) = true;
                if (n) {
                    if (normal_of[v] && *normal_of[v] != *n && normals[*normal_of[v]] != normals[*n] && normal_conflict_line == 0)
                        normal_conflict_line = lines.line();
                    normal_of[v] = n;
                }
            }
            check_face(lines, face, mesh.points.size());
            mesh.faces.push_back(std::move(face));
        } else if (key != "vt" && key != "vp" && key != "o" && key != "g" && key != "s" && key != "usemtl" && key != "mtllib") {
            lines.fail("v, vn, f (or vt, vp, o, g, s, usemtl, mtllib, #), got " + quoted(key));
        }
    }
    if (corners_with_normals) {
        if (normal_conflict_line)
            throw MeshFormatError(file, normal_conflict_line, "one normal per vertex (a mesh keeps vertex normals), got a vertex whose corners name different normals");
        if (corners_without)
            lines.fail("normals on every face corner or on none (a mesh keeps vertex normals), got faces of both kinds");
        mesh.normals.reserve(mesh.points.size());
        for (std::size_t v = 0; v < mesh.points.size(); ++v) {
            if (!normal_of[v]) lines.fail("every vertex in a face (vertex " + std::to_string(v + 1) + " is in none, so it has no normal)");
            mesh.normals.push_back(normals[*normal_of[v]]);
        }
    }
    return mesh;
}

Polygons parse_ply(std::string_view text, const std::string& file)
{
    Lines lines(text, file);
    std::vector<std::string_view> w;
    lines.require(w, 0, "ply");
    if (w.size() != 1 || w[0] != "ply") lines.fail("ply, got " + quoted(w[0]));
    lines.require(w, 0, "format ascii 1.0");
    if (w.size() != 3 || w[0] != "format" || w[1] != "ascii" || w[2] != "1.0")
        lines.fail("format ascii 1.0 (binary PLY goes to OpenMesh, which reads it without line numbers)");

    struct Property {
        std::string name;
        bool list = false;
    };
    struct Element {
        std::string name;
        std::size_t count = 0;
        std::vector<Property> properties;
    };
    std::vector<Element> elements;
    static const char* const scalar_types[] = {"char", "uchar", "short", "ushort", "int", "uint", "float", "double", "int8", "uint8",
                                               "int16", "uint16", "int32", "uint32", "float32", "float64"};
    const auto scalar_type = [](std::string_view t) {
        return std::any_of(std::begin(scalar_types), std::end(scalar_types), [t](const char* s) { return t == s; });
    };
    for (;;) {
        lines.require(w, 0, "end_header");
        if (w[0] == "end_header" && w.size() == 1) break;
        if (w[0] == "comment" || w[0] == "obj_info") continue;
        if (w[0] == "element") {
            if (w.size() != 3) lines.fail("element <name> <count>");
            elements.push_back({std::string(w[1]), count_at(lines, w[2], "the element count"), {}});
        } else if (w[0] == "property") {
            if (elements.empty()) lines.fail("element before the first property");
            const bool list = w.size() == 5 && w[1] == "list";
            if (list ? !(scalar_type(w[2]) && scalar_type(w[3])) : !(w.size() == 3 && scalar_type(w[1])))
                lines.fail("property <type> <name> or property list <count type> <item type> <name>");
            const std::string name(w.back());
            for (const Property& p : elements.back().properties)
                if (p.name == name) lines.fail("distinct property names, got " + quoted(name) + " twice");
            elements.back().properties.push_back({name, list});
        } else {
            lines.fail("element, property, comment or end_header, got " + quoted(w[0]));
        }
    }
    // Which column holds what, checked before any data line is read.
    const auto find = [](const Element& e, const char* name) {
        for (std::size_t i = 0; i < e.properties.size(); ++i)
            if (e.properties[i].name == name) return static_cast<long>(i);
        return -1L;
    };
    const Element* vertex = nullptr;
    const Element* face = nullptr;
    for (const Element& e : elements) {
        if (e.name == "vertex" && !vertex) vertex = &e;
        if (e.name == "face" && !face) face = &e;
    }
    if (!vertex) lines.fail("an element vertex in the header");
    long xyz[3], nxyz[3];
    const char* const names[] = {"x", "y", "z", "nx", "ny", "nz"};
    int normals_found = 0;
    for (int k = 0; k < 3; ++k) {
        xyz[k] = find(*vertex, names[k]);
        nxyz[k] = find(*vertex, names[k + 3]);
        if (xyz[k] < 0 || vertex->properties[static_cast<std::size_t>(xyz[k])].list)
            lines.fail(std::string("a scalar vertex property ") + names[k] + " in the header");
        normals_found += nxyz[k] >= 0 && !vertex->properties[static_cast<std::size_t>(nxyz[k])].list;
    }
    if (normals_found != 0 && normals_found != 3) lines.fail("all of nx, ny, nz or none of them in the header");
    long indices = -1;
    if (face) {
        indices = find(*face, "vertex_indices");
        if (indices < 0) indices = find(*face, "vertex_index");
        if (indices < 0 || !face->properties[static_cast<std::size_t>(indices)].list)
            lines.fail("a list property vertex_indices (or vertex_index) of element face in the header");
    }

    Polygons mesh;
    for (const Element& e : elements) {
        const bool is_vertex = &e == vertex, is_face = &e == face;
        if (is_vertex) reserve_for(mesh.points, e.count, text);
        if (is_vertex && normals_found) reserve_for(mesh.normals, e.count, text);
        if (is_face) reserve_for(mesh.faces, e.count, text);
        for (std::size_t i = 0; i < e.count; ++i) {
            lines.require(w, 0, "line " + std::to_string(i + 1) + " of the " + std::to_string(e.count) + " of element " + e.name);
            std::vector<double> scalars(e.properties.size());
            PolygonFace f{{}, lines.line()};
            std::size_t at = 0;
            for (std::size_t p = 0; p < e.properties.size(); ++p) {
                if (at >= w.size()) lines.fail("a value for property " + e.properties[p].name + ", got the end of the line");
                if (!e.properties[p].list) {
                    scalars[p] = number_at(lines, w[at++], "a property value");
                    continue;
                }
                const std::size_t n = count_at(lines, w[at++], "a list length");
                if (n > w.size() - at) lines.fail(std::to_string(n) + " list items, got " + std::to_string(w.size() - at));
                for (std::size_t k = 0; k < n; ++k) {
                    if (is_face && static_cast<long>(p) == indices) f.vertices.push_back(count_at(lines, w[at], "a vertex index"));
                    else (void)number_at(lines, w[at], "a list item");
                    ++at;
                }
            }
            if (at != w.size()) lines.fail("one value per property of element " + e.name + ", got " + std::to_string(w.size() - at) + " more");
            if (is_vertex) {
                const auto s = [&scalars](long column) { return scalars[static_cast<std::size_t>(column)]; };
                mesh.points.push_back({s(xyz[0]), s(xyz[1]), s(xyz[2])});
                if (normals_found) mesh.normals.push_back({s(nxyz[0]), s(nxyz[1]), s(nxyz[2])});
            }
            if (is_face) {
                check_face(lines, f, vertex->count);
                mesh.faces.push_back(std::move(f));
            }
        }
    }
    if (lines.next(w, 0)) lines.fail("the end of the file after the elements the header lists, got " + quoted(w[0]));
    // A face may name a vertex whose line comes later in the file (face before vertex): the
    // indices were checked against the header's vertex count, which the data then had to meet.
    return mesh;
}

}  // namespace

Polygons parse_mesh_text(std::string_view text, TextFormat format, const std::string& file)
{
    switch (format) {
    case TextFormat::off: return parse_off(text, file);
    case TextFormat::obj: return parse_obj(text, file);
    case TextFormat::ply: return parse_ply(text, file);
    }
    throw std::logic_error("parse_mesh_text: unknown format");
}

}  // namespace rayq::mesh
