// rayq — the arithmetic of the batch filters, independent of the primitive types: the per-ray
// values (FilterRay, SphereFilterRay, BoundFilterRay), the bounding-sphere constants (BoundSlack)
// and the one test both batch patterns share (bound_keep), on packs of lanes or on one T; and the
// one-lane tests with which the scalar accurate path answers certain misses before its exact
// arithmetic (exactly_missed_sphere, exactly_missed_axial). batch/sphere.hpp and
// batch/bounding_sphere.hpp build on it.
#pragma once

#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <limits>
#include <type_traits>

#include "../detail/bounded.hpp"
#include "../detail/exact_crossings.hpp"
#include "../detail/inline.hpp"
#include "../detail/lanes.hpp"
#include "../detail/ulp.hpp"
#include "../ray.hpp"
#include "../vec3.hpp"

namespace rayq::batch {
template <class T>
struct BoundingSphere;
}  // namespace rayq::batch

namespace rayq::detail {

// The center and radius computed in double and the radius rounded up into T with a relative
// margin that covers double's own rounding (a few ulps of double, far below one of float).
template <class T>
batch::BoundingSphere<T> to_bound(const Vec3<double>& c, double radius, double fine)
{
    const double r = radius * (1 + 64 * std::numeric_limits<double>::epsilon());
    T rt = static_cast<T>(r);
    if (static_cast<double>(rt) < r) rt = next_up(rt);  // inline: this runs per ray in accurate's own miss test
    return {{static_cast<T>(c.x), static_cast<T>(c.y), static_cast<T>(c.z)}, rt, static_cast<T>(fine)};
}

// The smallest of the lengths that are not zero (a cone's apex radius is zero by design).
inline double smallest_nonzero(std::initializer_list<double> lengths)
{
    double m = std::numeric_limits<double>::infinity();
    for (const double x : lengths)
        if (x != 0) m = std::min(m, std::abs(x));
    return m;
}

inline double norm2(const Vec3<double>& v) { return std::sqrt(dot(v, v)); }

}  // namespace rayq::detail

namespace rayq::batch {

using rayq::detail::norm1;  // |v|₁, the filters' bound on a point's coordinates

// What both filters need of one ray, computed once per ray, and their shared constants. The
// constructors are forced inline: in a large translation unit (rayq-bench-embree) GCC called them
// out of line, and 16 capped cylinders under `fast` ran at 16 M rays/s native against 26 M in a
// small program; 28.6 inlined.
template <class T>
struct FilterRay {
    Vec3<T> origin;
    T o1;  // |o|₁

    RAYQ_INLINE explicit FilterRay(const Ray<T>& ray) : origin(ray.origin), o1(norm1(ray.origin)) {}

    // Every policy's discriminant of a sphere errs by at most γ(n)·(b² + |a·c|) ≤ 2γ(n)·a·(|u|² + r²)
    // with n ≤ 10 (pbrt-v4 "Managing Rounding Error" §6.8.1 bounds; Ray Tracing Gems ch. 7 for the
    // forms): K = 256 unit roundoffs covers it with a wide margin, plus the filter's own ≤ 8ε·|u|².
    static constexpr int k_slack = 256;
    static constexpr T k_eps() { return T(k_slack) * std::numeric_limits<T>::epsilon(); }
    // Products that underflow err by at most denorm_min/2 absolutely; in the scalar policies such
    // errors are divided by a = |d|² (≥ the smallest normal for a usable ray), so K·min/|d|² (plus
    // K·min for the filter's own underflow) bounds them in units of ℓ².
    static constexpr T k_min = T(k_slack) * std::numeric_limits<T>::min();
    static inline const T sqrt_k_min = std::sqrt(k_min) * T(1.001);
    // The rounding argument holds while the policies' products stay finite: at most
    // |d|²·(|u|² + r²) (fast's b² and a·c, stable's |d|²·(r² − ℓ²)), within a factor 4. Where they
    // overflow a policy may report a hit anywhere (stable's discriminant overflowed and put a hit
    // at t = 0: fixtures/fuzz/sphere/crash-stable-overflow-scene-drops-hit). With |d|, |o|₁, |c|₁
    // and r below H = 2^((max_exponent − 8)/4) those products stay below 5H⁴ ≤ max/16, so a ray
    // with a longer |d| or |o|₁ keeps every lane, and a sphere with a larger |c|₁ or r is stored
    // with an infinite radius, which every comparison below keeps (no test per lane).
    static inline const T huge = std::ldexp(T(1), (std::numeric_limits<T>::max_exponent - 8) / 4);
};

// The window tests' side of a ray: |d|, 1/|d| (t is measured in units of d) and the underflow
// slack on t, √(K·min)/|d| and more (√(a + b) ≤ √a + √b: no second square root). One square root
// and one division, each factored so that no step is subnormal: min/|d|² was, for every ray with
// |d| > 1, and a subnormal result costs x86 a ~100-cycle assist (most of a small scene's time per
// ray).
template <class T>
struct RayScale {
    T len, inv_len, t_slack_abs;

