// DisplayPose: the sign conventions of the gimbal (which edge moves away for +H and +V) and
// where the camera sits in the display frame.
#include <gtest/gtest.h>

#include <cmath>

#include "display_view/display_pose.h"

using namespace inim;

TEST(DisplayPose, SignConventions) {
  DisplayPose p;
  p.distanceMm = 350.0;
  p.rotHDeg = 7.0;
  const Transform w = p.displayToWorld();
  // +H: the display's right edge moves away from the camera (toward -z), the left edge closer.
  EXPECT_LT(w.point(Point3d(50.0, 0.0, 0.0)).z, 0.0);
  EXPECT_GT(w.point(Point3d(-50.0, 0.0, 0.0)).z, 0.0);
  EXPECT_NEAR(p.normalInWorld().x, std::sin(7.0 * M_PI / 180.0), 1e-12);
  // The camera, in the display frame, sits at azimuth -H: to the display's left.
  ViewingPose cp = p.cameraPose();
  EXPECT_NEAR(cp.eye.x, -350.0 * std::sin(7.0 * M_PI / 180.0), 1e-9);
  EXPECT_NEAR(cp.eye.z, 350.0 * std::cos(7.0 * M_PI / 180.0), 1e-9);
  EXPECT_NEAR(glm::length(cp.lookAt), 0.0, 1e-12);
  // +V: the top edge moves away from the camera; the camera sits below the display normal.
  DisplayPose v;
  v.rotVDeg = 7.0;
  EXPECT_LT(v.displayToWorld().point(Point3d(0.0, 30.0, 0.0)).z, 0.0);
  EXPECT_LT(v.cameraPose().eye.y, 0.0);
  // Both: the camera stays at distance D from the centre.
  DisplayPose b{7.0, -7.0, 350.0};
  EXPECT_NEAR(glm::length(b.cameraPose().eye), 350.0, 1e-9);
}
