// rayq — the batch paths of every bounded primitive: a conservative SIMD filter on bounding
// spheres, in both batch patterns, then the scalar intersector on the lanes it keeps.
//
//   * one ray against many primitives stored as structure of arrays (the BVH-leaf pattern):
//     BoundSoA + bound_candidates (scene.hpp uses it for disks, parallelograms, triangles,
//     cylinders and cones; spheres have their own, tighter filter in batch/sphere.hpp);
//   * many rays against one primitive (the stream/packet pattern): RayStream + ray_candidates, and
//     batch::intersect / batch::occluded over a span of rays.
//
// As with the sphere filter, the answers are the scalar path's, bit for bit: a lane is dropped
// only when the policy certainly misses there. A hit lies near the primitive: `accurate` decides
// exactly, and `fast`/`stable` hits on flat primitives are within rounding of the surface (the hit
// point is computed and tested, so it errs by a few ε·(|o| + |c| + |t·d|): pbrt-v4 "Managing
// Rounding Error" §6.8). The filter therefore drops a primitive only when the ray's line passes its
// bounding sphere (center c, radius R) by more than √(Kε)·(|o − c| + R) + Kε·(|o|₁ + |c|₁),
// K = 256 unit roundoffs — the √ term also covers a discriminant error's effect near tangency
// (Ray Tracing Gems ch. 7) — or, triangles and parallelograms, by more than the filter's own
// rounding where their plane test (below) drops it too. No window test for them: a policy's t may
// err far more than its point near a flat part seen edge-on.
//
// `accurate` decides hit and window exactly and rounds t correctly, so its exact hit lies within
// R of c, and its t within R/|d| of the center's projection tc = (c − o)·d/|d|²: the filter keeps
// only lanes whose line passes within R + Kε·(R + |o − c|) of the center (the filter's own
// rounding; no √ term) and whose [tc − R/|d|, tc + R/|d|], widened by Kε·(|tc| + R/|d|), meets
// the window. The √(Kε) slack of the other policies kept ~14× more lanes on the benchmark's
// capped cylinders (24 per ray of 1,024 where ~1.7 pass the exact test).
//
// Triangles and parallelograms get a second, wider test under `fast` and `stable`
// (BoundingSphere::plane_slack). These decide inside with Cramer's numerators (Möller–Trumbore),
// each erring by at most g = 16ε of |q|·|d|·|e| (q = o − corner), against the determinant
// det = −d·(e0 × e1) = |d|·|e0 × e1|·s, s = |d̂·n̂| the sine of the ray's angle to the plane. The
// exact crossing X of a line they accept is therefore within ~6g·κ·(|q| + |e|)/s of the primitive
// (≤ 36g·κ·(|o − c| + R)/s), κ = |e0|·|e1|/|e0 × e1| (1.15 for an equilateral triangle, huge for a
// sliver), and X lies on the line: a lane is dropped only if also s·(ℓ − R) > a·(|o − c| + R),
// a = 576ε·κ (ℓ the line's distance from c). Without it a line nearly in the plane and far beside
// the primitive can be "hit": the fuzz harnesses' scene and stream invariants found such a hit on
// a float sliver triangle (κ ≈ 3e7).
// That test keeps every lane Cramer's decisions may accept, so their line test needs no √(Kε)
// slack, only the filter's own rounding (bound_keep).
//
// Cylinders under `fast` and `stable`: their quadratic is the norm form |u' + t·v|² = w² of the
// projected line, u' = fl((o − p0) × A), v = fl(d × A), with a and b from the same computed v. So
// even when v is only rounding noise (a ray parallel to the axis, where a nearly vanishes), the
// roots are those of a line within ε·|t·d| of the true one, solved with the sphere's errors: the
// hit's true squared distance from the axis errs by at most Kε·(|u|² + r²) (the discriminant's
// error b² + |ac| ≤ 2a·(|u|² + r²), as for the sphere filter; Ray Tracing Gems ch. 7), and its
// axial coordinate, from the slab's t = ((p − o)·A)/(d·A), by a few ε·|o − p|, however small
// d·A. Its squared distance from the bound's center is thus at most R² + 2Kε·(|u|² + R²): the
// line test (BoundTest::point) keeps every lane they hit, and a window test may use the sphere
// filter's margin. (kernel test BatchTest.FilterKeepsCylinderHitsAlongTheAxis measures the worst
// case at 1% of that slack.) Disks test the point at their t as well.
//
// Not filtered (bound_filter_exact_v is false; the batch paths run the scalar loop): cones under
// `fast` and `stable`. Their a = |v|² − s² cancels for a ray parallel to a generator, so a, b and c
// round as three unrelated perturbations and the far root ~ −2b/a of no nearby cone may land in
// the slab — the fuzz harnesses' scene and stream invariants found such hits half a radius away
// from a cone.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <initializer_list>
#include <limits>
#include <optional>
#include <type_traits>
#include <vector>

