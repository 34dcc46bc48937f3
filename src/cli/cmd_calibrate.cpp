// inim calibrate: characterise the display's colour chain at several poses, fit and verify
// corrections, export the panel-side one (src/runs/calibrate_run.h).
#include <cstdio>
#include <memory>
#include <optional>

#include "cli/commands.h"
#include "cli/options.h"
#include "runs/calibrate_run.h"
#include "runs/eia_run.h"

namespace inim::cli {

void addCalibrateCommand(CLI::App& app) {
  struct Opts {
    CalibrateSettings s;
    std::optional<std::string> white, gamut;  // absent: the library's defaults
    RunOptions run;
  };
  auto o = std::make_shared<Opts>();
  CLI::App* cmd = &app;
  CalibrateSettings& s = o->s;
  cmd->add_option("--out", s.outDir, "Output folder")->required();
  cmd->add_option("--display", s.displayPath, "Display JSON (default: the paper's prototype)");
  cmd->add_option("--assumed-display", s.assumedDisplayPath,
                  "The display the EIAs are made for, when the panel shown differs from its description (e.g. "
                  "placeholder primaries in the file, measured ones in the panel) (default: --display)");
  cmd->add_option("--camera", s.camera, "Camera description (name in optics/cameras or a file)")->capture_default_str();
  cmd->add_option("--poses", s.poses, "Poses to measure, of centre, left, right, top, bottom (the first one is the "
                                      "headline pose)")
      ->delimiter(',')
      ->capture_default_str();
  cmd->add_option("--angle", s.angleDeg, "Angle of the side poses, degrees")->capture_default_str();
  cmd->add_option("--distance-mm", s.distanceMm, "Camera distance (default: the camera description's)");
  cmd->add_option("--field-space", s.fieldSpace,
                  "The field's colour space: lin_rec709, display_p3, acescg or spectral")->capture_default_str();
  cmd->add_option("--white-balance", o->white, "The EIA's white gains: none (colorimetric) or d65 (the paper's path)")
      ->default_str(s.whiteBalanceD65 ? "d65" : "none");
  cmd->add_option("--gamut", o->gamut, "Gamut mapping: clip or desaturate")
      ->default_str(s.gamut == GamutMapping::Clip ? "clip" : "desaturate");
  cmd->add_option("--grid-levels", s.gridLevels, "Levels per channel of the drive grid used to fit")->capture_default_str();
  cmd->add_option("--holdout", s.holdOutInGamut, "Hold-out colours from the panel's gamut")->capture_default_str();
  cmd->add_option("--holdout-out-of-gamut", s.holdOutOutOfGamut, "Hold-out colours outside it (inside Rec.2020)")
      ->capture_default_str();
  cmd->add_option("--patches", s.patchCsv, "More colours to verify: a CSV with columns name,X,Y,Z (D65 white Y = 1)");
  cmd->add_option("--correction", s.correction, "Exported model: auto (lowest hold-out error at the first pose), "
                                                "matrix_3x3, root_polynomial_2 or lut3d")
      ->capture_default_str();
  cmd->add_option("--lut-size", s.lutSize, "Nodes per axis of the exported 3D LUT")->capture_default_str();
  cmd->add_option("--panel-bits", s.panelBits, "Bits of the panel's encoded input (0: float)")->capture_default_str();
  cmd->add_option("--width", s.render.width, "View width in pixels of the measuring renders")->capture_default_str();
  cmd->add_option("--direct-checks", s.directChecks, "Patches rendered directly to check the linear chain model")
      ->capture_default_str();
  addRunOptions(cmd, o->run, [o] {
    o->run.applySeed(o->s.seed);
    o->run.applySeed(o->s.render.view.seed);
    if (o->white) o->s.whiteBalanceD65 = parseWhiteBalanceD65(*o->white);
    if (o->gamut) o->s.gamut = parseGamut(*o->gamut);
    CalibrateObserver observer;
    observer.poseDone = [](const PoseResponse& p) {
      std::printf("pose %-7s %-7s %7lld px measured, %.1f s\n", p.pose.name.c_str(), p.pose.label.c_str(),
                  (long long)p.pixels, p.seconds);
      std::fflush(stdout);
    };
    const CalibrateResult r = runCalibration(o->s, observer);
    std::fputs(calibrationSummary(r).c_str(), stdout);
  });
}

}  // namespace inim::cli
