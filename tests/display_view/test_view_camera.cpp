// The view camera made from another pose's (makeViewCamera's samePrecomputed): the real lens
// moved, not focused and scanned again, gives the rays of one made from scratch at that pose,
// bit for bit; a different focus is not taken from it.
#include <gtest/gtest.h>

#include <cstring>

#include "core/rng.h"
#include "display_view/display_pose.h"
#include "display_view/view_camera.h"
#include "view_test_util.h"

using namespace inim;
using namespace view_test;

TEST(ViewCamera, CameraMovedFromAnotherPoseTracesTheSameRays) {
  ViewCameraOptions o;
  o.width = 96;
  const DisplayPose first{0.0, 0.0, 350.0}, second{7.0, -7.0, 350.0};
  const auto made = makeViewCamera(defaultCamera(), first, o);
  const auto moved = makeViewCamera(defaultCamera(), second, o, made.get());
  const auto fresh = makeViewCamera(defaultCamera(), second, o);
  ASSERT_EQ(moved->kind(), CameraModelKind::RealLens);
  Rng rng(3, 1);
  int passed = 0;
  for (int i = 0; i < 2000; ++i) {
    const Vec2 pixel(96.0f * rng.uniform(), 72.0f * rng.uniform()), lens(rng.uniform(), rng.uniform());
    const float lambda = 400.0f + 300.0f * rng.uniform();
    Ray a, b;
    const float wa = moved->generateRay(pixel, lens, lambda, a), wb = fresh->generateRay(pixel, lens, lambda, b);
    ASSERT_EQ(wa, wb);
    if (!(wa > 0.0f)) continue;
    ++passed;
    EXPECT_EQ(std::memcmp(&a, &b, sizeof(Ray)), 0);
  }
  EXPECT_GT(passed, 1000);
  // Another focus: focused anew, not moved.
  o.focusMm = 300.0;
  const auto refocused = makeViewCamera(defaultCamera(), second, o, made.get());
  const auto* lens = dynamic_cast<const RealLensCameraModel*>(refocused.get());
  ASSERT_NE(lens, nullptr);
  EXPECT_EQ(lens->focusDistanceMm(), 300.0);
  EXPECT_NE(lens->sensorDistanceMm(), dynamic_cast<const RealLensCameraModel*>(made.get())->sensorDistanceMm());
}
