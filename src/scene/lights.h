#pragma once
// Light sources: point and spot lights (delta positions), area lights (any emissive shape,
// including the rectangular "rect" lights of the scene file) and a uniform environment.
// Lights are plain structs dispatched by a switch (no virtual calls on the hot path); one
// light is chosen per shading point from a power-proportional (or uniform) distribution.
#include <algorithm>
#include <string>
#include <vector>

#include "core/geometry.h"
#include "scene/materials.h"
#include "scene/scene_geometry.h"
#include "spectral/baked_spectrum.h"

#ifndef INIM_ALWAYS_INLINE
#define INIM_ALWAYS_INLINE __attribute__((always_inline))
#endif

namespace inim {

enum class LightType { Point, Spot, Area, Environment };

struct Light {
  LightType type = LightType::Point;
  std::string name;
  BakedSpectrum spectrum;  // intensity (point, spot) or radiance (area, environment)
  Point3 position{0.0f};   // point, spot
  Frame frame = Frame::fromZ(Vec3(0, 0, -1));  // spot: frame.z is the axis
  float cosFalloffStart = 1.0f, cosFalloffEnd = 0.0f;  // spot
  int shape = -1;           // area
  const Shape* shapePtr = nullptr;  // area: &geometry.shape(shape), set by build()
  bool twoSided = false;    // area
  float power = 0.0f;       // for light selection
  float pdfAreaConst = 0.0f;  // area: float(1 / shape area), set by build()
};

// Where light is sampled from: a point and the unit normal of the hemisphere that matters
// (shading normal on the side of the outgoing direction).
struct LightSampleContext {
  Point3 p{0.0f};
  Vec3 n{0.0f};
};

struct LightSample {
  SampledSpectrum L;       // incident radiance (or intensity / r^2 for delta lights)
  Vec3 wi{0.0f};           // unit direction toward the light
  Point3 pLight{0.0f};     // sampled point (finite lights)
  Vec3 nLight{0.0f};       // its normal (area lights)
  float pdf = 0.0f;        // solid-angle pdf (1 for delta lights), without selection pmf
  bool delta = false;
  bool infinite = false;
};

enum class LightSelection { Power, Uniform, All };

class LightSet {
 public:
  LightSet() = default;
  // Area lights refer to shapes of `geometry` and take their emission from `materials`.
  void build(std::vector<Light> lights, const SceneGeometry* geometry, LightSelection selection);
  void setSelection(LightSelection s);

  const std::vector<Light>& lights() const { return lights_; }
  bool empty() const { return lights_.empty(); }
  int environment() const { return env_; }
  LightSelection selection() const { return selection_; }
  // Picks a light; -1 if none can be picked.
  int select(float u, float* pmf) const;
  // select(), inlined: a linear scan (same index as the binary search) for few lights.
  INIM_ALWAYS_INLINE int selectInline(float u, float* pmf) const {
    const int n = int(cdf_.size());
    if (n == 0 || cdf_[n - 1] <= 0.0f) return -1;
    int i = 0;
    if (n <= 16) {
      while (i < n && !(u < cdf_[i])) ++i;  // first i with cdf[i] > u (upper_bound)
    } else {
      i = int(std::upper_bound(cdf_.begin(), cdf_.end(), u) - cdf_.begin());
    }
    i = std::min(i, n - 1);
    while (i > 0 && pmf_[i] == 0.0f) --i;  // u landed on a zero-width step
    *pmf = pmf_[i];
    return pmf_[i] > 0.0f ? i : -1;
  }
  float pmf(int light) const;

  bool sample(int light, const LightSampleContext& ctx, Vec2 u, float u3,
              const SampledWavelengths& lambda, LightSample* ls) const;
  // sample(), inlined into the hot path (defined in scene/light_sample_inl.h).
  bool sampleInline(int light, const LightSampleContext& ctx, Vec2 u, float u3,
                    const SampledWavelengths& lambda, LightSample* ls) const;
  // Solid-angle pdf that sample() would give for the direction from ctx to the point hit
  // h on area light `light` (without the selection pmf).
  float pdfArea(int light, const LightSampleContext& ctx, const Hit& h) const;
  float pdfEnvironment(const LightSampleContext& ctx, const Vec3& wi) const;
  SampledSpectrum environmentLe(const SampledWavelengths& lambda) const {
    return env_ >= 0 ? lights_[env_].spectrum.sample(lambda) : SampledSpectrum(0.0f);
  }

 private:
  void buildDistribution();
  std::vector<Light> lights_;
  const SceneGeometry* geometry_ = nullptr;
  LightSelection selection_ = LightSelection::Power;
  std::vector<float> pmf_, cdf_;
  int env_ = -1;
};

}  // namespace inim
