#include "scene/analytic_scene.h"

#include <cmath>
#include <stdexcept>

namespace inim {

std::unique_ptr<AnalyticScene> AnalyticScene::load(const std::string& path,
                                                   const std::optional<IntegratorSettings>& s) {
  auto scene = std::make_unique<AnalyticScene>(loadSceneDescription(path));
  if (s) scene->setIntegratorSettings(*s);
  return scene;
}

std::unique_ptr<AnalyticScene> AnalyticScene::fromJson(const Json& j, const std::string& file,
                                                       const std::optional<IntegratorSettings>& s) {
  auto scene = std::make_unique<AnalyticScene>(parseSceneDescription(j, file));
  if (s) scene->setIntegratorSettings(*s);
  return scene;
}

AnalyticScene::AnalyticScene(SceneDescription d)
    : file_(d.file), materials_(std::move(d.materials)), objects_(std::move(d.objects)),
      dropped_(d.droppedTriangles) {
  geometry_ = std::make_unique<SceneGeometry>(std::move(d.shapes));
  lights_.build(std::move(d.lights), geometry_.get(), d.integrator.lightSelection);
  integrator_ = std::make_unique<Integrator>(*geometry_, materials_, lights_, d.integrator);
}

void AnalyticScene::setIntegratorSettings(const IntegratorSettings& s) {
  if (s.maxDepth < 0) throw std::invalid_argument("IntegratorSettings::maxDepth must be >= 0");
  lights_.setSelection(s.lightSelection);
  integrator_ = std::make_unique<Integrator>(*geometry_, materials_, lights_, s);
}

void AnalyticScene::bounds(Point3& lo, Point3& hi) const {
  // The objects of the scene file (rect lights are placed around the content, not part of it).
  lo = Point3(kInfinity);
  hi = Point3(-kInfinity);
  for (const SceneObject& o : objects_) {
    lo = glm::min(lo, geometry_->shape(o.shape).lo);
    hi = glm::max(hi, geometry_->shape(o.shape).hi);
  }
  if (objects_.empty()) lo = hi = Point3(0.0f);
}

const SceneObject* AnalyticScene::objectById(int id) const {
  for (const SceneObject& o : objects_)
    if (o.id == id) return &o;
  return nullptr;
}

namespace {

// The caller's wavelengths are const: a terminated packet is reported as 4x the hero
// radiance in L[0] (see analytic_scene.h). Non-finite values never leave the scene.
inline FieldSample finish(SampledSpectrum L, float t, const SampledWavelengths& lambda,
                          const SampledWavelengths& lambda0) {
  if (lambda.secondaryTerminated() && !lambda0.secondaryTerminated()) {
    L[0] *= float(kNumWavelengths);
    for (int i = 1; i < kNumWavelengths; ++i) L[i] = 0.0f;
  }
  for (int i = 0; i < kNumWavelengths; ++i)
    if (!std::isfinite(L[i])) L[i] = 0.0f;
  FieldSample out;
  out.L = L;
  out.secondaryTerminated = lambda.secondaryTerminated() && !lambda0.secondaryTerminated();
  out.depth = t;
  out.opacity = std::isfinite(t) ? 1.0f : 0.0f;
  return out;
}

// The query ray as traced: unit direction, tNear >= 0. False for a degenerate ray.
inline bool toRay(const FieldRay& fr, Ray* ray) {
  float len2 = glm::dot(fr.d, fr.d);
  if (!(len2 > 0.0f) || !std::isfinite(len2) || !isFinite(fr.o)) return false;
  // The interface promises unit directions; renormalise only what is off by > 1e-6.
  Vec3 d = std::abs(len2 - 1.0f) <= 2e-6f ? fr.d : fr.d * (1.0f / std::sqrt(len2));
  *ray = Ray{fr.o, d, std::max(0.0f, fr.tNear), fr.tFar};
  return true;
}

// SceneGeometry::toEmbree, inlined.
inline void fillEmbreeRay(const Ray& ray, uint32_t mask, RTCRay* r) {
  r->org_x = ray.o.x;
  r->org_y = ray.o.y;
  r->org_z = ray.o.z;
  r->dir_x = ray.d.x;
  r->dir_y = ray.d.y;
  r->dir_z = ray.d.z;
  r->tnear = ray.tMin;
  r->tfar = ray.tMax;
  r->time = 0.0f;
  r->mask = mask;
  r->id = 0;
  r->flags = 0;
}

}  // namespace

FieldSample AnalyticScene::queryOne(const FieldRay& fr, const SampledWavelengths& lambda0,
                                    uint64_t seed) const {
  Ray ray;
  if (!toRay(fr, &ray)) {
    FieldSample out;
    out.L = SampledSpectrum(0.0f);
    return out;  // a degenerate ray sees nothing
  }
  PathRandom rng(seed, fr.id, fr.sample, fr.stratumIndex());
  SampledWavelengths lambda = lambda0;
  float t;
  SampledSpectrum L = integrator_->Li(ray, lambda, rng, &t);
  return finish(L, t, lambda, lambda0);
}

// A small wavefront per chunk of rays: the primary rays go to Embree as one coherent
// stream (rtcIntersect1M), each ray is shaded, and the direct integrator's shadow rays go
// as a second stream (rtcOccluded1M). Every ray computes exactly what queryOne computes
// (same arithmetic, same random numbers), so batching never changes an answer.
void AnalyticScene::query(std::span<const FieldRay> rays, std::span<const SampledWavelengths> lambda,
                          std::span<FieldSample> out, uint64_t seed) const {
  if (lambda.size() != rays.size() || out.size() != rays.size())
    throw std::invalid_argument("AnalyticScene::query: rays, lambda and out must have the same size");
  constexpr size_t kChunk = 64;
  RTCRayHit rh[kChunk];
  constexpr int kShadows = Integrator::kMaxDeferredShadows;
  RTCRay shadow[kChunk * kShadows];
  Ray ray[kChunk];
  bool valid[kChunk];
  SampledWavelengths lam[kChunk];
  SampledSpectrum L[kChunk];
  float t[kChunk];
  ShadowRequest req[kChunk * kShadows];  // ray i's at i * kShadows + light
  uint32_t shadowOf[kChunk * kShadows];
  RTCScene scene = geometry_->embreeScene();
  // Query rays of a batch are usually neighbours (pixels, samples of a pixel): coherent.
  // Shadow rays go to different lights and points on them: measured faster as incoherent.
  RTCIntersectContext ctx, shadowCtx;
  rtcInitIntersectContext(&ctx);
  ctx.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
  rtcInitIntersectContext(&shadowCtx);
  shadowCtx.flags = RTC_INTERSECT_CONTEXT_FLAG_INCOHERENT;
  const uint32_t shadowMask = integrator_->shadowMask();
  const bool filterShadows = integrator_->settings().filterShadows && geometry_->hasFilters();

  for (size_t base = 0; base < rays.size(); base += kChunk) {
    const size_t n = std::min(kChunk, rays.size() - base);
    for (size_t i = 0; i < n; ++i) {
      Ray r;
      valid[i] = toRay(rays[base + i], &r);
      // A degenerate ray gets an empty interval: Embree reports no hit for it.
      if (!valid[i]) r = Ray{Point3(0.0f), Vec3(0, 0, 1), 1.0f, 0.0f};
      ray[i] = r;
      fillEmbreeRay(r, kMaskAll, &rh[i].ray);
      rh[i].hit.geomID = RTC_INVALID_GEOMETRY_ID;
      rh[i].hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    }
    rtcIntersect1M(scene, &ctx, rh, unsigned(n), sizeof(RTCRayHit));

    unsigned ns = 0;
    for (size_t i = 0; i < n; ++i) {
      for (int k = 0; k < kShadows; ++k) req[i * kShadows + k].active = false;
      if (!valid[i]) {
        L[i] = SampledSpectrum(0.0f);
        t[i] = kInfinity;
        lam[i] = lambda[base + i];
        continue;
      }
      const FieldRay& fr = rays[base + i];
      PathRandom rng(seed, fr.id, fr.sample, fr.stratumIndex());
      lam[i] = lambda[base + i];
      Hit h;
      bool hit = geometry_->hitFromEmbree(ray[i], rh[i], &h);
      L[i] = integrator_->LiFromHit(ray[i], hit, h, lam[i], rng, &t[i], &req[i * kShadows]);
      for (size_t r = i * kShadows; r < (i + 1) * kShadows; ++r)
        if (req[r].active) {
          fillEmbreeRay(req[r].ray, shadowMask, &shadow[ns]);
          shadowOf[ns++] = uint32_t(r);
        }
    }
    if (ns > 0) rtcOccluded1M(scene, &shadowCtx, shadow, ns, sizeof(RTCRay));
    // Summed per ray in light order, then added, as Integrator::Li does (same rounding).
    SampledSpectrum direct[kChunk];
    for (size_t i = 0; i < n; ++i) direct[i] = SampledSpectrum(0.0f);
    for (unsigned k = 0; k < ns; ++k) {
      if (shadow[k].tfar < 0.0f) continue;  // blocked
      const uint32_t r = shadowOf[k], i = r / kShadows;
      // filterTransmittance is exactly 1 unless the ray may meet a filter: skip the call.
      if (filterShadows && geometry_->mayHitFilter(req[r].ray))
        direct[i] += req[r].contribution * integrator_->filterTransmittance(req[r], lam[i]);
      else
        direct[i] += req[r].contribution;
    }
    for (size_t i = 0; i < n; ++i) L[i] += direct[i];
    for (size_t i = 0; i < n; ++i) out[base + i] = finish(L[i], t[i], lam[i], lambda[base + i]);
  }
}

}  // namespace inim
