// rayq::oracle — private: the kernel's data structs read as exact rational problems, with the
// oracle's own domain checks (exact: a radius is positive, a cross product is non-zero, …).
// Reads fields only; calls no kernel function.
#pragma once

#include <cmath>

#include <rayq/oracle/oracle.hpp>

#include "exact.hpp"

namespace rayq::oracle::exact {

struct Converter {
    bool ok = true;
    std::string why;

    void require(bool condition, const char* reason)
    {
        if (ok && !condition) ok = false, why = reason;
    }

    template <class T>
    Q num(T x, const char* what)
    {
        require(std::isfinite(x), what);
        return std::isfinite(x) ? Q(static_cast<double>(x)) : Q(0);
    }
    template <class T>
    V vec(const Vec3<T>& v, const char* what)
    {
        return {num(v.x, what), num(v.y, what), num(v.z, what)};
    }
    // A bound that may be infinite (never NaN).
    template <class T>
    Bound bound(T x, const char* what)
    {
        require(!std::isnan(x), what);
        if (std::isnan(x)) return finite(Q(0));
        if (std::isinf(x)) return x > 0 ? plus_infinity() : minus_infinity();
        return finite(Q(static_cast<double>(x)));
    }

    template <class T>
    RayQ ray(const Ray<T>& r)
    {
        RayQ q{vec(r.origin, "ray: origin is not finite"), vec(r.direction, "ray: direction is not finite"),
               bound(r.tmin, "ray: tmin is NaN"), bound(r.tmax, "ray: tmax is NaN")};
        require(!is_zero(q.d), "ray: direction is zero");
        require(compare(q.tmin, q.tmax, Q(0)) < 0, "ray: the window tmin < t < tmax is empty");
        return q;
    }

    template <class T>
    Shape shape(const Sphere<T>& s)
    {
        SphereQ q{vec(s.center, "sphere: center is not finite"), num(s.radius, "sphere: radius is not finite")};
        require(sgn(q.r) > 0, "sphere: radius <= 0");
        return q;
    }
    template <class T>
    Shape shape(const Plane<T>& p)
    {
        PlaneQ q{vec(p.point, "plane: point is not finite"), vec(p.normal, "plane: normal is not finite")};
        require(!is_zero(q.n), "plane: normal is zero");
        return q;
    }
    template <class T>
    Shape shape(const Disk<T>& d)
    {
        DiskQ q{vec(d.center, "disk: center is not finite"), vec(d.normal, "disk: normal is not finite"),
                num(d.radius, "disk: radius is not finite")};
        require(!is_zero(q.n), "disk: normal is zero");
        require(sgn(q.r) > 0, "disk: radius <= 0");
        return q;
    }
    template <class T>
    Shape shape(const Parallelogram<T>& p)
    {
        ParallelogramQ q{vec(p.corner, "parallelogram: corner is not finite"), vec(p.edge0, "parallelogram: edge0 is not finite"),
                         vec(p.edge1, "parallelogram: edge1 is not finite")};
        require(!is_zero(cross(q.e0, q.e1)), "parallelogram: edges are parallel (no area)");
        return q;
    }
    template <class T>
    Shape shape(const Triangle<T>& t)
    {
        TriangleQ q{vec(t.a, "triangle: a is not finite"), vec(t.b, "triangle: b is not finite"), vec(t.c, "triangle: c is not finite")};
        require(!is_zero(cross(q.b - q.a, q.c - q.a)), "triangle: vertices are collinear (no area)");
        return q;
    }
    template <class T>
    Shape shape(const Cylinder<T>& c)
    {
        CylinderQ q{vec(c.p0, "cylinder: p0 is not finite"), vec(c.p1, "cylinder: p1 is not finite"),
                    num(c.radius, "cylinder: radius is not finite"), c.caps == Caps::both};
        require(sgn(q.r) > 0, "cylinder: radius <= 0");
        require(!is_zero(q.p1 - q.p0), "cylinder: p0 = p1");
        require(c.caps == Caps::none || c.caps == Caps::both, "cylinder: caps is not a Caps value");
        return q;
    }
    template <class T>
    Shape shape(const Cone<T>& c)
    {
        ConeQ q{vec(c.p0, "cone: p0 is not finite"), num(c.r0, "cone: r0 is not finite"), vec(c.p1, "cone: p1 is not finite"),
                num(c.r1, "cone: r1 is not finite"), c.caps == Caps::both};
        require(sgn(q.r0) >= 0 && sgn(q.r1) >= 0, "cone: a radius is negative");
        require(sgn(q.r0) > 0 || sgn(q.r1) > 0, "cone: both radii are zero");
        require(!is_zero(q.p1 - q.p0), "cone: p0 = p1");
        require(c.caps == Caps::none || c.caps == Caps::both, "cone: caps is not a Caps value");
        return q;
    }
    template <class T>
    Shape shape(const Quadric<T>& f)
    {
        QuadricQ q;
        const T k[10] = {f.A, f.B, f.C, f.D, f.E, f.F, f.G, f.H, f.I, f.J};
        bool any = false;
        for (int i = 0; i < 10; ++i) {
            q.k[i] = num(k[i], "quadric: a coefficient is not finite");
            if (i < 9) any = any || sgn(q.k[i]) != 0;
        }
        require(any, "quadric: no non-constant term");
        const T lo[3] = {f.clip.lo.x, f.clip.lo.y, f.clip.lo.z}, hi[3] = {f.clip.hi.x, f.clip.hi.y, f.clip.hi.z};
        for (int i = 0; i < 3; ++i) {
            q.lo[i] = bound(lo[i], "quadric: clip box bound is NaN");
            q.hi[i] = bound(hi[i], "quadric: clip box bound is NaN");
            require(compare(q.lo[i], q.hi[i], Q(0)) <= 0, "quadric: clip box is empty (lo > hi)");
        }
        return q;
    }

    template <class T>
    AffineQ affine(const Affine3<T>& a)
    {
        AffineQ q;
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 4; ++j) q.m[i][j] = num(a.m[i][j], "transformed: to_world is not finite");
        return q;
    }

    template <class T, class Prim>
    Problem problem(const Ray<T>& r, const Prim& p)
    {
        Problem out{ray(r), shape(p), std::nullopt, true, {}};
        out.defined = ok;
        out.why = why;
        return out;
    }
    template <class T, class Prim>
    Problem problem(const Ray<T>& r, const Transformed<Prim, T>& x)
    {
        Problem out{ray(r), shape(x.object), affine(x.to_world), true, {}};
        require(inverse(*out.to_world).has_value(), "transformed: to_world is singular");
        out.defined = ok;
        out.why = why;
        return out;
    }
};

template <class T, class Prim>
Problem to_problem(const Ray<T>& r, const Prim& p)
{
    return Converter{}.problem(r, p);
}

template <class T>
AffineQ to_affine(const Affine3<T>& a)
{
    return Converter{}.affine(a);
}

}  // namespace rayq::oracle::exact
