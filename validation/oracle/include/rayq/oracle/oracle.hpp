// rayq::oracle — what a ray EXACTLY does against each kernel primitive (issue 4).
//
// The oracle reads the kernel's plain data structs (Vec3, Ray, Sphere, …, Transformed) as exact
// inputs — every float and double is a rational number — and answers in exact arithmetic
// (GMP rationals and the quadratic field Q(√D) of the ray's equation). It shares no code path
// with the kernel: it never calls intersect, crossings, solve_quadratic, validate or any other
// kernel function. A second route through CGAL's kernels checks the oracle itself
// (second_route_agrees).
//
// This header is non-template and includes neither CGAL nor GMP; the arithmetic lives in the
// library's .cpp files (target rayq::oracle).
//
// What "exactly" means, primitive by primitive (the same conventions as the kernel's README):
//   * Curved primitives (sphere, cylinder side, cone side, quadric): along the ray's LINE the
//     surface equation is a polynomial F(t) of degree <= 2 with F < 0 inside. The closed set
//     {t : F(t) <= 0} is a union of intervals; its finite end points are the crossings (left
//     ends enter, right ends exit). So a ray touching the surface from outside (an exact double
//     root) crosses once, tangent; a ray touching it from inside (F <= 0 everywhere, e.g. along
//     a cone's axis through the apex) does not cross; a line lying in the surface (F ≡ 0) does
//     not cross.
//   * Cylinder and cone: the side is clipped to the slab 0 <= (p − p0)·A <= |A|² (A = p1 − p0),
//     rim included. With Caps::both the solid is side-solid ∩ slab; where the ray's entry or exit
//     is an exact tie between side and cap plane, the cap wins — except at a cone's zero-radius
//     end (an apex), which is never a cap. The cone's second nappe lies outside the slab.
//   * Quadric: the crossings whose exact points lie in the clip box (bounds inclusive, infinite
//     bounds allowed); a clipped near root leaves the far one.
//   * Flat primitives: the ray's line meets the plane at one rational t unless it is parallel
//     (d·n = 0, including lying in the plane: no crossing). Inside tests are exact and inclusive
//     (disk rim, parallelogram and triangle edges and corners). Entering = d·n < 0 (meets the
//     front side).
//   * Transformed<Prim>: the world solid is to_world(object), with to_world's inverse computed
//     EXACTLY in rationals. The stored (rounded) to_object is ignored: the kernel's use of it is
//     part of the error being measured.
//   * The hit is the first crossing with tmin < t < tmax, compared exactly (infinite bounds allowed).
// Inputs outside the domain (NaN/Inf fields, radius <= 0, zero axis/normal/direction,
// degenerate triangle or parallelogram, both cone radii 0, quadric without a non-constant term,
// empty clip box, singular to_world, empty window) give ExactHit::defined = false.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <rayq/cone.hpp>
#include <rayq/cylinder.hpp>
#include <rayq/disk.hpp>
#include <rayq/hit.hpp>
#include <rayq/parallelogram.hpp>
#include <rayq/plane.hpp>
#include <rayq/quadric.hpp>
#include <rayq/ray.hpp>
#include <rayq/sphere.hpp>
#include <rayq/transformed.hpp>
#include <rayq/triangle.hpp>

