// inim eia: orthoscopic elemental-image synthesis. Display + scene (a Field) + placement ->
// the EIA at the panel's full resolution: a linear EXR of drive values (+ A, Z with --aovs),
// an encoded PNG beside it, and optionally the placement preview and the triads as a Zemax
// SDF source file. The run is src/runs/eia_run.h.
#include <chrono>
#include <cstdio>
#include <memory>
#include <string>

#include "cli/commands.h"
#include "cli/options.h"
#include "runs/eia_run.h"
#include "runs/run_file.h"

namespace inim::cli {

namespace {

struct EiaOpts {
  std::string scene, field, fieldColors, colorsEncoding = "srgb", out, png, sdf, run, preview;
  std::string triads, exposure, gamut, whiteBalance, calibration;
  DisplayArgs display;
  PlacementArgs place;
  RealLensArgs realLens;
  double vcpMm = kDefaultVcpMm;
  int spp = 1;
  bool aovs = false, quiet = false;
  RunOptions runOpts;
  CLI::Option *sceneOpt, *fieldOpt, *colorsOpt, *triOpt, *vcpOpt, *sppOpt, *expOpt, *gamutOpt, *wbOpt, *calOpt;
};

// Settings: defaults < run file < command line. The field's own default placement (a trained
// model's) is below the run file's.
EiaRunSettings eiaRunSettings(const EiaOpts& o, const RunFile& run) {
  EiaRunSettings e;
  if (int(o.sceneOpt->count()) + int(o.fieldOpt->count()) + int(o.colorsOpt->count()) > 1)
    throw InputError("", "--field", "more than one of --scene, --field, --field-colors", "one field source");
  e.fieldPath = o.sceneOpt->count() ? o.scene : o.fieldOpt->count() ? o.field : run.scene.value_or("");
  e.fieldKey = o.fieldOpt->count() ? "field" : "scene";
  e.fieldColorsPath = o.fieldColors;
  e.colorsEncoding = o.colorsEncoding == "srgb" ? ColorEncoding::SRGB : ColorEncoding::Linear;
  e.placement = run.placement;
  e.placementOverride = placementOverride(o.place);
  SynthesisSettings& s = e.synthesis;
  s.vcpMm = optionOrRun(o.vcpOpt, o.vcpMm, run.vcpMm, kDefaultVcpMm);
  s.spp = optionOrRun(o.sppOpt, o.spp, run.spp, 1);
  checkQuerySampling(s.vcpMm, s.spp);
  s.seed = optionOrRun(o.runOpts.seedOpt, o.runOpts.seed, run.seed, o.runOpts.seed);
  try {
    applyExposure(optionOrRun(o.expOpt, o.exposure, run.exposure, std::string("auto")), s);
  } catch (const InputError& e) {
    throw o.expOpt->count() ? e : e.withFile(run.file);  // a run file's value is named as the file spells it
  }
  s.gamut = parseGamut(optionOrRun(o.gamutOpt, o.gamut, run.gamut, std::string("clip")));
  s.whiteBalanceD65 = parseWhiteBalanceD65(optionOrRun(o.wbOpt, o.whiteBalance, run.whiteBalance, std::string("none")));
  e.calibrationPath = optionOrRun(o.calOpt, o.calibration, run.calibration, std::string());
  if (!o.calOpt->count() && run.calibration) e.calibrationKey = "calibration (" + run.file + ")";
  s.aovs = o.aovs;
  s.progress = !o.quiet;
  e.displayPath = optionOrRun(o.display.displayOpt, o.display.display, run.display, std::string());
  e.layout = layoutOverride(o.display, &run);
  const RealLensRayOptions realLens = realLensRayOptions(o.realLens);  // an error without --real-lens
  if (o.realLens.on) e.realLens = realLens;
  e.triadWavelengths = optionOrRun(o.triOpt, o.triads, run.triadWavelengths, std::string("panel"));
  e.out = o.out, e.png = o.png, e.preview = o.preview, e.sdf = o.sdf;
  return e;
}

}  // namespace

void addEiaCommand(CLI::App& app) {
  auto o = std::make_shared<EiaOpts>();
  auto* cmd = app.add_subcommand(
      "eia", "Orthoscopic EIA synthesis: query the scene along every reversed display ray from the VCP and write the "
             "panel drive values");
  addDisplayOptions(cmd, o->display);
  o->sceneOpt = cmd->add_option("--scene", o->scene, "Scene JSON (default: scenes/paper-fig7.json)");
  o->fieldOpt = cmd->add_option("--field", o->field, "The field to show: a scene JSON, a trained radiance field (.inimrf) or Gaussian splats (.ply, .splat)");
  o->colorsOpt = cmd->add_option("--field-colors", o->fieldColors,
                                 "Colours of an external field, one per query ray written by `inim rays --for-field` "
                                 "with the same display, placement and settings (.npy or .exr: R G B [A [depth]])");
  cmd->add_option("--field-colors-encoding", o->colorsEncoding,
                  "srgb (NeRF outputs, default) or linear: how --field-colors values are encoded")
      ->capture_default_str();
  cmd->add_option("--out", o->out, "Output EXR of linear drive values at the panel resolution")->required();
  cmd->add_option("--png", o->png, "Encoded PNG (default: beside --out, same name, .png)");
  cmd->add_option("--sdf", o->sdf, "Also write the triads (3 rays per display ray) as a Zemax SDF source file");
  o->triOpt = cmd->add_option("--triad-wavelengths", o->triads,
                              "Triad wavelengths: panel (primary peaks, default), paper (656,566,471), "
                              "zemax-sequential (620,525,460) or R,G,B in nm");
  addPlacementOptions(cmd, o->place);
  cmd->add_option("--run", o->run, "Run file (JSON): placement and settings; command-line options override it");
  o->vcpOpt = cmd->add_option("--vcp-mm", o->vcpMm, "VCP distance D_VCP in front of the MLA (the near clipping plane), mm")
                  ->capture_default_str();
  o->sppOpt = cmd->add_option("--spp", o->spp, "Field samples per display ray (wavelengths, light samples)")
                  ->capture_default_str();
  o->expOpt = cmd->add_option("--exposure", o->exposure,
                              "Drive = E x panel-native RGB (field luminance 1/E = panel white), or auto (default: the "
                              "99th percentile of the brightest channel of the pixels that see the scene -> full "
                              "drive)");
  o->gamutOpt = cmd->add_option("--gamut", o->gamut, "Out-of-gamut mapping: clip (per channel, default) or desaturate");
  o->wbOpt = cmd->add_option("--white-balance", o->whiteBalance,
                             "none (colorimetric, default) or d65 (gains so that D65 drives 1,1,1)");
  o->calOpt = cmd->add_option("--calibration", o->calibration,
                              "Panel calibration applied to the drive values after the gamut mapping: a 3D LUT "
                              "(.cube or .clf, drive -> drive, e.g. from `inim calibrate`; default: none)");
  addRealLensOptions(cmd, o->realLens,
                     "Query the scene along the real-lens display rays (traced through the refracting MLA at the "
                     "physical lens centres) instead of the pinhole rays");
  cmd->add_flag("--aovs", o->aovs, "Add A (opacity) and Z (display z of the first surface, mm) channels to the EXR");
  cmd->add_option("--preview", o->preview, "Placement preview PNG (central ray of each lenslet, like the paper's Fig. 4)");
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
