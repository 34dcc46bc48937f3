// Fig. 11's error against depth (runs/fig11_depth.h): the reference of an analytic scene
// (a flat plane, through the scene loader and integrator as fig11 uses them) has the plane's
// display z in its Z channel, through a scaled placement too; taking the depth channels off
// leaves R, G, B as they were; the figure's L is the reconstruction's, through the cover glass
// when the display has one; and a small run writes the bins, the figure and metrics.json's
// "depth_error", its reference images staying R, G, B.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "camera/camera_config.h"
#include "camera/camera_model.h"
#include "display/display.h"
#include "display/display_info.h"
#include "runs/fig11.h"
#include "runs/fig11_depth.h"
#include "fixtures.h"
#include "grey_plane.h"
#include "field/placement.h"
#include "scene/analytic_scene.h"
#include "display_view/display_pose.h"
#include "display_view/reference_renderer.h"

using namespace inim;

namespace {



// Reference of the plane through `placement`, seen head-on from 200 mm: 64 x 48 pixels of
// 0.05 mm at 20 mm (a 31 x 23 mm field at the plane).
Image planeReference(const AnalyticScene& scene, const Placement& placement) {
  const DisplayPose pose{0.0, 0.0, 200.0};
  PinholeCameraModel cam(SensorGeometry{64, 48, 0.05}, pose.cameraPose(), 20.0, false);
  ReferenceSettings s;
  s.spp = 8;
  s.progress = false;
  s.depth = true;
  return renderReference(scene, placement.toDisplay(), cam, fixtures::defaultSensor(), s).image;
}

// Largest |Z - z| over the fully covered pixels, and how many there are.
std::pair<double, int> zErrorOnCovered(const Image& img, double z) {
  double worst = 0.0;
  int covered = 0;
  const int a = img.channelIndex("A"), zc = img.channelIndex("Z");
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x)
      if (img.at(x, y, a) == 1.0f) {
        ++covered;
        worst = std::max(worst, std::abs(double(img.at(x, y, zc)) - z));
      }
  return {worst, covered};
}

}  // namespace

TEST(Fig11Depth, AnalyticPlaneHasItsDisplayZ) {
  const auto scene = fixtures::greyPlaneAt5mm(20);
  const auto [err, covered] = zErrorOnCovered(planeReference(*scene, Placement{}), 5.0);
  std::printf("[ measured ] analytic plane at z = 5: %d covered pixels, max |Z - 5| = %.2e mm\n", covered, err);
  EXPECT_GT(covered, 400);
  EXPECT_LE(err, 1e-3);
}

TEST(Fig11Depth, AnalyticPlaneWithPlacementScaleTwoIsAtTen) {
  const auto scene = fixtures::greyPlaneAt5mm(20);
  Placement pl;
  pl.scale = Vec3d(2.0);
  const auto [err, covered] = zErrorOnCovered(planeReference(*scene, pl), 10.0);
  std::printf("[ measured ] analytic plane placed at z = 10 (scale 2): %d covered pixels, max |Z - 10| = %.2e mm\n",
              covered, err);
  EXPECT_EQ(covered, 64 * 48);  // 40 x 40 mm now: it fills the 30 x 23 mm view
  EXPECT_LE(err, 1e-3);
}

TEST(Fig11Depth, TakingTheDepthChannelsOffLeavesTheColourAsItWas) {
  const auto scene = fixtures::greyPlaneAt5mm(20);
  Image withDepth = planeReference(*scene, Placement{});
  const Image original = withDepth;
  const ReferenceDepth d = takeDepthChannels(withDepth);
  ASSERT_TRUE(d.present);
  ASSERT_EQ(withDepth.channels, (std::vector<std::string>{"R", "G", "B"}));
  for (int y = 0; y < original.height; ++y)
    for (int x = 0; x < original.width; ++x) {
      const size_t i = size_t(y) * size_t(original.width) + size_t(x);
      for (int c = 0; c < 3; ++c) ASSERT_EQ(withDepth.at(x, y, c), original.at(x, y, c));
      ASSERT_EQ(d.coverage[i], original.at(x, y, 3));
      ASSERT_EQ(d.z[i], original.at(x, y, 4));
      ASSERT_EQ(d.spread[i], original.at(x, y, 5));
    }
  // An image without depth is left alone.
  Image rgb = withDepth;
  EXPECT_FALSE(takeDepthChannels(rgb).present);
  EXPECT_EQ(rgb.data, withDepth.data);
}

