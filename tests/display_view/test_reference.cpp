// The reference view: a scene point at a known display-frame position (through the placement
// and the display pose) lands on the pixel the camera model predicts; a uniform D65 field is a
// white furnace; determinism; the images of the reference renderer before it became a call of
// the field renderer, bit for bit. Depth channels: a plane's display z (through a scaled
// placement too), colour unchanged by asking for depth, determinism.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <optional>
#include <utility>

#include "core/parallel.h"
#include "core/rng.h"
#include "core/transform.h"
#include "field_render/probe_field.h"
#include "spectral/cie.h"
#include "field/placement.h"
#include "camera/chromatic_spread.h"
#include "display_view/display_pose.h"
#include "display_view/reference_renderer.h"
#include "display_view/view_camera.h"
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

// The field's reference through the default camera (of `kind`, `width` px) at seeds 1 and 2.
std::pair<Image, Image> twoSeeds(const Field& field, int width, int spp,
                                 std::optional<CameraModelKind> kind = std::nullopt) {
  ViewCameraOptions co;
  co.width = width;
  co.kind = kind;
  const auto cam = makeViewCamera(defaultCamera(), DisplayPose{}, co);
  ReferenceSettings s;
  s.spp = spp;
  s.progress = false;
  Image one = renderReference(field, Transform(), *cam, defaultCamera().sensor, s).image;
  s.seed = 2;
  return {std::move(one), renderReference(field, Transform(), *cam, defaultCamera().sensor, s).image};
}

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

// The setups of the tests below: a spectral and an RGB probe field through a placement, seen by
// a pinhole, a thin lens with natural vignetting and a dispersive prism pinhole (cam 0, 1, 2),
// 6 samples per pixel in batches of 29.
template <class Body>
void forEachProbeSetup(Body body) {
  using namespace inim::render_test;
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
      body(rgb, cam, f, place, *m, s);
    }
}

// A dispersive camera's rays are traced per wavelength only when asked, or (Auto) when the camera
// spreads a point's colours over more than kDispersionThresholdPx: the prism pinhole shifts the
// sensor point by 1e-4 mm per nm, 0.2 px of its 0.05 mm pitch at 450 and 650 nm, so Auto carries
// every wavelength on one ray. In a D65 furnace both give camera white times the camera weight.
TEST(ReferenceRenderer, CameraDispersionIsTracedOnlyWhereItShows) {
  const TestField sky(Vec3d(0.0), 1.0, true);
  const render_test::PrismPinhole prism(SensorGeometry{19, 11, 0.05}, ViewingPose{});
  EXPECT_NEAR(chromaticSpreadPx(prism), 0.2, 1e-3);
  ReferenceSettings s;
  s.spp = 16;
  s.progress = false;
  s.dispersion = CameraDispersion::Trace;
  const ViewResult traced = renderReference(sky, Transform(), prism, defaultCamera().sensor, s);
  s.dispersion = CameraDispersion::Auto;
  const ViewResult carried = renderReference(sky, Transform(), prism, defaultCamera().sensor, s);
  EXPECT_EQ(traced.stats.tracedRays, 19u * 11u * 16u * 4u);
  EXPECT_EQ(carried.stats.tracedRays, 19u * 11u * 16u);
  EXPECT_TRUE(traced.stats.dispersive);
  EXPECT_FALSE(carried.stats.dispersive);
  // The prism's weight is 0.5 + 0.001 x: 0.5095 on average over the 19 columns.
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(mean(traced.image, c), 0.5095, 0.01) << "channel " << c;
    EXPECT_NEAR(mean(carried.image, c), 0.5095, 0.01) << "channel " << c;
  }
  const PinholeCameraModel pinhole(SensorGeometry{19, 11, 0.05}, ViewingPose{}, 20.0, true);
  EXPECT_EQ(chromaticSpreadPx(pinhole), 0.0);
}

