#pragma once
// Helpers for the scene tests: scenes from inline JSON, single-ray queries, MC averages.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "core/error.h"
#include "core/output_file.h"
#include "scene/analytic_scene.h"

namespace inim::test {

// A per-test scratch folder (removed by the OS's tmp cleaning; tests overwrite files).
inline std::string scratchDir() {
  auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  std::filesystem::path p = std::filesystem::temp_directory_path() / "inim_scene_tests" /
                            (std::string(info->test_suite_name()) + "." + info->name());
  std::filesystem::create_directories(p);
  return p.string();
}

inline std::string writeFile(const std::string& dir, const std::string& name,
                             const std::string& text) {
  std::string path = dir + "/" + name;
  std::ofstream(path) << text;
  return path;
}

inline std::unique_ptr<AnalyticScene> sceneFromString(
    const std::string& json, const std::string& file = "inline-test-scene.json",
    const std::optional<IntegratorSettings>& s = std::nullopt) {
  return AnalyticScene::fromJson(Json::parse(json), file, s);
}

// Wavelengths with the hero at `hero` nm (the others follow at +117.5 nm, wrapped).
inline SampledWavelengths wavelengthsAt(float hero) {
  return SampledWavelengths::sampleUniform((hero - kLambdaMin) / (kLambdaMax - kLambdaMin));
}

inline FieldSample queryRay(const AnalyticScene& s, Point3 o, Vec3 d, const SampledWavelengths& l,
                            uint64_t id = 0, uint32_t sample = 0, uint64_t seed = 1) {
  FieldRay r;
  r.o = o;
  r.d = glm::normalize(d);
  r.id = id;
  r.sample = sample;
  return s.queryOne(r, l, seed);
}

struct MeanEstimate {
  double mean[kNumWavelengths] = {0, 0, 0, 0};
  double stderr_[kNumWavelengths] = {0, 0, 0, 0};
};

// Mean and standard error of n samples of the same ray.
inline MeanEstimate averageRay(const AnalyticScene& s, Point3 o, Vec3 d, const SampledWavelengths& l,
                               int n, uint64_t seed = 7) {
  double sum[kNumWavelengths] = {0, 0, 0, 0}, sum2[kNumWavelengths] = {0, 0, 0, 0};
  for (int k = 0; k < n; ++k) {
    FieldSample f = queryRay(s, o, d, l, 12345, uint32_t(k), seed);
    for (int i = 0; i < kNumWavelengths; ++i) {
      sum[i] += f.L[i];
      sum2[i] += double(f.L[i]) * f.L[i];
    }
  }
  MeanEstimate e;
  for (int i = 0; i < kNumWavelengths; ++i) {
    e.mean[i] = sum[i] / n;
    double var = std::max(0.0, sum2[i] / n - e.mean[i] * e.mean[i]);
    e.stderr_[i] = std::sqrt(var / n);
  }
  return e;
}

inline bool allFinite(const SampledSpectrum& s) { return !s.hasNaN(); }

}  // namespace inim::test
