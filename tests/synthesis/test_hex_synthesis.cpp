// EIA synthesis on hex-lattice layouts: a point source lights, in every hexagonal EI that
// sees it, the pixel pinhole geometry predicts; the EIA is black outside the EIs; the preview
// runs.
#include <gtest/gtest.h>

#include "rays/pinhole_rays.h"
#include "synth_test_util.h"
#include "synthesis/eia_synthesis.h"
#include "synthesis/preview.h"

using namespace inim;
using namespace synth_test;

class HexPointImage : public ::testing::TestWithParam<std::tuple<double, EiLayoutKind>> {};

TEST_P(HexPointImage, LandsOnPredictedPixel) {
  auto [z, kind] = GetParam();
  Display disp = hexDisplay(
      {.cols = 11, .rows = 9, .eiPx = 9, .layout = kind, .lensPitchMm = kind == EiLayoutKind::LensGrid ? 0.95 : 0.0});
  const EiLayout L = computeLayout(disp);
  const SynthesisResult r = expectPointImageOnPredictedPixels(L, disp.panel, z);
  // Nothing outside the EIs.
  for (int y = 0; y < L.panelH; ++y)
    for (int x = 0; x < L.panelW; ++x) {
      int k, l;
      if (!L.eiAtPixel(x - L.panelCol0, y - L.panelRow0, k, l)) {
        ASSERT_EQ(brightness(r.eia, x, y), 0.0f);
      }
    }
}

INSTANTIATE_TEST_SUITE_P(RealAndVirtual, HexPointImage,
                         ::testing::Values(std::tuple{12.0, EiLayoutKind::Parallel},
                                           std::tuple{-12.0, EiLayoutKind::Parallel},
                                           std::tuple{25.0, EiLayoutKind::Parallel},
                                           std::tuple{16.0, EiLayoutKind::LensGrid},
                                           std::tuple{-16.0, EiLayoutKind::LensGrid}));

// A big uniform sphere fills every EI: every hex EI pixel is lit, all others are black; the
// placement preview draws one ray per lenslet.
TEST(HexSynthesis, UniformFieldFillsExactlyTheHexEis) {
  Display disp = hexDisplay({.cols = 7, .rows = 6, .eiPx = 9});
  EiLayout L = computeLayout(disp);
  MockField f({{Vec3d(0.0, 0.0, -300.0), 200.0, Vec3(0.5f), 0.0, nullptr}}, FieldEncoding::RGB);
  SynthesisSettings s = quietSettings(50.0);
  SynthesisResult r = synthesizeEia(L, disp.panel, f, s);
  int64_t lit = 0;
  for (int y = 0; y < L.panelH; ++y)
    for (int x = 0; x < L.panelW; ++x) {
      int k, l;
      const bool in = L.eiAtPixel(x - L.panelCol0, y - L.panelRow0, k, l);
      const bool on = brightness(r.eia, x, y) > 0.0f;
      EXPECT_EQ(in, on) << x << "," << y;
      lit += on;
    }
  EXPECT_EQ(lit, L.numRays());
  PreviewSettings ps;
  PreviewResult pr = renderPlacementPreview(L, f, Transform(), 50.0, ps);
  EXPECT_EQ(pr.lenslets, 7 * 6);
  EXPECT_EQ(pr.missed, 0);
}
