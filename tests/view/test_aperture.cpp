// The Aperture panel estimator (view_renderer.h): the aperture quadrature table against Monte
// Carlo over the camera's own lens samples, the channel lookup against lookupPx, and the
// renderer's agreement with the point-sampling reference estimator (region means, RMSE within
// the point estimator's own noise, uniform white energy, Fresnel's dropped ghost branch), and
// determinism across thread counts.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <cstdlib>

#include "core/parallel.h"
#include "core/rng.h"
#include "mla/real_mla.h"
#include "view/aperture_kernel.h"
#include "view/display_pose.h"
#include "view/panel_emitter.h"
#include "view/view_camera.h"
#include "view/view_renderer.h"
#include "real_setup.h"
#include "view_test_util.h"

using namespace inim;
using namespace view_test;

namespace {

// The default camera (real lens) at a small width, 350 mm from the display centre.
std::unique_ptr<CameraModel> defaultRealCamera(int width) {
  DisplayPose pose;
  pose.distanceMm = defaultCamera().distanceMm;
  ViewCameraOptions o;
  o.width = width;
  return makeViewCamera(defaultCamera(), pose, o);
}

// Integral of the camera weight over its lens samples: stratified Monte Carlo, n x n.
double weightIntegralMc(const CameraModel& cam, Vec2 pixel, int n) {
  Rng rng(3, 1);
  double s = 0.0;
  Ray r;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i)
      s += std::max(0.0f, cam.generateRay(pixel, Vec2(float((i + rng.uniform()) / n), float((j + rng.uniform()) / n)),
                                          550.0f, r));
  return s / (double(n) * n);
}

}  // namespace

TEST(ApertureKernel, TotalWeightIsTheCameraWeightIntegral) {
  // Real lens (rear-plane coordinates; vignetting at the corners) and thin lens (lens samples).
  auto real = defaultRealCamera(648);
  RealSetup r;
  const CameraModel* cams[2] = {real.get(), r.camera.get()};
  for (const CameraModel* cam : cams) {
    ApertureSpace space(*cam);
    const float W = float(cam->width()), H = float(cam->height());
    for (Vec2 p : {Vec2(0.5f * W, 0.5f * H), Vec2(0.8f * W, 0.3f * H), Vec2(1.0f, 1.0f), Vec2(W - 1.0f, H - 1.0f)}) {
      for (int grid : {8, 12, 16}) {
        uint64_t rays = 0;
        const ApertureKernel k = buildApertureKernel(space, p, 550.0f, grid, rays);
        ASSERT_TRUE(k.valid());
        const double mc = weightIntegralMc(*cam, p, 400);
        std::printf("[ measured ] %s pixel (%.0f, %.0f), grid %2d: %zu points, %llu rays, table / MC = %.5f\n",
                    cameraModelName(cam->kind()), p.x, p.y, grid, k.points.size(), (unsigned long long)rays,
                    k.total / mc);
        EXPECT_NEAR(k.total / mc, 1.0, grid >= 12 ? 0.004 : 0.015) << "grid " << grid;
        // The centre is the weighted centroid.
        double sx = 0.0, sy = 0.0;
        for (const auto& q : k.points) {
          sx += double(q.w) * q.ax;
          sy += double(q.w) * q.ay;
        }
        EXPECT_NEAR(sx / k.total, 0.0, 1e-4 * (k.cellW + k.cellH));
        EXPECT_NEAR(sy / k.total, 0.0, 1e-4 * (k.cellW + k.cellH));
      }
    }
  }
}

