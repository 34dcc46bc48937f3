// The Quadrature panel estimator (view_renderer.h) and its pieces: convex polygon clipping and
// moments against closed forms, the single-channel box average against the all-channel one,
// the MLA lattice queries, and the renderer against the point-sampling reference (square and
// hex lattices, thin and real lens, uniform white energy), its convergence in spp, and
// determinism across thread counts.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>

#include "core/parallel.h"
#include "core/rng.h"
#include "mla/real_mla.h"
#include "view/convex_polygon.h"
#include "view/display_pose.h"
#include "view/ideal_mla.h"
#include "view/panel_emitter.h"
#include "view/view_camera.h"
#include "view/view_renderer.h"
#include "real_setup.h"
#include "view_test_util.h"

using namespace inim;
using namespace view_test;

TEST(ConvexPolygon, MomentsOfASquareAndATriangle) {
  const PolygonMoments sq = ConvexPolygon::rect(2.0, 3.0, 3.0, 4.0).moments();
  EXPECT_NEAR(sq.area, 1.0, 1e-12);
  EXPECT_NEAR(sq.centroid.x, 2.5, 1e-12);
  EXPECT_NEAR(sq.centroid.y, 3.5, 1e-12);
  EXPECT_NEAR(sq.cxx, 1.0 / 12.0, 1e-12);
  EXPECT_NEAR(sq.cyy, 1.0 / 12.0, 1e-12);
  EXPECT_NEAR(sq.cxy, 0.0, 1e-12);
  // The right triangle (0,0) (1,0) (0,1): area 1/2, centroid (1/3, 1/3), covariance
  // [1/18, -1/36; -1/36, 1/18]; clockwise order gives the same.
  for (bool cw : {false, true}) {
    ConvexPolygon t;
    t.n = 3;
    t.v[0] = Vec2d(0, 0);
    t.v[1] = cw ? Vec2d(0, 1) : Vec2d(1, 0);
    t.v[2] = cw ? Vec2d(1, 0) : Vec2d(0, 1);
    const PolygonMoments m = t.moments();
    EXPECT_NEAR(m.area, 0.5, 1e-12);
    EXPECT_NEAR(m.centroid.x, 1.0 / 3.0, 1e-12);
    EXPECT_NEAR(m.centroid.y, 1.0 / 3.0, 1e-12);
    EXPECT_NEAR(m.cxx, 1.0 / 18.0, 1e-12);
    EXPECT_NEAR(m.cyy, 1.0 / 18.0, 1e-12);
    EXPECT_NEAR(m.cxy, -1.0 / 36.0, 1e-12);
  }
}

TEST(ConvexPolygon, ClippingAgreesWithPointCounting) {
  // A unit square cut by random half-planes: the clipped area against the share of a 400 x 400
  // grid of points that satisfy every cut.
  Rng rng(7, 1);
  for (int trial = 0; trial < 50; ++trial) {
    ConvexPolygon p = ConvexPolygon::rect(0, 0, 1, 1);
    Vec2d a[3];
    double c[3];
    for (int k = 0; k < 3; ++k) {
      const double ang = 6.283185307 * rng.uniformDouble();
      a[k] = Vec2d(std::cos(ang), std::sin(ang));
      c[k] = a[k].x * 0.5 + a[k].y * 0.5 + (rng.uniformDouble() - 0.3) * 0.6;
      p = p.clipped(a[k], c[k]);
    }
    int in = 0;
    const int n = 400;
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const Vec2d q((i + 0.5) / n, (j + 0.5) / n);
        bool ok = true;
        for (int k = 0; k < 3; ++k) ok = ok && a[k].x * q.x + a[k].y * q.y <= c[k];
        in += ok;
      }
    EXPECT_NEAR(p.empty() ? 0.0 : p.moments().area, double(in) / (n * n), 4.0 / n) << "trial " << trial;
  }
}

TEST(ConvexPolygon, PulledBackHalfPlaneHoldsExactlyWhereTheMappedPointSatisfiesIt) {
  Rng rng(3, 4);
  const double J[2][2] = {{0.07, -0.004}, {0.003, -0.065}};  // a camera pixel -> MLA mm map
  const Vec2d q0(1.3, -0.7), p0(100.5, 200.5), nrm(0.5, 0.8660254);
  const double c = 0.2;
  Vec2d a;
  double cc;
  pullBackHalfPlane(q0, J, p0, nrm, c, a, cc);
  for (int i = 0; i < 2000; ++i) {
    const Vec2d p(p0.x + 40.0 * (rng.uniformDouble() - 0.5), p0.y + 40.0 * (rng.uniformDouble() - 0.5));
    const Vec2d d = p - p0;
    const Vec2d q(q0.x + J[0][0] * d.x + J[0][1] * d.y, q0.y + J[1][0] * d.x + J[1][1] * d.y);
    const double sq = nrm.x * q.x + nrm.y * q.y - c, sp = a.x * p.x + a.y * p.y - cc;
    if (std::abs(sq) < 1e-9) continue;
    EXPECT_EQ(sq <= 0.0, sp <= 0.0) << i;
  }
}