// The default real lens vignettes about 40 % of its lens samples at the edge of its pupil box.
// The reference averages the rays that pass by their weights and scales by the pixel's mean
// weight (display_view/aperture_mean.h). In an RGB furnace (the same colour along every ray: nothing else
// varies) two seeds then agree to float precision wherever a lens sample passed, where the count
// of passing samples (4 per pixel) would make them differ by tens of percent; and the level is
// the mean camera weight, checked against a Monte Carlo mean of generateRay's weights.
namespace {

class RgbFurnace final : public Field {
 public:
  FieldEncoding encoding() const override { return FieldEncoding::RGB; }
  void query(std::span<const FieldRay>, std::span<const SampledWavelengths>, std::span<FieldSample> out,
             uint64_t) const override {
    for (FieldSample& f : out) f = FieldSample{}, f.rgb = Vec3(1.0f);  // D65 white, Y = 1
  }
  void bounds(Point3& lo, Point3& hi) const override { lo = Point3(-1.0f), hi = Point3(1.0f); }
};

}  // namespace

TEST(ReferenceRenderer, VignettedLensSamplesAddNoGrain) {
  ViewCameraOptions co;
  co.width = 24;
  const auto cam = makeViewCamera(defaultCamera(), DisplayPose{}, co);
  const RgbFurnace furnace;
  const auto [one, two] = twoSeeds(furnace, 24, 4);
  double worst = 0.0;
  int counted = 0;
  for (size_t i = 0; i < one.data.size(); ++i) {
    if (!(one.data[i] > 0.0f && two.data[i] > 0.0f)) continue;  // no sample passed: the darkest corners
    ++counted;
    worst = std::max(worst, std::abs(double(one.data[i]) - two.data[i]) / double(two.data[i]));
  }
  std::printf("[ measured ] largest difference between seeds: %.2e over %d of %zu values\n", worst, counted,
              one.data.size());
  EXPECT_GT(counted, int(0.95 * double(one.data.size())));
  EXPECT_LT(worst, 1e-5);
  // The centre 4 x 4 pixels against the Monte Carlo mean weight at their middle.
  Rng rng(11, 0);
  double sum = 0.0, centre = 0.0;
  const int n = 40000, cx = cam->width() / 2, cy = cam->height() / 2;
  for (int i = 0; i < n; ++i) {
    Ray r;
    sum += std::max(0.0f, cam->generateRay(Vec2(float(cx), float(cy)), Vec2(rng.uniform(), rng.uniform()), 550.0f, r));
  }
  for (int y = cy - 2; y < cy + 2; ++y)
    for (int x = cx - 2; x < cx + 2; ++x) centre += (one.at(x, y, 0) + one.at(x, y, 1) + one.at(x, y, 2)) / 48.0;
  std::printf("[ measured ] centre %.4f, Monte Carlo mean camera weight %.4f\n", centre, sum / n);
  EXPECT_NEAR(centre, sum / n, 0.01 * sum / n);
}

// The lens vignettes 4 in 10 of its pupil box's samples at f/4. The kept samples take the
// wavelengths and light strata of points 0, 1, ... (field_render/field_renderer.cpp): taken from
// the surviving points, the 4 x spp wavelengths of a pixel were no longer stratified, and a grey
// D65 sky through the real lens had 2.5 x the colour noise it has through a thin lens.
TEST(ReferenceRenderer, VignettedLensSamplesKeepTheWavelengthStrata) {
  TestField sky(Vec3d(0.0), 1.0, true);
  auto chromaNoise = [&](CameraModelKind kind) {
    const auto [one, two] = twoSeeds(sky, 32, 8, kind);
    // The rms difference of the chromaticity r / (r + g + b) between the seeds.
    double sum = 0.0;
    int n = 0;
    for (int y = 0; y < one.height; ++y)
      for (int x = 0; x < one.width; ++x) {
        const double a = one.at(x, y, 0) + one.at(x, y, 1) + one.at(x, y, 2);
        const double b = two.at(x, y, 0) + two.at(x, y, 1) + two.at(x, y, 2);
        if (!(a > 0.0 && b > 0.0)) continue;
        const double d = one.at(x, y, 0) / a - two.at(x, y, 0) / b;
        sum += d * d;
        ++n;
      }
    EXPECT_GT(n, one.width * one.height * 9 / 10);
    return std::sqrt(sum / std::max(n, 1));
  };
  const double real = chromaNoise(CameraModelKind::RealLens), thin = chromaNoise(CameraModelKind::ThinLens);
  std::printf("[ measured ] rms chromaticity difference between seeds: real lens %.2e, thin lens %.2e\n", real, thin);
  EXPECT_GT(thin, 0.0);
  EXPECT_LT(real, 1.3 * thin);
}

