// Command-line tests of `inim place` (the placement page's server) and of what it writes: the
// process prints one URL with its token and serves until SIGINT; its run file gives, through
// `inim eia --run`, the same EIA bytes as the equivalent command-line flags and as its own
// "write EIA" job.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <regex>
#include <string>

#include "cli/cli_helpers.h"
#include "cli/run_cli.h"
#include "place/place_jobs.h"
#include "place/place_state.h"
#include "scratch_dir.h"

namespace fs = std::filesystem;
using namespace inim;

namespace {

std::string quoted(const std::vector<std::string>& args) {
  std::string s;
  for (const auto& a : args) s += " '" + a + "'";
  return s;
}

}  // namespace

TEST(CliPlace, RunFileFlagsAndJobGiveTheSameEiaBytes) {
  ScratchDir dir("cli_place_eia");
  PlaceJobInput in;
  in.fieldPath = data("scenes/test/point-sphere.json");
  in.state.display = dir.path("display.json");
  writeText(in.state.display, smallDisplayJson(21, 15, 9));
  in.state.placement.translateMm = Vec3d(0.3, -0.2, 4.0 + 1.0 / 3.0);
  in.state.placement.rotateDeg = Vec3d(0.0, 0.0, 7.5);
  in.state.vcpMm = 60.0;
  in.state.layout = "toed-in";
  in.state.viewingDistanceMm = 300.0;
  ASSERT_EQ(writeRunFileJob(in, dir.path("out"), "run"), std::vector<std::string>{"run.json"});

  const CliResult a = runInim("eia --quiet --run " + dir.path("out/run.json") + " --out " + dir.path("a.exr"));
  ASSERT_EQ(a.status, 0) << a.output;
  const CliResult b = runInim("eia --quiet" + quoted(eiaArguments(in.state, in.fieldPath)) + " --out " + dir.path("b.exr"));
  ASSERT_EQ(b.status, 0) << b.output;
  writeEiaJob(in, dir.path("out"), "job", false);
  const std::string eia = fixtures::readBytes(dir.path("a.exr"));
  ASSERT_FALSE(eia.empty());
  EXPECT_EQ(eia, fixtures::readBytes(dir.path("b.exr")));
  EXPECT_EQ(eia, fixtures::readBytes(dir.path("out/job.exr")));
  EXPECT_EQ(fixtures::readBytes(dir.path("a.png")), fixtures::readBytes(dir.path("b.png")));
  EXPECT_EQ(fixtures::readBytes(dir.path("a.png")), fixtures::readBytes(dir.path("out/job.png")));
}

// On a display given as a compound stack, the page's "write EIA" job makes the EIA `inim eia`
// makes from its run file: along the chief rays traced through the stack.
TEST(CliPlace, AStackDisplaysJobIsTheTracedEiaOfItsRunFile) {
  ScratchDir dir("cli_place_stack");
  Json j = Json::parse(smallDisplayJson(11, 9, 9));
  j.erase("mla");
  j.erase("reconstruction_gap_mm");
  j["stack"] = Json::parse(R"({"layers": [{"type": "gap", "thickness_mm": 2.5},
      {"type": "lens_array", "pitch_mm": 0.9, "material": "PMMA", "thickness_mm": 1.0, "front": {"radius_mm": -2.0}},
      {"type": "gap", "thickness_mm": 0.8},
      {"type": "lens_array", "pitch_mm": 0.9, "material": "PMMA", "thickness_mm": 1.0, "back": {"radius_mm": 2.0}}]})");
  PlaceJobInput in;
  in.fieldPath = data("scenes/test/point-sphere.json");
  in.state.display = dir.path("compound.json");
  writeText(in.state.display, j.dump(2));
  in.state.placement.translateMm = Vec3d(0.0, 0.0, 4.0);
  ASSERT_EQ(writeRunFileJob(in, dir.path("out"), "run"), std::vector<std::string>{"run.json"});
  const CliResult a = runInim("eia --run " + dir.path("out/run.json") + " --out " + dir.path("a.exr"));
  ASSERT_EQ(a.status, 0) << a.output;
  EXPECT_NE(a.output.find("chief rays traced through the stack"), std::string::npos) << a.output;
  writeEiaJob(in, dir.path("out"), "job", false);
  const std::string eia = fixtures::readBytes(dir.path("a.exr"));
  ASSERT_FALSE(eia.empty());
  EXPECT_EQ(eia, fixtures::readBytes(dir.path("out/job.exr")));
}

TEST(CliPlace, PrintsOneUrlWithATokenAndStopsOnSigint) {
  ScratchDir dir("cli_place_url");
  int fds[2];
  ASSERT_EQ(pipe(fds), 0);
  const pid_t pid = fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    dup2(fds[1], 1);
    close(fds[0]);
    execl(INIM_BINARY, INIM_BINARY, "place", "--scene", data("scenes/test/point-sphere.json").c_str(), "--out",
          dir.path("out").c_str(), (char*)nullptr);
    _exit(127);
  }
  close(fds[1]);
  FILE* f = fdopen(fds[0], "r");
  char line[512] = "";
  ASSERT_NE(fgets(line, sizeof line, f), nullptr);
  EXPECT_TRUE(std::regex_match(std::string(line), std::regex("http://127\\.0\\.0\\.1:[0-9]+/\\?token=[0-9a-f]{32}\n")))
      << line;
  kill(pid, SIGINT);
  int status = 0;
  waitpid(pid, &status, 0);
  fclose(f);
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 130) << status;
  EXPECT_TRUE(fs::is_directory(dir.path("out")));
}

TEST(CliPlace, BadStartIsExitStatus2) {
  ScratchDir dir("cli_place_bad");
  expectBadInputWith(runInim, "place --scene " + dir.path("missing.json") + " --out " + dir.path("o"), {"missing.json"}, {});
  expectBadInputWith(runInim, "place --display " + dir.path("nodisplay.json") + " --out " + dir.path("o"),
                     {"nodisplay.json"}, {});
}
