// Tessellators: every bounded primitive as rows of vertices in a parametric domain (angle around an
// axis × position along it), stitched into outward triangles. See rayq/mesh/mesh.hpp.
#include "rayq/mesh/mesh.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace rayq::mesh {
namespace {

constexpr double pi = 3.14159265358979323846;
using VH = TriMesh::VertexHandle;

Vec3d unit(const Vec3d& v)
{
    const double l = length(v);
    return l > 0 ? v / l : v;
}

void require(bool ok, const std::string& what)
{
    if (!ok) throw std::invalid_argument("rayq::mesh::tessellate: " + what);
}

template <class Prim>
void require_valid(const Prim& p, int n)
{
    const Validation v = validate(p);
    require(static_cast<bool>(v), v.reason ? v.reason : "invalid primitive");
    require(n >= 3, "n must be at least 3");
}

// A right-handed orthonormal frame (e1 × e2 = e3).
struct Frame {
    Vec3d origin, e1, e2, e3;
    Vec3d dir(double x, double y, double z) const { return x * e1 + y * e2 + z * e3; }
};

Frame frame_along(const Vec3d& origin, const Vec3d& axis)
{
    const Vec3d e3 = unit(axis);
    const double ax = std::abs(e3.x), ay = std::abs(e3.y), az = std::abs(e3.z);
    const Vec3d pick = ax <= ay && ax <= az ? Vec3d{1, 0, 0} : (ay <= az ? Vec3d{0, 1, 0} : Vec3d{0, 0, 1});
    const Vec3d e1 = unit(pick - dot(pick, e3) * e3);
    return {origin, e1, cross(e3, e1), e3};
}

// cos and sin, exact at multiples of π/2 (where std::cos(π/2) gives 6e-17, not 0).
int quarter_turn(double a)
{
    const double q = a / (pi / 2), r = std::nearbyint(q);
    if (std::abs(q - r) > 1e-12) return -1;
    return static_cast<int>((static_cast<long>(r) % 4 + 4) % 4);
}
double cos_(double a)
{
    static constexpr double table[4] = {1, 0, -1, 0};
    const int k = quarter_turn(a);
    return k < 0 ? std::cos(a) : table[k];
}
double sin_(double a)
{
    static constexpr double table[4] = {0, 1, 0, -1};
    const int k = quarter_turn(a);
    return k < 0 ? std::sin(a) : table[k];
}

// Rings along a patch: in proportion to n, so that the triangles stay roughly isotropic (`ratio`:
// the patch's length along over its largest circumference), and exactly doubling when n doubles —
// the meshes at n = 8, 16, 32 … are nested refinements along as well as around.
int bands_for(int n, double ratio)
{
    const int per8 = std::max(1, static_cast<int>(std::ceil(8 * ratio - 1e-9)));
    return std::max(1, static_cast<int>(std::ceil(n * per8 / 8.0 - 1e-9)));
}

// The angle of column j of n, and of the middle of the face between columns j and j + 1.
double column_angle(int j, int n) { return 2 * pi * j / n; }
double middle_angle(int j, int n) { return 2 * pi * (j + 0.5) / n; }

// Adds vertices and faces, with corner normals on the halfedges (the one pointing into the corner).
class Builder {
public:
    explicit Builder(Tessellation& t) : t_(t) {}

    VH vertex(const Vec3d& p, const Vec3d& normal)
    {
        const VH v = t_.mesh.add_vertex(to_om(p));
        t_.mesh.set_normal(v, to_om(unit(normal)));
        return v;
    }

    struct Corner {
        VH v;
        Vec3d normal;
    };

    // Faces with a repeated vertex (collapsed at a pole) are skipped.
    void face(const Corner& a, const Corner& b, const Corner& c, Part part)
    {
        if (a.v == b.v || b.v == c.v || a.v == c.v) return;
        const auto f = t_.mesh.add_face(a.v, b.v, c.v);
        if (!f.is_valid()) throw std::logic_error("rayq::mesh: OpenMesh refused a face (non-manifold configuration)");
        for (const auto h : t_.mesh.fh_range(f)) {
            const VH to = t_.mesh.to_vertex_handle(h);
            const Vec3d& n = to == a.v ? a.normal : (to == b.v ? b.normal : c.normal);
            t_.mesh.set_normal(h, to_om(unit(n)));
        }
        t_.part.push_back(part);
    }

    // Vertex normals of creases and apexes: the normalized sum of the incident corner normals,
    // wherever those differ from the vertex normal.
    void finish()
    {
        TriMesh& m = t_.mesh;
        for (const auto v : m.vertices()) {
            OpenMesh::Vec3d sum(0, 0, 0);
            bool differ = false;
            for (const auto h : m.vih_range(v)) {
                if (m.is_boundary(h)) continue;
                sum += m.normal(h);
                differ = differ || m.normal(h) != m.normal(v);
            }
            if (differ && sum.norm() > 0) m.set_normal(v, sum / sum.norm());
        }
    }

