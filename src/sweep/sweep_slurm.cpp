#include "sweep/sweep_slurm.h"

#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/error.h"
#include "core/output_file.h"
#include "sweep/sweep_point.h"
#include "sweep/sweep_run.h"

namespace inim {
namespace fs = std::filesystem;

namespace {

fs::path slurmDir(const std::string& sweepDir) { return fs::path(sweepDir) / "slurm"; }

// A word for a shell script, single-quoted.
std::string shellWord(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

int nextSubmissionNumber(const std::string& sweepDir) {
  int n = 1;
  while (fs::exists(slurmDir(sweepDir) / ("tasks-" + std::to_string(n) + ".txt"))) ++n;
  return n;
}

std::string header(const std::string& name, const SlurmSettings& s, const std::string& log) {
  std::string h = "#!/bin/bash\n#SBATCH --job-name=" + name + "\n";
  h += "#SBATCH --cpus-per-task=" + std::to_string(s.cpusPerTask) + "\n";
  h += "#SBATCH --mem=" + s.memory + "\n#SBATCH --time=" + s.timeLimit + "\n";
  if (!s.partition.empty()) h += "#SBATCH --partition=" + s.partition + "\n";
  h += "#SBATCH --output=" + log + "\n";
  return h;
}

// Runs a command, returning its exit status and what it printed.
std::pair<int, std::string> runCommand(const std::string& cmd) {
  std::string out;
  FILE* p = popen((cmd + " 2>&1").c_str(), "r");
  if (!p) return {-1, "cannot run " + cmd};
  std::array<char, 4096> buf;
  size_t n;
  while ((n = fread(buf.data(), 1, buf.size(), p)) > 0) out.append(buf.data(), n);
  const int st = pclose(p);
  return {WIFEXITED(st) ? WEXITSTATUS(st) : -1, out};
}

std::string sbatch(const std::string& args) {
  const auto [status, out] = runCommand("sbatch --parsable " + args);
  std::string id = out.substr(0, out.find_first_of(";\n"));
  if (status != 0 || id.empty() || id.find_first_not_of("0123456789") != std::string::npos)
    throw std::runtime_error("sbatch " + args + " failed (status " + std::to_string(status) + "): " + out);
  return id;
}

std::vector<std::vector<std::string>> readTaskList(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path, "", "missing", "a task list of this sweep (inim sweep --slurm writes it)");
  std::vector<std::vector<std::string>> tasks;
  std::string line;
  while (std::getline(in, line)) {
    std::istringstream words(line);
    tasks.emplace_back();
    for (std::string id; words >> id;) tasks.back().push_back(id);
  }
  return tasks;
}

}  // namespace

SlurmSubmission writeSlurmScripts(const std::string& sweepDir, const std::vector<SweepPoint>& points,
                                  const SlurmSettings& s) {
  SlurmSubmission sub;
  std::vector<std::string> pending;
  for (const SweepPoint& p : points)
    if (completeSweepResult(sweepDir, p.id).is_null()) pending.push_back(p.id);
  sub.points = int(pending.size());
  if (pending.empty()) return sub;
  sub.number = nextSubmissionNumber(sweepDir);
  const std::string n = std::to_string(sub.number);
  const fs::path dir = slurmDir(sweepDir);
  const std::string absSweep = fs::absolute(sweepDir).lexically_normal().string();
  std::string tasks;
  const int per = std::max(1, s.pointsPerTask);
  for (size_t i = 0; i < pending.size(); i += per) {
    for (size_t k = i; k < std::min(pending.size(), i + per); ++k) tasks += (k > i ? " " : "") + pending[k];
    tasks += "\n";
    ++sub.tasks;
  }
  sub.firstAlone = sub.tasks > 1 && s.referenceCache != "off";
  sub.taskList = (dir / ("tasks-" + n + ".txt")).string();
  sub.arrayScript = (dir / ("array-" + n + ".sbatch")).string();
  sub.collectScript = (dir / ("collect-" + n + ".sbatch")).string();
  const std::string logs = (fs::absolute(dir) / "logs").string();
  std::string array = header("inim-sweep", s, logs + "/array-" + n + "_%A_%a.log");
  array += "#SBATCH --array=0-" + std::to_string(sub.tasks - 1) + "\n";
  array += s.extraEnvironment.empty() ? "" : s.extraEnvironment + "\n";
  array += "exec " + shellWord(s.program) + " sweep --out " + shellWord(absSweep) + " --slurm-task " +
           shellWord(fs::absolute(sub.taskList).string()) +
           " --task-index \"$SLURM_ARRAY_TASK_ID\" --threads \"${SLURM_CPUS_PER_TASK:-1}\"" +
           (s.referenceCache.empty() ? "" : " --reference-cache " + shellWord(s.referenceCache)) + "\n";
  SlurmSettings one = s;
  one.cpusPerTask = 1;
  std::string collect = header("inim-sweep-collect", one, logs + "/collect-" + n + "_%j.log");
  collect += s.extraEnvironment.empty() ? "" : s.extraEnvironment + "\n";
  collect += "exec " + shellWord(s.program) + " sweep --out " + shellWord(absSweep) + " --collect\n";
  fs::create_directories(logs);
  OutputSet out;
  writeTextFile(out.add(sub.taskList), tasks);
  writeTextFile(out.add(sub.arrayScript), array);
  writeTextFile(out.add(sub.collectScript), collect);
  out.commit();
  return sub;
}

std::string slurmSubmitCommands(const SlurmSubmission& sub) {
  const std::string array = shellWord(sub.arrayScript), collect = shellWord(sub.collectScript);
  if (!sub.firstAlone)
    return "a=$(sbatch --parsable " + array + ") && sbatch --dependency=afterok:$a " + collect + "\n";
  return "f=$(sbatch --parsable --array=0 " + array + ") && a=$(sbatch --parsable --array=1-" +
         std::to_string(sub.tasks - 1) + " --dependency=afterany:$f " + array + ") && sbatch --dependency=afterok:$f:$a " +
         collect + "\n";
}

void submitSlurm(const std::string& sweepDir, SlurmSubmission& sub) {
  if (sub.tasks == 0) return;
  const std::string array = shellWord(sub.arrayScript);
  if (sub.firstAlone) {
    sub.firstJob = sbatch("--array=0 " + array);
    sub.arrayJob =
        sbatch("--array=1-" + std::to_string(sub.tasks - 1) + " --dependency=afterany:" + sub.firstJob + " " + array);
    sub.collectJob = sbatch("--dependency=afterok:" + sub.firstJob + ":" + sub.arrayJob + " " + shellWord(sub.collectScript));
  } else {
    sub.arrayJob = sbatch(array);
    sub.collectJob = sbatch("--dependency=afterok:" + sub.arrayJob + " " + shellWord(sub.collectScript));
  }
  const Json j = {{"first_job", sub.firstJob}, {"array_job", sub.arrayJob}, {"collect_job", sub.collectJob},
                  {"task_list", sub.taskList}, {"tasks", sub.tasks}, {"points", sub.points}};
  OutputSet out;
  writeTextFile(out.add((slurmDir(sweepDir) / ("submitted-" + std::to_string(sub.number) + ".json")).string()),
                j.dump(2) + "\n");
  out.commit();
}

bool runSlurmTask(const std::string& sweepDir, const std::string& taskList, int index, int threads,
                  const std::string& referenceCache) {
  const auto tasks = readTaskList(taskList);
  if (index < 0 || index >= int(tasks.size()))
    throw InputError(taskList, "task_index", std::to_string(index),
                     "a task of this list, 0 to " + std::to_string(int(tasks.size()) - 1));
  bool recorded = true;
  for (const std::string& id : tasks[index]) {
    if (!completeSweepResult(sweepDir, id).is_null()) continue;  // a resubmitted task skips finished points
    std::printf("point %s\n", id.c_str());
    std::fflush(stdout);
    const Json r = runSweepPoint(sweepDir, id, threads, referenceCache);
    std::printf("point %s: %s\n", id.c_str(), r.value("status", "?").c_str());
    std::fflush(stdout);
    recorded = recorded && !recordedSweepResult(sweepDir, id).is_null();
  }
  return recorded;
}

std::string slurmLogOf(const std::string& sweepDir, const std::string& id) {
  const int last = nextSubmissionNumber(sweepDir) - 1;
  for (int n = last; n >= 1; --n) {
    const std::string ns = std::to_string(n);
    const auto tasks = readTaskList((slurmDir(sweepDir) / ("tasks-" + ns + ".txt")).string());
    for (size_t k = 0; k < tasks.size(); ++k) {
      if (std::find(tasks[k].begin(), tasks[k].end(), id) == tasks[k].end()) continue;
      const fs::path submitted = slurmDir(sweepDir) / ("submitted-" + ns + ".json");
      std::string job = "%A";
      if (fs::exists(submitted)) {
        const Json j = readJsonFile(submitted.string());
        job = k == 0 && !j.value("first_job", "").empty() ? j.value("first_job", "") : j.value("array_job", "%A");
      }
      return (fs::absolute(slurmDir(sweepDir)) / "logs" / ("array-" + ns + "_" + job + "_" + std::to_string(k) + ".log"))
          .string();
    }
  }
  return "";
}

}  // namespace inim
