// The Quadrature panel estimator (estimators/quadrature_estimator.h) against the point-sampling
// reference (square and hex lattices, real and ideal MLA, thin and real lens), its energy
// (uniform white: the transmitted path, and the dropped Fresnel ghosts' share) and its
// convergence in spp. Tolerances are stated at aperture grid 12.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <memory>
#include <stdexcept>

#include "mla_optics/ideal_mla.h"
#include "mla_optics/real_mla.h"
#include "display_view/estimators/quadrature_tables.h"
#include "display_view/view_renderer.h"
#include "real_setup.h"
#include "view_test_util.h"

using namespace inim;
using namespace view_test;

namespace {

// The quadrature estimator against the point estimator at 4096 spp (two seeds): overall mean
// and 4 x 4-pixel block means (each block straddles lenslet borders: a pixel here covers a
// quarter of a lenslet).
void expectAgreesWithPoint(const RealSetup& r, const char* what, const MlaModel* mla = nullptr) {
  const Image a = r.render(PanelEstimator::PointSample, 4096, 1, 1.0, nullptr, mla).image;
  const Image b = r.render(PanelEstimator::PointSample, 4096, 2, 1.0, nullptr, mla).image;
  const double m = meanAll(a);
  const double pointNoise = rmse(a, b) / std::sqrt(2.0);
  const ViewResult q16 = r.render(PanelEstimator::Quadrature, 16, 1, 1.0, nullptr, mla);
  for (int spp : {1, 4, 16}) {
    const ViewResult q = spp == 16 ? q16 : r.render(PanelEstimator::Quadrature, spp, 1, 1.0, nullptr, mla);
    const double e = rmse(q.image, a), conv = rmse(q.image, q16.image);
    std::printf("[ measured ] %s quadrature %2d spp: RMSE/mean vs point 4096 spp %.2f%% (point's own noise %.2f%%), "
                "vs quadrature 16 spp %.2f%%, mean ratio %.4f; %llu pieces, %llu strata split, %llu lost, "
                "%llu fallbacks\n",
                what, spp, 100.0 * e / m, 100.0 * pointNoise / m, 100.0 * conv / m, meanAll(q.image) / m,
                (unsigned long long)q.stats.quadrature.pieces, (unsigned long long)q.stats.quadrature.splitStrata,
                (unsigned long long)q.stats.quadrature.lostPieces, (unsigned long long)q.stats.quadrature.fallbacks);
    EXPECT_NEAR(meanAll(q.image) / m, 1.0, 0.01) << what << " " << spp << " spp";
    EXPECT_GT(q.stats.quadrature.splitStrata, 0u) << what;
    // Deterministic: 1 spp is within 3% (RMSE of the mean) of 16 spp although a third of the
    // pixels straddle a lenslet border.
    EXPECT_LT(conv, 0.03 * m) << what << " " << spp << " spp";
    // Pixel by pixel as close to the point reference as a stated tolerance on top of the
    // reference's own noise: 2% of the mean (the linearised MLA, the block-wise aperture table,
    // the border plane), 3% at 1 spp (one box per pixel piece although the lenslet's map is not
    // affine over a quarter of a lenslet).
    const double tol = (spp == 1 ? 0.03 : 0.02) * m;
    EXPECT_LT(e, std::sqrt(pointNoise * pointNoise + tol * tol)) << what << " " << spp << " spp";
  }
  const Image& f = q16.image;
  for (int by = 0; by < a.height / 4; ++by)
    for (int bx = 0; bx < a.width / 4; ++bx)
      for (int c = 0; c < 3; ++c) {
        const double pa = 0.5 * (blockMean(a, 4 * bx, 4 * by, 4, 4, c) + blockMean(b, 4 * bx, 4 * by, 4, 4, c));
        if (!(pa > 0.05 * m)) continue;
        EXPECT_NEAR(blockMean(f, 4 * bx, 4 * by, 4, 4, c) / pa, 1.0, 0.02)
            << what << " block " << bx << "," << by << " channel " << c;
      }
}

}  // namespace

TEST(ViewQuadrature, AgreesWithThePointEstimatorOnASquareLattice) { expectAgreesWithPoint(RealSetup(), "square"); }

