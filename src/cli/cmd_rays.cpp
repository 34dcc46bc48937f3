// inim rays: the pinhole chief ray of every pixel of every EI, as the paper's Zemax ray text
// (.txt, UTF-8 by default) or inim's binary rays (.irays). With --real-lens, the rays that
// actually leave the refracting lenslets (src/mla/real_lens_rays.h). With --in, converts a ray
// file (the paper's UTF-16LE macro output included) instead. With --for-field, the query rays
// of an EIA for an external field (src/field/ray_table.h).
#include <chrono>
#include <cstdio>
#include <memory>
#include <string>

#include "cli/commands.h"
#include "cli/options.h"
#include "core/format.h"
#include "core/output_file.h"
#include "core/progress.h"
#include "field/ray_table.h"
#include "rays/pinhole_rays.h"
#include "rays/ray_binary.h"
#include "rays/zemax_ray_text.h"
#include "synthesis/eia_synthesis.h"

namespace inim::cli {

namespace {

enum class RayFormat { Text, Binary, FieldTable };

RayFormat formatOf(const std::string& path, const std::string& key, bool forField = false) {
  const std::string ext = lowerExtension(path);
  if (forField) {
    if (ext == ".npy" || ext == ".exr") return RayFormat::FieldTable;
    throw InputError("", key, "\"" + path + "\"", "with --for-field, a .npy or .exr ray table");
  }
  if (ext == ".txt") return RayFormat::Text;
  if (ext == ".irays") return RayFormat::Binary;
  throw InputError("", key, "\"" + path + "\"", "a file ending in .txt (Zemax ray text) or .irays (inim binary rays)");
}

struct RaysOpts {
  DisplayArgs display;
  std::string out, in, ei, runFile;
  double gapMm = 0.0, vcpMm = kDefaultVcpMm;
  int spp = 1;
  bool macro = false, forField = false;
  PlacementArgs place;
  RealLensArgs realLens;
  RunOptions run;
  CLI::Option *gapOpt, *eiOpt, *inOpt, *vcpOpt, *sppOpt;
  ZemaxTextOptions text;  // set from --zemax-macro
};

// What was written: the ray count and a description.
struct Written {
  uint64_t count = 0;
  std::string what;
};

void checkCombinations(CLI::App* cmd, const RaysOpts& o) {
  if (!o.forField) {
    for (const char* name : {"--run", "--vcp-mm", "--spp", "--scale", "--rotate-deg", "--translate-mm"})
      if (cmd->count(name)) throw InputError("", name, "given", "--for-field as well (it sets up the query rays)");
  } else if (o.inOpt->count() || o.eiOpt->count() || o.macro) {
    throw InputError("", "--for-field", "with " + std::string(o.inOpt->count() ? "--in" : o.eiOpt->count() ? "--ei" : "--zemax-macro"),
                     "the whole display's query rays (no --in, --ei or --zemax-macro)");
  }
  if (o.inOpt->count() && (o.gapOpt->count() || o.display.layoutOpt->count() || o.display.distanceOpt->count() ||
                           o.eiOpt->count() || !o.display.display.empty() || o.realLens.onOpt->count()))
    throw InputError("", "--in", "\"" + o.in + "\"",
                     "no --display, --gap-mm, --layout, --viewing-distance-mm, --ei or --real-lens with --in (the "
                     "file already holds the rays)");
}

void writeRays(const std::string& tmp, const RaySet& rays, RayFormat format, ZemaxTextOptions text,
               const RayBinaryInfo& info, const char* label) {
  ProgressBar bar(label, rays.size());
  if (format == RayFormat::Text) {
    if (text.utf16) text.header = zemaxMacroHeader(int64_t(rays.size()));
    writeZemaxRayText(tmp, rays, text, &bar);
  } else {
    writeRayBinary(tmp, rays, info);
  }
  bar.finish();
}

Written convertRays(const RaysOpts& o, const std::string& tmp, RayFormat outFormat) {
  RayBinaryInfo info;
  RaySet rays = formatOf(o.in, "--in") == RayFormat::Text ? readZemaxRayText(o.in) : readRayBinary(o.in, &info);
  writeRays(tmp, rays, outFormat, o.text, info, "rays");
  return {rays.size(), "converted from " + o.in};
}

// The query rays exactly as `inim eia` asks them: synthesis run against a field that records
// its queries.
Written writeQueryRays(const RaysOpts& o, const Display& d, const EiLayout& L, const RaySet* realRays,
                       const std::string& tmp) {
  const RunFile run = o.runFile.empty() ? RunFile{} : loadRunFile(o.runFile);
  SynthesisSettings s;
  s.placement = resolvePlacement(run.placement, placementOverride(o.place));
  s.vcpMm = optionOrRun(o.vcpOpt, o.vcpMm, run.vcpMm, kDefaultVcpMm);
  if (!std::isfinite(s.vcpMm)) throw InputError("", "--vcp-mm", formatNumber(s.vcpMm), "a finite distance in mm");
  s.spp = optionOrRun(o.sppOpt, o.spp, run.spp, 1);
  if (s.spp < 1) throw InputError("", "--spp", std::to_string(s.spp), "a whole number >= 1");
  s.displayRays = realRays;
  s.progress = ProgressBar::stderrIsTerminal();
  RecordingField rec(size_t(L.numRays()) * size_t(s.spp), s.spp, Point3(-1e6f), Point3(1e6f));
  synthesizeEia(L, d.panel, rec, s);
  writeRayTable(tmp, rec.table());
  return {rec.table().rays.size(),
          "query rays of " + d.name + " (field frame; placement " + s.placement.describe() + ", VCP " +
              formatNumber(s.vcpMm) + " mm, " + std::to_string(s.spp) +
              " spp; row = display ray x spp + sample)"};
}

// One EI's rays (Zemax text only), positions relative to its pinhole or, for real-lens rays,
// its physical lens centre.
Written writeEiRays(const RaysOpts& o, const Display& d, const EiLayout& L, const RaySet* realRays,
                    const std::string& tmp, RayFormat outFormat) {
  if (outFormat != RayFormat::Text)
    throw InputError("", "--ei", "\"" + o.ei + "\"", "--out FILE.txt (single-EI files are Zemax text)");
  int k = -1, l = -1;
  if (std::sscanf(o.ei.c_str(), "%d,%d", &k, &l) != 2 || k < 0 || l < 0 || k >= L.eiCols || l >= L.eiRows)
    throw InputError("", "--ei", "\"" + o.ei + "\"",
                     "K,L with 0 <= K < " + std::to_string(L.eiCols) + " and 0 <= L < " + std::to_string(L.eiRows));
  ZemaxTextOptions text = o.text;
  if (text.utf16) text.header = zemaxMacroHeader(L.eiRayCount(k, l));
  const std::string ei = "EI (" + std::to_string(k) + ", " + std::to_string(l) + ") of " + d.name;
  if (!realRays) {
    writeZemaxEiRayText(tmp, L, k, l, text);
    return {uint64_t(L.eiRayCount(k, l)), ei};
  }
  // The EI's block of rays (ray order: EI column, then EI row from the bottom).
  const int64_t first = L.eiRayBegin(k, l);
  const double cx = L.lensXAt(k, l), cy = L.lensYAt(k, l);
  writeZemaxRayText(
      tmp, L.eiRayCount(k, l),
      [&](int64_t i, double* v) {
        const Ray r = realRays->ray(size_t(first + i));
        v[0] = double(r.o.x) - cx, v[1] = double(r.o.y) - cy, v[2] = r.o.z;
        v[3] = r.d.x, v[4] = r.d.y, v[5] = r.d.z;
      },
      text);
  return {uint64_t(L.eiRayCount(k, l)), ei + ", positions relative to its lens centre"};
}

Written writeDisplayRays(const RaysOpts& o, const Display& d, const EiLayout& L, const RaySet* realRays,
                         const std::string& tmp, RayFormat outFormat) {
  if (realRays) {
    writeRays(tmp, *realRays, outFormat, o.text, RayBinaryInfo::fromLayout(L), "write");
    return {realRays->size(), d.name};
  }
  if (outFormat == RayFormat::Text) {  // straight from the layout, without a ray set in memory
    ZemaxTextOptions text = o.text;
    if (text.utf16) text.header = zemaxMacroHeader(L.numRays());
    ProgressBar bar("rays", uint64_t(L.numRays()));
    writeZemaxRayText(tmp, L, text, &bar);
    bar.finish();
    return {uint64_t(L.numRays()), d.name};
  }
  ProgressBar bar("rays", uint64_t(L.numRays()));
  RaySet rays = generatePinholeRays(L, &bar);
  bar.finish();
  writeRayBinary(tmp, rays, RayBinaryInfo::fromLayout(L));
  return {rays.size(), d.name};
}

std::string layoutText(const Display& d, const EiLayout& L) {
  char buf[160];
  if (L.isHex())
    std::snprintf(buf, sizeof buf, " (%s layout, hex lattice, %d rows of %d EIs, %d px across the flats, g = %.6g mm)",
                  layoutName(L.kind), L.eiRows, L.eiCols, d.eiWidthPx, L.gapMm);
  else
    std::snprintf(buf, sizeof buf, " (%s layout, %d x %d EIs of %d x %d px, g = %.6g mm)", layoutName(L.kind), L.eiCols,
                  L.eiRows, L.eiW, L.eiH, L.gapMm);
  return buf;
}

std::string realLensNotes(const Display& d, const EiLayout& L, const RealLensRayOptions& ro,
                          const RealLensRayStats& stats) {
  std::string notes = summaryText(ro, stats) + "\n";
  if (L.kind != EiLayoutKind::Parallel) return notes;
  char note[200];
  std::snprintf(note, sizeof note,
                "note: real-lens rays go through the physical lens centres (pitch %.6g mm), not the parallel layout's "
                "EI-centred pinholes\n",
                d.mla.pitchMm);
  return notes + note;
}

}  // namespace

void addRaysCommand(CLI::App& app) {
  auto o = std::make_shared<RaysOpts>();
  auto* cmd = app.add_subcommand(
      "rays", "Write the display rays: one pinhole chief ray per EI pixel (origin on the pinhole, z = 0; unit "
              "direction toward the viewer), in the paper's ray order");
  addDisplayOptions(cmd, o->display);
  cmd->add_option("--out", o->out, "Output: FILE.txt (Zemax ray text, \"x, y, z, l, m, n\" %.8f) or FILE.irays")
      ->required();
  o->gapOpt = cmd->add_option("--gap-mm", o->gapMm, "Generate at this panel gap instead of generation_gap_mm");
  cmd->add_flag("--zemax-macro", o->macro,
                "Text as the paper's ZPL macro wrote it: UTF-16LE with BOM, CRLF, two header lines");
  o->eiOpt = cmd->add_option("--ei", o->ei,
                             "Only EI K,L (K from the left, L from the top), positions relative to its pinhole (the "
                             "macro's single-EI file); .txt only");
  addRealLensOptions(cmd, o->realLens,
                     "Trace every pixel's ray through the real MLA (refraction at n(lambda), the physical lens "
                     "centres) instead of the pinhole model; origins moved back to z = 0");
  o->inOpt = cmd->add_option("--in", o->in,
                             "Convert this ray file (.txt: Zemax text, UTF-8 or UTF-16LE; .irays) to --out instead "
                             "of generating rays");
  cmd->add_flag("--for-field", o->forField,
                "Write the orthoscopic QUERY rays instead (field frame, after the inverse placement; reversed display "
                "rays starting on the VCP) as a table for an external radiance field: --out FILE.npy (float32 N x 8: "
                "ox oy oz dx dy dz near far) or FILE.exr; fill in one colour per row and pass it to `inim eia "
                "--field-colors`");
  cmd->add_option("--run", o->runFile, "With --for-field: run file of the EIA (placement, VCP, spp)");
  addPlacementOptions(cmd, o->place);
  o->vcpOpt = cmd->add_option("--vcp-mm", o->vcpMm, "With --for-field: VCP distance in front of the MLA, mm")
                  ->capture_default_str();
  o->sppOpt = cmd->add_option("--spp", o->spp, "With --for-field: samples per display ray, as for inim eia")
                  ->capture_default_str();
  addRunOptions(cmd, o->run, [o, cmd] {
    const auto t0 = std::chrono::steady_clock::now();
    const RayFormat outFormat = formatOf(o->out, "--out", o->forField);
    checkCombinations(cmd, *o);
    o->text.utf16 = o->text.crlf = o->macro;
    OutputSet outputs;
    Written w;
    std::string notes;
    if (o->inOpt->count()) {
      w = convertRays(*o, outputs.add(o->out), outFormat);
    } else {
      const RealLensRayOptions ro = realLensRayOptions(o->realLens);
      Display d;
      EiLayout L = loadDisplayLayout(o->display, d);
      if (o->gapOpt->count()) L = L.withGap(checkedGap(o->gapMm, std::to_string(o->gapMm)));
      // Real-lens rays: traced before any output is opened (a bad MLA fails here).
      RealLensRayStats stats;
      const RaySet realRays = o->realLens.on ? traceRealLensRays(d, L, ro, &stats, true) : RaySet{};
      const RaySet* real = o->realLens.on ? &realRays : nullptr;
      const std::string tmp = outputs.add(o->out);
      w = o->forField        ? writeQueryRays(*o, d, L, real, tmp)
          : o->eiOpt->count() ? writeEiRays(*o, d, L, real, tmp, outFormat)
                              : writeDisplayRays(*o, d, L, real, tmp, outFormat);
      w.what += layoutText(d, L);
      if (o->realLens.on) notes = realLensNotes(d, L, ro, stats);
    }
    outputs.commit();
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    std::printf("wrote %llu rays to %s: %s, in %.2f s\n%s", (unsigned long long)w.count, o->out.c_str(), w.what.c_str(),
                s, notes.c_str());
  });
}

}  // namespace inim::cli
