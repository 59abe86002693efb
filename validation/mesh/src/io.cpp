// OpenMesh IO for tessellations.
#include "rayq/mesh/io.hpp"

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

bool read_mesh(TriMesh& mesh, const std::string& path, bool* has_normals)
{
    quiet();
    mesh.clear();
    OpenMesh::IO::Options opt = OpenMesh::IO::Options::VertexNormal;
    const bool ok = OpenMesh::IO::read_mesh(mesh, path, opt);
    if (has_normals) *has_normals = ok && opt.check(OpenMesh::IO::Options::VertexNormal);
    return ok;
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
