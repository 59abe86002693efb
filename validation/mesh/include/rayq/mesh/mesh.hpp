// rayq::mesh — tessellations of rayq's bounded primitives as OpenMesh triangle meshes (issue 5).
//
// Every bounded primitive has a tessellator: tessellate(prim, n) with n segments around the
// primitive's axis (or around its pole) and rings along it in proportion, so that the triangles stay
// roughly isotropic. Vertices lie on the exact surface up to the rounding of their coordinates
// (double throughout); faces are oriented outward (along the kernel's outward normal: ∇F for
// curved surfaces, the front side of flat ones); closed solids (sphere, capped cylinder, capped
// cone, ellipsoid) come out as closed 2-manifolds (no boundary edge, V − E + F = 2).
//
// Normals come from the analytic gradient, written independently of the kernel's own
// outward_normal() so that comparing the two means something:
//   * halfedge (corner) normals: the normal of the face's part at that corner — this is what
//     Raycaster interpolates. A rim vertex shared by a cap and the side has the cap's normal in
//     cap faces and the side's in side faces; at an apex (cone tip, where the gradient vanishes) the
//     corner normal is the normal along the generator through the middle of the face.
//   * vertex normals: the analytic normal at smooth vertices; at creases and apexes, the
//     normalized sum of the incident corner normals.
// Each face carries the Part it approximates (surface, cap0, cap1): Tessellation::part[face index].
//
// OpenMesh: the traits use Vec3d points and normals. OpenMesh's IO header must come before its mesh
// headers — it specializes the persistence templates that PropertyT's virtual functions use — and
// that in every translation unit: one that skipped it would instantiate PropertyT<Vec3d> (a
// vtable, inline functions) differently from io.cpp, and the linker keeps one of the two. So this
// header includes it first, always.
#pragma once

#include <functional>
#include <vector>

#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>

#include <rayq/rayq.hpp>

namespace rayq::mesh {

struct MeshTraits : OpenMesh::DefaultTraits {
    using Point = OpenMesh::Vec3d;
    using Normal = OpenMesh::Vec3d;
    VertexAttributes(OpenMesh::Attributes::Normal | OpenMesh::Attributes::Status);
    HalfedgeAttributes(OpenMesh::Attributes::PrevHalfedge | OpenMesh::Attributes::Normal);
    FaceAttributes(OpenMesh::Attributes::Normal | OpenMesh::Attributes::Status);
};
using TriMesh = OpenMesh::TriMesh_ArrayKernelT<MeshTraits>;

using Vec3d = rayq::Vec3<double>;

// An implicit function of the tessellated surface: F and ∇F at a point, for the given part
// (F = 0 on the part's surface, ∇F outward). |F|/|∇F| is the first-order (Sampson) distance.
struct Implicit {
    double value;
    Vec3d gradient;
};
using ImplicitFn = std::function<Implicit(const Vec3d&, Part)>;

struct Tessellation {
    TriMesh mesh;
    std::vector<Part> part;  // per face index: the part of the primitive the face approximates
    bool closed = false;     // a closed solid (expected: no boundary, Euler characteristic 2)
    ImplicitFn implicit;     // the primitive's surface, per part
    // Largest distance between the mesh and the surface (including the inscribed boundary polygons),
    // measured: the Sampson distance at the centroid, edge midpoints and three interior points of
    // every face (the extremes of a curved triangle's deviation are at such points).
    double deviation = 0;
    // The part of `deviation` the implicit function cannot see: how far the boundary polygon of a
    // flat part strays from the curved boundary it inscribes (a disk's rim: r(1 − cos(π/n))).
    double rim_deviation = 0;
};

inline Vec3d to_vec(const OpenMesh::Vec3d& v) { return {v[0], v[1], v[2]}; }
inline OpenMesh::Vec3d to_om(const Vec3d& v) { return {v.x, v.y, v.z}; }

// n >= 3 (segments around); throws std::invalid_argument for invalid primitives or n < 3.
Tessellation tessellate(const Sphere<double>& s, int n);
Tessellation tessellate(const Disk<double>& d, int n);
Tessellation tessellate(const Parallelogram<double>& p, int n);  // a k×k grid, k = max(1, n/8): exact
Tessellation tessellate(const Triangle<double>& t, int n);       // k² sub-triangles, k = max(1, n/8): exact
Tessellation tessellate(const Cylinder<double>& c, int n);       // open, or closed by its caps
Tessellation tessellate(const Cone<double>& c, int n);           // frustum or apex cone, open or capped
// Bounded quadrics: an ellipsoid in any orientation (clip box containing it), or a quadric whose
// axes are x, y, z (D = E = F = 0) cut to a bounded surface by the z-slab of its clip box: the named
// hyperboloids, paraboloid and elliptic cone, and z-cut ellipsoids. Tessellated in the parametric
// domain (angle around z, height), poles placed exactly; a double cone's two nappes meet at two
// coincident apex vertices (two components). Throws std::invalid_argument for anything else.
Tessellation tessellate(const Quadric<double>& q, int n);

// The object's tessellation mapped by to_world: vertices by to_world, normals by the inverse
// transpose (to_object's transposed linear part), faces reversed when det(to_world) < 0 so that
// they stay outward.
Tessellation transform(const Tessellation& object, const Affine3<double>& to_world, const Affine3<double>& to_object);

Tessellation tessellate(const Transformed<Sphere<double>>& x, int n);
Tessellation tessellate(const Transformed<Disk<double>>& x, int n);
Tessellation tessellate(const Transformed<Parallelogram<double>>& x, int n);
Tessellation tessellate(const Transformed<Triangle<double>>& x, int n);
Tessellation tessellate(const Transformed<Cylinder<double>>& x, int n);
Tessellation tessellate(const Transformed<Cone<double>>& x, int n);
Tessellation tessellate(const Transformed<Quadric<double>>& x, int n);

// Mesh facts used by the tests and the sweep.
struct Topology {
    std::size_t vertices = 0, edges = 0, faces = 0;
    std::size_t boundary_edges = 0, boundary_loops = 0;
    std::size_t nonmanifold_vertices = 0, degenerate_faces = 0;
    long euler() const { return static_cast<long>(vertices) - static_cast<long>(edges) + static_cast<long>(faces); }
};
Topology topology(const TriMesh& mesh);
double signed_volume(const TriMesh& mesh);  // (1/6) Σ a · (b × c) over faces
Vec3d face_normal(const TriMesh& mesh, int face);  // (b − a) × (c − a), not normalized
Vec3d centroid(const TriMesh& mesh, int face);

}  // namespace rayq::mesh
