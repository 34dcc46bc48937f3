#pragma once
// Text for figures: laid out by Pango, drawn antialiased by Cairo, always in DejaVu Sans (the
// Debian package fonts-dejavu-core) whatever the user's font configuration; see fonts.h.
// Text is UTF-8, one line; sizes are in pixels.
#include <string>
#include <vector>

#include "core/geometry.h"
#include "core/image.h"

namespace inim::draw {

struct Font {
  double size = 13.0;  // em size, px
  bool bold = false;
};

// The logical box of a line of text: advance widths by the font's ascent + descent.
struct TextSize {
  double width = 0.0, height = 0.0;
  double baseline = 0.0;  // from the top of the box
  int missingGlyphs = 0;  // characters the font has no glyph for (drawn as boxes)
};

TextSize measureText(const std::string& utf8, const Font& font = {});

// Draws text onto the first three channels of a float image, the top-left corner of its
// logical box at (x, y); pixels outside the image are left out. Only the pixels the glyphs
// touch change (blended by their coverage), so images next to the text keep their values.
void drawText(Image& img, int x, int y, const std::string& utf8, const Font& font, const Vec3& color);

// The font files text is drawn with. std::runtime_error when DejaVu Sans is not installed.
const std::vector<std::string>& fontFiles();

}  // namespace inim::draw
