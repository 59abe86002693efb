// rayq::fuzz — bytes to (ray, primitive), for the libFuzzer harnesses and the deterministic
// edge-case test (issue 9). Depends on the kernel only.
//
// Random bytes read as raw IEEE numbers are almost all huge, tiny or NaN, and a ray built from
// them almost never comes near a primitive. So the decoder is structured: the first byte picks
// the number type and the primitive within the family, the second byte the construction, and
// every number is read through a control byte that picks its kind (a moderate value, a small
// dyadic, a special value, raw bits, a huge or tiny magnitude, a value a few ulps off a moderate
// one). The constructions then place the ray where the kernel has to decide something hard:
// origin on or near the surface, direction near a tangent, near-parallel to a plane or an axis,
// through a rim, an edge, a corner or an apex, a window that ends at the hit. A short input
// reads zeros past its end, so every byte string decodes to some case.
//
// Every read is its own statement, declarator or braced-list element: C++ leaves the order of
// function arguments and of an operator's operands unspecified, and g++ and clang differ, so a
// stored input (a libFuzzer crash found under clang) decoded to another case under g++. The order
// kept is the source order, clang's.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string>
#include <type_traits>

#include <rayq/rayq.hpp>

namespace rayq::fuzz {

enum class Harness { flat, sphere, axial, quadric, transformed };
inline constexpr Harness all_harnesses[] = {Harness::flat, Harness::sphere, Harness::axial, Harness::quadric,
                                            Harness::transformed};
inline const char* harness_name(Harness h)
{
    switch (h) {
    case Harness::flat: return "flat";
    case Harness::sphere: return "sphere";
    case Harness::axial: return "axial";
    case Harness::quadric: return "quadric";
    case Harness::transformed: return "transformed";
    }
    return "?";
}

// The fuzzer's bytes, consumed front to back; zeros once they run out.
class ByteReader {
public:
    ByteReader(const std::uint8_t* data, std::size_t size) : data_(data), size_(size) {}

    std::uint8_t byte() { return pos_ < size_ ? data_[pos_++] : std::uint8_t(0); }
    std::uint64_t bits(int bytes)
    {
        std::uint64_t v = 0;
        for (int i = 0; i < bytes; ++i) v |= std::uint64_t(byte()) << (8 * i);
        return v;
    }
    // A value in [-1, 1) with 16 bits of resolution.
    double signed_unit() { return double(std::int16_t(bits(2))) / 32768.0; }
    // A value in [0, 1].
    double unit() { return double(bits(2)) / 65535.0; }
    // 10^-k with k in [1, kmax]: the offsets of the "near" constructions.
    double tiny(int kmax) { return std::pow(10.0, -double(1 + byte() % kmax)); }
    bool exhausted() const { return pos_ >= size_; }

private:
    const std::uint8_t* data_;
    std::size_t size_;
    std::size_t pos_ = 0;
};

// One number of any kind, chosen by a control byte (the shares are what a fuzzer mutating
// that byte explores: mostly usable values, a steady trickle of hostile ones).
template <class T>
T any_number(ByteReader& in)
{
    using L = std::numeric_limits<T>;
    const std::uint8_t control = in.byte();
    if (control < 96) return T(4 * in.signed_unit());            // moderate
    if (control < 128) return T(std::int8_t(in.byte())) / T(8);  // small dyadic: exact ties, ±0
    if (control < 176) {                                         // special values
        const T specials[] = {T(0), -T(0), T(1), -T(1), T(0.5), T(2), L::quiet_NaN(), -L::quiet_NaN(), L::infinity(),
                              -L::infinity(), L::denorm_min(), -L::denorm_min(), L::min(), -L::min(), L::max(), -L::max(),
                              L::epsilon(), T(1) + L::epsilon(), T(1) - L::epsilon() / 2, std::sqrt(L::max()),
                              T(1) / std::sqrt(L::max()), std::sqrt(L::min()), T(3) * L::denorm_min(), L::max() / 2};
        return specials[in.byte() % (sizeof(specials) / sizeof(specials[0]))];
    }
    if (control < 208) {  // raw bits: anything at all
        T v;
        if constexpr (sizeof(T) == 8) {
            const std::uint64_t b = in.bits(8);
            std::memcpy(&v, &b, 8);
        } else {
            const std::uint32_t b = std::uint32_t(in.bits(4));
            std::memcpy(&v, &b, 4);
        }
        return v;
    }
    if (control < 240) {  // huge or tiny magnitudes, inside the type's range
        const int max_exp = L::max_exponent10 - 1;
        const int e = int(std::int8_t(in.byte())) % max_exp;
        return T(4 * in.signed_unit() * std::pow(10.0, e));
    }
    // a few ulps off a moderate value
    T v = T(4 * in.signed_unit());
    const int steps = int(std::int8_t(in.byte())) % 5;
    for (int i = 0; i < std::abs(steps); ++i) v = std::nextafter(v, steps > 0 ? L::infinity() : -L::infinity());
    return v;
}

template <class T>
Vec3<T> any_vec(ByteReader& in) { return {any_number<T>(in), any_number<T>(in), any_number<T>(in)}; }

// A "geometry" frame: most primitives are built from moderate numbers times a common scale and
// moved by a common offset, so far-away and huge/tiny primitives come with usable shapes.
template <class T>
struct Frame {
    double scale = 1;
    Vec3<double> offset{0, 0, 0};

