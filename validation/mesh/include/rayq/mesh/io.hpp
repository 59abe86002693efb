// rayq::mesh — reading and writing tessellations through OpenMesh IO.
//
// The format follows the file name's extension: .off, .obj, .ply (ASCII) and .om (OpenMesh's
// binary format). Writes ask OpenMesh for 17 significant digits (write_mesh(m, file, opt, 17)).
//
// Precision, as measured with OpenMesh 9.0 (Debian libopenmesh-dev 9.0-4): its OFF, OBJ and PLY
// writers export points and normals through BaseExporter::point()/normal(), which return Vec3f — so
// these three formats carry single precision whatever the requested digits. A double mesh written
// to OFF or PLY comes back rounded to float (each coordinate is exactly double(float(x))), and float
// data round-trips exactly. The OBJ writer moreover prints fixed notation with 17 decimals, so
// coordinates below ~1e-8 also lose significant digits (below 5e-18 they become 0); read_mesh
// parses those decimals as doubles (OpenMesh's own reader would round them to float), and an OBJ
// file read and written again is identical. Only the .om format keeps doubles (bit-exact round
// trip). mesh_io_test pins all of this.
#pragma once

#include <string>

#include "mesh.hpp"

namespace rayq::mesh {

// Writes positions and faces, and vertex normals when `normals` is true. Returns false on failure.
bool write_mesh(const TriMesh& mesh, const std::string& path, bool normals = true);
// Reads into `mesh` (cleared first); vertex normals are read when the file has them (then
// *has_normals is set true). OFF, OBJ and ASCII PLY go through rayq's own strict readers
// (text_formats.hpp: double precision, errors with file and line); binary PLY and .om through
// OpenMesh. On failure returns false, leaves `mesh` empty and sets *error to the reason:
// "file:line: expected …" for a malformed text file (a face the mesh refuses included), or
// "file: …" when the file cannot be opened, has another extension, or OpenMesh cannot read it.
bool read_mesh(TriMesh& mesh, const std::string& path, bool* has_normals = nullptr, std::string* error = nullptr);

// The mesh with every point and vertex normal rounded to float: what OFF/OBJ/PLY can store.
TriMesh rounded_to_float(const TriMesh& mesh);

}  // namespace rayq::mesh
