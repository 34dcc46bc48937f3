// The legend never covers data: it takes a free corner of the plot area (top right first),
// else a free place inside, else a column right of the plot area; it leaves every data pixel
// as it was.
#include <gtest/gtest.h>

#include <cmath>

#include "analysis/plot.h"
#include "analysis/plot_test_util.h"

using namespace inim;
using plot_test::darkIn;
using plot_test::dataPixels;

namespace {

Plot basePlot() {
  Plot p;
  p.width = 700, p.height = 450;
  p.title = "legend placement";
  p.x.min = 0.0, p.x.max = 10.0;
  p.y.min = 0.0, p.y.max = 10.0;
  return p;
}

PlotSeries curve(const std::string& name, double (*f)(double), double x0 = 0.0, double x1 = 10.0) {
  PlotSeries s{name, {}, {}};
  for (int i = 0; i <= 100; ++i) {
    const double x = x0 + (x1 - x0) * i / 100.0;
    s.x.push_back(x);
    s.y.push_back(f(x));
  }
  s.markers = false;
  return s;
}

// The legend box holds no data pixel, and the rendered plot keeps every data pixel as the
// plot without a legend has it.
void expectLegendClearOfData(const Plot& p) {
  const PlotFrame f = plotFrame(p);
  ASSERT_FALSE(f.legend.empty());
  const std::vector<bool> ink = dataPixels(p);
  Plot noLegend = p;
  noLegend.legend = false;
  const Image with = renderPlot(p), without = renderPlot(noLegend);
  int inBox = 0, changed = 0, data = 0;
  for (int y = 0; y < p.height; ++y)
    for (int x = 0; x < p.width; ++x) {
      const size_t i = size_t(y) * size_t(p.width) + size_t(x);
      if (!ink[i]) continue;
      ++data;
      inBox += x >= f.legend.x0 && x < f.legend.x1 && y >= f.legend.y0 && y < f.legend.y1;
      for (int c = 0; c < 3; ++c) changed += with.at(x, y, c) != without.at(x, y, c);
    }
  EXPECT_GT(data, 200);  // the check is not vacuous
  EXPECT_EQ(inBox, 0);
  EXPECT_EQ(changed, 0);
  // The legend is drawn where the frame says: its entries' text is inside the box.
  EXPECT_GT(darkIn(with, f.legend.x0 + 2, f.legend.y0 + 2, f.legend.x1 - 2, f.legend.y1 - 2, 0.3f), 20);
}

// A dense zigzag over the whole plot area of basePlot: no free place inside.
PlotSeries denseZigzag() {
  PlotSeries z{"zigzag", {}, {}};
  for (int i = 0; i <= 120; ++i) z.x.push_back(i / 12.0), z.y.push_back(i % 2 ? 10.0 : 0.0);
  z.markers = false;
  return z;
}

}  // namespace

TEST(PlotLegend, TopRightWhenFree) {
  Plot p = basePlot();
  p.series.push_back(curve("rising slowly", [](double x) { return 0.3 * x; }));
  const PlotFrame f = plotFrame(p);
  ASSERT_FALSE(f.legend.empty());
  EXPECT_FALSE(f.legendOutside);
  EXPECT_GT(f.legend.x0, 0.5 * (f.left + f.right));  // right half
  EXPECT_LT(f.legend.y1, 0.5 * (f.top + f.bottom));  // top half
  expectLegendClearOfData(p);
}

TEST(PlotLegend, MovesToTheCornerTheDataLeaves) {
  // A falling curve fills the top left and the bottom right: the top right is free.
  Plot p = basePlot();
  p.series.push_back(curve("falling", [](double x) { return 10.0 - x; }));
  p.series.push_back(curve("falling too", [](double x) { return 9.0 - x; }));
  PlotFrame f = plotFrame(p);
  EXPECT_GT(f.legend.x0, 0.5 * (f.left + f.right));
  EXPECT_LT(f.legend.y1, 0.5 * (f.top + f.bottom));
  expectLegendClearOfData(p);
  // A valley (high at both ends) blocks both top corners: a bottom corner it is.
  Plot v = basePlot();
  v.series.push_back(curve("valley", [](double x) { return 0.4 * (x - 5.0) * (x - 5.0); }));
  v.series.push_back(curve("valley, shifted", [](double x) { return 0.4 * (x - 5.0) * (x - 5.0) + 0.5; }));
  f = plotFrame(v);
  ASSERT_FALSE(f.legendOutside);
  EXPECT_GT(f.legend.y0, 0.5 * (f.top + f.bottom));  // bottom half
  expectLegendClearOfData(v);
  // Data in all four corners (and the marker lines) but a gap in the middle: it goes there.
  Plot c = basePlot();
  c.series.push_back(curve("top", [](double) { return 9.5; }));
  c.series.push_back(curve("bottom", [](double) { return 0.5; }));
  PlotSeries left{"left", {0.5, 0.5}, {0.0, 10.0}}, right{"right", {9.5, 9.5}, {0.0, 10.0}};
  c.series.push_back(left);
  c.series.push_back(right);
  f = plotFrame(c);
  ASSERT_FALSE(f.legendOutside);
  expectLegendClearOfData(c);
}

