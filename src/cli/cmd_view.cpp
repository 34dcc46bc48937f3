// inim view: what a camera sees when the display shows an EIA (spectral Monte Carlo through the
// camera lens, the MLA and the panel's subpixels; src/display_view/view_renderer.h).
// inim reference: the same camera and pose looking at the scene itself, at the placement the
// EIA was made with (src/display_view/reference_renderer.h). Both run in src/runs/camera_run.h.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <memory>
#include <optional>
#include <string>
#include <tuple>

#include "cli/commands.h"
#include "cli/options.h"
#include "core/error.h"
#include "core/format.h"
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
  CLI::Option *focusOpt = nullptr, *widthOpt = nullptr, *heightOpt = nullptr;
  // The settings, checked: 0 means "the default" inside; given on the command line it is a mistake.
  CameraRunSettings settings() const {
    if (focusOpt->count() && !(s.focusMm > 0.0))
      throw InputError("", "focus_mm", formatNumber(s.focusMm), "a focus distance > 0 mm");
    for (auto [opt, v, key] : {std::tuple{widthOpt, s.width, "width"}, {heightOpt, s.height, "height"}})
      if (opt->count() && v < 1) throw InputError("", key, std::to_string(v), "a whole number of pixels >= 1");
    return s;
  }
};

void addCameraPoseOptions(CLI::App* cmd, CameraPoseOpts& o) {
  cmd->add_option("--camera", o.s.camera, "Camera: a name in optics/cameras/ or a JSON file (default: alvium-1800-u-500c)");
  addChoiceOption(cmd, "--camera-model", o.s.model,
                  {CameraModelKind::RealLens, CameraModelKind::ThinLens, CameraModelKind::Pinhole}, cameraModelName,
                  "Camera model (default: the camera file's)");
  cmd->add_option("--distance-mm", o.s.distanceMm,
                                  "Camera (entrance pupil) to display centre, mm (default: the camera file's distance_mm)");
  cmd->add_option("--rot-h-deg", o.s.rotHDeg,
                  "Display rotation about its vertical axis, degrees; + turns its right edge away from the camera")
      ->capture_default_str();
  cmd->add_option("--rot-v-deg", o.s.rotVDeg,
                  "Display rotation about its horizontal axis, degrees; + turns its top edge away from the camera")
      ->capture_default_str();
  o.focusOpt = cmd->add_option("--focus-mm", o.s.focusMm, "Focus distance from the entrance pupil, mm (default: the camera "
                                             "distance, i.e. the MLA plane)");
  o.widthOpt = cmd->add_option("--width", o.s.width, "Image width in pixels (default: the sensor's; a smaller width keeps the field "
                                        "of view and scales the pixel pitch)");
  o.heightOpt = cmd->add_option("--height", o.s.height, "Image height in pixels (default: the sensor's aspect ratio)");
  cmd->add_option("--spp", o.spp,
                  "Samples per pixel (default: 1 stratum for the quadrature estimator, " +
                      std::to_string(ViewSettings{}.spp) + " samples for the sampled ones)");
  cmd->add_option("--exposure", o.s.exposure,
                  "Exposure factor applied to the EXR and the PNG, or auto (99th percentile of the brightest channel "
                  "-> 0.9)")
      ->capture_default_str();
  cmd->add_option("--out", o.s.out, "Output EXR: linear, white-balanced camera RGB x exposure")->required();
  cmd->add_option("--png", o.s.png, "sRGB PNG (default: beside --out, same name, .png)");
  cmd->add_flag("--quiet", o.quiet, "Print nothing but warnings");
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
  std::optional<std::string> mla, spectral, estimator;
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
  if (o.spectral == "visible") vs.spectral = SpectralSampling::Visible;
  applyEstimatorPolicy(vs, o.estimator.value_or("auto"), o.cam.spp.has_value());
  return vs;
}

