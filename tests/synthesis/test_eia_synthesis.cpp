// The whole synthesis: EIA size and placement on the panel, determinism across thread counts,
// triads export -> EIA formation round trip, auto exposure, and the placement preview.
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>

#include "core/parallel.h"
#include "rays/pinhole_rays.h"
#include "spectral/color.h"
#include "synth_test_util.h"
#include "synthesis/eia_synthesis.h"
#include "synthesis/preview.h"
#include "triads/triads.h"

using namespace inim;
using namespace synth_test;

namespace {

// Real and virtual soft emitters, spectral, with per-sample noise keyed by (seed, id, sample)
// as a Monte Carlo field's would be.
MockField twoEmitters() {
  return MockField({{{-0.8, 0.3, 6.0}, 1.5, Vec3(0.6f, 0.3f, 0.1f), 0.8, nullptr},
                    {{0.7, -0.4, -8.0}, 2.5, Vec3(0.2f, 0.4f, 0.7f), 1.5, nullptr}},
                   FieldEncoding::Spectral, 0.5f);
}

SynthesisSettings settings() {
  SynthesisSettings s = quietSettings(40.0);
  s.spp = 2;
  s.aovs = true;
  return s;
}

}  // namespace

TEST(EiaSynthesis, CoversThePanelWithEisCentred) {
  Display disp = squareDisplay({.cols = 9, .rows = 7, .eiPx = 9});
  EiLayout L = computeLayout(disp);
  MockField f = twoEmitters();
  SynthesisResult r = synthesizeEia(L, disp.panel, f, settings());
  EXPECT_EQ(r.eia.width, disp.panel.widthPx);
  EXPECT_EQ(r.eia.height, disp.panel.heightPx);
  EXPECT_EQ(r.eia.channels, (std::vector<std::string>{"R", "G", "B", "A", "Z"}));
  EXPECT_EQ(r.drive.size(), size_t(L.numRays()) * 3);
  EXPECT_EQ(r.stats.displayRays, uint64_t(L.numRays()));
  EXPECT_EQ(r.stats.queries, uint64_t(L.numRays()) * 2);
  // Pixels outside the EIs are black; pixel values equal the per-ray drive values.
  for (int y = 0; y < r.eia.height; ++y)
    for (int x = 0; x < r.eia.width; ++x) {
      auto a = addressAtPanelPixel(L, {x, y});
      for (int c = 0; c < 5; ++c) {
        if (!a) {
          ASSERT_EQ(r.eia.at(x, y, c), 0.0f);
        } else if (c < 3) {
          ASSERT_EQ(r.eia.at(x, y, c), r.drive[size_t(rayIndex(L, *a)) * 3 + size_t(c)]);
        }
      }
    }
  EXPECT_GT(r.stats.realRays, 0u);
  EXPECT_GT(r.stats.virtualRays, 0u);
  // Crop and re-place round trip.
  Image area = eiaArea(L, r.eia);
  EXPECT_EQ(area.width, L.eiaW);
  Image back = onPanel(L, area);
  for (size_t i = 0; i < back.data.size(); i += 3)
    ASSERT_EQ(back.data[i], r.eia.data[i / 3 * 5]);
  // The encoded image follows the panel EOTF.
  Image enc = encodeForPanel(r.eia, disp.panel.eotf);
  int x = L.panelCol0 + L.eiaW / 2, y = L.panelRow0 + L.eiaH / 2;
  EXPECT_NEAR(enc.at(x, y, 1), disp.panel.eotf.encode(r.eia.at(x, y, 1)), 1e-6);
  expectInputError([&] { (void)eiaArea(L, Image(5, 5, {"R", "G", "B"})); });
}

