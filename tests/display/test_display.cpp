// Display catalog, EI layouts and derived paraxial quantities.
#include <gtest/gtest.h>

#include <cmath>

#include "core/error.h"
#include "core/output_file.h"
#include "display/display.h"
#include "display/display_info.h"
#include "display/ei_layout.h"
#include "fixtures.h"

using namespace inim;
using namespace fixtures;

namespace {


// The paper prototype with some keys replaced (a JSON patch on the top-level object).
std::string prototypeWith(const std::string& name, const Json& patch) {
  Json j = readJsonFile(defaultDisplayPath());
  j["panel"] = "sony-xperia-1-ii";
  j["mla"] = "fresnel-630";
  for (auto it = patch.begin(); it != patch.end(); ++it) {
    if (it.value().is_null())
      j.erase(it.key());
    else
      j[it.key()] = it.value();
  }
  return scratchFile(name, j.dump(2));
}

}  // namespace

TEST(DisplayCatalog, LoadsPaperPrototype) {
  Display d = loadDisplay(defaultDisplayPath());
  EXPECT_EQ(d.panel.widthPx, 3840);
  EXPECT_EQ(d.panel.heightPx, 1644);
  EXPECT_DOUBLE_EQ(d.panel.pixelPitchMm, 0.0395);
  EXPECT_NEAR(d.panel.widthMm(), 151.68, 1e-9);
  EXPECT_DOUBLE_EQ(d.mla.pitchMm, 1.0);
  EXPECT_EQ(d.mla.material, "PMMA");
  EXPECT_DOUBLE_EQ(d.generationGapMm, 3.3);
  EXPECT_DOUBLE_EQ(d.reconstructionGapMm, 4.0);
  EXPECT_EQ(d.eiWidthPx, 25);
  EXPECT_EQ(d.eiCols, 153);
  EXPECT_EQ(d.eiRows, 65);
  EXPECT_EQ(d.layout, EiLayoutKind::Parallel);
  EXPECT_EQ(d.panel.subpixels.type, "rgb-stripe");
  EXPECT_EQ(d.panel.subpixels.subpixels.size(), 3u);
  ASSERT_TRUE(d.panel.coverGlass.has_value());
  EXPECT_FALSE(d.panel.assumptions.empty());
  EXPECT_FALSE(d.mla.assumptions.empty());
  EXPECT_EQ(d.panel.primaries[0].kind, PrimarySpec::Kind::Gaussian);
  EXPECT_DOUBLE_EQ(primaryPeakNm(d.panel.primaries[0]), 625.0);
  EXPECT_DOUBLE_EQ(primaryPeakNm(d.panel.primaries[1]), 530.0);
  EXPECT_DOUBLE_EQ(primaryPeakNm(d.panel.primaries[2]), 460.0);
}

TEST(DisplayCatalog, PrimarySpectrumIsTheDocumentedGaussian) {
  Display d = loadDisplay(defaultDisplayPath());
  const PrimarySpec& g = d.panel.primaries[1];
  SpectrumPtr s = primarySpectrum(g);
  EXPECT_NEAR((*s)(float(g.meanNm)), 1.0f, 1e-6f);
  EXPECT_NEAR((*s)(float(g.meanNm + 0.5 * g.fwhmNm)), 0.5f, 1e-4f);
  EXPECT_NEAR((*s)(float(g.meanNm - 0.5 * g.fwhmNm)), 0.5f, 1e-4f);
}