    RAYQ_INLINE explicit RayScale(const Vec3<T>& direction)
        : len(length(direction)), inv_len(T(1) / len), t_slack_abs(FilterRay<T>::sqrt_k_min * (inv_len + T(1)) * inv_len)
    {
    }
};

// The sphere filter's ray: the line test's side of it (sphere_line), whose comparison is multiplied
// by |d|²: d, (1 − Kε)·|d|², the underflow slack times |d|² (k_min·(|d|² + 1): no subnormal step).
// The window test (sphere_candidates) is multiplied by |d|²
// and squared, and takes its terms from |d|² where it runs. Neither needs a square root or a
// division: most rays of a scene pass
// every group by the line test alone, and a ray with a candidate no longer waits for |d| and 1/|d|
// before its first scalar test (rayq-bench-embree, -march=native, float spheres under `fast` with
// point and normal, medians of 5, µs per 4,096 rays: 1,000 spheres 493 -> 478–484, 16 spheres 51 ->
// 50; the line tests alone went 9.0 -> 6.5 ns per ray when their square root and division were
// first deferred).
template <class T>
struct SphereFilterRay : FilterRay<T> {
    Vec3<T> direction;
    T dd, line_dd, line_slack;  // |d|², (1 − Kε)·|d|², k_min·(|d|² + 1)
    bool extreme;  // |d| or |o|₁ at least `huge` (|d|² against huge²: the margin above is 4): keep every lane

    RAYQ_INLINE explicit SphereFilterRay(const Ray<T>& ray) : FilterRay<T>(ray)
    {
        direction = ray.direction;
        dd = dot(ray.direction, ray.direction);
        line_dd = dd * (T(1) - FilterRay<T>::k_eps());
        line_slack = FilterRay<T>::k_min * (dd + T(1));
        extreme = !(dd < this->huge * this->huge && this->o1 < this->huge);
    }
};

// The same line test divided by (1 − Kε)·|d|² (batch/sphere.hpp, line_passes_group): d/|d| where
// SphereFilterRay has d, for scans over many lane groups. Its square root and division wait before
// the first group, but each group then needs one product fewer (rayq-bench-embree, -march=native,
// AVX2, `fast` with point and normal, ms per 65,536 rays, medians of 15: 1,000 spheres 19.5 ->
// 17.4; 16 spheres, two groups, lost 2-3% to the wait, which is why scenes of a few groups keep
// SphereFilterRay's).
// Finite: a usable ray has |d|² ≥ the smallest normal number, so 1/|d|² ≤ 2^(1 − min_exponent).
template <class T>
struct UnitLineRay {
    Vec3<T> n;  // d/(|d|·√(1 − Kε))
    T slack;    // SphereFilterRay::line_slack / ((1 − Kε)·|d|²), rounded up (0.1%, above its roundings)

