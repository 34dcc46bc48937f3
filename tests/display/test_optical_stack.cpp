// Optical stacks (display/optical_stack.h) and their first-order optics
// (display/stack_first_order.h): against the thick-lens and two-lens formulas, the MLA of
// today's displays as a one-layer stack, and every kind of bad stack refused with its key path.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "core/error.h"
#include "core/format.h"
#include "display/display.h"
#include "display/display_info.h"
#include "display/optical_stack.h"
#include "display/stack_first_order.h"
#include "fixtures.h"
#include "spectral/dispersion.h"

namespace inim {
namespace {

constexpr double kPanelW = 100.0, kPanelH = 60.0;

OpticalStack stackOf(const std::string& layers, const std::string& extra = "") {
  const Json j = parseJsonText(R"({"layers": [)" + layers + "]" + extra + "}", "stack.json");
  return parseOpticalStack(JsonObject(j, "stack.json", "stack"), kPanelW, kPanelH);
}

double nOf(const std::string& material, double lambdaNm = kLambdaDNm) {
  return MaterialCatalog::standard().dielectric(material)->n(float(lambdaNm));
}

// The key path of the InputError `stack` raises, or "" when it loads.
std::string refusedKey(const std::string& layers, const std::string& extra = "") {
  try {
    stackOf(layers, extra);
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "stack.json");
    return e.key();
  }
  return "";
}

TEST(OpticalStack, EvenAsphereSagIsTheConicPlusItsTerms) {
  StackSurface s;
  s.radiusMm = 10.0;
  s.conic = -1.0;  // a paraboloid: r^2 / (2 R)
  EXPECT_DOUBLE_EQ(*s.sag(2.0), 0.2);
  s.asphereMm = {1e-3, -2e-5};
  EXPECT_NEAR(*s.sag(2.0), 0.2 + 1e-3 * 16.0 - 2e-5 * 64.0, 1e-15);
  s = StackSurface{};
  s.radiusMm = -1.0;
  s.conic = 3.0;  // (1 + k) c^2 r^2 reaches 1 at r = 0.5
  EXPECT_TRUE(s.sag(0.49).has_value());
  EXPECT_FALSE(s.sag(0.51).has_value());
  EXPECT_TRUE(StackSurface{}.isPlane());
}

// A biconvex lens (R1 = +5, R2 = -5 mm, t = 2 mm) 10 mm from the panel: the lensmaker's
// thick-lens focal length and principal planes h1 = -f (n - 1) t / (n R2) from the first
// vertex, h2 = -f (n - 1) t / (n R1) from the second.
TEST(OpticalStack, ThickLensMatchesTheLensmakersFormula) {
  const OpticalStack s = stackOf(R"({"type": "gap", "thickness_mm": 10},
      {"type": "lens_array", "pitch_mm": 1, "material": "PMMA", "thickness_mm": 2,
       "back": {"radius_mm": 5}, "front": {"radius_mm": -5}})");
  const double n = nOf("PMMA"), r1 = 5.0, r2 = -5.0, t = 2.0;
  const double f = 1.0 / ((n - 1.0) * (1.0 / r1 - 1.0 / r2 + (n - 1.0) * t / (n * r1 * r2)));
  const StackFirstOrder fo = stackFirstOrder(s);
  EXPECT_NEAR(fo.focalLengthMm, f, 1e-12 * f);
  EXPECT_NEAR(fo.frontPrincipalZMm, 10.0 - f * (n - 1.0) * t / (n * r2), 1e-12);
  EXPECT_NEAR(fo.rearPrincipalZMm, 12.0 - f * (n - 1.0) * t / (n * r1), 1e-12);
  EXPECT_NEAR(fo.rearFocalZMm - fo.rearPrincipalZMm, f, 1e-12);
  EXPECT_NEAR(fo.frontPrincipalZMm - fo.frontFocalZMm, f, 1e-12);
  // L = g f / (g - f) with g from the panel to H.
  const double g = fo.frontPrincipalZMm;
  EXPECT_NEAR(*fo.referencePlaneMm, g * f / (g - f), 1e-9);
  EXPECT_NEAR(fo.viewingAngleDeg, 2.0 * std::atan(0.5 / g) * 180.0 / M_PI, 1e-12);
}

// Two plano-convex arrays 2 mm apart (a compound cell): 1/f = 1/f1 + 1/f2 - e / (f1 f2), e the
// distance from the first lens's rear principal plane to the second's front one, each found by
// analysing the lens alone at the same place.
TEST(OpticalStack, TwoLensCellMatchesTheCombinationFormula) {
  const std::string lensA = R"({"type": "lens_array", "pitch_mm": 1, "material": "PMMA", "thickness_mm": 1.5,
      "front": {"radius_mm": -1.62}})";
  const std::string lensB = R"({"type": "lens_array", "pitch_mm": 1, "material": "N-BK7", "thickness_mm": 1.2,
      "back": {"radius_mm": 2.5, "conic": -0.5}, "front": {"radius_mm": -8}})";
  const StackFirstOrder a = stackFirstOrder(stackOf(R"({"type": "gap", "thickness_mm": 3}, )" + lensA));
  const StackFirstOrder b = stackFirstOrder(stackOf(R"({"type": "gap", "thickness_mm": 6.5}, )" + lensB));
  const StackFirstOrder ab = stackFirstOrder(
      stackOf(R"({"type": "gap", "thickness_mm": 3}, )" + lensA + R"(, {"type": "gap", "thickness_mm": 2}, )" + lensB));
  const double e = b.frontPrincipalZMm - a.rearPrincipalZMm;
  const double f = 1.0 / (1.0 / a.focalLengthMm + 1.0 / b.focalLengthMm - e / (a.focalLengthMm * b.focalLengthMm));
  EXPECT_NEAR(ab.focalLengthMm, f, 1e-12 * std::fabs(f));
  EXPECT_EQ(stackOf(R"({"type": "gap", "thickness_mm": 3}, )" + lensA).lensArrayCount(), 1);
}

