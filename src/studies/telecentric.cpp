// inim study telecentric: the size of a reconstructed object seen from a finite distance D,
// EI layout parallel (the paper's) against toed-in (docs/design.md). EIA synthesised
// from the scene (synthesis/), seen through the panel's cover glass and the real MLA by a camera
// at D (view/); the same with the cover glass switched off as the control.
#include <algorithm>
#include <cmath>

#include "analysis/plot.h"
#include "camera/camera_config.h"
#include "display/cover_glass.h"
#include "studies/studies.h"
#include "studies/study_display.h"
#include "studies/study_pipeline.h"
#include "studies/study_report.h"
#include "display_view/display_model.h"
#include "display_view/view_renderer.h"

namespace inim {

namespace {

using namespace study_detail;

constexpr double kBarW = 24.0, kBarH = 12.0, kTiltDeg = 5.0;

// Mean horizontal chord of the bright bar over the rows with |y| < 3.5 mm on the plane z (each
// row: the outermost 50% crossings, half of the bar's median plateau), times cos(tilt): the
// bar's width. The tilt makes the rows cross the lenslet columns at different phases, so the
// facets' misalignment averages out instead of biasing every row alike.
double barWidth(const Image& img, const CameraModel& cam, double z) {
  double sum = 0.0;
  int n = 0;
  std::vector<double> X(size_t(img.width)), v(size_t(img.width));
  for (int y = 0; y < img.height; ++y) {
    for (int x = 0; x < img.width; ++x) {
      X[size_t(x)] = pixelOnPlane(cam, x, y, z).x;
      v[size_t(x)] = lum(img, x, y);
    }
    if (std::abs(pixelOnPlane(cam, img.width / 2, y, z).y) > 3.5) continue;
    std::vector<double> inner;
    for (int x = 0; x < img.width; ++x)
      if (std::abs(X[size_t(x)]) < 0.3 * kBarW) inner.push_back(v[size_t(x)]);
    if (inner.empty()) continue;
    std::nth_element(inner.begin(), inner.begin() + long(inner.size() / 2), inner.end());
    const double thr = 0.5 * inner[inner.size() / 2];
    if (!(thr > 0.0)) continue;
    double xl = std::nan(""), xr = std::nan("");
    for (int x = 1; x < img.width; ++x)
      if (v[size_t(x - 1)] < thr && v[size_t(x)] >= thr) {
        const double t = (thr - v[size_t(x - 1)]) / (v[size_t(x)] - v[size_t(x - 1)]);
        xl = X[size_t(x - 1)] + t * (X[size_t(x)] - X[size_t(x - 1)]);
        break;
      }
    for (int x = img.width - 1; x > 0; --x)
      if (v[size_t(x)] < thr && v[size_t(x - 1)] >= thr) {
        const double t = (v[size_t(x - 1)] - thr) / (v[size_t(x - 1)] - v[size_t(x)]);
        xr = X[size_t(x - 1)] + t * (X[size_t(x)] - X[size_t(x - 1)]);
        break;
      }
    if (std::isfinite(xl) && std::isfinite(xr)) sum += xr - xl, ++n;
  }
  return n ? sum / n * std::cos(kTiltDeg * M_PI / 180.0) : std::nan("");
}

// Quadrature strata per camera pixel (ViewSettings::spp; the estimator and its aperture grid
// are ViewSettings' defaults). The estimator has no noise: these counts keep the widths
// converged.
constexpr int kStrataFull = 4, kStrataQuick = 4;

// The display's geometry, the predictions, the bar and the sampling.
struct TeleSetup {
  StudyDisplay source;
  double g = 4.0, D = 350.0;
  double P = 0, f = 0;
  double pEi = 0, r = 0;  // the parallel layout's EI pitch and its ratio to the lens pitch
  double pixel = 0, Lref = 0;
  CoverGlassOptics glass;  // at 550 nm: the lenslets see the panel at the optical gap g_eff
  double gEff = 0;
  double flipX = 0;  // lens position beyond which the parallel layout flips (with the glass)
  std::vector<double> zs;
  int W = 0, H = 0;
  double sample = 0;  // mm per camera pixel on the bar's plane
  CameraDescription camDesc;
  Json scene;
  ViewSettings view;

