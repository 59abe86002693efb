// OpenMesh IO: the checked-in reference meshes (fixtures/meshes) match the tessellators and
// round-trip exactly through OFF, OBJ and PLY; the precision each format keeps is pinned: OFF and
// PLY keep floats, OBJ keeps 17 decimals in fixed notation (then float), OM keeps doubles.
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include <rayq/mesh/compare.hpp>
#include <rayq/mesh/io.hpp>

#ifndef RAYQ_MESH_FIXTURES
#error "RAYQ_MESH_FIXTURES (the fixtures/meshes directory) must be defined"
#endif

namespace {

using namespace rayq;
using namespace rayq::mesh;

struct Fixture {
    const char* file;
    const char* primitive;
};
// Written by `rayq-mesh-sweep --write-fixtures fixtures/meshes` (n = 8).
constexpr Fixture fixtures[] = {
    {"sphere_n8.off", "sphere"},
    {"cylinder_capped_n8.obj", "cylinder_capped"},
    {"frustum_capped_n8.ply", "frustum_capped"},
};

Tessellation fresh(const std::string& primitive, int n)
{
    for (const Case& c : standard_cases())
        if (c.name == primitive) return c.tessellate(n);
    throw std::logic_error("no case " + primitive);
}

// Faces as vertex index triples, each rotated to start at its smallest index (file formats keep
// the cyclic order, not necessarily the first corner).
std::vector<std::array<int, 3>> faces(const TriMesh& m)
{
    std::vector<std::array<int, 3>> out;
    for (const auto f : m.faces()) {
        std::array<int, 3> v{};
        int i = 0;
        for (const auto h : m.fh_range(f)) v[static_cast<std::size_t>(i++)] = m.to_vertex_handle(h).idx();
        while (v[0] > v[1] || v[0] > v[2]) v = {v[1], v[2], v[0]};
        out.push_back(v);
    }
    return out;
}

// What OpenMesh 9's OBJ writer and read_mesh make of a value: it is rounded to float, printed in
// fixed notation with 17 decimals (so values below ~1e-8 lose significant digits, and below 5e-18
// become 0) and parsed back as a double.
double through_obj(double x)
{
    char text[64];
    volatile float f = static_cast<float>(x);  // volatile: see to_float() in io.cpp (g++ 12 SLP bug)
    std::snprintf(text, sizeof text, "%.17f", static_cast<double>(f));
    return std::strtod(text, nullptr);
}

// Bitwise equality of points, vertex normals (when compared) and faces; `obj`: a as it comes back
// through an OBJ file.
void expect_identical(const TriMesh& a, const TriMesh& b, bool normals, bool obj = false)
{
    ASSERT_EQ(a.n_vertices(), b.n_vertices());
    ASSERT_EQ(a.n_faces(), b.n_faces());
    std::size_t points = 0, normal_diffs = 0;
    const auto expect = [obj](double x) { return obj ? through_obj(x) : x; };
    for (const auto v : a.vertices()) {
        const auto w = b.vertex_handle(static_cast<unsigned>(v.idx()));
        for (int k = 0; k < 3; ++k) {
            points += expect(a.point(v)[k]) != b.point(w)[k];
            normal_diffs += normals && expect(a.normal(v)[k]) != b.normal(w)[k];
        }
    }
    EXPECT_EQ(points, 0u) << "coordinates that differ";
    EXPECT_EQ(normal_diffs, 0u) << "normal components that differ";
    EXPECT_EQ(faces(a), faces(b));
}

std::string temp(const std::string& name) { return ::testing::TempDir() + "rayq_mesh_io_" + name; }

TEST(MeshIO, FixturesAreTheTessellationsRoundedToFloat)
{
    for (const Fixture& f : fixtures) {
        SCOPED_TRACE(f.file);
        TriMesh read;
        bool has_normals = false;
        ASSERT_TRUE(read_mesh(read, std::string(RAYQ_MESH_FIXTURES) + "/" + f.file, &has_normals));
        EXPECT_TRUE(has_normals);
        const Tessellation t = fresh(f.primitive, 8);
        expect_identical(rounded_to_float(t.mesh), read, true, std::string(f.file).find(".obj") != std::string::npos);
        const Topology topo = topology(read);
        EXPECT_EQ(topo.boundary_edges, 0u);
        EXPECT_EQ(topo.euler(), 2);
    }
}

TEST(MeshIO, FixturesRoundTripExactlyThroughEveryTextFormat)
{
    for (const Fixture& f : fixtures) {
        TriMesh original;
        ASSERT_TRUE(read_mesh(original, std::string(RAYQ_MESH_FIXTURES) + "/" + f.file));
        for (const char* ext : {".off", ".obj", ".ply", ".om"}) {
            SCOPED_TRACE(std::string(f.file) + " -> " + ext);
            const std::string path = temp(std::string(f.primitive) + ext);
            ASSERT_TRUE(write_mesh(original, path, true));
            TriMesh back;
            bool has_normals = false;
            ASSERT_TRUE(read_mesh(back, path, &has_normals));
            EXPECT_TRUE(has_normals);
            // An OBJ fixture read back and written as OBJ again is identical; other formats written as
            // OBJ lose digits of coordinates below ~1e-8 (fixed notation), exactly as modelled. OFF
            // and PLY hold the float rounding of what the OBJ reader read as doubles; OM all of it.
            const bool obj = std::string(ext) == ".obj", om = std::string(ext) == ".om";
            expect_identical(obj || om ? original : rounded_to_float(original), back, true, obj);
            if (obj && std::string(f.file).find(".obj") != std::string::npos) expect_identical(original, back, true);
            std::remove(path.c_str());
        }
    }
}

// OpenMesh 9's OFF/OBJ/PLY writers and readers go through Vec3f: a double mesh comes back as its
// float rounding, exactly (so float data round-trips, as above). The .om format keeps doubles.
TEST(MeshIO, TextFormatsKeepFloatPrecisionAndOmKeepsDouble)
{
    const Tessellation t = fresh("sphere", 16);
    const TriMesh as_float = rounded_to_float(t.mesh);
    std::size_t rounded = 0;
    for (const auto v : t.mesh.vertices())
        for (int k = 0; k < 3; ++k) rounded += t.mesh.point(v)[k] != as_float.point(v)[k];
    ASSERT_GT(rounded, 0u) << "the test needs coordinates that are not floats";
    for (const char* ext : {".off", ".obj", ".ply"}) {
        SCOPED_TRACE(ext);
        const std::string path = temp(std::string("double") + ext);
        ASSERT_TRUE(write_mesh(t.mesh, path, true));
        TriMesh back;
        ASSERT_TRUE(read_mesh(back, path));
        expect_identical(as_float, back, true, std::string(ext) == ".obj");
        std::remove(path.c_str());
    }
    const std::string path = temp("double.om");
    ASSERT_TRUE(write_mesh(t.mesh, path, true));
    TriMesh back;
    ASSERT_TRUE(read_mesh(back, path));
    expect_identical(t.mesh, back, true);
    std::remove(path.c_str());
}

// rayq's OFF/OBJ/PLY readers and OpenMesh's agree on the fixtures, up to OpenMesh's rounding to float
// (the fixtures hold floats, so the OFF and PLY ones agree bit for bit).
TEST(MeshIO, ReadsWhatOpenMeshReads)
{
    for (const Fixture& f : fixtures) {
        SCOPED_TRACE(f.file);
        const std::string path = std::string(RAYQ_MESH_FIXTURES) + "/" + f.file;
        TriMesh ours, theirs;
        ASSERT_TRUE(read_mesh(ours, path));
        OpenMesh::IO::Options opt = OpenMesh::IO::Options::VertexNormal;
        ASSERT_TRUE(OpenMesh::IO::read_mesh(theirs, path, opt));
        const bool obj = std::string(f.file).find(".obj") != std::string::npos;
        expect_identical(obj ? rounded_to_float(ours) : ours, theirs, true);
    }
}

TEST(MeshIO, ReadFailsCleanly)
{
    TriMesh m;
    std::string error;
    EXPECT_FALSE(read_mesh(m, temp("does_not_exist.off"), nullptr, &error));
    EXPECT_EQ(error, temp("does_not_exist.off") + ": cannot open the file");
    EXPECT_FALSE(read_mesh(m, std::string(RAYQ_MESH_FIXTURES) + "/README.md", nullptr, &error));
    EXPECT_NE(error.find("README.md: expected a file named .off, .obj, .ply or .om"), std::string::npos) << error;
}

// read_mesh on `text` written to `path` (removed afterwards).
bool read_written(const std::string& path, const char* text, TriMesh& m, bool* has_normals, std::string* error)
{
    {
        std::ofstream out(path, std::ios::binary);
        out << text;
    }
    const bool ok = read_mesh(m, path, has_normals, error);
    std::remove(path.c_str());
    return ok;
}

// A malformed file: false, an empty mesh, and "file:line: expected …".
TEST(MeshIO, MalformedTextFilesNameTheLine)
{
    struct Bad {
        const char* name;
        const char* text;
        int line;
        const char* expected;
    };
    const Bad cases[] = {
        {"bad_header.off", "# a comment\nOFX\n", 2, "expected OFF or NOFF, got 'OFX'"},
        {"short.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n", 4, "expected a point (3 numbers) for vertex 2, got the end of the file"},
        {"nan.off", "OFF 3 1 0\n0 0 0\n1 nan 0\n0 1 0\n3 0 1 2\n", 3, "expected y as a finite number, got 'nan'"},
        {"index.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n", 6, "expected vertex indices below the 3 points, got 3"},
        {"trailing.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n3 0 1 2\n", 7, "expected the end of the file after 1 faces"},
        {"repeat.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 2\n", 4, "expected a face's vertices to be distinct, got 1 twice"},
        {"zero.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n", 4, "expected a vertex index (1-based, or negative from the end), got '0'"},
        {"words.obj", "v 0 0 0\nv 1 0 0\nline 1 2\n", 3, "expected v, vn, f (or vt, vp, o, g, s, usemtl, mtllib, #), got 'line'"},
        {"normals.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nvn 0 0 1\nvn 0 0 -1\nf 1//1 2//1 3//1\nf 2//2 4//2 3//2\n", 8,
         "expected one normal per vertex"},
        {"binary.ply", "ply\nformat ascii 2.0\n", 2, "expected format ascii 1.0"},
        {"nox.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty float y\nproperty float z\nend_header\n0 0\n", 6,
         "expected a scalar vertex property x in the header"},
        {"list.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                     "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n4 0 1 2\n", 13,
         "expected 4 list items, got 3"},
        // Three triangles on edge 0–1, the third along 0→1 again: OpenMesh refuses it; read_mesh says so.
        {"fan.off", "OFF\n5 3 0\n0 0 0\n1 0 0\n0 1 0\n0 -1 0\n0 0 1\n3 0 1 2\n3 1 0 3\n3 0 1 4\n", 10,
         "expected a face that keeps the mesh a consistently oriented 2-manifold"},
        {"empty.obj", "", 0, nullptr},  // no faces, no points: an empty mesh, not an error
    };
    for (const Bad& c : cases) {
        SCOPED_TRACE(c.name);
        const std::string path = temp(c.name);
        TriMesh m;
        std::string error;
        const bool ok = read_written(path, c.text, m, nullptr, &error);
        if (!c.expected) {
            EXPECT_TRUE(ok) << error;
            continue;
        }
        EXPECT_FALSE(ok);
        EXPECT_EQ(m.n_vertices(), 0u);
        const std::string prefix = path + ":" + std::to_string(c.line) + ": " + c.expected;
        EXPECT_EQ(error.compare(0, prefix.size(), prefix), 0) << error;
    }
}

// What the formats allow beyond what OpenMesh writes: OFF counts on the keyword's line and face
// colours, OBJ polygons (split into triangles), negative indices and texture corners, PLY comments,
// extra properties and elements, CRLF line ends; coordinates keep double precision.
TEST(MeshIO, ReadsTheFormatsFreedoms)
{
    struct Good {
        const char* name;
        const char* text;
        std::size_t faces;
        bool normals;
    };
    const Good cases[] = {
        {"colours.off", "OFF 4 2 0\r\n0.1 0 0\r\n1 0 0\r\n1 1 0\r\n0 1 0\r\n3 0 1 2 255 0 0\r\n3 0 2 3 1 0 0 1\r\n", 2, false},
        {"quad.obj", "o quad\nv 0.1 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvn 0 0 1\ns off\nf -4/1/1 -3/1/1 -2/1/1 -1/1/1\n", 2, true},
        {"extra.ply", "ply\nformat ascii 1.0\ncomment made by hand\nelement vertex 3\nproperty double x\nproperty double y\n"
                      "property double z\nproperty uchar red\nelement face 1\nproperty list uchar int vertex_index\n"
                      "element edge 1\nproperty int vertex1\nproperty int vertex2\nend_header\n"
                      "0.1 0 0 7\n1 0 0 7\n0 1 0 7\n3 0 1 2\n0 1\n", 1, false},
    };
    for (const Good& c : cases) {
        SCOPED_TRACE(c.name);
        TriMesh m;
        std::string error;
        bool has_normals = false;
        ASSERT_TRUE(read_written(temp(c.name), c.text, m, &has_normals, &error)) << error;
        EXPECT_EQ(m.n_faces(), c.faces);
        EXPECT_EQ(has_normals, c.normals);
        EXPECT_EQ(m.point(m.vertex_handle(0))[0], 0.1) << "read as a double, not rounded to float";
    }
}

}  // namespace
