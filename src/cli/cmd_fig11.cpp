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
  addSetting(cmd, "out", o->s.outDir)->required();
  addSetting(cmd, "display", o->s.displayPath);
  addSetting(cmd, "field", o->s.fieldPath, "--scene");
  addSetting(cmd, "camera", o->s.camera);
  addSetting(cmd, "mla", o->mla);
  addChoiceSetting(cmd, "chief_rays", o->s.rays.chiefRays, {ChiefRays::Pinhole, ChiefRays::Traced}, chiefRaysName);
  addSetting(cmd, "width", o->s.width);
  addSetting(cmd, "spp", o->s.spp);
  addSetting(cmd, "aperture_grid", o->s.apertureGrid);
  addSetting(cmd, "reference_spp", o->s.referenceSpp);
  addSetting(cmd, "eia_spp", o->s.eiaSpp);
  addSetting(cmd, "angle", o->s.angleDeg);
  addSetting(cmd, "poses", o->s.poses);
  addSetting(cmd, "distance_mm", o->s.distanceMm);
  addSetting(cmd, "calibration", o->s.calibrationPath);
  addSetting(cmd, "budget", o->s.budget);
  addSetting(cmd, "budget_calibration", o->s.budgetCalibrationPath);
  addSetting(cmd, "budget_rungs", o->s.budgetRungs);
  addSetting(cmd, "budget_spp", o->s.budgetSpp);
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
    observer.budgetDone = [](const PoseBudget& b) { std::printf("%s", fig11BudgetText(b).c_str()), std::fflush(stdout); };
    runFig11(o->s, observer);
    std::printf("%s", fig11WrittenText(o->s).c_str());
  });
}

}  // namespace inim::cli
