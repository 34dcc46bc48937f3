// Exit-pupil bounds: sampling them loses no ray, and the weighted estimate of the sensor
// irradiance matches brute-force sampling of the whole rear window.
#include <gtest/gtest.h>

#include <cmath>

#include "camera/camera_config.h"
#include "camera/camera_model.h"
#include "camera/lens_loader.h"
#include "core/rng.h"

using namespace inim;

namespace {

struct Stats {
  double mean = 0, var = 0;
  int n = 0;
  double sigmaOfMean() const { return std::sqrt(var / n); }
};

void checkBounds(const RealLensCameraModel& cam, double lambda, const char* label) {
  const ExitPupilBounds& eb = cam.pupilBounds();
  const double w = eb.windowHalfWidth();
  const double z = cam.lens().sensorZ() - eb.rearZ();
  const double rMax = cam.sensor().halfDiagonalMm();
  for (double frac : {0.0, 0.45, 0.8, 0.97})
    for (double angDeg : {0.0, 37.0, 200.0}) {
      const double ang = angDeg * 3.14159265358979 / 180.0;
      const Vec2d s(frac * rMax * std::cos(ang), frac * rMax * std::sin(ang));
      // Brute force: stratified samples over the whole window 1.5 x the rear clear radius.
      const int n = 160;
      const double cell = 2.0 * w / n;
      double sum = 0, sum2 = 0;
      int passed = 0, lost = 0;
      const PupilBox& box = eb.box(std::sqrt(s.x * s.x + s.y * s.y));
      const double r = std::sqrt(s.x * s.x + s.y * s.y);
      const double c = r > 0 ? s.x / r : 1.0, sn = r > 0 ? s.y / r : 0.0;
      Rng rng(7, uint64_t(frac * 1000 + angDeg));
      for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
          const Point3d q(-w + (i + rng.uniformDouble()) * cell, -w + (j + rng.uniformDouble()) * cell, eb.rearZ());
          LensRay lr;
          const double f = cam.traceFromSensor(s, q, lambda, lr) / (z * z);
          sum += f;
          sum2 += f * f;
          if (f > 0.0) {
            ++passed;
            // Rotate back to the +x axis and test against the box.
            const double bx = c * q.x + sn * q.y, by = -sn * q.x + c * q.y;
            if (box.empty || bx < box.lo.x || bx > box.hi.x || by < box.lo.y || by > box.hi.y) ++lost;
          }
        }
      const double area = 4.0 * w * w;
      const double eBrute = area * sum / (n * n);
      // Stratified sampling: the variance bound of plain MC is conservative.
      const double sBrute = area * std::sqrt(std::max(0.0, sum2 / (n * n) - (sum / (n * n)) * (sum / (n * n))) / (n * n));
      EXPECT_EQ(lost, 0) << label << " r " << frac << " ang " << angDeg << ": passing rays outside the bounds";
      // Bounds sampling with the camera's weight cos^4 / (z^2 pdf).
      Stats st;
      const int m = 20000;
      double s1 = 0, s2 = 0;
      int bPassed = 0;
      for (int k = 0; k < m; ++k) {
        LensRay lr;
        const double wgt = cam.sampleLensRay(s, Vec2(rng.uniform(), rng.uniform()), lambda, lr);
        s1 += wgt;
        s2 += wgt * wgt;
        bPassed += wgt > 0 ? 1 : 0;
      }
      st.n = m;
      st.mean = s1 / m;
      st.var = s2 / m - st.mean * st.mean;
      const double sigma = std::sqrt(st.var / m + sBrute * sBrute);
      if (passed == 0) {
        EXPECT_EQ(bPassed, 0) << label;
        continue;
      }
      EXPECT_NEAR(st.mean, eBrute, 4.0 * sigma + 1e-12 * eBrute)
          << label << " r " << frac << " ang " << angDeg << " brute " << eBrute << " bounds " << st.mean;
      // The bounds make sampling efficient: a larger fraction of rays pass.
      const double fracBrute = double(passed) / (n * n), fracBounds = double(bPassed) / m;
      EXPECT_GE(fracBounds, fracBrute * 0.99) << label;
      if (angDeg == 0.0)
        std::printf("%s r/rmax %.2f: E/L brute %.5f, bounds %.5f +- %.5f; pass fraction %.3f -> %.3f\n", label, frac,
                    eBrute, st.mean, std::sqrt(st.var / m), fracBrute, fracBounds);
    }
}

}  // namespace

TEST(ExitPupil, BoundsLoseNoRaysAndKeepTheIrradiance) {
  // The Alvium camera (stand-in lens, f/4) at the d line and at the spectrum's ends.
  CameraDescription c = loadCameraDescription("alvium-1800-u-500c");
  auto m = makeCameraModel(c, defaultViewingPose(c));
  const auto& cam = dynamic_cast<const RealLensCameraModel&>(*m);
  checkBounds(cam, 587.56, "stand-in f/4 587nm");
  checkBounds(cam, 400.0, "stand-in f/4 400nm");
  checkBounds(cam, 700.0, "stand-in f/4 700nm");
}

TEST(ExitPupil, VignettedDoubleGaussFullFrame) {
  // dgauss.50mm at full aperture on a 36 x 24 mm sensor: strong vignetting off axis.
  SensorGeometry g{360, 240, 0.1};
  ViewingPose pose;
  pose.eye = {0, 0, 2000};
  RealLensCameraModel cam(loadLens("dgauss.50mm"), g, pose);
  checkBounds(cam, 587.56, "dgauss f/2");
  // Relative illumination falls toward the corner (vignetting + cos^4) but stays > 0.
  Rng rng(3, 4);
  double centre = 0, corner = 0;
  for (int k = 0; k < 20000; ++k) {
    Ray r;
    centre += cam.generateRay(Vec2(180.0f, 120.0f), Vec2(rng.uniform(), rng.uniform()), 587.56f, r);
    corner += cam.generateRay(Vec2(2.0f, 2.0f), Vec2(rng.uniform(), rng.uniform()), 587.56f, r);
  }
  centre /= 20000;
  corner /= 20000;
  EXPECT_NEAR(centre, 1.0, 0.02);
  EXPECT_LT(corner, 0.6);
  EXPECT_GT(corner, 0.01);
  std::printf("dgauss f/2 full frame: relative illumination centre %.3f, corner %.3f\n", centre, corner);
}