#include "../cone.hpp"
#include "../cylinder.hpp"
#include "../detail/bounded.hpp"
#include "../detail/inline.hpp"
#include "../detail/lanes.hpp"
#include "../disk.hpp"
#include "../hit.hpp"
#include "../parallelogram.hpp"
#include "../policy.hpp"
#include "../query.hpp"
#include "../ray.hpp"
#include "../triangle.hpp"
#include "filter_core.hpp"
#include "sphere.hpp"

namespace rayq::detail {

// The plane test's n̂ and a = 576ε·κ for a primitive whose inside test solves
// o + t·d = corner + α·e0 + β·e1 by Cramer's rule (see the header). From a = 1 on (or a κ that is
// not finite) every lane is kept, since s·(ℓ − R) ≤ |o − c| always.
template <class T>
void set_plane_slack(batch::BoundingSphere<T>& b, const Vec3<double>& e0, const Vec3<double>& e1)
{
    const Vec3<double> n = cross(e0, e1);
    const double area = norm2(n), kappa = norm2(e0) * norm2(e1) / area;
    const double a = 576 * std::numeric_limits<T>::epsilon() * kappa;
    b.plane_slack = a < 1 ? static_cast<T>(a) : T(1);
    if (area > 0) b.normal = {static_cast<T>(n.x / area), static_cast<T>(n.y / area), static_cast<T>(n.z / area)};
}

}  // namespace rayq::detail

