// The reference as a comparison renders it (runs/pose_comparison.h): full samples on the
// mask and as far as the band-limited reference's filter reaches from it, one sample elsewhere.
// On an analytic plane at z = 5 mm, whose filter reaches farther than at the MLA plane (so the
// second pass is needed), the compared pixels and the band-limited reference on the mask are
// those of the reference rendered in full, bit for bit, for fewer rays; a pixel far from the mask
// is the one-sample reference's.
#include <gtest/gtest.h>

#include <cstring>

#include "camera/camera_config.h"
#include "camera/camera_model.h"
#include "runs/pose_comparison.h"
#include "grey_plane.h"
#include "scene/analytic_scene.h"
#include "display_view/display_pose.h"
#include "display_view/reference_renderer.h"

using namespace inim;

namespace {



// 2 px lenslets (sigma 0.58 px, reach 2 px at z = 0); at z = 5 the EI pixel's cone adds
// 10 px (sigma 3.0 px, reach 10 px).
BandLimit testBand() { return BandLimit{0.1, 0.1, 1.0, 200.0, 0.05}; }

PixelMask centreMask(int W, int H) {
  PixelMask m;
  m.width = W, m.height = H;
  m.on.assign(size_t(W) * H, 0);
  for (int y = 14; y < 34; ++y)
    for (int x = 20; x < 44; ++x) m.on[size_t(y) * W + x] = 1;
  return m;
}

bool samePixel(const Image& a, const Image& b, int x, int y) {
  const size_t C = size_t(a.numChannels()), i = (size_t(y) * size_t(a.width) + size_t(x)) * C;
  return std::memcmp(&a.data[i], &b.data[i], sizeof(float) * C) == 0;
}

}  // namespace

TEST(PoseComparison, ComparedReferenceIsTheFullReferenceWhereItIsRead) {
  const auto scene = fixtures::greyPlaneAt5mm(40);
  const DisplayPose pose{0.0, 0.0, 200.0};
  PinholeCameraModel cam(SensorGeometry{64, 48, 0.05}, pose.cameraPose(), 20.0, false);
  const BandLimit band = testBand();
  ASSERT_GT(band.sigmaPx(5.0), 4.0 * band.sigmaPx(0.0));  // the second pass has work to do
  const PixelMask mask = centreMask(64, 48);
  ReferenceSettings s;
  s.spp = 8;
  s.progress = false;
  s.depth = true;
  ViewResult full = renderReference(*scene, Transform(), cam, fixtures::defaultSensor(), s);
  ViewResult compared = renderComparedReference(*scene, Transform(), cam, fixtures::defaultSensor(), s, mask, band);
  std::printf("[ measured ] rays: full %llu, compared %llu\n", (unsigned long long)full.stats.tracedRays,
              (unsigned long long)compared.stats.tracedRays);
  EXPECT_LT(compared.stats.tracedRays, full.stats.tracedRays * 3 / 4);
  int differing = 0;
  for (int y = 0; y < 48; ++y)
    for (int x = 0; x < 64; ++x)
      if (mask.counts(x, y) && !samePixel(full.image, compared.image, x, y)) ++differing;
  EXPECT_EQ(differing, 0);

  const ReferenceDepth fullDepth = takeDepthChannels(full.image);
  const ReferenceDepth comparedDepth = takeDepthChannels(compared.image);
  const Image a = bandLimitedReference(full.image, fullDepth, band);
  const Image b = bandLimitedReference(compared.image, comparedDepth, band);
  differing = 0;
  for (int y = 0; y < 48; ++y)
    for (int x = 0; x < 64; ++x)
      if (mask.counts(x, y) && !samePixel(a, b, x, y)) ++differing;
  EXPECT_EQ(differing, 0) << "band-limited pixels on the mask differ";

  // Far from the mask (corners, on the plane): the first of the pixel's 8 samples, as in a
  // one-sample reference.
  ReferenceSettings one = s;
  one.spp = 1;
  one.depth = false;
  const Image single = renderReference(*scene, Transform(), cam, fixtures::defaultSensor(), one).image;
  for (auto [x, y] : {std::pair{1, 1}, {62, 46}}) {
    EXPECT_TRUE(samePixel(single, compared.image, x, y));
    EXPECT_FALSE(samePixel(full.image, compared.image, x, y));
  }
}

TEST(PoseComparison, OneSampleOutsideAMapIsTheFirstOfTheFullSet) {
  // A reference with 1 sample outside a map equals, there, a 1-sample reference; inside, the
  // 8-sample one (the samples of a pixel do not depend on how many are drawn).
  const auto scene = fixtures::greyPlaneAt5mm(40);
  const DisplayPose pose{0.0, 0.0, 200.0};
  PinholeCameraModel cam(SensorGeometry{32, 24, 0.05}, pose.cameraPose(), 20.0, false);
  const PixelMask mask = [] {
    PixelMask m;
    m.width = 32, m.height = 24;
    m.on.assign(32 * 24, 0);
    for (int y = 8; y < 16; ++y)
      for (int x = 8; x < 24; ++x) m.on[size_t(y) * 32 + x] = 1;
    return m;
  }();
  ReferenceSettings s;
  s.spp = 8;
  s.progress = false;
  const Image full = renderReference(*scene, Transform(), cam, fixtures::defaultSensor(), s).image;
  ReferenceSettings one = s;
  one.spp = 1;
  const Image single = renderReference(*scene, Transform(), cam, fixtures::defaultSensor(), one).image;
  ReferenceSettings mixed = s;
  mixed.fullSamples = &mask.on;
  mixed.sppElsewhere = 1;
  const Image both = renderReference(*scene, Transform(), cam, fixtures::defaultSensor(), mixed).image;
  int wrong = 0;
  for (int y = 0; y < 24; ++y)
    for (int x = 0; x < 32; ++x)
      if (!samePixel(mask.counts(x, y) ? full : single, both, x, y)) ++wrong;
  EXPECT_EQ(wrong, 0);
}

TEST(PoseComparison, NoPixelOfTheMaskLeavesTheReferenceInFull) {
  const auto scene = fixtures::greyPlaneAt5mm(40);
  const DisplayPose pose{0.0, 0.0, 200.0};
  PinholeCameraModel cam(SensorGeometry{32, 24, 0.05}, pose.cameraPose(), 20.0, false);
  PixelMask empty;
  empty.width = 32, empty.height = 24;
  empty.on.assign(32 * 24, 0);
  ReferenceSettings s;
  s.spp = 4;
  s.progress = false;
  const ViewResult full = renderReference(*scene, Transform(), cam, fixtures::defaultSensor(), s);
  const ViewResult compared = renderComparedReference(*scene, Transform(), cam, fixtures::defaultSensor(), s, empty, testBand());
  ASSERT_EQ(full.image.data.size(), compared.image.data.size());
  EXPECT_EQ(std::memcmp(full.image.data.data(), compared.image.data.data(), full.image.data.size() * sizeof(float)), 0);
}
