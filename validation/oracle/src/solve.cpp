// rayq::oracle — the exact solver: every primitive formulated in rationals, its crossings as
// elements of Q(√D), compared exactly. Written from the geometry, not from the kernel.
#include <algorithm>
#include <utility>

#include "exact.hpp"

namespace rayq::oracle::exact {

int sign(const Alg& x, const Q& D)
{
    const int sa = sgn(x.a);
    const int sb = sgn(D) == 0 ? 0 : sgn(x.b);
    if (sb == 0) return sa;
    if (sa == 0 || sa == sb) return sb;
    // Opposite signs: the larger of a² and b²·D decides.
    const int c = cmp(x.a * x.a, x.b * x.b * D);
    return c > 0 ? sa : (c < 0 ? sb : 0);
}

Alg dot(const AV& p, const AV& q, const Q& D)
{
    return mul(p.x, q.x, D) + mul(p.y, q.y, D) + mul(p.z, q.z, D);
}

int compare(const Bound& x, const Bound& y, const Q& D)
{
    if (x.inf != 0 || y.inf != 0) return x.inf == y.inf ? 0 : (x.inf < y.inf ? -1 : 1);
    return compare(x.t, y.t, D);
}

std::string to_string(const Alg& x, const Q& D)
{
    if (sgn(x.b) == 0 || sgn(D) == 0) return x.a.get_str();
    return x.a.get_str() + " + " + x.b.get_str() + "*sqrt(" + D.get_str() + ")";
}

std::optional<AffineQ> inverse(const AffineQ& w)
{
    const auto& m = w.m;
    // Cofactor expansion; the inverse's (i, j) entry is the (j, i) cofactor over the determinant.
    Q cof[3][3];
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) {
            int rows[2], cols[2], nr = 0, nc = 0;
            for (int k = 0; k < 3; ++k) {
                if (k != r) rows[nr++] = k;
                if (k != c) cols[nc++] = k;
            }
            const Q minor = m[rows[0]][cols[0]] * m[rows[1]][cols[1]] - m[rows[0]][cols[1]] * m[rows[1]][cols[0]];
            cof[r][c] = ((r + c) % 2 == 0) ? minor : Q(-minor);
        }
    const Q det = m[0][0] * cof[0][0] + m[0][1] * cof[0][1] + m[0][2] * cof[0][2];
    if (sgn(det) == 0) return std::nullopt;
    AffineQ inv;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) inv.m[i][j] = cof[j][i] / det;
    for (int i = 0; i < 3; ++i) inv.m[i][3] = -(inv.m[i][0] * m[0][3] + inv.m[i][1] * m[1][3] + inv.m[i][2] * m[2][3]);
    return inv;
}

