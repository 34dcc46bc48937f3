#pragma once
// What fitting a radiance field to a dataset writes besides the model: the training log (CSV,
// one row per progress report) and an evaluation's rendered views and metrics. Also the
// coarse-to-fine schedule used when none is given.
#include <ostream>
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

// The training log: the header line, then one row per progress report.
void writeTrainingLogHeader(std::ostream& csv);
void writeTrainingLogRow(std::ostream& csv, const TrainProgress& p);

double meanPsnr(const std::vector<ViewScore>& scores);
double meanSsim(const std::vector<ViewScore>& scores);

// An evaluation in `dir`, added to `outputs` (written when the caller commits them):
// view_NNNN_model.png and view_NNNN_photo.png per scored frame, metrics.json (per view and
// the means) and metrics.csv.
void writeEvaluation(const std::string& dir, const std::string& model, const Dataset& data,
                     const std::vector<ViewScore>& scores, const std::vector<Image>& renders, OutputSet& outputs);

}  // namespace inim