TEST(PanelEmitter, ChannelBoxAverageMatchesTheAllChannelBoxAverage) {
  for (bool diamond : {false, true}) {
    Display d = smallDisplay(4, 3, 6, 0.05, 0.3, 1.0, 1.2);
    if (diamond) d.panel.subpixels = diamondLayout(0.8);
    const EiLayout L = computeLayout(d);
    PanelEmitter e(d.panel, L, patternEia(L), "pattern.exr", 1.2);
    Rng rng(9, 2);
    double worst = 0.0;
    for (int i = 0; i < 5000; ++i) {
      const double u = -1.0 + (L.panelW + 2.0) * rng.uniformDouble(), v = -1.0 + (L.panelH + 2.0) * rng.uniformDouble();
      const double hu = 2.0 * rng.uniformDouble() * rng.uniformDouble(), hv = 2.0 * rng.uniformDouble() * rng.uniformDouble();
      const auto all = e.boxAveragePx(u - hu, v - hv, u + hu, v + hv);
      for (int c = 0; c < 3; ++c)
        worst = std::max(worst, double(std::abs(e.channelBoxAveragePx(c, u - hu, v - hv, u + hu, v + hv) - all[size_t(c)])));
    }
    EXPECT_LT(worst, 1e-6) << (diamond ? "diamond" : "stripe");
  }
}

TEST(MlaLattice, LensletCellHoldsThePointAndIsTheNearestCentre) {
  for (bool hex : {false, true}) {
    RealSetup r(false, 24, 16, hex);
    const auto& real = dynamic_cast<const RealMla&>(*r.mla);
    IdealLensletMla ideal(r.layout, r.P, 3.3, r.g);
    const MlaModel* models[2] = {r.mla.get(), &ideal};
    Rng rng(11, 5);
    for (const MlaModel* m : models) {
      int checked = 0;
      for (int i = 0; i < 4000; ++i) {
        const double x = 6.0 * (rng.uniformDouble() - 0.5), y = 4.0 * (rng.uniformDouble() - 0.5);
        LensletCell c;
        if (!m->lensletCell(x, y, c)) continue;
        ++checked;
        for (int e = 0; e < c.n; ++e)
          EXPECT_LE(c.nx[size_t(e)] * (x - c.cx) + c.ny[size_t(e)] * (y - c.cy), c.h[size_t(e)] + 1e-9);
        // No other lattice centre is nearer (neighbours one pitch away in the 12 directions).
        const double d0 = std::hypot(x - c.cx, y - c.cy);
        for (int k = 0; k < 12; ++k) {
          const double ang = k * M_PI / 6.0, rr = (k & 1) ? c.pitch * std::sqrt(3.0) : c.pitch;
          LensletCell o;
          if (!m->lensletCell(c.cx + rr * std::cos(ang), c.cy + rr * std::sin(ang), o)) continue;
          EXPECT_GE(std::hypot(x - o.cx, y - o.cy), d0 - 1e-9);
        }
      }
      EXPECT_GT(checked, 2000) << (hex ? "hex" : "square");
    }
    // Caps toward the viewer: the lenslets meet at the edge middles, sag(P/2) below the vertex.
    EXPECT_NEAR(real.cellDepth(), real.capSag(0.5 * r.P) + (real.frontZ() - real.vertexZ()), 1e-3);
    EXPECT_EQ(ideal.cellDepth(), 0.0);
  }
}

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
                (unsigned long long)q.stats.quadratureParts, (unsigned long long)q.stats.splitStrata,
                (unsigned long long)q.stats.lostParts, (unsigned long long)q.stats.apertureFallbacks);
    EXPECT_NEAR(meanAll(q.image) / m, 1.0, 0.01) << what << " " << spp << " spp";
    EXPECT_GT(q.stats.splitStrata, 0u) << what;
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
  // mean is the point estimator's with weighted Fresnel.
  RealMlaOptions o;
  o.fresnel = FresnelMode::Weighted;
  RealSetup ww(true);
  ww.mla = RealMla::fromDisplay(ww.display, ww.layout, ww.g, o);
  const Image ptw = ww.render(PanelEstimator::PointSample, 1024).image;
  const ViewResult q = ww.render(PanelEstimator::Quadrature, 1);
  std::printf("[ measured ] uniform white: quadrature (1 spp) / point (1024 spp, weighted Fresnel) = %.4f\n",
              meanAll(q.image) / meanAll(ptw));
  EXPECT_NEAR(meanAll(q.image) / meanAll(ptw), 1.0, 0.005);
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
              sq / sa, (unsigned long long)q.stats.apertureFallbacks, (unsigned long long)q.stats.lostParts);
  EXPECT_NEAR(sq / sa, 1.0, 0.01);
}

TEST(ViewQuadrature, BitIdenticalOnOneAndTwoThreads) {
  expectBitIdenticalOnOneAndTwoThreads(RealSetup(), PanelEstimator::Quadrature, 2, 9);
}
