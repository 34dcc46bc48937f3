// EIA synthesis on hex-lattice layouts: a point source lights, in every hexagonal EI that
// sees it, the pixel pinhole geometry predicts; the EIA is black outside the EIs; the preview
// runs.
#include <gtest/gtest.h>

#include "display/hex_test_util.h"
#include "rays/pinhole_rays.h"
#include "synth_test_util.h"
#include "synthesis/eia_synthesis.h"
#include "synthesis/preview.h"

using namespace inim;
using namespace synth_test;

namespace {

float brightness(const Image& img, int x, int y) { return img.at(x, y, 0) + img.at(x, y, 1) + img.at(x, y, 2); }

}  // namespace

class HexPointImage : public ::testing::TestWithParam<std::tuple<double, EiLayoutKind>> {};

TEST_P(HexPointImage, LandsOnPredictedPixel) {
  auto [z, kind] = GetParam();
  Display disp = hex_test::hexDisplay(11, 9, 9, 0.1, 3.0, kind, kind == EiLayoutKind::LensGrid ? 0.95 : 0.0);
  EiLayout L = computeLayout(disp);
  const Point3d p(0.23, -0.17, z);
  const double footprint = L.pixelMm * std::abs(z) / L.gapMm;
  MockField f({{p, 3.0 * footprint, Vec3(0.3f), footprint, nullptr}}, FieldEncoding::RGB);
  SynthesisSettings s;
  s.progress = false;
  s.vcpMm = 50.0;
  SynthesisResult r = synthesizeEia(L, disp.panel, f, s);
  int seen = 0, ok = 0;
  for (int k = 0; k < L.eiCols; ++k)
    for (int l = 0; l < L.eiRows; ++l) {
      auto pred = predictPixelForPoint(L, k, l, p);
      if (!pred) continue;
      ++seen;
      float best = -1.0f;
      PixelCoord arg{};
      L.forEachRayOfEi(k, l, [&](int64_t, int col, int row, int, int) {
        const float b = brightness(r.eia, L.panelCol0 + col, L.panelRow0 + row);
        if (b > best) best = b, arg = {col, row};
      });
      if (best > 0.0f && arg == eiaPixel(L, *pred)) ++ok;
    }
  EXPECT_GE(seen, 12) << "too few EIs see the point";
  EXPECT_GE(ok, int(std::ceil(0.95 * seen))) << ok << " of " << seen << " EIs at z = " << z;
  EXPECT_EQ(r.stats.realRays > 0, z > 0);
  EXPECT_EQ(r.stats.virtualRays > 0, z < 0);
  // Nothing outside the EIs.
  for (int y = 0; y < L.panelH; ++y)
    for (int x = 0; x < L.panelW; ++x) {
      int k, l;
      if (!L.eiAtPixel(x - L.panelCol0, y - L.panelRow0, k, l)) ASSERT_EQ(brightness(r.eia, x, y), 0.0f);
    }
  std::printf("  hex, z = %+.0f mm (%s): brightest pixel = predicted in %d of %d EIs\n", z, layoutName(kind), ok, seen);
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
  Display disp = hex_test::hexDisplay(7, 6, 9, 0.1, 3.0);
  EiLayout L = computeLayout(disp);
  MockField f({{Vec3d(0.0, 0.0, -300.0), 200.0, Vec3(0.5f), 0.0, nullptr}}, FieldEncoding::RGB);
  SynthesisSettings s;
  s.progress = false;
  s.vcpMm = 50.0;
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
