// inim study telecentric: the size of a reconstructed object seen from a finite distance D,
// EI layout parallel (the paper's) against toed-in (DESIGN.md section 1 step 3). EIA synthesised
// from the scene (synthesis/), seen through the real MLA by a camera at D (view/).
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>

#include "analysis/plot.h"
#include "camera/camera_config.h"
#include "core/error.h"
#include "core/output_file.h"
#include "mla/real_mla.h"
#include "studies/studies.h"
#include "studies/study_common.h"
#include "studies/study_pipeline.h"
#include "view/display_model.h"
#include "view/view_renderer.h"

namespace fs = std::filesystem;

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

}  // namespace

StudyReport runTelecentric(const StudyOptions& o) {
  const std::string displayPath = o.displayPath.empty() ? defaultDisplayPath() : o.displayPath;
  const double g = 4.0, D = 350.0;
  const Display base = loadDisplay(displayPath);
  const double P = base.mla.pitchMm, f = lensletFocus(base.mla).focalLengthMm;
  const double pEi = base.eiWidthPx * base.panel.pixelPitchMm, r = pEi / P, px = base.panel.pixelPitchMm;
  const double Lref = g * f / (g - f);
  // Perceived size relative to the true size, parallel layout (see the report's derivation).
  auto sizeParallel = [&](double z) { return (1.0 - z / D) / (r - (1.0 - r) * z / g - z / D); };
  auto depthParallel = [&](double z) { return std::abs(z) < 1e-12 ? 0.0 : 1.0 / (r / z - (1.0 - r) / g); };
  // Display resolution at depth z: a facet's defocus P |z - L| / L plus a panel pixel imaged on L.
  auto resolution = [&](double z) { return P * std::abs(z - Lref) / Lref + px * Lref / g; };
  const double flipX = 0.5 * pEi / (1.0 + g / D - r);  // lens position where parallel flips

  const std::vector<double> zs = o.quick ? std::vector<double>{10, 19, 30} : std::vector<double>{-10, 0, 10, 19, 25, 30};
  const int W = o.quick ? 170 : 340, H = o.quick ? 50 : 100, spp = o.quick ? 8 : 16;
  const double sample = o.quick ? 0.2 : 0.1;
  const CameraDescription& camDesc = loadCameraDescription("alvium-1800-u-500c");
  const Json scene = litRectangleScene(kBarW, kBarH, Json(0.8), kTiltDeg);

  std::vector<double> wPar, wToe, wParPred;
  for (EiLayoutKind kind : {EiLayoutKind::Parallel, EiLayoutKind::ToedIn}) {
    Display d = cropDisplay(displayPath, 45, 25, g, kind, D);
    d.reconstructionGapMm = g;
    EiLayout L = computeLayout(d);
    for (double z : zs) {
      const Image eia = synthesizeAt(L, d, scene, z, 1);
      auto cam = axialThinLens(D, z, W, H, sample);
      ViewSettings vs;
      vs.spp = spp;
      vs.progress = false;
      vs.seed = 11;
      DisplayModel dm = makeDisplayModel(d, L, eia, "(synthesised)", MlaKind::Real, g);
      const ViewResult v = renderView(*cam, camDesc.sensor, *dm.mla, *dm.panel, dm.area, vs);
      (kind == EiLayoutKind::Parallel ? wPar : wToe).push_back(barWidth(v.image, *cam, z));
    }
  }
  for (double z : zs) wParPred.push_back(kBarW * sizeParallel(z));

  StudyReport rep;
  rep.study = "telecentric";
  for (size_t i = 0; i < zs.size(); ++i) {
    rep.values.push_back(compare("width, toed-in, z = " + fmt(zs[i], 0) + " mm", wToe[i], kBarW, resolution(zs[i]) / kBarW));
    rep.values.push_back(compare("width, parallel, z = " + fmt(zs[i], 0) + " mm", wPar[i], wParPred[i],
                                 resolution(zs[i]) / wParPred[i]));
  }
  rep.pass = allPass(rep.values);

  OutputSet out;
  const fs::path dir(o.outDir);
  const std::string mdPath = (dir / "report.md").string(), csvPath = (dir / "width_vs_depth.csv").string(),
                    pngPath = (dir / "width_vs_depth.png").string();
  {
    std::vector<std::vector<std::string>> rows;
    for (size_t i = 0; i < zs.size(); ++i)
      rows.push_back({csvNumber(zs[i]), csvNumber(kBarW), csvNumber(wToe[i]), csvNumber(wParPred[i]), csvNumber(wPar[i]),
                      csvNumber(depthParallel(zs[i])), csvNumber(resolution(zs[i]))});
    writeCsv(out.add(csvPath),
             {"z_mm", "true_width_mm", "width_toed_in_mm", "width_parallel_predicted_mm", "width_parallel_mm",
              "parallel_reconstructed_depth_mm", "resolution_mm"},
             rows);
  }
  {
    Plot p;
    p.title = "Bar width seen from D = " + fmt(D, 0) + " mm: parallel vs toed-in";
    p.x.title = "object depth z (mm)";
    p.y.title = "perceived width (mm)";
    std::vector<double> zc, wc, tc;
    for (int i = 0; i <= 200; ++i) {
      const double z = zs.front() - 2.0 + (zs.back() - zs.front() + 4.0) * i / 200.0;
      zc.push_back(z);
      wc.push_back(kBarW * sizeParallel(z));
      tc.push_back(kBarW);
    }
    PlotSeries a{"parallel, predicted", zc, wc};
    a.markers = false;
    a.dash = 8.0;
    PlotSeries b{"true width", zc, tc};
    b.markers = false;
    b.dash = 3.0;
    PlotSeries c{"parallel, measured", zs, wPar};
    c.line = false;
    PlotSeries e{"toed-in, measured", zs, wToe};
    e.line = false;
    p.series = {a, b, c, e};
    p.markers.push_back({Lref, "L"});
    writePlot(p, out.add(pngPath));
  }

  std::string md;
  md += "# Study: telecentric size error, parallel against toed-in\n\n";
  md += "**What.** The size of a reconstructed object as a camera " + fmt(D, 0) + " mm in front of the display sees "
        "it, for the paper's `parallel` EI layout and the `toed-in` layout for D = " + fmt(D, 0) + " mm, through the "
        "whole pipeline (synthesis, panel subpixels, real MLA, camera).\n\n";
  md += "**Prediction.** Pinhole picture: lens centres x_k = k P at z = 0, panel at z = −g, rays generated at the "
        "same g through pinholes at x_k^s. An eye at (0, D) looks through lens k at the panel point "
        "u_k = x_k (1 + g/D). That pixel was written with the scene along the ray from u_k through x_k^s, which "
        "meets depth z at X_seen = x_k^s + (x_k^s − u_k) z / g, while the eye's line of sight through x_k meets "
        "depth z at X_true = x_k (1 − z/D).\n\n"
        "- toed-in (x_k^s = x_k, EI k centred on u_k): X_seen = X_true for every lens: no size error, for any D "
        "(the layout's D only centres the EIs, i.e. places the viewing zone).\n"
        "- parallel (x_k^s on the EI grid, x_k^s = r x_k with r = EI pitch / lens pitch = " + fmt(pEi, 4) + " / " +
        fmt(P, 3) + " = " + fmt(r, 4) + "): X_seen = x_k [r − (1 − r) z/g − z/D], so the object is seen at the size "
        "ratio\n\n"
        "    S(z) = (1 − z/D) / (r − (1 − r) z/g − z/D)\n\n"
        "  (equivalently: all lenses' rays of a scene point (X, z) meet at depth z' = 1 / (r/z − (1 − r)/g), at "
        "X z'/z, and that point seen from D). S = 1/r = " + fmt(1.0 / r, 4) + " on the MLA plane, " +
        fmt(sizeParallel(Lref), 4) + " at z = L = " + fmt(Lref, 2) + " mm. A parallel layout whose EI pitch "
        "equalled the lens pitch (r = 1) would have S = 1 too: the telecentric EIs cost it the viewing zone instead "
        "— the eye sees lens k's own EI only while |x_k| g / D < P/2, and the paper's r < 1 makes that worse: "
        "u_k − r x_k = x_k (1 + g/D − r), so the parallel display flips beyond |x_k| = " + fmt(flipX, 1) +
        " mm at D = " + fmt(D, 0) + " mm (toed-in: never, for this viewer).\n\n";
  md += "**Method.** Scene: a diffuse bar " + fmt(kBarW, 0) + " × " + fmt(kBarH, 0) + " mm (reflectance 0.8, lit by a "
        "distant light), turned " + fmt(kTiltDeg, 0) + "° about z, centred on the axis at depth z. Display: the paper "
        "prototype cropped to its central 45 × 25 lenslets, rays generated at g = 4 mm = the viewing gap, layout "
        "parallel or toed-in (D = " + fmt(D, 0) + " mm). `synthesizeEia` (1 spp) → `renderView` through the real "
        "MLA, thin-lens camera (f = 12 mm, f/4) at D focused on the bar, " + std::to_string(W) + " × " +
        std::to_string(H) + " px of " + fmt(sample * 1000.0, 0) + " µm on the bar's plane, " + std::to_string(spp) +
        " spp. Width: in each row with |y| < 3.5 mm, the outermost 50% crossings (half the bar's median "
        "luminance), positions taken on the bar's plane along the pixels' chief rays (so the width is the angular "
        "size × distance, as the viewer judges it); the mean chord × cos 5°. Tolerance: the display's resolution at "
        "that depth, P |z − L| / L (a facet's defocus) + p L / g (a panel pixel imaged on L).\n\n";
  md += "**Result.**\n\n" + valuesTable(rep.values, "mm") + "\n";
  md += "| z (mm) | true (mm) | toed-in (mm) | parallel predicted (mm) | parallel measured (mm) | parallel depth z' (mm) | "
        "resolution (mm) |\n|---|---|---|---|---|---|---|\n";
  for (size_t i = 0; i < zs.size(); ++i)
    md += "| " + fmt(zs[i], 0) + " | " + fmt(kBarW, 2) + " | " + fmt(wToe[i], 3) + " | " + fmt(wParPred[i], 3) + " | " +
          fmt(wPar[i], 3) + " | " + fmt(depthParallel(zs[i]), 2) + " | " + fmt(resolution(zs[i]), 2) + " |\n";
  md += "\n![width vs depth](width_vs_depth.png)\n\nData: `width_vs_depth.csv`.\n\n";
  md += "**Verdict** (each width within the display's resolution at its depth of its prediction: the true width for "
        "toed-in, S(z) × the true width for parallel): " + verdictLine(rep.values) + "\n\n";
  md += "**Reproduce.**\n\n```\n" + reproduceCommand(rep.study, o) + "\n```\n";
  {
    std::ofstream fo(out.add(mdPath));
    fo << md;
    if (!fo) throw std::runtime_error("cannot write " + mdPath);
  }
  out.commit();
  rep.files = {mdPath, pngPath, csvPath};
  return rep;
}

}  // namespace inim
