#pragma once
// A sweep's folder and its local execution (docs/sweeps.md).
//
//   DIR/plan.json        the plan as read (every later step reads this one)
//   DIR/points/ID/       one folder per point (sweep_point.h)
//   DIR/references/      the sweep's reference cache, shared by its points
//   DIR/results.csv ...  the table and the report (sweep_table.h, sweep_report.h)
//
// Local execution runs each point as its own process (`inim sweep --out DIR --point ID
// --threads T`), at most `jobs` at once, each with a fixed thread budget: a crash or a memory
// blow-up stays in its point, which is recorded as failed with its log. The first point runs
// alone with all jobs' threads, so that it fills the reference cache before the others read it. Points already complete
// (checked: sweep_point.h) are skipped, partial ones redone. Ctrl-C stops the children; their
// outputs are written together or not at all, so nothing half-written is left.
#include <functional>
#include <string>
#include <vector>

#include "sweep/sweep_plan.h"

namespace inim {

std::string sweepReferenceCache(const std::string& sweepDir);

// Writes DIR/plan.json and every point's files; returns the points. Refused (InputError)
// before anything is written when the plan does not expand (sweep_plan.h).
std::vector<SweepPoint> prepareSweep(const SweepPlan& plan, const std::string& sweepDir, const std::string& program,
                                     int64_t maxPoints);
// The points of a prepared sweep (DIR/plan.json).
std::vector<SweepPoint> preparedSweepPoints(const std::string& sweepDir);

struct SweepRunSettings {
  std::string sweepDir;
  std::string program;      // the inim binary the points run in
  int jobs = 1;             // points at once
  int threadsPerPoint = 0;  // 0: the machine's threads / jobs
  std::string referenceCache;  // the points' reference cache folder, or "off"; "": DIR/references
  bool progress = true;     // a bar on a terminal
};

struct SweepPointOutcome {
  std::string id;
  bool ok = false, skipped = false;
  double seconds = 0.0;
  std::string log;  // the point's log file
};

struct SweepRunSummary {
  int total = 0, skipped = 0, done = 0, failed = 0;
  double seconds = 0.0;
  std::vector<SweepPointOutcome> outcomes;
};

// Runs the points not yet complete. `pointDone` (optional) is told as each one ends.
SweepRunSummary runSweepLocal(const std::vector<SweepPoint>& points, const SweepRunSettings& s,
                              const std::function<void(const SweepPointOutcome&)>& pointDone = {});

// The path of the running program (/proc/self/exe).
std::string currentProgram();

}  // namespace inim