namespace {

V linear(const AffineQ& a, const V& v)
{
    return {a.m[0][0] * v.x + a.m[0][1] * v.y + a.m[0][2] * v.z, a.m[1][0] * v.x + a.m[1][1] * v.y + a.m[1][2] * v.z,
            a.m[2][0] * v.x + a.m[2][1] * v.y + a.m[2][2] * v.z};
}
V apply(const AffineQ& a, const V& p) { return linear(a, p) + V{a.m[0][3], a.m[1][3], a.m[2][3]}; }
AV linear_transposed(const AffineQ& a, const AV& n)
{
    return {n.x * a.m[0][0] + n.y * a.m[1][0] + n.z * a.m[2][0], n.x * a.m[0][1] + n.y * a.m[1][1] + n.z * a.m[2][1],
            n.x * a.m[0][2] + n.y * a.m[1][2] + n.z * a.m[2][2]};
}

// {t : F(t) = A·t² + B·t + C <= 0} as closed intervals in ascending order. A line lying in the
// surface (F ≡ 0) gives nothing, as does a ray touching the surface from inside (a double root
// with A < 0: F <= 0 everywhere, and the set has no boundary).
struct Interval {
    Bound lo, hi;
    bool tangent = false;  // an isolated point: an exact double root touched from outside
};
struct SideSet {
    Q D;  // 0 unless the roots are irrational-capable distinct roots
    std::vector<Interval> intervals;
};

SideSet at_most_zero(const Q& A, const Q& B, const Q& C)
{
    SideSet s;
    s.D = 0;
    const Interval everything{minus_infinity(), plus_infinity(), false};
    const int sa = sgn(A);
    if (sa == 0) {
        if (sgn(B) == 0) {
            if (sgn(C) < 0) s.intervals.push_back(everything);
            return s;
        }
        const Q r = -C / B;
        if (sgn(B) > 0) s.intervals.push_back({minus_infinity(), finite(r)});
        else s.intervals.push_back({finite(r), plus_infinity()});
        return s;
    }
    const Q D = B * B - 4 * A * C;
    const int sd = sgn(D);
    if (sd < 0) {
        if (sa < 0) s.intervals.push_back(everything);
        return s;
    }
    const Q mid = -B / (2 * A);
    if (sd == 0) {
        if (sa > 0) s.intervals.push_back({finite(mid), finite(mid), true});
        else s.intervals.push_back(everything);
        return s;
    }
    const Q half = Q(1) / (2 * abs(A));
    Bound lo, hi;
    if (mpz_perfect_square_p(D.get_num_mpz_t()) && mpz_perfect_square_p(D.get_den_mpz_t())) {
        // Rational roots: keep them in Q (D = 0), so that every later step stays rational.
        mpz_class num, den;
        mpz_sqrt(num.get_mpz_t(), D.get_num_mpz_t());
        mpz_sqrt(den.get_mpz_t(), D.get_den_mpz_t());
        const Q root = Q(num) / Q(den);
        lo = finite(Q(mid - half * root));
        hi = finite(Q(mid + half * root));
    } else {
        s.D = D;
        lo = finite(Alg{mid, -half});
        hi = finite(Alg{mid, half});
    }
    if (sa > 0) s.intervals.push_back({lo, hi});
    else {
        s.intervals.push_back({minus_infinity(), lo});
        s.intervals.push_back({hi, plus_infinity()});
    }
    return s;
}

// Every finite end of the set is a crossing of the surface.
std::vector<Crossing> ends_of(const SideSet& s)
{
    std::vector<Crossing> out;
    for (const Interval& i : s.intervals) {
        if (i.lo.inf == 0) out.push_back({i.lo.t, Part::surface, true, i.tangent});
        if (i.hi.inf == 0) out.push_back({i.hi.t, Part::surface, false, i.tangent});
    }
    return out;
}

// The slab 0 <= (q + t·d)·A <= |A|² (q = o − p0), as a t-interval with the cap at each end.
struct Slab {
    bool empty = false;
    Bound lo, hi;
    Part lo_part = Part::cap0, hi_part = Part::cap1;
};

Slab slab_of(const V& q, const V& d, const V& A)
{
    const Q qa = dot(q, A), da = dot(d, A), aa = dot(A, A);
    Slab s;
    if (sgn(da) == 0) {
        s.empty = !(sgn(qa) >= 0 && cmp(qa, aa) <= 0);
        s.lo = minus_infinity();
        s.hi = plus_infinity();
        return s;
    }
    const Q t0 = -qa / da;         // on the plane through p0
    const Q t1 = (aa - qa) / da;   // on the plane through p1
    if (sgn(da) > 0) {
        s.lo = finite(t0), s.lo_part = Part::cap0;
        s.hi = finite(t1), s.hi_part = Part::cap1;
    } else {
        s.lo = finite(t1), s.lo_part = Part::cap1;
        s.hi = finite(t0), s.hi_part = Part::cap0;
    }
    return s;
}

// Open side: its crossings within the slab (rim included). Closed solid: side-solid ∩ slab, the
// cap winning exact ties unless that end has no cap (an apex).
std::vector<Crossing> axial_crossings(const SideSet& side, const Slab& slab, bool capped, bool cap0, bool cap1)
{
    std::vector<Crossing> out;
    if (slab.empty) return out;
    const Q& D = side.D;
    if (!capped) {
        for (const Crossing& c : ends_of(side))
            if (compare(slab.lo, finite(c.t), D) <= 0 && compare(finite(c.t), slab.hi, D) <= 0) out.push_back(c);
        return out;
    }
    const auto closes = [&](Part p) { return p == Part::cap0 ? cap0 : cap1; };
    for (const Interval& i : side.intervals) {
        const bool cap_in = compare(slab.lo, i.lo, D) >= 0;
        const bool cap_out = compare(slab.hi, i.hi, D) <= 0;
        const Bound enter = cap_in ? slab.lo : i.lo;
        const Bound exit = cap_out ? slab.hi : i.hi;
        if (compare(enter, exit, D) > 0) continue;
        const Part in_part = cap_in && closes(slab.lo_part) ? slab.lo_part : Part::surface;
        const Part out_part = cap_out && closes(slab.hi_part) ? slab.hi_part : Part::surface;
        const bool tangent_in = i.tangent && in_part == Part::surface && compare(enter, i.lo, D) == 0;
        const bool tangent_out = i.tangent && out_part == Part::surface && compare(exit, i.hi, D) == 0;
        if (enter.inf == 0) out.push_back({enter.t, in_part, true, tangent_in});
        if (exit.inf == 0) out.push_back({exit.t, out_part, false, tangent_out});
        break;  // the solid is convex: one interval survives the slab
    }
    return out;
}

// The answer of one shape for one (object-space) ray: crossings, the field, and how to get
// the outward normal at a crossing.
struct Local {
    Q D;
    std::vector<Crossing> crossings;
};

// ---- sphere: |o + t·d − c|² = r² -------------------------------------------------------------
Local crossings_of(const RayQ& ray, const SphereQ& s)
{
    const V x = ray.o - s.c;
    const SideSet side = at_most_zero(dot(ray.d, ray.d), 2 * dot(x, ray.d), dot(x, x) - s.r * s.r);
    return {side.D, ends_of(side)};
}
AV normal_of(const RayQ& ray, const SphereQ& s, const Crossing& c, const Q&)
{
    return point_at(ray.o, ray.d, c.t) - s.c;
}

// ---- flat primitives: one rational t ---------------------------------------------------------
// The line meets the plane through p with normal n at t = (p − o)·n / (d·n); parallel lines
// (including lines in the plane) do not cross.
std::optional<Q> plane_t(const RayQ& ray, const V& p, const V& n)
{
    const Q dn = dot(ray.d, n);
    if (sgn(dn) == 0) return std::nullopt;
    return Q(dot(p - ray.o, n) / dn);
}
V rational_point(const RayQ& ray, const Q& t) { return ray.o + ray.d * t; }

Local flat(const RayQ& ray, const V& n, const std::optional<Q>& t, bool inside)
{
    Local l;
    l.D = 0;
    if (t && inside) l.crossings.push_back({rational(*t), Part::surface, sgn(dot(ray.d, n)) < 0, false});
    return l;
}

Local crossings_of(const RayQ& ray, const PlaneQ& p) { return flat(ray, p.n, plane_t(ray, p.p, p.n), true); }
AV normal_of(const RayQ&, const PlaneQ& p, const Crossing&, const Q&) { return rational(p.n); }

Local crossings_of(const RayQ& ray, const DiskQ& d)
{
    const auto t = plane_t(ray, d.c, d.n);
    bool inside = false;
    if (t) {
        const V off = rational_point(ray, *t) - d.c;
        inside = cmp(dot(off, off), d.r * d.r) <= 0;
    }
    return flat(ray, d.n, t, inside);
}
AV normal_of(const RayQ&, const DiskQ& d, const Crossing&, const Q&) { return rational(d.n); }

// Coordinates (α, β) of the line's point in the plane corner + α·e0 + β·e1.
struct Planar {
    std::optional<Q> t;
    Q alpha, beta;
};
Planar planar(const RayQ& ray, const V& corner, const V& e0, const V& e1)
{
    const V n = cross(e0, e1);
    Planar p;
    p.t = plane_t(ray, corner, n);
    if (!p.t) return p;
    const V w = rational_point(ray, *p.t) - corner;  // = α·e0 + β·e1
    const Q nn = dot(n, n);
    p.alpha = dot(cross(w, e1), n) / nn;
    p.beta = dot(cross(e0, w), n) / nn;
    return p;
}
bool unit_interval(const Q& x) { return sgn(x) >= 0 && cmp(x, 1) <= 0; }

Local crossings_of(const RayQ& ray, const ParallelogramQ& p)
{
    const Planar c = planar(ray, p.corner, p.e0, p.e1);
    return flat(ray, cross(p.e0, p.e1), c.t, c.t && unit_interval(c.alpha) && unit_interval(c.beta));
}
AV normal_of(const RayQ&, const ParallelogramQ& p, const Crossing&, const Q&) { return rational(cross(p.e0, p.e1)); }

Local crossings_of(const RayQ& ray, const TriangleQ& tri)
{
    const V e0 = tri.b - tri.a, e1 = tri.c - tri.a;
    const Planar c = planar(ray, tri.a, e0, e1);
    const bool inside = c.t && sgn(c.alpha) >= 0 && sgn(c.beta) >= 0 && cmp(Q(c.alpha + c.beta), 1) <= 0;
    return flat(ray, cross(e0, e1), c.t, inside);
}
AV normal_of(const RayQ&, const TriangleQ& tri, const Crossing&, const Q&)
{
    return rational(cross(tri.b - tri.a, tri.c - tri.a));
}

// ---- cylinder: |(q + t·d) × A|² = r²|A|², q = o − p0, A = p1 − p0 --------------------------------
Local crossings_of(const RayQ& ray, const CylinderQ& cyl)
{
    const V A = cyl.p1 - cyl.p0, q = ray.o - cyl.p0;
    const V u = cross(q, A), v = cross(ray.d, A);
    const SideSet side = at_most_zero(dot(v, v), 2 * dot(u, v), dot(u, u) - cyl.r * cyl.r * dot(A, A));
    return {side.D, axial_crossings(side, slab_of(q, ray.d, A), cyl.caps, true, true)};
}
AV normal_of(const RayQ& ray, const CylinderQ& cyl, const Crossing& c, const Q& D)
{
    const V A = cyl.p1 - cyl.p0;
    if (c.part == Part::cap0) return rational(-A);
    if (c.part == Part::cap1) return rational(A);
    const AV x = point_at(ray.o, ray.d, c.t) - cyl.p0;
    (void)D;
    return x - A * (dot(x, A) * (Q(1) / dot(A, A)));  // the radial component
}

// ---- cone: |(q + t·d) × A|²·|A|² = (r0·|A|² + (r1 − r0)·(q + t·d)·A)² ----------------------------
Local crossings_of(const RayQ& ray, const ConeQ& cone)
{
    const V A = cone.p1 - cone.p0, q = ray.o - cone.p0;
    const Q aa = dot(A, A), dr = cone.r1 - cone.r0;
    const V u = cross(q, A), v = cross(ray.d, A);
    const Q w = cone.r0 * aa + dr * dot(q, A);  // |A|²·r(h) at t = 0
    const Q s = dr * dot(ray.d, A);             // its rate along the ray
    const SideSet side = at_most_zero(aa * dot(v, v) - s * s, 2 * (aa * dot(u, v) - w * s), aa * dot(u, u) - w * w);
    return {side.D, axial_crossings(side, slab_of(q, ray.d, A), cone.caps, sgn(cone.r0) > 0, sgn(cone.r1) > 0)};
}
AV normal_of(const RayQ& ray, const ConeQ& cone, const Crossing& c, const Q& D)
{
    const V A = cone.p1 - cone.p0;
    if (c.part == Part::cap0) return rational(-A);
    if (c.part == Part::cap1) return rational(A);
    // ½∇ of |X × A|²|A|² − (r0|A|² + (r1 − r0)X·A)²: |A|²(|A|²X − (X·A)A) − (r0|A|² + (r1 − r0)X·A)(r1 − r0)A.
    const Q aa = dot(A, A), dr = cone.r1 - cone.r0;
    const AV x = point_at(ray.o, ray.d, c.t) - cone.p0;
    const Alg xa = dot(x, A);
    const Alg radius_term = xa * dr + cone.r0 * aa;
    (void)D;
    return (x * aa - A * xa) * aa - A * (radius_term * dr);
}

// ---- quadric: F(o + t·d) = F₂(d)·t² + (∇F(o)·d)·t + F(o) ------------------------------------------
Alg eval_linear_gradient(const QuadricQ& f, const AV& p, int axis)
{
    const Q* k = f.k;  // A B C D E F G H I J
    if (axis == 0) return p.x * (2 * k[0]) + p.y * k[3] + p.z * k[4] + k[6];
    if (axis == 1) return p.y * (2 * k[1]) + p.x * k[3] + p.z * k[5] + k[7];
    return p.z * (2 * k[2]) + p.x * k[4] + p.y * k[5] + k[8];
}

bool in_box(const QuadricQ& f, const AV& p, const Q& D)
{
    const Alg* c[3] = {&p.x, &p.y, &p.z};
    for (int i = 0; i < 3; ++i) {
        if (compare(f.lo[i], finite(*c[i]), D) > 0) return false;
        if (compare(finite(*c[i]), f.hi[i], D) > 0) return false;
    }
    return true;
}

Local crossings_of(const RayQ& ray, const QuadricQ& f)
{
    const Q* k = f.k;
    const V& o = ray.o;
    const V& d = ray.d;
    const Q a = k[0] * d.x * d.x + k[1] * d.y * d.y + k[2] * d.z * d.z + k[3] * d.x * d.y + k[4] * d.x * d.z + k[5] * d.y * d.z;
    const V grad{2 * k[0] * o.x + k[3] * o.y + k[4] * o.z + k[6], 2 * k[1] * o.y + k[3] * o.x + k[5] * o.z + k[7],
                 2 * k[2] * o.z + k[4] * o.x + k[5] * o.y + k[8]};
    const Q c = k[0] * o.x * o.x + k[1] * o.y * o.y + k[2] * o.z * o.z + k[3] * o.x * o.y + k[4] * o.x * o.z +
                k[5] * o.y * o.z + k[6] * o.x + k[7] * o.y + k[8] * o.z + k[9];
    const SideSet side = at_most_zero(a, dot(grad, d), c);
    Local l{side.D, {}};
    for (const Crossing& x : ends_of(side))
        if (in_box(f, point_at(o, d, x.t), side.D)) l.crossings.push_back(x);
    return l;
}
AV normal_of(const RayQ& ray, const QuadricQ& f, const Crossing& c, const Q&)
{
    const AV p = point_at(ray.o, ray.d, c.t);
    return {eval_linear_gradient(f, p, 0), eval_linear_gradient(f, p, 1), eval_linear_gradient(f, p, 2)};
}

bool in_window(const RayQ& ray, const Alg& t, const Q& D)
{
    return compare(ray.tmin, finite(t), D) < 0 && compare(finite(t), ray.tmax, D) < 0;
}

}  // namespace

Solution solve(const Problem& problem)
{
    Solution s;
    s.direction = problem.ray.d;
    if (!problem.defined) return s;

    RayQ local = problem.ray;
    std::optional<AffineQ> inv;
    if (problem.to_world) {
        inv = inverse(*problem.to_world);
        if (!inv) return s;  // singular: outside the domain
        local.o = apply(*inv, problem.ray.o);
        local.d = linear(*inv, problem.ray.d);
    }
    s.defined = true;
    std::visit(
        [&](const auto& shape) {
            Local l = crossings_of(local, shape);
            s.D = l.D;
            s.crossings = std::move(l.crossings);
            for (std::size_t i = 0; i < s.crossings.size(); ++i)
                if (in_window(local, s.crossings[i].t, s.D)) {
                    s.first = i;
                    break;
                }
            if (!s.first) return;
            AV n = normal_of(local, shape, s.crossings[*s.first], s.D);
            if (inv) n = linear_transposed(*inv, n);
            s.normal = n;
            s.normal_defined = sign(n.x, s.D) != 0 || sign(n.y, s.D) != 0 || sign(n.z, s.D) != 0;
        },
        problem.shape);
    return s;
}

}  // namespace rayq::oracle::exact
