// inim study depth-sharpness: a slanted-edge target at a sweep of depths, its EIA synthesised
// (synthesis/) at g = 4 mm, the display seen through the real (and the ideal) MLA by a thin-lens
// camera focused on the target (view/): the edge MTF50 against depth, sharpest near the
// reference image plane L = g f / (g - f) (DESIGN.md 4b).
#include <algorithm>
#include <cmath>
#include <complex>
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

constexpr double kEdgeDeg = 30.0;  // slanted edge, tilted clockwise from vertical (texture.h)

struct EdgeResult {
  double mtf50 = std::nan("");  // cycles/mm on the target plane
  std::vector<double> esfD, esf;
};

// Slanted-edge MTF50 (ISO 12233 style): pixels projected on the edge normal, binned at 0.02 mm
// (the edge crosses the pixel grid, so the bins are super-resolved), ESF -> LSF (difference,
// Hann window) -> |DFT| normalised at 0 -> first 50% crossing.
EdgeResult edgeMtf50(const Image& img, const CameraModel& cam, double z) {
  const double a = kEdgeDeg * M_PI / 180.0, h = 0.02, half = 2.4;
  const int nb = int(std::lround(2.0 * half / h));
  std::vector<double> sum(size_t(nb), 0.0), cnt(size_t(nb), 0.0);
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) {
      const glm::dvec2 p = pixelOnPlane(cam, x, y, z);
      const double d = p.x * std::cos(a) + p.y * std::sin(a);
      const int b = int(std::floor((d + half) / h));
      if (b < 0 || b >= nb) continue;
      sum[size_t(b)] += lum(img, x, y);
      cnt[size_t(b)] += 1.0;
    }
  EdgeResult r;
  for (int b = 0; b < nb; ++b) {
    r.esfD.push_back(-half + (b + 0.5) * h);
    r.esf.push_back(cnt[size_t(b)] > 0 ? sum[size_t(b)] / cnt[size_t(b)] : std::nan(""));
  }
  // Fill empty bins from their neighbours.
  for (int b = 0; b < nb; ++b)
    if (!std::isfinite(r.esf[size_t(b)])) {
      int l = b - 1, u = b + 1;
      while (l >= 0 && !std::isfinite(r.esf[size_t(l)])) --l;
      while (u < nb && !std::isfinite(r.esf[size_t(u)])) ++u;
      r.esf[size_t(b)] = l >= 0 && u < nb ? 0.5 * (r.esf[size_t(l)] + r.esf[size_t(u)])
                         : l >= 0         ? r.esf[size_t(l)]
                         : u < nb         ? r.esf[size_t(u)]
                                          : 0.0;
    }
  std::vector<double> lsf(size_t(nb - 1));
  for (int b = 0; b + 1 < nb; ++b) {
    const double w = 0.5 - 0.5 * std::cos(2.0 * M_PI * (b + 0.5) / (nb - 1));
    lsf[size_t(b)] = (r.esf[size_t(b + 1)] - r.esf[size_t(b)]) * w;
  }
  auto mtf = [&](double f) {
    std::complex<double> s(0.0, 0.0);
    for (size_t i = 0; i < lsf.size(); ++i) s += lsf[i] * std::polar(1.0, -2.0 * M_PI * f * (i + 1) * h);
    return std::abs(s);
  };
  const double m0 = mtf(0.0);
  if (!(m0 > 0.0)) return r;
  double prevF = 0.0, prev = 1.0;
  for (int i = 1; i <= 2000; ++i) {
    const double f = 0.01 * i, m = mtf(f) / m0;
    if (m < 0.5) {
      r.mtf50 = prevF + (prev - 0.5) / (prev - m) * (f - prevF);
      break;
    }
    prevF = f, prev = m;
  }
  return r;
}

// The sharpest depth: parabola through the best sample and its two neighbours.
double peakDepth(const std::vector<double>& z, const std::vector<double>& v) {
  size_t b = 0;
  for (size_t i = 1; i < v.size(); ++i)
    if (v[i] > v[b]) b = i;
  if (b == 0 || b + 1 >= v.size()) return z[b];
  const double x0 = z[b - 1], x1 = z[b], x2 = z[b + 1], y0 = v[b - 1], y1 = v[b], y2 = v[b + 1];
  const double d1 = (y1 - y0) / (x1 - x0), d2 = (y2 - y1) / (x2 - x1), c = (d2 - d1) / (x2 - x0);
  if (!(c < 0.0)) return x1;
  const double xm = 0.5 * (x0 + x1) - d1 / (2.0 * c);
  return std::clamp(xm, x0, x2);
}

