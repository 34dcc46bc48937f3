// inim view: what a camera sees when the display shows an EIA (spectral Monte Carlo through the
// camera lens, the MLA and the panel's subpixels; src/view/view_renderer.h).
// inim reference: the same camera and pose looking at the scene itself, at the placement the
// EIA was made with (src/view/reference_renderer.h). Both run in src/experiments/camera_run.h.
#include <chrono>
#include <cstdio>
#include <memory>
#include <string>

#include "cli/commands.h"
#include "cli/options.h"
#include "experiments/camera_run.h"

namespace inim::cli {

namespace {

// Options shared by `view` and `reference`: camera, pose, image size, samples, outputs.
struct CameraPoseOpts {
  CameraRunSettings s;
  std::string cameraModel;
  double distanceMm = 0.0;
  int spp = 16;
  bool quiet = false;
  RunOptions run;
  CLI::Option *distanceOpt = nullptr, *sppOpt = nullptr;
  // The settings with the options that need their own parsing applied.
  CameraRunSettings settings() const {
    CameraRunSettings c = s;
    if (!cameraModel.empty())
      c.model = cameraModel == "pinhole"     ? CameraModelKind::Pinhole
                : cameraModel == "thin-lens" ? CameraModelKind::ThinLens
                                             : CameraModelKind::RealLens;
    if (distanceOpt->count()) c.distanceMm = distanceMm;
    return c;
  }
};

void addCameraPoseOptions(CLI::App* cmd, CameraPoseOpts& o) {
  cmd->add_option("--camera", o.s.camera, "Camera: a name in optics/cameras/ or a JSON file (default: alvium-1800-u-500c)");
  cmd->add_option("--camera-model", o.cameraModel, "real-lens, thin-lens or pinhole (default: the camera file's)")
      ->check(CLI::IsMember({"real-lens", "thin-lens", "pinhole"}));
  o.distanceOpt = cmd->add_option("--distance-mm", o.distanceMm,
                                  "Camera (entrance pupil) to display centre, mm (default: the camera file's distance_mm)");
  cmd->add_option("--rot-h-deg", o.s.rotHDeg,
                  "Display rotation about its vertical axis, degrees; + turns its right edge away from the camera")
      ->capture_default_str();
  cmd->add_option("--rot-v-deg", o.s.rotVDeg,
                  "Display rotation about its horizontal axis, degrees; + turns its top edge away from the camera")
      ->capture_default_str();
  cmd->add_option("--focus-mm", o.s.focusMm, "Focus distance from the entrance pupil, mm (default: the camera "
                                             "distance, i.e. the MLA plane)");
  cmd->add_option("--width", o.s.width, "Image width in pixels (default: the sensor's; a smaller width keeps the field "
                                        "of view and scales the pixel pitch)");
  cmd->add_option("--height", o.s.height, "Image height in pixels (default: the sensor's aspect ratio)");
  o.sppOpt = cmd->add_option("--spp", o.spp, "Samples per pixel")->capture_default_str();
  cmd->add_option("--exposure", o.s.exposure,
                  "Exposure factor applied to the EXR and the PNG, or auto (99th percentile of the brightest channel "
                  "-> 0.9)")
      ->capture_default_str();
  cmd->add_option("--out", o.s.out, "Output EXR: linear, white-balanced camera RGB x exposure")->required();
  cmd->add_option("--png", o.s.png, "sRGB PNG (default: beside --out, same name, .png)");
  cmd->add_flag("--quiet", o.quiet, "Print nothing but warnings");
}

struct ViewOpts {
  CameraPoseOpts cam;
  DisplayArgs display;
  std::string eia, mla = "real", spectral = "primaries", estimator = "auto";
  int apertureGrid = ViewSettings{}.apertureGrid, wavelengthNodes = 1;
  double gapMm = 0.0, background = 0.0, cosN = 0.0;
  bool noCoverGlass = false, relative = false, noCull = false;
  CLI::Option* gapOpt = nullptr;
};

ViewSettings viewSettings(const ViewOpts& o) {
  ViewSettings vs;
  vs.spp = o.cam.spp;
  vs.seed = o.cam.run.seed;
  vs.progress = !o.cam.quiet;
  vs.backgroundY = o.background;
  vs.cullTiles = !o.noCull;
  vs.spectral = o.spectral == "visible" ? SpectralSampling::Visible : SpectralSampling::Primaries;
  vs.apertureGrid = o.apertureGrid;
  vs.wavelengthNodes = o.wavelengthNodes;
  applyEstimatorPolicy(vs, o.estimator, o.cam.sppOpt->count() > 0);
  return vs;
}

void runViewCommand(const ViewOpts& o) {
  const auto t0 = std::chrono::steady_clock::now();
  ViewRunSettings s;
  s.camera = o.cam.settings();
  s.displayPath = o.display.display;
  s.layout = layoutOverride(o.display);
  if (o.gapOpt->count()) s.gapMm = o.gapMm;
  s.eiaPath = o.eia;
  s.mla = o.mla == "ideal" ? MlaKind::Ideal : MlaKind::Real;
  s.emitter.absolute = !o.relative;
  s.emitter.cosExponent = o.cosN;
  s.emitter.coverGlass = !o.noCoverGlass;
  s.view = viewSettings(o);
  const ViewRunResult r = runView(s, [&](const ViewRunResult& v) {
    if (o.cam.quiet) return;
    std::printf("%s", loadedText(s, v).c_str());
    std::fflush(stdout);
  });
  if (!r.render.stats.displayInView())
    std::fprintf(stderr,
                 "inim: warning: the display is out of the camera's view (%s): no camera ray reaches its active "
                 "area; the image shows only the background\n",
                 r.camera.pose.describe().c_str());
  if (o.cam.quiet) return;
  std::printf("%s", summaryText(r, s.view, secondsSince(t0)).c_str());
  std::printf("%s", writtenText(r, o.cam.s.out).c_str());
}

}  // namespace

void addViewCommand(CLI::App& app) {
  auto o = std::make_shared<ViewOpts>();
  auto* cmd = app.add_subcommand(
      "view", "Simulate what a camera sees when the display shows an EIA: spectral Monte Carlo through the camera "
              "lens, the MLA and the panel's subpixels");
  addDisplayOptions(cmd, o->display);
  cmd->add_option("--eia", o->eia, "EIA: linear drive values (EXR from inim eia), panel-sized or EIA-sized; a PNG is "
                                   "decoded through the panel's EOTF")
      ->required();
  cmd->add_option("--mla", o->mla, "MLA model: real (refracting lenslets) or ideal (paraxial thin lenses, the "
                                   "pinhole-MLA comparison)")
      ->check(CLI::IsMember({"real", "ideal"}))
      ->capture_default_str();
  o->gapOpt = cmd->add_option("--gap-mm", o->gapMm, "Panel to MLA reference plane, mm (default: the display's "
                                                    "reconstruction gap)");
  cmd->add_option("--spectral", o->spectral, "Wavelength sampling: primaries (importance-sampled per panel primary) "
                                             "or visible (4-wavelength packets)")
      ->check(CLI::IsMember({"primaries", "visible"}))
      ->capture_default_str();
  cmd->add_option("--estimator", o->estimator,
                  "Panel estimator: point (subpixel under each ray), footprint (box average over the sample's "
                  "share of the pixel footprint), quadrature (pixel area, aperture and spectra all by quadrature, no "
                  "noise; spp = strata per pixel, default 1) or auto (quadrature: the lowest error for the time at "
                  "every width in inim bench)")
      ->check(CLI::IsMember({"point", "footprint", "quadrature", "auto"}))
      ->capture_default_str();
  cmd->add_option("--aperture-grid", o->apertureGrid,
                  "quadrature: the camera aperture's quadrature table, N x N cells over the exit pupil")
      ->check(CLI::Range(2, 64))->capture_default_str();
  cmd->add_option("--wavelength-nodes", o->wavelengthNodes,
                  "quadrature, when something is dispersive: wavelength nodes per primary (1: each primary's "
                  "median wavelength, weighted by its whole spectrum)")
      ->check(CLI::Range(1, 64))->capture_default_str();
  cmd->add_option("--background", o->background, "Luminance of the (D65 grey) background around the display, in the "
                                                  "image's units (default 0: black)");
  cmd->add_option("--emission-cos-n", o->cosN, "Extra cos^n angular emission profile on top of the panel's (0: none)");
  cmd->add_flag("--no-cover-glass", o->noCoverGlass, "Ignore the panel's cover glass");
  cmd->add_flag("--no-cull", o->noCull, "Trace every tile, also those that cannot see the display");
  cmd->add_flag("--relative", o->relative, "Panel white = luminance 1 instead of its peak luminance in cd/m^2");
  addCameraPoseOptions(cmd, o->cam);
  addRunOptions(cmd, o->cam.run, [o] { runViewCommand(*o); });
}

void addReferenceCommand(CLI::App& app) {
  struct Opts {
    CameraPoseOpts cam;
    std::string scene, run, display;
    PlacementArgs place;
    std::string dispersion = "auto";
  };
  auto o = std::make_shared<Opts>();
  auto* cmd = app.add_subcommand(
      "reference", "Render the scene itself through the viewing camera at the same pose, placed as for the EIA "
                   "(the reference for inim view)");
  cmd->add_option("--scene,--field", o->scene,
                  "Scene JSON or trained radiance field (.inimrf) (default: the run file's, else scenes/paper-fig7.json)");
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
    s.fieldPath = !o->scene.empty() ? o->scene : run.scene.value_or("");
    s.placement = run.placement;
    s.placementOverride = placementOverride(o->place);
    s.displayPath = !o->display.empty() ? o->display : run.display.value_or("");
    s.reference.spp = o->cam.spp;
    s.reference.seed = o->cam.run.seed;
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
