// inim display info [FILE] [--json]: the derived quantities of a display description.
#include <cstdio>
#include <memory>
#include <string>

#include "cli/commands.h"
#include "cli/options.h"
#include "display/display.h"
#include "display/display_info.h"

namespace inim::cli {

void addDisplayCommand(CLI::App& app) {
  CLI::App* display = &app;
  display->require_subcommand(1);
  struct Opts {
    std::string file;
    bool json = false;
  };
  auto opts = std::make_shared<Opts>();
  auto* info = display->add_subcommand(
      "info", "Print derived quantities: f, viewing angle, reference image plane, EI vs lens pitch, viewing zones, "
              "depth range, assumptions");
  info->add_option("FILE", opts->file, "Display JSON (default: optics/displays/paper-prototype.json)");
  addSetting(info, "json", opts->json);
  info->callback([opts] {
    const std::string path = displayPathOrDefault(opts->file);
    Display d = loadDisplay(path);
    if (opts->json)
      std::printf("%s\n", displayInfoJson(d).dump(2).c_str());
    else
      std::printf("%s", displayInfoText(d).c_str());
  });
}

}  // namespace inim::cli
