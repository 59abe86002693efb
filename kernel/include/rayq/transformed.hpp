// rayq — a primitive placed in the world by an affine object-to-world map (3×4), stored with
// its inverse. Rays go into object space unnormalized, so t is the world ray's parameter.
#pragma once

#include <cmath>
#include <limits>

#include <algorithm>

#include "detail/bounded.hpp"
#include "detail/policy_ops.hpp"
#include "query.hpp"
#include "validation.hpp"

namespace rayq {

// p ↦ L·p + t, stored row-major as [L | t].
template <class T>
struct Affine3 {
    T m[3][4];

    static constexpr Affine3 identity() { return {{{T(1), T(0), T(0), T(0)}, {T(0), T(1), T(0), T(0)}, {T(0), T(0), T(1), T(0)}}}; }
    static constexpr Affine3 translation(const Vec3<T>& t)
    {
        return {{{T(1), T(0), T(0), t.x}, {T(0), T(1), T(0), t.y}, {T(0), T(0), T(1), t.z}}};
    }
    static constexpr Affine3 scaling(const Vec3<T>& s)
    {
        return {{{s.x, T(0), T(0), T(0)}, {T(0), s.y, T(0), T(0)}, {T(0), T(0), s.z, T(0)}}};
    }
    // Rotation by `angle` radians about `axis` (Rodrigues), then translation by `t`.
    static Affine3 rotation(const Vec3<T>& axis, T angle, const Vec3<T>& t = {T(0), T(0), T(0)})
    {
        const Vec3<T> k = detail::unit(axis);
        const T c = std::cos(angle), s = std::sin(angle), v = T(1) - c;
        return {{{c + k.x * k.x * v, k.x * k.y * v - k.z * s, k.x * k.z * v + k.y * s, t.x},
                 {k.y * k.x * v + k.z * s, c + k.y * k.y * v, k.y * k.z * v - k.x * s, t.y},
                 {k.z * k.x * v - k.y * s, k.z * k.y * v + k.x * s, c + k.z * k.z * v, t.z}}};
    }

    constexpr Vec3<T> linear(const Vec3<T>& v) const
    {
        return {m[0][0] * v.x + m[0][1] * v.y + m[0][2] * v.z, m[1][0] * v.x + m[1][1] * v.y + m[1][2] * v.z,
                m[2][0] * v.x + m[2][1] * v.y + m[2][2] * v.z};
    }
    // Lᵀ·v: with L the inverse's linear part, this carries normals (the inverse transpose).
    constexpr Vec3<T> linear_transposed(const Vec3<T>& v) const
    {
        return {m[0][0] * v.x + m[1][0] * v.y + m[2][0] * v.z, m[0][1] * v.x + m[1][1] * v.y + m[2][1] * v.z,
                m[0][2] * v.x + m[1][2] * v.y + m[2][2] * v.z};
    }
    constexpr Vec3<T> point(const Vec3<T>& p) const { return linear(p) + Vec3<T>{m[0][3], m[1][3], m[2][3]}; }

    constexpr T determinant() const
    {
        return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
               m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
    }

    // The inverse map by the adjugate; entries are NaN/Inf when the linear part is singular.
    Affine3 inverse() const
    {
        const T inv_det = T(1) / determinant();
        Affine3 r{};
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) {
                const int i1 = (j + 1) % 3, i2 = (j + 2) % 3, j1 = (i + 1) % 3, j2 = (i + 2) % 3;
                r.m[i][j] = (m[i1][j1] * m[i2][j2] - m[i1][j2] * m[i2][j1]) * inv_det;
            }
        const Vec3<T> t = r.linear(Vec3<T>{m[0][3], m[1][3], m[2][3]});
        r.m[0][3] = -t.x;
        r.m[1][3] = -t.y;
        r.m[2][3] = -t.z;
        return r;
    }

    // Composition: (a * b)(p) = a(b(p)).
    friend constexpr Affine3 operator*(const Affine3& a, const Affine3& b)
    {
        Affine3 r{};
        for (int i = 0; i < 3; ++i) {
            for (int j = 0; j < 4; ++j) {
                T s = j == 3 ? a.m[i][3] : T(0);
                for (int k = 0; k < 3; ++k) s += a.m[i][k] * b.m[k][j];
                r.m[i][j] = s;
            }
        }
        return r;
    }
};

template <class Prim, class T = scalar_t<Prim>>
struct Transformed {
    using scalar_type = T;
    Prim object;
    Affine3<T> to_world;
    Affine3<T> to_object;  // to_world's inverse

    static Transformed place(const Prim& object, const Affine3<T>& to_world) { return {object, to_world, to_world.inverse()}; }
};

template <class Prim>
Transformed<Prim> transformed(const Prim& object, const Affine3<scalar_t<Prim>>& to_world)
{
    return Transformed<Prim>::place(object, to_world);
}

template <class Prim, class T>
struct is_primitive<Transformed<Prim, T>> : std::bool_constant<is_primitive_v<Prim>> {};

