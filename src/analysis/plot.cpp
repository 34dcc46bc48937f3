#include "analysis/plot.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <stdexcept>

#include "analysis/bitmap_font.h"
#include "core/error.h"

namespace inim {

// ---------------------------------------------------------------------------------------
// Ticks

double niceStep(double lo, double hi, int maxTicks) {
  const double span = hi - lo;
  if (!(span > 0.0) || !std::isfinite(span)) return 1.0;
  const double raw = span / std::max(maxTicks, 1);
  const double mag = std::pow(10.0, std::floor(std::log10(raw)));
  for (double m : {1.0, 2.0, 5.0, 10.0})
    if (m * mag >= raw * (1.0 - 1e-12)) return m * mag;
  return 10.0 * mag;
}

std::vector<double> niceTicks(double lo, double hi, int maxTicks) {
  std::vector<double> t;
  if (!(hi > lo) || !std::isfinite(lo) || !std::isfinite(hi)) return t;
  const double step = niceStep(lo, hi, maxTicks);
  const double k0 = std::ceil(lo / step - 1e-9), k1 = std::floor(hi / step + 1e-9);
  for (double k = k0; k <= k1 && t.size() < 1000; k += 1.0) {
    double v = k * step;
    if (std::abs(v) < step * 1e-9) v = 0.0;
    t.push_back(v);
  }
  return t;
}

std::vector<double> logTicks(double lo, double hi) {
  std::vector<double> t;
  if (!(lo > 0.0) || !(hi > lo) || !std::isfinite(hi)) return t;
  const int d0 = int(std::ceil(std::log10(lo) - 1e-9)), d1 = int(std::floor(std::log10(hi) + 1e-9));
  if (d1 - d0 >= 2) {
    const int every = std::max(1, (d1 - d0 + 9) / 10);  // at most ~10 labelled decades
    for (int d = d0; d <= d1; d += every) t.push_back(std::pow(10.0, d));
    return t;
  }
  // Less than two decades: 1, 2, 5 x 10^k.
  for (int d = int(std::floor(std::log10(lo))) ; d <= int(std::ceil(std::log10(hi))); ++d)
    for (double m : {1.0, 2.0, 5.0}) {
      const double v = m * std::pow(10.0, d);
      if (v >= lo * (1.0 - 1e-9) && v <= hi * (1.0 + 1e-9)) t.push_back(v);
    }
  return t;
}

std::string formatTick(double v, double step) {
  char buf[48];
  if (v == 0.0) return "0";
  const double a = std::abs(v);
  if (a >= 1e6 || a < 1e-4) {
    std::snprintf(buf, sizeof buf, "%.3g", v);
    return buf;
  }
  int decimals = 0;
  step = std::abs(step);
  if (step > 0.0 && step < 1.0) decimals = std::min(6, int(std::ceil(-std::log10(step) - 1e-9)));
  std::snprintf(buf, sizeof buf, "%.*f", decimals, v);
  return buf;
}

Vec3 plotPalette(int i) {
  static const Vec3 kTab10[] = {{0.122f, 0.467f, 0.706f}, {1.000f, 0.498f, 0.055f}, {0.173f, 0.627f, 0.173f},
                                {0.839f, 0.153f, 0.157f}, {0.580f, 0.404f, 0.741f}, {0.549f, 0.337f, 0.294f},
                                {0.890f, 0.467f, 0.761f}, {0.498f, 0.498f, 0.498f}, {0.737f, 0.741f, 0.133f},
                                {0.090f, 0.745f, 0.812f}};
  return kTab10[((i % 10) + 10) % 10];
}

// ---------------------------------------------------------------------------------------
// Frame

namespace {
double axisValue(double v, bool log) { return log ? std::log10(v) : v; }
bool usable(double v, bool log) { return std::isfinite(v) && (!log || v > 0.0); }

// The shown range and ticks of one axis.
void axisRange(const PlotAxis& axis, std::vector<double> values, int maxTicks, double& lo, double& hi,
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
    throw InputError("", std::string(which) + " axis range", formatTick(*axis.min, 1e-6) + " .. " +
                                                                 formatTick(*axis.max, 1e-6),
                     "min < max");
  if (axis.log && (!(dlo > 0.0) || !(dhi > 0.0)))
    throw InputError("", std::string(which) + " axis range", formatTick(dlo, 1e-6), "positive values on a log axis");
  if (!(dhi > dlo)) {  // a single value: widen around it
    if (axis.log) {
      if (!axis.min) dlo /= 2.0;
      if (!axis.max) dhi *= 2.0;
      if (!(dhi > dlo)) dhi = dlo * 4.0;
    } else {
      const double d = dlo == 0.0 ? 1.0 : 0.1 * std::abs(dlo);
      if (!axis.min) dlo -= d;
      if (!axis.max) dhi += d;
      if (!(dhi > dlo)) dhi = dlo + 2.0 * d;
    }
  }
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

double tickStep(const std::vector<double>& t, bool log, double v) {
  if (log) return v;
  return t.size() >= 2 ? t[1] - t[0] : 1.0;
}
}  // namespace

double PlotFrame::pixelX(double x) const {
  const double a = axisValue(xMin, logX), b = axisValue(xMax, logX);
  return left + (axisValue(x, logX) - a) / (b - a) * (right - left);
}
double PlotFrame::pixelY(double y) const {
  const double a = axisValue(yMin, logY), b = axisValue(yMax, logY);
  return bottom - (axisValue(y, logY) - a) / (b - a) * (bottom - top);
}
bool PlotFrame::insideX(double x) const { return usable(x, logX) && x >= xMin && x <= xMax; }
bool PlotFrame::insideY(double y) const { return usable(y, logY) && y >= yMin && y <= yMax; }

PlotFrame plotFrame(const Plot& plot) {
  if (plot.width < 64 || plot.height < 48)
    throw InputError("", "plot size", std::to_string(plot.width) + " x " + std::to_string(plot.height),
                     "at least 64 x 48 pixels");
  std::vector<double> xs, ys;
  for (size_t i = 0; i < plot.series.size(); ++i) {
    const PlotSeries& s = plot.series[i];
    if (s.x.size() != s.y.size())
      throw InputError("", "plot series " + (s.name.empty() ? std::to_string(i) : s.name),
                       std::to_string(s.x.size()) + " x values and " + std::to_string(s.y.size()) + " y values",
                       "as many x values as y values");
    for (size_t k = 0; k < s.x.size(); ++k)
      if (usable(s.x[k], plot.x.log) && usable(s.y[k], plot.y.log)) xs.push_back(s.x[k]), ys.push_back(s.y[k]);
  }
  for (const PlotMarker& m : plot.markers) xs.push_back(m.value);
  for (const PlotMarker& m : plot.hMarkers) ys.push_back(m.value);

  const int s = std::max(plot.fontScale, 1);
  const int th = font::textHeight(s);
  PlotFrame f;
  f.logX = plot.x.log;
  f.logY = plot.y.log;
  const int maxTicksX = std::clamp(plot.width / (48 * s), 3, 10);
  const int maxTicksY = std::clamp(plot.height / (24 * s), 3, 10);
  axisRange(plot.x, xs, maxTicksX, f.xMin, f.xMax, f.xTicks, "x");
  axisRange(plot.y, ys, maxTicksY, f.yMin, f.yMax, f.yTicks, "y");

  int yLabelW = 0;
  for (double t : f.yTicks)
    yLabelW = std::max(yLabelW, font::textWidth(formatTick(t, tickStep(f.yTicks, f.logY, t)), s));
  const int margin = 4 * s + 4;
  const int tick = 3 * s;
  f.left = margin + (plot.y.title.empty() ? 0 : th + 4 * s) + yLabelW + tick + 2 * s;
  f.top = margin + (plot.title.empty() ? 0 : th + 4 * s) + th / 2;
  // Room for the last x tick label, centred on the right edge.
  int lastXLabel = f.xTicks.empty() ? 0 : font::textWidth(formatTick(f.xTicks.back(), tickStep(f.xTicks, f.logX, f.xTicks.back())), s);
  f.right = plot.width - margin - std::max(lastXLabel / 2, 2 * s);
  f.bottom = plot.height - margin - (plot.x.title.empty() ? 0 : th + 4 * s) - th - tick - 2 * s;
  if (f.right - f.left < 16 || f.bottom - f.top < 16)
    throw InputError("", "plot size", std::to_string(plot.width) + " x " + std::to_string(plot.height),
                     "room for the plot area next to its labels (a larger size or a smaller fontScale)");
  return f;
}

// ---------------------------------------------------------------------------------------
// Rendering

namespace {

class Painter {
 public:
  explicit Painter(Image& img) : img_(img) {}
  void blend(int x, int y, const Vec3& c, float a) {
    if (x < 0 || y < 0 || x >= img_.width || y >= img_.height || a <= 0.0f) return;
    a = std::min(a, 1.0f);
    for (int k = 0; k < 3; ++k) img_.at(x, y, k) = img_.at(x, y, k) * (1.0f - a) + c[k] * a;
  }
  void fill(int x0, int y0, int x1, int y1, const Vec3& c, float a = 1.0f) {  // [x0,x1) x [y0,y1)
    for (int y = y0; y < y1; ++y)
      for (int x = x0; x < x1; ++x) blend(x, y, c, a);
  }
  void hline(int x0, int x1, int y, const Vec3& c, double dash = 0.0) {
    for (int x = x0; x <= x1; ++x)
      if (dash <= 0.0 || std::fmod(double(x - x0), 2.0 * dash) < dash) blend(x, y, c, 1.0f);
  }
  void vline(int x, int y0, int y1, const Vec3& c, double dash = 0.0) {
    for (int y = y0; y <= y1; ++y)
      if (dash <= 0.0 || std::fmod(double(y - y0), 2.0 * dash) < dash) blend(x, y, c, 1.0f);
  }