// ---------------------------------------------------------------------------------------
// Depth (ReferenceSettings::depth): channels A, Z and dZ.

namespace {

// A square of half-width `half` in the plane z = z0 of the field frame, facing +z, emitting a
// flat spectrum of 1; nothing elsewhere.
class PlaneField final : public Field {
 public:
  PlaneField(double z0, double half) : z0_(z0), half_(half) {}
  FieldEncoding encoding() const override { return FieldEncoding::Spectral; }
  void query(std::span<const FieldRay> rays, std::span<const SampledWavelengths>, std::span<FieldSample> out,
             uint64_t) const override {
    for (size_t i = 0; i < rays.size(); ++i) {
      out[i] = FieldSample{};
      const Vec3d o(rays[i].o), d(rays[i].d);
      if (!(d.z < 0.0)) continue;
      const double t = (z0_ - o.z) / d.z;
      const Vec3d p = o + t * d;
      if (t <= 0.0 || std::abs(p.x) > half_ || std::abs(p.y) > half_) continue;
      out[i].L = SampledSpectrum(1.0f);
      out[i].opacity = 1.0f;
      out[i].depth = float(t);
    }
  }
  void bounds(Point3& lo, Point3& hi) const override {
    lo = Point3(float(-half_), float(-half_), float(z0_));
    hi = Point3(float(half_), float(half_), float(z0_));
  }

 private:
  double z0_, half_;
};

struct DepthCheck {
  int covered = 0, empty = 0, mixed = 0;
  double maxZError = 0.0;  // over covered pixels
  bool emptyHaveZeroZ = true;
};

DepthCheck checkDepth(const Image& img, double zExpected) {
  const int a = img.channelIndex("A"), z = img.channelIndex("Z");
  EXPECT_EQ(a, 3);
  EXPECT_EQ(z, 4);
  DepthCheck c;
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) {
      const float A = img.at(x, y, a), Z = img.at(x, y, z);
      EXPECT_GE(A, 0.0f);
      EXPECT_LE(A, 1.0f);
      if (A == 1.0f) {
        ++c.covered;
        c.maxZError = std::max(c.maxZError, std::abs(double(Z) - zExpected));
      } else if (A == 0.0f) {
        ++c.empty;
        c.emptyHaveZeroZ = c.emptyHaveZeroZ && Z == 0.0f;
      } else {
        ++c.mixed;
      }
    }
  return c;
}

}  // namespace

