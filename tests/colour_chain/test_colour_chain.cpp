// The colour chain's pieces with exact answers: the chart's colours, the panel's 8-bit input,
// relative colorimetry on an ideal chain, and corrections that undo a known distortion.
#include <gtest/gtest.h>

#include "colour_chain/chain_fit.h"
#include "colour_chain/colour_chain.h"
#include "colour_chain/patch_sets.h"
#include "colour_chain/verification.h"
#include "display/display.h"
#include "spectral/cie.h"
#include "fixtures.h"

namespace inim {
namespace {

Vec2d xy(const Vec3d& v) { return Vec2d(v.x, v.y) / (v.x + v.y + v.z); }

const Panel& paperPanel() {
  static const Panel p = loadDisplay(displayPathOrDefault("")).panel;
  return p;
}

// A pose whose response is the nominal panel seen through `mix` (channel crosstalk, a tint),
// scaled by `k` (light lost on the way).
PoseResponse syntheticPose(const PanelColor& panel, const glm::dmat3& mix, double k) {
  PoseResponse r;
  r.pose.name = "synthetic";
  r.xyzPerDrive = k * panel.driveToXYZ() * mix;
  r.cameraPerDrive = glm::dmat3(0.9, 0.05, 0.02, 0.1, 0.8, 0.1, 0.01, 0.07, 1.1) * r.xyzPerDrive;
  return r;
}

TEST(PatchSets, ColorCheckerNeutralsAreD65GreysOfTheirMeasuredLuminance) {
  const PatchSet cc = colorCheckerPatches();
  ASSERT_EQ(cc.patches.size(), 24u);
  const Vec2d d65 = xy(d65WhiteXyz());
  for (int i = 18; i < 24; ++i) EXPECT_LT(glm::length(xy(cc.patches[size_t(i)].xyz) - d65), 0.008) << cc.patches[size_t(i)].name;
  // BabelColor average: white 9.5 reflects ~90 %, black 2 ~3 % (Munsell values 9.5 and 2).
  EXPECT_NEAR(cc.patches[18].xyz.y, 0.90, 0.03);
  EXPECT_NEAR(cc.patches[23].xyz.y, 0.031, 0.006);
  // The radiance spectrum gives the same XYZ as the patch carries.
  EXPECT_LT(glm::length(spectrumToXYZ(*cc.patches[6].radiance) - cc.patches[6].xyz), 1e-9);
}

TEST(PatchSets, DriveGridAndHoldOutsHaveTheirStatedShape) {
  EXPECT_EQ(driveGrid(5).patches.size(), 125u);
  EXPECT_EQ(driveGrid(5).patches[124].drive, Vec3d(1.0));
  fixtures::expectInputError([] { driveGrid(1); });
  const PanelColor panel(paperPanel());
  const double e = calibrationExposure(panel);
  const PatchSet in = holdOutInGamut(panel, e, 100, 7, "lin_rec709");
  const PatchSet out = holdOutOutOfGamut(panel, e, 30, 7);
  ASSERT_EQ(in.patches.size(), 100u);
  ASSERT_EQ(out.patches.size(), 30u);
  for (const Patch& p : in.patches) {
    const Vec3d d = e * panel.driveFromXYZ(p.xyz);
    EXPECT_GE(std::min({d.x, d.y, d.z}), -1e-6);
    EXPECT_LE(std::max({d.x, d.y, d.z}), 1.0 + 1e-6);
    EXPECT_LT(glm::length(representableInField(p.xyz, "lin_rec709") - p.xyz), 1e-4);
  }
  for (const Patch& p : out.patches) {
    const Vec3d d = e * panel.driveFromXYZ(p.xyz);
    EXPECT_TRUE(std::min({d.x, d.y, d.z}) < -0.01 || std::max({d.x, d.y, d.z}) > 1.01);
  }
  // The same seed, the same colours.
  EXPECT_EQ(holdOutInGamut(panel, e, 100, 7, "lin_rec709").patches[42].xyz, in.patches[42].xyz);
}

TEST(PatchSets, PatchCsvRefusesWrongColumnsAndValues) {
  const std::string good = fixtures::scratchPath("patches.csv");
  fixtures::writeBytes(good, "# mine\nname,X,Y,Z\nred,0.41,0.21,0.02\n");
  EXPECT_EQ(readPatchCsv(good).patches.at(0).xyz, Vec3d(0.41, 0.21, 0.02));
  for (const char* bad : {"name,R,G,B\nred,1,0,0\n", "name,X,Y,Z\nred,0.4,0.2\n", "name,X,Y,Z\nred,nan,0.2,0.1\n",
                          "name,X,Y,Z\nred,0.4,abc,0.1\n", "name,X,Y,Z\n", "name,X,Y,Z\nred,-1,0.2,0.1\n"}) {
    const std::string f = fixtures::scratchPath("bad_patches.csv");
    fixtures::writeBytes(f, bad);
    const InputError e = fixtures::expectInputError([&] { readPatchCsv(f); });
    EXPECT_EQ(e.file(), f) << bad;
  }
}

TEST(PanelInput, EightBitSrgbStepsAndIdempotence) {
  PanelInput in{Eotf{}, 8};
  const Vec3d q = in.quantise(Vec3d(0.5, 0.0, 1.0));
  // sRGB encodes 0.5 as 0.7354: level 188 of 255, decoded 0.50289.
  EXPECT_NEAR(q.x, Eotf{}.decode(188.0 / 255.0), 1e-12);
  EXPECT_EQ(q.y, 0.0);
  EXPECT_EQ(q.z, 1.0);
  EXPECT_EQ(in.quantise(q), q);
  const PanelInput floatInput{Eotf{}, 0};
  EXPECT_EQ(floatInput.quantise(Vec3d(0.123)), Vec3d(0.123));
  EXPECT_EQ(in.quantise(Vec3d(-0.5, 2.0, 0.0)), Vec3d(0.0, 1.0, 0.0));  // clamped first
}

TEST(ColourChain, ExposureMapsTheFieldWhiteToTheBrightestD65) {
  const PanelColor panel(paperPanel());
  const Vec3d d = calibrationExposure(panel) * panel.driveFromXYZ(d65WhiteXyz());
  EXPECT_NEAR(std::max({d.x, d.y, d.z}), 1.0, 1e-12);
}

TEST(ColourChain, IdealChainShowsEveryTargetExactly) {
  const PanelColor panel(paperPanel());
  const double e = calibrationExposure(panel), k = 0.83;
  const PoseChain chain(syntheticPose(panel, glm::dmat3(1.0), k), PanelInput{Eotf{}, 0});
  EXPECT_NEAR(chain.whiteY(), k * e, 1e-12);
  ColourPath path{panel, panel, {e, false, GamutMapping::Clip, nullptr}, "spectral", PanelInput{Eotf{}, 0}, {}};
  const FieldToDrive toDrive = path.uncalibrated();
  for (const Patch& p : holdOutInGamut(panel, e, 50, 3).patches) {
    const Vec3d shown = chain.shownXyz(path.driveOf(toDrive, p.xyz));
    EXPECT_LT(deltaE2000(shown, chain.target(p.xyz), chain.labWhite()), 1e-3);
  }
}

TEST(ColourChain, EveryCorrectionUndoesCrosstalkOnColoursNeverFitted) {
  const PanelColor panel(paperPanel());
  const double e = calibrationExposure(panel);
  // 6 % of each channel leaks into its neighbours, and 10 % of the light is lost.
  const glm::dmat3 mix(0.90, 0.06, 0.0, 0.06, 0.88, 0.06, 0.0, 0.06, 0.94);
  const PoseChain chain(syntheticPose(panel, mix, 0.9), PanelInput{Eotf{}, 0});
  ColourPath path{panel, panel, {e, false, GamutMapping::Clip, nullptr}, "spectral", PanelInput{Eotf{}, 0}, {}};
  const PatchSet grid = driveGrid(5), hold = holdOutInGamut(panel, e, 120, 11);
  const VerificationRow before = verify(path, path.uncalibrated(), chain, {&hold}, "none", "");
  EXPECT_GT(before.inGamut.mean, 1.0);
  for (CorrectionKind kind : allCorrectionKinds()) {
    auto model = fitPanelCorrection(kind, {&chain}, path.uncalibrated(), grid, 17);
    const VerificationRow after = verify(path, path.corrected(model), chain, {&hold}, correctionName(kind), "this pose");
    EXPECT_GT(after.inGamut.count, 60) << correctionName(kind);
    EXPECT_LT(after.inGamut.max, 0.05) << correctionName(kind);  // exact but for float drive values
  }
}

TEST(ColourChain, CameraCorrectionLearnsTheDisplaysLight) {
  const PanelColor panel(paperPanel());
  const PoseChain chain(syntheticPose(panel, glm::dmat3(1.0), 1.0), PanelInput{Eotf{}, 0});
  auto model = fitCameraCorrection(CorrectionKind::Matrix, {&chain}, driveGrid(3));
  const Vec3d d(0.2, 0.7, 0.4);
  EXPECT_LT(glm::length(model->apply(chain.cameraRgb(d)) - chain.shownXyz(d)), 1e-9);
}

TEST(ColourChain, SummaryUsesInterpolatedPercentiles) {
  std::vector<double> v;
  for (int i = 1; i <= 20; ++i) v.push_back(i);
  const DeltaESummary s = summarise(v);
  EXPECT_DOUBLE_EQ(s.mean, 10.5);
  EXPECT_NEAR(s.p95, 19.05, 1e-12);
  EXPECT_DOUBLE_EQ(s.max, 20.0);
  EXPECT_EQ(summarise({}).count, 0);
}

TEST(ColourChain, UnknownFieldSpaceIsAnInputError) {
  const InputError e = fixtures::expectInputError([] { representableInField(Vec3d(0.5), "not_a_space"); });
  EXPECT_EQ(e.key(), "field_space");
}

}  // namespace
}  // namespace inim
