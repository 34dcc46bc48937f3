// radiance/: a trained model's EIA queries and the Lego training run, registered only when
// their inputs are given.
#include <cstdio>
#include <memory>

#include "bench/bench_context.h"
#include "dataset/dataset.h"
#include "field_files/field_factory.h"
#include "fitting/dataset_fit.h"
#include "radiance/trainer.h"
#include "synthesis/eia_synthesis.h"

namespace inim::bench {

namespace {

struct Results {
  double querySeconds = -1, queries = 0, hitFraction = 0;
  double trainSeconds = -1, psnr = 0, ssim = 0;
  int trainViews = 0, testViews = 0;
};
Results& results() {
  static Results r;
  return r;
}

// The model's own placement with the given values replacing its own (named as the model's).
Placement modelPlacement(const LoadedField& model, const PlacementOverride& given) {
  Placement p = model.placement.value_or(Placement{});
  if (given.scale) p.scale = *given.scale;
  if (given.rotateDeg) p.rotateDeg = *given.rotateDeg;
  if (given.translateMm) p.translateMm = *given.translateMm;
  (void)p.toDisplay();
  return p;
}

void registerEiaQuery(const RadianceBenchSettings& o) {
  LoadedField model = loadField(o.modelPath, "field_model");
  const Placement p = modelPlacement(model, o.placement);
  auto field = std::shared_ptr<Field>(std::move(model.field));
  benchmark::RegisterBenchmark("radiance/eia-query", [field, p](benchmark::State& state) {
    const Display d = loadDisplay(defaultDisplayPath());
    const EiLayout L = computeLayout(d);
    SynthesisSettings s;
    s.placement = p;
    s.progress = false;
    SynthesisResult r;
    for (auto _ : state) r = synthesizeEia(L, d.panel, *field, s);
    Results& res = results();
    res.querySeconds = r.stats.querySeconds;
    res.queries = double(r.stats.queries);
    res.hitFraction = double(r.stats.hitRays) / double(std::max<uint64_t>(1, r.stats.displayRays));
    state.counters["rays/s"] = benchmark::Counter(double(r.stats.queries), benchmark::Counter::kIsRate);
  })->Iterations(1)->UseRealTime()->Unit(benchmark::kMillisecond);
}

void registerTrainLego(const std::string& dir, int iterations) {
  benchmark::RegisterBenchmark("radiance/train-lego", [dir, iterations](benchmark::State& state) {
    DatasetOptions dop;
    dop.downscale = 4;
    const Dataset data = loadDataset(dir, dop);
    const TrainingRays rays = datasetRays(data, data.train);
    TrainConfig cfg;
    cfg.iterations = iterations;
    cfg.stageStarts = {0, iterations / 6, iterations / 2};
    cfg.boxLo = Point3(data.sceneBox.lo), cfg.boxHi = Point3(data.sceneBox.hi);
    cfg.background = Vec3(data.background);
    VoxelGrid grid;
    TrainStats st;
    for (auto _ : state) st = train(grid, rays, cfg);
    const std::vector<ViewScore> scores = evaluate(grid, data, data.test, nullptr);
    Results& res = results();
    res.trainSeconds = st.seconds;
    res.trainViews = int(data.train.size());
    res.testViews = int(scores.size());
    for (const auto& s : scores) res.psnr += s.psnr / double(scores.size()), res.ssim += s.ssim / double(scores.size());
    state.counters["heldout_psnr_db"] = res.psnr;
  })->Iterations(1)->UseRealTime()->Unit(benchmark::kMillisecond);
}

}  // namespace

void registerRadianceBenchmarks(const RadianceBenchSettings& settings) {
  if (!settings.modelPath.empty()) registerEiaQuery(settings);
  if (!settings.legoDir.empty()) registerTrainLego(settings.legoDir, settings.legoIterations);
}

void printRadianceBenchResults() {
  const Results& r = results();
  if (r.querySeconds >= 0)
    std::printf("\nradiance/eia-query: %.0f queries of the default display through the model in %.2f s (%.2f M/s; "
                "%.1f%% of the display rays see the field); target <= 30 s\n",
                r.queries, r.querySeconds, r.queries / r.querySeconds * 1e-6, 100.0 * r.hitFraction);
  if (r.trainSeconds >= 0)
    std::printf("\nradiance/train-lego: %d training views at 200 x 200, %.1f s of training; held-out PSNR %.2f dB, "
                "SSIM %.4f over %d views; target >= 28 dB within 600 s\n",
                r.trainViews, r.trainSeconds, r.psnr, r.ssim, r.testViews);
}

}  // namespace inim::bench