    Tessellation& t_;
};

// One row of a parametric patch: a ring of n vertices, or a single vertex (a pole).
struct Row {
    std::vector<VH> v;
    bool pole() const { return v.size() == 1; }
    VH at(int j) const { return pole() ? v[0] : v[static_cast<std::size_t>(j)]; }
};

// The corner normal of row r at angle phi (a pole is asked at the middle angle of the face).
using RowNormal = std::function<Vec3d(int row, double phi)>;

// Stitches consecutive rows into triangles (a, c, d), (a, d, b) for the quad a = A[j], b = A[j+1],
// c = B[j], d = B[j+1]. The whole patch is flipped when its middle band comes out against the
// analytic normal, so the patch is oriented by its normal field.
void stitch(Builder& b, const std::vector<Row>& rows, int n, const RowNormal& normal, Part part)
{
    const TriMesh& m = b.t_.mesh;
    // Orientation from the middle band's first non-degenerate triangle.
    const int mid = static_cast<int>(rows.size() - 1) / 2;
    bool flip = false;
    {
        const Row& A = rows[static_cast<std::size_t>(mid)];
        const Row& B = rows[static_cast<std::size_t>(mid) + 1];
        const VH a = A.at(0), bb = A.at(1 % n), c = B.at(0), d = B.at(1 % n);
        const VH t0 = a, t1 = A.pole() ? c : (B.pole() ? d : c), t2 = A.pole() ? d : (B.pole() ? bb : d);
        const Vec3d pa = to_vec(m.point(t0)), pb = to_vec(m.point(t1)), pc = to_vec(m.point(t2));
        const Vec3d geometric = cross(pb - pa, pc - pa);
        const Vec3d analytic = normal(mid, middle_angle(0, n)) + normal(mid + 1, middle_angle(0, n));
        flip = dot(geometric, analytic) < 0;
    }
    for (std::size_t r = 0; r + 1 < rows.size(); ++r) {
        const Row& A = rows[r];
        const Row& B = rows[r + 1];
        const int ra = static_cast<int>(r), rb = static_cast<int>(r + 1);
        for (int j = 0; j < n; ++j) {
            const int k = (j + 1) % n;
            const double mid_phi = middle_angle(j, n);
            const auto corner = [&](const Row& row, int index, int col) {
                return Builder::Corner{row.at(col), normal(index, row.pole() ? mid_phi : column_angle(col, n))};
            };
            const Builder::Corner a = corner(A, ra, j), bb = corner(A, ra, k), c = corner(B, rb, j), d = corner(B, rb, k);
            if (!flip) {
                b.face(a, c, d, part);
                b.face(a, d, bb, part);
            } else {
                b.face(a, d, c, part);
                b.face(a, bb, d, part);
            }
        }
    }
}

// The rows of a patch: point(r, phi) for r in [0, rows); `pole(r)` rows get one vertex. The first
// and last rows can be given (shared with a neighbouring patch).
std::vector<Row> make_rows(Builder& b, int rows, int n, const std::function<bool(int)>& pole,
                           const std::function<Vec3d(int, double)>& point, const RowNormal& normal,
                           const Row* first = nullptr, const Row* last = nullptr)
{
    std::vector<Row> out(static_cast<std::size_t>(rows));
    for (int r = 0; r < rows; ++r) {
        if (r == 0 && first) { out[0] = *first; continue; }
        if (r == rows - 1 && last) { out[static_cast<std::size_t>(r)] = *last; continue; }
        Row& row = out[static_cast<std::size_t>(r)];
        if (pole(r)) row.v.push_back(b.vertex(point(r, 0), normal(r, 0)));
        else
            for (int j = 0; j < n; ++j) row.v.push_back(b.vertex(point(r, column_angle(j, n)), normal(r, column_angle(j, n))));
    }
    return out;
}

// Sampson distance |F|/|∇F| at the centroid, edge midpoints and three interior points of every
// face: the measured deviation of the mesh from the surface.
double measure_deviation(const Tessellation& t)
{
    const TriMesh& m = t.mesh;
    double worst = 0;
    static constexpr double w[7][3] = {{1. / 3, 1. / 3, 1. / 3}, {.5, .5, 0}, {0, .5, .5}, {.5, 0, .5},
                                       {2. / 3, 1. / 6, 1. / 6}, {1. / 6, 2. / 3, 1. / 6}, {1. / 6, 1. / 6, 2. / 3}};
    for (const auto f : m.faces()) {
        std::array<Vec3d, 3> p{};
        int i = 0;
        for (const auto h : m.fh_range(f)) p[static_cast<std::size_t>(i++)] = to_vec(m.point(m.to_vertex_handle(h)));
        const Part part = t.part[static_cast<std::size_t>(f.idx())];
        for (const auto& wi : w) {
            const Vec3d q = wi[0] * p[0] + wi[1] * p[1] + wi[2] * p[2];
            const Implicit im = t.implicit(q, part);
            const double g = length(im.gradient);
            if (g > 0) worst = std::max(worst, std::abs(im.value) / g);
        }
    }
    return std::max(worst, t.rim_deviation);
}

Tessellation finish(Tessellation t, Builder& b)
{
    b.finish();
    t.deviation = measure_deviation(t);
    return t;
}

// ---------------------------------------------------------------------------------------------
// Axial solids: cylinder and cone (a cylinder is a cone with r0 = r1).

Tessellation axial(const Vec3d& p0, double r0, const Vec3d& p1, double r1, bool capped, int n)
{
    Tessellation t;
    Builder b(t);
    const Vec3d axis = p1 - p0;
    const double len = length(axis);
    const Frame f = frame_along(p0, axis);
    const double k = (r1 - r0) / len;  // dr/dh
    const double slant = std::hypot(len, r1 - r0);
    const int bands = bands_for(n, slant / (2 * pi * std::max(r0, r1)));
    const auto u_of = [bands](int r) { return static_cast<double>(r) / bands; };
    const auto radius = [&](int r) { return r == 0 ? r0 : (r == bands ? r1 : r0 + u_of(r) * (r1 - r0)); };
    const auto center = [&](int r) { return r == 0 ? p0 : (r == bands ? p1 : p0 + u_of(r) * axis); };
    const RowNormal side_normal = [&](int, double phi) { return f.dir(cos_(phi), sin_(phi), -k); };
    const auto side_point = [&](int r, double phi) {
        const double rr = radius(r);
        return rr == 0 ? center(r) : center(r) + f.dir(rr * cos_(phi), rr * sin_(phi), 0);
    };
    const std::vector<Row> side =
        make_rows(b, bands + 1, n, [&](int r) { return radius(r) == 0; }, side_point, side_normal);
    stitch(b, side, n, side_normal, Part::surface);

    if (capped) {
        const int rings = std::max(1, n / 8);
        for (const Part cap : {Part::cap0, Part::cap1}) {
            const bool at0 = cap == Part::cap0;
            const double rr = at0 ? r0 : r1;
            if (rr == 0) continue;  // an apex has no cap
            const Vec3d c = at0 ? p0 : p1;
            const Vec3d n_cap = at0 ? -f.e3 : f.e3;
            const RowNormal cap_normal = [n_cap](int, double) { return n_cap; };
            const auto cap_point = [&](int r, double phi) {
                const double rho = rr * r / rings;
                return r == 0 ? c : c + f.dir(rho * cos_(phi), rho * sin_(phi), 0);
            };
            const Row& rim = at0 ? side.front() : side.back();
            const std::vector<Row> rows = make_rows(b, rings + 1, n, [](int r) { return r == 0; }, cap_point, cap_normal, nullptr, &rim);
            stitch(b, rows, n, cap_normal, cap);
        }
    }
    t.closed = capped;
    // The boundary rings (open ends, or the rims the caps share) are polygons inscribed in circles.
    t.rim_deviation = std::max(r0, r1) * (1 - std::cos(pi / n));

    const double norm = std::sqrt(1 + k * k);
    const Frame fr = f;
    t.implicit = [fr, r0, k, len, norm](const Vec3d& p, Part part) -> Implicit {
        const Vec3d q = p - fr.origin;
        const double h = dot(q, fr.e3);
        if (part == Part::cap0) return {-h, -fr.e3};
        if (part == Part::cap1) return {h - len, fr.e3};
        const Vec3d radial = q - h * fr.e3;
        const double rho = length(radial);
        const Vec3d rhat = rho > 0 ? radial / rho : fr.e1;
        return {(rho - (r0 + k * h)) / norm, (rhat - k * fr.e3) / norm};
    };
    return finish(std::move(t), b);
}

// ---------------------------------------------------------------------------------------------
// Quadrics whose axes are those of a frame: A x² + B y² + C z² + G x + H y + I z + J in frame
// coordinates, cut by lo <= z <= hi. Tessellated by height: the cross-section at z is the ellipse
// A'(x − x0)² + B'(y − y0)² = −q(z) (coefficients normalized so that A', B' > 0).

struct AxisQuadric {
    double A, B, C, G, H, I, J;
    double lo, hi;  // z range of the clip (may be infinite)
};

struct Interval {
    double za, zb;
    bool pole_a, pole_b;  // the end is a root of q (the surface closes there), not a clip plane
    bool apex_a, apex_b;  // ... a double root (a cone's apex, where the gradient vanishes)
};

void add_quadric(Tessellation& t, Builder& b, const AxisQuadric& q0, const Frame& fr, int n, bool& closed)
{
    require(q0.A != 0 && q0.B != 0 && (q0.A > 0) == (q0.B > 0),
            "quadric: the cross-sections perpendicular to its axis are not ellipses (unsupported)");
    const double s = q0.A > 0 ? 1 : -1;
    const double A = s * q0.A, B = s * q0.B, C = s * q0.C, G = s * q0.G, H = s * q0.H, I = s * q0.I, J = s * q0.J;
    const double x0 = -G / (2 * A), y0 = -H / (2 * B);
    const double K = J - A * x0 * x0 - B * y0 * y0;  // q(z) = C z² + I z + K
    constexpr double inf = std::numeric_limits<double>::infinity();
    // Roots of q and the intervals where q <= 0, within [lo, hi]. A root within rounding of a clip
    // plane (the named constructors put a paraboloid's vertex or a cone's apex on the clip plane
    // through the center) counts as closing the surface there.
    const double scale = std::max({std::abs(q0.lo) < inf ? std::abs(q0.lo) : 0.0, std::abs(q0.hi) < inf ? std::abs(q0.hi) : 0.0, 1.0});
    const double tol = 1e-12 * scale;
    const auto ge = [tol](double a, double b) { return a >= b - tol; };
    const auto le = [tol](double a, double b) { return a <= b + tol; };
    std::vector<Interval> spans;
    std::function<double(double)> minus_q;  // −q(z) >= 0 on the intervals, in a cancellation-free form near roots
    if (C == 0) {
        require(I != 0, "quadric: degenerate (a cylinder or a plane pair; unbounded)");
        const double zr = -K / I;
        minus_q = [I, zr](double z) { return -I * (z - zr); };
        if (I > 0) spans.push_back({q0.lo, std::min(zr, q0.hi), false, le(zr, q0.hi), false, false});
        else spans.push_back({std::max(zr, q0.lo), q0.hi, ge(zr, q0.lo), false, false, false});
    } else {
        const double disc = I * I - 4 * C * K;
        const double disc_tol = 64 * std::numeric_limits<double>::epsilon() * (I * I + 4 * std::abs(C * K));
        if (std::abs(disc) <= disc_tol && C < 0) {
            // A double cone: −q = −C (z − zd)², zero only at the apex.
            const double zd = -I / (2 * C);
            minus_q = [C, zd](double z) { return -C * (z - zd) * (z - zd); };
            const bool at_lo = le(zd, q0.lo), at_hi = ge(zd, q0.hi);
            if (!at_lo && !at_hi) {
                spans.push_back({q0.lo, zd, false, true, false, true});
                spans.push_back({zd, q0.hi, true, false, true, false});
            } else spans.push_back({q0.lo, q0.hi, at_lo && ge(zd, q0.lo), at_hi && le(zd, q0.hi), at_lo, at_hi});
        } else if (disc < 0) {
            require(C < 0, "quadric: empty surface");
            minus_q = [C, I, K](double z) { return -(C * z * z + I * z + K); };
            spans.push_back({q0.lo, q0.hi, false, false, false, false});  // a one-sheet hyperboloid
        } else {
            const double sq = std::sqrt(disc);
            const double qq = -0.5 * (I + (I >= 0 ? sq : -sq));
            double z1 = qq / C, z2 = K / qq;
            if (z1 > z2) std::swap(z1, z2);
            minus_q = [C, z1, z2](double z) { return -C * (z - z1) * (z - z2); };
            if (C > 0) spans.push_back({std::max(z1, q0.lo), std::min(z2, q0.hi), ge(z1, q0.lo), le(z2, q0.hi), false, false});
            else {
                spans.push_back({q0.lo, std::min(z1, q0.hi), false, le(z1, q0.hi), false, false});
                spans.push_back({std::max(z2, q0.lo), q0.hi, ge(z2, q0.lo), false, false, false});
            }
        }
    }
    spans.erase(std::remove_if(spans.begin(), spans.end(), [](const Interval& iv) { return !(iv.za < iv.zb); }), spans.end());
    require(!spans.empty(), "quadric: no surface within the clip box");
    for (const Interval& iv : spans) require(std::isfinite(iv.za) && std::isfinite(iv.zb), "quadric: unbounded within its clip box");

    const double sa = std::sqrt(A), sb = std::sqrt(B);
    const auto local_grad = [&](double x, double y, double z) {
        return fr.dir(2 * q0.A * x + q0.G, 2 * q0.B * y + q0.H, 2 * q0.C * z + q0.I);
    };
    for (const Interval& iv : spans) {
        const bool smooth_a = iv.pole_a && !iv.apex_a, smooth_b = iv.pole_b && !iv.apex_b;
        const double dz = iv.zb - iv.za;
        const auto z_of = [&](double u) {
            if (u <= 0) return iv.za;
            if (u >= 1) return iv.zb;
            if (smooth_a && smooth_b) return iv.za + dz * (1 - std::cos(pi * u)) / 2;
            if (smooth_a) return iv.za + dz * (1 - std::cos(pi * u / 2));
            if (smooth_b) return iv.za + dz * std::sin(pi * u / 2);
            return iv.za + dz * u;
        };
        const auto radius = [&](double u) {
            if ((u <= 0 && iv.pole_a) || (u >= 1 && iv.pole_b)) return 0.0;
            return std::sqrt(std::max(0.0, minus_q(z_of(u))));
        };
        // Rows in proportion to the meridian's length over the largest circumference.
        double arc = 0, rmax = 0;
        {
            const int samples = 256;
            double pr = radius(0) / std::min(sa, sb), pz = z_of(0);
            rmax = pr;
            for (int i = 1; i <= samples; ++i) {
                const double u = static_cast<double>(i) / samples;
                const double r = radius(u) / std::min(sa, sb), z = z_of(u);
                arc += std::hypot(r - pr, z - pz);
                rmax = std::max(rmax, r);
                pr = r;
                pz = z;
            }
        }
        // A closed patch (pole to pole) gets at least n/2 rings, as a sphere does.
        double ratio = std::min(arc / (2 * pi * rmax), 4.0);
        if (iv.pole_a && iv.pole_b) ratio = std::max(ratio, 0.5);
        const int bands = std::max(bands_for(n, ratio), iv.pole_a && iv.pole_b ? 2 : 1);
        std::vector<double> us(static_cast<std::size_t>(bands) + 1);
        for (int r = 0; r <= bands; ++r) us[static_cast<std::size_t>(r)] = static_cast<double>(r) / bands;

        const auto is_pole = [&](int r) { return (r == 0 && iv.pole_a) || (r == bands && iv.pole_b); };
        const auto local_point = [&](int r, double phi, double& x, double& y, double& z) {
            const double u = us[static_cast<std::size_t>(r)];
            const double rr = radius(u);
            z = z_of(u);
            x = is_pole(r) ? x0 : x0 + rr / sa * cos_(phi);
            y = is_pole(r) ? y0 : y0 + rr / sb * sin_(phi);
        };
        const auto point = [&](int r, double phi) {
            double x, y, z;
            local_point(r, phi, x, y, z);
            return fr.origin + fr.dir(x, y, z);
        };
        const RowNormal normal = [&](int r, double phi) {
            // At an apex the gradient vanishes: take it along the generator, on the neighbouring row.
            const bool apex = (r == 0 && iv.apex_a) || (r == bands && iv.apex_b);
            const int rr = apex ? (r == 0 ? 1 : bands - 1) : r;
            double x, y, z;
            local_point(rr, phi, x, y, z);
            return unit(local_grad(x, y, z));
        };
        const std::vector<Row> rows = make_rows(b, bands + 1, n, is_pole, point, normal);
        stitch(b, rows, n, normal, Part::surface);
        // A boundary ring (cut by a clip plane) is a polygon inscribed in the cross-section ellipse
        // A'(x − x0)² + B'(y − y0)² = −q(z): the gap at its chords' midpoints, measured in the plane,
        // exceeds the distance to the surface where the surface meets the plane obliquely.
        for (const int r : {0, bands}) {
            if (is_pole(r)) continue;
            const double u = us[static_cast<std::size_t>(r)];
            const double rr = radius(u);
            for (int j = 0; j < n; ++j) {
                double xa, ya, xb, yb, z;
                local_point(r, column_angle(j, n), xa, ya, z);
                local_point(r, column_angle((j + 1) % n, n), xb, yb, z);
                const double x = 0.5 * (xa + xb) - x0, y = 0.5 * (ya + yb) - y0;
                const double g = A * x * x + B * y * y - rr * rr, gx = 2 * A * x, gy = 2 * B * y;
                t.rim_deviation = std::max(t.rim_deviation, std::abs(g) / std::hypot(gx, gy));
            }
        }
        closed = closed && iv.pole_a && iv.pole_b;
    }
    (void)t;
}

// Eigen-decomposition of a symmetric 3×3 matrix by cyclic Jacobi rotations: m = V·diag(w)·Vᵀ.
void symmetric_eigen(double m[3][3], double w[3], double v[3][3])
{
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) v[i][j] = i == j ? 1 : 0;
    for (int sweep = 0; sweep < 64; ++sweep) {
        const double off = m[0][1] * m[0][1] + m[0][2] * m[0][2] + m[1][2] * m[1][2];
        const double diag = m[0][0] * m[0][0] + m[1][1] * m[1][1] + m[2][2] * m[2][2];
        if (off <= 1e-34 * diag) break;
        for (int p = 0; p < 2; ++p)
            for (int q = p + 1; q < 3; ++q) {
                if (m[p][q] == 0) continue;
                const double theta = (m[q][q] - m[p][p]) / (2 * m[p][q]);
                const double tt = (theta >= 0 ? 1 : -1) / (std::abs(theta) + std::sqrt(theta * theta + 1));
                const double c = 1 / std::sqrt(tt * tt + 1), s = tt * c;
                for (int k = 0; k < 3; ++k) {  // m ← Jᵀ m J
                    const double mkp = m[k][p], mkq = m[k][q];
                    m[k][p] = c * mkp - s * mkq;
                    m[k][q] = s * mkp + c * mkq;
                }
                for (int k = 0; k < 3; ++k) {
                    const double mpk = m[p][k], mqk = m[q][k];
                    m[p][k] = c * mpk - s * mqk;
                    m[q][k] = s * mpk + c * mqk;
                }
                for (int k = 0; k < 3; ++k) {
                    const double vkp = v[k][p], vkq = v[k][q];
                    v[k][p] = c * vkp - s * vkq;
                    v[k][q] = s * vkp + c * vkq;
                }
            }
    }
    for (int i = 0; i < 3; ++i) w[i] = m[i][i];
}

