// Command-line tests of `inim sweep` on a small display: a bad plan is refused before anything
// is written; a local sweep records a failing point and goes on; a re-run skips complete points
// (checked: a damaged one is redone) and gives the same table; a point re-runs alone with the
// command its point.json gives; Ctrl-C stops the points and leaves no result half-written.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>

#include <chrono>
#include <filesystem>
#include <thread>

#include "cli/cli_helpers.h"
#include "cli/run_cli.h"
#include "core/json_config.h"
#include "scratch_dir.h"

namespace fs = std::filesystem;
using fixtures::readBytes;
using inim::Json;
using inim::readJsonFile;

namespace {

ScratchDir scratchFolder("test_cli_sweep");

std::string fresh(const std::string& name) {
  const std::string dir = scratchFolder.path(name);
  fs::remove_all(dir);
  return dir;
}

// A plan on the small display: gap x (a working MLA, one whose focal length no lens can have).
std::string writePlan(const std::string& name, const std::string& axes, const std::string& extra = "") {
  const std::string display = scratchFolder.path("display.json");
  if (!fs::exists(display)) writeText(display, smallDisplayJson(11, 9, 9));
  const std::string plan = scratchFolder.path(name);
  writeText(plan, R"({"base": {"display": ")" + display + R"(",
    "fig11": {"width": 40, "poses": ["centre"], "reference_spp": 2, "eia_spp": 1, "depth_error": false}},
    "axes": [)" + axes + "]" + extra + "}");
  return plan;
}

std::vector<std::string> pointIds(const std::string& out) {
  std::vector<std::string> ids;
  for (const auto& e : fs::directory_iterator(out + "/points")) ids.push_back(e.path().filename().string());
  std::sort(ids.begin(), ids.end());
  return ids;
}

// Files with ".tmp" in their name anywhere under `dir`.
int temporariesUnder(const std::string& dir) {
  int n = 0;
  for (const auto& e : fs::recursive_directory_iterator(dir))
    n += e.path().filename().string().find(".tmp") != std::string::npos;
  return n;
}

}  // namespace

TEST(CliSweep, ABadPlanIsRefusedBeforeAnythingIsWritten) {
  const std::string out = fresh("bad");
  expectBadInputWith(runInim, "sweep --plan " + writePlan("bad1.json", R"({"path": "mla.pich_mm", "values": [1]})") +
                                  " --out " + out,
                     {"bad1.json", "axes[0].path", "mla.pich_mm"}, {out + "/plan.json"});
  expectBadInputWith(runInim, "sweep --plan " + writePlan("bad2.json", R"({"path": "mla.pitch_mm", "values": []})") +
                                  " --out " + out,
                     {"bad2.json", "axes[0].values", "[]"}, {out + "/plan.json"});
  expectBadInputWith(runInim, "sweep --plan " + writePlan("bad3.json", R"({"path": "mla.pitch_mm", "values": ["a"]})") +
                                  " --out " + out,
                     {"bad3.json", "axes[0].values", "\"a\""}, {out + "/plan.json"});
  expectBadInputWith(runInim,
                     "sweep --max-points 3 --out " + out + " --plan " +
                         writePlan("bad4.json", R"({"path": "mla.pitch_mm", "values": [0.8, 0.9]},
                                                   {"path": "reconstruction_gap_mm", "values": [3, 3.5]})"),
                     {"bad4.json", "4 points", "at most 3"}, {out + "/plan.json"});
  expectBadInputWith(runInim, "sweep --out " + out, {"plan.json"}, {out + "/results.csv"});
  EXPECT_FALSE(fs::exists(out));
}

