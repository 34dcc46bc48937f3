// Distortion model and frame rays: undistort(distort(p)) = p, project(frameRay(p)) = p.
#include "dataset/intrinsics.h"

#include <gtest/gtest.h>

#include "dataset/dataset.h"
#include "dataset_test_util.h"

using namespace inim;

namespace {

Intrinsics distortedCamera() {
  Intrinsics k;
  k.width = 640;
  k.height = 480;
  k.fx = 500;
  k.fy = 510;
  k.cx = 322.5;
  k.cy = 236.25;
  k.k1 = -0.12;
  k.k2 = 0.03;
  k.p1 = 0.001;
  k.p2 = -0.0015;
  return k;
}

}  // namespace

TEST(Intrinsics, UndistortInvertsDistort) {
  Intrinsics k = distortedCamera();
  for (double x = -0.7; x <= 0.7; x += 0.1)
    for (double y = -0.5; y <= 0.5; y += 0.1) {
      glm::dvec2 p(x, y);
      glm::dvec2 back = undistortNormalized(k, distortNormalized(k, p));
      EXPECT_NEAR(back.x, x, 1e-12);
      EXPECT_NEAR(back.y, y, 1e-12);
    }
}

TEST(Intrinsics, ResizedScalesPixelEdges) {
  Intrinsics k = distortedCamera();
  Intrinsics h = k.resized(160, 120);
  EXPECT_DOUBLE_EQ(h.fx, 125.0);
  EXPECT_DOUBLE_EQ(h.cy, 236.25 / 4);
  EXPECT_EQ(h.k1, k.k1);
  // The image corner stays the image corner.
  glm::dvec2 n = pixelToNormalized(k, {640, 480}), m = pixelToNormalized(h, {160, 120});
  EXPECT_NEAR(n.x, m.x, 1e-12);
  EXPECT_NEAR(n.y, m.y, 1e-12);
}

TEST(FrameRay, ProjectInvertsFrameRay) {
  DatasetFrame f;
  f.intrinsics = distortedCamera();
  f.cameraToWorld = dataset_test::lookAtC2W({1.0, 2.0, 3.0}, {0.1, -0.2, 0.3}, {0.2, 1.0, 0.1});
  for (double px : {0.5, 100.25, 320.0, 639.5})
    for (double py : {0.5, 77.7, 240.0, 479.5}) {
      glm::dvec3 o, d;
      frameRay(f, px, py, o, d);
      EXPECT_NEAR(glm::length(d), 1.0, 1e-12);
      glm::dvec2 p;
      ASSERT_TRUE(projectToFrame(f, o + 2.5 * d, p));
      EXPECT_NEAR(p.x, px, 1e-8);
      EXPECT_NEAR(p.y, py, 1e-8);
    }
}

TEST(FrameRay, CentrePixelLooksDownMinusZ) {
  // A Blender-style camera: principal point at the centre, no distortion.
  DatasetFrame f;
  f.intrinsics.width = f.intrinsics.height = 800;
  f.intrinsics.fx = f.intrinsics.fy = 1111.1;
  f.intrinsics.cx = f.intrinsics.cy = 400;
  f.cameraToWorld = dataset_test::lookAtC2W({0, -4, 1}, {0, 0, 0.5}, {0, 0, 1});
  glm::dvec3 o, d;
  frameRay(f, 400, 400, o, d);  // the corner shared by the 4 central pixels = image centre
  glm::dvec3 minusZ = -glm::normalize(glm::dvec3(f.cameraToWorld[2]));
  EXPECT_NEAR(glm::length(d - minusZ), 0.0, 1e-12);
  EXPECT_NEAR(glm::length(o - glm::dvec3(0, -4, 1)), 0.0, 1e-12);
  // +x pixels go to the camera's right, lower rows (larger py) go down.
  glm::dvec3 dr, dd;
  frameRay(f, 700, 400, o, dr);
  frameRay(f, 400, 700, o, dd);
  EXPECT_GT(glm::dot(dr, glm::dvec3(f.cameraToWorld[0])), 0.1);
  EXPECT_LT(glm::dot(dd, glm::dvec3(f.cameraToWorld[1])), -0.1);
}