    RAYQ_INLINE explicit UnitLineRay(const Vec3<T>& direction, T dd)
    {
        constexpr T scale2 = T(1) / (T(1) - FilterRay<T>::k_eps());
        const T inv_dd = T(1) / dd;
        n = direction * (line_scale * std::sqrt(inv_dd));
        slack = FilterRay<T>::k_min * scale2 * (T(1) + inv_dd) * T(1.001);
    }
    static inline const T line_scale = T(1) / std::sqrt(T(1) - FilterRay<T>::k_eps());  // 1/√(1 − Kε)
};

template <class T>
struct BoundingSphere {
    Vec3<T> center;
    T radius;  // every point of the primitive is within `radius` of `center` (exactly, up to the
               // filter's Kε·|c| slack for the rounding of the center)
    T fine;    // the primitive's smallest nonzero length (radius, edge, axis): where its own
               // arithmetic may underflow (BoundSlack); 0 where it is known to leave the range
    Vec3<T> normal{};    // a planar (Cramer) primitive's unit normal, else zero
    T plane_slack = -1;  // its a = 576ε·κ (at most 1: every lane), else negative (header)
};

// The filter's constants (see the header comment).
template <class T>
struct BoundSlack {
    static constexpr T k_eps = T(256) * std::numeric_limits<T>::epsilon();
    // (a + b)² ≤ (1 + 1/16)·a² + 17·b²: a is the slack-widened radius, b the √(Kε) term, so the
    // comparison needs no square root per lane; (|u| + R)² ≤ 2(|u|² + R²) once more.
    static constexpr T widen = T(17) / T(16);
    static constexpr T relative = T(68) * k_eps;  // 17·b² ≤ 68Kε(|u|² + R²) + 34(Kε|o|₁)²
    static inline const T sqrt_k_eps = std::sqrt(k_eps);
    // The argument above is about rounding. Products also underflow or overflow, and then a
    // policy may report a hit anywhere (found by the fuzz harnesses' stream and scene
    // invariants): the fast and stable products of up to eight lengths in T (a cylinder's
    // discriminant b² − ac of b = (u × A)·(d × A): a float cylinder of radius 1e-6 seen along
    // d of length 1e-6 underflowed it, and the filter dropped a hit the scalar path reported), and
    // accurate's exact expansions of up to twelve factors in double, after exact_curved_crossings
    // has scaled the largest length to ~1 (so what counts there is the smallest length relative to
    // the largest). Lanes are therefore always kept when a length (|o − c|, R, the primitive's
    // finest length, |d|, |o|₁) leaves [tiny, huge], or when the finest length is below 2^-80 of
    // |o − c|: float ~[1.8e-5, 6.5e4], double ~[1.7e-26, 1.3e38].
    static inline const T tiny = std::max(std::sqrt(std::sqrt(std::sqrt(std::numeric_limits<T>::min()))),
                                          static_cast<T>(std::pow(std::numeric_limits<double>::min(), 1.0 / 12)));
    static inline const T huge = std::sqrt(std::sqrt(std::sqrt(std::numeric_limits<T>::max())));
    static constexpr T disparity = T(0x1p80);
    static bool outside(T length) { return !(length > tiny && length < huge); }
    // The same range for a length known by its square, narrowed by 8 ulps at each end so that it
    // answers `outside` for every square whose rounded square root `outside` would (a ray's |d|,
    // known as |d|² before its square root is taken).
    static inline const T tiny2 = static_cast<T>(double(tiny) * double(tiny) * (1 + 8 * double(std::numeric_limits<T>::epsilon())));
    static inline const T huge2 = static_cast<T>(double(huge) * double(huge) * (1 - 8 * double(std::numeric_limits<T>::epsilon())));
    RAYQ_INLINE static bool outside_squared(T length2) { return !(length2 > tiny2 && length2 < huge2); }