TEST(CliSweep, ALocalSweepRecordsFailuresResumesAndReRunsAPointAlone) {
  const std::string out = fresh("local");
  const std::string plan = writePlan("local.json", R"({"path": "reconstruction_gap_mm", "values": [3.2, 3.8]})",
                                     R"(, "alternatives": [{"name": "mla", "options": [{"label": "f3"},
                                        {"label": "broken", "set": {"mla.focal_length_mm": -3}}]}])");
  const CliResult first = runInim("sweep --plan " + plan + " --out " + out + " --jobs 2");
  // Two points fail (their display cannot be built): recorded, the others finish, exit 1.
  EXPECT_EQ(first.status, 1) << first.output;
  EXPECT_NE(first.output.find("4 points: 4 run (2 failed), 0 already complete"), std::string::npos) << first.output;
  EXPECT_NE(first.output.find("focal_length_mm"), std::string::npos) << first.output;
  const std::string table = readBytes(out + "/results.csv");
  EXPECT_NE(table.find(",broken,3.2,failed,"), std::string::npos) << table;
  EXPECT_NE(table.find(",f3,3.8,ok,centre,"), std::string::npos) << table;
  EXPECT_NE(readBytes(out + "/report.md").find("## Points without results"), std::string::npos);

  // Again: the two complete points are skipped, the failed ones tried again.
  const CliResult second = runInim("sweep --out " + out);
  EXPECT_NE(second.output.find("4 points: 2 run (2 failed), 2 already complete"), std::string::npos) << second.output;
  EXPECT_EQ(readBytes(out + "/results.csv"), table);

  // A complete point whose metrics.json changed is not complete: redone, to the same table.
  const Json results = readJsonFile(out + "/results.json");
  std::string okId;
  for (const Json& p : results["points"])
    if (p["status"] == "ok") okId = p["point"];
  ASSERT_FALSE(okId.empty());
  writeText(out + "/points/" + okId + "/fig11/metrics.json", "{}");
  const CliResult third = runInim("sweep --out " + out);
  EXPECT_NE(third.output.find("4 points: 3 run (2 failed), 1 already complete"), std::string::npos) << third.output;
  EXPECT_EQ(readBytes(out + "/results.csv"), table);

  // The point alone, by the command its point.json gives.
  const Json point = readJsonFile(out + "/points/" + okId + "/point.json");
  const std::string command = point["command"];
  ASSERT_EQ(command.find(std::string(INIM_BINARY) + " sweep --out " + out + " --point " + okId), 0u) << command;
  const Json before = readJsonFile(out + "/points/" + okId + "/result.json");
  const CliResult alone = runInim(command.substr(std::string(INIM_BINARY).size() + 1));
  EXPECT_EQ(alone.status, 0) << alone.output;
  const Json after = readJsonFile(out + "/points/" + okId + "/result.json");
  EXPECT_EQ(after["poses"], before["poses"]);  // the same metrics, bit for bit
  EXPECT_EQ(temporariesUnder(out), 0);
}

TEST(CliSweep, CtrlCStopsThePointsAndLeavesNoResultHalfWritten) {
  const std::string out = fresh("interrupted");
  const std::string plan =
      writePlan("interrupted.json", R"({"path": "reconstruction_gap_mm", "range": {"from": 3, "to": 4, "count": 6}})");
  const std::string log = scratchFolder.path("interrupted.log");
  const pid_t pid = spawnInimBinary(INIM_BINARY, "sweep --plan " + plan + " --out " + out + " --jobs 2", log);
  ASSERT_GT(pid, 0);
  // Stopped once two points run (their logs exist) and before the sweep ends.
  const auto end = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  auto running = [&] {
    int logs = 0;
    std::error_code ec;
    for (const auto& e : fs::recursive_directory_iterator(out + "/points", ec)) logs += e.path().filename() == "log.txt";
    return logs >= 2;
  };
  while (!running() && std::chrono::steady_clock::now() < end) std::this_thread::sleep_for(std::chrono::milliseconds(5));
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  kill(pid, SIGINT);
  int status = 0;
  waitpid(pid, &status, 0);
  ASSERT_TRUE(WIFEXITED(status)) << readBytes(log);
  EXPECT_EQ(WEXITSTATUS(status), 130) << readBytes(log);
  // Each point has a whole result or none, and no point was recorded as failed by the stop.
  int complete = 0;
  for (const std::string& id : pointIds(out)) {
    const std::string result = out + "/points/" + id + "/result.json";
    if (!fs::exists(result)) continue;
    EXPECT_EQ(readJsonFile(result)["status"], "ok") << readBytes(result);
    ++complete;
  }
  EXPECT_LT(complete, 6) << readBytes(log);
  EXPECT_EQ(temporariesUnder(out), 0);
  EXPECT_FALSE(fs::exists(out + "/results.csv"));
  // The re-run finishes the rest.
  const CliResult again = runInim("sweep --out " + out + " --jobs 2");
  EXPECT_EQ(again.status, 0) << again.output;
  EXPECT_NE(again.output.find(std::to_string(complete) + " already complete"), std::string::npos) << again.output;
}
