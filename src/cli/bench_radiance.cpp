#include "cli/bench_radiance.h"

#include <benchmark/benchmark.h>

#include <chrono>
#include <cstdio>
#include <memory>

#include "fitting/dataset_fit.h"
#include "cli/scene_options.h"
#include "display/display.h"
#include "display/ei_layout.h"
#include "radiance/radiance_field.h"
#include "radiance/trainer.h"
#include "synthesis/eia_synthesis.h"

namespace inim::cli {

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

}  // namespace

void addRadianceBenchOptions(CLI::App* cmd, RadianceBenchOptions& o) {
  cmd->add_option("--field-model", o.model, "Trained model (.inimrf) for radiance/eia-query");
  cmd->add_option("--field-scale", o.scale, "Its placement scale, mm per field unit (default: the model's)");
  cmd->add_option("--field-rotate-deg", o.rotate, "Its placement rotation rx,ry,rz, degrees");
  cmd->add_option("--field-translate-mm", o.translate, "Its placement translation, mm");
  cmd->add_option("--lego", o.lego, "Lego dataset folder for radiance/train-lego (e.g. ../shared/data/lego)");
  cmd->add_option("--lego-iterations", o.legoIterations, "Training iterations of radiance/train-lego")
      ->capture_default_str();
}

void registerRadianceBenchmarks(const RadianceBenchOptions& opts) {
  auto o = std::make_shared<RadianceBenchOptions>(opts);
  if (!o->model.empty()) {
    LoadedField lf = loadField(o->model, "--field-model");
    Placement p = lf.placement.value_or(Placement{});
    if (!o->scale.empty()) p.scale = parseVec3(o->scale, "--field-scale", true);
    if (!o->rotate.empty()) p.rotateDeg = parseVec3(o->rotate, "--field-rotate-deg");
    if (!o->translate.empty()) p.translateMm = parseVec3(o->translate, "--field-translate-mm");
    (void)p.toDisplay();
    auto field = std::shared_ptr<Field>(std::move(lf.field));
    benchmark::RegisterBenchmark("radiance/eia-query", [field, p](benchmark::State& state) {
      const Display d = loadDisplay(defaultDisplayPath());
      const EiLayout L = computeLayout(d);
      SynthesisSettings s;
      s.placement = p;
      s.progress = false;
      s.autoExposure = true;
      SynthesisResult r;
      for (auto _ : state) r = synthesizeEia(L, d.panel, *field, s);
      Results& res = results();
      res.querySeconds = r.stats.querySeconds;
      res.queries = double(r.stats.queries);
      res.hitFraction = double(r.stats.hitRays) / double(std::max<uint64_t>(1, r.stats.displayRays));
      state.counters["rays/s"] = benchmark::Counter(double(r.stats.queries), benchmark::Counter::kIsRate);
    })->Iterations(1)->UseRealTime()->Unit(benchmark::kMillisecond);
  }
  if (!o->lego.empty()) {
    benchmark::RegisterBenchmark("radiance/train-lego", [o](benchmark::State& state) {
      DatasetOptions dop;
      dop.downscale = 4;
      const Dataset data = loadDataset(o->lego, dop);
      const TrainingRays rays = datasetRays(data, data.train);
      TrainConfig cfg;
      cfg.iterations = o->legoIterations;
      cfg.stageStarts = {0, o->legoIterations / 6, o->legoIterations / 2};
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

}  // namespace inim::cli
