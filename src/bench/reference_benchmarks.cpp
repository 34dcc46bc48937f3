// reference/: the reference view of the default scene (inim reference, the comparison of every
// Fig. 11 pose) by each light-sampling choice of the direct integrator and sample count, timed,
// against a converged reference rendered once (the reference cache) to give each its error and
// its efficiency, error x time: relative MSE x seconds, so that a faster estimator that is
// noisier is not faster.
#include <cmath>
#include <cstdio>
#include <map>

#include "bench/bench_context.h"
#include "camera/camera_config.h"
#include "core/format.h"
#include "display_view/reference_cache.h"
#include "display_view/view_camera.h"
#include "field_files/field_factory.h"

namespace inim::bench {

namespace {

constexpr int kWidth = 324;           // the view's width (the quadrature and budget tests' size)
constexpr int kConvergedSpp = 1024;   // the converged reference: RMSE ~1/11 of 8 spp's
constexpr int kSpps[] = {2, 8, 32};

struct Estimator {
  const char* name;
  LightSelection selection;
};
constexpr Estimator kEstimators[] = {{"all-lights", LightSelection::All}, {"one-light", LightSelection::Power}};

struct ReferenceContext {
  CameraDescription desc;
  std::unique_ptr<CameraModel> camera;
  std::map<int, std::unique_ptr<AnalyticScene>> scenes;  // by estimator
  Image converged;
  bool convergedCached = false;
  double convergedSeconds = 0.0;
  std::map<std::pair<int, int>, Image> images;  // by (estimator, spp)
  std::map<std::pair<int, int>, double> seconds;
};
ReferenceContext& referenceContext() {
  static ReferenceContext c;
  return c;
}

ReferenceContext& builtReferenceContext() {
  ReferenceContext& c = referenceContext();
  if (c.camera) return c;
  c.desc = loadCameraDescription(defaultCameraPath());
  DisplayPose pose;
  pose.distanceMm = c.desc.distanceMm;
  ViewCameraOptions co;
  co.width = kWidth;
  c.camera = makeViewCamera(c.desc, pose, co);
  for (size_t e = 0; e < std::size(kEstimators); ++e) {
    std::unique_ptr<AnalyticScene> scene = AnalyticScene::load(defaultScenePath());
    IntegratorSettings is = scene->integratorSettings();
    is.lightSelection = kEstimators[e].selection;
    scene->setIntegratorSettings(is);
    c.scenes[int(e)] = std::move(scene);
  }
  // The default scene's own estimator, many samples, another seed; once per build of inim.
  ReferenceSettings rs;
  rs.spp = kConvergedSpp;
  rs.seed = 7;
  rs.progress = false;
  rs.fieldKey = fieldContentKey(defaultScenePath());
  ViewResult r = renderReference(*c.scenes[0], Transform(), *c.camera, c.desc.sensor, rs);
  c.converged = std::move(r.image);
  c.convergedCached = r.cached;
  c.convergedSeconds = r.stats.seconds;
  return c;
}

// Args: estimator, spp.
void benchReference(benchmark::State& state) {
  ReferenceContext& c = builtReferenceContext();
  const int e = int(state.range(0));
  ReferenceSettings rs;
  rs.spp = int(state.range(1));
  rs.progress = false;
  for (auto _ : state) {
    ViewResult r = renderReference(*c.scenes[e], Transform(), *c.camera, c.desc.sensor, rs);
    c.seconds[{e, rs.spp}] = r.stats.seconds;
    c.images[{e, rs.spp}] = std::move(r.image);
  }
}

}  // namespace

void registerReferenceBenchmarks() {
  for (size_t e = 0; e < std::size(kEstimators); ++e)
    for (int spp : kSpps)
      benchmark::RegisterBenchmark(("reference/" + std::string(kEstimators[e].name) + "/spp:" + std::to_string(spp)).c_str(),
                                   benchReference)
          ->Args({int64_t(e), spp})->Iterations(1)->UseRealTime()->Unit(benchmark::kMillisecond);
}

void printReferenceBenchResults() {
  ReferenceContext& c = referenceContext();
  if (c.images.empty()) return;
  std::printf("\nreference (default scene, real lens, 0 deg) at %d x %d against %d spp (%s): time, RMSE relative to "
              "the mean, efficiency = relative MSE x seconds (lower is better) and its ratio to all-lights at 8 spp\n",
              c.converged.width, c.converged.height, kConvergedSpp,
              c.convergedCached ? "from the reference cache" : (formatNumber(c.convergedSeconds, "%.1f") + " s to render").c_str());
  std::printf("  %-11s %6s %10s %10s %14s %12s\n", "estimator", "spp", "seconds", "RMSE", "MSE x s", "vs default");
  const auto base = c.images.find({0, 8});
  const double baseCost = base == c.images.end() ? NAN
                                                 : std::pow(relativeRmse(base->second, c.converged), 2) * c.seconds[{0, 8}];
  for (const auto& [key, img] : c.images) {
    const double rmse = relativeRmse(img, c.converged), cost = rmse * rmse * c.seconds[key];
    std::printf("  %-11s %6d %10.2f %9.2f%% %14.3e %11.2fx\n", kEstimators[key.first].name, key.second, c.seconds[key],
                100.0 * rmse, cost, baseCost / cost);
  }
}

}  // namespace inim::bench
