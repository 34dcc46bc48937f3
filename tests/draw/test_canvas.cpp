// The Cairo canvas: crisp 1-px lines where the coordinates say, filled shapes, images placed
// 1:1, clipping, text placement by anchor, transparent canvases as ink masks, and safety with
// huge coordinates.
#include <gtest/gtest.h>

#include "draw/canvas.h"

using namespace inim;
using namespace inim::draw;

namespace {
float red(const Image& img, int x, int y) { return img.at(x, y, 0); }
// Dark pixels (any channel below 0.5) inside [x0, x1) x [y0, y1).
int darkIn(const Image& img, int x0, int y0, int x1, int y1) {
  int n = 0;
  for (int y = std::max(0, y0); y < std::min(img.height, y1); ++y)
    for (int x = std::max(0, x0); x < std::min(img.width, x1); ++x) n += img.at(x, y, 0) < 0.5f;
  return n;
}
}  // namespace

TEST(Canvas, CrispLinesAndShapes) {
  Canvas cv(40, 30);
  cv.line({crisp(10), 2.0}, {crisp(10), 28.0}, {Vec3(0.0f)});
  cv.fillRect(20, 5, 30, 15, Vec3(1.0f, 0.0f, 0.0f));
  cv.disc({25.0, 22.0}, 4.0, Vec3(0.0f, 0.0f, 1.0f));
  const Image img = cv.toImage();
  ASSERT_EQ(img.width, 40);
  ASSERT_EQ(img.height, 30);
  // The 1-px line covers exactly column 10.
  EXPECT_EQ(red(img, 10, 15), 0.0f);
  EXPECT_EQ(red(img, 9, 15), 1.0f);
  EXPECT_EQ(red(img, 11, 15), 1.0f);
  // The rectangle covers whole pixels [20, 30) x [5, 15).
  EXPECT_EQ(img.at(20, 5, 1), 0.0f);
  EXPECT_EQ(img.at(29, 14, 1), 0.0f);
  EXPECT_EQ(img.at(30, 14, 1), 1.0f);
  EXPECT_EQ(img.at(19, 10, 1), 1.0f);
  // The disc's centre is pure blue.
  EXPECT_EQ(img.at(25, 22, 0), 0.0f);
  EXPECT_EQ(img.at(25, 22, 2), 1.0f);
}

TEST(Canvas, DashesClipsAndBreaks) {
  Canvas cv(100, 20);
  cv.line({0.0, crisp(5)}, {100.0, crisp(5)}, {Vec3(0.0f), 1.0, 10.0});
  cv.pushClip(0, 10, 50, 20);
  cv.line({0.0, crisp(15)}, {100.0, crisp(15)}, {Vec3(0.0f)});
  cv.popClip();
  const double nan = std::nan("");
  cv.polyline({{0.0, 18.5}, {20.0, 18.5}, {nan, nan}, {60.0, 18.5}, {100.0, 18.5}}, {Vec3(0.0f)});
  const Image img = cv.toImage();
  EXPECT_EQ(red(img, 5, 5), 0.0f);   // dash on [0, 10)
  EXPECT_EQ(red(img, 15, 5), 1.0f);  // gap on [10, 20)
  EXPECT_EQ(red(img, 25, 5), 0.0f);
  EXPECT_EQ(red(img, 40, 15), 0.0f);  // inside the clip
  EXPECT_EQ(red(img, 60, 15), 1.0f);  // outside
  EXPECT_EQ(red(img, 10, 18), 0.0f);
  EXPECT_EQ(red(img, 40, 18), 1.0f);  // the gap at the NaN point
  EXPECT_EQ(red(img, 80, 18), 0.0f);
}

TEST(Canvas, HugeCoordinatesAreClipped) {
  Canvas cv(50, 50);
  // A line from far outside through the middle: only its visible part matters.
  cv.line({-1e12, crisp(25)}, {1e12, crisp(25)}, {Vec3(0.0f)});
  cv.line({crisp(25), -1e300}, {crisp(25), 1e300}, {Vec3(0.0f)});
  const Image img = cv.toImage();
  EXPECT_EQ(red(img, 3, 25), 0.0f);
  EXPECT_EQ(red(img, 47, 25), 0.0f);
  EXPECT_EQ(red(img, 25, 3), 0.0f);
  EXPECT_EQ(red(img, 3, 3), 1.0f);
}

