// rayq::fuzz — a decoded case as one line of the fixture format (fixtures/README.md), so a
// finding can be pasted into a fixture file and read by rayq::oracle::parse_fixtures. Kernel-only
// (the fuzzers do not link the oracle); the replay test checks it against the oracle's parser.
#pragma once

#include <cstdio>
#include <string>
#include <type_traits>

#include <rayq/rayq.hpp>

namespace rayq::fuzz {

namespace detail_line {

template <class T>
void number(std::string& s, T v)
{
    char buf[64];
    if (v != v) std::snprintf(buf, sizeof buf, " nan");
    else if (v == std::numeric_limits<T>::infinity()) std::snprintf(buf, sizeof buf, " inf");
    else if (v == -std::numeric_limits<T>::infinity()) std::snprintf(buf, sizeof buf, " -inf");
    else std::snprintf(buf, sizeof buf, " %a", double(v));
    s += buf;
}
inline void number(std::string& s, Caps c) { s += c == Caps::both ? " both" : " none"; }

template <class T> const char* name(const Sphere<T>&) { return "sphere"; }
template <class T> const char* name(const Plane<T>&) { return "plane"; }
template <class T> const char* name(const Disk<T>&) { return "disk"; }
template <class T> const char* name(const Parallelogram<T>&) { return "parallelogram"; }
template <class T> const char* name(const Triangle<T>&) { return "triangle"; }
template <class T> const char* name(const Cylinder<T>&) { return "cylinder"; }
template <class T> const char* name(const Cone<T>&) { return "cone"; }
template <class T> const char* name(const Quadric<T>&) { return "quadric"; }

}  // namespace detail_line

// Calls f(field) for every field of a primitive in the fixture format's order (numbers as T,
// caps as rayq::Caps).
template <class T, class F> void each_vec(const Vec3<T>& v, F& f) { f(v.x); f(v.y); f(v.z); }
template <class T, class F> void each_field(const Sphere<T>& p, F&& f) { each_vec(p.center, f); f(p.radius); }
template <class T, class F> void each_field(const Plane<T>& p, F&& f) { each_vec(p.point, f); each_vec(p.normal, f); }
template <class T, class F> void each_field(const Disk<T>& p, F&& f) { each_vec(p.center, f); each_vec(p.normal, f); f(p.radius); }
template <class T, class F> void each_field(const Parallelogram<T>& p, F&& f) { each_vec(p.corner, f); each_vec(p.edge0, f); each_vec(p.edge1, f); }
template <class T, class F> void each_field(const Triangle<T>& p, F&& f) { each_vec(p.a, f); each_vec(p.b, f); each_vec(p.c, f); }
template <class T, class F> void each_field(const Cylinder<T>& p, F&& f) { each_vec(p.p0, f); each_vec(p.p1, f); f(p.radius); f(p.caps); }
template <class T, class F>
void each_field(const Cone<T>& p, F&& f)
{
    each_vec(p.p0, f);
    f(p.r0);
    each_vec(p.p1, f);
    f(p.r1);
    f(p.caps);
}
template <class T, class F>
void each_field(const Quadric<T>& q, F&& f)
{
    for (T v : {q.A, q.B, q.C, q.D, q.E, q.F, q.G, q.H, q.I, q.J}) f(v);
    each_vec(q.clip.lo, f);
    each_vec(q.clip.hi, f);
}
template <class P, class T, class F>
void each_field(const Transformed<P, T>& x, F&& f)
{
    each_field(x.object, f);
    for (const auto* a : {&x.to_world, &x.to_object})
        for (const auto& row : a->m)
            for (T v : row) f(v);
}

namespace detail_line {

template <class Prim>
std::string primitive_name(const Prim& p) { return name(p); }
template <class P, class T>
std::string primitive_name(const Transformed<P, T>& x) { return std::string("transformed-") + name(x.object); }

}  // namespace detail_line

// "<family> <primitive> <type> <ray> <fields>", numbers as printf("%a").
template <class Prim>
std::string fixture_line(const std::string& family, const Ray<scalar_t<Prim>>& ray, const Prim& prim)
{
    using T = scalar_t<Prim>;
    std::string s = family + " " + detail_line::primitive_name(prim) + (std::is_same_v<T, float> ? " float" : " double");
    const auto append = [&](auto v) { detail_line::number(s, v); };
    each_vec(ray.origin, append);
    each_vec(ray.direction, append);
    detail_line::number(s, ray.tmin);
    detail_line::number(s, ray.tmax);
    each_field(prim, append);
    return s;
}

}  // namespace rayq::fuzz
