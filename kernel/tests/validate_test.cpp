// validate() names the problem for each kind of bad primitive.
#include "test_support.hpp"

#include <string>

namespace rayq::test::validate_test {
namespace {

template <class Prim>
void expect_defect(const Prim& prim, Defect defect, const std::string& mentions)
{
    const Validation v = validate(prim);
    EXPECT_FALSE(v);
    EXPECT_EQ(v.defect, defect) << v.reason;
    EXPECT_NE(std::string(v.reason).find(mentions), std::string::npos) << v.reason;
}

template <class C>
class ValidateTest : public ::testing::Test {};
TYPED_TEST_SUITE(ValidateTest, AllConfigs, ConfigNames);

TYPED_TEST(ValidateTest, ReasonsNameTheFieldAndTheProblem)
{
    using T = typename TypeParam::T;
    constexpr T nan = std::numeric_limits<T>::quiet_NaN(), inf = std::numeric_limits<T>::infinity();
    const T huge = std::numeric_limits<T>::max();
    const auto z = v3<T>(0, 0, 0), e = v3<T>(0, 0, 1);

    EXPECT_TRUE(validate(Sphere<T>{z, T(1)}));
    EXPECT_STREQ(validate(Sphere<T>{z, T(1)}).reason, "ok");
    expect_defect(Sphere<T>{z, T(-1)}, Defect::nonpositive_radius, "radius");
    expect_defect(Sphere<T>{z, T(0)}, Defect::nonpositive_radius, "radius");
    expect_defect(Sphere<T>{z, nan}, Defect::non_finite, "radius");
    expect_defect(Sphere<T>{Vec3<T>{inf, T(0), T(0)}, T(1)}, Defect::non_finite, "center");

    expect_defect(Plane<T>{z, z}, Defect::zero_vector, "normal");
    expect_defect(Plane<T>{Vec3<T>{nan, T(0), T(0)}, e}, Defect::non_finite, "point");
    expect_defect(Plane<T>{z, Vec3<T>{huge, huge, T(0)}}, Defect::out_of_range, "normal");

    expect_defect(Disk<T>{z, e, T(0)}, Defect::nonpositive_radius, "radius");
    expect_defect(Disk<T>{z, z, T(1)}, Defect::zero_vector, "normal");

    expect_defect(Parallelogram<T>{z, e, T(3) * e}, Defect::degenerate, "parallel");
    expect_defect(Parallelogram<T>{z, z, e}, Defect::degenerate, "zero");
    expect_defect(Parallelogram<T>{z, e, Vec3<T>{T(0), nan, T(0)}}, Defect::non_finite, "edge1");

    expect_defect(Triangle<T>{z, e, T(2) * e}, Defect::degenerate, "collinear");
    expect_defect(Triangle<T>{z, e, Vec3<T>{T(0), T(0), inf}}, Defect::non_finite, "vertex c");

    expect_defect(Cylinder<T>{z, z, T(1), Caps::both}, Defect::zero_vector, "axis");
    expect_defect(Cylinder<T>{z, e, T(-1), Caps::none}, Defect::nonpositive_radius, "radius");
    expect_defect(Cylinder<T>{z, Vec3<T>{T(0), T(0), nan}, T(1), Caps::none}, Defect::non_finite, "p1");
    EXPECT_TRUE(validate(Cylinder<T>{z, e, T(1), Caps::none}));
}

}  // namespace
}  // namespace rayq::test::validate_test
