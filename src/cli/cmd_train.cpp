// inim train / inim eval: a voxel-grid radiance field (src/radiance) from a posed photo
// dataset (src/dataset), and its held-out quality. See src/radiance/trainer.h and
// src/fitting/fit_run.h.
#include <chrono>
#include <cstdio>
#include <memory>
#include <optional>
#include <string>

#include "cli/commands.h"
#include "cli/options.h"
#include "core/progress.h"
#include "fitting/fit_run.h"

namespace inim::cli {

namespace {

// The dataset options write DatasetOptions directly; the background is parsed when given.
struct DataArgs {
  std::string data;
  DatasetOptions options;
  std::optional<std::string> background;
};

void addDataOptions(CLI::App* cmd, DataArgs& a) {
  cmd->add_option("--data", a.data,
                  "Dataset: a folder with transforms.json / transforms_train.json (Blender, Nerfstudio, instant-ngp) "
                  "or a Middlebury *_par.txt, or the file itself")
      ->required();
  cmd->add_option("--downscale", a.options.downscale, "Integer image downscale factor (intrinsics follow)")->capture_default_str();
  cmd->add_option("--holdout-every", a.options.holdoutEvery, "Frame i is held out for testing when i % N == 0 (0: none)")
      ->capture_default_str();
  cmd->add_option("--background", a.background, "What transparent pixels composite onto: white, black or r,g,b")
      ->default_str("white");
}

DatasetOptions datasetOptions(const DataArgs& a) {
  DatasetOptions o = a.options;
  if (a.background) o.background = parseBackground(*a.background);
  return o;
}

// The options write TrainingRunSettings directly; the lists are parsed when given.
struct TrainOpts {
  DataArgs data;
  TrainingRunSettings s;
  std::optional<std::string> resolutions, stageStarts;
  bool quiet = false;
  RunOptions run;
};

void runTrain(const TrainOpts& o) {
  const auto t0 = std::chrono::steady_clock::now();
  TrainingRunSettings s = o.s;
  s.dataPath = o.data.data;
  TrainConfig& cfg = s.config;
  o.run.applySeed(cfg.seed);
  if (o.resolutions) cfg.resolutions = parseIntList(*o.resolutions, "resolutions");
  cfg.stageStarts = o.stageStarts ? parseIntList(*o.stageStarts, "stage_starts")
                                  : defaultStageStarts(cfg.iterations, int(cfg.resolutions.size()));
  s.data = datasetOptions(o.data);
  if (!o.quiet)
    s.loaded = [](const Dataset& data) {
      std::printf("%s", datasetText(data).c_str());
      std::fflush(stdout);
    };
  if (!o.quiet && ProgressBar::stderrIsTerminal())
    s.progress = [](const TrainProgress& p) {
      std::fprintf(stderr, "\rtrain  iteration %d/%d  loss %.5f  PSNR %.2f dB  grid %dx%dx%d  %.0f s   ", p.iteration,
                   p.iterations, p.loss, p.psnr, p.res.x, p.res.y, p.res.z, p.elapsedSeconds);
      std::fflush(stderr);
    };
  const TrainingRunResult r = runTraining(s);
  if (s.progress) std::fprintf(stderr, "\n");
  if (o.quiet) return;
  std::printf("%s", trainingText(s, r, secondsSince(t0)).c_str());
}

}  // namespace

void addTrainCommand(CLI::App& app) {
  auto o = std::make_shared<TrainOpts>();
  CLI::App* cmd = &app;
  addDataOptions(cmd, o->data);
  cmd->add_option("--out", o->s.modelPath, "Model file (.inimrf)")->required();
  cmd->add_option("--log", o->s.logPath, "CSV log of iteration, loss, PSNR, time (default: beside --out, .csv)");
  cmd->add_option("--iterations", o->s.config.iterations, "Training iterations")->capture_default_str();
  cmd->add_option("--batch", o->s.config.batchSize, "Rays per iteration")->capture_default_str();
  cmd->add_option("--time-budget-s", o->s.config.timeBudgetSeconds, "Also stop after this many seconds (then not deterministic)");
  cmd->add_option("--sh-degree", o->s.config.shDegree, "Spherical-harmonic degree of the colour, 0-2")->capture_default_str();
  cmd->add_option("--resolutions", o->resolutions, "Grid resolution (longest side, vertices) of each stage")
      ->default_str([&] {
        std::string list;
        for (int r : o->s.config.resolutions) list += (list.empty() ? "" : ",") + std::to_string(r);
        return list;
      }());
  cmd->add_option("--stage-starts", o->stageStarts,
                  "Iteration at which each stage starts (default: 0, then 1/6 and 1/2 of the iterations)");
  cmd->add_flag("--quiet", o->quiet, "Print nothing but warnings");
  addRunOptions(cmd, o->run, [o] { runTrain(*o); });
}

void addEvalCommand(CLI::App& app) {
  struct Opts {
    DataArgs data;
    std::string model, out;
    bool all = false, quiet = false;
    RunOptions run;
  };
  auto o = std::make_shared<Opts>();
  CLI::App* cmd = &app;
  cmd->add_option("--model", o->model, "Model file (.inimrf)")->required();
  addDataOptions(cmd, o->data);
  cmd->add_option("--out", o->out, "Folder for the rendered views (PNG, beside the photos) and metrics.json/.csv");
  cmd->add_flag("--all", o->all, "Evaluate every frame, not only the held-out ones");
  cmd->add_flag("--quiet", o->quiet, "Print only the means");
  addRunOptions(cmd, o->run, [o] {
    EvalRunSettings s;
    s.modelPath = o->model;
    s.dataPath = o->data.data;
    s.data = datasetOptions(o->data);
    s.allFrames = o->all;
    s.outDir = o->out;
    const EvalRunResult r = runEval(s);
    if (!o->quiet)
      for (const auto& v : r.scores)
        std::printf("frame %4d  PSNR %6.2f dB  SSIM %.4f  %s\n", v.frame, v.psnr, v.ssim, v.image.c_str());
    std::printf("mean over %zu views: PSNR %.2f dB, SSIM %.4f (%.1f s)\n", r.scores.size(), meanPsnr(r.scores),
                meanSsim(r.scores), r.seconds);
  });
}

}  // namespace inim::cli
