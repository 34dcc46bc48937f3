// The layers drawn inside a plot's area: heat map, polygons, bars, marker lines, series,
// annotations and the labels of marker lines.
#include <algorithm>
#include <cmath>
#include <sstream>

#include "analysis/plot_internal.h"

namespace inim::plotimpl {

using draw::Align;
using draw::P2;

Style::Style(const Plot& p)
    : tick{p.fontSize},
      axisTitle{std::round(1.08 * p.fontSize)},
      title{std::round(1.25 * p.fontSize), true},
      margin(std::round(0.7 * p.fontSize)),
      tickLength(std::round(0.4 * p.fontSize)),
      gap(std::round(0.3 * p.fontSize)) {}

std::vector<std::string> titleLines(const Plot& p, const Style& st) {
  std::vector<std::string> lines;
  const double room = p.width - 2.0 * st.margin;
  std::istringstream words(p.title);
  std::string word;
  while (words >> word) {
    if (!lines.empty() && draw::measureText(lines.back() + " " + word, st.title).width <= room)
      lines.back() += " " + word;
    else
      lines.push_back(word);
  }
  return lines;
}

double titleLineHeight(const Style& st) { return draw::measureText("Ag", st.title).height; }

double titleHeight(const Plot& p, const Style& st) {
  const auto lines = titleLines(p, st);
  return lines.empty() ? 0.0 : lines.size() * titleLineHeight(st) + st.gap;
}

Vec3 seriesColor(const Plot& p, size_t i) { return p.series[i].color.value_or(plotPalette(int(i))); }
Vec3 polygonColor(const Plot& p, size_t i) {
  return p.polygons[i].color.value_or(plotPalette(int(p.series.size() + i)));
}
Vec3 barsColor(const Plot& p, size_t i) {
  return p.bars[i].color.value_or(plotPalette(int(p.series.size() + p.polygons.size() + i)));
}

double barWidth(const PlotBars& b) {
  if (b.width > 0.0) return b.width;
  std::vector<double> x;
  for (double v : b.x)
    if (std::isfinite(v)) x.push_back(v);
  std::sort(x.begin(), x.end());
  double spacing = 0.0;
  for (size_t k = 1; k < x.size(); ++k)
    if (x[k] > x[k - 1] && (spacing == 0.0 || x[k] - x[k - 1] < spacing)) spacing = x[k] - x[k - 1];
  return 0.8 * (spacing > 0.0 ? spacing : 1.0);
}

Vec3 heatColor(const PlotHeatMap& h, double v, double cMin, double cMax) {
  return colorMap(h.map, (v - cMin) / (cMax - cMin));
}

namespace {

// The heat map, one colour per pixel from the cell under its centre (exact on log axes too).
void drawHeatMap(draw::Canvas& cv, const PlotHeatMap& h, const PlotFrame& f) {
  const double px0 = std::min(f.pixelX(h.x0), f.pixelX(h.x1)), px1 = std::max(f.pixelX(h.x0), f.pixelX(h.x1));
  const double py0 = std::min(f.pixelY(h.y0), f.pixelY(h.y1)), py1 = std::max(f.pixelY(h.y0), f.pixelY(h.y1));
  const int ix0 = int(std::floor(std::max(px0, f.left))), ix1 = int(std::ceil(std::min(px1, f.right)));
  const int iy0 = int(std::floor(std::max(py0, f.top))), iy1 = int(std::ceil(std::min(py1, f.bottom)));
  if (ix1 <= ix0 || iy1 <= iy0) return;
  Image img(ix1 - ix0, iy1 - iy0, {"R", "G", "B", "A"});
  for (int j = 0; j < img.height; ++j) {
    const double v = (f.dataY(iy0 + j + 0.5) - h.y0) / (h.y1 - h.y0);
    const int r = int(std::floor(v * h.rows));
    for (int i = 0; i < img.width; ++i) {
      const double u = (f.dataX(ix0 + i + 0.5) - h.x0) / (h.x1 - h.x0);
      const int c = int(std::floor(u * h.cols));
      if (!(u >= 0.0 && u < 1.0 && v >= 0.0 && v < 1.0) || c < 0 || c >= h.cols || r < 0 || r >= h.rows) continue;
      const double val = h.values[size_t(r) * size_t(h.cols) + size_t(c)];
      if (!std::isfinite(val)) continue;
      const Vec3 col = heatColor(h, val, f.cMin, f.cMax);
      for (int k = 0; k < 3; ++k) img.at(i, j, k) = col[k];
      img.at(i, j, 3) = 1.0f;
    }
  }
  cv.image(img, ix0, iy0);
}

void drawPolygon(draw::Canvas& cv, const PlotPolygon& poly, const Vec3& color, const PlotFrame& f) {
  std::vector<P2> pts;
  for (size_t k = 0; k < poly.x.size(); ++k)
    if (usable(poly.x[k], f.logX) && usable(poly.y[k], f.logY)) pts.push_back(f.toPixel(poly.x[k], poly.y[k]));
  if (pts.size() < 2) return;
  cv.fillPolygon(pts, color, poly.alpha);
  if (poly.edgeWidth > 0.0) cv.strokePolygon(pts, {color, poly.edgeWidth});
}

void drawBars(draw::Canvas& cv, const PlotBars& b, const Vec3& color, const PlotFrame& f) {
  const double hw = 0.5 * barWidth(b);
  // On a log y axis a base <= 0 means the bottom of the plot.
  const double base = usable(b.base, f.logY) ? f.pixelY(b.base) : f.bottom;
  for (size_t k = 0; k < b.x.size(); ++k) {
    if (!std::isfinite(b.x[k]) || !usable(b.y[k], f.logY)) continue;
    if (f.logX && !(b.x[k] - hw > 0.0)) continue;
    const double x0 = std::round(f.pixelX(b.x[k] - hw)), x1 = std::round(f.pixelX(b.x[k] + hw));
    const double y = std::round(f.pixelY(b.y[k])), y0 = std::round(base);
    cv.fillRect(std::min(x0, x1), std::min(y, y0), std::max(std::max(x0, x1), std::min(x0, x1) + 1.0),
                std::max(y, y0), color);
  }
}

void drawMarkerLines(draw::Canvas& cv, const Plot& p, const PlotFrame& f) {
  for (const PlotMarker& m : p.markers) {
    if (!f.insideX(m.value)) continue;
    const double x = std::min(std::floor(f.pixelX(m.value)), f.right - 1.0) + 0.5;
    cv.line({x, f.top}, {x, f.bottom}, {m.color, 1.0, m.dash});
  }
  for (const PlotMarker& m : p.hMarkers) {
    if (!f.insideY(m.value)) continue;
    const double y = std::min(std::floor(f.pixelY(m.value)), f.bottom - 1.0) + 0.5;
    cv.line({f.left, y}, {f.right, y}, {m.color, 1.0, m.dash});
  }
}

void drawSeries(draw::Canvas& cv, const Plot& p, const PlotFrame& f, size_t i, bool lines) {
  const PlotSeries& s = p.series[i];
  const Vec3 color = seriesColor(p, i);
  if (lines && s.line && s.lineWidth > 0.0) {
    std::vector<P2> pts(s.x.size());
    for (size_t k = 0; k < s.x.size(); ++k)
      pts[k] = usable(s.x[k], f.logX) && usable(s.y[k], f.logY) ? f.toPixel(s.x[k], s.y[k]) : P2(std::nan(""));
    cv.polyline(pts, {color, s.lineWidth, s.dash});
  }
  if (!lines && s.markers && s.markerRadius > 0.0)
    for (size_t k = 0; k < s.x.size(); ++k)
      if (f.insideX(s.x[k]) && f.insideY(s.y[k])) drawMarker(cv, s.marker, f.toPixel(s.x[k], s.y[k]), s.markerRadius, color);
}

draw::TextAnchor anchorOf(TextAnchorPoint a) {
  const int i = int(a);
  const Align h[3] = {Align::Start, Align::Centre, Align::End};
  return {h[i % 3], h[i / 3]};
}

// A label on a light box, over whatever is below it.
void boxedLabel(draw::Canvas& cv, const std::string& text, P2 topLeft, const draw::Font& font, const Vec3& color) {
  const draw::TextSize s = draw::measureText(text, font);
  cv.fillRect(topLeft.x - 2, topLeft.y, topLeft.x + s.width + 2, topLeft.y + s.height, Vec3(1.0f), 0.8);
  cv.text(text, topLeft, font, color);
}

// Labels of vertical markers go at the top, right of their line (left when there is no room),
// a row lower when they would overlap an earlier label; labels of horizontal markers at the
// right end, above their line (below at the top).
void drawMarkerLabels(draw::Canvas& cv, const Plot& p, const PlotFrame& f, const Style& st) {
  std::vector<PixelBox> placed;
  for (const PlotMarker& m : p.markers) {
    if (m.label.empty() || !f.insideX(m.value)) continue;
    const draw::TextSize s = draw::measureText(m.label, st.tick);
    const double x = std::floor(f.pixelX(m.value));
    PixelBox b{x + st.gap + 1, f.top + st.gap, 0, 0};
    if (b.x0 + s.width > f.right - 2) b.x0 = x - st.gap - std::ceil(s.width);
    b.x1 = b.x0 + s.width, b.y1 = b.y0 + s.height;
    for (bool moved = true; moved;) {
      moved = false;
      for (const PixelBox& q : placed)
        if (b.overlaps(q)) b.y0 = q.y1 + 1, b.y1 = b.y0 + s.height, moved = true;
    }
    placed.push_back(b);
    boxedLabel(cv, m.label, {b.x0, b.y0}, st.tick, m.color);
  }
  for (const PlotMarker& m : p.hMarkers) {
    if (m.label.empty() || !f.insideY(m.value)) continue;
    const draw::TextSize s = draw::measureText(m.label, st.tick);
    const double y = std::floor(f.pixelY(m.value));
    const double top = y - st.gap - s.height > f.top ? y - st.gap - s.height : y + st.gap;
    boxedLabel(cv, m.label, {f.right - st.gap - std::ceil(s.width), top}, st.tick, m.color);
  }
}

}  // namespace

// Open and line shapes are drawn a little larger than a disc of the same radius, so that
// they look as big.
void drawMarker(draw::Canvas& cv, MarkerShape shape, P2 c, double r, const Vec3& color) {
  const double w = std::max(1.5, 0.4 * r);
  switch (shape) {
    case MarkerShape::Disc:
      cv.disc(c, r, color);
      break;
    case MarkerShape::Circle: {
      std::vector<P2> ring(32);
      for (size_t k = 0; k < ring.size(); ++k) {
        const double a = 2.0 * kPi * double(k) / double(ring.size());
        ring[k] = c + (r + 0.5 * w) * P2(std::cos(a), std::sin(a));
      }
      cv.strokePolygon(ring, {color, w});
      break;
    }
    case MarkerShape::Triangle: {
      const double R = 1.3 * r;  // circumradius; the centroid is on the point
      cv.fillPolygon({c + R * P2(0.0, -1.0), c + R * P2(0.866, 0.5), c + R * P2(-0.866, 0.5)}, color);
      break;
    }
    case MarkerShape::Cross: {
      const double d = 1.1 * r;
      cv.line(c + P2(-d, -d), c + P2(d, d), {color, w});
      cv.line(c + P2(-d, d), c + P2(d, -d), {color, w});
      break;
    }
  }
}

double markerReach(double r) { return 1.3 * r + std::max(1.5, 0.4 * r); }

void drawContent(draw::Canvas& cv, const Plot& p, const PlotFrame& f) {
  const Style st(p);
  cv.pushClip(f.left, f.top, f.right, f.bottom);
  if (p.heatMap) drawHeatMap(cv, *p.heatMap, f);
  for (size_t i = 0; i < p.polygons.size(); ++i) drawPolygon(cv, p.polygons[i], polygonColor(p, i), f);
  for (size_t i = 0; i < p.bars.size(); ++i) drawBars(cv, p.bars[i], barsColor(p, i), f);
  drawMarkerLines(cv, p, f);
  for (size_t i = 0; i < p.series.size(); ++i) drawSeries(cv, p, f, i, true);
  cv.popClip();
  // Markers may reach past the plot area by their radius.
  double pad = 0.0;
  for (const PlotSeries& s : p.series) pad = std::max(pad, std::ceil(markerReach(s.markerRadius)) + 1.0);
  cv.pushClip(f.left - pad, f.top - pad, f.right + pad, f.bottom + pad);
  for (size_t i = 0; i < p.series.size(); ++i) drawSeries(cv, p, f, i, false);
  cv.popClip();
  cv.pushClip(f.left, f.top, f.right, f.bottom);
  for (const PlotText& t : p.texts)
    if (f.insideX(t.x) && f.insideY(t.y)) cv.text(t.text, f.toPixel(t.x, t.y), st.tick, t.color, anchorOf(t.anchor));
  drawMarkerLabels(cv, p, f, st);
  cv.popClip();
}

}  // namespace inim::plotimpl
