// The frame of a plot: data ranges and ticks, the plot area inside its labels, the colour
// bar, and the legend's place (a free spot inside the plot area, else outside at the right).
#include <algorithm>
#include <cmath>
#include <limits>

#include "analysis/plot.h"
#include "analysis/plot_internal.h"
#include "core/error.h"

namespace inim {

namespace {

using plotimpl::usable;

double axisValue(double v, bool log) { return log ? std::log10(v) : v; }

// A single value (or none): a range around it.
void widenEmpty(const PlotAxis& axis, double& lo, double& hi) {
  if (hi > lo) return;
  if (axis.log) {
    if (!axis.min) lo /= 2.0;
    if (!axis.max) hi *= 2.0;
    if (!(hi > lo)) hi = lo * 4.0;
  } else {
    const double d = lo == 0.0 ? 1.0 : 0.1 * std::abs(lo);
    if (!axis.min) lo -= d;
    if (!axis.max) hi += d;
    if (!(hi > lo)) hi = lo + 2.0 * d;
  }
}

// The shown range and ticks of one axis: the data range, or the axis' own limits, widened
// to whole ticks (whole decades on a log axis) where not given.
void axisRange(const PlotAxis& axis, const std::vector<double>& values, int maxTicks, double& lo, double& hi,
               std::vector<double>& ticks, const char* which) {
  bool have = false;
  double dlo = 0.0, dhi = 0.0;
  for (double v : values)
    if (usable(v, axis.log)) {
      if (!have) dlo = dhi = v, have = true;
      dlo = std::min(dlo, v);
      dhi = std::max(dhi, v);
    }
  if (!have) dlo = axis.log ? 1.0 : 0.0, dhi = axis.log ? 10.0 : 1.0;
  if (axis.min) dlo = *axis.min;
  if (axis.max) dhi = *axis.max;
  if (axis.min && axis.max && !(*axis.max > *axis.min))
    throw InputError("", std::string(which) + " axis range",
                     formatTick(*axis.min, 1e-6) + " .. " + formatTick(*axis.max, 1e-6), "min < max");
  if (axis.log && (!(dlo > 0.0) || !(dhi > 0.0)))
    throw InputError("", std::string(which) + " axis range", formatTick(dlo, 1e-6), "positive values on a log axis");
  widenEmpty(axis, dlo, dhi);
  if (axis.log) {
    if (!axis.min) dlo = std::pow(10.0, std::floor(std::log10(dlo) + 1e-9));
    if (!axis.max) dhi = std::pow(10.0, std::ceil(std::log10(dhi) - 1e-9));
    lo = dlo, hi = dhi;
    ticks = logTicks(lo, hi);
  } else {
    const double step = niceStep(dlo, dhi, maxTicks);
    if (!axis.min) dlo = std::floor(dlo / step + 1e-9) * step;
    if (!axis.max) dhi = std::ceil(dhi / step - 1e-9) * step;
    lo = dlo, hi = dhi;
    ticks = niceTicks(lo, hi, maxTicks);
  }
}

// A category axis: ticks at the categories' indices inside the range, by default
// [-0.5, n - 0.5] (whatever the data's extent).
void categoryRange(const PlotAxis& axis, double& lo, double& hi, std::vector<double>& ticks) {
  if (axis.log) throw InputError("", "x axis categories", "on a log axis", "a linear axis");
  lo = axis.min.value_or(-0.5);
  hi = axis.max.value_or(double(axis.categories.size()) - 0.5);
  if (!(hi > lo))
    throw InputError("", "x axis range", formatTick(lo, 1e-6) + " .. " + formatTick(hi, 1e-6), "min < max");
  ticks.clear();
  for (size_t i = 0; i < axis.categories.size(); ++i)
    if (double(i) >= lo && double(i) <= hi) ticks.push_back(double(i));
}

void checkLengths(size_t nx, size_t ny, const std::string& what) {
  if (nx != ny)
    throw InputError("", what, std::to_string(nx) + " x values and " + std::to_string(ny) + " y values",
                     "as many x values as y values");
}

// Every value that sets the axes' ranges: points of series and polygons, bar extents, the
// heat map's rectangle, marker lines. Checks the layers' sizes on the way.
void dataValues(const Plot& p, std::vector<double>& xs, std::vector<double>& ys) {
  auto name = [](const std::string& kind, const std::string& n, size_t i) {
    return kind + " " + (n.empty() ? std::to_string(i) : n);
  };
  auto points = [&](const std::vector<double>& x, const std::vector<double>& y) {
    for (size_t k = 0; k < x.size(); ++k)
      if (usable(x[k], p.x.log) && usable(y[k], p.y.log)) xs.push_back(x[k]), ys.push_back(y[k]);
  };
  for (size_t i = 0; i < p.series.size(); ++i) {
    checkLengths(p.series[i].x.size(), p.series[i].y.size(), name("plot series", p.series[i].name, i));
    points(p.series[i].x, p.series[i].y);
  }
  for (size_t i = 0; i < p.polygons.size(); ++i) {
    checkLengths(p.polygons[i].x.size(), p.polygons[i].y.size(), name("plot polygon", p.polygons[i].name, i));
    points(p.polygons[i].x, p.polygons[i].y);
  }
  for (size_t i = 0; i < p.bars.size(); ++i) {
    const PlotBars& b = p.bars[i];
    checkLengths(b.x.size(), b.y.size(), name("plot bars", b.name, i));
    const double hw = 0.5 * plotimpl::barWidth(b);
    for (size_t k = 0; k < b.x.size(); ++k) points({b.x[k] - hw, b.x[k] + hw, b.x[k]}, {b.y[k], b.y[k], b.base});
  }
  if (const auto& h = p.heatMap) {
    if (h->cols <= 0 || h->rows <= 0 || h->values.size() != size_t(h->cols) * size_t(h->rows))
      throw InputError("", "plot heat map", std::to_string(h->values.size()) + " values for " +
                       std::to_string(h->cols) + " x " + std::to_string(h->rows) + " cells",
                       "cols x rows values, both > 0");
    points({h->x0, h->x1}, {h->y0, h->y1});
  }
  for (const PlotMarker& m : p.markers) xs.push_back(m.value);
  for (const PlotMarker& m : p.hMarkers) ys.push_back(m.value);
}

double widestLabel(const std::vector<double>& ticks, bool log, const draw::Font& font) {
  double w = 0.0;
  for (double t : ticks) w = std::max(w, draw::measureText(plotimpl::tickLabel(ticks, log, t), font).width);
  return w;
}

// The heat map's colour range (the finite values' range unless given) and ticks, and the
// width the colour bar with its labels needs right of the plot area.
double colorBarRange(const Plot& p, const plotimpl::Style& st, PlotFrame& f) {
  const PlotHeatMap& h = *p.heatMap;
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (double v : h.values)
    if (std::isfinite(v)) lo = std::min(lo, v), hi = std::max(hi, v);
  if (!std::isfinite(lo)) lo = 0.0, hi = 1.0;
  if (h.min) lo = *h.min;
  if (h.max) hi = *h.max;
  if (h.min && h.max && !(hi > lo))
    throw InputError("", "heat map colour range", formatTick(lo, 1e-6) + " .. " + formatTick(hi, 1e-6), "min < max");
  PlotAxis c;
  c.min = h.min;
  c.max = h.max;
  widenEmpty(c, lo, hi);
  f.cMin = lo, f.cMax = hi;
  f.cTicks = niceTicks(lo, hi, std::clamp(int((f.bottom - f.top) / (3.0 * p.fontSize)), 2, 10));
  const double labels = widestLabel(f.cTicks, false, st.tick);
  const double title = h.label.empty() ? 0.0 : st.gap + draw::measureText(h.label, st.axisTitle).height;
  return std::ceil(p.fontSize + std::round(1.2 * p.fontSize) + st.tickLength + st.gap + labels + title);
}

// The right edge of the plot area and the colour bar's box, with `reserve` px kept free at
// the right of the image (an outside legend).
void horizontalLayout(const Plot& p, const plotimpl::Style& st, double colorBarW, double reserve, PlotFrame& f) {
  // Room for the last x tick label, centred on the right edge; a colour bar or legend there
  // starts a font size further right.
  const double lastX =
      f.xTicks.empty() ? 0.0 : draw::measureText(plotimpl::xTickLabel(p, f, f.xTicks.back()), st.tick).width;
  const double room = colorBarW > 0.0 || reserve > 0.0 ? std::max(lastX / 2.0 - p.fontSize, 0.0)
                                                       : std::max(lastX / 2.0, st.gap);
  f.right = std::floor(p.width - std::max(st.margin + room + colorBarW + reserve, p.areaRightInset));
  if (colorBarW > 0.0) {
    f.colorBar.x0 = f.right + std::round(p.fontSize);
    f.colorBar.x1 = f.colorBar.x0 + std::round(1.2 * p.fontSize);
    f.colorBar.y0 = f.top;
    f.colorBar.y1 = f.bottom;
  }
}

// Category labels that do not fit side by side (in the plot area as narrow as an outside
// legend would make it) are turned to read upwards; the plot area's bottom moves up for them.
void turnCategoryLabels(const Plot& p, const plotimpl::Style& st, PlotFrame& f) {
  if (p.x.categories.empty() || f.xTicks.empty()) return;
  double widest = 0.0;
  for (double t : f.xTicks) widest = std::max(widest, draw::measureText(plotimpl::xTickLabel(p, f, t), st.tick).width);
  const double legendW = p.legend ? plotimpl::legendSize(p).x + std::round(p.fontSize) : 0.0;
  const double spacing = (f.right - legendW - f.left) / (f.xMax - f.xMin);  // px per category
  if (widest + 2.0 * st.gap <= spacing) return;
  f.xLabelsUp = true;
  f.bottom -= std::ceil(std::max(0.0, widest - draw::measureText("0", st.tick).height));
  if (!f.colorBar.empty()) f.colorBar.y1 = f.bottom;
}

void checkRoom(const Plot& p, const PlotFrame& f) {
  if (f.right - f.left < 16 || f.bottom - f.top < 16)
    throw InputError("", "plot size", std::to_string(p.width) + " x " + std::to_string(p.height),
                     "room for the plot area next to its labels and legend (a larger size or a smaller fontSize)");
}

// The legend: a free spot inside the plot area (where the drawn content leaves room), else
// a column at the right of the image, the plot area narrowing for it.
void placeLegend(const Plot& p, const plotimpl::Style& st, double colorBarW, PlotFrame& f) {
  const glm::dvec2 size = plotimpl::legendSize(p);
  if (!p.legend || !(size.x > 0.0)) return;
  draw::Canvas mask(p.width, p.height, Vec3(0.0f), 0.0);
  plotimpl::drawContent(mask, p, f);
  const double inset = st.gap + 2.0;
  const PixelBox area{f.left + inset, f.top + inset, f.right - inset, f.bottom - inset};
  f.legend = plotimpl::freeBox(mask.alpha(), p.width, p.height, area, size, 3.0);
  if (!f.legend.empty()) return;
  f.legendOutside = true;
  horizontalLayout(p, st, colorBarW, size.x + std::round(p.fontSize), f);
  f.legend.x1 = p.width - st.margin;
  f.legend.x0 = f.legend.x1 - size.x;
  f.legend.y0 = f.top;
  f.legend.y1 = f.top + size.y;
}

}  // namespace

namespace plotimpl {
bool usable(double v, bool log) { return std::isfinite(v) && (!log || v > 0.0); }
}  // namespace plotimpl

double PlotFrame::pixelX(double x) const {
  const double a = axisValue(xMin, logX), b = axisValue(xMax, logX);
  return left + (axisValue(x, logX) - a) / (b - a) * (right - left);
}
double PlotFrame::pixelY(double y) const {
  const double a = axisValue(yMin, logY), b = axisValue(yMax, logY);
  return bottom - (axisValue(y, logY) - a) / (b - a) * (bottom - top);
}
double PlotFrame::dataX(double px) const {
  const double a = axisValue(xMin, logX), b = axisValue(xMax, logX);
  const double v = a + (px - left) / (right - left) * (b - a);
  return logX ? std::pow(10.0, v) : v;
}
double PlotFrame::dataY(double py) const {
  const double a = axisValue(yMin, logY), b = axisValue(yMax, logY);
  const double v = a + (bottom - py) / (bottom - top) * (b - a);
  return logY ? std::pow(10.0, v) : v;
}
bool PlotFrame::insideX(double x) const { return usable(x, logX) && x >= xMin && x <= xMax; }
bool PlotFrame::insideY(double y) const { return usable(y, logY) && y >= yMin && y <= yMax; }

PlotFrame plotFrame(const Plot& p) {
  if (p.width < 64 || p.height < 48 || p.width > 16384 || p.height > 16384)
    throw InputError("", "plot size", std::to_string(p.width) + " x " + std::to_string(p.height),
                     "64 x 48 to 16384 x 16384 pixels");
  std::vector<double> xs, ys;
  dataValues(p, xs, ys);
  const plotimpl::Style st(p);
  PlotFrame f;
  f.logX = p.x.log;
  f.logY = p.y.log;
  if (!p.y.categories.empty())
    throw InputError("", "y axis categories", std::to_string(p.y.categories.size()) + " names", "categories on the x axis only");
  if (p.x.categories.empty())
    axisRange(p.x, xs, std::clamp(int(p.width / (7.0 * p.fontSize)), 3, 10), f.xMin, f.xMax, f.xTicks, "x");
  else
    categoryRange(p.x, f.xMin, f.xMax, f.xTicks);
  axisRange(p.y, ys, std::clamp(int(p.height / (3.5 * p.fontSize)), 3, 10), f.yMin, f.yMax, f.yTicks, "y");

  const double th = draw::measureText("0", st.tick).height;
  const double yTitle = p.y.title.empty() ? 0.0 : draw::measureText(p.y.title, st.axisTitle).height + st.gap;
  const double xTitle = p.x.title.empty() ? 0.0 : draw::measureText(p.x.title, st.axisTitle).height + st.gap;
  const double title = plotimpl::titleHeight(p, st);
  f.left = std::ceil(std::max(st.margin + yTitle + widestLabel(f.yTicks, f.logY, st.tick) + st.tickLength + st.gap,
                              p.areaLeftMin));
  f.top = std::ceil(st.margin + title + th / 2.0);
  f.bottom = std::floor(p.height - st.margin - xTitle - th - st.tickLength - st.gap);
  const double colorBarW = p.heatMap ? colorBarRange(p, st, f) : 0.0;
  horizontalLayout(p, st, colorBarW, 0.0, f);
  turnCategoryLabels(p, st, f);
  checkRoom(p, f);
  placeLegend(p, st, colorBarW, f);
  checkRoom(p, f);
  return f;
}

void alignPlotAreas(std::vector<Plot*> plots) {
  // A narrower area can move a legend outside, which narrows it again: repeat until settled.
  for (int round = 0; round < 4; ++round) {
    double left = 0.0, inset = 0.0;
    for (const Plot* p : plots) {
      const PlotFrame f = plotFrame(*p);
      left = std::max(left, f.left), inset = std::max(inset, p->width - f.right);
    }
    bool settled = true;
    for (Plot* p : plots) {
      settled = settled && p->areaLeftMin == left && p->areaRightInset == inset;
      p->areaLeftMin = left, p->areaRightInset = inset;
    }
    if (settled) return;
  }
}

}  // namespace inim
