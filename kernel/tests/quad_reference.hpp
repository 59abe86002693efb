// A binary128 reference for the kernel tests: each primitive's implicit function written here
// (not the kernel's formulation), and Newton refinement of a kernel t to the exact root of the same
// float/double inputs (~1e-30 relative wherever the root is simple).
#pragma once

#include <rayq/rayq.hpp>

namespace rayq::test {

__extension__ typedef __float128 quad;

struct Q3 {
    quad x, y, z;
};
inline Q3 operator+(Q3 a, Q3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
inline Q3 operator-(Q3 a, Q3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
inline Q3 operator*(quad s, Q3 a) { return {s * a.x, s * a.y, s * a.z}; }
inline quad qdot(Q3 a, Q3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline Q3 qcross(Q3 a, Q3 b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
inline quad qabs(quad x) { return x < 0 ? -x : x; }
template <class T>
Q3 q3(const Vec3<T>& v) { return {quad(v.x), quad(v.y), quad(v.z)}; }

// F(o + t·d) for the exact primitive: what the root of means "the exact t".
template <class T>
quad implicit(const Sphere<T>& s, Q3 o, Q3 d, quad t, Part)
{
    const Q3 q = o - q3(s.center) + t * d;
    return qdot(q, q) - quad(s.radius) * quad(s.radius);
}
inline quad axial_plane(Q3 end, Q3 axis, Q3 o, Q3 d, quad t) { return qdot(o + t * d - end, axis); }
template <class T>
quad implicit(const Cylinder<T>& c, Q3 o, Q3 d, quad t, Part part)
{
    const Q3 axis = q3(c.p1) - q3(c.p0);
    if (part != Part::surface) return axial_plane(part == Part::cap0 ? q3(c.p0) : q3(c.p1), axis, o, d, t);
    const Q3 qa = qcross(o - q3(c.p0) + t * d, axis);
    return qdot(qa, qa) - quad(c.radius) * quad(c.radius) * qdot(axis, axis);
}
template <class T>
quad implicit(const Cone<T>& c, Q3 o, Q3 d, quad t, Part part)
{
    const Q3 axis = q3(c.p1) - q3(c.p0);
    if (part != Part::surface) return axial_plane(part == Part::cap0 ? q3(c.p0) : q3(c.p1), axis, o, d, t);
    const Q3 q = o - q3(c.p0) + t * d, qa = qcross(q, axis);
    const quad aa = qdot(axis, axis), r = quad(c.r0) * aa + (quad(c.r1) - quad(c.r0)) * qdot(q, axis);
    return qdot(qa, qa) * aa - r * r;
}
template <class T>
quad implicit(const Quadric<T>& k, Q3 o, Q3 d, quad t, Part)
{
    const Q3 p = o + t * d;
    return quad(k.A) * p.x * p.x + quad(k.B) * p.y * p.y + quad(k.C) * p.z * p.z + quad(k.D) * p.x * p.y + quad(k.E) * p.x * p.z +
           quad(k.F) * p.y * p.z + quad(k.G) * p.x + quad(k.H) * p.y + quad(k.I) * p.z + quad(k.J);
}
template <class T>
quad implicit(const Plane<T>& p, Q3 o, Q3 d, quad t, Part) { return qdot(o + t * d - q3(p.point), q3(p.normal)); }
template <class T>
quad implicit(const Disk<T>& p, Q3 o, Q3 d, quad t, Part) { return qdot(o + t * d - q3(p.center), q3(p.normal)); }
template <class T>
quad implicit(const Parallelogram<T>& p, Q3 o, Q3 d, quad t, Part)
{
    return qdot(o + t * d - q3(p.corner), qcross(q3(p.edge0), q3(p.edge1)));
}
template <class T>
quad implicit(const Triangle<T>& p, Q3 o, Q3 d, quad t, Part)
{
    return qdot(o + t * d - q3(p.a), qcross(q3(p.b) - q3(p.a), q3(p.c) - q3(p.a)));
}
// Transformed: the object sees the ray through the exact inverse of to_world (adjugate in binary128).
template <class P, class T>
quad implicit(const Transformed<P, T>& x, Q3 o, Q3 d, quad t, Part part)
{
    quad m[3][3], inv[3][3];
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) m[i][j] = quad(x.to_world.m[i][j]);
    const quad det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
                     m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            inv[i][j] = (m[(j + 1) % 3][(i + 1) % 3] * m[(j + 2) % 3][(i + 2) % 3] - m[(j + 1) % 3][(i + 2) % 3] * m[(j + 2) % 3][(i + 1) % 3]) / det;
    const auto apply = [&](Q3 v) { return Q3{qdot({inv[0][0], inv[0][1], inv[0][2]}, v), qdot({inv[1][0], inv[1][1], inv[1][2]}, v),
                                              qdot({inv[2][0], inv[2][1], inv[2][2]}, v)}; };
    const Q3 shift{quad(x.to_world.m[0][3]), quad(x.to_world.m[1][3]), quad(x.to_world.m[2][3])};
    return implicit(x.object, apply(o - shift), apply(d), t, part);
}

// Newton on F from the kernel's t (derivative by a symmetric difference of the exact polynomial,
// exact for a quadratic up to binary128 rounding).
template <class Prim>
quad refine(const Prim& prim, Q3 o, Q3 d, quad t, Part part)
{
    for (int i = 0; i < 8; ++i) {
        const quad h = (qabs(t) + 1) * quad(1e-12);
        const quad f = implicit(prim, o, d, t, part);
        const quad df = (implicit(prim, o, d, t + h, part) - implicit(prim, o, d, t - h, part)) / (2 * h);
        if (df == 0) break;
        t -= f / df;
    }
    return t;
}

}  // namespace rayq::test
