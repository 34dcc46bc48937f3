// Inputs must be regular files of a size the memory limit allows: a directory, a device, a
// loop of links or a huge file is refused by name before any read.
#include <gtest/gtest.h>

#include <filesystem>

#include "core/error.h"
#include "core/input_file.h"
#include "core/size_budget.h"
#include "fixtures.h"

namespace fs = std::filesystem;
using namespace inim;

TEST(InputFile, RegularFilesPassWithTheirSize) {
  const std::string f = fixtures::scratchFile("input_file_ok.json", "{}\n");
  EXPECT_EQ(checkInputFile(f), 3u);
  EXPECT_EQ(checkInputFile(f + ".missing"), 0u);  // left to the reader, which names what it wanted
}

TEST(InputFile, DirectoriesDevicesAndLinkLoopsAreRefused) {
  const std::string dir = fixtures::scratchPath("input_file_dir.json");
  fs::create_directories(dir);
  EXPECT_EQ(fixtures::expectInputError([&] { checkInputFile(dir); }).value(), "a directory");
  EXPECT_EQ(fixtures::expectInputError([] { checkInputFile("/dev/zero"); }).value(), "a device, pipe or socket");
  const std::string loop = fixtures::scratchPath("input_file_loop.json");
  fs::remove(loop);
  fs::create_symlink(loop, loop);
  const InputError e = fixtures::expectInputError([&] { checkInputFile(loop); });
  EXPECT_EQ(e.file(), loop);
  EXPECT_EQ(e.value(), "a loop of symbolic links");
  fs::remove(loop);
}

TEST(InputFile, FilesLargerThanTheMemoryLimitAreRefused) {
  const std::string f = fixtures::scratchFile("input_file_big.bin", "x");
  fs::resize_file(f, kMinInputFileLimitBytes + 1);  // sparse: no disk used
  ScopedMemoryLimit limit(1024);  // the floor, 64 MiB, is the limit
  const InputError e = fixtures::expectInputError([&] { checkInputFile(f); });
  EXPECT_NE(e.expected().find("--max-memory"), std::string::npos) << e.what();
}
