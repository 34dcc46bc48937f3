#pragma once
// Light transport for analytic scenes, sized to what the scene needs.
//
//  direct  (default) spectral direct lighting: next-event estimation with shadow rays at the
//          first non-specular surface, plus chains of specular reflection/refraction (mirror
//          metals, glass, thin filters) up to max_depth. Emitters seen directly or through
//          specular chains count fully.
//  path    unidirectional path tracing with next-event estimation and multiple importance
//          sampling (power heuristic), Russian roulette from rr_depth on.
//
// Thin filters (thin dielectrics) are transparent to shadow rays with their transmittance
// (coloured shadows); thick dielectrics block shadow rays (no caustics by NEE).
#include "core/geometry.h"
#include "scene/path_random.h"
#include "scene/lights.h"
#include "scene/materials.h"
#include "scene/scene_geometry.h"

namespace inim {

struct IntegratorSettings {
  enum class Type { Direct, Path };
  Type type = Type::Direct;
  int maxDepth = 8;        // scattering events (specular ones too) after the first hit
  LightSelection lightSelection = LightSelection::Power;
  int rrDepth = 3;         // path: Russian roulette from this depth on; < 0 disables it
  bool filterShadows = true;  // thin filters pass coloured light to shadow rays
};

// A shadow ray whose test was deferred, so that a batch of queries can trace all of them
// with one Embree stream call (AnalyticScene::query).
struct ShadowRequest {
  Ray ray;                  // t in (0, ray.tMax); d unnormalised toward finite lights
  bool infinite = false;
  Vec3 dir{0.0f};           // unit direction toward the light
  Point3 target{0.0f};      // end point (finite lights)
  SampledSpectrum contribution;  // radiance to add when unoccluded (times filter transmittance)
  bool active = false;
};

class Integrator {
 public:
  Integrator(const SceneGeometry& geometry, const std::vector<Material>& materials,
             const LightSet& lights, const IntegratorSettings& settings)
      : geom_(geometry), materials_(materials), lights_(lights), settings_(settings) {}

  // Radiance arriving along -ray.d at ray.o from the interval (ray.tMin, ray.tMax); ray.d
  // must be unit length. `lambda` may have its secondary wavelengths terminated (dispersion).
  // *hitT is the distance to the first surface (kInfinity on a miss).
  SampledSpectrum Li(const Ray& ray, SampledWavelengths& lambda, PathRandom& rng, float* hitT) const;
  // Li with the first intersection already done (`firstHit` is used iff didHit). If
  // `deferred` is non-null (kMaxDeferredShadows requests, all inactive), the direct integrator's
  // shadow rays are not traced but returned there (one, or one per light with
  // LightSelection::All and at most kMaxDeferredShadows lights); the caller adds each active
  // one's contribution when its ray is unoccluded (times filterTransmittance). Results equal
  // Li's exactly: same arithmetic, same random numbers.
  static constexpr int kMaxDeferredShadows = 4;
  SampledSpectrum LiFromHit(const Ray& ray, bool didHit, const Hit& firstHit,
                            SampledWavelengths& lambda, PathRandom& rng, float* hitT,
                            ShadowRequest* deferred) const;

  // Ray-mask bits of the shapes that block shadow rays.
  uint32_t shadowMask() const {
    return settings_.filterShadows ? kMaskOpaque : (kMaskOpaque | kMaskFilter);
  }
  // Product of the thin filters' transmittances along an unoccluded shadow ray (1 if the
  // scene has none or filter shadows are off).
  SampledSpectrum filterTransmittance(const ShadowRequest& r, const SampledWavelengths& lambda) const;
  // 0 if the shadow ray is blocked, else filterTransmittance.
  SampledSpectrum shadowTransmittance(const ShadowRequest& r, const SampledWavelengths& lambda) const;

  const IntegratorSettings& settings() const { return settings_; }

 private:
  struct Vertex;     // a shading point (integrator.cpp)
  struct PathState;  // radiance, throughput and MIS state along a path (integrator.cpp)
  // Light sampled from a non-specular vertex (NEE), MIS-weighted in path mode.
  // (or deferred: see LiFromHit; `beta` is the path throughput to fold into it).
  SampledSpectrum directLight(const Vertex& v, const SampledWavelengths& lambda, PathRandom& rng,
                              bool mis, const SampledSpectrum& beta,
                              ShadowRequest* deferred) const;
  SampledSpectrum directLightAll(const Vertex& v, const SampledWavelengths& lambda, PathRandom& rng,
                                 bool mis, const SampledSpectrum& beta, ShadowRequest* deferred) const;
  // LiFromHit for one integrator type (integrator.cpp).
  template <bool kPath>
  SampledSpectrum liImpl(const Ray& ray0, bool didHit, const Hit& firstHit,
                         SampledWavelengths& lambda, PathRandom& rng, float* hitT,
                         ShadowRequest* deferred) const;
  // The steps of liImpl at one vertex (integrator.cpp).
  void addEscaped(PathState& st, const Ray& ray, const SampledWavelengths& lambda, bool path) const;
  void addEmitted(PathState& st, const Hit& h, const Shape& s, const Material& m, bool front,
                  const SampledWavelengths& lambda, bool path) const;
  bool sampleBsdf(const Vertex& v, const SampledWavelengths& lambda, PathRandom& rng, PathState& st, Vec3& wi) const;
  void scatterSpecular(const Vertex& v, SampledWavelengths& lambda, PathRandom& rng, PathState& st, Vec3& wi) const;
  SampledSpectrum sampleOneLight(int light, float pmf, const Vertex& v,
                                 const SampledWavelengths& lambda, const LightUniforms& q, bool mis,
                                 const SampledSpectrum& beta, ShadowRequest* deferred) const;
  // BSDF value times |cos theta_i|, and its sampling pdf, at a non-specular vertex.
  SampledSpectrum evalBsdf(const Vertex& v, const Vec3& wi, const SampledWavelengths& lambda,
                           float* pdf) const;
  // A thin sheet's transmittance (and reflectance in *R) at incidence cosTheta.
  SampledSpectrum thinTransmittance(const Material& m, float cosTheta,
                                    const SampledWavelengths& lambda, SampledSpectrum* R) const;

  const SceneGeometry& geom_;
  const std::vector<Material>& materials_;
  const LightSet& lights_;
  IntegratorSettings settings_;
};

}  // namespace inim