    // The slack-widened radius R + Kε·(R + |c|₁); inf (every comparison keeps the lane) for
    // lengths outside the range or a center beyond it.
    static T reach(const BoundingSphere<T>& b)
    {
        const T c1 = norm1(b.center);
        if (outside(b.radius) || outside(b.fine) || !(c1 < huge)) return std::numeric_limits<T>::infinity();
        return b.radius + k_eps * (b.radius + c1);
    }
    // The |o − c|² from which on a lane is kept: huge², or less for a primitive whose finest
    // length is below 2^-80 of that distance.
    static T far(const BoundingSphere<T>& b)
    {
        const T f = b.fine * disparity;
        return std::min(huge * huge, f * f);
    }
};

// A direction `accurate` cannot bring near unit length exactly (a component of 2^512 beside a
// subnormal one), or whose components then span beyond 2^±64, gives products that leave double's
// range in the exact tests, which then decide wrongly (known_issues.hpp): a disk's normal (a hit
// 24 units from a disk of radius 3.3), a ray's direction (a component of 2^-902 beside 2: a hit
// at t = 0 one unit from a disk of radius 0.05) or a parallelogram's edge (components 2^-1074 and
// 1.3e-312 beside 0.96: a hit at t = −0 for a ray nearly in its plane, outside it; all found by
// the fuzz harnesses' scene and stream invariants). The filters keep every lane of such a
// primitive and, for the exact test, of such a ray, so batch and scalar still agree.
// Components already within range need no scaling (direction_near_unit returns them as they are):
// the common case, tested first and inline, as the bound filter does for every ray.
template <class T>
RAYQ_INLINE bool normal_within_exact_range(const Vec3<T>& normal)
{
    return detail::zero_or_within_exact_range(normal) || detail::zero_or_within_exact_range(detail::direction_near_unit(normal));
}

// What the bounding-sphere filter needs of one ray: d and |d|² for its line test, which compares
// ℓ²·|d|² (no square root or division stands between a ray and its first lane test, as in the
// sphere filter); the ray's scale (RayScale) for the window test and the plane test; Kε·|o|₁
// (squared and scaled) for the rounding of the hit point's absolute coordinates.
// `exact_range`: also keep every lane for a direction that `accurate`'s exact tests cannot take
// (normal_within_exact_range, above); only the exact test (BoundTest::exact) needs it, and a
// scene under `fast` or `stable` leaves it out (its 17 instructions per ray sat on the way to the
// first lane test: rayq-bench-embree, native, `fast` with point and normal over Embree's cone
// curves, three alternating runs: 16 capped cylinders 4.54, 4.64, 4.52 -> 4.87, 4.85, 4.81; one
// capped cylinder 5.62, 5.83, 5.69 -> 6.59, 6.45, 6.54).
template <class T>
struct BoundFilterRay : FilterRay<T>, RayScale<T> {
    Vec3<T> direction;
    T dd;         // |d|²
    T abs_slack;  // (34·(Kε·|o|₁)² + the underflow slack on ℓ²)·|d|² (inf: keep every lane, and
                  // t_slack_abs is inf too)