TEST(DisplayCatalog, CsvPrimaryAndDiamondLayout) {
  std::string csv = scratchFile("red.csv",
                                "# measured red primary (test)\nwavelength_nm,relative_power\n"
                                "600,0.1\n610,0.6\n622,1.0\n630,0.7\n650,0.05\n");
  Json p = readJsonFile(dataPath("optics/panels/sony-xperia-1-ii.json"));
  p["primaries"]["R"] = {{"csv", {{"file", "red.csv"}, {"column", "relative_power"}}}, {"scale", 0.9}};
  p["subpixel_layout"] = {{"type", "diamond"}};
  p["eotf"] = {{"gamma", 2.4}};
  Panel panel = loadPanel(scratchFile("csv_panel.json", p.dump()));
  EXPECT_EQ(panel.primaries[0].kind, PrimarySpec::Kind::Csv);
  EXPECT_EQ(panel.primaries[0].csvPath, csv);
  EXPECT_DOUBLE_EQ(primaryPeakNm(panel.primaries[0]), 622.0);
  EXPECT_NEAR((*primarySpectrum(panel.primaries[0]))(622.0f), 0.9f, 1e-6f);
  EXPECT_EQ(panel.subpixels.type, "diamond");
  EXPECT_EQ(panel.eotf.kind, Eotf::Kind::Gamma);
  EXPECT_EQ(panel.eotf.name(), "gamma 2.4");
  // Unknown keys inside a primary are errors naming the key path.
  p["primaries"]["G"]["gaussian"]["peak_nm"] = 530;
  EXPECT_EQ(expectInputError([&] { loadPanel(scratchFile("bad_primary.json", p.dump())); }).key(),
            "primaries.G.gaussian.peak_nm");
}

TEST(DisplayCatalog, EotfRoundTrips) {
  for (Eotf::Kind k : {Eotf::Kind::Linear, Eotf::Kind::SRGB, Eotf::Kind::Gamma}) {
    Eotf e;
    e.kind = k;
    for (double v : {0.0, 0.001, 0.04, 0.2, 0.5, 0.9, 1.0}) EXPECT_NEAR(e.decode(e.encode(v)), v, 1e-12);
  }
  Eotf s;
  EXPECT_NEAR(s.decode(0.5), 0.21404114, 1e-7);  // sRGB mid grey
}

TEST(DisplayCatalog, SubpixelLayouts) {
  SubpixelLayout st = rgbStripeLayout(0.8);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(st.emittingArea(c), 0.8 / 3.0 * 0.8, 1e-12);
  SubpixelLayout di = diamondLayout(0.8);
  EXPECT_EQ(di.tileW, 2);
  EXPECT_EQ(di.subpixels.size(), 8u);
  EXPECT_NEAR(di.emittingArea(0), di.emittingArea(2), 1e-12);  // as much red as blue
  EXPECT_GT(di.emittingArea(1), 0.0);

  // A custom layout in a panel file: parsed and stored.
  Json p = readJsonFile(dataPath("optics/panels/sony-xperia-1-ii.json"));
  p["subpixel_layout"] = Json::parse(R"({"type": "custom", "tile_px": [1, 1], "subpixels": [
      {"channel": "R", "polygon": [[0, 0], [0.3, 0], [0.3, 1]]},
      {"channel": "G", "polygon": [[0.35, 0], [0.65, 0], [0.65, 1], [0.35, 1]]},
      {"channel": "B", "polygon": [[0.7, 0], [1, 0], [1, 1], [0.7, 1]]}]})");
  Panel panel = loadPanel(scratchFile("custom_panel.json", p.dump()));
  EXPECT_EQ(panel.subpixels.type, "custom");
  EXPECT_NEAR(panel.subpixels.emittingArea(0), 0.15, 1e-12);

  p["subpixel_layout"]["subpixels"][0]["polygon"] = Json::parse("[[0, 0], [1.5, 0], [0.3, 1]]");
  InputError e = expectInputError([&] { loadPanel(scratchFile("bad_panel.json", p.dump())); });
  EXPECT_EQ(e.key(), "subpixel_layout.subpixels[0].polygon");
}