Implicit quadric_implicit(const Quadric<double>& q, const Vec3d& p)
{
    const double f = q.A * p.x * p.x + q.B * p.y * p.y + q.C * p.z * p.z + q.D * p.x * p.y + q.E * p.x * p.z + q.F * p.y * p.z +
                     q.G * p.x + q.H * p.y + q.I * p.z + q.J;
    const Vec3d g{2 * q.A * p.x + q.D * p.y + q.E * p.z + q.G, 2 * q.B * p.y + q.D * p.x + q.F * p.z + q.H,
                  2 * q.C * p.z + q.E * p.x + q.F * p.y + q.I};
    return {f, g};
}

// The flat primitives: a polygon grid in a plane, corner + (i/k)·e0 + (j/k)·e1. The given corners
// (a triangle's b and c, a parallelogram's corner + e0 and corner + e1) are placed exactly; the
// parallelogram's fourth corner is corner + e0 + e1 rounded, as the primitive defines it.
Tessellation flat_grid(const Vec3d& corner, const Vec3d& e0, const Vec3d& e1, const Vec3d& at_e0, const Vec3d& at_e1, int k,
                       bool triangle)
{
    Tessellation t;
    Builder b(t);
    const Vec3d nrm = unit(cross(e0, e1));
    std::vector<std::vector<VH>> v(static_cast<std::size_t>(k) + 1);
    for (int i = 0; i <= k; ++i)
        for (int j = 0; j <= (triangle ? k - i : k); ++j) {
            const double a = static_cast<double>(i) / k, c = static_cast<double>(j) / k;
            Vec3d p = corner + a * e0 + c * e1;
            if (i == 0 && j == 0) p = corner;
            else if (i == k && j == 0) p = at_e0;
            else if (i == 0 && j == k) p = at_e1;
            else if (i == k && j == k) p = corner + e0 + e1;
            v[static_cast<std::size_t>(i)].push_back(b.vertex(p, nrm));
        }
    const auto at = [&](int i, int j) { return Builder::Corner{v[static_cast<std::size_t>(i)][static_cast<std::size_t>(j)], nrm}; };
    for (int i = 0; i < k; ++i)
        for (int j = 0; j < (triangle ? k - i : k); ++j) {
            b.face(at(i, j), at(i + 1, j), at(triangle ? i : i + 1, j + 1), Part::surface);
            if (!triangle) b.face(at(i, j), at(i + 1, j + 1), at(i, j + 1), Part::surface);
            else if (i + j + 1 < k) b.face(at(i + 1, j), at(i + 1, j + 1), at(i, j + 1), Part::surface);
        }
    const Vec3d o = corner;
    t.implicit = [o, nrm](const Vec3d& p, Part) -> Implicit { return {dot(p - o, nrm), nrm}; };
    return finish(std::move(t), b);
}

}  // namespace

