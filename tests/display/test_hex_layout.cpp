// Hex-lattice EI layouts: hexagonal EIs as a Voronoi assignment of the pixel grid, checked by
// brute force against the lattice geometry; EI count against the area ratio; ray order.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <set>

#include "core/error.h"
#include "core/output_file.h"
#include "display/display.h"
#include "display/display_info.h"
#include "display/ei_layout.h"
#include "fixtures.h"

using namespace inim;
using fixtures::expectInputError;
using fixtures::hexDisplay;

namespace {

// Site (EI centre) of EI (k, l) recomputed from first principles: the hex lattice of pitch a
// (rows a sqrt(3)/2 apart, odd rows shifted by a/2) centred on the origin.
void expectedSite(int K, int R, double a, int k, int l, double& x, double& y) {
  const double xc = 0.5 * (K - 1) + (R > 1 ? 0.25 : 0.0), yc = 0.5 * (R - 1);
  x = (k - xc + ((l & 1) ? 0.5 : 0.0)) * a;
  y = (yc - l) * a * std::sqrt(3.0) / 2.0;
}

// Brute force over every EI: for each EIA pixel, the nearest EI centre and its distance, and
// the second-nearest distance (ties).
struct Nearest {
  int k = -1, l = -1;
  double d = std::numeric_limits<double>::infinity(), d2 = std::numeric_limits<double>::infinity();
};
Nearest nearestSite(const EiLayout& L, double a, double x, double y) {
  Nearest n;
  for (int k = 0; k < L.eiCols; ++k)
    for (int l = 0; l < L.eiRows; ++l) {
      double sx, sy;
      expectedSite(L.eiCols, L.eiRows, a, k, l, sx, sy);
      const double d = std::hypot(x - sx, y - sy);
      if (d < n.d) n.d2 = n.d, n.d = d, n.k = k, n.l = l;
      else if (d < n.d2) n.d2 = d;
    }
  return n;
}

}  // namespace

// Every EIA pixel is assigned to the nearest lenslet (EI) centre, checked by brute force over
// all EIs; pixels outside the array (nearer to a lenslet beyond the K x L ones than to any
// inside, i.e. farther than the cell's inradius from every EI centre's hexagon) are in none.
TEST(HexLayout, EveryPixelBelongsToTheNearestEiCentre) {
  for (auto [K, R, n] : {std::tuple{7, 5, 9}, std::tuple{6, 4, 10}, std::tuple{5, 6, 12}, std::tuple{1, 1, 7}}) {
    Display d = hexDisplay({.cols = K, .rows = R, .eiPx = n});
    EiLayout L = computeLayout(d);
    ASSERT_TRUE(L.isHex());
    const double a = n * L.pixelMm, s3 = std::sqrt(3.0);
    int64_t assigned = 0, outside = 0;
    for (int r = 0; r < L.eiaH; ++r)
      for (int c = 0; c < L.eiaW; ++c) {
        const double x = L.pixelCentreX(c), y = L.pixelCentreY(r);
        Nearest nb = nearestSite(L, a, x, y);
        int k, l;
        const bool in = L.eiAtPixel(c, r, k, l);
        // The pixel is inside nearest EI's hexagon (flat-to-flat a) unless it is outside the array.
        const double dx = std::abs(x - L.eiCentreXAt(nb.k, nb.l)), dy = std::abs(y - L.eiCentreYAt(nb.k, nb.l));
        const double hexNorm = std::max(dx, 0.5 * dx + 0.5 * s3 * dy);
        if (!in) {
          ++outside;
          EXPECT_GT(hexNorm, 0.5 * a * (1.0 - 1e-9)) << "pixel " << c << "," << r << " inside EI " << nb.k << ","
                                                      << nb.l << "'s hexagon but unassigned";
          continue;
        }
        ++assigned;
        double sx, sy;
        expectedSite(K, R, a, k, l, sx, sy);
        const double dk = std::hypot(x - sx, y - sy);
        // Assigned to the nearest centre (or to one tied with it within rounding).
        EXPECT_LE(dk, nb.d + 1e-9) << "pixel " << c << "," << r << " in EI " << k << "," << l << " but nearest is "
                                   << nb.k << "," << nb.l;
        if (nb.d2 - nb.d > 1e-9) {
          EXPECT_EQ(k, nb.k);
          EXPECT_EQ(l, nb.l);
        }
      }
    EXPECT_EQ(assigned, L.numRays());
    EXPECT_GT(assigned, 0);
    std::printf("  %d x %d EIs of %d px: %lld pixels in EIs, %lld outside, EIA %d x %d px\n", K, R, n,
                (long long)assigned, (long long)outside, L.eiaW, L.eiaH);
  }
}