TEST(EiaSynthesis, BitIdenticalOnOneAndTwoThreads) {
  Display disp = squareDisplay({.cols = 9, .rows = 7, .eiPx = 9});
  EiLayout L = computeLayout(disp);
  MockField f = twoEmitters();
  SynthesisSettings s = settings();
  s.raysPerBatch = 300;  // many batches, split differently across threads
  SynthesisResult r1, r2;
  {
    ThreadLimit t(1);
    r1 = synthesizeEia(L, disp.panel, f, s);
  }
  {
    ThreadLimit t(2);
    r2 = synthesizeEia(L, disp.panel, f, s);
  }
  ASSERT_EQ(r1.eia.data.size(), r2.eia.data.size());
  EXPECT_EQ(0, std::memcmp(r1.eia.data.data(), r2.eia.data.data(), r1.eia.data.size() * sizeof(float)));
  EXPECT_EQ(0, std::memcmp(r1.drive.data(), r2.drive.data(), r1.drive.size() * sizeof(float)));
  EXPECT_EQ(r1.stats.gamut.outOfGamut, r2.stats.gamut.outOfGamut);
  // Another batch size changes nothing either; another seed does.
  s.raysPerBatch = 4096;
  SynthesisResult r3 = synthesizeEia(L, disp.panel, f, s);
  EXPECT_EQ(0, std::memcmp(r1.drive.data(), r3.drive.data(), r1.drive.size() * sizeof(float)));
  s.seed = 2;
  SynthesisResult r4 = synthesizeEia(L, disp.panel, f, s);
  EXPECT_NE(0, std::memcmp(r1.drive.data(), r4.drive.data(), r1.drive.size() * sizeof(float)));
}

// Triads export of a synthesized EIA, traced back onto the panel plane, reproduces it.
TEST(EiaSynthesis, TriadsRoundTripThroughSdf) {
  Display disp = squareDisplay({.cols = 9, .rows = 7, .eiPx = 9});
  EiLayout L = computeLayout(disp);
  MockField f = twoEmitters();
  SynthesisResult r = synthesizeEia(L, disp.panel, f, settings());
  RaySet rays = generatePinholeRays(L);
  TriadWavelengths w = triadWavelengths(disp.panel, "panel");
  std::string sdf = scratchPath("eia.sdf");
  uint64_t n = writeTriadSdf(sdf, rays, r.drive, w);
  EXPECT_EQ(n, 3u * uint64_t(L.numRays()));
  EXPECT_EQ(std::filesystem::file_size(sdf), kSdfHeaderSize + kSdfRaySize * n);
  EiaFormation formed = formEiaFromSdf(L, sdf, w);
  EXPECT_EQ(formed.binned, n);
  Image area = eiaArea(L, r.eia);
  double maxErr = 0.0, maxV = 0.0;
  for (size_t i = 0; i < area.data.size(); ++i) {
    maxErr = std::max(maxErr, double(std::abs(area.data[i] - formed.eia.data[i])));
    maxV = std::max(maxV, double(area.data[i]));
  }
  EXPECT_LE(maxErr, 1e-6);
  EXPECT_GT(maxV, 0.1);
  std::printf("  triads -> SDF -> detector: max |error| %.3g over %zu values\n", maxErr, area.data.size());
}

TEST(EiaSynthesis, AutoExposureMapsPercentileToWhite) {
  Display disp = squareDisplay({.cols = 5, .rows = 5, .eiPx = 7});
  EiLayout L = computeLayout(disp);
  MockField f({{{0.0, 0.0, -1010.0}, 1000.0, Vec3(7.0f), 0.0, nullptr}}, FieldEncoding::RGB);
  SynthesisSettings s = quietSettings();
  s.autoExposure = true;
  SynthesisResult r = synthesizeEia(L, disp.panel, f, s);
  // The brightest channel of a uniform field reaches full drive.
  PanelColor pc(disp.panel);
  Vec3d d = pc.driveFromXYZ(Vec3d(ColorSystem::rec709ToXYZ() * Vec3(7.0f)));
  EXPECT_NEAR(r.stats.exposureUsed, 1.0 / std::max({d.x, d.y, d.z}), 1e-4);
  EXPECT_EQ(r.stats.gamut.overRange, 0u);
  EXPECT_NEAR(*std::max_element(r.drive.begin(), r.drive.end()), 1.0f, 1e-5f);
  s.exposure = -1.0;
  s.autoExposure = false;
  expectInputError([&] { (void)synthesizeEia(L, disp.panel, f, s); });
  s.exposure = 1.0;
  s.spp = 0;
  expectInputError([&] { (void)synthesizeEia(L, disp.panel, f, s); });
}

