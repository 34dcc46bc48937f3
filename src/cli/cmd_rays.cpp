// inim rays: the pinhole chief ray of every pixel of every EI, as the paper's Zemax ray text
// (.txt, UTF-8 by default) or inim's binary rays (.irays). With --real-lens, the rays that
// actually leave the refracting lenslets (src/mla/real_lens_rays.h). With --in, converts a ray
// file (the paper's UTF-16LE macro output included) instead.
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>

#include "core/format.h"
#include "cli/commands.h"
#include "cli/scene_options.h"
#include "core/error.h"
#include "core/output_file.h"
#include "core/parallel.h"
#include "core/progress.h"
#include "display/display.h"
#include "field/ray_table.h"
#include "mla/real_lens_rays.h"
#include "mla/real_mla.h"
#include "rays/pinhole_rays.h"
#include "rays/ray_binary.h"
#include "rays/zemax_ray_text.h"
#include "synthesis/display_overrides.h"
#include "synthesis/eia_synthesis.h"
#include "synthesis/placement.h"

namespace fs = std::filesystem;

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

}  // namespace

void addRaysCommand(CLI::App& app) {
  struct Opts {
    std::string display, out, in, layout, ei, realLensRay = "centroid", runFile;
    double gapMm = 0.0, viewingDistanceMm = 0.0, wavelengthNm = kLambdaDNm, vcpMm = kDefaultVcpMm;
    int spp = 1;
    bool macro = false, realLens = false, forField = false;
    PlacementArgs place;
    RunOptions run;
  };
  auto o = std::make_shared<Opts>();
  auto* cmd = app.add_subcommand(
      "rays", "Write the display rays: one pinhole chief ray per EI pixel (origin on the pinhole, z = 0; unit "
              "direction toward the viewer), in the paper's ray order");
  cmd->add_option("--display", o->display, "Display JSON (default: optics/displays/paper-prototype.json)");
  cmd->add_option("--out", o->out, "Output: FILE.txt (Zemax ray text, \"x, y, z, l, m, n\" %.8f) or FILE.irays")
      ->required();
  auto* gapOpt = cmd->add_option("--gap-mm", o->gapMm, "Generate at this panel gap instead of generation_gap_mm");
  auto* layoutOpt = cmd->add_option("--layout", o->layout, "EI layout: parallel, toed-in or lens-grid (default: the display's)");
  auto* distOpt = cmd->add_option("--viewing-distance-mm", o->viewingDistanceMm, "Viewing distance D for toed-in");
  cmd->add_flag("--zemax-macro", o->macro,
                "Text as the paper's ZPL macro wrote it: UTF-16LE with BOM, CRLF, two header lines");
  auto* eiOpt = cmd->add_option("--ei", o->ei,
                                "Only EI K,L (K from the left, L from the top), positions relative to its pinhole (the "
                                "macro's single-EI file); .txt only");
  auto* realOpt = cmd->add_flag("--real-lens", o->realLens,
                                "Trace every pixel's ray through the real MLA (refraction at n(lambda), the physical "
                                "lens centres) instead of the pinhole model; origins moved back to z = 0");
  auto* realRayOpt = cmd->add_option("--real-lens-ray", o->realLensRay,
                                     "With --real-lens: centroid (the power centroid of the pixel's exit bundle through "
                                     "its lenslet, default) or chief (the ray through the lenslet's aperture centre)");
  auto* wlOpt = cmd->add_option("--wavelength-nm", o->wavelengthNm, "With --real-lens: the wavelength, nm")
                    ->capture_default_str();
  auto* inOpt = cmd->add_option("--in", o->in,
                                "Convert this ray file (.txt: Zemax text, UTF-8 or UTF-16LE; .irays) to --out instead "
                                "of generating rays");
  auto* forFieldOpt = cmd->add_flag(
      "--for-field", o->forField,
      "Write the orthoscopic QUERY rays instead (field frame, after the inverse placement; reversed display rays "
      "starting on the VCP) as a table for an external radiance field: --out FILE.npy (float32 N x 8: ox oy oz dx dy "
      "dz near far) or FILE.exr; fill in one colour per row and pass it to `inim eia --field-colors`");
  auto* runFileOpt = cmd->add_option("--run", o->runFile, "With --for-field: run file of the EIA (placement, VCP, spp)");
  addPlacementOptions(cmd, o->place);
  auto* vcpOpt = cmd->add_option("--vcp-mm", o->vcpMm, "With --for-field: VCP distance in front of the MLA, mm")
                     ->capture_default_str();
  auto* sppOpt = cmd->add_option("--spp", o->spp, "With --for-field: samples per display ray, as for inim eia")
                     ->capture_default_str();
  addRunOptions(cmd, o->run);
  cmd->callback([=] {
    ThreadLimit threads(o->run.threads);
    const auto t0 = std::chrono::steady_clock::now();
    const RayFormat outFormat = formatOf(o->out, "--out", o->forField);
    if (!o->forField) {
      for (CLI::Option* opt : {runFileOpt, vcpOpt, sppOpt, o->place.scaleOpt, o->place.rotOpt, o->place.trOpt})
        if (opt->count())
          throw InputError("", opt->get_name(), "given", "--for-field as well (it sets up the query rays)");
    } else if (inOpt->count() || eiOpt->count() || o->macro) {
      throw InputError("", "--for-field", "with " + std::string(inOpt->count() ? "--in" : eiOpt->count() ? "--ei" : "--zemax-macro"),
                       "the whole display's query rays (no --in, --ei or --zemax-macro)");
    }
    ZemaxTextOptions text;
    if (o->macro) {
      text.utf16 = true;
      text.crlf = true;
    }
    OutputSet outputs;
    uint64_t count = 0;
    std::string what, extra;
    if (inOpt->count()) {
      if (gapOpt->count() || layoutOpt->count() || distOpt->count() || eiOpt->count() || !o->display.empty() ||
          realOpt->count())
        throw InputError("", "--in", "\"" + o->in + "\"",
                         "no --display, --gap-mm, --layout, --viewing-distance-mm, --ei or --real-lens with --in (the "
                         "file already holds the rays)");
      RayFormat inFormat = formatOf(o->in, "--in");
      RayBinaryInfo info;
      RaySet rays = inFormat == RayFormat::Text ? readZemaxRayText(o->in) : readRayBinary(o->in, &info);
      std::string tmp = outputs.add(o->out);
      if (outFormat == RayFormat::Text) {
        if (text.utf16) text.header = zemaxMacroHeader(int64_t(rays.size()));
        ProgressBar bar("rays", rays.size());
        writeZemaxRayText(tmp, rays, text, &bar);
        bar.finish();
      } else {
        writeRayBinary(tmp, rays, info);
      }
      count = rays.size();
      what = "converted from " + o->in;
    } else {
      if (!o->realLens && (realRayOpt->count() || wlOpt->count()))
        throw InputError("", realRayOpt->count() ? "--real-lens-ray" : "--wavelength-nm",
                         realRayOpt->count() ? "\"" + o->realLensRay + "\"" : formatNumber(o->wavelengthNm),
                         "--real-lens as well (the pinhole model has no refraction)");
      RealLensRayOptions ro;
      if (o->realLens) {
        ro.model = parseRealLensRayModel(o->realLensRay, "--real-lens-ray");
        if (!(o->wavelengthNm >= 360.0 && o->wavelengthNm <= 830.0))
          throw InputError("", "--wavelength-nm", formatNumber(o->wavelengthNm), "a wavelength in 360-830 nm");
        ro.wavelengthNm = o->wavelengthNm;
      }
      Display d = loadDisplay(displayPathOrDefault(o->display));
      LayoutOverride lo;
      if (layoutOpt->count()) lo.layout = o->layout;
      if (distOpt->count()) lo.viewingDistanceMm = o->viewingDistanceMm;
      EiLayout L = applyLayoutOverride(d, lo);
      if (gapOpt->count()) {
        if (!(o->gapMm > 0.0) || !std::isfinite(o->gapMm))
          throw InputError("", "--gap-mm", std::to_string(o->gapMm), "a gap > 0 mm");
        L = L.withGap(o->gapMm);
      }
      // Real-lens rays: traced before any output is opened (a bad MLA fails here).
      RaySet realRays;
      RealLensRayStats realStats;
      if (o->realLens) {
        std::unique_ptr<RealMla> mla = RealMla::fromDisplay(d, L, L.gapMm);
        ProgressBar bar("real-lens rays", uint64_t(L.numRays()));
        realRays = generateRealLensRays(L, *mla, ro, &realStats, &bar);
        bar.finish();
      }
      std::string tmp = outputs.add(o->out);
      if (o->forField) {
        // The query rays exactly as `inim eia` asks them: synthesis run against a field that
        // records its queries.
        RunFile run;
        if (runFileOpt->count()) run = loadRunFile(o->runFile);
        SynthesisSettings s;
        s.placement = resolvePlacement(o->place, run.placement);
        s.vcpMm = vcpOpt->count() ? o->vcpMm : run.vcpMm.value_or(kDefaultVcpMm);
        if (!std::isfinite(s.vcpMm)) throw InputError("", "--vcp-mm", formatNumber(s.vcpMm), "a finite distance in mm");
        s.spp = sppOpt->count() ? o->spp : run.spp.value_or(1);
        if (s.spp < 1) throw InputError("", "--spp", std::to_string(s.spp), "a whole number >= 1");
        s.displayRays = o->realLens ? &realRays : nullptr;
        s.progress = ProgressBar::stderrIsTerminal();
        const Point3 lo(-1e6f), hi(1e6f);
        RecordingField rec(size_t(L.numRays()) * size_t(s.spp), s.spp, lo, hi);
        synthesizeEia(L, d.panel, rec, s);
        writeRayTable(tmp, rec.table());
        count = rec.table().rays.size();
        what = "query rays of " + d.name + " (field frame; placement " + s.placement.describe() + ", VCP " +
               formatNumber(s.vcpMm) + " mm, " + std::to_string(s.spp) + " spp; row = display ray x spp + sample)";
      } else if (eiOpt->count() && o->realLens) {
        if (outFormat != RayFormat::Text)
          throw InputError("", "--ei", "\"" + o->ei + "\"", "--out FILE.txt (single-EI files are Zemax text)");
        int k = -1, l = -1;
        if (std::sscanf(o->ei.c_str(), "%d,%d", &k, &l) != 2 || k < 0 || l < 0 || k >= L.eiCols || l >= L.eiRows)
          throw InputError("", "--ei", "\"" + o->ei + "\"",
                           "K,L with 0 <= K < " + std::to_string(L.eiCols) + " and 0 <= L < " + std::to_string(L.eiRows));
        if (text.utf16) text.header = zemaxMacroHeader(L.eiRayCount(k, l));
        // The EI's block of rays (ray order: EI column, then EI row from the bottom), positions
        // relative to its physical lens centre.
        const int64_t first = L.eiRayBegin(k, l);
        const double cx = L.lensXAt(k, l), cy = L.lensYAt(k, l);
        writeZemaxRayText(
            tmp, L.eiRayCount(k, l),
            [&](int64_t i, double* v) {
              const Ray r = realRays.ray(size_t(first + i));
              v[0] = double(r.o.x) - cx, v[1] = double(r.o.y) - cy, v[2] = r.o.z;
              v[3] = r.d.x, v[4] = r.d.y, v[5] = r.d.z;
            },
            text);
        count = uint64_t(L.eiRayCount(k, l));
        what = "EI (" + std::to_string(k) + ", " + std::to_string(l) + ") of " + d.name + ", positions relative to its lens centre";
      } else if (o->realLens) {
        ProgressBar bar("write", realRays.size());
        if (outFormat == RayFormat::Text) {
          if (text.utf16) text.header = zemaxMacroHeader(int64_t(realRays.size()));
          writeZemaxRayText(tmp, realRays, text, &bar);
        } else {
          writeRayBinary(tmp, realRays, RayBinaryInfo::fromLayout(L));
        }
        bar.finish();
        count = realRays.size();
        what = d.name;
      } else if (eiOpt->count()) {
        if (outFormat != RayFormat::Text)
          throw InputError("", "--ei", "\"" + o->ei + "\"", "--out FILE.txt (single-EI files are Zemax text)");
        int k = -1, l = -1;
        if (std::sscanf(o->ei.c_str(), "%d,%d", &k, &l) != 2 || k < 0 || l < 0 || k >= L.eiCols || l >= L.eiRows)
          throw InputError("", "--ei", "\"" + o->ei + "\"",
                           "K,L with 0 <= K < " + std::to_string(L.eiCols) + " and 0 <= L < " + std::to_string(L.eiRows));
        if (text.utf16) text.header = zemaxMacroHeader(L.eiRayCount(k, l));
        writeZemaxEiRayText(tmp, L, k, l, text);
        count = uint64_t(L.eiRayCount(k, l));
        what = "EI (" + std::to_string(k) + ", " + std::to_string(l) + ") of " + d.name;
      } else if (outFormat == RayFormat::Text) {
        if (text.utf16) text.header = zemaxMacroHeader(L.numRays());
        ProgressBar bar("rays", uint64_t(L.numRays()));
        writeZemaxRayText(tmp, L, text, &bar);
        bar.finish();
        count = uint64_t(L.numRays());
        what = d.name;
      } else {
        ProgressBar bar("rays", uint64_t(L.numRays()));
        RaySet rays = generatePinholeRays(L, &bar);
        bar.finish();
        writeRayBinary(tmp, rays, RayBinaryInfo::fromLayout(L));
        count = rays.size();
        what = d.name;
      }
      char buf[160];
      if (L.isHex())
        std::snprintf(buf, sizeof buf, " (%s layout, hex lattice, %d rows of %d EIs, %d px across the flats, g = %.6g mm)",
                      layoutName(L.kind), L.eiRows, L.eiCols, d.eiWidthPx, L.gapMm);
      else
        std::snprintf(buf, sizeof buf, " (%s layout, %d x %d EIs of %d x %d px, g = %.6g mm)", layoutName(L.kind),
                      L.eiCols, L.eiRows, L.eiW, L.eiH, L.gapMm);
      what += buf;
      if (o->realLens) {
        extra += summaryText(ro, realStats) + "\n";
        if (L.kind == EiLayoutKind::Parallel) {
          char note[200];
          std::snprintf(note, sizeof note,
                        "note: real-lens rays go through the physical lens centres (pitch %.6g mm), not the "
                        "parallel layout's EI-centred pinholes\n",
                        d.mla.pitchMm);
          extra += note;
        }
      }
    }
    outputs.commit();
    double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    std::printf("wrote %llu rays to %s: %s, in %.2f s\n%s", (unsigned long long)count, o->out.c_str(), what.c_str(), s,
                extra.c_str());
  });
}

}  // namespace inim::cli