TEST(DisplayCatalog, FocalLengthFromRadius) {
  Json m = readJsonFile(dataPath("optics/mlas/fresnel-630.json"));
  m.erase("focal_length_mm");
  Mla mla = loadMla(scratchFile("mla_r_only.json", m.dump()));
  LensletFocus f = lensletFocus(mla);
  ASSERT_TRUE(f.indexD.has_value());
  EXPECT_NEAR(*f.indexD, 1.4906, 5e-4);  // PMMA n_d in spectra/materials.json
  EXPECT_NEAR(f.focalLengthMm, 1.62 / (*f.indexD - 1.0), 1e-12);
  EXPECT_NEAR(f.focalLengthMm, 3.3, 0.01);

  // Only f given: no catalog needed.
  Json m2 = readJsonFile(dataPath("optics/mlas/fresnel-630.json"));
  m2.erase("radius_of_curvature_mm");
  EXPECT_DOUBLE_EQ(lensletFocus(loadMla(scratchFile("mla_f_only.json", m2.dump()))).focalLengthMm, 3.3);

  // Both given but inconsistent.
  m["focal_length_mm"] = 4.0;
  Mla bad = loadMla(scratchFile("mla_bad.json", m.dump()));
  InputError e = expectInputError([&] { lensletFocus(bad); });
  EXPECT_EQ(e.key(), "focal_length_mm");
  EXPECT_NE(std::string(e.what()).find("mla_bad.json"), std::string::npos);
}

TEST(DisplayInfo, PaperPrototypeQuantities) {
  Display d = loadDisplay(defaultDisplayPath());
  DisplayInfo r = derive(d);
  EXPECT_DOUBLE_EQ(r.focus.focalLengthMm, 3.3);
  // psi = 2 atan(P / 2g): about 14.25 deg (+-7.1) at g = 4 mm.
  EXPECT_NEAR(r.reconstruction.viewingAngleDeg, 2.0 * std::atan(1.0 / 8.0) * 180.0 / kPiD, 1e-12);
  EXPECT_NEAR(r.reconstruction.viewingAngleDeg, 14.25, 0.01);
  // L = g f / (g - f) = 18.857 mm at g = 4; at infinity for g = f.
  ASSERT_TRUE(r.reconstruction.referencePlaneMm.has_value());
  EXPECT_NEAR(*r.reconstruction.referencePlaneMm, 4.0 * 3.3 / 0.7, 1e-9);
  EXPECT_EQ(r.reconstruction.referencePlaneKind, "real");
  EXPECT_FALSE(r.generation.referencePlaneMm.has_value());
  EXPECT_EQ(r.generation.referencePlaneKind, "infinity");
  EXPECT_NEAR(r.reconstruction.pixelAngularPitchDeg, std::atan(0.0395 / 4.0) * 180.0 / kPiD, 1e-12);
  // EIA: 3825 x 1625 px = 151.0875 x 64.1875 mm, at panel pixel (7, 9).
  EXPECT_EQ(r.eiaW, 3825);
  EXPECT_EQ(r.eiaH, 1625);
  EXPECT_NEAR(r.eiaWidthMm, 151.0875, 1e-9);
  EXPECT_NEAR(r.eiaHeightMm, 64.1875, 1e-9);
  EXPECT_EQ(r.panelCol0, 7);
  EXPECT_EQ(r.panelRow0, 9);
  EXPECT_EQ(r.numRays, 6215625);
  // EI pitch 0.9875 mm on a 1.0 mm MLA: EI-centre chief rays through the physical lenses
  // diverge from a virtual point g P / (p_EI - P) behind the MLA.
  EXPECT_NEAR(r.eiPitchXMm, 0.9875, 1e-12);
  ASSERT_TRUE(r.reconstruction.convergenceXMm.has_value());
  EXPECT_NEAR(*r.reconstruction.convergenceXMm, -320.0, 1e-6);
  EXPECT_NEAR(*r.generation.convergenceXMm, -264.0, 1e-6);
  // Left edge: EI centre at -75.05 mm, lens at -76 mm: the chief ray leans outward.
  EXPECT_NEAR(r.reconstruction.edgeChiefAngleXDeg[0], std::atan(-0.95 / 4.0) * 180.0 / kPiD, 1e-9);
  EXPECT_NEAR(r.reconstruction.edgeChiefAngleXDeg[1], -r.reconstruction.edgeChiefAngleXDeg[0], 1e-9);
  // The paper's generation rays: pinholes at the EI centres, parallel central rays.
  EXPECT_NEAR(r.pinholePitchXMm, 0.9875, 1e-12);
  EXPECT_FALSE(r.generationConvergenceXMm.has_value());
  EXPECT_NEAR(r.edgePinholeOffsetXMm, 0.95, 1e-9);
  EXPECT_NEAR(r.scaleErrorX, 1.0 / 0.9875 - 1.0, 1e-12);
  ASSERT_TRUE(r.viewingZone.has_value());
  EXPECT_NEAR(r.viewingZone->zoneWidthXMm, 0.9875 * 350.0 / 4.0, 1e-9);
  EXPECT_DOUBLE_EQ(r.viewingZone->commonWidthXMm, 0.0);  // edges flip at 350 mm
}

