// The colour-calibration figures: the spectral locus against CIE 1931 chromaticities, the
// chromaticity diagram (equal scales, the white point and the markers where they belong, the
// wavelength labels and the legend clear of the data, the points' CSV), the ΔE bars (one CSV
// row per patch, names turned when they crowd, sizes that do not match), and the swatch
// charts (layout size, each patch's colour at its centre).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "analysis/colour_plots.h"
#include "analysis/plot_test_util.h"
#include "draw/text.h"
#include "fixtures.h"

using namespace inim;

namespace {

const float kLevel = 1.0f / 255.0f + 1e-6f;

Vec3 pixel(const Image& img, double x, double y) {
  const int i = int(std::floor(x)), j = int(std::floor(y));
  return {img.at(i, j, 0), img.at(i, j, 1), img.at(i, j, 2)};
}

std::vector<std::string> lines(const std::string& path) {
  std::ifstream in(path);
  std::vector<std::string> out;
  for (std::string l; std::getline(in, l);) out.push_back(l);
  return out;
}

const std::vector<std::string> kPatchNames = {
    "dark skin", "light skin", "blue sky",     "foliage",     "blue flower", "bluish green",
    "orange",    "purplish blue", "moderate red", "purple",   "yellow green", "orange yellow",
    "blue",      "green",      "red",          "yellow",      "magenta",     "cyan",
    "white 9.5", "neutral 8",  "neutral 6.5",  "neutral 5",   "neutral 3.5", "black 2"};

// A diagram with two gamuts and points around the white point, the uncalibrated ones
// pushed outwards.
ChromaticityPlotData diagram() {
  ChromaticityPlotData d;
  d.title = "test";
  d.gamuts.push_back({"sRGB", {{{0.64, 0.33}, {0.30, 0.60}, {0.15, 0.06}}}, plotPalette(1)});
  d.gamuts.push_back({"panel", {{{0.68, 0.32}, {0.265, 0.69}, {0.15, 0.06}}}, Vec3(0.4f)});
  const Vec2d w(0.3127, 0.3290);
  for (int k = 0; k < 12; ++k) {
    const double a = 2.0 * kPi * k / 12.0;
    const Vec2d t = w + 0.12 * Vec2d(std::cos(a), std::sin(a));
    std::string label = "p";
    d.points.push_back({label += std::to_string(k), t, w + 1.3 * (t - w), t + Vec2d(0.002, -0.002)});
  }
  d.white = w;
  return d;
}

}  // namespace

// CIE 1931 2° chromaticities of monochromatic light (CIE 015:2018 tables): 520 nm
// (0.07430, 0.83380), 700 nm (0.73469, 0.26531); 360 nm and 830 nm close the locus.
TEST(ColourPlots, SpectralLocusMatchesCieChromaticities) {
  const std::vector<Vec2d> xy = spectralLocusXY(10.0);
  ASSERT_EQ(xy.size(), 48u);  // 360, 370, ..., 830
  EXPECT_NEAR(xy[16].x, 0.07430, 0.002);
  EXPECT_NEAR(xy[16].y, 0.83380, 0.002);
  EXPECT_NEAR(xy[34].x, 0.73469, 0.002);
  EXPECT_NEAR(xy[34].y, 0.26531, 0.002);
  // A step that does not divide the range still ends at 830 nm (the red end).
  const std::vector<Vec2d> odd = spectralLocusXY(7.0);
  EXPECT_NEAR(odd.back().x, xy.back().x, 1e-12);
  EXPECT_NEAR(odd.back().y, xy.back().y, 1e-12);
  for (const Vec2d& v : xy) EXPECT_GT(1.0 - v.x - v.y, -1e-6);  // z >= 0
  EXPECT_THROW(spectralLocusXY(0.0), std::invalid_argument);
}