TEST(ViewQuadrature, AgreesWithThePointEstimatorOnAHexLattice) {
  RealSetup r(false, 24, 16, true);
  expectAgreesWithPoint(r, "hex, real MLA");
  IdealLensletMla ideal(r.layout, r.P, 3.3, r.g);
  expectAgreesWithPoint(r, "hex, ideal MLA", &ideal);
}

TEST(ViewQuadrature, UniformWhiteMatchesTheTransmittedEnergy) {
  // Uniform white: the estimator integrates the path that Fresnel transmits (no ghosts), so its
  // mean is the point estimator's with weighted Fresnel; against the point estimator with
  // stochastic Fresnel (every path) it misses only the ghosts' small share (< 1%).
  RealMlaOptions o;
  o.fresnel = FresnelMode::Weighted;
  RealSetup ww(true);
  ww.mla = RealMla::fromDisplay(ww.display, ww.layout, ww.g, o);
  const Image ptw = ww.render(PanelEstimator::PointSample, 1024).image;
  const Image pt = RealSetup(true).render(PanelEstimator::PointSample, 1024).image;
  const ViewResult q = ww.render(PanelEstimator::Quadrature, 1);
  std::printf("[ measured ] uniform white: quadrature (1 spp) / point (1024 spp, weighted Fresnel) = %.4f, "
              "/ point (stochastic Fresnel) = %.4f; ghosts (stochastic / weighted - 1) = %.3f%%\n",
              meanAll(q.image) / meanAll(ptw), meanAll(q.image) / meanAll(pt), 100.0 * (meanAll(pt) / meanAll(ptw) - 1.0));
  EXPECT_NEAR(meanAll(q.image) / meanAll(ptw), 1.0, 0.005);
  EXPECT_NEAR(meanAll(q.image) / meanAll(pt), 1.0, 0.01);
  for (int c = 0; c < 3; ++c)
    EXPECT_NEAR(blockMean(q.image, 0, 0, 24, 16, c) / blockMean(ptw, 0, 0, 24, 16, c), 1.0, 0.01);
}

TEST(ViewQuadrature, RealLensAgreesWithThePointEstimator) {
  // The default real lens (dispersive glass: one camera ray per primary) at 200 mm, 640 px.
  RealSetup r;
  auto cam = realLensCameraAt200mm();
  const Image a = r.render(PanelEstimator::PointSample, 1024, 1, 1.0, cam.get()).image;
  const ViewResult q = r.render(PanelEstimator::Quadrature, 1, 1, 1.0, cam.get());
  double sa = 0.0, sq = 0.0;
  for (size_t i = 0; i < a.data.size(); ++i) sa += a.data[i], sq += q.image.data[i];
  std::printf("[ measured ] real lens: quadrature (1 spp) / point (1024 spp) = %.4f; %llu fallbacks, %llu lost\n",
              sq / sa, (unsigned long long)q.stats.quadrature.fallbacks, (unsigned long long)q.stats.quadrature.lostPieces);
  EXPECT_NEAR(sq / sa, 1.0, 0.01);
}

