// inim view: what a camera sees when the display shows an EIA (spectral Monte Carlo through the
// camera lens, the MLA and the panel's subpixels; src/view/view_renderer.h).
// inim reference: the same camera and pose looking at the scene itself, at the placement the
// EIA was made with (src/view/reference_renderer.h).
// Both write linear camera RGB (x exposure) as EXR and an sRGB PNG beside it.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <future>
#include <memory>
#include <string>

#include "camera/camera_config.h"
#include "cli/commands.h"
#include "cli/options.h"
#include "core/format.h"
#include "core/output_file.h"
#include "fields/field_factory.h"
#include "view/display_model.h"
#include "view/reference_renderer.h"
#include "view/view_camera.h"
#include "view/view_image.h"
#include "view/view_renderer.h"

namespace inim::cli {

namespace {

// Options shared by `view` and `reference`: camera, pose, image size, samples, outputs.
struct CameraPoseOpts {
  std::string camera, cameraModel, exposure = "auto", out, png;
  double distanceMm = 0.0, rotH = 0.0, rotV = 0.0, focusMm = 0.0;
  int width = 0, height = 0, spp = 16;
  bool quiet = false;
  RunOptions run;
  CLI::Option *distanceOpt = nullptr, *sppOpt = nullptr;
};

void addCameraPoseOptions(CLI::App* cmd, CameraPoseOpts& o) {
  cmd->add_option("--camera", o.camera, "Camera: a name in optics/cameras/ or a JSON file (default: alvium-1800-u-500c)");
  cmd->add_option("--camera-model", o.cameraModel, "real-lens, thin-lens or pinhole (default: the camera file's)")
      ->check(CLI::IsMember({"real-lens", "thin-lens", "pinhole"}));
  o.distanceOpt = cmd->add_option("--distance-mm", o.distanceMm,
                                  "Camera (entrance pupil) to display centre, mm (default: the camera file's distance_mm)");
  cmd->add_option("--rot-h-deg", o.rotH,
                  "Display rotation about its vertical axis, degrees; + turns its right edge away from the camera")
      ->capture_default_str();
  cmd->add_option("--rot-v-deg", o.rotV,
                  "Display rotation about its horizontal axis, degrees; + turns its top edge away from the camera")
      ->capture_default_str();
  cmd->add_option("--focus-mm", o.focusMm, "Focus distance from the entrance pupil, mm (default: the camera distance, "
                                           "i.e. the MLA plane)");
  cmd->add_option("--width", o.width, "Image width in pixels (default: the sensor's; a smaller width keeps the field of "
                                      "view and scales the pixel pitch)");
  cmd->add_option("--height", o.height, "Image height in pixels (default: the sensor's aspect ratio)");
  o.sppOpt = cmd->add_option("--spp", o.spp, "Samples per pixel")->capture_default_str();
  cmd->add_option("--exposure", o.exposure,
                  "Exposure factor applied to the EXR and the PNG, or auto (99th percentile of the brightest channel "
                  "-> 0.9)")
      ->capture_default_str();
  cmd->add_option("--out", o.out, "Output EXR: linear, white-balanced camera RGB x exposure")->required();
  cmd->add_option("--png", o.png, "sRGB PNG (default: beside --out, same name, .png)");
  cmd->add_flag("--quiet", o.quiet, "Print nothing but warnings");
}

struct CameraSetup {
  CameraDescription desc;
  DisplayPose pose;
  std::unique_ptr<CameraModel> camera;
  Exposure exposure;
  std::string png;
};

CameraSetup setupCamera(const CameraPoseOpts& o) {
  if (o.spp < 1) throw InputError("", "--spp", std::to_string(o.spp), "a whole number >= 1");
  requireExtension(o.out, "--out", {".exr"}, "an OpenEXR file name (.exr)");
  CameraSetup s;
  s.png = pngBeside(o.out, o.png);
  requireExtension(s.png, "--png", {".png"}, "a PNG file name (.png)");
  s.exposure = parseExposure(o.exposure);
  for (auto [v, key] : {std::pair{o.width, "--width"}, {o.height, "--height"}})
    if (v < 0) throw InputError("", key, std::to_string(v), "a whole number of pixels >= 1");
  s.desc = loadCameraDescription(o.camera.empty() ? defaultCameraPath() : o.camera);
  s.pose.rotHDeg = o.rotH;
  s.pose.rotVDeg = o.rotV;
  s.pose.distanceMm = o.distanceOpt->count() ? o.distanceMm : s.desc.distanceMm;
  if (!(s.pose.distanceMm > 0.0) || !std::isfinite(s.pose.distanceMm))
    throw InputError("", "--distance-mm", formatNumber(s.pose.distanceMm), "a camera distance > 0 mm");
  ViewCameraOptions co;
  if (!o.cameraModel.empty())
    co.kind = o.cameraModel == "pinhole"     ? CameraModelKind::Pinhole
              : o.cameraModel == "thin-lens" ? CameraModelKind::ThinLens
                                             : CameraModelKind::RealLens;
  co.width = o.width;
  co.height = o.height;
  co.focusMm = o.focusMm;
  if (o.focusMm < 0.0 || !std::isfinite(o.focusMm))
    throw InputError("", "--focus-mm", formatNumber(o.focusMm), "a focus distance > 0 mm");
  s.camera = makeViewCamera(s.desc, s.pose, co);
  return s;
}

// Writes the exposed EXR and the sRGB PNG together (temporaries renamed only when both
// succeed); returns the exposure factor.
double writeOutputs(const Image& cameraRgb, const CameraSetup& cs, const std::string& out) {
  const double k = exposureFactor(cameraRgb, cs.desc.sensor, cs.exposure);
  const Image exposed = scaledImage(cameraRgb, k);
  OutputSet outputs;
  const std::string exrTmp = outputs.add(out), pngTmp = outputs.add(cs.png);
  auto exr = std::async(std::launch::async, [&] { writeImage(exposed, exrTmp); });
  writeImage(cameraRgbToSrgb(exposed, cs.desc.sensor), pngTmp);
  exr.get();
  outputs.commit();
  return k;
}

void printCamera(const CameraSetup& cs) {
  std::printf("camera:      %s; %s\n", cs.desc.name.c_str(), cs.camera->describe().c_str());
  std::printf("image:       %d x %d px, pitch %s um; pose %s\n", cs.camera->width(), cs.camera->height(),
              formatNumber(cs.camera->sensor().pitchMm * 1e3).c_str(), cs.pose.describe().c_str());
}

void printWritten(double k, const CameraSetup& cs, const std::string& out) {
  std::printf("exposure:    %s%s\n", formatNumber(k).c_str(), cs.exposure.automatic ? " (auto: 99th percentile -> 0.9)" : "");
  std::printf("wrote:       %s, %s\n", out.c_str(), cs.png.c_str());
}

double secondsSince(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
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

// The EIA image, checked: EXR (linear drive values) or PNG (decoded through the panel's EOTF).
Image readEia(const std::string& path) {
  const std::string ext = lowerExtension(path);
  if (ext != ".exr" && ext != ".png")
    throw InputError("", "--eia", "\"" + path + "\"", "an EIA image: linear EXR (or encoded PNG)");
  if (!std::filesystem::exists(path)) throw InputError(path, "--eia", "\"" + path + "\"", "an existing EIA image");
  try {
    return readImage(path, true);
  } catch (const InputError& e) {
    throw e.file().empty() ? e.withFile(path) : e;
  }
}

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
  if (o.estimator == "auto")  // quadrature integrates the primaries' spectra: it needs --spectral primaries
    vs.panelEstimator = vs.spectral == SpectralSampling::Primaries ? PanelEstimator::Quadrature : PanelEstimator::Footprint;
  else
    parsePanelEstimator(o.estimator, vs.panelEstimator);
  // Quadrature has no noise: one stratum per pixel unless asked (RMSE ~1.3% of the mean
  // against 16 at the sensor's resolution; inim bench).
  if (vs.panelEstimator == PanelEstimator::Quadrature && o.cam.sppOpt->count() == 0) vs.spp = 1;
  return vs;
}

void printViewStats(const ViewSettings& vs, const ViewResult& r, double total, double loadSeconds) {
  std::printf("rendered:    %d spp, %s wavelengths (%d ray%s per sample%s), %.2f s render, %.2f s total "
              "(loading %.2f s)\n",
              vs.spp, spectralSamplingName(vs.spectral), r.stats.raysPerSample, r.stats.raysPerSample > 1 ? "s" : "",
              r.stats.dispersive ? ", dispersive" : "", r.stats.seconds, total, loadSeconds);
  std::printf("rays:        %llu traced, %llu on the display, %llu reached the panel, %llu on a subpixel; %llu "
              "pixels skipped (their tiles cannot see the display)\n",
              (unsigned long long)r.stats.tracedRays, (unsigned long long)r.stats.displayRays,
              (unsigned long long)r.stats.panelRays, (unsigned long long)r.stats.emittingRays,
              (unsigned long long)r.stats.culledPixels);
  if (vs.panelEstimator == PanelEstimator::Quadrature)
    std::printf("estimator:   quadrature: %llu pixel pieces integrated (%llu strata cut by a lenslet border), "
                "%llu pieces x primaries lost by the MLA, %llu fallbacks, %llu table/Jacobian rays\n",
                (unsigned long long)r.stats.quadratureParts, (unsigned long long)r.stats.splitStrata,
                (unsigned long long)r.stats.lostParts, (unsigned long long)r.stats.apertureFallbacks,
                (unsigned long long)r.stats.apertureRays);
  else
    std::printf("estimator:   %s\n", panelEstimatorName(vs.panelEstimator));
}

void runView(const ViewOpts& o) {
  const auto t0 = std::chrono::steady_clock::now();
  CameraSetup cs = setupCamera(o.cam);
  if (!(o.background >= 0.0) || !std::isfinite(o.background))
    throw InputError("", "--background", formatNumber(o.background), "a luminance >= 0");
  if (!(o.cosN >= 0.0) || !std::isfinite(o.cosN))
    throw InputError("", "--emission-cos-n", formatNumber(o.cosN), "an exponent >= 0");
  Display d;
  const EiLayout L = loadDisplayLayout(o.display, d);
  const double gap = o.gapOpt->count() ? o.gapMm : d.reconstructionGapMm;
  const double g = checkedGap(gap, formatNumber(gap));
  const Image eia = readEia(o.eia);
  EmitterSettings es;
  es.absolute = !o.relative;
  es.cosExponent = o.cosN;
  es.coverGlass = !o.noCoverGlass;
  es.encoded = lowerExtension(o.eia) == ".png";
  DisplayModel dm = makeDisplayModel(d, L, eia, o.eia, o.mla == "ideal" ? MlaKind::Ideal : MlaKind::Real, g, es);
  const ViewSettings vs = viewSettings(o);
  if (!o.cam.quiet) {
    std::printf("display:     %s (g = %s mm, %s MLA%s)\n", d.name.c_str(), formatNumber(g).c_str(),
                o.mla == "ideal" ? "ideal thin-lens" : "real refracting", dm.panel->hasCoverGlass() ? ", cover glass" : "");
    std::printf("eia:         %s (%d x %d px)\n", o.eia.c_str(), eia.width, eia.height);
    printCamera(cs);
    std::fflush(stdout);
  }
  const double loadSeconds = secondsSince(t0);
  const ViewResult r = renderView(*cs.camera, cs.desc.sensor, *dm.mla, *dm.panel, dm.area, vs);
  const double k = writeOutputs(r.image, cs, o.cam.out);
  if (!r.stats.displayInView())
    std::fprintf(stderr,
                 "inim: warning: the display is out of the camera's view (%s): no camera ray reaches its active "
                 "area; the image shows only the background\n",
                 cs.pose.describe().c_str());
  if (o.cam.quiet) return;
  printViewStats(vs, r, secondsSince(t0), loadSeconds);
  printWritten(k, cs, o.cam.out);
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
  addRunOptions(cmd, o->cam.run, [o] { runView(*o); });
}

void addReferenceCommand(CLI::App& app) {
  struct Opts {
    CameraPoseOpts cam;
    std::string scene, run, display;
    PlacementArgs place;
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
  addRunOptions(cmd, o->cam.run, [o] {
    const auto t0 = std::chrono::steady_clock::now();
    const RunFile run = o->run.empty() ? RunFile{} : loadRunFile(o->run);
    const std::string scenePath = !o->scene.empty() ? o->scene : run.scene.value_or(defaultScenePath());
    const LoadedField lf = loadField(scenePath, "scene");
    const Placement pl = resolvePlacement(run.placement ? run.placement : lf.placement, placementOverride(o->place));
    const Transform toDisplay = pl.toDisplay();
    CameraSetup cs = setupCamera(o->cam);
    Display d = loadDisplay(displayPathOrDefault(!o->display.empty() ? o->display : run.display.value_or("")));
    const DisplayArea area = lensletArrayArea(computeLayout(d), d.mla.pitchMm);
    if (!o->cam.quiet) {
      std::printf("scene:       %s; placement %s\n", scenePath.c_str(), pl.describe().c_str());
      printCamera(cs);
      std::fflush(stdout);
    }
    ReferenceSettings rs;
    rs.spp = o->cam.spp;
    rs.seed = o->cam.run.seed;
    rs.progress = !o->cam.quiet;
    const ViewResult r = renderReference(*lf.field, toDisplay, *cs.camera, cs.desc.sensor, rs);
    const double k = writeOutputs(r.image, cs, o->cam.out);
    if (displayCoverage(*cs.camera, area) == 0.0)
      std::fprintf(stderr, "inim: warning: the display is out of the camera's view (%s); the reference is rendered anyway\n",
                   cs.pose.describe().c_str());
    if (o->cam.quiet) return;
    std::printf("rendered:    %d spp, %.2f s render, %.2f s total; %llu rays, %llu hit the scene\n", rs.spp,
                r.stats.seconds, secondsSince(t0), (unsigned long long)r.stats.tracedRays,
                (unsigned long long)r.stats.emittingRays);
    printWritten(k, cs, o->cam.out);
  });
}

}  // namespace inim::cli