TEST(Fig11Depth, MarksAreTheReconstructionsLAndDepthRange) {
  Display d = loadDisplay(displayPathOrDefault(""));
  ASSERT_TRUE(d.panel.coverGlass.has_value());  // the prototype has one
  const GapInfo rec = derive(d).reconstruction;
  const DepthMarks withGlass = depthMarksFor(d);
  ASSERT_TRUE(withGlass.referencePlaneMm && rec.opticalReferencePlaneMm && rec.referencePlaneMm);
  EXPECT_EQ(*withGlass.referencePlaneMm, *rec.opticalReferencePlaneMm);
  EXPECT_NE(withGlass.referencePlaneLabel.find("cover glass"), std::string::npos);
  EXPECT_EQ(withGlass.samplingRangeMm, 2.0 * d.reconstructionGapMm);  // lateral sampling <= 2P
  // The depth of field: half a magnified pixel's worth of facet drift either side of L
  // (prototype: d = 0.0395 mm, g_eff = 3.812 mm, L_eff = 24.5 mm, P = 1 mm: about +-3.1 mm).
  ASSERT_TRUE(withGlass.depthOfFieldMm.has_value());
  const double L = *withGlass.referencePlaneMm, half = 0.5 * d.panel.pixelPitchMm * L * L / (*rec.opticalGapMm * 1.0);
  EXPECT_NEAR(withGlass.depthOfFieldMm->first, L - half, 1e-9);
  EXPECT_NEAR(withGlass.depthOfFieldMm->second, L + half, 1e-9);
  EXPECT_NEAR(half, 3.1, 0.1);
  // The glass moves the panel's image: without it, L = g f / (g - f) of the bare gap.
  d.panel.coverGlass.reset();
  const DepthMarks bare = depthMarksFor(d);
  ASSERT_TRUE(bare.referencePlaneMm.has_value());
  const double f = derive(d).focus.focalLengthMm, g = d.reconstructionGapMm;
  EXPECT_NEAR(*bare.referencePlaneMm, g * f / (g - f), 1e-9);
  EXPECT_NE(*bare.referencePlaneMm, *withGlass.referencePlaneMm);
  EXPECT_EQ(bare.referencePlaneLabel.find("cover glass"), std::string::npos);
}

// A small run (about 20 s, most of it the full-panel EIA): per pose the bins' CSV, the depth
// EXR and metrics.json's bins, counting at most the pixels that see the display; the reference
// EXR stays R, G, B; one figure. (Colour with depth on or off: ReferenceDepth tests in test_view.)
TEST(Fig11Depth, SmallRunWritesBinsFigureAndMetrics) {
  const fixtures::ScratchDir scratch("fig11_depth");
  Fig11Settings s;
  s.width = 64;
  s.spp = s.referenceSpp = s.eiaSpp = 1;
  s.outDir = scratch.path("out");
  ASSERT_TRUE(s.depthError);  // the default
  (void)runFig11(s);
  namespace fs = std::filesystem;
  const fs::path out(s.outDir);
  EXPECT_TRUE(fs::exists(out / "depth_error.png"));
  std::ifstream in(out / "metrics.json");
  const Json m = Json::parse(in);
  for (const char* pose : {"centre", "left", "right", "top", "bottom"}) {
    SCOPED_TRACE(pose);
    const std::string p(pose);
    EXPECT_TRUE(fs::exists(out / ("depth_error_" + p + ".csv")));
    const Image depth = readImage((out / ("reference_" + p + "_depth.exr")).string());
    EXPECT_EQ(depth.channels, (std::vector<std::string>{"A", "Z", "dZ"}));
    EXPECT_EQ(readImage((out / ("reference_" + p + ".exr")).string()).numChannels(), 3);
    const Json& bins = m.at(p).at("depth_error");
    ASSERT_EQ(bins.size(), 24u);
    int64_t counted = 0;
    for (const Json& b : bins) {
      EXPECT_LT(b.at("z_lo").get<double>(), b.at("z_hi").get<double>());
      counted += b.at("pixels").get<int64_t>() + b.at("mixed_pixels").get<int64_t>();
    }
    EXPECT_GT(counted, 0);
    EXPECT_LE(counted, m.at(p).at("pixels").get<int64_t>());
  }
}
