// Scenes and ray families shared by the adapter's tests: random spheres and capped cylinders in
// the cube [-1, 1]³ (optionally moved far away), rays aimed into it from outside, rays starting
// inside primitives, rays grazing a primitive's silhouette.
#pragma once

#include <rayq/rayq.hpp>

#include <cmath>
#include <cstdint>
#include <optional>
#include <random>
#include <vector>

namespace rayq_embree_test {

template <class T>
rayq::Vec3<T> narrow(const rayq::Vec3<double>& v) { return {T(v.x), T(v.y), T(v.z)}; }

// Primitive sizes shrink as N grows (~0.25·N^(-1/3)), so a ray meets a few of them at every N.
template <class Prim>
std::vector<Prim> random_primitives(std::size_t n, const rayq::Vec3<double>& offset, std::uint64_t seed)
{
    using T = rayq::scalar_t<Prim>;
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> u(-1, 1);
    std::normal_distribution<double> g;
    std::vector<Prim> out;
    const double r = 0.25 / std::cbrt(double(n));
    for (std::size_t i = 0; i < n; ++i) {
        const rayq::Vec3<double> c = rayq::Vec3<double>{u(rng), u(rng), u(rng)} + offset;
        if constexpr (std::is_same_v<Prim, rayq::Sphere<T>>) {
            out.push_back({narrow<T>(c), T(r * (0.5 + 0.25 * (u(rng) + 1)))});
        } else {
            const rayq::Vec3<double> axis = rayq::normalize(rayq::Vec3<double>{g(rng), g(rng), g(rng)}) * (r * (0.5 + 0.5 * (u(rng) + 1)));
            out.push_back({narrow<T>(c - axis), narrow<T>(c + axis), T(r * 0.6), rayq::Caps::both});
        }
    }
    return out;
}

// Rays from a sphere of radius 4 around the scene's centre, aimed at random points of its cube.
template <class T>
std::vector<rayq::Ray<T>> aimed_rays(std::size_t count, const rayq::Vec3<double>& offset, std::uint64_t seed)
{
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> u(-1, 1);
    std::normal_distribution<double> g;
    std::vector<rayq::Ray<T>> rays;
    for (std::size_t i = 0; i < count; ++i) {
        rayq::Vec3<double> o{g(rng), g(rng), g(rng)};
        o = o * (4.0 / rayq::length(o));
        const rayq::Vec3<double> target{u(rng), u(rng), u(rng)};
        rays.push_back({narrow<T>(o + offset), narrow<T>(rayq::normalize(target - o))});
    }
    return rays;
}

// The centre of a primitive (sphere centre, cylinder axis midpoint), in double.
template <class T>
rayq::Vec3<double> centre_of(const rayq::Sphere<T>& s) { return {s.center.x, s.center.y, s.center.z}; }
template <class T>
rayq::Vec3<double> centre_of(const rayq::Cylinder<T>& c)
{
    return rayq::Vec3<double>{double(c.p0.x) + c.p1.x, double(c.p0.y) + c.p1.y, double(c.p0.z) + c.p1.z} * 0.5;
}

// Rays starting at a primitive's centre (inside it), in random directions: the first hit leaves.
template <class Prim>
std::vector<rayq::Ray<rayq::scalar_t<Prim>>> inside_rays(const std::vector<Prim>& prims, std::size_t count, std::uint64_t seed)
{
    using T = rayq::scalar_t<Prim>;
    std::mt19937_64 rng(seed);
    std::normal_distribution<double> g;
    std::vector<rayq::Ray<T>> rays;
    for (std::size_t i = 0; i < count; ++i) {
        const Prim& p = prims[rng() % prims.size()];
        rays.push_back({narrow<T>(centre_of(p)), narrow<T>(rayq::normalize(rayq::Vec3<double>{g(rng), g(rng), g(rng)}))});
    }
    return rays;
}

// Rays starting on a primitive's surface (where a ray from a centre first meets one, to
// rounding), in random directions, tmin = 0: the crossing at the origin lies within rounding of
// tmin, so whether it counts (and whether the hit's bound must reach back to tmin) is the hard part.
template <class Prim>
std::vector<rayq::Ray<rayq::scalar_t<Prim>>> surface_rays(const std::vector<Prim>& prims, std::size_t count, std::uint64_t seed)
{
    using T = rayq::scalar_t<Prim>;
    // The second family's directions serve as the new random directions.
    const auto from_centre = inside_rays(prims, count, seed), turned = inside_rays(prims, count, seed + 1);
    std::vector<rayq::Ray<T>> rays;
    for (std::size_t k = 0; k < from_centre.size(); ++k) {
        std::optional<rayq::Hit<T>> first;
        for (const Prim& p : prims)
            if (const auto h = rayq::intersect(rayq::accurate, from_centre[k], p); h && (!first || h->t < first->t)) first = h;
        if (first) rays.push_back({first->point, turned[k].direction});
    }
    return rays;
}

// Rays tangent (in double, before rounding to T) to a random sphere, or through a random point of
// a cylinder's rim circle along the cap plane: near-tangent in T, the decisions that are hard.
template <class Prim>
std::vector<rayq::Ray<rayq::scalar_t<Prim>>> grazing_rays(const std::vector<Prim>& prims, std::size_t count, std::uint64_t seed)
{
    using T = rayq::scalar_t<Prim>;
    std::mt19937_64 rng(seed);
    std::normal_distribution<double> g;
    std::vector<rayq::Ray<T>> rays;
    for (std::size_t i = 0; i < count; ++i) {
        const Prim& p = prims[rng() % prims.size()];
        const rayq::Vec3<double> d = rayq::normalize(rayq::Vec3<double>{g(rng), g(rng), g(rng)});
        rayq::Vec3<double> touch;
        rayq::Vec3<double> dir = d;
        if constexpr (std::is_same_v<Prim, rayq::Sphere<T>>) {
            // Any unit vector perpendicular to d, scaled to the radius, from the centre.
            const rayq::Vec3<double> perp = rayq::normalize(rayq::cross(d, rayq::Vec3<double>{g(rng), g(rng), g(rng)}));
            touch = centre_of(p) + perp * double(p.radius);
        } else {
            const rayq::Vec3<double> p0{p.p0.x, p.p0.y, p.p0.z}, p1{p.p1.x, p.p1.y, p.p1.z};
            const rayq::Vec3<double> a = rayq::normalize(p1 - p0);
            const rayq::Vec3<double> radial = rayq::normalize(rayq::cross(a, d));
            touch = (rng() & 1 ? p0 : p1) + radial * double(p.radius);
            dir = rayq::normalize(rayq::cross(radial, a) + a * (1e-3 * g(rng)));  // along the cap's plane, or nearly
        }
        rays.push_back({narrow<T>(touch - dir * 5.0), narrow<T>(dir)});
    }
    return rays;
}

}  // namespace rayq_embree_test