TEST(DisplayInfo, VirtualReferencePlaneWhenGapBelowFocalLength) {
  Display d = loadDisplay(prototypeWith("virtual.json", {{"reconstruction_gap_mm", 3.0}}));
  DisplayInfo r = derive(d);
  ASSERT_TRUE(r.reconstruction.referencePlaneMm.has_value());
  EXPECT_NEAR(*r.reconstruction.referencePlaneMm, 3.0 * 3.3 / (3.0 - 3.3), 1e-9);
  EXPECT_EQ(r.reconstruction.referencePlaneKind, "virtual");
}

TEST(DisplayInfo, JsonAndText) {
  Display d = loadDisplay(defaultDisplayPath());
  Json j = displayInfoJson(d);
  EXPECT_EQ(j["eia"]["size_px"][0], 3825);
  EXPECT_TRUE(j["generation"]["reference_image_plane_mm"].is_null());
  EXPECT_NEAR(j["reconstruction"]["reference_image_plane_mm"].get<double>(), 18.857, 1e-3);
  EXPECT_FALSE(j["assumptions"].empty());
  std::string t = displayInfoText(d);
  EXPECT_NE(t.find("viewing angle psi"), std::string::npos);
  EXPECT_NE(t.find("3825 x 1625 px"), std::string::npos);
  EXPECT_NE(t.find("at infinity"), std::string::npos);
}

TEST(EiLayout, ParallelMatchesThePaperPinholeGrid) {
  Display d = loadDisplay(defaultDisplayPath());
  EiLayout L = computeLayout(d);
  // microlensxperia9875.dat: pinholes at ((k - 76) 0.9875, (32 - l) 0.9875).
  for (int k : {0, 1, 76, 152}) EXPECT_NEAR(L.pinholeX[size_t(k)], (k - 76) * 0.9875, 1e-9);
  for (int l : {0, 32, 64}) EXPECT_NEAR(L.pinholeY[size_t(l)], (32 - l) * 0.9875, 1e-9);
  for (int k = 0; k < L.eiCols; ++k) {
    EXPECT_EQ(L.eiCol0[size_t(k)], 25 * k);
    EXPECT_NEAR(L.eiCentreX(k), L.pinholeX[size_t(k)], 1e-12);
    EXPECT_NEAR(L.eiCentreX(k), -L.eiCentreX(L.eiCols - 1 - k), 1e-9);
  }
  EXPECT_NEAR(L.lensX[0], -76.0, 1e-12);
}

TEST(EiLayout, ToedInPitchIsPTimesOnePlusGOverD) {
  const double D = 350.0, g = 3.3, P = 1.0, p = 0.0395;
  Display d = loadDisplay(prototypeWith(
      "toed.json", {{"layout", "toed-in"}, {"viewing_distance_mm", D}, {"ei_count", {147, 63}}}));
  EiLayout L = computeLayout(d);
  DisplayInfo r = derive(d);
  const double ideal = P * (1.0 + g / D);
  EXPECT_NEAR(r.nominalEiPitchXMm, ideal, 1e-15);
  // Rounded to whole pixels: the average pitch is within a pixel over the array.
  EXPECT_NEAR(r.eiPitchXMm, ideal, p / (L.eiCols - 1));
  EXPECT_NEAR(r.eiPitchYMm, ideal, p / (L.eiRows - 1));
  for (int k = 0; k < L.eiCols; ++k) {
    // Each EI is centred on the projection of its lens centre from (0, 0, D), within half a pixel.
    EXPECT_LE(std::abs(L.eiCentreX(k) - L.lensX[size_t(k)] * (1.0 + g / D)), 0.5 * p + 1e-12);
    EXPECT_NEAR(L.pinholeX[size_t(k)], (k - 73) * P, 1e-12);
    if (k > 0) {
      EXPECT_GE(L.eiCol0[size_t(k)] - L.eiCol0[size_t(k - 1)], L.eiW);
    }
    EXPECT_NEAR(L.eiCentreX(k), -L.eiCentreX(L.eiCols - 1 - k), 1e-9);
  }
  for (int l = 0; l < L.eiRows; ++l)
    EXPECT_LE(std::abs(L.eiCentreY(l) - L.lensY[size_t(l)] * (1.0 + g / D)), 0.5 * p + 1e-12);
  // The central rays converge on the viewer.
  ASSERT_TRUE(r.generation.convergenceXMm.has_value());
  EXPECT_NEAR(*r.generation.convergenceXMm, D, 0.05 * D);
  ASSERT_TRUE(r.viewingZone.has_value());
  EXPECT_GT(r.viewingZone->commonWidthXMm, 0.5 * r.viewingZone->zoneWidthXMm);
}

