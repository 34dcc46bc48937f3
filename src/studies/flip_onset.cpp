// inim study flip-onset: turning the display, the view through a lenslet flips to the
// neighbouring elemental image at half the viewing angle, psi / 2 = atan(P / (2 g))
// (DESIGN.md 4b). Method of tests/view/test_flip_onset.cpp, swept over 0-12 degrees.
#include <cmath>
#include <filesystem>
#include <fstream>

#include "analysis/plot.h"
#include "core/error.h"
#include "core/output_file.h"
#include "core/rng.h"
#include "display/display.h"
#include "display/ei_layout.h"
#include "mla/real_mla.h"
#include "studies/studies.h"
#include "studies/study_common.h"
#include "view/ideal_mla.h"

namespace fs = std::filesystem;

namespace inim {

namespace {

using namespace study_detail;

// Fraction of the light that a parallel bundle at angle thetaDeg (x-z plane, from the +x side)
// through lenslet (k, l) delivers into that lenslet's own EI (48 x 48 rays over the cell).
double ownEiFraction(const MlaModel& mla, const EiLayout& L, double pitch, int k, int l, double thetaDeg) {
  const double th = thetaDeg * M_PI / 180.0;
  const Vec3 d(float(-std::sin(th)), 0.0f, float(-std::cos(th)));
  const double cx = L.lensX[size_t(k)], cy = L.lensY[size_t(l)];
  const double eiX = L.eiCentreX(k), halfEi = 0.5 * L.eiW * L.pixelMm;
  const int n = 48;
  double own = 0.0, all = 0.0;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const Point3 target(float(cx + ((i + 0.5) / n - 0.5) * pitch), float(cy + ((j + 0.5) / n - 0.5) * pitch), 0.0f);
      const float s = (mla.frontZ() + 1.0f) / std::abs(d.z);
      Ray r{target - s * d, d};
      Rng rng = Rng::forSample(3, uint64_t(j) * n + i);
      PanelArrival a;
      if (!mla.traceToPanel(r, 550.0f, rng, a)) continue;
      all += a.throughput;
      if (std::abs(a.p.x - eiX) <= halfEi) own += a.throughput;
    }
  return all > 0.0 ? own / all : 0.0;
}

// The first 50% crossing (downward) of the curve, linearly interpolated; NaN if none.
double halfCrossing(const std::vector<double>& x, const std::vector<double>& y) {
  for (size_t i = 1; i < y.size(); ++i)
    if (y[i - 1] >= 0.5 && y[i] < 0.5) return x[i - 1] + (y[i - 1] - 0.5) / (y[i - 1] - y[i]) * (x[i] - x[i - 1]);
  return std::nan("");
}

}  // namespace