// A plate has no power: it only shortens the reduced gap by t (1 - 1/n).
TEST(OpticalStack, APlateMovesTheReducedGapByItsThicknessTimesOneMinusOneOverN) {
  const std::string lens = R"({"type": "lens_array", "pitch_mm": 1, "material": "PMMA", "thickness_mm": 1.5,
      "front": {"radius_mm": -1.62}})";
  const StackFirstOrder bare = stackFirstOrder(stackOf(R"({"type": "gap", "thickness_mm": 3.7}, )" + lens));
  const StackFirstOrder plated = stackFirstOrder(stackOf(
      R"({"type": "plate", "thickness_mm": 0.7, "material": "N-BK7"}, {"type": "gap", "thickness_mm": 3}, )" + lens));
  EXPECT_NEAR(plated.focalLengthMm, bare.focalLengthMm, 1e-12);
  EXPECT_NEAR(bare.reducedGapMm - plated.reducedGapMm, 0.7 * (1.0 - 1.0 / nOf("N-BK7")), 1e-12);
}

// Today's displays as a one-layer stack: the lenslets' panel-side principal plane H lies at the
// display's gap, f = R / (n_d - 1), H' - H = T (n - 1) / n, in both orientations, and the
// viewing angle is display info's.
TEST(OpticalStack, TodaysMlaAsOneLayerHasItsGapFocalLengthAndViewingAngle) {
  const Display d = loadDisplay(defaultDisplayPath());
  const double n = nOf(d.mla.material), t = d.mla.substrateThicknessMm, g = d.reconstructionGapMm;
  for (Mla::Orientation o : {Mla::Orientation::CurvedTowardViewer, Mla::Orientation::CurvedTowardPanel}) {
    Mla mla = d.mla;
    mla.orientation = o;
    const OpticalStack s = stackFromMla(mla, g);
    ASSERT_EQ(s.layers.size(), 2u);
    const StackFirstOrder fo = stackFirstOrder(s);
    EXPECT_NEAR(fo.frontPrincipalZMm, g, 1e-12) << orientationName(o);
    EXPECT_NEAR(fo.focalLengthMm, *d.mla.radiusMm / (n - 1.0), 1e-12) << orientationName(o);
    EXPECT_NEAR(fo.rearPrincipalZMm - fo.frontPrincipalZMm, t * (n - 1.0) / n, 1e-12) << orientationName(o);
  }
  const StackFirstOrder fo = stackFirstOrder(stackFromMla(d.mla, g));
  EXPECT_NEAR(fo.viewingAngleDeg, derive(d).reconstruction.viewingAngleDeg, 1e-9);
}

