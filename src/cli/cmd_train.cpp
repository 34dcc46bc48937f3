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
  addSetting(cmd, "data", a.data)->required();
  addSetting(cmd, "downscale", a.options.downscale);
  addSetting(cmd, "holdout_every", a.options.holdoutEvery);
  addSetting(cmd, "background", a.background)->default_str("white");
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
  if (!o.quiet) s.loaded = [](const Dataset& data) { std::printf("%s", datasetText(data).c_str()), std::fflush(stdout); };
  if (!o.quiet && ProgressBar::stderrIsTerminal())
    s.progress = [](const TrainProgress& p) { std::fputs(trainProgressText(p).c_str(), stderr); };
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
  addSetting(cmd, "out", o->s.modelPath)->required();
  addSetting(cmd, "log", o->s.logPath);
  addSetting(cmd, "iterations", o->s.config.iterations);
  addSetting(cmd, "batch", o->s.config.batchSize);
  addSetting(cmd, "time_budget_s", o->s.config.timeBudgetSeconds);
  addSetting(cmd, "sh_degree", o->s.config.shDegree);
  addSetting(cmd, "resolutions", o->resolutions)->default_str([&] {
        std::string list;
        for (int r : o->s.config.resolutions) list += (list.empty() ? "" : ",") + std::to_string(r);
        return list;
      }());
  addSetting(cmd, "stage_starts", o->stageStarts);
  addSetting(cmd, "quiet", o->quiet);
  addRunOptions(cmd, o->run, [o] { runTrain(*o); });
}

void addEvalCommand(CLI::App& app) {
  struct Opts {
    EvalRunSettings s;
    DataArgs data;
    bool quiet = false;
    RunOptions run;
  };
  auto o = std::make_shared<Opts>();
  CLI::App* cmd = &app;
  addSetting(cmd, "model", o->s.modelPath)->required();
  addDataOptions(cmd, o->data);
  addSetting(cmd, "out", o->s.outDir);
  addSetting(cmd, "all", o->s.allFrames);
  addSetting(cmd, "quiet", o->quiet);
  addRunOptions(cmd, o->run, [o] {
    EvalRunSettings s = o->s;
    s.dataPath = o->data.data;
    s.data = datasetOptions(o->data);
    std::printf("%s", evalText(runEval(s), !o->quiet).c_str());
  });
}

}  // namespace inim::cli
