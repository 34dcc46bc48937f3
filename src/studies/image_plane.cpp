// inim study image-plane: the lenslets image the panel at the reference image plane
// L = g f / (g - f) in front of the viewer-side principal plane H' (DESIGN.md 4b). Method of
// tests/mla/test_reference_image_plane.cpp: a panel point under the centre lenslet traced
// forward through the real lenslet; the plane where the bundle's RMS radius is smallest. The
// lens-law checks leave the panel's cover glass out (the point emits in air at z = -g); the
// display as configured is checked too, the point emitting under the cover glass, against
// H' + L_eff with the optical gap g_eff = g - t (1 - 1/n).
#include <cmath>
#include <filesystem>
#include <fstream>

#include "analysis/plot.h"
#include "core/error.h"
#include "core/output_file.h"
#include "display/display.h"
#include "display/ei_layout.h"
#include "mla/real_mla.h"
#include "camera/lens_system.h"
#include "studies/cover_glass.h"
#include "studies/studies.h"
#include "studies/study_common.h"

namespace fs = std::filesystem;

namespace inim {

namespace {

using namespace study_detail;

struct Bundle {
  std::vector<Point3d> p;
  std::vector<Vec3d> d;
};

constexpr double kLambdaNm = 587.56;

// 41 x 41 rays from the panel point below the centre lenslet, half-angles (in air) up to maxDeg
// in x and y, traced to the viewer at n_d; only the rays that leave through the centre lenslet's
// cap. With `glass`, the point emits under the cover glass (z from -g to -g + t): each ray crosses
// the plate at the angle that Snell's law gives for its air direction and leaves its top.
Bundle traceBundle(const RealMla& mla, const EiLayout& L, double g, double maxDeg,
                   const CoverGlassOptics* glass = nullptr) {
  const int k = L.eiCols / 2, l = L.eiRows / 2;
  const Point3d src(L.lensX[size_t(k)], L.lensY[size_t(l)], -g);
  Bundle b;
  const int n = 41;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const double tx = std::tan((2.0 * (i + 0.5) / n - 1.0) * maxDeg * M_PI / 180.0);
      const double ty = std::tan((2.0 * (j + 0.5) / n - 1.0) * maxDeg * M_PI / 180.0);
      const Vec3d d = glm::normalize(Vec3d(tx, ty, 1.0));
      Point3d o = src;
      if (glass && glass->present) {
        Vec3d dg;  // the direction inside the glass (air -> glass, reversed)
        if (!snellRefract(-d, Vec3d(0, 0, 1), 1.0, glass->n, dg)) continue;
        dg = -dg;
        o = src + dg * (glass->thicknessMm / dg.z);
      }
      MlaExit e;
      if (!mla.traceToViewer(o, d, kLambdaNm, nullptr, e) || e.capK != k || e.capL != l || !(e.d.z > 0.0)) continue;
      b.p.push_back(e.p);
      b.d.push_back(e.d);
    }
  return b;
}

double rmsRadiusAt(const Bundle& b, double z) {
  if (b.p.empty()) return std::nan("");
  double cx = 0, cy = 0;
  std::vector<glm::dvec2> q;
  q.reserve(b.p.size());
  for (size_t i = 0; i < b.p.size(); ++i) {
    const double t = (z - b.p[i].z) / b.d[i].z;
    q.push_back({b.p[i].x + t * b.d[i].x, b.p[i].y + t * b.d[i].y});
    cx += q.back().x, cy += q.back().y;
  }
  cx /= double(q.size()), cy /= double(q.size());
  double s = 0;
  for (auto& v : q) s += (v.x - cx) * (v.x - cx) + (v.y - cy) * (v.y - cy);
  return std::sqrt(s / double(q.size()));
}

// The plane of the smallest RMS radius, z in [5, 120] mm in 0.05 mm steps.
double sharpestPlane(const Bundle& b) {
  double best = std::nan(""), bestR = 1e30;
  for (int i = 0; i <= 2300; ++i) {
    const double z = 5.0 + 0.05 * i;
    const double r = rmsRadiusAt(b, z);
    if (r < bestR) bestR = r, best = z;
  }
  return best;
}

}  // namespace