TEST(ReferenceDepth, FlatPlaneHeadOnGivesItsDisplayZ) {
  // The square covers the middle of the view and leaves a border of background around it.
  PlaneField plane(5.0, 8.0);
  DisplayPose pose{0.0, 0.0, 200.0};
  auto cam = pinholeCamera(pose.cameraPose(), 64, 48, 0.05, 20.0);
  ReferenceSettings s;
  s.spp = 8;
  s.progress = false;
  s.depth = true;
  const Image img = renderReference(plane, Transform(), *cam, defaultCamera().sensor, s).image;
  ASSERT_EQ(img.channels, (std::vector<std::string>{"R", "G", "B", "A", "Z", "dZ"}));
  const DepthCheck c = checkDepth(img, 5.0);
  std::printf("[ measured ] plane z = 5: %d covered, %d mixed, %d empty pixels, max |Z - 5| = %.2e mm\n", c.covered,
              c.mixed, c.empty, c.maxZError);
  EXPECT_GT(c.covered, 500);
  EXPECT_GT(c.empty, 100);
  EXPECT_GT(c.mixed, 0);  // the square's edges
  EXPECT_LE(c.maxZError, 1e-3);
  EXPECT_TRUE(c.emptyHaveZeroZ);
}

// A near square in front of a larger far one: dZ is 0 on either square alone and the two
// squares' distance on the pixels whose rays hit both, where Z lies between them.
TEST(ReferenceDepth, SpreadIsTheDistanceOfTheSurfacesAPixelStraddles) {
  PlaneField nearSquare(5.0, 4.0), farSquare(-15.0, 12.0);
  struct Both final : Field {
    const PlaneField &a, &b;
    Both(const PlaneField& a, const PlaneField& b) : a(a), b(b) {}
    FieldEncoding encoding() const override { return FieldEncoding::Spectral; }
    void query(std::span<const FieldRay> rays, std::span<const SampledWavelengths> l, std::span<FieldSample> out,
               uint64_t seed) const override {
      std::vector<FieldSample> far(out.size());
      a.query(rays, l, out, seed);
      b.query(rays, l, far, seed);
      for (size_t i = 0; i < out.size(); ++i)
        if (!(out[i].opacity > 0.0f)) out[i] = far[i];
    }
    void bounds(Point3& lo, Point3& hi) const override { b.bounds(lo, hi), hi.z = 5.0f; }
  } both(nearSquare, farSquare);
  auto cam = pinholeCamera(DisplayPose{0.0, 0.0, 200.0}.cameraPose(), 64, 48, 0.05, 20.0);
  ReferenceSettings s;
  s.spp = 8;
  s.progress = false;
  s.depth = true;
  const Image img = renderReference(both, Transform(), *cam, defaultCamera().sensor, s).image;
  const int a = img.channelIndex("A"), z = img.channelIndex("Z"), dz = img.channelIndex("dZ");
  ASSERT_EQ(dz, 5);
  int onNear = 0, onFar = 0, straddling = 0;
  double worstFlat = 0.0, worstEdge = 0.0;
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) {
      if (img.at(x, y, a) < 1.0f) continue;  // the far square's outer edge
      const double Z = img.at(x, y, z), D = img.at(x, y, dz);
      if (std::abs(Z - 5.0) < 1e-3 || std::abs(Z + 15.0) < 1e-3) {
        ++(Z > 0.0 ? onNear : onFar);
        worstFlat = std::max(worstFlat, D);
      } else {
        ++straddling;
        worstEdge = std::max(worstEdge, std::abs(D - 20.0));
      }
    }
  std::printf("[ measured ] %d near, %d far, %d straddling pixels; dZ alone <= %.1e, straddling |dZ - 20| <= %.1e mm\n",
              onNear, onFar, straddling, worstFlat, worstEdge);
  EXPECT_GT(onNear, 200);
  EXPECT_GT(onFar, 200);
  EXPECT_GT(straddling, 20);  // the near square's edges
  EXPECT_LE(worstFlat, 1e-3);
  EXPECT_LE(worstEdge, 1e-3);
}