namespace rayq::oracle {

// The exact answer for the closest hit.
struct ExactHit {
    bool defined = false;      // the input lies in the oracle's domain (see above)
    bool hit = false;          // a crossing with tmin < t < tmax exists
    Part part = Part::surface; // which piece (exact comparisons; ties go to the cap, never to an apex)
    bool entering = false;     // the truth for Hit::front_face
    bool tangent = false;      // the hit is an exact double root of the side equation
    float t_float = 0;         // t correctly rounded (to nearest, ties to even) to float
    double t_double = 0;       // ... and to double
    long double t_long = 0;    // t rounded to long double (from a 256-bit approximation)
    std::string t_exact;       // t as text: "a + b*sqrt(D)" with rationals a, b, D (or just "a")
    bool normal_defined = false;       // false where the gradient vanishes (a cone's apex)
    Vec3<double> outward_normal{};     // unit, at the exact point, pointing outside (front side)
    Vec3<double> facing_normal{};      // the same, flipped to face the ray when exactly d·n > 0
    std::vector<long double> crossings;  // every crossing of the whole line (window ignored), ascending, rounded
};

// The kernel's answer compared with the exact one. part/front_face/ulps/rel_error/faithful/
// other_crossing/normal_angle are meaningful when both hit (both_hit); bounded/bound_violated/
// uncertified whenever the kernel hits (a false hit's bound is violated unless some exact
// crossing of the line — outside the window or clipped — lies within it).
struct Measurement {
    bool defined = false;  // the oracle's domain; nothing else is meaningful without it
    bool exact_hit = false, kernel_hit = false;
    bool hit_agrees = false;
    bool tangent = false;  // the exact hit is a double root
    bool both_hit = false;
    bool part_agrees = false;
    bool front_face_agrees = false;
    double ulps = 0;       // |t_kernel − t_exact| / ulp_T(t_exact); ulp_T(x) = the spacing of T
                           // above the T value next to x toward zero; computed to 256 bits, then rounded
    double rel_error = 0;  // |t_kernel − t_exact| / |t_exact| (inf when t_exact = 0 ≠ t_kernel)
    bool faithful = false; // t_kernel is one of the two T values bracketing t_exact (or equals it;
                           // beyond the largest T, the largest T of its sign and infinity)
    bool bounded = false;  // the kernel's t_error is finite
    bool bound_violated = false;  // exactly: |t_kernel − t_exact| > t_error (a NaN or negative t_error counts)
    bool uncertified = false;     // a violation where no exact crossing of the line at all lies within t_error
    bool other_crossing = false;  // t_kernel is not faithful and is nearer another exact crossing of the line
                                  // than the first hit: the kernel reported a different crossing (e.g. it
                                  // missed a root near tmin)
    double normal_angle = 0;      // radians between the kernel's normal and the exact facing normal
                                  // (either orientation when exactly tangent); NaN when undefined
    bool exact_fallback = false;  // the kernel call needed exact arithmetic (set by measure_kernel)
};

// Everything the oracle knows about one (ray, primitive) pair, computed once; measure() then
// compares any number of kernel answers (e.g. the three policies) against it.
class Truth {
public:
#define RAYQ_ORACLE_TRUTH_CTORS(T)                                  \
    Truth(const Ray<T>&, const Sphere<T>&);                         \
    Truth(const Ray<T>&, const Plane<T>&);                          \
    Truth(const Ray<T>&, const Disk<T>&);                           \
    Truth(const Ray<T>&, const Parallelogram<T>&);                  \
    Truth(const Ray<T>&, const Triangle<T>&);                       \
    Truth(const Ray<T>&, const Cylinder<T>&);                       \
    Truth(const Ray<T>&, const Cone<T>&);                           \
    Truth(const Ray<T>&, const Quadric<T>&);                        \
    Truth(const Ray<T>&, const Transformed<Sphere<T>>&);            \
    Truth(const Ray<T>&, const Transformed<Plane<T>>&);             \
    Truth(const Ray<T>&, const Transformed<Disk<T>>&);              \
    Truth(const Ray<T>&, const Transformed<Parallelogram<T>>&);     \
    Truth(const Ray<T>&, const Transformed<Triangle<T>>&);          \
    Truth(const Ray<T>&, const Transformed<Cylinder<T>>&);          \
    Truth(const Ray<T>&, const Transformed<Cone<T>>&);              \
    Truth(const Ray<T>&, const Transformed<Quadric<T>>&);
    RAYQ_ORACLE_TRUTH_CTORS(float)
    RAYQ_ORACLE_TRUTH_CTORS(double)
#undef RAYQ_ORACLE_TRUTH_CTORS

    Truth(Truth&&) noexcept;
    Truth& operator=(Truth&&) noexcept;
    ~Truth();

    const ExactHit& first_hit() const;
    bool is_float() const;  // the inputs were float (measure() then expects a float hit)

    // The kernel hit must have the input's number type (std::logic_error otherwise).
    Measurement measure(const std::optional<Hit<float>>& kernel) const;
    Measurement measure(const std::optional<Hit<double>>& kernel) const;

