#pragma once
// A sweep on a Slurm cluster (docs/sweeps.md): inim writes the scripts and reads the results;
// Slurm schedules. Under DIR/slurm/:
//   tasks-N.txt      one line per array task: the ids of the points it runs
//   array-N.sbatch   the job array (#SBATCH --array=0-(tasks-1), --cpus-per-task, --mem, --time,
//                    --partition); task K runs `inim sweep --out DIR --slurm-task tasks-N.txt
//                    --task-index K`, one point after another, in the task's process
//   collect-N.sbatch the collection step, `inim sweep --out DIR --collect`, submitted with
//                    --dependency=afterok on the array (task 0 may go first, alone: firstAlone)
//   logs/            the tasks' logs: array-N_<job>_<task>.log
//   submitted-N.json the job ids (with --submit)
// N counts the submissions, so a resubmission of the failed points keeps the earlier logs. Only
// points not complete go into a submission. A task exits 0 when each of its points ended with a
// recorded result (ok or failed: a failed point does not stop the others, nor the collection).
#include <string>
#include <vector>

#include "sweep/sweep_plan.h"

namespace inim {

struct SlurmSettings {
  std::string program;        // the inim binary, as the nodes see it (a shared path)
  int cpusPerTask = 2;
  std::string memory = "8G";  // --mem
  std::string timeLimit = "02:00:00";
  std::string partition;      // "": the cluster's default
  int pointsPerTask = 1;
  std::string extraEnvironment;  // lines added before the command (module loads, exports)
  std::string referenceCache;    // "": DIR/references; a folder on the shared file system, or "off"
};

struct SlurmSubmission {
  int number = 0;  // N
  int tasks = 0, points = 0;
  std::string taskList, arrayScript, collectScript;
  // Task 0 is submitted alone first and the other tasks after it (--dependency=afterany), so
  // that it renders the references they share instead of all of them waiting on its claims
  // (with the reference cache on and more than one task).
  bool firstAlone = false;
  std::string firstJob, arrayJob, collectJob;  // with submitSlurm (firstJob: with firstAlone)
};

// The sbatch commands that submitSlurm runs, as shell lines (for a user who submits by hand).
std::string slurmSubmitCommands(const SlurmSubmission& sub);

// Writes the scripts for the points not complete (none: tasks = 0 and no scripts).
SlurmSubmission writeSlurmScripts(const std::string& sweepDir, const std::vector<SweepPoint>& points,
                                  const SlurmSettings& s);
// sbatch --parsable the array, then the collection with --dependency=afterok:<array>; records the
// ids in submitted-N.json. std::runtime_error with sbatch's own message when it fails.
void submitSlurm(const std::string& sweepDir, SlurmSubmission& sub);

// Runs array task `index` of `taskList`: its points, one after another. Returns false when some
// point could not record a result.
bool runSlurmTask(const std::string& sweepDir, const std::string& taskList, int index, int threads,
                  const std::string& referenceCache);

// The log of the task that ran `id` in the latest submission that had it ("" when none).
std::string slurmLogOf(const std::string& sweepDir, const std::string& id);

}  // namespace inim
