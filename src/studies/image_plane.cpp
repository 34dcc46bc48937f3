// inim study image-plane: the lenslets image the panel at the reference image plane
// L = g f / (g - f) in front of the viewer-side principal plane H' (docs/design.md). Method: a panel point under the centre lenslet traced
// forward through the real lenslet; the plane where the bundle's RMS radius is smallest. The
// lens-law checks leave the panel's cover glass out (the point emits in air at z = -g); the
// display as configured is checked too, the point emitting under the cover glass, against
// H' + L_eff with the optical gap g_eff = g - t (1 - 1/n).
#include <cmath>

#include "analysis/plot.h"
#include "camera/lens_system.h"
#include "display/cover_glass.h"
#include "display/display.h"
#include "display/ei_layout.h"
#include "mla_optics/real_mla.h"
#include "studies/studies.h"
#include "studies/study_display.h"
#include "studies/study_report.h"

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


double degrees(double rad) { return rad * 180.0 / M_PI; }

// The display, the lenslet's prediction at g = 4 mm in air and under the cover glass.
struct PlaneSetup {
  StudyDisplay source;
  EiLayout L;
  double f = 0, P = 0, g0 = 4.0;
  double hPrime = 0;      // H': the viewer-side principal plane
  double Lpred = 0;       // H' + g f / (g - f) at g0
  CoverGlassOptics glass;
  double gEff = 0, LpredGlass = 0;  // the optical gap at g0 and H' + g_eff f / (g_eff - f)
  double fullDeg = 0, fullDegGlass = 0;  // the full aperture seen from the point, in air and through the glass
};

// The full aperture seen from a panel point at gap g: the lens rim at P / 2 (paraxially).
double fullApertureDeg(double P, double g) { return degrees(std::atan(P / (2.0 * g))); }

PlaneSetup setUp(const StudyOptions& o) {
  PlaneSetup setup;
  setup.source = loadStudyDisplay(o);
  const Display& d = setup.source.display;
  setup.L = computeLayout(d);
  setup.f = lensletFocus(d.mla).focalLengthMm, setup.P = d.mla.pitchMm;
  setup.hPrime = RealMla::fromDisplay(d, setup.L, setup.g0)->rearNodalZ();
  setup.Lpred = setup.hPrime + setup.g0 * setup.f / (setup.g0 - setup.f);
  setup.glass = coverGlassOptics(d, float(kLambdaNm));
  setup.gEff = setup.glass.opticalGap(setup.g0);
  setup.LpredGlass = setup.hPrime + setup.gEff * setup.f / (setup.gEff - setup.f);
  setup.fullDeg = fullApertureDeg(setup.P, setup.g0);
  setup.fullDegGlass = fullApertureDeg(setup.P, setup.gEff);  // the rim seen through the glass, in air
  return setup;
}

// At g = 4 mm: the bundles' sharpest planes and their RMS radius (um) against z, paraxial and
// full aperture, in air and under the cover glass.
struct PlaneAtGap {
  double zParax = 0, zFull = 0, zParaxGlass = 0, zFullGlass = 0;
  std::vector<double> z, rParax, rFull, rParaxGlass, rFullGlass;
};

PlaneAtGap measureAtGap(const PlaneSetup& setup) {
  const auto mla = RealMla::fromDisplay(setup.source.display, setup.L, setup.g0);
  const Bundle parax = traceBundle(*mla, setup.L, setup.g0, 1.0), full = traceBundle(*mla, setup.L, setup.g0, setup.fullDeg);
  const Bundle paraxG = traceBundle(*mla, setup.L, setup.g0, 1.0, &setup.glass);
  const Bundle fullG = traceBundle(*mla, setup.L, setup.g0, setup.fullDegGlass, &setup.glass);
  PlaneAtGap m;
  m.zParax = sharpestPlane(parax), m.zFull = sharpestPlane(full);
  m.zParaxGlass = sharpestPlane(paraxG), m.zFullGlass = sharpestPlane(fullG);
  for (int i = 0; i <= 350; ++i) {
    const double z = 5.0 + 0.1 * i;
    m.z.push_back(z);
    m.rParax.push_back(rmsRadiusAt(parax, z) * 1000.0);
    m.rFull.push_back(rmsRadiusAt(full, z) * 1000.0);
    m.rParaxGlass.push_back(rmsRadiusAt(paraxG, z) * 1000.0);
    m.rFullGlass.push_back(rmsRadiusAt(fullG, z) * 1000.0);
  }
  return m;
}

// The sharpest plane against the gap, the MLA rebuilt at each gap (in air).
struct GapSweep {
  std::vector<double> gaps = {3.5, 3.75, 4.0, 4.5, 5.0};
  std::vector<double> predicted, paraxial, full;
};

