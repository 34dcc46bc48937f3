// The Footprint panel estimator (estimators/footprint_estimator.h) against the point-sampling
// reference estimator: the same image at high spp (region means and RMSE), energy (uniform
// white), a zero box reproducing the point estimator bit for bit. Thread-count determinism is
// tested in test_estimators.cpp, the emitter's box averages in test_panel_emitter.cpp.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>

#include "core/error.h"
#include "core/parallel.h"
#include "mla_optics/ideal_mla.h"
#include "mla_optics/real_mla.h"
#include "display_view/panel_emitter.h"
#include "display_view/view_renderer.h"
#include "real_setup.h"
#include "view_test_util.h"

using namespace inim;
using namespace view_test;

TEST(ViewFootprint, ZeroBoxIsBitIdenticalToThePointEstimator) {
  RealSetup r;
  const Image point = r.render(PanelEstimator::PointSample, 4).image;
  const ViewResult zero = r.render(PanelEstimator::Footprint, 4, 1, 0.0);
  EXPECT_GT(zero.stats.footprint.probeRays, 0u);
  ASSERT_EQ(point.data.size(), zero.image.data.size());
  EXPECT_EQ(std::memcmp(point.data.data(), zero.image.data.data(), point.data.size() * sizeof(float)), 0);
}

TEST(ViewFootprint, UniformWhiteIsThePanelWhiteAndEqualsThePointEstimator) {
  // Ideal MLA, pinhole camera: every pixel's exact value is the tile-averaged panel white.
  const double D = 2000.0, g = 3.0, P = 1.0, f = g / (1.5 + g / D);
  Display d = smallDisplay(8, 4, 10, 0.1, P, f, g);
  const EiLayout L = computeLayout(d);
  PanelEmitter panel(d.panel, L, uniformEia(L, 1, 1, 1), "white.exr", g);
  IdealLensletMla mla(L, P, f, g);
  ViewingPose pose;
  pose.eye = {0.0, 0.0, D};
  auto cam = pinholeCamera(pose, 4, 2, 0.01, 10.0);
  Vec3d white(0.0);
  for (int c = 0; c < 3; ++c) {
    class One final : public Spectrum {
     public:
      One(const PanelEmitter& e, int c) : e_(e), c_(c) {}
      float operator()(float l) const override { return e_.averageChannelSpectrum(c_, l); }
      float maxValue() const override { return 0.0f; }
      const PanelEmitter& e_;
      int c_;
    };
    white += defaultCamera().sensor.cameraRgb(One(panel, c));
  }
  // Each camera pixel spans 2 x 2 lenslets here (the lenslet lottery, not the panel's, dominates).
  ViewSettings s;
  s.spp = 1024;
  s.progress = false;
  s.panelEstimator = PanelEstimator::Footprint;
  ViewResult r = renderView(*cam, defaultCamera().sensor, mla, panel, L.activeArea(), s);
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(blockMean(r.image, 0, 0, 4, 2, c) / white[c], 1.0, 0.005) << "channel " << c;
    for (int y = 0; y < r.image.height; ++y)
      for (int x = 0; x < r.image.width; ++x)
        EXPECT_NEAR(r.image.at(x, y, c) / white[c], 1.0, 0.03) << x << "," << y << " channel " << c;
  }

  // Real MLA, thin lens, cover glass: white gives the same mean with both estimators.
  RealSetup w(true);
  const Image fp = w.render(PanelEstimator::Footprint, 64).image;
  const Image pt = w.render(PanelEstimator::PointSample, 1024).image;
  std::printf("[ measured ] real MLA, uniform white: mean footprint (64 spp) / point (1024 spp) = %.4f; "
              "RMSE/mean footprint %.2f%%\n", meanAll(fp) / meanAll(pt), 100.0 * rmse(fp, pt) / meanAll(pt));
  EXPECT_NEAR(meanAll(fp) / meanAll(pt), 1.0, 0.01);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(blockMean(fp, 0, 0, 24, 16, c) / blockMean(pt, 0, 0, 24, 16, c), 1.0, 0.015);
}

TEST(ViewFootprint, AgreesWithThePointEstimatorAtHighSpp) {
  // The point estimator at 4096 spp (two seeds, to measure its own noise) against the footprint
  // estimator, whose box shrinks as 1/sqrt(spp), so that its bias (a slightly wider panel-side
  // blur) vanishes. At 4096 spp a footprint image must be as close to a point image as another
  // point image is (its bias far below the point estimator's noise); the error of the footprint
  // image must fall with spp; region means must agree.
  RealSetup r;
  const Image a = r.render(PanelEstimator::PointSample, 4096, 1).image;
  const Image b = r.render(PanelEstimator::PointSample, 4096, 2).image;
  const double m = meanAll(a);
  const double pointPair = rmse(a, b);
  const double noiseA = pointPair / std::sqrt(2.0);  // RMSE of one point image
  std::printf("[ measured ] point 4096 spp: RMSE/mean of one image %.2f%%\n", 100.0 * noiseA / m);
  double prev = 1e300;
  for (int spp : {4, 16, 256, 4096}) {
    const ViewResult f = r.render(PanelEstimator::Footprint, spp, 5);
    const double e = rmse(f.image, a);
    // Excess over the reference's noise: the footprint image's own error (noise + bias).
    const double own = std::sqrt(std::max(0.0, e * e - noiseA * noiseA));
    std::printf("[ measured ] footprint %4d spp: RMSE/mean vs point 4096 %.2f%%, own error ~%.2f%%, mean ratio %.4f, "
                "probe failures %llu of %llu probes\n", spp, 100.0 * e / m, 100.0 * own / m, meanAll(f.image) / m,
                (unsigned long long)f.stats.footprint.probeFailures, (unsigned long long)f.stats.footprint.probeRays);
    EXPECT_LT(own, prev);
    prev = own;
    EXPECT_NEAR(meanAll(f.image) / m, 1.0, 0.01) << spp << " spp";
    if (spp == 4096) {
      EXPECT_LT(e, 1.25 * pointPair) << "footprint 4096 spp deviates from point 4096 spp more than two point images do";
      // Region means (6 x 4 blocks of 4 x 4 pixels, each channel) agree with both point images.
      for (int by = 0; by < 4; ++by)
        for (int bx = 0; bx < 6; ++bx)
          for (int c = 0; c < 3; ++c) {
            const double fa = blockMean(f.image, 4 * bx, 4 * by, 4, 4, c);
            const double pa = 0.5 * (blockMean(a, 4 * bx, 4 * by, 4, 4, c) + blockMean(b, 4 * bx, 4 * by, 4, 4, c));
            EXPECT_NEAR(fa / pa, 1.0, 0.02) << "block " << bx << "," << by << " channel " << c;
          }
      EXPECT_NEAR(meanAll(f.image) / m, 1.0, 0.003);
    }
  }
}

TEST(ViewFootprint, BadScaleIsAnInputError) {
  RealSetup r;
  EXPECT_THROW(r.render(PanelEstimator::Footprint, 1, 1, -1.0), InputError);
  EXPECT_THROW(r.render(PanelEstimator::Footprint, 1, 1, std::nan("")), InputError);
}
