// rayq::fuzz — the invariants every (ray, primitive) pair must satisfy, under every policy
// (issue 9). One definition for the libFuzzer harnesses, the deterministic edge-case test and the
// replay of fixtures/fuzz/: check() returns the violated invariants with readable descriptions
// (it never aborts), and each caller decides what a violation means (the fuzzers crash so that
// libFuzzer keeps the input, the tests fail and print it).
//
// Depends on the kernel and on the binary128 reference of kernel/tests/quad_reference.hpp
// (standard library only; add kernel/tests to the include path). The reference writes each
// primitive's implicit function itself and never calls the kernel, so it is an independent
// check of t_error.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <optional>
#include <string>
#include <type_traits>
#include <vector>

#include <rayq/rayq.hpp>
#include <rayq/batch/bounding_sphere.hpp>
#include <rayq/scene.hpp>

#include "fixture_line.hpp"
#include "known_issues.hpp"
#include "quad_reference.hpp"

namespace rayq::fuzz {

struct Violation {
    std::string invariant;  // a short stable name, e.g. "hit.t_in_window"
    std::string detail;     // what was seen, with numbers (%a: exact)
    bool known = false;     // in a class accurate_known_wrong lists (known_issues.hpp)
};

// What a check saw, beyond its violations (the tests count these to show they checked something).
struct Checked {
    std::vector<Violation> violations;
    bool usable_ray = false, valid_primitive = false;
    int hits = 0;               // policies that hit
    int certified = 0;          // hits whose t_error the reference confirmed
    int reference_uncertain = 0;  // hits with a finite t_error the reference could not decide
    bool accurate_skipped = false;  // a known hang (known_issues.hpp): accurate was not run
    int known = 0;                  // violations of known open issues, left out of `violations`
};

struct Options {
    unsigned scene_copies = 1;  // bounded primitives: copies in the scene and stream checks (>= 1)
    bool skip_known = !strict_mode();        // leave out known open violations (known_issues.hpp)
    bool skip_known_hangs = !strict_mode();  // do not run accurate where it is known to hang
};

// The scene and stream copies for a fuzz input: its last byte picks 1–9, so that the SIMD filters'
// full lane groups and tails are exercised. One rule for the libFuzzer harnesses, rayq-fuzz and the
// replay test, so that a stored input is checked as it was found.
inline unsigned scene_copies_for(const std::uint8_t* data, std::size_t size) { return 1 + (size > 0 ? data[size - 1] % 9 : 0); }

namespace detail_check {

using rayq::test::quad;

inline std::string hex(double v)
{
    char buf[64];
    std::snprintf(buf, sizeof buf, "%a", v);
    return buf;
}
inline std::string num(double v)
{
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.17g", v);
    return buf;
}
// binary128 to double without undefined behaviour: out-of-range values become ±inf.
inline double to_double(quad v)
{
    if (v != v) return std::numeric_limits<double>::quiet_NaN();
    if (v > quad(std::numeric_limits<double>::max())) return std::numeric_limits<double>::infinity();
    if (v < -quad(std::numeric_limits<double>::max())) return -std::numeric_limits<double>::infinity();
    return double(v);
}

template <class T>
bool finite(const Vec3<T>& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

// The README's "bad input" table, written out here rather than by calling the kernel's usable():
// non-finite origin or direction, a zero direction or one whose squared length under- or
// overflows, an empty or NaN window.
template <class T>
bool ray_may_hit(const Ray<T>& r)
{
    if (!finite(r.origin) || !finite(r.direction)) return false;
    const T dd = r.direction.x * r.direction.x + r.direction.y * r.direction.y + r.direction.z * r.direction.z;
    if (!(dd >= std::numeric_limits<T>::min()) || !std::isfinite(dd)) return false;
    return r.tmin < r.tmax;
}

template <class T>
bool same(T a, T b) { return a == b ? std::signbit(a) == std::signbit(b) || a != T(0) : (a != a && b != b); }
template <class T>
bool same(const Vec3<T>& a, const Vec3<T>& b) { return same(a.x, b.x) && same(a.y, b.y) && same(a.z, b.z); }
template <class T>
bool same(const Hit<T>& a, const Hit<T>& b)
{
    return same(a.t, b.t) && same(a.point, b.point) && same(a.normal, b.normal) && a.front_face == b.front_face &&
           a.part == b.part && same(a.t_error, b.t_error) && same(a.point_error, b.point_error);
}

// The full record cut down to `fields`: what a query asked for only those must return (the
// fields not asked for at their defaults: zero point and normal, infinite bounds).
template <class T>
Hit<T> restricted(const Hit<T>& full, HitFields fields)
{
    Hit<T> h{full.t};
    h.front_face = full.front_face;
    h.part = full.part;
    if (wants(fields, HitFields::point)) h.point = full.point;
    if (wants(fields, HitFields::normal)) h.normal = full.normal;
    if (wants(fields, HitFields::bounds)) h.t_error = full.t_error, h.point_error = full.point_error;
    return h;
}

inline const char* part_name(Part p) { return p == Part::surface ? "surface" : p == Part::cap0 ? "cap0" : "cap1"; }

template <class T>
std::string describe(const Hit<T>& h)
{
    return "t=" + hex(h.t) + " (" + num(h.t) + ") part=" + part_name(h.part) + " front_face=" + (h.front_face ? "1" : "0") +
           " normal=(" + num(h.normal.x) + ", " + num(h.normal.y) + ", " + num(h.normal.z) + ") t_error=" + num(h.t_error);
}

// The well-formedness of one hit record (intersect's, or a passage's).
template <class T>
void check_hit_record(const Ray<T>& ray, const Hit<T>& h, const std::string& where, std::vector<Violation>& out)
{
    const auto fail = [&](const char* name, const std::string& what) { out.push_back({name, where + ": " + what + "; " + describe(h)}); };
    if (!std::isfinite(h.t)) fail("hit.t_finite", "t is not finite");
    if (!(ray.tmin < h.t && h.t < ray.tmax)) fail("hit.t_in_window", "t outside (tmin, tmax) = (" + num(ray.tmin) + ", " + num(ray.tmax) + ")");
    if (!finite(h.point)) fail("hit.point_finite", "point (" + num(h.point.x) + ", " + num(h.point.y) + ", " + num(h.point.z) + ") not finite");
    const long double nx = h.normal.x, ny = h.normal.y, nz = h.normal.z;
    const long double len = std::sqrt(nx * nx + ny * ny + nz * nz);
    if (!(std::abs(len - 1) <= 1e-5L)) fail("hit.normal_unit", "|normal| - 1 = " + num(double(len - 1)));
    if (!(dot(h.normal, ray.direction) <= T(0))) fail("hit.normal_faces_ray", "dot(normal, direction) = " + num(dot(h.normal, ray.direction)));
    if (!(h.t_error >= T(0))) fail("hit.t_error_nonnegative", "t_error is negative or NaN");
    if (!(h.point_error.x >= T(0) && h.point_error.y >= T(0) && h.point_error.z >= T(0)))
        fail("hit.point_error_nonnegative", "a point_error component is negative or NaN");
}

// |v|₁ in binary128: the size the reference's resolution tests compare.
inline quad size1(const test::Q3& v) { return test::qabs(v.x) + test::qabs(v.y) + test::qabs(v.z); }

// Where the exact root near the kernel's t is, by binary128 Newton on the reference's implicit
// function F, and whether that is certain: F has opposite signs at r − δ and r + δ, each larger
// than F's evaluation error there, so a root lies in [r − δ, r + δ] whatever the rounding. The
// evaluation error is bounded by scale·2^-100·|∇F| (scale: the largest coordinate or field the
// evaluation adds up; binary128 rounds positions to scale·2^-113): a far-away primitive seen from
// nearby, or a line near tangency, is not well-conditioned and is left undecided. δ is tried from
// 1e-22·|r| upwards and stays far below any t_error of float or double.
struct Reference {
    bool certain = false;
    quad root = 0, delta = 0;
};

template <class Prim>
Reference reference_root(const Prim& prim, const test::Q3& o, const test::Q3& d, quad t, Part part, quad scale)
{
    using test::implicit;
    using test::qabs;
    for (int i = 0; i < 40; ++i) {
        const quad h = (qabs(t) + quad(1e-30)) * quad(1e-12);
        const quad f = implicit(prim, o, d, t, part);
        const quad df = (implicit(prim, o, d, t + h, part) - implicit(prim, o, d, t - h, part)) / (2 * h);
        if (!(df != 0) || f != f) return {};
        const quad step = f / df;
        t -= step;
        if (!(qabs(step) > qabs(t) * quad(1e-33))) break;
    }
    Reference r;
    r.root = t;
    // |∇F| at the root, by central differences in space (the origin moved, t fixed).
    const quad hs = (scale + qabs(t) * size1(d)) * quad(1e-15);
    if (!(hs > 0)) return r;
    quad grad = 0;
    for (int axis = 0; axis < 3; ++axis) {
        test::Q3 step{0, 0, 0};
        (axis == 0 ? step.x : axis == 1 ? step.y : step.z) = hs;
        grad += qabs(implicit(prim, o + step, d, t, part) - implicit(prim, o - step, d, t, part)) / (2 * hs);
    }
    const quad eval_error = std::max(scale, qabs(t) * size1(d)) * grad * quad(1e-30);
    const quad d_max = std::max({qabs(d.x), qabs(d.y), qabs(d.z)});
    for (const quad delta : {qabs(t) * quad(1e-22), qabs(t) * quad(1e-19), scale / d_max * quad(1e-26), scale / d_max * quad(1e-22)}) {
        if (!(delta > 0)) continue;
        const quad lo = implicit(prim, o, d, t - delta, part), hi = implicit(prim, o, d, t + delta, part);
        if (((lo < 0 && hi > 0) || (lo > 0 && hi < 0)) && qabs(lo) > eval_error && qabs(hi) > eval_error) {
            r.certain = true;
            r.delta = delta;
            return r;
        }
    }
    return r;
}

// Whether the binary128 reference can resolve a cylinder or cone near the root t. Its error
// estimate covers rounding in space (|∇F| times the positions' rounding) to first order, which
// fails when
//  * the axis p1 − p0 is not exact in binary128: a cylinder from (−2^-402, −2^226, 2^197) to
//    (0.75, 0.75, 0.75) got a reference root 0.92 from CGAL's;
//  * the radius is below 2^-80 of the offsets whose cross product with the axis gives the
//    distance from it (|q|, q = o + t·d − p0): that cross product then cancels beyond binary128's
//    113 bits, and its rounding, squared, outweighs F (a cylinder of radius 2^-239 seen from
//    2^-4 away got a reference root twice CGAL's);
//  * the axis is below 2^-80 of |q|: q's rounding then moves the point along the axis by more than
//    the axis is long, and a cone's radius there with it (a double cone of radius ~DBL_MAX and axis
//    2^-11 seen from 2^1022 got a reference root of -6.3e305, CGAL's is 7.1e307, as accurate's).
//  * a cone's point lies within 2^-40 of the apex's offset (|q| + |k·A|, apex p0 + k·A with
//    k = r0/(r0 − r1)): F is quadratic there, its terms are ~|q|² and cancel to ~dist², and the
//    error estimate, first order in |∇F| → 0, misses that rounding (a ray from 1e-28 beside the
//    apex of a cone of size 0.02 got a reference root of -2.9e-28; CGAL's is 7.1e-30, accurate's).
// All found by the axial libFuzzer harness once accurate ran everywhere; accurate matched CGAL.
// Flat primitives whose normal is a cross product of edges fail alike when
//  * an edge b − a is not exact in binary128: a triangle with a vertex at (−0.82, −2^133, −2^141)
//    and two near 2^173 got a reference root 9e-13 from CGAL's (flat libFuzzer harness);
//  * the edges are so close to parallel that the cross product cancels beyond 80 of its 113 bits.
inline bool exact_in_quad(quad a, quad b)  // a − b (TwoSum's error term is zero)
{
    const quad s = a - b, bv = s - a;
    return (a - (s - bv)) + (-b - bv) == 0;
}
inline bool exact_in_quad(const test::Q3& a, const test::Q3& b)
{
    return exact_in_quad(a.x, b.x) && exact_in_quad(a.y, b.y) && exact_in_quad(a.z, b.z);
}
template <class Prim>
bool reference_resolves(const Prim&, const test::Q3&, const test::Q3&, quad) { return true; }
// q = o + t·d − p0, the point's offset from the axis' start.
template <class T>
bool axial_reference_resolves(const Vec3<T>& p0, const Vec3<T>& p1, T radius, const test::Q3& q)
{
    if (!exact_in_quad(test::q3(p1), test::q3(p0))) return false;
    const quad reach = size1(q);
    const test::Q3 axis = test::q3(p1) - test::q3(p0);
    const quad axis_size = size1(axis);
    return test::qabs(quad(radius)) >= reach * quad(0x1p-80) && axis_size >= reach * quad(0x1p-80);
}
inline bool cross_resolves(const test::Q3& e0, const test::Q3& e1)
{
    return size1(test::qcross(e0, e1)) >= size1(e0) * size1(e1) * quad(0x1p-80);
}
template <class T>
bool reference_resolves(const Triangle<T>& p, const test::Q3&, const test::Q3&, quad)
{
    const test::Q3 a = test::q3(p.a), b = test::q3(p.b), c = test::q3(p.c);
    return exact_in_quad(b, a) && exact_in_quad(c, a) && cross_resolves(b - a, c - a);
}
template <class T>
bool reference_resolves(const Parallelogram<T>& p, const test::Q3&, const test::Q3&, quad)
{
    return cross_resolves(test::q3(p.edge0), test::q3(p.edge1));
}
template <class T>
bool reference_resolves(const Cylinder<T>& c, const test::Q3& o, const test::Q3& d, quad t)
{
    return axial_reference_resolves(c.p0, c.p1, c.radius, o - test::q3(c.p0) + t * d);
}
template <class T>
bool reference_resolves(const Cone<T>& c, const test::Q3& o, const test::Q3& d, quad t)
{
    const test::Q3 q = o - test::q3(c.p0) + t * d;
    if (!axial_reference_resolves(c.p0, c.p1, std::max(std::abs(c.r0), std::abs(c.r1)), q)) return false;
    if (c.r0 == c.r1) return true;  // no apex
    const test::Q3 apex_offset = (quad(c.r0) / (quad(c.r0) - quad(c.r1))) * (test::q3(c.p1) - test::q3(c.p0));
    return size1(q - apex_offset) >= (size1(q) + size1(apex_offset)) * quad(0x1p-40);
}

// t_error contains the exact root: a violation only when the reference is certain of a root
// outside [t − e, t + e] and F has one sign at t − e, t and t + e (no root in between either).
template <class T, class Prim>
void check_t_error(const Ray<T>& ray, const Prim& prim, const Hit<T>& h, const char* policy, Checked& out, bool known_wrong)
{
    if (!std::isfinite(h.t_error)) return;  // uncertified: allowed (tangency, undecidable trims)
    const test::Q3 o = test::q3(ray.origin), d = test::q3(ray.direction);
    quad scale = std::max({test::qabs(o.x), test::qabs(o.y), test::qabs(o.z)});
    each_field(prim, [&](auto v) {
        if constexpr (!std::is_same_v<decltype(v), Caps>)
            if (std::isfinite(v)) scale = std::max(scale, test::qabs(quad(v)));
    });
    const Reference ref = reference_root(prim, o, d, quad(h.t), h.part, scale);
    if (!ref.certain || !reference_resolves(prim, o, d, quad(h.t))) {
        ++out.reference_uncertain;
        return;
    }
    const quad dist = test::qabs(ref.root - quad(h.t));
    if (dist <= quad(h.t_error) + ref.delta) {
        ++out.certified;
        return;
    }
    const quad e = quad(h.t_error);
    const quad fl = test::implicit(prim, o, d, quad(h.t) - e, h.part), fm = test::implicit(prim, o, d, quad(h.t), h.part),
               fh = test::implicit(prim, o, d, quad(h.t) + e, h.part);
    const bool one_sign = (fl > 0 && fm > 0 && fh > 0) || (fl < 0 && fm < 0 && fh < 0);
    if (!one_sign) {
        ++out.reference_uncertain;
        return;
    }
    out.violations.push_back({"t_error.contains_exact_t", std::string(policy) + ": |t - t_exact| = " + num(to_double(dist)) +
                                                               " > t_error = " + num(h.t_error) + " (t_exact ~ " +
                                                               num(to_double(ref.root)) + "); " + describe(h),
                              known_wrong});
}

template <class Policy, class Prim>
void check_policy(Policy policy, const char* name, const Ray<scalar_t<Prim>>& ray, const Prim& prim, bool may_hit,
                  unsigned scene_copies, Checked& out)
{
    using T = scalar_t<Prim>;
    const std::optional<Hit<T>> hit = intersect(policy, ray, prim);
    const bool occ = occluded(policy, ray, prim);
    const Passages<T> all = intersect_all(policy, ray, prim);
    const std::string p = name;
    auto& v = out.violations;

    if (!may_hit && (hit || occ || !all.empty()))
        v.push_back({out.usable_ray ? "bad_primitive.no_hit" : "bad_ray.no_hit",
                     p + ": " + (out.usable_ray ? "an invalid primitive" : "an unusable ray (NaN/Inf/zero direction, empty window)") +
                         " was hit (intersect " + (hit ? "hit" : "missed") + ", occluded " + (occ ? "true" : "false") +
                         ", intersect_all " + std::to_string(all.size()) + ")"});
    if (hit) {
        ++out.hits;
        check_hit_record(ray, *hit, p + " intersect", v);
    }
    if (occ != hit.has_value())
        v.push_back({"occluded.agrees", p + ": occluded = " + (occ ? "true" : "false") + " but intersect " + (hit ? "hit" : "missed")});

    const bool known_wrong = std::is_same_v<Policy, accurate_policy> && accurate_known_wrong(ray, prim);
    // intersect_all: ascending, inside the window, and its first passage is intersect's hit.
    if (all.size() < 0 || all.size() > 2) v.push_back({"intersect_all.count", p + ": " + std::to_string(all.size()) + " passages"});
    else {
        for (int i = 0; i < all.size(); ++i) {
            check_hit_record(ray, all[i].hit, p + " intersect_all[" + std::to_string(i) + "]", v);
            if (i > 0 && !(all[i - 1].hit.t <= all[i].hit.t))
                v.push_back({"intersect_all.ascending", p + ": passage t " + num(all[i - 1].hit.t) + " then " + num(all[i].hit.t)});
        }
        // Where accurate is a known open issue its answer depends on the query too: closest hit and
        // all passages may take different units (found on a transformed cylinder of size 2^-511).
        if (all.empty() != !hit.has_value())
            v.push_back({"intersect_all.first_is_intersect",
                         p + ": intersect " + (hit ? "hit" : "missed") + " but intersect_all has " + std::to_string(all.size()) + " passages",
                         known_wrong});
        else if (hit && !same(all[0].hit, *hit))
            v.push_back({"intersect_all.first_is_intersect",
                         p + ": first passage " + describe(all[0].hit) + " differs from intersect's " + describe(*hit), known_wrong});
    }

    // The scene path (bounded primitives: a SIMD filter, with several copies so that lanes and
    // tails are exercised; the first copy must win) answers exactly what the scalar path does.
    // Where accurate is a known open issue (known_issues.hpp: exact expansions out of range) its t
    // also depends on the window, and the scene narrows the window after each hit, so a later
    // copy could win a tie it should lose: those cases (known_wrong) get one copy.
    Scene<Prim> scene;
    for (unsigned i = 0; i < (batch::has_bounding_sphere_v<Prim> && !known_wrong ? scene_copies : 1u); ++i) scene.add(prim);
    const auto scene_hit = intersect(policy, ray, scene);
    if (scene_hit.has_value() != hit.has_value())
        v.push_back({"scene.agrees", p + ": scene " + (scene_hit ? "hit" : "missed") + " but scalar intersect " + (hit ? "hit" : "missed")});
    else if (hit && (!same(scene_hit->hit, *hit) || scene_hit->index != 0))
        v.push_back({"scene.agrees", p + ": scene hit " + describe(scene_hit->hit) + " index " + std::to_string(scene_hit->index) +
                                         " differs from scalar " + describe(*hit)});
    // Fewer fields, the same answer: the scalar and the scene queries asked for t alone, or for the
    // point and normal without the bounds (the scene then builds the record from the crossing its
    // search found), give the full record's values in those fields and the defaults elsewhere.
    for (const HitFields fields : {HitFields::t, HitFields::point | HitFields::normal}) {
        const std::string f = fields == HitFields::t ? " (fields t)" : " (fields point|normal)";
        const auto part = intersect(policy, ray, prim, fields);
        const auto scene_part = intersect(policy, ray, scene, fields);
        if (part.has_value() != hit.has_value() || (hit && !same(*part, restricted(*hit, fields))))
            v.push_back({"fields.agree", p + f + ": intersect " + (part ? "hit " + describe(*part) : std::string("missed")) +
                                             ", full record " + (hit ? describe(*hit) : std::string("missed"))});
        if (scene_part.has_value() != hit.has_value() || (hit && (!same(scene_part->hit, restricted(*hit, fields)) || scene_part->index != 0)))
            v.push_back({"fields.scene_agrees", p + f + ": scene " + (scene_part ? "hit " + describe(scene_part->hit) : std::string("missed")) +
                                                    ", full record " + (hit ? describe(*hit) : std::string("missed"))});
    }
    const bool scene_occ = occluded(policy, ray, scene);
    if (scene_occ != occ)
        v.push_back({"scene.occluded_agrees", p + ": scene occluded = " + (scene_occ ? "true" : "false") + ", scalar " + (occ ? "true" : "false")});

    // The stream path (many rays against one primitive: the bounding-sphere filter in SIMD
    // lanes over copies of the ray, the last copy in a partial lane group): every copy's answer
    // is the scalar one.
    if constexpr (batch::has_bounding_sphere_v<Prim>) {
        batch::RayStream<T> stream;
        for (unsigned i = 0; i < scene_copies; ++i) stream.push_back(ray);
        std::vector<std::optional<Hit<T>>> stream_hits;
        std::vector<unsigned char> stream_occ;
        batch::intersect(policy, stream, prim, stream_hits);
        batch::occluded(policy, stream, prim, stream_occ);
        for (unsigned i = 0; i < scene_copies; ++i) {
            if (stream_hits[i].has_value() != hit.has_value() || (hit && !same(*stream_hits[i], *hit)) || bool(stream_occ[i]) != occ) {
                v.push_back({"stream.agrees", p + ": ray " + std::to_string(i) + " of a stream " +
                                                  (stream_hits[i] ? "hit " + describe(*stream_hits[i]) : std::string("missed")) +
                                                  ", occluded " + (stream_occ[i] ? "true" : "false") + "; scalar " +
                                                  (hit ? "hit " + describe(*hit) : std::string("missed"))});
                break;
            }
        }
    }

    if (hit) check_t_error(ray, prim, *hit, name, out, known_wrong);
}

}  // namespace detail_check

// Every invariant for one (ray, primitive) pair under fast, stable and accurate.
template <class Prim>
Checked check(const Ray<scalar_t<Prim>>& ray, const Prim& prim, const Options& options = {})
{
    Checked out;
    out.usable_ray = detail_check::ray_may_hit(ray);
    out.valid_primitive = static_cast<bool>(validate(prim));
    const bool may_hit = out.usable_ray && out.valid_primitive;
    const unsigned copies = std::max(1u, options.scene_copies);
    detail_check::check_policy(fast, "fast", ray, prim, may_hit, copies, out);
    detail_check::check_policy(stable, "stable", ray, prim, may_hit, copies, out);
    if (options.skip_known_hangs && accurate_may_hang(ray, prim)) out.accurate_skipped = true;
    else detail_check::check_policy(accurate, "accurate", ray, prim, may_hit, copies, out);
    if (options.skip_known) {
        const auto before = out.violations.size();
        out.violations.erase(std::remove_if(out.violations.begin(), out.violations.end(),
                                            [](const Violation& v) { return v.known || known_open(v.invariant); }),
                             out.violations.end());
        out.known = int(before - out.violations.size());
    }
    return out;
}

// One line per violation, for logs and test failures.
inline std::string to_string(const std::vector<Violation>& violations)
{
    std::string s;
    for (const auto& v : violations) s += "  [" + v.invariant + "] " + v.detail + "\n";
    return s;
}

}  // namespace rayq::fuzz