TEST(EiLayout, LensGridUsesPhysicalLensCentres) {
  Display d = loadDisplay(prototypeWith("lensgrid.json", {{"layout", "lens-grid"}}));
  EiLayout L = computeLayout(d);
  EXPECT_EQ(L.eiaW, 3825);
  EXPECT_NEAR(L.pinholeX[0], -76.0, 1e-12);
  EXPECT_NEAR(L.eiCentreX(0), -75.05, 1e-9);
  DisplayInfo r = derive(d);
  ASSERT_TRUE(r.generationConvergenceXMm.has_value());
  EXPECT_NEAR(*r.generationConvergenceXMm, -264.0, 1e-6);
}

TEST(DisplayValidation, EiGridLargerThanPanel) {
  std::string f = prototypeWith("too_big.json", {{"ei_count", {154, 65}}});
  InputError e = expectInputError([&] { loadDisplay(f); });
  EXPECT_EQ(e.file(), f);
  EXPECT_EQ(e.key(), "ei_count");
  EXPECT_NE(e.value().find("3850"), std::string::npos);
  // Toed-in with the full 153 x 65 grid at P (1 + g/D) = 1.0094 mm does not fit either.
  InputError e2 = expectInputError([&] {
    loadDisplay(prototypeWith("toed_big.json", {{"layout", "toed-in"}, {"viewing_distance_mm", 350}}));
  });
  EXPECT_EQ(e2.key(), "ei_count");
}

TEST(DisplayValidation, BadGapsPitchAndKeys) {
  EXPECT_EQ(expectInputError([&] { loadDisplay(prototypeWith("g0.json", {{"generation_gap_mm", 0}})); }).key(),
            "generation_gap_mm");
  EXPECT_EQ(expectInputError([&] { loadDisplay(prototypeWith("g1.json", {{"reconstruction_gap_mm", -4}})); }).key(),
            "reconstruction_gap_mm");
  EXPECT_EQ(expectInputError([&] { loadDisplay(prototypeWith("k.json", {{"gap_mm", 3}})); }).key(), "gap_mm");
  EXPECT_EQ(expectInputError([&] { loadDisplay(prototypeWith("px.json", {{"ei_px", 0}})); }).key(), "ei_px");
  EXPECT_EQ(expectInputError([&] { loadDisplay(prototypeWith("lay.json", {{"layout", "tilted"}})); }).key(), "layout");
  // Inline MLA with a zero pitch: the key path names the part.
  Json m = readJsonFile(dataPath("optics/mlas/fresnel-630.json"));
  m["pitch_mm"] = 0.0;
  EXPECT_EQ(expectInputError([&] { loadDisplay(prototypeWith("p0.json", {{"mla", m}})); }).key(), "mla.pitch_mm");
  m["pitch_mm"] = 1.0;
  m["lattice"] = "hex";  // hex lattices load (tests/display/test_hex_layout.cpp), with one ei_px
  EXPECT_EQ(expectInputError([&] { loadDisplay(prototypeWith("hex.json", {{"mla", m}, {"ei_px", Json::array({25, 24})}})); })
                .key(),
            "ei_px");
  EXPECT_EQ(expectInputError([&] { loadDisplay(prototypeWith("nopanel.json", {{"panel", "no-such-panel"}})); }).key(),
            "panel");
}