TEST(ApertureKernel, QuadratureOfTheEmitterMatchesBruteForceOverTheAperture) {
  // Camera pixel positions that see the small real setup: the kernel's quadrature (affine map
  // of the aperture to the panel, its random shifts averaged) against the aperture integral
  // traced ray by ray (500 x 500 points over the aperture domain, deterministic Fresnel), per
  // channel; thin lens and the default real lens (at 200 mm, 64 px wide).
  RealSetup r;
  RealMlaOptions o;
  o.fresnel = FresnelMode::Weighted;
  auto mla = RealMla::fromDisplay(r.display, r.layout, r.g, o);
  const float lambda = 550.0f;
  const float frontZ = mla->frontZ() + 0.01f;
  DisplayPose pose;
  pose.distanceMm = 200.0;
  ViewCameraOptions co;
  co.width = 640;
  auto real = makeViewCamera(defaultCamera(), pose, co);
  int checked = 0;
  for (int ci = 0; ci < 2; ++ci) {
    const CameraModel& cam = ci == 0 ? static_cast<const CameraModel&>(*r.camera) : *real;
    ApertureSpace space(cam);
    const float sx0 = ci == 0 ? 1.0f : 320.0f - 12.0f, sy0 = ci == 0 ? 1.0f : 240.0f - 8.0f, sc = ci == 0 ? 1.0f : 1.0f;
    for (int grid : {12, 32})
    for (Vec2 pix0 : {Vec2(7.3f, 5.6f), Vec2(12.1f, 8.4f), Vec2(3.6f, 11.2f)}) {
      const Vec2 pix(sx0 + sc * pix0.x - 1.0f, sy0 + sc * pix0.y - 1.0f);
      uint64_t rays = 0;
      const ApertureKernel k = buildApertureKernel(space, pix, lambda, grid, rays, frontZ);
      ASSERT_TRUE(k.valid());
      auto landMla = [&](const Vec2d& h, const Vec2d& sl, Vec2d& uv) -> bool {
        const Vec3 d = glm::normalize(Vec3(float(sl.x), float(sl.y), -1.0f));
        Rng rng(1, 1);
        PanelArrival arr;
        if (!mla->traceToPanel(Ray{Point3(float(h.x), float(h.y), frontZ), d, 0.0f, kInfinity}, lambda, rng, arr))
          return false;
        float f;
        return r.panel->emissionPointPx(arr.p, arr.d, lambda, uv, f);
      };
      auto land = [&](const Vec2d& a, Vec2d& uv, float& w, float& T) -> bool {
        Ray ray;
        w = space.ray(pix, a, lambda, ray);
        if (!(w > 0.0f)) return false;
        const Point3 p = ray.o + ((frontZ - ray.o.z) / ray.d.z) * ray.d;
        Rng rng(1, 1);
        PanelArrival arr;
        if (!mla->traceToPanel(Ray{p, ray.d, 0.0f, kInfinity}, lambda, rng, arr)) return false;
        float f;
        if (!r.panel->emissionPointPx(arr.p, arr.d, lambda, uv, f)) return false;
        T = arr.throughput * f;
        return true;
      };
      Vec2d uv0;
      float wc, Tc;
      ASSERT_TRUE(land(k.centre, uv0, wc, Tc));
      Ray cr;
      space.ray(pix, k.centre, lambda, cr);
      const Point3 cp = cr.o + ((frontZ - cr.o.z) / cr.d.z) * cr.d;
      const Vec2d h0(cp.x, cp.y), s0(cr.d.x / -double(cr.d.z), cr.d.y / -double(cr.d.z));
      double A[2][2], B[2][2];
      for (int m = 0; m < 4; ++m) {
        const int ax = m & 1;
        const bool slope = m >= 2;
        const double e = slope ? k.rmsS : std::max(k.rmsH, 0.002);
        const Vec2d dv = ax == 0 ? Vec2d(e, 0.0) : Vec2d(0.0, e);
        Vec2d up, um;
        ASSERT_TRUE(slope ? landMla(h0, s0 + dv, up) : landMla(h0 + dv, s0, up));
        ASSERT_TRUE(slope ? landMla(h0, s0 - dv, um) : landMla(h0 - dv, s0, um));
        double(&M)[2][2] = slope ? B : A;
        M[0][ax] = (up.x - um.x) / (2 * e);
        M[1][ax] = (up.y - um.y) / (2 * e);
      }
      double quad[3] = {0, 0, 0};
      for (int sj = 0; sj < 16; ++sj)
        for (int si = 0; si < 16; ++si) {
          const double sx = ((si + 0.5) / 16 - 0.5) * k.cellW, sy = ((sj + 0.5) / 16 - 0.5) * k.cellH;
          for (const auto& q : k.points) {
            const double dh[2] = {q.dhx + k.shiftH[0][0] * sx + k.shiftH[0][1] * sy,
                                  q.dhy + k.shiftH[1][0] * sx + k.shiftH[1][1] * sy};
            const double ds[2] = {q.dsx + k.shiftS[0][0] * sx + k.shiftS[0][1] * sy,
                                  q.dsy + k.shiftS[1][0] * sx + k.shiftS[1][1] * sy};
            const double u = uv0.x + A[0][0] * dh[0] + A[0][1] * dh[1] + B[0][0] * ds[0] + B[0][1] * ds[1];
            const double v = uv0.y + A[1][0] * dh[0] + A[1][1] * dh[1] + B[1][0] * ds[0] + B[1][1] * ds[1];
            for (int c = 0; c < 3; ++c) quad[c] += q.w * r.panel->channelDrivePx(c, u, v);
          }
        }
      const double J[2][2] = {{B[0][0], B[0][1]}, {B[1][0], B[1][1]}};
      for (double& v : quad) v *= Tc * wc / k.centreWeight / 256.0;
      Vec2d lo, hi;
      ASSERT_TRUE(space.domain(pix, lo, hi));
      double brute[3] = {0, 0, 0}, energy = 0.0;
      const int n = 500;
      const double cell = (hi.x - lo.x) * (hi.y - lo.y) / (double(n) * n);
      for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
          Vec2d uv;
          float w, T;
          const Vec2d a(lo.x + (hi.x - lo.x) * (i + 0.5) / n, lo.y + (hi.y - lo.y) * (j + 0.5) / n);
          if (!land(a, uv, w, T)) continue;
          energy += double(w) * cell;
          const PanelEmission e = r.panel->lookupPx(uv.x, uv.y);
          if (e.channel >= 0) brute[e.channel] += double(w) * T * e.weight * cell;
        }
      const double tot = brute[0] + brute[1] + brute[2];
      std::printf("[ measured ] %s grid %d pixel (%.1f, %.1f): table total / brute-force energy %.4f; B = [%.3g %.3g; %.3g %.3g] px per unit slope\n",
                  cameraModelName(cam.kind()), grid, pix.x, pix.y, k.total / energy, J[0][0], J[0][1], J[1][0], J[1][1]);
      for (int c = 0; c < 3; ++c) {
        std::printf("[ measured ]   channel %d: quadrature %.5g, brute force %.5g\n", c, quad[c], brute[c]);
        // The quadrature's own error (cells at the pupil's edge spread over whole cells) is
        // ~1-2% of the total at grid 12 and falls with the grid.
        EXPECT_NEAR(quad[c], brute[c], (grid == 12 ? 0.02 : 0.0075) * tot + 1e-9)
            << cameraModelName(cam.kind()) << " grid " << grid << " channel " << c;
      }
      ++checked;
    }
  }
  EXPECT_EQ(checked, 12);
}

