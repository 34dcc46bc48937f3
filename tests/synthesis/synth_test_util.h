#pragma once
// Shared helpers for the synthesis tests: analytic mock fields (so these tests do not depend on
// the Embree scene), the point-image check, and the fixtures (small displays, scratch files).
#include <cmath>
#include <cstdio>
#include <limits>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/error.h"
#include "core/image.h"
#include "core/rng.h"
#include "display/display.h"
#include "display/ei_layout.h"
#include "field/field.h"
#include "fixtures.h"
#include "rays/pinhole_rays.h"
#include "spectral/spectrum.h"
#include "synthesis/eia_synthesis.h"

namespace synth_test {

using namespace inim;
using namespace fixtures;

// Spheres in the field frame. Each is either a uniform emitter or a "soft" one whose radiance
// falls off as exp(-b^2 / sigma^2) with the ray's distance b from the centre (so the ray
// closest to the centre is the brightest). Spectral (emits `spectrum`, or rgb's luminance as a
// flat spectrum) or RGB (lin_rec709).
struct MockSphere {
  Vec3d c{0.0};
  double r = 1.0;
  Vec3 rgb{1.0f};
  double sigma = 0.0;  // 0: uniform
  SpectrumPtr spectrum;
};

class MockField final : public Field {
 public:
  MockField(std::vector<MockSphere> spheres, FieldEncoding enc, float noise = 0.0f)
      : spheres_(std::move(spheres)), enc_(enc), noise_(noise) {}
  FieldEncoding encoding() const override { return enc_; }
  void query(std::span<const FieldRay> rays, std::span<const SampledWavelengths> lambda,
             std::span<FieldSample> out, uint64_t seed) const override {
    for (size_t i = 0; i < rays.size(); ++i) {
      const FieldRay& fr = rays[i];
      FieldSample fs;
      Vec3d o(fr.o), d(fr.d);
      double best = std::numeric_limits<double>::infinity();
      const MockSphere* hit = nullptr;
      double bestB = 0.0;
      for (const MockSphere& s : spheres_) {
        Vec3d oc = s.c - o;
        double tca = glm::dot(oc, d);
        double b2 = glm::dot(oc, oc) - tca * tca;
        if (b2 > s.r * s.r) continue;
        double th = std::sqrt(s.r * s.r - b2);
        double t0 = tca - th, t1 = tca + th;
        double t = t0 >= fr.tNear ? t0 : t1 >= fr.tNear ? t1 : -1.0;
        if (t < fr.tNear || t > fr.tFar || t >= best) continue;
        best = t;
        hit = &s;
        bestB = std::sqrt(std::max(0.0, b2));
      }
      if (hit) {
        float w = hit->sigma > 0.0 ? float(std::exp(-bestB * bestB / (hit->sigma * hit->sigma))) : 1.0f;
        if (noise_ > 0.0f) w *= 1.0f + noise_ * (Rng::forSample(seed, fr.id, fr.sample).uniform() - 0.5f);
        if (enc_ == FieldEncoding::Spectral) {
          if (hit->spectrum)
            fs.L = hit->spectrum->sample(lambda[i]) * w;
          else
            fs.L = SampledSpectrum(w * (0.2126f * hit->rgb.x + 0.7152f * hit->rgb.y + 0.0722f * hit->rgb.z));
        } else {
          fs.rgb = hit->rgb * w;
        }
        fs.depth = float(best);
        fs.opacity = 1.0f;
      }
      out[i] = fs;
    }
  }
  void bounds(Point3& lo, Point3& hi) const override {
    Vec3d a(std::numeric_limits<double>::infinity()), b(-std::numeric_limits<double>::infinity());
    for (const auto& s : spheres_) {
      a = glm::min(a, s.c - Vec3d(s.r));
      b = glm::max(b, s.c + Vec3d(s.r));
    }
    if (spheres_.empty()) a = b = Vec3d(0.0);
    lo = Point3(a);
    hi = Point3(b);
  }

