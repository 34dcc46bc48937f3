// inim rays: the pinhole chief ray of every pixel of every EI, as the paper's Zemax ray text
// (.txt, UTF-8 by default) or inim's binary rays (.irays). With --in, converts a ray file
// (the paper's UTF-16LE macro output included) instead.
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>

#include "cli/commands.h"
#include "core/error.h"
#include "core/output_file.h"
#include "core/parallel.h"
#include "core/progress.h"
#include "display/display.h"
#include "rays/pinhole_rays.h"
#include "rays/ray_binary.h"
#include "rays/zemax_ray_text.h"
#include "synthesis/display_overrides.h"
#include "synthesis/placement.h"

namespace fs = std::filesystem;

namespace inim::cli {

namespace {

enum class RayFormat { Text, Binary };

RayFormat formatOf(const std::string& path, const std::string& key) {
  std::string ext = fs::path(path).extension().string();
  for (auto& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
  if (ext == ".txt") return RayFormat::Text;
  if (ext == ".irays") return RayFormat::Binary;
  throw InputError("", key, "\"" + path + "\"", "a file ending in .txt (Zemax ray text) or .irays (inim binary rays)");
}

}  // namespace

void addRaysCommand(CLI::App& app) {
  struct Opts {
    std::string display, out, in, layout, ei;
    double gapMm = 0.0, viewingDistanceMm = 0.0;
    bool macro = false;
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
  auto* inOpt = cmd->add_option("--in", o->in,
                                "Convert this ray file (.txt: Zemax text, UTF-8 or UTF-16LE; .irays) to --out instead "
                                "of generating rays");
  addRunOptions(cmd, o->run);
  cmd->callback([=] {
    ThreadLimit threads(o->run.threads);
    const auto t0 = std::chrono::steady_clock::now();
    const RayFormat outFormat = formatOf(o->out, "--out");
    ZemaxTextOptions text;
    if (o->macro) {
      text.utf16 = true;
      text.crlf = true;
    }
    OutputSet outputs;
    uint64_t count = 0;
    std::string what;
    if (inOpt->count()) {
      if (gapOpt->count() || layoutOpt->count() || distOpt->count() || eiOpt->count() || !o->display.empty())
        throw InputError("", "--in", "\"" + o->in + "\"",
                         "no --display, --gap-mm, --layout, --viewing-distance-mm or --ei with --in (the file "
                         "already holds the rays)");
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
      Display d = loadDisplay(o->display.empty() ? defaultDisplayPath() : o->display);
      LayoutOverride lo;
      if (layoutOpt->count()) lo.layout = o->layout;
      if (distOpt->count()) lo.viewingDistanceMm = o->viewingDistanceMm;
      EiLayout L = applyLayoutOverride(d, lo);
      if (gapOpt->count()) {
        if (!(o->gapMm > 0.0) || !std::isfinite(o->gapMm))
          throw InputError("", "--gap-mm", std::to_string(o->gapMm), "a gap > 0 mm");
        L = L.withGap(o->gapMm);
      }
      std::string tmp = outputs.add(o->out);
      if (eiOpt->count()) {
        if (outFormat != RayFormat::Text)
          throw InputError("", "--ei", "\"" + o->ei + "\"", "--out FILE.txt (single-EI files are Zemax text)");
        int k = -1, l = -1;
        if (std::sscanf(o->ei.c_str(), "%d,%d", &k, &l) != 2 || k < 0 || l < 0 || k >= L.eiCols || l >= L.eiRows)
          throw InputError("", "--ei", "\"" + o->ei + "\"",
                           "K,L with 0 <= K < " + std::to_string(L.eiCols) + " and 0 <= L < " + std::to_string(L.eiRows));
        if (text.utf16) text.header = zemaxMacroHeader(L.raysPerEi());
        writeZemaxEiRayText(tmp, L, k, l, text);
        count = uint64_t(L.raysPerEi());
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
      std::snprintf(buf, sizeof buf, " (%s layout, %d x %d EIs of %d x %d px, g = %.6g mm)", layoutName(L.kind),
                    L.eiCols, L.eiRows, L.eiW, L.eiH, L.gapMm);
      what += buf;
    }
    outputs.commit();
    double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    std::printf("wrote %llu rays to %s: %s, in %.2f s\n", (unsigned long long)count, o->out.c_str(), what.c_str(), s);
  });
}

}  // namespace inim::cli
