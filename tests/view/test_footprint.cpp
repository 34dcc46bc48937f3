// The Footprint panel estimator (view_renderer.h): the emitter's exact box average
// (PanelEmitter::boxAveragePx, rectangles and clipped polygons), and the renderer's agreement
// with the point-sampling reference estimator: the same image at high spp (region means and
// RMSE), energy (uniform white), a zero box reproducing the point estimator bit for bit, and
// determinism across thread counts.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>

#include "core/error.h"
#include "core/parallel.h"
#include "core/rng.h"
#include "mla/real_mla.h"
#include "view/ideal_mla.h"
#include "view/panel_emitter.h"
#include "view/view_renderer.h"
#include "real_setup.h"
#include "view_test_util.h"

using namespace inim;
using namespace view_test;

namespace {

// Dense midpoint-grid average of lookupPx over a box, per channel.
std::array<double, 3> gridAverage(const PanelEmitter& e, double u0, double v0, double u1, double v1, int n) {
  std::array<double, 3> s{0, 0, 0};
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const PanelEmission em = e.lookupPx(u0 + (i + 0.5) / n * (u1 - u0), v0 + (j + 0.5) / n * (v1 - v0));
      if (em.channel >= 0) s[size_t(em.channel)] += em.weight;
    }
  for (auto& v : s) v /= double(n) * n;
  return s;
}

void checkBoxAverages(const Display& d, const char* name) {
  const EiLayout L = computeLayout(d);
  PanelEmitter e(d.panel, L, patternEia(L), "pattern.exr", 1.2);
  Rng rng(7, 3);
  double worst = 0.0;
  for (int i = 0; i < 60; ++i) {
    // Boxes from 0.05 to 3 px, anywhere on the panel and across its edges.
    const double w = 0.05 + 2.95 * rng.uniformDouble(), h = 0.05 + 2.95 * rng.uniformDouble();
    const double u0 = -1.0 + (L.panelW + 1.0) * rng.uniformDouble(), v0 = -1.0 + (L.panelH + 1.0) * rng.uniformDouble();
    const auto a = e.boxAveragePx(u0, v0, u0 + w, v0 + h);
    const auto g = gridAverage(e, u0, v0, u0 + w, v0 + h, 600);
    for (int c = 0; c < 3; ++c) {
      worst = std::max(worst, std::abs(a[size_t(c)] - g[size_t(c)]));
      EXPECT_NEAR(a[size_t(c)], g[size_t(c)], 4e-3) << name << " box " << i << " channel " << c;
    }
  }
  std::printf("[ measured ] %s: largest |box average - 600 x 600 grid average| = %.2g\n", name, worst);
}

}  // namespace

TEST(PanelEmitterBox, StripeBoxAverageIsTheAreaIntegral) {
  checkBoxAverages(smallDisplay(4, 3, 6, 0.05, 0.3, 1.0, 1.2), "rgb stripe");
}

TEST(PanelEmitterBox, DiamondBoxAverageIsTheAreaIntegral) {
  Display d = smallDisplay(4, 3, 6, 0.05, 0.3, 1.0, 1.2);
  d.panel.subpixels = diamondLayout(0.8);
  checkBoxAverages(d, "diamond (clipped polygons)");
}

TEST(PanelEmitterBox, WholeTilesOfWhiteGiveTheFillFactorAndZeroBoxesThePoint) {
  for (bool diamond : {false, true}) {
    Display d = smallDisplay(4, 3, 6, 0.05, 0.3, 1.0, 1.2);
    if (diamond) d.panel.subpixels = diamondLayout(0.8);
    const EiLayout L = computeLayout(d);
    PanelEmitter e(d.panel, L, uniformEia(L, 1, 1, 1), "white.exr", 1.2);
    const int t = diamond ? 2 : 1;
    const auto a = e.boxAveragePx(2.0 * t, 4.0 * t, 5.0 * t, 6.0 * t);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(a[size_t(c)], 1.0 / e.areaFactor(c), 1e-6) << c;
    // Half of the box off the panel's left edge: half the light.
    const auto h = e.boxAveragePx(-3.0 * t, 4.0 * t, 3.0 * t, 6.0 * t);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(h[size_t(c)], 0.5 / e.areaFactor(c), 1e-6) << c;
    EXPECT_EQ(e.boxAveragePx(-5.0, -5.0, -1.0, -1.0)[0], 0.0f);
  }
  // A box of zero area is the point lookup, and emit() is lookupPx at emissionPointPx.
  Display d = smallDisplay(4, 3, 6, 0.05, 0.3, 1.0, 1.2);
  d.panel.coverGlass = CoverGlass{0.3, "N-BK7"};
  const EiLayout L = computeLayout(d);
  PanelEmitter e(d.panel, L, patternEia(L), "pattern.exr", 1.2);
  Rng rng(11, 5);
  for (int i = 0; i < 500; ++i) {
    const double u = L.panelW * rng.uniformDouble(), v = L.panelH * rng.uniformDouble();
    const PanelEmission p = e.lookupPx(u, v);
    const auto b = e.boxAveragePx(u, v, u, v);
    for (int c = 0; c < 3; ++c) EXPECT_EQ(b[size_t(c)], p.channel == c ? p.weight : 0.0f);
    const Point3 pt(float((u - 0.5 * L.eiaW - L.panelCol0) * L.pixelMm),
                    float((0.5 * L.eiaH + L.panelRow0 - v) * L.pixelMm), -1.2f);
    const Vec3 dir = glm::normalize(Vec3(float(rng.uniform() - 0.5), float(rng.uniform() - 0.5), -1.0f));
    Vec2d uv;
    float factor = 0.0f;
    ASSERT_TRUE(e.emissionPointPx(pt, dir, 550.0f, uv, factor));
    const PanelEmission em = e.emit(pt, dir, 550.0f), lk = e.lookupPx(uv.x, uv.y);
    EXPECT_EQ(em.channel, lk.channel);
    if (lk.channel >= 0 && lk.weight > 0.0f) {
      EXPECT_EQ(em.weight, lk.weight * factor);
    }
  }
}

