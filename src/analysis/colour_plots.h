#pragma once
// The figures of the colour-calibration study: patches (a ColorChecker, a drive-level grid,
// hold-out colours) shown on a simulated display, measured, and corrected.
//
//   - writeChromaticityPlot: the CIE 1931 xy diagram (spectral locus, gamut triangles) with
//     each patch's target, uncalibrated and calibrated chromaticity;
//   - writeDeltaEBars: the colour error of each patch before and after calibration, as
//     grouped bars with reference lines;
//   - swatchCharts: the patches themselves, chart beside chart ("target", "uncalibrated",
//     "calibrated"), for the eye.
//
// The plots are Plots (plot.h) built by chromaticityPlot() / deltaEBarsPlot(), so their
// frames can be asked where things are. Sizes that do not match are programming errors:
// std::invalid_argument.
//
// Usage:
//   ChromaticityPlotData d{"ColorChecker on the panel"};
//   d.gamuts.push_back({"sRGB", {{{0.64, 0.33}, {0.30, 0.60}, {0.15, 0.06}}}, plotPalette(1)});
//   d.points.push_back({"red", {0.54, 0.31}, {0.58, 0.30}, {0.545, 0.312}});
//   d.white = Vec2d(0.3127, 0.3290);
//   writeChromaticityPlot(d, out.add("chromaticity.png"), out.add("chromaticity.csv"));
#include <array>
#include <optional>
#include <string>
#include <vector>

#include "analysis/plot.h"

namespace inim {

using Vec2d = glm::dvec2;

struct GamutTriangle {
  std::string name;          // legend entry
  std::array<Vec2d, 3> xy;   // the primaries' chromaticities
  Vec3 colour;               // outline, and its light fill
};

// One patch: where it should be, where the uncalibrated display put it, where the calibrated
// one did. A non-finite before/after is not drawn (and written as nan to the CSV).
struct ChromaticityPoint {
  std::string label;
  Vec2d target, before, after;
};

struct ChromaticityPlotData {
  std::string title;
  std::vector<GamutTriangle> gamuts;  // e.g. "panel (nominal)", "sRGB", "panel seen at 0°"
  std::vector<ChromaticityPoint> points;
  std::optional<Vec2d> white;         // a white point marker (D65), labelled whiteLabel
  std::string whiteLabel = "D65";
  int height = 760;                   // px; the width follows from the equal aspect
};

// x, y of the spectral locus from 360 to 830 nm every stepNm (and at 830 nm), from the CIE
// 1931 CMF table (spectral/cmf_table.h). std::invalid_argument unless stepNm > 0.
std::vector<Vec2d> spectralLocusXY(double stepNm);

// The xy diagram: axes x 0-0.8, y 0-0.9 with equal scales; the spectral locus closed by the
// purple line, ticked and labelled at 460-620 nm every 20 nm; the gamut triangles (outline,
// light fill); per point the target (open circle), uncalibrated (filled triangle) and
// calibrated (cross) chromaticity with thin lines from the target to the other two; the
// white point. The legend lists the three marker kinds and the gamuts.
Plot chromaticityPlot(const ChromaticityPlotData& d);
// Writes the PNG and, if csvPath is not empty, the points as CSV
// (label, target_x, target_y, before_x, before_y, after_x, after_y).
void writeChromaticityPlot(const ChromaticityPlotData& d, const std::string& pngPath, const std::string& csvPath = "");

struct DeltaEBarsData {
  std::string title, yLabel = "CIEDE2000";
  std::vector<std::string> labels;     // one per patch (24 for the ColorChecker)
  std::vector<double> before, after;   // same length as labels; non-finite: no bar
  std::vector<double> thresholds;      // horizontal reference lines, e.g. {1, 2, 3}
  std::string beforeName = "uncalibrated", afterName = "calibrated";
  int width = 0, height = 520;         // px; width 0: from the number of patches
};

// Grouped bars, before beside after for each patch, the patch names under them (turned to
// read upwards when they do not fit side by side), the thresholds as dashed lines.
Plot deltaEBarsPlot(const DeltaEBarsData& d);
// Writes the PNG and, if csvPath is not empty, one CSV row per patch (patch, before, after).
void writeDeltaEBars(const DeltaEBarsData& d, const std::string& pngPath, const std::string& csvPath = "");

// One chart of patches: sRGB-encoded values in [0, 1] (clamped), row-major.
struct SwatchChart {
  std::string label;
  std::vector<Vec3> srgb;  // a non-finite patch is left empty (background)
};

struct SwatchStyle {
  int patch = 56;         // side of a patch, px
  int gap = 4;            // between patches, px
  int chartGap = 32;      // between charts, px
  int margin = 16;        // around everything, px
  double fontSize = 16.0; // labels (bold) and caption, px
  int labelGap = 8;       // between a label or the caption and the patches, px
  Vec3 background{0.2f, 0.2f, 0.2f};
  Vec3 textColor{0.92f, 0.92f, 0.92f};
};

// Where swatchCharts() puts things, in image pixels.
struct SwatchLayout {
  int width = 0, height = 0;
  std::vector<std::vector<PixelBox>> patches;  // [chart][patch]
  std::vector<PixelBox> labels;                // [chart], the label's text box
  PixelBox caption;                            // empty without a caption
};

// Charts side by side, each `columns` patches wide (6 for the ColorChecker: 4 rows of 6),
// each labelled above; patches as squares with thin gaps on a dark grey background, and an
// optional caption line under everything. std::invalid_argument unless columns > 0.
SwatchLayout swatchLayout(const std::vector<SwatchChart>& charts, int columns, const std::string& caption = "",
                          const SwatchStyle& style = {});
// The image (RGB, the values written to a PNG); the caller writes it.
Image swatchCharts(const std::vector<SwatchChart>& charts, int columns, const std::string& caption = "",
                   const SwatchStyle& style = {});

}  // namespace inim
