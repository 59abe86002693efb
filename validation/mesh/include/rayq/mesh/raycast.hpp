// rayq::mesh — closest hit of a ray with a triangle mesh through a CGAL AABB tree.
//
// The tree (CGAL::AABB_tree over Epick triangles) finds every face the ray meets with CGAL's exact
// (filtered) predicates, so no ray slips between two faces that share an edge; t and the barycentric
// coordinates are then computed in double (Möller–Trumbore) for those faces and the smallest t in
// the ray's window (tmin, tmax) wins. Whether the ray meets the face's front side is CGAL's exact
// orientation predicate: the origin lies strictly on the side its (b − a) × (c − a) points to.
// CGAL stays inside raycast.cpp; this header is plain C++.
#pragma once

#include <array>
#include <cstddef>
#include <memory>
#include <optional>

#include "mesh.hpp"

namespace rayq::mesh {

struct MeshHit {
    double t;                    // ray parameter (in units of the ray's direction)
    int face;                    // face index
    std::array<int, 3> vertex;   // the face's vertices, in the face's (counter-clockwise) order
    std::array<double, 3> bary;  // barycentric coordinates of the hit with respect to vertex[]
    Vec3d point;                 // Σ bary[i]·position(vertex[i])
    Vec3d normal;                // Σ bary[i]·corner normal, normalized: outward (the mesh's orientation)
    bool front;                  // the ray meets the face's front side (exact predicate)
    bool coplanar;               // the origin lies in the face's plane: `front` is meaningless
    bool degenerate;             // some face along the ray was met edge-on (ray in its plane)
    int candidates;              // faces the exact predicate reported along the whole ray
};

class Raycaster {
public:
    // Copies the mesh's triangles and corner normals (halfedge normals if set, else vertex normals).
    explicit Raycaster(const TriMesh& mesh);
    ~Raycaster();
    Raycaster(Raycaster&&) noexcept;
    Raycaster& operator=(Raycaster&&) noexcept;

    std::optional<MeshHit> closest_hit(const Ray<double>& ray) const;
    std::size_t size() const;  // number of triangles

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace rayq::mesh