StudyReport runFlipOnset(const StudyOptions& o) {
  const std::string displayPath = o.displayPath.empty() ? defaultDisplayPath() : o.displayPath;
  Display d = loadDisplay(displayPath);
  EiLayout L = computeLayout(d);
  const double g = d.reconstructionGapMm, P = d.mla.pitchMm, f = lensletFocus(d.mla).focalLengthMm;
  const double predicted = std::atan(P / (2.0 * g)) * 180.0 / M_PI;  // psi / 2

  IdealLensletMla ideal(L, P, f, g);
  auto real = makeRealMla(d, L, g);
  const int k = L.eiCols / 2, l = L.eiRows / 2;
  std::vector<double> angle, fIdeal, fReal;
  for (int i = 0; i <= 120; ++i) {
    const double t = 0.1 * i;
    angle.push_back(t);
    fIdeal.push_back(ownEiFraction(ideal, L, P, k, l, t));
    fReal.push_back(ownEiFraction(*real, L, P, k, l, t));
  }
  const double idealFlip = halfCrossing(angle, fIdeal), realFlip = halfCrossing(angle, fReal);

  StudyReport rep;
  rep.study = "flip-onset";
  rep.values = {compare("flip angle, ideal MLA", idealFlip, predicted, 0.10),
                compare("flip angle, real MLA", realFlip, predicted, 0.10)};
  rep.pass = allPass(rep.values);

  OutputSet out;
  const fs::path dir(o.outDir);
  const std::string csvPath = (dir / "flip_onset.csv").string(), pngPath = (dir / "flip_onset.png").string(),
                    mdPath = (dir / "report.md").string();
  std::vector<std::vector<std::string>> rows;
  for (size_t i = 0; i < angle.size(); ++i) rows.push_back({csvNumber(angle[i]), csvNumber(fIdeal[i]), csvNumber(fReal[i])});
  writeCsv(out.add(csvPath), {"angle_deg", "own_ei_fraction_ideal", "own_ei_fraction_real"}, rows);

  Plot plot;
  plot.title = "Flip onset, g = " + fmt(g, 2) + " mm";
  plot.x.title = "viewing angle (deg)";
  plot.y.title = "own-EI fraction";
  plot.x.min = 0.0, plot.x.max = 12.0, plot.y.min = 0.0, plot.y.max = 1.3;
  PlotSeries si{"ideal MLA", angle, fIdeal};
  si.markers = false;
  PlotSeries sr{"real MLA", angle, fReal};
  sr.markers = false;
  sr.dash = 8.0;
  plot.series = {si, sr};
  plot.markers.push_back({predicted, "psi/2"});
  plot.hMarkers.push_back({0.5, "50%", Vec3(0.4f, 0.4f, 0.4f), 4.0});
  writePlot(plot, out.add(pngPath));

  std::string md;
  md += "# Study: flip onset\n\n";
  md += "**What.** Turning the display, the view through a lenslet stops showing the lenslet's own elemental "
        "image (EI) and flips to the neighbouring one. This study measures the angle where that happens, for the "
        "ideal (thin, paraxial) and the real (refracting " + (d.mla.material.empty() ? std::string("PMMA") : d.mla.material) +
        ") lenslet array, at the reconstruction gap.\n\n";
  md += "**Prediction.** The flip happens at half the viewing angle, ψ/2 = atan(P / 2g) (DESIGN.md 4b). Display `" +
        displayPath + "`: P = " + fmt(P, 4) + " mm, g = " + fmt(g, 4) + " mm, f = " + fmt(f, 4) +
        " mm, so ψ/2 = **" + fmt(predicted, 3) + "°**.\n\n";
  md += "**Method** (that of `tests/view/test_flip_onset.cpp`). For each viewing angle θ from 0° to 12° in 0.1° "
        "steps, a parallel bundle of 48 × 48 rays, coming from the +x side at θ in the x-z plane, fills the centre "
        "lenslet (" + std::to_string(k) + ", " + std::to_string(l) + ") and is traced backward to the panel at 550 nm "
        "(`MlaModel::traceToPanel`; the real MLA with stochastic Fresnel, fixed seed). The own-EI fraction is the "
        "throughput landing within the lenslet's own EI column over the throughput reaching the panel. The flip angle "
        "is the first downward 50% crossing, interpolated linearly between the 0.1° samples.\n\n";
  md += "**Result.**\n\n" + valuesTable(rep.values, "deg") + "\n";
  md += "![own-EI fraction vs angle](flip_onset.png)\n\nData: `flip_onset.csv` (angle_deg, own_ei_fraction_ideal, "
        "own_ei_fraction_real).\n\n";
  md += "**Verdict** (tolerance ±10% of ψ/2): " + verdictLine(rep.values) +
        "\n\n";
  md += "**Reproduce.**\n\n```\n" + reproduceCommand(rep.study, o) + "\n```\n";
  {
    std::ofstream f(out.add(mdPath));
    f << md;
    if (!f) throw std::runtime_error("cannot write " + mdPath);
  }
  out.commit();
  rep.files = {mdPath, pngPath, csvPath};
  return rep;
}

}  // namespace inim
