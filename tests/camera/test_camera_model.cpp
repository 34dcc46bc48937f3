// The camera models: orientation, framing, focus, weights, determinism, dispersion, config.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "camera/camera_config.h"
#include "camera/camera_model.h"
#include "camera/lens_loader.h"
#include "camera_test_util.h"
#include "core/output_file.h"
#include "core/rng.h"

using namespace inim;
using inim::test::scratchFile;

namespace {

const CameraDescription& alvium() {
  static const CameraDescription c = loadCameraDescription("alvium-1800-u-500c");
  return c;
}

// The three models of the Alvium camera at the default pose (eye at z = 350, looking at 0).
struct Models {
  std::unique_ptr<CameraModel> pinhole, thin, real;
};
const Models& models() {
  static const Models m = [] {
    Models r;
    const CameraDescription& c = alvium();
    r.pinhole = makeCameraModel(c, defaultViewingPose(c), CameraModelKind::Pinhole);
    r.thin = makeCameraModel(c, defaultViewingPose(c), CameraModelKind::ThinLens);
    r.real = makeCameraModel(c, defaultViewingPose(c), CameraModelKind::RealLens);
    return r;
  }();
  return m;
}

// Where a ray meets the plane z = 0 (the display plane).
Vec3d hitDisplay(const Ray& r) {
  const double t = -double(r.o.z) / double(r.d.z);
  return Vec3d(r.o) + t * Vec3d(r.d);
}

// Mean display-plane hit (and its spread) of the rays of one pixel position over lens samples.
struct Footprint {
  Vec3d mean{0.0};
  double maxDev = 0.0;
  double rmsDev = 0.0;
  int rays = 0;
  double meanWeight = 0.0;
};
Footprint footprint(const CameraModel& cam, Vec2 pixel, float lambda = 587.56f, int n = 16) {
  std::vector<Vec3d> hits;
  double wsum = 0;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      Ray r;
      const float w = cam.generateRay(pixel, Vec2((i + 0.5f) / n, (j + 0.5f) / n), lambda, r);
      wsum += w;
      if (w > 0.0f) hits.push_back(hitDisplay(r));
    }
  Footprint f;
  f.rays = int(hits.size());
  f.meanWeight = wsum / (n * n);
  for (const auto& h : hits) f.mean += h / double(hits.size());
  for (const auto& h : hits) {
    f.maxDev = std::max(f.maxDev, glm::length(h - f.mean));
    f.rmsDev += glm::dot(h - f.mean, h - f.mean) / double(hits.size());
  }
  f.rmsDev = std::sqrt(f.rmsDev);
  return f;
}

}  // namespace

TEST(CameraModel, ImageIsUprightForEveryModel) {
  // Row 0 at the top, column 0 at the left: a pixel near the top-left corner sees the
  // display's upper left (x < 0, y > 0 in the display frame), the bottom-right pixel its lower right.
  const Models& m = models();
  for (const CameraModel* cam : {m.pinhole.get(), m.thin.get(), m.real.get()}) {
    const float W = float(cam->width()), H = float(cam->height());
    Footprint tl = footprint(*cam, Vec2(100.5f, 100.5f));
    Footprint br = footprint(*cam, Vec2(W - 100.5f, H - 100.5f));
    Footprint cc = footprint(*cam, Vec2(0.5f * W, 0.5f * H));
    ASSERT_GT(tl.rays, 0) << cameraModelName(cam->kind());
    EXPECT_LT(tl.mean.x, -50.0) << cameraModelName(cam->kind());
    EXPECT_GT(tl.mean.y, 30.0) << cameraModelName(cam->kind());
    EXPECT_GT(br.mean.x, 50.0);
    EXPECT_LT(br.mean.y, -30.0);
    EXPECT_NEAR(cc.mean.x, 0.0, 1e-3);
    EXPECT_NEAR(cc.mean.y, 0.0, 1e-3);
    // Rays point from the camera toward the display.
    Ray r;
    cam->generateRay(Vec2(0.5f * W, 0.5f * H), Vec2(0.5f, 0.5f), 550.0f, r);
    EXPECT_LT(r.d.z, -0.99f);
    EXPECT_NEAR(glm::length(r.d), 1.0f, 1e-6f);
  }
}

