#pragma once
// Test fields and cameras for the field renderer: a field whose every answer depends on every
// bit of the ray, its id, sample and wavelengths (so that any change in how rays are made
// changes the image), a pinhole that bends each wavelength its own way, and an image hash.
#include <cmath>
#include <cstdint>
#include <cstring>

#include "camera/camera_model.h"
#include "core/image.h"
#include "field/field.h"

namespace inim::render_test {

class ProbeField final : public Field {
 public:
  // `terminateEveryThird`: rays with id % 3 == 0 answer a packet with its secondary
  // wavelengths terminated (L[1..3] = 0), as a dispersive surface would.
  explicit ProbeField(FieldEncoding enc, bool terminateEveryThird = false) : enc_(enc), terminate_(terminateEveryThird) {}
  FieldEncoding encoding() const override { return enc_; }
  void query(std::span<const FieldRay> rays, std::span<const SampledWavelengths> lambda, std::span<FieldSample> out,
             uint64_t seed) const override {
    for (size_t i = 0; i < rays.size(); ++i) {
      const FieldRay& r = rays[i];
      const float s = r.o.x * 0.013f + r.o.y * 0.007f + r.o.z * 0.001f + r.d.x * 31.0f + r.d.y * 17.0f +
                      r.d.z * 3.0f + float(r.sample) * 0.01f + float(r.id % 97) * 0.001f + float(seed % 7);
      FieldSample& f = out[i];
      f = FieldSample{};
      if (enc_ == FieldEncoding::Spectral)
        for (int k = 0; k < kNumWavelengths; ++k) f.L[k] = 1.0f + std::sin(s + 0.01f * lambda[i][k]);
      f.rgb = Vec3(1.0f + std::sin(s), 1.0f + std::cos(s), 1.0f + std::sin(2.0f * s));
      f.opacity = r.d.x > 0.0f ? 1.0f : (r.d.y > 0.0f ? 0.25f : 0.0f);
      f.depth = r.d.y > 0.0f ? 100.0f + r.o.x + s : kInfinity;
      f.secondaryTerminated = terminate_ && (r.id % 3 == 0);
      if (f.secondaryTerminated) f.L[1] = f.L[2] = f.L[3] = 0.0f;
    }
  }
  void bounds(Point3& lo, Point3& hi) const override {
    lo = Point3(-1.0f);
    hi = Point3(1.0f);
  }

 private:
  FieldEncoding enc_;
  bool terminate_;
};

// A pinhole at image distance 20 mm whose rays tilt by 1e-4 mm of sensor offset per nm away
// from 550 nm; the weight varies across the image.
class PrismPinhole final : public CameraModel {
 public:
  PrismPinhole(const SensorGeometry& s, const ViewingPose& p) : CameraModel(s, p) {}
  float generateRay(Vec2 pixel, Vec2, float lambdaNm, Ray& out) const override {
    const Vec2d o = uprightSensorOffset(pixel);
    setRay(pose_.eye, toWorldDir(Vec3d(o.x + 1e-4 * (lambdaNm - 550.0), o.y, -20.0)), out);
    return 0.5f + 0.001f * pixel.x;
  }
  bool isDispersive() const override { return true; }
  CameraModelKind kind() const override { return CameraModelKind::Pinhole; }
  std::string describe() const override { return "prism pinhole"; }
  double horizontalFovDeg() const override { return 30.0; }
};

// FNV-1a over the bits of the pixel values.
inline uint64_t hashImage(const Image& img) {
  uint64_t h = 1469598103934665603ull;
  for (float v : img.data) {
    uint32_t b;
    std::memcpy(&b, &v, 4);
    for (int i = 0; i < 4; ++i) {
      h ^= (b >> (8 * i)) & 0xFFu;
      h *= 1099511628211ull;
    }
  }
  return h;
}

}  // namespace inim::render_test
