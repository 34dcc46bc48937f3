// Every numeric option of every command refuses values no device has (1e308, -1e308, 2^63,
// infinity, NaN) with the settings table's range, naming its flag, before any work: a
// regression suite generated from the commands themselves, so a new option is covered the day
// it is added. The parse runs in-process (the validators throw before any command runs).
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "cli/commands.h"
#include "cli/options.h"
#include "core/error.h"

using namespace inim;

namespace {

// Every command (and sub-command) below the program, with its path.
void collect(CLI::App* app, std::vector<CLI::App*>& out) {
  for (CLI::App* sub : app->get_subcommands({})) {
    out.push_back(sub);
    collect(sub, out);
  }
}

std::vector<std::string> pathOf(const CLI::App* cmd) {
  std::vector<std::string> path;
  for (; cmd && cmd->get_parent(); cmd = cmd->get_parent()) path.insert(path.begin(), cmd->get_name());
  return path;
}

}  // namespace

TEST(CliRanges, EveryNumericOptionRefusesValuesNoDeviceHas) {
  CLI::App probe;
  cli::addCommands(probe);
  std::vector<CLI::App*> commands;
  collect(&probe, commands);
  int checked = 0;
  for (CLI::App* cmd : commands) {
    for (const CLI::Option* opt : cmd->get_options()) {
      const std::string flag = opt->get_name();
      if (flag.rfind("--", 0) != 0 || flag == "--help") continue;
      std::string key = flag.substr(2);
      for (char& c : key) c = c == '-' ? '_' : c;
      const SettingInfo& info = cli::settingFor(cmd, key);
      if (std::isnan(info.lo)) continue;
      for (const char* bad : {"1e308", "-1e308", "9223372036854775808", "inf", "nan"}) {
        CLI::App app;
        cli::addCommands(app);
        std::vector<std::string> args = pathOf(cmd);
        args.push_back(flag);
        args.push_back(bad);
        std::vector<const char*> argv = {"inim"};
        for (const auto& a : args) argv.push_back(a.c_str());
        try {
          app.parse(int(argv.size()), argv.data());
          ADD_FAILURE() << flag << " " << bad << " accepted";
        } catch (const InputError& e) {
          EXPECT_EQ(e.key(), flag);
          EXPECT_EQ(e.expected(), rangeText(info)) << flag;
        } catch (const CLI::ParseError& e) {
          // An integer option refuses a number it cannot hold while converting: also exit 2.
          EXPECT_TRUE(std::string(bad) != "1e308" || std::string(e.what()).find(flag) != std::string::npos)
              << flag << " " << bad << ": " << e.what();
        }
        ++checked;
      }
    }
  }
  EXPECT_GT(checked, 5 * 50);  // about 60 numeric options
}
