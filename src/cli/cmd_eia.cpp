// inim eia: orthoscopic elemental-image synthesis. Display + scene (a Field) + placement ->
// the EIA at the panel's full resolution: a linear EXR of drive values (+ A, Z with --aovs),
// an encoded PNG beside it, and optionally the placement preview and the triads as a Zemax
// SDF source file. The run is src/runs/eia_run.h.
#include <chrono>
#include <cstdio>
#include <memory>
#include <optional>
#include <string>

#include "cli/commands.h"
#include "cli/options.h"
#include "runs/eia_run.h"
#include "core/format.h"
#include "runs/run_file.h"

namespace inim::cli {

namespace {

// Options that a run file may also set are optional: absent, the run file's value or the
// library's default (EiaRunSettings) holds.
struct EiaOpts {
  EiaRunSettings e;  // the settings the options write directly
  std::optional<std::string> scene, field, triads, exposure, gamut, whiteBalance, calibration;
  std::optional<double> vcpMm;
  std::optional<int> spp;
  std::string colorsEncoding = "srgb", run;
  DisplayArgs display;
  PlacementArgs place;
  RealLensArgs realLens;
  bool quiet = false;
  RunOptions runOpts;
};

// Settings: defaults < run file < command line. The field's own default placement (a trained
// model's) is below the run file's.
EiaRunSettings eiaRunSettings(const EiaOpts& o, const RunFile& run) {
  EiaRunSettings e = o.e;
  if (int(o.scene.has_value()) + int(o.field.has_value()) + int(!o.e.fieldColorsPath.empty()) > 1)
    throw InputError("", "--field", "more than one of --scene, --field, --field-colors", "one field source");
  resolveSetting(e.fieldPath, run.scene, o.scene ? o.scene : o.field);
  if (o.field) e.fieldKey = "field";
  e.colorsEncoding = o.colorsEncoding == "srgb" ? ColorEncoding::SRGB : ColorEncoding::Linear;
  e.placement = run.placement;
  e.placementOverride = placementOverride(o.place);
  SynthesisSettings& s = e.synthesis;
  resolveSetting(s.vcpMm, run.vcpMm, o.vcpMm);
  resolveSetting(s.spp, run.spp, o.spp);
  checkQuerySampling(s.vcpMm, s.spp);
  resolveSetting(s.seed, run.seed, o.runOpts.seed);
  if (const auto& text = chosenText(run.exposure, o.exposure)) try {
      applyExposure(*text, s);
    } catch (const InputError& err) {
      throw o.exposure ? err : err.withFile(run.file);  // a run file's value is named as the file spells it
    }
  if (const auto& text = chosenText(run.gamut, o.gamut)) s.gamut = parseGamut(*text);
  if (const auto& text = chosenText(run.whiteBalance, o.whiteBalance)) s.whiteBalanceD65 = parseWhiteBalanceD65(*text);
  resolveSetting(e.calibrationPath, run.calibration, o.calibration);
  if (!o.calibration && run.calibration) e.calibrationKey = "calibration (" + run.file + ")";
  s.progress = !o.quiet;
  resolveSetting(e.displayPath, run.display, givenValue(o.display.displayOpt, o.display.display));
  e.layout = layoutOverride(o.display, &run);
  const RealLensRayOptions realLens = realLensRayOptions(o.realLens);  // an error without --real-lens
  if (o.realLens.on) e.realLens = realLens;
  resolveSetting(e.triadWavelengths, run.triadWavelengths, o.triads);
  return e;
}

}  // namespace

void addEiaCommand(CLI::App& app) {
  auto o = std::make_shared<EiaOpts>();
  CLI::App* cmd = &app;
  addDisplayOptions(cmd, o->display);
  cmd->add_option("--scene", o->scene, "Scene JSON (default: scenes/paper-fig7.json)");
  cmd->add_option("--field", o->field, "The field to show: a scene JSON, a trained radiance field (.inimrf) or Gaussian splats (.ply, .splat)");
  cmd->add_option("--field-colors", o->e.fieldColorsPath,
                                 "Colours of an external field, one per query ray written by `inim rays --for-field` "
                                 "with the same display, placement and settings (.npy or .exr: R G B [A [depth]])");
  cmd->add_option("--field-colors-encoding", o->colorsEncoding,
                  "srgb (NeRF outputs, default) or linear: how --field-colors values are encoded")
      ->capture_default_str();
  cmd->add_option("--out", o->e.out, "Output EXR of linear drive values at the panel resolution")->required();
  cmd->add_option("--png", o->e.png, "Encoded PNG (default: beside --out, same name, .png)");
  cmd->add_option("--sdf", o->e.sdf, "Also write the triads (3 rays per display ray) as a Zemax SDF source file");
  cmd->add_option("--triad-wavelengths", o->triads,
                              "Triad wavelengths: panel (primary peaks, default), paper (656,566,471), "
                              "zemax-sequential (620,525,460) or R,G,B in nm");
  addPlacementOptions(cmd, o->place);
  cmd->add_option("--run", o->run, "Run file (JSON): placement and settings; command-line options override it");
  cmd->add_option("--vcp-mm", o->vcpMm, "VCP distance D_VCP in front of the MLA (the near clipping plane), mm")
      ->default_str(formatNumber(o->e.synthesis.vcpMm));
  cmd->add_option("--spp", o->spp, "Field samples per display ray (wavelengths, light samples)")
      ->default_str(std::to_string(o->e.synthesis.spp));
  cmd->add_option("--exposure", o->exposure,
                              "Drive = E x panel-native RGB (field luminance 1/E = panel white), or auto (default: the "
                              "99th percentile of the brightest channel of the pixels that see the scene -> full "
                              "drive)");
  cmd->add_option("--gamut", o->gamut, "Out-of-gamut mapping: clip (per channel, default) or desaturate");
  cmd->add_option("--white-balance", o->whiteBalance,
                             "none (colorimetric, default) or d65 (gains so that D65 drives 1,1,1)");
  cmd->add_option("--calibration", o->calibration,
                              "Panel calibration applied to the drive values after the gamut mapping: a 3D LUT "
                              "(.cube or .clf, drive -> drive, e.g. from `inim calibrate`; default: none)");
  addRealLensOptions(cmd, o->realLens,
                     "Query the scene along the real-lens display rays (traced through the refracting MLA at the "
                     "physical lens centres) instead of the pinhole rays");
  cmd->add_flag("--aovs", o->e.synthesis.aovs, "Add A (opacity) and Z (display z of the first surface, mm) channels to the EXR");
  cmd->add_option("--preview", o->e.preview, "Placement preview PNG (central ray of each lenslet, like the paper's Fig. 4)");
  cmd->add_flag("--quiet", o->quiet, "Print nothing but warnings");

  addRunOptions(cmd, o->runOpts, [o] {
    if (o->colorsEncoding != "srgb" && o->colorsEncoding != "linear")
      throw InputError("", "--field-colors-encoding", "\"" + o->colorsEncoding + "\"", "srgb or linear");
    const auto t0 = std::chrono::steady_clock::now();
    const RunFile run = o->run.empty() ? RunFile{} : loadRunFile(o->run);
    const EiaRunSettings s = eiaRunSettings(*o, run);
    const EiaRunResult r = runEia(s, [&](const EiaRunResult& loaded) {
      if (o->quiet) return;
      std::printf("%s", setupText(loaded, s.synthesis.vcpMm).c_str());
      std::fflush(stdout);
    });
    for (const auto& w : r.synthesis.stats.warnings) std::fprintf(stderr, "inim: warning: %s\n", w.c_str());
    if (o->quiet) return;
    std::printf("%s", summaryText(r, s).c_str());
    std::printf("total:       %.2f s (loading %.2f s, synthesis %.2f s, writing %.2f s)\n", secondsSince(t0),
                r.loadSeconds, r.synthesis.stats.seconds, r.writeSeconds);
  });
}

}  // namespace inim::cli