    RAYQ_INLINE explicit BoundFilterRay(const Ray<T>& ray, bool exact_range = true) : FilterRay<T>(ray), RayScale<T>(ray.direction)
    {
        direction = ray.direction;
        dd = dot(ray.direction, ray.direction);
        const T ko1 = BoundSlack<T>::k_eps * this->o1;
        const bool extreme = !(this->o1 < BoundSlack<T>::huge) || BoundSlack<T>::outside_squared(dd) ||
                             (exact_range && !normal_within_exact_range(ray.direction));
        // The underflow slack on ℓ²: K·min/|d|² + K·min (see FilterRay); times |d|², K·min·(1 + |d|²),
        // and one K·min more for the rounding of |d|² and of the 34·(Kε·|o|₁)²·|d|² below (which
        // underflows only below min). No step is subnormal.
        const T line_slack_abs = FilterRay<T>::k_min * (dd + T(2));
        abs_slack = extreme ? std::numeric_limits<T>::infinity() : T(34) * ko1 * ko1 * dd + line_slack_abs;
        if (extreme) this->t_slack_abs = std::numeric_limits<T>::infinity();  // nor the window test
    }
};

// The ray's direction as packs: d, |d|² and 1/|d| (see BoundFilterRay).
template <class P>
struct DirectionPacks {
    P dx, dy, dz, dd, inv_len;
};

// The window the filter tests against (see BoundTest): the ray's (tmin, tmax), narrowed as a
// scene finds nearer hits.
template <class P>
struct WindowPacks {
    P tmin, tmax, t_slack_abs;
};

// Which test the filter may make for `Policy` on `Prim` (see the header):
//   exact   accurate: the tight line test and a window test with Kε margins;
//   point   fast and stable on primitives whose reported t is the one whose point they test
//           (cylinders, disks): the line test with the √(Kε) slack, and a window test with the
//           sphere filter's margin, since that point lies within the slack of the bound;
//   line    fast and stable on the Cramer primitives (triangles, parallelograms), whose t may err
//           far more than the point they test near a flat part seen edge-on: the line test and
//           the plane test, no window test.
enum class BoundTest { exact, point, line };

// What every test of a bounding sphere starts from, given the center offset u = o − c, the
// direction d and the widened radius: |u|², u·d, the squared distance ℓ² from the center to the
// line times |d|², ℓ²·|d|² = |u|²·|d|² − (u·d)², and reach². Every comparison of ℓ² is made times
// |d|². Computed with cancellation, ℓ²·|d|² errs by at most ~24ε·|u|²·|d|² (with u's and |d|²'s
// rounding), far inside the Kε·|u|² slack of every test; finite for a ray that is not extreme
// (|u|² < far ≤ huge², |d|² < huge²), and a lane whose terms overflow is kept (NaN compares false).
template <class P>
struct LineTerms {
    P uu, ud, ll, rr;
};

template <class P>
RAYQ_INLINE LineTerms<P> line_terms(const P& ux, const P& uy, const P& uz, const DirectionPacks<P>& d, const P& reach)
{
    const P uu = ux * ux + uy * uy + uz * uz;
    const P ud = ux * d.dx + uy * d.dy + uz * d.dz;
    return {uu, ud, uu * d.dd - ud * ud, reach * reach};
}

// The line test of the window tests (Test ≠ line; in point's form also Test = line's, beside its
// plane test), on |u|², ℓ²·|d|² and reach²: true where the ray's line certainly passes the
// bound. exact: the filter's own rounding; point: that, the
// discriminant's error near tangency and the tested point's rounding, all within Kε·(|u|² + R²)
// in units of ℓ² (header); abs_slack comes times |d|² (BoundFilterRay).
template <class T, BoundTest Test, class P>
RAYQ_INLINE auto passes_line(const LineTerms<P>& l, const P& dd, const P& abs_slack)
{
    using S = BoundSlack<T>;
    constexpr T k_line = Test == BoundTest::exact ? S::k_eps : T(2) * S::k_eps;
    return l.ll > (P(T(1) + k_line) * l.rr + P(k_line) * l.uu) * dd + abs_slack;
}

// A planar primitive's plane_weight() as packs.
template <class P>
struct PlanePacks {
    P wx, wy, wz;
};

// The one test both patterns share, on packs P of T (or on T itself, the one-lane fallback): may
// some policy hit a primitive whose bounding sphere has center offset u = o − c and widened
// radius `reach`, along direction d? NaN and overflow keep a lane (the scalar path decides).
// With `plane`, also keep lanes the plane test keeps: drop only if
// (s/2a)²·(ℓ² − 2·reach²) > |u|² + reach², which implies s·(ℓ − reach) > a·(|u| + reach)
// ((x + y)² ≤ 2x² + 2y² twice), without a square root per lane; d̂·w = s/2a.
// With `window`, the window test too (Test ≠ line); Test = exact uses the tight line test.
template <class T, BoundTest Test, class P>
RAYQ_INLINE auto bound_keep(const P& ux, const P& uy, const P& uz, const DirectionPacks<P>& d, const P& reach, const P& far,
                            const P& abs_slack, const PlanePacks<P>* plane, const WindowPacks<P>* window)
{
    using S = BoundSlack<T>;
    const LineTerms<P> line = line_terms(ux, uy, uz, d, reach);
    const auto [uu, ud, ll, rr] = line;
    const auto out_of_range = !(uu < far);  // kept whatever the tests say
    if constexpr (Test == BoundTest::line) {
        if (!plane) {
            const P limit = (P(S::widen + S::relative) * rr + P(S::relative) * uu) * d.dd + abs_slack;
            return !(ll > limit) || out_of_range;
        }
        // With the plane test the √(Kε) slack is not needed: Cramer's accepted crossings lie within
        // a·(|u| + R)/s of the primitive (header), which the plane test keeps, so the line test
        // keeps only what the filter's own rounding may hide (as for `point`). The plane test
        // therefore takes that rounding off ℓ² itself (Kε·|u|²·|d|² + abs_slack, above the line
        // terms' ~24ε): the √(Kε) slack, 68Kε·|u|² in ℓ², had covered it, and it kept 25 float
        // triangles per ray of rayq-bench-scene's 1,024 where `accurate` keeps 1.35.
        const P sw = (d.dx * plane->wx + d.dy * plane->wy + d.dz * plane->wz) * d.inv_len;  // on d̂
        const P ll_low = (ll - P(S::k_eps) * uu * d.dd - abs_slack) * (d.inv_len * d.inv_len);
        return !passes_line<T, BoundTest::point>(line, d.dd, abs_slack) || !(sw * sw * (ll_low - P(2) * rr) > uu + rr) || out_of_range;
    } else {
        const auto line_far = passes_line<T, Test>(line, d.dd, abs_slack);
        if (rayq::detail::all_lanes(line_far && !out_of_range)) return out_of_range;  // most lane groups of a scene
        const P tc = -ud * (d.inv_len * d.inv_len);
        const P rad = reach * d.inv_len;
        // exact: |u| ≤ (|tc| + rad)·|d| on a kept line, so Kε of it covers tc's rounding, and of
        // rad the correctly rounded t's last ulp. point: the reported t's point is within
        // √(Kε)·(|u| + R) of the bound, so t within that of tc ± rad, as in the sphere filter.
        const P k = P(Test == BoundTest::exact ? T(2) * S::k_eps : S::sqrt_k_eps);
        const P margin = rad + k * (rayq::detail::abs_lanes(tc) + rad + rad) + window->t_slack_abs;
        return !(line_far || tc + margin < window->tmin || tc - margin > window->tmax) || out_of_range;
    }
}

// Axial primitives: a cylinder of radius max(r0, r1) around the axis segment, from its middle.
template <class T>
BoundingSphere<T> axial_bound(const Vec3<T>& p0, const Vec3<T>& p1, T r0, T r1)
{
    const Vec3<double> a = detail::lift<double>(p0), b = detail::lift<double>(p1);
    const double half = 0.5 * detail::norm2(b - a), r = std::max(double(r0), double(r1));
    return detail::to_bound<T>((a + b) * 0.5, std::sqrt(half * half + r * r), detail::smallest_nonzero({2 * half, double(r0), double(r1)}));
}

// The certain-miss tests of the scalar accurate path: whether `accurate` certainly reports no
// crossing of a primitive, because the ray's line passes a ball or tube that holds it farther than
// the rounding of the test can hide. One lane, on the primitive's own inputs in W (hardware double
// for float inputs), without division or square root. Rounding (pbrt-v4 "Managing Rounding Error"
// §6.8.1 bounds: one rounding of each difference, two per cross component, three per sum):
//   a ball of center o − m, radius² R²: |m × d|²/|d|² is the line's squared distance from the
//     center; the computed |m × d|² errs by at most ~20 unit roundoffs of |m|²·|d|², plus 2·|δm|
//     ·(|m| + |δm|)·|d|² for an error δm in m;
//   the tube of radius R around the line through p0 along A: (u·n)²/|n|² is the line's squared
//     distance from it, u = o − p0, n = d × A; computed, u·n errs by at most ~9 unit roundoffs of
//     |u|·|d|·|A| and |n|² by ~12 of |d|²·|A|², so (|u·n| − e)² > R²·(|n|² + e') needs at most
//     18·|u|²·|d|²·|A|² + 12·R²·|d|²·|A|² unit roundoffs more than the computed comparison.
// k = 256 unit roundoffs of the named terms covers each with a wide margin, and each comparison's
// own rounding. With every squared length and |d|² in 2^±200 no product overflows and an
// underflowing one (a tiny component) errs by far less than that slack; outside that range, or
// with NaN or infinite inputs, the tests answer nothing. (The scene and stream filters test the
// window before they call the scalar path; these do not.)
namespace certain_miss {
template <class W>
constexpr W miss_slack = W(256) * (std::numeric_limits<W>::epsilon() / 2);
template <class W>
RAYQ_INLINE bool moderate_square(W x) { return x >= W(0x1p-200) && x <= W(0x1p200); }
// The ball: |m × d|² > (R²·(1 + k) + k·(|m|² + ss))·|d|², where ss is 0 for an m with one rounding
// per component and |A|² for m = u − A/2.
template <class W>
RAYQ_INLINE bool line_passes_ball(const Vec3<W>& m, const Vec3<W>& d, W dd, W rr, W ss)
{
    constexpr W k = miss_slack<W>;
    const Vec3<W> md = cross(m, d);
    return dot(md, md) > (rr * (W(1) + k) + k * (dot(m, m) + ss)) * dd;
}
}  // namespace certain_miss

// A sphere: the ball itself (m = o − c).
template <class T>
inline bool exactly_missed_sphere(const Ray<T>& ray, const Vec3<T>& center, T radius)
{
    using W = typename rayq::detail::ExactComponent<T>::type;
    using certain_miss::moderate_square, rayq::detail::lift;
    const Vec3<W> m = lift<W>(ray.origin) - lift<W>(center), d = lift<W>(ray.direction);
    const W rr = W(radius) * W(radius), dd = dot(d, d);
    if (!(moderate_square(dot(m, m)) && moderate_square(dd) && moderate_square(rr))) return false;
    return certain_miss::line_passes_ball(m, d, dd, rr, W(0));
}

// An axial primitive (cylinder, cone) from p0 to p1 whose radii are at most R = max(|r0|, |r1|):
// the tube of radius R around its axis line, which holds the side and both caps, then its bounding
// ball, of center p0 + A/2 and radius² |A|²/4 + R² (A = p1 − p0; m = u − A/2 errs by at most 2
// unit roundoffs of |m| + |A|). Of a short, wide capped cylinder's misses the tube answers 80% and
// the ball 52%, together 95% (without them each took the quick lane's three parts, ~1,600
// instructions). A line parallel to the axis (n = 0) is left to the ball.
template <class T>
inline bool exactly_missed_axial(const Ray<T>& ray, const Vec3<T>& p0, const Vec3<T>& p1, T r0, T r1)
{
    using W = typename rayq::detail::ExactComponent<T>::type;
    using certain_miss::moderate_square, rayq::detail::lift;
    const Vec3<W> a = lift<W>(p1) - lift<W>(p0), u = lift<W>(ray.origin) - lift<W>(p0), d = lift<W>(ray.direction);
    const W r = std::max(std::abs(W(r0)), std::abs(W(r1))), rr = r * r;
    const W uu = dot(u, u), aa = dot(a, a), dd = dot(d, d);
    if (!(moderate_square(uu) && moderate_square(aa) && moderate_square(dd) && moderate_square(rr))) return false;
    constexpr W k = certain_miss::miss_slack<W>;
    const Vec3<W> n = cross(d, a);
    const W un = dot(u, n);
    if (un * un > rr * dot(n, n) * (W(1) + k) + k * (uu + rr) * (dd * aa)) return true;
    return certain_miss::line_passes_ball(u - a * W(0.5), d, dd, W(0.25) * aa + rr, aa);
}

}  // namespace rayq::batch
