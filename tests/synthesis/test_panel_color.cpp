// Colour to the panel: primaries' spectra -> drive (1,0,0)-proportional values, panel white ->
// (1,1,1), saturated spectral colours outside the panel gamut are counted and mapped.
#include <gtest/gtest.h>

#include "spectral/cie.h"
#include "spectral/color.h"
#include "synth_test_util.h"
#include "synthesis/eia_synthesis.h"
#include "synthesis/panel_color.h"

using namespace inim;
using namespace synth_test;

namespace {

Panel defaultPanel() { return loadDisplay(defaultDisplayPath()).panel; }

// Mean of each channel over the pixels that a ray maps to.
Vec3d meanDrive(const SynthesisResult& r) {
  Vec3d m(0.0);
  size_t n = r.drive.size() / 3;
  for (size_t i = 0; i < n; ++i) m += Vec3d(r.drive[i * 3], r.drive[i * 3 + 1], r.drive[i * 3 + 2]);
  return m / double(n);
}

// A field that covers every query ray with one emitter (a huge sphere whose near side is at
// z = -10 in the display frame).
MockField everywhere(SpectrumPtr spectrum) {
  return MockField({{{0.0, 0.0, -1010.0}, 1000.0, Vec3(1.0f), 0.0, std::move(spectrum)}}, FieldEncoding::Spectral);
}

}  // namespace

TEST(PanelColor, PrimariesAndWhiteExactly) {
  Panel panel = defaultPanel();
  PanelColor pc(panel);
  // drive (1,1,1) is the panel white with Y = 1.
  EXPECT_NEAR(pc.whiteXYZ().y, 1.0, 1e-12);
  Vec3d w = pc.luminanceWeights();
  EXPECT_NEAR(w.x + w.y + w.z, 1.0, 1e-12);
  for (int c = 0; c < 3; ++c) {
    SpectrumPtr s = primarySpectrum(panel.primaries[size_t(c)]);
    Vec3d d = pc.driveFromSpectrum(*s);
    for (int o = 0; o < 3; ++o)
      if (o != c) {
        EXPECT_NEAR(d[o] / d[c], 0.0, 1e-9) << "primary " << c << " channel " << o;
      }
    EXPECT_GT(d[c], 0.0);
  }
  // The sum of the primaries, normalised to Y = 1, is drive (1, 1, 1).
  std::array<SpectrumPtr, 3> prim;
  for (int c = 0; c < 3; ++c) prim[size_t(c)] = primarySpectrum(panel.primaries[size_t(c)]);
  double Yw = 0.0;
  for (auto& s : prim) Yw += spectrumToXYZ(*s).y;
  auto white = makeSpectrum([&](float l) { return float(((*prim[0])(l) + (*prim[1])(l) + (*prim[2])(l)) / Yw); });
  Vec3d dw = pc.driveFromSpectrum(*white);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(dw[c], 1.0, 1e-6);
  // White balance: D65 with the gains drives (1, 1, 1).
  Vec3d d65 = spectrumToXYZ(cie::D65());
  Vec3d dd = pc.driveFromXYZ(d65 / d65.y) * pc.d65WhiteGains();
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(dd[c], 1.0, 1e-9);
  std::printf("  panel white xy = (%.4f, %.4f); primaries R (%.3f, %.3f) G (%.3f, %.3f) B (%.3f, %.3f)\n",
              pc.whiteXY().x, pc.whiteXY().y, pc.primaryXY(0).x, pc.primaryXY(0).y, pc.primaryXY(1).x,
              pc.primaryXY(1).y, pc.primaryXY(2).x, pc.primaryXY(2).y);
}