GapSweep sweepGap(const PlaneSetup& setup) {
  GapSweep w;
  for (double g : w.gaps) {
    const auto mla = RealMla::fromDisplay(setup.source.display, setup.L, g);
    w.predicted.push_back(mla->rearNodalZ() + g * setup.f / (g - setup.f));
    w.paraxial.push_back(sharpestPlane(traceBundle(*mla, setup.L, g, 1.0)));
    w.full.push_back(sharpestPlane(traceBundle(*mla, setup.L, g, fullApertureDeg(setup.P, g))));
  }
  return w;
}

std::vector<StudyValue> judge(const PlaneSetup& setup, const PlaneAtGap& m, const GapSweep& w) {
  std::vector<StudyValue> v;
  v.push_back(compare("sharpest plane at g = 4 mm, paraxial (1°)", m.zParax, setup.Lpred, 0.02));
  v.push_back(compare("sharpest plane at g = 4 mm, full aperture (" + fixed(setup.fullDeg, 2) + "°)", m.zFull, setup.Lpred, 0.25));
  for (size_t i = 0; i < w.gaps.size(); ++i)
    v.push_back(compare("paraxial sharpest plane at g = " + fixed(w.gaps[i], 2) + " mm", w.paraxial[i], w.predicted[i], 0.02));
  v.push_back(compare("sharpest plane at g = 4 mm under the cover glass, paraxial (1°)", m.zParaxGlass, setup.LpredGlass, 0.02));
  v.push_back(compare("sharpest plane at g = 4 mm under the cover glass, full aperture (" + fixed(setup.fullDegGlass, 2) + "°)",
                      m.zFullGlass, setup.LpredGlass, 0.25));
  return v;
}

PlotSeries curve(const std::string& name, const std::vector<double>& x, const std::vector<double>& y, double dash) {
  PlotSeries c{name, x, y};
  c.markers = false;
  c.dash = dash;
  return c;
}

void writeData(ReportWriter& w, const PlaneSetup& setup, const PlaneAtGap& m, const GapSweep& sweep) {
  std::vector<std::vector<std::string>> rows;
  for (size_t i = 0; i < m.z.size(); ++i)
    rows.push_back({csvNumber(m.z[i]), csvNumber(m.rParax[i]), csvNumber(m.rFull[i]), csvNumber(m.rParaxGlass[i]),
                    csvNumber(m.rFullGlass[i])});
  w.csv("rms_vs_z.csv",
        {"z_mm", "rms_radius_um_paraxial", "rms_radius_um_full_aperture", "rms_radius_um_paraxial_cover_glass",
         "rms_radius_um_full_aperture_cover_glass"},
        rows);
  Plot p;
  p.title = "Panel point through the real lenslet, g = 4 mm";
  p.x.title = "z (mm, from the panel-side principal plane)";
  p.y.title = "RMS radius (um)";
  p.y.log = true;
  p.y.min = 0.1, p.y.max = 1e5;
  p.series = {curve("paraxial 1 deg", m.z, m.rParax, 0.0), curve("full " + fixed(setup.fullDeg, 1) + " deg", m.z, m.rFull, 0.0),
              curve("paraxial 1 deg, cover glass", m.z, m.rParaxGlass, 8.0),
              curve("full " + fixed(setup.fullDegGlass, 1) + " deg, cover glass", m.z, m.rFullGlass, 8.0)};
  p.markers.push_back({setup.Lpred, "H'+L " + fixed(setup.Lpred, 2)});
  p.markers.push_back({setup.LpredGlass, "H'+L_eff " + fixed(setup.LpredGlass, 2)});
  w.plot("rms_vs_z.png", p);

  rows.clear();
  for (size_t i = 0; i < sweep.gaps.size(); ++i)
    rows.push_back({csvNumber(sweep.gaps[i]), csvNumber(sweep.predicted[i]), csvNumber(sweep.paraxial[i]),
                    csvNumber(sweep.full[i])});
  w.csv("plane_vs_gap.csv", {"gap_mm", "predicted_mm", "sharpest_paraxial_mm", "sharpest_full_aperture_mm"}, rows);
  Plot q;
  q.title = "Sharpest plane vs gap (real lenslet)";
  q.x.title = "gap g (mm)";
  q.y.title = "sharpest plane z (mm)";
  std::vector<double> gx, gy;
  for (int i = 0; i <= 80; ++i) {
    const double g = 3.45 + (5.05 - 3.45) * i / 80.0;
    gx.push_back(g);
    gy.push_back(setup.hPrime + g * setup.f / (g - setup.f));
  }
  PlotSeries paraxial{"traced, paraxial", sweep.gaps, sweep.paraxial};
  paraxial.line = false;
  PlotSeries full{"traced, full aperture", sweep.gaps, sweep.full};
  full.line = false;
  q.series = {curve("H' + g f / (g - f)", gx, gy, 0.0), paraxial, full};
  q.markers.push_back({setup.f, "f = " + fixed(setup.f, 3) + " mm"});
  w.plot("plane_vs_gap.png", q);
}

