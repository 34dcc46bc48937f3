// The command line's shared helpers, called in-process: "an option given on the command line,
// else the run file's value, else the default", and how a library error's setting key is named
// by its flag.
#include <gtest/gtest.h>

#include <algorithm>
#include <optional>
#include <string>
#include <vector>

#include "cli/options.h"
#include "core/error.h"

using namespace inim;
using namespace inim::cli;

namespace {

// Parses `args` for an app with one option --spp (default 1) and returns that option.
struct OneOption {
  CLI::App app{"test"};
  int spp = 1;
  CLI::Option* opt = app.add_option("--spp", spp);
  explicit OneOption(std::vector<std::string> args) {
    std::reverse(args.begin(), args.end());  // CLI11 takes them last first
    app.parse(args);
  }
};

}  // namespace

TEST(CliOptions, OptionGivenWinsOverRunFileAndDefault) {
  OneOption given({"--spp", "7"});
  EXPECT_EQ(optionOrRun(given.opt, given.spp, std::optional<int>(3), 1), 7);
  EXPECT_EQ(optionOrRun(given.opt, given.spp, std::optional<int>(), 1), 7);
}

TEST(CliOptions, RunFileWinsOverDefaultWhenOptionAbsent) {
  OneOption absent({});
  EXPECT_EQ(optionOrRun(absent.opt, absent.spp, std::optional<int>(3), 1), 3);
  EXPECT_EQ(optionOrRun(absent.opt, absent.spp, std::optional<int>(), 5), 5);
  // An option given with its default value still wins (it was given).
  OneOption sameAsDefault({"--spp", "1"});
  EXPECT_EQ(optionOrRun(sameAsDefault.opt, sameAsDefault.spp, std::optional<int>(3), 1), 1);
  // No option at all (a command without it): run file, else default.
  EXPECT_EQ(optionOrRun<std::string>(nullptr, "x", std::optional<std::string>("run"), "default"), "run");
}

TEST(CliOptions, LibraryErrorIsPrintedWithTheFlag) {
  const InputError e("", "spp", "0", "a whole number >= 1");
  const InputError shown = asCommandLineError(e);
  EXPECT_EQ(shown.key(), "--spp");
  EXPECT_NE(std::string(shown.what()).find("key '--spp'"), std::string::npos) << shown.what();
  EXPECT_EQ(shown.value(), "0");
  EXPECT_EQ(shown.expected(), "a whole number >= 1");
  EXPECT_EQ(flagForSetting("vcp_mm"), "--vcp-mm");
  EXPECT_EQ(flagForSetting("width"), "--width");
  EXPECT_EQ(flagForSetting("rot_h_deg"), "--rot-h-deg");
  EXPECT_EQ(flagForSetting("angle_deg"), "--angle");
}

TEST(CliOptions, FileErrorsAndUnknownKeysKeepTheirKey) {
  // A run file's key names the file's own setting, not a flag.
  const InputError fromFile("run.json", "spp", "0", "a whole number >= 1");
  EXPECT_EQ(asCommandLineError(fromFile).key(), "spp");
  EXPECT_EQ(asCommandLineError(fromFile).file(), "run.json");
  // A key no flag sets, and a flag already, stay as they are.
  EXPECT_EQ(asCommandLineError(InputError("", "placement.scale", "[0]", "x")).key(), "placement.scale");
  EXPECT_EQ(asCommandLineError(InputError("", "--eia", "\"a\"", "x")).key(), "--eia");
}
