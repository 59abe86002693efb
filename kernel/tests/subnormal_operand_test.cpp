// No subnormal operand on ordinary rays. x86 takes a microcode assist for every instruction that
// reads a subnormal unless DAZ is set, and rayq needs DAZ off (its certified bounds assume gradual
// underflow). The certified bounds once added denorm_min at every operation: -march=native
// builds of rayq-bench ran `fast` with the full record and `accurate` 5-18x slower than SSE2
// builds of the same code (grow() in detail/bounded.hpp). The processor records such reads in
// the MXCSR denormal flag, which these tests read after each query: unit-size primitives tilted
// off the axes, rays from 4 units away aimed near them, every policy, float and double, the
// full hit record, any-hit and every crossing. CAD-like inputs as well: primitives aligned with
// the axes, and rays along the axes, whose zero components must not turn into subnormal
// products.
#include "test_support.hpp"

#include <random>
#include <string>
#include <type_traits>

#if defined(__SSE2__) || defined(_M_X64)
#include <xmmintrin.h>
#define RAYQ_TEST_HAS_MXCSR 1
#else
#define RAYQ_TEST_HAS_MXCSR 0
#endif

namespace rayq::test::subnormal_operand_test {
namespace {

#if RAYQ_TEST_HAS_MXCSR
constexpr unsigned kDenormalFlag = 0x2u;  // MXCSR bit 1 (DE): an instruction read a subnormal
void clear_flags() { _mm_setcsr(_mm_getcsr() & ~0x3Fu); }
bool read_a_subnormal() { return (_mm_getcsr() & kDenormalFlag) != 0; }
#endif

template <class T>
class SubnormalOperandTest : public ::testing::Test {};
TYPED_TEST_SUITE(SubnormalOperandTest, FloatTypes, FloatTypeNames);

const Vec3<double> kCenter{0.3, -0.2, 0.1};

template <class T>
Vec3<T> at(double x, double y, double z) { return {T(kCenter.x + x), T(kCenter.y + y), T(kCenter.z + z)}; }

// Origins 4 units from the center, aimed at random points within 1.5 of it: about half hit.
template <class T>
std::vector<Ray<T>> rays(std::uint64_t seed)
{
    std::mt19937_64 rng(seed);
    std::normal_distribution<double> gauss;
    std::uniform_real_distribution<double> box(-1.5, 1.5);
    std::vector<Ray<T>> out;
    for (int i = 0; i < 500; ++i) {
        const Vec3<double> g{gauss(rng), gauss(rng), gauss(rng)};
        const Vec3<double> o = kCenter + (4.0 / length(g)) * g;
        const Vec3<double> d = normalize(kCenter + Vec3<double>{box(rng), box(rng), box(rng)} - o);
        out.push_back({{T(o.x), T(o.y), T(o.z)}, {T(d.x), T(d.y), T(d.z)}});
    }
    return out;
}

// Rays along +x, +y, +z, then −x, −y, −z, and so on, from 4 units out, through random points
// within 1.5 of the center: every direction has two exact zero components.
template <class T>
std::vector<Ray<T>> axis_rays(std::uint64_t seed)
{
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> box(-1.5, 1.5);
    std::vector<Ray<T>> out;
    for (int i = 0; i < 500; ++i) {
        double o[3] = {kCenter.x + box(rng), kCenter.y + box(rng), kCenter.z + box(rng)}, d[3] = {0, 0, 0};
        const int axis = i % 3;
        const double sign = (i / 3) % 2 == 0 ? 1.0 : -1.0;
        o[axis] = (axis == 0 ? kCenter.x : axis == 1 ? kCenter.y : kCenter.z) - 4.0 * sign;
        d[axis] = sign;
        out.push_back({{T(o[0]), T(o[1]), T(o[2])}, {T(d[0]), T(d[1]), T(d[2])}});
    }
    return out;
}

enum class Rays { ordinary, along_axes };

// Every query on every ray, with the flag cleared before each; returns how many read a subnormal
// and describes the first.
template <class Policy, class Prim>
int rays_reading_subnormals(Policy policy, const Prim& prim, Rays family, std::string& first)
{
    using T = scalar_t<Prim>;
    int count = 0, hits = 0;
#if RAYQ_TEST_HAS_MXCSR
    for (const Ray<T>& r : family == Rays::ordinary ? rays<T>(0x5AB0) : axis_rays<T>(0xA815)) {
        clear_flags();
        const auto h = intersect(policy, r, prim, HitFields::all);
        const bool occ = occluded(policy, r, prim);
        const auto all = intersect_all(policy, r, prim);
        if (read_a_subnormal()) {
            if (count++ == 0)
                first = "ray o = (" + std::to_string(r.origin.x) + ", " + std::to_string(r.origin.y) + ", " + std::to_string(r.origin.z) +
                        ") d = (" + std::to_string(r.direction.x) + ", " + std::to_string(r.direction.y) + ", " +
                        std::to_string(r.direction.z) + ")" + (h ? " (hit)" : " (miss)");
        }
        hits += h.has_value() + occ + all.size();
    }
#endif
    EXPECT_GT(hits, 0);  // the rays do reach the primitive
    return count;
}

template <class Prim>
void expect_no_subnormal_operands(const Prim& prim, const char* name, Rays family = Rays::ordinary)
{
#if RAYQ_TEST_HAS_MXCSR
    const char* rays_name = family == Rays::ordinary ? "ordinary rays" : "rays along the axes";
    const auto one = [&](auto policy, const char* policy_name) {
        std::string first;
        EXPECT_EQ(rays_reading_subnormals(policy, prim, family, first), 0)
            << name << " under " << policy_name << ", " << rays_name << "; first: " << first;
    };
    one(fast, "fast"), one(stable, "stable"), one(accurate, "accurate");
#else
    (void)prim, (void)name, (void)family;
    GTEST_SKIP() << "no MXCSR on this target";
#endif
}

TYPED_TEST(SubnormalOperandTest, CurvedPrimitives)
{
    using T = TypeParam;
    const Vec3<T> axis{T(0.3), T(0.4), T(0.87)};
    expect_no_subnormal_operands(Sphere<T>{at<T>(0, 0, 0), T(1)}, "sphere");
    expect_no_subnormal_operands(Cylinder<T>::from_center(at<T>(0, 0, 0), axis, T(0.7), T(1.2), Caps::none), "open cylinder");
    expect_no_subnormal_operands(Cylinder<T>::from_center(at<T>(0, 0, 0), axis, T(0.7), T(1.2), Caps::both), "capped cylinder");
    expect_no_subnormal_operands(Cone<T>{at<T>(-0.36, -0.48, -1.044), T(0.9), at<T>(0.36, 0.48, 1.044), T(0.4), Caps::both}, "frustum");
    expect_no_subnormal_operands(Cone<T>{at<T>(-0.36, -0.48, -1.044), T(0.9), at<T>(0.36, 0.48, 1.044), T(0), Caps::none}, "cone");
}

TYPED_TEST(SubnormalOperandTest, FlatPrimitives)
{
    using T = TypeParam;
    const Vec3<T> tilt{T(0.2), T(0.3), T(0.93)};
    expect_no_subnormal_operands(Plane<T>{at<T>(0, 0, 0), tilt}, "plane");
    expect_no_subnormal_operands(Disk<T>{at<T>(0, 0, 0), tilt, T(1)}, "disk");
    expect_no_subnormal_operands(Parallelogram<T>{at<T>(-0.7, -0.6, 0.1), {T(1.6), T(0.3), T(-0.2)}, {T(-0.25), T(1.2), T(0.4)}},
                                 "parallelogram");
    expect_no_subnormal_operands(Triangle<T>{at<T>(-1.0, -0.8, 0.1), at<T>(1.1, -0.5, -0.2), at<T>(-0.2, 1.2, 0.3)}, "triangle");
}

TYPED_TEST(SubnormalOperandTest, QuadricsAndInstances)
{
    using T = TypeParam;
    const Vec3<T> ax{T(0.8), T(0.6), T(0)}, ay{T(-0.36), T(0.48), T(0.8)};
    expect_no_subnormal_operands(Quadric<T>::ellipsoid(at<T>(0, 0, 0), {T(1.1), T(0.7), T(0.5)}, ax, ay), "ellipsoid");
    expect_no_subnormal_operands(Quadric<T>::hyperboloid_one_sheet(at<T>(0, 0, 0), T(0.5), T(0.6), T(0.7), T(1)), "hyperboloid");
    const Affine3<T> m{{{T(0.9), T(0.2), T(-0.1), T(0.3)}, {T(-0.15), T(1.1), T(0.25), T(-0.2)}, {T(0.05), T(-0.3), T(0.8), T(0.1)}}};
    expect_no_subnormal_operands(transformed(Sphere<T>{{T(0), T(0), T(0)}, T(1)}, m), "transformed sphere");
    expect_no_subnormal_operands(transformed(Disk<T>{{T(0), T(0), T(0)}, {T(0.2), T(0.3), T(0.93)}, T(1)}, m), "transformed disk");
}

// CAD-like inputs: primitives whose axes, normals and edges lie along the coordinate axes, met by
// ordinary rays and by rays along the axes; and the tilted primitives above met by rays along the
// axes.
TYPED_TEST(SubnormalOperandTest, AxisAlignedPrimitives)
{
    using T = TypeParam;
    const Vec3<T> z{T(0), T(0), T(1)}, y{T(0), T(1), T(0)};
    for (const Rays family : {Rays::ordinary, Rays::along_axes}) {
        expect_no_subnormal_operands(Sphere<T>{at<T>(0, 0, 0), T(1)}, "sphere", family);
        expect_no_subnormal_operands(Cylinder<T>{at<T>(0, 0, -1), at<T>(0, 0, 1), T(0.7), Caps::none}, "z open cylinder", family);
        expect_no_subnormal_operands(Cylinder<T>{at<T>(0, 0, -1), at<T>(0, 0, 1), T(0.7), Caps::both}, "z capped cylinder", family);
        expect_no_subnormal_operands(Cone<T>{at<T>(0, -1, 0), T(0.9), at<T>(0, 1, 0), T(0.4), Caps::both}, "y frustum", family);
        expect_no_subnormal_operands(Cone<T>{at<T>(0, 0, -1), T(1), at<T>(0, 0, 1), T(0), Caps::both}, "z cone", family);
        expect_no_subnormal_operands(Plane<T>{at<T>(0, 0, 0), z}, "z plane", family);
        expect_no_subnormal_operands(Disk<T>{at<T>(0, 0, 0), y, T(1)}, "y disk", family);
        expect_no_subnormal_operands(Parallelogram<T>{at<T>(-1, -0.5, 0), {T(2), T(0), T(0)}, {T(0), T(1), T(0)}}, "xy parallelogram",
                                     family);
        expect_no_subnormal_operands(Triangle<T>{at<T>(-1, -1, 0), at<T>(1, -1, 0), at<T>(0, 1, 0)}, "triangle in z = c", family);
        expect_no_subnormal_operands(Quadric<T>::ellipsoid(at<T>(0, 0, 0), {T(1.1), T(0.7), T(0.5)}, {T(1), T(0), T(0)}, y), "ellipsoid",
                                     family);
    }
}

TYPED_TEST(SubnormalOperandTest, TiltedPrimitivesAlongTheAxes)
{
    using T = TypeParam;
    const Vec3<T> axis{T(0.3), T(0.4), T(0.87)}, tilt{T(0.2), T(0.3), T(0.93)};
    const Rays along = Rays::along_axes;
    expect_no_subnormal_operands(Cylinder<T>::from_center(at<T>(0, 0, 0), axis, T(0.7), T(1.2), Caps::both), "capped cylinder", along);
    expect_no_subnormal_operands(Cone<T>{at<T>(-0.36, -0.48, -1.044), T(0.9), at<T>(0.36, 0.48, 1.044), T(0.4), Caps::both}, "frustum",
                                 along);
    expect_no_subnormal_operands(Disk<T>{at<T>(0, 0, 0), tilt, T(1)}, "disk", along);
    expect_no_subnormal_operands(Triangle<T>{at<T>(-1.0, -0.8, 0.1), at<T>(1.1, -0.5, -0.2), at<T>(-0.2, 1.2, 0.3)}, "triangle", along);
    expect_no_subnormal_operands(Quadric<T>::hyperboloid_one_sheet(at<T>(0, 0, 0), T(0.5), T(0.6), T(0.7), T(1)), "hyperboloid", along);
}

}  // namespace
}  // namespace rayq::test::subnormal_operand_test