 private:
  Image& img_;
};

// Antialiased coverage of a thick polyline / discs, kept as the maximum per pixel, so that
// overlapping segments do not darken their joints.
class Coverage {
 public:
  Coverage(int w, int h, int cx0, int cy0, int cx1, int cy1)
      : w_(w), h_(h), cx0_(cx0), cy0_(cy0), cx1_(cx1), cy1_(cy1), c_(size_t(w) * h, 0.0f) {}
  // A segment; `phase` is the dash position (px along the line) at p0, advanced by its length.
  void segment(glm::dvec2 p0, glm::dvec2 p1, double width, double dash, double& phase) {
    const glm::dvec2 d = p1 - p0;
    const double len2 = glm::dot(d, d), len = std::sqrt(len2);
    const double r = 0.5 * width;
    const int x0 = std::max(cx0_, int(std::floor(std::min(p0.x, p1.x) - r - 1))),
              x1 = std::min(cx1_, int(std::ceil(std::max(p0.x, p1.x) + r + 1)));
    const int y0 = std::max(cy0_, int(std::floor(std::min(p0.y, p1.y) - r - 1))),
              y1 = std::min(cy1_, int(std::ceil(std::max(p0.y, p1.y) + r + 1)));
    for (int y = y0; y < y1; ++y)
      for (int x = x0; x < x1; ++x) {
        const glm::dvec2 p(x + 0.5, y + 0.5);
        double t = len2 > 0.0 ? std::clamp(glm::dot(p - p0, d) / len2, 0.0, 1.0) : 0.0;
        if (dash > 0.0 && std::fmod(phase + t * len, 2.0 * dash) >= dash) continue;
        const double dist = glm::length(p - (p0 + t * d));
        put(x, y, float(std::clamp(r + 0.5 - dist, 0.0, 1.0)));
      }
    phase += len;
  }
  void disc(glm::dvec2 c, double radius) {
    for (int y = std::max(cy0_, int(std::floor(c.y - radius - 1))); y < std::min(cy1_, int(std::ceil(c.y + radius + 1))); ++y)
      for (int x = std::max(cx0_, int(std::floor(c.x - radius - 1)));
           x < std::min(cx1_, int(std::ceil(c.x + radius + 1))); ++x) {
        const double dist = glm::length(glm::dvec2(x + 0.5, y + 0.5) - c);
        put(x, y, float(std::clamp(radius + 0.5 - dist, 0.0, 1.0)));
      }
  }
  void composite(Painter& p, const Vec3& color) const {
    for (int y = 0; y < h_; ++y)
      for (int x = 0; x < w_; ++x)
        if (float a = c_[size_t(y) * w_ + x]; a > 0.0f) p.blend(x, y, color, a);
  }

