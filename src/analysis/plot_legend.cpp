// The legend: its entries and size, the search for a place free of data, and its drawing.
#include <algorithm>
#include <cmath>
#include <limits>

#include "analysis/plot_internal.h"

namespace inim::plotimpl {

namespace {

// One legend row: a series (its line and marker) or a patch (a polygon's or bars' colour).
struct Entry {
  std::string name;
  Vec3 color;
  const PlotSeries* series = nullptr;
  double alpha = 1.0;  // of a patch
};

std::vector<Entry> entries(const Plot& p) {
  std::vector<Entry> e;
  for (size_t i = 0; i < p.series.size(); ++i)
    if (!p.series[i].name.empty()) e.push_back({p.series[i].name, seriesColor(p, i), &p.series[i]});
  for (size_t i = 0; i < p.polygons.size(); ++i)
    if (!p.polygons[i].name.empty()) e.push_back({p.polygons[i].name, polygonColor(p, i), nullptr, p.polygons[i].alpha});
  for (size_t i = 0; i < p.bars.size(); ++i)
    if (!p.bars[i].name.empty()) e.push_back({p.bars[i].name, barsColor(p, i)});
  return e;
}

// Spacing inside the legend box, px.
struct LegendMetrics {
  draw::Font font;
  double pad, sample, textGap, rowH;
  explicit LegendMetrics(const Plot& p)
      : font(Style(p).tick),
        pad(std::round(0.5 * p.fontSize)),
        sample(std::round(2.2 * p.fontSize)),
        textGap(std::round(0.5 * p.fontSize)),
        rowH(std::ceil(draw::measureText("Ag", font).height)) {}
};

// Summed-area table of the ink mask: ink pixels in any rectangle in O(1).
class InkCount {
 public:
  InkCount(const std::vector<uint8_t>& ink, int w, int h) : w_(w), h_(h), s_(size_t(w + 1) * size_t(h + 1), 0) {
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x)
        at(x + 1, y + 1) = at(x, y + 1) + at(x + 1, y) - at(x, y) + (ink[size_t(y) * size_t(w) + size_t(x)] > 0);
  }
  // Ink pixels in [x0, x1) x [y0, y1), clamped to the mask.
  long count(int x0, int y0, int x1, int y1) const {
    x0 = std::clamp(x0, 0, w_), x1 = std::clamp(x1, 0, w_), y0 = std::clamp(y0, 0, h_), y1 = std::clamp(y1, 0, h_);
    if (x1 <= x0 || y1 <= y0) return 0;
    return s_[idx(x1, y1)] - s_[idx(x0, y1)] - s_[idx(x1, y0)] + s_[idx(x0, y0)];
  }

 private:
  size_t idx(int x, int y) const { return size_t(y) * size_t(w_ + 1) + size_t(x); }
  long& at(int x, int y) { return s_[idx(x, y)]; }
  int w_, h_;
  std::vector<long> s_;
};

}  // namespace

glm::dvec2 legendSize(const Plot& p) {
  const std::vector<Entry> e = entries(p);
  if (e.empty()) return {0.0, 0.0};
  const LegendMetrics m(p);
  double textW = 0.0;
  for (const Entry& x : e) textW = std::max(textW, draw::measureText(x.name, m.font).width);
  return {std::ceil(2.0 * m.pad + m.sample + m.textGap + textW), 2.0 * m.pad + double(e.size()) * m.rowH};
}

PixelBox freeBox(const std::vector<uint8_t>& ink, int w, int h, const PixelBox& area, glm::dvec2 size,
                 double clearance) {
  const InkCount inkCount(ink, w, h);
  const int bw = int(std::ceil(size.x)), bh = int(std::ceil(size.y)), c = int(std::ceil(clearance));
  const int xl = int(std::ceil(area.x0)), xr = int(std::floor(area.x1)) - bw;
  const int yt = int(std::ceil(area.y0)), yb = int(std::floor(area.y1)) - bh;
  if (xr < xl || yb < yt) return {};
  auto free = [&](int x, int y) { return inkCount.count(x - c, y - c, x + bw + c, y + bh + c) == 0; };
  auto box = [&](int x, int y) { return PixelBox{double(x), double(y), double(x + bw), double(y + bh)}; };
  // Corners (top right first, where readers look for it), then the middles of the edges.
  const int xm = (xl + xr) / 2, ym = (yt + yb) / 2;
  const int pref[8][2] = {{xr, yt}, {xl, yt}, {xr, yb}, {xl, yb}, {xm, yt}, {xm, yb}, {xr, ym}, {xl, ym}};
  for (const auto& q : pref)
    if (free(q[0], q[1])) return box(q[0], q[1]);
  // Any free place, the nearest to a corner.
  long best = std::numeric_limits<long>::max();
  int bx = 0, by = 0;
  for (int y = yt; y <= yb; y += 2)
    for (int x = xl; x <= xr; x += 2) {
      const long d = long(std::min(x - xl, xr - x)) + long(std::min(y - yt, yb - y));
      if (d < best && free(x, y)) best = d, bx = x, by = y;
    }
  return best == std::numeric_limits<long>::max() ? PixelBox{} : box(bx, by);
}

void drawLegend(draw::Canvas& cv, const Plot& p, const PlotFrame& f) {
  if (f.legend.empty()) return;
  const std::vector<Entry> e = entries(p);
  const LegendMetrics m(p);
  const PixelBox& b = f.legend;
  cv.fillRect(b.x0, b.y0, b.x1, b.y1, Vec3(1.0f));
  cv.strokeRect(b.x0 + 0.5, b.y0 + 0.5, b.x1 - 0.5, b.y1 - 0.5, {Vec3(0.6f)});
  cv.pushClip(b.x0, b.y0, b.x1, b.y1);
  for (size_t r = 0; r < e.size(); ++r) {
    const double top = b.y0 + m.pad + double(r) * m.rowH, cy = std::floor(top + 0.5 * m.rowH) + 0.5;
    const double sx0 = b.x0 + m.pad, sx1 = sx0 + m.sample;
    if (const PlotSeries* s = e[r].series) {
      if (s->line && s->lineWidth > 0.0) cv.line({sx0, cy}, {sx1, cy}, {e[r].color, s->lineWidth, s->dash});
      if (s->markers && s->markerRadius > 0.0) drawMarker(cv, s->marker, {0.5 * (sx0 + sx1), cy}, s->markerRadius, e[r].color);
    } else {
      const double hh = std::round(0.35 * m.rowH);
      cv.fillRect(sx0, cy - hh, sx1, cy + hh, e[r].color, e[r].alpha);
      cv.strokeRect(sx0 + 0.5, cy - hh + 0.5, sx1 - 0.5, cy + hh - 0.5, {e[r].color});
    }
    cv.text(e[r].name, {sx1 + m.textGap, top + 0.5 * m.rowH}, m.font, Vec3(0.1f),
            {draw::Align::Start, draw::Align::Centre});
  }
  cv.popClip();
}

}  // namespace inim::plotimpl