TEST(ViewQuadrature, SharedTablesGiveTheSameImagesForOtherDisplays) {
  // Renders through one camera that differ in the display (the real and the ideal MLA, a white
  // and a patterned EIA) sharing their aperture tables: each image bit for bit its render with
  // tables of its own; the second render through the same MLA front plane traces no table ray.
  const RealSetup patterned, white(true);
  const IdealLensletMla ideal(patterned.layout, RealSetup::P, 3.3, RealSetup::g);
  ViewSettings s;
  s.spp = 2;
  s.progress = false;
  s.apertureGrid = 12;
  ViewSettings shared = s;
  shared.tableCache = std::make_shared<QuadratureTableCache>(*patterned.camera);
  struct Case {
    const RealSetup& setup;
    const MlaModel& mla;
  };
  uint64_t firstRays = 0;
  int index = 0;
  for (const Case& c : {Case{patterned, *patterned.mla}, Case{white, *white.mla}, Case{patterned, ideal}}) {
    const ViewResult own = renderView(*patterned.camera, defaultCamera().sensor, c.mla, *c.setup.panel,
                                      c.setup.layout.activeArea(), s);
    const ViewResult withShared = renderView(*patterned.camera, defaultCamera().sensor, c.mla, *c.setup.panel,
                                             c.setup.layout.activeArea(), shared);
    ASSERT_EQ(own.image.data.size(), withShared.image.data.size());
    EXPECT_EQ(std::memcmp(own.image.data.data(), withShared.image.data.data(), own.image.data.size() * sizeof(float)), 0)
        << "case " << index;
    if (index == 0) firstRays = withShared.stats.quadrature.probeRays;
    if (index == 1) {
      EXPECT_LT(withShared.stats.quadrature.probeRays, own.stats.quadrature.probeRays);
    }
    ++index;
  }
  EXPECT_GT(firstRays, 0u);
  // Another camera cannot use the cache.
  auto other = std::make_unique<ThinLensCameraModel>(*patterned.camera);
  EXPECT_THROW(renderView(*other, defaultCamera().sensor, *patterned.mla, *patterned.panel,
                          patterned.layout.activeArea(), shared),
               std::logic_error);
}

TEST(ViewQuadrature, CompanionPanelsAreEachTheirOwnRender) {
  // One pass through the real MLA and cover glass for panels that differ from the first in the
  // subpixel layout (each pixel a uniform emitter) or the drive (white) only: carried along
  // (canCarry); one without the cover glass is not, and renders alone. Each image is bit for
  // bit renderView's of its own panel, through a thin lens and through the real, dispersive one.
  const RealSetup r, white(true);
  Panel uniform = r.display.panel;
  uniform.subpixels.type = "custom";
  uniform.subpixels.tileW = uniform.subpixels.tileH = 1;
  uniform.subpixels.subpixels.clear();
  for (int c = 0; c < kNumPrimaries; ++c)
    uniform.subpixels.subpixels.push_back({c, {{0.0, 0.0}, {1.0, 0.0}, {1.0, 1.0}, {0.0, 1.0}}});
  const PanelEmitter uniformPanel(uniform, r.layout, patternEia(r.layout), "eia.exr", RealSetup::g);
  EmitterSettings noGlass;
  noGlass.coverGlass = false;
  const PanelEmitter bare(r.display.panel, r.layout, patternEia(r.layout), "eia.exr", RealSetup::g, noGlass);
  const std::vector<const PanelEmitter*> panels{r.panel.get(), &uniformPanel, white.panel.get(), &bare};
  ViewSettings s;
  s.spp = 2;
  s.progress = false;
  s.apertureGrid = 12;
  const CameraSensor& sensor = defaultCamera().sensor;
  const AreaMm area = r.layout.activeArea();
  const auto lens = realLensCameraAt200mm();
  const std::vector<const CameraModel*> cameras{r.camera.get(), lens.get()};
  for (const CameraModel* camera : cameras) {
    const EstimatorContext first(*camera, sensor, *r.mla, *r.panel, area, s);
    for (size_t k = 1; k < panels.size(); ++k)
      EXPECT_EQ(QuadratureEstimator::canCarry(first, EstimatorContext(*camera, sensor, *r.mla, *panels[k], area, s)),
                k < 3)
          << "panel " << k;
    const std::vector<ViewResult> together = renderViews(*camera, sensor, *r.mla, panels, area, s);
    ASSERT_EQ(together.size(), panels.size());
    for (size_t k = 0; k < panels.size(); ++k) {
      const ViewResult own = renderView(*camera, sensor, *r.mla, *panels[k], area, s);
      ASSERT_EQ(own.image.data.size(), together[k].image.data.size());
      EXPECT_GT(meanAll(own.image), 0.0) << "panel " << k;
      EXPECT_EQ(std::memcmp(own.image.data.data(), together[k].image.data.data(), own.image.data.size() * sizeof(float)),
                0)
          << "panel " << k << (camera == lens.get() ? ", real lens" : ", thin lens");
    }
    // The layouts differ, so the views do.
    EXPECT_GT(rmse(together[0].image, together[1].image), 0.0);
  }
}
