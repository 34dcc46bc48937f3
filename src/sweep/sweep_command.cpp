#include "sweep/sweep_command.h"

#include <filesystem>

#include "core/error.h"
#include "core/format.h"
#include "sweep/sweep_point.h"
#include "sweep/sweep_report.h"
#include "sweep/sweep_run.h"
#include "sweep/sweep_table.h"

namespace inim {
namespace fs = std::filesystem;

namespace {

using Print = std::function<void(const std::string&)>;

std::string absolutePath(const std::string& p) {
  std::string a = fs::absolute(p).lexically_normal().string();
  while (a.size() > 1 && a.back() == '/') a.pop_back();  // "DIR/." normalises to "DIR/"
  return a;
}

// Gathers the table and the report; lists the points without results, with their logs.
bool collect(const std::string& dir, const std::vector<SweepPoint>& points, const Print& print) {
  const std::string planPath = (fs::path(dir) / "plan.json").string();
  const SweepPlan plan = sweepPlanFromJson(readJsonFile(planPath), planPath);
  const SweepTable t = collectSweepTable(dir, points);
  writeSweepReport(dir, plan, points, t, currentProgram());
  int missing = 0;
  for (const SweepPointStatus& p : t.points) {
    if (p.status == "ok") continue;
    ++missing;
    const std::string log = slurmLogOf(dir, p.point->id);
    print("  " + p.point->id + " " + p.status + (p.error.empty() ? "" : ": " + p.error) +
          (log.empty() ? "" : "\n    log: " + log) + "\n    alone: " + sweepPointCommand(currentProgram(), dir, p.point->id) +
          "\n");
  }
  if (const SweepPoint* best = bestSweepPoint(t, points))
    print("best point: " + best->id + " (CIEDE2000 mean " +
          formatNumber(*t.row(*best, t.firstPose)->metrics[t.metric(kSweepHeadlineMetric)], "%.3f") + " at " +
          t.firstPose + ")\n");
  print("wrote " + dir + "/{results.csv,results.json,report.md,plots/}\n");
  if (missing)
    print(formatText("%d of %zu points have no result; run them again: inim sweep --out %s [--slurm --submit]\n",
                     missing, points.size(), dir.c_str()));
  return missing == 0;
}

bool slurmSubmission(const SweepCommand& c, const std::vector<SweepPoint>& points, const Print& print) {
  SlurmSettings s = c.slurmSettings;
  s.program = currentProgram();
  s.referenceCache = c.referenceCache;
  SlurmSubmission sub = writeSlurmScripts(c.out, points, s);
  if (sub.tasks == 0) return print("every point is complete; nothing to submit\n"), true;
  print(formatText("%d points in %d array tasks: %s\ncollection: %s\n", sub.points, sub.tasks, sub.arrayScript.c_str(),
                   sub.collectScript.c_str()));
  if (!c.submit) return print("submit:\n" + slurmSubmitCommands(sub)), true;
  submitSlurm(c.out, sub);
  print("submitted: " + (sub.firstJob.empty() ? "" : "first task job " + sub.firstJob + ", ") + "array job " +
        sub.arrayJob + ", collection job " + sub.collectJob + "\n");
  return true;
}

bool runLocally(const SweepCommand& c, const std::vector<SweepPoint>& points, const Print& print) {
  const SweepRunSettings s{c.out, currentProgram(), c.jobs, c.threadsPerPoint, c.referenceCache, true};
  const SweepRunSummary sum = runSweepLocal(points, s, [&](const SweepPointOutcome& p) {
    print(formatText("point %s: %s in %.1f s\n", p.id.c_str(), p.ok ? "ok" : "failed", p.seconds));
  });
  const int ran = sum.done + sum.failed;
  print(formatText("%d points: %d run (%d failed), %d already complete, in %.1f s (%.0f points per hour)\n", sum.total,
                   ran, sum.failed, sum.skipped, sum.seconds, ran > 0 ? 3600.0 * ran / sum.seconds : 0.0));
  return collect(c.out, points, print);
}

}  // namespace

bool runSweepCommand(SweepCommand c, const Print& print) {
  if (c.submit && !c.slurm) throw InputError("", "--submit", "given without --slurm", "--slurm --submit");
  c.out = absolutePath(c.out);
  if (c.referenceCache != "off" && !c.referenceCache.empty()) c.referenceCache = absolutePath(c.referenceCache);
  const std::string cache = c.referenceCache.empty() ? sweepReferenceCache(c.out) : c.referenceCache;
  if (!c.point.empty()) {
    const Json r = runSweepPoint(c.out, c.point, c.threads, cache);
    const bool ok = r.value("status", "") == "ok";
    print("point " + c.point + ": " + (ok ? "ok" : "failed: " + r.value("error", "")) + "\n");
    return ok;
  }
  if (!c.slurmTask.empty()) return runSlurmTask(c.out, c.slurmTask, c.taskIndex, c.threads, cache);
  const std::vector<SweepPoint> points =
      c.plan.empty() ? preparedSweepPoints(c.out) : prepareSweep(loadSweepPlan(c.plan), c.out, currentProgram(), c.maxPoints);
  if (c.collect) return collect(c.out, points, print);
  if (c.slurm) return slurmSubmission(c, points, print);
  return runLocally(c, points, print);
}

}  // namespace inim
