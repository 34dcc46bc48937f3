// The placement page's previews (src/place/place_preview.h) on the depth ramp, a plane whose
// depth runs linearly across the display: z = -x tan 27 deg + t_z. Where it crosses the MLA
// plane (x = t_z / tan 27 deg) the preview is red; in front of it (left) real, behind virtual.
#include <gtest/gtest.h>

#include <cmath>

#include "core/output_file.h"
#include "display/ei_layout.h"
#include "field_files/field_factory.h"
#include "place/place_preview.h"

using namespace inim;

namespace {

struct Ramp {
  LoadedField field = loadField(dataPath("scenes/test/depth-ramp.json"), "scene");
  Display display = loadDisplay(defaultDisplayPath());
  EiLayout layout = computeLayout(display);
};
Ramp& ramp() {
  static Ramp r;
  return r;
}

bool isRed(const Image& im, int x, int y) { return im.at(x, y, 0) == 1.0f && im.at(x, y, 1) == 0.0f && im.at(x, y, 2) == 0.0f; }

// Mean x (mm, display frame) of the red lenslets of a level-0 frame, and their count.
double redCentroidMm(const PreviewFrame& f, const EiLayout& L, int& count) {
  double sum = 0.0;
  count = 0;
  for (int y = 0; y < f.image.height; ++y)
    for (int x = 0; x < f.image.width; ++x)
      if (isRed(f.image, x, y)) sum += L.pinholeXAt(x, y), ++count;
  return count ? sum / count : std::nan("");
}

PreviewFrame level0(double tzMm) {
  Placement p;
  p.translateMm = Vec3d(0.0, 0.0, tzMm);
  PreviewRequest r;
  r.onPlaneToleranceMm = 0.5;
  return renderPlacePreview(ramp().layout, *ramp().field.field, p.toDisplay(), 100.0, r);
}

}  // namespace

TEST(PlacePreview, TheRedBandIsWhereTheRampCrossesTheMlaPlane) {
  const double tan27 = std::tan(27.0 * M_PI / 180.0);
  for (double tz : {0.0, 5.0, -8.0}) {
    const PreviewFrame f = level0(tz);
    ASSERT_EQ(f.image.width, ramp().layout.eiCols);
    ASSERT_EQ(f.image.height, ramp().layout.eiRows);
    int red = 0;
    const double x = redCentroidMm(f, ramp().layout, red);
    // |z| <= 0.5 mm is a band 2 x 0.5 / tan 27 = 1.96 mm wide: 2 lenslet columns, every row.
    EXPECT_NEAR(x, tz / tan27, 0.5) << "t_z " << tz;
    EXPECT_GE(red, ramp().layout.eiRows) << "t_z " << tz;
    EXPECT_LE(red, 3 * ramp().layout.eiRows) << "t_z " << tz;
    EXPECT_EQ(red, f.counts.onPlane);  // the exact red is the on-plane mark, nothing else
    // Left of the band the ramp is in front of the MLA (real), right of it behind (virtual).
    const double xCross = tz / tan27, halfW = 0.5 * ramp().layout.eiaW * ramp().layout.pixelMm;
    EXPECT_NEAR(f.counts.real / double(ramp().layout.eiRows), (xCross + halfW) / 0.9875, 3.0);
    EXPECT_NEAR(f.counts.virtualHits / double(ramp().layout.eiRows), (halfW - xCross) / 0.9875, 3.0);
    EXPECT_EQ(f.counts.missed, 0);
  }
}

TEST(PlacePreview, LevelsOneAndTwoShowTheSamePlacement) {
  Placement p;
  PreviewRequest r;
  r.level = 1;
  r.raysPerSide = 4;
  const PreviewFrame f1 = renderPlacePreview(ramp().layout, *ramp().field.field, p.toDisplay(), 100.0, r);
  EXPECT_EQ(f1.image.width, 4 * ramp().layout.eiCols);
  EXPECT_EQ(f1.image.height, 4 * ramp().layout.eiRows);
  EXPECT_GT(f1.counts.onPlane, 0);
  // At four rays per lenslet the band is as wide in mm, so four times as many pixels, +- a column.
  const PreviewFrame f0 = level0(0.0);
  EXPECT_NEAR(f1.counts.onPlane / 16.0, f0.counts.onPlane, ramp().layout.eiRows);

  r.level = 2;
  r.cameraWidth = 320;
  const PreviewFrame f2 = renderPlacePreview(ramp().layout, *ramp().field.field, p.toDisplay(), 100.0, r);
  EXPECT_EQ(f2.image.width, 320);
  // The camera sees the plane's crossing at the middle of the image (x = 0 projects to the centre).
  double sum = 0.0;
  int n = 0;
  for (int y = 0; y < f2.image.height; ++y)
    for (int x = 0; x < f2.image.width; ++x)
      if (isRed(f2.image, x, y)) sum += x, ++n;
  ASSERT_GT(n, 0);
  EXPECT_NEAR(sum / n, 0.5 * f2.image.width, 3.0);
}

TEST(PlacePreview, SameRequestSameBytesAndACancelledRenderStops) {
  EXPECT_EQ(encodePng(level0(2.0).image), encodePng(level0(2.0).image));
  PreviewRequest r;
  EXPECT_THROW(renderPlacePreview(ramp().layout, *ramp().field.field, Transform(), 100.0, r, [] { return true; }),
               PreviewCancelled);
}