// Odd rows are shifted right by half a pitch, as RealMla's lattice; the layout is centred.
TEST(HexLayout, LatticeMatchesRealMlaConvention) {
  Display d = hexDisplay({.cols = 8, .rows = 6, .eiPx = 10, .layout = EiLayoutKind::LensGrid, .lensPitchMm = 1.05});
  EiLayout L = computeLayout(d);
  const double P = 1.05;
  for (int k = 0; k < 8; ++k)
    for (int l = 0; l < 6; ++l) {
      EXPECT_NEAR(L.lensXAt(k, l) - L.lensXAt(0, 0), (k + 0.5 * (l & 1)) * P, 1e-12);
      EXPECT_NEAR(L.lensYAt(k, l) - L.lensYAt(0, 0), -l * P * std::sqrt(3.0) / 2.0, 1e-12);
      // lens-grid: pinholes at the lens centres.
      EXPECT_DOUBLE_EQ(L.pinholeXAt(k, l), L.lensXAt(k, l));
      EXPECT_DOUBLE_EQ(L.pinholeYAt(k, l), L.lensYAt(k, l));
    }
  // Centred: the lens centres' bounding box is symmetric about the origin.
  EXPECT_NEAR(L.lensXAt(0, 0) + L.lensXAt(7, 1), 0.0, 1e-12);
  EXPECT_NEAR(L.lensYAt(0, 0) + L.lensYAt(0, 5), 0.0, 1e-12);
  AreaMm A = L.activeArea();
  EXPECT_NEAR(A.x1 - A.x0, 8.5 * P, 1e-12);
  EXPECT_NEAR(A.y1 - A.y0, 5 * P * std::sqrt(3.0) / 2.0 + 2.0 * P / std::sqrt(3.0), 1e-12);
}

// The number of pixels in EIs matches the area ratio: each EI owns (about) one hexagon of
// area a^2 sqrt(3)/2, so pixels / EI -> n^2 sqrt(3)/2, and the number of EIs that fit a panel
// region is its area / the hex cell area, within edge effects.
TEST(HexLayout, EiCountAndSizeMatchAreaRatio) {
  for (int n : {9, 12, 25}) {
    const int K = 15, R = 13;
    Display d = hexDisplay({.cols = K, .rows = R, .eiPx = n, .pixelMm = 0.05});
    EiLayout L = computeLayout(d);
    const double cellPx = n * n * std::sqrt(3.0) / 2.0;
    const double mean = double(L.numRays()) / double(L.numEis());
    EXPECT_NEAR(mean, cellPx, 0.01 * cellPx) << "n = " << n;
    // Interior EIs all own ~ one cell (Voronoi cells of the pixel grid differ by a boundary row).
    for (int k = 1; k < K - 1; ++k)
      for (int l = 1; l < R - 1; ++l)
        EXPECT_NEAR(double(L.eiRayCount(k, l)), cellPx, 1.5 * n) << "EI " << k << "," << l;
    // EIs per panel area: the EIA rectangle holds K R EIs; its area over the cell area
    // overestimates by the ragged edges only (at most one cell row/column per side).
    const double a = n * L.pixelMm, cell = a * a * std::sqrt(3.0) / 2.0;
    const double rect = L.eiaW * L.pixelMm * L.eiaH * L.pixelMm;
    const double ratio = rect / cell;
    const double edge = 2.0 * (K + 1) + 2.0 * (R + 1);  // cells cut by the rectangle's sides
    EXPECT_GE(ratio, double(K * R));
    EXPECT_LE(ratio, double(K * R) + edge);
    std::printf("  n = %d: %.2f px per EI (hexagon %.2f px), EIA %.1f cells for %d EIs\n", n, mean, cellPx, ratio,
                K * R);
  }
}

// The paper-sized example: the hex variant of the prototype loads, its EI count matches
// the panel area over the hex cell area, and display info reports hex numbers.
TEST(HexLayout, ShippedHexExampleFitsThePanel) {
  Display d = loadDisplay(dataPath("optics/displays/hex-prototype-variant.json"));
  EiLayout L = computeLayout(d);
  ASSERT_TRUE(L.isHex());
  EXPECT_LE(L.eiaW, d.panel.widthPx);
  EXPECT_LE(L.eiaH, d.panel.heightPx);
  // Lenslets that fit the panel: panel area / (E^2 sqrt(3)/2), E the EI pitch, within one
  // ragged row/column per side.
  const double E = d.eiWidthPx * d.panel.pixelPitchMm;
  const double fit = d.panel.widthMm() * d.panel.heightMm() / (E * E * std::sqrt(3.0) / 2.0);
  EXPECT_LE(double(L.numEis()), fit);
  EXPECT_GE(double(L.numEis()), fit - (d.panel.widthMm() / E + 2.0 * d.panel.heightMm() / E) - 4.0);
  DisplayInfo info = derive(d);
  ASSERT_TRUE(info.hex.has_value());
  EXPECT_EQ(info.hex->lensletCount, 153 * 75);
  EXPECT_NEAR(info.hex->eiPixelsMean, 25 * 25 * std::sqrt(3.0) / 2.0, 4.0);
  EXPECT_NEAR(info.reconstruction.viewingAngleYDeg, 2.0 * std::atan(1.0 / (std::sqrt(3.0) * 4.0)) * 180.0 / M_PI,
              1e-9);
  EXPECT_GT(info.hex->eiaFill, 0.97);
  const std::string text = displayInfoText(d);
  EXPECT_NE(text.find("hex EIs"), std::string::npos);
  EXPECT_TRUE(displayInfoJson(d).contains("hex"));
}