TEST(OpticalStack, ABadStackIsRefusedNamingItsKeyPath) {
  const std::string gap = R"({"type": "gap", "thickness_mm": 3}, )";
  const std::string lens = R"("type": "lens_array", "pitch_mm": 1, "material": "PMMA", "thickness_mm": 1.5)";
  // Loads: the baseline every case below changes in one way.
  EXPECT_EQ(refusedKey(gap + "{" + lens + R"(, "front": {"radius_mm": -1.62}})"), "");
  // The caps do not close over the aperture: a square cell's corner lies 0.71 mm out, R = 0.6 mm.
  EXPECT_EQ(refusedKey(gap + "{" + lens + R"(, "front": {"radius_mm": -0.6}})"), "stack.layers[1].front");
  // An asphere undefined inside its aperture: (1 + k) c^2 r^2 > 1 at r = 0.6 mm.
  EXPECT_EQ(refusedKey(gap + R"({"type": "lens_array", "pitch_mm": 1.2, "material": "PMMA", "thickness_mm": 1.5,
      "aperture": "circle", "front": {"radius_mm": -1, "conic": 3}})"),
            "stack.layers[1].front");
  // Surfaces that cross: a 0.1 mm lens whose cap is 0.17 mm deep at the corners.
  EXPECT_EQ(refusedKey(gap + R"({"type": "lens_array", "pitch_mm": 1, "material": "PMMA", "thickness_mm": 0.1,
      "front": {"radius_mm": -1.62}})"),
            "stack.layers[1].thickness_mm");
  // Layers that overlap: a back surface bulging 0.17 mm toward a plate it touches.
  EXPECT_EQ(refusedKey(R"({"type": "plate", "thickness_mm": 1, "material": "N-BK7"}, {)" + lens +
                       R"(, "back": {"radius_mm": -1.62}})"),
            "stack.layers[1].back");
  EXPECT_EQ(refusedKey(R"({"type": "gap", "thickness_mm": 0.1}, {)" + lens + R"(, "back": {"radius_mm": -1.62}})"),
            "stack.layers[1].back");  // a gap too thin to hold it
  // A curvature radius below half the array (the panel's diagonal is 117 mm).
  EXPECT_EQ(refusedKey(gap + "{" + lens + R"(, "front": {"radius_mm": -1.62}})",
                       R"(, "curvature": {"shape": "sphere", "radius_mm": 40})"),
            "stack.curvature.radius_mm");
  EXPECT_EQ(refusedKey(gap + "{" + lens + R"(, "front": {"radius_mm": -1.62}})",
                       R"(, "curvature": {"shape": "cylinder", "radius_mm": 60})"),
            "");
  // A curved array that would touch a flat panel at its edge (centre behind, |R| 55 mm: the
  // array's edge dips 34 mm), one whose centre lies inside the stack, a curved panel under a
  // flat array, a curved panel too tight for the panel.
  EXPECT_EQ(refusedKey(gap + "{" + lens + R"(, "front": {"radius_mm": -1.62}})",
                       R"(, "curvature": {"shape": "cylinder", "radius_mm": -55})"),
            "stack.curvature.radius_mm");
  EXPECT_EQ(refusedKey(gap + "{" + lens + R"(, "front": {"radius_mm": -1.62}})", R"(, "panel_radius_mm": 500)"),
            "stack.panel_radius_mm");
  EXPECT_EQ(refusedKey(gap + "{" + lens + R"(, "front": {"radius_mm": -1.62}})",
                       R"(, "curvature": {"shape": "cylinder", "radius_mm": 500}, "panel_radius_mm": 20)"),
            "stack.panel_radius_mm");
  EXPECT_EQ(refusedKey(gap + "{" + lens + R"(, "front": {"radius_mm": -1.62}})",
                       R"(, "curvature": {"shape": "cylinder", "radius_mm": -500}, "panel_radius_mm": -497)"),
            "");  // concentric
  // A lattice that does not cover the 100 x 60 mm panel.
  EXPECT_EQ(refusedKey(gap + "{" + lens + R"(, "count": [90, 60], "front": {"radius_mm": -1.62}})"),
            "stack.layers[1].count");
  EXPECT_EQ(refusedKey(gap + "{" + lens + R"(, "count": [100, 60], "front": {"radius_mm": -1.62}})"), "");
  // Unknown keys, materials and kinds; a stack with nothing that forms views.
  EXPECT_EQ(refusedKey(gap + "{" + lens + R"(, "frnt": {"radius_mm": -1.62}})"), "stack.layers[1].frnt");
  EXPECT_EQ(refusedKey(R"({"type": "plate", "thickness_mm": 1, "material": "unobtainium"})"),
            "stack.layers[0].material");
  EXPECT_EQ(refusedKey(R"({"type": "prism", "thickness_mm": 1})"), "stack.layers[0].type");
  EXPECT_EQ(refusedKey(R"({"type": "gap", "thickness_mm": 1})"), "stack.layers");
}

