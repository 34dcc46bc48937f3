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

// The options write the library's settings (`e`: what only the command line sets) and the
// settings given one by one (resolveEiaRun puts them over the run file's).
struct EiaOpts {
  EiaRunSettings e;
  EiaGiven given;
  std::string colorsEncoding = "srgb", run;
  PlacementArgs place;
  RealLensArgs realLens;
  bool quiet = false;
  RunOptions runOpts;
};

}  // namespace

void addEiaCommand(CLI::App& app) {
  auto o = std::make_shared<EiaOpts>();
  CLI::App* cmd = &app;
  addDisplayOptions(cmd, o->given.display);
  addSetting(cmd, "scene", o->given.scene);
  addSetting(cmd, "field", o->given.field);
  addSetting(cmd, "field_colors", o->e.fieldColorsPath);
  addSetting(cmd, "field_colors_encoding", o->colorsEncoding);
  addSetting(cmd, "out", o->e.out)->required();
  addSetting(cmd, "png", o->e.png);
  addSetting(cmd, "sdf", o->e.sdf);
  addSetting(cmd, "zemax_model", o->e.zemaxModel);
  addSetting(cmd, "triad_wavelengths", o->given.triads);
  addPlacementOptions(cmd, o->place);
  addSetting(cmd, "run", o->run);
  addSetting(cmd, "vcp_mm", o->given.vcpMm)->default_str(formatNumber(o->e.synthesis.vcpMm));
  addSetting(cmd, "spp", o->given.spp)->default_str(std::to_string(o->e.synthesis.spp));
  addSetting(cmd, "exposure", o->given.exposure);
  addSetting(cmd, "gamut", o->given.gamut);
  addSetting(cmd, "white_balance", o->given.whiteBalance);
  addSetting(cmd, "calibration", o->given.calibration);
  addRealLensOptions(cmd, o->realLens);
  addSetting(cmd, "aovs", o->e.synthesis.aovs);
  addSetting(cmd, "preview", o->e.preview);
  addSetting(cmd, "quiet", o->quiet);

  addRunOptions(cmd, o->runOpts, [o] {
    const auto t0 = std::chrono::steady_clock::now();
    const RunFile run = o->run.empty() ? RunFile{} : loadRunFile(o->run);
    EiaRunSettings base = o->e;
    base.colorsEncoding = o->colorsEncoding == "srgb" ? ColorEncoding::SRGB : ColorEncoding::Linear;
    base.synthesis.progress = !o->quiet;
    base.rays = o->realLens.resolve();
    EiaGiven given = o->given;
    given.seed = o->runOpts.seed;
    given.placement = placementOverride(o->place);
    const EiaRunSettings s = resolveEiaRun(base, run, given);
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
