// inim train / inim eval: a voxel-grid radiance field (src/radiance) from a posed photo
// dataset (src/dataset), and its held-out quality. See src/radiance/trainer.h and
// src/fitting/fit_run.h.
#include <chrono>
#include <cstdio>
#include <memory>
#include <string>

#include "cli/commands.h"
#include "cli/options.h"
#include "core/progress.h"
#include "fitting/fit_run.h"

namespace inim::cli {

namespace {

struct DataArgs {
  std::string data, background = "white";
  int downscale = 1, holdoutEvery = 8;
};

void addDataOptions(CLI::App* cmd, DataArgs& a) {
  cmd->add_option("--data", a.data,
                  "Dataset: a folder with transforms.json / transforms_train.json (Blender, Nerfstudio, instant-ngp) "
                  "or a Middlebury *_par.txt, or the file itself")
      ->required();
  cmd->add_option("--downscale", a.downscale, "Integer image downscale factor (intrinsics follow)")->capture_default_str();
  cmd->add_option("--holdout-every", a.holdoutEvery, "Frame i is held out for testing when i % N == 0 (0: none)")
      ->capture_default_str();
  cmd->add_option("--background", a.background, "What transparent pixels composite onto: white, black or r,g,b")
      ->capture_default_str();
}

DatasetOptions datasetOptions(const DataArgs& a) {
  DatasetOptions o;
  o.downscale = a.downscale;
  o.holdoutEvery = a.holdoutEvery;
  o.background = parseBackground(a.background);
  return o;
}

struct TrainOpts {
  DataArgs data;
  std::string out, log, resolutions = "64,128,160", stageStarts;
  int iterations = 3000, batch = 4096, shDegree = 1;
  double timeBudget = 0;
  bool quiet = false;
  RunOptions run;
};

void runTrain(const TrainOpts& o) {
  const auto t0 = std::chrono::steady_clock::now();
  TrainingRunSettings s;
  s.dataPath = o.data.data;
  s.modelPath = o.out;
  s.logPath = o.log;
  TrainConfig& cfg = s.config;
  cfg.iterations = o.iterations;
  cfg.batchSize = o.batch;
  cfg.shDegree = o.shDegree;
  cfg.timeBudgetSeconds = o.timeBudget;
  cfg.seed = o.run.seed;
  cfg.resolutions = parseIntList(o.resolutions, "resolutions");
  cfg.stageStarts = o.stageStarts.empty() ? defaultStageStarts(o.iterations, int(cfg.resolutions.size()))
                                          : parseIntList(o.stageStarts, "stage_starts");
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
  auto* cmd = app.add_subcommand(
      "train", "Train a voxel-grid radiance field (density + spherical-harmonic colour, Adam, TV, coarse to fine) "
               "from a posed photo dataset, on the CPU");
  addDataOptions(cmd, o->data);
  cmd->add_option("--out", o->out, "Model file (.inimrf)")->required();
  cmd->add_option("--log", o->log, "CSV log of iteration, loss, PSNR, time (default: beside --out, .csv)");
  cmd->add_option("--iterations", o->iterations, "Training iterations")->capture_default_str();
  cmd->add_option("--batch", o->batch, "Rays per iteration")->capture_default_str();
  cmd->add_option("--time-budget-s", o->timeBudget, "Also stop after this many seconds (then not deterministic)");
  cmd->add_option("--sh-degree", o->shDegree, "Spherical-harmonic degree of the colour, 0-2")->capture_default_str();
  cmd->add_option("--resolutions", o->resolutions, "Grid resolution (longest side, vertices) of each stage")
      ->capture_default_str();
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
  auto* cmd = app.add_subcommand("eval", "Held-out PSNR and SSIM of a trained radiance field, and its rendered views");
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
