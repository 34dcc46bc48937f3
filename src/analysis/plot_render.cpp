// Rendering a plot: grid, the layers (plot_layers.cpp), axes with ticks and labels, the
// colour bar, the legend (plot_legend.cpp) and the titles.
#include <algorithm>
#include <cmath>

#include "analysis/plot.h"
#include "analysis/plot_internal.h"

namespace inim {

namespace {

using draw::Align;
using plotimpl::Style;

const Vec3 kBlack(0.0f), kText(0.1f), kGrid(0.88f);

// Crisp pixel-centre coordinates of ticks, kept inside the plot area.
double tickX(const PlotFrame& f, double t) { return std::clamp(std::floor(f.pixelX(t)), f.left, f.right - 1.0) + 0.5; }
double tickY(const PlotFrame& f, double t) { return std::clamp(std::floor(f.pixelY(t)), f.top, f.bottom - 1.0) + 0.5; }

void drawGrid(draw::Canvas& cv, const Plot& p, const PlotFrame& f) {
  if (p.x.categories.empty())
    for (double t : f.xTicks)
      if (const double x = tickX(f, t); x > f.left + 1.0 && x < f.right - 1.0) cv.line({x, f.top}, {x, f.bottom}, {kGrid});
  for (double t : f.yTicks)
    if (const double y = tickY(f, t); y > f.top + 1.0 && y < f.bottom - 1.0) cv.line({f.left, y}, {f.right, y}, {kGrid});
}

// Turned x labels (categories) end at the axis, reading upwards.
void drawAxes(draw::Canvas& cv, const Plot& p, const PlotFrame& f, const Style& st) {
  for (double t : f.xTicks) {
    const double x = tickX(f, t);
    cv.line({x, f.bottom}, {x, f.bottom + st.tickLength}, {kBlack});
    cv.text(plotimpl::xTickLabel(p, f, t), {x, f.bottom + st.tickLength + st.gap}, st.tick, kText,
            {Align::Centre, Align::Start}, f.xLabelsUp);
  }
  for (double t : f.yTicks) {
    const double y = tickY(f, t);
    cv.line({f.left - st.tickLength, y}, {f.left, y}, {kBlack});
    cv.text(plotimpl::tickLabel(f.yTicks, f.logY, t), {f.left - st.tickLength - st.gap, y}, st.tick, kText,
            {Align::End, Align::Centre});
  }
  cv.strokeRect(f.left - 0.5, f.top - 0.5, f.right + 0.5, f.bottom + 0.5, {kBlack});
}

// The colour bar: one row of pixels per colour (cMin at the bottom), ticks and labels at its
// right, its title further right reading upwards.
void drawColorBar(draw::Canvas& cv, const Plot& p, const PlotFrame& f, const Style& st) {
  const PixelBox& b = f.colorBar;
  const PlotHeatMap& h = *p.heatMap;
  for (int y = int(b.y0); y < int(b.y1); ++y) {
    const double t = (b.y1 - (y + 0.5)) / (b.y1 - b.y0);
    cv.fillRect(b.x0, y, b.x1, y + 1, plotimpl::heatColor(h, f.cMin + t * (f.cMax - f.cMin), f.cMin, f.cMax));
  }
  cv.strokeRect(b.x0 - 0.5, b.y0 - 0.5, b.x1 + 0.5, b.y1 + 0.5, {kBlack});
  double labelsRight = b.x1;
  for (double t : f.cTicks) {
    const double y = std::clamp(std::floor(b.y1 - (t - f.cMin) / (f.cMax - f.cMin) * (b.y1 - b.y0)), b.y0, b.y1 - 1) + 0.5;
    cv.line({b.x1, y}, {b.x1 + st.tickLength, y}, {kBlack});
    const draw::TextSize s = cv.text(plotimpl::tickLabel(f.cTicks, false, t),
                                     {b.x1 + st.tickLength + st.gap, y}, st.tick, kText, {Align::Start, Align::Centre});
    labelsRight = std::max(labelsRight, b.x1 + st.tickLength + st.gap + s.width);
  }
  if (!h.label.empty())
    cv.text(h.label, {labelsRight + st.gap, 0.5 * (b.y0 + b.y1)}, st.axisTitle, kBlack, {Align::Start, Align::Centre},
            true);
}

void drawTitles(draw::Canvas& cv, const Plot& p, const PlotFrame& f, const Style& st) {
  const double cx = 0.5 * (f.left + f.right);
  // Each line centred over the plot area, moved left (then right) to stay inside the image.
  const double lineHeight = titleLineHeight(st);
  double y = st.margin;
  for (const std::string& line : titleLines(p, st)) {
    const double hw = 0.5 * draw::measureText(line, st.title).width;
    cv.text(line, {std::max(st.margin + hw, std::min(cx, p.width - st.margin - hw)), y}, st.title, kBlack,
            {Align::Centre, Align::Start});
    y += lineHeight;
  }
  if (!p.x.title.empty())
    cv.text(p.x.title, {cx, p.height - st.margin}, st.axisTitle, kBlack, {Align::Centre, Align::End});
  if (!p.y.title.empty())
    cv.text(p.y.title, {st.margin, 0.5 * (f.top + f.bottom)}, st.axisTitle, kBlack, {Align::Start, Align::Centre}, true);
}

}  // namespace

Image renderPlot(const Plot& plot) {
  const PlotFrame f = plotFrame(plot);
  const Style st(plot);
  draw::Canvas cv(plot.width, plot.height);
  if (plot.grid) drawGrid(cv, plot, f);
  plotimpl::drawContent(cv, plot, f);
  drawAxes(cv, plot, f, st);
  if (plot.heatMap) drawColorBar(cv, plot, f, st);
  plotimpl::drawLegend(cv, plot, f);
  drawTitles(cv, plot, f, st);
  return cv.toImage();
}

void writePlot(const Plot& plot, const std::string& path) { writeImage(renderPlot(plot), path); }

}  // namespace inim
