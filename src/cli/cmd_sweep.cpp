// inim sweep: design sweeps, locally or on a Slurm cluster (src/sweep, docs/sweeps.md).
#include <cstdio>
#include <filesystem>
#include <memory>

#include "cli/commands.h"
#include "cli/options.h"
#include "core/error.h"
#include "core/format.h"
#include "sweep/sweep_point.h"
#include "sweep/sweep_report.h"
#include "sweep/sweep_run.h"
#include "sweep/sweep_slurm.h"
#include "sweep/sweep_table.h"

namespace inim::cli {

namespace {

struct SweepOpts {
  std::string plan, out, point, slurmTask, referenceCache;
  int jobs = 1, threadsPerPoint = 0, taskIndex = 0;
  int64_t maxPoints = kDefaultMaxSweepPoints;
  bool slurm = false, submit = false, collect = false;
  SlurmSettings slurmSettings;
  RunOptions run;
};

// Gathers the table and the report; prints the points without results, with their logs.
int collect(const std::string& dir, const std::vector<SweepPoint>& points) {
  const std::string planPath = (std::filesystem::path(dir) / "plan.json").string();
  const SweepPlan plan = sweepPlanFromJson(readJsonFile(planPath), planPath);
  const SweepTable t = collectSweepTable(dir, points);
  writeSweepReport(dir, plan, points, t, currentProgram());
  int missing = 0;
  for (const SweepPointStatus& p : t.points) {
    if (p.status == "ok") continue;
    ++missing;
    const std::string log = slurmLogOf(dir, p.point->id);
    std::printf("  %s %s%s%s\n", p.point->id.c_str(), p.status.c_str(), p.error.empty() ? "" : (": " + p.error).c_str(),
                log.empty() ? "" : ("\n    log: " + log).c_str());
  }
  if (const SweepPoint* best = bestSweepPoint(t, points))
    std::printf("best point: %s (CIEDE2000 mean %.3f at %s)\n", best->id.c_str(),
                *t.row(*best, t.firstPose)->metrics[t.metric(kSweepHeadlineMetric)], t.firstPose.c_str());
  std::printf("wrote %s/{results.csv,results.json,report.md,plots/}\n", dir.c_str());
  if (missing)
    std::printf("%d of %zu points have no result; run them again: inim sweep --out %s [--slurm --submit]\n", missing,
                points.size(), dir.c_str());
  return missing ? 1 : 0;
}

int slurmSubmission(const SweepOpts& o, const std::vector<SweepPoint>& points) {
  SlurmSettings s = o.slurmSettings;
  s.program = currentProgram();
  s.referenceCache = o.referenceCache;
  SlurmSubmission sub = writeSlurmScripts(o.out, points, s);
  if (sub.tasks == 0) return std::printf("every point is complete; nothing to submit\n"), 0;
  std::printf("%d points in %d array tasks: %s\ncollection: %s\n", sub.points, sub.tasks, sub.arrayScript.c_str(),
              sub.collectScript.c_str());
  if (!o.submit) return std::printf("submit:\n%s", slurmSubmitCommands(sub).c_str()), 0;
  submitSlurm(o.out, sub);
  std::printf("submitted: %sarray job %s, collection job %s\n",
              sub.firstJob.empty() ? "" : ("first task job " + sub.firstJob + ", ").c_str(), sub.arrayJob.c_str(),
              sub.collectJob.c_str());
  return 0;
}

int runSweep(SweepOpts& o) {
  o.out = std::filesystem::absolute(o.out).lexically_normal().string();
  while (o.out.size() > 1 && o.out.back() == '/') o.out.pop_back();  // "DIR/." normalises to "DIR/"
  if (o.referenceCache != "off" && !o.referenceCache.empty())
    o.referenceCache = std::filesystem::absolute(o.referenceCache).lexically_normal().string();
  const std::string cache = o.referenceCache.empty() ? sweepReferenceCache(o.out) : o.referenceCache;
  if (!o.point.empty()) {
    const Json r = runSweepPoint(o.out, o.point, o.run.threads, cache);
    if (r.value("status", "") != "ok") throw std::runtime_error("point " + o.point + " failed: " + r.value("error", ""));
    return std::printf("point %s: ok\n", o.point.c_str()), 0;
  }
  if (!o.slurmTask.empty()) return runSlurmTask(o.out, o.slurmTask, o.taskIndex, o.run.threads, cache) ? 0 : 1;
  const std::vector<SweepPoint> points = o.plan.empty() ? preparedSweepPoints(o.out)
                                                        : prepareSweep(loadSweepPlan(o.plan), o.out, currentProgram(), o.maxPoints);
  if (o.collect) return collect(o.out, points);
  if (o.slurm) return slurmSubmission(o, points);
  SweepRunSettings s{o.out, currentProgram(), o.jobs, o.threadsPerPoint, o.referenceCache, true};
  const SweepRunSummary sum = runSweepLocal(points, s, [](const SweepPointOutcome& p) {
    std::printf("point %s: %s in %.1f s\n", p.id.c_str(), p.ok ? "ok" : "failed", p.seconds);
    std::fflush(stdout);
  });
  std::printf("%d points: %d run (%d failed), %d already complete, in %.1f s (%.0f points per hour)\n", sum.total,
              sum.done + sum.failed, sum.failed, sum.skipped, sum.seconds,
              sum.done + sum.failed > 0 ? 3600.0 * (sum.done + sum.failed) / sum.seconds : 0.0);
  return collect(o.out, points);
}

}  // namespace

void addSweepCommand(CLI::App& app) {
  auto o = std::make_shared<SweepOpts>();
  CLI::App* cmd = &app;
  addSetting(cmd, "plan", o->plan);
  addSetting(cmd, "out", o->out)->required();
  addSetting(cmd, "jobs", o->jobs);
  addSetting(cmd, "threads_per_point", o->threadsPerPoint);
  addSetting(cmd, "max_points", o->maxPoints);
  addSetting(cmd, "slurm", o->slurm);
  addSetting(cmd, "submit", o->submit);
  addSetting(cmd, "partition", o->slurmSettings.partition);
  addSetting(cmd, "cpus_per_task", o->slurmSettings.cpusPerTask);
  addSetting(cmd, "mem", o->slurmSettings.memory);
  addSetting(cmd, "time_limit", o->slurmSettings.timeLimit);
  addSetting(cmd, "points_per_task", o->slurmSettings.pointsPerTask);
  addSetting(cmd, "point", o->point);
  addSetting(cmd, "collect", o->collect);
  addSetting(cmd, "slurm_task", o->slurmTask);
  addSetting(cmd, "task_index", o->taskIndex);
  addSetting(cmd, "reference_cache", o->referenceCache);
  addRunOptions(cmd, o->run, [o] {
    if (o->submit && !o->slurm) throw InputError("", "--submit", "given without --slurm", "--slurm --submit");
    if (runSweep(*o) != 0) throw std::runtime_error("the sweep in " + o->out + " is not complete (see above)");
  });
}

}  // namespace inim::cli
