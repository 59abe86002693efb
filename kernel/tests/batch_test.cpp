// The batch paths of the bounded primitives (batch/bounding_sphere.hpp): the bounding-sphere filter
// never drops a primitive that some policy hits — on rays grazing the primitive's curved side, rays
// nearly parallel to its flat parts, rays far away and translated far from the origin — and both
// batch patterns (one ray against many primitives in a Scene, many rays against one primitive)
// answer exactly what the scalar queries answer, bit for bit, for every policy and type.
#include <bitset>
#include <cstdint>
#include <functional>
#include <random>
#include <tuple>
#include <typeinfo>

#include <rayq/batch/bounding_sphere.hpp>
#include <rayq/scene.hpp>

#include "test_support.hpp"

namespace rayq::test::batch_test {
namespace {

template <class C>
class BatchTest : public ::testing::Test {};
TYPED_TEST_SUITE(BatchTest, AllConfigs, ConfigNames);

using V = Vec3<double>;

// The filters as the scene and batch::intersect call them for Prim under Policy (the scene's ray
// checks the direction's exact range only for the exact test: SceneStore::filter_ray).
template <class Policy, class Prim, class T>
batch::BoundFilterRay<T> scene_filter_ray(const Ray<T>& ray)
{
    return batch::BoundFilterRay<T>(ray, batch::bound_test_v<Policy, Prim> == batch::BoundTest::exact);
}
template <class Policy, class Prim, class T>
std::uint32_t scene_candidates(const batch::BoundFilterRay<T>& f, const Ray<T>& ray, const batch::BoundSoA<T>& soa, std::size_t g)
{
    return batch::bound_candidates<Policy, batch::bound_test_v<Policy, Prim>>(f, ray.tmin, ray.tmax, soa, g);
}
// The scene's skip of a whole lane group by the line test alone (SceneStore::scan_filtered).
template <class Policy, class Prim, class T>
bool scene_skips_group(const Ray<T>& ray, const batch::BoundSoA<T>& soa, std::size_t g)
{
    return batch::line_passes_group<batch::bound_test_v<Policy, Prim>>(scene_filter_ray<Policy, Prim>(ray), soa, g);
}
template <class Policy, class Prim, class T>
std::uint32_t stream_candidates(const batch::RayStream<T>& stream, std::size_t g, const batch::BoundingSphere<T>& b)
{
    return batch::ray_candidates<Policy, batch::bound_test_v<Policy, Prim>>(stream, g, batch::PrimitiveBound<T>(b));
}

// A point on a primitive's surface with two tangent directions there (double, before rounding).
struct SurfacePoint {
    V point, t1, t2;
};

struct Gen : Random {
    using Random::Random;

    // A primitive of each kind somewhere in a box of half-size `extent` around `offset`.
    template <class T>
    void make(Disk<T>& d, const V& at, double size) { d = {scalar_cast<T>(at), scalar_cast<T>(unit_vector()), T(size)}; }
    template <class T>
    void make(Triangle<T>& t, const V& at, double size)
    {
        t = {scalar_cast<T>(at + unit_vector() * size), scalar_cast<T>(at + unit_vector() * size), scalar_cast<T>(at + unit_vector() * size)};
    }
    template <class T>
    void make(Parallelogram<T>& p, const V& at, double size)
    {
        p = {scalar_cast<T>(at), scalar_cast<T>(unit_vector() * size), scalar_cast<T>(unit_vector() * (size * uniform(0.2, 1.5)))};
    }
    template <class T>
    void make(Cylinder<T>& c, const V& at, double size)
    {
        c = {scalar_cast<T>(at), scalar_cast<T>(at + unit_vector() * (size * uniform(0.3, 3))), T(size * log_uniform(0.05, 1)),
             uniform(0, 1) < 0.5 ? Caps::both : Caps::none};
    }
    template <class T>
    void make(Cone<T>& c, const V& at, double size)
    {
        const bool apex = uniform(0, 1) < 0.3;
        c = {scalar_cast<T>(at), T(size * log_uniform(0.05, 1)), scalar_cast<T>(at + unit_vector() * (size * uniform(0.3, 3))),
             apex ? T(0) : T(size * log_uniform(0.05, 1)), uniform(0, 1) < 0.5 ? Caps::both : Caps::none};
    }

