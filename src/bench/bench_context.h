#pragma once
// What the benchmarks of src/bench share: the default scene with one camera ray per pixel of
// the default render, and the default display with its orthoscopic query rays. Built on first
// use, so that a filtered run builds only what it needs.
#include <benchmark/benchmark.h>

#include <memory>
#include <vector>

#include "bench/benchmarks.h"
#include "core/image.h"
#include "display/display.h"
#include "display/ei_layout.h"
#include "field/field.h"
#include "camera/fov_camera.h"
#include "scene/analytic_scene.h"

namespace inim::bench {

struct SceneContext {
  std::unique_ptr<AnalyticScene> scene;
  FovCameraSettings camera;
  std::vector<FieldRay> rays;  // one camera ray per pixel of the render
  std::vector<SampledWavelengths> lambdas;
};
SceneContext& sceneContext();

struct EiaContext {
  Display display;
  EiLayout layout;
  std::vector<FieldRay> queries;
  std::vector<SampledWavelengths> lambdas;
};
EiaContext& eiaContext();

// The "rays/s" counter: `rays` per iteration.
void setRaysPerSecond(benchmark::State& state, size_t rays);

// The default display's EIA of `field` (auto exposure, 1 sample per display ray): rays/s and
// peak memory.
void eiaLoop(benchmark::State& state, const Field& field);

// Registers `fn` under `name` timed in real time (ms): one iteration when `once` (whole runs),
// else for at least `minTime` seconds.
void registerTimed(const char* name, void (*fn)(benchmark::State&), bool once, double minTime);

// Peak resident memory of the process so far, MiB.
double peakRssMiB();

// RMSE of `a` against `ref` over the pixels where the reference has signal, relative to the
// reference's mean there (view_benchmarks.cpp).
double relativeRmse(const Image& a, const Image& ref);

// Each family registers its benchmarks; the print functions add their tables after the run.
void registerQueryBenchmarks(double minTime);
void registerViewBenchmarks(const ViewBenchSettings& settings);
void printViewBenchResults();
void registerRadianceBenchmarks(const RadianceBenchSettings& settings);
void printRadianceBenchResults();
void registerFig11Benchmarks();
void registerSplatBenchmarks(double minTime);
void registerSceneBenchmarks();
void registerMlaBenchmarks(double minTime);
void registerLensBenchmarks(double minTime);
void registerPlaceBenchmarks(const RadianceBenchSettings& model, double minTime);
void printFig11BenchResults();
void registerReferenceBenchmarks();
void printReferenceBenchResults();
void registerSweepBenchmarks();
void printSweepBenchResults();

}  // namespace inim::bench