TEST(PanelColor, GamutMappingClipAndDesaturate) {
  const Vec3 w(0.25f, 0.65f, 0.10f);
  Vec3 d(1.3f, 0.4f, -0.2f);
  EXPECT_TRUE(mapToGamut(d, w, GamutMapping::Clip));
  EXPECT_EQ(d, Vec3(1.0f, 0.4f, 0.0f));
  d = Vec3(1.3f, 0.4f, -0.2f);
  float Y = glm::dot(w, d);
  EXPECT_TRUE(mapToGamut(d, w, GamutMapping::Desaturate));
  EXPECT_NEAR(glm::dot(w, d), Y, 1e-6f) << "desaturation keeps panel luminance";
  EXPECT_GE(std::min({d.x, d.y, d.z}), 0.0f);
  EXPECT_LE(std::max({d.x, d.y, d.z}), 1.0f);
  EXPECT_TRUE(std::abs(d.x - 1.0f) < 1e-6f || std::abs(d.z) < 1e-6f) << "moved just to the gamut boundary";
  // In gamut: untouched and not counted.
  Vec3 in(0.2f, 1.0f, 0.0f);
  EXPECT_FALSE(mapToGamut(in, w, GamutMapping::Desaturate));
  EXPECT_EQ(in, Vec3(0.2f, 1.0f, 0.0f));
  // NaN -> black, counted.
  Vec3 bad(std::nanf(""), 0.5f, 0.5f);
  EXPECT_TRUE(mapToGamut(bad, w, GamutMapping::Clip));
  EXPECT_EQ(bad, Vec3(0.0f));
  GamutStats st;
  Vec3 a(2.0f, 0.5f, 0.5f), b(0.5f, 0.5f, 0.5f);
  mapToGamut(a, w, GamutMapping::Clip, st);
  mapToGamut(b, w, GamutMapping::Clip, st);
  EXPECT_EQ(st.pixels, 2u);
  EXPECT_EQ(st.outOfGamut, 1u);
  EXPECT_EQ(st.overRange, 1u);
  EXPECT_EQ(st.negative, 0u);
}

// Through the whole synthesis (spectral sampling, 4 wavelengths per sample): a field
// emitting exactly the red primary's spectrum gives drive values proportional to (1, 0, 0);
// the panel white gives (1, 1, 1) x exposure.
TEST(PanelColor, SynthesisOfPrimaryAndWhiteSpectra) {
  Display disp = squareDisplay({.cols = 3, .rows = 3, .eiPx = 7});
  EiLayout L = computeLayout(disp);
  PanelColor pc(disp.panel);
  std::array<SpectrumPtr, 3> prim;
  for (int c = 0; c < 3; ++c) prim[size_t(c)] = primarySpectrum(disp.panel.primaries[size_t(c)]);
  double Yw = 0.0;
  for (auto& s : prim) Yw += spectrumToXYZ(*s).y;
  SynthesisSettings s = quietSettings();
  s.spp = 64;
  s.exposure = 0.5;
  for (int c = 0; c < 3; ++c) {
    auto p = prim[size_t(c)];
    MockField f = everywhere(makeSpectrum([p, Yw](float l) { return float((*p)(l) / Yw); }));
    SynthesisResult r = synthesizeEia(L, disp.panel, f, s);
    Vec3d m = meanDrive(r);
    Vec3d exact = pc.driveFromSpectrum(*p) / Yw * 0.5;
    EXPECT_NEAR(m[c], exact[c], 0.01 * exact[c]) << "primary " << c;
    for (int o = 0; o < 3; ++o)
      if (o != c) {
        EXPECT_LT(m[o], 0.01 * m[c]) << "primary " << c << " leaks into channel " << o;
      }
    std::printf("  primary %s: mean drive (%.4f, %.4f, %.4f), exact (%.4f, %.4f, %.4f)\n", channelName(c), m.x, m.y,
                m.z, exact.x, exact.y, exact.z);
  }
  MockField white = everywhere(makeSpectrum(
      [prim, Yw](float l) { return float(((*prim[0])(l) + (*prim[1])(l) + (*prim[2])(l)) / Yw); }));
  SynthesisResult r = synthesizeEia(L, disp.panel, white, s);
  Vec3d m = meanDrive(r);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(m[c], 0.5, 0.005);
  std::printf("  panel white at exposure 0.5: mean drive (%.4f, %.4f, %.4f)\n", m.x, m.y, m.z);
  // Exposure 2 at unit white: full drive, every pixel over range, counted and clipped to 1.
  s.exposure = 2.0;
  r = synthesizeEia(L, disp.panel, white, s);
  EXPECT_EQ(r.stats.gamut.overRange, r.stats.gamut.pixels);
  for (float v : r.drive) ASSERT_EQ(v, 1.0f);
}

