// Scenes (scene.hpp) and the sphere batch filter (batch/sphere.hpp): the answers equal the scalar
// queries run over every primitive, bit for bit, for every policy and type — on generic rays and
// on the rays that stress a culling filter (near tangency far away, where the fast policy's
// discriminant is noise; tiny and huge directions; windows that end just before a hit).
#include <bitset>
#include <random>

#include <rayq/scene.hpp>

#include "test_support.hpp"

namespace rayq::test::scene_test {
namespace {

template <class C>
class SceneTest : public ::testing::Test {};
TYPED_TEST_SUITE(SceneTest, AllConfigs, ConfigNames);

template <class T>
struct World : Random {
    using Random::Random;

    // Spheres of mixed sizes spread over a box, a few invalid ones among them.
    Sphere<T> sphere(double extent)
    {
        const double pick = uniform(0, 1);
        Vec3<double> c{uniform(-extent, extent), uniform(-extent, extent), uniform(-extent, extent)};
        double r = log_uniform(1e-3, 0.2) * extent;
        if (pick < 0.03) r = -r;                                           // invalid: negative radius
        if (pick > 0.97) r = std::numeric_limits<double>::quiet_NaN();     // invalid: NaN
        return {scalar_cast<T>(c), T(r)};
    }

    // A ray chosen to stress the filter: aimed near the outline of one of the spheres (relative
    // distance to tangency 10^-k on either side), from near or far, with a direction of unusual
    // length, or a generic random ray; random windows.
    Ray<T> ray(const std::vector<Sphere<T>>& spheres, double extent)
    {
        const int kind = std::uniform_int_distribution<int>(0, 5)(rng);
        const Sphere<T>& s = spheres[std::uniform_int_distribution<std::size_t>(0, spheres.size() - 1)(rng)];
        const double r = std::isfinite(double(s.radius)) ? std::abs(double(s.radius)) : 1.0;
        const Vec3<double> c{double(s.center.x), double(s.center.y), double(s.center.z)};
        Vec3<double> d = unit_vector(), o;
        if (kind == 0) {
            o = Vec3<double>{uniform(-2, 2), uniform(-2, 2), uniform(-2, 2)} * extent;
        } else {
            // Offset perpendicular to d by r·(1 ± 10^-k), then back off along d.
            Vec3<double> side = cross(d, unit_vector());
            side = side / length(side);
            const int k = std::uniform_int_distribution<int>(1, std::is_same_v<T, float> ? 7 : 15)(rng);
            const double delta = (uniform(0, 1) < 0.5 ? -1 : 1) * std::pow(10.0, -k);
            const double distance = kind == 2 ? log_uniform(1e2, 1e7) * r : uniform(0, 4) * extent;
            o = c + side * (r * (1 + delta)) - d * distance;
            if (kind == 3) o = c + unit_vector() * (r * uniform(0, 1));  // from inside
        }
        if (kind == 4) d = d * log_uniform(1e-15, 1e15);                 // unusual direction length
        // or one so short that |d|² underflows or is subnormal (float 1e-25..1e-15, double 1e-165..1e-145)
        if (kind == 4 && uniform(0, 1) < 0.3) {
            const bool single = std::is_same_v<T, float>;
            d = d / length(d) * log_uniform(single ? 1e-25 : 1e-165, single ? 1e-15 : 1e-145);
        }
        Ray<T> out{scalar_cast<T>(o), scalar_cast<T>(d)};
        if (kind == 5 || uniform(0, 1) < 0.2) {  // a window that may end just before or after a hit
            const auto h = intersect(stable, out, s);
            if (h) out.tmax = std::nextafter(h->t, uniform(0, 1) < 0.5 ? T(0) : std::numeric_limits<T>::infinity());
            if (uniform(0, 1) < 0.3) out.tmin = -out.tmax;
        } else if (uniform(0, 1) < 0.25) {  // one that starts just before or after the ray leaves the sphere
            const auto all = intersect_all(stable, out, s, HitFields::t);
            if (!all.empty()) {
                out.tmin = std::nextafter(all[all.size() - 1].hit.t, uniform(0, 1) < 0.5 ? -std::numeric_limits<T>::infinity()
                                                                                          : std::numeric_limits<T>::infinity());
                if (!(out.tmin < out.tmax)) out.tmin = T(0);
            }
        }
        return out;
    }
};

// Brute force: the scalar query over every primitive in scene order; strict < keeps the first.
template <class Policy, class T, class Prim>
void brute(Policy p, const Ray<T>& ray, const std::vector<Prim>& prims, int type, std::optional<SceneHit<T>>& best)
{
    for (std::size_t i = 0; i < prims.size(); ++i)
        if (const auto h = intersect(p, ray, prims[i]); h && (!best || h->t < best->hit.t)) best = SceneHit<T>{*h, type, i};
}

template <class T>
void expect_same_hit(const Hit<T>& a, const Hit<T>& b)
{
    EXPECT_TRUE(same_bits(a.t, b.t)) << a.t << " vs " << b.t;
    EXPECT_EQ(a.point, b.point);
    EXPECT_EQ(a.normal, b.normal);
    EXPECT_EQ(a.part, b.part);
    EXPECT_EQ(a.front_face, b.front_face);
    EXPECT_TRUE(same_bits(a.t_error, b.t_error));
}

// The filter keeps every sphere that any policy hits in the window, and so do both line tests
// by which a scan skips whole groups (against d, and against d/|d| for many groups).
TYPED_TEST(SceneTest, SphereFilterNeverDropsAHit)
{
    using T = typename TypeParam::T;
    World<T> w(0x5CE4E001 + sizeof(T));
    std::size_t kept = 0, hits = 0, lanes = 0, passed = 0, passed_unit = 0, line_kept = 0;
    for (int scene = 0; scene < 40; ++scene) {
        batch::SphereSoA<T> soa;
        std::vector<Sphere<T>> spheres;
        for (int i = 0; i < 64; ++i) {
            spheres.push_back(w.sphere(10.0));
            soa.push_back(spheres.back());
        }
        for (int k = 0; k < 200; ++k) {
            const Ray<T> ray = w.ray(spheres, 10.0);
            if (!usable(ray)) continue;
            const batch::SphereFilterRay<T> f(ray);
            const batch::UnitLineRay<T> unit(ray.direction, f.dd);
            for (std::size_t g = 0; g < soa.groups(); ++g) {
                const std::uint32_t m = batch::sphere_candidates(f, ray.tmin, ray.tmax, soa, g);
                kept += std::bitset<32>(m).count();
                // The scene walks the line test's lanes and visits those candidates() keeps
                // (SceneStore::scan_filtered): every candidate must be among them.
                const std::uint32_t line = batch::sphere_line_candidates(f, soa, g);
                EXPECT_EQ(m & ~line, 0u) << "a candidate the line test drops, group " << g;
                line_kept += std::bitset<32>(line).count();
                const bool line_passes = batch::line_passes_group(f, soa, g);
                const bool unit_passes = batch::line_passes_group(f, unit, soa, g);
                passed += line_passes;
                passed_unit += unit_passes;
                for (int lane = 0; lane < batch::SphereSoA<T>::width; ++lane) {
                    const std::size_t i = g * batch::SphereSoA<T>::width + static_cast<std::size_t>(lane);
                    if (i >= spheres.size()) break;
                    ++lanes;
                    const bool hit = occluded(TypeParam::policy, ray, spheres[i]);
                    hits += hit;
                    if (hit) {
                        EXPECT_TRUE(m >> lane & 1u) << "dropped sphere " << i << " hit at t = "
                                                    << intersect(TypeParam::policy, ray, spheres[i])->t;
                        EXPECT_FALSE(line_passes) << "group of sphere " << i << " skipped (line test against d)";
                        EXPECT_FALSE(unit_passes) << "group of sphere " << i << " skipped (line test against d/|d|)";
                    }
                }
            }
        }
    }
    // It must also cull: rays aimed at one of 64 scattered spheres pass most of the others by.
    EXPECT_LT(kept, lanes / 2) << "kept " << kept << " of " << lanes << " lanes (" << hits << " hits)";
    EXPECT_GE(line_kept, kept);
    EXPECT_LT(line_kept, lanes / 2) << "the line test kept " << line_kept << " of " << lanes << " lanes";
    // The two line tests differ only by rounding: d/|d| skips nearly every group d skips.
    EXPECT_GE(passed_unit, passed - passed / 100) << passed_unit << " groups skipped against d/|d|, " << passed << " against d";
    EXPECT_GT(passed, 0u);
}

TYPED_TEST(SceneTest, EqualsTheScalarQueriesOverEveryPrimitive)
{
    using T = typename TypeParam::T;
    const auto p = TypeParam::policy;
    World<T> w(0x5CE4E002 + sizeof(T));
    for (int scene_n : {1, 3, 17, 100}) {
        Scene<Sphere<T>, Cylinder<T>, Triangle<T>> scene;
        std::vector<Sphere<T>> spheres;
        std::vector<Cylinder<T>> cylinders;
        std::vector<Triangle<T>> triangles;
        for (int i = 0; i < scene_n; ++i) {
            spheres.push_back(w.sphere(10.0));
            EXPECT_EQ(scene.add(spheres.back()), spheres.size() - 1);
            if (i % 3 == 0) {
                const Vec3<T> a = scalar_cast<T>(w.unit_vector() * 8.0), b = a + scalar_cast<T>(w.unit_vector() * w.uniform(0.5, 3));
                cylinders.push_back({a, b, T(w.log_uniform(0.05, 1)), i % 2 == 0 ? Caps::both : Caps::none});
                scene.add(cylinders.back());
                triangles.push_back({scalar_cast<T>(w.unit_vector() * 9.0), scalar_cast<T>(w.unit_vector() * 9.0), scalar_cast<T>(w.unit_vector() * 9.0)});
                scene.add(triangles.back());
            }
        }
        // A tie: the second copy of a sphere must never replace the first.
        spheres.push_back(spheres.front());
        scene.add(spheres.back());
        EXPECT_EQ(scene.size(), spheres.size() + cylinders.size() + triangles.size());
        for (int k = 0; k < 1500; ++k) {
            const Ray<T> ray = w.ray(spheres, 10.0);
            std::optional<SceneHit<T>> expected;
            brute(p, ray, spheres, 0, expected);
            brute(p, ray, cylinders, 1, expected);
            brute(p, ray, triangles, 2, expected);
            const auto got = intersect(p, ray, scene);
            ASSERT_EQ(got.has_value(), expected.has_value()) << "scene of " << scene_n << ", ray " << k;
            EXPECT_EQ(occluded(p, ray, scene), expected.has_value());
            if (!got) continue;
            EXPECT_EQ(got->type, expected->type);
            EXPECT_EQ(got->index, expected->index);
            expect_same_hit(got->hit, expected->hit);
            const auto ref = nearest(p, ray, scene);
            ASSERT_TRUE(ref);
            EXPECT_TRUE(same_bits(ref->t, expected->hit.t));
        }
    }
}

// Scenes of cylinders alone, with rays aimed at them (the test above aims at spheres): at their
// sides, rims and caps, from inside, along and across their axes (where the scalar query's solver
// and slab take their special branches), in windows that end near a hit; capped, open and invalid
// cylinders in the same lane groups; copies of a cylinder for ties. Every answer must be the scalar
// queries', bit for bit: the bounding-sphere filter may drop no cylinder a policy hits.
TYPED_TEST(SceneTest, CylinderScenesEqualTheScalarQueries)
{
    using T = typename TypeParam::T;
    const auto p = TypeParam::policy;
    World<T> w(0xC71E0000 + sizeof(T));
    for (int scene_n : {3, 8, 19, 40}) {
        Scene<Cylinder<T>> scene;
        std::vector<Cylinder<T>> cylinders;
        for (int i = 0; i < scene_n; ++i) {
            const Vec3<double> a = w.unit_vector() * w.uniform(0, 6), axis = w.unit_vector() * w.uniform(0.2, 3);
            const bool aligned = i % 5 == 1;  // axis along z: rays along z are parallel, along x perpendicular
            Cylinder<T> c{scalar_cast<T>(a), scalar_cast<T>(aligned ? a + Vec3<double>{0, 0, 2} : a + axis), T(w.log_uniform(0.05, 1.5)),
                          i % 4 == 3 ? Caps::none : Caps::both};
            if (i % 11 == 7) c.radius = -c.radius;  // invalid: kept, never hit
            if (i % 13 == 12) c = cylinders.front();  // a tie: the first copy wins
            cylinders.push_back(c);
            scene.add(c);
        }
        int hits = 0, cap_hits = 0;
        for (int k = 0; k < 3000; ++k) {
            const Cylinder<T>& c = cylinders[std::uniform_int_distribution<std::size_t>(0, cylinders.size() - 1)(w.rng)];
            const Vec3<double> p0 = scalar_cast<double>(c.p0), p1 = scalar_cast<double>(c.p1);
            const double r = std::abs(double(c.radius));
            // A target on the cylinder's side, rim or caps (or just off them), then a direction.
            const double h = w.uniform(-0.1, 1.1), angle = w.uniform(0, 6.283185307179586), rho = r * w.uniform(0, 1.05);
            Vec3<double> axis = p1 - p0, e = cross(axis, Vec3<double>{1, 0, 0});
            if (length(e) < 1e-3 * length(axis)) e = cross(axis, Vec3<double>{0, 1, 0});
            e = normalize(e);
            const Vec3<double> f = cross(normalize(axis), e);
            const Vec3<double> target = p0 + axis * h + (e * std::cos(angle) + f * std::sin(angle)) * rho;
            const int kind = std::uniform_int_distribution<int>(0, 5)(w.rng);
            Vec3<double> d = w.unit_vector();
            if (kind == 1) d = Vec3<double>{0, 0, w.uniform(0, 1) < 0.5 ? 1.0 : -1.0};  // along the aligned axes
            if (kind == 2) d = Vec3<double>{1, 0, 0};                                    // across them
            Vec3<double> o = target - d * w.uniform(0, 20);
            if (kind == 3) o = target;  // from on or inside the surface
            Ray<T> ray{scalar_cast<T>(o), scalar_cast<T>(d)};
            if (kind == 4) {  // a window that ends just before or after a scalar hit
                std::optional<SceneHit<T>> first;
                brute(stable, ray, cylinders, 0, first);
                if (first) ray.tmax = std::nextafter(first->hit.t, w.uniform(0, 1) < 0.5 ? T(0) : std::numeric_limits<T>::infinity());
            }
            std::optional<SceneHit<T>> expected;
            brute(p, ray, cylinders, 0, expected);
            const auto got = intersect(p, ray, scene);
            ASSERT_EQ(got.has_value(), expected.has_value()) << "scene of " << scene_n << ", ray " << k;
            EXPECT_EQ(occluded(p, ray, scene), expected.has_value()) << "scene of " << scene_n << ", ray " << k;
            if (!got) continue;
            ++hits;
            cap_hits += got->hit.part != Part::surface;
            EXPECT_EQ(got->index, expected->index) << "scene of " << scene_n << ", ray " << k;
            expect_same_hit(got->hit, expected->hit);
        }
        // The rays must reach both parts: sides and caps.
        EXPECT_GT(hits, 1000);
        EXPECT_GT(cap_hits, 100);
    }
}

TYPED_TEST(SceneTest, BadRaysAndInvalidPrimitivesNeverHit)
{
    using T = typename TypeParam::T;
    constexpr T inf = std::numeric_limits<T>::infinity(), nan = std::numeric_limits<T>::quiet_NaN();
    Scene<Sphere<T>, Plane<T>> scene;
    scene.add(Sphere<T>{v3<T>(0, 0, 5), T(-1)});   // invalid: kept, never hit
    scene.add(Sphere<T>{v3<T>(0, 0, 9), nan});
    scene.add(Plane<T>{v3<T>(0, 0, 20), v3<T>(0, 0, 0)});
    const Ray<T> forward = ray(v3<T>(0, 0, 0), v3<T>(0, 0, 1));
    EXPECT_FALSE(intersect(TypeParam::policy, forward, scene));
    EXPECT_FALSE(occluded(TypeParam::policy, forward, scene));
    scene.add(Sphere<T>{v3<T>(0, 0, 5), T(1)});
    const auto h = intersect(TypeParam::policy, forward, scene);
    ASSERT_TRUE(h);
    EXPECT_EQ(h->index, 2u);
    EXPECT_EQ(h->hit.t, T(4));
    for (const Vec3<T>& d : {v3<T>(0, 0, 0), Vec3<T>{nan, T(0), T(1)}, Vec3<T>{T(0), inf, T(1)}}) {
        EXPECT_FALSE(intersect(TypeParam::policy, ray(v3<T>(0, 0, 0), d), scene));
        EXPECT_FALSE(occluded(TypeParam::policy, ray(v3<T>(0, 0, 0), d), scene));
    }
    EXPECT_FALSE(intersect(TypeParam::policy, ray(Vec3<T>{nan, T(0), T(0)}, v3<T>(0, 0, 1)), scene));
    Scene<Sphere<T>> empty;
    EXPECT_FALSE(intersect(TypeParam::policy, forward, empty));
    EXPECT_FALSE(occluded(TypeParam::policy, forward, empty));
}

// complete() builds the record of the crossing it is given, even where that primitive's crossings,
// computed again, would not name it (GCC contracting a·b + c differently in the search and in the
// scalar query, on FMA targets): an exit while the entry lies in the window gets a bound reaching
// back to tmin; a point where the ray misses gets a record whose bound claims nothing. (It called
// intersect() before, which returned the entry, and for the miss threw std::bad_optional_access.)
TYPED_TEST(SceneTest, CompleteBuildsTheRecordOfTheCrossingItIsGiven)
{
    using T = typename TypeParam::T;
    Scene<Sphere<T>> scene;
    scene.add(Sphere<T>{v3<T>(0, 0, 5), T(1)});
    const Ray<T> through = ray(v3<T>(0, 0, 0), v3<T>(0, 0, 1));
    const SceneHit<T> exit = complete(TypeParam::policy, through, scene, SceneRef<T>{T(6), 0, 0, Part::surface, false});
    EXPECT_EQ(exit.hit.t, T(6));
    EXPECT_FALSE(exit.hit.front_face);
    EXPECT_GE(exit.hit.t_error, T(6));  // the entry at 4 may be the first hit: back to tmin = 0
    EXPECT_EQ(exit.hit.normal.z, T(-1));  // leaving: faces the ray from inside
    const SceneHit<T> entry = complete(TypeParam::policy, through, scene, SceneRef<T>{T(4), 0, 0, Part::surface, true});
    EXPECT_EQ(entry.hit.t, T(4));
    EXPECT_LT(entry.hit.t_error, T(1e-3));  // nothing before it: not widened
    const Ray<T> past = ray(v3<T>(T(1.5), 0, 0), v3<T>(0, 0, 1));  // 1.5 from the center: no root at all
    const SceneHit<T> none = complete(TypeParam::policy, past, scene, SceneRef<T>{T(5), 0, 0, Part::surface, true});
    EXPECT_EQ(none.hit.t, T(5));
    EXPECT_TRUE(std::isinf(none.hit.t_error));
}

}  // namespace
}  // namespace rayq::test::scene_test
