#pragma once
// Figures for the reports of validation studies ("sharpness vs depth", "brightness vs
// rotation angle", "RMSE vs time"), drawn with Cairo and Pango (src/draw) into an image (PNG).
//
// A plot has one pair of axes (linear or base-10 log, ticks and tick labels, titles; named
// categories along x) and layers, bottom to top: a heat map (with a colour bar at the right),
// filled polygons, bars, marker lines (vertical at an x, horizontal at a y), line / scatter
// series (markers: disc, circle, triangle, cross), text annotations.
// The legend lists the named series, polygons and bars; it goes where it covers no data:
// the free corner of the plot area, else any free place inside, else outside at the right.
// The data behind each plot goes to CSV (csv.h, included here).
//
// Writers write directly to the path given; for "no partial output", pass a temporary from
// OutputSet::add() and commit.
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "analysis/colormap.h"
#include "analysis/csv.h"
#include "core/geometry.h"
#include "core/image.h"

namespace inim {

// The shape of a series' markers: filled disc, open circle, filled triangle (point up), cross (x).
enum class MarkerShape { Disc, Circle, Triangle, Cross };

struct PlotSeries {
  std::string name;           // legend entry; empty: not listed in the legend
  std::vector<double> x, y;   // same length; a non-finite value breaks the line there
  std::optional<Vec3> color{};  // default: the palette colour of the series' index
  bool line = true;
  bool markers = true;
  double lineWidth = 2.0;     // px
  double markerRadius = 3.5;  // px
  double dash = 0.0;          // > 0: dashed line, dash length (and gap) in px
  MarkerShape marker = MarkerShape::Disc;
};

// A marker line across the plot: vertical at x = value (markers) or horizontal at
// y = value (hMarkers), with an optional label near its end.
struct PlotMarker {
  double value = 0.0;
  std::string label;
  Vec3 color{0.75f, 0.1f, 0.1f};
  double dash = 6.0;  // 0 = solid
};

// A filled polygon in data coordinates (a gamut triangle, a band), closed automatically.
struct PlotPolygon {
  std::string name;             // legend entry; empty: not listed
  std::vector<double> x, y;     // the vertices, same length
  std::optional<Vec3> color{};  // default: the palette colour after the series'
  double alpha = 0.35;          // opacity of the fill
  double edgeWidth = 1.0;       // outline in the solid colour, px; 0: none
};

// Bars from `base` up (or down) to y at each x: a histogram, the bins of a spectrum.
struct PlotBars {
  std::string name;             // legend entry; empty: not listed
  std::vector<double> x, y;     // bar centres and heights, same length
  double width = 0.0;           // in x units; 0: 0.8 x the smallest spacing of x (0.8 for one bar)
  double base = 0.0;
  std::optional<Vec3> color{};  // default: the palette colour after the series' and polygons'
};

// A grid of values shown as colours, over the data rectangle [x0, x1] x [y0, y1]: cell
// (column c, row r) covers x0 + [c, c+1] (x1 - x0) / cols and y0 + [r, r+1] (y1 - y0) / rows,
// so row 0 is at y0 (the bottom when y0 < y1). Non-finite values are left transparent.
struct PlotHeatMap {
  int cols = 0, rows = 0;
  std::vector<double> values;      // rows * cols, row-major: values[r * cols + c]
  double x0 = 0.0, x1 = 1.0, y0 = 0.0, y1 = 1.0;
  std::optional<double> min{}, max{};  // colour range; default: the range of the finite values
  ColorMap map = ColorMap::Viridis;
  std::string label{};             // title of the colour bar
};

// Which point of a text's box sits on its anchor.
enum class TextAnchorPoint { TopLeft, Top, TopRight, Left, Centre, Right, BottomLeft, Bottom, BottomRight };

// A text annotation at a data position (left out when the position is outside the axes).
struct PlotText {
  double x = 0.0, y = 0.0;
  std::string text;
  Vec3 color{0.1f, 0.1f, 0.1f};
  TextAnchorPoint anchor = TextAnchorPoint::BottomLeft;
};

struct PlotAxis {
  std::string title;
  std::optional<double> min, max;  // default: the data range (with markers), widened to whole ticks
  bool log = false;                // base-10 log scale; values <= 0 are left out
  // Category names (x axis only, linear): the ticks are at x = 0, 1, ..., n-1 and labelled
  // with these names, turned to read upwards when they do not fit side by side (patches of a
  // colour chart under grouped bars). The default range is then [-0.5, n - 0.5]; no grid
  // lines are drawn across at the ticks.
  std::vector<std::string> categories{};
};

struct Plot {
  int width = 800, height = 500;  // px
  std::string title;
  PlotAxis x, y;
  std::vector<PlotSeries> series;
  std::vector<PlotPolygon> polygons;
  std::vector<PlotBars> bars;
  std::optional<PlotHeatMap> heatMap;
  std::vector<PlotText> texts;
  std::vector<PlotMarker> markers;   // vertical lines at x = value
  std::vector<PlotMarker> hMarkers;  // horizontal lines at y = value
  bool legend = true;
  bool grid = true;
  // Panels stacked in one figure line up their plot areas (alignPlotAreas): the area's left
  // edge at least areaLeftMin px from the image's left edge, its right edge at least
  // areaRightInset px from the image's right edge. 0: as the plot's own layout needs.
  double areaLeftMin = 0.0, areaRightInset = 0.0;
  double fontSize = 13.0;  // px, of tick labels, legend and annotations (titles a little larger)
};

// A rectangle in pixels, [x0, x1) x [y0, y1).
struct PixelBox {
  double x0 = 0.0, y0 = 0.0, x1 = 0.0, y1 = 0.0;
  bool empty() const { return !(x1 > x0 && y1 > y0); }
  bool overlaps(const PixelBox& o) const { return !empty() && !o.empty() && x0 < o.x1 && o.x0 < x1 && y0 < o.y1 && o.y0 < y1; }
};

// Where things go in a rendered plot. Pixel coordinates are continuous, x to the right and y
// down from the image's top-left corner (pixel centres at half-integers): the data range
// [xMin, xMax] x [yMin, yMax] maps to [left, right] x [bottom, top] (whole pixels).
struct PlotFrame {
  double left = 0, top = 0, right = 0, bottom = 0;
  double xMin = 0, xMax = 1, yMin = 0, yMax = 1;
  bool logX = false, logY = false;
  std::vector<double> xTicks, yTicks;
  bool xLabelsUp = false;      // the x tick labels (categories) are turned to read upwards
  PixelBox legend;             // the legend's box; empty without a legend
  bool legendOutside = false;  // no free room inside: the legend is right of the plot area
  PixelBox colorBar;           // the heat map's colour bar; empty without a heat map
  double cMin = 0, cMax = 1;   // the colour bar's range (cMin at its bottom)
  std::vector<double> cTicks;

