// The exact oracle on hand cases whose answers are known exactly: t, tangency, parts at rims and
// apexes, the clip box's fallback to the far root, transformed primitives, correct rounding, and
// the measurement of a kernel answer.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

#include <rayq/oracle/oracle.hpp>

namespace {

using namespace rayq;
using namespace rayq::oracle;

constexpr double inf = std::numeric_limits<double>::infinity();

Ray<double> ray(Vec3<double> o, Vec3<double> d, double tmin = 0, double tmax = inf) { return {o, d, tmin, tmax}; }

void expect_normal(const ExactHit& h, Vec3<double> n, double tol = 1e-15)
{
    ASSERT_TRUE(h.normal_defined);
    EXPECT_NEAR(h.outward_normal.x, n.x, tol);
    EXPECT_NEAR(h.outward_normal.y, n.y, tol);
    EXPECT_NEAR(h.outward_normal.z, n.z, tol);
}

// ---- sphere ------------------------------------------------------------------------------------------
TEST(OracleExact, SphereKnownRationalRoot)
{
    const ExactHit h = exact_first_hit(ray({0, 0, -5}, {0, 0, 1}), Sphere<double>{{0, 0, 0}, 1});
    ASSERT_TRUE(h.defined && h.hit);
    EXPECT_EQ(h.t_double, 4.0);
    EXPECT_EQ(h.t_float, 4.0f);
    EXPECT_EQ(h.t_exact, "4");
    EXPECT_TRUE(h.entering);
    EXPECT_FALSE(h.tangent);
    EXPECT_EQ(h.part, Part::surface);
    expect_normal(h, {0, 0, -1});
    ASSERT_EQ(h.crossings.size(), 2u);
    EXPECT_EQ(h.crossings[0], 4.0L);
    EXPECT_EQ(h.crossings[1], 6.0L);
}

TEST(OracleExact, SphereIrrationalRootIsCorrectlyRounded)
{
    // t = 5 − √3/2.
    const ExactHit h = exact_first_hit(ray({0.5, 0, -5}, {0, 0, 1}), Sphere<double>{{0, 0, 0}, 1});
    ASSERT_TRUE(h.hit);
    EXPECT_EQ(h.t_exact, "5 + -1/2*sqrt(3)");
    const long double t = 5.0L - std::sqrt(3.0L) / 2;
    EXPECT_NEAR(static_cast<double>(h.t_long), static_cast<double>(t), 1e-18);
    // Correct rounding: within half an ulp of the 64-bit value (which is far more precise).
    EXPECT_LE(std::fabs(static_cast<long double>(h.t_double) - t), 0.5L * (std::nextafter(h.t_double, inf) - h.t_double));
    EXPECT_LE(std::fabs(static_cast<long double>(h.t_float) - t), 0.5L * (std::nextafter(h.t_float, 1e30f) - h.t_float));
    expect_normal(h, {0.5, 0, -std::sqrt(0.75)});
}

TEST(OracleExact, SphereExactTangencyIsAHitAndTangent)
{
    const ExactHit h = exact_first_hit(ray({-5, 1, 0}, {1, 0, 0}), Sphere<double>{{0, 0, 0}, 1});
    ASSERT_TRUE(h.hit);
    EXPECT_TRUE(h.tangent);
    EXPECT_TRUE(h.entering);
    EXPECT_EQ(h.t_double, 5.0);
    expect_normal(h, {0, 1, 0});
    // The exact normal is perpendicular to the ray: either orientation faces it.
    EXPECT_EQ(h.facing_normal.y, 1.0);
    // One ulp further out: no hit at all.
    const ExactHit miss = exact_first_hit(ray({-5, std::nextafter(1.0, 2.0), 0}, {1, 0, 0}), Sphere<double>{{0, 0, 0}, 1});
    EXPECT_TRUE(miss.defined);
    EXPECT_FALSE(miss.hit);
    // One ulp further in: two roots 2^-26-ish apart, not tangent.
    const ExactHit near = exact_first_hit(ray({-5, std::nextafter(1.0, 0.0), 0}, {1, 0, 0}), Sphere<double>{{0, 0, 0}, 1});
    ASSERT_TRUE(near.hit);
    EXPECT_FALSE(near.tangent);
    EXPECT_LT(near.t_double, 5.0);
}

TEST(OracleExact, SphereFromInsideExits)
{
    const ExactHit h = exact_first_hit(ray({0, 0, 0}, {0, 0, 2}), Sphere<double>{{0, 0, 0}, 1});
    ASSERT_TRUE(h.hit);
    EXPECT_EQ(h.t_double, 0.5);
    EXPECT_FALSE(h.entering);
    expect_normal(h, {0, 0, 1});
    EXPECT_EQ(h.facing_normal.z, -1.0);  // faces the ray
}

TEST(OracleExact, WindowBoundsAreExclusiveAndExact)
{
    const Sphere<double> s{{0, 0, 0}, 1};
    // Origin on the surface heading out: the roots are 0 and −2; t = 0 is not > tmin = 0.
    EXPECT_FALSE(exact_first_hit(ray({0, 0, 1}, {0, 0, 1}), s).hit);
    // Heading in: 0 is excluded, the exit at 2 counts.
    const ExactHit in = exact_first_hit(ray({0, 0, 1}, {0, 0, -1}), s);
    ASSERT_TRUE(in.hit);
    EXPECT_EQ(in.t_double, 2.0);
    EXPECT_FALSE(in.entering);
    // tmax = 4 exactly excludes the root at 4; the next double above includes it.
    EXPECT_FALSE(exact_first_hit(ray({0, 0, -5}, {0, 0, 1}, 0, 4), s).hit);
    EXPECT_TRUE(exact_first_hit(ray({0, 0, -5}, {0, 0, 1}, 0, std::nextafter(4.0, 5.0)), s).hit);
    // tmin = 4: the far root.
    const ExactHit far = exact_first_hit(ray({0, 0, -5}, {0, 0, 1}, 4), s);
    ASSERT_TRUE(far.hit);
    EXPECT_EQ(far.t_double, 6.0);
    EXPECT_FALSE(far.entering);
    // A negative window: the first crossing in it is the lower one.
    EXPECT_EQ(exact_first_hit(ray({0, 0, 5}, {0, 0, 1}, -inf, 0), s).t_double, -6.0);
    EXPECT_EQ(exact_first_hit(ray({0, 0, 5}, {0, 0, 1}, -5, 0), s).t_double, -4.0);
}

TEST(OracleExact, FloatInputs)
{
    const ExactHit h = exact_first_hit(Ray<float>{{0, 0, -5}, {0, 0, 1}}, Sphere<float>{{0, 0, 0}, 1});
    ASSERT_TRUE(h.hit);
    EXPECT_EQ(h.t_float, 4.0f);
    EXPECT_EQ(h.t_double, 4.0);
}

// ---- correct rounding at exact ties ----------------------------------------------------------------
TEST(OracleExact, TiesRoundToEven)
{
    // A plane at x = t, ray from the origin along +x: t is exactly the plane's offset.
    const auto t_of = [](double x) { return exact_first_hit(ray({0, 0, 0}, {1, 0, 0}), Plane<double>{{x, 0, 0}, {1, 0, 0}}); };
    const double half_float_ulp = std::ldexp(1.0, -24);
    EXPECT_EQ(t_of(1 + half_float_ulp).t_float, 1.0f);                                  // tie: even is 1
    EXPECT_EQ(t_of(1 + 3 * half_float_ulp).t_float, 1.0f + std::ldexp(1.0f, -22));     // tie: even is 1 + 2^-22
    EXPECT_EQ(t_of(1 + half_float_ulp + std::ldexp(1.0, -40)).t_float, 1.0f + std::ldexp(1.0f, -23));  // above the tie
    EXPECT_EQ(t_of(1 + half_float_ulp).t_double, 1 + half_float_ulp);
    // t = 1/3: both roundings of a non-dyadic rational.
    const ExactHit third = exact_first_hit(ray({0, 0, 0}, {3, 0, 0}), Plane<double>{{1, 0, 0}, {1, 0, 0}});
    EXPECT_EQ(third.t_double, 1.0 / 3.0);
    EXPECT_EQ(third.t_float, 1.0f / 3.0f);
    EXPECT_EQ(third.t_exact, "1/3");
}

// ---- cylinder ----------------------------------------------------------------------------------------
TEST(OracleExact, CylinderRimTieGoesToTheCap)
{
    const Cylinder<double> cyl{{0, 0, 0}, {0, 0, 2}, 1, Caps::both};
    // Through the rim point (1, 0, 0): side and cap0 plane are both reached at t = 1.
    const ExactHit h = exact_first_hit(ray({2, 0, -1}, {-1, 0, 1}), cyl);
    ASSERT_TRUE(h.hit);
    EXPECT_EQ(h.t_double, 1.0);
    EXPECT_EQ(h.part, Part::cap0);
    EXPECT_TRUE(h.entering);
    expect_normal(h, {0, 0, -1});
    // Its exit at t = 3 is the rim of cap1: another tie, the cap wins.
    const ExactHit out = exact_first_hit(ray({2, 0, -1}, {-1, 0, 1}, 2), cyl);
    ASSERT_TRUE(out.hit);
    EXPECT_EQ(out.t_double, 3.0);
    EXPECT_EQ(out.part, Part::cap1);
    EXPECT_FALSE(out.entering);
    // Open: the same point belongs to the side (rim included in the slab).
    const ExactHit open = exact_first_hit(ray({2, 0, -1}, {-1, 0, 1}), Cylinder<double>{{0, 0, 0}, {0, 0, 2}, 1, Caps::none});
    ASSERT_TRUE(open.hit);
    EXPECT_EQ(open.t_double, 1.0);
    EXPECT_EQ(open.part, Part::surface);
    // Tilted by an ulp so that the line reaches the cap plane outside the rim: the side is first.
    const ExactHit beside = exact_first_hit(ray({2, 0, -1}, {-1, 0, std::nextafter(1.0, 2.0)}), cyl);
    ASSERT_TRUE(beside.hit);
    EXPECT_EQ(beside.part, Part::surface);
}

TEST(OracleExact, CylinderCapsSideAndAxialRays)
{
    const Cylinder<double> capped{{0, 0, 0}, {0, 0, 2}, 1, Caps::both};
    const Cylinder<double> open{{0, 0, 0}, {0, 0, 2}, 1, Caps::none};
    const ExactHit cap = exact_first_hit(ray({0.5, 0, -1}, {0, 0, 1}), capped);
    ASSERT_TRUE(cap.hit);
    EXPECT_EQ(cap.part, Part::cap0);
    EXPECT_EQ(cap.t_double, 1.0);
    // Parallel to the axis inside the open tube: no crossing.
    EXPECT_FALSE(exact_first_hit(ray({0.5, 0, -1}, {0, 0, 1}), open).hit);
    // From inside the capped solid along the axis: exits through cap1.
    const ExactHit up = exact_first_hit(ray({0, 0, 1}, {0, 0, 1}), capped);
    ASSERT_TRUE(up.hit);
    EXPECT_EQ(up.part, Part::cap1);
    EXPECT_FALSE(up.entering);
    // The side: normal radial.
    const ExactHit side = exact_first_hit(ray({-5, 0, 1}, {1, 0, 0}), open);
    ASSERT_TRUE(side.hit);
    EXPECT_EQ(side.t_double, 4.0);
    expect_normal(side, {-1, 0, 0});
    // Exactly tangent to the side.
    const ExactHit tangent = exact_first_hit(ray({-5, 1, 1}, {1, 0, 0}), open);
    ASSERT_TRUE(tangent.hit);
    EXPECT_TRUE(tangent.tangent);
    EXPECT_EQ(tangent.t_double, 5.0);
    // Beyond the slab the side does not count.
    EXPECT_FALSE(exact_first_hit(ray({-5, 0, 3}, {1, 0, 0}), capped).hit);
}

// ---- cone --------------------------------------------------------------------------------------------
TEST(OracleExact, ConeApexIsNeverACap)
{
    const Cone<double> cone{{0, 0, 0}, 0, {0, 0, 1}, 1, Caps::both};  // apex at the origin, opening up
    // Up the axis: enters the solid at the apex (part surface, not cap0), leaves through cap1.
    const ExactHit axis = exact_first_hit(ray({0, 0, -1}, {0, 0, 1}), cone);
    ASSERT_TRUE(axis.hit);
    EXPECT_EQ(axis.t_double, 1.0);
    EXPECT_EQ(axis.part, Part::surface);
    EXPECT_TRUE(axis.entering);
    EXPECT_FALSE(axis.normal_defined);  // the gradient vanishes at the apex
    const ExactHit exit = exact_first_hit(ray({0, 0, -1}, {0, 0, 1}, 1), cone);
    ASSERT_TRUE(exit.hit);
    EXPECT_EQ(exit.part, Part::cap1);
    EXPECT_EQ(exit.t_double, 2.0);
    // The open cone: touched from inside at the apex only (F <= 0 all along the line): no crossing.
    EXPECT_FALSE(exact_first_hit(ray({0, 0, -1}, {0, 0, 1}), Cone<double>{{0, 0, 0}, 0, {0, 0, 1}, 1, Caps::none}).hit);
    // A line through the apex outside the cone's angle: an exact double root there, tangent.
    const ExactHit touch = exact_first_hit(ray({-2, 0, -1}, {2, 0, 1}), cone);
    ASSERT_TRUE(touch.hit);
    EXPECT_TRUE(touch.tangent);
    EXPECT_EQ(touch.t_double, 1.0);
    EXPECT_EQ(touch.part, Part::surface);
    // The apex at p1 (r1 = 0): coming down the axis from above, the first contact is the apex.
    const Cone<double> down{{0, 0, 0}, 1, {0, 0, 1}, 0, Caps::both};
    const ExactHit top = exact_first_hit(ray({0, 0, 3}, {0, 0, -1}), down);
    ASSERT_TRUE(top.hit);
    EXPECT_EQ(top.t_double, 2.0);
    EXPECT_EQ(top.part, Part::surface);
}

TEST(OracleExact, ConeSideAndCaps)
{
    const Cone<double> cone{{0, 0, 0}, 0, {0, 0, 1}, 1, Caps::both};
    const ExactHit side = exact_first_hit(ray({-5, 0, 0.5}, {1, 0, 0}), cone);
    ASSERT_TRUE(side.hit);
    EXPECT_EQ(side.t_double, 4.5);
    expect_normal(side, {-std::sqrt(0.5), 0, -std::sqrt(0.5)});
    // From above through the cap at radius 1/2.
    const ExactHit cap = exact_first_hit(ray({0.5, 0, 3}, {0, 0, -1}), cone);
    ASSERT_TRUE(cap.hit);
    EXPECT_EQ(cap.part, Part::cap1);
    EXPECT_EQ(cap.t_double, 2.0);
    // The rim of cap1 exactly: the cap wins the tie.
    const ExactHit rim = exact_first_hit(ray({1, 0, 3}, {0, 0, -1}), cone);
    ASSERT_TRUE(rim.hit);
    EXPECT_EQ(rim.part, Part::cap1);
    // The second nappe (below the apex) is outside the slab.
    EXPECT_FALSE(exact_first_hit(ray({-5, 0, -0.5}, {1, 0, 0}), cone).hit);
    // A frustum: radius 2 at p0, 1 at p1.
    const Cone<double> frustum{{0, 0, 0}, 2, {0, 0, 2}, 1, Caps::none};
    const ExactHit f = exact_first_hit(ray({-5, 0, 1}, {1, 0, 0}), frustum);  // radius 1.5 at z = 1
    ASSERT_TRUE(f.hit);
    EXPECT_EQ(f.t_double, 3.5);
}

// ---- quadric -----------------------------------------------------------------------------------------
Quadric<double> quadric(double A, double B, double C, double D, double E, double F, double G, double H, double I, double J,
                        Box<double> clip = {{-inf, -inf, -inf}, {inf, inf, inf}})
{
    return {A, B, C, D, E, F, G, H, I, J, clip};
}

TEST(OracleExact, QuadricClippedNearRootFallsBackToTheFarOne)
{
    const Quadric<double> q = quadric(1, 1, 1, 0, 0, 0, 0, 0, 0, -1, {{-inf, -inf, -inf}, {inf, inf, 0.5}});
    const ExactHit h = exact_first_hit(ray({0, 0, 5}, {0, 0, -1}), q);
    ASSERT_TRUE(h.hit);
    EXPECT_EQ(h.t_double, 6.0);
    EXPECT_FALSE(h.entering);
    expect_normal(h, {0, 0, -1});
    // The box bound is inclusive: z = 1 itself is kept when hi.z = 1.
    const ExactHit edge = exact_first_hit(ray({0, 0, 5}, {0, 0, -1}), quadric(1, 1, 1, 0, 0, 0, 0, 0, 0, -1, {{-inf, -inf, -inf}, {inf, inf, 1}}));
    EXPECT_EQ(edge.t_double, 4.0);
}

TEST(OracleExact, QuadricBothSheetsAndInsideLines)
{
    // x² + y² − z² − 1 (hyperboloid of one sheet).
    const Quadric<double> h1 = quadric(1, 1, -1, 0, 0, 0, 0, 0, 0, -1);
    const ExactHit across = exact_first_hit(ray({-5, 0, 0}, {1, 0, 0}), h1);
    ASSERT_TRUE(across.hit);
    EXPECT_EQ(across.t_double, 4.0);
    EXPECT_TRUE(across.entering);
    // Along the axis F = −z² − 1 < 0 everywhere: inside all along, no crossing.
    EXPECT_FALSE(exact_first_hit(ray({0, 0, -5}, {0, 0, 1}), h1).hit);
    // a < 0: F(t) = −0.75t² + 10t − 26, inside before the first root: the first crossing exits.
    const ExactHit steep = exact_first_hit(ray({0, 0, -5}, {0.5, 0, 1}), h1);
    ASSERT_TRUE(steep.hit);
    EXPECT_FALSE(steep.entering);
    EXPECT_EQ(steep.t_exact, "20/3 + -2/3*sqrt(22)");
    // A line lying in the surface (a ruling x = 1, y = t, z = t): F ≡ 0, no crossing.
    EXPECT_FALSE(exact_first_hit(ray({1, -3, -3}, {0, 1, 1}), h1).hit);
    // Linear along the ray (a = 0): the paraboloid x² + y² − z, ray along its axis from below.
    const ExactHit par = exact_first_hit(ray({0, 0, -2}, {0, 0, 1}), quadric(1, 1, 0, 0, 0, 0, 0, 0, -1, 0));
    ASSERT_TRUE(par.hit);
    EXPECT_EQ(par.t_double, 2.0);
    EXPECT_TRUE(par.entering);
}

TEST(OracleExact, QuadricSphereAgreesWithSphereExactly)
{
    // (x − 1)² + (y + 2)² + (z − 0.5)² − 9/4, expanded: the same exact roots as the Sphere.
    const Quadric<double> q = quadric(1, 1, 1, 0, 0, 0, -2, 4, -1, 1 + 4 + 0.25 - 2.25);
    const Sphere<double> s{{1, -2, 0.5}, 1.5};
    std::mt19937_64 g(7);
    std::uniform_real_distribution<double> u(-4, 4);
    int hits = 0;
    for (int i = 0; i < 300; ++i) {
        const Vec3<double> o{u(g), u(g), u(g)}, target{1 + u(g) / 2, -2 + u(g) / 2, 0.5 + u(g) / 2};
        const Ray<double> r = ray(o, target - o);
        const ExactHit a = exact_first_hit(r, q), b = exact_first_hit(r, s);
        ASSERT_EQ(a.hit, b.hit);
        if (!a.hit) continue;
        ++hits;
        EXPECT_EQ(a.t_double, b.t_double);
        EXPECT_EQ(a.t_float, b.t_float);
        EXPECT_EQ(a.entering, b.entering);
        EXPECT_EQ(a.tangent, b.tangent);
        EXPECT_NEAR(a.outward_normal.x, b.outward_normal.x, 1e-15);
    }
    EXPECT_GT(hits, 50);
}

// ---- flat primitives ------------------------------------------------------------------------------------
TEST(OracleExact, FlatInsideTestsAreInclusiveAndExact)
{
    const Triangle<double> tri{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    const auto down = [](double x, double y) { return ray({x, y, 1}, {0, 0, -1}); };
    EXPECT_TRUE(exact_first_hit(down(0.25, 0.25), tri).hit);
    EXPECT_TRUE(exact_first_hit(down(0.5, 0.5), tri).hit);  // on the hypotenuse
    EXPECT_TRUE(exact_first_hit(down(1, 0), tri).hit);      // a corner
    EXPECT_FALSE(exact_first_hit(down(0.5, std::nextafter(0.5, 1.0)), tri).hit);
    EXPECT_FALSE(exact_first_hit(down(-std::numeric_limits<double>::denorm_min(), 0.5), tri).hit);
    const ExactHit front = exact_first_hit(down(0.25, 0.25), tri);
    EXPECT_TRUE(front.entering);  // from +z, the side (b − a) × (c − a) points to
    expect_normal(front, {0, 0, 1});
    EXPECT_FALSE(exact_first_hit(ray({0.25, 0.25, -1}, {0, 0, 1}), tri).entering);

    const Parallelogram<double> quad{{0, 0, 0}, {2, 0, 0}, {0, 3, 0}};
    EXPECT_TRUE(exact_first_hit(down(2, 3), quad).hit);
    EXPECT_FALSE(exact_first_hit(down(2, std::nextafter(3.0, 4.0)), quad).hit);

    const Disk<double> disk{{0, 0, 0}, {0, 0, 1}, 5};
    EXPECT_TRUE(exact_first_hit(down(3, 4), disk).hit);  // exactly on the rim
    EXPECT_FALSE(exact_first_hit(down(3, std::nextafter(4.0, 5.0)), disk).hit);

    const Plane<double> plane{{0, 0, 0}, {0, 0, 1}};
    EXPECT_FALSE(exact_first_hit(ray({0, 0, 1}, {1, 0, 0}), plane).hit);  // parallel
    EXPECT_FALSE(exact_first_hit(ray({0, 0, 0}, {1, 0, 0}), plane).hit);  // in the plane
    const ExactHit skim = exact_first_hit(ray({0, 0, 1}, {1, 0, -std::ldexp(1.0, -60)}), plane);
    ASSERT_TRUE(skim.hit);
    EXPECT_EQ(skim.t_double, std::ldexp(1.0, 60));
}

// ---- transformed ------------------------------------------------------------------------------------------
TEST(OracleExact, TransformedUsesTheExactInverseNotTheStoredOne)
{
    const Affine3<double> w{{{3, 0, 0, 10}, {0, 3, 0, 0}, {0, 0, 3, 0}}};
    // to_object deliberately wrong: the oracle must not read it.
    const Transformed<Sphere<double>> x{{{0, 0, 0}, 1}, w, Affine3<double>::identity()};
    const ExactHit h = exact_first_hit(ray({0, 0, 0}, {1, 0, 0}), x);
    ASSERT_TRUE(h.hit);
    EXPECT_EQ(h.t_double, 7.0);
    EXPECT_TRUE(h.entering);
    expect_normal(h, {-1, 0, 0});
    // The correctly rounded inverse.
    const Affine3<double> inv = rounded_inverse(w);
    EXPECT_EQ(inv.m[0][0], 1.0 / 3.0);
    EXPECT_EQ(inv.m[0][3], -10.0 / 3.0);
    EXPECT_EQ(inv.m[1][1], 1.0 / 3.0);
}

TEST(OracleExact, TransformedEllipsoidNormalGoesThroughTheInverseTranspose)
{
    // The unit sphere stretched by 2 along x: x²/4 + y² + z² = 1.
    const Affine3<double> w{{{2, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}}};
    const Transformed<Sphere<double>> x{{{0, 0, 0}, 1}, w, rounded_inverse(w)};
    const ExactHit along = exact_first_hit(ray({-5, 0, 0}, {1, 0, 0}), x);
    EXPECT_EQ(along.t_double, 3.0);
    const ExactHit h = exact_first_hit(ray({1, -5, 0}, {0, 1, 0}), x);  // y = −√(3/4)
    ASSERT_TRUE(h.hit);
    EXPECT_EQ(h.t_exact, "5 + -1/2*sqrt(3)");
    const double ny = -std::sqrt(0.75), nx = 0.25, len = std::sqrt(nx * nx + ny * ny);
    expect_normal(h, {nx / len, ny / len, 0});
}

TEST(OracleExact, TransformedByTheIdentityMatchesTheObject)
{
    std::mt19937_64 g(11);
    std::uniform_real_distribution<double> u(-3, 3);
    const Affine3<double> id = Affine3<double>::identity();
    for (int i = 0; i < 100; ++i) {
        const Ray<double> r = ray({u(g), u(g), u(g)}, {u(g), u(g), u(g)});
        const Cylinder<double> cyl{{u(g), u(g), u(g)}, {u(g), u(g), u(g)}, std::fabs(u(g)) + 0.1, i % 2 ? Caps::both : Caps::none};
        const Cone<double> cone{{u(g), u(g), u(g)}, std::fabs(u(g)), {u(g), u(g), u(g)}, std::fabs(u(g)) + 0.1, i % 2 ? Caps::both : Caps::none};
        const Triangle<double> tri{{u(g), u(g), u(g)}, {u(g), u(g), u(g)}, {u(g), u(g), u(g)}};
        const auto same = [](const ExactHit& a, const ExactHit& b) {
            EXPECT_EQ(a.hit, b.hit);
            EXPECT_EQ(a.t_exact, b.t_exact);
            EXPECT_EQ(a.part, b.part);
            EXPECT_EQ(a.entering, b.entering);
            EXPECT_EQ(a.outward_normal.x, b.outward_normal.x);
        };
        same(exact_first_hit(r, Transformed<Cylinder<double>>{cyl, id, id}), exact_first_hit(r, cyl));
        same(exact_first_hit(r, Transformed<Cone<double>>{cone, id, id}), exact_first_hit(r, cone));
        same(exact_first_hit(r, Transformed<Triangle<double>>{tri, id, id}), exact_first_hit(r, tri));
    }
}

// ---- the domain -------------------------------------------------------------------------------------------
TEST(OracleExact, InputsOutsideTheDomainAreUndefined)
{
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const Ray<double> r = ray({0, 0, -5}, {0, 0, 1});
    EXPECT_FALSE(exact_first_hit(r, Sphere<double>{{0, 0, 0}, 0}).defined);
    EXPECT_FALSE(exact_first_hit(r, Sphere<double>{{0, 0, nan}, 1}).defined);
    EXPECT_FALSE(exact_first_hit(ray({0, 0, 0}, {0, 0, 0}), Sphere<double>{{0, 0, 0}, 1}).defined);
    EXPECT_FALSE(exact_first_hit(ray({0, 0, -5}, {0, 0, 1}, 2, 1), Sphere<double>{{0, 0, 0}, 1}).defined);
    EXPECT_FALSE(exact_first_hit(r, Triangle<double>{{0, 0, 0}, {1, 1, 1}, {2, 2, 2}}).defined);
    EXPECT_FALSE(exact_first_hit(r, Cone<double>{{0, 0, 0}, 0, {0, 0, 1}, 0, Caps::none}).defined);
    EXPECT_FALSE(exact_first_hit(r, quadric(0, 0, 0, 0, 0, 0, 0, 0, 0, 1)).defined);
    const Affine3<double> singular{{{1, 0, 0, 0}, {0, 1, 0, 0}, {1, 1, 0, 0}}};
    EXPECT_FALSE(exact_first_hit(r, Transformed<Sphere<double>>{{{0, 0, 0}, 1}, singular, singular}).defined);
    EXPECT_TRUE(exact_first_hit(r, Sphere<double>{{0, 0, 0}, 1}).defined);
}

// ---- measuring a kernel answer ---------------------------------------------------------------------------
Hit<double> hit(double t, Vec3<double> n, bool front, double t_error = inf, Part part = Part::surface)
{
    Hit<double> h{};
    h.t = t;
    h.normal = n;
    h.front_face = front;
    h.part = part;
    h.t_error = t_error;
    return h;
}

TEST(OracleMeasure, UlpsFaithfulnessAndBounds)
{
    const Ray<double> r = ray({0, 0, -5}, {0, 0, 1});
    const Sphere<double> s{{0, 0, 0}, 1};  // exact t = 4
    const double up = std::nextafter(4.0, 5.0), down = std::nextafter(4.0, 3.0);

    Measurement m = measure(r, s, hit(4.0, {0, 0, -1}, true));
    EXPECT_TRUE(m.hit_agrees && m.both_hit && m.part_agrees && m.front_face_agrees && m.faithful);
    EXPECT_EQ(m.ulps, 0.0);
    EXPECT_EQ(m.normal_angle, 0.0);
    EXPECT_FALSE(m.bounded);
    EXPECT_FALSE(m.bound_violated);

    m = measure(r, s, hit(up, {0, 0, -1}, true, 0x1p-60));
    EXPECT_EQ(m.ulps, 1.0);
    EXPECT_FALSE(m.faithful);  // t is a double: only t itself is faithful
    EXPECT_TRUE(m.bounded);
    EXPECT_TRUE(m.bound_violated);
    EXPECT_TRUE(m.uncertified);  // no exact crossing (4 or 6) within 2^-60 of it
    EXPECT_FALSE(m.other_crossing);
    EXPECT_FALSE(measure(r, s, hit(up, {0, 0, -1}, true, up - 4.0)).bound_violated);  // exactly on the bound
    // Below a power of two the spacing halves, but the unit is the ulp above the T toward zero of t.
    EXPECT_EQ(measure(r, s, hit(down, {0, 0, -1}, true)).ulps, 0.5);
    EXPECT_TRUE(measure(r, s, hit(4.0, {0, 0, -1}, true, std::numeric_limits<double>::quiet_NaN())).bound_violated);

    // The wrong crossing: the exit at 6.
    m = measure(r, s, hit(6.0, {0, 0, 1}, false, 0.5));
    EXPECT_TRUE(m.bound_violated);
    EXPECT_FALSE(m.uncertified);  // 6 is an exact crossing within the bound
    EXPECT_TRUE(m.other_crossing);
    EXPECT_FALSE(m.front_face_agrees);
    EXPECT_NEAR(m.normal_angle, std::acos(-1.0), 1e-15);
    EXPECT_TRUE(measure(r, s, hit(5.0, {0, 0, -1}, true, 0.5)).uncertified);

    // Hit versus miss.
    m = measure(r, s, std::optional<Hit<double>>{});
    EXPECT_FALSE(m.hit_agrees);
    EXPECT_TRUE(m.exact_hit);
    EXPECT_FALSE(m.kernel_hit);
    EXPECT_TRUE(std::isnan(m.ulps));

    // A false hit: its finite bound is violated unless some crossing of the line lies within it.
    const Ray<double> past = ray({0, 0, 1}, {0, 0, 1});  // on the surface heading out: crossings −2 and 0
    m = measure(past, s, hit(0x1p-60, {0, 0, 1}, false, 0x1p-50));
    EXPECT_FALSE(m.hit_agrees);
    EXPECT_TRUE(m.bounded);
    EXPECT_FALSE(m.bound_violated);  // the crossing at 0 is within 2^-50 of it
    m = measure(ray({0, 2, -5}, {0, 0, 1}), s, hit(5.0, {0, 0, -1}, true, 0.5));  // exact miss, no crossing at all
    EXPECT_TRUE(m.bound_violated);
    EXPECT_TRUE(m.uncertified);
    EXPECT_FALSE(measure(ray({0, 2, -5}, {0, 0, 1}), s, hit(5.0, {0, 0, -1}, true)).bound_violated);  // no bound claimed

    // Irrational t: the two neighbours are faithful, the next ones are not.
    const Ray<double> r2 = ray({0.5, 0, -5}, {0, 0, 1});
    const double t = exact_first_hit(r2, s).t_double;
    const double other = t < 5.0 - std::sqrt(0.75L) ? std::nextafter(t, 5.0) : std::nextafter(t, 4.0);
    EXPECT_TRUE(measure(r2, s, hit(t, {0, 0, -1}, true)).faithful);
    EXPECT_TRUE(measure(r2, s, hit(other, {0, 0, -1}, true)).faithful);
    EXPECT_LE(measure(r2, s, hit(t, {0, 0, -1}, true)).ulps, 0.5);
    const double beyond = t < other ? std::nextafter(t, 4.0) : std::nextafter(t, 5.0);
    EXPECT_FALSE(measure(r2, s, hit(beyond, {0, 0, -1}, true)).faithful);
    EXPECT_GT(measure(r2, s, hit(beyond, {0, 0, -1}, true)).ulps, 1.0);

    // Parts.
    const Cylinder<double> cyl{{0, 0, 0}, {0, 0, 2}, 1, Caps::both};
    EXPECT_FALSE(measure(ray({0.5, 0, -1}, {0, 0, 1}), cyl, hit(1.0, {0, 0, -1}, true, inf, Part::surface)).part_agrees);
    EXPECT_TRUE(measure(ray({0.5, 0, -1}, {0, 0, 1}), cyl, hit(1.0, {0, 0, -1}, true, inf, Part::cap0)).part_agrees);
}

TEST(OracleMeasure, TypeMismatchIsALogicError)
{
    const Truth truth(Ray<float>{{0, 0, -5}, {0, 0, 1}}, Sphere<float>{{0, 0, 0}, 1});
    EXPECT_TRUE(truth.is_float());
    EXPECT_THROW(truth.measure(std::optional<Hit<double>>{}), std::logic_error);
    EXPECT_NO_THROW(truth.measure(std::optional<Hit<float>>{}));
}

// ---- the oracle's own consistency on random inputs ---------------------------------------------------------
TEST(OracleExact, RoundingsAreConsistent)
{
    std::mt19937_64 g(3);
    std::uniform_real_distribution<double> u(-10, 10);
    int hits = 0;
    for (int i = 0; i < 400; ++i) {
        const Ray<double> r = ray({u(g), u(g), u(g)}, {u(g), u(g), u(g)});
        const Cone<double> c{{u(g), u(g), u(g)}, std::fabs(u(g)), {u(g), u(g), u(g)}, std::fabs(u(g)) + 0.1, i % 2 ? Caps::both : Caps::none};
        const ExactHit h = exact_first_hit(r, c);
        ASSERT_TRUE(h.defined);
        if (!h.hit) continue;
        ++hits;
        // The double is the nearest to the 64-bit value; the float is within half a float ulp.
        const long double ulp_d = std::nextafter(std::fabs(h.t_double), inf) - std::fabs(h.t_double);
        EXPECT_LE(std::fabs(h.t_long - h.t_double), 0.5L * ulp_d + 1e-30L);
        const long double ulp_f = std::nextafter(std::fabs(h.t_float), 1e30f) - std::fabs(h.t_float);
        EXPECT_LE(std::fabs(h.t_long - h.t_float), 0.5L * ulp_f * (1 + 1e-9L));
        EXPECT_GT(h.t_double, 0.0);
        // Crossings ascend and contain the hit.
        for (std::size_t k = 1; k < h.crossings.size(); ++k) EXPECT_LE(h.crossings[k - 1], h.crossings[k]);
        EXPECT_NE(std::find(h.crossings.begin(), h.crossings.end(), h.t_long), h.crossings.end());
        if (h.normal_defined) {
            const Vec3<double>& n = h.outward_normal;
            EXPECT_NEAR(n.x * n.x + n.y * n.y + n.z * n.z, 1.0, 1e-15);
            const Vec3<double>& f = h.facing_normal;
            EXPECT_LE(f.x * r.direction.x + f.y * r.direction.y + f.z * r.direction.z, 1e-12);
        }
    }
    EXPECT_GT(hits, 50);
}

}  // namespace