// ---------------------------------------------------------------------------------------------

Tessellation tessellate(const Sphere<double>& s, int n)
{
    require_valid(s, n);
    Tessellation t;
    Builder b(t);
    const int bands = std::max(2, (n + 1) / 2);
    const auto theta = [bands](int r) { return pi * r / bands; };
    const auto sincos = [&](int r, double& st, double& ct) {
        if (r == 0) { st = 0; ct = 1; return; }
        if (r == bands) { st = 0; ct = -1; return; }
        st = sin_(theta(r));
        ct = cos_(theta(r));
    };
    const RowNormal normal = [&](int r, double phi) {
        double st, ct;
        sincos(r, st, ct);
        return Vec3d{st * cos_(phi), st * sin_(phi), ct};
    };
    const auto point = [&](int r, double phi) { return s.center + s.radius * normal(r, phi); };
    const std::vector<Row> rows = make_rows(b, bands + 1, n, [&](int r) { return r == 0 || r == bands; }, point, normal);
    stitch(b, rows, n, normal, Part::surface);
    t.closed = true;
    const Vec3d c = s.center;
    const double r = s.radius;
    t.implicit = [c, r](const Vec3d& p, Part) -> Implicit {
        const Vec3d q = p - c;
        const double l = length(q);
        return {l - r, l > 0 ? q / l : Vec3d{0, 0, 1}};
    };
    return finish(std::move(t), b);
}

