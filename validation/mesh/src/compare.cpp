// The kernel against the meshes: band, agreement, errors and rates. See rayq/mesh/compare.hpp.
#include "rayq/mesh/compare.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <random>

#include "rayq/mesh/raycast.hpp"

namespace rayq::mesh {

namespace {

constexpr double nan = std::numeric_limits<double>::quiet_NaN();

Vec3d unit(const Vec3d& v) { return v / length(v); }

double angle(const Vec3d& a, const Vec3d& b) { return std::atan2(length(cross(a, b)), dot(a, b)); }

const char* part_name(Part p) { return p == Part::cap0 ? "cap0" : (p == Part::cap1 ? "cap1" : "surface"); }

ErrorStats stats(std::vector<double> v)
{
    ErrorStats s;
    s.count = v.size();
    if (v.empty()) return s;
    std::sort(v.begin(), v.end());
    const auto at = [&](double q) {
        const double pos = q * static_cast<double>(v.size() - 1);
        const std::size_t i = static_cast<std::size_t>(pos);
        const double f = pos - static_cast<double>(i);
        return i + 1 < v.size() ? v[i] * (1 - f) + v[i + 1] * f : v[i];
    };
    s.median = at(0.5);
    s.p90 = at(0.9);
    s.max = v.back();
    return s;
}

struct Bound {
    Vec3d center;
    double radius;
};

Bound bounding_sphere(const Case& c)
{
    const Tessellation t = c.tessellate(32);
    Vec3d lo{1e300, 1e300, 1e300}, hi{-1e300, -1e300, -1e300};
    for (const auto v : t.mesh.vertices()) {
        const Vec3d p = to_vec(t.mesh.point(v));
        lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
        hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
    }
    const Vec3d center = 0.5 * (lo + hi);
    double r = 0;
    for (const auto v : t.mesh.vertices()) r = std::max(r, length(to_vec(t.mesh.point(v)) - center));
    return {center, 1.05 * r};
}

// Half the rays come from a sphere of radius 3R toward a random point of the bounding ball; half
// start anywhere in the ball (inside closed solids, or near the surface) in a random direction.
std::vector<Ray<double>> make_rays(const Bound& b, int count, std::uint64_t seed)
{
    std::mt19937_64 rng(seed);
    std::normal_distribution<double> gauss(0.0, 1.0);
    std::uniform_real_distribution<double> uniform(0.0, 1.0);
    const auto on_sphere = [&] {
        Vec3d v{};
        do v = {gauss(rng), gauss(rng), gauss(rng)};
        while (length(v) < 1e-3);
        return unit(v);
    };
    const auto in_ball = [&] { return on_sphere() * std::cbrt(uniform(rng)); };
    std::vector<Ray<double>> rays;
    rays.reserve(static_cast<std::size_t>(count));
    for (int i = 0; i < count; ++i) {
        if (i % 2 == 0) {
            const Vec3d origin = b.center + 3 * b.radius * on_sphere();
            const Vec3d target = b.center + b.radius * in_ball();
            rays.push_back({origin, unit(target - origin)});
        } else {
            rays.push_back({b.center + b.radius * in_ball(), on_sphere()});
        }
    }
    return rays;
}

struct Status {
    bool hit = false;
    Part part = Part::surface;
    bool front = false;
    double t = 0;
    double cos_incidence = 1;
};

Status status_of(const Case& c, const Ray<double>& r)
{
    const auto h = c.intersect(r);
    if (!h) return {};
    return {true, h->part, h->front_face, h->t, std::abs(dot(h->normal, r.direction)) / length(r.direction)};
}

// The band test. The ray is perturbed by `band` and the kernel asked again; any change of answer
// (hit or miss, part, front face, or a jump in t) puts the ray in the band.
//   * 14 translates: the origin moved by ±u, ±v, ±d and the 8 diagonals (±u ± v ± d)/√3 of the
//     ray's frame. They catch silhouettes and rims (within `band` in projection along d) and
//     origins within `band` of the surface.
//   * 8 tilts: the direction turned toward ±u, ±v about either end of the ray's chord through
//     the bounding ball, by 2·band/chord, so that every point of the chord moves by at least
//     `band` in some tilt. They catch rays that run alongside a surface containing lines parallel
//     to them (a ray along a cylinder's or a cone's generator, a hyperboloid's ruling, seen edge-on:
//     the translates jump over such a surface without changing the answer, while the mesh, within
//     `deviation` of it, may be met).
bool in_band(const Case& c, const Ray<double>& ray, const Status& s, double band, const Bound& bound)
{
    const double dl = length(ray.direction);
    const Vec3d d = ray.direction / dl;
    const Vec3d pick = std::abs(d.x) < 0.6 ? Vec3d{1, 0, 0} : Vec3d{0, 1, 0};
    const Vec3d u = unit(cross(d, pick)), v = cross(d, u);
    const auto changed = [&](const Ray<double>& moved, double expected) {
        const Status m = status_of(c, moved);
        if (m.hit != s.hit) return true;
        if (!s.hit) return false;
        if (m.part != s.part || m.front != s.front) return true;
        // t may move by the shift along d, plus the lateral shift over the slope of the surface;
        // more than that is a jump (to another sheet, or past a clipped near root).
        const double slack = 8 * band / std::max(std::min(s.cos_incidence, m.cos_incidence), 1e-3);
        return std::abs(m.t - expected) * dl > slack;
    };

    Vec3d offsets[14];
    int k = 0;
    for (const Vec3d& e : {u, v, d}) {
        offsets[k++] = e;
        offsets[k++] = -e;
    }
    const double g = 1 / std::sqrt(3.0);
    for (int i = 0; i < 8; ++i) offsets[k++] = g * ((i & 1 ? 1.0 : -1.0) * u + (i & 2 ? 1.0 : -1.0) * v + (i & 4 ? 1.0 : -1.0) * d);
    for (const Vec3d& o : offsets)
        if (changed({ray.origin + band * o, ray.direction, ray.tmin, ray.tmax}, s.t - band * dot(o, d) / dl)) return true;

    // The chord of the ray (t >= 0, in distance units along d) through the bounding ball.
    const Vec3d oc = ray.origin - bound.center;
    const double b = dot(oc, d), cc = dot(oc, oc) - bound.radius * bound.radius;
    const double disc = b * b - cc;
    if (disc <= 0) return false;
    const double t0 = std::max(0.0, -b - std::sqrt(disc)), t1 = -b + std::sqrt(disc);
    if (!(t1 > t0)) return false;
    const double beta = 2 * band / (t1 - t0);
    for (const double pivot : {t0, t1}) {
        const Vec3d p = ray.origin + pivot * d;
        for (const Vec3d& e : {u, -u, v, -v}) {
            const Vec3d dt = unit(d + beta * e);
            // Through the pivot, with the origin where it was when the pivot is the origin itself.
            const Vec3d origin = pivot == 0 ? ray.origin : p - pivot * dt;
            if (changed({origin, dt * dl, ray.tmin, ray.tmax}, s.t)) return true;
        }
    }
    return false;
}

// The origin within `band` of the surface of some part (first-order distance |F|/|∇F| to the
// untrimmed surface: conservative). The perturbed rays do not always see this — an origin next to
// the surface by an open rim, the ray leaving through the opening, misses under every perturbation
// while the mesh, inscribed, may put the origin on its other side.
bool near_surface(const Tessellation& t, const std::vector<Part>& parts, const Vec3d& origin, double band)
{
    for (const Part p : parts) {
        const Implicit im = t.implicit(origin, p);
        const double g = length(im.gradient);
        if (g > 0 && std::abs(im.value) < band * g) return true;
    }
    return false;
}

std::string kernel_text(const std::optional<Hit<double>>& k)
{
    if (!k) return "kernel: miss";
    return "kernel: t=" + hex(k->t) + " (" + std::to_string(k->t) + ") part=" + part_name(k->part) +
           " front_face=" + (k->front_face ? "1" : "0") + " point=" + hex(k->point);
}

std::string mesh_text(const std::optional<MeshHit>& m, const Tessellation& t)
{
    if (!m) return "mesh: miss";
    return "mesh: t=" + hex(m->t) + " (" + std::to_string(m->t) + ") face=" + std::to_string(m->face) +
           " part=" + part_name(t.part[static_cast<std::size_t>(m->face)]) + " front=" + (m->front ? "1" : "0") +
           " point=" + hex(m->point);
}

}  // namespace

std::size_t CaseResult::disagreements() const
{
    std::size_t n = 0;
    for (const Level& l : levels) n += l.disagreements();
    return n;
}

double loglog_slope(const std::vector<double>& x, const std::vector<double>& y)
{
    if (x.size() != y.size() || x.size() < 2) return nan;
    double sx = 0, sy = 0, sxx = 0, sxy = 0;
    const double n = static_cast<double>(x.size());
    for (std::size_t i = 0; i < x.size(); ++i) {
        if (!(x[i] > 0) || !(y[i] > 0) || !std::isfinite(y[i])) return nan;
        const double lx = std::log(x[i]), ly = std::log(y[i]);
        sx += lx;
        sy += ly;
        sxx += lx * lx;
        sxy += lx * ly;
    }
    return (n * sxy - sx * sy) / (n * sxx - sx * sx);
}

CaseResult run_case(const Case& c, const SweepOptions& o)
{
    CaseResult result;
    result.name = c.name;
    result.flat = c.flat;
    result.apex = c.apex;
    const Bound bound = bounding_sphere(c);
    const std::vector<Ray<double>> rays = make_rays(bound, o.rays, o.seed);
    std::vector<std::optional<Hit<double>>> kernel(rays.size());
    std::vector<Status> status(rays.size());
    for (std::size_t i = 0; i < rays.size(); ++i) {
        kernel[i] = c.intersect(rays[i]);
        status[i] = status_of(c, rays[i]);
    }

    // Per level and ray: the errors of a compared, agreeing hit on a curved part (NaN otherwise).
    std::vector<std::vector<double>> t_ray, n_ray;
    for (const int n : o.resolutions) {
        t_ray.emplace_back(rays.size(), nan);
        n_ray.emplace_back(rays.size(), nan);
        const auto start = std::chrono::steady_clock::now();
        const Tessellation t = c.tessellate(n);
        const Raycaster caster(t.mesh);
        Level level;
        level.n = n;
        level.faces = t.mesh.n_faces();
        level.deviation = t.deviation;
        // A floor for the exact (flat) meshes: skip rays within rounding of an edge.
        const double band = std::max(o.band_factor * t.deviation, 1e-12 * bound.radius);
        std::vector<Part> parts;
        for (const Part p : t.part)
            if (std::find(parts.begin(), parts.end(), p) == parts.end()) parts.push_back(p);
        std::vector<double> t_curved, n_curved, t_flat, n_flat;
        const auto record = [&](const char* kind, const Ray<double>& ray, const std::string& detail) {
            if (static_cast<int>(result.examples.size()) < o.max_examples) result.examples.push_back({kind, n, ray, detail});
        };
        for (std::size_t i = 0; i < rays.size(); ++i) {
            const Ray<double>& ray = rays[i];
            ++level.rays;
            const auto& k = kernel[i];
            if (near_surface(t, parts, ray.origin, band) || in_band(c, ray, status[i], band, bound)) {
                ++level.band;
                continue;
            }
            const auto m = caster.closest_hit(ray);
            if (m && (m->coplanar || m->degenerate)) {  // met edge-on: no orientation to compare
                ++level.band;
                continue;
            }
            const std::string where = "primitive " + c.reproducer + ", ray " + describe(ray) + ", n = " + std::to_string(n);
            if (k.has_value() != m.has_value()) {
                ++level.hit_miss;
                record("hit/miss", ray, kernel_text(k) + "; " + mesh_text(m, t) + "; " + where);
                continue;
            }
            if (!k) {
                ++level.compared_misses;
                continue;
            }
            ++level.compared_hits;
            if (!k->front_face) ++level.inside_origins;
            const Part mesh_part = t.part[static_cast<std::size_t>(m->face)];
            bool agree = true;
            if (mesh_part != k->part) {
                ++level.part;
                agree = false;
                record("part", ray, kernel_text(k) + "; " + mesh_text(m, t) + "; " + where);
            }
            if (m->front != k->front_face) {
                ++level.front;
                agree = false;
                record("front", ray, kernel_text(k) + "; " + mesh_text(m, t) + "; " + where);
            }
            if (!agree) continue;
            const Vec3d d = unit(ray.direction);
            const double t_err = std::abs(m->t - k->t) * length(ray.direction);
            const Vec3d face_n = face_normal(t.mesh, m->face);
            const double cos_mesh = std::abs(dot(face_n, d)) / length(face_n);
            const double cos_kernel = std::abs(dot(k->normal, d));
            if (t_err > 4 * t.deviation / std::max(std::min(cos_mesh, cos_kernel), 1e-6) + 1e-12 * bound.radius) {
                ++level.t_outliers;
                record("t outlier", ray, kernel_text(k) + "; " + mesh_text(m, t) + "; " + where);
                continue;
            }
            const Vec3d outward = k->front_face ? k->normal : -k->normal;
            const double n_err = angle(outward, m->normal);
            const bool curved = !c.flat && k->part == Part::surface;
            (curved ? t_curved : t_flat).push_back(t_err);
            (curved ? n_curved : n_flat).push_back(n_err);
            if (curved) {
                t_ray.back()[i] = t_err;
                n_ray.back()[i] = n_err;
            }
        }
        level.t_curved = stats(std::move(t_curved));
        level.normal_curved = stats(std::move(n_curved));
        level.t_flat = stats(std::move(t_flat));
        level.normal_flat = stats(std::move(n_flat));
        level.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        result.levels.push_back(level);
    }

    // The common rays: compared on a curved part at every level.
    std::vector<std::size_t> common;
    for (std::size_t i = 0; i < rays.size(); ++i) {
        bool all = true;
        for (const auto& level : t_ray) all = all && !std::isnan(level[i]);
        if (all) common.push_back(i);
    }
    std::vector<double> ns, te, ne;
    for (std::size_t l = 0; l < result.levels.size(); ++l) {
        Level& level = result.levels[l];
        std::vector<double> tc, nc;
        for (const std::size_t i : common) {
            tc.push_back(t_ray[l][i]);
            nc.push_back(n_ray[l][i]);
        }
        level.t_common = stats(std::move(tc));
        level.normal_common = stats(std::move(nc));
        ns.push_back(level.n);
        te.push_back(level.t_common.count ? level.t_common.median : nan);
        ne.push_back(level.normal_common.count ? level.normal_common.median : nan);
    }
    result.slope_t = c.flat ? nan : loglog_slope(ns, te);
    result.slope_normal = c.flat ? nan : loglog_slope(ns, ne);
    return result;
}

}  // namespace rayq::mesh
