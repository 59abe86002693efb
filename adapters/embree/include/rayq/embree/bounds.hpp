// rayq::embree — conservative world-space boxes for rayq primitives, in the floats Embree's BVH
// stores.
//
// Embree culls a primitive when the ray misses its box, so the box must contain every point where
// rayq can report a hit, not just the exact surface. What can put a reported hit outside the exact
// surface's box, and what the padding therefore covers (S = the largest coordinate magnitude of the
// primitive's box, or of the ray origins when Options::origin_bound says they reach farther):
//   - the box's own rounding to float, and Embree's slab test (t = (box − origin)·(1/direction) in
//     float; its error is a few ulps of the coordinates and of the origin): a few u_float·S;
//   - for double primitives, the ray handed to Embree is the double ray rounded to float, so the
//     line Embree traverses is off by ~u_float·(|origin| + t·|direction|) ≲ u_float·S;
//   - the policy's own decision error: `accurate` decides hit/miss exactly on the (float or
//     double) inputs, so its hits lie on the exact surface and need nothing more; `stable`
//     (Hearn–Baker) accepts lines that miss by at most a few u·|origin − primitive| (the
//     perpendicular f − (f·d̂)d̂ is accurate to a few ulps of |f|): a few u_T·S; `fast` (textbook
//     b² − 4ac) cancels, and accepts lines that miss by up to ~sqrt(c·u_T)·|f| (at 10⁴ in float,
//     a unit sphere "hits" lines 1–2 units away): sqrt(64·u_T)·S.
// Hence pad = 32·u_float·S + 32·u_T·S (+ sqrt(64·u_T)·S for `fast`), then rounded outward. The
// factors are 4–8× the estimates above; adapter_bounds_test.cpp checks that no hit any policy
// reports lies outside the padded box, far-away and grazing families included.
#pragma once

#include <rayq/rayq.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <type_traits>

#include <embree3/rtcore.h>

