// Hit::t_error is certified: the exact root lies within it (reference: quad_reference.hpp).
#include "quad_reference.hpp"
#include "test_support.hpp"

#include <random>

namespace rayq::test::certified_bound_test {
namespace {

template <class C>
class CertifiedBoundTest : public ::testing::Test {};
TYPED_TEST_SUITE(CertifiedBoundTest, AllConfigs, ConfigNames);

template <class Policy, class Prim>
void check_bound(Policy policy, const Prim& prim, const char* name, std::uint64_t seed, double world = 1, double squash_x = 1)
{
    using T = scalar_t<Prim>;
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> u(-1, 1), lg(-2, 2);
    int hits = 0, violations = 0, infinite = 0;
    double worst_ratio = 0;  // t_error / |t − t_exact|: how conservative (reported, not asserted)
    double max_ulps = 0, max_rel = 0;  // the error itself, reported per primitive and policy
    std::vector<double> ratios;
    for (int i = 0; i < 20000; ++i) {
        const double scale = std::pow(10.0, lg(rng));
        const Vec3<T> o{T(4 * world * u(rng)), T(4 * world * u(rng)), T(4 * world * u(rng))};
        const Vec3<T> aim{T(1.2 * world * u(rng)), T(1.2 * world * u(rng)), T(1.2 * world * u(rng))};
        const Vec3<T> d{T((aim.x - o.x) * scale * squash_x), T((aim.y - o.y) * scale), T((aim.z - o.z) * scale)};
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
        const quad ulp = quad(std::nextafter(h->t, std::numeric_limits<T>::infinity())) - quad(h->t);
        max_ulps = std::max(max_ulps, double(err / ulp));
        if (exact != 0) max_rel = std::max(max_rel, double(err / qabs(exact)));
        // The point bound follows from it: |point − exact point| per component.
        const Q3 p_exact = q3(o) + exact * q3(d);
        EXPECT_LE(double(qabs(quad(h->point.x) - p_exact.x)), double(h->point_error.x)) << name << " ray " << i;
        EXPECT_LE(double(qabs(quad(h->point.y) - p_exact.y)), double(h->point_error.y)) << name << " ray " << i;
        EXPECT_LE(double(qabs(quad(h->point.z) - p_exact.z)), double(h->point_error.z)) << name << " ray " << i;
    }
    std::sort(ratios.begin(), ratios.end());
    if (!ratios.empty()) worst_ratio = ratios.front();
    std::printf("t_error %-22s %-6s %-8s hits=%5d max_ulps=%-8.3g max_rel=%-8.2g violations=%d uncertified=%d bound/actual median=%.3g p99=%.3g min=%.3g\n", name,
                std::is_same_v<T, float> ? "float" : "double", ConfigNames::GetName<Config<T, Policy>>(0).c_str() + (std::is_same_v<T, float> ? 6 : 7),
                hits, max_ulps, max_rel, violations, infinite, ratios.empty() ? 0.0 : ratios[ratios.size() / 2],
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

// The cone's surface residual has degree eight: the static filter takes it only where every input
// is zero or within 2^±64 (query.hpp, static_residual), Bounded elsewhere. Both sides of that
// line: cones and rays scaled by 2^±12 (within), and rays whose direction's x is 2^-80 of its
// usual size (a nonzero input below 2^-64).
TYPED_TEST(CertifiedBoundTest, ConesOnBothSidesOfTheStaticRange)
{
    using T = typename TypeParam::T;
    const auto p = TypeParam::policy;
    for (const double world : {0x1p-12, 0x1p12}) {
        const auto at = [&](double x, double y, double z) { return v3<T>(x * world, y * world, z * world); };
        const std::string name = "cone frustum x2^" + std::to_string(int(std::log2(world)));
        check_bound(p, Cone<T>{at(-0.3, -0.6, -0.9), T(0.9 * world), at(0.5, 0.4, 0.8), T(0.2 * world), Caps::both}, name.c_str(), 14, world);
    }
    check_bound(p, Cone<T>{v3<T>(-0.3, -0.6, -0.9), T(0.9), v3<T>(0.5, 0.4, 0.8), T(0.2), Caps::both}, "cone frustum, d.x tiny", 15, 1, 0x1p-80);
}

}  // namespace
}  // namespace rayq::test::certified_bound_test
