#include "draw/text.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "draw/fonts.h"

namespace inim::draw {

TextSize measureText(const std::string& utf8, const Font& font) {
  auto lock = detail::textLock();
  PangoLayout* layout = detail::makeLayout(nullptr, utf8, font);
  const TextSize s = detail::layoutSize(layout);
  g_object_unref(layout);
  return s;
}

void drawText(Image& img, int x, int y, const std::string& utf8, const Font& font, const Vec3& color) {
  if (utf8.empty() || img.numChannels() < 3) return;
  // The glyphs' coverage, rendered into an 8-bit mask around the text's ink and logical boxes,
  // then blended into the image.
  auto lock = detail::textLock();
  PangoLayout* layout = detail::makeLayout(nullptr, utf8, font);
  PangoRectangle ink, logical;
  pango_layout_get_pixel_extents(layout, &ink, &logical);
  const int x0 = std::min(ink.x, logical.x) - 1, y0 = std::min(ink.y, logical.y) - 1;
  const int x1 = std::max(ink.x + ink.width, logical.x + logical.width) + 1;
  const int y1 = std::max(ink.y + ink.height, logical.y + logical.height) + 1;
  cairo_surface_t* mask = cairo_image_surface_create(CAIRO_FORMAT_A8, x1 - x0, y1 - y0);
  cairo_t* cr = cairo_create(mask);
  cairo_translate(cr, -x0, -y0);
  pango_cairo_update_layout(cr, layout);
  cairo_set_source_rgba(cr, 0.0, 0.0, 0.0, 1.0);
  pango_cairo_show_layout(cr, layout);
  cairo_destroy(cr);
  g_object_unref(layout);
  lock.unlock();

  cairo_surface_flush(mask);
  const unsigned char* data = cairo_image_surface_get_data(mask);
  const int stride = cairo_image_surface_get_stride(mask);
  for (int j = 0; j < y1 - y0; ++j)
    for (int i = 0; i < x1 - x0; ++i) {
      const int px = x + x0 + i, py = y + y0 + j;
      const float a = float(data[size_t(j) * size_t(stride) + size_t(i)]) / 255.0f;
      if (a <= 0.0f || px < 0 || py < 0 || px >= img.width || py >= img.height) continue;
      for (int c = 0; c < 3; ++c) img.at(px, py, c) = img.at(px, py, c) * (1.0f - a) + color[c] * a;
    }
  cairo_surface_destroy(mask);
}

}  // namespace inim::draw