StudyReport runImagePlane(const StudyOptions& o) {
  const std::string displayPath = displayPathOrDefault(o.displayPath);
  Display d = loadDisplay(displayPath);
  EiLayout L = computeLayout(d);
  const double f = lensletFocus(d.mla).focalLengthMm, P = d.mla.pitchMm;
  const double g0 = 4.0;
  auto realAt = [&](double g) {
    auto m = makeRealMla(d, L, g);
    std::unique_ptr<RealMla> r(dynamic_cast<RealMla*>(m.get()));
    if (!r) throw std::runtime_error("image-plane study: makeRealMla did not return a RealMla");
    m.release();
    return r;
  };
  auto fullDeg = [&](double g) { return std::atan(P / (2.0 * g)) * 180.0 / M_PI; };

  // 1. RMS radius against z at g = 4 mm.
  auto mla0 = realAt(g0);
  const double hPrime = mla0->rearNodalZ();
  const double Lpred = hPrime + g0 * f / (g0 - f);
  const Bundle parax = traceBundle(*mla0, L, g0, 1.0), full = traceBundle(*mla0, L, g0, fullDeg(g0));
  const double zParax = sharpestPlane(parax), zFull = sharpestPlane(full);
  // The display as configured: the same point under the panel's cover glass.
  const CoverGlassOptics glass = coverGlassOptics(d, float(kLambdaNm));
  const double gEff = glass.opticalGap(g0), LpredGlass = hPrime + gEff * f / (gEff - f);
  // The full aperture seen from the point through the glass: the lens rim at P/2 subtends
  // atan(P / 2 g_eff) in air (paraxially).
  const double fullDegGlass = std::atan(P / (2.0 * gEff)) * 180.0 / M_PI;
  const Bundle paraxG = traceBundle(*mla0, L, g0, 1.0, &glass), fullG = traceBundle(*mla0, L, g0, fullDegGlass, &glass);
  const double zParaxG = sharpestPlane(paraxG), zFullG = sharpestPlane(fullG);
  std::vector<double> zs, rParax, rFull, rParaxG, rFullG;
  for (int i = 0; i <= 350; ++i) {
    const double z = 5.0 + 0.1 * i;
    zs.push_back(z);
    rParax.push_back(rmsRadiusAt(parax, z) * 1000.0);
    rFull.push_back(rmsRadiusAt(full, z) * 1000.0);
    rParaxG.push_back(rmsRadiusAt(paraxG, z) * 1000.0);
    rFullG.push_back(rmsRadiusAt(fullG, z) * 1000.0);
  }

  // 2. Sharpest plane against the gap.
  const std::vector<double> gaps = {3.5, 3.75, 4.0, 4.5, 5.0};
  std::vector<double> gPred, gParax, gFull;
  for (double g : gaps) {
    auto m = realAt(g);
    gPred.push_back(m->rearNodalZ() + g * f / (g - f));
    gParax.push_back(sharpestPlane(traceBundle(*m, L, g, 1.0)));
    gFull.push_back(sharpestPlane(traceBundle(*m, L, g, fullDeg(g))));
  }

  StudyReport rep;
  rep.study = "image-plane";
  rep.values.push_back(compare("sharpest plane at g = 4 mm, paraxial (1°)", zParax, Lpred, 0.02));
  rep.values.push_back(compare("sharpest plane at g = 4 mm, full aperture (" + fmt(fullDeg(g0), 2) + "°)", zFull, Lpred, 0.25));
  for (size_t i = 0; i < gaps.size(); ++i)
    rep.values.push_back(compare("paraxial sharpest plane at g = " + fmt(gaps[i], 2) + " mm", gParax[i], gPred[i], 0.02));
  rep.values.push_back(compare("sharpest plane at g = 4 mm under the cover glass, paraxial (1°)", zParaxG, LpredGlass, 0.02));
  rep.values.push_back(compare("sharpest plane at g = 4 mm under the cover glass, full aperture (" + fmt(fullDegGlass, 2) + "°)",
                               zFullG, LpredGlass, 0.25));
  rep.pass = allPass(rep.values);

  OutputSet out;
  const fs::path dir(o.outDir);
  const std::string mdPath = (dir / "report.md").string();
  const std::string csv1 = (dir / "rms_vs_z.csv").string(), png1 = (dir / "rms_vs_z.png").string();
  const std::string csv2 = (dir / "plane_vs_gap.csv").string(), png2 = (dir / "plane_vs_gap.png").string();
  {
    std::vector<std::vector<std::string>> rows;
    for (size_t i = 0; i < zs.size(); ++i)
      rows.push_back({csvNumber(zs[i]), csvNumber(rParax[i]), csvNumber(rFull[i]), csvNumber(rParaxG[i]),
                      csvNumber(rFullG[i])});
    writeCsv(out.add(csv1),
             {"z_mm", "rms_radius_um_paraxial", "rms_radius_um_full_aperture", "rms_radius_um_paraxial_cover_glass",
              "rms_radius_um_full_aperture_cover_glass"},
             rows);
    rows.clear();
    for (size_t i = 0; i < gaps.size(); ++i)
      rows.push_back({csvNumber(gaps[i]), csvNumber(gPred[i]), csvNumber(gParax[i]), csvNumber(gFull[i])});
    writeCsv(out.add(csv2), {"gap_mm", "predicted_mm", "sharpest_paraxial_mm", "sharpest_full_aperture_mm"}, rows);
  }
  {
    Plot p;
    p.title = "Panel point through the real lenslet, g = 4 mm";
    p.x.title = "z (mm, from the panel-side principal plane)";
    p.y.title = "RMS radius (um)";
    p.y.log = true;
    p.y.min = 0.1, p.y.max = 1e5;
    PlotSeries a{"paraxial 1 deg", zs, rParax};
    a.markers = false;
    PlotSeries b{"full " + fmt(fullDeg(g0), 1) + " deg", zs, rFull};
    b.markers = false;
    PlotSeries ag{"paraxial 1 deg, cover glass", zs, rParaxG};
    ag.markers = false;
    ag.dash = 8.0;
    PlotSeries bg{"full " + fmt(fullDegGlass, 1) + " deg, cover glass", zs, rFullG};
    bg.markers = false;
    bg.dash = 8.0;
    p.series = {a, b, ag, bg};
    p.markers.push_back({Lpred, "H'+L " + fmt(Lpred, 2)});
    p.markers.push_back({LpredGlass, "H'+L_eff " + fmt(LpredGlass, 2)});
    writePlot(p, out.add(png1));
  }
  {
    Plot p;
    p.title = "Sharpest plane vs gap (real lenslet)";
    p.x.title = "gap g (mm)";
    p.y.title = "sharpest plane z (mm)";
    std::vector<double> gx, gy;
    for (int i = 0; i <= 80; ++i) {
      const double g = 3.45 + (5.05 - 3.45) * i / 80.0;
      gx.push_back(g);
      gy.push_back(hPrime + g * f / (g - f));
    }
    PlotSeries pred{"H' + g f / (g - f)", gx, gy};
    pred.markers = false;
    PlotSeries a{"traced, paraxial", gaps, gParax};
    a.line = false;
    PlotSeries b{"traced, full aperture", gaps, gFull};
    b.line = false;
    p.series = {pred, a, b};
    p.markers.push_back({f, "f = " + fmt(f, 3) + " mm"});
    writePlot(p, out.add(png2));
  }

  std::string md;
  md += "# Study: reference image plane\n\n";
  md += "**What.** Where a lenslet of the real (refracting) MLA images a panel point: the plane in front of the "
        "display where a reconstructed point is sharpest, and how it moves with the gap g.\n\n";
  md += "**Prediction.** Thick-lens imaging: g is measured from the panel-side principal plane H (z = 0), the image "
        "distance L = g f / (g − f) from the viewer-side one H' (z = T (n − 1)/n = " + fmt(hPrime, 3) +
        " mm). Display `" + displayPath + "`: f = " + fmt(f, 4) + " mm, so at g = 4 mm the sharpest plane is at "
        "H' + L = **" + fmt(Lpred, 2) + " mm** for a panel point in air.\n\n"
        "*The panel's cover glass.* The lens-law checks (g = 4 mm, and the gap sweep) deliberately leave the panel's "
        "cover glass out: the point emits in air at z = −g, so that they test the lenslet alone. The display as "
        "configured has " + (glass.present ? fmt(glass.thicknessMm, 2) + " mm of " + glass.material + " (n = " +
        fmt(glass.n, 4) + " at 587.56 nm)" : std::string("no cover glass")) + " on the emitting plane, which the "
        "view simulation refracts every ray through (`PanelEmitter`); seen through it the point sits "
        "t (1 − 1/n) nearer, at the optical gap g_eff = " + fmt(gEff, 4) + " mm, and the lenslet images it at "
        "H' + g_eff f / (g_eff − f) = **" + fmt(LpredGlass, 2) + " mm** (g = 4 mm). That is checked separately: the "
        "same point emitting under the plate.\n\n";
  md += "**Method** (that of `tests/mla/test_reference_image_plane.cpp`). A point on the panel (z = −g) under the "
        "centre lenslet emits 41 × 41 rays, uniform in the tangents of half-angles up to 1° (paraxial) or up to "
        "atan(P / 2g) (the full aperture); each is traced forward through the real lenslet at n_d (587.56 nm, "
        "Weighted Fresnel) and kept if it leaves through the centre lenslet's cap. The RMS radius of the bundle about "
        "its centroid is evaluated on planes of constant z; the sharpest plane is the minimum over z ∈ [5, 120] mm "
        "in 0.05 mm steps. The gap sweep rebuilds the MLA at each g. Under the cover glass (g = 4 mm only), each ray "
        "keeps its direction in air and crosses the plate from the point at the angle Snell's law gives (the "
        "angles of the bundle are those in air: up to 1° and up to atan(P / 2 g_eff) = " + fmt(fullDegGlass, 2) +
        "°, the lens rim seen through the plate), leaving the plate's top at z = −g + t.\n\n";
  md += "**Result.**\n\n" + valuesTable(rep.values, "mm") + "\n";
  md += "Full aperture against the gap (no tolerance: spherical aberration of a plano-convex lenslet pulls the "
        "sharpest plane toward the MLA):\n\n| g (mm) | predicted (mm) | paraxial (mm) | full aperture (mm) |\n"
        "|---|---|---|---|\n";
  for (size_t i = 0; i < gaps.size(); ++i)
    md += "| " + fmt(gaps[i], 2) + " | " + fmt(gPred[i], 2) + " | " + fmt(gParax[i], 2) + " | " + fmt(gFull[i], 2) + " |\n";
  md += "\n![RMS radius vs z](rms_vs_z.png)\n\n![sharpest plane vs gap](plane_vs_gap.png)\n\n";
  md += "Data: `rms_vs_z.csv` (z_mm, RMS radius in µm, paraxial and full aperture), `plane_vs_gap.csv`.\n\n";
  md += "Under the cover glass, the full aperture's sharpest plane is " + fmt(zFullG, 2) + " mm against " +
        fmt(zFull, 2) + " mm in air (paraxial " + fmt(zParaxG, 2) + " against " + fmt(zParax, 2) + " mm).\n\n";
  md += "**Verdict** (paraxial within ±2%, full aperture within ±25% of the prediction; H' + L in air, "
        "H' + L_eff under the cover glass): " + verdictLine(rep.values) +
        "\n\n";
  md += "**Reproduce.**\n\n```\n" + reproduceCommand(rep.study, o) + "\n```\n";
  {
    std::ofstream fo(out.add(mdPath));
    fo << md;
    if (!fo) throw std::runtime_error("cannot write " + mdPath);
  }
  out.commit();
  rep.files = {mdPath, png1, csv1, png2, csv2};
  return rep;
}

}  // namespace inim
