#pragma once
// A small built-in 5x7 bitmap font for labels on generated images (contact sheets, plots,
// previews), so that no font file or font library is needed.
//
// Coverage: printable ASCII (32..126) and a few symbols that labels of this project use:
// ° ± µ μ × · ² − Δ θ λ σ ψ ≈ →. Text is UTF-8; a character without a glyph is drawn as a
// hollow box. Glyphs are 5 px wide on a 9-row cell: 7 rows from the cap height down to the
// baseline, plus 2 rows for the descenders of g j p q y , ; µ. The advance is 6 px; all
// sizes scale by an integer factor.
#include <cstdint>
#include <string>

#include "core/geometry.h"
#include "core/image.h"

namespace inim::font {

constexpr int kGlyphWidth = 5;
constexpr int kAscent = 7;       // cap height: rows 0..6 sit on the baseline
constexpr int kGlyphHeight = 9;  // rows of a glyph cell, descenders included (the line height)
constexpr int kAdvance = 6;  // glyph width + 1 px spacing

// The rows of a glyph cell, top to bottom; bit 4 (value 16) is the leftmost column.
struct Glyph {
  char32_t codePoint;
  uint8_t rows[kGlyphHeight];
};

// The glyph of a code point, or nullptr when the font has none.
const Glyph* findGlyph(char32_t codePoint);
// The glyph drawn for characters the font lacks (a hollow box).
const Glyph& missingGlyph();
// Whether pixel (col, row) of a glyph is set; col in [0,5), row in [0,9).
inline bool glyphPixel(const Glyph& g, int col, int row) { return (g.rows[row] >> (4 - col)) & 1; }

// UTF-8 to code points; invalid bytes become U+FFFD (drawn as the missing glyph).
std::u32string decodeUtf8(const std::string& utf8);

// Size of a single line of text in pixels at integer `scale` (>= 1). The width excludes the
// trailing 1-px spacing column of the last glyph; empty text has width 0.
int textWidth(const std::string& utf8, int scale = 1);
inline int textHeight(int scale = 1) { return kGlyphHeight * scale; }

enum class TextDirection {
  Horizontal,  // left to right
  Up,          // rotated 90° counter-clockwise: reads bottom to top (y-axis titles)
};

// Draws text into the first three channels of `img` with opacity `alpha` (pixels outside
// the image are clipped). (x, y) is the top-left corner of the text's bounding box, whose
// size is textWidth x textHeight (Horizontal) or textHeight x textWidth (Up).
void drawText(Image& img, int x, int y, const std::string& utf8, const Vec3& color, int scale = 1,
              TextDirection dir = TextDirection::Horizontal, float alpha = 1.0f);

}  // namespace inim::font