    // A point on the surface (flat parts: inside or on the rim; axial: on the side or a rim).
    template <class T>
    SurfacePoint on(const Disk<T>& d)
    {
        const V n = scalar_cast<double>(d.normal) / length(scalar_cast<double>(d.normal)), e = perpendicular(n);
        const double s = uniform(0, 1) < 0.5 ? 1.0 : std::sqrt(uniform(0, 1));
        return {scalar_cast<double>(d.center) + e * (double(d.radius) * s), e, cross(n, e)};
    }
    template <class T>
    SurfacePoint on(const Triangle<T>& t)
    {
        const V a = scalar_cast<double>(t.a), b = scalar_cast<double>(t.b), c = scalar_cast<double>(t.c);
        double u = uniform(0, 1), v = uniform(0, 1);
        if (u + v > 1) u = 1 - u, v = 1 - v;
        if (uniform(0, 1) < 0.5) v = 0;  // on an edge
        const V e = (b - a) / length(b - a);
        const V n = cross(b - a, c - a);
        return {a + (b - a) * u + (c - a) * v, e, cross(n / length(n), e)};
    }
    template <class T>
    SurfacePoint on(const Parallelogram<T>& p)
    {
        const V e0 = scalar_cast<double>(p.edge0), e1 = scalar_cast<double>(p.edge1);
        const double u = uniform(0, 1), v = uniform(0, 1) < 0.5 ? 1.0 : uniform(0, 1);
        const V n = cross(e0, e1);
        return {scalar_cast<double>(p.corner) + e0 * u + e1 * v, e0 / length(e0), cross(n / length(n), e0 / length(e0))};
    }
    SurfacePoint axial(const V& p0, double r0, const V& p1, double r1)
    {
        const V axis = (p1 - p0) / length(p1 - p0), e1 = perpendicular(axis), e2 = cross(axis, e1);
        const double s = uniform(0, 1) < 0.3 ? (uniform(0, 1) < 0.5 ? 0.0 : 1.0) : uniform(0, 1);
        const double phi = uniform(0, 6.283185307179586);
        const V radial = e1 * std::cos(phi) + e2 * std::sin(phi);
        const double r = r0 + (r1 - r0) * s;
        const V point = p0 + (p1 - p0) * s + radial * r;
        const V around = cross(axis, radial);                      // tangent along the circle
        const V along = (p1 - p0) + radial * (r1 - r0);            // tangent along the generator
        return {point, around, along / length(along)};
    }
    template <class T>
    SurfacePoint on(const Cylinder<T>& c) { return axial(scalar_cast<double>(c.p0), double(c.radius), scalar_cast<double>(c.p1), double(c.radius)); }
    template <class T>
    SurfacePoint on(const Cone<T>& c) { return axial(scalar_cast<double>(c.p0), double(c.r0), scalar_cast<double>(c.p1), double(c.r1)); }

