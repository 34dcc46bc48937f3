// OutputSet and writeImage under failure and interruption: old outputs stay intact until a
// commit, temporaries never outlive their run (stale ones of dead processes are swept, those of
// live processes are not), SIGINT/SIGTERM turn into Interrupted at the polling points, and the
// same image written twice gives the same bytes (no time stamp in the EXR header).
#include <gtest/gtest.h>
#include <OpenImageIO/imageio.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <chrono>
#include <filesystem>
#include <string>
#include <thread>

#include "core/image.h"
#include "core/interrupt.h"
#include "core/output_file.h"
#include "core/parallel.h"
#include "core/progress.h"
#include "scratch_dir.h"

namespace fs = std::filesystem;
using namespace inim;
using fixtures::readBytes;
using fixtures::writeBytes;

namespace {

ScratchDir scratch("output_file");

// A fresh folder in the scratch folder.
std::string folder(const std::string& name) {
  const std::string dir = scratch.path(name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

// The id of a process that has exited and been reaped (so kill(pid, 0) fails with ESRCH).
pid_t deadPid() {
  const pid_t pid = fork();
  if (pid == 0) _exit(0);
  int status = 0;
  waitpid(pid, &status, 0);
  return pid;
}

int hiddenTemporaries(const std::string& dir) {
  int n = 0;
  for (const auto& e : fs::directory_iterator(dir)) n += e.path().filename().string().find(".tmp") != std::string::npos;
  return n;
}

// Delivers `sig` through the real handlers, as Ctrl-C or kill would: to this thread (raise), or
// to the process (`toProcess`: kill; any thread that does not block it takes it, soon).
void receiveSignal(int sig, bool toProcess = false) {
  signal(sig, SIG_DFL);  // a test run as a background job may start with it ignored
  installInterruptHandlers();
  if (toProcess)
    kill(getpid(), sig);
  else
    raise(sig);
}

// Clears the signal and restores the default action after each interruption test.
struct InterruptTest : ::testing::Test {
  void TearDown() override {
    clearInterrupt();
    signal(SIGINT, SIG_DFL);
    signal(SIGTERM, SIG_DFL);
  }
};

Image gradient(int w, int h) {
  Image img(w, h, {"R", "G", "B"});
  for (size_t i = 0; i < img.data.size(); ++i) img.data[i] = float(i % 977) / 977.0f;
  return img;
}

}  // namespace

TEST(OutputSet, OldOutputStaysUntilCommitAndTemporaryNeverOutlivesTheSet) {
  const std::string dir = folder("commit"), out = dir + "/a.txt";
  writeBytes(out, "old");
  {
    OutputSet set;
    writeTextFile(set.add(out), "new");
    EXPECT_EQ(hiddenTemporaries(dir), 1);
  }  // not committed: a failed run
  EXPECT_EQ(readBytes(out), "old");
  EXPECT_EQ(hiddenTemporaries(dir), 0);
  {
    OutputSet set;
    writeTextFile(set.add(out), "new");
    set.commit();
  }
  EXPECT_EQ(readBytes(out), "new");
  EXPECT_EQ(hiddenTemporaries(dir), 0);
}

TEST(OutputSet, SweepsStaleTemporariesOfDeadProcessesOnly) {
  const std::string dir = folder("stale");
  const pid_t dead = deadPid();
  ASSERT_TRUE(kill(dead, 0) == -1 && errno == ESRCH) << "pid " << dead << " was reused";
  const std::string d = std::to_string(dead), live = std::to_string(getpid());
  const std::vector<std::string> stale = {".eia.tmp" + d + ".exr", ".eia.tmp" + d + ".sdf", ".notes.tmp" + d};
  const std::vector<std::string> kept = {
      ".eia.tmp" + live + ".exr",  // this process: alive
      ".eia.tmp1.exr",             // pid 1: alive (EPERM counts as alive)
      "eia.tmp" + d + ".exr",      // not hidden: not inim's pattern
      ".eia.tmp" + d + "x.exr",    // no pid at the end
      ".eia.tmp" + d + ".exr.bak", // the temporary's name is not the whole name
      "eia.exr"};
  for (const auto& f : stale) writeBytes(dir + "/" + f, "partial");
  for (const auto& f : kept) writeBytes(dir + "/" + f, "keep");
  fs::create_directory(dir + "/.dir.tmp" + d + ".exr");  // not a regular file
  {
    OutputSet set;
    set.add(dir + "/other.png");  // any run into the folder sweeps it
  }
  for (const auto& f : stale) EXPECT_FALSE(fs::exists(dir + "/" + f)) << f;
  for (const auto& f : kept) EXPECT_EQ(readBytes(dir + "/" + f), "keep") << f;
  EXPECT_TRUE(fs::is_directory(dir + "/.dir.tmp" + d + ".exr"));
  EXPECT_EQ(removeStaleTemporaries(dir), 0);  // nothing more to sweep
  writeBytes(dir + "/.x.tmp" + d + ".png", "partial");
  EXPECT_EQ(removeStaleTemporaries(dir), 1);
}

TEST_F(InterruptTest, SignalIsRecordedAndPolledAsInterrupted) {
  EXPECT_EQ(interruptSignal(), 0);
  EXPECT_NO_THROW(throwIfInterrupted());
  receiveSignal(SIGTERM);
  EXPECT_EQ(interruptSignal(), SIGTERM);
  try {
    throwIfInterrupted();
    ADD_FAILURE() << "no Interrupted";
  } catch (const Interrupted& e) {
    EXPECT_EQ(e.signal, SIGTERM);
    EXPECT_EQ(e.exitStatus(), 143);
  }
  clearInterrupt();
  receiveSignal(SIGINT);
  EXPECT_EQ(Interrupted{interruptSignal()}.exitStatus(), 130);
}

TEST_F(InterruptTest, ParallelLoopsAndProgressStopOnASignal) {
  std::atomic<int64_t> done{0};
  const int64_t count = 1 << 20;
  // The signal arrives after the first chunk: the loop stops long before the end. It is sent to
  // the process, as Ctrl-C is (a thread-directed raise() on one of TBB's workers, which block
  // signals, would stay pending), and each chunk takes ~2 us, far longer than its delivery.
  EXPECT_THROW(parallelForRange(
                   count,
                   [&](int64_t b, int64_t e) {
                     if (done.fetch_add(e - b) == 0) receiveSignal(SIGINT, true);
                     volatile double work = 0.0;
                     for (int i = 0; i < 2000; ++i) work = work + i;
                   },
                   nullptr, 64),
               Interrupted);
  EXPECT_LT(done.load(), count / 2);
  EXPECT_THROW(parallelForTiles(64, 64, [](const Tile&) {}), Interrupted);
  ProgressBar bar("test", 10, false);
  EXPECT_THROW(bar.add(1), Interrupted);
}

TEST_F(InterruptTest, InterruptedRunRemovesItsTemporariesAndKeepsOldOutputs) {
  const std::string dir = folder("interrupted"), exr = dir + "/eia.exr", txt = dir + "/eia.txt";
  writeImage(gradient(40, 30), exr);
  writeBytes(txt, "old");
  const std::string oldExr = readBytes(exr);
  try {
    OutputSet set;
    writeTextFile(set.add(txt), "new");
    writeImage(gradient(40, 31), set.add(exr));
    receiveSignal(SIGTERM);
    EXPECT_THROW(writeImage(gradient(40, 31), set.add(dir + "/more.exr")), Interrupted);
    set.commit();
    ADD_FAILURE() << "commit after a signal";
  } catch (const Interrupted&) {
  }
  EXPECT_EQ(readBytes(exr), oldExr);
  EXPECT_EQ(readBytes(txt), "old");
  EXPECT_EQ(hiddenTemporaries(dir), 0);
  EXPECT_FALSE(fs::exists(dir + "/more.exr"));
}

TEST(WriteImage, SameImageTwiceGivesTheSameBytesWithoutATimeStamp) {
  const std::string dir = folder("bytes");
  const Image img = gradient(57, 300);  // 300 rows: the last band of rows is partial
  for (const std::string ext : {".exr", ".png"}) {
    writeImage(img, dir + "/a" + ext);
    std::this_thread::sleep_for(std::chrono::milliseconds(1100));  // a time stamp would change
    writeImage(img, dir + "/b" + ext);
    const std::string a = readBytes(dir + "/a" + ext);
    EXPECT_GT(a.size(), 100u) << ext;
    EXPECT_TRUE(a == readBytes(dir + "/b" + ext)) << ext << " files differ";
    auto in = OIIO::ImageInput::open(dir + "/a" + ext);
    ASSERT_TRUE(in);
    EXPECT_EQ(in->spec().find_attribute("DateTime"), nullptr) << ext;
  }
  const Image back = readImage(dir + "/a.exr");
  ASSERT_EQ(back.data.size(), img.data.size());
  EXPECT_TRUE(back.data == img.data);  // float EXR: exact, band by band
}
