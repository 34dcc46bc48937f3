// Text through Pango: DejaVu Sans is found, sizes behave, the labels of this project have
// glyphs, and drawing onto a float image changes only the pixels under the glyphs.
#include <gtest/gtest.h>

#include <filesystem>

#include "draw/text.h"

using namespace inim;
using namespace inim::draw;

TEST(Text, UsesDejaVuSans) {
  const auto& files = fontFiles();
  ASSERT_FALSE(files.empty());
  EXPECT_EQ(std::filesystem::path(files[0]).filename(), "DejaVuSans.ttf");
  for (const std::string& f : files) EXPECT_TRUE(std::filesystem::exists(f)) << f;
}

TEST(Text, SizesGrowWithTextAndFont) {
  const TextSize a = measureText("0.25"), b = measureText("0.25 mm"), big = measureText("0.25", {26.0});
  EXPECT_GT(a.width, 10.0);
  EXPECT_GT(b.width, a.width + 10.0);
  EXPECT_NEAR(big.width, 2.0 * a.width, 0.15 * a.width);
  // DejaVu Sans: ascent + descent is 1.16 em, the baseline 0.93 em down (each rounded up to
  // whole pixels: metrics are hinted).
  EXPECT_GE(a.height, 13.0 * 1.164);
  EXPECT_LE(a.height, 13.0 * 1.164 + 2.0);
  EXPECT_GE(a.baseline, 13.0 * 0.928);
  EXPECT_LE(a.baseline, 13.0 * 0.928 + 1.0);
  EXPECT_GT(measureText("Title", {13.0, true}).width, measureText("Title", {13.0, false}).width);
  EXPECT_EQ(measureText("").width, 0.0);
}

TEST(Text, LabelSymbolsHaveGlyphs) {
  EXPECT_EQ(measureText("ψ/2 ± 0.5° ΔE₀₀ λ = 550 nm, 3 µm × 2, x² − 1 ≈ 0 → σ").missingGlyphs, 0);
  EXPECT_GT(measureText("\xEE\x80\x80").missingGlyphs, 0);  // U+E000, private use: no glyph
  EXPECT_EQ(measureText("a\xFF" "b").missingGlyphs, 0);    // a bad byte becomes U+FFFD, which has one
}

TEST(Text, DrawsOnlyUnderTheGlyphs) {
  Image img(120, 30, {"R", "G", "B"});
  std::fill(img.data.begin(), img.data.end(), 1.0f);
  const Font f{16.0};
  const TextSize s = measureText("Hello", f);
  drawText(img, 10, 5, "Hello", f, Vec3(0.0f));
  int dark = 0, grey = 0, outside = 0;
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) {
      const float v = img.at(x, y, 0);
      const bool inBox = x >= 10 && x < 10 + std::ceil(s.width) && y >= 5 && y < 5 + std::ceil(s.height);
      if (v < 1.0f && !inBox) ++outside;
      if (inBox && v < 0.2f) ++dark;
      if (inBox && v > 0.2f && v < 0.8f) ++grey;  // antialiased edges
    }
  EXPECT_GT(dark, 60);
  EXPECT_GT(grey, 10);
  EXPECT_EQ(outside, 0);
  // Same call, same pixels; clipped at the image border without harm.
  Image again(120, 30, {"R", "G", "B"});
  std::fill(again.data.begin(), again.data.end(), 1.0f);
  drawText(again, 10, 5, "Hello", f, Vec3(0.0f));
  EXPECT_EQ(img.data, again.data);
  EXPECT_NO_THROW(drawText(again, 100, 20, "clipped text", f, Vec3(0.0f)));
  EXPECT_NO_THROW(drawText(again, -50, -10, "clipped text", f, Vec3(0.0f)));
}
