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

// Parses `args` for an app with one optional option --spp and returns its value.
std::optional<int> parsedSpp(std::vector<std::string> args) {
  CLI::App app{"test"};
  std::optional<int> spp;
  app.add_option("--spp", spp);
  std::reverse(args.begin(), args.end());  // CLI11 takes them last first
  app.parse(args);
  return spp;
}

}  // namespace

TEST(CliOptions, OptionGivenWinsOverRunFileAndDefault) {
  int spp = 1;  // the library's default
  resolveSetting(spp, std::optional<int>(3), parsedSpp({"--spp", "7"}));
  EXPECT_EQ(spp, 7);
  spp = 1;
  resolveSetting(spp, std::optional<int>(), parsedSpp({"--spp", "7"}));
  EXPECT_EQ(spp, 7);
}

TEST(CliOptions, RunFileWinsOverDefaultWhenOptionAbsent) {
  int spp = 1;
  resolveSetting(spp, std::optional<int>(3), parsedSpp({}));
  EXPECT_EQ(spp, 3);
  spp = 5;
  resolveSetting(spp, std::optional<int>(), parsedSpp({}));
  EXPECT_EQ(spp, 5);  // neither: the default stands
  // An option given with the default's value still wins (it was given).
  spp = 1;
  resolveSetting(spp, std::optional<int>(3), parsedSpp({"--spp", "1"}));
  EXPECT_EQ(spp, 1);
  // Text settings parsed by the library: the text that wins, or none.
  const std::optional<std::string> run("desaturate"), none;
  EXPECT_EQ(*chosenText(run, std::optional<std::string>("clip")), "clip");
  EXPECT_EQ(*chosenText(run, none), "desaturate");
  EXPECT_FALSE(chosenText(none, none).has_value());
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
