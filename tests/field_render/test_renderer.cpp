// The field renderer through the camera family: furnaces (spectral and RGB, pinhole and thin
// lens), the camera's weight, a dispersive camera's hero-wavelength rays, determinism, and the
// images of the renderer before the two camera families were unified, bit for bit.
#include <gtest/gtest.h>

#include <cmath>

#include "camera/camera_model.h"
#include "camera/fov_camera.h"
#include "core/parallel.h"
#include "probe_field.h"
#include "field_render/renderer.h"
#include "spectral/rgb_to_spectrum.h"

using namespace inim;
using namespace inim::render_test;

namespace {
// A field that returns the same emission everywhere: a furnace for the renderer. With
// `terminated`, spectral answers keep only the hero wavelength (L[0] = 4x the hero).
class UniformField : public Field {
 public:
  UniformField(Vec3 rgb, FieldEncoding enc, bool terminated = false)
      : rgb_(rgb), enc_(enc), terminated_(terminated), spec_(rgb) {}
  FieldEncoding encoding() const override { return enc_; }
  void query(std::span<const FieldRay> rays, std::span<const SampledWavelengths> lambda,
             std::span<FieldSample> out, uint64_t) const override {
    for (size_t i = 0; i < rays.size(); ++i) {
      if (enc_ == FieldEncoding::Spectral) out[i].L = spec_.sample(lambda[i]);
      if (terminated_) {
        out[i].L = SampledSpectrum(0.0f);
        out[i].L[0] = float(kNumWavelengths) * spec_(lambda[i][0]);
        out[i].secondaryTerminated = true;
      }
      out[i].rgb = rgb_;
      out[i].depth = 100.0f;
      out[i].opacity = 1.0f;
    }
  }
  void bounds(Point3& lo, Point3& hi) const override { lo = Point3(-1.0f); hi = Point3(1.0f); }

 private:
  Vec3 rgb_;
  FieldEncoding enc_;
  bool terminated_;
  RGBIlluminantSpectrum spec_;
};

FovCameraSettings smallCamera(float apertureMm = 0.0f) {
  FovCameraSettings c;
  c.width = 24;
  c.height = 16;
  c.apertureMm = apertureMm;
  c.focusDistanceMm = apertureMm > 0.0f ? 200.0f : 0.0f;
  return c;
}

RenderSettings quiet(int spp) {
  RenderSettings s;
  s.spp = spp;
  s.progress = false;
  return s;
}

Vec3d meanRgb(const Image& img) {
  Vec3d sum(0.0);
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x)
      for (int c = 0; c < 3; ++c) sum[c] += img.at(x, y, c);
  return sum / (double(img.width) * img.height);
}
}  // namespace

// An emitter of RGB (1,1,1) as a D65 illuminant spectrum renders as Rec.709 white (1,1,1):
// the spectral path (wavelength sampling, CMFs, XYZ -> RGB) closes on itself.
TEST(Renderer, SpectralFurnaceReturnsInputWhite) {
  UniformField f({1, 1, 1}, FieldEncoding::Spectral);
  RenderResult r = renderField(f, FovCameraModel(smallCamera()), quiet(64));
  const Vec3d m = meanRgb(r.image);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(m[c], 1.0, 0.01) << "channel " << c;
  EXPECT_FLOAT_EQ(r.image.at(3, 3, 3), 1.0f);   // opacity
  EXPECT_FLOAT_EQ(r.image.at(3, 3, 4), 100.0f);  // depth
  EXPECT_EQ(r.raysTraced, 24u * 16u * 64u);
}

// A uniform emitter seen through any lens is its radiance, in every pixel: the pinhole and the
// thin lens of both parametrisations of the family (field of view, or sensor and focal length,
// without natural vignetting).
TEST(Renderer, UniformEmitterIsItsRadianceThroughPinholeAndThinLens) {
  UniformField f({0.2f, 0.5f, 0.7f}, FieldEncoding::RGB);
  SensorGeometry sensor{24, 16, 0.01};
  const ViewingPose pose;
  std::unique_ptr<CameraModel> cameras[] = {
      std::make_unique<FovCameraModel>(smallCamera()), std::make_unique<FovCameraModel>(smallCamera(8.0f)),
      std::make_unique<PinholeCameraModel>(sensor, pose, 20.0, false),
      std::make_unique<ThinLensCameraModel>(sensor, pose, 20.0, 2.0, 300.0, false)};
  for (const auto& cam : cameras) {
    RenderResult r = renderField(f, *cam, quiet(3));
    for (int y = 0; y < r.image.height; ++y)
      for (int x = 0; x < r.image.width; ++x) {
        ASSERT_NEAR(r.image.at(x, y, 0), 0.2f, 1e-6f) << cam->describe();
        ASSERT_NEAR(r.image.at(x, y, 1), 0.5f, 1e-6f) << cam->describe();
        ASSERT_NEAR(r.image.at(x, y, 2), 0.7f, 1e-6f) << cam->describe();
        ASSERT_EQ(r.image.at(x, y, 3), 1.0f);
      }
  }
}

