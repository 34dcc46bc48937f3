// inim rays: the pinhole chief ray of every pixel of every EI, as the paper's Zemax ray text
// (.txt, UTF-8 by default) or inim's binary rays (.irays). With --real-lens, the rays that
// actually leave the refracting lenslets (src/mla_optics/real_lens_rays.h). With --in, converts a ray
// file (the paper's UTF-16LE macro output included) instead. With --for-field, the query rays
// of an EIA for an external field (src/field/ray_table.h).
#include <chrono>
#include <cstdio>
#include <memory>
#include <optional>
#include <string>

#include "cli/commands.h"
#include "cli/options.h"
#include "core/format.h"
#include "runs/eia_run.h"
#include "runs/ray_export.h"
#include "runs/run_file.h"

namespace inim::cli {

namespace {

struct RaysOpts {
  RayExportSettings s;  // the settings the options write directly
  DisplayArgs display;
  std::string runFile;
  std::optional<double> vcpMm;  // with --for-field; absent: the run file's, else the default
  std::optional<int> spp;
  PlacementArgs place;
  RealLensArgs realLens;
  RunOptions run;
  CLI::Option *gapOpt, *eiOpt, *inOpt;
};

void checkCombinations(CLI::App* cmd, const RaysOpts& o) {
  if (!o.s.forField) {
    for (const char* name : {"--run", "--vcp-mm", "--spp", "--scale", "--rotate-deg", "--translate-mm"})
      if (cmd->count(name)) throw InputError("", name, "given", "--for-field as well (it sets up the query rays)");
  } else if (o.inOpt->count() || o.eiOpt->count() || o.s.zemaxMacro) {
    throw InputError("", "--for-field", "with " + std::string(o.inOpt->count() ? "--in" : o.eiOpt->count() ? "--ei" : "--zemax-macro"),
                     "the whole display's query rays (no --in, --ei or --zemax-macro)");
  }
  const DisplayArgs& d = o.display;
  if (o.inOpt->count() && (o.gapOpt->count() || d.layout || d.viewingDistanceMm || o.eiOpt->count() || d.display ||
                           o.realLens.on || o.realLens.chiefRays))
    throw InputError("", "--in", "\"" + o.s.in + "\"",
                     "no --display, --gap-mm, --layout, --viewing-distance-mm, --ei or --real-lens with --in (the "
                     "file already holds the rays)");
}

RayExportSettings exportSettings(const RaysOpts& o) {
  RayExportSettings s = o.s;
  if (!s.in.empty()) return s;
  s.rays = o.realLens.resolve();
  s.displayPath = o.display.display.value_or("");
  s.layout = layoutOverride(o.display);
  if (!s.forField) return s;
  const RunFile run = o.runFile.empty() ? RunFile{} : loadRunFile(o.runFile);
  s.placement = run.placement;
  s.placementOverride = placementOverride(o.place);
  resolveSetting(s.vcpMm, run.vcpMm, o.vcpMm);
  resolveSetting(s.spp, run.spp, o.spp);
  checkQuerySampling(s.vcpMm, s.spp);
  return s;
}

}  // namespace

void addRaysCommand(CLI::App& app) {
  auto o = std::make_shared<RaysOpts>();
  CLI::App* cmd = &app;
  addDisplayOptions(cmd, o->display);
  addSetting(cmd, "out", o->s.out)->required();
  o->gapOpt = addSetting(cmd, "gap_mm", o->s.gapMm);
  addSetting(cmd, "zemax_macro", o->s.zemaxMacro);
  o->eiOpt = addSetting(cmd, "ei", o->s.ei);
  addRealLensOptions(cmd, o->realLens);
  o->inOpt = addSetting(cmd, "in", o->s.in);
  addSetting(cmd, "for_field", o->s.forField);
  addSetting(cmd, "run", o->runFile);
  addPlacementOptions(cmd, o->place);
  addSetting(cmd, "vcp_mm", o->vcpMm)->default_str(formatNumber(o->s.vcpMm));
  addSetting(cmd, "spp", o->spp)->default_str(std::to_string(o->s.spp));
  addRunOptions(cmd, o->run, [o, cmd] {
    const auto t0 = std::chrono::steady_clock::now();
    (void)rayFileFormat(o->s.out, "--out", o->s.forField);
    checkCombinations(cmd, *o);
    const RayExportResult r = exportRays(exportSettings(*o));
    std::printf("%s", exportText(o->s, r, secondsSince(t0)).c_str());
  });
}

}  // namespace inim::cli
