// Shared by the kernel tests: the float/double × policy grid, a random generator and small helpers.
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <optional>
#include <random>
#include <string>
#include <type_traits>

#include <rayq/rayq.hpp>

namespace rayq::test {

// The random draws the tests build primitives and rays from (seeded: every run draws the same).
struct Random {
    std::mt19937_64 rng;
    explicit Random(std::uint64_t seed) : rng(seed) {}

    double uniform(double a, double b) { return std::uniform_real_distribution<double>(a, b)(rng); }
    double log_uniform(double lo, double hi) { return std::pow(10.0, uniform(std::log10(lo), std::log10(hi))); }
    // Uniform on the sphere: three normal deviates, normalized.
    Vec3<double> unit_vector()
    {
        std::normal_distribution<double> n;
        return normalize(Vec3<double>{n(rng), n(rng), n(rng)});  // braces: drawn in order
    }
    Vec3<double> perpendicular(const Vec3<double>& a) { return normalize(cross(a, unit_vector())); }
};

template <class T_, class Policy_>
struct Config {
    using T = T_;
    using Policy = Policy_;
    static constexpr Policy policy{};
};

using AllConfigs = ::testing::Types<Config<float, fast_policy>, Config<float, stable_policy>, Config<float, accurate_policy>,
                                    Config<double, fast_policy>, Config<double, stable_policy>, Config<double, accurate_policy>>;

// The scalar types alone, for tests whose policies vary inside the test. Named types: GoogleTest's
// two-argument TYPED_TEST_SUITE leaves a variadic macro argument empty, which clang's -Wpedantic
// (the sanitizer build) rejects under -Werror.
using FloatTypes = ::testing::Types<float, double>;
struct FloatTypeNames {
    template <class T>
    static std::string GetName(int) { return std::is_same_v<T, float> ? "float" : "double"; }
};

struct ConfigNames {
    template <class C>
    static std::string GetName(int)
    {
        const std::string t = FloatTypeNames::GetName<typename C::T>(0);
        if (std::is_same_v<typename C::Policy, fast_policy>) return t + "_fast";
        if (std::is_same_v<typename C::Policy, stable_policy>) return t + "_stable";
        return t + "_accurate";
    }
};

template <class T>
Vec3<T> v3(double x, double y, double z) { return {T(x), T(y), T(z)}; }

template <class T>
Ray<T> ray(Vec3<T> o, Vec3<T> d, T tmin = T(0), T tmax = std::numeric_limits<T>::infinity()) { return {o, d, tmin, tmax}; }

// The same bits (so -0 differs from +0 and a NaN equals itself): answers that must agree exactly.
template <class T>
bool same_bits(const T& a, const T& b) { return std::memcmp(&a, &b, sizeof(T)) == 0; }

// Tolerance for analytic checks: a few ulps of the problem's scale.
template <class T>
T tol(double scale = 1.0) { return T(16) * std::numeric_limits<T>::epsilon() * T(scale); }

// The invariants every hit must satisfy, whatever the primitive.
template <class T>
void expect_well_formed(const Ray<T>& r, const Hit<T>& h)
{
    EXPECT_TRUE(std::isfinite(h.t));
    EXPECT_GT(h.t, r.tmin);
    EXPECT_LT(h.t, r.tmax);
    EXPECT_TRUE(std::isfinite(h.point.x) && std::isfinite(h.point.y) && std::isfinite(h.point.z));
    EXPECT_NEAR(double(length(h.normal)), 1.0, 1e-5);
    EXPECT_LE(double(dot(h.normal, r.direction)), 0.0);
    EXPECT_GE(h.t_error, T(0));  // not NaN
    EXPECT_TRUE(h.point_error.x >= T(0) && h.point_error.y >= T(0) && h.point_error.z >= T(0));
}

// intersect() and occluded() agree, and a hit is well formed.
template <class Policy, class Prim>
std::optional<Hit<scalar_t<Prim>>> checked_intersect(Policy p, const Ray<scalar_t<Prim>>& r, const Prim& prim)
{
    auto h = intersect(p, r, prim);
    EXPECT_EQ(h.has_value(), occluded(p, r, prim));
    if (h) expect_well_formed(r, *h);
    return h;
}

// The accurate closest hit and intersect_all's first passage: both present and the same t and
// t_error (the fuzz invariant intersect_all.first_is_intersect). Returns all passages.
template <class Prim>
Passages<scalar_t<Prim>> expect_first_passage_is_closest_hit(const Ray<scalar_t<Prim>>& r, const Prim& prim)
{
    const auto hit = intersect(accurate, r, prim);
    const auto all = intersect_all(accurate, r, prim);
    EXPECT_TRUE(hit);
    EXPECT_GE(all.size(), 1);
    if (hit && all.size() >= 1) {
        EXPECT_EQ(all[0].hit.t, hit->t);
        EXPECT_EQ(std::signbit(all[0].hit.t), std::signbit(hit->t));
        EXPECT_EQ(all[0].hit.t_error, hit->t_error);
    }
    return all;
}

}  // namespace rayq::test