std::string predictionText(const PlaneSetup& setup) {
  return "Thick-lens imaging: g is measured from the panel-side principal plane H (z = 0), the image distance "
         "L = g f / (g − f) from the viewer-side one H' (z = T (n − 1)/n = " + fixed(setup.hPrime, 3) +
         " mm). Display `" + setup.source.path + "`: f = " + fixed(setup.f, 4) + " mm, so at g = 4 mm the sharpest plane is at "
         "H' + L = **" + fixed(setup.Lpred, 2) + " mm** for a panel point in air.\n\n"
         "*The panel's cover glass.* The lens-law checks (g = 4 mm, and the gap sweep) deliberately leave the panel's "
         "cover glass out: the point emits in air at z = −g, so that they test the lenslet alone. The display as "
         "configured has " +
         (setup.glass.present ? fixed(setup.glass.thicknessMm, 2) + " mm of " + setup.glass.material + " (n = " + fixed(setup.glass.n, 4) +
                                " at 587.56 nm)"
                          : std::string("no cover glass")) +
         " on the emitting plane, which the view simulation refracts every ray through (`PanelEmitter`); seen "
         "through it the point sits t (1 − 1/n) nearer, at the optical gap g_eff = " + fixed(setup.gEff, 4) +
         " mm, and the lenslet images it at H' + g_eff f / (g_eff − f) = **" + fixed(setup.LpredGlass, 2) +
         " mm** (g = 4 mm). That is checked separately: the same point emitting under the plate.";
}

std::string methodText(const PlaneSetup& setup) {
  return "(its verdict asserted by `Studies.ImagePlaneMatchesThickLensPrediction` in "
         "`tests/studies/test_studies.cpp`). A point on the panel (z = −g) under the centre lenslet "
         "emits 41 × 41 rays, uniform in the tangents of half-angles up to 1° (paraxial) or up to atan(P / 2g) (the full "
         "aperture); each is traced forward through the real lenslet at n_d (587.56 nm, Weighted Fresnel) and kept if "
         "it leaves through the centre lenslet's cap. The RMS radius of the bundle about its centroid is evaluated on "
         "planes of constant z; the sharpest plane is the minimum over z ∈ [5, 120] mm in 0.05 mm steps. The gap sweep "
         "rebuilds the MLA at each g. Under the cover glass (g = 4 mm only), each ray keeps its direction in air and "
         "crosses the plate from the point at the angle Snell's law gives (the angles of the bundle are those in air: "
         "up to 1° and up to atan(P / 2 g_eff) = " + fixed(setup.fullDegGlass, 2) +
         "°, the lens rim seen through the plate), leaving the plate's top at z = −g + t.";
}

std::vector<std::string> writeReport(const StudyOptions& o, const PlaneSetup& setup, const PlaneAtGap& m,
                                     const GapSweep& sweep, const std::vector<StudyValue>& values) {
  ReportWriter w("image-plane", o, "reference image plane");
  w.section("What",
            "Where a lenslet of the real (refracting) MLA images a panel point: the plane in front of the display where "
            "a reconstructed point is sharpest, and how it moves with the gap g.");
  w.section("Prediction", predictionText(setup));
  w.text("**Method** " + methodText(setup) + "\n\n");
  w.results(values, "mm");
  std::string t = "Full aperture against the gap (no tolerance: spherical aberration of a plano-convex lenslet pulls the "
                  "sharpest plane toward the MLA):\n\n| g (mm) | predicted (mm) | paraxial (mm) | full aperture (mm) |\n"
                  "|---|---|---|---|\n";
  for (size_t i = 0; i < sweep.gaps.size(); ++i)
    t += "| " + fixed(sweep.gaps[i], 2) + " | " + fixed(sweep.predicted[i], 2) + " | " + fixed(sweep.paraxial[i], 2) +
         " | " + fixed(sweep.full[i], 2) + " |\n";
  w.text(t);
  writeData(w, setup, m, sweep);
  w.text("\n![RMS radius vs z](rms_vs_z.png)\n\n![sharpest plane vs gap](plane_vs_gap.png)\n\n"
         "Data: `rms_vs_z.csv` (z_mm, RMS radius in µm, paraxial and full aperture), `plane_vs_gap.csv`.\n\n");
  w.text("Under the cover glass, the full aperture's sharpest plane is " + fixed(m.zFullGlass, 2) + " mm against " +
         fixed(m.zFull, 2) + " mm in air (paraxial " + fixed(m.zParaxGlass, 2) + " against " + fixed(m.zParax, 2) +
         " mm).\n\n");
  w.verdict("paraxial within ±2%, full aperture within ±25% of the prediction; H' + L in air, H' + L_eff under the "
            "cover glass",
            values);
  return w.commit();
}

}  // namespace

StudyReport runImagePlane(const StudyOptions& o) {
  const PlaneSetup setup = setUp(o);
  const PlaneAtGap m = measureAtGap(setup);
  const GapSweep sweep = sweepGap(setup);
  StudyReport rep = makeReport("image-plane", judge(setup, m, sweep));
  rep.files = writeReport(o, setup, m, sweep, rep.values);
  return rep;
}

}  // namespace inim