 private:
  void put(int x, int y, float a) {
    if (x < 0 || y < 0 || x >= w_ || y >= h_) return;
    float& v = c_[size_t(y) * w_ + x];
    v = std::max(v, a);
  }
  int w_, h_, cx0_, cy0_, cx1_, cy1_;
  std::vector<float> c_;
};

}  // namespace

Image renderPlot(const Plot& plot) {
  const PlotFrame f = plotFrame(plot);
  Image img(plot.width, plot.height, {"R", "G", "B"});
  std::fill(img.data.begin(), img.data.end(), 1.0f);
  Painter paint(img);
  const int s = std::max(plot.fontScale, 1);
  const int th = font::textHeight(s);
  const Vec3 black(0.0f), gridColor(0.88f), textColor(0.1f);
  const int L = int(f.left), T = int(f.top), R = int(f.right), B = int(f.bottom);
  const int tick = 3 * s;

  // Grid and ticks.
  for (double t : f.xTicks) {
    const int x = int(std::floor(f.pixelX(t)));
    if (plot.grid && x > L && x < R - 1) paint.vline(x, T, B - 1, gridColor);
    paint.vline(std::min(x, R - 1), B, B + tick - 1, black);
    const std::string label = formatTick(t, tickStep(f.xTicks, f.logX, t));
    const int w = font::textWidth(label, s);
    font::drawText(img, x - w / 2, B + tick + 2 * s, label, textColor, s);
  }
  for (double t : f.yTicks) {
    const int y = int(std::floor(f.pixelY(t)));
    if (plot.grid && y > T && y < B - 1) paint.hline(L, R - 1, y, gridColor);
    paint.hline(L - tick, L - 1, std::min(y, B - 1), black);
    const std::string label = formatTick(t, tickStep(f.yTicks, f.logY, t));
    const int w = font::textWidth(label, s);
    font::drawText(img, L - tick - 2 * s - w, y - font::kAscent * s / 2, label, textColor, s);
  }

  // Marker lines.
  for (const PlotMarker& m : plot.markers) {
    if (!f.insideX(m.value)) continue;
    const int x = std::min(int(std::floor(f.pixelX(m.value))), R - 1);
    paint.vline(x, T, B - 1, m.color, m.dash);
  }
  for (const PlotMarker& m : plot.hMarkers) {
    if (!f.insideY(m.value)) continue;
    const int y = std::min(int(std::floor(f.pixelY(m.value))), B - 1);
    paint.hline(L, R - 1, y, m.color, m.dash);
  }

  // Series: lines clipped to the plot area, markers may reach past it by their radius.
  for (size_t i = 0; i < plot.series.size(); ++i) {
    const PlotSeries& ser = plot.series[i];
    const Vec3 color = ser.color.value_or(plotPalette(int(i)));
    if (ser.line && ser.lineWidth > 0.0) {
      Coverage cov(img.width, img.height, L, T, R, B);
      double phase = 0.0;
      bool have = false;
      glm::dvec2 prev(0.0);
      for (size_t k = 0; k < ser.x.size(); ++k) {
        if (!usable(ser.x[k], f.logX) || !usable(ser.y[k], f.logY)) {
          have = false;
          continue;
        }
        const glm::dvec2 p = f.toPixel(ser.x[k], ser.y[k]);
        if (have) cov.segment(prev, p, ser.lineWidth, ser.dash, phase);
        prev = p;
        have = true;
      }
      cov.composite(paint, color);
    }
    if (ser.markers && ser.markerRadius > 0.0) {
      const int pad = int(std::ceil(ser.markerRadius)) + 1;
      Coverage cov(img.width, img.height, L - pad, T - pad, R + pad, B + pad);
      for (size_t k = 0; k < ser.x.size(); ++k)
        if (f.insideX(ser.x[k]) && f.insideY(ser.y[k])) cov.disc(f.toPixel(ser.x[k], ser.y[k]), ser.markerRadius);
      cov.composite(paint, color);
    }
  }

  // Marker labels, over the data on a light box.
  auto label = [&](int x, int y, const std::string& text, const Vec3& color) {
    const int w = font::textWidth(text, s);
    paint.fill(x - s, y - s, x + w + s, y + th + s, Vec3(1.0f), 0.8f);
    font::drawText(img, x, y, text, color, s);
  };
  for (const PlotMarker& m : plot.markers) {
    if (m.label.empty() || !f.insideX(m.value)) continue;
    const int x = std::min(int(std::floor(f.pixelX(m.value))), R - 1);
    const int w = font::textWidth(m.label, s);
    label(x + 3 * s + w < R ? x + 3 * s : x - 3 * s - w, T + 2 * s, m.label, m.color);
  }
  for (const PlotMarker& m : plot.hMarkers) {
    if (m.label.empty() || !f.insideY(m.value)) continue;
    const int y = std::min(int(std::floor(f.pixelY(m.value))), B - 1);
    const int w = font::textWidth(m.label, s);
    label(R - 3 * s - w, y - 2 * s - th > T ? y - 2 * s - th : y + 2 * s, m.label, m.color);
  }

  // Frame.
  paint.hline(L - 1, R, T - 1, black);
  paint.hline(L - 1, R, B, black);
  paint.vline(L - 1, T - 1, B, black);
  paint.vline(R, T - 1, B, black);

  // Legend (top right, inside the plot area).
  if (plot.legend) {
    std::vector<size_t> named;
    int textW = 0;
    for (size_t i = 0; i < plot.series.size(); ++i)
      if (!plot.series[i].name.empty()) {
        named.push_back(i);
        textW = std::max(textW, font::textWidth(plot.series[i].name, s));
      }
    if (!named.empty()) {
      const int pad = 3 * s, sample = 12 * s, rowH = th + 3 * s;
      const int boxW = pad + sample + 2 * s + textW + pad, boxH = pad + int(named.size()) * rowH - 3 * s + pad;
      const int bx1 = R - 4 * s, bx0 = bx1 - boxW, by0 = T + 4 * s, by1 = by0 + boxH;
      paint.fill(bx0, by0, bx1, by1, Vec3(1.0f), 0.85f);
      paint.hline(bx0, bx1, by0, Vec3(0.6f));
      paint.hline(bx0, bx1, by1, Vec3(0.6f));
      paint.vline(bx0, by0, by1, Vec3(0.6f));
      paint.vline(bx1, by0, by1, Vec3(0.6f));
      for (size_t r = 0; r < named.size(); ++r) {
        const PlotSeries& ser = plot.series[named[r]];
        const Vec3 color = ser.color.value_or(plotPalette(int(named[r])));
        const int ty = by0 + pad + int(r) * rowH;
        const double cy = ty + th / 2.0;
        Coverage cov(img.width, img.height, bx0, by0, bx1, by1);
        double phase = 0.0;
        if (ser.line) cov.segment({bx0 + pad, cy}, {bx0 + pad + sample, cy}, ser.lineWidth, ser.dash, phase);
        if (ser.markers) cov.disc({bx0 + pad + sample / 2.0, cy}, ser.markerRadius);
        cov.composite(paint, color);
        font::drawText(img, bx0 + pad + sample + 2 * s, ty, ser.name, textColor, s);
      }
    }
  }

  // Titles.
  const int margin = 4 * s + 4;
  if (!plot.title.empty()) {
    const int w = font::textWidth(plot.title, s);
    font::drawText(img, std::max(margin, (L + R) / 2 - w / 2), margin, plot.title, black, s);
  }
  if (!plot.x.title.empty()) {
    const int w = font::textWidth(plot.x.title, s);
    font::drawText(img, (L + R) / 2 - w / 2, plot.height - margin - th, plot.x.title, black, s);
  }
  if (!plot.y.title.empty()) {
    const int w = font::textWidth(plot.y.title, s);
    font::drawText(img, margin, std::max(0, (T + B) / 2 - w / 2), plot.y.title, black, s, font::TextDirection::Up);
  }
  return img;
}

void writePlot(const Plot& plot, const std::string& path) { writeImage(renderPlot(plot), path); }

// ---------------------------------------------------------------------------------------
// CSV

std::string csvField(const std::string& s) {
  if (s.find_first_of(",\"\r\n") == std::string::npos) return s;
  std::string out = "\"";
  for (char c : s) {
    if (c == '"') out += '"';
    out += c;
  }
  return out + "\"";
}

std::string csvNumber(double v) {
  if (std::isnan(v)) return "nan";
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.10g", v);
  return buf;
}

std::string csvText(const std::vector<std::string>& header, const std::vector<std::vector<std::string>>& rows) {
  std::string out;
  auto line = [&](const std::vector<std::string>& fields) {
    for (size_t i = 0; i < fields.size(); ++i) {
      if (i) out += ',';
      out += csvField(fields[i]);
    }
    out += "\n";
  };
  if (!header.empty()) line(header);
  for (const auto& r : rows) line(r);
  return out;
}

void writeCsv(const std::string& path, const std::vector<std::string>& header,
              const std::vector<std::vector<std::string>>& rows) {
  std::ofstream out(path, std::ios::binary);
  if (!out) throw std::runtime_error("cannot write " + path);
  out << csvText(header, rows);
  out.close();
  if (!out) throw std::runtime_error("cannot write " + path);
}

}  // namespace inim