TEST(ApertureKernel, ChannelLookupMatchesLookupPx) {
  for (bool diamond : {false, true}) {
    Display d = smallDisplay(4, 3, 6, 0.05, 0.3, 1.0, 1.2);
    if (diamond) d.panel.subpixels = diamondLayout(0.8);
    const EiLayout L = computeLayout(d);
    PanelEmitter e(d.panel, L, patternEia(L), "pattern.exr", 1.2);
    Rng rng(5, 2);
    int mismatches = 0;
    for (int i = 0; i < 20000; ++i) {
      const double u = -1.0 + (L.panelW + 2.0) * rng.uniformDouble(), v = -1.0 + (L.panelH + 2.0) * rng.uniformDouble();
      const PanelEmission p = e.lookupPx(u, v);
      for (int c = 0; c < 3; ++c)
        if (e.channelDrivePx(c, u, v) != (p.channel == c ? p.weight : 0.0f)) ++mismatches;
    }
    EXPECT_EQ(mismatches, 0) << (diamond ? "diamond" : "stripe");
  }
}

TEST(ViewAperture, AgreesWithThePointEstimatorAtHighSpp) {
  RealSetup r;
  const Image a = r.render(PanelEstimator::PointSample, 4096, 1).image;
  const Image b = r.render(PanelEstimator::PointSample, 4096, 2).image;
  const double m = meanAll(a);
  const double pointPair = rmse(a, b);
  const double noiseA = pointPair / std::sqrt(2.0);
  std::printf("[ measured ] point 4096 spp: RMSE/mean of one image %.2f%%\n", 100.0 * noiseA / m);
  for (int spp : {1, 4, 16, 256}) {
    const ViewResult f = r.render(PanelEstimator::Aperture, spp, 5);
    const ViewResult f2 = r.render(PanelEstimator::Aperture, spp, 6);
    const double e = rmse(f.image, a);
    const double selfNoise = rmse(f.image, f2.image) / std::sqrt(2.0);
    std::printf("[ measured ] aperture %4d spp: noise RMSE/mean %.2f%%, RMSE/mean vs point 4096 %.2f%%, mean ratio "
                "%.4f, %llu of %llu rays fell back (%.2f s)\n",
                spp, 100.0 * selfNoise / m, 100.0 * e / m, meanAll(f.image) / m,
                (unsigned long long)f.stats.apertureFallbacks,
                (unsigned long long)(f.stats.apertureFallbacks + f.stats.apertureSamples), f.stats.seconds);
    EXPECT_NEAR(meanAll(f.image) / m, 1.0, 0.01) << spp << " spp";
    if (spp == 256) {
      // As close to a point image as another point image is, up to a stated tolerance of 1% of
      // the mean (the bias of the affine model, the block-wise aperture table and the dropped
      // Fresnel ghosts).
      const double tol = 0.01 * m;
      EXPECT_LT(e, std::sqrt(pointPair * pointPair + selfNoise * selfNoise + tol * tol));
      for (int by = 0; by < 4; ++by)
        for (int bx = 0; bx < 6; ++bx)
          for (int c = 0; c < 3; ++c) {
            const double fa = blockMean(f.image, 4 * bx, 4 * by, 4, 4, c);
            const double pa = 0.5 * (blockMean(a, 4 * bx, 4 * by, 4, 4, c) + blockMean(b, 4 * bx, 4 * by, 4, 4, c));
            EXPECT_NEAR(fa / pa, 1.0, 0.02) << "block " << bx << "," << by << " channel " << c;
          }
    }
  }
}

