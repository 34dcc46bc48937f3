// inim study braiding: multifaceted braiding. A reconstructed point away from the reference
// image plane L is seen as facets, one per lenslet, that do not line up. Its EIA is synthesised
// (synthesis/) and its light traced from the lit panel pixels through the real MLA (mla/):
// per lenslet, where the point appears (projected on its own depth) against the eye position.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>

#include "analysis/plot.h"
#include "core/error.h"
#include "core/output_file.h"
#include "core/rng.h"
#include "mla/real_mla.h"
#include "studies/studies.h"
#include "studies/study_common.h"
#include "studies/study_pipeline.h"
#include "view/ideal_mla.h"

namespace fs = std::filesystem;

namespace inim {

namespace {

using namespace study_detail;

struct Reg {  // weighted sums for a straight-line fit v = a + b u
  double w = 0, u = 0, v = 0, uu = 0, uv = 0;
  void add(double wt, double uu_, double vv) {
    w += wt, u += wt * uu_, v += wt * vv, uu += wt * uu_ * uu_, uv += wt * uu_ * vv;
  }
  double slope() const {
    const double mu = u / w, var = uu / w - mu * mu;
    return var > 1e-12 ? (uv / w - mu * v / w) / var : std::nan("");
  }
  double at(double x) const { return v / w + slope() * (x - u / w); }
};

struct FacetResult {
  double jump = std::nan("");    // facet-to-facet jump of the apparent position (mm at the point's depth)
  double slope = std::nan("");   // d(apparent position) / d(eye position) inside a facet
  double facetDepth = std::nan("");  // the depth that in-facet parallax belongs to
  int lenslets = 0;
};

// A pinhole eye scanned along x on the plane z = D (E = -60 ... 60 mm, 0.5 mm steps) looks at
// the display: rays from E to a grid on the MLA plane (x in [-8, 8] mm every 20 um, 5 rows
// within the centre lenslet row) are traced back through the MLA to the panel, where they pick
// up the luminance of the EIA pixel they land on (x throughput), if it lies in the lenslet's own
// EI. What the eye sees through lenslet k is the point at the luminance-weighted mean X of those
// rays' lines of sight on the point's plane z = zr. Per lenslet, a line X = b_k + s_k E over the
// eye positions where the facet shows the whole spot; neighbouring lines compared halfway
// between their windows give the jump, the in-facet slope s the facets' apparent depth
// (zr - s D) / (1 - s).
FacetResult measureFacets(const MlaModel& mla, const EiLayout& L, const Image& eia, double zr, double D,
                          bool vertical = false) {
  const int nE = 241, nX = 801, nY = 5;
  const double E0 = -60.0, dE = 0.5;
  // Along x (lenslet columns k) or, vertical, along y (lenslet rows l; y decreases with l).
  const int K = vertical ? L.eiRows : L.eiCols;
  const std::vector<double>& centre = vertical ? L.lensY : L.lensX;
  const double P = K > 1 ? std::abs(centre[1] - centre[0]) : 1.0;  // lens pitch
  std::vector<double> w(size_t(nE) * K, 0.0), wx(size_t(nE) * K, 0.0);
  for (int ie = 0; ie < nE; ++ie) {
    const double E = E0 + dE * ie;
    const Point3 eye(vertical ? 0.0f : float(E), vertical ? float(E) : 0.0f, float(D));
    for (int iy = 0; iy < nY; ++iy)
      for (int ix = 0; ix < nX; ++ix) {
        const double mx = -8.0 + 0.02 * ix, my = ((iy + 0.5) / nY - 0.5) * 0.9 * P;
        const double ax = vertical ? my : mx - E, ay = vertical ? mx - E : my;
        const Vec3 dir = glm::normalize(Vec3(float(ax), float(ay), float(-D)));
        Rng rng = Rng::forSample(5, uint64_t(ie) * 100000u + uint64_t(iy) * 10000u + uint64_t(ix));
        PanelArrival a;
        if (!mla.traceToPanel(Ray{eye, dir}, 587.56f, rng, a)) continue;
        const int k = vertical ? a.lensletL : a.lensletK;
        if (k < 0 || k >= K) continue;
        const int col = int(std::floor(a.p.x / L.pixelMm + 0.5 * L.eiaW));
        const int row = int(std::floor(0.5 * L.eiaH - a.p.y / L.pixelMm));
        if (col < 0 || row < 0 || col >= L.eiaW || row >= L.eiaH) continue;
        // Only the lenslet's own EI: beyond psi/2 the eye sees the neighbouring EI's copy of the
        // point through it (the flipped repeat), which is not braiding.
        if (vertical ? (row < L.eiRow0[size_t(k)] || row >= L.eiRow0[size_t(k)] + L.eiH)
                     : (col < L.eiCol0[size_t(k)] || col >= L.eiCol0[size_t(k)] + L.eiW))
          continue;
        const double v = lum(eia, col + L.panelCol0, row + L.panelRow0) * a.throughput;
        if (!(v > 0.0)) continue;
        const double X = E + (mx - E) * (D - zr) / D;  // the eye's line of sight on the plane z = zr
        w[size_t(ie) * K + k] += v;
        wx[size_t(ie) * K + k] += v * X;
      }
  }
  FacetResult res;
  // Per lenslet: a line over the eye positions where the facet shows the whole spot (at least
  // 70% of that facet's brightest; nearer the window's ends the lenslet's rim or its EI's edge
  // clips the spot and pulls the apparent position toward the facet's centre).
  std::vector<Reg> lines(static_cast<size_t>(K));
  std::vector<bool> ok(static_cast<size_t>(K), false);
  Reg slopes;
  for (int k = 0; k < K; ++k) {
    double peak = 0.0;
    for (int ie = 0; ie < nE; ++ie) peak = std::max(peak, w[size_t(ie) * K + k]);
    if (!(peak > 0.0)) continue;
    Reg& line = lines[size_t(k)];
    for (int ie = 0; ie < nE; ++ie) {
      const double v = w[size_t(ie) * K + k];
      if (v < 0.7 * peak) continue;
      line.add(1.0, E0 + dE * ie, wx[size_t(ie) * K + k] / v);
    }
    if (line.w < 4) continue;
    const double s = line.slope();
    if (!std::isfinite(s)) continue;
    ok[size_t(k)] = true;
    ++res.lenslets;
    slopes.add(line.w, 0.0, s);
  }
  // The jump between neighbouring facets: both lines at the eye position halfway between their
  // windows (the least extrapolation), X_{k+1}(E) - X_k(E) (lens centres increase with k).
  double js = 0.0, jw = 0.0;
  for (int k = 0; k + 1 < K; ++k) {
    if (!ok[size_t(k)] || !ok[size_t(k + 1)]) continue;
    const Reg &a = lines[size_t(k)], &b = lines[size_t(k + 1)];
    const double Em = 0.5 * (a.u / a.w + b.u / b.w), wt = std::min(a.w, b.w);
    js += wt * (b.at(Em) - a.at(Em)) * (centre[size_t(k + 1)] > centre[size_t(k)] ? 1.0 : -1.0);
    jw += wt;
  }
  if (!(jw > 0.0)) return res;
  res.jump = js / jw;
  res.slope = slopes.v / slopes.w;
  res.facetDepth = (zr - res.slope * D) / (1.0 - res.slope);
  return res;
}

// Signed facet-to-facet jump predicted for a point at depth z (thin lenslets, pinhole eye at D).
double predictedJump(double P, double Lr, double D, double z) { return P * (1.0 - Lr / z) * (D - z) / (D - Lr); }

// The first sign change from - to + among z > 0, interpolated linearly.
double zeroCrossing(const std::vector<double>& z, const std::vector<double>& b) {
  for (size_t i = 1; i < z.size(); ++i)
    if (z[i - 1] > 0.0 && std::isfinite(b[i - 1]) && std::isfinite(b[i]) && b[i - 1] < 0.0 && b[i] >= 0.0)
      return z[i - 1] + (0.0 - b[i - 1]) / (b[i] - b[i - 1]) * (z[i] - z[i - 1]);
  return std::nan("");
}

}  // namespace

StudyReport runBraiding(const StudyOptions& o) {
  const std::string displayPath = o.displayPath.empty() ? defaultDisplayPath() : o.displayPath;
  const double g = 4.0, D = 350.0;
  Display d = cropDisplay(displayPath, 31, 31, g, EiLayoutKind::ToedIn, D);
  d.reconstructionGapMm = g;
  const double gPaper = loadDisplay(displayPath).generationGapMm;
  EiLayout L = computeLayout(d);
  const double f = lensletFocus(d.mla).focalLengthMm, P = d.mla.pitchMm;
  auto realOwned = makeRealMla(d, L, g);
  const auto* real = dynamic_cast<const RealMla*>(realOwned.get());
  if (!real) throw std::runtime_error("braiding study: makeRealMla did not return a RealMla");
  const IdealLensletMla ideal(L, P, f, g);
  const double Lideal = g * f / (g - f), hPrime = real->rearNodalZ(), Lreal = hPrime + Lideal;
  const std::vector<double> zs = o.quick ? std::vector<double>{-20, 10, 15, 21, 28, 40}
                                         : std::vector<double>{-30, -20, -12, 8, 10, 12.5, 15, 17, 18.5, 20,
                                                               21.5, 23.5, 27, 32, 40};

  // [0] ideal lenslets, [1] real lenslets; both see the same synthesised EIA.
  std::vector<FacetResult> res[2], resV[2];  // along x (lenslet columns), along y (rows)
  for (double z : zs) {
    // A point: a sphere about one EI pixel's footprint at its depth (p |z| / g), so every EI
    // that sees it lights one or two pixels and its image on L is smaller than a facet.
    const double radius = std::max(0.03, 0.75 * L.pixelMm * std::abs(z) / g);
    const Image eia = synthesizeAt(L, d, emissiveSphereScene(radius, 1.0), z, 1);
    res[0].push_back(measureFacets(ideal, L, eia, z, D));
    res[1].push_back(measureFacets(*real, L, eia, z, D));
    resV[0].push_back(measureFacets(ideal, L, eia, z, D, true));
    resV[1].push_back(measureFacets(*real, L, eia, z, D, true));
  }
  const double Lm[2] = {Lideal, Lreal};
  const char* name[2] = {"ideal MLA", "real MLA"};
  auto col = [&](int m, auto fn) {
    std::vector<double> v;
    for (const auto& r : res[m]) v.push_back(fn(r));
    return v;
  };
  auto jumps = [&](int m) { return col(m, [](const FacetResult& r) { return r.jump; }); };
  auto depths = [&](int m) { return col(m, [](const FacetResult& r) { return r.facetDepth; }); };
  auto at = [&](const std::vector<double>& v, double z) {
    for (size_t i = 0; i < zs.size(); ++i)
      if (std::abs(zs[i] - z) < 1e-9) return v[i];
    return std::nan("");
  };
  // Mean apparent facet depth over the depths more than 4 mm from L (closer, the in-facet
  // parallax is ~0 whatever the facets' depth, and the estimate is ill-conditioned).
  auto meanFacetDepth = [&](int m) {
    const auto v = depths(m);
    double s = 0.0;
    int n = 0;
    for (size_t i = 0; i < zs.size(); ++i)
      if (std::isfinite(v[i]) && std::abs(zs[i] - Lm[m]) > 4.0) s += v[i], ++n;
    return n ? s / n : std::nan("");
  };

  StudyReport rep;
  rep.study = "braiding";
  const double tolZero[2] = {0.10, 0.25}, tolJump[2] = {0.20, 0.35}, tolDepth[2] = {0.10, 0.25};
  for (int m = 0; m < 2; ++m) {
    const std::string n = name[m];
    const auto j = jumps(m);
    rep.values.push_back(compare("depth of zero braiding, " + n, zeroCrossing(zs, j), Lm[m], tolZero[m]));
    rep.values.push_back(compare("facet jump at z = 40 mm, " + n, at(j, 40.0), predictedJump(P, Lm[m], D, 40.0), tolJump[m]));
    rep.values.push_back(compare("facet jump at z = 10 mm, " + n, at(j, 10.0), predictedJump(P, Lm[m], D, 10.0), tolJump[m]));
    rep.values.push_back(
        compare("facet jump at z = -20 mm (virtual), " + n, at(j, -20.0), predictedJump(P, Lm[m], D, -20.0), tolJump[m]));
    rep.values.push_back(compare("apparent depth of the facets (mean), " + n, meanFacetDepth(m), Lm[m], tolDepth[m]));
  }
  // The same along y (eye scanned vertically, lenslet rows).
  for (int m = 0; m < 2; ++m) {
    std::vector<double> jv;
    for (const auto& r : resV[m]) jv.push_back(r.jump);
    rep.values.push_back(compare("facet jump at z = 40 mm, vertical, " + std::string(name[m]), at(jv, 40.0),
                                 predictedJump(P, Lm[m], D, 40.0), tolJump[m]));
    rep.values.push_back(compare("facet jump at z = -20 mm, vertical, " + std::string(name[m]), at(jv, -20.0),
                                 predictedJump(P, Lm[m], D, -20.0), tolJump[m]));
  }
  // The real lenslets' jumps against the same formula with L = their measured facet depth.
  const double Leff = meanFacetDepth(1);
  rep.values.push_back(compare("facet jump at z = 40 mm, real MLA, L = its facet depth", at(jumps(1), 40.0),
                               predictedJump(P, Leff, D, 40.0), 0.15));
  rep.values.push_back(compare("facet jump at z = 10 mm, real MLA, L = its facet depth", at(jumps(1), 10.0),
                               predictedJump(P, Leff, D, 10.0), 0.15));
  rep.pass = allPass(rep.values);

  OutputSet out;
  const fs::path dir(o.outDir);
  const std::string mdPath = (dir / "report.md").string(), csvPath = (dir / "braiding.csv").string(),
                    png1 = (dir / "facet_jump_vs_depth.png").string(), png2 = (dir / "facet_depth.png").string();
  {
    std::vector<std::vector<std::string>> rows;
    for (int m = 0; m < 2; ++m)
      for (size_t i = 0; i < zs.size(); ++i)
        rows.push_back({m == 0 ? "ideal" : "real", csvNumber(zs[i]), csvNumber(predictedJump(P, Lm[m], D, zs[i])),
                        csvNumber(res[m][i].jump), csvNumber(res[m][i].slope), csvNumber(res[m][i].facetDepth),
                        std::to_string(res[m][i].lenslets), csvNumber(resV[m][i].jump),
                        csvNumber(resV[m][i].facetDepth)});
    writeCsv(out.add(csvPath),
             {"mla", "z_mm", "jump_predicted_mm", "jump_measured_mm", "in_facet_parallax_slope",
              "apparent_facet_depth_mm", "lenslets", "jump_vertical_mm", "apparent_facet_depth_vertical_mm"},
             rows);
  }
  {
    Plot p;
    p.title = "Braiding: facet-to-facet jump of a point (eye at " + fmt(D, 0) + " mm)";
    p.x.title = "point depth z (mm)";
    p.y.title = "jump (mm on the point's plane)";
    for (int m = 0; m < 2; ++m) {
      std::vector<double> zc, jc;
      for (int i = 0; i <= 400; ++i) {
        const double z = zs.front() + (zs.back() - zs.front()) * i / 400.0;
        zc.push_back(z);
        jc.push_back(std::abs(z) < 4.0 ? std::nan("") : predictedJump(P, Lm[m], D, z));
      }
      PlotSeries pr{"predicted, L = " + fmt(Lm[m], 2), zc, jc};
      pr.markers = false;
      pr.dash = m == 0 ? 0.0 : 8.0;
      pr.color = plotPalette(m);
      PlotSeries s{"traced, " + std::string(name[m]), zs, jumps(m)};
      s.line = false;
      s.color = plotPalette(m);
      p.series.push_back(pr);
      p.series.push_back(s);
    }
    p.y.min = -3.0, p.y.max = 3.5;
    p.markers.push_back({Lreal, "H'+L"});
    p.hMarkers.push_back({0.0, "", Vec3(0.4f, 0.4f, 0.4f), 3.0});
    writePlot(p, out.add(png1));
  }
  {
    Plot p;
    p.title = "Apparent depth of the facets (in-facet parallax)";
    p.x.title = "point depth z (mm)";
    p.y.title = "facet depth (mm)";
    for (int m = 0; m < 2; ++m) {
      PlotSeries s{"traced, " + std::string(name[m]), zs, depths(m)};
      s.line = false;
      p.series.push_back(s);
    }
    PlotSeries id{"z (no braiding)", {zs.front(), zs.back()}, {zs.front(), zs.back()}};
    id.markers = false;
    id.dash = 6.0;
    p.series.push_back(id);
    p.hMarkers.push_back({Lreal, "H'+L " + fmt(Lreal, 2)});
    writePlot(p, out.add(png2));
  }

  std::string md;
  md += "# Study: multifaceted braiding\n\n";
  md += "**What.** A reconstructed point away from the reference image plane is not one point: each lenslet shows "
        "its own facet of it, and neighbouring facets do not line up (\"braided\"). This study measures that "
        "misalignment for a point at depths in front of and behind the MLA, with the EIA synthesised from the scene, "
        "seen by a pinhole eye through the ideal (thin) and the real (refracting) lenslets.\n\n";
  md += "**Prediction** (paraxial, thin lenslets of focal f at gap g, image plane L = g f / (g − f)). A point at "
        "(X, z) is written into EI c (lens centre x_c) at the panel pixel on the pinhole ray through x_c. Lenslet c "
        "images that pixel to the plane L, at Q_c = x_c + (X − x_c) L / z: the pinhole (chief) ray still passes "
        "through (X, z), but the light of the facet comes from Q_c. An eye at (E, D) that sees the point through "
        "lenslet c sees it in the direction of Q_c; projected on the point's own plane z it appears at "
        "x = E + (Q_c − E)(D − z)/(D − L). So inside a facet the point moves with the eye as if it sat at depth L "
        "(in-facet parallax dx/dE = (z − L)/(D − L)), and between neighbouring facets (x_c → x_c + P) the facet "
        "lines are offset by\n\n"
        "    B(z) = P (1 − L/z) (D − z) / (D − L)   (mm on the point's plane)\n\n"
        "which is 0 at z = L, negative between the MLA and L, positive beyond L, and larger than P behind the MLA "
        "(z < 0: the facets are inverted). The offset equals the sweep inside one facet, so on average the point "
        "stays where it should (each lenslet's full bundle is centred on the pinhole ray through (X, z)): braiding "
        "is what an eye with a pupil smaller than a facet's spacing sees, point facets jumping by B as the eye "
        "moves. A generation gap g_gen ≠ g (the paper's " + fmt(gPaper, 1) + " mm against 4 mm) writes a point at "
        "z_s into exactly the pixels that g_gen = g writes for z = z_s g / g_gen, so it is the same EIA, rebuilt at "
        "z_r = z_s g / g_gen: the prediction holds with z_r, and needs no separate run. Here P = " + fmt(P, 3) +
        " mm, f = " + fmt(f, 4) + " mm, g = " + fmt(g, 1) + " mm, D = " + fmt(D, 0) + " mm: L = " + fmt(Lideal, 2) +
        " mm for the ideal lenslets (at z = 0) and H' + L = " + fmt(Lreal, 2) + " mm for the real ones (paraxial; "
        "image-plane study).\n\n";
  md += "**Method.** Scene: an emissive sphere on the axis at depth z, of radius 0.75 p |z| / g (at least 30 µm; p the panel pixel): about one EI pixel's footprint at that depth, so each EI that sees it lights one or two pixels. Display: the paper prototype "
        "cropped to its central 31 × 31 lenslets, toed-in layout for D = 350 mm (pinholes on the lens centres), "
        "rays generated at g = 4 mm; `synthesizeEia` (1 spp) gives the EIA. A pinhole eye on the plane z = D scans "
        "x from −60 to 60 mm in 0.5 mm steps; from each position, rays to a grid on the MLA plane (x ∈ [−8, 8] mm "
        "every 20 µm, 5 rows across the centre lenslet row) are traced back to the panel through the MLA "
        "(`MlaModel::traceToPanel`: `IdealLensletMla`, and the real MLA at 587.56 nm with stochastic Fresnel), and "
        "take the luminance of the EIA pixel they land on (the pixel as a uniform emitter) × throughput, counted only when that pixel belongs to the lenslet's own EI (beyond ψ/2 the eye sees the neighbouring EI's copy of the point, the flipped repeat, which is not braiding). Through "
        "lenslet k, the eye sees the point at the luminance-weighted mean of its lines of sight on the plane z. "
        "Per lenslet, over the eye positions where the facet shows the whole spot (at least 70% of its own "
        "peak; nearer its window's ends the lenslet's rim or its EI's edge clips the spot and pulls the apparent "
        "position toward the facet's centre), a straight line X = b_k + s_k E. The jump between neighbouring "
        "facets is X_{k+1}(E) − X_k(E) at the eye position halfway between their windows (averaged over the "
        "pairs), and the mean in-facet slope s gives the apparent depth of the facets, (z − s D)/(1 − s) (L when the prediction holds). The same "
        "scan along y (eye moving vertically, lenslet rows) checks the vertical facets.\n\n";
  md += "**Result.**\n\n" + valuesTable(rep.values, "mm") + "\n";
  md += "| z (mm) | predicted jump, ideal (mm) | measured, ideal (mm) | predicted, real (mm) | measured, real (mm) | "
        "predicted, real, L = " + fmt(Leff, 2) + " (mm) | facet depth, ideal (mm) | facet depth, real (mm) | lenslets (real) | "
        "vertical jump, ideal (mm) | vertical jump, real (mm) |\n|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (size_t i = 0; i < zs.size(); ++i)
    md += "| " + fmt(zs[i], 1) + " | " + fmt(predictedJump(P, Lideal, D, zs[i]), 3) + " | " + fmt(res[0][i].jump, 3) +
          " | " + fmt(predictedJump(P, Lreal, D, zs[i]), 3) + " | " + fmt(res[1][i].jump, 3) + " | " +
          fmt(predictedJump(P, Leff, D, zs[i]), 3) + " | " +
          fmt(res[0][i].facetDepth, 2) + " | " + fmt(res[1][i].facetDepth, 2) + " | " + std::to_string(res[1][i].lenslets) +
          " | " + fmt(resV[0][i].jump, 3) + " | " + fmt(resV[1][i].jump, 3) + " |\n";
  md += "\n![facet jump vs depth](facet_jump_vs_depth.png)\n\n![apparent facet depth](facet_depth.png)\n\n"
        "Data: `braiding.csv`.\n\n";
  md += "**Verdict.** Ideal lenslets: the zero of the jump and the mean facet depth within ±10% of L, the jumps "
        "within ±20% of B(z). Real lenslets: ±25%, ±35% and ±25% of the same quantities with L = H' + L — their "
        "spherical aberration pulls the focus of the outer zones toward the MLA (full aperture 16.3 mm in the "
        "image-plane study), and an eye looks through every zone of a facet in turn. With L replaced by the real lenslets' measured facet depth (" +
        fmt(Leff, 2) + " mm, their effective image plane for an eye), their jumps follow the same formula within ±15%. " +
        verdictLine(rep.values) +
        "\n\n";
  md += "**Reproduce.**\n\n```\n" + reproduceCommand(rep.study, o) + "\n```\n";
  {
    std::ofstream fo(out.add(mdPath));
    fo << md;
    if (!fo) throw std::runtime_error("cannot write " + mdPath);
  }
  out.commit();
  rep.files = {mdPath, png1, png2, csvPath};
  return rep;
}

}  // namespace inim