template <class Prim, class T>
inline Validation validate(const Transformed<Prim, T>& x)
{
    const Validation inner = validate(x.object);
    if (!inner) return inner;
    bool finite = true;
    for (const auto* a : {&x.to_world, &x.to_object})
        for (const auto& row : a->m)
            for (T v : row) finite = finite && std::isfinite(v);
    // Singular when the determinant is negligible against the product of the column lengths
    // (Hadamard's bound, |det| <= ∏|colᵢ|): a scale-free test.
    const auto& m = x.to_world.m;
    const T hadamard = length(Vec3<T>{m[0][0], m[1][0], m[2][0]}) * length(Vec3<T>{m[0][1], m[1][1], m[2][1]}) *
                       length(Vec3<T>{m[0][2], m[1][2], m[2][2]});
    const T det = x.to_world.determinant();
    return detail::Validator{}
        .require(finite, Defect::non_finite, "Transformed: a matrix entry is NaN or infinite (or the map is singular)")
        .require(std::abs(det) > T(64) * std::numeric_limits<T>::epsilon() * hadamard, Defect::degenerate,
                 "Transformed: to_world is singular (determinant ~ 0)")
        .result();
}

// The object sees origin' = W⁻¹·o and direction' = L⁻¹·d, and the same t and window.
template <class Policy, class Prim, class T>
inline Crossings<T> crossings(Policy policy, const Ray<T>& ray, const Transformed<Prim, T>& x, int limit = 2)
{
    const Ray<T> local{x.to_object.point(ray.origin), x.to_object.linear(ray.direction), ray.tmin, ray.tmax};
    return detail::crossings_up_to(policy, local, x.object, limit, 0);
}

namespace detail {

// How far the stored inverse M may be from the exact W⁻¹, relative to the point it maps: with
// E = I − M·W (homogeneous 4×4, last row 0, computed with certified bounds) W⁻¹ = (I − E)⁻¹·M,
// so |W⁻¹x − M·x|∞ <= ‖E‖∞/(1 − ‖E‖∞) · ‖(M·x, w)‖∞ (w = 1 for points, 0 for directions).
template <class T>
inline T inverse_defect(const Affine3<T>& m, const Affine3<T>& w)
{
    using B = Bounded<T>;
    T norm = T(0);
    for (int i = 0; i < 3; ++i) {
        T row = T(0);
        for (int j = 0; j < 4; ++j) {
            B mw = j == 3 ? B{m.m[i][3]} : B{T(0)};
            for (int k = 0; k < 3; ++k) mw += B{m.m[i][k]} * B{w.m[k][j]};
            row = grow(row + upper(B{i == j ? T(1) : T(0)} - mw));
        }
        norm = std::max(norm, row);
    }
    if (!(norm < T(0.5))) return std::numeric_limits<T>::infinity();
    return grow(norm / ((T(1) - norm) * (T(1) - T(2) * unit_roundoff<T>)));
}

template <class T>
inline Vec3<Bounded<T>> map_bounded(const Affine3<T>& m, const Vec3<Bounded<T>>& v, bool point, T defect)
{
    using B = Bounded<T>;
    B r[3];
    const B x[3] = {v.x, v.y, v.z};
    T largest = point ? T(1) : T(0);
    for (int i = 0; i < 3; ++i) {
        r[i] = point ? B{m.m[i][3]} : B{T(0)};
        for (int k = 0; k < 3; ++k) r[i] += B{m.m[i][k]} * x[k];
        largest = std::max(largest, upper(r[i]));
    }
    const T widen = grow(defect * largest);
    for (B& c : r) c.e = grow(c.e + widen);
    return {r[0], r[1], r[2]};
}

}  // namespace detail

// The object's residual along the object-space ray, widened by the inverse's own error, so the
// bound holds for the exact map to_world — the input — not only for the stored to_object.
template <class Prim, class T>
inline detail::Residual<detail::Bounded<T>> residual(const Transformed<Prim, T>& x, const Vec3<detail::Bounded<T>>& o,
                                    const Vec3<detail::Bounded<T>>& d, detail::Bounded<T> t, Part part)
{
    const T defect = detail::inverse_defect(x.to_object, x.to_world);
    return residual(x.object, detail::map_bounded(x.to_object, o, true, defect), detail::map_bounded(x.to_object, d, false, defect), t,
                    part);
}

// The object's trims along the object-space ray (mapped as for the residual).
template <class Prim, class T>
inline detail::Margins<detail::Bounded<T>> trim_margins(const Transformed<Prim, T>& x, const Vec3<detail::Bounded<T>>& o,
                                                        const Vec3<detail::Bounded<T>>& d, detail::Bounded<T> t, Part part)
{
    const T defect = detail::inverse_defect(x.to_object, x.to_world);
    return trim_margins(x.object, detail::map_bounded(x.to_object, o, true, defect),
                        detail::map_bounded(x.to_object, d, false, defect), t, part);
}

// The transform rounds: accurate's decisions on transformed instances are not exact (issue 4).
template <class Prim, class T>
struct accurate_decides_exactly<Transformed<Prim, T>> : std::false_type {};

// Normals go back through the inverse transpose; the entering flag needs no change, since an
// affine bijection maps the solid's inside to the inside.
template <class Prim, class T>
inline Vec3<T> outward_normal(const Transformed<Prim, T>& x, const Vec3<T>& p, Part part)
{
    const Vec3<T> n = detail::unit(outward_normal(x.object, x.to_object.point(p), part));
    return x.to_object.linear_transposed(n);
}

}  // namespace rayq
