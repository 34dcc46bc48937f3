#pragma once
// Paraxial quantities derived from a display description (docs/design.md §5.1), as a
// struct, as JSON and as text (for `inim display info [FILE] [--json]`).
#include <array>
#include <optional>
#include <string>
#include <vector>

#include "core/json_config.h"
#include "display/display.h"
#include "display/ei_layout.h"

namespace inim {

// Chief rays of the EI centres through the *physical* lens centres (pitch P) at one gap.
struct GapInfo {
  double gapMm = 0.0;
  double viewingAngleDeg = 0.0;    // psi = 2 atan(P / (2 g))
  // Vertical: the same for square cells; hex (pointy-top cells, 2 P / sqrt(3) tall):
  // 2 atan(P / (sqrt(3) g)). Reported for hex only.
  double viewingAngleYDeg = 0.0;
  double eiViewingAngleDeg = 0.0;  // 2 atan(p_EI / (2 g)): the angle one EI fills
  // L = g f / (g - f): the plane where the lenslets image the panel. nullopt when g == f
  // (at infinity); negative = virtual (behind the MLA, g < f).
  std::optional<double> referencePlaneMm;
  std::string referencePlaneKind;  // "infinity", "real" or "virtual"
  double pixelAngularPitchDeg = 0.0;  // atan(pixel / g): angle between neighbour pixels' rays
  // Seen through the panel's cover glass (thickness t, index n at 550 nm), the panel sits at the
  // optical gap g_eff = g - t (1 - 1/n) (paraxial): the view simulation's lenslets image it at
  // g_eff f / (g_eff - f) and its viewing angle is 2 atan(P / (2 g_eff)). nullopt without glass.
  std::optional<double> opticalGapMm, opticalViewingAngleDeg, opticalReferencePlaneMm;
  // EI centre chief rays converge at z = g P / (p_EI - P): > 0 in front (viewer side),
  // < 0 a virtual point behind the MLA (rays diverge); nullopt when p_EI == P (parallel).
  std::optional<double> convergenceXMm, convergenceYMm;
  // Angle from +z of the chief ray of the edge EIs' centres, degrees, signed along the axis:
  // [left, right] in x, [top, bottom] in y. 0 for a parallel chief-ray bundle.
  std::array<double, 2> edgeChiefAngleXDeg{}, edgeChiefAngleYDeg{};
  // Depth range (criterion in depthCriterion): lateral sampling at depth z is
  // max(P, P |z| / g) (docs/design.md §5.1); the range is where it stays <= 2 P, |z| <= 2 g.
  double depthRangeMm = 0.0;
  // Depth at which one pixel's footprint through a pinhole, pixel |z| / g, reaches P.
  double pixelFootprintDepthMm = 0.0;
};

// Viewing zones at distance V in front of the MLA, at the reconstruction gap, with the
// physical lens centres: EI (k) is seen through its lens from x in
// [X + (X - e_right) V/g, X + (X - e_left) V/g] (X lens centre, e EI edges).
struct ViewingZone {
  double distanceMm = 0.0;
  double zoneWidthXMm = 0.0, zoneWidthYMm = 0.0;  // one EI's zone
  std::array<double, 2> edgeZoneCentreXMm{};      // left-most, right-most EI column
  std::array<double, 2> edgeZoneCentreYMm{};      // top, bottom EI row
  double centreZoneCentreXMm = 0.0, centreZoneCentreYMm = 0.0;  // the middle EI
  // Where every EI is seen through its own lens (0 when the zones have no common part).
  double commonWidthXMm = 0.0, commonWidthYMm = 0.0;
  double commonCentreXMm = 0.0, commonCentreYMm = 0.0;
};

// Hex lattices: EIs are hexagons of pixels (display/ei_layout.h).
struct HexInfo {
  int64_t lensletCount = 0;          // K x L indexed lenslets
  double lensRowPitchMm = 0.0;       // P sqrt(3) / 2
  double lensCellAreaMm2 = 0.0;      // P^2 sqrt(3) / 2
  double eiFlatPx = 0.0;             // EI flat-to-flat width (ei_px)
  double eiNominalPixels = 0.0;      // one EI hexagon's area in pixels, ei_px^2 sqrt(3) / 2
  int64_t eiPixelsMin = 0, eiPixelsMax = 0;
  double eiPixelsMean = 0.0;         // pixels an EI owns (a Voronoi cell of the pixel grid)
  int eiBoxW = 0, eiBoxH = 0;        // bounding box of the largest EI, px
  double eiaFill = 0.0;              // fraction of the EIA rectangle's pixels that are in an EI
  double lensletFill = 0.0;          // lenslet array area (K L cell areas) / its bounding box
  double activeWidthMm = 0.0, activeHeightMm = 0.0;  // lenslet array's bounding box
};

struct DisplayInfo {
  std::string name, file, layout;
  // panel
  int panelW = 0, panelH = 0;
  double pixelMm = 0.0, panelWidthMm = 0.0, panelHeightMm = 0.0;
  // MLA
  std::string lattice;
  double lensPitchMm = 0.0;
  LensletFocus focus;
  // EIs
  int eiW = 0, eiH = 0, eiCols = 0, eiRows = 0;
  double nominalEiPitchXMm = 0.0, nominalEiPitchYMm = 0.0;  // n p, or P (1 + g/D) toed-in
  double eiPitchXMm = 0.0, eiPitchYMm = 0.0;                // as placed (average), mm
  // EIA
  int eiaW = 0, eiaH = 0;
  double eiaWidthMm = 0.0, eiaHeightMm = 0.0;
  int panelCol0 = 0, panelRow0 = 0;
  double eiaCentreOffsetXMm = 0.0, eiaCentreOffsetYMm = 0.0;  // EIA centre - panel centre
  int64_t numRays = 0;
  // Ray generation (pinholes of the layout, at the generation gap)
  double pinholePitchXMm = 0.0, pinholePitchYMm = 0.0;
  std::optional<double> generationConvergenceXMm;  // central rays of the generated bundle
  std::array<double, 2> generationEdgeAngleXDeg{};
  // Pinhole minus physical lens centre at the left-most / top-most EI, mm, and the
  // lateral scale P / p_pinhole - 1 a reconstruction gets at the MLA plane.
  double edgePinholeOffsetXMm = 0.0, edgePinholeOffsetYMm = 0.0;
  double scaleErrorX = 0.0, scaleErrorY = 0.0;
  GapInfo generation, reconstruction;
  std::optional<ViewingZone> viewingZone;
  std::optional<HexInfo> hex;  // hex lattices only
  std::string depthCriterion;
  std::vector<std::string> assumptions;  // panel, MLA and display, prefixed by their part
};

DisplayInfo derive(const Display& d);
Json displayInfoJson(const Display& d);
std::string displayInfoText(const Display& d);
Json toJson(const DisplayInfo& info);
std::string toText(const DisplayInfo& info);

}  // namespace inim
