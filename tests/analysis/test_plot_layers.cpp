// The layers besides series: bars span their base to their height, polygons are filled
// inside only, a heat map puts each cell's colour where its data rectangle is and has a
// monotone colour bar, text annotations are drawn at their data position; and colour maps.
#include <gtest/gtest.h>

#include <cmath>

#include "analysis/plot.h"
#include "analysis/plot_test_util.h"

using namespace inim;
using plot_test::darkIn;

namespace {

const float kLevel = 0.5f / 255.0f + 1e-6f;  // half an 8-bit level

Vec3 at(const Image& img, double x, double y) {
  const int i = int(std::floor(x)), j = int(std::floor(y));
  return {img.at(i, j, 0), img.at(i, j, 1), img.at(i, j, 2)};
}

void expectColour(const Vec3& got, const Vec3& want, float tol, const std::string& where) {
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(got[c], want[c], tol) << where << " channel " << c;
}

// Perceived lightness of a display colour (Rec. 709 weights on the encoded values).
double luma(const Vec3& c) { return 0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z; }

Plot axes(double x0, double x1, double y0, double y1) {
  Plot p;
  p.width = 600, p.height = 400;
  p.grid = false;
  p.x.min = x0, p.x.max = x1, p.y.min = y0, p.y.max = y1;
  return p;
}

}  // namespace

TEST(PlotLayers, BarsSpanBaseToHeight) {
  Plot p = axes(0.0, 4.0, 0.0, 6.0);
  const Vec3 green(0.1f, 0.6f, 0.2f);
  PlotBars b{"counts", {1.0, 2.0, 3.0}, {2.0, 5.0, 3.0}};
  b.width = 0.5;
  b.color = green;
  p.bars.push_back(b);
  p.legend = false;
  const Image img = renderPlot(p);
  const PlotFrame f = plotFrame(p);
  for (size_t k = 0; k < 3; ++k) {
    const double x = f.pixelX(b.x[k]), top = f.pixelY(b.y[k]);
    expectColour(at(img, x, 0.5 * (top + f.bottom)), green, kLevel, "bar middle");
    expectColour(at(img, x, top + 1.5), green, kLevel, "just below the top");
    expectColour(at(img, x, top - 1.5), Vec3(1.0f), 0.0f, "just above the top");
    // The bar's half-width, 0.25 x units, either side of its centre.
    expectColour(at(img, f.pixelX(b.x[k] - 0.2), top + 3), green, kLevel, "left part");
    expectColour(at(img, f.pixelX(b.x[k] - 0.3), top + 3), Vec3(1.0f), 0.0f, "left of the bar");
  }
  // Default width: 0.8 of the spacing; bars below zero grow down from the base.
  PlotBars d{"", {1.0, 2.0}, {-1.0, 1.0}};
  d.color = green;
  Plot q = axes(0.0, 3.0, -2.0, 2.0);
  q.bars.push_back(d);
  const Image qi = renderPlot(q);
  const PlotFrame g = plotFrame(q);
  expectColour(at(qi, g.pixelX(1.35), g.pixelY(-0.5)), green, kLevel, "down bar, inside 0.4");
  expectColour(at(qi, g.pixelX(1.45), g.pixelY(-0.5)), Vec3(1.0f), 0.0f, "down bar, outside 0.4");
  expectColour(at(qi, g.pixelX(1.0), g.pixelY(0.5)), Vec3(1.0f), 0.0f, "above the down bar");
}

TEST(PlotLayers, PolygonsFillInsideOnly) {
  Plot p = axes(0.0, 1.0, 0.0, 1.0);
  const Vec3 c(0.2f, 0.4f, 0.8f);
  PlotPolygon tri{"gamut", {0.1, 0.9, 0.5}, {0.1, 0.1, 0.9}};
  tri.color = c;
  tri.alpha = 0.5;
  tri.edgeWidth = 2.0;
  p.polygons.push_back(tri);
  const Image img = renderPlot(p);
  const PlotFrame f = plotFrame(p);
  // Inside: the colour at half opacity over white.
  const Vec3 half = 0.5f * c + Vec3(0.5f);
  expectColour(at(img, f.pixelX(0.5), f.pixelY(0.4)), half, 1.5f / 255.0f, "inside");
  // Outside (left of the left edge, above the apex): white.
  expectColour(at(img, f.pixelX(0.2), f.pixelY(0.6)), Vec3(1.0f), 0.0f, "outside");
  expectColour(at(img, f.pixelX(0.5), f.pixelY(0.97)), Vec3(1.0f), 0.0f, "above the apex");
  // The edge, on the base, in the solid colour.
  expectColour(at(img, f.pixelX(0.5), std::floor(f.pixelY(0.1)) + 0.5), c, 0.1f, "edge");
}

