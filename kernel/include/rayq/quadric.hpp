// rayq — general quadric F(x, y, z) = Ax² + By² + Cz² + Dxy + Exz + Fyz + Gx + Hy + Iz + J = 0,
// inside where F < 0, outward normal ∇F, optionally clipped by an axis-aligned box.
// Named constructors build the classic quadrics; orient the unbounded ones with Transformed.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>

#include "detail/bounded.hpp"
#include "detail/eft.hpp"
#include "detail/policy_ops.hpp"
#include "detail/spans.hpp"
#include "quadratic.hpp"
#include "query.hpp"
#include "validation.hpp"

namespace rayq {

template <class T>
struct Box {
    Vec3<T> lo, hi;

    static constexpr Box everything()
    {
        constexpr T inf = std::numeric_limits<T>::infinity();
        return {{-inf, -inf, -inf}, {inf, inf, inf}};
    }
    constexpr bool contains(const Vec3<T>& p) const
    {
        return lo.x <= p.x && p.x <= hi.x && lo.y <= p.y && p.y <= hi.y && lo.z <= p.z && p.z <= hi.z;
    }
};

template <class T>
struct Quadric {
    using scalar_type = T;
    T A, B, C, D, E, F, G, H, I, J;
    Box<T> clip = Box<T>::everything();  // hits outside do not count

    // F(p) = (p − c)ᵀ·M·(p − c) + g·(p − c) + k with M symmetric, expanded into the ten coefficients.
    static Quadric centered(const Vec3<T>& c, const T (&m)[3][3], const Vec3<T>& g, T k, Box<T> clip = Box<T>::everything())
    {
        const Vec3<T> mc{m[0][0] * c.x + m[0][1] * c.y + m[0][2] * c.z, m[1][0] * c.x + m[1][1] * c.y + m[1][2] * c.z,
                         m[2][0] * c.x + m[2][1] * c.y + m[2][2] * c.z};
        const Vec3<T> lin = g - T(2) * mc;
        return {m[0][0], m[1][1], m[2][2], T(2) * m[0][1], T(2) * m[0][2], T(2) * m[1][2], lin.x, lin.y, lin.z,
                dot(c, mc) - dot(g, c) + k, clip};
    }

    // x'²/a² + y'²/b² + z'²/c² = 1 in the frame (axis_x, axis_y, axis_x × axis_y) centred at `center`;
    // the axes need not be unit but must be perpendicular.
    static Quadric ellipsoid(const Vec3<T>& center, const Vec3<T>& semi_axes, const Vec3<T>& axis_x = {T(1), T(0), T(0)},
                             const Vec3<T>& axis_y = {T(0), T(1), T(0)})
    {
        const Vec3<T> e[3] = {detail::unit(axis_x), detail::unit(axis_y), detail::unit(cross(axis_x, axis_y))};
        const T w[3] = {T(1) / (semi_axes.x * semi_axes.x), T(1) / (semi_axes.y * semi_axes.y), T(1) / (semi_axes.z * semi_axes.z)};
        T m[3][3] = {};
        for (int k = 0; k < 3; ++k) {
            const T ek[3] = {e[k].x, e[k].y, e[k].z};
            for (int i = 0; i < 3; ++i)
                for (int j = 0; j < 3; ++j) m[i][j] += w[k] * ek[i] * ek[j];
        }
        return centered(center, m, {T(0), T(0), T(0)}, T(-1));
    }

