#include "draw/canvas.h"

#include <algorithm>
#include <stdexcept>

#include "draw/fonts.h"

namespace inim::draw {

struct Canvas::Impl {
  cairo_surface_t* surface = nullptr;
  cairo_t* cr = nullptr;
  int clipDepth = 0;
};

namespace {

bool finite(P2 p) { return std::isfinite(p.x) && std::isfinite(p.y); }

// Liang-Barsky: clips segment a-b to the box; false when nothing is left. A clipped end is
// computed on the boundary it crosses (its other coordinate from the slope), which stays
// exact for very long segments where a + t (b - a) would cancel.
bool clipSegment(P2& a, P2& b, P2 lo, P2 hi) {
  double t0 = 0.0, t1 = 1.0;
  int e0 = -1, e1 = -1;  // the boundary that set t0, t1
  const P2 d = b - a;
  const double p[4] = {-d.x, d.x, -d.y, d.y}, q[4] = {a.x - lo.x, hi.x - a.x, a.y - lo.y, hi.y - a.y};
  for (int i = 0; i < 4; ++i) {
    if (p[i] == 0.0) {
      if (q[i] < 0.0) return false;
      continue;
    }
    const double t = q[i] / p[i];
    if (p[i] < 0.0 && t > t0) t0 = t, e0 = i;
    if (p[i] > 0.0 && t < t1) t1 = t, e1 = i;
    if (t0 > t1) return false;
  }
  const double bound[4] = {lo.x, hi.x, lo.y, hi.y};
  auto onBoundary = [&](int e) {
    if (e < 2) return P2(bound[e], a.y + (bound[e] - a.x) * (d.y / d.x));
    return P2(a.x + (bound[e] - a.y) * (d.x / d.y), bound[e]);
  };
  if (e0 >= 0) a = onBoundary(e0);
  if (e1 >= 0) b = onBoundary(e1);
  return finite(a) && finite(b);
}

void setColor(cairo_t* cr, const Vec3& c, double alpha) {
  cairo_set_source_rgba(cr, std::clamp(double(c.x), 0.0, 1.0), std::clamp(double(c.y), 0.0, 1.0),
                        std::clamp(double(c.z), 0.0, 1.0), std::clamp(alpha, 0.0, 1.0));
}

void setStroke(cairo_t* cr, const Stroke& s) {
  setColor(cr, s.color, s.alpha);
  cairo_set_line_width(cr, std::max(s.width, 0.0));
  cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);
  cairo_set_line_cap(cr, s.dash > 0.0 ? CAIRO_LINE_CAP_BUTT : CAIRO_LINE_CAP_ROUND);
  const double dash = s.dash;
  cairo_set_dash(cr, &dash, s.dash > 0.0 ? 1 : 0, 0.0);
}

uint8_t to8(float v) { return uint8_t(std::lround(std::clamp(std::isfinite(v) ? v : 0.0f, 0.0f, 1.0f) * 255.0f)); }

}  // namespace

Canvas::Canvas(int width, int height, const Vec3& background, double backgroundAlpha)
    : impl_(std::make_unique<Impl>()), width_(width), height_(height) {
  if (width <= 0 || height <= 0 || width > 32767 || height > 32767)
    throw std::runtime_error("canvas size " + std::to_string(width) + " x " + std::to_string(height) +
                             " out of range (1..32767)");
  impl_->surface = cairo_image_surface_create(CAIRO_FORMAT_ARGB32, width, height);
  impl_->cr = cairo_create(impl_->surface);
  if (cairo_status(impl_->cr) != CAIRO_STATUS_SUCCESS) throw std::runtime_error("cannot create a Cairo canvas");
  cairo_set_antialias(impl_->cr, CAIRO_ANTIALIAS_GRAY);
  cairo_set_operator(impl_->cr, CAIRO_OPERATOR_SOURCE);
  setColor(impl_->cr, background, backgroundAlpha);
  cairo_paint(impl_->cr);
  cairo_set_operator(impl_->cr, CAIRO_OPERATOR_OVER);
}