namespace rayq::batch {

template <class T>
BoundingSphere<T> bounding_sphere(const Sphere<T>& s) { return {s.center, s.radius, s.radius}; }

// A disk whose normal, or a triangle or parallelogram whose edge, is out of the exact range
// (normal_within_exact_range, filter_core.hpp) keeps every lane: its finest length is set to 0.
template <class T>
BoundingSphere<T> bounding_sphere(const Disk<T>& d)
{
    return detail::to_bound<T>(detail::lift<double>(d.center), double(d.radius), normal_within_exact_range(d.normal) ? double(d.radius) : 0.0);
}

template <class T>
BoundingSphere<T> bounding_sphere(const Triangle<T>& t)
{
    const Vec3<double> a = detail::lift<double>(t.a), b = detail::lift<double>(t.b), c = detail::lift<double>(t.c);
    const Vec3<double> m = (a + b + c) / 3.0;
    BoundingSphere<T> bound = detail::to_bound<T>(m, std::max({detail::norm2(a - m), detail::norm2(b - m), detail::norm2(c - m)}),
                                                  detail::smallest_nonzero({detail::norm2(b - a), detail::norm2(c - b), detail::norm2(a - c)}));
    detail::set_plane_slack(bound, b - a, c - a);  // the edges planar_coordinates solves with
    if (!normal_within_exact_range(b - a) || !normal_within_exact_range(c - a)) bound.fine = T(0);  // keep every lane
    return bound;
}

template <class T>
BoundingSphere<T> bounding_sphere(const Parallelogram<T>& p)
{
    const Vec3<double> e0 = detail::lift<double>(p.edge0), e1 = detail::lift<double>(p.edge1);
    const Vec3<double> m = detail::lift<double>(p.corner) + (e0 + e1) * 0.5;
    BoundingSphere<T> bound = detail::to_bound<T>(m, 0.5 * std::max(detail::norm2(e0 + e1), detail::norm2(e0 - e1)),
                                                  detail::smallest_nonzero({detail::norm2(e0), detail::norm2(e1)}));
    detail::set_plane_slack(bound, e0, e1);
    if (!normal_within_exact_range(e0) || !normal_within_exact_range(e1)) bound.fine = T(0);  // keep every lane
    return bound;
}

template <class T>
BoundingSphere<T> bounding_sphere(const Cylinder<T>& c) { return axial_bound(c.p0, c.p1, c.radius, c.radius); }

template <class T>
BoundingSphere<T> bounding_sphere(const Cone<T>& c) { return axial_bound(c.p0, c.p1, c.r0, c.r1); }

template <class Prim, class = void>
struct has_bounding_sphere : std::false_type {};
template <class Prim>
struct has_bounding_sphere<Prim, std::void_t<decltype(bounding_sphere(std::declval<const Prim&>()))>> : std::true_type {};
template <class Prim>
inline constexpr bool has_bounding_sphere_v = has_bounding_sphere<Prim>::value;

template <class Prim>
struct is_cone : std::false_type {};
template <class T>
struct is_cone<Cone<T>> : std::true_type {};

// Whether the bounding-sphere filter keeps every primitive `Policy` hits (see the header comment).
template <class Policy, class Prim>
inline constexpr bool bound_filter_exact_v =
    has_bounding_sphere_v<Prim> && (std::is_same_v<Policy, accurate_policy> || !is_cone<Prim>::value);

// The plane test's weight n̂/(2a), so that a lane computes s/2a as one dot product (zero for a
// primitive without a plane test; a ≥ 576ε, so it stays finite).
template <class T>
Vec3<T> plane_weight(const BoundingSphere<T>& b)
{
    if (!(b.plane_slack > T(0))) return {T(0), T(0), T(0)};
    return b.normal * (T(1) / (T(2) * b.plane_slack));
}

// What the filter needs of one primitive, computed once per primitive: its bounding sphere's
// center, BoundSlack's reach and far, and the plane weight.
template <class T>
struct PrimitiveBound {
    Vec3<T> center{};
    T reach = T(0), far = T(0);
    Vec3<T> w{};          // plane_weight()
    bool planar = false;  // it has a plane test

    PrimitiveBound() = default;
    explicit PrimitiveBound(const BoundingSphere<T>& b)
        : center(b.center), reach(BoundSlack<T>::reach(b)), far(BoundSlack<T>::far(b)), w(plane_weight(b)), planar(b.plane_slack >= T(0))
    {
    }
};

// Bounding spheres as structure of arrays, in whole lane groups (padding as in SphereSoA).
template <class T>
struct BoundSoA {
    static constexpr int width = rayq::detail::Lanes<T>::width;
    rayq::detail::LaneColumn<T> cx, cy, cz, reach, far;  // PrimitiveBound of each primitive
    rayq::detail::LaneColumn<T> wx, wy, wz;
    bool planar = false;  // some primitive has a plane test
    std::size_t count = 0;

