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
  if (o.inOpt->count() && (o.gapOpt->count() || o.display.layoutOpt->count() || o.display.distanceOpt->count() ||
                           o.eiOpt->count() || !o.display.display.empty() || o.realLens.onOpt->count()))
    throw InputError("", "--in", "\"" + o.s.in + "\"",
                     "no --display, --gap-mm, --layout, --viewing-distance-mm, --ei or --real-lens with --in (the "
                     "file already holds the rays)");
}

RayExportSettings exportSettings(const RaysOpts& o) {
  RayExportSettings s = o.s;
  if (!s.in.empty()) return s;
  const RealLensRayOptions realLens = realLensRayOptions(o.realLens);
  if (o.realLens.on) s.realLens = realLens;
  s.displayPath = o.display.display;
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
  cmd->add_option("--out", o->s.out, "Output: FILE.txt (Zemax ray text, \"x, y, z, l, m, n\" %.8f) or FILE.irays")
      ->required();
  o->gapOpt = cmd->add_option("--gap-mm", o->s.gapMm, "Generate at this panel gap instead of generation_gap_mm");
  cmd->add_flag("--zemax-macro", o->s.zemaxMacro,
                "Text as the paper's ZPL macro wrote it: UTF-16LE with BOM, CRLF, two header lines");
  o->eiOpt = cmd->add_option("--ei", o->s.ei,
                             "Only EI K,L (K from the left, L from the top), positions relative to its pinhole (the "
                             "macro's single-EI file); .txt only");
  addRealLensOptions(cmd, o->realLens,
                     "Trace every pixel's ray through the real MLA (refraction at n(lambda), the physical lens "
                     "centres) instead of the pinhole model; origins moved back to z = 0");
  o->inOpt = cmd->add_option("--in", o->s.in,
                             "Convert this ray file (.txt: Zemax text, UTF-8 or UTF-16LE; .irays) to --out instead "
                             "of generating rays");
  cmd->add_flag("--for-field", o->s.forField,
                "Write the orthoscopic QUERY rays instead (field frame, after the inverse placement; reversed display "
                "rays starting on the VCP) as a table for an external radiance field: --out FILE.npy (float32 N x 8: "
                "ox oy oz dx dy dz near far) or FILE.exr; fill in one colour per row and pass it to `inim eia "
                "--field-colors`");
  cmd->add_option("--run", o->runFile, "With --for-field: run file of the EIA (placement, VCP, spp)");
  addPlacementOptions(cmd, o->place);
  cmd->add_option("--vcp-mm", o->vcpMm, "With --for-field: VCP distance in front of the MLA, mm")
      ->default_str(formatNumber(o->s.vcpMm));
  cmd->add_option("--spp", o->spp, "With --for-field: samples per display ray, as for inim eia")
      ->default_str(std::to_string(o->s.spp));
  addRunOptions(cmd, o->run, [o, cmd] {
    const auto t0 = std::chrono::steady_clock::now();
    (void)rayFileFormat(o->s.out, "--out", o->s.forField);
    checkCombinations(cmd, *o);
    const RayExportResult r = exportRays(exportSettings(*o));
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    std::printf("wrote %llu rays to %s: %s, in %.2f s\n%s", (unsigned long long)r.count, o->s.out.c_str(), r.what.c_str(),
                s, r.notes.c_str());
  });
}

}  // namespace inim::cli