Canvas::~Canvas() {
  cairo_destroy(impl_->cr);
  cairo_surface_destroy(impl_->surface);
}

void Canvas::line(P2 a, P2 b, const Stroke& s) { polyline({a, b}, s); }

void Canvas::polyline(const std::vector<P2>& points, const Stroke& s) {
  // Segments are clipped to a box well around the canvas (Cairo's fixed-point coordinates
  // overflow near 2^23); a piece starts anew only where clipping or a gap broke the line.
  cairo_t* cr = impl_->cr;
  const double m = 8.0 * (width_ + height_) + 64.0 + s.width;
  const P2 lo(-m, -m), hi(width_ + m, height_ + m);
  bool open = false;
  P2 last(0.0);
  cairo_new_path(cr);
  for (size_t i = 1; i < points.size(); ++i) {
    P2 a = points[i - 1], b = points[i];
    if (!finite(a) || !finite(b) || !clipSegment(a, b, lo, hi)) {
      open = false;
      continue;
    }
    if (!open || a != last) cairo_move_to(cr, a.x, a.y);
    cairo_line_to(cr, b.x, b.y);
    open = (b == points[i]);
    last = b;
  }
  setStroke(cr, s);
  cairo_stroke(cr);
}

void Canvas::fillPolygon(const std::vector<P2>& points, const Vec3& color, double alpha) {
  cairo_t* cr = impl_->cr;
  const double m = 8.0 * (width_ + height_) + 64.0;
  cairo_new_path(cr);
  for (const P2& p : points)
    if (finite(p)) cairo_line_to(cr, std::clamp(p.x, -m, width_ + m), std::clamp(p.y, -m, height_ + m));
  cairo_close_path(cr);
  setColor(cr, color, alpha);
  cairo_fill(cr);
}

void Canvas::strokePolygon(const std::vector<P2>& points, const Stroke& s) {
  if (points.empty()) return;
  std::vector<P2> closed = points;
  closed.push_back(points.front());
  polyline(closed, s);
}

void Canvas::fillRect(double x0, double y0, double x1, double y1, const Vec3& color, double alpha) {
  fillPolygon({{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}}, color, alpha);
}

void Canvas::strokeRect(double x0, double y0, double x1, double y1, const Stroke& s) {
  strokePolygon({{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}}, s);
}

void Canvas::disc(P2 c, double radius, const Vec3& color, double alpha) {
  if (!finite(c) || !(radius > 0.0)) return;
  cairo_t* cr = impl_->cr;
  cairo_new_path(cr);
  cairo_arc(cr, c.x, c.y, radius, 0.0, 2.0 * kPi);
  setColor(cr, color, alpha);
  cairo_fill(cr);
}

void Canvas::image(const Image& img, int x, int y) {
  if (img.width <= 0 || img.height <= 0) return;
  const int r = img.channelIndex("R") >= 0 ? img.channelIndex("R") : 0;
  const int g = img.channelIndex("G") >= 0 ? img.channelIndex("G") : std::min(1, img.numChannels() - 1);
  const int b = img.channelIndex("B") >= 0 ? img.channelIndex("B") : std::min(2, img.numChannels() - 1);
  const int a = img.channelIndex("A");
  cairo_surface_t* src = cairo_image_surface_create(CAIRO_FORMAT_ARGB32, img.width, img.height);
  cairo_surface_flush(src);
  unsigned char* data = cairo_image_surface_get_data(src);
  const int stride = cairo_image_surface_get_stride(src);
  for (int j = 0; j < img.height; ++j) {
    auto* row = reinterpret_cast<uint32_t*>(data + size_t(j) * size_t(stride));
    for (int i = 0; i < img.width; ++i) {
      const uint32_t al = a >= 0 ? to8(img.at(i, j, a)) : 255u;
      auto pre = [&](int c) { return (uint32_t(to8(img.at(i, j, c))) * al + 127u) / 255u; };  // premultiplied
      row[i] = (al << 24) | (pre(r) << 16) | (pre(g) << 8) | pre(b);
    }
  }
  cairo_surface_mark_dirty(src);
  cairo_new_path(impl_->cr);
  cairo_set_source_surface(impl_->cr, src, x, y);
  cairo_pattern_set_filter(cairo_get_source(impl_->cr), CAIRO_FILTER_NEAREST);
  cairo_rectangle(impl_->cr, x, y, img.width, img.height);
  cairo_fill(impl_->cr);
  cairo_surface_destroy(src);
}

