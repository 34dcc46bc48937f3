#include "display/display_info.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/format.h"
#include "display/cover_glass.h"
#include "display/stack_first_order.h"
#include "spectral/dispersion.h"

namespace inim {

namespace {

double deg(double rad) { return rad * 180.0 / kPiD; }

std::optional<double> convergence(double g, double P, double pEi) {
  double dp = pEi - P;
  if (std::abs(dp) <= 1e-12 * std::max(P, pEi)) return std::nullopt;
  return g * P / dp;
}

double averagePitch(const std::vector<double>& centres, double fallback) {
  if (centres.size() < 2) return fallback;
  return std::abs(centres.back() - centres.front()) / double(centres.size() - 1);
}

GapInfo gapInfo(const Display& d, const EiLayout& L, double f, double g) {
  GapInfo r;
  const double P = d.mla.pitchMm, p = L.pixelMm;
  r.gapMm = g;
  const double Py = L.lensRowPitchMm() > 0.0 ? L.lensRowPitchMm() : P;  // lens row pitch
  r.viewingAngleDeg = deg(2.0 * std::atan(P / (2.0 * g)));
  r.viewingAngleYDeg = L.isHex() ? deg(2.0 * std::atan(P / (std::sqrt(3.0) * g))) : r.viewingAngleDeg;
  r.eiViewingAngleDeg = deg(2.0 * std::atan((L.isHex() ? L.eiFlatMm : L.eiW * p) / (2.0 * g)));
  if (std::abs(g - f) <= 1e-9 * f) {
    r.referencePlaneKind = "infinity";
  } else {
    r.referencePlaneMm = g * f / (g - f);
    r.referencePlaneKind = *r.referencePlaneMm > 0 ? "real" : "virtual";
  }
  r.pixelAngularPitchDeg = deg(std::atan(p / g));
  if (const CoverGlassOptics glass = coverGlassOptics(d, 550.0f); glass.present) {
    const double ge = glass.opticalGap(g);
    r.opticalGapMm = ge;
    r.opticalViewingAngleDeg = deg(2.0 * std::atan(P / (2.0 * ge)));
    if (std::abs(ge - f) > 1e-9 * f) r.opticalReferencePlaneMm = ge * f / (ge - f);
  }

  std::vector<double> ex(size_t(L.eiCols)), ey(size_t(L.eiRows));
  for (int k = 0; k < L.eiCols; ++k) ex[size_t(k)] = L.eiCentreX(k);
  for (int l = 0; l < L.eiRows; ++l) ey[size_t(l)] = L.eiCentreY(l);
  r.convergenceXMm = convergence(g, P, averagePitch(ex, P));
  r.convergenceYMm = convergence(g, Py, averagePitch(ey, Py));
  r.edgeChiefAngleXDeg = {deg(std::atan((L.lensX.front() - ex.front()) / g)),
                          deg(std::atan((L.lensX.back() - ex.back()) / g))};
  r.edgeChiefAngleYDeg = {deg(std::atan((L.lensY.front() - ey.front()) / g)),
                          deg(std::atan((L.lensY.back() - ey.back()) / g))};
  r.depthRangeMm = 2.0 * g;
  r.pixelFootprintDepthMm = g * P / p;
  return r;
}

ViewingZone viewingZone(const EiLayout& L, double g, double V) {
  ViewingZone z;
  z.distanceMm = V;
  const double hw = L.isHex() ? 0.5 * L.eiFlatMm : 0.5 * L.eiW * L.pixelMm,
               hh = L.isHex() ? L.eiFlatMm / std::sqrt(3.0) : 0.5 * L.eiH * L.pixelMm;
  auto zone = [&](double X, double e, double half) {
    // The zone seen through lens X from EI [e - half, e + half]; returns {lower, upper}.
    return std::array<double, 2>{X + (X - (e + half)) * V / g, X + (X - (e - half)) * V / g};
  };
  double loX = -1e300, hiX = 1e300, loY = -1e300, hiY = 1e300;
  for (int k = 0; k < L.eiCols; ++k)
    for (int l = 0; l < std::min(L.eiRows, L.isHex() ? 2 : 1); ++l) {  // hex: both row parities
      auto a = zone(L.lensXAt(k, l), L.eiCentreXAt(k, l), hw);
      loX = std::max(loX, a[0]);
      hiX = std::min(hiX, a[1]);
    }
  for (int l = 0; l < L.eiRows; ++l) {
    auto a = zone(L.lensY[size_t(l)], L.eiCentreY(l), hh);
    loY = std::max(loY, a[0]);
    hiY = std::min(hiY, a[1]);
  }
  z.zoneWidthXMm = 2.0 * hw * V / g;
  z.zoneWidthYMm = 2.0 * hh * V / g;
  auto centre = [&](double X, double e) { return X + (X - e) * V / g; };
  z.edgeZoneCentreXMm = {centre(L.lensX.front(), L.eiCentreX(0)),
                         centre(L.lensX.back(), L.eiCentreX(L.eiCols - 1))};
  z.edgeZoneCentreYMm = {centre(L.lensY.front(), L.eiCentreY(0)),
                         centre(L.lensY.back(), L.eiCentreY(L.eiRows - 1))};
  int km = L.eiCols / 2, lm = L.eiRows / 2;
  z.centreZoneCentreXMm = centre(L.lensX[size_t(km)], L.eiCentreX(km));
  z.centreZoneCentreYMm = centre(L.lensY[size_t(lm)], L.eiCentreY(lm));
  z.commonWidthXMm = std::max(0.0, hiX - loX);
  z.commonWidthYMm = std::max(0.0, hiY - loY);
  z.commonCentreXMm = z.commonWidthXMm > 0 ? 0.5 * (loX + hiX) : 0.0;
  z.commonCentreYMm = z.commonWidthYMm > 0 ? 0.5 * (loY + hiY) : 0.0;
  return z;
}

Json optNum(const std::optional<double>& v) { return v ? Json(*v) : Json(nullptr); }

Json gapJson(const GapInfo& g) {
  Json j;
  j["gap_mm"] = g.gapMm;
  j["viewing_angle_deg"] = g.viewingAngleDeg;
  j["ei_viewing_angle_deg"] = g.eiViewingAngleDeg;
  j["optical_gap_mm"] = optNum(g.opticalGapMm);
  j["optical_viewing_angle_deg"] = optNum(g.opticalViewingAngleDeg);
  j["optical_reference_plane_mm"] = optNum(g.opticalReferencePlaneMm);
  j["reference_image_plane_mm"] = optNum(g.referencePlaneMm);
  j["reference_image_plane"] = g.referencePlaneKind;
  j["pixel_angular_pitch_deg"] = g.pixelAngularPitchDeg;
  j["ei_centre_ray_convergence_mm"] = {optNum(g.convergenceXMm), optNum(g.convergenceYMm)};
  j["edge_chief_ray_angle_x_deg"] = {g.edgeChiefAngleXDeg[0], g.edgeChiefAngleXDeg[1]};
  j["edge_chief_ray_angle_y_deg"] = {g.edgeChiefAngleYDeg[0], g.edgeChiefAngleYDeg[1]};
  j["depth_range_mm"] = {-g.depthRangeMm, g.depthRangeMm};
  j["pixel_footprint_equals_pitch_depth_mm"] = g.pixelFootprintDepthMm;
  return j;
}

std::string optText(const std::optional<double>& v, const char* none) {
  return v ? formatText("%.2f mm", *v) : std::string(none);
}

std::string gapText(const char* title, const GapInfo& g) {
  std::string s = formatText("%s gap g = %.4g mm\n", title, g.gapMm);
  s += formatText("  viewing angle psi = 2 atan(P/2g)    %.3f deg (+-%.3f); one EI fills %.3f deg\n",
           g.viewingAngleDeg, 0.5 * g.viewingAngleDeg, g.eiViewingAngleDeg);
  if (g.referencePlaneMm)
    s += formatText("  reference image plane L = gf/(g-f) %.3f mm (%s)\n", *g.referencePlaneMm,
             g.referencePlaneKind.c_str());
  else
    s += "  reference image plane L = gf/(g-f) at infinity (g = f)\n";
  s += formatText("  pixel angular pitch atan(p/g)       %.4f deg\n", g.pixelAngularPitchDeg);
  if (g.opticalGapMm) {
    s += formatText("  through the panel's cover glass: optical gap g_eff = g - t(1 - 1/n) %.4f mm (550 nm), psi %.3f deg",
             *g.opticalGapMm, *g.opticalViewingAngleDeg);
    s += g.opticalReferencePlaneMm ? formatText(", L %.3f mm\n", *g.opticalReferencePlaneMm) : std::string(", L at infinity\n");
  }
  s += "  EI-centre chief rays (physical lens centres) converge at x: " +
       optText(g.convergenceXMm, "never (parallel)") + ", y: " +
       optText(g.convergenceYMm, "never (parallel)") + "  (< 0: virtual point behind the MLA)\n";
  s += formatText("  edge chief-ray angles: left %.3f, right %.3f, top %.3f, bottom %.3f deg\n",
           g.edgeChiefAngleXDeg[0], g.edgeChiefAngleXDeg[1], g.edgeChiefAngleYDeg[0],
           g.edgeChiefAngleYDeg[1]);
  s += formatText("  depth range |z| <= %.3g mm; pixel footprint p|z|/g reaches P at |z| = %.4g mm\n",
           g.depthRangeMm, g.pixelFootprintDepthMm);
  return s;
}

}  // namespace

DisplayInfo derive(const Display& d) {
  EiLayout L = computeLayout(d);
  DisplayInfo r;
  r.name = d.name;
  r.file = d.file;
  r.layout = layoutName(d.layout);
  r.panelW = d.panel.widthPx;
  r.panelH = d.panel.heightPx;
  r.pixelMm = d.panel.pixelPitchMm;
  r.panelWidthMm = d.panel.widthMm();
  r.panelHeightMm = d.panel.heightMm();
  r.lattice = latticeName(d.mla.lattice);
  r.lensPitchMm = d.mla.pitchMm;
  r.focus = lensletFocus(d.mla);
  r.eiW = d.eiWidthPx;
  r.eiH = d.eiHeightPx;
  r.eiCols = d.eiCols;
  r.eiRows = d.eiRows;
  const double P = d.mla.pitchMm, p = r.pixelMm;
  if (d.layout == EiLayoutKind::ToedIn) {
    r.nominalEiPitchXMm = r.nominalEiPitchYMm = P * (1.0 + d.generationGapMm / *d.viewingDistanceMm);
  } else {
    r.nominalEiPitchXMm = r.eiW * p;
    r.nominalEiPitchYMm = r.eiH * p;
  }
  if (L.isHex()) {  // rows are sqrt(3)/2 of the pitch along a row apart
    r.nominalEiPitchYMm = r.nominalEiPitchXMm * std::sqrt(3.0) / 2.0;
    HexInfo h;
    h.lensletCount = L.numEis();
    h.lensRowPitchMm = L.lensRowPitchMm();
    h.lensCellAreaMm2 = L.lensCellAreaMm2();
    h.eiFlatPx = d.eiWidthPx;
    h.eiNominalPixels = double(d.eiWidthPx) * d.eiWidthPx * std::sqrt(3.0) / 2.0;
    h.eiPixelsMin = INT64_MAX;
    for (int k = 0; k < L.eiCols; ++k)
      for (int l = 0; l < L.eiRows; ++l) {
        const int64_t c = L.eiRayCount(k, l);
        h.eiPixelsMin = std::min(h.eiPixelsMin, c);
        h.eiPixelsMax = std::max(h.eiPixelsMax, c);
      }
    h.eiPixelsMean = double(L.numRays()) / double(std::max<int64_t>(1, L.numEis()));
    h.eiBoxW = L.eiW;
    h.eiBoxH = L.eiH;
    h.eiaFill = double(L.numRays()) / (double(L.eiaW) * double(L.eiaH));
    const AreaMm a = L.activeArea();
    h.activeWidthMm = a.x1 - a.x0;
    h.activeHeightMm = a.y1 - a.y0;
    h.lensletFill = double(L.numEis()) * h.lensCellAreaMm2 / (h.activeWidthMm * h.activeHeightMm);
    r.hex = h;
  }
  std::vector<double> ex(size_t(L.eiCols)), ey(size_t(L.eiRows));
  for (int k = 0; k < L.eiCols; ++k) ex[size_t(k)] = L.eiCentreX(k);
  for (int l = 0; l < L.eiRows; ++l) ey[size_t(l)] = L.eiCentreY(l);
  r.eiPitchXMm = averagePitch(ex, r.nominalEiPitchXMm);
  r.eiPitchYMm = averagePitch(ey, r.nominalEiPitchYMm);
  r.eiaW = L.eiaW;
  r.eiaH = L.eiaH;
  r.eiaWidthMm = L.eiaW * p;
  r.eiaHeightMm = L.eiaH * p;
  r.panelCol0 = L.panelCol0;
  r.panelRow0 = L.panelRow0;
  // Panel centre in EIA pixel coordinates is (panelW/2 - panelCol0, panelH/2 - panelRow0).
  r.eiaCentreOffsetXMm = -(0.5 * L.panelW - L.panelCol0 - 0.5 * L.eiaW) * p;
  r.eiaCentreOffsetYMm = (0.5 * L.panelH - L.panelRow0 - 0.5 * L.eiaH) * p;
  r.numRays = L.numRays();

  r.pinholePitchXMm = averagePitch(L.pinholeX, P);
  r.pinholePitchYMm = averagePitch(L.pinholeY, L.lensRowPitchMm());
  r.generationConvergenceXMm = convergence(d.generationGapMm, r.pinholePitchXMm, r.eiPitchXMm);
  r.generationEdgeAngleXDeg = {deg(std::atan((L.pinholeX.front() - ex.front()) / d.generationGapMm)),
                               deg(std::atan((L.pinholeX.back() - ex.back()) / d.generationGapMm))};
  r.edgePinholeOffsetXMm = L.pinholeX.front() - L.lensX.front();
  r.edgePinholeOffsetYMm = L.pinholeY.front() - L.lensY.front();
  r.scaleErrorX = P / r.pinholePitchXMm - 1.0;
  r.scaleErrorY = L.lensRowPitchMm() / r.pinholePitchYMm - 1.0;

  r.generation = gapInfo(d, L, r.focus.focalLengthMm, d.generationGapMm);
  r.reconstruction = gapInfo(d, L, r.focus.focalLengthMm, d.reconstructionGapMm);
  if (d.viewingDistanceMm) r.viewingZone = viewingZone(L, d.reconstructionGapMm, *d.viewingDistanceMm);
  r.depthCriterion =
      "lateral sampling at depth z is max(P, P|z|/g) (docs/design.md §5.1); the depth range is where it "
      "stays <= 2P, i.e. |z| <= 2g";
  for (const auto& a : d.panel.assumptions) r.assumptions.push_back("panel: " + a);
  for (const auto& a : d.mla.assumptions) r.assumptions.push_back("mla: " + a);
  for (const auto& a : d.assumptions) r.assumptions.push_back("display: " + a);
  return r;
}

Json toJson(const DisplayInfo& r) {
  Json j;
  j["name"] = r.name;
  j["file"] = r.file;
  j["panel"] = {{"resolution_px", {r.panelW, r.panelH}},
                {"pixel_pitch_mm", r.pixelMm},
                {"active_area_mm", {r.panelWidthMm, r.panelHeightMm}}};
  Json mla = {{"lattice", r.lattice},
              {"pitch_mm", r.lensPitchMm},
              {"focal_length_mm", r.focus.focalLengthMm},
              {"focal_length_source", r.focus.source},
              {"index_d", optNum(r.focus.indexD)},
              {"focal_length_from_radius_mm", optNum(r.focus.focalFromRadiusMm)}};
  j["mla"] = mla;
  j["ei"] = {{"size_px", {r.eiW, r.eiH}},
             {"count", {r.eiCols, r.eiRows}},
             {"layout", r.layout},
             {"nominal_pitch_mm", {r.nominalEiPitchXMm, r.nominalEiPitchYMm}},
             {"pitch_mm", {r.eiPitchXMm, r.eiPitchYMm}},
             {"pitch_px", {r.eiPitchXMm / r.pixelMm, r.eiPitchYMm / r.pixelMm}},
             {"pitch_over_lens_pitch", {r.eiPitchXMm / r.lensPitchMm, r.eiPitchYMm / r.lensPitchMm}}};
  j["eia"] = {{"size_px", {r.eiaW, r.eiaH}},
              {"size_mm", {r.eiaWidthMm, r.eiaHeightMm}},
              {"panel_origin_px", {r.panelCol0, r.panelRow0}},
              {"centre_offset_from_panel_centre_mm", {r.eiaCentreOffsetXMm, r.eiaCentreOffsetYMm}}};
  j["rays"] = r.numRays;
  j["generation_rays"] = {
      {"pinhole_pitch_mm", {r.pinholePitchXMm, r.pinholePitchYMm}},
      {"central_ray_convergence_x_mm", optNum(r.generationConvergenceXMm)},
      {"edge_central_ray_angle_x_deg", {r.generationEdgeAngleXDeg[0], r.generationEdgeAngleXDeg[1]}},
      {"edge_pinhole_minus_lens_centre_mm", {r.edgePinholeOffsetXMm, r.edgePinholeOffsetYMm}},
      {"reconstruction_scale_error", {r.scaleErrorX, r.scaleErrorY}}};
  j["generation"] = gapJson(r.generation);
  j["reconstruction"] = gapJson(r.reconstruction);
  if (r.viewingZone) {
    const auto& z = *r.viewingZone;
    j["viewing_zone"] = {{"distance_mm", z.distanceMm},
                         {"gap_mm", r.reconstruction.gapMm},
                         {"zone_width_mm", {z.zoneWidthXMm, z.zoneWidthYMm}},
                         {"centre_ei_zone_centre_mm", {z.centreZoneCentreXMm, z.centreZoneCentreYMm}},
                         {"edge_zone_centre_x_mm", {z.edgeZoneCentreXMm[0], z.edgeZoneCentreXMm[1]}},
                         {"edge_zone_centre_y_mm", {z.edgeZoneCentreYMm[0], z.edgeZoneCentreYMm[1]}},
                         {"common_zone_width_mm", {z.commonWidthXMm, z.commonWidthYMm}},
                         {"common_zone_centre_mm", {z.commonCentreXMm, z.commonCentreYMm}}};
  } else {
    j["viewing_zone"] = nullptr;
  }
  if (r.hex) {
    const HexInfo& h = *r.hex;
    j["hex"] = {{"lenslets", h.lensletCount},
                {"lens_row_pitch_mm", h.lensRowPitchMm},
                {"lens_cell_area_mm2", h.lensCellAreaMm2},
                {"ei_flat_to_flat_px", h.eiFlatPx},
                {"ei_nominal_pixels", h.eiNominalPixels},
                {"ei_pixels_min_mean_max", {h.eiPixelsMin, h.eiPixelsMean, h.eiPixelsMax}},
                {"ei_box_px", {h.eiBoxW, h.eiBoxH}},
                {"eia_fill", h.eiaFill},
                {"lenslet_array_size_mm", {h.activeWidthMm, h.activeHeightMm}},
                {"lenslet_array_fill", h.lensletFill},
                {"viewing_angle_deg", {r.reconstruction.viewingAngleDeg, r.reconstruction.viewingAngleYDeg}}};
  }
  j["depth_range_criterion"] = r.depthCriterion;
  j["assumptions"] = r.assumptions;
  return j;
}

std::string toText(const DisplayInfo& r) {
  std::string s;
  s += formatText("Display: %s\n", r.name.c_str());
  if (!r.file.empty()) s += formatText("  file %s\n", r.file.c_str());
  s += formatText("Panel: %d x %d px, pixel %.4f mm, %.2f x %.2f mm\n", r.panelW, r.panelH, r.pixelMm,
           r.panelWidthMm, r.panelHeightMm);
  s += formatText("MLA: %s lattice, pitch P = %.4f mm, f = %.4f mm (%s)", r.lattice.c_str(), r.lensPitchMm,
           r.focus.focalLengthMm, r.focus.source.c_str());
  if (r.focus.focalFromRadiusMm)
    s += formatText("; R/(n_d-1) = %.4f mm with n_d = %.4f", *r.focus.focalFromRadiusMm, *r.focus.indexD);
  s += "\n";
  if (r.hex) {
    const HexInfo& h = *r.hex;
    s += formatText("  hex lattice: %lld lenslets (%d rows of %d), row pitch P sqrt(3)/2 = %.4f mm, cell area "
             "%.4f mm^2; lenslet array %.3f x %.3f mm (%.1f %% of its bounding box)\n",
             (long long)h.lensletCount, r.eiRows, r.eiCols, h.lensRowPitchMm, h.lensCellAreaMm2,
             h.activeWidthMm, h.activeHeightMm, 100.0 * h.lensletFill);
    s += formatText("EIs: %d x %d hex EIs (rows of %d), %g px flat-to-flat, layout %s\n", r.eiCols, r.eiRows,
             r.eiCols, h.eiFlatPx, r.layout.c_str());
    s += formatText("  pixels per EI: %lld to %lld, mean %.2f (hexagon area %.2f px); bounding box %d x %d px; "
             "%.1f %% of the EIA rectangle is in an EI\n",
             (long long)h.eiPixelsMin, (long long)h.eiPixelsMax, h.eiPixelsMean, h.eiNominalPixels, h.eiBoxW,
             h.eiBoxH, 100.0 * h.eiaFill);
    s += formatText("  viewing angle (reconstruction gap) %.3f deg across the flats (x), %.3f deg corner to corner (y)\n",
             r.reconstruction.viewingAngleDeg, r.reconstruction.viewingAngleYDeg);
  } else {
    s += formatText("EIs: %d x %d of %d x %d px, layout %s\n", r.eiCols, r.eiRows, r.eiW, r.eiH, r.layout.c_str());
  }
  s += formatText("  EI pitch %.5f x %.5f mm (%.3f x %.3f px; nominal %.5f mm), %.4f x lens pitch\n",
           r.eiPitchXMm, r.eiPitchYMm, r.eiPitchXMm / r.pixelMm, r.eiPitchYMm / r.pixelMm,
           r.nominalEiPitchXMm, r.eiPitchXMm / r.lensPitchMm);
  s += formatText("EIA: %d x %d px = %.3f x %.3f mm, at panel pixel (%d, %d); its centre is %.4f, %.4f mm "
           "from the panel centre\n",
           r.eiaW, r.eiaH, r.eiaWidthMm, r.eiaHeightMm, r.panelCol0, r.panelRow0,
           r.eiaCentreOffsetXMm, r.eiaCentreOffsetYMm);
  s += formatText("Rays: %lld (one per EI pixel)\n", (long long)r.numRays);
  s += formatText("Generation rays: pinhole pitch %.5f x %.5f mm; central rays converge at x: %s; "
           "edge central-ray angle %.3f / %.3f deg\n",
           r.pinholePitchXMm, r.pinholePitchYMm,
           optText(r.generationConvergenceXMm, "never (parallel)").c_str(),
           r.generationEdgeAngleXDeg[0], r.generationEdgeAngleXDeg[1]);
  s += formatText("  pinhole - lens centre at the left/top edge: %.4f / %.4f mm; reconstruction scale "
           "error P/p_pinhole - 1 = %.3f %% / %.3f %%\n",
           r.edgePinholeOffsetXMm, r.edgePinholeOffsetYMm, 100.0 * r.scaleErrorX, 100.0 * r.scaleErrorY);
  s += gapText("Generation", r.generation);
  s += gapText("Reconstruction", r.reconstruction);
  if (r.viewingZone) {
    const auto& z = *r.viewingZone;
    s += formatText("Viewing zones at %.4g mm (reconstruction gap, physical lenses):\n", z.distanceMm);
    s += formatText("  one EI's zone %.2f x %.2f mm; centre EI's zone centred at (%.2f, %.2f) mm\n",
             z.zoneWidthXMm, z.zoneWidthYMm, z.centreZoneCentreXMm, z.centreZoneCentreYMm);
    s += formatText("  edge EIs' zones centred at x %.2f / %.2f mm, y %.2f / %.2f mm\n", z.edgeZoneCentreXMm[0],
             z.edgeZoneCentreXMm[1], z.edgeZoneCentreYMm[0], z.edgeZoneCentreYMm[1]);
    s += formatText("  common zone (every EI through its own lens): %.2f x %.2f mm", z.commonWidthXMm,
             z.commonWidthYMm);
    s += (z.commonWidthXMm > 0 && z.commonWidthYMm > 0) ? "\n" : " (none: edges flip)\n";
  }
  s += "Depth range criterion: " + r.depthCriterion + "\n";
  if (!r.assumptions.empty()) {
    s += "Assumptions:\n";
    for (const auto& a : r.assumptions) s += "  - " + a + "\n";
  }
  return s;
}

namespace {

Json stackJson(const OpticalStack& s, const StackFirstOrder& fo) {
  Json layers = Json::array();
  for (size_t i = 0; i < s.layers.size(); ++i)
    layers.push_back({{"type", layerKindName(s.layers[i].kind)},
                      {"z_mm", {s.layerBackZ(i), s.layerBackZ(i + 1)}},
                      {"material", s.layers[i].material.empty() ? "air" : s.layers[i].material}});
  Json j = {{"layers", layers}, {"wavelength_nm", fo.wavelengthNm}, {"afocal", fo.afocal}};
  if (fo.afocal) return j;
  j["focal_length_mm"] = fo.focalLengthMm;
  j["principal_planes_z_mm"] = {fo.frontPrincipalZMm, fo.rearPrincipalZMm};
  j["focal_points_z_mm"] = {fo.frontFocalZMm, fo.rearFocalZMm};
  j["reduced_gap_mm"] = fo.reducedGapMm;
  j["reference_plane_mm"] = fo.referencePlaneMm ? Json(*fo.referencePlaneMm) : Json(nullptr);
  j["viewing_angle_deg"] = fo.viewingAngleDeg;
  j["depth_range_mm"] = {-2.0 * fo.reducedGapMm, 2.0 * fo.reducedGapMm};
  if (const std::optional<ApertureStop> stop = findApertureStop(s, fo.wavelengthNm))
    j["aperture_stop"] = {{"layer", stop->what}, {"z_mm", stop->zMm}, {"radius_mm", stop->radiusMm}};
  return j;
}

// A display whose stack is described only: the panel and the stack.
}  // namespace

Json displayInfoJson(const Display& d) {
  Json j = toJson(derive(d));
  if (d.stack) j["stack"] = stackJson(*d.stack, stackFirstOrder(*d.stack));
  return j;
}

std::string displayInfoText(const Display& d) {
  std::string text = toText(derive(d));
  if (d.stack) text += "\n" + stackText(*d.stack, stackFirstOrder(*d.stack));
  return text;
}

}  // namespace inim