    void push_back(const BoundingSphere<T>& b)
    {
        // Padding lanes: a point bound at the origin, in range (far = inf), as the sphere filter's
        // padding is, so that the line test passes them as it passes any bound the line misses. With
        // far = 0 they were out of range, kept, and a group with padding was never skipped whole
        // (20 capped cylinders, standalone loop, -march=native, ns per ray with point and normal:
        // 41.7–44.1 -> 36.3–38.6).
        if (count % width == 0) {
            for (rayq::detail::LaneColumn<T>* v : {&cx, &cy, &cz, &reach, &wx, &wy, &wz}) v->resize(v->size() + width, T(0));
            far.resize(far.size() + width, std::numeric_limits<T>::infinity());
        }
        const PrimitiveBound<T> p(b);
        cx[count] = p.center.x;
        cy[count] = p.center.y;
        cz[count] = p.center.z;
        reach[count] = p.reach;
        far[count] = p.far;
        wx[count] = p.w.x;
        wy[count] = p.w.y;
        wz[count] = p.w.z;
        planar = planar || p.planar;
        ++count;
    }
    template <class Prim>
    void push_back(const Prim& p) { push_back(bounding_sphere(p)); }
    std::size_t groups() const { return cx.size() / width; }
    std::uint32_t live(std::size_t g) const
    {
        const std::size_t n = count - g * width;
        return n >= static_cast<std::size_t>(width) ? (width == 32 ? ~0u : (1u << width) - 1u) : (1u << n) - 1u;
    }
};

template <class Prim>
struct reports_tested_point : std::false_type {};
template <class T>
struct reports_tested_point<Cylinder<T>> : std::true_type {};
template <class T>
struct reports_tested_point<Disk<T>> : std::true_type {};

template <class Policy, class Prim>
inline constexpr BoundTest bound_test_v = std::is_same_v<Policy, accurate_policy> ? BoundTest::exact
                                          : reports_tested_point<Prim>::value       ? BoundTest::point
                                                                                    : BoundTest::line;

// Bit i set: primitive i of lane group g may be hit by `Policy` in (tmin, tmax); clear: certainly
// missed. Test: bound_test_v<Policy, the stored primitive type>.
template <class Policy, BoundTest Test, class T>
RAYQ_INLINE std::uint32_t bound_candidates(const BoundFilterRay<T>& f, T tmin, T tmax, const BoundSoA<T>& s, std::size_t g)
{
    using L = rayq::detail::Lanes<T>;
    using P = typename L::pack;
    const std::size_t i = g * L::width;
    const DirectionPacks<P> d{P(f.direction.x), P(f.direction.y), P(f.direction.z), P(f.dd), P(f.inv_len)};
    PlanePacks<P> plane;
    const bool planar = Test == BoundTest::line && s.planar;
    if (planar) plane = {L::load(&s.wx[i]), L::load(&s.wy[i]), L::load(&s.wz[i])};
    const WindowPacks<P> window{P(tmin), P(tmax), P(f.t_slack_abs)};
    const auto keep = bound_keep<T, Test>(P(f.origin.x) - L::load(&s.cx[i]), P(f.origin.y) - L::load(&s.cy[i]),
                                          P(f.origin.z) - L::load(&s.cz[i]), d, L::load(&s.reach[i]), L::load(&s.far[i]),
                                          P(f.abs_slack), planar ? &plane : nullptr, &window);
    return L::bits(keep) & s.live(g);
}

// Whether the ray's line certainly passes the bounds from index i on, by the window tests' line
// test alone: as packs P (loaded by `load`) or as one T. Never for Test = line, whose plane test
// may keep a lane the line test drops.
template <BoundTest Test, class P, class T, class Load>
RAYQ_INLINE auto line_passes_bounds(const BoundFilterRay<T>& f, const BoundSoA<T>& s, std::size_t i, Load load)
{
    static_assert(Test != BoundTest::line, "the line test alone decides nothing for Test = line");
    const P dd(f.dd);
    const DirectionPacks<P> d{P(f.direction.x), P(f.direction.y), P(f.direction.z), dd, P(f.inv_len)};  // 1/|d|: unused here
    const LineTerms<P> line = line_terms(P(f.origin.x) - load(&s.cx[i]), P(f.origin.y) - load(&s.cy[i]), P(f.origin.z) - load(&s.cz[i]), d,
                                         load(&s.reach[i]));
    return passes_line<T, Test>(line, dd, P(f.abs_slack)) && line.uu < load(&s.far[i]);
}

// The lanes of group g that the line test alone keeps (Test ≠ line; no window test): a superset of
// bound_candidates'. A lane out of range is kept, as bound_keep keeps it.
template <BoundTest Test, class T>
RAYQ_INLINE std::uint32_t bound_line_candidates(const BoundFilterRay<T>& f, const BoundSoA<T>& s, std::size_t g)
{
    using L = rayq::detail::Lanes<T>;
    const auto load = [](const T* p) RAYQ_INLINE_LAMBDA { return L::load(p); };
    return ~L::bits(line_passes_bounds<Test, typename L::pack>(f, s, g * L::width, load)) & s.live(g);
}

// Whether the ray's line certainly passes every primitive of group g (what a scan skips groups
// by; bound_candidates then gives them no lane). Always false for Test = line.
template <BoundTest Test, class T>
RAYQ_INLINE bool line_passes_group(const BoundFilterRay<T>& f, const BoundSoA<T>& s, std::size_t g)
{
    if constexpr (Test == BoundTest::line) {
        return false;
    } else {
        using L = rayq::detail::Lanes<T>;
        const auto load = [](const T* p) RAYQ_INLINE_LAMBDA { return L::load(p); };
        return rayq::detail::all_lanes(line_passes_bounds<Test, typename L::pack>(f, s, g * L::width, load));
    }
}

// The same for primitive i alone, in scalar arithmetic: a scene of one or two primitives tests each
// so before its scalar query (cheaper than a lane group's set-up).
template <BoundTest Test, class T>
RAYQ_INLINE bool line_passes_bound(const BoundFilterRay<T>& f, const BoundSoA<T>& s, std::size_t i)
{
    if constexpr (Test == BoundTest::line) return false;
    else return line_passes_bounds<Test, T>(f, s, i, [](const T* p) RAYQ_INLINE_LAMBDA { return *p; });
}

// ---- many rays against one primitive -------------------------------------------------------------

// Rays, and what the filter needs of each as structure of arrays in whole lane groups (padding
// lanes, and rays that can never hit, are masked out by live()).
template <class T>
struct RayStream {
    std::vector<Ray<T>> rays;
    static constexpr int width = rayq::detail::Lanes<T>::width;
    rayq::detail::LaneColumn<T> ox, oy, oz, dx, dy, dz, dd, inv_len, abs_slack;  // BoundFilterRay's
    rayq::detail::LaneColumn<T> tmin, tmax, t_slack_abs;                         // the window test's (exact policies)
    std::vector<unsigned char> usable_ray;
    std::size_t count = 0;

