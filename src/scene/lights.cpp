#include "scene/lights.h"

#include <algorithm>
#include <cmath>

#include "core/sampling.h"

namespace inim {

namespace {
inline float smoothStep(float x, float a, float b) {
  if (a == b) return x < a ? 0.0f : 1.0f;
  float t = std::clamp((x - a) / (b - a), 0.0f, 1.0f);
  return t * t * (3.0f - 2.0f * t);
}
inline float safeSqrt(float x) { return std::sqrt(std::max(0.0f, x)); }

// Sphere lights seen from outside are sampled by the cone they subtend (pbrt-v4), if the
// transform keeps them spheres.
inline bool useCone(const Shape& s, const Point3& p, Point3* centre, float* radius) {
  if (s.type != ShapeType::Sphere || !s.similarity) return false;
  *centre = Point3(s.T);
  *radius = float(s.radius * s.uniformScale);
  glm::vec3 d = p - *centre;
  return glm::dot(d, d) > (*radius) * (*radius) * 1.0001f;
}
}  // namespace

void LightSet::build(std::vector<Light> lights, const SceneGeometry* geometry,
                     LightSelection selection) {
  lights_ = std::move(lights);
  geometry_ = geometry;
  selection_ = selection;
  env_ = -1;
  float radius = geometry ? 0.5f * geometry->extent() : 1.0f;
  for (size_t i = 0; i < lights_.size(); ++i) {
    Light& l = lights_[i];
    if (l.type == LightType::Area) l.shapePtr = &geometry->shape(l.shape);
    float avg = l.spectrum.average();
    switch (l.type) {
      case LightType::Point: l.power = 4.0f * kPi * avg; break;
      case LightType::Spot:
        l.power = avg * 2.0f * kPi * (1.0f - 0.5f * (l.cosFalloffStart + l.cosFalloffEnd));
        break;
      case LightType::Area:
        l.power = avg * kPi * float(geometry->shape(l.shape).area) * (l.twoSided ? 2.0f : 1.0f);
        break;
      case LightType::Environment:
        env_ = int(i);
        l.power = avg * 4.0f * kPi * kPi * radius * radius;
        break;
    }
    if (!(l.power >= 0.0f) || !std::isfinite(l.power)) l.power = 0.0f;
  }
  buildDistribution();
}

void LightSet::setSelection(LightSelection s) {
  selection_ = s;
  buildDistribution();
}

void LightSet::buildDistribution() {
  size_t n = lights_.size();
  pmf_.assign(n, 0.0f);
  cdf_.assign(n, 0.0f);
  double total = 0.0;
  for (const Light& l : lights_) total += selection_ == LightSelection::Power ? l.power : (l.power > 0 ? 1.0 : 0.0);
  if (total <= 0.0) return;
  double acc = 0.0;
  for (size_t i = 0; i < n; ++i) {
    double w = selection_ == LightSelection::Power ? lights_[i].power : (lights_[i].power > 0 ? 1.0 : 0.0);
    pmf_[i] = float(w / total);
    acc += w / total;
    cdf_[i] = float(acc);
  }
  cdf_.back() = 1.0f;
}

int LightSet::select(float u, float* pmf) const {
  if (cdf_.empty() || cdf_.back() <= 0.0f) return -1;
  int i = int(std::upper_bound(cdf_.begin(), cdf_.end(), u) - cdf_.begin());
  i = std::min(i, int(cdf_.size()) - 1);
  while (i > 0 && pmf_[i] == 0.0f) --i;  // u landed on a zero-width step
  *pmf = pmf_[i];
  return pmf_[i] > 0.0f ? i : -1;
}

float LightSet::pmf(int light) const {
  if (light < 0 || light >= int(pmf_.size())) return 0.0f;
  if (selection_ == LightSelection::All) return lights_[light].power > 0.0f ? 1.0f : 0.0f;
  return pmf_[light];
}

bool LightSet::sample(int li, const LightSampleContext& ctx, Vec2 u, float u3,
                      const SampledWavelengths& lambda, LightSample* ls) const {
  const Light& l = lights_[li];
  switch (l.type) {
    case LightType::Point:
    case LightType::Spot: {
      Vec3 d = l.position - ctx.p;
      float r2 = glm::dot(d, d);
      if (!(r2 > 0.0f)) return false;
      ls->wi = d * (1.0f / std::sqrt(r2));
      float scale = 1.0f;
      if (l.type == LightType::Spot) {
        float cosTheta = glm::dot(-ls->wi, l.frame.z);
        scale = smoothStep(cosTheta, l.cosFalloffEnd, l.cosFalloffStart);
        if (scale <= 0.0f) return false;
      }
      ls->L = l.spectrum.sample(lambda) * (scale / r2);
      ls->pLight = l.position;
      ls->nLight = Vec3(0.0f);
      ls->pdf = 1.0f;
      ls->delta = true;
      ls->infinite = false;
      return true;
    }
    case LightType::Environment: {
      Vec3 w;
      if (ctx.n != Vec3(0.0f)) {
        Vec3 local = sampleCosineHemisphere(u);
        w = Frame::fromZ(ctx.n).fromLocal(local);
        ls->pdf = cosineHemispherePdf(local.z);
      } else {
        w = sampleUniformSphere(u);
        ls->pdf = kUniformSpherePdf;
      }
      if (!(ls->pdf > 0.0f)) return false;
      ls->wi = glm::normalize(w);
      ls->L = l.spectrum.sample(lambda);
      ls->delta = false;
      ls->infinite = true;
      return true;
    }
    case LightType::Area: {
      const Shape& s = *l.shapePtr;
      Point3 c;
      float rad;
      if (useCone(s, ctx.p, &c, &rad)) {
        float dc = glm::length(ctx.p - c);
        float sinThetaMax = rad / dc;
        float sin2ThetaMax = sinThetaMax * sinThetaMax;
        float cosThetaMax = safeSqrt(1.0f - sin2ThetaMax);
        float oneMinusCosThetaMax = 1.0f - cosThetaMax;
        float cosTheta = (cosThetaMax - 1.0f) * u.x + 1.0f;
        float sin2Theta = 1.0f - cosTheta * cosTheta;
        if (sin2ThetaMax < 0.00068523f) {  // small cone: first-order Taylor (pbrt-v4)
          sin2Theta = sin2ThetaMax * u.x;
          cosTheta = std::sqrt(1.0f - sin2Theta);
          oneMinusCosThetaMax = sin2ThetaMax / 2.0f;
        }
        float cosAlpha = sin2Theta / sinThetaMax +
                         cosTheta * safeSqrt(1.0f - sin2Theta / sin2ThetaMax);
        float sinAlpha = safeSqrt(1.0f - cosAlpha * cosAlpha);
        float phi = u.y * 2.0f * kPi;
        Vec3 wl(sinAlpha * std::cos(phi), sinAlpha * std::sin(phi), cosAlpha);
        Frame f = Frame::fromZ(glm::normalize(c - ctx.p));
        Vec3 n = f.fromLocal(-wl);
        ls->pLight = c + rad * n;
        ls->nLight = n;
        Vec3 d = ls->pLight - ctx.p;
        float dl = glm::length(d);
        if (!(dl > 0.0f)) return false;
        ls->wi = d * (1.0f / dl);
        ls->pdf = 1.0f / (2.0f * kPi * oneMinusCosThetaMax);
      } else {
        ShapeSample ss = sampleShapeArea(s, u, u3);
        Vec3 d = ss.p - ctx.p;
        float d2 = glm::dot(d, d);
        if (!(d2 > 0.0f)) return false;
        ls->wi = d * (1.0f / std::sqrt(d2));
        float cosL = -glm::dot(ss.n, ls->wi);
        if (!l.twoSided && cosL <= 0.0f) return false;
        if (std::abs(cosL) < 1e-7f) return false;
        ls->pLight = ss.p;
        ls->nLight = ss.n;
        ls->pdf = ss.pdfArea * d2 / std::abs(cosL);
      }
      if (!l.twoSided && glm::dot(ls->nLight, ls->wi) >= 0.0f) return false;
      if (!(ls->pdf > 0.0f) || !std::isfinite(ls->pdf)) return false;
      ls->L = l.spectrum.sample(lambda);
      ls->delta = false;
      ls->infinite = false;
      return true;
    }
  }
  return false;
}

float LightSet::pdfArea(int li, const LightSampleContext& ctx, const Hit& h) const {
  const Light& l = lights_[li];
  if (l.type != LightType::Area) return 0.0f;
  const Shape& s = geometry_->shape(l.shape);
  Point3 c;
  float rad;
  if (useCone(s, ctx.p, &c, &rad)) {
    float dc = glm::length(ctx.p - c);
    float sin2ThetaMax = (rad / dc) * (rad / dc);
    float cosThetaMax = safeSqrt(1.0f - sin2ThetaMax);
    float oneMinusCosThetaMax = 1.0f - cosThetaMax;
    if (sin2ThetaMax < 0.00068523f) oneMinusCosThetaMax = sin2ThetaMax / 2.0f;
    return 1.0f / (2.0f * kPi * oneMinusCosThetaMax);
  }
  Vec3 d = h.p - ctx.p;
  float d2 = glm::dot(d, d);
  if (!(d2 > 0.0f)) return 0.0f;
  float cosL = std::abs(glm::dot(h.ng, d)) / std::sqrt(d2);
  if (cosL < 1e-7f) return 0.0f;
  return shapePdfArea(s, h) * d2 / cosL;
}

float LightSet::pdfEnvironment(const LightSampleContext& ctx, const Vec3& wi) const {
  if (env_ < 0) return 0.0f;
  if (ctx.n != Vec3(0.0f)) return cosineHemispherePdf(glm::dot(ctx.n, wi));
  return kUniformSpherePdf;
}

}  // namespace inim