TEST(EiaSynthesis, PreviewShowsRealVirtualAndMlaCrossing) {
  Display disp = squareDisplay({.cols = 15, .rows = 9, .eiPx = 9});
  EiLayout L = computeLayout(disp);
  // A real sphere, a virtual sphere, and a large sphere whose surface crosses the MLA plane.
  MockField f({{{-5.5, 0.0, 5.0}, 1.0, Vec3(1.0f), 0.0, nullptr},
               {{5.8, 0.0, -3.0}, 0.8, Vec3(1.0f), 0.0, nullptr},
               {{0.0, 0.0, -4.0}, 4.5, Vec3(1.0f), 0.0, nullptr}},
              FieldEncoding::RGB);
  PreviewResult p = renderPlacementPreview(L, f, Transform(), 30.0);
  EXPECT_EQ(p.lenslets, L.eiCols * L.eiRows);
  EXPECT_GT(p.real, 0);
  EXPECT_GT(p.virtualHits, 0);
  EXPECT_GT(p.crossingLenslets, 0);
  EXPECT_GT(p.image.width, 400);
  EXPECT_GT(p.image.height, 100);
  // Drawn: not a blank canvas, and some pixels in the "real" orange.
  int orange = 0, dark = 0;
  for (int y = 0; y < p.image.height; ++y)
    for (int x = 0; x < p.image.width; ++x) {
      float r = p.image.at(x, y, 0), g = p.image.at(x, y, 1), b = p.image.at(x, y, 2);
      if (r > 0.8f && g > 0.3f && g < 0.6f && b < 0.2f) ++orange;
      if (r + g + b < 0.5f) ++dark;
    }
  EXPECT_GT(orange, 10);
  EXPECT_GT(dark, 100);
  std::string png = scratchPath("preview.png");
  writeImage(p.image, png);
  EXPECT_GT(std::filesystem::file_size(png), 1000u);
}

TEST(EiaSynthesis, PreviewLabelsAreAntialiasedTextAndDeterministic) {
  Display disp = squareDisplay({.cols = 15, .rows = 9, .eiPx = 9});
  EiLayout L = computeLayout(disp);
  MockField f({{{-5.5, 0.0, 5.0}, 1.0, Vec3(1.0f), 0.0, nullptr}, {{5.8, 0.0, -3.0}, 0.8, Vec3(1.0f), 0.0, nullptr}},
              FieldEncoding::RGB);
  const PreviewResult p = renderPlacementPreview(L, f, Transform(), 30.0);
  const Image& img = p.image;
  // Dark pixels, and grey ones (antialiased glyph edges, which a bitmap font has none of),
  // in a band of the image.
  auto count = [&](int y0, int y1, int& dark, int& grey) {
    dark = grey = 0;
    for (int y = std::max(0, y0); y < std::min(img.height, y1); ++y)
      for (int x = 0; x < img.width; ++x) {
        const float v = img.at(x, y, 0) + img.at(x, y, 1) + img.at(x, y, 2);
        dark += v < 0.9f;
        grey += v > 1.2f && v < 2.4f && std::abs(img.at(x, y, 0) - img.at(x, y, 2)) < 0.02f;
      }
  };
  int dark = 0, grey = 0;
  count(0, 40, dark, grey);  // the views' titles, above the views
  EXPECT_GT(dark, 200);
  EXPECT_GT(grey, 50);
  count(img.height - 70, img.height - 50, dark, grey);  // the colour key's names under the views
  EXPECT_GT(dark, 200);
  // Same pixels on one thread.
  ThreadLimit one(1);
  const PreviewResult again = renderPlacementPreview(L, f, Transform(), 30.0);
  EXPECT_EQ(again.image.data, img.data);
}
