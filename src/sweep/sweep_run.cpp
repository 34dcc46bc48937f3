#include "sweep/sweep_run.h"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstring>
#include <limits>
#include <chrono>
#include <filesystem>
#include <map>
#include <thread>

#include "core/error.h"
#include "core/format.h"
#include "core/interrupt.h"
#include "core/output_file.h"
#include "core/parallel.h"
#include "core/progress.h"
#include "sweep/sweep_point.h"

extern char** environ;

namespace inim {
namespace fs = std::filesystem;

std::string sweepReferenceCache(const std::string& sweepDir) { return (fs::path(sweepDir) / "references").string(); }

std::string currentProgram() {
  std::error_code ec;
  const fs::path p = fs::read_symlink("/proc/self/exe", ec);
  return ec ? "inim" : p.string();
}

std::vector<SweepPoint> prepareSweep(const SweepPlan& plan, const std::string& sweepDir, const std::string& program,
                                     int64_t maxPoints) {
  const std::vector<SweepPoint> points = expandSweep(plan, maxPoints);  // every refusal before any output
  {
    OutputSet out;
    writeTextFile(out.add((fs::path(sweepDir) / "plan.json").string()), sweepPlanJson(plan).dump(2) + "\n");
    out.commit();
  }
  for (const SweepPoint& p : points) writeSweepPointFiles(sweepDir, p, program);
  return points;
}

std::vector<SweepPoint> preparedSweepPoints(const std::string& sweepDir) {
  const std::string path = (fs::path(sweepDir) / "plan.json").string();
  if (!fs::exists(path)) throw InputError(path, "", "missing", "a sweep folder made by inim sweep --plan");
  return expandSweep(sweepPlanFromJson(readJsonFile(path), path), std::numeric_limits<int64_t>::max());
}

namespace {

struct Child {
  std::string id;
  std::chrono::steady_clock::time_point start;
};

pid_t spawnPoint(const SweepRunSettings& s, const std::string& id, int threads) {
  const std::string log = (fs::path(sweepPointDir(s.sweepDir, id)) / "log.txt").string();
  std::vector<std::string> args = {s.program, "sweep", "--out", s.sweepDir, "--point", id,
                                   "--threads", std::to_string(threads)};
  if (!s.referenceCache.empty()) args.insert(args.end(), {"--reference-cache", s.referenceCache});
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_adddup2(&actions, STDOUT_FILENO, STDERR_FILENO);
  posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
  pid_t pid = 0;
  const int err = posix_spawn(&pid, s.program.c_str(), &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (err != 0) throw std::runtime_error("cannot start " + s.program + ": " + std::strerror(err));
  return pid;
}

std::string exitText(int status) {
  if (WIFEXITED(status)) return "exit status " + std::to_string(WEXITSTATUS(status));
  if (WIFSIGNALED(status)) return std::string("killed by signal ") + strsignal(WTERMSIG(status));
  return "ended";
}

void stopChildren(std::map<pid_t, Child>& running) {
  for (const auto& [pid, c] : running) kill(pid, SIGTERM);
  for (const auto& [pid, c] : running) {
    int st = 0;
    waitpid(pid, &st, 0);
  }
  running.clear();
}

}  // namespace

SweepRunSummary runSweepLocal(const std::vector<SweepPoint>& points, const SweepRunSettings& s,
                              const std::function<void(const SweepPointOutcome&)>& pointDone) {
  const auto start = std::chrono::steady_clock::now();
  SweepRunSummary sum;
  sum.total = int(points.size());
  std::vector<std::string> queue;
  for (const SweepPoint& p : points) {
    if (completeSweepResult(s.sweepDir, p.id).is_null()) {
      queue.push_back(p.id);
    } else {
      SweepPointOutcome o{p.id, true, true, 0.0, ""};
      ++sum.skipped;
      sum.outcomes.push_back(o);
    }
  }
  const int jobs = std::max(1, s.jobs);
  const int threads = s.threadsPerPoint > 0 ? s.threadsPerPoint : std::max(1, hardwareThreads() / jobs);
  ProgressBar bar("sweep", queue.size(), s.progress && ProgressBar::stderrIsTerminal());
  auto note = [&] {
    bar.setNote(formatText("%d done, %d failed, %d left", sum.done, sum.failed,
                           int(points.size()) - sum.skipped - sum.done - sum.failed));
  };
  note();
  std::map<pid_t, Child> running;
  size_t next = 0;
  // The first point runs alone with every thread: it renders the references the others
  // share, which they would otherwise wait for with their cores idle (reference_cache.h).
  const bool warmUp = queue.size() > 1 && jobs > 1 && s.referenceCache != "off";
  try {
    while (next < queue.size() || !running.empty()) {
      throwIfInterrupted();
      const bool firstAlone = warmUp && (next == 0 || (next == 1 && !running.empty()));
      while (int(running.size()) < (firstAlone ? 1 : jobs) && next < queue.size()) {
        const int pointThreads = warmUp && next == 0 ? threads * jobs : threads;
        const std::string& id = queue[next++];
        running[spawnPoint(s, id, pointThreads)] = {id, std::chrono::steady_clock::now()};
      }
      int status = 0;
      const pid_t pid = waitpid(-1, &status, WNOHANG);
      if (pid <= 0) {
        std::this_thread::sleep_for(std::chrono::milliseconds(50));
        continue;
      }
      const auto it = running.find(pid);
      if (it == running.end()) continue;
      SweepPointOutcome o;
      o.id = it->second.id;
      o.seconds = secondsSince(it->second.start);
      o.log = (fs::path(sweepPointDir(s.sweepDir, o.id)) / "log.txt").string();
      running.erase(it);
      // A point stopped by the same Ctrl-C is not a failure: the sweep stops, the point stays partial.
      const bool stopped = (WIFSIGNALED(status) && (WTERMSIG(status) == SIGINT || WTERMSIG(status) == SIGTERM)) ||
                           (WIFEXITED(status) && (WEXITSTATUS(status) == 130 || WEXITSTATUS(status) == 143));
      if (stopped) throwIfInterrupted();
      o.ok = !completeSweepResult(s.sweepDir, o.id).is_null();
      const Json recorded = recordedSweepResult(s.sweepDir, o.id);
      if (!o.ok && (recorded.is_null() || recorded.value("status", "") != "failed"))
        recordSweepFailure(s.sweepDir, o.id, "the point's process ended (" + exitText(status) + "); log: " + o.log);
      (o.ok ? sum.done : sum.failed) += 1;
      sum.outcomes.push_back(o);
      bar.add(1);
      note();
      if (pointDone) pointDone(o);
    }
  } catch (...) {
    stopChildren(running);
    throw;
  }
  bar.finish();
  sum.seconds = secondsSince(start);
  // The outcomes in the plan's order, whatever order the points ended in.
  std::map<std::string, int> order;
  for (const SweepPoint& p : points) order[p.id] = p.index;
  std::sort(sum.outcomes.begin(), sum.outcomes.end(),
            [&](const SweepPointOutcome& a, const SweepPointOutcome& b) { return order[a.id] < order[b.id]; });
  return sum;
}

}  // namespace inim
