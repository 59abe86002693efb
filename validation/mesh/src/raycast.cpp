// Ray–mesh closest hit through a CGAL AABB tree (the only translation unit that includes CGAL).
#include "rayq/mesh/raycast.hpp"

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <iterator>
#include <limits>
#include <vector>

namespace rayq::mesh {

namespace {
using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = K::Point_3;
using Triangle3 = K::Triangle_3;
using Iterator = std::vector<Triangle3>::const_iterator;
using Primitive = CGAL::AABB_triangle_primitive<K, Iterator>;
using Tree = CGAL::AABB_tree<CGAL::AABB_traits<K, Primitive>>;

Point point(const Vec3d& v) { return {v.x, v.y, v.z}; }
}  // namespace

struct Raycaster::Impl {
    std::vector<Triangle3> triangles;
    std::vector<std::array<int, 3>> vertex;
    std::vector<std::array<Vec3d, 3>> position, normal;
    Tree tree;
};

Raycaster::Raycaster(const TriMesh& mesh) : impl_(std::make_unique<Impl>())
{
    Impl& d = *impl_;
    const std::size_t nf = mesh.n_faces();
    d.triangles.reserve(nf);
    d.vertex.reserve(nf);
    d.position.reserve(nf);
    d.normal.reserve(nf);
    const bool corner_normals = mesh.has_halfedge_normals();
    for (const auto f : mesh.faces()) {
        std::array<int, 3> v{};
        std::array<Vec3d, 3> p{}, n{};
        int i = 0;
        for (const auto h : mesh.fh_range(f)) {
            if (i == 3) break;
            const auto vh = mesh.to_vertex_handle(h);
            v[static_cast<std::size_t>(i)] = vh.idx();
            p[static_cast<std::size_t>(i)] = to_vec(mesh.point(vh));
            OpenMesh::Vec3d nv = corner_normals ? mesh.normal(h) : OpenMesh::Vec3d(0, 0, 0);
            if (nv.sqrnorm() == 0 && mesh.has_vertex_normals()) nv = mesh.normal(vh);
            n[static_cast<std::size_t>(i)] = to_vec(nv);
            ++i;
        }
        d.triangles.emplace_back(point(p[0]), point(p[1]), point(p[2]));
        d.vertex.push_back(v);
        d.position.push_back(p);
        d.normal.push_back(n);
    }
    d.tree.insert(d.triangles.cbegin(), d.triangles.cend());
    d.tree.build();
}

Raycaster::~Raycaster() = default;
Raycaster::Raycaster(Raycaster&&) noexcept = default;
Raycaster& Raycaster::operator=(Raycaster&&) noexcept = default;

std::size_t Raycaster::size() const { return impl_->triangles.size(); }

std::optional<MeshHit> Raycaster::closest_hit(const Ray<double>& ray) const
{
    const Impl& d = *impl_;
    if (d.triangles.empty() || !usable(ray)) return std::nullopt;
    // CGAL stores a ray as two points: origin and origin + direction (rounded). The predicates are
    // exact for that ray, which differs from ours by an ulp of the direction.
    const K::Ray_3 query(point(ray.origin), K::Vector_3(ray.direction.x, ray.direction.y, ray.direction.z));
    std::vector<Primitive::Id> found;
    d.tree.all_intersected_primitives(query, std::back_inserter(found));

    std::optional<MeshHit> best;
    bool degenerate = false;
    for (const Primitive::Id& id : found) {
        const std::size_t f = static_cast<std::size_t>(std::distance(d.triangles.cbegin(), id));
        const auto& p = d.position[f];
        // Möller–Trumbore in double, for a face the exact predicate says the ray meets.
        const Vec3d e1 = p[1] - p[0], e2 = p[2] - p[0];
        const Vec3d pv = cross(ray.direction, e2);
        const double det = dot(e1, pv);
        if (det == 0) {  // the ray lies in the face's plane: met edge-on
            degenerate = true;
            continue;
        }
        const Vec3d s = ray.origin - p[0];
        double u = dot(s, pv) / det;
        const Vec3d qv = cross(s, e1);
        double v = dot(ray.direction, qv) / det;
        const double t = dot(e2, qv) / det;
        if (!(ray.tmin < t && t < ray.tmax)) continue;
        if (best && !(t < best->t)) continue;
        // The predicate decided the face is met; clamp the rounded coordinates onto the triangle.
        u = std::clamp(u, 0.0, 1.0);
        v = std::clamp(v, 0.0, 1.0);
        if (u + v > 1) {
            const double sum = u + v;
            u /= sum;
            v /= sum;
        }
        const double w = 1 - u - v;
        MeshHit h{};
        h.t = t;
        h.face = static_cast<int>(f);
        h.vertex = d.vertex[f];
        h.bary = {w, u, v};
        h.point = w * p[0] + u * p[1] + v * p[2];
        const auto& n = d.normal[f];
        const Vec3d ni = w * n[0] + u * n[1] + v * n[2];
        const double len = length(ni);
        h.normal = len > 0 ? ni / len : ni;
        const CGAL::Orientation side = CGAL::orientation(d.triangles[f][0], d.triangles[f][1], d.triangles[f][2], point(ray.origin));
        h.front = side == CGAL::POSITIVE;
        h.coplanar = side == CGAL::COPLANAR;
        best = h;
    }
    if (best) {
        best->degenerate = degenerate;
        best->candidates = static_cast<int>(found.size());
    }
    return best;
}

}  // namespace rayq::mesh