TEST(PlotLegend, OutsideWhenNoRoomInside) {
  Plot p = basePlot();
  p.series.push_back(denseZigzag());
  p.series.push_back(curve("line", [](double x) { return x; }));
  const PlotFrame f = plotFrame(p);
  ASSERT_TRUE(f.legendOutside);
  EXPECT_GE(f.legend.x0, f.right + 2.0);  // right of the plot area and its frame line
  EXPECT_LE(f.legend.x1, p.width);
  EXPECT_GE(f.legend.y0, 0.0);
  EXPECT_LE(f.legend.y1, p.height);
  // The plot area narrowed for it; the data stays untouched by the legend.
  Plot noLegend = p;
  noLegend.legend = false;
  EXPECT_LT(f.right, plotFrame(noLegend).right - (f.legend.x1 - f.legend.x0));
  const Image img = renderPlot(p);
  EXPECT_GT(darkIn(img, f.legend.x0 + 2, f.legend.y0 + 2, f.legend.x1 - 2, f.legend.y1 - 2, 0.3f), 20);
  EXPECT_EQ(darkIn(img, f.right + 2, f.legend.y1 + 2, p.width, f.bottom), 0);  // nothing else out there
}

// Panels stacked in one figure: one with its legend outside and narrow tick labels, one
// without a legend and with wide ones. Aligned, their plot areas share both edges, and the
// legend still sits right of the area, clear of it.
TEST(PlotLegend, StackedPanelsLineUpWhenTheLegendGoesOutside) {
  Plot top = basePlot();
  top.series.push_back(denseZigzag());
  Plot bottom = basePlot();
  bottom.legend = false;
  bottom.y.max = 123450.0;  // wide tick labels
  bottom.series.push_back(curve("wide labels", [](double x) { return 12345.0 * x; }));
  ASSERT_TRUE(plotFrame(top).legendOutside);
  ASSERT_NE(plotFrame(top).right, plotFrame(bottom).right);
  ASSERT_NE(plotFrame(top).left, plotFrame(bottom).left);
  alignPlotAreas({&top, &bottom});
  const PlotFrame a = plotFrame(top), b = plotFrame(bottom);
  EXPECT_EQ(a.left, b.left);
  EXPECT_EQ(a.right, b.right);
  EXPECT_TRUE(a.legendOutside);
  EXPECT_GE(a.legend.x0, a.right + 2.0);
  EXPECT_EQ(a.xMin, b.xMin);
  EXPECT_EQ(a.xMax, b.xMax);
}

TEST(PlotLegend, ListsOnlyNamedLayersAndNothingWithoutNames) {
  Plot p = basePlot();
  PlotSeries unnamed{"", {1.0, 9.0}, {1.0, 2.0}};
  p.series.push_back(unnamed);
  EXPECT_TRUE(plotFrame(p).legend.empty());
  p.legend = true;
  PlotBars bars{"bars", {2.0, 3.0}, {1.0, 2.0}};
  p.bars.push_back(bars);
  PlotPolygon poly{"area", {6.0, 8.0, 7.0}, {1.0, 1.0, 3.0}};
  p.polygons.push_back(poly);
  const PlotFrame f = plotFrame(p);
  ASSERT_FALSE(f.legend.empty());
  // Two rows: taller than one line of text, shorter than three.
  const double h = f.legend.y1 - f.legend.y0;
  EXPECT_GT(h, 2.0 * 13.0);
  EXPECT_LT(h, 3.0 * 13.0 * 1.3 + 14.0);
  p.legend = false;
  EXPECT_TRUE(plotFrame(p).legend.empty());
}
