// inim study NAME --out DIR [--display FILE] [--quick]: a validation study (src/studies/studies.h) that
// writes report.md, plots (PNG) and their data (CSV) into DIR. Exit status 1 when the
// study's verdict fails, 2 for bad input.
#include <cstdio>
#include <memory>

#include "cli/commands.h"
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
  cmd->add_option("--out", o->study.outDir, "Output folder")->required();
  cmd->add_option("--display", o->study.displayPath, "Display JSON (default: the paper's prototype)");
  cmd->add_flag("--quick", o->study.quick,
                "The CI-sized form the tests run (fewer depths, smaller images and budgets; its own tolerances)");
  cmd->callback([o]() {
    const StudyReport r = runStudy(o->name, o->study);
    for (const auto& v : r.values)
      std::printf("%-55s measured %9.3f  predicted %9.3f  (tol %2.0f%%)  %s\n", v.name.c_str(), v.measured, v.predicted,
                  100.0 * v.tolerance, v.pass ? "ok" : "FAIL");
    for (const auto& f : r.files) std::printf("wrote %s\n", f.c_str());
    std::printf("%s: %s\n", r.study.c_str(), r.pass ? "PASS" : "FAIL");
    if (!r.pass) throw CLI::RuntimeError(1);
  });
}

}  // namespace inim::cli
