// The outputs of real `inim eia` runs: a run stopped by SIGINT or SIGTERM while writing exits
// with 128 + the signal, leaves no temporary and the previous run's outputs byte for byte; a
// run killed outright (SIGKILL) leaves temporaries that the next run into the folder removes,
// sparing those of live processes; two identical runs give byte-identical EXR, PNG and SDF.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "cli/cli_helpers.h"
#include "cli/run_cli.h"
#include "scratch_dir.h"

extern char** environ;

namespace fs = std::filesystem;
using fixtures::readBytes;

namespace {

std::string binary() {
  if (const char* b = std::getenv("INIM_TEST_BINARY"); b && *b) return b;
  return INIM_BINARY;
}

ScratchDir scratchFolder("test_cli_outputs");

// A fresh folder in the scratch folder.
std::string folder(const std::string& name) {
  const std::string dir = scratchFolder.path(name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

// 100 x 60 EIs of 15 px: a 1506 x 906 px EIA and a 130 MB SDF, about a second of writing.
std::string largeDisplay() {
  static const std::string file = [] {
    const std::string f = scratchFolder.path("large.json");
    writeText(f, fixtures::smallDisplayJson({.cols = 100, .rows = 60, .eiPx = 15, .lensPitchMm = 1.5}));
    return f;
  }();
  return file;
}

std::string smallDisplay() {
  static const std::string file = [] {
    const std::string f = scratchFolder.path("small.json");
    writeText(f, smallDisplayJson(11, 9, 9));
    return f;
  }();
  return file;
}

// `inim eia` of the default scene into dir/<stem>.exr, .png and .sdf.
std::string eiaArgs(const std::string& display, const std::string& dir, const std::string& stem = "eia") {
  return "eia --quiet --display " + display + " --out " + dir + "/" + stem + ".exr --sdf " + dir + "/" + stem + ".sdf";
}

pid_t spawnInim(const std::string& args, const std::string& log) { return spawnInimBinary(binary(), args, log); }

// The names in `dir` that contain ".tmp" (+ `pid`, if given).
std::vector<std::string> temporaries(const std::string& dir, pid_t pid = 0) {
  const std::string mark = ".tmp" + (pid ? std::to_string(pid) : std::string());
  std::vector<std::string> found;
  for (const auto& e : fs::directory_iterator(dir))
    if (e.path().filename().string().find(mark) != std::string::npos) found.push_back(e.path().filename().string());
  return found;
}

// Waits until `pid` has a temporary in `dir` (it is writing its outputs); false if it ended
// first or took more than a minute.
bool waitUntilWriting(const std::string& dir, pid_t pid) {
  const auto end = std::chrono::steady_clock::now() + std::chrono::minutes(1);
  while (std::chrono::steady_clock::now() < end) {
    if (!temporaries(dir, pid).empty()) return true;
    if (waitpid(pid, nullptr, WNOHANG) == pid) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  return false;
}

int waitStatus(pid_t pid) {
  int status = 0;
  waitpid(pid, &status, 0);
  return status;
}

const std::vector<std::string> kOutputs = {"eia.exr", "eia.png", "eia.sdf"};

class CliInterrupt : public ::testing::TestWithParam<int> {};

}  // namespace

TEST_P(CliInterrupt, StoppedWhileWritingExitsCleanlyAndKeepsTheOldOutputs) {
  const int sig = GetParam();
  const std::string dir = folder("stop" + std::to_string(sig));
  CliResult first = runInimBinary(binary(), eiaArgs(largeDisplay(), dir));
  ASSERT_EQ(first.status, 0) << first.output;
  std::vector<std::string> old;
  for (const auto& f : kOutputs) old.push_back(readBytes(dir + "/" + f));

  // Another exposure: had this run committed, every output would differ.
  const std::string log = dir + "/../stop.log";
  const pid_t pid = spawnInim(eiaArgs(largeDisplay(), dir) + " --exposure 0.3", log);
  ASSERT_GT(pid, 0);
  ASSERT_TRUE(waitUntilWriting(dir, pid)) << readBytes(log);
  kill(pid, sig);
  const int status = waitStatus(pid);
  ASSERT_TRUE(WIFEXITED(status)) << "ended by signal " << WTERMSIG(status) << "\n" << readBytes(log);
  EXPECT_EQ(WEXITSTATUS(status), 128 + sig) << readBytes(log);
  EXPECT_NE(readBytes(log).find("interrupted"), std::string::npos) << readBytes(log);
  EXPECT_EQ(readBytes(log).find("libpng"), std::string::npos) << readBytes(log);  // one message, inim's
  EXPECT_EQ(temporaries(dir), std::vector<std::string>{});
  for (size_t i = 0; i < kOutputs.size(); ++i)
    EXPECT_TRUE(readBytes(dir + "/" + kOutputs[i]) == old[i]) << kOutputs[i] << " changed";
  fs::remove_all(dir);
}

TEST_P(CliInterrupt, StoppedWhileLoadingAHugeScenePromptly) {
  const int sig = GetParam();
  const std::string dir = folder("load" + std::to_string(sig));
  fs::create_directories(dir);
  std::string scene = R"({"materials": {"glow": {"type": "emitter", "spectrum": "D65"}}, "objects": [)";
  for (int i = 0; i < 400000; ++i)
    scene += std::string(i ? "," : "") + "{\"type\": \"sphere\", \"radius_mm\": 0.1, \"translate_mm\": [" +
             std::to_string(i % 1000) + ", " + std::to_string(i / 1000) + ", -10], \"material\": \"glow\"}";
  writeText(dir + "/big.json", scene + "]}");
  const std::string log = dir + "/../load.log";
  const pid_t pid = spawnInim("render --scene " + dir + "/big.json --width 8 --height 8 --spp 1 --out " + dir + "/r.exr", log);
  ASSERT_GT(pid, 0);
  // Signalled once it has opened the scene (the loading phase: reading, parsing, building).
  bool opened = false;
  const auto end = std::chrono::steady_clock::now() + std::chrono::seconds(30);
  while (!opened && std::chrono::steady_clock::now() < end && waitpid(pid, nullptr, WNOHANG) == 0) {
    std::error_code ec;
    for (const auto& fd : fs::directory_iterator("/proc/" + std::to_string(pid) + "/fd", ec))
      opened = opened || fs::read_symlink(fd.path(), ec).filename() == "big.json";
    if (!opened) std::this_thread::sleep_for(std::chrono::microseconds(200));
  }
  ASSERT_TRUE(opened) << readBytes(log);
  std::this_thread::sleep_for(std::chrono::milliseconds(100));
  const auto t0 = std::chrono::steady_clock::now();
  kill(pid, sig);
  const int status = waitStatus(pid);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  ASSERT_TRUE(WIFEXITED(status)) << readBytes(log);
  EXPECT_EQ(WEXITSTATUS(status), 128 + sig) << readBytes(log);
  // Within a second on a quiet machine (the note gives the time measured); 2 s leaves room for a
  // loaded one, far below the minutes a load that ignored the signal took.
  EXPECT_LT(seconds, 2.0);
  EXPECT_FALSE(fs::exists(dir + "/r.exr"));
  fs::remove_all(dir);
}

INSTANTIATE_TEST_SUITE_P(IntAndTerm, CliInterrupt, ::testing::Values(SIGINT, SIGTERM),
                         [](const auto& info) { return std::string(info.param == SIGINT ? "SIGINT" : "SIGTERM"); });

TEST(CliOutputs, KilledRunsTemporariesAreRemovedByTheNextRunLiveOnesKept) {
  const std::string dir = folder("killed"), log = dir + "/../killed.log";
  const pid_t pid = spawnInim(eiaArgs(largeDisplay(), dir), log);
  ASSERT_GT(pid, 0);
  ASSERT_TRUE(waitUntilWriting(dir, pid)) << readBytes(log);
  kill(pid, SIGKILL);  // cannot be caught: the temporaries stay behind
  const int status = waitStatus(pid);
  ASSERT_TRUE(WIFSIGNALED(status));
  const std::vector<std::string> stale = temporaries(dir, pid);
  ASSERT_FALSE(stale.empty());
  const std::string live = ".eia.tmp" + std::to_string(getpid()) + ".exr";  // this test: alive
  writeText(dir + "/" + live, "in progress");

  CliResult next = runInimBinary(binary(), eiaArgs(smallDisplay(), dir, "small"));
  ASSERT_EQ(next.status, 0) << next.output;
  for (const auto& f : stale) EXPECT_FALSE(fs::exists(dir + "/" + f)) << f << " was left";
  EXPECT_EQ(readBytes(dir + "/" + live), "in progress");
  EXPECT_EQ(temporaries(dir), std::vector<std::string>{live});
  EXPECT_TRUE(fs::exists(dir + "/small.exr") && fs::exists(dir + "/small.png") && fs::exists(dir + "/small.sdf"));
  fs::remove_all(dir);
}

// A write that fails part-way, as on a full disk: the shell's file-size limit (ulimit -f, with
// SIGXFSZ ignored, so that write() fails with EFBIG as it would with ENOSPC) stops the writes
// past 1 MB. The run exits 2 naming the file asked for, not its temporary, and leaves no output.
TEST(CliOutputs, AWriteThatFailsPartWayNamesTheFileAskedForAndLeavesNothing) {
  const std::string dir = folder("full");
  CliResult r = runInimBinary("trap '' XFSZ; ulimit -f 2048; exec " + binary(), eiaArgs(largeDisplay(), dir));
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find(dir + "/eia."), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find(".tmp"), std::string::npos) << r.output;
  EXPECT_EQ(temporaries(dir), std::vector<std::string>{});
  for (const auto& f : kOutputs) EXPECT_FALSE(fs::exists(dir + "/" + f)) << f;
  fs::remove_all(dir);
}

TEST(CliOutputs, IdenticalRunsGiveByteIdenticalFiles) {
  const std::string a = folder("same_a"), b = folder("same_b");
  CliResult r = runInimBinary(binary(), eiaArgs(smallDisplay(), a));
  ASSERT_EQ(r.status, 0) << r.output;
  std::this_thread::sleep_for(std::chrono::milliseconds(1100));  // a time stamp in a header would differ
  r = runInimBinary(binary(), eiaArgs(smallDisplay(), b));
  ASSERT_EQ(r.status, 0) << r.output;
  for (const auto& f : kOutputs) {
    const std::string first = readBytes(a + "/" + f);
    EXPECT_GT(first.size(), 200u) << f;
    EXPECT_TRUE(first == readBytes(b + "/" + f)) << f << " differs between identical runs";
  }
}
