// The default placement of a splat scene: COLMAP axes turned into the display frame and the
// robust box of the positions fitted to the panel, whatever a few far-out splats do.
#include <gtest/gtest.h>

#include <random>

#include "splats/splat_placement.h"

namespace inim {
namespace {

// 2000 splats uniform in x [-2, 2], y [-1, 1], z [3, 5] (COLMAP: y down, z away from the
// camera) and 20 floaters 1000 units out.
Gaussians boxScene() {
  Gaussians g;
  g.resize(2020, 0);
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  for (size_t i = 0; i < 2000; ++i) g.position[i] = Vec3(2.0f * u(rng), u(rng), 4.0f + u(rng));
  for (size_t i = 2000; i < 2020; ++i) g.position[i] = Vec3(1000.0f, -1000.0f, 1000.0f);
  return g;
}

TEST(SplatPlacement, RobustBoxFitsThePanelAndFacesTheViewer) {
  const Gaussians g = boxScene();
  const SplatBox box = robustSplatBox(g);
  // The 2nd..98th percentiles of a uniform [-1, 1] are about -0.96..0.96; floaters ignored.
  EXPECT_NEAR(box.lo.y, -0.96f, 0.03f);
  EXPECT_NEAR(box.hi.y, 0.96f, 0.03f);
  EXPECT_NEAR(box.hi.x, 1.92f, 0.06f);
  const SplatFrame f = defaultSplatFrame(g);
  // y limits: 0.9 * 65 mm over the y extent (x would allow 0.9 * 151.8 / 3.84 = 35.6 mm/unit).
  EXPECT_NEAR(f.scale, 0.9f * kSplatPanelHeightMm / (box.hi.y - box.lo.y), 1e-3f * f.scale);
  const Point3 lo = f.toField(box.lo), hi = f.toField(box.hi);
  EXPECT_LE(std::fabs(hi.x - lo.x), 0.9f * kSplatPanelWidthMm);
  EXPECT_NEAR(std::fabs(hi.y - lo.y), 0.9f * kSplatPanelHeightMm, 1e-3f);
  const Point3 centre = f.toField(0.5f * (box.lo + box.hi));
  EXPECT_NEAR(glm::length(centre), 0.0f, 1e-3f);
  // COLMAP y down -> display y up; farther from the camera -> farther from the viewer (-z);
  // x keeps its sense.
  EXPECT_LT(f.toField(Vec3(0, 1, 4)).y, f.toField(Vec3(0, 0, 4)).y);
  EXPECT_LT(f.toField(Vec3(0, 0, 5)).z, f.toField(Vec3(0, 0, 4)).z);
  EXPECT_GT(f.toField(Vec3(1, 0, 4)).x, f.toField(Vec3(0, 0, 4)).x);
}

}  // namespace
}  // namespace inim