// Apertures and barriers load; a pinhole sheet alone forms views (a pinhole-array display).
TEST(OpticalStack, PinholeAndBarrierLayersLoadAndHaveNoPower) {
  const OpticalStack s = stackOf(R"({"type": "gap", "thickness_mm": 3},
      {"type": "apertures", "pitch_mm": 1, "hole": "circle", "hole_mm": 0.1, "thickness_mm": 0.01},
      {"type": "barriers", "pitch_mm": 1, "height_mm": 2, "wall_mm": 0.02, "wall_reflectance": 0.04})");
  ASSERT_EQ(s.layers.size(), 3u);
  EXPECT_EQ(s.layers[2].kind, StackLayer::Kind::Barriers);
  EXPECT_DOUBLE_EQ(s.totalThicknessMm(), 5.01);
  EXPECT_TRUE(stackFirstOrder(s).afocal);
  EXPECT_NE(stackText(s, stackFirstOrder(s)).find("afocal"), std::string::npos);
}

// The prototype's display file with "stack" in place of "mla" and "reconstruction_gap_mm".
std::string prototypeWithStack(const std::string& name, const Json& stack) {
  Json j = readJsonFile(defaultDisplayPath());
  j.erase("mla");
  j.erase("reconstruction_gap_mm");
  j["panel"] = "sony-xperia-1-ii";
  j["stack"] = stack;
  return fixtures::scratchFile(name, j.dump(2));
}

// The prototype's MLA written as a stack loads for every stage as the same MLA, at the gap its
// layers give; written back as a stack it is the same layers.
TEST(OpticalStack, ADisplayFileWithOneLensArrayIsTodaysMla) {
  const Display legacy = loadDisplay(defaultDisplayPath());
  const double n = nOf("PMMA");
  const double gapLayer = 4.0 - 1.5 / n;  // H 4 mm from the panel, as the prototype's gap
  const Json stack = Json::parse(R"({"layers": [{"type": "gap", "thickness_mm": )" + formatText("%.17g", gapLayer) +
                                 R"(}, {"type": "lens_array", "pitch_mm": 1.0, "material": "PMMA", "thickness_mm": 1.5,
                                 "front": {"radius_mm": -1.62}}]})");
  const Display d = loadDisplay(prototypeWithStack("one_layer.json", stack));
  ASSERT_TRUE(d.stack.has_value());
  EXPECT_NEAR(d.reconstructionGapMm, legacy.reconstructionGapMm, 1e-12);
  EXPECT_EQ(d.generationGapMm, legacy.generationGapMm);
  EXPECT_EQ(d.mla.pitchMm, legacy.mla.pitchMm);
  EXPECT_EQ(*d.mla.radiusMm, *legacy.mla.radiusMm);
  EXPECT_EQ(d.mla.substrateThicknessMm, legacy.mla.substrateThicknessMm);
  EXPECT_EQ(d.mla.orientation, legacy.mla.orientation);
  EXPECT_EQ(d.mla.aperture, legacy.mla.aperture);
  const OpticalStack back = stackFromMla(d.mla, d.reconstructionGapMm);
  EXPECT_NEAR(back.layers[0].thicknessMm, gapLayer, 1e-12);
  EXPECT_EQ(back.layers[1].front.radiusMm, -1.62);
  EXPECT_NE(displayInfoText(d).find("Optical stack (2 layers"), std::string::npos);
  EXPECT_NEAR(displayInfoJson(d)["stack"]["reduced_gap_mm"].get<double>(), 4.0, 1e-12);
}