TEST(CameraModel, ModelsFrameTheDisplayAlike) {
  // The pinhole and the thin lens use the real lens's EFL and focus, so their framing agrees
  // with the real lens (which adds a little distortion) within 1 %.
  const Models& m = models();
  const float W = float(m.real->width()), H = float(m.real->height());
  const Vec2 edge(W - 0.5f, 0.5f * H), corner(W - 0.5f, H - 0.5f);
  for (Vec2 p : {edge, corner}) {
    const Vec3d a = footprint(*m.pinhole, p).mean, b = footprint(*m.thin, p).mean, c = footprint(*m.real, p).mean;
    EXPECT_NEAR(a.x, b.x, 1e-3 * std::abs(a.x));
    // Paraxially the real lens magnifies 0.23 % less (its principal plane is not at the
    // entrance pupil); at the edge its barrel distortion widens the view by about 1 %.
    EXPECT_NEAR(c.x / b.x, 1.0, 0.02);
    if (p.y != edge.y) {
      EXPECT_NEAR(c.y / b.y, 1.0, 0.02);
    }
    std::printf("pixel (%.1f, %.1f): display x real %.3f mm, thin lens %.3f mm (ratio %.4f)\n", p.x, p.y, c.x, b.x,
                c.x / b.x);
  }
  // The camera frames the ~152 mm wide display from 350 mm (the stand-in's design goal).
  const double width = 2.0 * footprint(*m.real, edge).mean.x;
  EXPECT_GT(width, 152.0);
  EXPECT_LT(width, 170.0);
  EXPECT_NEAR(m.real->horizontalFovDeg(), m.thin->horizontalFovDeg(), 0.3);
  std::printf("display-plane width seen: %.2f mm; FOV real %.3f deg, thin %.3f deg\n", width,
              m.real->horizontalFovDeg(), m.thin->horizontalFovDeg());
}

TEST(CameraModel, RaysOfOnePixelMeetOnThePlaneOfFocus) {
  // Every ray of one pixel position meets the plane of focus (the display, 350 mm away) at
  // one point for the thin lens, and within the real lens's aberrations for the real lens:
  // under half a pixel near the axis; off axis (14 deg) the stand-in's field curvature and
  // astigmatism spread it more (~0.7 pixel RMS), as a spot diagram traced the other way
  // (object point -> sensor) confirms.
  const Models& m = models();
  const double footprintMm = alvium().sensor.geometry().pitchMm * 350.0 / 12.0;  // one pixel on the display
  const RealLensCameraModel& real = dynamic_cast<const RealLensCameraModel&>(*m.real);
  for (const CameraModel* cam : {m.thin.get(), m.real.get()})
    for (Vec2 p : {Vec2(1296.0f, 972.0f), Vec2(700.3f, 900.7f), Vec2(2400.0f, 150.0f)}) {
      Footprint f = footprint(*cam, p);
      EXPECT_GT(f.rays, 100);
      std::printf("%s pixel (%.1f, %.1f): bundle on the display plane RMS %.4f mm, max %.4f mm (pixel %.4f mm)\n",
                  cameraModelName(cam->kind()), p.x, p.y, f.rmsDev, f.maxDev, footprintMm);
      const bool offAxis = p.x == 2400.0f;
      EXPECT_LT(f.rmsDev, (offAxis ? 1.0 : 0.5) * footprintMm) << cameraModelName(cam->kind()) << " pixel " << p.x << ", " << p.y;
      if (cam == m.real.get()) {
        // Reciprocity: the spot of that display point on the sensor, scaled by the magnification.
        const Vec3d local(glm::dot(f.mean - cam->pose().eye, cam->right()), glm::dot(f.mean - cam->pose().eye, cam->up()),
                          glm::dot(f.mean - cam->pose().eye, cam->back()));
        const Point3d obj(local.x, local.y, local.z + real.lensInfo().entrancePupil.positionMm);
        SpotDiagram sd = spotDiagram(real.lens(), obj, real.sensorDistanceMm(), 587.56, 41);
        const double mag = 12.0 / (350.0 - 12.0);
        EXPECT_NEAR(sd.rmsRadiusMm / mag, f.rmsDev, 0.35 * f.rmsDev + 0.002);
        // The spot centroid is the sensor point of the pixel (inverted image).
        const Vec2d sp = real.sensorPoint(p);
        EXPECT_NEAR(sd.centroidMm.x, sp.x, 0.25 * alvium().sensor.geometry().pitchMm);
        EXPECT_NEAR(sd.centroidMm.y, sp.y, 0.25 * alvium().sensor.geometry().pitchMm);
      }
    }
  // Out of focus, at 20 mm in front of the display, the bundle spreads (depth of field).
  double spread = 0;
  for (int k = 0; k < 64; ++k) {
    Ray r;
    if (real.generateRay(Vec2(1296.0f, 972.0f), Vec2((k % 8 + 0.5f) / 8, (k / 8 + 0.5f) / 8), 587.56f, r) > 0) {
      const double t = (20.0 - r.o.z) / r.d.z;
      spread = std::max(spread, std::hypot(r.o.x + t * r.d.x, r.o.y + t * r.d.y));
    }
  }
  // Blur radius ~ EPD/2 x 20 / 350 = 1.5 mm x 0.057 = 0.086 mm.
  EXPECT_GT(spread, 0.05);
  EXPECT_LT(spread, 0.12);
}