  // Per optical gap ge (g_eff with the glass, g without): the facets line up for the target
  // depth z0 = g f / (ge - f), and a panel pixel is imaged on Le = ge f / (ge - f).
  double zLine(double ge) const { return g * f / (ge - f); }
  double imagePlane(double ge) const { return ge * f / (ge - f); }
  // Perceived size relative to the true size (the report's derivation): parallel layout, and
  // toed-in (1 without glass).
  double sizeParallel(double z, double ge) const { return (1.0 - z / D) / (r - (1.0 - r) * z / g - (ge / g) * z / D); }
  double sizeToedIn(double z, double ge) const { return (1.0 - z / D) / (1.0 - (ge / g) * z / D); }
  double depthParallel(double z, double ge) const {
    return std::abs(z) < 1e-12 ? 0.0 : (ge / g) / (r / z - (1.0 - r) / g);
  }
  // Display resolution at depth z: a facet's defocus P |z - z0| / z0 plus a panel pixel imaged
  // on Le, p Le / ge (without glass P |z - L| / L + p L / g).
  double resolution(double z, double ge) const {
    return P * std::abs(z - zLine(ge)) / zLine(ge) + pixel * imagePlane(ge) / ge;
  }
};

TeleSetup setUp(const StudyOptions& o) {
  TeleSetup setup;
  setup.source = loadStudyDisplay(o);
  const Display& base = setup.source.display;
  setup.P = base.mla.pitchMm, setup.f = lensletFocus(base.mla).focalLengthMm;
  setup.pixel = base.panel.pixelPitchMm;
  setup.pEi = base.eiWidthPx * setup.pixel, setup.r = setup.pEi / setup.P;
  setup.Lref = setup.g * setup.f / (setup.g - setup.f);
  setup.glass = coverGlassOptics(base, 550.0f);
  setup.gEff = setup.glass.opticalGap(setup.g);
  setup.flipX = 0.5 * setup.pEi / (1.0 + setup.gEff / setup.D - setup.r);
  setup.zs = o.quick ? std::vector<double>{10, 19, 30} : std::vector<double>{-10, 0, 10, 19, 25, 30};
  setup.W = o.quick ? 170 : 340, setup.H = o.quick ? 50 : 100;
  setup.sample = o.quick ? 0.2 : 0.1;
  setup.camDesc = loadCameraDescription("alvium-1800-u-500c");
  setup.scene = litRectangleScene(kBarW, kBarH, Json(0.8), kTiltDeg);
  setup.view.spp = o.quick ? kStrataQuick : kStrataFull;
  setup.view.progress = false;
  setup.view.seed = 11;
  return setup;
}

// Widths [glass][layout] per depth: glass 0 = the display as configured (the panel's cover
// glass, as PanelEmitter models it), 1 = cover glass switched off (the control); layout
// 0 = parallel, 1 = toed-in.
struct TeleWidths {
  std::vector<double> w[2][2];
};

// One layout: the bar at each depth, seen with and without the cover glass.
void measureLayout(const TeleSetup& setup, EiLayoutKind kind, TeleWidths& widths) {
  const int li = kind == EiLayoutKind::Parallel ? 0 : 1;
  const Display d = pipelineDisplay(setup.source.display, 45, 25, setup.g, kind, setup.D);
  const EiLayout L = computeLayout(d);
  for (double z : setup.zs) {
    const Image eia = synthesizeAt(L, d, setup.scene, z, 1);
    const auto cam = axialThinLens(setup.D, z, setup.W, setup.H, setup.sample);
    for (int gi = 0; gi < 2; ++gi) {
      if (gi == 1 && !setup.glass.present) {  // nothing to switch off: the control is the run itself
        widths.w[1][li].push_back(widths.w[0][li].back());
        continue;
      }
      EmitterSettings es;
      es.coverGlass = gi == 0;
      const DisplayModel dm = makeDisplayModel(d, L, eia, "(synthesised)", MlaKind::Real, setup.g, es);
      const ViewResult v = renderView(*cam, setup.camDesc.sensor, *dm.mla, *dm.panel, dm.area, setup.view);
      widths.w[gi][li].push_back(barWidth(v.image, *cam, z));
    }
  }
}

TeleWidths measure(const TeleSetup& setup) {
  TeleWidths widths;
  for (EiLayoutKind kind : {EiLayoutKind::Parallel, EiLayoutKind::ToedIn}) measureLayout(setup, kind, widths);
  return widths;
}

// The optical gap of each glass case: g_eff with the glass, g without.
double opticalGapOf(const TeleSetup& setup, int gi) { return gi == 0 ? setup.gEff : setup.g; }

std::vector<StudyValue> judge(const TeleSetup& setup, const TeleWidths& m) {
  std::vector<StudyValue> v;
  for (int gi = 0; gi < 2; ++gi) {
    const double ge = opticalGapOf(setup, gi);
    const std::string sfx = gi == 0 ? "" : ", no cover glass";
    for (size_t i = 0; i < setup.zs.size(); ++i) {
      const double z = setup.zs[i], toed = kBarW * setup.sizeToedIn(z, ge), parallel = kBarW * setup.sizeParallel(z, ge);
      v.push_back(compare("width, toed-in, z = " + fixed(z, 0) + " mm" + sfx, m.w[gi][1][i], toed,
                          setup.resolution(z, ge) / toed));
      v.push_back(compare("width, parallel, z = " + fixed(z, 0) + " mm" + sfx, m.w[gi][0][i], parallel,
                          setup.resolution(z, ge) / parallel));
    }
  }
  return v;
}

// The configured display's widths judged as before the cover glass was accounted for (against
// the no-glass prediction and resolution), for the report.
bool passesWithoutGlassPrediction(const TeleSetup& setup, const TeleWidths& m) {
  bool pass = true;
  for (size_t i = 0; i < setup.zs.size(); ++i) {
    const double z = setup.zs[i];
    pass = pass && std::abs(m.w[0][1][i] - kBarW * setup.sizeToedIn(z, setup.g)) <= setup.resolution(z, setup.g);
    pass = pass && std::abs(m.w[0][0][i] - kBarW * setup.sizeParallel(z, setup.g)) <= setup.resolution(z, setup.g);
  }
  return pass;
}

void writeCsvData(ReportWriter& w, const TeleSetup& setup, const TeleWidths& m) {
  std::vector<std::vector<std::string>> rows;
  for (int gi = 0; gi < 2; ++gi) {
    const double ge = opticalGapOf(setup, gi);
    for (size_t i = 0; i < setup.zs.size(); ++i) {
      const double z = setup.zs[i];
      rows.push_back({gi == 0 ? "yes" : "no", csvNumber(z), csvNumber(kBarW), csvNumber(kBarW * setup.sizeToedIn(z, ge)),
                      csvNumber(m.w[gi][1][i]), csvNumber(kBarW * setup.sizeParallel(z, ge)), csvNumber(m.w[gi][0][i]),
                      csvNumber(setup.depthParallel(z, ge)), csvNumber(setup.resolution(z, ge))});
    }
  }
  w.csv("width_vs_depth.csv",
        {"cover_glass", "z_mm", "true_width_mm", "width_toed_in_predicted_mm", "width_toed_in_mm",
         "width_parallel_predicted_mm", "width_parallel_mm", "parallel_reconstructed_depth_mm", "resolution_mm"},
        rows);
}

void writeWidthPlot(ReportWriter& w, const TeleSetup& setup, const TeleWidths& m) {
  Plot p;
  p.title = "Bar width seen from D = " + fixed(setup.D, 0) + " mm: parallel vs toed-in";
  p.x.title = "object depth z (mm)";
  p.y.title = "perceived width (mm)";
  std::vector<double> zc, wc, wcNo, tc, tcNo;
  for (int i = 0; i <= 200; ++i) {
    const double z = setup.zs.front() - 2.0 + (setup.zs.back() - setup.zs.front() + 4.0) * i / 200.0;
    zc.push_back(z);
    wc.push_back(kBarW * setup.sizeParallel(z, setup.gEff));
    wcNo.push_back(kBarW * setup.sizeParallel(z, setup.g));
    tc.push_back(kBarW * setup.sizeToedIn(z, setup.gEff));
    tcNo.push_back(kBarW);
  }
  auto curve = [&](const char* name, const std::vector<double>& y, double dash, int colour) {
    PlotSeries c{name, zc, y};
    c.markers = false;
    c.dash = dash;
    c.color = plotPalette(colour);
    return c;
  };
  auto points = [&](const char* name, const std::vector<double>& y, int colour) {
    PlotSeries c{name, setup.zs, y};
    c.line = false;
    c.color = plotPalette(colour);
    return c;
  };
  p.series = {curve("parallel, predicted", wc, 8.0, 0),
              curve("parallel, predicted, no glass", wcNo, 3.0, 2),
              curve("toed-in, predicted", tc, 8.0, 1),
              curve("true width (toed-in, no glass)", tcNo, 3.0, 3),
              points("parallel, measured", m.w[0][0], 0),
              points("parallel, measured, no glass", m.w[1][0], 2),
              points("toed-in, measured", m.w[0][1], 1),
              points("toed-in, measured, no glass", m.w[1][1], 3)};
  p.markers.push_back({setup.Lref, "L"});
  p.markers.push_back({setup.zLine(setup.gEff), "z_g"});
  w.plot("width_vs_depth.png", p);
}

std::string predictionText(const TeleSetup& setup) {
  return "Pinhole picture: lens centres x_k = k P at z = 0, panel at z = −g, rays generated at the same g through "
         "pinholes at x_k^s. Without cover glass, an eye at (0, D) looks through lens k at the panel point "
         "u_k = x_k (1 + g/D). That pixel was written with the scene along the ray from u_k through x_k^s, which meets "
         "depth z at X_seen = x_k^s + (x_k^s − u_k) z / g, while the eye's line of sight through x_k meets depth z at "
         "X_true = x_k (1 − z/D).\n\n"
         "- toed-in (x_k^s = x_k, EI k centred on u_k): X_seen = X_true for every lens: no size error, for any D "
         "(the layout's D only centres the EIs, i.e. places the viewing zone).\n"
         "- parallel (x_k^s on the EI grid, x_k^s = r x_k with r = EI pitch / lens pitch = " + fixed(setup.pEi, 4) + " / " +
         fixed(setup.P, 3) + " = " + fixed(setup.r, 4) + "): X_seen = x_k [r − (1 − r) z/g − z/D], so the object is seen at "
         "the size ratio\n\n"
         "    S(z) = (1 − z/D) / (r − (1 − r) z/g − z/D)\n\n"
         "  (equivalently: all lenses' rays of a scene point (X, z) meet at depth z' = 1 / (r/z − (1 − r)/g), at "
         "X z'/z, and that point seen from D). S = 1/r = " + fixed(1.0 / setup.r, 4) + " on the MLA plane, " +
         fixed(setup.sizeParallel(setup.Lref, setup.g), 4) + " at z = L = " + fixed(setup.Lref, 2) + " mm. A parallel layout whose EI "
         "pitch equalled the lens pitch (r = 1) would have S = 1 too: the telecentric EIs cost it the viewing zone "
         "instead — the eye sees lens k's own EI only while |x_k| g / D < P/2, and the paper's r < 1 makes that worse: "
         "u_k − r x_k = x_k (1 + g/D − r).";
}

std::string glassPredictionText(const TeleSetup& setup) {
  return "*With the panel's cover glass* (" +
         (setup.glass.present ? fixed(setup.glass.thicknessMm, 2) + " mm of " + setup.glass.material + ", n = " + fixed(setup.glass.n, 4) +
                                " at 550 nm; the view simulation's `PanelEmitter` refracts every ray through it"
                          : std::string("none in this display")) +
         "), the lenses see the panel at the optical gap g_eff = g − t (1 − 1/n) = " + fixed(setup.gEff, 4) +
         " mm, while the synthesis's pinhole rays run in air at g. The eye looks through lens k at "
         "u_k = x_k (1 + g_eff/D), so X_seen = x_k^s + (x_k^s − x_k (1 + g_eff/D)) z / g, and\n\n"
         "    toed-in: S_g(z) = (1 − z/D) / (1 − (g_eff/g) z/D),   parallel: S_g(z) = (1 − z/D) / (r − (1 − r) z/g − "
         "(g_eff/g) z/D)\n\n"
         "(every point is rebuilt g_eff / g nearer the MLA, at the same lateral position, so it subtends slightly "
         "less from D: toed-in " + fixed(100.0 * (setup.sizeToedIn(19.0, setup.gEff) - 1.0), 2) + "% at z = 19 mm, " +
         fixed(100.0 * (setup.sizeToedIn(30.0, setup.gEff) - 1.0), 2) + "% at 30 mm; parallel " +
         fixed(100.0 * (setup.sizeParallel(30.0, setup.gEff) / setup.sizeParallel(30.0, setup.g) - 1.0), 2) +
         "% against the no-glass S at 30 mm). The parallel display flips beyond |x| = " + fixed(setup.flipX, 1) +
         " mm on the display at D = " + fixed(setup.D, 0) + " mm (toed-in: never, for this viewer). These are the "
         "predictions for the display as configured; S(z) without the glass is the control's.\n\n";
}

std::string methodText(const TeleSetup& setup) {
  return "Scene: a diffuse bar " + fixed(kBarW, 0) + " × " + fixed(kBarH, 0) + " mm (reflectance 0.8, lit by a "
         "distant light), turned " + fixed(kTiltDeg, 0) + "° about z, centred on the axis at depth z. Display: the "
         "paper prototype cropped to its central 45 × 25 lenslets, rays generated at g = 4 mm = the viewing gap, "
         "layout parallel or toed-in (D = " + fixed(setup.D, 0) + " mm). `synthesizeEia` (1 spp) → `renderView` through "
         "the real MLA, the panel's subpixels and its cover glass, and, as the control, the same with the cover glass "
         "switched off (`EmitterSettings::coverGlass = false`); thin-lens camera (f = 12 mm, f/4) at D focused on the "
         "bar, " + std::to_string(setup.W) + " × " + std::to_string(setup.H) + " px of " + fixed(setup.sample * 1000.0, 0) +
         " µm on the bar's plane; the view's estimator is `inim view`'s default, " +
         panelEstimatorName(setup.view.panelEstimator) + " (pixel area in " + std::to_string(setup.view.spp) +
         " strata, aperture grid " + std::to_string(setup.view.apertureGrid) + ", no noise). Width: in each row with "
         "|y| < 3.5 mm, the outermost 50% crossings (half the bar's median luminance), positions taken on the bar's "
         "plane along the pixels' chief rays (so the width is the angular size × distance, as the viewer judges it); "
         "the mean chord × cos 5°. Tolerance: the display's resolution at that depth, P |z − z_0| / z_0 (a facet's "
         "defocus, the facets lining up at z_0) + p L_e / g_e (a panel pixel imaged on L_e): with the glass "
         "z_0 = z_g = g f / (g_eff − f) = " + fixed(setup.zLine(setup.gEff), 2) + " mm and L_e / g_e = L_eff / g_eff "
         "(depth-sharpness study), without it z_0 = L and L / g.";
}

std::string resultTables(const TeleSetup& setup, const TeleWidths& m) {
  std::string t;
  for (int gi = 0; gi < 2; ++gi) {
    const double ge = opticalGapOf(setup, gi);
    t += gi == 0 ? "The display as configured (with the cover glass):\n\n" : "\nControl, cover glass switched off:\n\n";
    t += "| z (mm) | true (mm) | toed-in predicted (mm) | toed-in (mm) | parallel predicted (mm) | parallel measured (mm) "
         "| parallel depth z' (mm) | resolution (mm) |\n|---|---|---|---|---|---|---|---|\n";
    for (size_t i = 0; i < setup.zs.size(); ++i) {
      const double z = setup.zs[i];
      t += "| " + fixed(z, 0) + " | " + fixed(kBarW, 2) + " | " + fixed(kBarW * setup.sizeToedIn(z, ge), 3) + " | " +
           fixed(m.w[gi][1][i], 3) + " | " + fixed(kBarW * setup.sizeParallel(z, ge), 3) + " | " + fixed(m.w[gi][0][i], 3) +
           " | " + fixed(setup.depthParallel(z, ge), 2) + " | " + fixed(setup.resolution(z, ge), 2) + " |\n";
    }
  }
  return t + "\n![width vs depth](width_vs_depth.png)\n\nData: `width_vs_depth.csv`.\n\n";
}

std::string discussionText(const TeleSetup& setup, const TeleWidths& m) {
  const double zLast = setup.zs.back();
  const double maxGlassChange = std::max(std::abs(setup.sizeToedIn(zLast, setup.gEff) - 1.0),
                                         std::abs(setup.sizeParallel(zLast, setup.gEff) / setup.sizeParallel(zLast, setup.g) - 1.0));
  std::string measured, depths, predicted;
  for (size_t i = 0; i < setup.zs.size(); ++i) {
    const std::string sep = i ? ", " : "";
    measured += sep + fixed(100.0 * (m.w[0][1][i] / m.w[1][1][i] - 1.0), 2) + "% / " +
                fixed(100.0 * (m.w[0][0][i] / m.w[1][0][i] - 1.0), 2) + "%";
    depths += sep + fixed(setup.zs[i], 0);
    predicted += sep + fixed(100.0 * (setup.sizeToedIn(setup.zs[i], setup.gEff) - 1.0), 2) + "% / " +
                 fixed(100.0 * (setup.sizeParallel(setup.zs[i], setup.gEff) / setup.sizeParallel(setup.zs[i], setup.g) - 1.0), 2) + "%";
  }
  return "The cover glass changes the predicted widths by at most " + fixed(100.0 * maxGlassChange, 2) +
         "% here, less than the display's resolution, so this study cannot separate the two predictions; it checks "
         "that the layouts' size behaviour holds for the display as configured. Judged against the no-glass "
         "prediction and resolution (as an earlier version of this study did: its render had the glass, its "
         "prediction did not), the configured display's widths would " +
         std::string(passesWithoutGlassPrediction(setup, m) ? "also pass" : "not all pass") + ". The glass moves the "
         "depth where the facets line up from L = " + fixed(setup.Lref, 2) + " mm to z_g = " + fixed(setup.zLine(setup.gEff), 2) +
         " mm, which changes the tolerance: tighter beyond about 22.5 mm, looser nearer the MLA. Measured, the "
         "configured display's widths differ from the control's by " + measured + " (toed-in / parallel, at z = " +
         depths + " mm), against a predicted " + predicted + ": beyond L the control's widths are larger than the "
         "size change explains. There its facets are further from lining up (they line up at L, the configured "
         "display's at z_g), and the outermost 50% crossings of a frayed edge lengthen the chord; the tolerance's "
         "facet-defocus term covers that.";
}

// The full form's verdict values measured with the Footprint estimator at 16 spp, before the
// view default became Quadrature (validation/telecentric/report.md of that version).
const std::vector<EarlierValue> kFootprintValues = {
    {24.450, 24.031}, {23.585, 23.601}, {24.064, 24.000}, {24.638, 24.304}, {24.128, 23.967}, {25.062, 25.096},
    {23.912, 23.935}, {25.878, 25.899}, {23.940, 23.914}, {26.523, 26.490}, {23.856, 23.895}, {27.169, 27.021},
    {24.558, 24.000}, {23.729, 23.570}, {24.063, 24.000}, {24.630, 24.304}, {24.108, 24.000}, {25.136, 25.132},
    {24.088, 24.000}, {26.069, 25.974}, {24.034, 24.000}, {26.934, 26.596}, {24.295, 24.000}, {27.392, 27.156}};

std::vector<std::string> writeReport(const StudyOptions& o, const TeleSetup& setup, const TeleWidths& m,
                                     const std::vector<StudyValue>& values) {
  ReportWriter w("telecentric", o, "telecentric size error, parallel against toed-in");
  w.section("What",
            "The size of a reconstructed object as a camera " + fixed(setup.D, 0) + " mm in front of the display sees it, for "
            "the paper's `parallel` EI layout and the `toed-in` layout for D = " + fixed(setup.D, 0) + " mm, through the "
            "whole pipeline (synthesis, panel subpixels and cover glass, real MLA, camera), for the display as "
            "configured and, as the control, with the panel's cover glass switched off.");
  w.section("Prediction", predictionText(setup));
  w.text(glassPredictionText(setup));
  w.section("Method", methodText(setup));
  w.results(values, "mm");
  w.text(resultTables(setup, m));
  writeCsvData(w, setup, m);
  writeWidthPlot(w, setup, m);
  w.section("Discussion", discussionText(setup, m));
  if (!o.quick)
    w.changes("The views were rendered with the Footprint estimator at 16 spp; they now use `inim view`'s default, "
              "the " + std::string(panelEstimatorName(setup.view.panelEstimator)) + " estimator (no noise) at " +
              std::to_string(setup.view.spp) + " strata per pixel and aperture grid " +
              std::to_string(setup.view.apertureGrid) + ". The predictions and tolerances are unchanged; the widths "
              "before and now:",
              values, kFootprintValues, "mm");
  w.verdict("each width within the display's resolution at its depth of its prediction: S_g(z) × the true width with "
            "the glass, the true width (toed-in) and S(z) × the true width (parallel) without it",
            values);
  return w.commit();
}

}  // namespace

StudyReport runTelecentric(const StudyOptions& o) {
  const TeleSetup setup = setUp(o);
  const TeleWidths m = measure(setup);
  StudyReport rep = makeReport("telecentric", judge(setup, m));
  rep.files = writeReport(o, setup, m, rep.values);
  return rep;
}

}  // namespace inim
