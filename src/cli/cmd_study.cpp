// inim study NAME --out DIR [--display FILE] [--quick]: a validation study (src/studies/studies.h) that
// writes report.md, plots (PNG) and their data (CSV) into DIR. Exit status 1 when the
// study's verdict fails, 2 for bad input.
#include <cstdio>
#include <memory>

#include "cli/commands.h"
#include "cli/options.h"
#include "studies/studies.h"

namespace inim::cli {

void addStudyCommand(CLI::App& app) {
  struct Opts {
    std::string name;
    StudyOptions study;
  };
  auto o = std::make_shared<Opts>();
  CLI::App* cmd = &app;
  std::string list = "Studies:\n";
  for (const StudyInfo& s : studies()) list += "  " + std::string(s.name) + ": " + s.summary + "\n";
  cmd->footer(list);
  cmd->add_option("name", o->name, "Study (listed below)")->required()->check(CLI::IsMember(studyNames()));
  addSetting(cmd, "out", o->study.outDir)->required();
  addSetting(cmd, "display", o->study.displayPath);
  addSetting(cmd, "quick", o->study.quick);
  cmd->callback([o]() {
    const StudyReport r = runStudy(o->name, o->study);
    std::printf("%s", studyReportText(r).c_str());
    if (!r.pass) throw CLI::RuntimeError(1);
  });
}

}  // namespace inim::cli
