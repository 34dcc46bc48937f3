#pragma once
// A raster canvas for figures (plots, diagrams), drawn with Cairo: antialiased lines, dashes,
// filled shapes, images and text (text.h). Coordinates are pixels, continuous, x to the right
// and y down from the top-left corner; pixel (i, j) covers [i, i+1) x [j, j+1), so a 1-px line
// is crisp at a half-integer coordinate (crisp()). Drawing is deterministic: the same calls
// give the same pixels, whatever the thread.
#include <cmath>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "core/geometry.h"
#include "core/image.h"
#include "draw/text.h"

namespace inim::draw {

using P2 = glm::dvec2;

struct Stroke {
  Vec3 color{0.0f};
  double width = 1.0;  // px
  double dash = 0.0;   // > 0: dashes of this length with gaps as long, px
  double alpha = 1.0;
};

// Where a text's box sits relative to its anchor point, per axis: Start = the box's left
// (top) edge on the point, Centre, End = its right (bottom) edge.
enum class Align { Start, Centre, End };
struct TextAnchor {
  Align h = Align::Start, v = Align::Start;
};

// The centre of the pixel holding coordinate v: where a 1-px line along it is crisp.
inline double crisp(double v) { return std::floor(v) + 0.5; }

class Canvas {
 public:
  // A canvas filled with `background`; backgroundAlpha 0 leaves it transparent (see alpha()).
  Canvas(int width, int height, const Vec3& background = Vec3(1.0f), double backgroundAlpha = 1.0);
  ~Canvas();
  Canvas(const Canvas&) = delete;
  Canvas& operator=(const Canvas&) = delete;
  int width() const { return width_; }
  int height() const { return height_; }

  void line(P2 a, P2 b, const Stroke& s);
  // A connected line through the points; a non-finite point breaks it (no segment to or
  // from it). Far-away points are clipped first, so any finite coordinate is safe.
  void polyline(const std::vector<P2>& points, const Stroke& s);
  // A closed polygon, filled (non-zero winding rule).
  void fillPolygon(const std::vector<P2>& points, const Vec3& color, double alpha = 1.0);
  void strokePolygon(const std::vector<P2>& points, const Stroke& s);
  void fillRect(double x0, double y0, double x1, double y1, const Vec3& color, double alpha = 1.0);
  void strokeRect(double x0, double y0, double x1, double y1, const Stroke& s);
  void disc(P2 centre, double radius, const Vec3& color, double alpha = 1.0);
  // Places an image's pixels 1:1 with their top-left corner at (x, y): R, G, B (display
  // values in [0, 1]) and A when present (else opaque).
  void image(const Image& img, int x, int y);

  // A line of text, its logical box placed against `at` by `anchor`; `up` turns it 90° to
  // read bottom to top (a y-axis title), the anchor then applying to the turned box. The box
  // is moved to whole pixels so that glyphs stay crisp. Returns the box drawn.
  TextSize text(const std::string& utf8, P2 at, const Font& font, const Vec3& color, TextAnchor anchor = {},
                bool up = false);

  // Later drawing is clipped to the rectangle (intersected with any clip already set), until
  // the matching popClip().
  void pushClip(double x0, double y0, double x1, double y1);
  void popClip();

  // The pixels as an RGB image, values k / 255 (exact 8-bit levels).
  Image toImage() const;
  // The opacity of every pixel (row-major, 0..255): on a transparent canvas, where anything
  // was drawn.
  std::vector<uint8_t> alpha() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  int width_, height_;
};

}  // namespace inim::draw