TEST(CameraModel, WeightsAreRelativeIllumination) {
  const Models& m = models();
  const float W = float(m.real->width()), H = float(m.real->height());
  // Centre weight 1; corners: the pinhole and thin lens give cos^4 of the chief ray.
  EXPECT_NEAR(footprint(*m.pinhole, Vec2(0.5f * W, 0.5f * H)).meanWeight, 1.0, 1e-6);
  const double half = 0.5 * alvium().sensor.geometry().halfDiagonalMm() * 2.0;
  const double d = dynamic_cast<const PinholeCameraModel&>(*m.pinhole).imageDistanceMm();
  const double cos2 = d * d / (d * d + half * half);
  EXPECT_NEAR(footprint(*m.pinhole, Vec2(0.0f, 0.0f)).meanWeight, cos2 * cos2, 1e-4);
  EXPECT_NEAR(footprint(*m.thin, Vec2(0.0f, 0.0f)).meanWeight, cos2 * cos2, 1e-4);
  // Real lens: Monte Carlo mean weight at the centre is 1 (its normalisation).
  Rng rng(11, 0);
  double sum = 0;
  const int n = 20000;
  for (int k = 0; k < n; ++k) {
    Ray r;
    sum += m.real->generateRay(int(W / 2), int(H / 2), rng, 587.56f, r);
  }
  EXPECT_NEAR(sum / n, 1.0, 0.02);
  const double corner = footprint(*m.real, Vec2(0.5f, 0.5f), 587.56f, 64).meanWeight;
  EXPECT_GT(corner, 0.5);
  EXPECT_LT(corner, 1.0);
  std::printf("stand-in relative illumination at the corner %.3f (cos^4: %.3f)\n", corner, cos2 * cos2);
}

TEST(CameraModel, DeterministicAndDispersive) {
  const Models& m = models();
  Rng a(42, 7), b(42, 7);
  for (int k = 0; k < 100; ++k) {
    Ray ra, rb;
    const float wa = m.real->generateRay(1000, 500, a, 550.0f, ra);
    const float wb = m.real->generateRay(1000, 500, b, 550.0f, rb);
    EXPECT_EQ(wa, wb);
    EXPECT_EQ(ra.o, rb.o);
    EXPECT_EQ(ra.d, rb.d);
  }
  // Dispersive glass: the ray depends (slightly) on the wavelength.
  EXPECT_TRUE(m.real->isDispersive());
  EXPECT_FALSE(m.thin->isDispersive());
  Ray r1, r2;
  m.real->generateRay(Vec2(100.0f, 100.0f), Vec2(0.3f, 0.6f), 450.0f, r1);
  m.real->generateRay(Vec2(100.0f, 100.0f), Vec2(0.3f, 0.6f), 650.0f, r2);
  const float dd = glm::length(r1.d - r2.d);
  EXPECT_GT(dd, 0.0f);
  EXPECT_LT(dd, 1e-3f);
  // A pbrt lens without dispersion gives the same ray at every wavelength.
  SensorGeometry g{64, 48, 0.2};
  ViewingPose pose;
  pose.eye = {0, 0, 1000};
  RealLensCameraModel dg(loadLens("dgauss.50mm"), g, pose);
  EXPECT_FALSE(dg.isDispersive());
  Ray q1, q2;
  dg.generateRay(Vec2(10.0f, 10.0f), Vec2(0.3f, 0.6f), 450.0f, q1);
  dg.generateRay(Vec2(10.0f, 10.0f), Vec2(0.3f, 0.6f), 650.0f, q2);
  EXPECT_EQ(q1.d, q2.d);
}

