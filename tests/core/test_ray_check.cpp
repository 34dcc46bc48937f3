// The ray tracer's door: what no ray may be, from every extreme a hostile file can hold.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "core/error.h"
#include "core/ray_check.h"

using namespace inim;

namespace {

bool passes(const Vec3d& o, const Vec3d& d) {
  try {
    checkRay(o, d, "rays.npy", "row 7");
    return true;
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "rays.npy");
    EXPECT_EQ(e.key(), "row 7");
    return false;
  }
}

}  // namespace

TEST(RayCheck, OrdinaryRaysPass) {
  EXPECT_TRUE(passes({0, 0, 0}, {0, 0, 1}));
  EXPECT_TRUE(passes({-0.0, 1e-310, 5e6}, glm::normalize(Vec3d(1, 2, 3))));  // -0 and subnormals are numbers
  EXPECT_TRUE(passes({kMaxRayCoordinateMm, 0, 0}, {1, 0, 0}));
}

TEST(RayCheck, EmbreeBoundExtremesAreRefused) {
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  for (double big : {9.223372036854775808e18, 1.8446744073709552e19, 3e38, 1e30, -3e38, 1.0000001e7})
    EXPECT_FALSE(passes({big, 0, 0}, {0, 0, 1})) << big;
  EXPECT_FALSE(passes({nan, 0, 0}, {0, 0, 1}));
  EXPECT_FALSE(passes({0, 0, 0}, {0, nan, 1}));
  EXPECT_FALSE(passes({0, 0, inf}, {0, 0, 1}));
  EXPECT_FALSE(passes({0, 0, 0}, {0, 0, 0}));              // zero direction
  EXPECT_FALSE(passes({0, 0, 0}, {0, 0, 1.00001}));        // not unit
  EXPECT_FALSE(passes({0, 0, 0}, {4.9e-324, 0, 0}));       // a subnormal direction has no length
  EXPECT_TRUE(passes({0, 0, 0}, {0, 0, 1.0000005}));       // within 1e-6
}
