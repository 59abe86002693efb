// rayq — one ray against many spheres stored as structure of arrays (the BVH-leaf pattern).
//
// The batch path is a conservative culling filter in SIMD lanes followed by the scalar
// intersector on the lanes it keeps, so its answers are the scalar path's, bit for bit, for
// every policy: the filter only has to be sure that a lane it drops would have been a miss in
// the window under any policy. It drops a sphere when the ray's line passes it by clearly more
// than every policy's discriminant error, or when the sphere lies clearly outside (tmin, tmax).
#pragma once

#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "../detail/lanes.hpp"
#include "filter_core.hpp"
#include "../ray.hpp"
#include "../sphere.hpp"

namespace rayq::batch {

// Spheres as structure of arrays, in whole lane groups; the last group is padded with zeros
// (finite, so no lane computes NaN) and live() masks the padding out.
template <class T>
struct SphereSoA {
    static constexpr int width = detail::Lanes<T>::width;
    rayq::detail::LaneColumn<T> cx, cy, cz, r;
    rayq::detail::LaneColumn<T> reach2;  // r²·(1 + Kε)/(1 − Kε): the line test's side of each sphere (sphere_line)
    std::size_t count = 0;

    void push_back(const Sphere<T>& s)
    {
        if (count % width == 0) {  // open a new lane group, filled with padding
            for (rayq::detail::LaneColumn<T>* v : {&cx, &cy, &cz, &r, &reach2}) v->resize(v->size() + width, T(0));
        }
        cx[count] = s.center.x;
        cy[count] = s.center.y;
        cz[count] = s.center.z;
        // Beyond the range where the policies' products stay finite: kept by every comparison.
        const T huge = SphereFilterRay<T>::huge;
        r[count] = std::abs(s.radius) < huge && norm1(s.center) < huge ? s.radius : std::numeric_limits<T>::infinity();
        constexpr T k_eps = SphereFilterRay<T>::k_eps();
        reach2[count] = r[count] * r[count] * ((T(1) + k_eps) / (T(1) - k_eps));
        ++count;
    }
    std::size_t groups() const { return cx.size() / width; }
    // Lanes of group g that hold spheres (the last group may be partly padding).
    std::uint32_t live(std::size_t g) const
    {
        const std::size_t n = count - g * width;
        return n >= static_cast<std::size_t>(width) ? (width == 32 ? ~0u : (1u << width) - 1u) : (1u << n) - 1u;
    }
};

// The line test of sphere_candidates: which lanes of group g the ray's line certainly passes by,
// and u·d (times −1/|d|²: the center's t).
template <class P>
struct SphereLine {
    P ud;
    decltype(P() < P()) far;
};
// u = o − c for the spheres of lane group g.
template <class T>
RAYQ_INLINE Vec3<typename detail::Lanes<T>::pack> offsets_from_centers(const FilterRay<T>& f, const SphereSoA<T>& s, std::size_t g)
{
    using L = detail::Lanes<T>;
    using P = typename L::pack;
    const std::size_t i = g * L::width;
    return {P(f.origin.x) - L::load(&s.cx[i]), P(f.origin.y) - L::load(&s.cy[i]), P(f.origin.z) - L::load(&s.cz[i])};
}

template <class T>
RAYQ_INLINE SphereLine<typename detail::Lanes<T>::pack> sphere_line(const SphereFilterRay<T>& f, const SphereSoA<T>& s, std::size_t g)
{
    using L = detail::Lanes<T>;
    using P = typename L::pack;
    const std::size_t i = g * L::width;
    const auto [ux, uy, uz] = offsets_from_centers(f, s, g);
    // The line passes by when ℓ² > r² + Kε·(|u|² + r²) + slack, ℓ² = |u|² − (u·d)²/|d|² the
    // squared distance from the center to the line. Multiplied by |d|², that is
    // (|u|² − r²·(1 + Kε)/(1 − Kε))·(1 − Kε)·|d|² − (u·d)² > slack·|d|²: every factor moves to the
    // ray's side (f.line_dd, f.line_slack) or the sphere's (SphereSoA::reach2), and u·d is the
    // window test's too. (It was divided by 1 − Kε, u·d scaled by 1/√(1 − Kε): three products per
    // ray on the way to the first lane test and one per kept group; rayq-bench-embree, native,
    // AVX-512, `fast` with point and normal, `--rounds=3`, three alternating runs: 16 spheres
    // 0.942, 0.952, 0.946 -> 0.917, 0.926, 0.923 ms per 65,536 rays.)
    // With d itself rather than d/|d|, no square root and division stand between a ray and its
    // first lane test: most rays of a scene miss every sphere, and that chain was most of their
    // time (16 float spheres, -march=native, ns per ray of a closest hit with point and normal:
    // 20.3 -> 17.9; 1,000 spheres, where the extra product per lane group counts, 137.8 -> 140.2).
    // Computed with cancellation, its error (≤ 16ε·(|u|² + r²)·|d|², with the stored sides' and
    // (1 − Kε)·|d|²'s rounding) is inside the Kε slack; clarity beats precision here. Finite: |u|,
    // |d| and r are below 2H (FilterRay::huge, else the lane or the ray keeps everything), so the
    // products stay below 12H⁴.
    const P uu = uz * uz + uy * uy + ux * ux;
    const P ud = ux * P(f.direction.x) + uy * P(f.direction.y) + uz * P(f.direction.z);
    return {ud, (uu - L::load(&s.reach2[i])) * P(f.line_dd) - ud * ud > P(f.line_slack)};
}

// Whether the ray's line certainly passes by every sphere of group g (what a scan skips by).
template <class T>
RAYQ_INLINE bool line_passes_group(const SphereFilterRay<T>& f, const SphereSoA<T>& s, std::size_t g)
{
    return !f.extreme && detail::all_lanes(sphere_line(f, s, g).far);
}

// The same answer from sphere_line's comparison divided by (1 − Kε)·|d|² (UnitLineRay): the line
// passes by when |u|² − reach² − (u·n)² > slack, n = d/(|d|·√(1 − Kε)): seven multiplies per group
// where sphere_line has eight. Its rounding: the cancelling sum errs by at most 16ε·(|u|² + r²), as
// sphere_line's does before its factor |d|², and n's own (a division, a square root, three
// products: ≤ 5ε relative) adds ≤ 11ε·|u|² to (u·n)²: inside the Kε slack with room. Finite under
// the same bounds (|u|, r below 2H, |n| ≈ 1).
template <class T>
RAYQ_INLINE bool line_passes_group(const SphereFilterRay<T>& f, const UnitLineRay<T>& unit, const SphereSoA<T>& s, std::size_t g)
{
    using L = detail::Lanes<T>;
    using P = typename L::pack;
    const std::size_t i = g * L::width;
    const auto [ux, uy, uz] = offsets_from_centers(f, s, g);
    const P un = ux * P(unit.n.x) + uy * P(unit.n.y) + uz * P(unit.n.z);
    const P w = ((ux * ux - L::load(&s.reach2[i])) + uy * uy + uz * uz) - un * un;
    return !f.extreme && detail::all_lanes(w > P(unit.slack));
}

// The lanes of group g whose sphere the ray's line may meet (sphere_line alone, no window test):
// a superset of sphere_candidates'.
template <class T>
RAYQ_INLINE std::uint32_t sphere_line_candidates(const SphereFilterRay<T>& f, const SphereSoA<T>& s, std::size_t g)
{
    if (f.extreme) return s.live(g);
    return ~detail::Lanes<T>::bits(sphere_line(f, s, g).far) & s.live(g);
}

// Bit i set: sphere i of lane group g may be hit in (tmin, tmax) by some policy; clear: it is
// certainly missed by every policy. NaN and overflow keep a lane (the scalar path decides).
template <class T>
RAYQ_INLINE std::uint32_t sphere_candidates(const SphereFilterRay<T>& f, T tmin, T tmax, const SphereSoA<T>& s, std::size_t g)
{
    using L = detail::Lanes<T>;
    using P = typename L::pack;
    const T sqrt_k_eps = std::sqrt(SphereFilterRay<T>::k_eps());
    if (f.extreme) return s.live(g);
    const SphereLine<P> l = sphere_line(f, s, g);
    const P r = L::load(&s.r[g * L::width]);
    const auto line_far = l.far;
    if (detail::all_lanes(line_far)) return 0;  // the common case in a scene: no lane near the line
    // The crossings lie in tc ± r/|d|; a policy's t errs by at most √(Kε)·(|tc| + 2r/|d|) (the
    // square root of the discriminant's error near tangency: Ray Tracing Gems ch. 7). So the
    // sphere lies behind the window where (1 + 2√(Kε))·r/|d| < tmin − tc − √(Kε)·|tc| − slack_t,
    // and beyond it where the same is below tc − √(Kε)·|tc| − slack_t − tmax. Times |d|² and
    // squared, neither needs |d| (a square root and a division on the way to a ray's first
    // candidate): x > 0 and x² > (1 + 2√(Kε))²·r²·|d|², with x = (tmin − tc − …)·|d|², tc·|d|² =
    // −u·d. The comparison's own rounding (a few ε of its terms) is far inside the √(Kε) margin.
    // Underflow needs no slack of its own: x > 0 puts tmin or tmax more than slack_t from tc, so a
    // dropped sphere the policy hits in the window would have (1 + 2√(Kε))·r/|d| > slack_t ≥
    // √(K·min)/|d|·max(1, 1/|d|): its right side exceeds K·min, a normal number, rounded, not flushed.
    const P e = -l.ud;  // tc·|d|²
    const P se = P(sqrt_k_eps) * detail::abs_lanes(e);
    const T widen = T(1) + T(2) * sqrt_k_eps;
    // slack_t·|d|² = √(K·min)·(|d| + |d|²) at most √(K·min)·(1/2 + 3|d|²/2), as |d| ≤ (1 + |d|²)/2.
    const T t_slack_dd = FilterRay<T>::sqrt_k_min * (T(0.5) + T(1.5) * f.dd);
    const P rhs = r * r * P(f.dd * widen * widen);
    const P x_behind = P(tmin * f.dd - t_slack_dd) - e - se;
    const P x_beyond = e - se - P(tmax * f.dd + t_slack_dd);
    const auto behind = x_behind > P(0) && x_behind * x_behind > rhs;
    const auto beyond = x_beyond > P(0) && x_beyond * x_beyond > rhs;
    const auto drop = line_far || behind || beyond;
    return ~L::bits(drop) & s.live(g);
}

}  // namespace rayq::batch
