#pragma once
// Gaussian splats as a Field, ray traced as in 3DGRT (Moenne-Loccoz et al., "3D Gaussian Ray
// Tracing", SIGGRAPH Asia 2024), so any ray can be asked (the display's rays are not one
// pinhole camera's, which a rasteriser would need):
//
//  - every Gaussian is bounded by its ellipsoid at the response cut-off, where
//    opacity * exp(-1/2 d^2) = 1/255 (d^2 = 2 ln(255 opacity)); Gaussians that never reach
//    1/255 are left out. The ellipsoids are Embree user primitives (boxes in the BVH, the exact
//    test in the intersect callback);
//  - a Gaussian's sample along a ray is its point of maximum response: in the Gaussian's unit
//    frame (o' = S^-1 R^T (o - mu), d' = S^-1 R^T d) at t = -(o'.d')/|d'|^2, with
//    d^2 = |d' x o'|^2 / |d'|^2, alpha = min(0.99, opacity exp(-1/2 d^2)). The ray meets the
//    cut-off ellipsoid exactly when alpha >= 1/255, so that is the intersect test;
//  - hits are gathered in a k-buffer of the k nearest (by t, then index: deterministic),
//    composited front to back, and the ray is traced again from the last one until the
//    transmittance T < 1e-3 or no hits remain;
//  - colour is the SH along the ray direction + 0.5, clamped at 0 (splats/splat_sh.h),
//    composited in the trainer's encoded space and linearised with the sRGB EOTF at the end
//    (declared lin_rec709, see splats/gaussians.h); the background is black (rgb is the
//    composited colour, opacity = 1 - T says how much of it is splats);
//  - depth is the composited expected depth sum(w_i t_i) / sum(w_i), w_i = T_i alpha_i, of the
//    max-response distances (infinity when nothing was hit);
//  - a Gaussian whose max-response point lies outside [tNear, tFar] is not counted.
//
// The field frame is the display frame: the Gaussians stay in their file's frame and rays are
// moved into it by `frame` (display = scale * R * splat + translate; splats/splat_placement.h
// gives the default). Queries are deterministic and TBB-parallel over the batch.
//
//   SplatField f(loadGaussians("scene.ply"), defaultSplatFrame(g));
//   f.query(rays, {}, out, seed);
#include <embree3/rtcore.h>

#include <memory>
#include <vector>

#include "field/field.h"
#include "splats/gaussians.h"

namespace inim {

// A similarity transform from the splats' frame into the field (display) frame.
struct SplatFrame {
  float scale = 1.0f;                // display mm per splat unit
  glm::mat3 rotation{1.0f};          // proper rotation
  Vec3 translate{0.0f};              // mm
  Point3 toField(const Point3& p) const { return scale * (rotation * p) + translate; }
};

struct SplatTraceSettings {
  int kBuffer = 16;                // hits gathered per trace
  float minTransmittance = 1e-3f;  // stop once T falls below
};

// A Gaussian ready for ray queries: its unit-frame map S^-1 R^T, mean and opacity.
struct SplatPrimitive {
  glm::mat3 toUnit;
  Vec3 mean;
  float opacity;
  uint32_t index;  // into the Gaussians
  Vec3 lo, hi;     // box of the cut-off ellipsoid
};

// The max-response sample of `p` along o + t d (splat frame): t and alpha (before the 1/255
// test, after the 0.99 cap). In double: trained Gaussians are up to ~1000:1 thin, and the
// cross product of nearly parallel o' and d' loses float's digits (2e-4 in alpha seen).
inline void splatMaxResponse(const SplatPrimitive& p, const Vec3& o, const Vec3& d, float* t, float* alpha) {
  const glm::dmat3 M(p.toUnit);
  const glm::dvec3 ou = M * (glm::dvec3(o) - glm::dvec3(p.mean)), du = M * glm::dvec3(d);
  const double dd = glm::dot(du, du);
  *t = float(-glm::dot(ou, du) / dd);
  const glm::dvec3 c = glm::cross(du, ou);
  *alpha = float(std::min(0.99, double(p.opacity) * std::exp(-0.5 * glm::dot(c, c) / dd)));
}
constexpr float kSplatMinAlpha = 1.0f / 255.0f;

// One ray's answer in the splat frame, before linearisation.
struct SplatTraceResult {
  Vec3 encodedRgb{0.0f};  // composited SH colour, trainer's encoded space
  float depth = kInfinity;  // splat-frame units
  float opacity = 0.0f;
  int evaluated = 0;  // Gaussians composited
  int traces = 0;     // Embree traversals
};

class SplatField : public Field {
 public:
  explicit SplatField(Gaussians g, const SplatFrame& frame = {}, const SplatTraceSettings& settings = {});
  ~SplatField() override;
  SplatField(const SplatField&) = delete;
  SplatField& operator=(const SplatField&) = delete;

  FieldEncoding encoding() const override { return FieldEncoding::RGB; }
  std::string colorSpace() const override { return "lin_rec709"; }
  // Deterministic: `seed` and `lambda` are unused.
  void query(std::span<const FieldRay> rays, std::span<const SampledWavelengths> lambda,
             std::span<FieldSample> out, uint64_t seed) const override;
  // Bounds of the cut-off ellipsoids, in the field frame.
  void bounds(Point3& lo, Point3& hi) const override;

  // One ray in the splat frame (d unit), t in [tNear, tFar].
  SplatTraceResult trace(const Vec3& o, const Vec3& d, float tNear, float tFar) const;
  // One query ray (field frame) as query() traces it; depth in splat units.
  SplatTraceResult traceFieldRay(const FieldRay& ray) const;
  // The Embree scene of the cut-off boxes (for benchmarks of the bare traversal).
  RTCScene embreeScene() const { return scene_; }

  const Gaussians& gaussians() const { return g_; }
  const std::vector<SplatPrimitive>& primitives() const { return prims_; }
  const SplatFrame& frame() const { return frame_; }

 private:
  void buildScene();

  Gaussians g_;
  SplatFrame frame_;
  SplatTraceSettings settings_;
  std::vector<SplatPrimitive> prims_;  // Gaussians that reach 1/255
  RTCDevice device_ = nullptr;
  RTCScene scene_ = nullptr;
};

// Builds the primitive of Gaussian i (toUnit = S^-1 R^T) with the box of its ellipsoid where
// opacity exp(-1/2 d^2) = 1/255; false when its opacity never reaches 1/255.
bool makeSplatPrimitive(const Gaussians& g, size_t i, SplatPrimitive* out);

}  // namespace inim
