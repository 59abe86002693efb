// Randomized property tests: every primitive × {float, double} × {fast, stable, accurate} against
// an independent long double reference computed from the same (already rounded to T) inputs.
//
// Per ray, with the reference's first hit at t_ref, incidence cosine cosθ (between the ray and the
// surface normal there), L the problem's length scale (sphere |o − c| + r, plane |p − o|, disk
// |o − c| + r, parallelogram |o − corner| + |e0| + |e1|, triangle |o − a| + |b − a| + |c − a|,
// cylinder |o − p0| + |p1 − p0| + r) and ε = numeric_limits<T>::epsilon():
//   * rays whose hit/miss or part decision is borderline are left out of the comparisons: the
//     reference's margin (the smallest of: relative distance to tangency, to an edge or rim, cosθ
//     of every crossing, and |t|·|d|/L of every crossing, i.e. the origin's distance from the
//     surface) is below kBorderline (fast and stable: 1e-3 double, 1e-2 float; accurate, which
//     decides exactly: 1e-9);
//   * otherwise hit/miss, part and front_face agree with the reference, and for a hit
//       |t − t_ref| <= kT · ε · (L + |t_ref|·|d|) / (|d| · cosθ)
//     (L + |t_ref|·|d| is the length scale, 1/cosθ the condition number of the crossing), the
//     kernel's hit point lies on the surface it names,
//       residual <= kP · ε · (L + |t_ref|·|d| + |p_ref|)
//     (|p_ref| for the rounding of the point's absolute coordinates), the certified bounds hold
//     (|t − t_ref| <= t_error, |point − p_ref| <= point_error per component), and under the
//     accurate policy t is t_ref correctly rounded (|t − t_ref| <= ulp/2);
//   * intersect() and occluded() agree on every ray (checked_intersect).
// Each combination prints one line: the worst relative and ulp error of t over the compared hits;
// k_t, k_p, the smallest kT and kP that would have passed; and the worst |t − t_ref| / t_error.
// The reference agrees with a __float128 build of itself to 0.001 ulp of double (checked once,
// by hand: the worst difference over every compared hit of every combination).
#include "test_support.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <initializer_list>
#include <limits>
#include <random>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace rayq::test::property_test {
namespace {

// The bounds, in the units defined above, per policy: about twice the worst value measured (the
// k_t / k_p columns of the printed lines) over these seeds and 60 other seed sets, float and
// double alike (x86-64, g++ 12 and clang 14, -O2, no FMA). Worst measured k_t / k_p:
//   fast      118 / 101   sphere float: b² − ac cancels for a small, distant quadric, an error
//                         that grows with distance/radius (cylinders: 105 / 91);
//   stable    2.94 / 2.54 triangle float / parallelogram double (quadrics: 1.25 / 1.16);
//   accurate  0.248 / 0.42 plane float / sphere float: t correctly rounded, which by itself
//                         implies k_t <= 0.5.
// The flat primitives run the same arithmetic under fast and stable.
constexpr double kTFast = 250;
constexpr double kTStable = 6;
constexpr double kTAccurate = 0.5;
constexpr double kPFast = 200;
constexpr double kPStable = 5;
constexpr double kPAccurate = 1;

template <class P> constexpr double k_t() { return std::is_same_v<P, fast_policy> ? kTFast : std::is_same_v<P, stable_policy> ? kTStable : kTAccurate; }
template <class P> constexpr double k_p() { return std::is_same_v<P, fast_policy> ? kPFast : std::is_same_v<P, stable_policy> ? kPStable : kPAccurate; }
template <class P> constexpr const char* policy_name() { return std::is_same_v<P, fast_policy> ? "fast" : std::is_same_v<P, stable_policy> ? "stable" : "accurate"; }
// Below this margin a ray is borderline. The accurate policy decides exactly, so for it only the
// reference's own resolution (about 1e-15 relative) limits the comparison.
template <class T, class P>
constexpr double kBorderline = std::is_same_v<P, accurate_policy> ? 1e-9 : std::is_same_v<T, float> ? 1e-2 : 1e-3;

constexpr int kPrimitives = 250;  // per combination
constexpr int kRaysEach = 16;     // per primitive: 4000 rays per combination
constexpr int kMaxFailingRays = 8;

// ---------------------------------------------------------------------------------------------
// Random input. Everything is drawn in double from the engine's raw bits (reproducible across
// standard libraries), then rounded to T: the kernel and the reference see the same numbers. Two
// draws are never operands of one operator (unsequenced): every compiler sees the same rays.

struct Rng {
    std::mt19937_64 eng;
    double u01() { return static_cast<double>(eng() >> 11) * 0x1p-53; }
    double uni(double lo, double hi) { return lo + (hi - lo) * u01(); }
    double log_uni(double lo, double hi) { return lo * std::pow(hi / lo, u01()); }
    bool chance(double p) { return u01() < p; }
    Vec3<double> box(double h) { return {uni(-h, h), uni(-h, h), uni(-h, h)}; }
    Vec3<double> unit()
    {
        const double z = uni(-1, 1), phi = uni(0, 6.283185307179586), s = std::sqrt(1 - z * z);
        return {s * std::cos(phi), s * std::sin(phi), z};
    }
    // A random direction with a log-uniform length.
    Vec3<double> vector(double lo, double hi)
    {
        const double len = log_uni(lo, hi);
        return len * unit();
    }
};

template <class T> Vec3<T> to(const Vec3<double>& v) { return {T(v.x), T(v.y), T(v.z)}; }
template <class T> Vec3<double> dbl(const Vec3<T>& v) { return {double(v.x), double(v.y), double(v.z)}; }

// Two unit vectors perpendicular to n (any length) and to each other.
inline std::pair<Vec3<double>, Vec3<double>> basis(const Vec3<double>& n)
{
    const Vec3<double> nn = normalize(n);
    const Vec3<double> u = normalize(cross(nn, std::abs(nn.x) < 0.9 ? Vec3<double>{1, 0, 0} : Vec3<double>{0, 1, 0}));
    return {u, cross(nn, u)};
}

inline std::string hex(double x)
{
    char buf[40];
    std::snprintf(buf, sizeof buf, "%a", x);
    return buf;
}
template <class T> std::string hex(const Vec3<T>& v) { return "{" + hex(double(v.x)) + ", " + hex(double(v.y)) + ", " + hex(double(v.z)) + "}"; }

// ---------------------------------------------------------------------------------------------
// The long double reference: its own vector type and formulas, nothing from the kernel.

using LD = long double;
struct V {
    LD x, y, z;
};
V operator+(const V& a, const V& b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
V operator-(const V& a, const V& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
V operator*(LD s, const V& a) { return {s * a.x, s * a.y, s * a.z}; }
LD ldot(const V& a, const V& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
V lcross(const V& a, const V& b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
LD llen(const V& a) { return std::sqrt(ldot(a, a)); }
template <class T> V ld(const Vec3<T>& v) { return {LD(v.x), LD(v.y), LD(v.z)}; }

// The last bits of t come from residuals that cancel (the plane distance (p − o)·n, |g|² − r²),
// so those are evaluated in unevaluated sums hi + lo of long doubles (error-free products):
// about twice the long double precision, from the exact inputs. t itself is a long
// double, 2^-11 of a double ulp.
struct X {
    LD hi, lo;
};
X exact(LD a) { return {a, 0}; }
X renorm(LD hi, LD lo)
{
    const LD s = hi + lo;
    return {s, lo - (s - hi)};
}
X operator+(const X& a, const X& b)
{
    const LD s = a.hi + b.hi, bb = s - a.hi;
    return renorm(s, ((a.hi - (s - bb)) + (b.hi - bb)) + (a.lo + b.lo));
}
X operator-(const X& a) { return {-a.hi, -a.lo}; }
X operator-(const X& a, const X& b) { return a + -b; }
// Dekker's product with Veltkamp's split at half the significand (2^32 + 1 for x87's 64 bits):
// exact, and much faster than a software fmal.
X two_product(LD a, LD b)
{
    static const LD split = std::ldexp(LD(1), (std::numeric_limits<LD>::digits + 1) / 2) + 1;
    const LD ca = split * a, cb = split * b;
    const LD ah = ca - (ca - a), al = a - ah, bh = cb - (cb - b), bl = b - bh;
    const LD p = a * b;
    return {p, ((ah * bh - p) + ah * bl + al * bh) + al * bl};
}
X operator*(const X& a, const X& b)
{
    const X p = two_product(a.hi, b.hi);
    return renorm(p.hi, p.lo + (a.hi * b.lo + a.lo * b.hi));
}
LD val(const X& a) { return a.hi + a.lo; }
struct XV {
    X x, y, z;
};
template <class T> XV xv(const Vec3<T>& v) { return {exact(v.x), exact(v.y), exact(v.z)}; }
XV operator+(const XV& a, const XV& b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
XV operator-(const XV& a, const XV& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
XV operator*(const X& s, const XV& a) { return {s * a.x, s * a.y, s * a.z}; }
X xdot(const XV& a, const XV& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
XV xcross(const XV& a, const XV& b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
V val(const XV& a) { return {val(a.x), val(a.y), val(a.z)}; }

struct RefCrossing {
    LD t;
    Part part;
    bool entering;
    LD cos;  // |cos| of the angle between the ray and the surface normal
};

struct Ref {
    LD scale;  // L
    LD speed;  // |d|
    LD margin = std::numeric_limits<LD>::infinity();
    int count = 0;
    RefCrossing cand[2]{};  // the line's crossings, ascending
    bool hit = false;
    RefCrossing first{};    // the first with t > 0

    Ref(LD l, const V& d) : scale(l), speed(llen(d)) {}
    void limit(LD m) { margin = std::min(margin, m); }
    void add(LD t, Part p, bool entering, LD cos) { cand[count++] = {t, p, entering, cos}; }
    Ref& finish()
    {
        for (int i = 0; i < count; ++i) {
            limit(cand[i].cos);
            limit(std::abs(cand[i].t) * speed / scale);
            if (!hit && cand[i].t > 0) {
                hit = true;
                first = cand[i];
            }
        }
        return *this;
    }
};

// Where |f + t·d| = r: the closest approach l = f − (f·d/d·d)·d gives the discriminant
// d·d·(r − |l|)(r + |l|) without cancellation, the q-form gives both roots, and two Newton steps
// on the primitive's residual F(t) (computed in X from the unrounded inputs) polish them.
// f, d are the components normal to the surface's generators (all of them for the sphere, those
// perpendicular to the axis for a cylinder); speed is the ray's full |d|.
struct Roots {
    bool real;
    LD t0, t1;
    LD l;     // |l|, the distance of closest approach
    LD cos;   // |g·d|/(r·speed) at either root: the incidence cosine
};
template <class Residual>
Roots norm_roots(const V& f, const V& d, LD r, LD speed, Residual residual)
{
    const LD a = ldot(d, d), b = ldot(f, d);
    const LD l = llen(f - (b / a) * d);
    Roots out{false, 0, 0, l, 0};
    if (!(l < r)) return out;
    const LD root = std::sqrt(a * (r - l) * (r + l));
    const LD fl = llen(f);
    const LD q = -(b + std::copysign(root, b));
    LD t0 = q / a, t1 = (fl - r) * (fl + r) / q;
    if (t1 < t0) std::swap(t0, t1);
    for (LD* t : {&t0, &t1})
        for (int k = 0; k < 2; ++k) {
            const auto [value, slope] = residual(*t);
            if (slope != 0) *t -= value / slope;
        }
    out.real = true;
    out.t0 = t0;
    out.t1 = t1;
    out.cos = root / (r * speed);  // |g·d| = √(b² − ac) at a root
    return out;
}

// ---------------------------------------------------------------------------------------------
// The primitives: how to draw one, where to aim at it, the reference, the surface residual.

template <class T_>
struct SphereKind {
    using T = T_;
    using Prim = Sphere<T>;
    static constexpr const char* name = "sphere";
    static constexpr bool solid = true;
    static Prim make(Rng& g) { return {to<T>(g.box(5)), T(g.log_uni(0.1, 10))}; }
    static Vec3<double> aim(Rng& g, const Prim& s)
    {
        const double rho = 1.25 * double(s.radius) * g.u01();
        return dbl(s.center) + rho * g.unit();
    }
    static Ref reference(const Ray<T>& ray, const Prim& s)
    {
        const V d = ld(ray.direction), f = ld(ray.origin) - ld(s.center);
        const LD r = s.radius;
        Ref ref(llen(f) + r, d);
        // F(t) = |o + t·d − c|² − r², F' = 2 g·d.
        const Roots k = norm_roots(f, d, r, llen(d), [&](LD t) {
            const XV g = (xv(ray.origin) - xv(s.center)) + exact(t) * xv(ray.direction);
            return std::pair<LD, LD>{val(xdot(g, g) - exact(r) * exact(r)), 2 * ldot(val(g), d)};
        });
        ref.limit(std::abs(r - k.l) / r);  // tangency
        if (k.real) {
            ref.add(k.t0, Part::surface, true, k.cos);
            ref.add(k.t1, Part::surface, false, k.cos);
        }
        return ref.finish();
    }
    static LD residual(const Prim& s, const V& p, Part) { return std::abs(llen(p - ld(s.center)) - LD(s.radius)); }
    static std::string describe(const Prim& s) { return "Sphere{center=" + hex(s.center) + ", radius=" + hex(double(s.radius)) + "}"; }
};

// The flat primitives share the plane crossing t = ((p − o)·n)/(d·n), here in X.
template <class T>
void flat_crossing(Ref& ref, const Ray<T>& ray, const XV& p, const XV& n, bool inside)
{
    const XV o = xv(ray.origin), d = xv(ray.direction);
    const LD den = val(xdot(d, n));
    const LD cos = std::abs(den) / (llen(val(d)) * llen(val(n)));
    ref.limit(cos);
    if (den != 0 && inside) ref.add(val(xdot(p - o, n)) / den, Part::surface, den < 0, cos);
}
inline LD plane_t(const V& o, const V& d, const V& p, const V& n) { return ldot(p - o, n) / ldot(d, n); }
inline LD plane_distance(const V& x, const V& p, const V& n) { return std::abs(ldot(x - p, n)) / llen(n); }

template <class T_>
struct PlaneKind {
    using T = T_;
    using Prim = Plane<T>;
    static constexpr const char* name = "plane";
    static constexpr bool solid = false;
    static Prim make(Rng& g) { return {to<T>(g.box(5)), to<T>(g.vector(0.1, 10))}; }
    static Vec3<double> aim(Rng& g, const Prim& p)
    {
        const auto [u, w] = basis(dbl(p.normal));
        const double a = g.uni(-5, 5), b = g.uni(-5, 5);
        return dbl(p.point) + a * u + b * w;
    }
    static Ref reference(const Ray<T>& ray, const Prim& p)
    {
        const V o = ld(ray.origin), d = ld(ray.direction), pt = ld(p.point);
        Ref ref(llen(pt - o), d);
        flat_crossing(ref, ray, xv(p.point), xv(p.normal), true);
        return ref.finish();
    }
    static LD residual(const Prim& p, const V& x, Part) { return plane_distance(x, ld(p.point), ld(p.normal)); }
    static std::string describe(const Prim& p) { return "Plane{point=" + hex(p.point) + ", normal=" + hex(p.normal) + "}"; }
};

template <class T_>
struct DiskKind {
    using T = T_;
    using Prim = Disk<T>;
    static constexpr const char* name = "disk";
    static constexpr bool solid = false;
    static Prim make(Rng& g) { return {to<T>(g.box(5)), to<T>(g.vector(0.1, 10)), T(g.log_uni(0.1, 10))}; }
    static Vec3<double> aim(Rng& g, const Prim& k)
    {
        const auto [u, w] = basis(dbl(k.normal));
        const double rho = 1.3 * double(k.radius) * std::sqrt(g.u01()), phi = g.uni(0, 6.283185307179586);
        return dbl(k.center) + (rho * std::cos(phi)) * u + (rho * std::sin(phi)) * w;
    }
    static Ref reference(const Ray<T>& ray, const Prim& k)
    {
        const V o = ld(ray.origin), d = ld(ray.direction), c = ld(k.center), n = ld(k.normal);
        const LD r = k.radius;
        Ref ref(llen(o - c) + r, d);
        const LD rho = llen((o - c) + plane_t(o, d, c, n) * d);
        ref.limit(std::abs(r - rho) / r);  // rim
        flat_crossing(ref, ray, xv(k.center), xv(k.normal), rho <= r);
        return ref.finish();
    }
    static LD residual(const Prim& k, const V& x, Part) { return plane_distance(x, ld(k.center), ld(k.normal)); }
    static std::string describe(const Prim& k)
    {
        return "Disk{center=" + hex(k.center) + ", normal=" + hex(k.normal) + ", radius=" + hex(double(k.radius)) + "}";
    }
};

// Two edge vectors of lengths log-uniform in [0.1, 10], at least ~6° apart.
inline std::pair<Vec3<double>, Vec3<double>> edges(Rng& g)
{
    for (;;) {
        const Vec3<double> a = g.unit(), b = g.unit();
        if (length(cross(a, b)) >= 0.1) return {g.log_uni(0.1, 10) * a, g.log_uni(0.1, 10) * b};
    }
}

// The plane corner + α·e0 + β·e1 at the ray's crossing.
struct PlaneCoords {
    LD alpha, beta;
};
inline PlaneCoords plane_coords(const V& o, const V& d, const V& corner, const V& e0, const V& e1)
{
    const V n = lcross(e0, e1);
    const LD nn = ldot(n, n);
    const V g = (o - corner) + plane_t(o, d, corner, n) * d;
    return {ldot(lcross(g, e1), n) / nn, ldot(lcross(e0, g), n) / nn};
}

// The edge margin of a convex region given by constraints s_i >= 0, each s_i a barycentric
// coordinate (the distance to that edge relative to the region's extent across it): inside, the
// smallest slack; outside, the largest violation (the decision flips only when all of them do).
inline LD region_margin(std::initializer_list<LD> s)
{
    LD slack = std::numeric_limits<LD>::infinity(), violation = 0;
    for (const LD x : s) {
        if (x >= 0) slack = std::min(slack, x);
        else violation = std::max(violation, -x);
    }
    return violation > 0 ? violation : slack;
}

template <class T_>
struct ParallelogramKind {
    using T = T_;
    using Prim = Parallelogram<T>;
    static constexpr const char* name = "parallelogram";
    static constexpr bool solid = false;
    static Prim make(Rng& g)
    {
        const auto [e0, e1] = edges(g);
        return {to<T>(g.box(5)), to<T>(e0), to<T>(e1)};
    }
    static Vec3<double> aim(Rng& g, const Prim& p)
    {
        const double a = g.uni(-0.25, 1.25), b = g.uni(-0.25, 1.25);
        return dbl(p.corner) + a * dbl(p.edge0) + b * dbl(p.edge1);
    }
    static Ref reference(const Ray<T>& ray, const Prim& p)
    {
        const V o = ld(ray.origin), d = ld(ray.direction), c = ld(p.corner), e0 = ld(p.edge0), e1 = ld(p.edge1);
        Ref ref(llen(o - c) + llen(e0) + llen(e1), d);
        const PlaneCoords pc = plane_coords(o, d, c, e0, e1);
        ref.limit(region_margin({pc.alpha, 1 - pc.alpha, pc.beta, 1 - pc.beta}));  // edges
        const bool inside = 0 <= pc.alpha && pc.alpha <= 1 && 0 <= pc.beta && pc.beta <= 1;
        flat_crossing(ref, ray, xv(p.corner), xcross(xv(p.edge0), xv(p.edge1)), inside);
        return ref.finish();
    }
    static LD residual(const Prim& p, const V& x, Part) { return plane_distance(x, ld(p.corner), lcross(ld(p.edge0), ld(p.edge1))); }
    static std::string describe(const Prim& p)
    {
        return "Parallelogram{corner=" + hex(p.corner) + ", edge0=" + hex(p.edge0) + ", edge1=" + hex(p.edge1) + "}";
    }
};

template <class T_>
struct TriangleKind {
    using T = T_;
    using Prim = Triangle<T>;
    static constexpr const char* name = "triangle";
    static constexpr bool solid = false;
    static Prim make(Rng& g)
    {
        const auto [e0, e1] = edges(g);
        const Vec3<double> a = g.box(5);
        return {to<T>(a), to<T>(a + e0), to<T>(a + e1)};
    }
    static Vec3<double> aim(Rng& g, const Prim& tri)
    {
        const Vec3<double> a = dbl(tri.a);
        const double s = g.uni(-0.2, 1.0), t = g.uni(-0.2, 1.0);
        return a + s * (dbl(tri.b) - a) + t * (dbl(tri.c) - a);
    }
    static Ref reference(const Ray<T>& ray, const Prim& tri)
    {
        const V o = ld(ray.origin), d = ld(ray.direction), a = ld(tri.a), e0 = ld(tri.b) - a, e1 = ld(tri.c) - a;
        Ref ref(llen(o - a) + llen(e0) + llen(e1), d);
        const PlaneCoords pc = plane_coords(o, d, a, e0, e1);
        const LD gamma = 1 - pc.alpha - pc.beta;
        ref.limit(region_margin({pc.alpha, pc.beta, gamma}));  // edges
        const XV xa = xv(tri.a);
        flat_crossing(ref, ray, xa, xcross(xv(tri.b) - xa, xv(tri.c) - xa), pc.alpha >= 0 && pc.beta >= 0 && gamma >= 0);
        return ref.finish();
    }
    static LD residual(const Prim& tri, const V& x, Part)
    {
        const V a = ld(tri.a);
        return plane_distance(x, a, lcross(ld(tri.b) - a, ld(tri.c) - a));
    }
    static std::string describe(const Prim& tri) { return "Triangle{a=" + hex(tri.a) + ", b=" + hex(tri.b) + ", c=" + hex(tri.c) + "}"; }
};

// Infinite cylinder |(o + t·d − p0)⊥| = r, the axial height z(t) = (o + t·d − p0)·â in [0, H]
// for the side, and the cap planes z = 0, z = H closing the solid for Caps::both.
template <class T_, Caps C>
struct CylinderKind {
    using T = T_;
    using Prim = Cylinder<T>;
    static constexpr const char* name = C == Caps::none ? "cylinder" : "capped_cylinder";
    static constexpr bool solid = true;  // open, but its inside is still reachable
    static Prim make(Rng& g)
    {
        const Vec3<double> c = g.box(5), h = g.vector(0.05, 5);
        return {to<T>(c - h), to<T>(c + h), T(g.log_uni(0.1, 10)), C};
    }
    static Vec3<double> aim(Rng& g, const Prim& cyl)
    {
        const Vec3<double> p0 = dbl(cyl.p0), axis = dbl(cyl.p1) - p0;
        const auto [u, w] = basis(axis);
        const double rho = 1.3 * double(cyl.radius) * std::sqrt(g.u01()), phi = g.uni(0, 6.283185307179586);
        const double s = g.uni(-0.25, 1.25);
        return p0 + s * axis + (rho * std::cos(phi)) * u + (rho * std::sin(phi)) * w;
    }
    static Ref reference(const Ray<T>& ray, const Prim& cyl)
    {
        const V o = ld(ray.origin), d = ld(ray.direction), p0 = ld(cyl.p0), p1 = ld(cyl.p1);
        const LD r = cyl.radius, H = llen(p1 - p0);
        const V ax = (1 / H) * (p1 - p0);
        Ref ref(llen(o - p0) + H + r, d);
        const LD h0 = ldot(p0 - o, ax), h1 = ldot(p1 - o, ax), da = ldot(d, ax);  // z(t) = t·da − h0
        const V fp = (o - p0) + h0 * ax, dp = d - da * ax;                          // ⊥ the axis
        if (ldot(dp, dp) == 0) {  // parallel to the axis: not drawn at random
            ref.limit(0);
            return ref.finish();
        }
        // F(t) = |g × A|² − r²|A|² with g = o + t·d − p0, A = p1 − p0; F' = 2 (g × A)·(d × A).
        const XV xA = xv(cyl.p1) - xv(cyl.p0);
        const X rA2 = exact(r) * exact(r) * xdot(xA, xA);
        const V dxA = lcross(d, val(xA));
        const Roots k = norm_roots(fp, dp, r, llen(d), [&](LD t) {
            const XV gA = xcross((xv(ray.origin) - xv(cyl.p0)) + exact(t) * xv(ray.direction), xA);
            return std::pair<LD, LD>{val(xdot(gA, gA) - rA2), 2 * ldot(val(gA), dxA)};
        });
        ref.limit(std::abs(r - k.l) / r);  // tangency
        const auto rim = [&](LD t) { return std::min(std::abs(t * da - h0), std::abs(h1 - t * da)) / H; };
        if (k.real) ref.limit(std::min(rim(k.t0), rim(k.t1)));
        if constexpr (C == Caps::none) {
            if (k.real) {
                const auto on_side = [&](LD t) { return t * da - h0 >= 0 && h1 - t * da >= 0; };
                if (on_side(k.t0)) ref.add(k.t0, Part::surface, true, k.cos);
                if (on_side(k.t1)) ref.add(k.t1, Part::surface, false, k.cos);
            }
        } else {
            const LD cap_cos = std::abs(da) / llen(d);
            ref.limit(cap_cos);
            // The planes through p0 and p1: t = ((p − o)·A)/(d·A), in X.
            const LD d_A = val(xdot(xv(ray.direction), xA));
            const LD s0 = val(xdot(xv(cyl.p0) - xv(ray.origin), xA)) / d_A;
            const LD s1 = val(xdot(xv(cyl.p1) - xv(ray.origin), xA)) / d_A;
            ref.limit(std::abs(llen(fp + s0 * dp) - r) / r);  // rim, seen from the cap planes
            ref.limit(std::abs(llen(fp + s1 * dp) - r) / r);
            const bool up = da > 0;
            const LD se = up ? s0 : s1, sx = up ? s1 : s0;
            const Part pe = up ? Part::cap0 : Part::cap1, px = up ? Part::cap1 : Part::cap0;
            if (k.real) {
                const LD enter = std::max(k.t0, se), exit = std::min(k.t1, sx);
                if (enter <= exit) {
                    ref.add(enter, se >= k.t0 ? pe : Part::surface, true, se >= k.t0 ? cap_cos : k.cos);
                    ref.add(exit, sx <= k.t1 ? px : Part::surface, false, sx <= k.t1 ? cap_cos : k.cos);
                }
            }
        }
        return ref.finish();
    }
    static LD residual(const Prim& cyl, const V& x, Part part)
    {
        const V p0 = ld(cyl.p0), p1 = ld(cyl.p1), ax = (1 / llen(p1 - p0)) * (p1 - p0);
        if (part == Part::cap0) return std::abs(ldot(x - p0, ax));
        if (part == Part::cap1) return std::abs(ldot(x - p1, ax));
        const V q = x - p0;
        return std::abs(llen(q - ldot(q, ax) * ax) - LD(cyl.radius));
    }
    static std::string describe(const Prim& cyl)
    {
        return std::string("Cylinder{p0=") + hex(cyl.p0) + ", p1=" + hex(cyl.p1) + ", radius=" + hex(double(cyl.radius)) +
               (C == Caps::none ? ", Caps::none}" : ", Caps::both}");
    }
};

const char* part_name(Part p) { return p == Part::surface ? "surface" : p == Part::cap0 ? "cap0" : "cap1"; }

int test_parts()
{
    return ::testing::UnitTest::GetInstance()->current_test_info()->result()->total_part_count();
}

// ---------------------------------------------------------------------------------------------

template <class Kind, class Policy>
void run(std::uint64_t seed)
{
    using T = typename Kind::T;
    constexpr bool accurate = std::is_same_v<Policy, accurate_policy>;
    constexpr double eps = std::numeric_limits<T>::epsilon();
    constexpr double borderline = kBorderline<T, Policy>;
    const char* tname = std::is_same_v<T, float> ? "float" : "double";
    if constexpr (std::numeric_limits<LD>::digits < std::numeric_limits<T>::digits + 8)
        GTEST_SKIP() << "long double is not wider than " << tname << " here: no reference";
    SCOPED_TRACE(std::string("property ") + Kind::name + " " + tname + " " + policy_name<Policy>() + ", mt19937_64 seed " +
                 std::to_string(seed));

    Rng g{std::mt19937_64(seed)};
    int rays = 0, compared = 0, skipped = 0, failing = 0;
    double max_rel = 0, max_kt = 0, max_kp = 0, max_cert = 0;
    std::vector<double> ulps;
    ulps.reserve(static_cast<std::size_t>(kPrimitives * kRaysEach));

    for (int i = 0; i < kPrimitives && failing < kMaxFailingRays; ++i) {
        const typename Kind::Prim prim = Kind::make(g);
        for (int j = 0; j < kRaysEach && failing < kMaxFailingRays; ++j, ++rays) {
            // A fifth of the rays of a solid start near it, about half of those inside.
            const Vec3<double> o = Kind::solid && g.chance(0.2) ? Kind::aim(g, prim) : g.box(10);
            const Vec3<double> aim = Kind::aim(g, prim);
            Vec3<double> dir = g.log_uni(0.01, 100) * normalize(aim - o);
            if (g.chance(0.15)) dir = -dir;  // some rays point away
            const Ray<T> ray{to<T>(o), to<T>(dir)};

            const int before = test_parts();
            const auto hit = checked_intersect(Policy{}, ray, prim);
            const Ref ref = Kind::reference(ray, prim);
            const auto context = [&] {
                std::string s = "ray #" + std::to_string(rays) + " (primitive " + std::to_string(i) + "): " + Kind::describe(prim) +
                                "\n  Ray{origin=" + hex(ray.origin) + ", direction=" + hex(ray.direction) + "}\n  kernel: ";
                s += hit ? "t=" + hex(double(hit->t)) + " part=" + part_name(hit->part) + " front_face=" +
                               std::to_string(hit->front_face) + " t_error=" + hex(double(hit->t_error))
                         : std::string("miss");
                s += "\n  reference: ";
                s += ref.hit ? "t=" + hex(double(ref.first.t)) + " (" + std::to_string(double(ref.first.t)) + ") part=" +
                                   part_name(ref.first.part) + " front_face=" + std::to_string(ref.first.entering)
                             : std::string("miss");
                return s + " margin=" + std::to_string(double(ref.margin));
            };
            if (test_parts() != before) ADD_FAILURE() << "intersect/occluded disagree or the hit is malformed\n" << context();

            if (ref.margin >= borderline) {
                if (hit.has_value() != ref.hit) ADD_FAILURE() << "hit/miss differs from the reference\n" << context();
                if (hit && ref.hit) {
                    const LD t_ref = ref.first.t, speed = ref.speed;
                    const LD t_slack = std::ldexp(std::abs(t_ref), -(std::numeric_limits<T>::digits + 4));  // the reference's error, generously
                    const double err = double(std::abs(LD(hit->t) - t_ref));
                    const double unit_t = eps * double((ref.scale + std::abs(t_ref) * speed) / (speed * ref.first.cos));
                    const V p = ld(hit->point), o_ = ld(ray.origin), d_ = ld(ray.direction), p_ref = o_ + t_ref * d_;
                    const double res = double(Kind::residual(prim, p, hit->part));
                    const double unit_p = eps * double(ref.scale + std::abs(t_ref) * speed + llen(p_ref));
                    const T tr = T(t_ref);
                    const double ulp = double(std::nextafter(std::abs(tr), std::numeric_limits<T>::infinity()) - std::abs(tr));
                    if (!(err <= k_t<Policy>() * unit_t))
                        ADD_FAILURE() << "|t - t_ref| = " << err << " > " << k_t<Policy>() << " eps L/(|d| cos) = " << k_t<Policy>() * unit_t
                                      << "\n" << context();
                    if (accurate && !(err <= 0.5 * ulp + double(t_slack)))
                        ADD_FAILURE() << "accurate: t is not correctly rounded, " << err / ulp << " ulps off\n" << context();
                    if (!(res <= k_p<Policy>() * unit_p))
                        ADD_FAILURE() << "hit point off the surface by " << res << " > " << k_p<Policy>() * unit_p << "\n" << context();
                    if (hit->part != ref.first.part) ADD_FAILURE() << "part differs\n" << context();
                    if (hit->front_face != ref.first.entering) ADD_FAILURE() << "front_face differs\n" << context();
                    // The certified bounds contain the exact values.
                    if (!(err <= double(LD(hit->t_error) + t_slack)))
                        ADD_FAILURE() << "|t - t_ref| = " << err << " exceeds the certified t_error " << hit->t_error << "\n" << context();
                    const LD pe[3] = {hit->point_error.x, hit->point_error.y, hit->point_error.z};
                    const LD pd[3] = {std::abs(p.x - p_ref.x), std::abs(p.y - p_ref.y), std::abs(p.z - p_ref.z)};
                    const LD ds[3] = {d_.x, d_.y, d_.z}, os[3] = {o_.x, o_.y, o_.z};
                    for (int a = 0; a < 3; ++a)
                        if (!(pd[a] <= pe[a] + std::abs(ds[a]) * t_slack + std::ldexp(std::abs(os[a]) + std::abs(t_ref * ds[a]), -60)))
                            ADD_FAILURE() << "point component " << a << " off by " << double(pd[a]) << " > certified point_error "
                                          << double(pe[a]) << "\n" << context();

                    ++compared;
                    max_rel = std::max(max_rel, err / double(std::abs(t_ref)));
                    ulps.push_back(err / ulp);
                    max_kt = std::max(max_kt, err / unit_t);
                    max_kp = std::max(max_kp, res / unit_p);
                    if (hit->t_error > T(0)) max_cert = std::max(max_cert, err / double(hit->t_error));
                }
            } else {
                ++skipped;
            }
            if (test_parts() != before) ++failing;
        }
    }
    if (failing >= kMaxFailingRays) ADD_FAILURE() << "stopped after " << failing << " failing rays";

    double max_ulps = 0, p99 = 0;
    if (!ulps.empty()) {
        max_ulps = *std::max_element(ulps.begin(), ulps.end());
        const auto k = ulps.begin() + static_cast<std::ptrdiff_t>(0.99 * double(ulps.size() - 1));
        std::nth_element(ulps.begin(), k, ulps.end());
        p99 = *k;
    }
    std::printf("property %s %s %s: n=%d hits=%d borderline=%d max_rel=%.2g max_ulps=%.3g p99_ulps=%.3g k_t=%.3g k_p=%.3g "
                "t/t_error=%.2g\n",
                Kind::name, tname, policy_name<Policy>(), rays, compared, skipped, max_rel, max_ulps, p99, max_kt, max_kp, max_cert);
    std::fflush(stdout);
    // The draw aims at the primitive: a good fraction hits and few rays are borderline.
    EXPECT_GE(compared, rays / 5);
    EXPECT_LE(skipped, rays / 10);
}

template <class C>
class PropertyTest : public ::testing::Test {};
TYPED_TEST_SUITE(PropertyTest, AllConfigs, ConfigNames);

// One seed per (primitive, T), shared by the three policies so that they see the same rays.
template <class T> constexpr std::uint64_t seed(std::uint64_t base) { return std::is_same_v<T, float> ? base : base + 1; }

TYPED_TEST(PropertyTest, Sphere) { run<SphereKind<typename TypeParam::T>, typename TypeParam::Policy>(seed<typename TypeParam::T>(0x5EED0100)); }
TYPED_TEST(PropertyTest, Plane) { run<PlaneKind<typename TypeParam::T>, typename TypeParam::Policy>(seed<typename TypeParam::T>(0x5EED0200)); }
TYPED_TEST(PropertyTest, Disk) { run<DiskKind<typename TypeParam::T>, typename TypeParam::Policy>(seed<typename TypeParam::T>(0x5EED0300)); }
TYPED_TEST(PropertyTest, Parallelogram)
{
    run<ParallelogramKind<typename TypeParam::T>, typename TypeParam::Policy>(seed<typename TypeParam::T>(0x5EED0400));
}
TYPED_TEST(PropertyTest, Triangle) { run<TriangleKind<typename TypeParam::T>, typename TypeParam::Policy>(seed<typename TypeParam::T>(0x5EED0500)); }
TYPED_TEST(PropertyTest, OpenCylinder)
{
    run<CylinderKind<typename TypeParam::T, Caps::none>, typename TypeParam::Policy>(seed<typename TypeParam::T>(0x5EED0600));
}
TYPED_TEST(PropertyTest, CappedCylinder)
{
    run<CylinderKind<typename TypeParam::T, Caps::both>, typename TypeParam::Policy>(seed<typename TypeParam::T>(0x5EED0700));
}

}  // namespace
}  // namespace rayq::test::property_test