    static Frame read(ByteReader& in)
    {
        Frame f;
        const std::uint8_t kind = in.byte();
        if (kind >= 160) f.scale = std::pow(10.0, double(std::int8_t(in.byte()) % (std::is_same_v<T, float> ? 12 : 40)));
        if (kind % 4 == 3) {
            const double far = std::pow(10.0, double(in.byte() % (std::is_same_v<T, float> ? 10 : 20)));
            f.offset = {far * in.signed_unit(), far * in.signed_unit(), far * in.signed_unit()};
        }
        return f;
    }
    T length(double v) const { return T(v * scale); }
    Vec3<T> point(double x, double y, double z) const
    {
        return {T(x * scale + offset.x), T(y * scale + offset.y), T(z * scale + offset.z)};
    }
    Vec3<T> point(ByteReader& in) const
    {
        const double x = 2 * in.signed_unit(), y = 2 * in.signed_unit(), z = 2 * in.signed_unit();
        return point(x, y, z);
    }
    Vec3<T> vector(ByteReader& in) const
    {
        return {T(2 * in.signed_unit() * scale), T(2 * in.signed_unit() * scale), T(2 * in.signed_unit() * scale)};
    }
    T positive(ByteReader& in) const { return T((0.05 + 1.5 * in.unit()) * scale); }
};

// A decoded case: the ray, the primitive, and which construction produced it (for messages).
template <class Prim>
struct Case {
    Ray<scalar_t<Prim>> ray;
    Prim prim;
    std::string construction;
};

namespace detail_decode {

template <class T>
Vec3<long double> wide(const Vec3<T>& v) { return {(long double)v.x, (long double)v.y, (long double)v.z}; }
template <class T>
Vec3<T> narrow(const Vec3<long double>& v) { return {T(v.x), T(v.y), T(v.z)}; }

// Any unit vector perpendicular to n (n need not be unit).
inline Vec3<long double> perpendicular(const Vec3<long double>& n, double angle)
{
    const Vec3<long double> helper = std::abs(n.x) < std::abs(n.y) ? Vec3<long double>{1, 0, 0} : Vec3<long double>{0, 1, 0};
    Vec3<long double> u = cross(n, helper);
    const long double lu = length(u);
    if (!(lu > 0)) return {1, 0, 0};
    u = u / lu;
    Vec3<long double> w = cross(n, u);
    const long double lw = length(w);
    if (lw > 0) w = w / lw;
    return u * (long double)std::cos(angle) + w * (long double)std::sin(angle);
}

// Where to aim, and how big the primitive is: for the "aimed" construction and as fall-backs.
template <class T> Vec3<T> aim_point(const Sphere<T>& s) { return s.center; }
template <class T> Vec3<T> aim_point(const Plane<T>& p) { return p.point; }
template <class T> Vec3<T> aim_point(const Disk<T>& d) { return d.center; }
template <class T> Vec3<T> aim_point(const Parallelogram<T>& p) { return p.corner + (p.edge0 + p.edge1) * T(0.5); }
template <class T> Vec3<T> aim_point(const Triangle<T>& t) { return (t.a + t.b + t.c) / T(3); }
template <class T> Vec3<T> aim_point(const Cylinder<T>& c) { return (c.p0 + c.p1) * T(0.5); }
template <class T> Vec3<T> aim_point(const Cone<T>& c) { return (c.p0 + c.p1) * T(0.5); }
template <class T>
Vec3<T> aim_point(const Quadric<T>& q)
{
    // The clip box's center where it is finite; the origin of the quadric's frame otherwise.
    const auto mid = [](T lo, T hi) { return std::isfinite(lo) && std::isfinite(hi) ? lo / 2 + hi / 2 : T(0); };
    return {mid(q.clip.lo.x, q.clip.hi.x), mid(q.clip.lo.y, q.clip.hi.y), mid(q.clip.lo.z, q.clip.hi.z)};
}
template <class P, class T> Vec3<T> aim_point(const Transformed<P, T>& x) { return x.to_world.point(aim_point(x.object)); }

template <class T> T size_of(const Sphere<T>& s) { return s.radius; }
template <class T> T size_of(const Plane<T>&) { return T(1); }
template <class T> T size_of(const Disk<T>& d) { return d.radius; }
template <class T> T size_of(const Parallelogram<T>& p) { return length(p.edge0) + length(p.edge1); }
template <class T> T size_of(const Triangle<T>& t) { return length(t.b - t.a) + length(t.c - t.a); }
template <class T> T size_of(const Cylinder<T>& c) { return length(c.p1 - c.p0) + c.radius; }
template <class T> T size_of(const Cone<T>& c) { return length(c.p1 - c.p0) + std::max(c.r0, c.r1); }
template <class T> T size_of(const Quadric<T>&) { return T(1); }
template <class P, class T>
T size_of(const Transformed<P, T>& x)
{
    const auto& m = x.to_world.m;
    const T col = length(Vec3<T>{m[0][0], m[1][0], m[2][0]}) + length(Vec3<T>{m[0][1], m[1][1], m[2][1]}) +
                  length(Vec3<T>{m[0][2], m[1][2], m[2][2]});
    return size_of(x.object) * col / 3;
}

// A point on a boundary the kernel must decide exactly (rim, edge, corner, apex) and the plane
// normal there (for "parallel through the rim"); false where the primitive has none.
struct Rim {
    Vec3<long double> point, normal;
};
template <class T> bool rim_point(const Sphere<T>&, ByteReader&, Rim&) { return false; }
template <class T> bool rim_point(const Plane<T>&, ByteReader&, Rim&) { return false; }
template <class T> bool rim_point(const Quadric<T>&, ByteReader&, Rim&) { return false; }
template <class T>
bool rim_point(const Disk<T>& d, ByteReader& in, Rim& r)
{
    const auto n = wide(d.normal);
    r.normal = n;
    r.point = wide(d.center) + perpendicular(n, 6.283185307179586 * in.unit()) * (long double)d.radius;
    return true;
}
inline Vec3<long double> on_edge(const Vec3<long double>& a, const Vec3<long double>& b, ByteReader& in)
{
    const std::uint8_t k = in.byte();
    if (k < 64) return a;  // a corner
    const long double s = k < 96 ? 0.5L : (long double)in.unit();
    return a + (b - a) * s;
}
template <class T>
bool rim_point(const Parallelogram<T>& p, ByteReader& in, Rim& r)
{
    const auto c = wide(p.corner), e0 = wide(p.edge0), e1 = wide(p.edge1);
    r.normal = cross(e0, e1);
    const Vec3<long double> corners[4] = {c, c + e0, c + e0 + e1, c + e1};
    const int i = in.byte() % 4;
    r.point = on_edge(corners[i], corners[(i + 1) % 4], in);
    return true;
}
template <class T>
bool rim_point(const Triangle<T>& t, ByteReader& in, Rim& r)
{
    const Vec3<long double> v[3] = {wide(t.a), wide(t.b), wide(t.c)};
    r.normal = cross(v[1] - v[0], v[2] - v[0]);
    const int i = in.byte() % 3;
    r.point = on_edge(v[i], v[(i + 1) % 3], in);
    return true;
}
template <class T>
bool rim_point(const Cylinder<T>& c, ByteReader& in, Rim& r)
{
    const auto axis = wide(c.p1) - wide(c.p0);
    r.normal = axis;
    const bool end1 = in.byte() % 2;
    r.point = (end1 ? wide(c.p1) : wide(c.p0)) + perpendicular(axis, 6.283185307179586 * in.unit()) * (long double)c.radius;
    return true;
}
template <class T>
bool rim_point(const Cone<T>& c, ByteReader& in, Rim& r)
{
    const auto axis = wide(c.p1) - wide(c.p0);
    r.normal = axis;
    const bool end1 = in.byte() % 2;
    const long double radius = end1 ? c.r1 : c.r0;  // 0: the apex itself
    r.point = (end1 ? wide(c.p1) : wide(c.p0)) + perpendicular(axis, 6.283185307179586 * in.unit()) * radius;
    return true;
}
template <class P, class T>
bool rim_point(const Transformed<P, T>& x, ByteReader& in, Rim& r)
{
    Rim local;
    if (!rim_point(x.object, in, local)) return false;
    const auto p = x.to_world.point(narrow<T>(local.point));
    r.point = wide(p);
    r.normal = wide(x.to_object.linear_transposed(narrow<T>(local.normal)));
    return true;
}

// A direction the kernel finds hard to be parallel to: a flat primitive's plane, a cylinder's
// axis, a cone's generator line; false where there is none.
template <class T> bool hard_direction(const Sphere<T>&, ByteReader&, Vec3<long double>&, Vec3<long double>&) { return false; }
template <class T> bool hard_direction(const Quadric<T>&, ByteReader&, Vec3<long double>&, Vec3<long double>&) { return false; }
template <class T>
bool in_plane(const Vec3<long double>& n, ByteReader& in, Vec3<long double>& dir, Vec3<long double>& off)
{
    dir = perpendicular(n, 6.283185307179586 * in.unit());
    off = n / length(n);
    return true;
}
template <class T> bool hard_direction(const Plane<T>& p, ByteReader& in, Vec3<long double>& d, Vec3<long double>& o) { return in_plane<T>(wide(p.normal), in, d, o); }
template <class T> bool hard_direction(const Disk<T>& p, ByteReader& in, Vec3<long double>& d, Vec3<long double>& o) { return in_plane<T>(wide(p.normal), in, d, o); }
template <class T>
bool hard_direction(const Parallelogram<T>& p, ByteReader& in, Vec3<long double>& d, Vec3<long double>& o)
{
    return in_plane<T>(cross(wide(p.edge0), wide(p.edge1)), in, d, o);
}
template <class T>
bool hard_direction(const Triangle<T>& t, ByteReader& in, Vec3<long double>& d, Vec3<long double>& o)
{
    return in_plane<T>(cross(wide(t.b) - wide(t.a), wide(t.c) - wide(t.a)), in, d, o);
}
template <class T>
bool hard_direction(const Cylinder<T>& c, ByteReader& in, Vec3<long double>& d, Vec3<long double>& o)
{
    d = wide(c.p1) - wide(c.p0);
    o = perpendicular(d, 6.283185307179586 * in.unit());
    return true;
}
template <class T>
bool hard_direction(const Cone<T>& c, ByteReader& in, Vec3<long double>& d, Vec3<long double>& o)
{
    const auto axis = wide(c.p1) - wide(c.p0);
    const auto radial = perpendicular(axis, 6.283185307179586 * in.unit());
    d = axis + radial * ((long double)c.r1 - (long double)c.r0);  // along a generator line
    o = radial;
    return true;
}
template <class P, class T>
bool hard_direction(const Transformed<P, T>& x, ByteReader& in, Vec3<long double>& d, Vec3<long double>& o)
{
    Vec3<long double> ld, lo;
    if (!hard_direction(x.object, in, ld, lo)) return false;
    d = wide(x.to_world.linear(narrow<T>(ld)));
    o = wide(x.to_object.linear_transposed(narrow<T>(lo)));
    return true;
}

template <class T>
Ray<T> ray_through(const Vec3<long double>& target, const Vec3<long double>& dir, long double back, T tmin = T(0),
                   T tmax = std::numeric_limits<T>::infinity())
{
    return {narrow<T>(target - dir * back), narrow<T>(dir), tmin, tmax};
}

}  // namespace detail_decode

// The ray for a decoded primitive, by the construction the selector byte names.
template <class Prim>
Case<Prim> make_case(const Prim& prim, ByteReader& in)
{
    using namespace detail_decode;
    using T = scalar_t<Prim>;
    constexpr T inf = std::numeric_limits<T>::infinity();
    const std::uint8_t selector = in.byte();
    const long double size = std::isfinite(size_of(prim)) && size_of(prim) > 0 ? (long double)size_of(prim) : 1.0L;
    const Vec3<long double> center = wide(aim_point(prim));
    const auto random_dir = [&] {
        Vec3<long double> d{in.signed_unit(), in.signed_unit(), in.signed_unit()};
        return length(d) > 0 ? d : Vec3<long double>{0, 0, 1};
    };
    // A direction length that is not always 1: rays need not be unit.
    const auto dir_scale = [&]() -> long double {
        const std::uint8_t k = in.byte();
        return k < 128 ? 1.0L : std::pow(10.0L, (long double)(int(std::int8_t(k)) % (std::is_same_v<T, float> ? 8 : 30)));
    };
    // An aimed ray: from 2–10 sizes away through a point near the center.
    const auto aimed = [&](const char* name) {
        const Vec3<long double> toward = random_dir();
        const Vec3<long double> target = center + toward * (size * (long double)in.unit());
        const Vec3<long double> unit_dir = random_dir();
        const Vec3<long double> dir = unit_dir * dir_scale();
        const long double back = size * (2 + 8 * (long double)in.unit()) / length(dir);
        return Case<Prim>{ray_through<T>(target, dir, back), prim, name};
    };
    // A surface point: where an aimed ray hits (the kernel's stable policy only builds the case).
    const auto surface = [&](Vec3<long double>& p, Vec3<long double>& n) {
        for (int attempt = 0; attempt < 3; ++attempt) {
            const Case<Prim> probe = aimed("probe");
            if (const auto h = intersect(stable, probe.ray, prim)) {
                p = wide(h->point);
                n = wide(h->normal) * (long double)(h->front_face ? 1 : -1);  // outward
                return true;
            }
        }
        return false;
    };
    const auto signed_tiny = [&](int kmax) {
        const long double sign = (in.byte() & 1) ? 1 : -1;
        return sign * (long double)in.tiny(kmax);
    };
    const int kmax = std::is_same_v<T, float> ? 7 : 15;

    switch (selector % 9) {
    case 0: {  // raw: every ray field any number at all
        Ray<T> r{any_vec<T>(in), any_vec<T>(in)};
        if (in.byte() & 1) r.tmin = any_number<T>(in);
        if (in.byte() & 1) r.tmax = any_number<T>(in);
        return {r, prim, "raw"};
    }
    case 1: return aimed("aimed");
    case 2: {  // origin on the surface, or a hair off it, going anywhere
        Vec3<long double> p, n;
        if (!surface(p, n)) return aimed("aimed");
        const std::uint8_t how = in.byte();
        Vec3<T> o = narrow<T>(p);
        if (how % 3 == 1) o = narrow<T>(p + n / length(n) * (signed_tiny(kmax) * size));
        if (how % 3 == 2)  // a few ulps per coordinate
            for (T* c : {&o.x, &o.y, &o.z})
                for (int i = in.byte() % 4; i > 0; --i) *c = std::nextafter(*c, (in.byte() & 1) ? inf : -inf);
        Vec3<long double> d = random_dir();
        if (how & 8) d = n * (long double)((how & 16) ? 1 : -1) + d * 0.3L;  // clearly in or out
        return {Ray<T>{o, narrow<T>(d * dir_scale())}, prim, "surface-origin"};
    }
    case 3: {  // a line a hair from tangency at a surface point
        Vec3<long double> p, n;
        if (!surface(p, n)) return aimed("aimed");
        const Vec3<long double> un = n / length(n);
        const Vec3<long double> tangent = perpendicular(un, 6.283185307179586 * in.unit());
        const Vec3<long double> skewed = tangent + un * signed_tiny(kmax);
        const Vec3<long double> d = skewed * dir_scale();
        const long double lift = signed_tiny(kmax);
        const Vec3<long double> target = p + un * (lift * size * (long double)((in.byte() & 1) ? 1 : 0));
        return {ray_through<T>(target, d, size * (1 + 4 * (long double)in.unit()) / length(d)), prim, "tangent"};
    }
    case 4: {  // through a rim, edge, corner or apex, a hair inside or outside
        Rim rim;
        if (!rim_point(prim, in, rim) || !(length(rim.normal) > 0)) return aimed("aimed");
        const Vec3<long double> un = rim.normal / length(rim.normal);
        const Vec3<long double> outward = rim.point - center;
        Vec3<long double> target = rim.point;
        if (in.byte() & 1 && length(outward) > 0) target = target + outward * signed_tiny(kmax);
        Vec3<long double> d = random_dir();
        if (in.byte() & 1) d = d + un * (long double)(in.byte() & 1 ? 2 : -2);  // through the rim's plane
        if (in.byte() % 4 == 0) {  // along it
            const Vec3<long double> along = perpendicular(un, 6.283185307179586 * in.unit());
            d = along + un * signed_tiny(kmax);
        }
        d = d * dir_scale();
        return {ray_through<T>(target, d, size * (1 + 4 * (long double)in.unit()) / length(d)), prim, "rim"};
    }
    case 5: {  // near-parallel to a plane, an axis or a cone's generator line
        Vec3<long double> d, off;
        if (!hard_direction(prim, in, d, off) || !(length(d) > 0) || !(length(off) > 0)) return aimed("aimed");
        d = d / length(d) + off / length(off) * signed_tiny(kmax);
        Vec3<long double> target = center + off / length(off) * (size * (long double)in.signed_unit());
        if (in.byte() & 1) {  // on a surface point's line instead
            Vec3<long double> p, n;
            if (surface(p, n)) target = p;
        }
        d = d * dir_scale();
        return {ray_through<T>(target, d, size * (1 + 4 * (long double)in.unit()) / length(d)), prim, "parallel"};
    }
    case 6: {  // a window that ends or starts a hair from the hit
        Case<Prim> c = aimed("window");
        if (const auto h = intersect(stable, c.ray, prim)) {
            const T t = h->t;
            const std::uint8_t how = in.byte();
            T edge = t;
            for (int i = in.byte() % 3; i > 0; --i) edge = std::nextafter(edge, (how & 2) ? inf : T(0));
            if (how & 1) c.ray.tmax = edge; else c.ray.tmin = edge;
            if (how & 4) c.ray.tmin = -inf;
        }
        return c;
    }
    case 7: {  // origin inside (near the center), going anywhere; window any numbers
        const Vec3<long double> toward = random_dir();
        const Vec3<T> origin = narrow<T>(center + toward * (size * 0.1L * (long double)in.unit()));
        const Vec3<long double> unit_dir = random_dir();
        Ray<T> r{origin, narrow<T>(unit_dir * dir_scale())};
        if (in.byte() & 1) r.tmin = any_number<T>(in);
        if (in.byte() & 1) r.tmax = any_number<T>(in);
        return {r, prim, "inside"};
    }
    default: {  // an aimed ray with one hostile field
        Case<Prim> c = aimed("aimed-hostile");
        T* fields[] = {&c.ray.origin.x, &c.ray.origin.y, &c.ray.origin.z, &c.ray.direction.x, &c.ray.direction.y,
                       &c.ray.direction.z, &c.ray.tmin, &c.ray.tmax};
        const T hostile = any_number<T>(in);  // read first: C++17 sequences an assignment's right side first
        *fields[in.byte() % 8] = hostile;
        return c;
    }
    }
}

// ---- primitives ---------------------------------------------------------------------------------
// Each decoder reads a primitive: one time in eight every field is any number (invalid and
// hostile primitives must be rejected, never crash); otherwise a usable shape in a Frame.
template <class T>
bool raw_fields(ByteReader& in) { return in.byte() < 32; }

template <class T>
Sphere<T> decode_sphere(ByteReader& in)
{
    if (raw_fields<T>(in)) return {any_vec<T>(in), any_number<T>(in)};
    const Frame<T> f = Frame<T>::read(in);
    return {f.point(in), f.positive(in)};
}
template <class T>
Plane<T> decode_plane(ByteReader& in)
{
    if (raw_fields<T>(in)) return {any_vec<T>(in), any_vec<T>(in)};
    const Frame<T> f = Frame<T>::read(in);
    const Vec3<T> n{T(in.signed_unit()), T(in.signed_unit()), T(in.byte() < 64 ? 0.0 : in.signed_unit())};
    return {f.point(in), n};
}
template <class T>
Disk<T> decode_disk(ByteReader& in)
{
    if (raw_fields<T>(in)) return {any_vec<T>(in), any_vec<T>(in), any_number<T>(in)};
    const Frame<T> f = Frame<T>::read(in);
    return {f.point(in), Vec3<T>{T(in.signed_unit()), T(in.signed_unit()), T(in.signed_unit())}, f.positive(in)};
}
template <class T>
Parallelogram<T> decode_parallelogram(ByteReader& in)
{
    if (raw_fields<T>(in)) return {any_vec<T>(in), any_vec<T>(in), any_vec<T>(in)};
    const Frame<T> f = Frame<T>::read(in);
    const Vec3<T> corner = f.point(in), e0 = f.vector(in);
    Vec3<T> e1 = f.vector(in);
    if (in.byte() < 32) {  // a sliver
        const T stretch = T(1 + in.tiny(7));
        e1 = e0 * stretch + Vec3<T>{T(in.tiny(7) * f.scale), 0, 0};
    }
    return {corner, e0, e1};
}
template <class T>
Triangle<T> decode_triangle(ByteReader& in)
{
    if (raw_fields<T>(in)) return {any_vec<T>(in), any_vec<T>(in), any_vec<T>(in)};
    const Frame<T> f = Frame<T>::read(in);
    const Vec3<T> a = f.point(in), b = f.point(in);
    Vec3<T> c = f.point(in);
    if (in.byte() < 32) {  // a sliver
        const T along = T(in.unit());
        c = a + (b - a) * along + Vec3<T>{0, T(in.tiny(7) * f.scale), 0};
    }
    return {a, b, c};
}
template <class T>
Caps decode_caps(ByteReader& in) { return in.byte() & 1 ? Caps::both : Caps::none; }
template <class T>
Cylinder<T> decode_cylinder(ByteReader& in)
{
    if (raw_fields<T>(in)) return {any_vec<T>(in), any_vec<T>(in), any_number<T>(in), decode_caps<T>(in)};
    const Frame<T> f = Frame<T>::read(in);
    const Vec3<T> p0 = f.point(in);
    Vec3<T> axis = f.vector(in);
    if (in.byte() < 64) axis = {T(0), T(0), axis.z};  // axis-aligned: exact ties
    return {p0, p0 + axis, f.positive(in), decode_caps<T>(in)};
}
template <class T>
Cone<T> decode_cone(ByteReader& in)
{
    if (raw_fields<T>(in)) return {any_vec<T>(in), any_number<T>(in), any_vec<T>(in), any_number<T>(in), decode_caps<T>(in)};
    const Frame<T> f = Frame<T>::read(in);
    const Vec3<T> p0 = f.point(in);
    Vec3<T> axis = f.vector(in);
    if (in.byte() < 64) axis = {T(0), T(0), axis.z};
    T r0 = f.positive(in), r1 = f.positive(in);
    const std::uint8_t apex = in.byte();
    if (apex < 96) r0 = T(0);  // an apex at p0
    else if (apex < 128) r1 = T(0);
    else if (apex < 144) r1 = r0;  // a cylinder in disguise
    return {p0, r0, p0 + axis, r1, decode_caps<T>(in)};
}
template <class T>
Quadric<T> decode_quadric(ByteReader& in)
{
    const std::uint8_t kind = in.byte();
    if (kind < 24) {  // every coefficient and the clip box: any numbers
        Quadric<T> q{any_number<T>(in), any_number<T>(in), any_number<T>(in), any_number<T>(in), any_number<T>(in),
                     any_number<T>(in), any_number<T>(in), any_number<T>(in), any_number<T>(in), any_number<T>(in)};
        if (in.byte() & 1) q.clip = {any_vec<T>(in), any_vec<T>(in)};
        return q;
    }
    const Frame<T> f = Frame<T>::read(in);
    const Vec3<T> c = f.point(in);
    const T a = f.positive(in), b = f.positive(in), cc = f.positive(in), h = f.positive(in) * 2;
    Quadric<T> q;
    switch (kind % 7) {
    case 0: {
        const Vec3<T> axis_x{T(in.signed_unit()), T(in.signed_unit()), T(1)};
        const Vec3<T> axis_y{T(1), T(in.signed_unit()), T(in.signed_unit())};
        q = Quadric<T>::ellipsoid(c, Vec3<T>{a, b, cc}, axis_x, axis_y);
        break;
    }
    case 1: q = Quadric<T>::elliptic_paraboloid(c, a, b, cc, h); break;
    case 2: q = Quadric<T>::hyperboloid_one_sheet(c, a, b, cc, h); break;
    case 3: q = Quadric<T>::hyperboloid_two_sheets(c, a, b, cc, h); break;
    case 4: q = Quadric<T>::elliptic_cone(c, a, b, cc, h); break;
    case 5: q = Quadric<T>::ellipsoid(c, Vec3<T>{a, b, cc}); break;  // axis-aligned: exact ties
    default: {  // small integer coefficients: degenerate and exactly representable shapes (planes pairs, cylinders)
        T k[10];
        for (T& v : k) v = T(int(in.byte() % 7) - 3);
        q = {k[0], k[1], k[2], k[3], k[4], k[5], k[6], k[7], k[8], k[9]};
    }
    }
    const std::uint8_t clip = in.byte();
    if (clip < 64) {  // a clip box face through the shape: the near root clipped, the far one counts
        const T cut = T(c.z + f.scale * in.signed_unit());
        if (clip & 1) q.clip.lo.z = cut; else q.clip.hi.z = cut;
    }
    return q;
}

template <class T>
Affine3<T> decode_affine(ByteReader& in)
{
    const std::uint8_t kind = in.byte();
    Affine3<T> m = Affine3<T>::identity();
    if (kind < 24) {  // any numbers
        for (auto& row : m.m)
            for (T& v : row) v = any_number<T>(in);
        return m;
    }
    const Frame<T> f = Frame<T>::read(in);
    const Vec3<T> axis{T(in.signed_unit()), T(in.signed_unit()), T(in.signed_unit() + 0.01)};
    const T angle = T(3.14159 * in.signed_unit());
    m = Affine3<T>::rotation(axis, angle, f.point(in));
    if (kind % 3 != 0) {  // anisotropic scaling, sometimes extreme
        const auto s = [&] {
            const double magnitude = in.byte() < 32 ? in.tiny(kind % 2 ? 6 : 3) : 0.2 + 2 * in.unit();
            return T(magnitude * (in.byte() & 1 ? -1 : 1));
        };
        m = m * Affine3<T>::scaling(Vec3<T>{s(), s(), s()});
    }
    if (kind % 5 == 0) m.m[0][1] += T(in.signed_unit());  // a shear
    return m;
}

// ---- families -------------------------------------------------------------------------------------
// visit(case) is called once with the decoded Case<Prim> (a concrete type, so a harness only
// instantiates its own family).
template <class T, class Visit>
void decode_flat(ByteReader& in, std::uint8_t which, Visit&& visit)
{
    switch (which % 4) {
    case 0: { const auto p = decode_plane<T>(in); visit(make_case(p, in)); break; }
    case 1: { const auto p = decode_disk<T>(in); visit(make_case(p, in)); break; }
    case 2: { const auto p = decode_parallelogram<T>(in); visit(make_case(p, in)); break; }
    default: { const auto p = decode_triangle<T>(in); visit(make_case(p, in)); break; }
    }
}
template <class T, class Visit>
void decode_axial(ByteReader& in, std::uint8_t which, Visit&& visit)
{
    if (which % 2 == 0) { const auto p = decode_cylinder<T>(in); visit(make_case(p, in)); }
    else { const auto p = decode_cone<T>(in); visit(make_case(p, in)); }
}
template <class T, class Visit>
void decode_transformed(ByteReader& in, std::uint8_t which, Visit&& visit)
{
    const auto place = [&](const auto& object) {
        using Prim = std::decay_t<decltype(object)>;
        const Affine3<T> to_world = decode_affine<T>(in);
        Transformed<Prim> x = transformed(object, to_world);
        const std::uint8_t inverse = in.byte();
        if (inverse < 16) x.to_object.m[inverse % 3][inverse % 4] = any_number<T>(in);  // a stored inverse that lies
        visit(make_case(x, in));
    };
    switch (which % 8) {
    case 0: place(decode_sphere<T>(in)); break;
    case 1: place(decode_plane<T>(in)); break;
    case 2: place(decode_disk<T>(in)); break;
    case 3: place(decode_parallelogram<T>(in)); break;
    case 4: place(decode_triangle<T>(in)); break;
    case 5: place(decode_cylinder<T>(in)); break;
    case 6: place(decode_cone<T>(in)); break;
    default: place(decode_quadric<T>(in)); break;
    }
}

template <Harness H, class T, class Visit>
void decode_as(ByteReader& in, std::uint8_t which, Visit&& visit)
{
    if constexpr (H == Harness::flat) decode_flat<T>(in, which, visit);
    else if constexpr (H == Harness::sphere) { const auto s = decode_sphere<T>(in); visit(make_case(s, in)); }
    else if constexpr (H == Harness::axial) decode_axial<T>(in, which, visit);
    else if constexpr (H == Harness::quadric) { const auto q = decode_quadric<T>(in); visit(make_case(q, in)); }
    else decode_transformed<T>(in, which, visit);
}

// The whole input: byte 0 picks float or double (bit 0) and the primitive (the rest). The
// harness is a template parameter so that a fuzzer instantiates only its own family.
template <Harness H, class Visit>
void decode(const std::uint8_t* data, std::size_t size, Visit&& visit)
{
    ByteReader in(data, size);
    const std::uint8_t head = in.byte();
    if (head & 1) decode_as<H, float>(in, std::uint8_t(head >> 1), visit);
    else decode_as<H, double>(in, std::uint8_t(head >> 1), visit);
}

// The same with the harness chosen at run time (the replay test: every family in one program).
template <class Visit>
void decode(Harness h, const std::uint8_t* data, std::size_t size, Visit&& visit)
{
    switch (h) {
    case Harness::flat: decode<Harness::flat>(data, size, visit); break;
    case Harness::sphere: decode<Harness::sphere>(data, size, visit); break;
    case Harness::axial: decode<Harness::axial>(data, size, visit); break;
    case Harness::quadric: decode<Harness::quadric>(data, size, visit); break;
    case Harness::transformed: decode<Harness::transformed>(data, size, visit); break;
    }
}

}  // namespace rayq::fuzz
