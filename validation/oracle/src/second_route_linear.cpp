// rayq::oracle — the second route for flat primitives: CGAL's exact kernel (Epeck) intersects the
// ray's Line_3 with a Plane_3 or Triangle_3 (a parallelogram as two triangles sharing a
// diagonal). The window test and the entering flag (Plane_3::oriented_side of the direction) are
// derived from CGAL's objects; then the oracle's t and point are compared exactly.
#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/intersections.h>

#include <cmath>
#include <optional>
#include <type_traits>

#include "second_route.hpp"

namespace rayq::oracle {

namespace {

using K = CGAL::Exact_predicates_exact_constructions_kernel;
using FT = K::FT;

// Epeck's exact number type is mpq_class under CGAL_USE_GMPXX (CGAL::CGAL defines it), else Gmpq.
template <class Exact>
exact::Q exact_to_q(const Exact& q)
{
    if constexpr (std::is_same_v<Exact, mpq_class>) return q;
    else return exact::Q(q.mpq());
}
exact::Q to_q(const FT& x) { return exact_to_q(CGAL::exact(x)); }

template <class T>
K::Point_3 point(const Vec3<T>& v)
{
    return K::Point_3(static_cast<double>(v.x), static_cast<double>(v.y), static_cast<double>(v.z));
}
template <class T>
K::Vector_3 vector(const Vec3<T>& v)
{
    return K::Vector_3(static_cast<double>(v.x), static_cast<double>(v.y), static_cast<double>(v.z));
}

// CGAL's crossing of the line with a flat piece: the point, its t and whether the ray meets the
// front (positive) side of `oriented` there.
struct RouteHit {
    K::Point_3 p;
    FT t;
    bool entering;
};

template <class T>
std::optional<RouteHit> route_point(const Ray<T>& ray, const K::Point_3& p, const K::Plane_3& oriented)
{
    const K::Point_3 o = point(ray.origin);
    const K::Vector_3 d = vector(ray.direction);
    const FT t = ((p - o) * d) / (d * d);
    if (std::isfinite(ray.tmin) ? !(t > FT(static_cast<double>(ray.tmin))) : ray.tmin > 0) return std::nullopt;
    if (std::isfinite(ray.tmax) ? !(t < FT(static_cast<double>(ray.tmax))) : ray.tmax < 0) return std::nullopt;
    const bool entering = oriented.oriented_side(oriented.point() + d) == CGAL::ON_NEGATIVE_SIDE;
    return RouteHit{p, t, entering};
}

// A point result of intersection(), or nothing (no intersection, or the line lies in the plane).
template <class Result>
std::optional<K::Point_3> as_point(const Result& r)
{
    if (!r) return std::nullopt;
    if (const K::Point_3* p = boost::get<K::Point_3>(&*r)) return *p;
    return std::nullopt;
}

template <class T, class Prim>
Agreement compare_with_oracle(const Ray<T>& ray, const Prim& prim, const std::optional<RouteHit>& route)
{
    const exact::Solution oracle = second_route::oracle_answer(ray, prim);
    if (!oracle.defined) return second_route::disagree("outside the oracle's domain");
    const bool oracle_hit = oracle.first.has_value();
    if (oracle_hit != route.has_value())
        return second_route::disagree(std::string("hit: oracle ") + (oracle_hit ? "hits" : "misses") + ", CGAL " +
                                      (route ? "hits" : "misses"));
    if (!route) return second_route::agree();
    const exact::Crossing& c = oracle.crossings[*oracle.first];
    if (sgn(c.t.b) != 0 && sgn(oracle.D) != 0) return second_route::disagree("oracle t is irrational for a flat primitive");
    if (c.t.a != to_q(route->t))
        return second_route::disagree("t differs: oracle " + c.t.a.get_str() + ", CGAL " + to_q(route->t).get_str());
    exact::Converter conv;
    const exact::V o = conv.vec(ray.origin, ""), d = conv.vec(ray.direction, "");
    const exact::V p = o + d * c.t.a;
    if (p.x != to_q(route->p.x()) || p.y != to_q(route->p.y()) || p.z != to_q(route->p.z()))
        return second_route::disagree("the hit point differs");
    if (c.entering != route->entering) return second_route::disagree("entering differs");
    if (c.tangent) return second_route::disagree("a flat crossing marked tangent");
    return second_route::agree();
}

template <class T>
std::optional<RouteHit> triangle_route(const Ray<T>& ray, const K::Point_3& a, const K::Point_3& b, const K::Point_3& c)
{
    const K::Line_3 line(point(ray.origin), vector(ray.direction));
    const auto p = as_point(CGAL::intersection(line, K::Triangle_3(a, b, c)));
    if (!p) return std::nullopt;
    return route_point(ray, *p, K::Plane_3(a, b, c));
}

template <class T>
Agreement plane_agrees(const Ray<T>& ray, const Plane<T>& plane)
{
    const K::Plane_3 h(point(plane.point), vector(plane.normal));  // positive side along the normal
    const K::Line_3 line(point(ray.origin), vector(ray.direction));
    const auto p = as_point(CGAL::intersection(line, h));
    return compare_with_oracle(ray, plane, p ? route_point(ray, *p, h) : std::nullopt);
}

template <class T>
Agreement triangle_agrees(const Ray<T>& ray, const Triangle<T>& tri)
{
    return compare_with_oracle(ray, tri, triangle_route(ray, point(tri.a), point(tri.b), point(tri.c)));
}

template <class T>
Agreement parallelogram_agrees(const Ray<T>& ray, const Parallelogram<T>& q)
{
    // corner, corner + e0, corner + e0 + e1, corner + e1 — exact sums, both halves oriented along e0 × e1.
    const K::Point_3 c0 = point(q.corner);
    const K::Point_3 c1 = c0 + vector(q.edge0);
    const K::Point_3 c2 = c1 + vector(q.edge1);
    const K::Point_3 c3 = c0 + vector(q.edge1);
    auto hit = triangle_route(ray, c0, c1, c2);
    if (!hit) hit = triangle_route(ray, c0, c2, c3);
    return compare_with_oracle(ray, q, hit);
}

}  // namespace

Agreement second_route_agrees(const Ray<float>& r, const Plane<float>& p) { return plane_agrees(r, p); }
Agreement second_route_agrees(const Ray<double>& r, const Plane<double>& p) { return plane_agrees(r, p); }
Agreement second_route_agrees(const Ray<float>& r, const Triangle<float>& t) { return triangle_agrees(r, t); }
Agreement second_route_agrees(const Ray<double>& r, const Triangle<double>& t) { return triangle_agrees(r, t); }
Agreement second_route_agrees(const Ray<float>& r, const Parallelogram<float>& p) { return parallelogram_agrees(r, p); }
Agreement second_route_agrees(const Ray<double>& r, const Parallelogram<double>& p) { return parallelogram_agrees(r, p); }

}  // namespace rayq::oracle
