// The field-of-view camera (inim render, capture): framing, orientation, focus, its sensor as
// the equivalent pinhole's, and errors that name the settings.
#include <gtest/gtest.h>

#include <cmath>

#include "camera/fov_camera.h"
#include "expect_input_error.h"

using namespace inim;

namespace {
FovCameraSettings smallCamera() {
  FovCameraSettings c;
  c.width = 24;
  c.height = 16;
  return c;
}
Ray rayAt(const CameraModel& cam, float px, float py, Vec2 lens = Vec2(0.5f)) {
  Ray r;
  EXPECT_EQ(cam.generateRay(Vec2(px, py), lens, 550.0f, r), 1.0f);
  return r;
}
}  // namespace

TEST(FovCamera, CentreRayAlongViewAndFieldOfView) {
  FovCameraSettings c = smallCamera();
  c.width = 100;
  c.height = 50;
  c.hfovDeg = 90.0f;
  FovCameraModel cam(c);
  EXPECT_NEAR(rayAt(cam, 50.0f, 25.0f).d.z, -1.0f, 1e-6f);
  EXPECT_NEAR(rayAt(cam, 100.0f, 25.0f).d.x, std::sqrt(0.5f), 1e-5f);  // right edge: 45 degrees
  EXPECT_GT(rayAt(cam, 50.0f, 0.0f).d.y, 0.0f);                        // row 0 is the top
  EXPECT_EQ(cam.kind(), CameraModelKind::Pinhole);
  EXPECT_DOUBLE_EQ(cam.horizontalFovDeg(), 90.0);
}

// A thin lens focuses: every lens sample for one film point meets at the focus distance.
TEST(FovCamera, ThinLensRaysConvergeOnPlaneOfFocus) {
  FovCameraSettings c = smallCamera();
  c.apertureMm = 10.0f;
  c.focusDistanceMm = 200.0f;
  FovCameraModel cam(c);
  EXPECT_EQ(cam.kind(), CameraModelKind::ThinLens);
  Point3 p0;
  for (int i = 0; i < 5; ++i) {
    Ray r = rayAt(cam, 7.3f, 4.1f, {0.1f + 0.2f * i, 0.9f - 0.15f * i});
    float t = (150.0f - r.o.z) / r.d.z;  // eye at z = 350 looking at -z: focus plane z = 150
    Point3 p = r.at(t);
    if (i == 0) p0 = p;
    EXPECT_NEAR(glm::length(p - p0), 0.0f, 1e-3f);
  }
}

// One family: the camera's sensor is that of a pinhole at an image distance of 1 mm, and that
// pinhole (in double precision) makes the same rays to float precision, at any pose.
TEST(FovCamera, SameRaysAsTheEquivalentPinhole) {
  FovCameraSettings c = smallCamera();
  c.hfovDeg = 40.0f;
  c.pose = {{30.0, 70.0, 150.0}, {1.0, -2.0, -5.0}, {0.0, 1.0, 0.0}};
  FovCameraModel cam(c);
  EXPECT_NEAR(cam.sensor().widthMm(), 2.0 * std::tan(20.0 * M_PI / 180.0), 1e-12);
  PinholeCameraModel pinhole(cam.sensor(), c.pose, 1.0, false);
  for (float px : {0.0f, 5.25f, 24.0f})
    for (float py : {0.0f, 11.5f, 16.0f}) {
      Ray a = rayAt(cam, px, py), b;
      pinhole.generateRay(Vec2(px, py), Vec2(0.5f), 550.0f, b);
      EXPECT_LT(glm::length(a.d - b.d), 2e-6f) << px << ", " << py;
      EXPECT_LT(glm::length(a.o - b.o), 1e-4f);
    }
}

TEST(FovCamera, ErrorsNameTheSettings) {
  auto keyOf = [](void (*edit)(FovCameraSettings&)) {
    return expectInputError([&] {
             FovCameraSettings c = smallCamera();
             edit(c);
             FovCameraModel cam(c);
           }).key();
  };
  EXPECT_EQ(keyOf([](FovCameraSettings& c) { c.width = 0; }), "width");
  EXPECT_EQ(keyOf([](FovCameraSettings& c) { c.height = -2; }), "height");
  EXPECT_EQ(keyOf([](FovCameraSettings& c) { c.hfovDeg = 180.0f; }), "hfov_deg");
  EXPECT_EQ(keyOf([](FovCameraSettings& c) { c.apertureMm = -1.0f; }), "aperture_mm");
  EXPECT_EQ(keyOf([](FovCameraSettings& c) { c.pose.lookAt = c.pose.eye; }), "pose");
  EXPECT_EQ(keyOf([](FovCameraSettings& c) { c.pose.up = Vec3d(0.0, 0.0, 2.0); }), "pose.up");
}
