// `inim calibrate` end to end at a small size: the exported files as OpenColorIO and its
// ociochecklut read them agree with the fit, the linear chain model agrees with a direct render,
// the headline metrics are there, and the result does not depend on the thread count.
#include <gtest/gtest.h>

#include <OpenColorIO/OpenColorIO.h>

#include <cstdio>
#include <filesystem>
#include <fstream>

#include "../calibration/test_functions.h"
#include "core/output_file.h"
#include "core/parallel.h"
#include "display/display.h"
#include "runs/calibrate_run.h"
#include "spectral/color.h"
#include "fixtures.h"

namespace OCIO = OCIO_NAMESPACE;
namespace fs = std::filesystem;

namespace inim {
namespace {

CalibrateSettings quickSettings(const std::string& out) {
  CalibrateSettings s;
  s.outDir = out;
  s.poses = {"centre", "right"};
  s.render.width = 96;
  s.render.view.apertureGrid = 8;
  s.holdOutInGamut = 30, s.holdOutOutOfGamut = 10;
  s.lutSize = 17;
  s.directChecks = 1;
  return s;
}

const CalibrateResult& quickRun() {
  static const CalibrateResult r = runCalibration(quickSettings(fixtures::scratchPath("calibrate")));
  return r;
}

Vec3d ocioApply(const std::string& file, const Vec3d& rgb) {
  OCIO::FileTransformRcPtr t = OCIO::FileTransform::Create();
  t->setSrc(file.c_str());
  t->setInterpolation(OCIO::INTERP_TETRAHEDRAL);
  float px[3] = {float(rgb.x), float(rgb.y), float(rgb.z)};
  OCIO::Config::CreateRaw()->getProcessor(t)->getDefaultCPUProcessor()->applyRGB(px);
  return {px[0], px[1], px[2]};
}

TEST(CalibrateRun, WritesEveryFileAndTheHeadlineMetrics) {
  const CalibrateResult& r = quickRun();
  for (const std::string& f : {r.files.cube, r.files.clf, r.files.config}) EXPECT_TRUE(fs::exists(f)) << f;
  for (const char* f : {"calibration.json", "stages.csv", "verification.csv"})
    EXPECT_TRUE(fs::exists(fs::path(r.files.cube).parent_path() / f)) << f;
  const Json& in = r.json["holdout"]["in_gamut"];
  for (const char* key : {"de2000_mean_before", "de2000_mean_after", "de2000_p95_after", "de2000_max_after"})
    EXPECT_TRUE(in.contains(key)) << key;
  EXPECT_TRUE(r.json["holdout"]["per_pose"]["right"]["in_gamut"].contains("de2000_mean_after"));
  EXPECT_GT(in["count"].get<int>(), 20);
  EXPECT_LE(in["de2000_mean_after"].get<double>(), in["de2000_mean_before"].get<double>() + 0.05);
  // verification.csv holds every row calibration.json does, the exported LUT's included.
  std::ifstream csv(fs::path(r.files.cube).parent_path() / "verification.csv");
  int lines = -1, exportedLines = 0;  // less the header
  for (std::string line; std::getline(csv, line);) ++lines, exportedLines += line.find("(exported LUT)") != std::string::npos;
  EXPECT_EQ(size_t(lines), r.json["verification"].size());
  EXPECT_EQ(exportedLines, 2);  // one per pose
  // Both panels: the one the EIAs are made for and the one shown (here the same display).
  EXPECT_EQ(r.json["panel"], r.json["shown_panel"]);
}

// EIAs made for another panel than the one shown: colours the shown panel can show but the
// assumed one cannot encode are reported on their own, never in the in-gamut statistic. With one
// panel there are none.
TEST(CalibrateRun, ColoursOutsideTheAssumedGamutAreKeptOutOfTheInGamutStatistic) {
  for (const Json& v : quickRun().json["verification"]) EXPECT_EQ(v["outside_assumed_gamut"]["count"].get<int>(), 0);
  CalibrateSettings s = quickSettings(fixtures::scratchPath("calibrate_mismatch"));
  s.displayPath = defaultDisplayPath();  // placeholder primaries, a wider gamut than the OLED's
  s.assumedDisplayPath = dataPath("optics/displays/paper-prototype-measured-oled.json");
  s.poses = {"centre"};
  s.holdOutInGamut = 200, s.holdOutOutOfGamut = 400;
  const CalibrateResult r = runCalibration(s);
  const Json& pose = r.json["holdout"]["per_pose"]["centre"];
  EXPECT_GT(pose["outside_assumed_gamut"]["count"].get<int>(), 0);
  EXPECT_EQ(pose["in_gamut"]["count"].get<int>() + pose["outside_assumed_gamut"]["count"].get<int>() +
                pose["out_of_gamut"]["count"].get<int>(),
            int(r.holdIn.patches.size() + r.holdOut.patches.size()));
  EXPECT_NE(r.json["panel"], r.json["shown_panel"]);
}

TEST(CalibrateRun, LinearChainModelMatchesADirectRender) { EXPECT_LT(quickRun().maxDirectCheckError, 1e-5); }

TEST(CalibrateRun, OpenColorIOReadsTheExportedLutsAsInimAppliesThem) {
  const CalibrateResult& r = quickRun();
  for (const Vec3d& x : testing::pseudoRandomColours(60)) {
    const Vec3d ours = r.exported->eval(x);
    for (const std::string& file : {r.files.cube, r.files.clf}) {
      const Vec3d ocio = ocioApply(file, x);
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(ocio[c], ours[c], 1e-4) << file;
    }
  }
  // The exported table is the chosen fit: on drives whose correction stays inside the panel's
  // range, it agrees with the model itself.
  const CorrectionReport* chosen = nullptr;
  for (const CorrectionReport& c : r.corrections)
    if (c.name == r.chosen) chosen = &c;
  ASSERT_NE(chosen, nullptr);
  int compared = 0;
  for (const Vec3d& x : testing::pseudoRandomColours(200, 0.1, 0.8)) {
    const Vec3d fit = chosen->allPoses->apply(x);
    if (glm::any(glm::lessThan(fit, Vec3d(0.02))) || glm::any(glm::greaterThan(fit, Vec3d(0.98)))) continue;
    ++compared;
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(r.exported->eval(x)[c], fit[c], 2e-3);
  }
  EXPECT_GT(compared, 50);
}

// Rec.709 content converted through the exported OCIO config lands on the drive inim itself puts
// on the panel for that colour (Rec.709 -> the panel's native drive -> the LUT -> clamped).
TEST(CalibrateRun, TheOcioConfigTakesRec709ContentToInimsCorrectedDrive) {
  const CalibrateResult& r = quickRun();
  OCIO::ConstConfigRcPtr config = OCIO::Config::CreateFromFile(r.files.config.c_str());
  OCIO::ConstCPUProcessorRcPtr cpu = config->getProcessor("lin_rec709", "panel_calibrated")->getDefaultCPUProcessor();
  const FieldToDrive corrected = r.path.corrected(r.exported);
  int compared = 0;
  for (const Vec3d& rgb : testing::pseudoRandomColours(80, 0.0, 0.9)) {
    float px[3] = {float(rgb.x), float(rgb.y), float(rgb.z)};
    cpu->applyRGB(px);
    const Vec3d xyz = Vec3d(ColorSystem::rec709ToXYZ() * Vec3(rgb));
    const Vec3d ours = r.path.driveOf(corrected, xyz);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(px[c], ours[c], 2e-4) << rgb.x << " " << rgb.y << " " << rgb.z;
    for (int c = 0; c < 3; ++c) EXPECT_TRUE(px[c] >= 0.0f && px[c] <= 1.0f);  // clamped as a panel is driven
    ++compared;
  }
  EXPECT_EQ(compared, 80);
}

TEST(CalibrateRun, OciochecklutReadsTheCube) {
  if (std::system("command -v ociochecklut > /dev/null 2>&1") != 0)
    GTEST_SKIP() << "ociochecklut not found (Debian package opencolorio-tools)";
  const CalibrateResult& r = quickRun();
  const Vec3d x(0.25, 0.5, 0.75);
  FILE* p = popen(("ociochecklut " + r.files.cube + " 0.25 0.5 0.75 2>&1").c_str(), "r");
  ASSERT_NE(p, nullptr);
  std::string out, line;
  char buf[512];
  while (fgets(buf, sizeof buf, p)) line = buf, out += line;
  pclose(p);
  double v[3] = {0, 0, 0};
  ASSERT_EQ(std::sscanf(line.c_str(), "%lf %lf %lf", &v[0], &v[1], &v[2]), 3) << out;
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(v[c], r.exported->eval(x)[c], 1e-4) << out;
}

TEST(CalibrateRun, TheTableDoesNotDependOnTheThreadCount) {
  std::string one, two;
  {
    ThreadLimit limit(1);
    one = fixtures::readBytes(runCalibration(quickSettings(fixtures::scratchPath("calibrate_t1"))).files.cube);
  }
  {
    ThreadLimit limit(2);
    two = fixtures::readBytes(runCalibration(quickSettings(fixtures::scratchPath("calibrate_t2"))).files.cube);
  }
  EXPECT_FALSE(one.empty());
  EXPECT_EQ(one, fixtures::readBytes(quickRun().files.cube));
  EXPECT_EQ(one, two);
}

TEST(CalibrateRun, BadSettingsAreRefusedBeforeAnyOutput) {
  const std::string out = fixtures::scratchPath("calibrate_bad");
  auto refused = [&](auto change, const char* key) {
    CalibrateSettings s = quickSettings(out);
    change(s);
    const InputError e = fixtures::expectInputError([&] { runCalibration(s); });
    EXPECT_NE(e.key().find(key), std::string::npos) << e.what();
    EXPECT_FALSE(fs::exists(fs::path(out) / "calibration.json"));
  };
  refused([](CalibrateSettings& s) { s.poses = {"sideways"}; }, "poses");
  refused([](CalibrateSettings& s) { s.fieldSpace = "no_such_space"; }, "field_space");
  refused([](CalibrateSettings& s) { s.angleDeg = 95; }, "angle_deg");
  refused([](CalibrateSettings& s) { s.correction = "spline"; }, "correction");
  refused([](CalibrateSettings& s) { s.gridLevels = 1; }, "grid_levels");
  const std::string csv = fixtures::scratchPath("patches_bad.csv");
  fixtures::writeBytes(csv, "name,R,G,B\nred,1,0,0\n");
  refused([&](CalibrateSettings& s) { s.patchCsv = csv; }, "columns");
  // --out naming an existing file: refused with the settings, before the characterisation.
  refused([&](CalibrateSettings& s) { s.outDir = csv; }, "out");
}

}  // namespace
}  // namespace inim