  double pixelX(double x) const;
  double pixelY(double y) const;
  glm::dvec2 toPixel(double x, double y) const { return {pixelX(x), pixelY(y)}; }
  double dataX(double px) const;  // the inverse of pixelX
  double dataY(double py) const;
  bool insideX(double x) const;  // within the shown range (and > 0 on a log axis)
  bool insideY(double y) const;
};

// The frame renderPlot() uses: data ranges, ticks, the plot area, the legend's place (which
// depends on where the data is drawn) and the colour bar. InputError when a layer's x and y
// lengths differ, a heat map's size does not match its values, an explicit range is empty, or
// categories are given for the y axis or a log x axis.
PlotFrame plotFrame(const Plot& plot);
Image renderPlot(const Plot& plot);
// Sets the plots' areaLeftMin and areaRightInset so that, all of the same width, their plot
// areas share one left and one right edge (an x axis read across panels stacked vertically).
void alignPlotAreas(std::vector<Plot*> plots);
// renderPlot + writeImage (PNG by extension).
void writePlot(const Plot& plot, const std::string& path);

// Ticks: multiples of 1, 2 or 5 x 10^k inside [lo, hi], at most about maxTicks of them.
std::vector<double> niceTicks(double lo, double hi, int maxTicks = 8);
double niceStep(double lo, double hi, int maxTicks = 8);
// Ticks of a log axis: powers of ten inside [lo, hi] (lo > 0); 1-2-5 steps when the range
// spans less than two decades.
std::vector<double> logTicks(double lo, double hi);
// A tick label with just enough decimals for ticks `step` apart.
std::string formatTick(double value, double step);
// The default colour of series i (matplotlib's "tab10" palette).
Vec3 plotPalette(int i);

}  // namespace inim
