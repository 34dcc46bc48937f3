// The reference view: a scene point at a known display-frame position (through the placement
// and the display pose) lands on the pixel the camera model predicts; a uniform D65 field is a
// white furnace; determinism; the images of the reference renderer before it became a call of
// the field renderer, bit for bit.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>

#include "core/parallel.h"
#include "core/transform.h"
#include "render/probe_field.h"
#include "spectral/cie.h"
#include "field/placement.h"
#include "view/display_pose.h"
#include "view/reference_renderer.h"
#include "view_test_util.h"

using namespace inim;
using namespace view_test;

namespace {

// A spectral field: a sphere (field frame) emitting a flat spectrum of 1, black elsewhere; or,
// with `sky`, D65 at luminance 1 along every ray.
class TestField final : public Field {
 public:
  TestField(Vec3d c, double r, bool sky = false) : c_(c), r_(r), sky_(sky) {}
  FieldEncoding encoding() const override { return FieldEncoding::Spectral; }
  void query(std::span<const FieldRay> rays, std::span<const SampledWavelengths> lambda, std::span<FieldSample> out,
             uint64_t) const override {
    static const double d65Y = spectrumToXYZ(cie::D65()).y;
    for (size_t i = 0; i < rays.size(); ++i) {
      FieldSample& f = out[i];
      f = FieldSample{};
      if (sky_) {
        for (int k = 0; k < kNumWavelengths; ++k) f.L[k] = float(cie::D65()(lambda[i][k]) / d65Y);
        continue;
      }
      const Vec3d o(rays[i].o), d(rays[i].d), oc = o - c_;
      const double b = glm::dot(oc, d), cc = glm::dot(oc, oc) - r_ * r_, disc = b * b - cc;
      if (disc < 0.0 || -b - std::sqrt(disc) <= 0.0) continue;
      f.L = SampledSpectrum(1.0f);
      f.opacity = 1.0f;
      f.depth = float(-b - std::sqrt(disc));
    }
  }
  void bounds(Point3& lo, Point3& hi) const override {
    lo = Point3(c_ - Vec3d(r_));
    hi = Point3(c_ + Vec3d(r_));
  }

 private:
  Vec3d c_;
  double r_;
  bool sky_;
};

Vec2d centroid(const Image& img) {
  double sx = 0, sy = 0, sw = 0;
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) {
      const double v = img.at(x, y, 0) + img.at(x, y, 1) + img.at(x, y, 2);
      sx += v * (x + 0.5);
      sy += v * (y + 0.5);
      sw += v;
    }
  EXPECT_GT(sw, 0.0);
  return {sx / sw, sy / sw};
}

}  // namespace

TEST(ReferenceRenderer, ScenePointLandsWhereTheCameraPredicts) {
  const Vec3d cField(1.0, 1.5, 2.0);
  TestField field(cField, 0.15);
  Placement pl;
  pl.scale = Vec3d(2.0);
  pl.rotateDeg = Vec3d(0.0, 0.0, 30.0);
  pl.translateMm = Vec3d(3.0, -2.0, 5.0);
  // The display-frame position, by hand: rotate 30 deg about z, scale 2, translate.
  const double a = 30.0 * M_PI / 180.0;
  const Vec3d pd(2.0 * (std::cos(a) * cField.x - std::sin(a) * cField.y) + 3.0,
                 2.0 * (std::sin(a) * cField.x + std::cos(a) * cField.y) - 2.0, 2.0 * cField.z + 5.0);
  const Vec3d viaPlacement = pl.toDisplay().point(cField);
  EXPECT_NEAR(glm::length(viaPlacement - pd), 0.0, 1e-9);
  // The gimbal: world = Ry(H) Rx(-V) display, by hand.
  const double H = 10.0 * M_PI / 180.0, V = -5.0 * M_PI / 180.0, D = 300.0;
  const Vec3d rx(pd.x, std::cos(-V) * pd.y - std::sin(-V) * pd.z, std::sin(-V) * pd.y + std::cos(-V) * pd.z);
  const Vec3d pw(std::cos(H) * rx.x + std::sin(H) * rx.z, rx.y, -std::sin(H) * rx.x + std::cos(H) * rx.z);
  // Pinhole at (0, 0, D) looking down -z, image distance d, W x H pixels of `pitch`.
  const int W = 96, Hh = 64;
  const double d = 25.0, pitch = 0.02;
  const Vec2d expected(0.5 * W + d * pw.x / (D - pw.z) / pitch, 0.5 * Hh - d * pw.y / (D - pw.z) / pitch);
  ASSERT_GT(expected.x, 10.0);
  ASSERT_LT(expected.x, W - 10.0);
  ASSERT_GT(expected.y, 10.0);
  ASSERT_LT(expected.y, Hh - 10.0);
  DisplayPose pose{10.0, -5.0, D};
  auto cam = pinholeCamera(pose.cameraPose(), W, Hh, pitch, d);
  ReferenceSettings s;
  s.spp = 32;
  s.progress = false;
  ViewResult r = renderReference(field, pl.toDisplay(), *cam, defaultCamera().sensor, s);
  const Vec2d c = centroid(r.image);
  std::printf("[ measured ] sphere centroid (%.3f, %.3f) px, predicted (%.3f, %.3f)\n", c.x, c.y, expected.x, expected.y);
  EXPECT_NEAR(c.x, expected.x, 0.25);
  EXPECT_NEAR(c.y, expected.y, 0.25);
  EXPECT_GT(r.stats.emittingRays, 0u);
}