Tessellation tessellate(const Disk<double>& d, int n)
{
    require_valid(d, n);
    Tessellation t;
    Builder b(t);
    const Frame f = frame_along(d.center, d.normal);
    const int rings = std::max(1, n / 8);
    const RowNormal normal = [&](int, double) { return f.e3; };
    const auto point = [&](int r, double phi) {
        const double rho = d.radius * r / rings;
        return r == 0 ? d.center : d.center + f.dir(rho * cos_(phi), rho * sin_(phi), 0);
    };
    const std::vector<Row> rows = make_rows(b, rings + 1, n, [](int r) { return r == 0; }, point, normal);
    stitch(b, rows, n, normal, Part::surface);
    const Vec3d c = d.center, e3 = f.e3;
    t.implicit = [c, e3](const Vec3d& p, Part) -> Implicit { return {dot(p - c, e3), e3}; };
    t.rim_deviation = d.radius * (1 - std::cos(pi / n));
    return finish(std::move(t), b);
}

Tessellation tessellate(const Parallelogram<double>& p, int n)
{
    require_valid(p, n);
    return flat_grid(p.corner, p.edge0, p.edge1, p.corner + p.edge0, p.corner + p.edge1, std::max(1, n / 8), false);
}

Tessellation tessellate(const Triangle<double>& tri, int n)
{
    require_valid(tri, n);
    return flat_grid(tri.a, tri.b - tri.a, tri.c - tri.a, tri.b, tri.c, std::max(1, n / 8), true);
}

