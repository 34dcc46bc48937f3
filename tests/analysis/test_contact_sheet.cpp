// Contact sheets: the sheet is as large as its layout says, every cell holds its image
// unchanged (or area-averaged when downscaled), and the Fig. 11 cross puts each view where
// the paper does.
#include <gtest/gtest.h>

#include <cmath>

#include "analysis/contact_sheet.h"
#include "analysis/colormap.h"
#include "draw/text.h"
#include "spectral/color.h"

using namespace inim;

namespace {

// Text sizes as the sheet lays them out: whole pixels, one line height per font.
int lineHeight(double size) { return int(std::ceil(draw::measureText("Ag", {size}).height)); }
int textWidth(const std::string& s, double size) { return int(std::ceil(draw::measureText(s, {size}).width)); }

Image pattern(int w, int h, float seed) {
  Image img(w, h, {"R", "G", "B"});
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int c = 0; c < 3; ++c) img.at(x, y, c) = std::fmod(0.13f * x + 0.29f * y + 0.31f * c + seed, 1.0f);
  return img;
}

// Whether the sheet holds `img` with its top-left corner at (x0, y0).
void expectPlaced(const Image& sheet, const Image& img, int x0, int y0) {
  int bad = 0;
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x)
      for (int c = 0; c < 3; ++c)
        if (sheet.at(x0 + x, y0 + y, c) != img.at(x, y, c)) ++bad;
  EXPECT_EQ(bad, 0) << "image at (" << x0 << ", " << y0 << ") differs";
}

}  // namespace

TEST(ContactSheet, GridSizeAndCellsAsLaidOut) {
  ContactSheetOptions o;
  o.margin = 5;
  o.gap = 3;
  o.titleSize = 11.0;
  o.titleGap = 2;
  Image a = pattern(30, 20, 0.1f), b = pattern(50, 10, 0.2f), c = pattern(12, 25, 0.3f);
  SheetGrid grid = {{SheetCell{"a", a}, SheetCell{"b", b}}, {SheetCell{"", c}, std::nullopt}};
  SheetLayout L;
  Image sheet = composeContactSheet(grid, o, 1, &L);
  // Columns: max(30, 12) = 30 and 50; rows: title line + 2, then max(20, 10) = 20; row 2 has
  // no title, 25.
  const int th = lineHeight(11.0);
  ASSERT_GE(th, 12);
  ASSERT_LE(th, 16);
  const int expectedW = 5 + 30 + 3 + 50 + 5;
  const int expectedH = 5 + (th + 2 + 20) + 3 + 25 + 5;
  EXPECT_EQ(sheet.width, expectedW);
  EXPECT_EQ(sheet.height, expectedH);
  EXPECT_EQ(L.width, expectedW);
  EXPECT_EQ(L.height, expectedH);
  ASSERT_TRUE(L.cells[0][0].used && L.cells[0][1].used && L.cells[1][0].used && !L.cells[1][1].used);
  EXPECT_EQ(L.cells[0][0].x, 5);
  EXPECT_EQ(L.cells[0][0].y, 5 + th + 2);
  EXPECT_EQ(L.cells[0][1].x, 5 + 30 + 3);
  EXPECT_EQ(L.cells[1][0].x, 5 + (30 - 12) / 2);  // centred in its column
  EXPECT_EQ(L.cells[1][0].y, 5 + th + 2 + 20 + 3);
  expectPlaced(sheet, a, L.cells[0][0].x, L.cells[0][0].y);
  expectPlaced(sheet, b, L.cells[0][1].x, L.cells[0][1].y);
  expectPlaced(sheet, c, L.cells[1][0].x, L.cells[1][0].y);
  // The titles are drawn: dark pixels in the title band of cell (0, 0) and of cell (0, 1),
  // antialiased (grey levels at the glyphs' edges), and none between the bands.
  int dark = 0, grey = 0;
  for (int c = 0; c < 2; ++c)
    for (int y = L.cells[0][c].titleY; y < L.cells[0][c].titleY + th; ++y)
      for (int x = L.cells[0][c].titleX; x < L.cells[0][c].titleX + textWidth(c ? "b" : "a", 11.0); ++x) {
        dark += sheet.at(x, y, 0) < 0.3f;
        grey += sheet.at(x, y, 0) > 0.3f && sheet.at(x, y, 0) < 0.9f;
      }
  EXPECT_GT(dark, 6);
  EXPECT_GT(grey, 2);
  for (int y = L.cells[0][0].titleY; y < L.cells[0][0].titleY + th; ++y)
    for (int x = L.cells[0][0].x + a.width; x < L.cells[0][1].titleX; ++x) EXPECT_EQ(sheet.at(x, y, 0), 1.0f);
  // Background elsewhere (inside the empty cell).
  EXPECT_EQ(sheet.at(L.width - 6, L.height - 6, 1), 1.0f);
}