TEST(PlotLayers, HeatMapCellsAndMonotoneColourBar) {
  Plot p = axes(0.0, 4.0, 0.0, 3.0);
  PlotHeatMap h;
  h.cols = 4, h.rows = 3;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 4; ++c) h.values.push_back(r * 4 + c);  // 0 .. 11, row 0 at y = 0
  h.values[5] = std::nan("");                                    // a hole
  h.x0 = 0.0, h.x1 = 4.0, h.y0 = 0.0, h.y1 = 3.0;
  h.label = "value";
  p.heatMap = h;
  const Image img = renderPlot(p);
  const PlotFrame f = plotFrame(p);
  EXPECT_DOUBLE_EQ(f.cMin, 0.0);
  EXPECT_DOUBLE_EQ(f.cMax, 11.0);
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 4; ++c) {
      const Vec3 got = at(img, f.pixelX(c + 0.5), f.pixelY(r + 0.5));
      const double v = h.values[size_t(r * 4 + c)];
      const Vec3 want = std::isfinite(v) ? colorMap(ColorMap::Viridis, v / 11.0) : Vec3(1.0f);
      expectColour(got, want, 1.5f / 255.0f, "cell " + std::to_string(r) + "," + std::to_string(c));
    }
  // The colour bar: right of the plot area, as tall as it, lightness rising bottom to top
  // from the map's first colour to its last.
  const PixelBox& b = f.colorBar;
  ASSERT_FALSE(b.empty());
  EXPECT_GT(b.x0, f.right);
  EXPECT_LE(b.x1, p.width);
  EXPECT_EQ(b.y0, f.top);
  EXPECT_EQ(b.y1, f.bottom);
  // Each row's colour is the map's at its height; lightness never falls going up by more
  // than 8-bit rounding of one channel can make it (a quarter of a level).
  const double cx = 0.5 * (b.x0 + b.x1);
  double prev = -1.0;
  int falls = 0;
  for (int y = int(b.y1) - 1; y >= int(b.y0); --y) {
    const Vec3 got = at(img, cx, y + 0.5);
    const double t = (b.y1 - (y + 0.5)) / (b.y1 - b.y0);
    expectColour(got, colorMap(ColorMap::Viridis, t), 1.0f / 255.0f, "bar row " + std::to_string(y));
    falls += luma(got) < prev - 0.25 / 255.0;
    prev = std::max(prev, luma(got));
  }
  EXPECT_EQ(falls, 0);
  EXPECT_GT(luma(at(img, cx, b.y0 + 0.5)) - luma(at(img, cx, b.y1 - 0.5)), 0.6);
  expectColour(at(img, cx, b.y1 - 0.5), colorMap(ColorMap::Viridis, 0.0), 2.0f / 255.0f, "bar bottom");
  expectColour(at(img, cx, b.y0 + 0.5), colorMap(ColorMap::Viridis, 1.0), 2.0f / 255.0f, "bar top");
  // Its tick labels right of it, and its title further right.
  ASSERT_GE(f.cTicks.size(), 2u);
  EXPECT_GT(darkIn(img, b.x1 + 2, b.y0 - 8, b.x1 + 40, b.y1 + 8), 20);
  EXPECT_GT(darkIn(img, b.x1 + 30, b.y0, p.width, b.y1), 20);
}

TEST(PlotLayers, HeatMapPushesTheLegendOutside) {
  Plot p = axes(0.0, 1.0, 0.0, 1.0);
  p.heatMap = PlotHeatMap{2, 2, {0.0, 1.0, 2.0, 3.0}};
  p.series.push_back({"profile", {0.1, 0.9}, {0.2, 0.8}});
  const PlotFrame f = plotFrame(p);
  ASSERT_TRUE(f.legendOutside);
  EXPECT_GE(f.legend.x0, f.colorBar.x1);  // plot area | colour bar | legend
  EXPECT_FALSE(f.legend.overlaps(f.colorBar));
}

