#include "scene/integrator.h"

#include <algorithm>
#include <cmath>

#include "core/sampling.h"
#include "scene/light_sample_inl.h"

namespace inim {

struct Integrator::Vertex {
  const Hit* h;
  const Material* m;
  Vec3 wo;   // unit, toward where the light goes
  Vec3 ng;   // geometric normal on wo's side
  Vec3 ns;   // shading normal on wo's side
  SampledSpectrum albedo;  // diffuse reflectance at the hit
};

SampledSpectrum Integrator::thinTransmittance(const Material& m, float cosTheta,
                                              const SampledWavelengths& lambda,
                                              SampledSpectrum* R) const {
  SampledSpectrum T;
  cosTheta = std::clamp(cosTheta, 0.0f, 1.0f);
  const bool clear = m.negLogTau.isConstant() && m.negLogTau(550.0f) <= 0.0f;
  const bool constN = !m.dispersive;
  float n0 = m.n(lambda[0]);
  float R0 = fresnelDielectric(cosTheta, n0);
  float invCosT0 = 1.0f;
  if (!clear) {
    // The internal path grows as 1/cos(theta_t) at oblique incidence.
    float sin2T = (1.0f - cosTheta * cosTheta) / (n0 * n0);
    invCosT0 = 1.0f / std::sqrt(std::max(1e-6f, 1.0f - sin2T));
  }
  for (int i = 0; i < kNumWavelengths; ++i) {
    float R1 = R0, invCosT = invCosT0;
    if (!constN && i > 0) {
      float n = m.n(lambda[i]);
      R1 = fresnelDielectric(cosTheta, n);
      float sin2T = (1.0f - cosTheta * cosTheta) / (n * n);
      invCosT = 1.0f / std::sqrt(std::max(1e-6f, 1.0f - sin2T));
    }
    float tau = clear ? 1.0f : std::exp(-m.negLogTau(lambda[i]) * invCosT);
    float Rt, Tt;
    thinSheet(R1, tau, &Rt, &Tt);
    (*R)[i] = Rt;
    T[i] = Tt;
  }
  return T;
}

SampledSpectrum Integrator::filterTransmittance(const ShadowRequest& req,
                                                const SampledWavelengths& lambda) const {
  SampledSpectrum T(1.0f);
  if (!settings_.filterShadows || !geom_.mayHitFilter(req.ray)) return T;
  Ray r = req.ray;
  for (int k = 0; k < 16; ++k) {
    Hit h;
    if (!geom_.intersectFilter(r, &h)) break;
    const Material& m = materials_[geom_.shape(h.shape).material];
    SampledSpectrum R;
    T *= thinTransmittance(m, std::abs(glm::dot(h.ng, req.dir)), lambda, &R);
    if (T.isBlack()) return T;
    Point3 o = spawnOrigin(h, req.dir);
    r = req.infinite ? Ray{o, req.dir, 0.0f, kInfinity} : Ray{o, req.target - o, 0.0f, 1.0f};
  }
  return T;
}

SampledSpectrum Integrator::shadowTransmittance(const ShadowRequest& req,
                                                const SampledWavelengths& lambda) const {
  if (geom_.occluded(req.ray, shadowMask())) return SampledSpectrum(0.0f);
  return filterTransmittance(req, lambda);
}

// evalBsdf, sampleOneLight and directLight are inlined into LiFromHit so that the light
// sample, the BSDF value and the shadow request stay in registers (copies of Vec3-packed
// structs through the stack stall on store forwarding).
INIM_ALWAYS_INLINE inline SampledSpectrum Integrator::evalBsdf(
    const Vertex& v, const Vec3& wi, const SampledWavelengths& lambda, float* pdf) const {
  *pdf = 0.0f;
  if (glm::dot(wi, v.ng) <= 0.0f) return SampledSpectrum(0.0f);  // reflection only
  float cosI = glm::dot(wi, v.ns);
  if (cosI <= 0.0f) return SampledSpectrum(0.0f);
  if (v.m->type == MaterialType::Diffuse) {
    *pdf = cosI * kInvPi;
    return v.albedo * (cosI * kInvPi);
  }
  // Rough conductor.
  Frame f = Frame::fromZ(v.ns);
  Vec3 woL = f.toLocal(v.wo), wiL = f.toLocal(wi);
  *pdf = ggx::pdfReflect(woL, wiL, v.m->alpha);
  return roughConductorF(*v.m, woL, wiL, lambda) * wiL.z;
}

INIM_ALWAYS_INLINE inline SampledSpectrum Integrator::sampleOneLight(
    int light, float pmf, const Vertex& v, const SampledWavelengths& lambda, const LightUniforms& q, bool mis,
    const SampledSpectrum& beta, ShadowRequest* deferred) const {
  LightSampleContext ctx{v.h->p, v.ns};
  LightSample ls;
  if (!lights_.sampleInline(light, ctx, q.u, q.u3, lambda, &ls)) return SampledSpectrum(0.0f);
  float bsdfPdf;
  SampledSpectrum f = evalBsdf(v, ls.wi, lambda, &bsdfPdf);
  if (f.isBlack() || ls.L.isBlack()) return SampledSpectrum(0.0f);
  // Filled in place when deferred (no copy of the request).
  ShadowRequest local;
  ShadowRequest& req = deferred ? *deferred : local;
  Point3 o = spawnOrigin(*v.h, ls.wi);
  req.infinite = ls.infinite;
  req.dir = ls.wi;
  if (ls.infinite) {
    req.ray = Ray{o, ls.wi, 0.0f, kInfinity};
  } else {
    Point3 target = ls.pLight;
    if (!ls.delta) {
      // Pull the target off the light's surface, toward the shading point.
      float e = offsetEpsilon(ls.pLight, lights_.lights()[light].shapePtr->extent);
      target += (glm::dot(ls.nLight, o - ls.pLight) >= 0.0f ? e : -e) * ls.nLight;
    }
    req.target = target;
    req.ray = Ray{o, target - o, 0.0f, 1.0f};
  }
  float w = 1.0f;
  if (mis && !ls.delta) w = powerHeuristic(pmf * ls.pdf, bsdfPdf);
  req.contribution = beta * f * ls.L * (w / (pmf * ls.pdf));
  if (deferred) {
    req.active = true;
    return SampledSpectrum(0.0f);
  }
  SampledSpectrum Tr = shadowTransmittance(req, lambda);
  if (Tr.isBlack()) return SampledSpectrum(0.0f);
  return req.contribution * Tr;
}

// LightSelection::All: every light, each with its own shadow ray, deferred when there is room
// (see LiFromHit). The lights share one point of their areas' parameter square.
SampledSpectrum Integrator::directLightAll(const Vertex& v, const SampledWavelengths& lambda,
                                           PathRandom& rng, bool mis, const SampledSpectrum& beta,
                                           ShadowRequest* deferred) const {
  SampledSpectrum sum(0.0f);
  const LightUniforms q = rng.light();
  const int n = int(lights_.lights().size());
  const bool defer = deferred && n <= kMaxDeferredShadows;
  for (int i = 0; i < n; ++i) {
    float pmf = lights_.pmf(i);
    if (pmf > 0.0f) sum += sampleOneLight(i, pmf, v, lambda, q, mis, beta, defer ? &deferred[i] : nullptr);
  }
  return sum;
}

INIM_ALWAYS_INLINE inline SampledSpectrum Integrator::directLight(
    const Vertex& v, const SampledWavelengths& lambda, PathRandom& rng, bool mis,
    const SampledSpectrum& beta, ShadowRequest* deferred) const {
  if (lights_.selection() == LightSelection::All) return directLightAll(v, lambda, rng, mis, beta, deferred);
  float pmf;
  const LightUniforms q = rng.light();
  int light = lights_.selectInline(q.select, &pmf);
  if (light < 0) return SampledSpectrum(0.0f);
  return sampleOneLight(light, pmf, v, lambda, q, mis, beta, deferred);
}

SampledSpectrum Integrator::Li(const Ray& ray, SampledWavelengths& lambda, PathRandom& rng,
                               float* hitT) const {
  Hit h;
  bool hit = geom_.intersect(ray, &h);
  return LiFromHit(ray, hit, h, lambda, rng, hitT, nullptr);
}

SampledSpectrum Integrator::LiFromHit(const Ray& ray0, bool didHit, const Hit& firstHit,
                                      SampledWavelengths& lambda, PathRandom& rng, float* hitT,
                                      ShadowRequest* deferred) const {
  if (settings_.type == IntegratorSettings::Type::Path)
    return liImpl<true>(ray0, didHit, firstHit, lambda, rng, hitT, deferred);
  return liImpl<false>(ray0, didHit, firstHit, lambda, rng, hitT, deferred);
}

// The state a path carries from vertex to vertex.
struct Integrator::PathState {
  SampledSpectrum L{0.0f}, beta{1.0f};
  bool specular = true;  // emitters seen by the query ray or through specular chains count fully
  float prevPdf = 0.0f;
  LightSampleContext prevCtx;
  const Material* medium = nullptr;  // absorbing dielectric the ray travels in
};

// The environment seen by a ray that leaves the scene: fully after a specular chain, MIS-weighted
// against light sampling after a non-specular vertex (path mode only).
INIM_ALWAYS_INLINE inline void Integrator::addEscaped(PathState& st, const Ray& ray, const SampledWavelengths& lambda,
                                                      bool path) const {
  const int env = lights_.environment();
  if (env < 0) return;
  const SampledSpectrum Le = lights_.environmentLe(lambda);
  if (st.specular) {
    st.L += st.beta * Le;
  } else if (path) {
    const float pl = lights_.pmf(env) * lights_.pdfEnvironment(st.prevCtx, ray.d);
    st.L += st.beta * Le * powerHeuristic(st.prevPdf, pl);
  }
}

// An emitter hit, weighted like addEscaped.
INIM_ALWAYS_INLINE inline void Integrator::addEmitted(PathState& st, const Hit& h, const Shape& s, const Material& m,
                                                      bool front, const SampledWavelengths& lambda, bool path) const {
  if (!m.emissive || !(m.twoSided || front)) return;
  const SampledSpectrum Le = m.Le.sample(lambda);
  if (st.specular) {
    st.L += st.beta * Le;
  } else if (path && s.light >= 0) {
    const float pl = lights_.pmf(s.light) * lights_.pdfArea(s.light, st.prevCtx, h);
    st.L += st.beta * Le * powerHeuristic(st.prevPdf, pl);
  }
}

// The next direction from a non-specular vertex (diffuse: cosine-weighted; rough conductor:
// GGX visible normals), its throughput folded into st.beta. False: the path ends.
INIM_ALWAYS_INLINE inline bool Integrator::sampleBsdf(const Vertex& v, const SampledWavelengths& lambda,
                                                      PathRandom& rng, PathState& st, Vec3& wi) const {
  const Material& m = *v.m;
  Frame f = Frame::fromZ(v.ns);
  Vec2 u(rng.uniform(), rng.uniform());
  float pdf;
  SampledSpectrum weight;
  if (m.type == MaterialType::Diffuse) {
    Vec3 wiL = sampleCosineHemisphere(u);
    pdf = cosineHemispherePdf(wiL.z);
    wi = f.fromLocal(wiL);
    weight = v.albedo;  // f cos / pdf
  } else {
    Vec3 woL = f.toLocal(v.wo);
    if (woL.z <= 0.0f) return false;
    Vec3 wm = ggx::sampleWm(woL, u, m.alpha);
    Vec3 wiL = reflect(woL, wm);
    if (wiL.z <= 0.0f) return false;
    pdf = ggx::pdfReflect(woL, wiL, m.alpha);
    if (!(pdf > 0.0f)) return false;
    wi = f.fromLocal(wiL);
    weight = roughConductorF(m, woL, wiL, lambda) * (wiL.z / pdf);
  }
  if (!(pdf > 0.0f) || glm::dot(wi, v.ng) <= 0.0f) return false;
  st.beta *= weight;
  st.specular = false;
  st.prevPdf = pdf;
  st.prevCtx = LightSampleContext{v.h->p, v.ns};
  wi = glm::normalize(wi);
  return true;
}

// The next direction from a specular vertex: a mirror, a dielectric interface (reflect or
// refract, a dispersive one keeping the hero wavelength only) or a thin sheet (reflect or pass
// straight through). A sheet that neither reflects nor transmits leaves st.beta black.
INIM_ALWAYS_INLINE inline void Integrator::scatterSpecular(const Vertex& v, SampledWavelengths& lambda,
                                                           PathRandom& rng, PathState& st, Vec3& wi) const {
  const Material& m = *v.m;
  const Hit& h = *v.h;
  const Vec3 wo = v.wo;
  switch (m.type) {
    case MaterialType::Conductor: {
      st.beta *= conductorFresnel(m, std::abs(glm::dot(v.ns, wo)), lambda);
      wi = reflect(wo, v.ns);
      st.specular = true;
      break;
    }
    case MaterialType::Dielectric: {
      // h.ns points outward: cos > 0 means the ray arrives from outside.
      float cosO = glm::dot(h.ns, wo);
      float n0 = m.n(lambda[0]);
      float R0 = fresnelDielectric(cosO, n0);
      SampledSpectrum R(R0);
      if (m.dispersive)
        for (int i = 1; i < kNumWavelengths; ++i) R[i] = fresnelDielectric(cosO, m.n(lambda[i]));
      float etap;
      Vec3 wt;
      bool canRefract = R0 < 1.0f && refract(wo, h.ns, n0, &etap, &wt);
      if (!canRefract || rng.uniform() < R0) {
        wi = reflect(wo, h.ns);
        if (canRefract) st.beta *= R / R0;  // R0 == 1 (TIR): weight R(lambda)/1
        else st.beta *= R;
      } else {
        if (m.dispersive && !lambda.secondaryTerminated()) {
          // Each wavelength refracts its own way: only the hero goes on.
          lambda.terminateSecondary();
          for (int i = 1; i < kNumWavelengths; ++i) st.beta[i] = 0.0f;
        }
        // Weight T/(1-R0) == 1 at the hero wavelength; radiance scales by 1/eta^2.
        st.beta *= 1.0f / (etap * etap);
        wi = wt;
        st.medium = (cosO > 0.0f && m.absorbing) ? &m : nullptr;
      }
      st.specular = true;
      break;
    }
    default: {  // thin dielectric sheet: reflect, or pass straight through
      SampledSpectrum R;
      SampledSpectrum T = thinTransmittance(m, std::abs(glm::dot(v.ng, wo)), lambda, &R);
      float ra = R.average(), ta = T.average();
      if (!(ra + ta > 0.0f)) {
        st.beta = SampledSpectrum(0.0f);
        break;
      }
      float pR = ra / (ra + ta);
      if (rng.uniform() < pR) {
        wi = reflect(wo, v.ng);
        st.beta *= R / pR;
        st.specular = true;
      } else {
        wi = -wo;
        st.beta *= T / (1.0f - pR);
        // With coloured shadows, light sampling already looked through the sheet, so
        // the path keeps the MIS state of its last scattering vertex.
        if (!settings_.filterShadows) st.specular = true;
      }
      break;
    }
  }
}

// One instance per integrator type, so that the direct one carries no path-tracing code
// (smaller, and its helpers are inlined once).
template <bool kPath>
SampledSpectrum Integrator::liImpl(const Ray& ray0, bool didHit, const Hit& firstHit,
                                   SampledWavelengths& lambda, PathRandom& rng, float* hitT,
                                   ShadowRequest* deferred) const {
  constexpr bool path = kPath;
  PathState st;
  // The current ray: the caller's at depth 0 (not copied), then `next`.
  const Ray* rayp = &ray0;
  Ray next;
  *hitT = kInfinity;

  Hit scratch;
  for (int depth = 0;; ++depth) {
    const bool hit = depth == 0 ? didHit : geom_.intersect(*rayp, &scratch);
    const Hit& h = depth == 0 ? firstHit : scratch;
    if (!hit) {
      addEscaped(st, *rayp, lambda, path);
      break;
    }
    if (depth == 0) *hitT = h.t;
    if (st.medium) {
      for (int i = 0; i < kNumWavelengths; ++i)
        st.beta[i] *= std::exp(-st.medium->sigma(lambda[i]) * h.t);
    }
    const Shape& s = geom_.shape(h.shape);
    const Material& m = materials_[s.material];
    Vec3 wo = -rayp->d;
    bool front = glm::dot(h.ng, wo) >= 0.0f;
    addEmitted(st, h, s, m, front, lambda, path);
    if (m.type == MaterialType::Emitter) break;
    const bool last = depth >= settings_.maxDepth;
    Vertex v{&h, &m, wo, front ? h.ng : -h.ng, front ? h.ns : -h.ns, SampledSpectrum(0.0f)};
    Vec3 wi;

    if (!m.isSpecular()) {
      if (m.type == MaterialType::Diffuse)
        v.albedo = m.reflectance.type() == TextureType::Constant
                       ? m.reflectance.constantSpectrum().sample(lambda)
                       : m.reflectance.evaluate(h.tex, lambda);
      if (!path) {  // direct lighting ends at the first non-specular surface
        st.L += directLight(v, lambda, rng, false, st.beta, deferred);
        break;
      }
      if (last) break;
      st.L += directLight(v, lambda, rng, true, st.beta, nullptr);
      if (!sampleBsdf(v, lambda, rng, st, wi)) break;
    } else {
      if (last) break;
      scatterSpecular(v, lambda, rng, st, wi);
    }
    if (st.beta.isBlack()) break;
    if (path && settings_.rrDepth >= 0 && depth >= settings_.rrDepth) {
      float q = std::max(0.0f, 1.0f - st.beta.maxValue());
      if (rng.uniform() < q) break;
      st.beta = st.beta / (1.0f - q);
    }
    next = Ray{spawnOrigin(h, wi), wi, 0.0f, kInfinity};
    rayp = &next;
  }
  return st.L;
}

}  // namespace inim
