#pragma once
// LightSet::sampleInline, the body of LightSet::sample, for the translation units of the
// per-ray hot path (lights.cpp, integrator.cpp): inlined there, the light sample stays in
// registers instead of going through memory (store-forwarding stalls on Vec3 copies).
#include <algorithm>
#include <cmath>

#include "core/sampling.h"
#include "scene/lights.h"

namespace inim {

namespace lightdetail {
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
}  // namespace lightdetail

INIM_ALWAYS_INLINE inline bool LightSet::sampleInline(int li, const LightSampleContext& ctx, Vec2 u,
                                                      float u3, const SampledWavelengths& lambda,
                                                      LightSample* ls) const {
  using namespace lightdetail;
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
        ShapeSample ss;
        if (s.parallelogram) {  // sampleShapeArea's first case, inlined
          ss.p = s.corner + u.x * s.e1 + u.y * s.e2;
          ss.n = s.pnormal;
          ss.pdfArea = l.pdfAreaConst;
        } else {
          ss = sampleShapeArea(s, u, u3);
        }
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

}  // namespace inim
