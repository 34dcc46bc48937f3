// The real MLA on a hex-lattice display: its lenslets sit exactly where the EI layout puts
// them, and its real-lens rays agree with the pinhole rays paraxially.
#include <gtest/gtest.h>

#include <cmath>

#include "display/hex_test_util.h"
#include "mla_optics/real_lens_rays.h"
#include "mla_test_util.h"
#include "rays/pinhole_rays.h"

using namespace inim;
using namespace mla_test;

namespace {

// The prototype's panel pixel, lens pitch, focal length and EI size on a small hex display.
Display hexPaperLike(int K, int R, EiLayoutKind kind) {
  Display d = hex_test::hexDisplay(K, R, 25, 0.0395, 3.3, kind, 1.0);
  d.mla.substrateThicknessMm = 1.5;
  d.mla.radiusMm = 1.62;
  d.mla.focalLengthMm.reset();
  return d;
}

}  // namespace

// A ray straight down each layout lens centre stays in that lenslet and reaches the panel
// under its centre; RealMla's lensletCentre and cellAt agree with the layout for every (k, l).
TEST(HexRealMla, LensletCentresCoincideWithLayout) {
  for (auto [K, R] : {std::pair{6, 5}, std::pair{5, 4}, std::pair{1, 1}}) {
    for (EiLayoutKind kind : {EiLayoutKind::Parallel, EiLayoutKind::LensGrid}) {
      Display d = hexPaperLike(K, R, kind);
      EiLayout L = computeLayout(d);
      auto mla = RealMla::fromDisplay(d, L, d.reconstructionGapMm, RealMlaOptions{FresnelMode::Off});
      ASSERT_EQ(mla->geometry().lattice, Mla::Lattice::Hex);
      for (int k = 0; k < K; ++k)
        for (int l = 0; l < R; ++l) {
          const double x = L.lensXAt(k, l), y = L.lensYAt(k, l);
          const Point3d c = mla->lensletCentre(k, l);
          EXPECT_NEAR(c.x, x, 1e-12);
          EXPECT_NEAR(c.y, y, 1e-12);
          int ck, cl;
          mla->cellAt(x, y, ck, cl);
          EXPECT_EQ(ck, k);
          EXPECT_EQ(cl, l);
          // Trace straight down the axis from in front of the MLA.
          Rng rng(1, 0);
          PanelArrival a;
          Ray ray{Point3(float(x), float(y), mla->frontZ() + 1.0f), Vec3(0.0f, 0.0f, -1.0f)};
          ASSERT_TRUE(mla->traceToPanel(ray, 550.0f, rng, a));
          EXPECT_EQ(a.lensletK, k);
          EXPECT_EQ(a.lensletL, l);
          EXPECT_NEAR(a.p.x, x, 1e-5);
          EXPECT_NEAR(a.p.y, y, 1e-5);
          // Off-centre by 0.45 P toward each neighbour: still this lenslet (cell inradius P/2).
          for (int dir = 0; dir < 6; ++dir) {
            const double ang = dir * M_PI / 3.0;
            Ray r2{Point3(float(x + 0.45 * std::cos(ang)), float(y + 0.45 * std::sin(ang)), mla->frontZ() + 1.0f),
                   Vec3(0.0f, 0.0f, -1.0f)};
            int kk, ll;
            mla->cellAt(r2.o.x, r2.o.y, kk, ll);
            EXPECT_EQ(kk, k);
            EXPECT_EQ(ll, l);
          }
        }
      // The lenslet array's bounding box holds every cell and nothing beyond.
      AreaMm A = L.activeArea();
      int kk, ll;
      mla->cellAt(A.x0 + 1e-6, L.lensYAt(0, 0), kk, ll);
      EXPECT_EQ(kk, 0);
      mla->cellAt(A.x0 - 1e-3, L.lensYAt(0, 0), kk, ll);
      EXPECT_EQ(kk, -1);
    }
  }
}

// Real-lens rays on a hex lens-grid display agree with the pinhole rays through the same lens
// centres: paraxially (pixels near the lens axis) to a small fraction of a degree, everywhere
// within the square lattice's bounds (tests/mla_optics/test_real_lens_rays.cpp).
TEST(HexRealMla, RealLensRaysAgreeWithPinholeParaxially) {
  Display d = hexPaperLike(5, 4, EiLayoutKind::LensGrid);
  EiLayout L = computeLayout(d);
  auto mla = RealMla::fromDisplay(d, L, L.gapMm);
  RaySet pin = generatePinholeRays(L);
  for (auto model : {RealLensRayModel::Chief, RealLensRayModel::Centroid}) {
    RealLensRayOptions o;
    o.model = model;
    RealLensRayStats st;
    RaySet rays = generateRealLensRays(L, *mla, o, &st);
    ASSERT_EQ(rays.size(), pin.size());
    EXPECT_EQ(st.fallback, 0u);
    double worst = 0.0, worstParaxial = 0.0, worstAxis = 0.0;
    for (int64_t r = 0; r < L.numRays(); ++r) {
      const RayAddress a = rayAddress(L, r);
      const PixelCoord p = eiaPixel(L, a);
      const double off = std::hypot(L.pixelCentreX(p.col) - L.lensXAt(a.k, a.l), L.pixelCentreY(p.row) - L.lensYAt(a.k, a.l));
      const double ang = angle(unit(Vec3d(rays.ray(size_t(r)).d)), unit(Vec3d(pin.ray(size_t(r)).d)));
      worst = std::max(worst, ang);
      if (off < 0.1) worstParaxial = std::max(worstParaxial, ang);
      if (off < 0.03) worstAxis = std::max(worstAxis, ang);
      EXPECT_NEAR(rays.ox[size_t(r)], L.lensXAt(a.k, a.l), 0.15);
      EXPECT_NEAR(rays.oy[size_t(r)], L.lensYAt(a.k, a.l), 0.15);
    }
    std::printf("  %s: %lld hex rays, largest angle to the pinhole ray %.4f deg, within 0.1 mm of the axis %.5f deg, "
                "within 0.03 mm %.5f deg\n",
                realLensRayModelName(model), (long long)L.numRays(), worst * 180 / M_PI, worstParaxial * 180 / M_PI,
                worstAxis * 180 / M_PI);
    EXPECT_LT(worst * 180 / M_PI, model == RealLensRayModel::Chief ? 0.1 : 0.3);
    // The chief ray is exact paraxially; the centroid of the full-aperture (f/3.3) bundle
    // carries the lenslet's aberrations, which vanish toward the axis (linearly in the offset).
    EXPECT_LT(worstParaxial * 180 / M_PI, model == RealLensRayModel::Chief ? 0.001 : 0.02);
    EXPECT_LT(worstAxis * 180 / M_PI, model == RealLensRayModel::Chief ? 0.001 : 0.006);
    EXPECT_LT(worstAxis, 0.5 * worstParaxial + 1e-9);
  }
}

// The view simulation's factory on a hex display builds a hex RealMla over the same lenslets.
TEST(HexRealMla, MakeRealMlaUsesLayoutLattice) {
  Display d = hexPaperLike(4, 3, EiLayoutKind::Parallel);
  EiLayout L = computeLayout(d);
  RealMlaGeometry g = RealMla::geometryFor(d, L, 4.0);
  EXPECT_EQ(g.lattice, Mla::Lattice::Hex);
  EXPECT_EQ(g.cols, 4);
  EXPECT_EQ(g.rows, 3);
  EXPECT_DOUBLE_EQ(g.originXMm, L.lensXAt(0, 0));
  EXPECT_DOUBLE_EQ(g.originYMm, L.lensYAt(0, 0));
}
