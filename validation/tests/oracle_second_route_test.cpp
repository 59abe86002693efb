// The oracle checked by a second, independent route: CGAL's Exact_spherical_kernel_3 for spheres
// and its exact kernel (Epeck) for planes, triangles and parallelograms must agree with the oracle
// EXACTLY (hit, t in Q(√D), the point, entering, tangency) on hand-built, random, generated and
// checked-in cases.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <type_traits>

#include <rayq/oracle/fixtures.hpp>

namespace {

using namespace rayq;
using namespace rayq::oracle;

constexpr double inf = std::numeric_limits<double>::infinity();

template <class T>
Vec3<T> v(double x, double y, double z) { return {T(x), T(y), T(z)}; }

// Counts what was checked, so that the tests also prove they exercised hits and misses.
struct Count {
    int hits = 0, misses = 0, tangents = 0;
};

template <class T, class Prim>
void check(const Ray<T>& r, const Prim& p, Count& count)
{
    if (!exact_first_hit(r, p).defined) return;  // degenerate (random integer triangles): no question to answer
    const Agreement a = second_route_agrees(r, p);
    ASSERT_TRUE(a.agrees) << a.why;
    const ExactHit h = exact_first_hit(r, p);
    (h.hit ? count.hits : count.misses)++;
    if (h.tangent) ++count.tangents;
}

TEST(OracleSecondRoute, HandCases)
{
    Count c;
    const Sphere<double> unit{{0, 0, 0}, 1};
    check(Ray<double>{{0, 0, -5}, {0, 0, 1}}, unit, c);
    check(Ray<double>{{0.5, 0, -5}, {0, 0, 1}}, unit, c);
    check(Ray<double>{{-5, 1, 0}, {1, 0, 0}}, unit, c);           // tangent
    check(Ray<double>{{0.1, 0.2, 0}, {1, 0.3, 0.7}}, unit, c);    // inside
    check(Ray<double>{{0, 0, 5}, {0, 0, 1}}, unit, c);            // behind
    check(Ray<double>{{0, 0, 1}, {0, 0, 1}}, unit, c);            // on the surface, heading out
    check(Ray<double>{{0, 0, -5}, {0, 0, 1}, 4, 6}, unit, c);     // both roots on the window's edges
    check(Ray<double>{{0, 0, -5}, {0, 0, 1}, -inf, 4.5}, unit, c);
    check(Ray<float>{{-5, 1, 0}, {1, 0, 0}}, Sphere<float>{{0, 0, 0}, 1}, c);
    check(Ray<double>{{0, 0, 0}, {1, 1, 1}}, Plane<double>{{3, 0, 0}, {1, 0, 0}}, c);
    check(Ray<double>{{0, 0, 1}, {1, 0, 0}}, Plane<double>{{0, 0, 0}, {0, 0, 1}}, c);  // parallel
    check(Ray<double>{{0, 0, 0}, {1, 0, 0}}, Plane<double>{{0, 0, 0}, {0, 0, 1}}, c);  // in the plane
    const Triangle<double> tri{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    check(Ray<double>{{0.25, 0.25, 1}, {0, 0, -1}}, tri, c);
    check(Ray<double>{{0.5, 0.5, 1}, {0, 0, -1}}, tri, c);   // edge
    check(Ray<double>{{1, 0, 1}, {0, 0, -1}}, tri, c);       // corner
    check(Ray<double>{{0.5, std::nextafter(0.5, 1.0), 1}, {0, 0, -1}}, tri, c);
    check(Ray<double>{{0.25, 0.25, -1}, {0, 0, 1}}, tri, c);  // from the back
    const Parallelogram<double> quad{{0, 0, 0}, {2, 0, 0}, {1, 3, 0}};
    check(Ray<double>{{1.5, 1.5, 1}, {0, 0, -1}}, quad, c);   // on the shared diagonal
    check(Ray<double>{{3, 3, 1}, {0, 0, -1}}, quad, c);       // the far corner
    check(Ray<double>{{0, 3, 1}, {0, 0, -1}}, quad, c);       // outside the skewed edge
    EXPECT_GT(c.hits, 10);
    EXPECT_GT(c.misses, 4);
    EXPECT_EQ(c.tangents, 2);
}

// Integer geometry makes exact tangencies and edge hits likely.
template <class T>
void random_cases(std::uint64_t seed, Count& c)
{
    std::mt19937_64 g(seed);
    std::uniform_real_distribution<double> u(-8, 8);
    std::uniform_int_distribution<int> small(-4, 4);
    const auto rv = [&] { return v<T>(u(g), u(g), u(g)); };
    const auto iv = [&] { return v<T>(small(g), small(g), small(g)); };
    for (int i = 0; i < 300; ++i) {
        const Ray<T> r{rv(), rv()};
        check(r, Sphere<T>{rv(), T(std::fabs(u(g)) + 0.1)}, c);
        check(r, Triangle<T>{rv(), rv(), rv()}, c);
        check(r, Parallelogram<T>{rv(), rv(), rv()}, c);
        check(r, Plane<T>{rv(), rv()}, c);
        // Tangent: a line at exactly the radius from the center.
        const Vec3<T> center = iv();
        const T radius = T(1 + std::abs(small(g)));
        check(Ray<T>{{center.x - 10, center.y + radius, center.z}, {T(1), T(0), T(0)}}, Sphere<T>{center, radius}, c);
        // Integer rays against integer triangles hit edges and corners.
        const Ray<T> ir{iv(), iv()};
        if (ir.direction.x != 0 || ir.direction.y != 0 || ir.direction.z != 0) {
            check(ir, Triangle<T>{iv(), iv(), iv()}, c);
            check(ir, Parallelogram<T>{iv(), iv(), iv()}, c);
            check(ir, Sphere<T>{iv(), T(1 + std::abs(small(g)))}, c);
        }
    }
}

TEST(OracleSecondRoute, RandomDouble)
{
    Count c;
    random_cases<double>(1, c);
    EXPECT_GT(c.hits, 300);
    EXPECT_GT(c.misses, 300);
    EXPECT_GT(c.tangents, 250);
}

TEST(OracleSecondRoute, RandomFloat)
{
    Count c;
    random_cases<float>(2, c);
    EXPECT_GT(c.hits, 300);
    EXPECT_GT(c.tangents, 250);
}

// Generated families and the checked-in fixtures of the four primitives the second route knows.
void check_fixture(const Fixture& f, Count& c)
{
    std::visit(
        [&](const auto& in) {
            using Prim = std::decay_t<decltype(in.prim)>;
            using T = typename Prim::scalar_type;
            if constexpr (std::is_same_v<Prim, Sphere<T>> || std::is_same_v<Prim, Plane<T>> ||
                          std::is_same_v<Prim, Triangle<T>> || std::is_same_v<Prim, Parallelogram<T>>) {
                SCOPED_TRACE(format_fixture(f));
                check(in.ray, in.prim, c);
            }
        },
        f.input);
}

TEST(OracleSecondRoute, GeneratedFamilies)
{
    Count c;
    for (const char* p : {"sphere", "plane", "triangle", "parallelogram"})
        for (Scalar s : {Scalar::f64, Scalar::f32})
            for (const Fixture& f : generate_cases(p, s, 150, 99)) check_fixture(f, c);
    EXPECT_GT(c.hits, 300);
    EXPECT_GT(c.misses, 100);
}

TEST(OracleSecondRoute, CheckedInFixtures)
{
    Count c;
    for (const Fixture& f : load_fixture_directory(RAYQ_ORACLE_FIXTURES)) check_fixture(f, c);
    EXPECT_GT(c.hits + c.misses, 100);
}

}  // namespace