TEST(CameraModel, PoseFollowsEyeLookAtUp) {
  // Rotating the pose: the camera 7 deg to the right of the display normal still sees the
  // display centre at the image centre, and the up vector sets the image's vertical.
  const CameraDescription& c = alvium();
  ViewingPose pose;
  const double a = 7.0 * 3.14159265358979 / 180.0;
  pose.eye = {350.0 * std::sin(a), 0.0, 350.0 * std::cos(a)};
  auto cam = makeCameraModel(c, pose);
  Footprint cc = footprint(*cam, Vec2(1296.0f, 972.0f));
  EXPECT_NEAR(cc.mean.x, 0.0, 1e-3);
  EXPECT_NEAR(cc.mean.y, 0.0, 1e-3);
  // Upside-down camera: the top-left pixel now sees the lower right.
  pose = defaultViewingPose(c);
  pose.up = {0.0, -1.0, 0.0};
  auto flipped = makeCameraModel(c, pose, CameraModelKind::ThinLens);
  Footprint tl = footprint(*flipped, Vec2(100.5f, 100.5f));
  EXPECT_GT(tl.mean.x, 50.0);
  EXPECT_LT(tl.mean.y, -30.0);
  // Degenerate poses are input errors.
  pose = defaultViewingPose(c);
  pose.lookAt = pose.eye;
  expectInputError([&] { makeCameraModel(c, pose, CameraModelKind::Pinhole); });
  pose = defaultViewingPose(c);
  pose.up = {0.0, 0.0, 1.0};
  InputError e = expectInputError([&] { makeCameraModel(c, pose, CameraModelKind::Pinhole); });
  EXPECT_EQ(e.key(), "pose.up");
  // A focus closer than the lens can reach.
  pose = defaultViewingPose(c);
  RealLensCameraModel::Settings s;
  s.focusDistanceMm = 3.0;
  expectInputError([&] { RealLensCameraModel(c.lens, c.sensor.geometry(), pose, s); });
}

TEST(CameraConfig, AlviumDescription) {
  const CameraDescription& c = alvium();
  EXPECT_EQ(c.sensor.geometry().widthPx, 2592);
  EXPECT_EQ(c.sensor.geometry().heightPx, 1944);
  EXPECT_NEAR(c.sensor.geometry().widthMm(), 5.70, 0.01);
  EXPECT_NEAR(c.sensor.geometry().heightMm(), 4.28, 0.01);
  EXPECT_DOUBLE_EQ(c.fNumber, 4.0);
  EXPECT_DOUBLE_EQ(c.distanceMm, 350.0);
  EXPECT_EQ(c.model, CameraModelKind::RealLens);
  EXPECT_FALSE(c.assumptions.empty());
  EXPECT_TRUE(c.sensor.hasSensitivity());
  const auto& real = dynamic_cast<const RealLensCameraModel&>(*models().real);
  EXPECT_NEAR(real.lensInfo().fNumber, 4.0, 0.04);
  EXPECT_NEAR(real.lensInfo().eflMm, 12.0, 0.012);
  std::printf("%s\n", real.describe().c_str());
}

TEST(CameraConfig, BadCameraFilesNameFileAndKey) {
  Json j = readJsonFile(defaultCameraPath());
  auto write = [&](const std::string& name, const Json& v) { return scratchFile(name, v.dump(2)); };
  Json b = j;
  b["f_number"] = 1.0;  // faster than the stand-in's f/2.03
  std::string f = write("fast.json", b);
  InputError e = expectInputError([&] { loadCameraDescription(f); });
  EXPECT_EQ(e.file(), f);
  EXPECT_EQ(e.key(), "f_number");
  b = j;
  b["lens"] = "no-such-lens";
  f = write("nolens.json", b);
  e = expectInputError([&] { loadCameraDescription(f); });
  EXPECT_EQ(e.key(), "lens");
  b = j;
  b["sensor"]["pixel_pitch_mm"] = -1.0;
  f = write("pitch.json", b);
  e = expectInputError([&] { loadCameraDescription(f); });
  EXPECT_EQ(e.key(), "sensor.pixel_pitch_mm");
  b = j;
  b["distance"] = 300.0;  // misspelt
  f = write("typo.json", b);
  e = expectInputError([&] { loadCameraDescription(f); });
  EXPECT_EQ(e.key(), "distance");
  b = j;
  b["sensor"]["spectral_sensitivity"] = "spectra/nothing.csv";
  f = write("sens.json", b);
  e = expectInputError([&] { loadCameraDescription(f); });
  EXPECT_EQ(e.key(), "sensor.spectral_sensitivity");
  b = j;
  b["model"] = "pinhole";
  b["lens"] = dataPath("optics/lenses/dgauss.50mm.dat");
  b.erase("f_number");
  f = write("pinhole.json", b);
  CameraDescription p = loadCameraDescription(f);
  EXPECT_EQ(makeCameraModel(p, defaultViewingPose(p))->kind(), CameraModelKind::Pinhole);
}