    struct Impl;

private:
    std::unique_ptr<Impl> impl_;
};

// One-shot forms of the above.
#define RAYQ_ORACLE_FREE_FUNCTIONS(T, PRIM)                                                  \
    ExactHit exact_first_hit(const Ray<T>& ray, const PRIM& prim);                           \
    Measurement measure(const Ray<T>& ray, const PRIM& prim, const std::optional<Hit<T>>& kernel);
#define RAYQ_ORACLE_FREE_FUNCTIONS_FOR(T)                                  \
    RAYQ_ORACLE_FREE_FUNCTIONS(T, Sphere<T>)                               \
    RAYQ_ORACLE_FREE_FUNCTIONS(T, Plane<T>)                                \
    RAYQ_ORACLE_FREE_FUNCTIONS(T, Disk<T>)                                 \
    RAYQ_ORACLE_FREE_FUNCTIONS(T, Parallelogram<T>)                        \
    RAYQ_ORACLE_FREE_FUNCTIONS(T, Triangle<T>)                             \
    RAYQ_ORACLE_FREE_FUNCTIONS(T, Cylinder<T>)                             \
    RAYQ_ORACLE_FREE_FUNCTIONS(T, Cone<T>)                                 \
    RAYQ_ORACLE_FREE_FUNCTIONS(T, Quadric<T>)                              \
    RAYQ_ORACLE_FREE_FUNCTIONS(T, Transformed<Sphere<T>>)                  \
    RAYQ_ORACLE_FREE_FUNCTIONS(T, Transformed<Plane<T>>)                   \
    RAYQ_ORACLE_FREE_FUNCTIONS(T, Transformed<Disk<T>>)                    \
    RAYQ_ORACLE_FREE_FUNCTIONS(T, Transformed<Parallelogram<T>>)           \
    RAYQ_ORACLE_FREE_FUNCTIONS(T, Transformed<Triangle<T>>)                \
    RAYQ_ORACLE_FREE_FUNCTIONS(T, Transformed<Cylinder<T>>)                \
    RAYQ_ORACLE_FREE_FUNCTIONS(T, Transformed<Cone<T>>)                    \
    RAYQ_ORACLE_FREE_FUNCTIONS(T, Transformed<Quadric<T>>)
RAYQ_ORACLE_FREE_FUNCTIONS_FOR(float)
RAYQ_ORACLE_FREE_FUNCTIONS_FOR(double)
#undef RAYQ_ORACLE_FREE_FUNCTIONS_FOR
#undef RAYQ_ORACLE_FREE_FUNCTIONS

// to_world's inverse computed exactly, each entry correctly rounded: the best to_object a
// Transformed can store (the fixture generator uses it; the oracle itself never reads to_object).
Affine3<float> rounded_inverse(const Affine3<float>& to_world);
Affine3<double> rounded_inverse(const Affine3<double>& to_world);

// The second route: the same question answered by CGAL (spheres by Exact_spherical_kernel_3's
// Line_3 ∩ Sphere_3; planes, triangles and parallelograms — as two triangles — by the exact
// kernel's Line_3 ∩ Plane_3 / Triangle_3), compared EXACTLY with the oracle: hit, t (as an
// element of Q(√D)), the hit point, entering and tangency. `why` says what differed.
struct Agreement {
    bool agrees = false;
    std::string why;
    explicit operator bool() const { return agrees; }
};
Agreement second_route_agrees(const Ray<float>&, const Sphere<float>&);
Agreement second_route_agrees(const Ray<double>&, const Sphere<double>&);
Agreement second_route_agrees(const Ray<float>&, const Plane<float>&);
Agreement second_route_agrees(const Ray<double>&, const Plane<double>&);
Agreement second_route_agrees(const Ray<float>&, const Triangle<float>&);
Agreement second_route_agrees(const Ray<double>&, const Triangle<double>&);
Agreement second_route_agrees(const Ray<float>&, const Parallelogram<float>&);
Agreement second_route_agrees(const Ray<double>&, const Parallelogram<double>&);

}  // namespace rayq::oracle
