// rayq::mesh — strict readers for the text mesh formats (OFF, OBJ, ASCII PLY), without OpenMesh.
//
// read_mesh (io.hpp) reads OFF, OBJ and ASCII PLY through these, not through OpenMesh's readers:
// OpenMesh's report a malformed file as a bare `false` (its log says why, nowhere else), parse
// coordinates into float, and drop a face it cannot add without a word. These name the file, the
// line and what was expected (MeshFormatError), keep every coordinate at double precision, and
// leave the faces to read_mesh, which reports a face the mesh refuses on its own line.
//
// What each format accepts (anything else is an error naming its line):
//   OFF  `OFF` or `NOFF` (normals follow each point); the counts `V F E`, on the header line or
//        the next; V points; F faces `n i_1 … i_n` with an optional RGB or RGBA colour (ignored).
//   OBJ  `v x y z`, `vn x y z`, `f a b c …` with corners `v`, `v/t`, `v//n` or `v/t/n` (1-based,
//        or negative: relative to the end); `vt`, `vp`, `o`, `g`, `s`, `usemtl`, `mtllib` are
//        skipped. Normals become vertex normals: every corner of a vertex must name the same one.
//   PLY  `format ascii 1.0`; `element vertex` with float properties x y z (and nx ny nz, all or
//        none; others are skipped); `element face` with a list property vertex_indices (or
//        vertex_index); other elements are skipped line by line.
// Everywhere: `#` comments (OFF, OBJ) and blank lines are skipped, coordinates must be finite
// numbers, indices must name an existing vertex, a face has at least three distinct vertices.
// The fuzz harness rayq_fuzz_parsers (tools/fuzz/parsers_fuzz_target.cpp) holds them to this.
#pragma once

#include <array>
#include <cstddef>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace rayq::mesh {

enum class TextFormat { off, obj, ply };

// By the path's extension (.off, .obj, .ply, any case); nullopt for anything else.
std::optional<TextFormat> text_format_of(const std::string& path);

// A face, as listed: vertex indices (0-based) and the line it was read from.
struct PolygonFace {
    std::vector<std::size_t> vertices;
    std::size_t line = 0;
};

// A mesh as the file lists it: points, vertex normals (empty, or one per point), polygons.
struct Polygons {
    std::vector<std::array<double, 3>> points;
    std::vector<std::array<double, 3>> normals;
    std::vector<PolygonFace> faces;
};

// A malformed mesh file: what() is "file:line: expected …" (line 1 for an empty file).
class MeshFormatError : public std::runtime_error {
public:
    MeshFormatError(const std::string& file, std::size_t line, const std::string& expected);
    const std::string& file() const { return file_; }
    std::size_t line() const { return line_; }

private:
    std::string file_;
    std::size_t line_;
};

// Parses `text` (the whole file) as `format`; `file` names it in errors. Throws MeshFormatError.
// A binary PLY header is an error here (read_mesh hands binary PLY to OpenMesh).
Polygons parse_mesh_text(std::string_view text, TextFormat format, const std::string& file);

}  // namespace rayq::mesh
