#pragma once
// Sampling helpers: warps from [0,1)^2 to common domains, with their pdfs.
#include <algorithm>
#include <cmath>

#include "core/geometry.h"

namespace inim {

// Shirley–Chiu concentric map: square -> unit disk, area preserving.
inline Vec2 sampleUniformDiskConcentric(Vec2 u) {
  Vec2 o = 2.0f * u - Vec2(1.0f);
  if (o.x == 0.0f && o.y == 0.0f) return Vec2(0.0f);
  float r, theta;
  if (std::abs(o.x) > std::abs(o.y)) {
    r = o.x;
    theta = (kPi / 4.0f) * (o.y / o.x);
  } else {
    r = o.y;
    theta = (kPi / 2.0f) - (kPi / 4.0f) * (o.x / o.y);
  }
  return r * Vec2(std::cos(theta), std::sin(theta));
}

// Cosine-weighted hemisphere about +z; pdf = cos(theta)/pi.
inline Vec3 sampleCosineHemisphere(Vec2 u) {
  Vec2 d = sampleUniformDiskConcentric(u);
  float z = std::sqrt(std::max(0.0f, 1.0f - d.x * d.x - d.y * d.y));
  return {d.x, d.y, z};
}
inline float cosineHemispherePdf(float cosTheta) { return std::max(cosTheta, 0.0f) * kInvPi; }

// Uniform direction on the unit sphere; pdf = 1/(4 pi).
inline Vec3 sampleUniformSphere(Vec2 u) {
  float z = 1.0f - 2.0f * u.x;
  float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
  float phi = 2.0f * kPi * u.y;
  return {r * std::cos(phi), r * std::sin(phi), z};
}
constexpr float kUniformSpherePdf = 1.0f / (4.0f * kPi);

// Uniform direction in a cone about +z with cos(half-angle) = cosMax; pdf = 1/(2 pi (1-cosMax)).
inline Vec3 sampleUniformCone(Vec2 u, float cosMax) {
  float cosTheta = (1.0f - u.x) + u.x * cosMax;
  float sinTheta = std::sqrt(std::max(0.0f, 1.0f - cosTheta * cosTheta));
  float phi = u.y * 2.0f * kPi;
  return {std::cos(phi) * sinTheta, std::sin(phi) * sinTheta, cosTheta};
}
inline float uniformConePdf(float cosMax) { return 1.0f / (2.0f * kPi * (1.0f - cosMax)); }

// Uniform point on a triangle, as barycentrics (b0, b1); b2 = 1 - b0 - b1.
inline Vec2 sampleUniformTriangle(Vec2 u) {
  float su = std::sqrt(u.x);
  return {1.0f - su, u.y * su};
}

// Veach's power heuristic (beta = 2) for multiple importance sampling.
inline float powerHeuristic(float fPdf, float gPdf) {
  float f = fPdf * fPdf, g = gPdf * gPdf;
  if (std::isinf(f)) return 1.0f;
  return (f + g) > 0.0f ? f / (f + g) : 0.0f;
}

// Stratified sample i of n in [0,1), jittered by u.
inline float stratified1D(int i, int n, float u) { return std::min((i + u) / n, 0x1.fffffep-1f); }

}  // namespace inim
