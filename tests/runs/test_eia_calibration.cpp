// `inim eia --calibration` as a library run: the calibration file's LUT is applied to every
// drive value of the EIA. An identity LUT changes nothing (bit for bit); a LUT that halves the
// drive halves every EIA value (tetrahedral interpolation reproduces affine maps, so only float
// rounding remains); a bad file is named before any output.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "calibration/calibration_file.h"
#include "calibration/lut_io.h"
#include "core/output_file.h"
#include "runs/eia_run.h"
#include "synthesis/eia_correction.h"
#include "fixtures.h"

using namespace inim;

namespace {

const fixtures::ScratchDir& scratch() {
  static const fixtures::ScratchDir dir("eia_calibration");
  return dir;
}

// A small display and the paper-fig7 scene, auto exposure, written under `name`.
EiaRunSettings smallRun(const std::string& name, const std::string& calibration) {
  static const std::string display = [] {
    const std::string path = scratch().path("display.json");
    fixtures::writeBytes(path, fixtures::smallDisplayJson({11, 9, 9}));
    return path;
  }();
  EiaRunSettings s;
  s.displayPath = display;
  s.fieldPath = dataPath("scenes/paper-fig7.json");
  s.synthesis.autoExposure = true;
  s.synthesis.progress = false;
  s.calibrationPath = calibration;
  s.out = scratch().path(name + ".exr");
  return s;
}

std::string writeLut(const std::string& name, const ColourFunction& f) {
  const std::string path = scratch().path(name);
  writeCube(path, Lut3d::sample(f, Lut3d::kDefaultSize), name);
  return path;
}

}  // namespace

TEST(EiaCalibration, IdentityLutLeavesTheEiaBitIdentical) {
  const EiaRunResult plain = runEia(smallRun("plain", ""));
  const EiaRunResult identity =
      runEia(smallRun("identity", writeLut("identity.cube", [](const Vec3d& x) { return x; })));
  EXPECT_EQ(plain.calibration, "none");
  EXPECT_NE(identity.calibration.find("identity.cube"), std::string::npos);
  const std::vector<float>& a = plain.synthesis.eia.data;
  ASSERT_EQ(a.size(), identity.synthesis.eia.data.size());
  EXPECT_TRUE(a == identity.synthesis.eia.data);
  EXPECT_TRUE(plain.synthesis.drive == identity.synthesis.drive);
  // The scene is seen: the comparison is not between black images.
  size_t lit = 0;
  for (float v : a) lit += v > 0.0f;
  EXPECT_GT(lit, a.size() / 20);
}

TEST(EiaCalibration, HalvingLutHalvesEveryDriveValue) {
  const EiaRunResult plain = runEia(smallRun("plain2", ""));
  const EiaRunSettings halfSettings = smallRun("half", writeLut("half.cube", [](const Vec3d& x) { return 0.5 * x; }));
  const EiaRunResult half = runEia(halfSettings);
  const Image& a = plain.synthesis.eia;
  const Image& b = half.synthesis.eia;
  ASSERT_EQ(a.data.size(), b.data.size());
  double worst = 0.0, brightest = 0.0;
  for (size_t i = 0; i < a.data.size(); ++i) {
    worst = std::max(worst, std::abs(double(b.data[i]) - 0.5 * double(a.data[i])));
    brightest = std::max(brightest, double(a.data[i]));
  }
  EXPECT_LE(worst, 1e-6);
  EXPECT_GT(brightest, 0.5);  // drive values that halving visibly changes
  // The same exposure: the correction comes after it (and after the gamut mapping).
  EXPECT_EQ(plain.synthesis.stats.exposureUsed, half.synthesis.stats.exposureUsed);
  EXPECT_NE(summaryText(half, halfSettings).find("calibration: " + half.calibration),
            std::string::npos);
}

TEST(EiaCalibration, BadFileIsNamedBeforeAnyOutput) {
  const std::string bad = scratch().path("bad.cube");
  fixtures::writeBytes(bad, "LUT_3D_SIZE 2\n0 0 0\n");
  EiaRunSettings s = smallRun("bad", bad);
  InputError e = fixtures::expectInputError([&] { (void)runEia(s); });
  EXPECT_EQ(e.file(), bad);
  s.calibrationPath = scratch().path("missing.clf");
  e = fixtures::expectInputError([&] { (void)runEia(s); });
  EXPECT_EQ(e.key(), "calibration");
  EXPECT_EQ(e.file(), s.calibrationPath);
  s.calibrationPath = scratch().path("lut.3dl");
  EXPECT_EQ(fixtures::expectInputError([&] { (void)runEia(s); }).key(), "calibration");
  EXPECT_FALSE(std::filesystem::exists(s.out));
  EXPECT_FALSE(std::filesystem::exists(scratch().path("bad.png")));
}

// The budget's calibration rung corrects an EIA already made (synthesis/eia_correction.h): that
// must be the EIA `inim eia --calibration` makes, bit for bit, with a LUT that is not affine and
// mixes channels (so that tetrahedral interpolation and clamping both matter).
TEST(EiaCalibration, CorrectingAMadeEiaIsMakingItCorrected) {
  const std::string lut = writeLut("mixing.cube", [](const Vec3d& x) {
    return Vec3d(std::pow(x.x, 0.8) + 0.1 * x.y, 0.9 * x.y + 0.2 * x.z * x.z, 1.1 * x.z - 0.05 * x.x);
  });
  const EiaRunResult plain = runEia(smallRun("plain3", ""));
  const EiaRunResult made = runEia(smallRun("mixing", lut));
  const Image corrected = correctedEia(plain.layout, plain.synthesis.eia, *loadCalibration(lut));
  ASSERT_EQ(corrected.data.size(), made.synthesis.eia.data.size());
  EXPECT_TRUE(corrected.data == made.synthesis.eia.data);
  EXPECT_FALSE(corrected.data == plain.synthesis.eia.data);
}

// The EXR keeps the exposure the EIA was made with, for `inim view --reference`.
TEST(EiaCalibration, TheEiaHeaderKeepsItsExposure) {
  const EiaRunSettings s = smallRun("header", "");
  const EiaRunResult r = runEia(s);
  const std::optional<double> e = readImageNumber(s.out, kEiaExposureHeader);
  ASSERT_TRUE(e.has_value());
  EXPECT_EQ(*e, r.synthesis.stats.exposureUsed);
  EXPECT_NE(r.synthesis.stats.exposureUsed, 1.0);  // auto exposure chose a factor
  EXPECT_FALSE(readImageNumber(s.out, "inim:no_such_entry").has_value());
}
