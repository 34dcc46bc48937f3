// The shared reference datasets (skipped when absent): NeRF's Lego (Blender, RGBA 800x800) and
// Middlebury's templeSparseRing.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include "dataset/dataset.h"

using namespace inim;

namespace {
const std::string kData = "/work/shared/data";
}

TEST(SharedData, LegoAtDownscale4) {
  const std::string dir = kData + "/lego";
  if (!std::filesystem::exists(dir + "/transforms_train.json")) GTEST_SKIP() << dir << " absent";
  double angleX = nlohmann::json::parse(std::ifstream(dir + "/transforms_train.json"))["camera_angle_x"];
  DatasetOptions o;
  o.downscale = 4;
  auto t0 = std::chrono::steady_clock::now();
  Dataset d = loadDataset(dir, o);
  double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  EXPECT_EQ(d.format, "blender");
  ASSERT_EQ(d.frames.size(), 100u);
  EXPECT_EQ(d.test.size(), 13u);
  for (const DatasetFrame& f : d.frames) {
    ASSERT_EQ(f.image.width, 200);
    ASSERT_EQ(f.image.height, 200);
    EXPECT_NEAR(f.intrinsics.fx, 0.5 * 200 / std::tan(0.5 * angleX), 1e-9);
    EXPECT_EQ(f.intrinsics.cx, 100.0);
  }
  // White background: the corner is white, and some pixel is not.
  EXPECT_NEAR(d.frames[0].image.at(0, 0, 0), 1.0f, 1e-6);
  const Box3d& b = d.sceneBox;
  std::printf("lego: %zu frames loaded in %.2f s; box (%.3f %.3f %.3f) - (%.3f %.3f %.3f), near %.3f far %.3f\n",
              d.frames.size(), secs, b.lo.x, b.lo.y, b.lo.z, b.hi.x, b.hi.y, b.hi.z, d.nearPlane, d.farPlane);
  // NeRF trains Lego in [-1.5, 1.5]^3 with near 2, far 6.
  for (int a = 0; a < 3; ++a) {
    EXPECT_NEAR(b.lo[a], -1.5, 0.3);
    EXPECT_NEAR(b.hi[a], 1.5, 0.3);
  }
  EXPECT_LT(d.nearPlane, 2.7);
  EXPECT_GT(d.farPlane, 5.3);
}

TEST(SharedData, TempleSparseRingBoxContainsTheModel) {
  const std::string dir = kData + "/templeSparseRing";
  if (!std::filesystem::exists(dir + "/templeSR_par.txt")) GTEST_SKIP() << dir << " absent";
  Dataset d = loadDataset(dir);
  EXPECT_EQ(d.format, "middlebury");
  ASSERT_EQ(d.frames.size(), 16u);
  EXPECT_EQ(d.frames[0].intrinsics.width, 640);
  EXPECT_EQ(d.frames[0].intrinsics.height, 480);
  const Box3d& b = d.sceneBox;
  std::printf("temple: box (%.4f %.4f %.4f) - (%.4f %.4f %.4f), near %.3f far %.3f\n", b.lo.x, b.lo.y,
              b.lo.z, b.hi.x, b.hi.y, b.hi.z, d.nearPlane, d.farPlane);
  // The tight boxes: the data folder's README, and the one quoted for the full temple ring.
  for (auto [lo, hi] : {std::pair{glm::dvec3(-0.073568, 0.021728, -0.012445), glm::dvec3(0.028855, 0.181892, 0.062736)},
                        std::pair{glm::dvec3(-0.054568, 0.001728, -0.042945), glm::dvec3(0.047855, 0.161892, 0.032236)}}) {
    EXPECT_TRUE(b.contains(lo)) << lo.x << " " << lo.y << " " << lo.z;
    EXPECT_TRUE(b.contains(hi)) << hi.x << " " << hi.y << " " << hi.z;
  }
  // Every camera sees the model's centre in its image.
  glm::dvec3 centre(-0.0224, 0.1018, 0.0251);
  for (const DatasetFrame& f : d.frames) {
    glm::dvec2 p;
    ASSERT_TRUE(projectToFrame(f, centre, p));
    EXPECT_GT(p.x, 0);
    EXPECT_LT(p.x, 640);
    EXPECT_GT(p.y, 0);
    EXPECT_LT(p.y, 480);
  }
}
