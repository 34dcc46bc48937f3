#include <gtest/gtest.h>

#include "core/parallel.h"
#include "render/renderer.h"
#include "spectral/rgb_to_spectrum.h"

using namespace inim;

namespace {
// A field that returns the same emission everywhere: a furnace for the renderer.
class UniformField : public Field {
 public:
  UniformField(Vec3 rgb, FieldEncoding enc) : rgb_(rgb), enc_(enc), spec_(rgb) {}
  FieldEncoding encoding() const override { return enc_; }
  void query(std::span<const FieldRay> rays, std::span<const SampledWavelengths> lambda,
             std::span<FieldSample> out, uint64_t) const override {
    for (size_t i = 0; i < rays.size(); ++i) {
      if (enc_ == FieldEncoding::Spectral) out[i].L = spec_.sample(lambda[i]);
      out[i].rgb = rgb_;
      out[i].depth = 100.0f;
      out[i].opacity = 1.0f;
    }
  }
  void bounds(Point3& lo, Point3& hi) const override { lo = Point3(-1.0f); hi = Point3(1.0f); }

 private:
  Vec3 rgb_;
  FieldEncoding enc_;
  RGBIlluminantSpectrum spec_;
};

CameraSpec smallCamera() {
  CameraSpec c;
  c.width = 24;
  c.height = 16;
  return c;
}
}  // namespace

// An emitter of RGB (1,1,1) as a D65 illuminant spectrum renders as Rec.709 white (1,1,1):
// the spectral path (wavelength sampling, CMFs, XYZ -> RGB) closes on itself.
TEST(Renderer, SpectralFurnaceReturnsInputWhite) {
  UniformField f({1, 1, 1}, FieldEncoding::Spectral);
  RenderSettings s;
  s.spp = 64;
  s.progress = false;
  RenderResult r = renderField(f, ThinLensCamera(smallCamera()), s);
  double sum[3] = {0, 0, 0};
  for (int y = 0; y < r.image.height; ++y)
    for (int x = 0; x < r.image.width; ++x)
      for (int c = 0; c < 3; ++c) sum[c] += r.image.at(x, y, c);
  double n = double(r.image.width) * r.image.height;
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(sum[c] / n, 1.0, 0.01) << "channel " << c;
  EXPECT_FLOAT_EQ(r.image.at(3, 3, 3), 1.0f);   // opacity
  EXPECT_FLOAT_EQ(r.image.at(3, 3, 4), 100.0f);  // depth
}

TEST(Renderer, RGBFieldPassesThroughExactly) {
  UniformField f({0.2f, 0.5f, 0.7f}, FieldEncoding::RGB);
  RenderSettings s;
  s.spp = 2;
  s.progress = false;
  RenderResult r = renderField(f, ThinLensCamera(smallCamera()), s);
  EXPECT_NEAR(r.image.at(5, 5, 0), 0.2f, 1e-6f);
  EXPECT_NEAR(r.image.at(5, 5, 1), 0.5f, 1e-6f);
  EXPECT_NEAR(r.image.at(5, 5, 2), 0.7f, 1e-6f);
}

TEST(Renderer, BitIdenticalOnOneAndTwoThreads) {
  UniformField f({0.9f, 0.3f, 0.1f}, FieldEncoding::Spectral);
  RenderSettings s;
  s.spp = 4;
  s.progress = false;
  auto run = [&](int threads) {
    ThreadLimit limit(threads);
    return renderField(f, ThinLensCamera(smallCamera()), s).image.data;
  };
  EXPECT_EQ(run(1), run(2));
}

TEST(Camera, CentreRayAlongViewAndFieldOfView) {
  CameraSpec c = smallCamera();
  c.width = 100;
  c.height = 50;
  c.hfovDeg = 90.0f;
  ThinLensCamera cam(c);
  Ray centre = cam.generateRay(50.0f, 25.0f, {0.5f, 0.5f});
  EXPECT_NEAR(centre.d.z, -1.0f, 1e-6f);
  Ray right = cam.generateRay(100.0f, 25.0f, {0.5f, 0.5f});  // right edge: 45 degrees
  EXPECT_NEAR(right.d.x, std::sqrt(0.5f), 1e-5f);
  Ray top = cam.generateRay(50.0f, 0.0f, {0.5f, 0.5f});  // row 0 is the top
  EXPECT_GT(top.d.y, 0.0f);
}

// A thin lens focuses: every lens sample for one film point meets at the focus distance.
TEST(Camera, ThinLensRaysConvergeOnPlaneOfFocus) {
  CameraSpec c = smallCamera();
  c.apertureMm = 10.0f;
  c.focusDistanceMm = 200.0f;
  ThinLensCamera cam(c);
  Point3 p0;
  for (int i = 0; i < 5; ++i) {
    Ray r = cam.generateRay(7.3f, 4.1f, {0.1f + 0.2f * i, 0.9f - 0.15f * i});
    float t = (150.0f - r.o.z) / r.d.z;  // eye at z = 350 looking at -z: focus plane z = 150
    Point3 p = r.at(t);
    if (i == 0) p0 = p;
    EXPECT_NEAR(glm::length(p - p0), 0.0f, 1e-3f);
  }
}
