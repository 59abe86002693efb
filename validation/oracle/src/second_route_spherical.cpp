// rayq::oracle — the second route for spheres: CGAL's Exact_spherical_kernel_3 intersects the
// ray's Line_3 with the Sphere_3 (its algebraic kernel solves the system; points come back with
// Root_of_2 coordinates and a multiplicity). The window, the order and the entering flag are
// derived here from those points alone; only then is the oracle's answer compared, exactly.
#include <CGAL/Exact_spherical_kernel_3.h>
#include <CGAL/Spherical_kernel_intersections.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "second_route.hpp"

namespace rayq::oracle {

namespace {

using SK = CGAL::Exact_spherical_kernel_3;
using FT = SK::FT;
using Root = SK::Root_of_2;
using ArcPoint = SK::Circular_arc_point_3;

FT ft(double x) { return FT(x); }
FT ft(const exact::Q& q) { return FT(q.get_mpq_t()); }
Root root(const exact::Alg& x, const exact::Q& D)
{
    if (sgn(x.b) == 0 || sgn(D) == 0) return Root(ft(x.a));
    return CGAL::make_root_of_2(ft(x.a), ft(x.b), ft(D));
}

struct RoutePoint {
    ArcPoint p;
    unsigned multiplicity;
    Root t;
};

template <class T>
Agreement sphere_route(const Ray<T>& ray, const Sphere<T>& sphere)
{
    const exact::Solution oracle = second_route::oracle_answer(ray, sphere);
    if (!oracle.defined) return second_route::disagree("outside the oracle's domain");

    const double o[3] = {ray.origin.x, ray.origin.y, ray.origin.z};
    const double d[3] = {ray.direction.x, ray.direction.y, ray.direction.z};
    const SK::Point_3 origin(ft(o[0]), ft(o[1]), ft(o[2]));
    const SK::Line_3 line(origin, SK::Vector_3(ft(d[0]), ft(d[1]), ft(d[2])));
    const FT r(static_cast<double>(sphere.radius));
    const SK::Sphere_3 s(SK::Point_3(ft(sphere.center.x), ft(sphere.center.y), ft(sphere.center.z)), r * r);

    using Result = CGAL::SK3_Intersection_traits<SK, SK::Sphere_3, SK::Line_3>::type;
    std::vector<Result> found;
    CGAL::intersection(s, line, std::back_inserter(found));

    // t along the line from the coordinate where the direction is largest.
    int axis = 0;
    for (int i = 1; i < 3; ++i)
        if (std::fabs(d[i]) > std::fabs(d[axis])) axis = i;
    std::vector<RoutePoint> points;
    for (const Result& r : found) {
        const auto* pm = boost::get<std::pair<ArcPoint, unsigned>>(&r);
        if (!pm) return second_route::disagree("CGAL returned an unexpected intersection type");
        const Root coord = axis == 0 ? pm->first.x() : axis == 1 ? pm->first.y() : pm->first.z();
        Root t = coord - ft(o[axis]);
        t /= ft(d[axis]);
        points.push_back({pm->first, pm->second, t});
    }
    std::sort(points.begin(), points.end(), [](const RoutePoint& a, const RoutePoint& b) { return a.t < b.t; });

    // The first point inside the window; entering unless it is the second of two.
    const RoutePoint* first = nullptr;
    bool entering = false;
    for (std::size_t i = 0; i < points.size(); ++i) {
        const bool above = !std::isfinite(ray.tmin) ? ray.tmin < 0 : points[i].t > ft(static_cast<double>(ray.tmin));
        const bool below = !std::isfinite(ray.tmax) ? ray.tmax > 0 : points[i].t < ft(static_cast<double>(ray.tmax));
        if (above && below) {
            first = &points[i];
            entering = points[i].multiplicity == 2 || (points.size() == 2 && i == 0);
            break;
        }
    }

    const bool oracle_hit = oracle.first.has_value();
    if (oracle_hit != (first != nullptr))
        return second_route::disagree(std::string("hit: oracle ") + (oracle_hit ? "hits" : "misses") + ", CGAL " +
                                      (first ? "hits" : "misses"));
    if (!first) return second_route::agree();
    const exact::Crossing& c = oracle.crossings[*oracle.first];
    if (root(c.t, oracle.D) != first->t) return second_route::disagree("t differs: oracle " + exact::to_string(c.t, oracle.D));
    const exact::AV p = exact::point_at(exact::Converter{}.vec(ray.origin, ""), exact::Converter{}.vec(ray.direction, ""), c.t);
    if (root(p.x, oracle.D) != first->p.x() || root(p.y, oracle.D) != first->p.y() || root(p.z, oracle.D) != first->p.z())
        return second_route::disagree("the hit point differs");
    if (c.tangent != (first->multiplicity == 2)) return second_route::disagree("tangency differs");
    if (c.entering != entering) return second_route::disagree("entering differs");
    return second_route::agree();
}

}  // namespace

Agreement second_route_agrees(const Ray<float>& ray, const Sphere<float>& s) { return sphere_route(ray, s); }
Agreement second_route_agrees(const Ray<double>& ray, const Sphere<double>& s) { return sphere_route(ray, s); }

}  // namespace rayq::oracle
