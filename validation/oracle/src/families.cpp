// rayq::oracle — the generated families of issue 4. Geometry is built in long double from a
// counter-based random stream (SplitMix64 of seed, primitive, family, index), then rounded to
// the case's number type; the oracle, not the construction, says what the rounded case does.
// Builds inputs only: nothing here calls the kernel (Transformed's to_object is the oracle's
// correctly rounded exact inverse).
#include <rayq/oracle/fixtures.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <type_traits>
#include <limits>
#include <stdexcept>

namespace rayq::oracle {

namespace {

using LD = long double;
constexpr LD pi = 3.141592653589793238462643383279502884L;
constexpr LD ld_inf = std::numeric_limits<LD>::infinity();

// ---- long double vectors -----------------------------------------------------------------------
struct L3 {
    LD x = 0, y = 0, z = 0;
};
L3 operator+(const L3& a, const L3& b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
L3 operator-(const L3& a, const L3& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
L3 operator-(const L3& a) { return {-a.x, -a.y, -a.z}; }
L3 operator*(const L3& a, LD s) { return {a.x * s, a.y * s, a.z * s}; }
LD dot(const L3& a, const L3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
L3 cross(const L3& a, const L3& b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
LD norm(const L3& a) { return std::sqrt(dot(a, a)); }
L3 unit(const L3& a) { return a * (1 / norm(a)); }

// ---- the random stream -------------------------------------------------------------------------
std::uint64_t splitmix(std::uint64_t& s)
{
    std::uint64_t z = (s += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}
std::uint64_t fnv(const std::string& s, std::uint64_t h = 1469598103934665603ull)
{
    for (unsigned char c : s) h = (h ^ c) * 1099511628211ull;
    return h;
}

// Every draw is its own statement or braced-list element: C++ leaves the order of function
// arguments and of operator operands unspecified, and the fixtures must not depend on the compiler.
// (Where a draw order had to be picked, it is the one g++ used, so the checked-in fixtures stand.)
struct Rng {
    std::uint64_t state;
    LD uniform() { return static_cast<LD>(splitmix(state) >> 11) * 0x1p-53L; }  // [0, 1)
    LD uniform(LD a, LD b) { return a + (b - a) * uniform(); }
    LD log_uniform(LD a, LD b) { return a * std::pow(b / a, uniform()); }
    bool coin() { return (splitmix(state) >> 63) != 0; }
    int below(int n) { return static_cast<int>(splitmix(state) % static_cast<std::uint64_t>(n)); }
    L3 unit_vector()
    {
        for (;;) {
            const L3 v{uniform(-1, 1), uniform(-1, 1), uniform(-1, 1)};
            const LD n = dot(v, v);
            if (n > 1e-4L && n <= 1) return v * (1 / std::sqrt(n));
        }
    }
    L3 in_ball(LD radius)
    {
        for (;;) {
            const L3 v{uniform(-1, 1), uniform(-1, 1), uniform(-1, 1)};
            if (dot(v, v) <= 1) return v * radius;
        }
    }
    L3 perpendicular(const L3& n)  // a random unit vector ⊥ n
    {
        for (;;) {
            const L3 c = cross(n, unit_vector());
            if (norm(c) > 1e-3L * norm(n)) return unit(c);
        }
    }
    // Direction lengths vary: rays need not be unit.
    LD length() { return log_uniform(0.25L, 4.0L); }
};

// ---- the family of a case ------------------------------------------------------------------------
struct Spec {
    std::string cls;   // generic, grazing, parallel, rim, axial, apex, far, translated, inside, surface, clip
    int side = 0;      // +1 "in" (closer / inside), −1 "out", 0 none
    int k = 0;         // 10^-k closeness
    int e = 0;         // 10^e distance
    bool exact = false;  // apex.exact
};

Spec parse_spec(const std::string& family)
{
    Spec s;
    std::size_t start = 0;
    bool first = true;
    while (start <= family.size()) {
        const std::size_t dot = family.find('.', start);
        const std::string part = family.substr(start, dot == std::string::npos ? std::string::npos : dot - start);
        if (first) s.cls = part, first = false;
        else if (part == "in") s.side = +1;
        else if (part == "out") s.side = -1;
        else if (part == "exact") s.exact = true;
        else if (part.size() > 1 && part[0] == 'k') s.k = std::stoi(part.substr(1));
        else if (part.size() > 1 && part[0] == 'e') s.e = std::stoi(part.substr(1));
        else throw std::invalid_argument("rayq::oracle: unknown family part '" + part + "' in " + family);
        if (dot == std::string::npos) break;
        start = dot + 1;
    }
    return s;
}

LD closeness(const Spec& s) { return std::pow(10.0L, -static_cast<LD>(s.k)); }
LD ratio_in_out(const Spec& s) { return 1 - static_cast<LD>(s.side) * closeness(s); }  // in: 1 − 10^-k, out: 1 + 10^-k

// ---- shapes in long double -------------------------------------------------------------------------
struct RayL {
    L3 o, d;
    LD tmin = 0, tmax = ld_inf;
};
struct SphereL { L3 c; LD r; };
struct PlaneL { L3 p, n; };
struct DiskL { L3 c, n; LD r; };
struct ParallelogramL { L3 corner, e0, e1; };
struct TriangleL { L3 a, b, c; };
struct CylinderL { L3 p0, p1; LD r; bool caps; };
struct ConeL { L3 p0; LD r0; L3 p1; LD r1; bool caps; };
// (p − c)ᵀ·M·(p − c) + g·(p − c) + k with M = Σ w_i e_i e_iᵀ, g = gz·e_2, clipped by a world box.
struct QuadricL {
    L3 c, e[3];
    LD w[3], gz, k;
    L3 lo{-ld_inf, -ld_inf, -ld_inf}, hi{ld_inf, ld_inf, ld_inf};

    LD value(const L3& p) const
    {
        const L3 q = p - c;
        LD f = k + gz * dot(e[2], q);
        for (int i = 0; i < 3; ++i) f += w[i] * dot(e[i], q) * dot(e[i], q);
        return f;
    }
    L3 gradient(const L3& p) const
    {
        const L3 q = p - c;
        L3 g = e[2] * gz;
        for (int i = 0; i < 3; ++i) g = g + e[i] * (2 * w[i] * dot(e[i], q));
        return g;
    }
};

void shift(SphereL& s, const L3& v) { s.c = s.c + v; }
void shift(PlaneL& s, const L3& v) { s.p = s.p + v; }
void shift(DiskL& s, const L3& v) { s.c = s.c + v; }
void shift(ParallelogramL& s, const L3& v) { s.corner = s.corner + v; }
void shift(TriangleL& s, const L3& v) { s.a = s.a + v, s.b = s.b + v, s.c = s.c + v; }
void shift(CylinderL& s, const L3& v) { s.p0 = s.p0 + v, s.p1 = s.p1 + v; }
void shift(ConeL& s, const L3& v) { s.p0 = s.p0 + v, s.p1 = s.p1 + v; }
void shift(QuadricL& s, const L3& v)
{
    s.c = s.c + v;
    s.lo = s.lo + v;  // ±inf stays ±inf
    s.hi = s.hi + v;
}

void frame(Rng& g, L3 e[3])
{
    e[2] = g.unit_vector();
    e[0] = g.perpendicular(e[2]);
    e[1] = cross(e[2], e[0]);
}

// A ray through `target` along a random direction, starting `dist` before it.
RayL aim(Rng& g, const L3& target, const L3& dir_unit, LD dist)
{
    const LD len = g.length();
    return {target - dir_unit * dist, dir_unit * len, 0, ld_inf};
}

// A direction making an angle of at most max_angle with `axis`.
L3 cone_direction(Rng& g, const L3& axis, LD max_angle)
{
    const LD a = g.uniform(0, max_angle);
    return unit(axis * std::cos(a) + g.perpendicular(axis) * std::sin(a));
}

// ---- rounding ------------------------------------------------------------------------------------
template <class T>
Vec3<T> r3(const L3& v) { return {static_cast<T>(v.x), static_cast<T>(v.y), static_cast<T>(v.z)}; }
template <class T>
Ray<T> round_ray(const RayL& r)
{
    return {r3<T>(r.o), r3<T>(r.d), static_cast<T>(r.tmin), static_cast<T>(r.tmax)};
}
template <class T> Sphere<T> round_shape(const SphereL& s) { return {r3<T>(s.c), static_cast<T>(s.r)}; }
template <class T> Plane<T> round_shape(const PlaneL& s) { return {r3<T>(s.p), r3<T>(s.n)}; }
template <class T> Disk<T> round_shape(const DiskL& s) { return {r3<T>(s.c), r3<T>(s.n), static_cast<T>(s.r)}; }
template <class T> Parallelogram<T> round_shape(const ParallelogramL& s) { return {r3<T>(s.corner), r3<T>(s.e0), r3<T>(s.e1)}; }
template <class T> Triangle<T> round_shape(const TriangleL& s) { return {r3<T>(s.a), r3<T>(s.b), r3<T>(s.c)}; }
template <class T> Cylinder<T> round_shape(const CylinderL& s)
{
    return {r3<T>(s.p0), r3<T>(s.p1), static_cast<T>(s.r), s.caps ? Caps::both : Caps::none};
}
template <class T> Cone<T> round_shape(const ConeL& s)
{
    return {r3<T>(s.p0), static_cast<T>(s.r0), r3<T>(s.p1), static_cast<T>(s.r1), s.caps ? Caps::both : Caps::none};
}
template <class T> Quadric<T> round_shape(const QuadricL& s)
{
    // Expand (p − c)ᵀM(p − c) + g·(p − c) + k into the ten coefficients.
    LD m[3][3] = {};
    for (int i = 0; i < 3; ++i) {
        const LD ei[3] = {s.e[i].x, s.e[i].y, s.e[i].z};
        for (int r = 0; r < 3; ++r)
            for (int c = 0; c < 3; ++c) m[r][c] += s.w[i] * ei[r] * ei[c];
    }
    const L3 g = s.e[2] * s.gz;
    const LD c[3] = {s.c.x, s.c.y, s.c.z};
    LD mc[3];
    for (int r = 0; r < 3; ++r) mc[r] = m[r][0] * c[0] + m[r][1] * c[1] + m[r][2] * c[2];
    const L3 lin = g - L3{mc[0], mc[1], mc[2]} * 2;
    const LD j = c[0] * mc[0] + c[1] * mc[1] + c[2] * mc[2] - dot(g, s.c) + s.k;
    const auto t = [](LD x) { return static_cast<T>(x); };
    Quadric<T> q{t(m[0][0]), t(m[1][1]), t(m[2][2]), t(2 * m[0][1]), t(2 * m[0][2]), t(2 * m[1][2]),
                 t(lin.x), t(lin.y), t(lin.z), t(j), {r3<T>(s.lo), r3<T>(s.hi)}};
    return q;
}

template <class T, class Shape>
Fixture fixture(const std::string& family, const RayL& ray, const Shape& shape)
{
    using Prim = decltype(round_shape<T>(shape));
    return {family, AnyInput(Input<Prim>{round_ray<T>(ray), round_shape<T>(shape)})};
}

// Moves a rounded origin by a few ulps per coordinate (the "surface" family).
template <class T>
Vec3<T> jitter(Rng& g, Vec3<T> v)
{
    T* c[3] = {&v.x, &v.y, &v.z};
    for (T* x : c) {
        const int steps = g.below(7) - 3;
        for (int i = 0; i < std::abs(steps); ++i)
            *x = std::nextafter(*x, steps > 0 ? std::numeric_limits<T>::infinity() : -std::numeric_limits<T>::infinity());
    }
    return v;
}

// ---- random shapes -------------------------------------------------------------------------------
SphereL random_sphere(Rng& g) { return {g.in_ball(10), g.log_uniform(0.1L, 10)}; }
CylinderL random_cylinder(Rng& g)
{
    const L3 c = g.in_ball(10), a = g.unit_vector();
    const LD r = g.log_uniform(0.1L, 10), h = r * g.uniform(0.5L, 5);
    return {c - a * (h / 2), c + a * (h / 2), r, g.coin()};
}
ConeL random_cone(Rng& g, bool apex)
{
    const L3 c = g.in_ball(10), a = g.unit_vector();
    const LD r1 = g.log_uniform(0.1L, 10), h = r1 * g.uniform(0.5L, 5);
    const LD r0 = apex ? 0 : r1 * g.uniform(0.1L, 0.9L);
    if (g.coin() || apex) return {c - a * (h / 2), r0, c + a * (h / 2), r1, g.coin()};
    return {c - a * (h / 2), r1, c + a * (h / 2), r0, g.coin()};  // the narrow end at p1
}
QuadricL random_quadric(Rng& g, int kind)
{
    QuadricL q;
    q.c = g.in_ball(10);
    frame(g, q.e);
    const LD s = g.log_uniform(0.2L, 5);
    const LD a = s * g.uniform(0.5L, 2), b = s * g.uniform(0.5L, 2), c = s * g.uniform(0.5L, 2);
    q.w[0] = 1 / (a * a), q.w[1] = 1 / (b * b), q.gz = 0;
    switch (kind) {
    case 0: q.w[2] = 1 / (c * c), q.k = -1; break;   // ellipsoid
    case 1: q.w[2] = -1 / (c * c), q.k = -1; break;  // hyperboloid of one sheet
    case 2: q.w[2] = -1 / (c * c), q.k = 1; break;   // of two sheets (inside: within the bowls)
    case 3: q.w[2] = 0, q.gz = -1 / c, q.k = 0; break;  // elliptic paraboloid
    default: q.w[2] = -1 / (c * c), q.k = 0; break;  // elliptic cone
    }
    if (kind != 0 || g.coin()) {  // unbounded kinds always clipped; ellipsoids sometimes
        const LD half = s * g.uniform(1, 3);
        q.lo = q.c - L3{half, half, half} * g.uniform(0.5L, 1);
        q.hi = q.c + L3{half, half, half} * g.uniform(0.5L, 1);
    }
    return q;
}
PlaneL random_plane(Rng& g)
{
    const L3 p = g.in_ball(10);
    const LD scale = g.log_uniform(0.5L, 2);
    const L3 n = g.unit_vector();
    return {p, n * scale};
}
DiskL random_disk(Rng& g)
{
    const L3 c = g.in_ball(10);
    const LD scale = g.log_uniform(0.5L, 2);
    const L3 n = g.unit_vector();
    const LD r = g.log_uniform(0.1L, 10);
    return {c, n * scale, r};
}
ParallelogramL random_parallelogram(Rng& g)
{
    const LD s = g.log_uniform(0.1L, 10);
    const L3 n = g.unit_vector();
    const LD len0 = s * g.uniform(0.5L, 2);
    const L3 e0 = g.perpendicular(n) * len0;
    const LD len1 = s * g.uniform(0.5L, 2);
    const LD skew = g.uniform(-0.5L, 0.5L);
    const L3 e1 = unit(cross(n, e0) + e0 * (1 / norm(e0)) * skew) * len1;
    return {g.in_ball(10), e0, e1};
}
TriangleL random_triangle(Rng& g)
{
    const ParallelogramL p = random_parallelogram(g);
    return {p.corner, p.corner + p.e0, p.corner + p.e1};
}

LD size_of(const SphereL& s) { return s.r; }
LD size_of(const CylinderL& s) { return std::max(s.r, norm(s.p1 - s.p0)); }
LD size_of(const ConeL& s) { return std::max({s.r0, s.r1, norm(s.p1 - s.p0)}); }
LD size_of(const QuadricL& q) { return 1 / std::sqrt(std::max({std::fabs(q.w[0]), std::fabs(q.w[1]), LD(1e-30L)})); }
LD size_of(const PlaneL&) { return 1; }
LD size_of(const DiskL& d) { return d.r; }
LD size_of(const ParallelogramL& p) { return std::max(norm(p.e0), norm(p.e1)); }
LD size_of(const TriangleL& t) { return std::max(norm(t.b - t.a), norm(t.c - t.a)); }
L3 center_of(const SphereL& s) { return s.c; }
L3 center_of(const CylinderL& s) { return (s.p0 + s.p1) * 0.5L; }
L3 center_of(const ConeL& s) { return (s.p0 + s.p1) * 0.5L; }
L3 center_of(const QuadricL& q) { return q.c; }
L3 center_of(const PlaneL& p) { return p.p; }
L3 center_of(const DiskL& d) { return d.c; }
L3 center_of(const ParallelogramL& p) { return p.corner + (p.e0 + p.e1) * 0.5L; }
L3 center_of(const TriangleL& t) { return (t.a + t.b + t.c) * (1 / 3.0L); }

// A generic ray: through a random point around the shape, from a few sizes away; one in four
// gets a finite tmax.
template <class Shape>
RayL generic_ray(Rng& g, const Shape& s)
{
    const LD size = size_of(s);
    const L3 dir = g.unit_vector();
    const LD dist = size * g.uniform(2, 10);
    RayL r = aim(g, center_of(s) + g.in_ball(1.5L * size), dir, dist);
    if (g.below(4) == 0) r.tmax = dist / norm(r.d) * g.uniform(0.5L, 2);
    return r;
}

// A tiny shape seen from far: the ray aims inside (in) or just outside (out) its bounding size.
template <class Shape>
RayL far_ray(Rng& g, const Shape& s, const Spec& spec)
{
    const LD size = size_of(s);
    const LD reach = size * (g.coin() ? g.uniform(0, 0.5L) : g.uniform(1.2L, 2));
    const L3 dir = g.unit_vector();
    const L3 offset = g.in_ball(1);
    return aim(g, center_of(s) + offset * reach, dir, size * std::pow(10.0L, static_cast<LD>(spec.e)));
}

L3 translation_of(Rng& g, const Spec& spec) { return g.unit_vector() * std::pow(10.0L, static_cast<LD>(spec.e)); }

// ---- per primitive ---------------------------------------------------------------------------------
template <class T>
Fixture sphere_case(Rng& g, const std::string& family, const Spec& spec)
{
    SphereL s = random_sphere(g);
    RayL r;
    if (spec.cls == "generic" || spec.cls == "translated") r = generic_ray(g, s);
    else if (spec.cls == "grazing") {
        const L3 d = g.unit_vector(), e = g.perpendicular(d);
        r = aim(g, s.c + e * (s.r * ratio_in_out(spec)), d, s.r * g.uniform(1.5L, 5));
    } else if (spec.cls == "far") {
        r = far_ray(g, s, spec);
    } else if (spec.cls == "inside") {
        const L3 o = s.c + g.in_ball(0.9L * s.r);
        const LD len = g.length();
        const L3 d = g.unit_vector();
        r = {o, d * len, 0, ld_inf};
    } else if (spec.cls == "surface") {
        const L3 n = g.unit_vector();
        const L3 dir = cone_direction(g, n * static_cast<LD>(spec.side < 0 ? 1 : -1), pi / 3);
        RayL ray{s.c + n * s.r, dir * g.length(), 0, ld_inf};
        Fixture f = fixture<T>(family, ray, s);
        auto& in = std::get<Input<Sphere<T>>>(f.input);
        in.ray.origin = jitter(g, in.ray.origin);
        return f;
    } else throw std::invalid_argument("rayq::oracle: no family " + family + " for sphere");
    if (spec.cls == "translated") {
        const L3 v = translation_of(g, spec);
        shift(s, v);
        r.o = r.o + v;
    }
    return fixture<T>(family, r, s);
}

// A flat shape's plane: a point and unit normal.
struct FlatFrame {
    L3 p, n;
};
FlatFrame flat_frame(const PlaneL& s) { return {s.p, unit(s.n)}; }
FlatFrame flat_frame(const DiskL& s) { return {s.c, unit(s.n)}; }
FlatFrame flat_frame(const ParallelogramL& s) { return {s.corner, unit(cross(s.e0, s.e1))}; }
FlatFrame flat_frame(const TriangleL& s) { return {s.a, unit(cross(s.b - s.a, s.c - s.a))}; }

// A point on (in) or just off (out) a flat shape's boundary.
L3 rim_point(Rng& g, const PlaneL& s, const Spec&)
{
    const LD dist = g.uniform(0, 2);
    return s.p + g.perpendicular(s.n) * dist;
}
L3 rim_point(Rng& g, const DiskL& s, const Spec& spec) { return s.c + g.perpendicular(s.n) * (s.r * ratio_in_out(spec)); }
L3 rim_point(Rng& g, const ParallelogramL& s, const Spec& spec)
{
    const LD eps = static_cast<LD>(spec.side) * closeness(spec);
    const LD along = g.uniform(0.1L, 0.9L);
    LD a = along, b = along;
    switch (g.below(4)) {
    case 0: b = eps; break;      // β = 0 edge
    case 1: b = 1 - eps; break;  // β = 1 edge
    case 2: a = eps; break;
    default: a = 1 - eps; break;
    }
    if (g.below(8) == 0) a = g.coin() ? eps : 1 - eps, b = g.coin() ? eps : 1 - eps;  // a corner
    return s.corner + s.e0 * a + s.e1 * b;
}
L3 rim_point(Rng& g, const TriangleL& s, const Spec& spec)
{
    const LD eps = static_cast<LD>(spec.side) * closeness(spec);
    const LD lambda = g.uniform(0.1L, 0.9L);
    LD a, b;
    switch (g.below(3)) {
    case 0: a = lambda, b = eps; break;                                // edge ab (β = 0)
    case 1: a = eps, b = lambda; break;                                // edge ac (α = 0)
    default: a = lambda * (1 - eps), b = (1 - lambda) * (1 - eps); break;  // edge bc (α + β = 1)
    }
    if (g.below(8) == 0) a = eps, b = eps;  // the corner a
    return s.a + (s.b - s.a) * a + (s.c - s.a) * b;
}
// A point well inside (or, for misses, outside) a flat shape.
L3 inner_point(Rng& g, const PlaneL& s)
{
    const LD dist = g.uniform(0, 2);
    return s.p + g.perpendicular(s.n) * dist;
}
L3 inner_point(Rng& g, const DiskL& s)
{
    const LD dist = s.r * g.uniform(0, 0.9L);
    return s.c + g.perpendicular(s.n) * dist;
}
L3 inner_point(Rng& g, const ParallelogramL& s)
{
    const LD b = g.uniform(0.1L, 0.9L);
    const LD a = g.uniform(0.1L, 0.9L);
    return s.corner + s.e0 * a + s.e1 * b;
}
L3 inner_point(Rng& g, const TriangleL& s)
{
    const LD a = g.uniform(0.05L, 0.9L), b = g.uniform(0.05L, 0.95L - a);
    return s.a + (s.b - s.a) * a + (s.c - s.a) * b;
}

template <class T, class Shape>
Fixture flat_case(Rng& g, const std::string& family, const Spec& spec, Shape s)
{
    const FlatFrame f = flat_frame(s);
    const LD size = size_of(s);
    RayL r;
    if (spec.cls == "generic" || spec.cls == "translated") r = generic_ray(g, s);
    else if (spec.cls == "parallel") {
        // |d̂·n̂| = 10^-k: the ray skims the plane and lands near a point inside (or outside).
        const LD eps = closeness(spec) * (g.coin() ? 1 : -1);
        const L3 along = g.perpendicular(f.n);
        const L3 dir = unit(along * std::sqrt(1 - eps * eps) + f.n * eps);
        const L3 target = g.coin() ? inner_point(g, s) : center_of(s) + along * (size * g.uniform(1.5L, 3));
        r = aim(g, target, dir, size * g.uniform(0.5L, 2));
    } else if (spec.cls == "rim") {
        const LD dist = size * g.uniform(1, 5);
        const bool up = g.coin();
        const L3 dir = cone_direction(g, up ? f.n : -f.n, pi / 3);
        r = aim(g, rim_point(g, s, spec), dir, dist);
    } else if (spec.cls == "far") {
        r = far_ray(g, s, spec);
    } else if (spec.cls == "surface") {
        const L3 dir = cone_direction(g, f.n * static_cast<LD>(spec.side < 0 ? 1 : -1), pi / 3);
        Fixture fx = fixture<T>(family, RayL{inner_point(g, s), dir * g.length(), 0, ld_inf}, s);
        auto& in = std::get<Input<decltype(round_shape<T>(s))>>(fx.input);
        in.ray.origin = jitter(g, in.ray.origin);
        return fx;
    } else throw std::invalid_argument("rayq::oracle: no family " + family + " for a flat primitive");
    if (spec.cls == "translated") {
        const L3 v = translation_of(g, spec);
        shift(s, v);
        r.o = r.o + v;
    }
    return fixture<T>(family, r, s);
}

// Axial solids: axis unit, length, radius at a height fraction.
struct Axial {
    L3 p0, a;  // a: unit axis
    LD h, r0, r1;
    LD radius(LD s) const { return r0 + (r1 - r0) * s; }
    L3 at(LD s) const { return p0 + a * (h * s); }
};
Axial axial_of(const CylinderL& c) { return {c.p0, unit(c.p1 - c.p0), norm(c.p1 - c.p0), c.r, c.r}; }
Axial axial_of(const ConeL& c) { return {c.p0, unit(c.p1 - c.p0), norm(c.p1 - c.p0), c.r0, c.r1}; }

// Side grazing: a line in the tangent plane at a side point, moved off it by ∓10^-k of the radius.
RayL side_grazing(Rng& g, const Axial& ax, const Spec& spec)
{
    const LD s = g.uniform(0.3L, 0.7L);
    const L3 e = g.perpendicular(ax.a);
    const LD r = ax.radius(s);
    const L3 p = ax.at(s) + e * r;
    const L3 n = unit(e - ax.a * ((ax.r1 - ax.r0) / ax.h));       // outward normal
    const L3 gen = unit(ax.a * ax.h + e * (ax.r1 - ax.r0));        // the generator through p
    const L3 w = unit(cross(n, gen));                             // tangent, across the generator
    const LD beta = g.uniform(-pi / 8, pi / 8);
    const L3 dir = unit(w * std::cos(beta) + gen * std::sin(beta));
    const L3 target = p - n * (static_cast<LD>(spec.side) * closeness(spec) * r);
    const LD dist = r * g.uniform(1.5L, 5);
    return aim(g, target, g.coin() ? dir : -dir, dist);
}

// Through a cap plane at (1 ∓ 10^-k) of its radius, heading into the slab.
RayL cap_rim(Rng& g, const Axial& ax, bool at_p1, const Spec& spec)
{
    const L3 e = g.perpendicular(ax.a);
    const LD r = at_p1 ? ax.r1 : ax.r0;
    const L3 target = ax.at(at_p1 ? 1 : 0) + e * (r * ratio_in_out(spec));
    const L3 inward = at_p1 ? -ax.a : ax.a;
    const LD dist = std::max(r, ax.h) * g.uniform(1, 4);
    return aim(g, target, cone_direction(g, inward, pi / 3), dist);
}

template <class T, class Shape>
Fixture axial_case(Rng& g, const std::string& family, const Spec& spec, Shape s)
{
    RayL r;
    const LD size = size_of(s);
    if constexpr (std::is_same_v<Shape, ConeL>) {
        if (spec.cls == "apex") {
            s = random_cone(g, true);  // r0 = 0: p0 is the apex
            const Axial ax = axial_of(s);
            const LD opening = ax.r1 / ax.h;  // tan of the half-angle
            if (spec.exact) {
                // Small dyadic numbers throughout, so the rounded line passes exactly through the apex.
                const L3 p0{static_cast<LD>(g.below(64) - 32) / 8, static_cast<LD>(g.below(64) - 32) / 8,
                            static_cast<LD>(g.below(64) - 32) / 8};
                const L3 axis{static_cast<LD>(g.below(5) - 2), static_cast<LD>(g.below(5) - 2), static_cast<LD>(g.below(3) + 1)};
                s = {p0, 0, p0 + axis, static_cast<LD>(g.below(8) + 1) / 4, g.coin()};
                const L3 d{static_cast<LD>(g.below(9) - 4), static_cast<LD>(g.below(9) - 4), static_cast<LD>(g.below(9) - 4)};
                const L3 dir = dot(d, d) == 0 ? L3{1, 0, 0} : d;
                return fixture<T>(family, RayL{p0 - dir * static_cast<LD>(g.below(4) + 1), dir, 0, ld_inf}, s);
            }
            const LD tilt = spec.side > 0 ? g.uniform(0, 0.8L) * opening : g.uniform(1.5L, 4) * opening;
            const L3 dir = unit(ax.a + g.perpendicular(ax.a) * tilt);
            const L3 miss = g.perpendicular(dir) * (closeness(spec) * ax.r1);
            const LD dist = ax.h * g.uniform(1, 3);
            r = aim(g, ax.p0 + miss, g.coin() ? dir : -dir, dist);
            return fixture<T>(family, r, s);
        }
    }
    const Axial ax = axial_of(s);
    if (spec.cls == "generic" || spec.cls == "translated") r = generic_ray(g, s);
    else if (spec.cls == "grazing") r = side_grazing(g, ax, spec);
    else if (spec.cls == "rim") {
        s.caps = true;
        const bool at_p1 = ax.r0 <= 0 ? true : (ax.r1 <= 0 ? false : g.coin());
        r = cap_rim(g, ax, at_p1, spec);
    } else if (spec.cls == "axial") {
        const L3 e = g.perpendicular(ax.a);
        const bool up = g.coin();
        const L3 dir = unit((up ? ax.a : -ax.a) + g.perpendicular(ax.a) * closeness(spec));
        const LD start = g.coin() ? (up ? -g.uniform(0.2L, 2) : 1 + g.uniform(0.2L, 2)) : g.uniform(0.1L, 0.9L);
        r = {ax.p0 + ax.a * (ax.h * start) + e * (ax.r0 * g.uniform(0, 0.95L)), dir * g.length(), 0, ld_inf};
    } else if (spec.cls == "far") {
        r = far_ray(g, s, spec);
    } else if (spec.cls == "inside") {
        const LD h = g.uniform(0.05L, 0.95L);
        const LD off = ax.radius(h) * g.uniform(0, 0.9L);
        const L3 o = ax.at(h) + g.perpendicular(ax.a) * off;
        const LD len = g.length();
        const L3 d = g.unit_vector();
        r = {o, d * len, 0, ld_inf};
    } else if (spec.cls == "surface") {
        const LD h = g.uniform(0.1L, 0.9L);
        const L3 e = g.perpendicular(ax.a);
        const L3 n = unit(e - ax.a * ((ax.r1 - ax.r0) / ax.h));
        const L3 dir = cone_direction(g, n * static_cast<LD>(spec.side < 0 ? 1 : -1), pi / 3);
        Fixture f = fixture<T>(family, RayL{ax.at(h) + e * ax.radius(h), dir * g.length(), 0, ld_inf}, s);
        auto& in = std::get<Input<decltype(round_shape<T>(s))>>(f.input);
        in.ray.origin = jitter(g, in.ray.origin);
        return f;
    } else throw std::invalid_argument("rayq::oracle: no family " + family + " for an axial primitive");
    (void)size;
    if (spec.cls == "translated") {
        const L3 v = translation_of(g, spec);
        shift(s, v);
        r.o = r.o + v;
    }
    return fixture<T>(family, r, s);
}

template <class T>
Fixture quadric_case(Rng& g, const std::string& family, const Spec& spec)
{
    RayL r;
    QuadricL q;
    if (spec.cls == "generic" || spec.cls == "translated") {
        q = random_quadric(g, g.below(5));
        r = generic_ray(g, q);
    } else if (spec.cls == "grazing" || spec.cls == "surface" || spec.cls == "inside" || spec.cls == "far" || spec.cls == "clip") {
        q = random_quadric(g, 0);  // ellipsoids: tangency and inside are well defined
        q.lo = {-ld_inf, -ld_inf, -ld_inf}, q.hi = {ld_inf, ld_inf, ld_inf};
        const LD a = 1 / std::sqrt(q.w[0]), b = 1 / std::sqrt(q.w[1]), c = 1 / std::sqrt(q.w[2]);
        const LD u = g.uniform(0, 2 * pi), v = g.uniform(-pi / 2.5L, pi / 2.5L);
        const L3 p = q.c + q.e[0] * (a * std::cos(u) * std::cos(v)) + q.e[1] * (b * std::sin(u) * std::cos(v)) +
                     q.e[2] * (c * std::sin(v));
        const L3 n = unit(q.gradient(p));
        const LD small = std::min({a, b, c});
        if (spec.cls == "grazing") {
            const LD dist = small * g.uniform(1.5L, 5);
            const L3 dir = g.perpendicular(n);
            r = aim(g, p - n * (static_cast<LD>(spec.side) * closeness(spec) * small), dir, dist);
        } else if (spec.cls == "surface") {
            const L3 dir = cone_direction(g, n * static_cast<LD>(spec.side < 0 ? 1 : -1), pi / 3);
            Fixture f = fixture<T>(family, RayL{p, dir * g.length(), 0, ld_inf}, q);
            auto& in = std::get<Input<Quadric<T>>>(f.input);
            in.ray.origin = jitter(g, in.ray.origin);
            return f;
        } else if (spec.cls == "inside") {
            const L3 o = q.c + (p - q.c) * g.uniform(0, 0.9L);
            const LD len = g.length();
            const L3 d = g.unit_vector();
            r = {o, d * len, 0, ld_inf};
        } else if (spec.cls == "far") {
            r = far_ray(g, q, spec);
        } else {
            // clip: keep one half (along a world axis through the center); the ray comes from the
            // other side, so its near root is clipped and the far one counts.
            const int axis = g.below(3);
            const bool keep_upper = g.coin();
            LD* lo[3] = {&q.lo.x, &q.lo.y, &q.lo.z};
            LD* hi[3] = {&q.hi.x, &q.hi.y, &q.hi.z};
            const LD cc[3] = {q.c.x, q.c.y, q.c.z};
            (keep_upper ? *lo[axis] : *hi[axis]) = cc[axis];
            L3 toward{0, 0, 0};
            (axis == 0 ? toward.x : axis == 1 ? toward.y : toward.z) = keep_upper ? 1 : -1;
            const L3 dir = cone_direction(g, toward, pi / 4);
            const L3 target = q.c + g.in_ball(0.3L * small);
            r = aim(g, target, dir, 4 * std::max({a, b, c}));
        }
    } else throw std::invalid_argument("rayq::oracle: no family " + family + " for quadric");
    if (spec.cls == "translated") {
        const L3 v = translation_of(g, spec);
        shift(q, v);
        r.o = r.o + v;
    }
    return fixture<T>(family, r, q);
}

// ---- transformed: an object-space case placed by a random affine map ------------------------------
struct AffineL {
    LD m[3][4];
    L3 point(const L3& p) const { return linear(p) + L3{m[0][3], m[1][3], m[2][3]}; }
    L3 linear(const L3& v) const
    {
        return {m[0][0] * v.x + m[0][1] * v.y + m[0][2] * v.z, m[1][0] * v.x + m[1][1] * v.y + m[1][2] * v.z,
                m[2][0] * v.x + m[2][1] * v.y + m[2][2] * v.z};
    }
};

AffineL random_affine(Rng& g, const L3& translation)
{
    L3 e[3];
    frame(g, e);
    const LD s[3] = {g.log_uniform(0.3L, 3), g.log_uniform(0.3L, 3), g.log_uniform(0.3L, 3)};
    const LD shear = g.below(3) == 0 ? g.uniform(-0.5L, 0.5L) : 0;
    AffineL a{};
    // L = R·S·(I + shear·x⊗y), R's columns e[i].
    for (int r = 0; r < 3; ++r) {
        const LD row[3] = {(r == 0 ? e[0].x : r == 1 ? e[0].y : e[0].z) * s[0], (r == 0 ? e[1].x : r == 1 ? e[1].y : e[1].z) * s[1],
                           (r == 0 ? e[2].x : r == 1 ? e[2].y : e[2].z) * s[2]};
        a.m[r][0] = row[0];
        a.m[r][1] = row[1] + row[0] * shear;
        a.m[r][2] = row[2];
    }
    a.m[0][3] = translation.x, a.m[1][3] = translation.y, a.m[2][3] = translation.z;
    return a;
}

template <class T, class Prim>
Fixture place(Rng& g, const std::string& family, const Spec& spec, const Fixture& object_case)
{
    const auto& in = std::get<Input<Prim>>(object_case.input);
    const L3 translation = spec.cls == "translated" ? translation_of(g, spec) : g.in_ball(10);
    const AffineL w = random_affine(g, translation);
    const L3 o{in.ray.origin.x, in.ray.origin.y, in.ray.origin.z}, d{in.ray.direction.x, in.ray.direction.y, in.ray.direction.z};
    const RayL world{w.point(o), w.linear(d), static_cast<LD>(in.ray.tmin), static_cast<LD>(in.ray.tmax)};
    Transformed<Prim> x{in.prim, {}, {}};
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 4; ++j) x.to_world.m[i][j] = static_cast<T>(w.m[i][j]);
    x.to_object = rounded_inverse(x.to_world);
    return {family, AnyInput(Input<Transformed<Prim>>{round_ray<T>(world), x})};
}

template <class T>
Fixture transformed_case(Rng& g, const std::string& inner, const std::string& family, const Spec& spec)
{
    // The object case: generic for "translated" (the map carries the translation).
    const std::string object_family = spec.cls == "translated" ? "generic" : family;
    const Spec object_spec = parse_spec(object_family);
    if (inner == "sphere") return place<T, Sphere<T>>(g, family, spec, sphere_case<T>(g, object_family, object_spec));
    if (inner == "cylinder")
        return place<T, Cylinder<T>>(g, family, spec, axial_case<T>(g, object_family, object_spec, random_cylinder(g)));
    if (inner == "cone") return place<T, Cone<T>>(g, family, spec, axial_case<T>(g, object_family, object_spec, random_cone(g, false)));
    if (inner == "quadric") return place<T, Quadric<T>>(g, family, spec, quadric_case<T>(g, object_family, object_spec));
    if (inner == "triangle")
        return place<T, Triangle<T>>(g, family, spec, flat_case<T>(g, object_family, object_spec, random_triangle(g)));
    throw std::invalid_argument("rayq::oracle: no generator for transformed-" + inner);
}

template <class T>
Fixture generate_typed(const std::string& primitive, const std::string& family, Rng& g)
{
    const Spec spec = parse_spec(family);
    if (primitive == "sphere") return sphere_case<T>(g, family, spec);
    if (primitive == "plane") return flat_case<T>(g, family, spec, random_plane(g));
    if (primitive == "disk") return flat_case<T>(g, family, spec, random_disk(g));
    if (primitive == "parallelogram") return flat_case<T>(g, family, spec, random_parallelogram(g));
    if (primitive == "triangle") return flat_case<T>(g, family, spec, random_triangle(g));
    if (primitive == "cylinder") return axial_case<T>(g, family, spec, random_cylinder(g));
    if (primitive == "cone") return axial_case<T>(g, family, spec, random_cone(g, g.below(4) == 0));
    if (primitive == "quadric") return quadric_case<T>(g, family, spec);
    const std::string prefix = "transformed-";
    if (primitive.compare(0, prefix.size(), prefix) == 0) return transformed_case<T>(g, primitive.substr(prefix.size()), family, spec);
    throw std::invalid_argument("rayq::oracle: no generator for primitive " + primitive);
}

std::string two_digits(int n) { return (n < 10 ? "0" : "") + std::to_string(n); }

void add_k(std::vector<std::string>& out, const std::string& cls, bool sided, int kmax)
{
    for (int k = 1; k <= kmax; ++k) {
        if (sided) {
            out.push_back(cls + ".in.k" + two_digits(k));
            out.push_back(cls + ".out.k" + two_digits(k));
        } else {
            out.push_back(cls + ".k" + two_digits(k));
        }
    }
}
void add_e(std::vector<std::string>& out, const std::string& cls, int emax)
{
    for (int e = 1; e <= emax; ++e) out.push_back(cls + ".e" + two_digits(e));
}

}  // namespace

const std::vector<std::string>& generated_primitives()
{
    static const std::vector<std::string> names = {
        "sphere", "plane", "disk", "parallelogram", "triangle", "cylinder", "cone", "quadric",
        "transformed-sphere", "transformed-cylinder", "transformed-cone", "transformed-quadric", "transformed-triangle"};
    return names;
}

std::vector<std::string> family_names(const std::string& primitive, Scalar s)
{
    const int kmax = s == Scalar::f64 ? 15 : 7;
    std::vector<std::string> out = {"generic"};
    const bool curved = primitive == "sphere" || primitive == "cylinder" || primitive == "cone" || primitive == "quadric";
    const bool flat = primitive == "plane" || primitive == "disk" || primitive == "parallelogram" || primitive == "triangle";
    if (curved) add_k(out, "grazing", true, kmax);
    if (flat) add_k(out, "parallel", false, kmax);
    if (flat && primitive != "plane") add_k(out, "rim", true, kmax);
    if (primitive == "cylinder" || primitive == "cone") add_k(out, "rim", true, kmax);
    if (primitive == "cylinder") add_k(out, "axial", false, kmax);
    if (primitive == "cone") {
        add_k(out, "apex", true, kmax);
        out.push_back("apex.exact");
    }
    if (primitive == "quadric") out.push_back("clip");
    if (curved || flat) add_e(out, "far", 8);
    if (primitive.compare(0, 12, "transformed-") == 0) {
        if (primitive == "transformed-triangle") {
            add_k(out, "parallel", false, kmax);
            add_k(out, "rim", true, kmax);
        } else {
            add_k(out, "grazing", true, kmax);
        }
    }
    add_e(out, "translated", 8);
    if (curved) out.push_back("inside");
    if (curved || flat) {
        out.push_back("surface.in");
        out.push_back("surface.out");
    }
    return out;
}

Fixture generate(const std::string& primitive, Scalar s, const std::string& family, std::uint64_t seed, std::uint64_t index)
{
    std::uint64_t mix = seed ^ fnv(primitive) ^ (fnv(family) * 3) ^ (s == Scalar::f32 ? 0x5151ull : 0xD0D0ull);
    Rng g{splitmix(mix) ^ (index * 0x9E3779B97F4A7C15ull)};
    splitmix(g.state);
    // Rounding can collapse a shape (a small triangle 10^8 away in float); draw again until the
    // case is inside the oracle's domain.
    for (int attempt = 0;; ++attempt) {
        Fixture f = s == Scalar::f32 ? generate_typed<float>(primitive, family, g) : generate_typed<double>(primitive, family, g);
        if (attempt == 99 || truth_of(f.input).first_hit().defined) return f;
    }
}

std::vector<Fixture> generate_cases(const std::string& primitive, Scalar s, std::size_t count, std::uint64_t seed)
{
    const std::vector<std::string> families = family_names(primitive, s);
    std::vector<Fixture> out;
    out.reserve(count);
    for (std::size_t i = 0; i < count; ++i)
        out.push_back(generate(primitive, s, families[i % families.size()], seed, i / families.size()));
    return out;
}

std::vector<Fixture> curated_fixtures(const std::string& primitive)
{
    std::vector<Fixture> out;
    for (Scalar s : {Scalar::f64, Scalar::f32}) {
        const int kmax = s == Scalar::f64 ? 15 : 7;
        for (const std::string& family : family_names(primitive, s)) {
            const Spec spec = parse_spec(family);
            int copies = 1;
            if (spec.cls == "generic") copies = 3;
            if (spec.k != 0) {
                const bool keep = s == Scalar::f64 ? (spec.k == 1 || spec.k == 5 || spec.k == 10 || spec.k == kmax)
                                                   : (spec.k == 1 || spec.k == 4 || spec.k == kmax);
                if (!keep) continue;
            }
            if (spec.cls == "far" && spec.e != 3 && spec.e != 8) continue;
            if (spec.cls == "translated" && spec.e != 8) continue;
            if (spec.cls == "clip" || spec.exact) copies = 2;
            for (int i = 0; i < copies; ++i) out.push_back(generate(primitive, s, family, curated_seed, static_cast<std::uint64_t>(i)));
        }
    }
    return out;
}

}  // namespace rayq::oracle
