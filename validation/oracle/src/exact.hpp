// rayq::oracle — private: the exact arithmetic (GMP rationals and the quadratic field Q(√D)),
// the primitives as rational data, and the solver. No CGAL here; nothing from the kernel but
// the Part enum.
#pragma once

#include <gmpxx.h>

#include <cstddef>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include <rayq/hit.hpp>

namespace rayq::oracle::exact {

using Q = mpq_class;

inline int sgn(const Q& q) { return ::sgn(q); }

struct V {
    Q x, y, z;
};
inline V operator+(const V& a, const V& b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
inline V operator-(const V& a, const V& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
inline V operator-(const V& a) { return {-a.x, -a.y, -a.z}; }
inline V operator*(const V& a, const Q& s) { return {a.x * s, a.y * s, a.z * s}; }
inline Q dot(const V& a, const V& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline V cross(const V& a, const V& b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
inline bool is_zero(const V& a) { return sgn(a.x) == 0 && sgn(a.y) == 0 && sgn(a.z) == 0; }

// x = a + b·√D, D >= 0 fixed by context (the discriminant of one ray's equation).
struct Alg {
    Q a, b;
};
inline Alg rational(const Q& a) { return {a, Q(0)}; }
inline Alg operator+(const Alg& x, const Alg& y) { return {x.a + y.a, x.b + y.b}; }
inline Alg operator-(const Alg& x, const Alg& y) { return {x.a - y.a, x.b - y.b}; }
inline Alg operator-(const Alg& x) { return {-x.a, -x.b}; }
inline Alg operator+(const Alg& x, const Q& r) { return {x.a + r, x.b}; }
inline Alg operator-(const Alg& x, const Q& r) { return {x.a - r, x.b}; }
inline Alg operator*(const Alg& x, const Q& s) { return {x.a * s, x.b * s}; }
inline Alg mul(const Alg& x, const Alg& y, const Q& D) { return {x.a * y.a + x.b * y.b * D, x.a * y.b + x.b * y.a}; }

// The sign of a + b·√D, exactly.
int sign(const Alg& x, const Q& D);
inline int compare(const Alg& x, const Alg& y, const Q& D) { return sign(x - y, D); }
inline int compare(const Alg& x, const Q& r, const Q& D) { return sign(x - r, D); }

// A point or vector with coordinates in Q(√D).
struct AV {
    Alg x, y, z;
};
inline AV point_at(const V& o, const V& d, const Alg& t) { return {t * d.x + o.x, t * d.y + o.y, t * d.z + o.z}; }
inline AV operator-(const AV& p, const V& c) { return {p.x - c.x, p.y - c.y, p.z - c.z}; }
inline AV operator*(const V& v, const Alg& s) { return {s * v.x, s * v.y, s * v.z}; }
inline AV operator+(const AV& p, const AV& q) { return {p.x + q.x, p.y + q.y, p.z + q.z}; }
inline AV operator-(const AV& p, const AV& q) { return {p.x - q.x, p.y - q.y, p.z - q.z}; }
inline AV operator*(const AV& p, const Q& s) { return {p.x * s, p.y * s, p.z * s}; }
inline AV rational(const V& v) { return {rational(v.x), rational(v.y), rational(v.z)}; }
inline Alg dot(const AV& p, const V& v) { return p.x * v.x + p.y * v.y + p.z * v.z; }
inline AV cross(const AV& p, const V& v)
{
    return {p.y * v.z - p.z * v.y, p.z * v.x - p.x * v.z, p.x * v.y - p.y * v.x};
}
Alg dot(const AV& p, const AV& q, const Q& D);

// An extended real: ±∞ or a finite element of Q(√D).
struct Bound {
    int inf = 0;  // −1: −∞, +1: +∞, 0: finite
    Alg t;
};
inline Bound finite(const Alg& t) { return {0, t}; }
inline Bound finite(const Q& t) { return {0, rational(t)}; }
inline Bound minus_infinity() { return {-1, {}}; }
inline Bound plus_infinity() { return {+1, {}}; }
int compare(const Bound& x, const Bound& y, const Q& D);

// The ray; window bounds are rational or infinite.
struct RayQ {
    V o, d;
    Bound tmin, tmax;
};

struct SphereQ { V c; Q r; };
struct PlaneQ { V p, n; };
struct DiskQ { V c, n; Q r; };
struct ParallelogramQ { V corner, e0, e1; };
struct TriangleQ { V a, b, c; };
struct CylinderQ { V p0, p1; Q r; bool caps; };
struct ConeQ { V p0; Q r0; V p1; Q r1; bool caps; };
struct QuadricQ {
    Q k[10];             // A B C D E F G H I J
    Bound lo[3], hi[3];  // clip box (rational or infinite)
};
struct AffineQ {
    Q m[3][4];  // [L | t]
};

using Shape = std::variant<SphereQ, PlaneQ, DiskQ, ParallelogramQ, TriangleQ, CylinderQ, ConeQ, QuadricQ>;

struct Problem {
    RayQ ray;
    Shape shape;
    std::optional<AffineQ> to_world;  // Transformed: the object's placement (its inverse is computed exactly)
    bool defined = true;
    std::string why;  // when !defined
};

struct Crossing {
    Alg t;
    Part part;
    bool entering;
    bool tangent;
};

struct Solution {
    bool defined = false;
    Q D;                              // every t below lies in Q(√D)
    std::vector<Crossing> crossings;  // along the whole line, ascending in t
    std::optional<std::size_t> first; // the first crossing with tmin < t < tmax
    AV normal;                        // outward (world) normal at the first hit, any length
    bool normal_defined = false;
    V direction;                      // the world ray's direction
};

Solution solve(const Problem& problem);

// to_world's exact inverse; nullopt when singular.
std::optional<AffineQ> inverse(const AffineQ& w);

// Text of an element of Q(√D).
std::string to_string(const Alg& x, const Q& D);

}  // namespace rayq::oracle::exact