namespace rayq::embree {

// A box in double (every float and double input converts exactly); nullopt-free: an unbounded
// primitive (a plane, an unclipped quadric) gets Box<double>::everything().
using WorldBox = Box<double>;

namespace detail {

inline WorldBox empty_box()
{
    constexpr double inf = std::numeric_limits<double>::infinity();
    return {{inf, inf, inf}, {-inf, -inf, -inf}};
}

inline void include(WorldBox& b, const Vec3<double>& p)
{
    b.lo = {std::min(b.lo.x, p.x), std::min(b.lo.y, p.y), std::min(b.lo.z, p.z)};
    b.hi = {std::max(b.hi.x, p.x), std::max(b.hi.y, p.y), std::max(b.hi.z, p.z)};
}

inline void include(WorldBox& b, const WorldBox& other)
{
    include(b, other.lo);
    include(b, other.hi);
}

template <class T>
Vec3<double> lift(const Vec3<T>& v) { return {double(v.x), double(v.y), double(v.z)}; }

// The box of a disk of radius r around `center` in the plane normal to `axis`: along coordinate i
// it reaches r·sqrt(1 − â_i²).
inline WorldBox disk_box(const Vec3<double>& center, const Vec3<double>& axis, double r)
{
    const double len2 = dot(axis, axis);
    const auto reach = [&](double a) { return r * std::sqrt(std::max(0.0, 1.0 - a * a / len2)); };
    const Vec3<double> e{reach(axis.x), reach(axis.y), reach(axis.z)};
    return {center - e, center + e};
}

inline bool finite_box(const WorldBox& b) { return isfinite(b.lo) && isfinite(b.hi); }

}  // namespace detail

// The exact box of each bounded primitive (up to double rounding, which the padding covers).
template <class T>
WorldBox world_box(const Sphere<T>& s)
{
    const Vec3<double> c = detail::lift(s.center), r{double(s.radius), double(s.radius), double(s.radius)};
    return {c - r, c + r};
}

template <class T>
WorldBox world_box(const Cylinder<T>& cyl)
{
    const Vec3<double> p0 = detail::lift(cyl.p0), p1 = detail::lift(cyl.p1);
    WorldBox b = detail::disk_box(p0, p1 - p0, cyl.radius);
    detail::include(b, detail::disk_box(p1, p1 - p0, cyl.radius));
    return b;
}

template <class T>
WorldBox world_box(const Cone<T>& cone)
{
    const Vec3<double> p0 = detail::lift(cone.p0), p1 = detail::lift(cone.p1);
    WorldBox b = detail::disk_box(p0, p1 - p0, cone.r0);
    detail::include(b, detail::disk_box(p1, p1 - p0, cone.r1));
    return b;
}

template <class T>
WorldBox world_box(const Disk<T>& d)
{
    return detail::disk_box(detail::lift(d.center), detail::lift(d.normal), d.radius);
}

template <class T>
WorldBox world_box(const Triangle<T>& t)
{
    WorldBox b = detail::empty_box();
    for (const auto& p : {t.a, t.b, t.c}) detail::include(b, detail::lift(p));
    return b;
}

template <class T>
WorldBox world_box(const Parallelogram<T>& p)
{
    const Vec3<double> c = detail::lift(p.corner), e0 = detail::lift(p.edge0), e1 = detail::lift(p.edge1);
    WorldBox b = detail::empty_box();
    for (const auto& q : {c, c + e0, c + e1, c + e0 + e1}) detail::include(b, q);
    return b;
}

// Unbounded: Embree then never culls it (correct, no speed-up). A quadric's clip box bounds its
// hits when finite; named quadrics (ellipsoid, ...) are not bounded from their coefficients here.
template <class T>
WorldBox world_box(const Plane<T>&) { return WorldBox::everything(); }

template <class T>
WorldBox world_box(const Quadric<T>& q)
{
    const WorldBox clip{detail::lift(q.clip.lo), detail::lift(q.clip.hi)};
    return detail::finite_box(clip) ? clip : WorldBox::everything();
}

// An instance: the object's box corners mapped to the world (an affine map sends the box to a
// parallelepiped whose box is that of its eight corners).
template <class Prim, class T>
WorldBox world_box(const Transformed<Prim, T>& x)
{
    const WorldBox ob = world_box(x.object);
    if (!detail::finite_box(ob)) return WorldBox::everything();
    WorldBox b = detail::empty_box();
    for (int corner = 0; corner < 8; ++corner) {
        const double p[3] = {corner & 1 ? ob.hi.x : ob.lo.x, corner & 2 ? ob.hi.y : ob.lo.y, corner & 4 ? ob.hi.z : ob.lo.z};
        double w[3];
        for (int i = 0; i < 3; ++i)
            w[i] = double(x.to_world.m[i][0]) * p[0] + double(x.to_world.m[i][1]) * p[1] + double(x.to_world.m[i][2]) * p[2] +
                   double(x.to_world.m[i][3]);
        detail::include(b, Vec3<double>{w[0], w[1], w[2]});
    }
    // The mapped corners are rounded in double; their box grows by the same relative padding below.
    return b;
}

namespace detail {

template <class T>
inline constexpr double unit_roundoff = std::numeric_limits<T>::epsilon() / 2;

// Embree rejects boxes beyond ±FLT_LARGE (1.844e18) as invalid and drops the primitive; an
// unbounded primitive, or one reaching beyond this, gets the box ±embree_large.
inline constexpr double embree_large = 1e18;

inline float round_down_to_float(double x)
{
    float f = static_cast<float>(x);
    if (double(f) > x) f = std::nextafter(f, -std::numeric_limits<float>::infinity());
    return f;
}

inline float round_up_to_float(double x)
{
    float f = static_cast<float>(x);
    if (double(f) < x) f = std::nextafter(f, std::numeric_limits<float>::infinity());
    return f;
}

}  // namespace detail

// The padding (absolute, in world units) for a primitive whose coordinates reach `magnitude`
// (largest |coordinate| of its box, or of the ray origins if larger), under `Policy`, for scalar
// type T. See the header comment for where each term comes from.
template <class Policy, class T>
double padding(double magnitude)
{
    const double uf = detail::unit_roundoff<float>, ut = detail::unit_roundoff<T>;
    double pad = 32 * uf * magnitude + 32 * ut * magnitude;
    if constexpr (std::is_same_v<Policy, fast_policy>) pad += std::sqrt(64 * ut) * magnitude;
    return pad;
}

// The padded, outward-rounded float box Embree stores for `prim`; an invalid primitive gets an
// inverted box, which Embree's builder drops (it is never hit either way).
template <class Policy, class Prim>
RTCBounds embree_bounds(const Prim& prim, double origin_bound = 0)
{
    using T = scalar_t<Prim>;
    RTCBounds out{};
    if (!validate(prim)) {
        out.lower_x = out.lower_y = out.lower_z = std::numeric_limits<float>::infinity();
        out.upper_x = out.upper_y = out.upper_z = -std::numeric_limits<float>::infinity();
        return out;
    }
    WorldBox b = world_box(prim);
    const double large = detail::embree_large;
    if (detail::finite_box(b)) {
        const double magnitude =
            std::max({std::abs(b.lo.x), std::abs(b.lo.y), std::abs(b.lo.z), std::abs(b.hi.x), std::abs(b.hi.y), std::abs(b.hi.z),
                      std::abs(origin_bound)});
        const double pad = padding<Policy, T>(magnitude);
        const Vec3<double> p{pad, pad, pad};
        b = {b.lo - p, b.hi + p};
    }
    // Beyond Embree's range (or unbounded): the whole range, so every ray Embree takes (origins
    // within ±large/2: QueryContext::embree_ray) visits it and rayq decides.
    if (!(std::max({-b.lo.x, -b.lo.y, -b.lo.z, b.hi.x, b.hi.y, b.hi.z}) <= large)) b = {{-large, -large, -large}, {large, large, large}};
    const auto lo = [&](double v) { return detail::round_down_to_float(v); };
    const auto hi = [&](double v) { return detail::round_up_to_float(v); };
    out.lower_x = lo(b.lo.x), out.lower_y = lo(b.lo.y), out.lower_z = lo(b.lo.z);
    out.upper_x = hi(b.hi.x), out.upper_y = hi(b.hi.y), out.upper_z = hi(b.hi.z);
    return out;
}

}  // namespace rayq::embree