Tessellation tessellate(const Cylinder<double>& c, int n)
{
    require_valid(c, n);
    return axial(c.p0, c.radius, c.p1, c.radius, c.caps == Caps::both, n);
}

Tessellation tessellate(const Cone<double>& c, int n)
{
    require_valid(c, n);
    return axial(c.p0, c.r0, c.p1, c.r1, c.caps == Caps::both, n);
}

Tessellation tessellate(const Quadric<double>& q, int n)
{
    require_valid(q, n);
    Tessellation t;
    Builder b(t);
    bool closed = true;
    if (q.D == 0 && q.E == 0 && q.F == 0) {
        const Frame world{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
        add_quadric(t, b, {q.A, q.B, q.C, q.G, q.H, q.I, q.J, q.clip.lo.z, q.clip.hi.z}, world, n, closed);
    } else {
        // Rotated: only an ellipsoid (definite quadratic part), whole within its clip box.
        double m[3][3] = {{q.A, q.D / 2, q.E / 2}, {q.D / 2, q.B, q.F / 2}, {q.E / 2, q.F / 2, q.C}};
        const double mm[3][3] = {{m[0][0], m[0][1], m[0][2]}, {m[1][0], m[1][1], m[1][2]}, {m[2][0], m[2][1], m[2][2]}};
        double w[3], v[3][3];
        symmetric_eigen(m, w, v);
        require((w[0] > 0 && w[1] > 0 && w[2] > 0) || (w[0] < 0 && w[1] < 0 && w[2] < 0),
                "quadric: a rotated quadric must be an ellipsoid (rotate the others with Transformed)");
        // Center: M c = −g/2, by Cramer's rule.
        const Vec3d g{q.G, q.H, q.I};
        const Vec3d c0{mm[0][0], mm[1][0], mm[2][0]}, c1{mm[0][1], mm[1][1], mm[2][1]}, c2{mm[0][2], mm[1][2], mm[2][2]};
        const double det = dot(c0, cross(c1, c2));
        const Vec3d rhs = -0.5 * g;
        const Vec3d center{dot(rhs, cross(c1, c2)) / det, dot(c0, cross(rhs, c2)) / det, dot(c0, cross(c1, rhs)) / det};
        const double k = q.J + 0.5 * dot(g, center);
        Frame fr{center, {v[0][0], v[1][0], v[2][0]}, {v[0][1], v[1][1], v[2][1]}, {v[0][2], v[1][2], v[2][2]}};
        if (dot(cross(fr.e1, fr.e2), fr.e3) < 0) fr.e3 = -fr.e3;
        // The whole ellipsoid must lie in the clip box: half-extent along world axis a is
        // sqrt(Σ (e_i·a)² · (−k/λ_i)).
        for (int axis = 0; axis < 3; ++axis) {
            const double e[3] = {axis == 0 ? fr.e1.x : axis == 1 ? fr.e1.y : fr.e1.z, axis == 0 ? fr.e2.x : axis == 1 ? fr.e2.y : fr.e2.z,
                                 axis == 0 ? fr.e3.x : axis == 1 ? fr.e3.y : fr.e3.z};
            double ext = 0;
            for (int i = 0; i < 3; ++i) ext += e[i] * e[i] * (-k / w[i]);
            require(ext > 0, "quadric: empty ellipsoid");
            ext = std::sqrt(ext);
            const double c = axis == 0 ? center.x : axis == 1 ? center.y : center.z;
            const double lo = axis == 0 ? q.clip.lo.x : axis == 1 ? q.clip.lo.y : q.clip.lo.z;
            const double hi = axis == 0 ? q.clip.hi.x : axis == 1 ? q.clip.hi.y : q.clip.hi.z;
            require(lo <= c - ext && c + ext <= hi, "quadric: a rotated ellipsoid must lie within its clip box");
        }
        constexpr double inf = std::numeric_limits<double>::infinity();
        add_quadric(t, b, {w[0], w[1], w[2], 0, 0, 0, k, -inf, inf}, fr, n, closed);
    }
    // x and y clip bounds must not cut the surface: every vertex inside the box.
    for (const auto v : t.mesh.vertices()) {
        const Vec3d p = to_vec(t.mesh.point(v));
        require(q.clip.lo.x <= p.x && p.x <= q.clip.hi.x && q.clip.lo.y <= p.y && p.y <= q.clip.hi.y,
                "quadric: the clip box cuts the surface other than by z planes (unsupported)");
    }
    t.closed = closed;
    t.implicit = [q](const Vec3d& p, Part) { return quadric_implicit(q, p); };
    return finish(std::move(t), b);
}

// ---------------------------------------------------------------------------------------------

Tessellation transform(const Tessellation& object, const Affine3<double>& to_world, const Affine3<double>& to_object)
{
    Tessellation t;
    Builder b(t);
    const TriMesh& m = object.mesh;
    const bool reverse = to_world.determinant() < 0;
    const auto normal = [&](const OpenMesh::Vec3d& nv) { return unit(to_object.linear_transposed(to_vec(nv))); };
    std::vector<VH> map(m.n_vertices());
    for (const auto v : m.vertices())
        map[static_cast<std::size_t>(v.idx())] = b.vertex(to_world.point(to_vec(m.point(v))), normal(m.normal(v)));
    for (const auto f : m.faces()) {
        std::vector<Builder::Corner> c;
        for (const auto h : m.fh_range(f)) c.push_back({map[static_cast<std::size_t>(m.to_vertex_handle(h).idx())], normal(m.normal(h))});
        const Part part = object.part[static_cast<std::size_t>(f.idx())];
        if (reverse) b.face(c[0], c[2], c[1], part);
        else b.face(c[0], c[1], c[2], part);
    }
    t.closed = object.closed;
    const ImplicitFn inner = object.implicit;
    t.implicit = [inner, to_object](const Vec3d& p, Part part) -> Implicit {
        const Implicit im = inner(to_object.point(p), part);
        return {im.value, to_object.linear_transposed(im.gradient)};
    };
    // Lengths grow by at most the largest singular value of the linear part (power iteration on LᵀL).
    Vec3d x{1, 1, 1};
    double sigma2 = 0;
    for (int i = 0; i < 100; ++i) {
        const Vec3d y = to_world.linear_transposed(to_world.linear(x));
        sigma2 = length(y) / length(x);
        x = y / length(y);
    }
    t.rim_deviation = object.rim_deviation * std::sqrt(sigma2) * (1 + 1e-9);
    return finish(std::move(t), b);
}

namespace {
template <class Prim>
Tessellation tessellate_transformed(const Transformed<Prim>& x, int n)
{
    const Validation v = validate(x);
    require(static_cast<bool>(v), v.reason ? v.reason : "invalid transformed primitive");
    return transform(tessellate(x.object, n), x.to_world, x.to_object);
}
}  // namespace

Tessellation tessellate(const Transformed<Sphere<double>>& x, int n) { return tessellate_transformed(x, n); }
Tessellation tessellate(const Transformed<Disk<double>>& x, int n) { return tessellate_transformed(x, n); }
Tessellation tessellate(const Transformed<Parallelogram<double>>& x, int n) { return tessellate_transformed(x, n); }
Tessellation tessellate(const Transformed<Triangle<double>>& x, int n) { return tessellate_transformed(x, n); }
Tessellation tessellate(const Transformed<Cylinder<double>>& x, int n) { return tessellate_transformed(x, n); }
Tessellation tessellate(const Transformed<Cone<double>>& x, int n) { return tessellate_transformed(x, n); }
Tessellation tessellate(const Transformed<Quadric<double>>& x, int n) { return tessellate_transformed(x, n); }

// ---------------------------------------------------------------------------------------------

Topology topology(const TriMesh& m)
{
    Topology t;
    t.vertices = m.n_vertices();
    t.edges = m.n_edges();
    t.faces = m.n_faces();
    std::vector<char> seen(m.n_halfedges(), 0);
    for (const auto e : m.edges())
        if (m.is_boundary(e)) ++t.boundary_edges;
    for (const auto h : m.halfedges()) {
        if (!m.is_boundary(h) || seen[static_cast<std::size_t>(h.idx())]) continue;
        ++t.boundary_loops;
        auto g = h;
        do {
            seen[static_cast<std::size_t>(g.idx())] = 1;
            g = m.next_halfedge_handle(g);
        } while (g != h && !seen[static_cast<std::size_t>(g.idx())]);
    }
    for (const auto v : m.vertices())
        if (!m.is_manifold(v)) ++t.nonmanifold_vertices;
    for (const auto f : m.faces()) {
        const Vec3d nf = face_normal(m, f.idx());
        if (nf.x == 0 && nf.y == 0 && nf.z == 0) ++t.degenerate_faces;
    }
    return t;
}

namespace {
std::array<Vec3d, 3> corners(const TriMesh& m, int face)
{
    std::array<Vec3d, 3> p{};
    int i = 0;
    for (const auto h : m.fh_range(m.face_handle(static_cast<unsigned>(face)))) p[static_cast<std::size_t>(i++)] = to_vec(m.point(m.to_vertex_handle(h)));
    return p;
}
}  // namespace

double signed_volume(const TriMesh& m)
{
    double v = 0;
    for (const auto f : m.faces()) {
        const auto p = corners(m, f.idx());
        v += dot(p[0], cross(p[1], p[2]));
    }
    return v / 6;
}

Vec3d face_normal(const TriMesh& m, int face)
{
    const auto p = corners(m, face);
    return cross(p[1] - p[0], p[2] - p[0]);
}

Vec3d centroid(const TriMesh& m, int face)
{
    const auto p = corners(m, face);
    return (p[0] + p[1] + p[2]) / 3.0;
}

}  // namespace rayq::mesh