// The centre of the sharp band: the contiguous run of depths around the maximum where the
// curve stays at or above `frac` of it (midpoint of its ends).
double bandCentre(const std::vector<double>& z, const std::vector<double>& v, double frac) {
  size_t b = 0;
  for (size_t i = 1; i < v.size(); ++i)
    if (v[i] > v[b]) b = i;
  size_t lo = b, hi = b;
  while (lo > 0 && v[lo - 1] >= frac * v[b]) --lo;
  while (hi + 1 < v.size() && v[hi + 1] >= frac * v[b]) ++hi;
  return 0.5 * (z[lo] + z[hi]);
}

}  // namespace

StudyReport runDepthSharpness(const StudyOptions& o) {
  const std::string displayPath = o.displayPath.empty() ? defaultDisplayPath() : o.displayPath;
  const double g = 4.0, D = 350.0;
  Display d = cropDisplay(displayPath, 25, 25, g, EiLayoutKind::ToedIn, D);
  d.reconstructionGapMm = g;
  EiLayout L = computeLayout(d);
  const double f = lensletFocus(d.mla).focalLengthMm, P = d.mla.pitchMm;
  auto probe = makeRealMla(d, L, g);
  const auto* realProbe = dynamic_cast<const RealMla*>(probe.get());
  const double hPrime = realProbe ? realProbe->rearNodalZ() : 0.0;
  const double Lideal = g * f / (g - f), Lreal = hPrime + Lideal;

  const std::vector<double> zs = o.quick ? std::vector<double>{-8, 6, 12, 16, 19, 22, 26, 34}
                                         : std::vector<double>{-15, -8, -3, 3, 6, 9, 12, 14, 16, 18, 19.5,
                                                               21, 23, 25, 28, 32, 38, 45};
  const int W = o.quick ? 100 : 160, spp = o.quick ? 12 : 32;
  const double sample = o.quick ? 0.06 : 0.04;
  const CameraDescription& camDesc = loadCameraDescription("alvium-1800-u-500c");
  const Json scene = litRectangleScene(
      12.0, 12.0, Json{{"type", "slanted_edge"}, {"angle_deg", kEdgeDeg}, {"background", 0.8}, {"ink", 0.05}});

  std::vector<double> mReal, mIdeal;
  std::vector<Image> strip;
  std::vector<double> stripZ;
  for (double z : zs) {
    const Image eia = synthesizeAt(L, d, scene, z, 1);
    auto cam = axialThinLens(D, z, W, W, sample);
    ViewSettings vs;
    vs.spp = spp;
    vs.progress = false;
    vs.seed = 7;
    for (MlaKind kind : {MlaKind::Real, MlaKind::Ideal}) {
      DisplayModel dm = makeDisplayModel(d, L, eia, "(synthesised)", kind, g);
      const ViewResult v = renderView(*cam, camDesc.sensor, *dm.mla, *dm.panel, dm.area, vs);
      const EdgeResult e = edgeMtf50(v.image, *cam, z);
      (kind == MlaKind::Real ? mReal : mIdeal).push_back(e.mtf50);
      if (kind == MlaKind::Real && (std::abs(z - 3.0) < 1e-9 || std::abs(z - 19.5) < 1e-9 || std::abs(z - 38.0) < 1e-9 ||
                                    std::abs(z - 6.0) < 1e-9 || std::abs(z - 19.0) < 1e-9 || std::abs(z - 34.0) < 1e-9)) {
        strip.push_back(v.image);
        stripZ.push_back(z);
      }
    }
  }
  const double zReal = peakDepth(zs, mReal), zIdeal = peakDepth(zs, mIdeal);
  const double bReal = bandCentre(zs, mReal, 0.7), bIdeal = bandCentre(zs, mIdeal, 0.7);

  StudyReport rep;
  rep.study = "depth-sharpness";
  rep.values = {compare("sharpest depth (MTF50 maximum), real MLA", zReal, Lreal, 0.25),
                compare("centre of the sharp band (MTF50 >= 70% of max), real MLA", bReal, Lreal, 0.25)};
  rep.pass = allPass(rep.values);

  OutputSet out;
  const fs::path dir(o.outDir);
  const std::string mdPath = (dir / "report.md").string(), csvPath = (dir / "mtf50_vs_depth.csv").string(),
                    pngPath = (dir / "mtf50_vs_depth.png").string(), viewsPath = (dir / "views.png").string();
  {
    std::vector<std::vector<std::string>> rows;
    for (size_t i = 0; i < zs.size(); ++i) rows.push_back({csvNumber(zs[i]), csvNumber(mReal[i]), csvNumber(mIdeal[i])});
    writeCsv(out.add(csvPath), {"z_mm", "mtf50_cyc_per_mm_real_mla", "mtf50_cyc_per_mm_ideal_mla"}, rows);
  }
  {
    Plot p;
    p.title = "Slanted edge at depth z: MTF50 on the target plane (g = 4 mm)";
    p.x.title = "target depth z (mm, + in front of the MLA)";
    p.y.title = "MTF50 (cycles/mm)";
    p.y.min = 0.0;
    PlotSeries a{"real MLA", zs, mReal};
    PlotSeries b{"ideal MLA", zs, mIdeal};
    b.dash = 8.0;
    p.series = {a, b};
    p.markers.push_back({Lreal, "H'+L " + fmt(Lreal, 2)});
    p.markers.push_back({0.0, "MLA", Vec3(0.4f, 0.4f, 0.4f), 3.0});
    writePlot(p, out.add(pngPath));
  }
  {
    // The real-MLA views at three depths, side by side, normalised to their 99th percentile.
    const int gap = 4, n = int(strip.size());
    Image m(n * W + (n - 1) * gap, W, {"R", "G", "B"});
    for (int i = 0; i < n; ++i) {
      std::vector<float> v(strip[size_t(i)].data);
      std::vector<float> s = v;
      std::nth_element(s.begin(), s.begin() + long(0.99 * double(s.size() - 1)), s.end());
      const float top = std::max(1e-12f, s[size_t(0.99 * double(s.size() - 1))]);
      for (int y = 0; y < W; ++y)
        for (int x = 0; x < W; ++x)
          for (int c = 0; c < 3; ++c)
            m.at(i * (W + gap) + x, y, c) = std::pow(std::clamp(strip[size_t(i)].at(x, y, c) / top, 0.0f, 1.0f), 1.0f / 2.2f);
    }
    writeImage(m, out.add(viewsPath));
  }

  std::string md;
  md += "# Study: sharpness against depth\n\n";
  md += "**What.** How sharp the display reconstructs a resolution target as the target moves in depth, through the "
        "whole pipeline: the EIA is synthesised from the scene (orthoscopic synthesis, pinhole display rays at "
        "g = 4 mm), shown on the panel's RGB subpixels behind the MLA at g = 4 mm, and seen by a camera that "
        "focuses on the target (as a viewer accommodates on the image).\n\n";
  md += "**Prediction.** A lenslet images the panel sharply on the reference image plane, L = g f / (g − f) in front "
        "of it (DESIGN.md 4b): display `" + displayPath + "`, f = " + fmt(f, 4) + " mm, P = " + fmt(P, 3) +
        " mm, g = 4 mm, so L = " + fmt(Lideal, 2) + " mm for the ideal (thin) lenslets at z = 0 and H' + L = " +
        fmt(Lreal, 2) + " mm for the real plano-convex lenslets (viewer-side principal plane H' at z = " +
        fmt(hPrime, 3) + " mm; the image-plane study). Only on that plane do the lenslets' images of the EI pixels "
        "line up into one image; a target elsewhere is seen as facets (one per lenslet) that are defocused by "
        "≈ P |z − L| / L and misaligned (braiding study), so the reconstruction is sharpest at z ≈ L and falls off "
        "on both sides.\n\n";
  md += "**Method.** Scene: a 12 × 12 mm slanted-edge target (edge " + fmt(kEdgeDeg, 0) + "° from vertical through its centre — steep "
        "enough that, over the camera's field, the edge crosses several lenslet columns and rows, so the facets' "
        "misalignment shows as blur of the edge instead of depending on where the edge happens to sit; reflectance "
        "0.8 / 0.05, lit by a distant light so its radiance is exact) placed at depth z by the placement "
        "translation. Display: the paper prototype cropped to its central 25 × 25 lenslets, rays generated at "
        "g = 4 mm with the toed-in layout for D = 350 mm (the pinholes on the physical lens centres, so synthesis "
        "and display share the lenslet geometry; the parallel layout's EI/lens pitch mismatch is the subject of the "
        "telecentric study). `synthesizeEia` (1 spp) gives the EIA; `renderView` shows it through the real "
        "refracting MLA (and the ideal thin-lens MLA, `--mla ideal`) at g = 4 mm, with the panel's subpixels, seen by "
        "a thin-lens camera 350 mm away (f = 12 mm, f/4: the 3 mm pupil of the paper's camera stand-in) focused on "
        "the target plane, " + std::to_string(W) + " × " + std::to_string(W) + " px of " + fmt(sample * 1000.0, 0) +
        " µm on the target, " + std::to_string(spp) + " spp. Sharpness: ISO 12233-style slanted-edge MTF — pixels "
        "projected (chief ray) onto the target plane and onto the edge normal, binned at 20 µm, ESF → LSF (Hann "
        "window) → |DFT|; MTF50 in cycles per mm on the target. The sharpest depth is the vertex of the parabola "
        "through the best sample and its neighbours.\n\n";
  md += "**Result.**\n\n" + valuesTable(rep.values, "mm") + "\n";
  md += "Ideal lenslets (no verdict, see the discussion): MTF50 maximum at " + fmt(zIdeal, 2) + " mm, sharp-band centre " +
        fmt(bIdeal, 2) + " mm, against L = " + fmt(Lideal, 2) + " mm.\n\n";
  md += "| z (mm) | MTF50 real MLA (cyc/mm) | MTF50 ideal MLA (cyc/mm) |\n|---|---|---|\n";
  for (size_t i = 0; i < zs.size(); ++i)
    md += "| " + fmt(zs[i], 1) + " | " + fmt(mReal[i], 3) + " | " + fmt(mIdeal[i], 3) + " |\n";
  md += "\n![MTF50 vs depth](mtf50_vs_depth.png)\n\n";
  md += "Real-MLA views (target plane, " + fmt(W * sample, 1) + " mm wide) at z = ";
  for (size_t i = 0; i < stripZ.size(); ++i) md += (i ? ", " : "") + fmt(stripZ[i], 1);
  md += " mm:\n\n![views](views.png)\n\nData: `mtf50_vs_depth.csv`.\n\n";
  md += "**Discussion.** Through the real lenslets the edge is sharpest near H' + L, as predicted, and falls off "
        "steeply on both sides: toward the MLA each lenslet shows a magnified piece of the target and the edge breaks "
        "into lenslet-sized steps (views at 3 and 6 mm); beyond L the facets are misaligned by the braiding jump "
        "P (1 − L/z)(D − z)/(D − L) (braiding study) and the edge frays; behind the MLA (virtual target) the facets "
        "are inverted and the sharpness is lowest. **Not as predicted:** through the ideal (aberration-free) "
        "lenslets the MTF50 does not peak at L = " + fmt(Lideal, 2) + " mm but stays on a plateau from about L to "
        "28 mm, with its maximum at " + fmt(zIdeal, 1) + " mm. The braiding study shows that the ideal lenslets' "
        "facets do line up at 18.4 mm, so something other than braiding limits the edge near L there; the views "
        "show the panel's pixel grid and black matrix imaged sharply by the ideal lenslets at L, and each facet "
        "quantises the edge to its own EI's pixel phase (the EI pitch is not a whole number of pixels), a jaggedness "
        "of about one magnified pixel (p L / g = " + fmt(d.panel.pixelPitchMm * Lideal / g, 2) + " mm) at every depth. Which of "
        "these flattens the ideal curve has not been isolated; the ideal-MLA numbers are reported, not judged.\n\n";
  md += "**Verdict** (the real lenslets' sharpest depth, and the centre of the band of depths where MTF50 stays "
        "within 70% of its maximum, within ±25% of H' + L: the real lenslets' spherical aberration pulls the best "
        "focus toward the MLA, to 16.3 mm at full aperture in the image-plane study and to an effective 17.0 mm for "
        "an eye in the braiding study; the depth step near L is 1.5-2 mm, 8-10%): " + verdictLine(rep.values) + "\n\n";
  md += "**Reproduce.**\n\n```\n" + reproduceCommand(rep.study, o) + "\n```\n";
  {
    std::ofstream fo(out.add(mdPath));
    fo << md;
    if (!fo) throw std::runtime_error("cannot write " + mdPath);
  }
  out.commit();
  rep.files = {mdPath, pngPath, csvPath, viewsPath};
  return rep;
}

}  // namespace inim