TEST(DisplayValidation, ToedInNeedsRoomForWholePixelEis) {
  // P (1 + g/D) = 1.0094 mm = 25.6 px cannot hold 26 px EIs.
  InputError e = expectInputError([&] {
    loadDisplay(prototypeWith("toed_overlap.json", {{"layout", "toed-in"},
                                                    {"viewing_distance_mm", 350},
                                                    {"ei_px", 26},
                                                    {"ei_count", {100, 40}}}));
  });
  EXPECT_EQ(e.key(), "viewing_distance_mm");
  // Toed-in without a viewing distance.
  EXPECT_EQ(expectInputError([&] {
              loadDisplay(prototypeWith("toed_nod.json", {{"layout", "toed-in"}, {"viewing_distance_mm", nullptr}}));
            }).key(),
            "viewing_distance_mm");
}

TEST(DisplayInfo, CoverGlassShortensTheOpticalGap) {
  // The default panel's 0.55 mm N-BK7 cover glass (n = 1.51852 at 550 nm, Sellmeier): the
  // lenslets see the panel at g - t (1 - 1/n); without glass there is no optical gap to report.
  Display d = loadDisplay(defaultDisplayPath());
  ASSERT_TRUE(d.panel.coverGlass.has_value());
  const double t = d.panel.coverGlass->thicknessMm, n = 1.51852;
  const DisplayInfo r = derive(d);
  ASSERT_TRUE(r.reconstruction.opticalGapMm.has_value());
  const double ge = 4.0 - t * (1.0 - 1.0 / n);
  EXPECT_NEAR(*r.reconstruction.opticalGapMm, ge, 1e-4);
  EXPECT_NEAR(*r.reconstruction.opticalViewingAngleDeg, 2.0 * std::atan(0.5 / ge) * 180.0 / kPiD, 1e-3);
  EXPECT_NEAR(*r.reconstruction.opticalReferencePlaneMm, ge * 3.3 / (ge - 3.3), 1e-2);
  d.panel.coverGlass.reset();
  EXPECT_FALSE(derive(d).reconstruction.opticalGapMm.has_value());
}

// The command-line tests' small display file (fixtures.h) loads as the display it describes:
// 11 x 9 EIs of 9 px of 0.1 mm, centred on a panel 3 px larger on each side; a panel smaller
// than the EIA is refused.
TEST(DisplayCatalog, SmallDisplayFileLoadsAsDescribed) {
  const Display d = loadDisplay(scratchFile("small.json", smallDisplayJson({.cols = 11, .rows = 9, .eiPx = 9})));
  EXPECT_EQ(d.panel.widthPx, 11 * 9 + 6);
  EXPECT_EQ(d.panel.heightPx, 9 * 9 + 6);
  EXPECT_DOUBLE_EQ(d.panel.pixelPitchMm, 0.1);
  EXPECT_DOUBLE_EQ(d.panel.primaries[1].meanNm, 530.0);
  EXPECT_DOUBLE_EQ(d.mla.pitchMm, 0.9);
  EXPECT_DOUBLE_EQ(lensletFocus(d.mla).focalLengthMm, 3.0);
  EXPECT_DOUBLE_EQ(d.generationGapMm, 3.0);
  EXPECT_DOUBLE_EQ(d.reconstructionGapMm, 3.5);
  const EiLayout L = computeLayout(d);
  EXPECT_EQ(L.eiaW, 99);
  EXPECT_EQ(L.eiaH, 81);
  EXPECT_EQ(L.panelCol0, 3);
  EXPECT_EQ(L.panelRow0, 3);
  const std::string tooSmall = scratchFile(
      "too_small.json", smallDisplayJson({.cols = 11, .rows = 9, .eiPx = 9, .panelWidthPx = 60, .panelHeightPx = 60}));
  EXPECT_EQ(expectInputError([&] { loadDisplay(tooSmall); }).key(), "ei_count");
}
