// The colour-calibration figures: the xy chromaticity diagram, the ΔE bars and the swatch
// charts. The plots are built from plot.h's layers; the swatches are drawn on a canvas.
#include "analysis/colour_plots.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "draw/canvas.h"
#include "spectral/cmf_table.h"

namespace inim {

namespace {

const Vec3 kTargetColour(0.1f, 0.1f, 0.1f);
const Vec3 kBeforeColour(0.839f, 0.153f, 0.157f);  // tab10 red
const Vec3 kAfterColour(0.122f, 0.467f, 0.706f);   // tab10 blue
const Vec3 kWhiteColour(0.35f, 0.35f, 0.35f);
const double kXMax = 0.8, kYMax = 0.9;             // the diagram's axes
const Vec2d kLabelCentre(0.3127, 0.3290);          // wavelength labels point away from D65

bool finite(const Vec2d& v) { return std::isfinite(v.x) && std::isfinite(v.y); }
Vec3 lighter(const Vec3& c, float t) { return c + t * (Vec3(1.0f) - c); }

Vec2d locusAt(double nm) {
  const Vec3 xyz = cmfTable()(float(nm));
  const double s = double(xyz.x) + double(xyz.y) + double(xyz.z);
  return {xyz.x / s, xyz.y / s};
}

// The spectral locus every nm, closed by the purple line.
PlotSeries locusSeries() {
  PlotSeries s{"", {}, {}};
  for (const Vec2d& v : spectralLocusXY(1.0)) s.x.push_back(v.x), s.y.push_back(v.y);
  s.x.push_back(s.x.front()), s.y.push_back(s.y.front());
  s.color = Vec3(0.15f);
  s.markers = false;
  s.lineWidth = 1.5;
  return s;
}

// Thin lines from each target to its before (or after) point: one series broken by NaNs.
PlotSeries offsetLines(const std::vector<ChromaticityPoint>& pts, Vec2d ChromaticityPoint::*to, const Vec3& colour) {
  PlotSeries s{"", {}, {}};
  for (const ChromaticityPoint& p : pts) {
    if (!finite(p.target) || !finite(p.*to)) continue;
    s.x.insert(s.x.end(), {p.target.x, (p.*to).x, std::nan("")});
    s.y.insert(s.y.end(), {p.target.y, (p.*to).y, std::nan("")});
  }
  s.color = colour;
  s.markers = false;
  s.lineWidth = 1.0;
  return s;
}

PlotSeries pointMarkers(const std::string& name, const std::vector<ChromaticityPoint>& pts,
                        Vec2d ChromaticityPoint::*at, MarkerShape shape, const Vec3& colour, double radius) {
  PlotSeries s{name, {}, {}};
  for (const ChromaticityPoint& p : pts) s.x.push_back((p.*at).x), s.y.push_back((p.*at).y);
  s.color = colour;
  s.line = false;
  s.marker = shape;
  s.markerRadius = radius;
  return s;
}

PlotAxis diagramAxis(const std::string& title, double max) {
  PlotAxis a;
  a.title = title;
  a.min = 0.0;
  a.max = max;
  return a;
}

// Widens or narrows the image until the plot area has equal x and y scales (the plot area's
// left edge and height do not depend on the width).
void equalAspect(Plot& p) {
  for (int k = 0; k < 4; ++k) {
    const PlotFrame f = plotFrame(p);
    const double want = (f.bottom - f.top) * (f.xMax - f.xMin) / (f.yMax - f.yMin);
    const long dw = std::lround(want - (f.right - f.left));
    if (dw == 0) return;
    p.width += int(dw);
  }
}

// A title wider than the figure makes the figure larger, at the same aspect (the title font
// and margin as plot_layers.cpp's Style).
void fitTitle(Plot& p) {
  const double margin = std::round(0.7 * p.fontSize);
  const double want = draw::measureText(p.title, {std::round(1.25 * p.fontSize), true}).width + 2.0 * margin;
  for (int k = 0; k < 3 && p.width < want; ++k) {
    p.height = int(std::ceil(p.height * want / p.width));
    equalAspect(p);
  }
}

// The anchor that puts a label on the side of its point that `dir` (data units, y up) points to.
TextAnchorPoint anchorAway(const Vec2d& dir) {
  static const TextAnchorPoint bySector[8] = {TextAnchorPoint::Left,     TextAnchorPoint::BottomLeft,
                                              TextAnchorPoint::Bottom,   TextAnchorPoint::BottomRight,
                                              TextAnchorPoint::Right,    TextAnchorPoint::TopRight,
                                              TextAnchorPoint::Top,      TextAnchorPoint::TopLeft};
  const int sector = int(std::lround(std::atan2(dir.y, dir.x) / (0.25 * kPi)));
  return bySector[(sector % 8 + 8) % 8];
}

// Whether a text anchored at a data position lies inside the plot area.
bool labelFits(const Plot& p, const PlotFrame& f, const std::string& text, const Vec2d& at, TextAnchorPoint a) {
  const draw::TextSize s = draw::measureText(text, {p.fontSize});
  const Vec2d px = f.toPixel(at.x, at.y);
  const double x0 = px.x - 0.5 * double(int(a) % 3) * s.width, y0 = px.y - 0.5 * double(int(a) / 3) * s.height;
  return x0 >= f.left + 2.0 && y0 >= f.top + 2.0 && x0 + s.width <= f.right - 2.0 && y0 + s.height <= f.bottom - 2.0;
}

// Short ticks across the locus at 460-620 nm, labelled outside it (inside where the label
// would leave the axes, as at 500 nm next to x = 0).
void addWavelengthLabels(Plot& p) {
  const PlotFrame f = plotFrame(p);
  PlotSeries ticks{"", {}, {}};
  ticks.color = Vec3(0.15f);
  ticks.markers = false;
  ticks.lineWidth = 1.0;
  for (int nm = 460; nm <= 620; nm += 20) {
    const Vec2d at = locusAt(nm), tangent = locusAt(nm + 1.0) - locusAt(nm - 1.0);
    Vec2d n = glm::normalize(Vec2d(-tangent.y, tangent.x));
    if (glm::dot(n, at - kLabelCentre) < 0.0) n = -n;
    const std::string text = std::to_string(nm);
    if (!labelFits(p, f, text, at + 0.018 * n, anchorAway(n))) n = -n;
    ticks.x.insert(ticks.x.end(), {at.x, at.x + 0.01 * n.x, std::nan("")});
    ticks.y.insert(ticks.y.end(), {at.y, at.y + 0.01 * n.y, std::nan("")});
    const Vec2d pos = at + 0.014 * n;
    p.texts.push_back({pos.x, pos.y, text, Vec3(0.2f), anchorAway(n)});
  }
  p.series.push_back(ticks);
}

}  // namespace

std::vector<Vec2d> spectralLocusXY(double stepNm) {
  if (!(stepNm > 0.0)) throw std::invalid_argument("spectralLocusXY: step must be > 0 nm");
  std::vector<Vec2d> xy;
  const double lo = kLambdaMin, hi = kLambdaMax;
  for (long k = 0; lo + double(k) * stepNm < hi; ++k) xy.push_back(locusAt(lo + double(k) * stepNm));
  xy.push_back(locusAt(hi));
  return xy;
}

Plot chromaticityPlot(const ChromaticityPlotData& d) {
  Plot p;
  p.title = d.title;
  p.height = d.height;
  p.width = int(std::lround(d.height * kXMax / kYMax));
  p.x = diagramAxis("x", kXMax);
  p.y = diagramAxis("y", kYMax);
  for (const GamutTriangle& g : d.gamuts) {
    PlotPolygon poly{g.name, {g.xy[0].x, g.xy[1].x, g.xy[2].x}, {g.xy[0].y, g.xy[1].y, g.xy[2].y}, g.colour};
    poly.alpha = 0.1;
    poly.edgeWidth = 1.5;
    p.polygons.push_back(poly);
  }
  p.series.push_back(locusSeries());
  p.series.push_back(offsetLines(d.points, &ChromaticityPoint::before, lighter(kBeforeColour, 0.3f)));
  p.series.push_back(offsetLines(d.points, &ChromaticityPoint::after, lighter(kAfterColour, 0.3f)));
  p.series.push_back(pointMarkers("target", d.points, &ChromaticityPoint::target, MarkerShape::Circle, kTargetColour, 4.0));
  p.series.push_back(
      pointMarkers("uncalibrated", d.points, &ChromaticityPoint::before, MarkerShape::Triangle, kBeforeColour, 3.5));
  p.series.push_back(
      pointMarkers("calibrated", d.points, &ChromaticityPoint::after, MarkerShape::Cross, kAfterColour, 4.0));
  if (d.white) {
    PlotSeries w{d.whiteLabel, {d.white->x}, {d.white->y}};
    w.color = kWhiteColour;
    w.line = false;
    w.markerRadius = 3.0;
    p.series.push_back(w);
  }
  equalAspect(p);
  fitTitle(p);
  addWavelengthLabels(p);
  return p;
}

void writeChromaticityPlot(const ChromaticityPlotData& d, const std::string& pngPath, const std::string& csvPath) {
  writePlot(chromaticityPlot(d), pngPath);
  if (csvPath.empty()) return;
  std::vector<std::vector<std::string>> rows;
  for (const ChromaticityPoint& q : d.points)
    rows.push_back({q.label, csvNumber(q.target.x), csvNumber(q.target.y), csvNumber(q.before.x),
                    csvNumber(q.before.y), csvNumber(q.after.x), csvNumber(q.after.y)});
  writeCsv(csvPath, {"label", "target_x", "target_y", "before_x", "before_y", "after_x", "after_y"}, rows);
}

namespace {

void checkBars(const DeltaEBarsData& d) {
  if (d.before.size() != d.labels.size() || d.after.size() != d.labels.size())
    throw std::invalid_argument("DeltaEBarsData: " + std::to_string(d.labels.size()) + " labels, " +
                                std::to_string(d.before.size()) + " before and " + std::to_string(d.after.size()) +
                                " after values (want as many of each)");
}

std::string shortNumber(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

// The top of the y axis: a whole tick above the largest bar or threshold with a fifth to
// spare, where the legend goes.
double headroom(const DeltaEBarsData& d) {
  double top = 0.0;
  for (const std::vector<double>* v : {&d.before, &d.after, &d.thresholds})
    for (double x : *v)
      if (std::isfinite(x)) top = std::max(top, x);
  if (!(top > 0.0)) return 1.0;
  const double step = niceStep(0.0, 1.2 * top);
  return std::ceil(1.2 * top / step - 1e-9) * step;
}

}  // namespace

Plot deltaEBarsPlot(const DeltaEBarsData& d) {
  checkBars(d);
  const size_t n = d.labels.size();
  Plot p;
  p.title = d.title;
  p.y.title = d.yLabel;
  p.y.min = 0.0;
  p.y.max = headroom(d);
  p.x.categories = d.labels;
  p.height = d.height;
  p.width = d.width > 0 ? d.width : std::clamp(int(200 + 34 * n), 640, 2400);
  PlotBars before{d.beforeName, {}, d.before, 0.4, 0.0, kBeforeColour};
  PlotBars after{d.afterName, {}, d.after, 0.4, 0.0, kAfterColour};
  for (size_t i = 0; i < n; ++i) before.x.push_back(double(i) - 0.2), after.x.push_back(double(i) + 0.2);
  p.bars = {before, after};
  for (double t : d.thresholds) p.hMarkers.push_back({t, shortNumber(t), Vec3(0.35f), 5.0});
  return p;
}

void writeDeltaEBars(const DeltaEBarsData& d, const std::string& pngPath, const std::string& csvPath) {
  writePlot(deltaEBarsPlot(d), pngPath);
  if (csvPath.empty()) return;
  std::vector<std::vector<std::string>> rows;
  for (size_t i = 0; i < d.labels.size(); ++i) rows.push_back({d.labels[i], csvNumber(d.before[i]), csvNumber(d.after[i])});
  writeCsv(csvPath, {"patch", d.beforeName, d.afterName}, rows);
}

SwatchLayout swatchLayout(const std::vector<SwatchChart>& charts, int columns, const std::string& caption,
                          const SwatchStyle& st) {
  if (columns <= 0) throw std::invalid_argument("swatchCharts: columns must be > 0, got " + std::to_string(columns));
  size_t rows = 0;
  for (const SwatchChart& c : charts) rows = std::max(rows, (c.srgb.size() + size_t(columns) - 1) / size_t(columns));
  const int chartW = columns * st.patch + (columns - 1) * st.gap;
  const int chartH = rows == 0 ? 0 : int(rows) * st.patch + (int(rows) - 1) * st.gap;
  const draw::Font labelFont{st.fontSize, true}, captionFont{st.fontSize};
  bool anyLabel = false;
  for (const SwatchChart& c : charts) anyLabel = anyLabel || !c.label.empty();
  const int labelH = anyLabel ? int(std::ceil(draw::measureText("Ag", labelFont).height)) : 0;
  const int top = st.margin + (anyLabel ? labelH + st.labelGap : 0);

  SwatchLayout l;
  int x = st.margin;
  for (const SwatchChart& c : charts) {
    const draw::TextSize ls = draw::measureText(c.label, labelFont);
    const int colW = std::max(chartW, int(std::ceil(ls.width)));
    const int x0 = x + (colW - chartW) / 2;
    std::vector<PixelBox> boxes;
    for (size_t k = 0; k < c.srgb.size(); ++k) {
      const int px = x0 + int(k % size_t(columns)) * (st.patch + st.gap), py = top + int(k / size_t(columns)) * (st.patch + st.gap);
      boxes.push_back({double(px), double(py), double(px + st.patch), double(py + st.patch)});
    }
    l.patches.push_back(boxes);
    const double lx = x + 0.5 * (colW - ls.width);
    l.labels.push_back({lx, double(st.margin), lx + ls.width, st.margin + ls.height});
    x += colW + st.chartGap;
  }
  int contentW = charts.empty() ? 0 : x - st.chartGap - st.margin;
  int bottom = top + chartH;
  if (!caption.empty()) {
    const draw::TextSize cs = draw::measureText(caption, captionFont);
    contentW = std::max(contentW, int(std::ceil(cs.width)));
    const double cy = bottom + st.labelGap;
    l.caption = {double(st.margin), cy, st.margin + cs.width, cy + cs.height};
    bottom = int(std::ceil(l.caption.y1));
  }
  l.width = std::max(contentW + 2 * st.margin, 1);
  l.height = std::max(bottom + st.margin, 1);
  return l;
}

Image swatchCharts(const std::vector<SwatchChart>& charts, int columns, const std::string& caption,
                   const SwatchStyle& st) {
  const SwatchLayout l = swatchLayout(charts, columns, caption, st);
  draw::Canvas cv(l.width, l.height, st.background);
  for (size_t i = 0; i < charts.size(); ++i) {
    cv.text(charts[i].label, {l.labels[i].x0, l.labels[i].y0}, {st.fontSize, true}, st.textColor);
    for (size_t k = 0; k < charts[i].srgb.size(); ++k) {
      const Vec3& c = charts[i].srgb[k];
      if (!isFinite(c)) continue;
      const PixelBox& b = l.patches[i][k];
      cv.fillRect(b.x0, b.y0, b.x1, b.y1, glm::clamp(c, Vec3(0.0f), Vec3(1.0f)));
    }
  }
  if (!caption.empty()) cv.text(caption, {l.caption.x0, l.caption.y0}, {st.fontSize}, st.textColor);
  return cv.toImage();
}

}  // namespace inim
