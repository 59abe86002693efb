// The primitives of the mesh cross-check, type-erased into Case (the one place that instantiates
// the kernel's intersect for every primitive type).
#include <cstdio>
#include <string>

#include "rayq/mesh/compare.hpp"

namespace rayq::mesh {

std::string hex(double v)
{
    char buf[64];
    std::snprintf(buf, sizeof buf, "%a", v);
    return buf;
}

std::string hex(const Vec3d& v) { return "{" + hex(v.x) + ", " + hex(v.y) + ", " + hex(v.z) + "}"; }

std::string describe(const Ray<double>& r)
{
    return "rayq::Ray<double>{" + hex(r.origin) + ", " + hex(r.direction) + "}";
}

namespace {

const char* caps(Caps c) { return c == Caps::both ? "rayq::Caps::both" : "rayq::Caps::none"; }

std::string repro(const Sphere<double>& s) { return "rayq::Sphere<double>{" + hex(s.center) + ", " + hex(s.radius) + "}"; }
std::string repro(const Disk<double>& d)
{
    return "rayq::Disk<double>{" + hex(d.center) + ", " + hex(d.normal) + ", " + hex(d.radius) + "}";
}
std::string repro(const Parallelogram<double>& p)
{
    return "rayq::Parallelogram<double>{" + hex(p.corner) + ", " + hex(p.edge0) + ", " + hex(p.edge1) + "}";
}
std::string repro(const Triangle<double>& t) { return "rayq::Triangle<double>{" + hex(t.a) + ", " + hex(t.b) + ", " + hex(t.c) + "}"; }
std::string repro(const Cylinder<double>& c)
{
    return "rayq::Cylinder<double>{" + hex(c.p0) + ", " + hex(c.p1) + ", " + hex(c.radius) + ", " + caps(c.caps) + "}";
}
std::string repro(const Cone<double>& c)
{
    return "rayq::Cone<double>{" + hex(c.p0) + ", " + hex(c.r0) + ", " + hex(c.p1) + ", " + hex(c.r1) + ", " + caps(c.caps) + "}";
}
std::string repro(const Quadric<double>& q)
{
    std::string s = "rayq::Quadric<double>{";
    for (double v : {q.A, q.B, q.C, q.D, q.E, q.F, q.G, q.H, q.I, q.J}) s += hex(v) + ", ";
    return s + "{" + hex(q.clip.lo) + ", " + hex(q.clip.hi) + "}}";
}
std::string repro(const Affine3<double>& a)
{
    std::string s = "rayq::Affine3<double>{{";
    for (int i = 0; i < 3; ++i) {
        s += i ? ", {" : "{";
        for (int j = 0; j < 4; ++j) s += (j ? ", " : "") + hex(a.m[i][j]);
        s += "}";
    }
    return s + "}}";
}
template <class Prim>
std::string repro(const Transformed<Prim>& x)
{
    return "rayq::transformed(" + repro(x.object) + ", " + repro(x.to_world) + ")";
}

template <class Prim>
Case make_case(std::string name, const Prim& prim, bool flat, bool closed, bool apex)
{
    Case c;
    c.name = std::move(name);
    c.flat = flat;
    c.closed = closed;
    c.apex = apex;
    c.tessellate = [prim](int n) { return tessellate(prim, n); };
    c.intersect = [prim](const Ray<double>& r) { return intersect(accurate, r, prim); };
    c.outward_normal = [prim](const Vec3d& p, Part part) { return outward_normal(prim, p, part); };
    c.reproducer = repro(prim);
    return c;
}

Affine3<double> shear()
{
    return {{{1.0, 0.35, -0.2, 0.1}, {0.0, 0.9, 0.25, -0.3}, {0.15, 0.0, 1.1, 0.2}}};
}

}  // namespace

std::vector<Case> standard_cases()
{
    using V = Vec3d;
    std::vector<Case> out;
    out.push_back(make_case("sphere", Sphere<double>{{0.25, -0.5, 0.125}, 1.25}, false, true, false));
    out.push_back(make_case("disk", Disk<double>{{0.1, 0.2, -0.3}, {0.3, -0.5, 1.0}, 1.1}, true, false, false));
    out.push_back(make_case("parallelogram", Parallelogram<double>{{-1.0, -0.5, 0.2}, {2.0, 0.3, 0.1}, {0.4, 1.5, -0.3}}, true, false, false));
    out.push_back(make_case("triangle", Triangle<double>{{-1.0, -1.0, 0.1}, {1.2, -0.8, 0.3}, {0.1, 1.1, -0.2}}, true, false, false));
    const Cylinder<double> cyl{{0.0, 0.0, -1.0}, {0.2, 0.1, 1.0}, 0.7, Caps::none};
    out.push_back(make_case("cylinder_open", cyl, false, false, false));
    out.push_back(make_case("cylinder_capped", Cylinder<double>{cyl.p0, cyl.p1, cyl.radius, Caps::both}, false, true, false));
    const Cone<double> frustum{{0.0, 0.0, -1.0}, 1.0, {0.1, 0.2, 0.8}, 0.4, Caps::none};
    out.push_back(make_case("frustum_open", frustum, false, false, false));
    out.push_back(make_case("frustum_capped", Cone<double>{frustum.p0, frustum.r0, frustum.p1, frustum.r1, Caps::both}, false, true, false));
    out.push_back(make_case("cone_open", Cone<double>{{0.1, 0.0, -0.9}, 0.9, {0.0, 0.1, 0.9}, 0.0, Caps::none}, false, false, true));
    out.push_back(make_case("cone_capped", Cone<double>{{0.0, 0.1, -0.8}, 0.0, {0.1, 0.0, 1.0}, 0.8, Caps::both}, false, true, true));
    out.push_back(make_case("ellipsoid", Quadric<double>::ellipsoid({0.1, -0.2, 0.3}, {1.2, 0.8, 0.5}, {1.0, 1.0, 0.0}, {-1.0, 1.0, 1.0}),
                            false, true, false));
    {
        Quadric<double> bowl = Quadric<double>::ellipsoid({0.0, 0.1, -0.2}, {1.0, 0.8, 0.9});
        bowl.clip.hi.z = 0.3;  // cut above: an open bowl
        out.push_back(make_case("ellipsoid_cut", bowl, false, false, false));
    }
    out.push_back(make_case("hyperboloid_one_sheet", Quadric<double>::hyperboloid_one_sheet({0.1, -0.1, 0.2}, 0.6, 0.8, 0.9, 1.0), false,
                            false, false));
    out.push_back(make_case("hyperboloid_two_sheets", Quadric<double>::hyperboloid_two_sheets({0.0, 0.1, -0.1}, 0.7, 0.5, 0.4, 1.0),
                            false, false, false));
    out.push_back(
        make_case("paraboloid", Quadric<double>::elliptic_paraboloid({0.1, 0.2, -0.6}, 0.6, 0.9, 0.7, 1.2), false, false, false));
    out.push_back(make_case("elliptic_cone", Quadric<double>::elliptic_cone({0.0, 0.0, 0.1}, 0.6, 0.4, 1.0, 0.9), false, false, true));

    const Affine3<double> place = Affine3<double>::rotation(V{1.0, 2.0, 3.0}, 0.7, V{0.3, -0.2, 0.5});
    out.push_back(make_case("transformed_sphere",
                            transformed(Sphere<double>{{0.0, 0.0, 0.0}, 1.0}, place * Affine3<double>::scaling(V{1.5, 0.7, 1.0})), false,
                            true, false));
    out.push_back(make_case("transformed_cylinder_mirror",
                            transformed(Cylinder<double>{{0.0, 0.0, -0.8}, {0.0, 0.0, 0.8}, 0.6, Caps::both},
                                        place * Affine3<double>::scaling(V{-1.0, 1.2, 0.8})),
                            false, true, false));
    out.push_back(make_case("transformed_cone_shear",
                            transformed(Cone<double>{{0.0, 0.0, -0.8}, 0.9, {0.0, 0.0, 0.9}, 0.0, Caps::both}, shear()), false, true,
                            true));
    out.push_back(make_case("transformed_hyperboloid",
                            transformed(Quadric<double>::hyperboloid_one_sheet({0.0, 0.0, 0.0}, 0.5, 0.7, 0.8, 0.9), place), false,
                            false, false));
    out.push_back(make_case("transformed_disk_mirror",
                            transformed(Disk<double>{{0.0, 0.0, 0.0}, {0.0, 0.0, 1.0}, 1.0}, place * Affine3<double>::scaling(V{1.3, -0.9, 1.0})),
                            true, false, false));
    return out;
}

}  // namespace rayq::mesh