    // A ray that stresses the filter near `prim`: along a tangent of its surface tilted by ±10^-k
    // out of it (grazing a curved side, nearly parallel to a flat part), from near or far; or a
    // random ray; with an odd direction length and windows at times.
    template <class T, class Prim>
    Ray<T> ray_near(const Prim& prim, double extent)
    {
        const int kind = std::uniform_int_distribution<int>(0, 5)(rng);
        const SurfacePoint s = on(prim);
        V o, d;
        if (kind == 0) {
            o = V{uniform(-2, 2), uniform(-2, 2), uniform(-2, 2)} * extent + s.point;
            d = unit_vector();
        } else {
            // kind 5: along t2 (an axial primitive's generator, where its quadratic degenerates).
            const double phi = kind == 5 ? 1.5707963267948966 : uniform(0, 6.283185307179586);
            const V tangent = s.t1 * std::cos(phi) + s.t2 * std::sin(phi);
            V n = cross(s.t1, s.t2);
            n = n / length(n);
            const int k = std::uniform_int_distribution<int>(1, std::is_same_v<T, float> ? 7 : 15)(rng);
            d = tangent + n * ((uniform(0, 1) < 0.5 ? -1 : 1) * std::pow(10.0, -k));
            const double distance = kind == 2 ? log_uniform(1e2, 1e6) * extent : uniform(0, 3) * extent;
            o = s.point - d * distance + n * (uniform(0, 1) < 0.2 ? uniform(-1e-6, 1e-6) * extent : 0.0);
        }
        if (kind == 3) d = d * log_uniform(1e-12, 1e12);
        Ray<T> out{scalar_cast<T>(o), scalar_cast<T>(d)};
        if (uniform(0, 1) < 0.2) out.tmin = -out.tmax;
        return out;
    }
};

// The bounded primitives with a bounding-sphere filter, for one scalar type.
template <class T>
using Bounded = std::tuple<Disk<T>, Triangle<T>, Parallelogram<T>, Cylinder<T>, Cone<T>>;

template <class F, class... Prims>
void each_type(F f, std::tuple<Prims...>*) { (f(static_cast<Prims*>(nullptr)), ...); }

template <class T>
void expect_same(const std::optional<Hit<T>>& a, const std::optional<Hit<T>>& b)
{
    ASSERT_EQ(a.has_value(), b.has_value());
    if (!a) return;
    EXPECT_TRUE(same_bits(a->t, b->t)) << a->t << " vs " << b->t;
    EXPECT_EQ(a->point, b->point);
    EXPECT_EQ(a->normal, b->normal);
    EXPECT_EQ(a->part, b->part);
    EXPECT_EQ(a->front_face, b->front_face);
    EXPECT_TRUE(same_bits(a->t_error, b->t_error));
}

// The bounding sphere holds the primitive: sampled surface points lie inside it.
TYPED_TEST(BatchTest, BoundingSpheresHoldTheirPrimitives)
{
    using T = typename TypeParam::T;
    Gen g(0xB0D5 + sizeof(T));
    each_type(
        [&](auto* tag) {
            using Prim = std::remove_pointer_t<decltype(tag)>;
            for (int i = 0; i < 200; ++i) {
                Prim prim;
                g.make(prim, g.unit_vector() * g.log_uniform(1e-3, 1e4), g.log_uniform(1e-3, 1e3));
                const batch::BoundingSphere<T> b = batch::bounding_sphere(prim);
                for (int k = 0; k < 20; ++k) {
                    const V p = g.on(prim).point;
                    const double distance = length(p - scalar_cast<double>(b.center));
                    // The center is rounded to T: the filter's Kε·|c|₁ slack covers that.
                    const double slack = 4 * std::numeric_limits<T>::epsilon() * length(scalar_cast<double>(b.center)) + 1e-300;
                    EXPECT_LE(distance, double(b.radius) * (1 + 1e-12) + slack) << typeid(Prim).name();
                }
            }
        },
        static_cast<Bounded<T>*>(nullptr));
}

// Every primitive the policy hits in the ray's window is kept; most of the scattered others are
// culled. (Cones under fast and stable are not filtered: bound_filter_exact_v.)
TYPED_TEST(BatchTest, FilterNeverDropsAHit)
{
    using T = typename TypeParam::T;
    Gen g(0xB0D6 + sizeof(T));
    each_type(
        [&](auto* tag) {
            using Prim = std::remove_pointer_t<decltype(tag)>;
            using Policy = std::decay_t<decltype(TypeParam::policy)>;
            if constexpr (!batch::bound_filter_exact_v<Policy, Prim>) return;
            SCOPED_TRACE(typeid(Prim).name());
            std::size_t kept = 0, lanes = 0, hits = 0, skipped_groups = 0, passed_lanes = 0, line_kept = 0;
            for (int scene = 0; scene < 24; ++scene) {
                // Far from the origin at times: the hit point's rounding grows with |o| and |c|.
                const V offset = scene % 3 == 0 ? g.unit_vector() * g.log_uniform(1e2, 1e5) : V{0, 0, 0};
                std::vector<Prim> prims(48);
                batch::BoundSoA<T> soa;
                for (Prim& p : prims) {
                    g.make(p, offset + V{g.uniform(-10, 10), g.uniform(-10, 10), g.uniform(-10, 10)}, g.log_uniform(0.01, 2));
                    soa.push_back(p);
                }
                for (int k = 0; k < 120; ++k) {
                    Ray<T> ray = g.ray_near<T>(prims[std::size_t(k) % prims.size()], 10.0);
                    if (k % 3 == 1) {  // a window that may end before, between or after the primitives
                        ray.tmin = T(g.uniform(0, 20));
                        ray.tmax = ray.tmin + T(g.log_uniform(1e-3, 30));
                    } else if (k % 3 == 2) {  // a window just around the aimed-at primitive's hit
                        if (const auto h = intersect(TypeParam::policy, ray, prims[std::size_t(k) % prims.size()])) {
                            ray.tmin = std::nextafter(h->t, T(0));
                            ray.tmax = std::nextafter(h->t, std::numeric_limits<T>::infinity());
                        }
                    }
                    if (!usable(ray)) continue;
                    const batch::BoundFilterRay<T> f = scene_filter_ray<Policy, Prim>(ray);
                    for (std::size_t grp = 0; grp < soa.groups(); ++grp) {
                        const std::uint32_t m = scene_candidates<Policy, Prim>(f, ray, soa, grp);
                        const bool skipped = scene_skips_group<Policy, Prim>(ray, soa, grp);
                        skipped_groups += skipped;
                        kept += std::bitset<32>(m).count();
                        // The scene walks the line test's lanes and visits those candidates() keeps
                        // (SceneStore::scan_filtered): every candidate must be among them.
                        if constexpr (batch::bound_test_v<Policy, Prim> != batch::BoundTest::line) {
                            const std::uint32_t line = batch::bound_line_candidates<batch::bound_test_v<Policy, Prim>>(f, soa, grp);
                            EXPECT_EQ(m & ~line, 0u) << "a candidate the line test drops, group " << grp;
                            line_kept += std::bitset<32>(line).count();
                        }
                        for (int lane = 0; lane < batch::BoundSoA<T>::width; ++lane) {
                            const std::size_t i = grp * batch::BoundSoA<T>::width + std::size_t(lane);
                            if (i >= prims.size()) break;
                            ++lanes;
                            const bool hit = occluded(TypeParam::policy, ray, prims[i]);
                            hits += hit;
                            // The one-lane line test of scenes of one or two primitives (SceneStore::scan).
                            const bool passed = batch::line_passes_bound<batch::bound_test_v<Policy, Prim>>(f, soa, i);
                            passed_lanes += passed;
                            if (hit) {
                                EXPECT_TRUE(m >> lane & 1u) << "dropped primitive " << i << " that the policy hits";
                                EXPECT_FALSE(skipped) << "the line test skipped the group of primitive " << i << ", which the policy hits";
                                EXPECT_FALSE(passed) << "the one-lane line test passed primitive " << i << ", which the policy hits";
                            }
                        }
                    }
                }
            }
            EXPECT_GT(hits, 0u);
            EXPECT_LT(kept, lanes / 2) << "kept " << kept << " of " << lanes << " lanes (" << hits << " hits)";
            // Skipping is exercised only where a group can be passed whole (narrow SIMD lanes).
            if (batch::bound_test_v<Policy, Prim> != batch::BoundTest::line && batch::BoundSoA<T>::width <= 4) {
                EXPECT_GT(skipped_groups, 0u);
            }
            if (batch::bound_test_v<Policy, Prim> != batch::BoundTest::line) {
                EXPECT_GT(passed_lanes, lanes / 2);
                // The line test alone culls too (the window test only narrows what it keeps).
                EXPECT_GE(line_kept, kept);
                EXPECT_LT(line_kept, lanes / 2) << "the line test kept " << line_kept << " of " << lanes << " lanes";
            }
        },
        static_cast<Bounded<T>*>(nullptr));
}

// Slivers seen edge-on: triangles and parallelograms of aspect up to 10/ε, and lines nearly in their
// plane passing beside them. fast and stable then decide inside on rounding noise and may report a
// hit far from the primitive (the fuzz harnesses found one on a float sliver); the filter's plane
// test must keep every such lane, in both batch patterns.
TYPED_TEST(BatchTest, FilterKeepsSliversSeenEdgeOn)
{
    using T = typename TypeParam::T;
    using Policy = std::decay_t<decltype(TypeParam::policy)>;
    Gen g(0xB0D8 + sizeof(T));
    std::size_t hits = 0;
    const auto check = [&](const auto& prim, const V& center, const V& normal, const V& along, double size) {
        using Prim = std::decay_t<decltype(prim)>;
        const batch::BoundingSphere<T> b = batch::bounding_sphere(prim);
        batch::BoundSoA<T> soa;
        soa.push_back(prim);
        for (int k = 0; k < 64; ++k) {
            // In the plane, beside the primitive, tilted out of it by 10^-12 .. 10^-1 radians.
            const V side = g.perpendicular(normal);
            const V at = center + side * (size * g.log_uniform(0.01, 30)) + along * (size * g.uniform(-2, 2));
            const V in_plane = g.perpendicular(normal);
            const V dir = in_plane + normal * ((g.uniform(0, 1) < 0.5 ? -1.0 : 1.0) * g.log_uniform(1e-12, 1e-1));
            const Ray<T> ray{scalar_cast<T>(at - dir * (size * g.log_uniform(1, 100))), scalar_cast<T>(dir)};
            if (!usable(ray)) continue;
            const bool hit = occluded(TypeParam::policy, ray, prim);
            hits += hit;
            if (!hit) continue;
            const batch::BoundFilterRay<T> f = scene_filter_ray<Policy, Prim>(ray);
            EXPECT_TRUE((scene_candidates<Policy, Prim>(f, ray, soa, 0) & 1u)) << typeid(Prim).name() << " scene filter dropped a hit";
            batch::RayStream<T> stream;
            stream.push_back(ray);
            EXPECT_TRUE((stream_candidates<Policy, Prim>(stream, 0, b) & 1u)) << typeid(Prim).name() << " stream filter dropped a hit";
        }
    };
    for (int i = 0; i < 200; ++i) {
        const double size = g.log_uniform(1e-2, 1e2), aspect = g.log_uniform(1, 10 / std::numeric_limits<T>::epsilon());
        const V center = g.unit_vector() * g.log_uniform(1e-3, 1e3), normal = g.unit_vector(), along = g.perpendicular(normal);
        const V across = cross(normal, along);
        // A sliver: long along `along`, 1/aspect as wide.
        const Triangle<T> tri{scalar_cast<T>(center - along * size), scalar_cast<T>(center + along * size),
                              scalar_cast<T>(center + along * (size * g.uniform(-1, 1)) + across * (size / aspect))};
        if (validate(tri)) check(tri, center, normal, along, size);
        const Parallelogram<T> par{scalar_cast<T>(center - along * size), scalar_cast<T>(along * (2 * size)),
                                   scalar_cast<T>(along * (size * g.uniform(-1, 1)) + across * (size / aspect))};
        if (validate(par)) check(par, center, normal, along, size);
    }
    EXPECT_GT(hits, 0u);
}

// A lane group that is only partly filled (the rest padding) is skipped whole by the line test when
// the line passes its primitives by far, as a full group is: a scene of one cylinder once ran the
// candidate test for every ray, its padding lanes counted as out of range.
TYPED_TEST(BatchTest, PartlyFilledGroupIsSkippedByTheLineTest)
{
    using T = typename TypeParam::T;
    using Policy = std::decay_t<decltype(TypeParam::policy)>;
    using Prim = Cylinder<T>;
    const Prim cylinder{{T(5), T(5), T(4)}, {T(5), T(5), T(6)}, T(0.5), Caps::both};
    batch::BoundSoA<T> soa;
    soa.push_back(cylinder);
    ASSERT_EQ(soa.groups(), 1u);
    // Beside the cylinder, far from it and from the origin (where padding lanes sit).
    const Ray<T> beside{{T(-20), T(-3), T(20)}, {T(1), T(0.25), T(0)}};
    const Ray<T> through{{T(-20), T(5), T(5)}, {T(1), T(0), T(0)}};
    ASSERT_FALSE(occluded(TypeParam::policy, beside, cylinder));
    ASSERT_TRUE(occluded(TypeParam::policy, through, cylinder));
    EXPECT_TRUE((scene_skips_group<Policy, Prim>(beside, soa, 0)));
    EXPECT_FALSE((scene_skips_group<Policy, Prim>(through, soa, 0)));
}

// Cylinders seen along their axis, where the quadratic's leading coefficient is rounding noise:
// lines tilted off the axis by 10^-12 .. 10^-1 radians, passing inside and beside the cylinder.
// Every hit fast and stable report must lie within the filter's slack of the bounding sphere
// (the header's argument), so both batch patterns keep it. The worst ratio of a hit's excess
// over the bounding sphere (in squared distance) to the filter's slack is printed (and must stay
// below 1).
TYPED_TEST(BatchTest, FilterKeepsCylinderHitsAlongTheAxis)
{
    using T = typename TypeParam::T;
    using Policy = std::decay_t<decltype(TypeParam::policy)>;
    Gen g(0xB0D9 + sizeof(T));
    std::size_t hits = 0, accurate_misses = 0;
    double worst = -std::numeric_limits<double>::infinity();
    for (int i = 0; i < 300; ++i) {
        const double r = g.log_uniform(1e-2, 1e2), h = r * g.log_uniform(0.1, 100);
        const V center = g.unit_vector() * g.log_uniform(1e-3, 1e3), axis = g.unit_vector();
        const Cylinder<T> cyl{scalar_cast<T>(center - axis * (h / 2)), scalar_cast<T>(center + axis * (h / 2)), T(r),
                              g.uniform(0, 1) < 0.5 ? Caps::both : Caps::none};
        if (!validate(cyl)) continue;
        const batch::BoundingSphere<T> b = batch::bounding_sphere(cyl);
        batch::BoundSoA<T> soa;
        soa.push_back(cyl);
        for (int k = 0; k < 32; ++k) {
            const V side = g.perpendicular(axis);
            const V dir = axis + g.perpendicular(axis) * ((g.uniform(0, 1) < 0.5 ? -1.0 : 1.0) * g.log_uniform(1e-12, 1e-1));
            const double beside = k % 2 ? 1 + (g.uniform(0, 1) < 0.5 ? -1 : 1) * g.log_uniform(1e-9, 1e-1) : g.log_uniform(0.5, 30);
            const V at = center + side * (r * beside) - dir * (h * g.uniform(0.6, 10));
            const Ray<T> ray{scalar_cast<T>(at), scalar_cast<T>(dir)};
            if (!usable(ray)) continue;
            const auto hit = intersect(TypeParam::policy, ray, cyl, HitFields::t);
            if (!hit) continue;
            ++hits;
            accurate_misses += !occluded(accurate, ray, cyl);
            // How far outside the bounding sphere the line's point at the reported t lies, in units
            // of ℓ², against the point test's slack 2Kε·(|o − c|² + R²) + 34·(Kε·|o|₁)².
            using W = long double;
            const W t = hit->t;
            W dist2 = 0, u2 = 0, o1 = 0;
            for (int a = 0; a < 3; ++a) {
                const W o = (&ray.origin.x)[a], d = (&ray.direction.x)[a], c = (&b.center.x)[a];
                dist2 += (o + t * d - c) * (o + t * d - c);
                u2 += (o - c) * (o - c);
                o1 += std::abs(o);
            }
            const W k_eps = 256 * W(std::numeric_limits<T>::epsilon());
            const W rr = W(b.radius) * W(b.radius);
            const W slack = 2 * k_eps * (u2 + rr) + 34 * (k_eps * o1) * (k_eps * o1);
            worst = std::max(worst, double((dist2 - rr) / slack));
            const batch::BoundFilterRay<T> f = scene_filter_ray<Policy, Cylinder<T>>(ray);
            EXPECT_TRUE((scene_candidates<Policy, Cylinder<T>>(f, ray, soa, 0) & 1u)) << "scene filter dropped a hit";
            EXPECT_FALSE((scene_skips_group<Policy, Cylinder<T>>(ray, soa, 0))) << "scene's line test skipped a hit";
            EXPECT_FALSE((batch::line_passes_bound<batch::bound_test_v<Policy, Cylinder<T>>>(f, soa, 0))) << "the one-lane line test passed a hit";
            batch::RayStream<T> stream;
            stream.push_back(ray);
            EXPECT_TRUE((stream_candidates<Policy, Cylinder<T>>(stream, 0, b) & 1u)) << "stream filter dropped a hit";
            // The window test: a window just around the reported t keeps it.
            Ray<T> around = ray;
            around.tmin = std::nextafter(hit->t, T(0));
            around.tmax = std::nextafter(hit->t, std::numeric_limits<T>::infinity());
            EXPECT_TRUE((scene_candidates<Policy, Cylinder<T>>(scene_filter_ray<Policy, Cylinder<T>>(around), around, soa, 0) & 1u))
                << "window test dropped a hit";
        }
    }
    std::printf("cylinders along the axis, %s %s: %zu hits (%zu where accurate misses), worst (distance² from the bound − R²)/slack %.3g\n",
                sizeof(T) == 4 ? "float" : "double", typeid(Policy).name(), hits, accurate_misses, worst);
    EXPECT_GT(hits, 100u);
    EXPECT_LT(worst, 1.0);
}

// Many rays against one primitive: batch::intersect / batch::occluded equal the scalar queries.
TYPED_TEST(BatchTest, StreamEqualsTheScalarQueries)
{
    using T = typename TypeParam::T;
    const auto p = TypeParam::policy;
    Gen g(0xB0D7 + sizeof(T));
    each_type(
        [&](auto* tag) {
            using Prim = std::remove_pointer_t<decltype(tag)>;
            SCOPED_TRACE(typeid(Prim).name());
            std::size_t hits = 0, rays = 0;
            for (int n : {1, 5, 37, 300}) {
                Prim prim;
                g.make(prim, g.unit_vector() * g.uniform(0, 3), g.log_uniform(0.1, 2));
                batch::RayStream<T> stream;
                for (int k = 0; k < n; ++k) stream.push_back(g.ray_near<T>(prim, 3.0));
                stream.push_back(Ray<T>{Vec3<T>{T(0), T(0), T(0)}, Vec3<T>{T(0), T(0), T(0)}});  // never hits
                std::vector<std::optional<Hit<T>>> got;
                std::vector<unsigned char> blocked;
                batch::intersect(p, stream, prim, got);
                batch::occluded(p, stream, prim, blocked);
                ASSERT_EQ(got.size(), stream.rays.size());
                ASSERT_EQ(blocked.size(), stream.rays.size());
                for (std::size_t i = 0; i < stream.rays.size(); ++i) {
                    const auto expected = intersect(p, stream.rays[i], prim);
                    expect_same(got[i], expected);
                    EXPECT_EQ(bool(blocked[i]), occluded(p, stream.rays[i], prim));
                    hits += expected.has_value();
                    ++rays;
                }
            }
            EXPECT_GT(hits, rays / 10);
        },
        static_cast<Bounded<T>*>(nullptr));
}

// One ray against many primitives in a Scene: the same answer as the scalar loop, bit for bit.
TYPED_TEST(BatchTest, SceneOfEveryBoundedTypeEqualsTheScalarLoop)
{
    using T = typename TypeParam::T;
    const auto p = TypeParam::policy;
    Gen g(0xB0D8 + sizeof(T));
    Scene<Disk<T>, Triangle<T>, Parallelogram<T>, Cylinder<T>, Cone<T>> scene;
    std::tuple<std::vector<Disk<T>>, std::vector<Triangle<T>>, std::vector<Parallelogram<T>>, std::vector<Cylinder<T>>, std::vector<Cone<T>>> lists;
    std::vector<std::function<Ray<T>()>> aims;
    each_type(
        [&](auto* tag) {
            using Prim = std::remove_pointer_t<decltype(tag)>;
            auto& list = std::get<std::vector<Prim>>(lists);
            for (int i = 0; i < 20; ++i) {
                Prim prim;
                g.make(prim, V{g.uniform(-8, 8), g.uniform(-8, 8), g.uniform(-8, 8)}, g.log_uniform(0.05, 2));
                list.push_back(prim);
                EXPECT_EQ(scene.add(prim), list.size() - 1);
            }
            aims.push_back([&g, &list] { return g.ray_near<T>(list[std::uniform_int_distribution<std::size_t>(0, list.size() - 1)(g.rng)], 8.0); });
        },
        static_cast<Bounded<T>*>(nullptr));
    for (int k = 0; k < 1500; ++k) {
        const Ray<T> ray = aims[std::size_t(k) % aims.size()]();
        std::optional<SceneHit<T>> expected;
        int type = 0;
        std::apply(
            [&](const auto&... list) {
                const auto one = [&](const auto& prims) {
                    for (std::size_t i = 0; i < prims.size(); ++i)
                        if (const auto h = intersect(p, ray, prims[i]); h && (!expected || h->t < expected->hit.t))
                            expected = SceneHit<T>{*h, type, i};
                    ++type;
                };
                (one(list), ...);
            },
            lists);
        const auto got = intersect(p, ray, scene);
        ASSERT_EQ(got.has_value(), expected.has_value()) << "ray " << k;
        EXPECT_EQ(occluded(p, ray, scene), expected.has_value());
        if (!got) continue;
        EXPECT_EQ(got->type, expected->type);
        EXPECT_EQ(got->index, expected->index);
        expect_same(std::optional<Hit<T>>(got->hit), std::optional<Hit<T>>(expected->hit));
    }
}

// Every lane column starts on a 64-byte boundary (detail::LaneAllocator), so no lane group's load
// spans two cache lines, whatever the allocator would otherwise have returned.
TYPED_TEST(BatchTest, LaneColumnsStartOnACacheLine)
{
    using T = typename TypeParam::T;
    const auto aligned = [](const auto& column) { return reinterpret_cast<std::uintptr_t>(column.data()) % 64 == 0; };
    batch::SphereSoA<T> spheres;
    batch::BoundSoA<T> bounds;
    batch::RayStream<T> rays;
    std::vector<char> interleave;  // other allocations between the columns' growth
    for (int i = 0; i < 40; ++i) {
        spheres.push_back(Sphere<T>{{T(i), T(0), T(0)}, T(1)});
        bounds.push_back(Cylinder<T>{{T(i), T(0), T(0)}, {T(i), T(1), T(0)}, T(0.5), Caps::both});
        rays.push_back(Ray<T>{{T(0), T(0), T(i)}, {T(1), T(0), T(0)}});
        interleave.resize(interleave.size() + 24);
        for (const auto* c : {&spheres.cx, &spheres.cy, &spheres.cz, &spheres.r, &spheres.reach2}) EXPECT_TRUE(aligned(*c));
        for (const auto* c : {&bounds.cx, &bounds.cy, &bounds.cz, &bounds.reach, &bounds.far, &bounds.wx, &bounds.wy, &bounds.wz})
            EXPECT_TRUE(aligned(*c));
        for (const auto* c : {&rays.ox, &rays.oy, &rays.oz, &rays.dx, &rays.dy, &rays.dz, &rays.dd, &rays.inv_len, &rays.abs_slack, &rays.tmin, &rays.tmax})
            EXPECT_TRUE(aligned(*c));
    }
}

// A candidate mask's lowest lane: the compiler's bit scan and the portable de Bruijn fallback agree
// with the lane that a scan from bit 0 finds, for every single bit and for random masks.
TEST(LaneMask, LowestBitIsTheFirstSetLane)
{
    const auto by_scan = [](std::uint32_t m) {
        int i = 0;
        while (!(m >> i & 1u)) ++i;
        return i;
    };
    std::mt19937 rng(7);
    for (int k = 0; k < 32 + 1000; ++k) {
        const std::uint32_t m = k < 32 ? 1u << k : (static_cast<std::uint32_t>(rng()) | 1u) << (rng() % 32);
        EXPECT_EQ(rayq::detail::lowest_bit(m), by_scan(m)) << std::bitset<32>(m);
        EXPECT_EQ(rayq::detail::lowest_bit_de_bruijn(m), by_scan(m)) << std::bitset<32>(m);
    }
    static_assert(rayq::detail::lowest_bit_de_bruijn(0x80000000u) == 31, "usable in constant expressions");
}

}  // namespace
}  // namespace rayq::test::batch_test