TEST(ReferenceDepth, PlacementScaleIsAppliedToTheHit) {
  // Field z = 5 placed with scale 2 sits at display z = 10: FieldSample::depth is in field units
  // along the field-frame ray, half the display distance. A thin lens sends every sample of a
  // pixel from its own point of the aperture, so the hits differ in everything but z.
  PlaneField plane(5.0, 5.0);
  Placement pl;
  pl.scale = Vec3d(2.0);
  DisplayPose pose{0.0, 0.0, 200.0};
  SensorGeometry sensor{64, 48, 0.05};
  ThinLensCameraModel cam(sensor, pose.cameraPose(), 20.0, 2.0, 150.0, false);
  ReferenceSettings s;
  s.spp = 8;
  s.progress = false;
  s.depth = true;
  const Image img = renderReference(plane, pl.toDisplay(), cam, defaultCamera().sensor, s).image;
  const DepthCheck c = checkDepth(img, 10.0);
  std::printf("[ measured ] plane at field z = 5, scale 2: %d covered pixels, max |Z - 10| = %.2e mm\n", c.covered,
              c.maxZError);
  EXPECT_GT(c.covered, 500);
  EXPECT_LE(c.maxZError, 1e-3);
  EXPECT_TRUE(c.emptyHaveZeroZ);
}

// R, G, B do not depend on whether depth is asked for: the same bits, for every camera kind of
// the unification test above (a dispersive one included) and both field encodings.
TEST(ReferenceDepth, ColourIsBitIdenticalWithDepthOnOrOff) {
  forEachProbeSetup([&](int rgb, int, const Field& f, const Transform& place, const CameraModel& m,
                        ReferenceSettings s) {
    const ViewResult off = renderReference(f, place, m, defaultCamera().sensor, s);
    s.depth = true;
    const ViewResult on = renderReference(f, place, m, defaultCamera().sensor, s);
    ASSERT_EQ(off.image.numChannels(), 3);
    ASSERT_EQ(on.image.numChannels(), 6);
    int differing = 0, hitPixels = 0;
    for (int y = 0; y < on.image.height; ++y)
      for (int x = 0; x < on.image.width; ++x) {
        for (int c = 0; c < 3; ++c) {
          const float a = off.image.at(x, y, c), b = on.image.at(x, y, c);
          if (std::memcmp(&a, &b, sizeof(float)) != 0) ++differing;
        }
        if (on.image.at(x, y, 3) > 0.0f) ++hitPixels;
      }
    EXPECT_EQ(differing, 0) << (rgb ? "RGB " : "spectral ") << m.describe();
    EXPECT_EQ(on.stats.emittingRays, off.stats.emittingRays);
    // A counts the rays the probe field answers with opacity > 0, as the stats do.
    EXPECT_EQ(hitPixels > 0, on.stats.emittingRays > 0) << m.describe();
  });
}

TEST(ReferenceDepth, BitIdenticalOnOneAndTwoThreads) {
  PlaneField plane(3.0, 6.0);
  Placement pl;
  pl.scale = Vec3d(1.5);
  pl.rotateDeg = Vec3d(10.0, -20.0, 5.0);
  DisplayPose pose{7.0, -3.0, 200.0};
  auto cam = pinholeCamera(pose.cameraPose(), 48, 32, 0.02, 20.0, true);
  ReferenceSettings s;
  s.spp = 4;
  s.progress = false;
  s.depth = true;
  s.raysPerBatch = 37;
  Image one, two;
  {
    ThreadLimit t(1);
    one = renderReference(plane, pl.toDisplay(), *cam, defaultCamera().sensor, s).image;
  }
  {
    ThreadLimit t(2);
    two = renderReference(plane, pl.toDisplay(), *cam, defaultCamera().sensor, s).image;
  }
  ASSERT_EQ(one.data.size(), two.data.size());
  EXPECT_EQ(std::memcmp(one.data.data(), two.data.data(), one.data.size() * sizeof(float)), 0);
  double zMax = 0.0;
  for (int y = 0; y < one.height; ++y)
    for (int x = 0; x < one.width; ++x) zMax = std::max(zMax, double(std::abs(one.at(x, y, 4))));
  EXPECT_GT(zMax, 0.0);  // the tilted plane is in view
}
