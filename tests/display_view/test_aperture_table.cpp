// The Quadrature estimator's aperture table (estimators/aperture_table.h): its total weight
// against Monte Carlo over the camera's own lens samples (real and thin lens), and its points
// mapped through the linearised MLA against the aperture integral traced ray by ray.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "core/rng.h"
#include "mla_optics/real_mla.h"
#include "display_view/estimators/aperture_table.h"
#include "display_view/display_pose.h"
#include "display_view/panel_emitter.h"
#include "display_view/view_camera.h"
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

// The table's offsets as an affine function of the aperture coordinates (weighted least
// squares, offsets = H (a - centre), S (a - centre)): moves the whole table by a sub-cell shift.
struct AffineFit {
  double H[2][2] = {}, S[2][2] = {};
};
AffineFit fitOffsets(const ApertureTable& k) {
  double Saa[2][2] = {}, Sha[2][2] = {}, Ssa[2][2] = {};
  for (const auto& p : k.points) {
    const double a[2] = {p.ax, p.ay}, dh[2] = {p.dhx, p.dhy}, ds[2] = {p.dsx, p.dsy};
    for (int i = 0; i < 2; ++i)
      for (int j = 0; j < 2; ++j) {
        Saa[i][j] += p.w * a[i] * a[j];
        Sha[i][j] += p.w * dh[i] * a[j];
        Ssa[i][j] += p.w * ds[i] * a[j];
      }
  }
  AffineFit f;
  const double det = Saa[0][0] * Saa[1][1] - Saa[0][1] * Saa[1][0];
  if (!(std::abs(det) > 0.0)) return f;
  const double inv[2][2] = {{Saa[1][1] / det, -Saa[0][1] / det}, {-Saa[1][0] / det, Saa[0][0] / det}};
  for (int i = 0; i < 2; ++i)
    for (int j = 0; j < 2; ++j) {
      f.H[i][j] = Sha[i][0] * inv[0][j] + Sha[i][1] * inv[1][j];
      f.S[i][j] = Ssa[i][0] * inv[0][j] + Ssa[i][1] * inv[1][j];
    }
  return f;
}

}  // namespace

TEST(ApertureTable, TotalWeightIsTheCameraWeightIntegral) {
  // Real lens (rear-plane coordinates; vignetting at the corners) and thin lens (lens samples).
  auto real = defaultRealCamera(648);
  RealSetup r;
  const CameraModel* cams[2] = {real.get(), r.camera.get()};
  for (const CameraModel* cam : cams) {
    const float W = float(cam->width()), H = float(cam->height());
    for (Vec2 p : {Vec2(0.5f * W, 0.5f * H), Vec2(0.8f * W, 0.3f * H), Vec2(1.0f, 1.0f), Vec2(W - 1.0f, H - 1.0f)}) {
      for (int grid : {8, 12, 16}) {
        uint64_t rays = 0;
        const ApertureTable k = buildApertureTable(*cam, p, 550.0f, grid, rays);
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

TEST(ApertureTable, QuadratureOfTheEmitterMatchesBruteForceOverTheAperture) {
  // Camera pixel positions that see the small real setup: the table's quadrature (the MLA
  // linearised about the centre ray, the table shifted by sub-cell offsets and averaged, so that
  // each point covers its cell) against the aperture integral traced ray by ray (500 x 500
  // points over the aperture domain, deterministic Fresnel), per channel; thin lens and the
  // default real lens (at 200 mm, 640 px wide).
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
    const float sx0 = ci == 0 ? 1.0f : 320.0f - 12.0f, sy0 = ci == 0 ? 1.0f : 240.0f - 8.0f, sc = ci == 0 ? 1.0f : 1.0f;
    for (int grid : {12, 32})
    for (Vec2 pix0 : {Vec2(7.3f, 5.6f), Vec2(12.1f, 8.4f), Vec2(3.6f, 11.2f)}) {
      const Vec2 pix(sx0 + sc * pix0.x - 1.0f, sy0 + sc * pix0.y - 1.0f);
      uint64_t rays = 0;
      const ApertureTable k = buildApertureTable(cam, pix, lambda, grid, rays, frontZ);
      ASSERT_TRUE(k.valid());
      const AffineFit shift = fitOffsets(k);
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
        w = cam.apertureRay(pix, a, lambda, ray);
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
      cam.apertureRay(pix, k.centre, lambda, cr);
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
            const double dh[2] = {q.dhx + shift.H[0][0] * sx + shift.H[0][1] * sy,
                                  q.dhy + shift.H[1][0] * sx + shift.H[1][1] * sy};
            const double ds[2] = {q.dsx + shift.S[0][0] * sx + shift.S[0][1] * sy,
                                  q.dsy + shift.S[1][0] * sx + shift.S[1][1] * sy};
            const double u = uv0.x + A[0][0] * dh[0] + A[0][1] * dh[1] + B[0][0] * ds[0] + B[0][1] * ds[1];
            const double v = uv0.y + A[1][0] * dh[0] + A[1][1] * dh[1] + B[1][0] * ds[0] + B[1][1] * ds[1];
            for (int c = 0; c < 3; ++c) quad[c] += q.w * r.panel->channelDrivePx(c, u, v);
          }
        }
      const double J[2][2] = {{B[0][0], B[0][1]}, {B[1][0], B[1][1]}};
      for (double& v : quad) v *= Tc * wc / k.centreWeight / 256.0;
      Vec2d lo, hi;
      ASSERT_TRUE(cam.apertureDomain(pix, lo, hi));
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