TEST(ViewAperture, UniformWhiteEnergyAndGhosts) {
  // Uniform white: the aperture estimator's mean against the point estimator with stochastic
  // Fresnel (all paths, ghosts included) and with weighted Fresnel (the transmitted path only,
  // what the aperture estimator integrates): the ghost branch's share of the energy.
  RealSetup w(true);
  const Image pt = w.render(PanelEstimator::PointSample, 1024).image;
  const ViewResult ap = w.render(PanelEstimator::Aperture, 64);
  RealMlaOptions o;
  o.fresnel = FresnelMode::Weighted;
  RealSetup ww(true);
  ww.mla = RealMla::fromDisplay(ww.display, ww.layout, ww.g, o);
  const Image ptw = ww.render(PanelEstimator::PointSample, 1024).image;
  std::printf("[ measured ] uniform white: mean aperture (64 spp) / point (1024 spp, stochastic Fresnel) = %.4f, "
              "/ point (weighted Fresnel) = %.4f; ghosts (stochastic / weighted - 1) = %.3f%%; fallbacks %llu of %llu\n",
              meanAll(ap.image) / meanAll(pt), meanAll(ap.image) / meanAll(ptw),
              100.0 * (meanAll(pt) / meanAll(ptw) - 1.0), (unsigned long long)ap.stats.apertureFallbacks,
              (unsigned long long)(ap.stats.apertureFallbacks + ap.stats.apertureSamples));
  EXPECT_NEAR(meanAll(ap.image) / meanAll(ptw), 1.0, 0.005);
  EXPECT_NEAR(meanAll(ap.image) / meanAll(pt), 1.0, 0.01);
  for (int c = 0; c < 3; ++c)
    EXPECT_NEAR(blockMean(ap.image, 0, 0, 24, 16, c) / blockMean(ptw, 0, 0, 24, 16, c), 1.0, 0.01);
}