// The camera's weight scales the estimate: a pinhole with natural vignetting sees a uniform
// emitter as cos^4 of the chief ray's angle.
TEST(Renderer, CameraWeightIsApplied) {
  UniformField f({1.0f, 1.0f, 1.0f}, FieldEncoding::RGB);
  const double d = 4.0, pitch = 0.25;  // a wide field: the corner pixel's chief ray at ~46 degrees
  PinholeCameraModel cam(SensorGeometry{24, 16, pitch}, ViewingPose{}, d, true);
  RenderResult r = renderField(f, cam, quiet(64));
  for (Vec2 px : {Vec2(12.0f, 8.0f), Vec2(0.0f, 0.0f), Vec2(23.0f, 5.0f)}) {
    const double sx = (px.x + 0.5 - 12.0) * pitch, sy = (px.y + 0.5 - 8.0) * pitch;
    const double cosT = d / std::sqrt(sx * sx + sy * sy + d * d);
    const double expected = std::pow(cosT, 4);
    EXPECT_NEAR(r.image.at(int(px.x), int(px.y), 0), expected, 0.01 * expected) << px.x << ", " << px.y;
  }
  EXPECT_LT(r.image.at(0, 0, 0), 0.5f);  // the corner is far darker than the centre
}

// A dispersive camera traces one ray per wavelength, each counting its hero wavelength only:
// the D65 furnace still renders white (times the camera's weight), whether or not the field
// terminated the secondary wavelengths.
TEST(Renderer, DispersiveCameraEstimatesFromHeroWavelengths) {
  PrismPinhole cam(SensorGeometry{24, 16, 0.05}, ViewingPose{});
  for (bool terminated : {false, true}) {
    UniformField f({1, 1, 1}, FieldEncoding::Spectral, terminated);
    RenderResult r = renderField(f, cam, quiet(64));
    EXPECT_EQ(r.raysTraced, 24u * 16u * 64u * uint64_t(kNumWavelengths));
    Vec3d sum(0.0);
    for (int y = 0; y < r.image.height; ++y)
      for (int x = 0; x < r.image.width; ++x)
        for (int c = 0; c < 3; ++c) sum[c] += r.image.at(x, y, c) / (0.5 + 0.001 * (x + 0.5));
    sum /= 24.0 * 16.0;
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(sum[c], 1.0, 0.02) << "channel " << c << " terminated " << terminated;
  }
}

TEST(Renderer, BitIdenticalOnOneAndTwoThreads) {
  UniformField f({0.9f, 0.3f, 0.1f}, FieldEncoding::Spectral);
  auto run = [&](int threads) {
    ThreadLimit limit(threads);
    return renderField(f, FovCameraModel(smallCamera(4.0f)), quiet(4)).image.data;
  };
  EXPECT_EQ(run(1), run(2));
}

// The images of the renderer before the camera families were unified (field_render/camera.h's
// ThinLensCamera into field_render/renderer.cpp's own loop), hashed bit for bit: a pinhole and a thin
// lens, a spectral and an RGB field, every channel (R, G, B, A, Z). The spectral hashes were
// re-taken when visible-wavelength sampling moved to one logarithm per wavelength (wavelengths
// moved by <= 1.2e-4 nm, pdfs by <= 1.6e-6 relative: tests/spectral/test_sampled.cpp).
TEST(Renderer, SameImagesAsBeforeTheCamerasWereUnified) {
  const uint64_t expected[2][2] = {{0xd9c90821c42150b9ull, 0x8c586613f3ae3c32ull},
                                   {0x64e070c70c7082e9ull, 0x41be78815b1a0cb0ull}};
  for (int rgb = 0; rgb < 2; ++rgb)
    for (int lens = 0; lens < 2; ++lens) {
      ProbeField f(rgb ? FieldEncoding::RGB : FieldEncoding::Spectral);
      FovCameraSettings c;
      c.width = 21;
      c.height = 13;
      c.hfovDeg = 31.0f;
      c.pose.eye = Point3d(12.5, -7.25, 310.0);
      c.pose.lookAt = Point3d(1.0, 2.0, -3.0);
      if (lens) {
        c.apertureMm = 8.0f;
        c.focusDistanceMm = 280.0f;
      }
      RenderSettings s = quiet(5);
      s.seed = 11;
      s.raysPerBatch = 37;
      RenderResult r = renderField(f, FovCameraModel(c), s);
      EXPECT_EQ(hashImage(r.image), expected[rgb][lens]) << (rgb ? "RGB" : "spectral") << (lens ? " thin lens" : " pinhole");
      EXPECT_EQ(r.raysTraced, 21u * 13u * 5u);
    }
}