TEST(ContactSheet, Fig11CrossPlacesEveryView) {
  ContactSheetOptions o;
  o.titleSize = 11.0;
  o.heading = "Fig. 11";
  Fig11Views v;
  const char* labels[] = {"0°", "-7° H", "+7° H", "+7° V", "-7° V"};
  std::optional<ViewPair>* slots[] = {&v.centre, &v.left, &v.right, &v.top, &v.bottom};
  for (int i = 0; i < 5; ++i)
    *slots[i] = ViewPair{labels[i], pattern(90, 80, 0.1f * i), pattern(90, 80, 0.05f + 0.1f * i), std::nullopt};
  SheetLayout L;
  Image sheet = composeFig11Sheet(v, o, &L);
  // 6 columns, each as wide as the widest of its 90 px images and its titles "<label>
  // reference" and "<label>  reconstruction" (the latter wider than the images).
  auto col = [](std::initializer_list<const char*> labels, const char* kind) {
    int w = 90;
    for (const char* l : labels) w = std::max(w, textWidth(std::string(l) + "  " + kind, 11.0));
    return w;
  };
  const int colsW = col({"-7° H"}, "reference") + col({"-7° H"}, "reconstruction") +
                    col({"+7° V", "0°", "-7° V"}, "reference") + col({"+7° V", "0°", "-7° V"}, "reconstruction") +
                    col({"+7° H"}, "reference") + col({"+7° H"}, "reconstruction");
  ASSERT_GT(col({"0°"}, "reconstruction"), 90);
  const int rowH = lineHeight(11.0) + o.titleGap + 80;
  EXPECT_EQ(sheet.width, 2 * o.margin + colsW + 3 * o.gap + 2 * o.groupGap);
  EXPECT_EQ(sheet.height, 2 * o.margin + (lineHeight(o.headingSize) + 2 * o.gap) + 3 * rowH + 2 * o.gap);
  // The heading is drawn at its place.
  int headingInk = 0;
  for (int y = L.headingY; y < L.headingY + lineHeight(o.headingSize); ++y)
    for (int x = L.headingX; x < L.headingX + textWidth("Fig. 11", o.headingSize); ++x) headingInk += sheet.at(x, y, 1) < 0.5f;
  EXPECT_GT(headingInk, 30);
  // Cross: top and bottom in the middle pair of columns, the row between holds left, centre, right.
  const int pos[5][2] = {{1, 2}, {1, 0}, {1, 4}, {0, 2}, {2, 2}};  // row, column of each reference
  for (int i = 0; i < 5; ++i) {
    const CellRect& ref = L.cells[size_t(pos[i][0])][size_t(pos[i][1])];
    const CellRect& rec = L.cells[size_t(pos[i][0])][size_t(pos[i][1] + 1)];
    ASSERT_TRUE(ref.used && rec.used) << labels[i];
    expectPlaced(sheet, (*slots[i])->reference, ref.x, ref.y);
    expectPlaced(sheet, (*slots[i])->reconstruction, rec.x, rec.y);
    EXPECT_EQ(ref.y, rec.y);
    EXPECT_LT(ref.x, rec.x);  // reference on the left
  }
  EXPECT_FALSE(L.cells[0][0].used);
  EXPECT_FALSE(L.cells[2][5].used);
  EXPECT_LT(L.cells[0][2].y, L.cells[1][2].y);
  EXPECT_LT(L.cells[1][2].y, L.cells[2][2].y);
  EXPECT_EQ(fig11Grid(v)[1][3]->title, "0°  reconstruction");
  EXPECT_EQ(fig11Grid(v)[1][0]->title, "-7° H  reference");
}