TEST(ColourPlots, ChromaticityDiagramHasEqualScalesAndDrawsItsPoints) {
  const ChromaticityPlotData d = diagram();
  const Plot p = chromaticityPlot(d);
  const PlotFrame f = plotFrame(p);
  EXPECT_EQ(f.xMin, 0.0);
  EXPECT_EQ(f.xMax, 0.8);
  EXPECT_EQ(f.yMin, 0.0);
  EXPECT_EQ(f.yMax, 0.9);
  // One data unit is as many pixels across as up (to a pixel over the axis).
  EXPECT_NEAR((f.right - f.left) / 0.8, (f.bottom - f.top) / 0.9, 1.0 / 0.8);

  const std::string png = fixtures::scratchPath("chromaticity.png"), csv = fixtures::scratchPath("chromaticity.csv");
  writeChromaticityPlot(d, png, csv);
  const Image img = readImage(png);
  EXPECT_EQ(img.width, p.width);
  EXPECT_EQ(img.height, p.height);

  // The white point marker is dark where only a light gamut fill would be.
  const Vec3 white = pixel(img, f.pixelX(d.white->x), f.pixelY(d.white->y));
  EXPECT_LT(std::max({white.x, white.y, white.z}), 0.5f);
  ChromaticityPlotData none = d;
  none.white.reset();
  const Vec3 noWhite = pixel(renderPlot(chromaticityPlot(none)), f.pixelX(d.white->x), f.pixelY(d.white->y));
  EXPECT_GT(std::min({noWhite.x, noWhite.y, noWhite.z}), 0.7f);

  // A target's open circle: dark on its ring; the uncalibrated triangle: red at its centre.
  const ChromaticityPoint& q = d.points[3];
  const glm::dvec2 t = f.toPixel(q.target.x, q.target.y), b = f.toPixel(q.before.x, q.before.y);
  EXPECT_GT(plot_test::darkIn(img, t.x - 7, t.y - 7, t.x + 7, t.y + 7), 12);
  const Vec3 tri = pixel(img, b.x, b.y);
  EXPECT_GT(tri.x, 0.7f);
  EXPECT_LT(tri.y, 0.35f);

  // The CSV: a header and one row per point, a missing point written as nan.
  const std::vector<std::string> rows = lines(csv);
  ASSERT_EQ(rows.size(), d.points.size() + 1);
  EXPECT_EQ(rows[0], "label,target_x,target_y,before_x,before_y,after_x,after_y");
  EXPECT_EQ(rows[1].substr(0, 3), "p0,");
  ChromaticityPlotData missing = d;
  missing.points[0].after = Vec2d(std::nan(""));
  writeChromaticityPlot(missing, png, csv);
  EXPECT_NE(lines(csv)[1].find(",nan,nan"), std::string::npos);
}

TEST(ColourPlots, WavelengthLabelsAndLegendStayClear) {
  const Plot p = chromaticityPlot(diagram());
  const PlotFrame f = plotFrame(p);
  // Nine labels, 460-620 nm, all inside the axes (500 nm lies next to x = 0: its label goes
  // inside the locus rather than off the plot).
  ASSERT_EQ(p.texts.size(), 9u);
  for (const PlotText& t : p.texts) EXPECT_TRUE(f.insideX(t.x) && f.insideY(t.y)) << t.text << " nm";
  // The legend (three marker kinds, the white point, two gamuts) sits inside on no data.
  ASSERT_FALSE(f.legend.empty());
  EXPECT_FALSE(f.legendOutside);
  const std::vector<bool> ink = plot_test::dataPixels(p);
  int covered = 0;
  for (int y = int(f.legend.y0); y < int(f.legend.y1); ++y)
    for (int x = int(f.legend.x0); x < int(f.legend.x1); ++x) covered += ink[size_t(y) * size_t(p.width) + size_t(x)];
  EXPECT_EQ(covered, 0);
}

TEST(ColourPlots, DeltaEBarsOneCsvRowPerPatchAndReadableNames) {
  DeltaEBarsData d;
  d.title = "ColorChecker";
  d.labels = kPatchNames;
  for (size_t i = 0; i < d.labels.size(); ++i) d.before.push_back(2.0 + 0.2 * double(i)), d.after.push_back(0.5);
  d.thresholds = {1.0, 2.0, 3.0};
  const std::string png = fixtures::scratchPath("de.png"), csv = fixtures::scratchPath("de.csv");
  writeDeltaEBars(d, png, csv);
  const std::vector<std::string> rows = lines(csv);
  ASSERT_EQ(rows.size(), d.labels.size() + 1);
  EXPECT_EQ(rows[0], "patch,uncalibrated,calibrated");
  EXPECT_EQ(rows[1], "dark skin,2,0.5");

  const Plot p = deltaEBarsPlot(d);
  const PlotFrame f = plotFrame(p);
  const Image img = readImage(png);
  EXPECT_EQ(img.width, p.width);
  // 24 names do not fit side by side: turned, one text height each within a patch's width.
  EXPECT_TRUE(f.xLabelsUp);
  const double perPatch = (f.right - f.left) / (f.xMax - f.xMin);
  EXPECT_GE(perPatch, draw::measureText("Ag", {p.fontSize}).height + 4.0);
  // The highest bar and the legend both inside, the legend on no bar.
  EXPECT_GE(f.yMax, d.before.back());
  ASSERT_FALSE(f.legend.empty());
  EXPECT_FALSE(f.legendOutside);
  // Before and after side by side around each patch's tick, in their own colours.
  const double y = f.pixelY(0.25);
  const Vec3 left = pixel(img, f.pixelX(5.0 - 0.2), y), right = pixel(img, f.pixelX(5.0 + 0.2), y);
  EXPECT_GT(left.x, right.x + 0.3f);
  EXPECT_GT(right.z, left.z + 0.3f);
}

