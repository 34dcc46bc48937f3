#pragma once
// A tiny analytic scene for training tests: three constant-coloured spheres in [-1,1]^3 on a
// white background, ray traced exactly (with 4x4 supersampling for smooth edges) from
// cameras on a sphere around it.
#include <cmath>
#include <cstdlib>
#include <vector>

#include "core/error.h"
#include "radiance/trainer.h"

namespace synthetic {

using inim::Point3;
using inim::Vec3;

struct Sphere {
  Point3 c;
  float r;
  Vec3 rgb;
};

inline const std::vector<Sphere>& spheres() {
  static const std::vector<Sphere> s{{Point3(-0.35f, -0.1f, 0.0f), 0.4f, Vec3(0.85f, 0.2f, 0.15f)},
                                     {Point3(0.4f, 0.15f, 0.1f), 0.35f, Vec3(0.15f, 0.7f, 0.3f)},
                                     {Point3(0.0f, 0.2f, -0.45f), 0.3f, Vec3(0.2f, 0.3f, 0.85f)}};
  return s;
}

// Colour seen along o + t d (d unit): the nearest sphere's colour, else white.
inline Vec3 trace(const Point3& o, const Vec3& d) {
  float best = inim::kInfinity;
  Vec3 rgb(1.0f);
  for (const Sphere& s : spheres()) {
    Vec3 oc = o - s.c;
    float b = glm::dot(oc, d), c = glm::dot(oc, oc) - s.r * s.r, disc = b * b - c;
    if (disc < 0.0f) continue;
    float t = -b - std::sqrt(disc);
    if (t > 0.0f && t < best) best = t, rgb = s.rgb;
  }
  return rgb;
}

struct Camera {
  Point3 eye;
  Vec3 right, up, back;  // OpenGL camera-to-world axes
  float focal;           // pixels
};

inline Camera camera(int index, int count, int size) {
  // Fibonacci points on the sphere, radius 3, looking at the origin.
  float golden = 2.39996323f;
  float z = 1.0f - 2.0f * (float(index) + 0.5f) / float(count);
  float r = std::sqrt(1.0f - z * z), phi = golden * float(index);
  Point3 eye = 3.0f * Vec3(r * std::cos(phi), r * std::sin(phi), z);
  Vec3 back = glm::normalize(eye);
  Vec3 worldUp = std::abs(back.z) > 0.9f ? Vec3(0, 1, 0) : Vec3(0, 0, 1);
  Vec3 right = glm::normalize(glm::cross(worldUp, back));
  Vec3 up = glm::cross(back, right);
  return {eye, right, up, back, 0.5f * float(size) / std::tan(0.5f * inim::radians(45.0f))};
}

inline Vec3 pixelDir(const Camera& c, float px, float py, int size) {
  Vec3 d((px - 0.5f * size) / c.focal, -(py - 0.5f * size) / c.focal, -1.0f);
  return glm::normalize(d.x * c.right + d.y * c.up + d.z * c.back);
}

// Rays and exact (supersampled) colours of views [first, first + n) of `count`.
inline void render(int index, int count, int size, inim::TrainingRays& rays) {
  Camera c = camera(index, count, size);
  for (int j = 0; j < size; ++j)
    for (int i = 0; i < size; ++i) {
      Vec3 sum(0.0f);
      for (int sy = 0; sy < 4; ++sy)
        for (int sx = 0; sx < 4; ++sx)
          sum += trace(c.eye, pixelDir(c, float(i) + (sx + 0.5f) / 4.0f, float(j) + (sy + 0.5f) / 4.0f, size));
      rays.origin.push_back(c.eye);
      rays.dir.push_back(pixelDir(c, float(i) + 0.5f, float(j) + 0.5f, size));
      rays.rgb.push_back(sum / 16.0f);
    }
}

// The CI training config: small, seconds on 2 cores. INIM_SYN_TV overrides the TV weights
// (for experiments; the test itself runs with the defaults).
inline inim::TrainConfig config() {
  inim::TrainConfig cfg;
  cfg.boxLo = Point3(-1.0f);
  cfg.boxHi = Point3(1.0f);
  cfg.iterations = 1200;
  cfg.batchSize = 2048;
  cfg.resolutions = {32, 64};
  cfg.stageStarts = {0, 300};
  cfg.shDegree = 0;
  cfg.progressInterval = 100;
  cfg.seed = 3;
  if (const char* tv = std::getenv("INIM_SYN_TV")) cfg.tvDensity = std::atof(tv), cfg.tvColor = 0.1f * cfg.tvDensity;
  return cfg;
}

}  // namespace synthetic