// A flat compound stack loads for every stage: the equivalent MLA has the stack's focal length
// and the gap runs to its principal plane H; curved, it is traced too, on a hex lattice with walls
// between its caps (a hex aperture smaller than its cell) as well, and `display info` describes
// it. "mla" beside "stack" is an error.
TEST(OpticalStack, ACompoundStackIsTracedFlatCurvedAndWithWallsBetweenHexCaps) {
  Json stack = Json::parse(R"({"layers": [{"type": "gap", "thickness_mm": 3},
      {"type": "lens_array", "pitch_mm": 1.0, "material": "PMMA", "thickness_mm": 1.5, "front": {"radius_mm": -1.62}},
      {"type": "gap", "thickness_mm": 1},
      {"type": "lens_array", "pitch_mm": 1.0, "material": "PMMA", "thickness_mm": 1.5, "back": {"radius_mm": 1.62}}]})");
  const Display flat = loadDisplay(prototypeWithStack("compound.json", stack));
  EXPECT_TRUE(flat.stackTraced);
  const StackFirstOrder fo = stackFirstOrder(*flat.stack);
  EXPECT_NEAR(*flat.mla.focalLengthMm, fo.focalLengthMm, 1e-12);
  EXPECT_NEAR(flat.reconstructionGapMm, fo.reducedGapMm, 1e-12);
  EXPECT_EQ(flat.mla.pitchMm, 1.0);

  stack["curvature"] = {{"shape", "sphere"}, {"radius_mm", 4000}};
  for (int i : {1, 3}) stack["layers"][i]["pitch_mm"] = 0.9875;  // curved, the EIs lie under their lenslets
  EXPECT_TRUE(loadDisplay(prototypeWithStack("curved.json", stack)).stackTraced);
  for (int i : {1, 3})  // hex caps inside a smaller hex aperture: walls between them, curved
    stack["layers"][i]["lattice"] = "hex", stack["layers"][i]["aperture"] = "hex", stack["layers"][i]["aperture_mm"] = 0.8;
  Json hexWalls = readJsonFile(prototypeWithStack("curved-hex-walls.json", stack));
  hexWalls["ei_count"] = {150, 65};  // hex rows shifted by half a pitch: one column fewer fits
  const std::string file = fixtures::scratchFile("curved-hex-walls-150.json", hexWalls.dump(2));
  const Display d = loadDisplay(file);
  EXPECT_TRUE(d.stackTraced);
  const std::string text = displayInfoText(d);
  EXPECT_NE(text.find("effective focal length"), std::string::npos) << text;
  EXPECT_NE(text.find("curved: lenslet centres on a sphere"), std::string::npos) << text;
  EXPECT_FALSE(displayInfoJson(d)["stack"]["afocal"].get<bool>());
  Json both = readJsonFile(file);
  both["mla"] = "fresnel-630";
  const std::string bad = fixtures::scratchFile("both.json", both.dump());
  EXPECT_EQ(fixtures::expectInputError([&] { loadDisplay(bad); }).key(), "mla");
}

}  // namespace
}  // namespace inim
