#pragma once
// What `inim sweep` does with its options (docs/sweeps.md): prepare a plan's points and run them
// locally, write (and submit) the Slurm scripts, run one point or one array task, or collect the
// table and the report. The command line only fills SweepCommand and prints the lines.
#include <cstdint>
#include <functional>
#include <string>

#include "sweep/sweep_plan.h"
#include "sweep/sweep_slurm.h"

namespace inim {

struct SweepCommand {
  std::string plan;            // "": the plan already in `out`
  std::string out;             // the sweep's folder
  std::string point;           // run this point alone
  std::string slurmTask;       // run an array task of this task list ...
  int taskIndex = 0;           // ... this one
  std::string referenceCache;  // "": DIR/references; a folder, or "off"
  int jobs = 1, threadsPerPoint = 0;
  int threads = 0;             // of a point run alone or an array task (0: all)
  int64_t maxPoints = kDefaultMaxSweepPoints;
  bool slurm = false, submit = false, collect = false;
  SlurmSettings slurmSettings;  // program and referenceCache are set from the above
};

// Runs what `c` asks, telling the user through `print` (whole lines). InputError for bad input
// before anything is written; false when the sweep (or the point, or the task) is not complete.
bool runSweepCommand(SweepCommand c, const std::function<void(const std::string&)>& print);

}  // namespace inim