TEST(PlotLayers, TextAnnotationsAtTheirDataPosition) {
  Plot p = axes(0.0, 10.0, 0.0, 10.0);
  p.texts.push_back({2.0, 8.0, "D65", Vec3(0.0f), TextAnchorPoint::TopLeft});
  p.texts.push_back({8.0, 2.0, "E", Vec3(0.0f), TextAnchorPoint::BottomRight});
  p.texts.push_back({20.0, 2.0, "outside the axes", Vec3(0.0f)});
  const Image img = renderPlot(p);
  const PlotFrame f = plotFrame(p);
  const glm::dvec2 a = f.toPixel(2.0, 8.0), b = f.toPixel(8.0, 2.0);
  EXPECT_GT(darkIn(img, a.x, a.y, a.x + 40, a.y + 18), 15);  // below right of its anchor
  EXPECT_EQ(darkIn(img, a.x - 30, a.y - 20, a.x - 1, a.y - 1), 0);
  EXPECT_GT(darkIn(img, b.x - 20, b.y - 18, b.x, b.y), 5);  // above left of its anchor
  EXPECT_EQ(darkIn(img, b.x + 1, b.y + 1, b.x + 30, b.y + 20), 0);
  // Only the two annotations in the plot area (no grid is dark).
  const int all = darkIn(img, f.left + 1, f.top + 1, f.right - 1, f.bottom - 1);
  EXPECT_EQ(all, darkIn(img, a.x, a.y, a.x + 40, a.y + 18) + darkIn(img, b.x - 20, b.y - 18, b.x, b.y));
}

TEST(PlotLayers, MarkerShapes) {
  Plot p = axes(0.0, 5.0, 0.0, 2.0);
  p.legend = false;
  const Vec3 c(0.1f, 0.2f, 0.7f);
  const MarkerShape shapes[4] = {MarkerShape::Disc, MarkerShape::Circle, MarkerShape::Triangle, MarkerShape::Cross};
  for (int i = 0; i < 4; ++i) {
    PlotSeries s{"", {double(i + 1)}, {1.0}};
    s.line = false, s.color = c, s.markerRadius = 6.0, s.marker = shapes[i];
    p.series.push_back(s);
  }
  const Image img = renderPlot(p);
  const PlotFrame f = plotFrame(p);
  auto at = [&](int i, double dx, double dy) {
    const glm::dvec2 q = f.toPixel(i + 1.0, 1.0);
    return ::at(img, q.x + dx, q.y + dy);
  };
  const Vec3 white(1.0f);
  // Disc: filled to its radius.
  expectColour(at(0, 0, 0), c, kLevel, "disc centre");
  expectColour(at(0, 0, -9), white, 0.0f, "beyond the disc");
  // Circle: open, a ring just outside the radius.
  expectColour(at(1, 0, 0), white, 0.0f, "circle centre");
  expectColour(at(1, 0, -7.2), c, 0.1f, "circle ring");
  // Triangle, point up: filled at the centre and towards the apex, empty beside the apex.
  expectColour(at(2, 0, 0), c, kLevel, "triangle centre");
  expectColour(at(2, 0, -6), c, 0.1f, "towards the apex");
  expectColour(at(2, 5, -6), white, 0.0f, "beside the apex");
  // Cross: ink along the diagonals, none straight up or across.
  expectColour(at(3, 0, 0), c, 0.1f, "cross centre");
  expectColour(at(3, 4.5, 4.5), c, 0.15f, "cross arm");
  expectColour(at(3, 0, -5), white, 0.0f, "above the cross centre");
  expectColour(at(3, 5, 0), white, 0.0f, "right of the cross centre");
}

TEST(PlotLayers, ColourMapsRiseInLightness) {
  for (ColorMap m : {ColorMap::Viridis, ColorMap::Grey}) {
    double prev = -1.0;
    for (int i = 0; i <= 256; ++i) {
      const double l = luma(colorMap(m, i / 256.0));
      EXPECT_GT(l, prev);
      prev = l;
    }
    EXPECT_EQ(colorMap(m, -1.0), colorMap(m, 0.0));
    EXPECT_EQ(colorMap(m, 2.0), colorMap(m, 1.0));
  }
  // Viridis' ends and middle (matplotlib's entries 0, 128 and 255).
  expectColour(colorMap(ColorMap::Viridis, 0.0), Vec3(0.267004f, 0.004874f, 0.329415f), 1e-6f, "viridis 0");
  expectColour(colorMap(ColorMap::Viridis, 128.0 / 255.0), Vec3(0.127568f, 0.566949f, 0.550556f), 1e-6f,
               "viridis 128");
  expectColour(colorMap(ColorMap::Viridis, 1.0), Vec3(0.993248f, 0.906157f, 0.143936f), 1e-6f, "viridis 255");
}