ViewRunSettings viewRunSettings(const ViewOpts& o) {
  ViewRunSettings s = o.s;
  s.camera = o.cam.settings();
  s.displayPath = o.display.display;
  s.layout = layoutOverride(o.display);
  if (o.mla == "ideal") s.mla = MlaKind::Ideal;
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
    std::fprintf(stderr, "%s", outOfViewWarning(r.view).c_str());
    if (o.cam.quiet) return;
    std::printf("%s", summaryText(r.view, s.view, secondsSince(t0)).c_str());
    std::printf("%s", comparisonText(r).c_str());
    if (!r.hasMetrics) std::fprintf(stderr, "inim: warning: no pixel sees the display; no metrics\n");
    std::printf("exposure:    %s (both images)\nwrote:       ", formatNumber(r.exposure).c_str());
    for (size_t i = 0; i < r.written.size(); ++i) std::printf("%s%s", i ? ", " : "", r.written[i].c_str());
    std::printf("\n");
    return;
  }
  const ViewRunResult r = runView(s, loaded);
  std::fprintf(stderr, "%s", outOfViewWarning(r).c_str());
  if (o.cam.quiet) return;
  std::printf("%s", summaryText(r, s.view, secondsSince(t0)).c_str());
  std::printf("%s", writtenText(r, o.cam.s.out).c_str());
}

void addViewReferenceOptions(CLI::App* cmd, ViewReferenceOpts& o) {
  cmd->add_flag("--reference", o.on,
                "Also render the scene itself from the same pose and compare (as inim fig11 does): NAME_reference, "
                "NAME_error.png, NAME_metrics.json and the error budget NAME_budget.json|csv|png beside --out");
  cmd->add_option("--scene,--field", o.scene,
                  "--reference: the EIA's scene or field (default: the run file's, else scenes/paper-fig7.json)");
  cmd->add_option("--run", o.run, "--reference: the EIA's run file (scene, placement)");
  addPlacementOptions(cmd, o.place);
  cmd->add_option("--eia-exposure", o.rs.eiaExposure,
                                     "--reference: the EIA's drive per unit field luminance (default: its EXR "
                                     "header, written by inim eia and inim fig11)");
  cmd->add_option("--reference-spp", o.rs.referenceSpp, "--reference: samples per pixel of the reference")
      ->capture_default_str();
  cmd->add_flag("--no-budget", o.noBudget, "--reference: compare only, without the error budget");
  cmd->add_option("--budget-rungs", o.rs.budgetRungs,
                  "--reference: only these budget rungs (comma separated, as inim fig11 --budget-rungs)")
      ->delimiter(',');
  cmd->add_option("--budget-calibration", o.rs.budgetCalibrationPath,
                  "--reference: the budget's calibration rung, a .cube or .clf from inim calibrate");
  cmd->add_option("--budget-spp", o.rs.budgetSpp, "--reference: strata per pixel of every budget rung")
      ->capture_default_str();
}

}  // namespace

void addViewCommand(CLI::App& app) {
  auto o = std::make_shared<ViewOpts>();
  CLI::App* cmd = &app;
  addDisplayOptions(cmd, o->display);
  cmd->add_option("--eia", o->s.eiaPath, "EIA: linear drive values (EXR from inim eia), panel-sized or EIA-sized; a PNG is "
                                   "decoded through the panel's EOTF")
      ->required();
  cmd->add_option("--mla", o->mla, "MLA model: real (refracting lenslets) or ideal (paraxial thin lenses, the "
                                   "pinhole-MLA comparison)")
      ->check(CLI::IsMember({"real", "ideal"}))
      ->default_str(o->s.mla == MlaKind::Real ? "real" : "ideal");
  cmd->add_option("--gap-mm", o->s.gapMm, "Panel to MLA reference plane, mm (default: the display's "
                                                    "reconstruction gap)");
  cmd->add_option("--spectral", o->spectral, "Wavelength sampling: primaries (importance-sampled per panel primary) "
                                             "or visible (4-wavelength packets)")
      ->check(CLI::IsMember({"primaries", "visible"}))
      ->default_str(spectralSamplingName(o->view.spectral));
  cmd->add_option("--estimator", o->estimator,
                  "Panel estimator: point (subpixel under each ray), footprint (box average over the sample's "
                  "share of the pixel footprint), quadrature (pixel area, aperture and spectra all by quadrature, no "
                  "noise; spp = strata per pixel, default 1) or auto (quadrature: the lowest error for the time at "
                  "every width in inim bench)")
      ->check(CLI::IsMember({"point", "footprint", "quadrature", "auto"}))
      ->default_str("auto");
  cmd->add_option("--aperture-grid", o->view.apertureGrid,
                  "quadrature: the camera aperture's quadrature table, N x N cells over the exit pupil")
      ->check(CLI::Range(2, 64))->capture_default_str();
  cmd->add_option("--wavelength-nodes", o->view.wavelengthNodes,
                  "quadrature, when something is dispersive: wavelength nodes per primary (1: each primary's "
                  "median wavelength, weighted by its whole spectrum)")
      ->check(CLI::Range(1, 64))->capture_default_str();
  cmd->add_option("--background", o->view.backgroundY, "Luminance of the (D65 grey) background around the display, in the "
                                                  "image's units (default 0: black)");
  cmd->add_option("--emission-cos-n", o->s.emitter.cosExponent, "Extra cos^n angular emission profile on top of the panel's (0: none)");
  cmd->add_flag("--no-cover-glass", o->noCoverGlass, "Ignore the panel's cover glass");
  cmd->add_flag("--no-cull", o->noCull, "Trace every tile, also those that cannot see the display");
  cmd->add_flag("--relative", o->relative, "Panel white = luminance 1 instead of its peak luminance in cd/m^2");
  addCameraPoseOptions(cmd, o->cam);
  addViewReferenceOptions(cmd, o->ref);
  addRunOptions(cmd, o->cam.run, [o] { runViewCommand(*o); });
}

