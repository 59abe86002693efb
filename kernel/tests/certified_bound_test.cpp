// Hit::t_error is certified: the exact root lies within it. The reference refines the kernel's t by
// Newton's method on each primitive's implicit function evaluated in binary128 (a formulation
// written here, not the kernel's), so it finds the exact root of the same float/double inputs to
// ~1e-30 relative wherever the root is simple.
#include "test_support.hpp"

#include <random>

namespace rayq::test {
namespace {

__extension__ typedef __float128 quad;

struct Q3 {
    quad x, y, z;
};
Q3 operator+(Q3 a, Q3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
Q3 operator-(Q3 a, Q3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
Q3 operator*(quad s, Q3 a) { return {s * a.x, s * a.y, s * a.z}; }
quad qdot(Q3 a, Q3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
Q3 qcross(Q3 a, Q3 b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
quad qabs(quad x) { return x < 0 ? -x : x; }
template <class T>
Q3 q3(const Vec3<T>& v) { return {quad(v.x), quad(v.y), quad(v.z)}; }

// F(o + t·d) for the exact primitive: what the root of means "the exact t".
template <class T>
quad implicit(const Sphere<T>& s, Q3 o, Q3 d, quad t, Part)
{
    const Q3 q = o - q3(s.center) + t * d;
    return qdot(q, q) - quad(s.radius) * quad(s.radius);
}
quad axial_plane(Q3 end, Q3 axis, Q3 o, Q3 d, quad t) { return qdot(o + t * d - end, axis); }
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

template <class C>
class CertifiedBoundTest : public ::testing::Test {};
TYPED_TEST_SUITE(CertifiedBoundTest, AllConfigs, ConfigNames);

template <class Policy, class Prim>
void check_bound(Policy policy, const Prim& prim, const char* name, std::uint64_t seed)
{
    using T = scalar_t<Prim>;
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> u(-1, 1), lg(-2, 2);
    int hits = 0, violations = 0, infinite = 0;
    double worst_ratio = 0;  // t_error / |t − t_exact|: how conservative (reported, not asserted)
    std::vector<double> ratios;
    for (int i = 0; i < 20000; ++i) {
        const double scale = std::pow(10.0, lg(rng));
        const Vec3<T> o{T(4 * u(rng)), T(4 * u(rng)), T(4 * u(rng))};
        const Vec3<T> aim{T(1.2 * u(rng)), T(1.2 * u(rng)), T(1.2 * u(rng))};
        const Vec3<T> d{T((aim.x - o.x) * scale), T((aim.y - o.y) * scale), T((aim.z - o.z) * scale)};
        const Ray<T> r{o, d};
        const auto h = intersect(policy, r, prim);
        if (!h) continue;
        ++hits;
        if (!std::isfinite(h->t_error)) {
            ++infinite;
            continue;
        }
        const quad exact = refine(prim, q3(o), q3(d), quad(h->t), h->part);
        const quad err = qabs(quad(h->t) - exact);
        if (err > quad(h->t_error)) {
            ++violations;
            ADD_FAILURE() << name << " ray " << i << ": |t - t_exact| = " << double(err) << " > t_error = " << h->t_error;
        }
        if (err > 0) ratios.push_back(double(quad(h->t_error) / err));
        // The point bound follows from it: |point − exact point| per component.
        const Q3 p_exact = q3(o) + exact * q3(d);
        EXPECT_LE(double(qabs(quad(h->point.x) - p_exact.x)), double(h->point_error.x)) << name << " ray " << i;
        EXPECT_LE(double(qabs(quad(h->point.y) - p_exact.y)), double(h->point_error.y)) << name << " ray " << i;
        EXPECT_LE(double(qabs(quad(h->point.z) - p_exact.z)), double(h->point_error.z)) << name << " ray " << i;
    }
    std::sort(ratios.begin(), ratios.end());
    if (!ratios.empty()) worst_ratio = ratios.front();
    std::printf("t_error %-22s %-6s %-8s hits=%5d violations=%d uncertified=%d bound/actual median=%.3g p99=%.3g min=%.3g\n", name,
                std::is_same_v<T, float> ? "float" : "double", ConfigNames::GetName<Config<T, Policy>>(0).c_str() + (std::is_same_v<T, float> ? 6 : 7),
                hits, violations, infinite, ratios.empty() ? 0.0 : ratios[ratios.size() / 2],
                ratios.empty() ? 0.0 : ratios[ratios.size() * 99 / 100], worst_ratio);
    EXPECT_GT(hits, 1000) << name;
    EXPECT_LT(infinite, hits / 100 + 1) << name << ": the certificate should fail only near tangency";
}

TYPED_TEST(CertifiedBoundTest, ExactRootLiesWithinTError)
{
    using T = typename TypeParam::T;
    const auto p = TypeParam::policy;
    check_bound(p, Sphere<T>{v3<T>(0.1, -0.2, 0.3), T(1)}, "sphere", 1);
    check_bound(p, Plane<T>{v3<T>(0.1, 0.2, 0.3), v3<T>(0.3, -1, 0.7)}, "plane", 2);
    check_bound(p, Disk<T>{v3<T>(0.1, 0.2, 0.3), v3<T>(0.3, -1, 0.7), T(1.1)}, "disk", 3);
    check_bound(p, Parallelogram<T>{v3<T>(-1, -0.9, 0.1), v3<T>(2, 0.3, 0.1), v3<T>(0.2, 1.8, -0.4)}, "parallelogram", 4);
    check_bound(p, Triangle<T>{v3<T>(-1, -0.9, 0.1), v3<T>(1.3, -0.2, 0.3), v3<T>(0.2, 1.4, -0.4)}, "triangle", 5);
    check_bound(p, Cylinder<T>{v3<T>(-0.3, -0.6, -0.9), v3<T>(0.5, 0.4, 0.8), T(0.7), Caps::both}, "cylinder capped", 6);
    check_bound(p, Cylinder<T>{v3<T>(-0.3, -0.6, -0.9), v3<T>(0.5, 0.4, 0.8), T(0.7), Caps::none}, "cylinder open", 7);
    check_bound(p, Cone<T>{v3<T>(-0.3, -0.6, -0.9), T(0.9), v3<T>(0.5, 0.4, 0.8), T(0.2), Caps::both}, "cone frustum", 8);
    check_bound(p, Cone<T>{v3<T>(-0.3, -0.6, -0.9), T(1), v3<T>(0.5, 0.4, 0.8), T(0), Caps::both}, "cone apex", 9);
    check_bound(p, Quadric<T>::ellipsoid(v3<T>(0.1, 0, -0.1), v3<T>(1.2, 0.7, 0.9), v3<T>(1, 1, 0), v3<T>(-1, 1, 0.5)), "ellipsoid", 10);
    check_bound(p, Quadric<T>::hyperboloid_one_sheet(v3<T>(0, 0, 0), T(0.5), T(0.6), T(0.8), T(1)), "hyperboloid1", 11);
    check_bound(p, transformed(Sphere<T>{v3<T>(0, 0, 0), T(1)},
                               Affine3<T>::rotation(v3<T>(1, 2, 3), T(0.3), v3<T>(0.1, 0.2, 0.3)) * Affine3<T>::scaling(v3<T>(1.1, 0.6, 0.9))),
                "transformed sphere", 12);
    check_bound(p, transformed(Cylinder<T>{v3<T>(0, 0, -1), v3<T>(0, 0, 1), T(0.5), Caps::both},
                               Affine3<T>::rotation(v3<T>(-1, 2, 0.5), T(1.1), v3<T>(0.1, -0.2, 0))),
                "transformed cylinder", 13);
}

}  // namespace
}  // namespace rayq::test
