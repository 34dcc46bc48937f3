// inim study braiding: multifaceted braiding. A reconstructed point away from the reference
// image plane L is seen as facets, one per lenslet, that do not line up. Its EIA is synthesised
// (synthesis/) and its light traced from the lit panel pixels through the real MLA (mla/) and the
// panel's cover glass (PanelEmitter::emissionPointPx, as the view simulation does; with the glass
// switched off as the control): per lenslet, where the point appears (projected on its own depth)
// against the eye position.
#include <algorithm>
#include <cmath>

#include "analysis/plot.h"
#include "core/rng.h"
#include "mla_optics/real_mla.h"
#include "studies/cover_glass.h"
#include "studies/studies.h"
#include "studies/study_display.h"
#include "studies/study_pipeline.h"
#include "mla_optics/ideal_mla.h"
#include "studies/study_report.h"

namespace inim {

namespace {

using namespace study_detail;

constexpr float kLambdaNm = 587.56f;  // the trace's wavelength (real MLA and cover glass at n_d)

// A weighted least-squares line v = a + b u: the sums of the weights and of weight x u, v, u^2, u v.
struct LineFit {
  double w = 0, u = 0, v = 0, uu = 0, uv = 0;
  void add(double weight, double x, double y) {
    w += weight, u += weight * x, v += weight * y, uu += weight * x * x, uv += weight * x * y;
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

// The eye's scan: positions E = -60 ... 60 mm in 0.5 mm steps; from each, rays to a grid on the
// MLA plane (x in [-8, 8] mm every 20 um, 5 rows within the centre lenslet row).
constexpr int kEyePositions = 241, kGridX = 801, kGridRows = 5;
constexpr double kEyeStart = -60.0, kEyeStep = 0.5;

// What the eye sees through each lenslet k from each position ie: the luminance weight w and
// the weighted sum of the line-of-sight positions X on the point's plane (index ie * K + k).
struct EyeScan {
  int K = 0;                         // lenslets along the scan
  const std::vector<double>* centre = nullptr;  // their centres along the scan
  std::vector<double> weight, weightedX;
};

// A pinhole eye scanned along x on the plane z = D (or, vertical, along y) looks at the display:
// its rays are traced back through the MLA to the panel, where they pick up the luminance of the
// EIA pixel they land on (x throughput), if it lies in the lenslet's own EI.
EyeScan scanEye(const MlaModel& mla, const PanelEmitter& em, const EiLayout& L, const Image& eia, double zr, double D,
                bool vertical) {
  EyeScan scan;
  // Along x (lenslet columns k) or, vertical, along y (lenslet rows l; y decreases with l).
  scan.K = vertical ? L.eiRows : L.eiCols;
  scan.centre = vertical ? &L.lensY : &L.lensX;
  const int K = scan.K;
  const double P = K > 1 ? std::abs((*scan.centre)[1] - (*scan.centre)[0]) : 1.0;  // lens pitch
  scan.weight.assign(size_t(kEyePositions) * K, 0.0);
  scan.weightedX.assign(size_t(kEyePositions) * K, 0.0);
  for (int ie = 0; ie < kEyePositions; ++ie) {
    const double E = kEyeStart + kEyeStep * ie;
    const Point3 eye(vertical ? 0.0f : float(E), vertical ? float(E) : 0.0f, float(D));
    for (int iy = 0; iy < kGridRows; ++iy)
      for (int ix = 0; ix < kGridX; ++ix) {
        const double mx = -8.0 + 0.02 * ix, my = ((iy + 0.5) / kGridRows - 0.5) * 0.9 * P;
        const double ax = vertical ? my : mx - E, ay = vertical ? mx - E : my;
        const Vec3 dir = glm::normalize(Vec3(float(ax), float(ay), float(-D)));
        Rng rng = Rng::forSample(5, uint64_t(ie) * 100000u + uint64_t(iy) * 10000u + uint64_t(ix));
        PanelArrival a;
        if (!mla.traceToPanel(Ray{eye, dir}, kLambdaNm, rng, a)) continue;
        const int k = vertical ? a.lensletL : a.lensletK;
        if (k < 0 || k >= K) continue;
        // Where the ray meets the emitter: through the cover glass when the emitter models it
        // (PanelEmitter::emissionPointPx, as the view simulation does), else at the landing point.
        Vec2d uv;
        float factor = 0.0f;
        if (!em.emissionPointPx(a.p, a.d, kLambdaNm, uv, factor)) continue;
        const int pcol = int(std::floor(uv.x)), prow = int(std::floor(uv.y));
        const int col = pcol - L.panelCol0, row = prow - L.panelRow0;
        if (col < 0 || row < 0 || col >= L.eiaW || row >= L.eiaH) continue;
        // Only the lenslet's own EI: beyond psi/2 the eye sees the neighbouring EI's copy of the
        // point through it (the flipped repeat), which is not braiding.
        if (vertical ? (row < L.eiRow0[size_t(k)] || row >= L.eiRow0[size_t(k)] + L.eiH)
                     : (col < L.eiCol0[size_t(k)] || col >= L.eiCol0[size_t(k)] + L.eiW))
          continue;
        const double v = lum(eia, pcol, prow) * a.throughput * factor;
        if (!(v > 0.0)) continue;
        const double X = E + (mx - E) * (D - zr) / D;  // the eye's line of sight on the plane z = zr
        scan.weight[size_t(ie) * K + k] += v;
        scan.weightedX[size_t(ie) * K + k] += v * X;
      }
  }
  return scan;
}

// What the eye sees through lenslet k is the point at the luminance-weighted mean X of the
// scan's lines of sight. Per lenslet, a line X = b_k + s_k E over the eye positions where the
// facet shows the whole spot; neighbouring lines compared halfway between their windows give
// the jump, the in-facet slope s the facets' apparent depth (zr - s D) / (1 - s).
FacetResult fitFacets(const EyeScan& scan, double zr, double D) {
  const int K = scan.K;
  const std::vector<double>& centre = *scan.centre;
  FacetResult res;
  // Per lenslet: a line over the eye positions where the facet shows the whole spot (at least
  // 70% of that facet's brightest; nearer the window's ends the lenslet's rim or its EI's edge
  // clips the spot and pulls the apparent position toward the facet's centre).
  std::vector<LineFit> lines(static_cast<size_t>(K));
  std::vector<bool> fitted(static_cast<size_t>(K), false);
  LineFit slopes;
  for (int k = 0; k < K; ++k) {
    double peak = 0.0;
    for (int ie = 0; ie < kEyePositions; ++ie) peak = std::max(peak, scan.weight[size_t(ie) * K + k]);
    if (!(peak > 0.0)) continue;
    LineFit& line = lines[size_t(k)];
    for (int ie = 0; ie < kEyePositions; ++ie) {
      const double v = scan.weight[size_t(ie) * K + k];
      if (v < 0.7 * peak) continue;
      line.add(1.0, kEyeStart + kEyeStep * ie, scan.weightedX[size_t(ie) * K + k] / v);
    }
    if (line.w < 4) continue;
    const double s = line.slope();
    if (!std::isfinite(s)) continue;
    fitted[size_t(k)] = true;
    ++res.lenslets;
    slopes.add(line.w, 0.0, s);
  }
  // The jump between neighbouring facets: both lines at the eye position halfway between their
  // windows (the least extrapolation), X_{k+1}(E) - X_k(E) (lens centres increase with k).
  double jumpSum = 0.0, jumpWeight = 0.0;
  for (int k = 0; k + 1 < K; ++k) {
    if (!fitted[size_t(k)] || !fitted[size_t(k + 1)]) continue;
    const LineFit &a = lines[size_t(k)], &b = lines[size_t(k + 1)];
    const double Em = 0.5 * (a.u / a.w + b.u / b.w), wt = std::min(a.w, b.w);
    jumpSum += wt * (b.at(Em) - a.at(Em)) * (centre[size_t(k + 1)] > centre[size_t(k)] ? 1.0 : -1.0);
    jumpWeight += wt;
  }
  if (!(jumpWeight > 0.0)) return res;
  res.jump = jumpSum / jumpWeight;
  res.slope = slopes.v / slopes.w;
  res.facetDepth = (zr - res.slope * D) / (1.0 - res.slope);
  return res;
}

FacetResult measureFacets(const MlaModel& mla, const PanelEmitter& em, const EiLayout& L, const Image& eia, double zr,
                          double D, bool vertical = false) {
  return fitFacets(scanEye(mla, em, L, eia, zr, D, vertical), zr, D);
}

// Signed facet-to-facet jump predicted for a point placed at depth z, seen by a pinhole eye at D,
// when the facets line up for the target depth z0 and appear at the depth Lf (report: z0 = Lf = L
// for thin lenslets without cover glass).
double predictedJump(double P, double z0, double Lf, double D, double z) {
  return P * (1.0 - z0 / z) * (D - z) / (D - Lf);
}

// The first sign change from - to + among z > 0, interpolated linearly.
double zeroCrossing(const std::vector<double>& z, const std::vector<double>& b) {
  for (size_t i = 1; i < z.size(); ++i)
    if (z[i - 1] > 0.0 && std::isfinite(b[i - 1]) && std::isfinite(b[i]) && b[i - 1] < 0.0 && b[i] >= 0.0)
      return z[i - 1] + (0.0 - b[i - 1]) / (b[i] - b[i - 1]) * (z[i] - z[i - 1]);
  return std::nan("");
}


// Cases: [0] ideal and [1] real lenslets, the display as configured (the panel's cover glass,
// refracted as PanelEmitter does); [2] ideal and [3] real with the cover glass switched off (the
// control). All four see the same synthesised EIA.
constexpr int kCases = 4;
int mlaOf(int c) { return c % 2; }  // 0 ideal, 1 real
bool glassOf(int c) { return c < 2; }
const char* const kMlaName[2] = {"ideal MLA", "real MLA"};
std::string caseName(int c) { return std::string(kMlaName[mlaOf(c)]) + (glassOf(c) ? "" : ", no cover glass"); }

// The display (the prototype's central 31 x 31 lenslets, toed-in for D, rays at g = 4 mm), both
// lenslet arrays, the emitters with and without the glass, and the paraxial predictions.
struct BraidSetup {
  StudyDisplay source;
  Display d;
  EiLayout L;
  double g = 4.0, D = 350.0;
  double f = 0, P = 0, hPrime = 0, Lideal = 0;
  CoverGlassOptics glass;  // at the trace's wavelength
  double gEff = 0, LeffGlass = 0, zGlass = 0;
  std::vector<double> zs;
  // Per case (derived in the report): the lenslets image the panel, seen at the optical gap ge,
  // at Le = ge f / (ge - f) from H' (hp), so the facets appear at Lf = H' + Le; the chief rays
  // rebuild a target placed at z at H' + z ge / g, so the facets line up for the target depth
  // z0 = Le g / ge.
  double z0[kCases] = {}, Lf[kCases] = {}, ge[kCases] = {}, hp[kCases] = {};
  std::unique_ptr<RealMla> real;
  std::unique_ptr<IdealLensletMla> ideal;
  std::unique_ptr<PanelEmitter> emitterGlass, emitterNoGlass;

  const MlaModel& mla(int c) const { return mlaOf(c) == 0 ? static_cast<const MlaModel&>(*ideal) : *real; }
  const PanelEmitter& emitter(int c) const { return glassOf(c) ? *emitterGlass : *emitterNoGlass; }
  double jumpPred(int c, double z) const { return predictedJump(P, z0[c], Lf[c], D, z); }
};

BraidSetup setUp(const StudyOptions& o) {
  BraidSetup setup;
  setup.source = loadStudyDisplay(o);
  setup.d = pipelineDisplay(setup.source.display, 31, 31, setup.g, EiLayoutKind::ToedIn, setup.D);
  setup.L = computeLayout(setup.d);
  setup.f = lensletFocus(setup.d.mla).focalLengthMm, setup.P = setup.d.mla.pitchMm;
  setup.real = RealMla::fromDisplay(setup.d, setup.L, setup.g);
  setup.ideal = std::make_unique<IdealLensletMla>(setup.L, setup.P, setup.f, setup.g);
  setup.Lideal = setup.g * setup.f / (setup.g - setup.f), setup.hPrime = setup.real->rearNodalZ();
  setup.glass = coverGlassOptics(setup.d, kLambdaNm);
  setup.gEff = setup.glass.opticalGap(setup.g);
  setup.LeffGlass = setup.gEff * setup.f / (setup.gEff - setup.f), setup.zGlass = setup.g * setup.f / (setup.gEff - setup.f);
  setup.zs = o.quick ? std::vector<double>{-20, 10, 15, 21, 28, 40}
                 : std::vector<double>{-30, -20, -12, 8, 10, 12.5, 15, 17, 18.5, 20, 21.5, 23.5, 27, 32, 40};
  for (int c = 0; c < kCases; ++c) {
    setup.hp[c] = mlaOf(c) == 1 ? setup.hPrime : 0.0;
    setup.ge[c] = glassOf(c) ? setup.gEff : setup.g;
    const double Le = setup.ge[c] * setup.f / (setup.ge[c] - setup.f);
    setup.z0[c] = Le * setup.g / setup.ge[c];
    setup.Lf[c] = setup.hp[c] + Le;
  }
  setup.emitterGlass = geometryEmitter(setup.d, setup.L, setup.g, true);
  setup.emitterNoGlass = geometryEmitter(setup.d, setup.L, setup.g, false);
  return setup;
}

// Per case, per depth: the facets along x (lenslet columns) and along y (rows); the mean
// apparent facet depth L_m and the target depth z0 = (L_m - H') g / ge it implies.
struct BraidMeasurement {
  std::vector<FacetResult> horizontal[kCases], vertical[kCases];
  double LfMeas[kCases] = {}, z0Meas[kCases] = {};

  static std::vector<double> column(const std::vector<FacetResult>& results, double FacetResult::*field) {
    std::vector<double> v;
    for (const auto& r : results) v.push_back(r.*field);
    return v;
  }
  std::vector<double> jumps(int c) const { return column(horizontal[c], &FacetResult::jump); }
  std::vector<double> verticalJumps(int c) const { return column(vertical[c], &FacetResult::jump); }
  std::vector<double> depths(int c) const { return column(horizontal[c], &FacetResult::facetDepth); }
  // The real lenslets' jumps against the same formula with the facet depth they show: their
  // effective image plane for an eye (spherical aberration).
  double jumpPredMeasured(const BraidSetup& setup, int c, double z) const {
    return predictedJump(setup.P, z0Meas[c], LfMeas[c], setup.D, z);
  }
};

// The value of v at the sampled depth z (NaN when z is not sampled).
double atDepth(const std::vector<double>& zs, const std::vector<double>& v, double z) {
  for (size_t i = 0; i < zs.size(); ++i)
    if (std::abs(zs[i] - z) < 1e-9) return v[i];
  return std::nan("");
}

// Mean apparent facet depth over the depths more than 4 mm from the predicted one (closer, the
// in-facet parallax is ~0 whatever the facets' depth, and the estimate is ill-conditioned).
double meanFacetDepth(const std::vector<double>& zs, const std::vector<double>& depths, double predicted) {
  double sum = 0.0;
  int n = 0;
  for (size_t i = 0; i < zs.size(); ++i)
    if (std::isfinite(depths[i]) && std::abs(zs[i] - predicted) > 4.0) sum += depths[i], ++n;
  return n ? sum / n : std::nan("");
}

BraidMeasurement measure(const BraidSetup& setup) {
  BraidMeasurement m;
  for (double z : setup.zs) {
    // A point: a sphere about one EI pixel's footprint at its depth (p |z| / g), so every EI
    // that sees it lights one or two pixels and its image on L is smaller than a facet.
    const double radius = std::max(0.03, 0.75 * setup.L.pixelMm * std::abs(z) / setup.g);
    const Image eia = synthesizeAt(setup.L, setup.d, emissiveSphereScene(radius, 1.0), z, 1);
    for (int c = 0; c < kCases; ++c) {
      m.horizontal[c].push_back(measureFacets(setup.mla(c), setup.emitter(c), setup.L, eia, z, setup.D));
      m.vertical[c].push_back(measureFacets(setup.mla(c), setup.emitter(c), setup.L, eia, z, setup.D, true));
    }
  }
  for (int c = 0; c < kCases; ++c) {
    m.LfMeas[c] = meanFacetDepth(setup.zs, m.depths(c), setup.Lf[c]);
    m.z0Meas[c] = (m.LfMeas[c] - setup.hp[c]) * setup.g / setup.ge[c];
  }
  return m;
}

// The same tolerances for the display as configured (group 0) and the control (group 1); the
// ideal lenslets' tighter than the real ones' (spherical aberration).
std::vector<StudyValue> judge(const BraidSetup& setup, const BraidMeasurement& m) {
  const double tolZero[2] = {0.10, 0.25}, tolJump[2] = {0.20, 0.35}, tolDepth[2] = {0.10, 0.25};
  auto at = [&](const std::vector<double>& values, double z) { return atDepth(setup.zs, values, z); };
  std::vector<StudyValue> v;
  for (int group = 0; group < 2; ++group) {
    for (int mla = 0; mla < 2; ++mla) {
      const int c = 2 * group + mla;
      const std::string n = caseName(c);
      const auto j = m.jumps(c);
      v.push_back(compare("depth of zero braiding, " + n, zeroCrossing(setup.zs, j), setup.z0[c], tolZero[mla]));
      v.push_back(compare("facet jump at z = 40 mm, " + n, at(j, 40.0), setup.jumpPred(c, 40.0), tolJump[mla]));
      v.push_back(compare("facet jump at z = 10 mm, " + n, at(j, 10.0), setup.jumpPred(c, 10.0), tolJump[mla]));
      v.push_back(compare("facet jump at z = -20 mm (virtual), " + n, at(j, -20.0), setup.jumpPred(c, -20.0), tolJump[mla]));
      v.push_back(compare("apparent depth of the facets (mean), " + n, m.LfMeas[c], setup.Lf[c], tolDepth[mla]));
    }
    // The same along y (eye scanned vertically, lenslet rows).
    for (int mla = 0; mla < 2; ++mla) {
      const int c = 2 * group + mla;
      const auto jv = m.verticalJumps(c);
      const std::string n = caseName(c);
      v.push_back(compare("facet jump at z = 40 mm, vertical, " + n, at(jv, 40.0), setup.jumpPred(c, 40.0), tolJump[mla]));
      v.push_back(compare("facet jump at z = -20 mm, vertical, " + n, at(jv, -20.0), setup.jumpPred(c, -20.0), tolJump[mla]));
    }
    const int c = 2 * group + 1;
    const std::string sfx = group == 0 ? "" : ", no cover glass";
    v.push_back(compare("facet jump at z = 40 mm, real MLA, L = its facet depth" + sfx, at(m.jumps(c), 40.0),
                        m.jumpPredMeasured(setup, c, 40.0), 0.15));
    v.push_back(compare("facet jump at z = 10 mm, real MLA, L = its facet depth" + sfx, at(m.jumps(c), 10.0),
                        m.jumpPredMeasured(setup, c, 10.0), 0.15));
  }
  return v;
}

void writeCsvData(ReportWriter& w, const BraidSetup& setup, const BraidMeasurement& m) {
  std::vector<std::vector<std::string>> rows;
  for (int c = 0; c < kCases; ++c)
    for (size_t i = 0; i < setup.zs.size(); ++i) {
      const FacetResult &h = m.horizontal[c][i], &v = m.vertical[c][i];
      rows.push_back({mlaOf(c) == 0 ? "ideal" : "real", glassOf(c) ? "yes" : "no", csvNumber(setup.zs[i]),
                      csvNumber(setup.jumpPred(c, setup.zs[i])), csvNumber(h.jump), csvNumber(h.slope),
                      csvNumber(h.facetDepth), std::to_string(h.lenslets), csvNumber(v.jump), csvNumber(v.facetDepth)});
    }
  w.csv("braiding.csv",
        {"mla", "cover_glass", "z_mm", "jump_predicted_mm", "jump_measured_mm", "in_facet_parallax_slope",
         "apparent_facet_depth_mm", "lenslets", "jump_vertical_mm", "apparent_facet_depth_vertical_mm"},
        rows);
}

void writePlots(ReportWriter& w, const BraidSetup& setup, const BraidMeasurement& m) {
  Plot p;
  p.title = "Braiding: facet-to-facet jump of a point (eye at " + fixed(setup.D, 0) + " mm)";
  p.x.title = "point depth z (mm)";
  p.y.title = "jump (mm on the point's plane)";
  for (int c = 0; c < kCases; ++c) {
    std::vector<double> zc, jc;
    for (int i = 0; i <= 400; ++i) {
      const double z = setup.zs.front() + (setup.zs.back() - setup.zs.front()) * i / 400.0;
      zc.push_back(z);
      jc.push_back(std::abs(z) < 4.0 ? std::nan("") : setup.jumpPred(c, z));
    }
    // (the real lenslets' paraxial curve differs from the ideal one's only through H': one entry)
    PlotSeries predicted{
        mlaOf(c) == 0 ? std::string("B(z), ") + (glassOf(c) ? "glass" : "no glass") + ", z0 = " + fixed(setup.z0[c], 2)
                      : std::string(),
        zc, jc};
    predicted.markers = false;
    predicted.dash = mlaOf(c) == 0 ? 0.0 : 8.0;
    predicted.color = plotPalette(c);
    PlotSeries measured{std::string(mlaOf(c) == 0 ? "ideal" : "real") + (glassOf(c) ? ", glass" : ", no glass"), setup.zs,
                        m.jumps(c)};
    measured.line = false;
    measured.color = plotPalette(c);
    p.series.push_back(predicted);
    p.series.push_back(measured);
  }
  p.y.min = -3.0, p.y.max = 3.5;
  p.markers.push_back({setup.z0[0], "z_g"});
  p.markers.push_back({setup.Lideal, "L"});
  p.hMarkers.push_back({0.0, "", Vec3(0.4f, 0.4f, 0.4f), 3.0});
  w.plot("facet_jump_vs_depth.png", p);

  Plot q;
  q.title = "Apparent depth of the facets (in-facet parallax)";
  q.x.title = "point depth z (mm)";
  q.y.title = "facet depth (mm)";
  for (int c = 0; c < kCases; ++c) {
    PlotSeries traced{"traced, " + caseName(c), setup.zs, m.depths(c)};
    traced.line = false;
    traced.color = plotPalette(c);
    q.series.push_back(traced);
  }
  PlotSeries identity{"z (no braiding)", {setup.zs.front(), setup.zs.back()}, {setup.zs.front(), setup.zs.back()}};
  identity.markers = false;
  identity.dash = 6.0;
  q.series.push_back(identity);
  q.hMarkers.push_back({setup.Lf[0], "L_eff " + fixed(setup.Lf[0], 2)});
  q.hMarkers.push_back({setup.Lf[3], "H'+L " + fixed(setup.Lf[3], 2)});
  w.plot("facet_depth.png", q);
}

std::string predictionText(const BraidSetup& setup) {
  std::string t =
      "(paraxial). *Thin lenslets, no cover glass*: focal f at gap g, image plane L = g f / (g − f). A point at (X, z) "
      "is written into EI c (lens centre x_c) at the panel pixel on the pinhole ray through x_c. Lenslet c images that "
      "pixel to the plane L, at Q_c = x_c + (X − x_c) L / z: the pinhole (chief) ray still passes through (X, z), but "
      "the light of the facet comes from Q_c. An eye at (E, D) that sees the point through lenslet c sees it in the "
      "direction of Q_c; projected on the point's own plane z it appears at x = E + (Q_c − E)(D − z)/(D − L). So "
      "inside a facet the point moves with the eye as if it sat at depth L (in-facet parallax dx/dE = "
      "(z − L)/(D − L)), and between neighbouring facets (x_c → x_c + P) the facet lines are offset by\n\n"
      "    B(z) = P (1 − L/z) (D − z) / (D − L)   (mm on the point's plane)\n\n"
      "which is 0 at z = L, negative between the MLA and L, positive beyond L, and larger than P behind the MLA "
      "(z < 0: the facets are inverted). The offset equals the sweep inside one facet, so on average the point stays "
      "where it should (each lenslet's full bundle is centred on the pinhole ray through (X, z)): braiding is what an "
      "eye with a pupil smaller than a facet's spacing sees, point facets jumping by B as the eye moves.\n\n";
  t += "*In general* (as in the depth-sharpness study): the lenslets see the panel at an optical gap g_e and image it "
       "at L_e = g_e f / (g_e − f) from their viewer-side principal plane H' (z = H'; 0 for thin lenslets, " +
       fixed(setup.hPrime, 3) + " mm for the real ones), so the facets appear at L_f = H' + L_e. The synthesis's pinhole "
       "rays run in air at g through the lens centres on z = 0; the lenslets' chief rays leave H' with the slope "
       "g / g_e times the pinhole ray's, so they rebuild a point placed at (X, z) at (X, H' + z g_e / g), and the "
       "facets line up for the target depth z_0 = L_e g / g_e. Then Q_c = x_c + (X − x_c) z_0 / z on the plane L_f, "
       "and\n\n"
       "    B(z) = P (1 − z_0/z) (D − z) / (D − L_f),   in-facet parallax dx/dE = (z − L_f)/(D − L_f)\n\n"
       "(the apparent facet depth measured below is L_f). Without cover glass g_e = g: z_0 = L = " + fixed(setup.Lideal, 2) +
       " mm for thin and thick lenslets alike, L_f = L (ideal) or H' + L = " + fixed(setup.hPrime + setup.Lideal, 2) +
       " mm (real). With the panel's cover glass (" +
       (setup.glass.present ? fixed(setup.glass.thicknessMm, 2) + " mm of " + setup.glass.material + ", n = " + fixed(setup.glass.n, 4) +
                              " at " + fixed(kLambdaNm, 2) + " nm, the trace's wavelength"
                        : std::string("none in this display")) +
       "), the panel is seen t (1 − 1/n) nearer: g_e = g_eff = " + fixed(setup.gEff, 4) + " mm, L_eff = " +
       fixed(setup.LeffGlass, 2) + " mm, and the facets line up for **z_g = g f / (g_eff − f) = " + fixed(setup.zGlass, 2) +
       " mm** (ideal and real), where they appear at " + fixed(setup.Lf[0], 2) + " mm (ideal) and H' + L_eff = " +
       fixed(setup.Lf[1], 2) + " mm (real). This is the prediction for the display as configured. A generation gap "
       "g_gen ≠ g (the paper's " + fixed(setup.source.display.generationGapMm, 1) + " mm against 4 mm) writes a point at "
       "z_s into exactly the pixels that g_gen = g writes for z = z_s g / g_gen, so it is the same EIA with the point "
       "placed at z = z_s g / g_gen: the prediction holds with that z, and needs no separate run. Here P = " +
       fixed(setup.P, 3) + " mm, f = " + fixed(setup.f, 4) + " mm, g = " + fixed(setup.g, 1) + " mm, D = " + fixed(setup.D, 0) + " mm.";
  return t;
}

std::string methodText() {
  return "Scene: an emissive sphere on the axis at depth z, of radius 0.75 p |z| / g (at least 30 µm; p the panel "
         "pixel): about one EI pixel's footprint at that depth, so each EI that sees it lights one or two pixels. "
         "Display: the paper prototype cropped to its central 31 × 31 lenslets, toed-in layout for D = 350 mm "
         "(pinholes on the lens centres), rays generated at g = 4 mm; `synthesizeEia` (1 spp) gives the EIA. A pinhole "
         "eye on the plane z = D scans x from −60 to 60 mm in 0.5 mm steps; from each position, rays to a grid on the "
         "MLA plane (x ∈ [−8, 8] mm every 20 µm, 5 rows across the centre lenslet row) are traced back to the panel "
         "through the MLA (`MlaModel::traceToPanel`: `IdealLensletMla`, and the real MLA with stochastic Fresnel, both "
         "at 587.56 nm) to the emitting plane z = −g, and from there to the emitter by `PanelEmitter::emissionPointPx`, "
         "the view simulation's own code: refracted at the cover glass's top (z = −g + t, Snell at the glass index at "
         "587.56 nm) and carried down through the plate to z = −g, or, for the control, with the emitter's cover glass "
         "switched off (`EmitterSettings::coverGlass = false`; the landing point itself). Each ray takes the luminance "
         "of the EIA pixel it meets there (the pixel as a uniform emitter) × throughput × the emitter's glass "
         "transmittance factor, counted only when that pixel belongs to the lenslet's own EI (beyond ψ/2 the eye sees "
         "the neighbouring EI's copy of the point, the flipped repeat, which is not braiding). Through lenslet k, the "
         "eye sees the point at the luminance-weighted mean of its lines of sight on the plane z. Per lenslet, over "
         "the eye positions where the facet shows the whole spot (at least 70% of its own peak; nearer its window's "
         "ends the lenslet's rim or its EI's edge clips the spot and pulls the apparent position toward the facet's "
         "centre), a straight line X = b_k + s_k E. The jump between neighbouring facets is X_{k+1}(E) − X_k(E) at "
         "the eye position halfway between their windows (averaged over the pairs), and the mean in-facet slope s "
         "gives the apparent depth of the facets, (z − s D)/(1 − s) (L_f when the prediction holds; averaged over the "
         "depths more than 4 mm from the predicted L_f). The same scan along y (eye moving vertically, lenslet rows) "
         "checks the vertical facets.";
}

// Per group (with the glass, the control without it): the predictions and the measured facets per depth.
std::string resultTables(const BraidSetup& setup, const BraidMeasurement& m) {
  std::string t;
  for (int group = 0; group < 2; ++group) {
    const int ci = 2 * group, cr = 2 * group + 1;
    t += group == 0 ? "The display as configured (with the cover glass): z_0 = " + fixed(setup.z0[ci], 2) + " mm, L_f = " +
                          fixed(setup.Lf[ci], 2) + " (ideal) / " + fixed(setup.Lf[cr], 2) + " mm (real).\n\n"
                    : "\nControl, cover glass switched off: z_0 = " + fixed(setup.z0[ci], 2) + " mm, L_f = " +
                          fixed(setup.Lf[ci], 2) + " (ideal) / " + fixed(setup.Lf[cr], 2) + " mm (real).\n\n";
    t += "| z (mm) | predicted jump, ideal (mm) | measured, ideal (mm) | predicted, real (mm) | measured, real (mm) | "
         "predicted, real, L_f = " + fixed(m.LfMeas[cr], 2) + " (mm) | facet depth, ideal (mm) | facet depth, real (mm) | "
         "lenslets (real) | vertical jump, ideal (mm) | vertical jump, real (mm) |\n"
         "|---|---|---|---|---|---|---|---|---|---|---|\n";
    for (size_t i = 0; i < setup.zs.size(); ++i) {
      const double z = setup.zs[i];
      const FacetResult &hi = m.horizontal[ci][i], &hr = m.horizontal[cr][i];
      t += "| " + fixed(z, 1) + " | " + fixed(setup.jumpPred(ci, z), 3) + " | " + fixed(hi.jump, 3) + " | " +
           fixed(setup.jumpPred(cr, z), 3) + " | " + fixed(hr.jump, 3) + " | " + fixed(m.jumpPredMeasured(setup, cr, z), 3) +
           " | " + fixed(hi.facetDepth, 2) + " | " + fixed(hr.facetDepth, 2) + " | " + std::to_string(hr.lenslets) +
           " | " + fixed(m.vertical[ci][i].jump, 3) + " | " + fixed(m.vertical[cr][i].jump, 3) + " |\n";
    }
  }
  return t + "\n![facet jump vs depth](facet_jump_vs_depth.png)\n\n![apparent facet depth](facet_depth.png)\n\n"
             "Data: `braiding.csv`.\n\n";
}

std::string discussionText(const BraidSetup& setup, const BraidMeasurement& m) {
  const double zeroGlass = zeroCrossing(setup.zs, m.jumps(0)), zeroNo = zeroCrossing(setup.zs, m.jumps(2));
  // The gap that would put the measured depth where it is: z_0 = g f / (g_e - f), L_f = g_e f / (g_e - f).
  const double f = setup.f, g = setup.g;
  return "With the cover glass the ideal facets line up at " + fixed(zeroGlass, 2) + " mm (z_g = " + fixed(setup.z0[0], 2) +
         " mm) and appear at " + fixed(m.LfMeas[0], 2) + " mm (L_eff = " + fixed(setup.Lf[0], 2) + " mm); without it at " +
         fixed(zeroNo, 2) + " mm and " + fixed(m.LfMeas[2], 2) + " mm (L = " + fixed(setup.Lideal, 2) +
         " mm). An earlier version of this study read the EIA pixel at the landing point on z = −g, without the glass, "
         "and compared everything with L: its numbers were those of the control (the depth-sharpness study finds the "
         "same with its slanted edge: the ideal lenslets sharpest near z_g with the glass, near L without). The "
         "ideal lenslets fall short of the paraxial depths in both cases, by more with the glass; expressed as an "
         "optical gap (z_0 = g f / (g_e − f), L_f = g_e f / (g_e − f)) both shortfalls are small gap offsets of similar "
         "size, " + signedFixed((g * f / zeroNo + f) - g, 3) + " / " + signedFixed((g * f / zeroGlass + f) - setup.gEff, 3) +
         " mm (zero without / with the glass) and " + signedFixed(m.LfMeas[2] * f / (m.LfMeas[2] - f) - g, 3) + " / " +
         signedFixed(m.LfMeas[0] * f / (m.LfMeas[0] - f) - setup.gEff, 3) +
         " mm (facet depth), which the glass amplifies because the depth is about twice as sensitive to the gap at "
         "g_eff − f = " + fixed(setup.gEff - f, 3) + " mm as at g − f = " + fixed(g - f, 3) + " mm; its cause (the spot's "
         "pixel quantisation, the fit windows) is not isolated here. For the thick real lenslets the paraxial zero of "
         "the jump is z_0 = L (not H' + L, as an earlier version predicted): their chief rays rebuild the point H' "
         "further out, where they also image the panel. The real lenslets' spherical aberration pulls the focus of "
         "their outer zones toward the MLA (full aperture 16.3 mm in the image-plane study, without glass), and an eye "
         "looks through every zone of a facet in turn: their facets appear at " + fixed(m.LfMeas[1], 2) +
         " mm with the glass (paraxial " + fixed(setup.Lf[1], 2) + ") and " + fixed(m.LfMeas[3], 2) +
         " mm without (paraxial " + fixed(setup.Lf[3], 2) + "). With that measured facet depth L_m in place of L_f, and "
         "z_0 = (L_m − H') g / g_e, their jumps follow the same formula.";
}

std::vector<std::string> writeReport(const StudyOptions& o, const BraidSetup& setup, const BraidMeasurement& m,
                                     const std::vector<StudyValue>& values) {
  ReportWriter w("braiding", o, "multifaceted braiding");
  w.section("What",
            "A reconstructed point away from the depth where the facets line up is not one point: each lenslet shows its "
            "own facet of it, and neighbouring facets do not line up (\"braided\"). This study measures that "
            "misalignment for a point at depths in front of and behind the MLA, with the EIA synthesised from the "
            "scene, seen by a pinhole eye through the ideal (thin) and the real (refracting) lenslets — for the display "
            "as configured (the panel's cover glass included, as the view simulation models it) and, as the control, "
            "with the cover glass switched off.");
  w.text("**Prediction** " + predictionText(setup) + "\n\n");
  w.section("Method", methodText());
  w.results(values, "mm");
  w.text(resultTables(setup, m));
  writeCsvData(w, setup, m);
  writePlots(w, setup, m);
  w.section("Discussion", discussionText(setup, m));
  w.verdict("ideal lenslets: the zero of the jump within ±10% of z_0, the mean facet depth within ±10% of L_f, the "
            "jumps within ±20% of B(z); real lenslets: ±25%, ±25% and ±35% of the same paraxial quantities "
            "(spherical aberration), and their jumps within ±15% of B(z) with their own measured facet depth; the same "
            "tolerances for the display as configured and for the control",
            values);
  return w.commit();
}

}  // namespace

StudyReport runBraiding(const StudyOptions& o) {
  const BraidSetup setup = setUp(o);
  const BraidMeasurement m = measure(setup);
  StudyReport rep = makeReport("braiding", judge(setup, m));
  rep.files = writeReport(o, setup, m, rep.values);
  return rep;
}

}  // namespace inim