    void clear()
    {
        rays.clear();
        for (rayq::detail::LaneColumn<T>* v : columns()) v->clear();
        usable_ray.clear();
        count = 0;
    }
    void push_back(const Ray<T>& ray)
    {
        rays.push_back(ray);
        if (count % width == 0) {
            for (rayq::detail::LaneColumn<T>* v : columns()) v->resize(v->size() + width, T(0));
            usable_ray.resize(usable_ray.size() + width, 0);
        }
        usable_ray[count] = usable(ray);
        if (usable_ray[count]) {  // an unusable ray never hits: its lane stays zero and is masked
            const BoundFilterRay<T> f(ray);
            ox[count] = f.origin.x, oy[count] = f.origin.y, oz[count] = f.origin.z;
            dx[count] = f.direction.x, dy[count] = f.direction.y, dz[count] = f.direction.z;
            dd[count] = f.dd, inv_len[count] = f.inv_len, abs_slack[count] = f.abs_slack;
            tmin[count] = ray.tmin, tmax[count] = ray.tmax, t_slack_abs[count] = f.t_slack_abs;
        }
        ++count;
    }
    std::size_t groups() const { return ox.size() / width; }
    std::uint32_t live(std::size_t g) const
    {
        std::uint32_t m = 0;
        for (int lane = 0; lane < width && g * width + std::size_t(lane) < count; ++lane)
            m |= std::uint32_t(usable_ray[g * width + std::size_t(lane)]) << lane;
        return m;
    }

private:
    std::array<rayq::detail::LaneColumn<T>*, 12> columns() { return {&ox, &oy, &oz, &dx, &dy, &dz, &dd, &inv_len, &abs_slack, &tmin, &tmax, &t_slack_abs}; }
};

// Bit i set: ray i of lane group g may hit the primitive bounded by `b` under `Policy`.
// Test: bound_test_v<Policy, the primitive's type>.
template <class Policy, BoundTest Test, class T>
inline std::uint32_t ray_candidates(const RayStream<T>& s, std::size_t g, const PrimitiveBound<T>& b)
{
    using L = rayq::detail::Lanes<T>;
    using P = typename L::pack;
    const std::size_t i = g * L::width;
    const DirectionPacks<P> d{L::load(&s.dx[i]), L::load(&s.dy[i]), L::load(&s.dz[i]), L::load(&s.dd[i]), L::load(&s.inv_len[i])};
    const PlanePacks<P> plane{P(b.w.x), P(b.w.y), P(b.w.z)};
    const bool planar = Test == BoundTest::line && b.planar;
    [[maybe_unused]] WindowPacks<P> window;
    if constexpr (Test != BoundTest::line) window = {L::load(&s.tmin[i]), L::load(&s.tmax[i]), L::load(&s.t_slack_abs[i])};
    const auto keep = bound_keep<T, Test>(L::load(&s.ox[i]) - P(b.center.x), L::load(&s.oy[i]) - P(b.center.y),
                                          L::load(&s.oz[i]) - P(b.center.z), d, P(b.reach), P(b.far), L::load(&s.abs_slack[i]),
                                          planar ? &plane : nullptr, &window);
    return L::bits(keep) & s.live(g);
}

// Calls visit(i) for every ray i of `rays` that may hit `prim` under `policy`, in order: the
// filter's candidates, or every usable ray where the filter is not exact for this policy.
template <class Policy, class Prim, class Visit>
void each_candidate(Policy, const RayStream<scalar_t<Prim>>& rays, const Prim& prim, Visit visit)
{
    using T = scalar_t<Prim>;
    if (!validate(prim)) return;
    [[maybe_unused]] PrimitiveBound<T> b;
    if constexpr (bound_filter_exact_v<Policy, Prim>) b = PrimitiveBound<T>(bounding_sphere(prim));
    for (std::size_t g = 0; g < rays.groups(); ++g) {
        std::uint32_t m = rays.live(g);
        if constexpr (bound_filter_exact_v<Policy, Prim>) m = ray_candidates<Policy, bound_test_v<Policy, Prim>>(rays, g, b);
        for (; m != 0; m &= m - 1) visit(g * RayStream<T>::width + static_cast<std::size_t>(rayq::detail::lowest_bit(m)));
    }
}

// The stream pattern: out[i] = rayq::intersect(policy, rays.rays[i], prim, fields), bit for bit,
// with the filter skipping the rays that certainly miss.
template <class Policy, class Prim, std::enable_if_t<has_bounding_sphere_v<Prim>, int> = 0>
void intersect(Policy policy, const RayStream<scalar_t<Prim>>& rays, const Prim& prim, std::vector<std::optional<Hit<scalar_t<Prim>>>>& out,
               HitFields fields = HitFields::all)
{
    out.assign(rays.count, std::nullopt);
    each_candidate(policy, rays, prim, [&](std::size_t i) { out[i] = rayq::intersect(policy, rays.rays[i], prim, fields); });
}

// out[i] = rayq::occluded(policy, rays.rays[i], prim).
template <class Policy, class Prim, std::enable_if_t<has_bounding_sphere_v<Prim>, int> = 0>
void occluded(Policy policy, const RayStream<scalar_t<Prim>>& rays, const Prim& prim, std::vector<unsigned char>& out)
{
    out.assign(rays.count, 0);
    each_candidate(policy, rays, prim, [&](std::size_t i) { out[i] = rayq::occluded(policy, rays.rays[i], prim); });
}

}  // namespace rayq::batch