// A saturated spectral colour (a narrow line at 495 nm, cyan) lies outside the panel's
// primaries: every pixel is counted as out of gamut (a negative channel), and desaturation
// keeps its luminance.
TEST(PanelColor, SpectralColourOutsideGamutIsCounted) {
  Display disp = squareDisplay({.cols = 3, .rows = 3, .eiPx = 7});
  EiLayout L = computeLayout(disp);
  PanelColor pc(disp.panel);
  auto line = makeSpectrum([](float l) { return float(std::exp(-0.5 * std::pow((l - 495.0) / 4.0, 2))); });
  Vec3d exact = pc.driveFromSpectrum(*line);
  ASSERT_LT(std::min({exact.x, exact.y, exact.z}), -0.05 * std::max({exact.x, exact.y, exact.z}));
  const double Y = spectrumToXYZ(*line).y;
  MockField f = everywhere(makeSpectrum([line, Y](float l) { return float((*line)(l) * 0.1 / Y); }));
  SynthesisSettings s = quietSettings();
  s.spp = 16;
  SynthesisResult r = synthesizeEia(L, disp.panel, f, s);
  EXPECT_EQ(r.stats.gamut.pixels, uint64_t(L.numRays()));
  EXPECT_EQ(r.stats.gamut.outOfGamut, r.stats.gamut.pixels);
  EXPECT_EQ(r.stats.gamut.negative, r.stats.gamut.pixels);
  EXPECT_LT(r.stats.gamut.minChannel, 0.0);
  s.gamut = GamutMapping::Desaturate;
  SynthesisResult rd = synthesizeEia(L, disp.panel, f, s);
  EXPECT_EQ(rd.stats.gamut.outOfGamut, rd.stats.gamut.pixels);
  Vec3d m = meanDrive(rd);
  EXPECT_NEAR(glm::dot(pc.luminanceWeights(), m), 0.1, 0.004) << "desaturation keeps luminance";
  std::printf("  495 nm line: exact drive (%.3f, %.3f, %.3f) per unit Y; %llu of %llu pixels out of gamut\n",
              exact.x / Y, exact.y / Y, exact.z / Y, (unsigned long long)r.stats.gamut.outOfGamut,
              (unsigned long long)r.stats.gamut.pixels);
}

// RGB fields go through OCIO: linear Rec.709 white at Y = 0.5 gives the same drive values as
// a spectral field with D65's XYZ at Y = 0.5.
TEST(PanelColor, RgbFieldThroughOcio) {
  Display disp = squareDisplay({.cols = 3, .rows = 3, .eiPx = 5});
  EiLayout L = computeLayout(disp);
  PanelColor pc(disp.panel);
  MockField f({{{0.0, 0.0, -1010.0}, 1000.0, Vec3(0.5f), 0.0, nullptr}}, FieldEncoding::RGB);
  SynthesisSettings s = quietSettings();
  SynthesisResult r = synthesizeEia(L, disp.panel, f, s);
  Vec3d xyz = Vec3d(ColorSystem::rec709ToXYZ() * Vec3(0.5f));
  Vec3d expected = pc.driveFromXYZ(xyz);
  Vec3d m = meanDrive(r);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(m[c], expected[c], 1e-4);
  s.whiteBalanceD65 = true;
  m = meanDrive(synthesizeEia(L, disp.panel, f, s));
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(m[c], 0.5, 2e-3) << "D65 white balance";
}
