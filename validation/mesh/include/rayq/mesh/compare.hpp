// rayq::mesh — the kernel against meshed primitives: agreement and convergence rates (issue 5).
//
// For a primitive and a resolution n, the same rays (fixed by the seed, independent of n) go to
// the kernel (rayq::accurate, double) and to the tessellation's Raycaster:
//   * the band: a ray is skipped when the kernel's answer (hit or miss, part, front face, and t
//     without a jump) changes for any of 14 translates of the ray by band_factor·deviation — the
//     ray's origin moved along ±u, ±v, ±d and the 8 diagonals of its (u, v, d) frame — or for any
//     of 8 tilts (toward ±u, ±v about either end of the ray's chord through the bounding ball, so
//     that every point of the chord moves by that distance). This takes out rays that pass within
//     that distance of a silhouette or a rim in projection, rays that run alongside a surface
//     containing lines parallel to them (generators, rulings: translates jump over those), and
//     origins that close to the surface: exactly where a mesh within `deviation` of the surface may
//     legitimately answer differently. So is a ray whose origin lies within that distance of the
//     (untrimmed) surface of any part, by the implicit function's first-order distance |F|/|∇F|.
//   * outside the band, every disagreement counts: hit vs miss, part (the hit face's region vs the
//     kernel's part), front face (face orientation vs the kernel's front_face), and t outliers
//     (|t_mesh − t_kernel| beyond 4·deviation/cos θ, θ the larger incidence of the two).
//   * errors: |t_mesh − t_kernel| and the angle between the mesh's interpolated normal and the
//     kernel's outward normal, collected separately for hits on curved parts and on flat parts
//     (caps, disks, polygons: there the mesh is the surface, so the error is rounding only).
// The rate is the least-squares slope of log(median error on curved parts) against log(n), the
// medians taken over the same rays at every n: those that are compared (outside the band, agreeing)
// curved-part hits at every resolution of the fit. (Per-level medians over all compared hits are
// reported too; at small n the band removes most near-tangent rays — the ones with the larger
// errors — so those medians come from a different, easier population and flatten the slope.)
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "mesh.hpp"

namespace rayq::mesh {

// One primitive of the cross-check, type-erased.
struct Case {
    std::string name;
    bool flat = false;     // every face lies exactly in the surface: t errors are rounding only
    bool closed = false;   // a closed solid
    bool apex = false;     // has a cone apex (the gradient vanishes; interpolated normals degrade there)
    std::function<Tessellation(int n)> tessellate;
    std::function<std::optional<Hit<double>>(const Ray<double>&)> intersect;  // rayq::accurate
    std::function<Vec3d(const Vec3d&, Part)> outward_normal;                  // the kernel's
    std::string reproducer;  // C++ for the primitive, fields as hex floats
};

// The primitives of the sweep: every bounded primitive, open and capped axial solids, frustum and
// apex cones, the bounded quadrics, and transformed instances (one with a reflection).
std::vector<Case> standard_cases();

struct SweepOptions {
    std::vector<int> resolutions{8, 16, 32, 64, 128, 256, 512};
    int rays = 20000;
    std::uint64_t seed = 1;
    double band_factor = 2.0;
    int max_examples = 8;  // disagreements kept per case, with reproducers
};

struct Disagreement {
    std::string kind;  // "hit/miss", "part", "front", "t outlier"
    int n;
    Ray<double> ray;
    std::string detail;  // kernel vs mesh answers, and a hex-float reproducer
};

struct ErrorStats {
    std::size_t count = 0;
    double median = 0, p90 = 0, max = 0;
};

struct Level {
    int n = 0;
    std::size_t faces = 0;
    double deviation = 0;
    std::size_t rays = 0, band = 0, compared_hits = 0, compared_misses = 0, inside_origins = 0;
    std::size_t hit_miss = 0, part = 0, front = 0, t_outliers = 0;
    ErrorStats t_curved, normal_curved, t_flat, normal_flat;  // over every compared hit of this level
    ErrorStats t_common, normal_common;  // over the rays compared on curved parts at every level (the fit's)
    double seconds = 0;
    std::size_t disagreements() const { return hit_miss + part + front + t_outliers; }
};

struct CaseResult {
    std::string name;
    bool flat = false, apex = false;
    std::vector<Level> levels;
    double slope_t = 0, slope_normal = 0;  // NaN when not measurable (flat primitives)
    std::vector<Disagreement> examples;
    std::size_t disagreements() const;
};

CaseResult run_case(const Case& c, const SweepOptions& options);

// Least-squares slope of log(y) against log(x); NaN unless every y is finite and positive.
double loglog_slope(const std::vector<double>& x, const std::vector<double>& y);

std::string hex(double v);          // "0x1.8p+1"
std::string hex(const Vec3d& v);    // "{0x1p+0, 0x0p+0, -0x1p-1}"
std::string describe(const Ray<double>& r);

}  // namespace rayq::mesh
