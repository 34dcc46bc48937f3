// inim calibrate: characterise the display's colour chain at several poses, fit and verify
// corrections, export the panel-side one (src/runs/calibrate_run.h).
#include <cstdio>
#include <memory>
#include <optional>

#include "cli/commands.h"
#include "core/error.h"
#include "cli/options.h"
#include "runs/calibrate_run.h"
#include "runs/eia_run.h"

namespace inim::cli {

void addCalibrateCommand(CLI::App& app) {
  struct Opts {
    CalibrateSettings s;
    std::optional<std::string> white, gamut, grade;  // absent: the library's defaults
    RunOptions run;
  };
  auto o = std::make_shared<Opts>();
  CLI::App* cmd = &app;
  CalibrateSettings& s = o->s;
  addSetting(cmd, "out", s.outDir)->required();
  addSetting(cmd, "display", s.displayPath);
  addSetting(cmd, "assumed_display", s.assumedDisplayPath);
  addSetting(cmd, "camera", s.camera);
  addSetting(cmd, "poses", s.poses);
  addSetting(cmd, "angle", s.angleDeg);
  addSetting(cmd, "distance_mm", s.distanceMm);
  addSetting(cmd, "field_space", s.fieldSpace);
  addSetting(cmd, "white_balance", o->white)->default_str(s.whiteBalanceD65 ? "d65" : "none");
  addSetting(cmd, "gamut", o->gamut)->default_str(s.gamut == GamutMapping::Clip ? "clip" : "desaturate");
  addSetting(cmd, "grid_levels", s.gridLevels);
  addSetting(cmd, "holdout", s.holdOutInGamut);
  addSetting(cmd, "holdout_out_of_gamut", s.holdOutOutOfGamut);
  addSetting(cmd, "patches", s.patchCsv);
  addSetting(cmd, "correction", s.correction);
  addSetting(cmd, "lut_size", s.lutSize);
  addSetting(cmd, "panel_bits", s.panelBits);
  addSetting(cmd, "width", s.render.width);
  addSetting(cmd, "direct_checks", s.directChecks);
  addSetting(cmd, "grade", o->grade)->default_str("1,3");
  addRunOptions(cmd, o->run, [o] {
    o->run.applySeed(o->s.seed);
    o->run.applySeed(o->s.render.view.seed);
    if (o->white) o->s.whiteBalanceD65 = parseWhiteBalanceD65(*o->white);
    if (o->gamut) o->s.gamut = parseGamut(*o->gamut);
    if (o->grade) parseGrade(*o->grade, o->s);
    CalibrateObserver observer;
    observer.poseDone = [](const PoseResponse& p) { std::printf("%s", poseResponseText(p).c_str()), std::fflush(stdout); };
    const CalibrateResult r = runCalibration(o->s, observer);
    std::fputs(calibrationSummary(r).c_str(), stdout);
    if (!r.failedPoses.empty()) {  // the outputs are written; the exit status says the grade was missed
      std::string poses;
      for (const std::string& p : r.failedPoses) poses += (poses.empty() ? "" : ", ") + p;
      throw GradeFailed("the calibration misses its grade at " + poses + " (calibration.json: grade)");
    }
  });
}

}  // namespace inim::cli
