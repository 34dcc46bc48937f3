// `inim study architectures`: the catalogue's display architectures (optics/displays: today's
// single MLA, a convex-concave double MLA, a symmetric compound array, a pinhole array, an MLA
// with barrier walls) on the same panel and the default scene, each seen as in Fig. 11 with its
// error budget (a rung for each layer kind the ideal display lacks): one contact sheet each, the
// budget, the error against depth, and the first-order viewing angle, reference plane and depth
// range side by side, with which design suits which scene depth.
#include <algorithm>
#include <cmath>
#include <filesystem>

#include "analysis/depth_error.h"
#include "analysis/plot.h"
#include "core/error.h"
#include "core/format.h"
#include "core/output_file.h"
#include "display/display_info.h"
#include "display/stack_first_order.h"
#include "runs/fig11.h"
#include "studies/studies.h"
#include "studies/study_report.h"

namespace fs = std::filesystem;

namespace inim {

using namespace study_detail;

namespace {

struct Design {
  std::string stem, label, architecture;
};

const std::vector<Design>& designs() {
  static const std::vector<Design> list = {
      {"paper-prototype", "paper prototype", "one plano-convex MLA (today's)"},
      {"double-mla-convex-concave", "double MLA", "convex then concave MLA (virtual EIA)"},
      {"compound-symmetric", "compound array", "two plano-convex MLAs, caps facing, stop grid"},
      {"pinhole-array", "pinhole array", "opaque sheet with holes, no lens"},
      {"barrier-mla", "barrier MLA", "the prototype's MLA with absorbing walls"},
      {"curved-mla-flat-panel", "curved MLA", "the prototype's MLA bent into a 2 m cylinder over the flat panel"},
  };
  return list;
}

// The ladder's rungs any design may have, in order (columns of the budget table).
const std::vector<std::string> kLadder = {"ideal",     "+subpixels",  "+real_mla",    "+apertures",
                                          "+barriers", "+cover_glass", "+colour_chain"};

struct DesignRun {
  Design design;
  double pitchMm = 0.0, gapMm = 0.0, psiDeg = 0.0, depthRangeMm = 0.0;
  std::optional<double> focalMm, lMm;  // L through the cover glass; none at infinity
  double centreDe = 0.0, meanDe = 0.0, floorDe = 0.0;
  std::vector<double> rungDe;          // kLadder; NaN where the design has no such rung
  std::vector<DepthBin> bins;          // 0°
};

std::vector<std::string> ladderOf(const Display& d) {
  std::vector<std::string> names;
  for (const BudgetRung& r : budgetRungs(&d))
    if (!r.removal && !r.calibrated) names.push_back(r.name);
  return names;
}

DesignRun runDesign(const StudyOptions& o, const Design& design, const fs::path& scratch) {
  DesignRun run;
  run.design = design;
  const Display d = loadDisplay(dataPath("optics/displays/" + design.stem + ".json"));
  const DisplayInfo info = derive(d);
  const GapInfo& g = info.reconstruction;
  run.pitchMm = d.mla.pitchMm;
  run.gapMm = d.reconstructionGapMm;
  run.psiDeg = g.opticalViewingAngleDeg.value_or(g.viewingAngleDeg);
  run.lMm = g.opticalReferencePlaneMm ? g.opticalReferencePlaneMm : g.referencePlaneMm;
  run.depthRangeMm = g.depthRangeMm;
  if (!d.stack) run.focalMm = lensletFocus(d.mla).focalLengthMm;
  else if (const StackFirstOrder fo = stackFirstOrder(*d.stack); !fo.afocal) run.focalMm = fo.focalLengthMm;
  else run.lMm.reset();  // no power (a pinhole sheet): it forms no image of the panel
  Fig11Settings s;
  s.display = d;
  s.outDir = (scratch / design.stem).string();
  s.budget = true;
  s.budgetRungs = ladderOf(d);
  s.sheetImageWidth = 324;  // the sheets kept in the repository: half the views' width
  if (o.quick) {
    s.width = 128;
    s.eiaSpp = 1;
    s.poses = {"centre"};
  }
  const Fig11Result r = runFig11(s);
  for (const Fig11View& v : r.views) {
    if (!v.hasMetrics) continue;
    run.meanDe += v.metrics.deltaE.mean / double(r.views.size());
    if (v.name == "centre") run.centreDe = v.metrics.deltaE.mean, run.bins = v.depthBins;
  }
  const PoseBudget& b = r.budgets.front();
  run.floorDe = b.noiseFloor.deltaE.mean;
  for (const std::string& name : kLadder) {
    double de = NAN;
    for (const RungResult& rr : b.ladder)
      if (rr.rung.name == name && !rr.skipped) de = rr.metrics.deltaE.mean;
    run.rungDe.push_back(de);
  }
  return run;
}

std::string lText(const DesignRun& r) { return r.lMm ? fixed(*r.lMm, 1) : r.focalMm ? std::string("∞") : std::string("none"); }

// Pixel-weighted mean CIEDE2000 of the bins whose centre lies in [zLo, zHi); NaN when none.
double bandError(const std::vector<DepthBin>& bins, double zLo, double zHi) {
  double sum = 0.0;
  int64_t n = 0;
  for (const DepthBin& b : bins)
    if (b.zCentre >= zLo && b.zCentre < zHi && std::isfinite(b.de2000Mean)) sum += b.de2000Mean * double(b.pixels), n += b.pixels;
  return n ? sum / double(n) : NAN;
}

struct DepthBand {
  std::string name;
  double zLo, zHi;
};
const std::vector<DepthBand> kBands = {{"behind the display (z < -10 mm)", -1e9, -10.0},
                                       {"near its plane (-10 to 10 mm)", -10.0, 10.0},
                                       {"in front (z > 10 mm)", 10.0, 1e9}};

std::string firstOrderTable(const std::vector<DesignRun>& runs) {
  std::string t = "| design | architecture | P (mm) | f (mm) | g (mm) | ψ (°) | L (mm) | depth range (mm) | noise "
                  "floor | full chain, 0° | full chain, mean of poses |\n|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const DesignRun& r : runs)
    t += "| " + r.design.label + " | " + r.design.architecture + " | " + fixed(r.pitchMm, 4) + " | " +
         (r.focalMm ? fixed(*r.focalMm, 3) : std::string("–")) + " | " + fixed(r.gapMm, 3) + " | " + fixed(r.psiDeg, 1) +
         " | " + lText(r) + " | ±" + fixed(r.depthRangeMm, 1) + " | " + fixed(r.floorDe, 2) + " | " +
         fixed(r.centreDe, 2) + " | " + fixed(r.meanDe, 2) + " |\n";
  return t + "\n";
}

std::string budgetTable(const std::vector<DesignRun>& runs) {
  std::string t = "| design |";
  for (const std::string& n : kLadder) t += " " + n + " |";
  t += "\n|---|";
  for (size_t i = 0; i < kLadder.size(); ++i) t += "---|";
  t += "\n";
  for (const DesignRun& r : runs) {
    t += "| " + r.design.label + " |";
    for (double v : r.rungDe) t += " " + fixedOrDash(v, 2) + " |";
    t += "\n";
  }
  return t + "\n";
}

std::string bandTable(const std::vector<DesignRun>& runs, std::string& suits) {
  std::string t = "| design |";
  for (const DepthBand& b : kBands) t += " " + b.name + " |";
  t += "\n|---|---|---|---|\n";
  for (const DesignRun& r : runs) {
    t += "| " + r.design.label + " |";
    for (const DepthBand& b : kBands) t += " " + fixedOrDash(bandError(r.bins, b.zLo, b.zHi), 2) + " |";
    t += "\n";
  }
  for (const DepthBand& b : kBands) {
    const DesignRun* best = nullptr;
    double bestDe = INFINITY;
    for (const DesignRun& r : runs)
      if (const double e = bandError(r.bins, b.zLo, b.zHi); std::isfinite(e) && e < bestDe) bestDe = e, best = &r;
    suits += "- " + b.name + ": " +
             (best ? "**" + best->design.label + "** (" + fixed(bestDe, 2) + " CIEDE2000; ψ " + fixed(best->psiDeg, 1) +
                         "°, L " + lText(*best) + " mm)"
                   : std::string("no design shows scene content there")) +
             "\n";
  }
  return t + "\n";
}

// Per design: the budget's largest step (what costs it most) and its first order.
std::string discussionText(const std::vector<DesignRun>& runs) {
  std::string t;
  for (const DesignRun& r : runs) {
    double prev = r.rungDe.front(), worst = -INFINITY;
    std::string step;
    for (size_t i = 1; i < kLadder.size(); ++i) {
      if (!std::isfinite(r.rungDe[i])) continue;
      if (r.rungDe[i] - prev > worst) worst = r.rungDe[i] - prev, step = kLadder[i];
      prev = r.rungDe[i];
    }
    t += "- **" + r.design.label + "**: ideal display " + fixed(r.rungDe.front(), 2) + ", full chain " +
         fixed(r.rungDe.back(), 2) + "; its largest step is " + step + " (" + signedFixed(worst, 2) + "). ψ " +
         fixed(r.psiDeg, 1) + "°, L " + lText(r) + " mm, depth range ±" + fixed(r.depthRangeMm, 1) + " mm.\n";
  }
  return t + "\nThe errors are against the reference exposed alike (fig11's common exposure), so a design that "
             "passes less light (a pinhole sheet's open area, walls that stop the rays a lenslet takes from beyond "
             "its cell) shows it as error: the budget's + apertures and + barriers steps are mostly that light. The "
             "barrier walls stand in the lenslets' paths wherever the camera sees a lenslet from farther off its "
             "axis than its cell allows (the display's outer columns and rows at 350 mm), which the EIs, toed-in for "
             "a far viewer to stay on their cells, cannot avoid. The curved MLA aims its lenslets by its shape (their "
             "axes meet 2 m in front), and over a flat panel its gap grows toward the left and right edges (1.4 mm "
             "more at the outer columns): those columns' images move nearer the display, so its first order holds "
             "for the centre only. Its lenslets sit on the EI pitch (0.9875 mm, as the double MLA's), not on "
             "the prototype's 1.0 mm, so part of its lead over the prototype is that match, not the curvature. The "
             "designs differ in pitch too (the compound array "
             "has 1.58 mm lenslets, 96 x 41 of them), which sets the lateral sampling at every depth.\n\n";
}

Plot depthPlot(const std::vector<DesignRun>& runs) {
  Plot p;
  p.title = "Error against depth at 0° (dashed: L of the same colour)";
  p.x.title = "scene depth z (mm, display frame; > 0 toward the viewer)";
  p.y.title = "mean CIEDE2000 against the reference";
  for (size_t i = 0; i < runs.size(); ++i) {
    PlotSeries s{runs[i].design.label, {}, {}};
    s.color = plotPalette(int(i));
    for (const DepthBin& b : runs[i].bins) s.x.push_back(b.zCentre), s.y.push_back(b.de2000Mean);
    p.series.push_back(s);
    if (runs[i].lMm && std::abs(*runs[i].lMm) < 80.0) p.markers.push_back({*runs[i].lMm, "", plotPalette(int(i)), 5.0});
  }
  p.markers.push_back({0.0, "MLA", Vec3(0.0f), 0.0});
  p.y.min = 0.0;
  return p;
}

// Each design's own fig11 pictures kept beside the report (flat names: the report's folder).
void keepPictures(ReportWriter& w, const fs::path& scratch, const DesignRun& r) {
  for (const char* what : {"contact_sheet", "budget", "depth_error"}) {
    const fs::path from = scratch / r.design.stem / (std::string(what) + ".png");
    if (fs::exists(from)) fs::copy_file(from, w.file(std::string(what) + "_" + r.design.stem + ".png"),
                                        fs::copy_options::overwrite_existing);
  }
}

}  // namespace

StudyReport runArchitectures(const StudyOptions& o) {
  if (!o.displayPath.empty())
    throw InputError("", "display", "\"" + o.displayPath + "\"",
                     "no --display: the study compares the catalogue's designs (optics/displays)");
  ReportWriter w("architectures", o, "display architectures compared on the default scene");
  const fs::path scratch = fs::path(o.outDir) / ".architectures-runs";
  std::vector<DesignRun> runs;
  for (const Design& d : designs()) runs.push_back(runDesign(o, d, scratch));
  for (const DesignRun& r : runs) keepPictures(w, scratch, r);
  std::error_code ec;
  fs::remove_all(scratch, ec);

  std::vector<StudyValue> values;
  for (const DesignRun& r : runs)
    values.push_back(bound(r.design.label + ": ideal display - full chain, at 0°", r.rungDe.front() - r.rungDe.back(),
                           r.floorDe, false));
  w.section("What", "Which of the catalogue's display architectures (optics/displays, all on the Xperia 1 II panel "
                    "with 25 or 40 px EIs) reconstructs the default scene best, where in depth, and why: each seen as "
                    "in Fig. 11 (inim fig11 with its error budget), its EIA from each pixel's chief ray traced through "
                    "the display's stack (the pinhole rays for today's single MLA).");
  w.section("Prediction", "First order (docs/formats.md §3.6a; through the panel's cover glass): the viewing angle "
                          "ψ = 2 atan(P / 2 g_eff), the reference image plane L = g_eff f / (g_eff - f) and the depth "
                          "range |z| <= 2 g (lateral sampling within 2 P). A wider ψ (a short g) serves the side "
                          "poses, a real L near the scene serves the depths around it, and layers that absorb "
                          "(pinholes, walls) cost light and add their own budget rung.");
  w.section("Method", std::string("inim fig11 --budget with the ladder up to the full chain (ideal display, + "
                                  "subpixels, + real MLA, the stack's + apertures and + barriers where it has them, + "
                                  "cover glass, + colour chain) at ") +
                          (o.quick ? "128 px, the 0° pose only" : "648 px, the five poses") +
                          "; the error against depth at 0°; each depth band's pixel-weighted mean error.");
  w.text("## First order and error\n\n" + firstOrderTable(runs) + "## Error budget at 0° (mean CIEDE2000)\n\n" +
         budgetTable(runs));
  std::string suits;
  const std::string bands = bandTable(runs, suits);
  w.text("## Error by scene depth at 0° (mean CIEDE2000)\n\n" + bands + "Which suits which scene depth:\n\n" + suits +
         "\n![error against depth](depth.png)\n\n");
  w.plot("depth.png", depthPlot(runs));
  std::vector<std::vector<std::string>> rows;
  for (const DesignRun& r : runs)
    for (const DepthBin& b : r.bins)
      rows.push_back({r.design.stem, fixed(b.zCentre, 3), std::to_string(b.pixels), fixedOrDash(b.de2000Mean, 4)});
  w.csv("depth.csv", {"design", "z_centre_mm", "pixels", "de2000_mean"}, rows);
  w.section("Discussion", "\n\n" + discussionText(runs));
  std::string sheets = "## Contact sheets and budgets\n\n";
  for (const DesignRun& r : runs)
    sheets += "### " + r.design.label + " (`optics/displays/" + r.design.stem + ".json`)\n\n![contact sheet](contact_sheet_" +
              r.design.stem + ".png)\n\n![budget](budget_" + r.design.stem + ".png)\n\n";
  w.text(sheets);
  w.text("**Result.**\n\n" + boundsTable(values) + "\n");
  w.verdict("for every design, the ideal display is no worse than the full chain beyond the noise floor (ideal - "
            "full <= floor, mean CIEDE2000 at 0°)",
            values);
  StudyReport report = makeReport("architectures", values);
  report.files = w.commit();
  return report;
}

}  // namespace inim
