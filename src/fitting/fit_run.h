#pragma once
// `inim train` and `inim eval` as a library: a radiance field fitted to a posed photo dataset,
// written as a model file with its training log (CSV, one row per progress report), and an
// evaluation's rendered views and metrics.
#include <functional>
#include <string>
#include <vector>

#include "core/output_file.h"
#include "dataset/dataset.h"
#include "fitting/dataset_fit.h"
#include "radiance/trainer.h"

namespace inim {

// The iteration at which each of `stages` grid stages starts: three stages at 0, 1/6 and 1/2 of
// the iterations; another count evenly over the first half.
std::vector<int> defaultStageStarts(int iterations, int stages);

struct TrainingRunSettings {
  std::string dataPath;
  DatasetOptions data;
  TrainConfig config;     // its box and background are the dataset's
  std::string modelPath;  // .inimrf
  std::string logPath;    // "": beside the model, .csv
  std::function<void(const Dataset&)> loaded;             // optional: the dataset, before training
  std::function<void(const TrainProgress&)> progress;     // optional: each progress report
};

struct TrainingRunResult {
  TrainStats stats;
  std::vector<ViewScore> heldOut;  // the held-out frames, scored after training
  double evalSeconds = 0;
  glm::ivec3 gridResolution{0};
  int shDegree = 0;
  std::string logPath;
};

// Trains, saves the model and the log, and scores the held-out frames; the files land together
// at the end. InputError naming `out` unless the model path ends in .inimrf.
TrainingRunResult runTraining(const TrainingRunSettings& s);

// Whole numbers separated by commas ("64,128,160"); InputError naming `key` otherwise.
std::vector<int> parseIntList(const std::string& text, const std::string& key);
// What transparent pixels composite onto: white, black or r,g,b in [0, 1]; InputError naming
// `background` otherwise.
glm::vec3 parseBackground(const std::string& text);

struct EvalRunSettings {
  std::string modelPath;  // .inimrf
  std::string dataPath;
  DatasetOptions data;
  bool allFrames = false;  // every frame, not only the held-out ones
  std::string outDir;      // "": no files (see writeEvaluation)
};

struct EvalRunResult {
  std::vector<ViewScore> scores;
  double seconds = 0;  // the evaluation alone, without loading or writing
};

// Scores the model against the dataset's frames and writes the evaluation when asked.
// InputError naming `holdout_every` when there is no frame to score.
EvalRunResult runEval(const EvalRunSettings& s);

// What `inim train` prints: the dataset once loaded (file, frames, size, scene box), and after
// the run the training, the held-out scores and the files written (with the total time).
std::string datasetText(const Dataset& data);
// One progress line (no newline; starts with a carriage return, for a terminal).
std::string trainProgressText(const TrainProgress& p);
// One line per scored view (when perView) and the means.
std::string evalText(const EvalRunResult& r, bool perView);
std::string trainingText(const TrainingRunSettings& s, const TrainingRunResult& r, double totalSeconds);

double meanPsnr(const std::vector<ViewScore>& scores);
double meanSsim(const std::vector<ViewScore>& scores);

// An evaluation in `dir`, added to `outputs` (written when the caller commits them):
// view_NNNN_model.png and view_NNNN_photo.png per scored frame, metrics.json (per view and
// the means) and metrics.csv.
void writeEvaluation(const std::string& dir, const std::string& model, const Dataset& data,
                     const std::vector<ViewScore>& scores, const std::vector<Image>& renders, OutputSet& outputs);

}  // namespace inim
