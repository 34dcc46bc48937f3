// inim view: what a camera sees when the display shows an EIA (spectral Monte Carlo through the
// camera lens, the MLA and the panel's subpixels; src/display_view/view_renderer.h).
// inim reference: the same camera and pose looking at the scene itself, at the placement the
// EIA was made with (src/display_view/reference_renderer.h). Both run in src/runs/camera_run.h.
#include <chrono>
#include <cstdio>
#include <memory>
#include <optional>
#include <string>

#include "cli/commands.h"
#include "cli/options.h"
#include "runs/camera_run.h"
#include "runs/view_reference.h"
#include "runs/run_file.h"

namespace inim::cli {

namespace {

// Options shared by `view` and `reference`: camera, pose, image size, samples, outputs.
struct CameraPoseOpts {
  CameraRunSettings s;
  std::optional<int> spp;  // absent: the library's (ViewSettings, ReferenceSettings)
  bool quiet = false;
  RunOptions run;
};

void addCameraPoseOptions(CLI::App* cmd, CameraPoseOpts& o) {
  addSetting(cmd, "camera", o.s.camera);
  addChoiceSetting(cmd, "camera_model", o.s.model,
                   {CameraModelKind::RealLens, CameraModelKind::ThinLens, CameraModelKind::Pinhole}, cameraModelName);
  addSetting(cmd, "distance_mm", o.s.distanceMm);
  addSetting(cmd, "rot_h_deg", o.s.rotHDeg);
  addSetting(cmd, "rot_v_deg", o.s.rotVDeg);
  addSetting(cmd, "focus_mm", o.s.focusMm);
  addSetting(cmd, "width", o.s.width);
  addSetting(cmd, "height", o.s.height);
  addSetting(cmd, "spp", o.spp);
  addSetting(cmd, "exposure", o.s.exposure);
  addSetting(cmd, "out", o.s.out)->required();
  addSetting(cmd, "png", o.s.png);
  addSetting(cmd, "quiet", o.quiet);
}

// `inim view --reference`: the scene, its placement and the budget's settings.
struct ViewReferenceOpts {
  ViewReferenceSettings rs;  // the settings the options write directly
  bool on = false, noBudget = false;
  std::optional<std::string> scene;
  std::string run;
  PlacementArgs place;
};

// The options write the library's settings directly; those with a policy of their own
// (estimator, spp) or a name to parse are optional.
struct ViewOpts {
  ViewReferenceOpts ref;
  CameraPoseOpts cam;
  DisplayArgs display;
  ViewRunSettings s;
  ViewSettings view;  // before the estimator policy
  std::optional<std::string> estimator;
  bool noCoverGlass = false, relative = false, noCull = false;
};

// The estimator policy on the options given, from ViewSettings' defaults (autoViewSettings
// when nothing is given).
ViewSettings viewSettings(const ViewOpts& o) {
  ViewSettings vs = o.view;
  resolveSetting(vs.spp, std::nullopt, o.cam.spp);
  o.cam.run.applySeed(vs.seed);
  vs.progress = !o.cam.quiet;
  vs.cullTiles = !o.noCull;
  applyEstimatorPolicy(vs, o.estimator.value_or("auto"), o.cam.spp.has_value());
  return vs;
}

ViewRunSettings viewRunSettings(const ViewOpts& o) {
  ViewRunSettings s = o.s;
  s.camera = o.cam.s;
  s.displayPath = o.display.display.value_or("");
  s.layout = layoutOverride(o.display);
  s.emitter.absolute = !o.relative;
  s.emitter.coverGlass = !o.noCoverGlass;
  s.view = viewSettings(o);
  return s;
}

ViewReferenceSettings viewReferenceSettings(const ViewReferenceOpts& o) {
  const RunFile run = o.run.empty() ? RunFile{} : loadRunFile(o.run);
  ViewReferenceSettings rs = o.rs;
  resolveSetting(rs.fieldPath, run.scene, o.scene);
  rs.placement = run.placement;
  rs.placementOverride = placementOverride(o.place);
  rs.budget = !o.noBudget;
  return rs;
}

void runViewCommand(const ViewOpts& o) {
  const auto t0 = std::chrono::steady_clock::now();
  const ViewRunSettings s = viewRunSettings(o);
  auto loaded = [&](const ViewRunResult& v) {
    std::fprintf(stderr, "%s", driveClampedWarning(v, s.eiaPath).c_str());
    if (o.cam.quiet) return;
    std::printf("%s", loadedText(s, v).c_str());
    std::fflush(stdout);
  };
  if (o.ref.on) {
    const ViewReferenceResult r = runViewWithReference(s, viewReferenceSettings(o.ref), loaded);
    std::fprintf(stderr, "%s", comparisonWarnings(r).c_str());
    if (!o.cam.quiet) std::printf("%s%s", summaryText(r.view, s.view, secondsSince(t0)).c_str(), comparisonText(r).c_str());
    return;
  }
  const ViewRunResult r = runView(s, loaded);
  std::fprintf(stderr, "%s", outOfViewWarning(r).c_str());
  if (!o.cam.quiet) std::printf("%s%s", summaryText(r, s.view, secondsSince(t0)).c_str(), writtenText(r, o.cam.s.out).c_str());
}

void addViewReferenceOptions(CLI::App* cmd, ViewReferenceOpts& o) {
  addSetting(cmd, "reference", o.on);
  addSetting(cmd, "field", o.scene, "--scene");
  addSetting(cmd, "run", o.run);
  addPlacementOptions(cmd, o.place);
  addSetting(cmd, "eia_exposure", o.rs.eiaExposure);
  addSetting(cmd, "reference_spp", o.rs.referenceSpp);
  addSetting(cmd, "no_budget", o.noBudget);
  addSetting(cmd, "budget_rungs", o.rs.budgetRungs);
  addSetting(cmd, "budget_calibration", o.rs.budgetCalibrationPath);
  addSetting(cmd, "budget_spp", o.rs.budgetSpp);
}

}  // namespace

void addViewCommand(CLI::App& app) {
  auto o = std::make_shared<ViewOpts>();
  CLI::App* cmd = &app;
  addDisplayOptions(cmd, o->display);
  addSetting(cmd, "eia", o->s.eiaPath)->required();
  addChoiceSetting(cmd, "mla", o->s.mla, {MlaKind::Real, MlaKind::Ideal}, mlaKindName);
  addSetting(cmd, "gap_mm", o->s.gapMm);
  addChoiceSetting(cmd, "spectral", o->view.spectral, {SpectralSampling::Primaries, SpectralSampling::Visible},
                   spectralSamplingName);
  addSetting(cmd, "estimator", o->estimator)->default_str("auto");
  addSetting(cmd, "aperture_grid", o->view.apertureGrid);
  addSetting(cmd, "wavelength_nodes", o->view.wavelengthNodes);
  addSetting(cmd, "background", o->view.backgroundY);
  addSetting(cmd, "emission_cos_n", o->s.emitter.cosExponent);
  addSetting(cmd, "no_cover_glass", o->noCoverGlass);
  addSetting(cmd, "no_cull", o->noCull);
  addSetting(cmd, "relative", o->relative);
  addCameraPoseOptions(cmd, o->cam);
  addViewReferenceOptions(cmd, o->ref);
  addRunOptions(cmd, o->cam.run, [o] { runViewCommand(*o); });
}

void addReferenceCommand(CLI::App& app) {
  struct Opts {
    CameraPoseOpts cam;
    ReferenceRunSettings s;
    std::optional<std::string> scene, display;
    std::string run;
    PlacementArgs place;
  };
  auto o = std::make_shared<Opts>();
  CLI::App* cmd = &app;
  addSetting(cmd, "field", o->scene, "--scene");
  addSetting(cmd, "run", o->run);
  addPlacementOptions(cmd, o->place);
  addSetting(cmd, "display", o->display);
  addCameraPoseOptions(cmd, o->cam);
  addChoiceSetting(cmd, "camera_dispersion", o->s.reference.dispersion,
                   {CameraDispersion::Auto, CameraDispersion::Trace, CameraDispersion::Ignore}, cameraDispersionName);
  addRunOptions(cmd, o->cam.run, [o] {
    const auto t0 = std::chrono::steady_clock::now();
    const RunFile run = o->run.empty() ? RunFile{} : loadRunFile(o->run);
    ReferenceRunSettings s = o->s;
    s.camera = o->cam.s;
    resolveSetting(s.fieldPath, run.scene, o->scene);
    s.placement = run.placement;
    s.placementOverride = placementOverride(o->place);
    resolveSetting(s.displayPath, run.display, o->display);
    resolveSetting(s.reference.spp, std::nullopt, o->cam.spp);
    o->cam.run.applySeed(s.reference.seed);
    s.reference.progress = !o->cam.quiet;
    const ReferenceRunResult r = runReference(s, [&](const ReferenceRunResult& v) {
      if (!o->cam.quiet) std::printf("%s", loadedText(v).c_str()), std::fflush(stdout);
    });
    std::fprintf(stderr, "%s", displayOutOfViewWarning(r).c_str());
    if (!o->cam.quiet)
      std::printf("%s%s", summaryText(r, s.reference, secondsSince(t0)).c_str(), writtenText(r, o->cam.s.out).c_str());
  });
}

}  // namespace inim::cli
