#include "scene/materials.h"

#include <algorithm>
#include <cmath>

namespace inim {

float fresnelDielectric(float cosThetaI, float eta) {
  cosThetaI = std::clamp(cosThetaI, -1.0f, 1.0f);
  if (cosThetaI < 0.0f) {
    eta = 1.0f / eta;
    cosThetaI = -cosThetaI;
  }
  float sin2ThetaI = 1.0f - cosThetaI * cosThetaI;
  float sin2ThetaT = sin2ThetaI / (eta * eta);
  if (sin2ThetaT >= 1.0f) return 1.0f;  // total internal reflection
  float cosThetaT = std::sqrt(std::max(0.0f, 1.0f - sin2ThetaT));
  float rParl = (eta * cosThetaI - cosThetaT) / (eta * cosThetaI + cosThetaT);
  float rPerp = (cosThetaI - eta * cosThetaT) / (cosThetaI + eta * cosThetaT);
  return 0.5f * (rParl * rParl + rPerp * rPerp);
}

float fresnelConductor(float cosThetaI, float eta, float k) {
  // Real-valued closed form of the complex Fresnel equations (outside index 1).
  double c = std::clamp(double(cosThetaI), 0.0, 1.0);
  double cos2 = c * c, sin2 = 1.0 - cos2;
  double eta2 = double(eta) * eta, k2 = double(k) * k;
  double t0 = eta2 - k2 - sin2;
  double a2plusb2 = std::sqrt(t0 * t0 + 4.0 * eta2 * k2);
  double t1 = a2plusb2 + cos2;
  double a = std::sqrt(std::max(0.0, 0.5 * (a2plusb2 + t0)));
  double t2 = 2.0 * c * a;
  double Rs = (t1 - t2) / (t1 + t2);
  double t3 = cos2 * a2plusb2 + sin2 * sin2;
  double t4 = t2 * sin2;
  double Rp = Rs * (t3 - t4) / (t3 + t4);
  return float(0.5 * (Rp + Rs));
}

bool refract(const Vec3& wi, Vec3 n, float eta, float* etap, Vec3* wt) {
  float cosThetaI = glm::dot(n, wi);
  if (cosThetaI < 0.0f) {
    eta = 1.0f / eta;
    cosThetaI = -cosThetaI;
    n = -n;
  }
  float sin2ThetaI = std::max(0.0f, 1.0f - cosThetaI * cosThetaI);
  float sin2ThetaT = sin2ThetaI / (eta * eta);
  if (sin2ThetaT >= 1.0f) return false;
  float cosThetaT = std::sqrt(1.0f - sin2ThetaT);
  *wt = -wi / eta + (cosThetaI / eta - cosThetaT) * n;
  *wt = glm::normalize(*wt);
  if (etap) *etap = eta;
  return true;
}

void thinSheet(float R, float tau, float* Rtot, float* Ttot) {
  float den = 1.0f - R * R * tau * tau;
  if (!(den > 0.0f)) {  // R == 1 and tau == 1: a perfect mirror
    *Rtot = 1.0f;
    *Ttot = 0.0f;
    return;
  }
  float oneMinusR2 = (1.0f - R) * (1.0f - R);
  *Rtot = R + oneMinusR2 * tau * tau * R / den;
  *Ttot = oneMinusR2 * tau / den;
}

namespace ggx {

static inline float cos2Theta(const Vec3& w) { return w.z * w.z; }
static inline float tan2Theta(const Vec3& w) {
  float c2 = cos2Theta(w);
  return std::max(0.0f, 1.0f - c2) / c2;
}

float D(const Vec3& wm, float alpha) {
  float t2 = tan2Theta(wm);
  if (std::isinf(t2) || std::isnan(t2)) return 0.0f;
  float c4 = cos2Theta(wm) * cos2Theta(wm);
  if (c4 < 1e-16f) return 0.0f;
  float e = t2 / (alpha * alpha);
  return 1.0f / (kPi * alpha * alpha * c4 * (1.0f + e) * (1.0f + e));
}
float lambda(const Vec3& w, float alpha) {
  float t2 = tan2Theta(w);
  if (std::isinf(t2) || std::isnan(t2)) return 0.0f;
  return (std::sqrt(1.0f + alpha * alpha * t2) - 1.0f) * 0.5f;
}
float G1(const Vec3& w, float alpha) { return 1.0f / (1.0f + lambda(w, alpha)); }
float G(const Vec3& wo, const Vec3& wi, float alpha) {
  return 1.0f / (1.0f + lambda(wo, alpha) + lambda(wi, alpha));
}
Vec3 sampleWm(const Vec3& wo, Vec2 u, float alpha) {
  Vec3 wh = glm::normalize(Vec3(alpha * wo.x, alpha * wo.y, wo.z));
  if (wh.z < 0.0f) wh = -wh;
  Vec3 t1 = (wh.z < 0.99999f) ? glm::normalize(glm::cross(Vec3(0, 0, 1), wh)) : Vec3(1, 0, 0);
  Vec3 t2 = glm::cross(wh, t1);
  // Uniform disk, warped toward the visible half.
  float r = std::sqrt(u.x), phi = 2.0f * kPi * u.y;
  Vec2 p(r * std::cos(phi), r * std::sin(phi));
  float h = std::sqrt(std::max(0.0f, 1.0f - p.x * p.x));
  float s = 0.5f * (1.0f + wh.z);
  p.y = (1.0f - s) * h + s * p.y;
  float pz = std::sqrt(std::max(0.0f, 1.0f - p.x * p.x - p.y * p.y));
  Vec3 nh = p.x * t1 + p.y * t2 + pz * wh;
  return glm::normalize(Vec3(alpha * nh.x, alpha * nh.y, std::max(1e-6f, nh.z)));
}
float pdfReflect(const Vec3& wo, const Vec3& wi, float alpha) {
  if (wo.z <= 0.0f || wi.z <= 0.0f) return 0.0f;
  Vec3 wm = wo + wi;
  float l = glm::length(wm);
  if (l == 0.0f) return 0.0f;
  wm /= l;
  float dwm = G1(wo, alpha) / wo.z * D(wm, alpha) * std::abs(glm::dot(wo, wm));
  return dwm / (4.0f * std::abs(glm::dot(wo, wm)));
}

}  // namespace ggx

SampledSpectrum conductorFresnel(const Material& m, float cosThetaI,
                                 const SampledWavelengths& lambda) {
  SampledSpectrum F;
  for (int i = 0; i < kNumWavelengths; ++i)
    F[i] = fresnelConductor(cosThetaI, m.eta(lambda[i]), m.k(lambda[i]));
  return F;
}

SampledSpectrum roughConductorF(const Material& m, const Vec3& wo, const Vec3& wi,
                                const SampledWavelengths& lambda) {
  if (wo.z <= 0.0f || wi.z <= 0.0f) return SampledSpectrum(0.0f);
  Vec3 wm = wo + wi;
  float l = glm::length(wm);
  if (l == 0.0f) return SampledSpectrum(0.0f);
  wm /= l;
  float d = ggx::D(wm, m.alpha) * ggx::G(wo, wi, m.alpha) / (4.0f * wo.z * wi.z);
  return conductorFresnel(m, std::abs(glm::dot(wo, wm)), lambda) * d;
}

}  // namespace inim