void addReferenceCommand(CLI::App& app) {
  struct Opts {
    CameraPoseOpts cam;
    std::optional<std::string> scene, display;
    std::string run;
    PlacementArgs place;
    std::string dispersion = "auto";
  };
  auto o = std::make_shared<Opts>();
  CLI::App* cmd = &app;
  cmd->add_option("--scene,--field", o->scene,
                  "Scene JSON, trained radiance field (.inimrf) or Gaussian splats (.ply, .splat) (default: the run file's, else scenes/paper-fig7.json)");
  cmd->add_option("--run", o->run, "Run file of the EIA (placement, scene, display); options override it");
  addPlacementOptions(cmd, o->place);
  cmd->add_option("--display", o->display, "Display JSON (default: the run file's, else the paper prototype): "
                                           "checks that the display area is in view");
  addCameraPoseOptions(cmd, o->cam);
  cmd->add_option("--camera-dispersion", o->dispersion,
                  "auto (trace the camera lens per wavelength only when it spreads a point's colours over more "
                  "than 0.25 px), trace, or ignore (rays at 550 nm carry every wavelength)")
      ->check(CLI::IsMember({"auto", "trace", "ignore"}))
      ->capture_default_str();
  addRunOptions(cmd, o->cam.run, [o] {
    const auto t0 = std::chrono::steady_clock::now();
    const RunFile run = o->run.empty() ? RunFile{} : loadRunFile(o->run);
    ReferenceRunSettings s;
    s.reference.dispersion = o->dispersion == "trace"    ? CameraDispersion::Trace
                             : o->dispersion == "ignore" ? CameraDispersion::Ignore
                                                         : CameraDispersion::Auto;
    s.camera = o->cam.settings();
    resolveSetting(s.fieldPath, run.scene, o->scene);
    s.placement = run.placement;
    s.placementOverride = placementOverride(o->place);
    resolveSetting(s.displayPath, run.display, o->display);
    resolveSetting(s.reference.spp, std::nullopt, o->cam.spp);
    o->cam.run.applySeed(s.reference.seed);
    s.reference.progress = !o->cam.quiet;
    const ReferenceRunResult r = runReference(s, [&](const ReferenceRunResult& v) {
      if (o->cam.quiet) return;
      std::printf("scene:       %s; placement %s\n", v.fieldPath.c_str(), v.placement.describe().c_str());
      std::printf("%s", cameraText(v.camera).c_str());
      std::fflush(stdout);
    });
    if (!r.displayInView)
      std::fprintf(stderr, "inim: warning: the display is out of the camera's view (%s); the reference is rendered anyway\n",
                   r.camera.pose.describe().c_str());
    if (o->cam.quiet) return;
    std::printf("%s", summaryText(r, s.reference, secondsSince(t0)).c_str());
    std::printf("%s", writtenText(r, o->cam.s.out).c_str());
  });
}

}  // namespace inim::cli
