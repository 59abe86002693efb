// OpenMesh IO for tessellations.
#include "rayq/mesh/io.hpp"

#include <fstream>
#include <optional>
#include <sstream>

#include "rayq/mesh/text_formats.hpp"

namespace rayq::mesh {

namespace {
struct Quiet {
    Quiet() { omlog().disable(); }
};
void quiet()
{
    static const Quiet once;
    (void)once;
}
}  // namespace

bool write_mesh(const TriMesh& mesh, const std::string& path, bool normals)
{
    quiet();
    OpenMesh::IO::Options opt = OpenMesh::IO::Options::Default;
    if (normals) opt += OpenMesh::IO::Options::VertexNormal;
    if (path.size() >= 3 && path.compare(path.size() - 3, 3, ".om") == 0) opt += OpenMesh::IO::Options::Binary;
    return OpenMesh::IO::write_mesh(mesh, path, opt, 17);
}

namespace {

std::optional<std::string> file_text(const std::string& path)
{
    std::ifstream in(path, std::ios::binary);
    if (!in) return std::nullopt;
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
}

// "ply" then "format binary_…": OpenMesh reads it (there are no lines to name).
bool binary_ply(const std::string& text)
{
    const std::size_t second = text.find('\n');
    return second != std::string::npos && text.compare(second + 1, 13, "format binary") == 0;
}

// The listed polygons as a TriMesh: OpenMesh splits polygons into triangles and refuses a face that
// would make the mesh non-manifold, which is reported on the face's line instead of being dropped.
void build(TriMesh& mesh, const Polygons& polygons, const std::string& path)
{
    std::vector<TriMesh::VertexHandle> vertices;
    vertices.reserve(polygons.points.size());
    for (const auto& p : polygons.points) vertices.push_back(mesh.add_vertex({p[0], p[1], p[2]}));
    for (std::size_t i = 0; i < polygons.normals.size(); ++i) {
        const auto& n = polygons.normals[i];
        mesh.set_normal(vertices[i], {n[0], n[1], n[2]});
    }
    std::vector<TriMesh::VertexHandle> corners;
    for (const PolygonFace& face : polygons.faces) {
        corners.clear();
        for (const std::size_t v : face.vertices) corners.push_back(vertices[v]);
        omerr().disable();  // its "complex edge" line would say less than the error below
        const bool added = mesh.add_face(corners).is_valid();
        omerr().enable();
        if (!added)
            throw MeshFormatError(path, face.line,
                                  "a face that keeps the mesh a consistently oriented 2-manifold (an edge of this one already has two "
                                  "faces or the same direction in another face, or it pinches a vertex)");
    }
}

}  // namespace

bool read_mesh(TriMesh& mesh, const std::string& path, bool* has_normals, std::string* error)
{
    quiet();
    mesh.clear();
    if (has_normals) *has_normals = false;
    const auto fail = [&](const std::string& message) {
        mesh.clear();
        if (error) *error = message;
        return false;
    };
    const std::optional<std::string> text = file_text(path);
    if (!text) return fail(path + ": cannot open the file");
    const std::optional<TextFormat> format = text_format_of(path);
    const bool om = path.size() >= 3 && path.compare(path.size() - 3, 3, ".om") == 0;
    if (format && !(*format == TextFormat::ply && binary_ply(*text))) {
        try {
            const Polygons polygons = parse_mesh_text(*text, *format, path);
            build(mesh, polygons, path);
            if (has_normals) *has_normals = !polygons.normals.empty();
            return true;
        } catch (const MeshFormatError& e) {
            return fail(e.what());
        }
    }
    if (!format && !om) return fail(path + ": expected a file named .off, .obj, .ply or .om (the name picks the format)");
    OpenMesh::IO::Options opt = OpenMesh::IO::Options::VertexNormal;
    if (!OpenMesh::IO::read_mesh(mesh, path, opt))
        return fail(path + ": expected a mesh OpenMesh can read as binary " + (om ? "OM" : "PLY") + " (it says no more, and a binary file has no lines)");
    if (has_normals) *has_normals = opt.check(OpenMesh::IO::Options::VertexNormal);
    return true;
}

namespace {
// double → float → double, through a volatile: g++ 12.2 (Debian 12.2.0-14) at -O2 vectorizes a pair
// of `(double)(float)x` conversions (SLP) into a plain copy, dropping the rounding — wrong code,
// reproduced with `struct V { double v[3]; }; V g(const V& x) { return {{(double)(float)x.v[0],
// (double)(float)x.v[1], (double)(float)x.v[2]}}; }`: components 0 and 1 come back unrounded
// (fine at -O1 or with -fno-tree-slp-vectorize, and with clang).
double to_float(double x)
{
    volatile float f = static_cast<float>(x);
    return f;
}
}  // namespace

TriMesh rounded_to_float(const TriMesh& mesh)
{
    TriMesh out = mesh;
    const auto round = [](const OpenMesh::Vec3d& v) { return OpenMesh::Vec3d(to_float(v[0]), to_float(v[1]), to_float(v[2])); };
    for (const auto v : out.vertices()) {
        out.set_point(v, round(out.point(v)));
        out.set_normal(v, round(out.normal(v)));
    }
    return out;
}

}  // namespace rayq::mesh
