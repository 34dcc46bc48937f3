#include "scene/lights.h"

#include <algorithm>
#include <cmath>

#include "core/sampling.h"
#include "scene/light_sample_inl.h"

namespace inim {

using namespace lightdetail;

void LightSet::build(std::vector<Light> lights, const SceneGeometry* geometry,
                     LightSelection selection) {
  lights_ = std::move(lights);
  geometry_ = geometry;
  selection_ = selection;
  env_ = -1;
  float radius = geometry ? 0.5f * geometry->extent() : 1.0f;
  for (size_t i = 0; i < lights_.size(); ++i) {
    Light& l = lights_[i];
    if (l.type == LightType::Area) {
      l.shapePtr = &geometry->shape(l.shape);
      l.pdfAreaConst = float(1.0 / l.shapePtr->area);
    }
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

int LightSet::select(float u, float* pmf) const { return selectInline(u, pmf); }

float LightSet::pmf(int light) const {
  if (light < 0 || light >= int(pmf_.size())) return 0.0f;
  if (selection_ == LightSelection::All) return lights_[light].power > 0.0f ? 1.0f : 0.0f;
  return pmf_[light];
}

bool LightSet::sample(int li, const LightSampleContext& ctx, Vec2 u, float u3,
                      const SampledWavelengths& lambda, LightSample* ls) const {
  return sampleInline(li, ctx, u, u3, lambda, ls);
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