 private:
  std::vector<MockSphere> spheres_;
  FieldEncoding enc_;
  float noise_;
};

// Ray-sphere entry distance (display frame, double), or nullopt.
inline std::optional<double> sphereEntry(const Vec3d& o, const Vec3d& d, const Vec3d& c, double r) {
  Vec3d oc = c - o;
  double tca = glm::dot(oc, d), b2 = glm::dot(oc, oc) - tca * tca;
  if (b2 > r * r) return std::nullopt;
  double t0 = tca - std::sqrt(r * r - b2);
  if (t0 < 0.0) return std::nullopt;
  return t0;
}

// A spectrum defined by a lambda.
template <class F>
class FnSpectrum final : public Spectrum {
 public:
  explicit FnSpectrum(F f, float maxV = 1.0f) : f_(f), max_(maxV) {}
  float operator()(float l) const override { return f_(l); }
  float maxValue() const override { return max_; }

 private:
  F f_;
  float max_;
};
template <class F>
SpectrumPtr makeSpectrum(F f) {
  return std::make_shared<FnSpectrum<F>>(f);
}

// Synthesis settings without the progress bar.
inline SynthesisSettings quietSettings(double vcpMm = SynthesisSettings{}.vcpMm) {
  SynthesisSettings s;
  s.progress = false;
  s.autoExposure = false;  // exposure 1: the tests predict drive values
  s.vcpMm = vcpMm;
  return s;
}

inline float brightness(const Image& img, int x, int y) { return img.at(x, y, 0) + img.at(x, y, 1) + img.at(x, y, 2); }

// A point's image in a panel-sized EIA: for every EI that pinhole geometry says sees `p`,
// whether the EI's brightest pixel is the predicted one (ties: the first in ray order).
// Returns {EIs that see p, EIs whose brightest pixel is the predicted one}.
inline std::pair<int, int> brightestMatchesPrediction(const EiLayout& L, const Image& eia, const Point3d& p) {
  int seen = 0, ok = 0;
  for (int k = 0; k < L.eiCols; ++k)
    for (int l = 0; l < L.eiRows; ++l) {
      const auto pred = predictPixelForPoint(L, k, l, p);
      if (!pred) continue;
      ++seen;
      float best = -1.0f;
      PixelCoord arg{};
      L.forEachRayOfEi(k, l, [&](int64_t, int col, int row, int, int) {
        const float b = brightness(eia, L.panelCol0 + col, L.panelRow0 + row);
        if (b > best) best = b, arg = {col, row};
      });
      if (best > 0.0f && arg == eiaPixel(L, *pred)) ++ok;
    }
  return {seen, ok};
}

// A small soft emitter at (0.23, -0.17, z), its sigma a pixel's footprint at z (so the ray
// nearest its centre is the brightest), synthesized with the VCP at 50 mm: in every EI that
// sees it (12 at least), the brightest pixel is the one pinhole geometry predicts (in 95 % of
// them at least), and its rays are real for z > 0, virtual for z < 0. Returns the synthesis.
inline SynthesisResult expectPointImageOnPredictedPixels(const EiLayout& L, const Panel& panel, double z) {
  const Point3d p(0.23, -0.17, z);
  const double footprint = L.pixelMm * std::abs(z) / L.gapMm;
  const MockField f({{p, 3.0 * footprint, Vec3(0.3f), footprint, nullptr}}, FieldEncoding::RGB);
  SynthesisResult r = synthesizeEia(L, panel, f, quietSettings(50.0));
  const auto [seen, ok] = brightestMatchesPrediction(L, r.eia, p);
  EXPECT_GE(seen, 12) << "too few EIs see the point";
  EXPECT_GE(ok, int(std::ceil(0.95 * seen))) << ok << " of " << seen << " EIs at z = " << z;
  EXPECT_EQ(r.stats.realRays > 0, z > 0);
  EXPECT_EQ(r.stats.virtualRays > 0, z < 0);
  std::printf("  %sz = %+.0f mm (%s): brightest pixel = predicted in %d of %d EIs\n", L.isHex() ? "hex, " : "", z,
              layoutName(L.kind), ok, seen);
  return r;
}

}  // namespace synth_test
