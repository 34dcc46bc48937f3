#pragma once
// Minimal line / scatter plots rendered to an image (PNG), for the reports of validation/
// studies ("sharpness vs depth", "brightness vs rotation angle", "RMSE vs time"), with no
// plotting library: axes, ticks and tick labels, axis titles, a title, a legend, several
// series, linear or log axes, and vertical / horizontal marker lines (e.g. a predicted ψ or L).
// Text uses the built-in bitmap font (bitmap_font.h). Plus a small CSV writer for the data
// behind each plot.
//
// Writers write directly to the path given; for "no partial output", pass a temporary from
// OutputSet::add() and commit.
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "core/geometry.h"
#include "core/image.h"

namespace inim {

struct PlotSeries {
  std::string name;           // legend entry; empty: not listed in the legend
  std::vector<double> x, y;   // same length; a non-finite value breaks the line there
  std::optional<Vec3> color{};  // default: the palette colour of the series' index
  bool line = true;
  bool markers = true;
  double lineWidth = 2.0;     // px
  double markerRadius = 3.5;  // px
  double dash = 0.0;          // > 0: dashed line, dash length (and gap) in px
};

// A marker line across the plot: vertical at x = value (markers) or horizontal at
// y = value (hMarkers), with an optional label near its end.
struct PlotMarker {
  double value = 0.0;
  std::string label;
  Vec3 color{0.75f, 0.1f, 0.1f};
  double dash = 6.0;  // 0 = solid
};

struct PlotAxis {
  std::string title;
  std::optional<double> min, max;  // default: the data range (with markers), widened to whole ticks
  bool log = false;                // base-10 log scale; values <= 0 are left out
};

struct Plot {
  int width = 800, height = 500;  // px
  std::string title;
  PlotAxis x, y;
  std::vector<PlotSeries> series;
  std::vector<PlotMarker> markers;   // vertical lines at x = value
  std::vector<PlotMarker> hMarkers;  // horizontal lines at y = value
  bool legend = true;
  bool grid = true;
  int fontScale = 2;  // 5x7 glyphs x fontScale
};

// Where the data goes in a rendered plot. Pixel coordinates are continuous, x to the right
// and y down from the image's top-left corner (pixel centres at half-integers): the data
// range [xMin, xMax] x [yMin, yMax] maps to [left, right] x [bottom, top].
struct PlotFrame {
  double left = 0, top = 0, right = 0, bottom = 0;
  double xMin = 0, xMax = 1, yMin = 0, yMax = 1;
  bool logX = false, logY = false;
  std::vector<double> xTicks, yTicks;

  double pixelX(double x) const;
  double pixelY(double y) const;
  glm::dvec2 toPixel(double x, double y) const { return {pixelX(x), pixelY(y)}; }
  bool insideX(double x) const;  // within the shown range (and > 0 on a log axis)
  bool insideY(double y) const;
};

// The frame renderPlot() uses: data ranges, ticks and the plot area. InputError when a
// series' x and y lengths differ or an explicit range is empty.
PlotFrame plotFrame(const Plot& plot);
Image renderPlot(const Plot& plot);
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

// CSV (RFC 4180): fields with a comma, quote or newline are quoted, quotes doubled.
std::string csvField(const std::string& s);
// A number as CSV text: %.10g; "inf", "-inf" and "nan" for non-finite values.
std::string csvNumber(double v);
std::string csvText(const std::vector<std::string>& header, const std::vector<std::vector<std::string>>& rows);
// Writes header + rows; std::runtime_error if the file cannot be written.
void writeCsv(const std::string& path, const std::vector<std::string>& header,
              const std::vector<std::vector<std::string>>& rows);

}  // namespace inim