TEST(ContactSheet, DownscaleIsAnAreaAverage) {
  Image big = pattern(40, 20, 0.4f);
  ContactSheetOptions o;
  o.maxImageWidth = 20;
  SheetLayout L;
  Image sheet = composeContactSheet({{SheetCell{"", big}}}, o, 1, &L);
  const CellRect& r = L.cells[0][0];
  EXPECT_EQ(r.width, 20);
  EXPECT_EQ(r.height, 10);
  for (int y = 0; y < 10; ++y)
    for (int x = 0; x < 20; ++x)
      for (int c = 0; c < 3; ++c) {
        const double avg = 0.25 * (double(big.at(2 * x, 2 * y, c)) + big.at(2 * x + 1, 2 * y, c) +
                                   big.at(2 * x, 2 * y + 1, c) + big.at(2 * x + 1, 2 * y + 1, c));
        EXPECT_NEAR(sheet.at(r.x + x, r.y + y, c), avg, 1e-6);
      }
  // Non-integer ratios keep the mean of a constant image.
  Image grey(7, 5, {"R", "G", "B"});
  std::fill(grey.data.begin(), grey.data.end(), 0.375f);
  Image small = resampleArea(grey, 3, 2);
  for (float v : small.data) EXPECT_NEAR(v, 0.375f, 1e-6);
}

TEST(ContactSheet, ToDisplayEncodesSrgb) {
  Image lin(2, 1, {"R", "G", "B"});
  lin.at(0, 0, 0) = 0.18f, lin.at(0, 0, 1) = 0.5f, lin.at(0, 0, 2) = 0.0f;
  lin.at(1, 0, 0) = 4.0f, lin.at(1, 0, 1) = -0.1f, lin.at(1, 0, 2) = 1.0f;
  Image d = toDisplay(lin);
  EXPECT_NEAR(d.at(0, 0, 0), srgbEncode(0.18f), 1e-4);
  EXPECT_NEAR(d.at(0, 0, 1), srgbEncode(0.5f), 1e-4);
  EXPECT_NEAR(d.at(0, 0, 2), 0.0f, 1e-6);
  EXPECT_EQ(d.at(1, 0, 0), 1.0f);  // clamped
  EXPECT_GE(d.at(1, 0, 1), 0.0f);
  EXPECT_NEAR(d.at(1, 0, 2), 1.0f, 1e-4);
  Image half = toDisplay(lin, "lin_rec709", 0.5f);
  EXPECT_NEAR(half.at(0, 0, 1), srgbEncode(0.25f), 1e-4);
}

// With error maps the cross gains a fourth row: left, top, centre, bottom, right, each map
// placed as given; an error map shows 0 as Viridis' dark end, the maximum as its yellow end, and
// masked pixels as grey.
TEST(ContactSheet, Fig11ErrorMapsFormAFourthRow) {
  Fig11Views v;
  const char* labels[] = {"H -7°", "V +7°", "0°", "V -7°", "H +7°"};
  std::optional<ViewPair>* slots[] = {&v.left, &v.top, &v.centre, &v.bottom, &v.right};
  for (int i = 0; i < 5; ++i)
    *slots[i] = ViewPair{labels[i], pattern(40, 30, 0.1f), pattern(40, 30, 0.2f), pattern(40, 30, 0.1f * i)};
  SheetLayout L;
  const Image sheet = composeFig11Sheet(v, {}, &L, "dE");
  ASSERT_EQ(L.cells.size(), 4u);
  for (int i = 0; i < 5; ++i) {
    const CellRect& c = L.cells[3][size_t(i)];
    ASSERT_TRUE(c.used) << labels[i];
    expectPlaced(sheet, *(*slots[i])->errorMap, c.x, c.y);
  }
  const std::vector<float> e = {0.0f, 25.0f, 50.0f, 80.0f};
  const std::vector<uint8_t> mask = {1, 1, 1, 0};
  const Image m = errorMapImage(e, 4, 1, 50.0, &mask);
  EXPECT_NEAR(m.at(0, 0, 0), colorMap(ColorMap::Viridis, 0.0).x, 1e-6);
  EXPECT_NEAR(m.at(2, 0, 1), colorMap(ColorMap::Viridis, 1.0).y, 1e-6);
  EXPECT_FLOAT_EQ(m.at(3, 0, 0), 0.5f);
}
