// inim sweep: design sweeps, locally or on a Slurm cluster (src/sweep/sweep_command.h,
// docs/sweeps.md).
#include <cstdio>
#include <memory>
#include <stdexcept>

#include "cli/commands.h"
#include "cli/options.h"
#include "sweep/sweep_command.h"

namespace inim::cli {

void addSweepCommand(CLI::App& app) {
  auto c = std::make_shared<SweepCommand>();
  CLI::App* cmd = &app;
  addSetting(cmd, "plan", c->plan);
  addSetting(cmd, "out", c->out)->required();
  addSetting(cmd, "jobs", c->jobs);
  addSetting(cmd, "threads_per_point", c->threadsPerPoint);
  addSetting(cmd, "max_points", c->maxPoints);
  addSetting(cmd, "reference_cache", c->referenceCache);
  addSetting(cmd, "slurm", c->slurm);
  addSetting(cmd, "submit", c->submit);
  addSetting(cmd, "partition", c->slurmSettings.partition);
  addSetting(cmd, "cpus_per_task", c->slurmSettings.cpusPerTask);
  addSetting(cmd, "mem", c->slurmSettings.memory);
  addSetting(cmd, "time_limit", c->slurmSettings.timeLimit);
  addSetting(cmd, "points_per_task", c->slurmSettings.pointsPerTask);
  addSetting(cmd, "point", c->point);
  addSetting(cmd, "slurm_task", c->slurmTask);
  addSetting(cmd, "task_index", c->taskIndex);
  addSetting(cmd, "collect", c->collect);
  addSetting(cmd, "threads", c->threads);
  cmd->callback([c] {
    const bool complete = runSweepCommand(*c, [](const std::string& line) {
      std::printf("%s", line.c_str());
      std::fflush(stdout);
    });
    if (!complete) throw std::runtime_error("the sweep in " + c->out + " is not complete (see above)");
  });
}

}  // namespace inim::cli
