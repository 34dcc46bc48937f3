#pragma once
// A sweep's result (docs/sweeps.md): results.csv and results.json (sweep_table.h), plots of each
// metric against each axis at the headline pose with the best point marked, a heat map of the
// headline metric over the first two axes (the other parameters at the best point's values),
// and report.md linking them, with the sensitivity at the best point: for each axis, the slope
// of the headline metric from the neighbouring points and the range of the axis within which it
// stays within 1 CIEDE2000 of the best (the tolerance a design must be built to). Differences
// below the references' noise floor (the budget's, when the sweep ran it) are marked as not
// significant. All files are written together, or none.
#include <string>
#include <vector>

#include "sweep/sweep_plan.h"
#include "sweep/sweep_table.h"

namespace inim {

// The headline metric (CIEDE2000 mean at the first pose) and the tolerance band of the report.
constexpr const char* kSweepHeadlineMetric = "de_mean";
constexpr double kSweepToleranceDe = 1.0;

struct AxisSensitivity {
  std::string axis;
  double slope = 0.0;      // d(metric)/d(axis) at the best point (central, or one-sided at an end)
  double change = 0.0;     // the metric's change over the slope's span (its significance, against the noise floor)
  bool slopeKnown = false;
  double lo = 0.0, hi = 0.0;         // the axis range within kSweepToleranceDe of the best
  bool loAtEnd = false, hiAtEnd = false;  // the range reaches the sweep's end (the tolerance is wider)
};

// The best point at the headline pose (null when no point has metrics).
const SweepPoint* bestSweepPoint(const SweepTable& t, const std::vector<SweepPoint>& points);
// Along each axis through the best point, the other parameters held.
std::vector<AxisSensitivity> sweepSensitivity(const SweepTable& t, const std::vector<SweepPoint>& points,
                                              const SweepPlan& plan);

// Writes results.csv, results.json, plots/*.png and report.md into `sweepDir`. `program`: for the
// command that re-runs the best point.
void writeSweepReport(const std::string& sweepDir, const SweepPlan& plan, const std::vector<SweepPoint>& points,
                      const SweepTable& t, const std::string& program);

}  // namespace inim
