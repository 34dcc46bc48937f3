// The built-in 5x7 font: coverage, UTF-8 decoding, sizes, and pixel-exact drawing in both
// directions.
#include <gtest/gtest.h>

#include "analysis/bitmap_font.h"

using namespace inim;

TEST(BitmapFont, CoversAsciiAndLabelSymbols) {
  for (char32_t c = 32; c <= 126; ++c) {
    const font::Glyph* g = font::findGlyph(c);
    ASSERT_NE(g, nullptr) << int(c);
    EXPECT_EQ(g->codePoint, c);
  }
  for (char32_t c : {U'°', U'±', U'µ', U'Δ', U'ψ', U'λ', U'σ', U'×', U'−', U'≈'}) EXPECT_NE(font::findGlyph(c), nullptr);
  EXPECT_EQ(font::findGlyph(U'€'), nullptr);
  // Distinct glyphs for letters (no copy-paste slips between upper and lower case).
  for (char32_t c = U'a'; c <= U'z'; ++c) {
    const auto* lo = font::findGlyph(c);
    const auto* up = font::findGlyph(c - 32);
    bool same = true;
    for (int r = 0; r < font::kGlyphHeight; ++r) same = same && lo->rows[r] == up->rows[r];
    EXPECT_FALSE(same) << char(c);
  }
}

TEST(BitmapFont, DecodesUtf8) {
  EXPECT_EQ(font::decodeUtf8("0\xC2\xB0 H"), std::u32string(U"0° H"));
  EXPECT_EQ(font::decodeUtf8("\xCE\x94" "E"), std::u32string(U"ΔE"));
  EXPECT_EQ(font::decodeUtf8("a\xFF" "b"), std::u32string(U"a\uFFFDb"));
  EXPECT_EQ(font::decodeUtf8("\xC2"), std::u32string(U"\uFFFD"));  // truncated
}

TEST(BitmapFont, Sizes) {
  EXPECT_EQ(font::textWidth("", 2), 0);
  EXPECT_EQ(font::textWidth("A", 1), 5);
  EXPECT_EQ(font::textWidth("AB", 1), 11);
  EXPECT_EQ(font::textWidth("7°", 3), 33);  // two glyphs, not three bytes
  EXPECT_EQ(font::textHeight(2), 18);  // 9-row cells: 7 above the baseline, 2 descender rows
}

TEST(BitmapFont, DrawsGlyphPixels) {
  Image img(20, 12, {"R", "G", "B"});
  std::fill(img.data.begin(), img.data.end(), 1.0f);
  font::drawText(img, 2, 3, "T", Vec3(0.0f), 2);
  const font::Glyph* g = font::findGlyph(U'T');
  for (int r = 0; r < font::kGlyphHeight && 3 + 2 * r + 1 < 12; ++r)
    for (int c = 0; c < 5; ++c)
      for (int a = 0; a < 2; ++a)
        for (int b = 0; b < 2; ++b)
          EXPECT_EQ(img.at(2 + 2 * c + b, 3 + 2 * r + a, 0), font::glyphPixel(*g, c, r) ? 0.0f : 1.0f);
  // Clipped at the border without crashing.
  font::drawText(img, -7, -3, "Wide text beyond", Vec3(0.0f), 3);
  font::drawText(img, 18, 10, "x", Vec3(0.0f), 1, font::TextDirection::Up);
}

TEST(BitmapFont, UpRotatesCounterClockwise) {
  // "L" rotated: the glyph's bottom bar becomes a vertical bar on the right, reading upward.
  const int w = font::textWidth("L");
  Image img(font::kGlyphHeight, w, {"Y"});
  font::drawText(img, 0, 0, "L", Vec3(1.0f), 1, font::TextDirection::Up);
  const font::Glyph* g = font::findGlyph(U'L');
  for (int r = 0; r < font::kGlyphHeight; ++r)
    for (int c = 0; c < 5; ++c) EXPECT_EQ(img.at(r, w - 1 - c, 0), font::glyphPixel(*g, c, r) ? 1.0f : 0.0f);
}