TextSize Canvas::text(const std::string& utf8, P2 at, const Font& font, const Vec3& color, TextAnchor anchor,
                      bool up) {
  if (utf8.empty() || !finite(at)) return {};
  cairo_t* cr = impl_->cr;
  auto lock = detail::textLock();
  cairo_save(cr);
  PangoLayout* layout = detail::makeLayout(cr, utf8, font);
  const TextSize size = detail::layoutSize(layout);
  const double bw = up ? size.height : size.width, bh = up ? size.width : size.height;
  auto frac = [](Align a) { return a == Align::Start ? 0.0 : a == Align::Centre ? 0.5 : 1.0; };
  const double x = std::round(at.x - frac(anchor.h) * bw), y = std::round(at.y - frac(anchor.v) * bh);
  if (up) {
    cairo_translate(cr, x, y + std::round(bh));
    cairo_rotate(cr, -0.5 * kPi);
  } else {
    cairo_translate(cr, x, y);
  }
  pango_cairo_update_layout(cr, layout);
  cairo_move_to(cr, 0.0, 0.0);
  setColor(cr, color, 1.0);
  pango_cairo_show_layout(cr, layout);
  cairo_new_path(cr);  // the path is not part of the saved state: leave no current point behind
  g_object_unref(layout);
  cairo_restore(cr);
  return size;
}

void Canvas::pushClip(double x0, double y0, double x1, double y1) {
  cairo_save(impl_->cr);
  cairo_new_path(impl_->cr);
  cairo_rectangle(impl_->cr, x0, y0, x1 - x0, y1 - y0);
  cairo_clip(impl_->cr);
  ++impl_->clipDepth;
}

void Canvas::popClip() {
  if (impl_->clipDepth == 0) return;
  cairo_restore(impl_->cr);
  --impl_->clipDepth;
}

Image Canvas::toImage() const {
  cairo_surface_flush(impl_->surface);
  const unsigned char* data = cairo_image_surface_get_data(impl_->surface);
  const int stride = cairo_image_surface_get_stride(impl_->surface);
  Image img(width_, height_, {"R", "G", "B"});
  for (int j = 0; j < height_; ++j) {
    const auto* row = reinterpret_cast<const uint32_t*>(data + size_t(j) * size_t(stride));
    for (int i = 0; i < width_; ++i) {
      const uint32_t p = row[i];  // opaque pixels: premultiplied = straight colour
      img.at(i, j, 0) = float((p >> 16) & 255u) / 255.0f;
      img.at(i, j, 1) = float((p >> 8) & 255u) / 255.0f;
      img.at(i, j, 2) = float(p & 255u) / 255.0f;
    }
  }
  return img;
}

std::vector<uint8_t> Canvas::alpha() const {
  cairo_surface_flush(impl_->surface);
  const unsigned char* data = cairo_image_surface_get_data(impl_->surface);
  const int stride = cairo_image_surface_get_stride(impl_->surface);
  std::vector<uint8_t> a(size_t(width_) * size_t(height_));
  for (int j = 0; j < height_; ++j) {
    const auto* row = reinterpret_cast<const uint32_t*>(data + size_t(j) * size_t(stride));
    for (int i = 0; i < width_; ++i) a[size_t(j) * size_t(width_) + size_t(i)] = uint8_t(row[i] >> 24);
  }
  return a;
}

}  // namespace inim::draw
