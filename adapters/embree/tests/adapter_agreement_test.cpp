// rayq::embree::Scene against rayq's scalar loop over every primitive: for random rays aimed into
// scenes of 1, 16 and 1,000 spheres and capped cylinders, rays starting inside primitives or on
// their surfaces, grazing rays, and the same scenes moved 10⁴ away, under every policy in float
// and double, the adapter's closest hit is the loop's (same t bit for bit, same primitive, same
// record), nearest() gives the same t and primitive, and occluded agrees.
#include <rayq/embree.hpp>

#include <gtest/gtest.h>

#include <cstring>
#include <string>

#include "test_scenes.hpp"

namespace {

using namespace rayq_embree_test;

// The reference: intersect() over every primitive in order; the first of equal t wins.
template <class Policy, class Prim>
std::optional<std::pair<rayq::Hit<rayq::scalar_t<Prim>>, std::size_t>> brute_force(Policy policy, const rayq::Ray<rayq::scalar_t<Prim>>& ray,
                                                                                     const std::vector<Prim>& prims)
{
    std::optional<std::pair<rayq::Hit<rayq::scalar_t<Prim>>, std::size_t>> best;
    for (std::size_t i = 0; i < prims.size(); ++i)
        if (auto h = rayq::intersect(policy, ray, prims[i]); h && (!best || h->t < best->first.t)) best = std::make_pair(*h, i);
    return best;
}

template <class Policy, class Prim>
bool brute_force_any(Policy policy, const rayq::Ray<rayq::scalar_t<Prim>>& ray, const std::vector<Prim>& prims)
{
    for (const Prim& p : prims)
        if (rayq::occluded(policy, ray, p)) return true;
    return false;
}

template <class T>
bool same_bits(T a, T b) { return std::memcmp(&a, &b, sizeof a) == 0; }

template <class T>
bool same_bits(const rayq::Vec3<T>& a, const rayq::Vec3<T>& b) { return same_bits(a.x, b.x) && same_bits(a.y, b.y) && same_bits(a.z, b.z); }

struct Tally {
    std::size_t rays = 0, hits = 0, mismatches = 0;
};

// Compares one ray; returns false (and says why) on the first disagreement.
template <class Policy, class Prim>
void compare(const rayq::embree::Scene<Prim, Policy>& scene, Policy policy, const std::vector<Prim>& prims,
             const rayq::Ray<rayq::scalar_t<Prim>>& ray, const std::string& what, Tally& tally)
{
    ++tally.rays;
    const auto expected = brute_force(policy, ray, prims);
    const auto got = scene.intersect(ray);
    tally.hits += expected.has_value();
    const bool any = scene.occluded(ray);
    const auto ref = scene.nearest(ray);  // the same answer without the record
    bool ok = expected.has_value() == got.has_value() && any == brute_force_any(policy, ray, prims) &&
              ref.has_value() == got.has_value() && (!ref || (same_bits(ref->t, got->hit.t) && ref->primID == got->primID));
    if (ok && expected) {
        const auto& e = expected->first;
        const auto& g = got->hit;
        ok = same_bits(e.t, g.t) && expected->second == got->primID && got->geomID == 0 && same_bits(e.normal, g.normal) &&
             e.part == g.part && e.front_face == g.front_face && same_bits(e.t_error, g.t_error) && same_bits(e.point, g.point) &&
             got->tfar >= float(e.t) && (sizeof(e.t) == 4 ? got->tfar == float(e.t) : true);
    }
    if (!ok && ++tally.mismatches <= 5) {
        ADD_FAILURE() << what << ": ray o=(" << ray.origin.x << ", " << ray.origin.y << ", " << ray.origin.z << ") d=(" << ray.direction.x
                      << ", " << ray.direction.y << ", " << ray.direction.z << "): loop "
                      << (expected ? "hit t=" + std::to_string(double(expected->first.t)) + " #" + std::to_string(expected->second) : "miss")
                      << ", adapter "
                      << (got ? "hit t=" + std::to_string(double(got->hit.t)) + " #" + std::to_string(got->primID) : "miss")
                      << ", occluded " << any;
    }
}

template <class Prim, class Policy>
void agreement(Policy policy, const char* policy_name, double far)
{
    using T = rayq::scalar_t<Prim>;
    const rayq::Vec3<double> offset{far, -far, far};
    for (std::size_t n : {std::size_t(1), std::size_t(16), std::size_t(1000)}) {
        const std::vector<Prim> prims = random_primitives<Prim>(n, offset, 0xE3B0 + n);
        rayq::embree::Options options;
        options.device_config = "threads=1";
        options.max_leaf_size = n == 1000 ? 3 : 0;  // leaves of several primitives (automatic: 1 at this size)
        const rayq::embree::Scene<Prim, Policy> scene(prims, policy, options);
        const std::size_t count = n == 1000 ? 150 : 300;
        const std::string what = std::string(policy_name) + (sizeof(T) == 4 ? " float" : " double") + " N=" + std::to_string(n) +
                                 (far != 0 ? " far" : "");
        Tally aimed, inside, surface, grazing, from_origin;
        for (const auto& ray : aimed_rays<T>(count, offset, 0xA1 + n)) compare(scene, policy, prims, ray, what + " aimed", aimed);
        for (const auto& ray : inside_rays(prims, count / 3, 0xB2 + n)) compare(scene, policy, prims, ray, what + " inside", inside);
        for (const auto& ray : surface_rays(prims, count / 3, 0xE5 + n)) compare(scene, policy, prims, ray, what + " from the surface", surface);
        for (const auto& ray : grazing_rays(prims, count, 0xC3 + n)) compare(scene, policy, prims, ray, what + " grazing", grazing);
        if (far != 0) {
            // Far-away scenes seen from the world origin: |origin − primitive| ≈ 1.7·10⁴.
            for (auto ray : aimed_rays<T>(count / 3, offset, 0xD4 + n)) {
                ray.direction = narrow<T>(rayq::normalize(rayq::Vec3<double>{ray.origin.x, ray.origin.y, ray.origin.z} +
                                                          rayq::Vec3<double>{ray.direction.x, ray.direction.y, ray.direction.z} * 4.0));
                ray.origin = {T(0), T(0), T(0)};
                compare(scene, policy, prims, ray, what + " from the origin", from_origin);
            }
        }
        EXPECT_EQ(aimed.mismatches + inside.mismatches + surface.mismatches + grazing.mismatches + from_origin.mismatches, 0u) << what;
        // The families must exercise both answers, or the comparison proves little.
        EXPECT_GT(aimed.hits, 0u) << what;
        EXPECT_LT(aimed.hits, aimed.rays) << what;
        EXPECT_EQ(inside.hits, inside.rays) << what << ": a ray from inside a closed primitive always leaves it";
        EXPECT_GT(grazing.hits, 0u) << what;
        EXPECT_GT(surface.hits, 0u) << what;
    }
}

template <class Prim>
void agreement_every_policy(double far)
{
    agreement<Prim>(rayq::fast, "fast", far);
    agreement<Prim>(rayq::stable, "stable", far);
    agreement<Prim>(rayq::accurate, "accurate", far);
}

TEST(EmbreeAgreement, SpheresFloat) { agreement_every_policy<rayq::Sphere<float>>(0); }
TEST(EmbreeAgreement, SpheresDouble) { agreement_every_policy<rayq::Sphere<double>>(0); }
TEST(EmbreeAgreement, CappedCylindersFloat) { agreement_every_policy<rayq::Cylinder<float>>(0); }
TEST(EmbreeAgreement, CappedCylindersDouble) { agreement_every_policy<rayq::Cylinder<double>>(0); }
TEST(EmbreeAgreement, FarAwaySpheresFloat) { agreement_every_policy<rayq::Sphere<float>>(1e4); }
TEST(EmbreeAgreement, FarAwaySpheresDouble) { agreement_every_policy<rayq::Sphere<double>>(1e4); }
TEST(EmbreeAgreement, FarAwayCappedCylindersFloat) { agreement_every_policy<rayq::Cylinder<float>>(1e4); }
TEST(EmbreeAgreement, FarAwayCappedCylindersDouble) { agreement_every_policy<rayq::Cylinder<double>>(1e4); }

// Equal t on two primitives (the same sphere twice): the lower index wins, as in the scalar loop,
// whichever one Embree's traversal visits first.
TEST(EmbreeAgreement, TiesGoToTheLowerIndex)
{
    const rayq::Sphere<float> s{{0, 0, 5}, 1};
    const std::vector<rayq::Sphere<float>> prims{{{3, 0, 5}, 0.5f}, s, {{-3, 0, 5}, 0.5f}, s, s};
    const rayq::embree::Scene<rayq::Sphere<float>, rayq::accurate_policy> scene(prims);
    const auto hit = scene.intersect({{0, 0, 0}, {0, 0, 1}});
    ASSERT_TRUE(hit.has_value());
    EXPECT_EQ(hit->primID, 1u);
    EXPECT_EQ(hit->hit.t, 4.0f);
}

}  // namespace
