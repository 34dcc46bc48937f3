#pragma once
// One design point of a sweep, run alone. Its folder, DIR/points/ID/, holds
//   point.json    the point: id, index, parameters, the resolved configuration, the command
//   display.json  its display, as one file (panel and MLA inlined)
//   fig11/        the fig11 run's outputs (runs/fig11.h), written together at its end
//   result.json   written last: status ("ok" or "failed" with the error), the metrics per pose,
//                 times, the references read from the cache, and the SHA-256 of point.json and
//                 of fig11's metrics.json and budget.json
//   log.txt       what the run printed (local runs; Slurm tasks log under DIR/slurm/logs)
// A point is complete when result.json says "ok", belongs to this point.json and every file it
// names has the recorded hash: checked, not assumed. An interrupted run leaves no result.json.
#include <string>

#include "core/json_config.h"
#include "sweep/sweep_plan.h"

namespace inim {

std::string sweepPointDir(const std::string& sweepDir, const std::string& id);

// point.json and display.json (rewritten only when they differ, so a complete point stays so).
// `program`: the inim binary, for the command that re-runs the point.
void writeSweepPointFiles(const std::string& sweepDir, const SweepPoint& point, const std::string& program);
// The command that runs the point alone.
std::string sweepPointCommand(const std::string& program, const std::string& sweepDir, const std::string& id);

// The point's result.json when the point is complete, else null.
Json completeSweepResult(const std::string& sweepDir, const std::string& id);
// The point's result.json as it is (complete or not; null when absent or unreadable).
Json recordedSweepResult(const std::string& sweepDir, const std::string& id);

// Runs the point from its point.json with at most `threads` worker threads (0: all) and
// writes result.json. A point that fails (bad values, a display that cannot be built) is
// recorded as failed with its error and returns normally; Interrupted propagates, leaving none.
// `referenceCache`: the folder of the sweep's reference cache, or "off".
Json runSweepPoint(const std::string& sweepDir, const std::string& id, int threads, const std::string& referenceCache);
// A failed result for a point whose process ended without writing one (killed, out of memory).
void recordSweepFailure(const std::string& sweepDir, const std::string& id, const std::string& error);

}  // namespace inim