TEST(ReferenceRenderer, D65FurnaceGivesCameraWhite) {
  TestField sky(Vec3d(0.0), 1.0, true);
  ViewingPose pose;
  auto cam = pinholeCamera(pose, 8, 6, 0.01, 10.0);
  ReferenceSettings s;
  s.spp = 256;
  s.progress = false;
  ViewResult r = renderReference(sky, Transform(), *cam, defaultCamera().sensor, s);
  // Camera RGB is white balanced so that D65 at luminance 1 gives (1, 1, 1).
  std::printf("[ measured ] D65 furnace camera RGB: %.4f %.4f %.4f\n", mean(r.image, 0), mean(r.image, 1), mean(r.image, 2));
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(mean(r.image, c), 1.0, 0.01) << "channel " << c;
}

TEST(ReferenceRenderer, BitIdenticalOnOneAndTwoThreads) {
  TestField field(Vec3d(0.0, 0.0, 3.0), 2.0);
  DisplayPose pose{7.0, 0.0, 200.0};
  auto cam = pinholeCamera(pose.cameraPose(), 48, 32, 0.01, 20.0, true);
  ReferenceSettings s;
  s.spp = 4;
  s.progress = false;
  Image one, two;
  {
    ThreadLimit t(1);
    one = renderReference(field, Transform(), *cam, defaultCamera().sensor, s).image;
  }
  {
    ThreadLimit t(2);
    two = renderReference(field, Transform(), *cam, defaultCamera().sensor, s).image;
  }
  ASSERT_EQ(one.data.size(), two.data.size());
  EXPECT_EQ(std::memcmp(one.data.data(), two.data.data(), one.data.size() * sizeof(float)), 0);
}

// The images of the reference renderer before it became the field renderer with its own sampler
// and film (its own loop in view/reference_renderer.cpp), hashed bit for bit: a pinhole and a
// thin lens with natural vignetting and a dispersive pinhole (one ray per wavelength, packets
// the field terminates), a spectral and an RGB field, through a placement.
TEST(ReferenceRenderer, SameImagesAsBeforeTheRenderersWereUnified) {
  using namespace inim::render_test;
  const uint64_t expected[2][3] = {{0xee3d3ff8c3432c4bull, 0xa3a850238d7ec7b1ull, 0x41ecfbc58163acc1ull},
                                   {0x4a2f30f358104ecdull, 0x9b445e5ec0971b1bull, 0xc21bff50a238d704ull}};
  const uint64_t hits[3] = {0, 92, 0};
  const ViewingPose pose{{10.0, 5.0, 250.0}, {0.0, 1.0, -2.0}, {0.0, 1.0, 0.0}};
  const SensorGeometry sensor{19, 11, 0.05};
  const Transform place = Transform::translate(Vec3d(1.0, -2.0, 3.0)) * Transform::scale(Vec3d(1.5));
  for (int rgb = 0; rgb < 2; ++rgb)
    for (int cam = 0; cam < 3; ++cam) {
      ProbeField f(rgb ? FieldEncoding::RGB : FieldEncoding::Spectral, true);
      std::unique_ptr<CameraModel> m;
      if (cam == 0) m = std::make_unique<PinholeCameraModel>(sensor, pose, 20.0, true);
      if (cam == 1) m = std::make_unique<ThinLensCameraModel>(sensor, pose, 20.0, 2.8, 240.0, true);
      if (cam == 2) m = std::make_unique<PrismPinhole>(sensor, pose);
      ReferenceSettings s;
      s.spp = 6;
      s.seed = 5;
      s.progress = false;
      s.raysPerBatch = 29;
      ViewResult r = renderReference(f, place, *m, defaultCamera().sensor, s);
      EXPECT_EQ(hashImage(r.image), expected[rgb][cam]) << (rgb ? "RGB " : "spectral ") << m->describe();
      EXPECT_EQ(r.stats.tracedRays, 19u * 11u * 6u * (cam == 2 ? 4u : 1u));
      EXPECT_EQ(r.stats.emittingRays, hits[cam]);
    }
}