// Ray order: EIs by column then row from the bottom, each EI's pixels by box column then row
// from the bottom; rayIndex / rayAddress / eiAtPixel agree; each EI's rays are contiguous.
TEST(HexLayout, RayOrderIsConsistent) {
  Display d = hexDisplay({.cols = 6, .rows = 5, .eiPx = 10});
  EiLayout L = computeLayout(d);
  std::set<int64_t> pixels;
  int64_t expected = 0;
  for (int64_t e = 0; e < L.numEis(); ++e) {
    int k, l;
    L.eiFromOrder(e, k, l);
    EXPECT_EQ(L.eiRayBegin(k, l), expected);
    EXPECT_EQ(L.rayBeginOfEiOrder(e), expected);
    int prevI = -1, prevJb = -1;
    L.forEachRayOfEi(k, l, [&](int64_t r, int col, int row, int i, int j) {
      EXPECT_EQ(r, expected++);
      int kk, ll;
      ASSERT_TRUE(L.eiAtPixel(col, row, kk, ll));
      EXPECT_EQ(kk, k);
      EXPECT_EQ(ll, l);
      EXPECT_TRUE(i >= 0 && i < L.eiW && j >= 0 && j < L.eiH);
      const int jb = L.eiH - 1 - j;
      EXPECT_TRUE(i > prevI || (i == prevI && jb > prevJb));
      prevI = i, prevJb = jb;
      EXPECT_TRUE(pixels.insert(int64_t(row) * L.eiaW + col).second);
    });
  }
  EXPECT_EQ(expected, L.numRays());
}

// Toed-in hex: EI centres at the lens centres projected from the viewpoint (pitch
// P (1 + g/D)), EIs the hexagons of ei_px around them (gaps between them), pinholes at the
// lens centres; EIs that would overlap are an input error.
TEST(HexLayout, ToedIn) {
  const double g = 3.0, D = 150.0, P = 1.0;
  fixtures::SmallDisplay toedIn{
      .cols = 7, .rows = 5, .eiPx = 9, .gapMm = g, .layout = EiLayoutKind::ToedIn, .lensPitchMm = P, .viewingDistanceMm = D};
  Display d = hexDisplay(toedIn);
  EiLayout L = computeLayout(d);
  const double m = 1.0 + g / D;
  for (int k = 0; k < 7; ++k)
    for (int l = 0; l < 5; ++l) {
      EXPECT_NEAR(L.eiCentreXAt(k, l), L.lensXAt(k, l) * m, 1e-12);
      EXPECT_NEAR(L.eiCentreYAt(k, l), L.lensYAt(k, l) * m, 1e-12);
      EXPECT_DOUBLE_EQ(L.pinholeXAt(k, l), L.lensXAt(k, l));
    }
  const double s3 = std::sqrt(3.0);
  for (int r = 0; r < L.eiaH; ++r)
    for (int c = 0; c < L.eiaW; ++c) {
      int k, l;
      if (!L.eiAtPixel(c, r, k, l)) continue;
      const double dx = std::abs(L.pixelCentreX(c) - L.eiCentreXAt(k, l)),
                   dy = std::abs(L.pixelCentreY(r) - L.eiCentreYAt(k, l));
      EXPECT_LE(std::max(dx, 0.5 * dx + 0.5 * s3 * dy), 0.45 + 1e-9);
    }
  // 12 px EIs do not fit a 1.02 mm = 10.2 px pitch.
  toedIn.eiPx = 12;
  Display bad = hexDisplay(toedIn);
  EXPECT_EQ(expectInputError([&] { (void)computeLayout(bad); }).key(), "viewing_distance_mm");
}

TEST(HexLayout, EiPxMustBeOneNumber) {
  Display d = hexDisplay();
  d.eiHeightPx = d.eiWidthPx + 1;
  EXPECT_EQ(expectInputError([&] { (void)computeLayout(d); }).key(), "ei_px");
}
