// Exposure and sRGB encoding of camera RGB images.
#include <gtest/gtest.h>

#include <cmath>

#include "core/error.h"
#include "spectral/color.h"
#include "display_view/view_image.h"
#include "view_test_util.h"

using namespace inim;
using namespace view_test;

TEST(ViewImage, AutoExposureMapsThePercentileToTarget) {
  const CameraSensor& sensor = defaultCamera().sensor;
  Image img(400, 300, {"R", "G", "B"});
  for (int y = 0; y < 300; ++y)
    for (int x = 0; x < 400; ++x)
      for (int c = 0; c < 3; ++c) img.at(x, y, c) = x < 200 ? 0.0f : 2.0f;  // half black, half a D65 grey of Y = 2
  // Camera RGB (2, 2, 2) is D65 at Y = 2: linear Rec.709 (2, 2, 2); auto exposure maps it to 0.9.
  EXPECT_NEAR(exposureFactor(img, sensor, Exposure{}), 0.45, 1e-3);
  // A single noisy pixel does not set the exposure (blocks are averaged first).
  img.at(300, 150, 1) = 1e4f;
  EXPECT_NEAR(exposureFactor(img, sensor, Exposure{}), 0.45, 2e-3);
  EXPECT_EQ(exposureFactor(img, sensor, parseExposure("0.25")), 0.25);
  EXPECT_THROW(parseExposure("-1"), InputError);
  EXPECT_THROW(parseExposure("bright"), InputError);
  EXPECT_TRUE(parseExposure("auto").automatic);
  Image black(10, 10, {"R", "G", "B"});
  EXPECT_EQ(exposureFactor(black, sensor, Exposure{}), 1.0);
}

TEST(ViewImage, CameraWhiteEncodesToSrgbGrey) {
  const CameraSensor& sensor = defaultCamera().sensor;
  Image img(2, 1, {"R", "G", "B"});
  for (int c = 0; c < 3; ++c) {
    img.at(0, 0, c) = 0.2f;
    img.at(1, 0, c) = 5.0f;  // over range: clamped
  }
  Image s = cameraRgbToSrgb(img, sensor);
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(s.at(0, 0, c), srgbEncode(0.2f), 2e-3) << c;
    EXPECT_EQ(s.at(1, 0, c), 1.0f);
  }
  Image k = scaledImage(img, 2.0);
  EXPECT_FLOAT_EQ(k.at(0, 0, 1), 0.4f);
}
