// inim fig11: the paper's Fig. 11 reproduced in software (src/runs/fig11.h): the EIA,
// five reconstructed and five reference views, a contact sheet and metrics.
#include <cstdio>
#include <memory>

#include "cli/commands.h"
#include "cli/options.h"
#include "runs/fig11.h"

namespace inim::cli {

void addFig11Command(CLI::App& app) {
  struct Opts {
    Fig11Settings s;
    std::string mla = "real";
    PlacementArgs place;
    RunOptions run;
  };
  auto o = std::make_shared<Opts>();
  CLI::App* cmd = &app;
  cmd->add_option("--out", o->s.outDir, "Output folder")->required();
  cmd->add_option("--display", o->s.displayPath, "Display JSON (default: the paper's prototype)");
  cmd->add_option("--scene,--field", o->s.fieldPath,
                  "The field: a scene JSON, a trained radiance field (.inimrf) or Gaussian splats (.ply, .splat) (default: scenes/paper-fig7.json)");
  cmd->add_option("--camera", o->s.camera, "Camera description (name in optics/cameras or a file)")->capture_default_str();
  cmd->add_option("--mla", o->mla, "MLA model for the reconstruction: real (refracting) or ideal (thin lenslets)")
      ->check(CLI::IsMember({"real", "ideal"}))
      ->capture_default_str();
  cmd->add_option("--width", o->s.width, "View width in pixels (the sensor's pixel pitch scales; 2592 = full)")
      ->capture_default_str();
  cmd->add_option("--spp", o->s.spp,
                  "Strata per pixel of the reconstructed views (quadrature estimator: deterministic; with the "
                  "default aperture grid RMSE 2.5% of the mean against 16 strata on a 32 x 32 grid at 648 px, "
                  "2.2% at 2 strata in 1.5 x the time)")
      ->capture_default_str();
  cmd->add_option("--aperture-grid", o->s.apertureGrid,
                  "Aperture quadrature grid of the reconstructed views (N x N cells over the exit pupil; 16: RMSE "
                  "1.1% at 4 strata, 2.2 x the time)")
      ->check(CLI::Range(2, 64))
      ->capture_default_str();
  cmd->add_option("--reference-spp", o->s.referenceSpp, "Samples per pixel of the reference views")->capture_default_str();
  cmd->add_option("--eia-spp", o->s.eiaSpp, "Field samples per display ray for the EIA")->capture_default_str();
  cmd->add_option("--angle", o->s.angleDeg, "Viewing angle of the four side views, degrees")->capture_default_str();
  cmd->add_option("--poses", o->s.poses, "Only these poses (comma separated): centre, left, right, top, bottom")
      ->delimiter(',');
  cmd->add_option("--distance-mm", o->s.distanceMm, "Camera distance (default: the camera description's)");
  cmd->add_option("--calibration", o->s.calibrationPath,
                  "Panel calibration applied to the EIA's drive values, as `inim eia --calibration` (.cube or "
                  ".clf; default: none)");
  cmd->add_flag("--budget", o->s.budget,
                "Error budget per view: the ladder from an ideal display to the real one, the full chain with one "
                "effect removed, the noise floor (budget.json, budget.csv, budget.png)");
  cmd->add_option("--budget-calibration", o->s.budgetCalibrationPath,
                  "The budget's calibration rung: a .cube or .clf from inim calibrate (default: --calibration)");
  cmd->add_option("--budget-rungs", o->s.budgetRungs,
                  "Only these rungs (comma separated): ideal, +subpixels, +real_mla, +cover_glass, +colour_chain, "
                  "+calibration, -subpixels, -real_mla, -cover_glass, -colour_chain")
      ->delimiter(',');
  cmd->add_option("--budget-spp", o->s.budgetSpp,
                  "Strata per pixel of every rung, the full chain included (1: RMSE 2.5% of the mean, within 3x the "
                  "plain run's time; --spp's value reuses the run's own view as the full chain)")
      ->capture_default_str();
  addPlacementOptions(cmd, o->place);
  addRunOptions(cmd, o->run, [o] {
    o->s.mla = o->mla == "ideal" ? MlaKind::Ideal : MlaKind::Real;
    o->run.applySeed(o->s.seed);
    o->s.placement = placementOverride(o->place);
    Fig11Observer observer;
    observer.eiaDone = [](const Fig11Result& r) { std::printf("%s", fig11EiaText(r).c_str()); };
    observer.viewDone = [](const Fig11View& v) {
      std::fprintf(stderr, "%s", fig11ViewWarnings(v).c_str());
      std::printf("%s", fig11ViewText(v).c_str());
    };
    observer.budgetDone = [](const PoseBudget& b) {
      std::printf("  budget %-7s %s\n", b.pose.c_str(), budgetLine(b).c_str());
      std::fflush(stdout);
    };
    runFig11(o->s, observer);
    std::printf("%s", fig11WrittenText(o->s).c_str());
  });
}

}  // namespace inim::cli