TEST(ColourPlots, MismatchedSizesAreProgrammingErrors) {
  DeltaEBarsData d;
  d.labels = {"a", "b"};
  d.before = {1.0, 2.0};
  d.after = {1.0};
  EXPECT_THROW(deltaEBarsPlot(d), std::invalid_argument);
  EXPECT_THROW(writeDeltaEBars(d, fixtures::scratchPath("never.png")), std::invalid_argument);
  EXPECT_THROW(swatchCharts({{"a", {Vec3(0.5f)}}}, 0), std::invalid_argument);
}

TEST(ColourPlots, SwatchChartsSizeAndPatchColours) {
  std::vector<SwatchChart> charts = {{"target", {}}, {"uncalibrated", {}}, {"calibrated", {}}};
  for (size_t c = 0; c < charts.size(); ++c)
    for (int k = 0; k < 24; ++k)
      charts[c].srgb.push_back(Vec3(float(k) / 23.0f, float(c) / 2.0f, float((7 * k) % 24) / 23.0f));
  const SwatchStyle st;
  const Image img = swatchCharts(charts, 6);
  // 3 charts of 6 x 4 patches side by side, labels above.
  const int chartW = 6 * st.patch + 5 * st.gap, chartH = 4 * st.patch + 3 * st.gap;
  const int labelH = int(std::ceil(draw::measureText("Ag", {st.fontSize, true}).height));
  EXPECT_EQ(img.width, 2 * st.margin + 3 * chartW + 2 * st.chartGap);
  EXPECT_EQ(img.height, st.margin + labelH + st.labelGap + chartH + st.margin);

  const SwatchLayout l = swatchLayout(charts, 6);
  ASSERT_EQ(l.patches.size(), 3u);
  for (size_t c = 0; c < charts.size(); ++c) {
    ASSERT_EQ(l.patches[c].size(), 24u);
    for (size_t k = 0; k < 24; ++k) {
      const PixelBox& b = l.patches[c][k];
      EXPECT_EQ(b.x1 - b.x0, st.patch);
      const Vec3 got = pixel(img, 0.5 * (b.x0 + b.x1), 0.5 * (b.y0 + b.y1));
      for (int i = 0; i < 3; ++i) EXPECT_NEAR(got[i], charts[c].srgb[k][i], kLevel) << c << "/" << k;
      // The gap right of a patch (inside its chart) is the background.
      if (k % 6 != 5) {
        const Vec3 gap = pixel(img, b.x1 + 0.5 * st.gap, 0.5 * (b.y0 + b.y1));
        for (int i = 0; i < 3; ++i) EXPECT_NEAR(gap[i], st.background[i], kLevel);
      }
    }
  }
  // Patch k is in row k / 6, column k % 6.
  EXPECT_EQ(l.patches[0][7].x0, l.patches[0][1].x0);
  EXPECT_EQ(l.patches[0][7].y0, l.patches[0][1].y0 + st.patch + st.gap);

  // A caption adds a line below, drawn in the text colour; values outside [0, 1] are clamped.
  charts[0].srgb[0] = Vec3(1.5f, -0.2f, 0.5f);
  const Image withCaption = swatchCharts(charts, 6, "ColorChecker");
  const SwatchLayout lc = swatchLayout(charts, 6, "ColorChecker");
  EXPECT_GT(withCaption.height, img.height);
  ASSERT_FALSE(lc.caption.empty());
  EXPECT_GE(lc.caption.y0, l.patches[0][23].y1);
  int bright = 0;
  for (int y = int(lc.caption.y0); y < int(lc.caption.y1); ++y)
    for (int x = int(lc.caption.x0); x < int(lc.caption.x1); ++x) bright += withCaption.at(x, y, 0) > 0.6f;
  EXPECT_GT(bright, 20);
  const PixelBox& b0 = lc.patches[0][0];
  const Vec3 clamped = pixel(withCaption, 0.5 * (b0.x0 + b0.x1), 0.5 * (b0.y0 + b0.y1));
  EXPECT_NEAR(clamped.x, 1.0f, kLevel);
  EXPECT_NEAR(clamped.y, 0.0f, kLevel);
}