TEST(ViewAperture, RealLensAgreesWithThePointEstimator) {
  // The default real-lens camera (rear-plane aperture coordinates) at 640 px wide and 200 mm:
  // the small display covers ~40 x 27 pixels (a pixel ~0.15 mm of the MLA). Mean and block
  // means over the display's pixels against the point estimator.
  RealSetup r;
  auto cam = realLensCameraAt200mm();
  const Image a = r.render(PanelEstimator::PointSample, 1024, 1, 1.0, cam.get()).image;
  const ViewResult f = r.render(PanelEstimator::Aperture, 64, 3, 1.0, cam.get());
  int x0 = a.width, x1 = -1, y0 = a.height, y1 = -1;
  for (int y = 0; y < a.height; ++y)
    for (int x = 0; x < a.width; ++x)
      if (a.at(x, y, 0) + a.at(x, y, 1) + a.at(x, y, 2) > 0.0f) {
        x0 = std::min(x0, x);
        x1 = std::max(x1, x);
        y0 = std::min(y0, y);
        y1 = std::max(y1, y);
      }
  ASSERT_GT(x1 - x0, 20);
  ASSERT_GT(y1 - y0, 12);
  // Inner region (2 px from the display's edge), in 4 x 3 blocks.
  x0 += 2, y0 += 2, x1 -= 2, y1 -= 2;
  const int bw = (x1 - x0 + 1) / 4, bh = (y1 - y0 + 1) / 3;
  double ma = 0.0, mf = 0.0, worst = 0.0;
  for (int c = 0; c < 3; ++c) {
    ma += blockMean(a, x0, y0, 4 * bw, 3 * bh, c);
    mf += blockMean(f.image, x0, y0, 4 * bw, 3 * bh, c);
  }
  for (int by = 0; by < 3; ++by)
    for (int bx = 0; bx < 4; ++bx)
      for (int c = 0; c < 3; ++c) {
        const double pa = blockMean(a, x0 + bx * bw, y0 + by * bh, bw, bh, c);
        const double fa = blockMean(f.image, x0 + bx * bw, y0 + by * bh, bw, bh, c);
        worst = std::max(worst, std::abs(fa / pa - 1.0));
        EXPECT_NEAR(fa / pa, 1.0, 0.03) << "block " << bx << "," << by << " channel " << c;
      }
  std::printf("[ measured ] real lens: display region mean aperture (64 spp) / point (1024 spp) = %.4f, worst block "
              "%.2f%%, fallbacks %llu of %llu\n", mf / ma, 100.0 * worst,
              (unsigned long long)f.stats.apertureFallbacks,
              (unsigned long long)(f.stats.apertureFallbacks + f.stats.apertureSamples));
  EXPECT_GT(f.stats.apertureSamples, f.stats.apertureFallbacks);
  EXPECT_NEAR(mf / ma, 1.0, 0.01);
}

TEST(ViewAperture, BitIdenticalOnOneAndTwoThreads) {
  expectBitIdenticalOnOneAndTwoThreads(RealSetup(), PanelEstimator::Aperture, 3, 9);
}