TEST(ViewFootprint, ZeroBoxIsBitIdenticalToThePointEstimator) {
  RealSetup r;
  const Image point = r.render(PanelEstimator::PointSample, 4).image;
  const ViewResult zero = r.render(PanelEstimator::Footprint, 4, 1, 0.0);
  EXPECT_GT(zero.stats.probeRays, 0u);
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
  ViewResult r = renderView(*cam, defaultCamera().sensor, mla, panel, lensletArrayArea(L, P), s);
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
                (unsigned long long)f.stats.probeFailures, (unsigned long long)f.stats.probeRays);
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

TEST(ViewFootprint, BitIdenticalOnOneAndTwoThreads) {
  RealSetup r;
  for (PanelEstimator e : {PanelEstimator::Footprint, PanelEstimator::PointSample}) {
    Image one, two;
    {
      ThreadLimit t(1);
      one = r.render(e, 3, 9).image;
    }
    {
      ThreadLimit t(2);
      two = r.render(e, 3, 9).image;
    }
    ASSERT_EQ(one.data.size(), two.data.size());
    EXPECT_EQ(std::memcmp(one.data.data(), two.data.data(), one.data.size() * sizeof(float)), 0)
        << panelEstimatorName(e);
    for (float v : one.data) ASSERT_TRUE(std::isfinite(v));
  }
}

TEST(ViewFootprint, BadScaleIsAnInputError) {
  RealSetup r;
  EXPECT_THROW(r.render(PanelEstimator::Footprint, 1, 1, -1.0), InputError);
  EXPECT_THROW(r.render(PanelEstimator::Footprint, 1, 1, std::nan("")), InputError);
}

// Diagnostics (run with --gtest_also_run_disabled_tests): the noise of one image (from two
// seeds) at the default camera's scale (a camera pixel covers ~64 um of the MLA), split by
// source: the panel lottery, the MLA's stochastic Fresnel choices, the lens aperture.
TEST(ViewFootprint, DISABLED_NoiseBudget) {
  for (int variant = 0; variant < 4; ++variant) {
    RealSetup r(false, 96, 64);
    if (variant >= 2) {
      RealMlaOptions o;
      o.fresnel = FresnelMode::Off;
      r.mla = RealMla::fromDisplay(r.display, r.layout, r.g, o);
    }
    if (variant == 3) r.camera = std::make_unique<ThinLensCameraModel>(r.camera->sensor(), r.camera->pose(), 12.0, 400.0, r.D);
    if (variant == 1) continue;
    for (PanelEstimator e : {PanelEstimator::PointSample, PanelEstimator::Footprint}) {
      if (variant > 1 && e == PanelEstimator::PointSample) continue;
      for (int spp : {1, 4, 16}) {
        const ViewResult a = r.render(e, spp, 1), b = r.render(e, spp, 2);
        std::printf("[ measured ] %s, %s: %2d spp noise RMSE/mean %.2f%% (%.2f s)\n",
                    variant == 0 ? "stochastic Fresnel" : variant == 1 ? "stochastic Fresnel" :
                    variant == 2 ? "Fresnel off" : "Fresnel off, f/400",
                    panelEstimatorName(e), spp, 100.0 * rmse(a.image, b.image) / std::sqrt(2.0) / meanAll(a.image),
                    a.stats.seconds);
      }
    }
  }
}
