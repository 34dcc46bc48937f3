#include "runs/ray_export.h"

#include <cstdio>
#include <memory>

#include "display/gap_range.h"
#include "core/error.h"
#include "core/format.h"
#include "core/output_file.h"
#include "core/file_kinds.h"
#include "core/progress.h"
#include "display/display.h"
#include "field/ray_table.h"
#include "mla_optics/real_mla.h"
#include "rays/pinhole_rays.h"
#include "rays/ray_binary.h"
#include "rays/zemax_ray_text.h"
#include "synthesis/eia_synthesis.h"

namespace inim {

RayFileFormat rayFileFormat(const std::string& path, const std::string& key, bool forField) {
  if (forField) {
    (void)requireFileKind(path, key, {FileKind::Npy, FileKind::Exr}, "with --for-field, a .npy or .exr ray table");
    return RayFileFormat::FieldTable;
  }
  return requireFileKind(path, key, {FileKind::Txt, FileKind::Irays},
                         "a file ending in .txt (Zemax ray text) or .irays (inim binary rays)") == FileKind::Txt
             ? RayFileFormat::ZemaxText
             : RayFileFormat::Binary;
}

namespace {

// Where the rays go, and the display they come from.
struct Target {
  const RayExportSettings& s;
  RayFileFormat format;
  ZemaxTextOptions text;
  std::string tmp;
  Display display;
  EiLayout layout;
  const RaySet* realRays = nullptr;
};

void writeRays(const Target& t, const RaySet& rays, const RayBinaryInfo& info, const char* label) {
  ProgressBar bar(label, rays.size());
  if (t.format == RayFileFormat::ZemaxText) {
    ZemaxTextOptions text = t.text;
    if (text.utf16) text.header = zemaxMacroHeader(int64_t(rays.size()));
    writeZemaxRayText(t.tmp, rays, text, &bar);
  } else {
    writeRayBinary(t.tmp, rays, info);
  }
  bar.finish();
}

// The query rays exactly as an EIA asks them: synthesis run against a field that records its
// queries.
RayExportResult writeQueryRays(const Target& t) {
  SynthesisSettings s;
  s.placement = resolvePlacement(t.s.placement, t.s.placementOverride);
  s.vcpMm = t.s.vcpMm;
  s.spp = t.s.spp;
  s.displayRays = t.realRays;
  s.progress = ProgressBar::stderrIsTerminal();
  RecordingField rec(size_t(t.layout.numRays()) * size_t(s.spp), s.spp, Point3(-1e6f), Point3(1e6f));
  synthesizeEia(t.layout, t.display.panel, rec, s);
  writeRayTable(t.tmp, rec.table());
  return {rec.table().rays.size(),
          "query rays of " + t.display.name + " (field frame; placement " + s.placement.describe() + ", VCP " +
              formatNumber(s.vcpMm) + " mm, " + std::to_string(s.spp) + " spp; row = display ray x spp + sample)",
          ""};
}

// One EI's rays (Zemax text only), positions relative to its pinhole or, for real-lens rays,
// its physical lens centre.
RayExportResult writeEiRays(const Target& t) {
  const EiLayout& L = t.layout;
  if (t.format != RayFileFormat::ZemaxText)
    throw InputError("", "ei", "\"" + t.s.ei + "\"", "--out FILE.txt (single-EI files are Zemax text)");
  int k = -1, l = -1;
  if (std::sscanf(t.s.ei.c_str(), "%d,%d", &k, &l) != 2 || k < 0 || l < 0 || k >= L.eiCols || l >= L.eiRows)
    throw InputError("", "ei", "\"" + t.s.ei + "\"",
                     "K,L with 0 <= K < " + std::to_string(L.eiCols) + " and 0 <= L < " + std::to_string(L.eiRows));
  ZemaxTextOptions text = t.text;
  if (text.utf16) text.header = zemaxMacroHeader(L.eiRayCount(k, l));
  const std::string ei = "EI (" + std::to_string(k) + ", " + std::to_string(l) + ") of " + t.display.name;
  if (!t.realRays) {
    writeZemaxEiRayText(t.tmp, L, k, l, text);
    return {uint64_t(L.eiRayCount(k, l)), ei, ""};
  }
  // The EI's block of rays (ray order: EI column, then EI row from the bottom).
  const int64_t first = L.eiRayBegin(k, l);
  const double cx = L.lensXAt(k, l), cy = L.lensYAt(k, l);
  writeZemaxRayText(
      t.tmp, L.eiRayCount(k, l),
      [&](int64_t i, double* v) {
        const Ray r = t.realRays->ray(size_t(first + i));
        v[0] = double(r.o.x) - cx, v[1] = double(r.o.y) - cy, v[2] = r.o.z;
        v[3] = r.d.x, v[4] = r.d.y, v[5] = r.d.z;
      },
      text);
  return {uint64_t(L.eiRayCount(k, l)), ei + ", positions relative to its lens centre", ""};
}

RayExportResult writeDisplayRays(const Target& t) {
  const EiLayout& L = t.layout;
  if (t.realRays) {
    writeRays(t, *t.realRays, RayBinaryInfo::fromLayout(L), "write");
    return {t.realRays->size(), t.display.name, ""};
  }
  ProgressBar bar("rays", uint64_t(L.numRays()));
  if (t.format == RayFileFormat::ZemaxText) {  // straight from the layout, without a ray set in memory
    ZemaxTextOptions text = t.text;
    if (text.utf16) text.header = zemaxMacroHeader(L.numRays());
    writeZemaxRayText(t.tmp, L, text, &bar);
    bar.finish();
    return {uint64_t(L.numRays()), t.display.name, ""};
  }
  RaySet rays = generatePinholeRays(L, &bar);
  bar.finish();
  writeRayBinary(t.tmp, rays, RayBinaryInfo::fromLayout(L));
  return {rays.size(), t.display.name, ""};
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

std::string raysNotes(const Display& d, const EiLayout& L, const std::string& summary) {
  std::string notes = summary + "\n";
  if (L.kind != EiLayoutKind::Parallel) return notes;
  char note[200];
  std::snprintf(note, sizeof note,
                "note: real-lens and traced chief rays go through the physical lens centres (pitch %.6g mm), not the parallel layout's "
                "EI-centred pinholes\n",
                d.mla.pitchMm);
  return notes + note;
}

RayExportResult convertRays(const RayExportSettings& s, const ZemaxTextOptions& text, RayFileFormat outFormat) {
  RayBinaryInfo info;
  const RaySet rays = rayFileFormat(s.in, "in") == RayFileFormat::ZemaxText ? readZemaxRayText(s.in)
                                                                            : readRayBinary(s.in, &info);
  OutputSet outputs;
  Target t{s, outFormat, text, outputs.add(s.out), {}, {}, nullptr};
  writeRays(t, rays, info, "rays");
  outputs.commit();
  return {rays.size(), "converted from " + s.in, ""};
}

}  // namespace

RayExportResult exportRays(const RayExportSettings& s) {
  const RayFileFormat outFormat = rayFileFormat(s.out, "out", s.forField);
  ZemaxTextOptions text;
  text.utf16 = text.crlf = s.zemaxMacro;
  if (!s.in.empty()) return convertRays(s, text, outFormat);
  OutputSet outputs;
  Target t{s, outFormat, text, "", loadDisplay(displayPathOrDefault(s.displayPath)), {}, nullptr};
  t.layout = applyLayoutOverride(t.display, s.layout);
  if (s.gapMm) {
    checkGapMm(*s.gapMm, "", "gap_mm");
    t.layout = t.layout.withGap(*s.gapMm);
  }
  // Real-lens or traced chief rays: traced before any output is opened (a bad MLA fails here).
  const DisplayRays rays = displayRaysFor(t.display, t.layout, s.rays, true);
  if (rays.rays) t.realRays = &*rays.rays;
  t.tmp = outputs.add(s.out);
  RayExportResult r = s.forField ? writeQueryRays(t) : !s.ei.empty() ? writeEiRays(t) : writeDisplayRays(t);
  outputs.commit();
  r.what += layoutText(t.display, t.layout);
  if (rays.rays) r.notes = raysNotes(t.display, t.layout, rays.summary);
  return r;
}

std::string exportText(const RayExportSettings& s, const RayExportResult& r, double seconds) {
  return formatText("wrote %llu rays to %s: %s, in %.2f s\n", (unsigned long long)r.count, s.out.c_str(),
                    r.what.c_str(), seconds) +
         r.notes;
}

}  // namespace inim