TEST(Canvas, ImagesArePlacedOneToOne) {
  Image src(3, 2, {"R", "G", "B"});
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 3; ++x) src.at(x, y, 0) = float(x + 3 * y) / 5.0f, src.at(x, y, 1) = 0.2f;
  Canvas cv(10, 10);
  cv.image(src, 4, 6);
  const Image img = cv.toImage();
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 3; ++x) {
      EXPECT_NEAR(img.at(4 + x, 6 + y, 0), src.at(x, y, 0), 0.5f / 255.0f);
      EXPECT_NEAR(img.at(4 + x, 6 + y, 1), 0.2f, 0.5f / 255.0f);
    }
  EXPECT_EQ(img.at(3, 6, 1), 1.0f);
  EXPECT_EQ(img.at(7, 6, 1), 1.0f);
}

TEST(Canvas, TextIsPlacedByItsAnchor) {
  const Font f{14.0};
  const TextSize s = measureText("Label 42", f);
  Canvas cv(200, 200);
  cv.text("Label 42", {100.0, 20.0}, f, Vec3(0.0f), {Align::Centre, Align::Start});
  cv.text("Label 42", {190.0, 190.0}, f, Vec3(0.0f), {Align::End, Align::End});
  cv.text("Label 42", {10.0, 100.0}, f, Vec3(0.0f), {Align::Start, Align::Centre}, true);
  const Image img = cv.toImage();
  const int w = int(std::ceil(s.width)), h = int(std::ceil(s.height));
  // Centred horizontally below y = 20.
  EXPECT_GT(darkIn(img, 100 - w / 2 - 1, 20, 100 + w / 2 + 1, 20 + h), 40);
  EXPECT_EQ(darkIn(img, 0, 0, 200, 19), 0);
  // Bottom-right corner at (190, 190).
  EXPECT_GT(darkIn(img, 190 - w, 190 - h, 190, 190), 40);
  EXPECT_EQ(darkIn(img, 191, 150, 200, 200), 0);
  // Turned up: a box h wide and w tall, centred on y = 100, its left edge at x = 10.
  EXPECT_GT(darkIn(img, 10, 100 - w / 2 - 1, 10 + h, 100 + w / 2 + 1), 40);
  EXPECT_EQ(darkIn(img, 0, 50, 9, 150), 0);
  EXPECT_EQ(darkIn(img, 10, 100 + w / 2 + 2, 10 + h, 150), 0);
}

TEST(Canvas, ShapesAfterTextStartAfresh) {
  // Text leaves no current point behind: a rectangle drawn next covers itself only (no
  // sliver back to where the text began).
  Canvas cv(200, 100);
  cv.text("label", {10.0, 10.0}, {13.0}, Vec3(0.0f));
  cv.fillRect(150, 60, 190, 90, Vec3(0.0f), 0.5);
  cv.disc({100.0, 80.0}, 3.0, Vec3(0.0f));
  cv.fillPolygon({{20.0, 90.0}, {40.0, 90.0}, {30.0, 70.0}}, Vec3(0.0f));
  const Image img = cv.toImage();
  int stray = 0;
  for (int y = 0; y < 100; ++y)
    for (int x = 0; x < 200; ++x) {
      const bool expected = (x < 60 && y < 30) || (x >= 150 && y >= 60) || (x >= 96 && x < 104 && y >= 76 && y < 84) ||
                            (x >= 19 && x <= 41 && y >= 69);
      stray += !expected && img.at(x, y, 0) < 1.0f;
    }
  EXPECT_EQ(stray, 0);
}

TEST(Canvas, TransparentCanvasIsAnInkMask) {
  Canvas cv(20, 20, Vec3(0.0f), 0.0);
  cv.fillRect(5, 5, 10, 10, Vec3(0.3f));
  const std::vector<uint8_t> a = cv.alpha();
  ASSERT_EQ(a.size(), 400u);
  EXPECT_EQ(a[size_t(7 * 20 + 7)], 255);
  EXPECT_EQ(a[size_t(2 * 20 + 2)], 0);
  EXPECT_EQ(a[size_t(12 * 20 + 7)], 0);
}

TEST(Canvas, DrawingIsDeterministic) {
  auto draw = [] {
    Canvas cv(120, 80);
    cv.polyline({{3.3, 70.1}, {40.7, 10.2}, {90.1, 60.9}, {117.2, 5.5}}, {Vec3(0.1f, 0.4f, 0.8f), 2.0, 6.0});
    cv.disc({60.2, 40.7}, 3.5, Vec3(0.9f, 0.2f, 0.1f), 0.7);
    cv.text("ψ = 4.5°", {10.0, 10.0}, {13.0}, Vec3(0.0f));
    return cv.toImage();
  };
  EXPECT_EQ(draw().data, draw().data);
}
