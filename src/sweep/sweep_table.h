#pragma once
// A sweep's table: one row per point and pose, with the point's parameters and the metrics of
// fig11 and the budget (sweep_point.h's result.json). results.csv holds what the points
// computed and nothing about how they ran (times, cache hits), so a sweep run locally and the
// same sweep run on a cluster give the same file, byte for byte; results.json adds the points'
// status, errors, times and the reference cache's hit rate.
#include <optional>
#include <string>
#include <vector>

#include "core/json_config.h"
#include "sweep/sweep_plan.h"

namespace inim {

struct SweepRow {
  const SweepPoint* point = nullptr;
  std::string status;  // "ok", "failed", "missing"
  std::string pose;    // "" for a point without metrics
  std::vector<std::optional<double>> metrics;  // in SweepTable::metricNames' order
};

struct SweepPointStatus {
  const SweepPoint* point = nullptr;
  std::string status, error;
  double seconds = 0.0;
  int referencesCached = 0, referencesRendered = 0;
};

struct SweepTable {
  std::vector<std::string> metricNames;  // psnr_db, ssim, de_mean, ..., budget_<rung>
  std::vector<SweepRow> rows;
  std::vector<SweepPointStatus> points;
  int cached = 0, rendered = 0;                  // references over the points
  std::optional<double> noiseFloor;              // mean noise floor (CIEDE2000) at the first pose, with the budget
  std::string firstPose;                         // the headline pose
  // The row of `point` at `pose`, or null.
  const SweepRow* row(const SweepPoint& point, const std::string& pose) const;
  // Index of a metric in metricNames (-1 when absent).
  int metric(const std::string& name) const;
};

// Reads every point's result (complete ones; failed ones with their error; others "missing").
SweepTable collectSweepTable(const std::string& sweepDir, const std::vector<SweepPoint>& points);

// The CSV and JSON texts.
std::string sweepTableCsv(const SweepTable& t, const std::vector<SweepPoint>& points);
Json sweepTableJson(const SweepTable& t);

}  // namespace inim