    // The unbounded quadrics, axis along z through `center`, clipped to the slab of the box below.
    // x²/a² + y²/b² = z/c for 0 <= z <= height (vertex at center, opening toward +z).
    static Quadric elliptic_paraboloid(const Vec3<T>& center, T a, T b, T c, T height)
    {
        return axial(center, T(1) / (a * a), T(1) / (b * b), T(0), {T(0), T(0), T(-1) / c}, T(0), T(0), height);
    }
    // x²/a² + y²/b² − z²/c² = 1 for |z| <= half_height.
    static Quadric hyperboloid_one_sheet(const Vec3<T>& center, T a, T b, T c, T half_height)
    {
        return axial(center, T(1) / (a * a), T(1) / (b * b), T(-1) / (c * c), {}, T(-1), -half_height, half_height);
    }
    // z²/c² − x²/a² − y²/b² = 1 for |z| <= half_height; inside is within the two bowls.
    static Quadric hyperboloid_two_sheets(const Vec3<T>& center, T a, T b, T c, T half_height)
    {
        return axial(center, T(1) / (a * a), T(1) / (b * b), T(-1) / (c * c), {}, T(1), -half_height, half_height);
    }
    // x²/a² + y²/b² = z²/c² for |z| <= half_height (apex at center; a double cone).
    static Quadric elliptic_cone(const Vec3<T>& center, T a, T b, T c, T half_height)
    {
        return axial(center, T(1) / (a * a), T(1) / (b * b), T(-1) / (c * c), {}, T(0), -half_height, half_height);
    }

private:
    static Quadric axial(const Vec3<T>& center, T mx, T my, T mz, Vec3<T> g, T k, T z_lo, T z_hi)
    {
        constexpr T inf = std::numeric_limits<T>::infinity();
        const T m[3][3] = {{mx, T(0), T(0)}, {T(0), my, T(0)}, {T(0), T(0), mz}};
        const Box<T> clip{{-inf, -inf, center.z + z_lo}, {inf, inf, center.z + z_hi}};
        return centered(center, m, g, k, clip);
    }
};

template <class T>
struct is_primitive<Quadric<T>> : std::true_type {};

template <class T>
inline Validation validate(const Quadric<T>& q)
{
    const T coef[10] = {q.A, q.B, q.C, q.D, q.E, q.F, q.G, q.H, q.I, q.J};
    bool finite = true, all_zero = true, degree = false;
    for (int i = 0; i < 10; ++i) {
        finite = finite && std::isfinite(coef[i]);
        all_zero = all_zero && coef[i] == T(0);
        degree = degree || (i < 9 && coef[i] != T(0));
    }
    return detail::Validator{}
        .require(finite, Defect::non_finite, "Quadric: a coefficient is NaN or infinite")
        .require(!all_zero, Defect::degenerate, "Quadric: all ten coefficients are zero")
        .require(degree, Defect::degenerate, "Quadric: only the constant J is non-zero (no surface)")
        .require(!std::isnan(q.clip.lo.x) && !std::isnan(q.clip.lo.y) && !std::isnan(q.clip.lo.z) &&
                     !std::isnan(q.clip.hi.x) && !std::isnan(q.clip.hi.y) && !std::isnan(q.clip.hi.z),
                 Defect::non_finite, "Quadric: clip box has a NaN bound")
        .require(q.clip.lo.x <= q.clip.hi.x && q.clip.lo.y <= q.clip.hi.y && q.clip.lo.z <= q.clip.hi.z, Defect::degenerate,
                 "Quadric: clip box is empty (lo > hi)")
        .result();
}

namespace detail {

// F(o + t·d) = a·t² + 2·b·t + c with a = F₂(d) (the quadratic part at d), 2b = ∇F(o)·d, c = F(o).
template <class Policy, class T>
inline CoefficientQuadratic<T> along_ray(Policy, const Quadric<T>& q, const Ray<T>& ray)
{
    const Vec3<T>& o = ray.origin;
    const Vec3<T>& d = ray.direction;
    const T h = T(0.5);
    const T a_l[6] = {q.A * d.x, q.B * d.y, q.C * d.z, q.D * d.x, q.E * d.x, q.F * d.y};
    const T a_r[6] = {d.x, d.y, d.z, d.y, d.z, d.z};
    const T b_l[12] = {q.A * o.x, q.B * o.y, q.C * o.z, h * q.D * o.x, h * q.D * o.y, h * q.E * o.x,
                       h * q.E * o.z, h * q.F * o.y, h * q.F * o.z, h * q.G, h * q.H, h * q.I};
    const T b_r[12] = {d.x, d.y, d.z, d.y, d.x, d.z, d.x, d.z, d.y, d.x, d.y, d.z};
    const T c_l[10] = {q.A * o.x, q.B * o.y, q.C * o.z, q.D * o.x, q.E * o.x, q.F * o.y, q.G, q.H, q.I, q.J};
    const T c_r[10] = {o.x, o.y, o.z, o.y, o.z, o.z, o.x, o.y, o.z, T(1)};
    if constexpr (compensated_v<Policy>) return {dot2(a_l, a_r), dot2(b_l, b_r), dot2(c_l, c_r)};
    else {
        const auto sum = [](const auto& l, const auto& r) {
            T s = T(0);
            for (std::size_t i = 0; i < sizeof(l) / sizeof(l[0]); ++i) s += l[i] * r[i];
            return s;
        };
        return {sum(a_l, a_r), sum(b_l, b_r), sum(c_l, c_r)};
    }
}

}  // namespace detail

// The surface's crossings whose points lie in the clip box; a clipped near root leaves the far one.
template <class Policy, class T>
inline Crossings<T> crossings(Policy policy, const Ray<T>& ray, const Quadric<T>& q)
{
    const Crossings<T> all = detail::crossings_of(solve_quadratic(policy, detail::along_ray(policy, q, ray)));
    Crossings<T> out;
    for (const auto& c : all)
        if (q.clip.contains(detail::point_at(policy, ray.origin, ray.direction, c.t))) out.add(c.t, c.part, c.entering);
    return out;
}

// F(o + t·d), ∇F·d and F₂(d), with certified bounds (for Hit::t_error).
// Inside the clip box: p − lo >= 0 and hi − p >= 0 for each finite bound.
template <class T, class N>
inline detail::Margins<N> trim_margins(const Quadric<T>& q, const Vec3<N>& o, const Vec3<N>& d, N t, Part)
{
    const Vec3<N> p = o + t * d;
    const N pc[3] = {p.x, p.y, p.z};
    const T lo[3] = {q.clip.lo.x, q.clip.lo.y, q.clip.lo.z}, hi[3] = {q.clip.hi.x, q.clip.hi.y, q.clip.hi.z};
    detail::Margins<N> m;
    for (int i = 0; i < 3; ++i) {
        if (std::isfinite(lo[i])) m.add(pc[i] - N{lo[i]});
        if (std::isfinite(hi[i])) m.add(N{hi[i]} - pc[i]);
    }
    return m;
}

// Quadrics are outside the accurate policy's exact contract (issue 4): their trims are checked.
template <class T>
struct accurate_decides_exactly<Quadric<T>> : std::false_type {};

template <class N, class T>
inline detail::Residual<N> residual(const Quadric<T>& q, const Vec3<N>& o, const Vec3<N>& d, N t, Part)
{
    using B = N;
    const Vec3<B> p = o + t * d;
    // k·x·y and k·x, skipped for a zero coefficient (most quadrics have some): the exact zero the
    // Bounded product now gives as well (grow_exact_operands), without its work, and a zero term
    // even where a coordinate of p overflows. 2k is exact.
    const auto kxy = [](T k, const B& x, const B& y) { return k == T(0) ? B{T(0)} : B{k} * x * y; };
    const auto kx = [](T k, const B& x) { return k == T(0) ? B{T(0)} : B{k} * x; };
    const B f = kxy(q.A, p.x, p.x) + kxy(q.B, p.y, p.y) + kxy(q.C, p.z, p.z) + kxy(q.D, p.x, p.y) + kxy(q.E, p.x, p.z) +
                kxy(q.F, p.y, p.z) + kx(q.G, p.x) + kx(q.H, p.y) + kx(q.I, p.z) + B{q.J};
    const Vec3<B> grad{kx(T(2) * q.A, p.x) + kx(q.D, p.y) + kx(q.E, p.z) + B{q.G}, kx(T(2) * q.B, p.y) + kx(q.D, p.x) + kx(q.F, p.z) + B{q.H},
                       kx(T(2) * q.C, p.z) + kx(q.E, p.x) + kx(q.F, p.y) + B{q.I}};
    const B a = kxy(q.A, d.x, d.x) + kxy(q.B, d.y, d.y) + kxy(q.C, d.z, d.z) + kxy(q.D, d.x, d.y) + kxy(q.E, d.x, d.z) + kxy(q.F, d.y, d.z);
    return {f, dot(grad, d), a};
}

template <class T>
inline Vec3<T> outward_normal(const Quadric<T>& q, const Vec3<T>& p, Part)
{
    // The gradient, every coefficient scaled by s (a power of two: only the direction matters).
    const auto gradient = [&](T s) -> Vec3<T> {
        return {T(2) * (s * q.A) * p.x + (s * q.D) * p.y + (s * q.E) * p.z + s * q.G,
                T(2) * (s * q.B) * p.y + (s * q.D) * p.x + (s * q.F) * p.z + s * q.H,
                T(2) * (s * q.C) * p.z + (s * q.E) * p.x + (s * q.F) * p.y + s * q.I};
    };
    const Vec3<T> g = gradient(T(1));
    if (std::isfinite(g.x) && std::isfinite(g.y) && std::isfinite(g.z)) return g;
    // Overflow (a coefficient or the point near the largest float): scale so that each of the
    // four terms of a component, at most 2·|coefficient|·max(|p|, 1), stays below 2^(max_exponent−3);
    // the terms lost to underflow are far below the sum's rounding.
    const T coefficient = std::max({std::abs(q.A), std::abs(q.B), std::abs(q.C), std::abs(q.D), std::abs(q.E), std::abs(q.F),
                                    std::abs(q.G), std::abs(q.H), std::abs(q.I)});
    const T extent = std::max({std::abs(p.x), std::abs(p.y), std::abs(p.z), T(1)});
    if (!(std::isfinite(coefficient) && std::isfinite(extent))) return g;
    const int excess = std::ilogb(coefficient) + std::ilogb(extent) + 6 - std::numeric_limits<T>::max_exponent;
    return gradient(std::ldexp(T(1), -std::max(excess, 0)));
}

}  // namespace rayq
