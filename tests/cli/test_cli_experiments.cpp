// Command-line tests of `inim fig11` and `inim study`: they run the built binary. fig11 at a
// small size writes the views, the contact sheet and metrics whose values are in their ranges;
// a quick study writes its report and data; bad settings name their flags.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "cli/cli_helpers.h"
#include "core/image.h"
#include "scratch_dir.h"

namespace fs = std::filesystem;

namespace {
ScratchDir scratchFolder("test_cli_experiments");
std::string path(const std::string& name) { return scratchFolder.path(name); }
}  // namespace

TEST(CliFig11, SmallRunWritesViewsAndMetricsInRange) {
  const std::string out = path("fig11");
  const CliResult r = runInim("fig11 --out " + out + " --width 96 --spp 1 --reference-spp 1 --eia-spp 1");
  ASSERT_EQ(r.status, 0) << r.output;
  for (const char* f : {"eia.exr", "eia.png", "contact_sheet.png", "metrics.json", "metrics.csv"})
    EXPECT_TRUE(fs::exists(fs::path(out) / f)) << f;
  std::ifstream in(fs::path(out) / "metrics.json");
  const nlohmann::json m = nlohmann::json::parse(in);
  for (const char* pose : {"centre", "left", "right", "top", "bottom"}) {
    SCOPED_TRACE(pose);
    ASSERT_TRUE(m.contains(pose));
    EXPECT_TRUE(fs::exists(fs::path(out) / ("view_" + std::string(pose) + ".exr")));
    EXPECT_TRUE(fs::exists(fs::path(out) / ("reference_" + std::string(pose) + ".png")));
    const auto& v = m[pose];
    // The reconstruction is not the reference (a display loses resolution), so PSNR is finite.
    const double psnr = v.at("psnr_db").get<double>();
    EXPECT_TRUE(std::isfinite(psnr) && psnr > 0.0 && psnr < 100.0) << psnr;
    const double ssim = v.at("ssim").get<double>();
    EXPECT_TRUE(ssim >= -1.0 && ssim <= 1.0) << ssim;
    const double deMean = v.at("de2000_mean").get<double>(), deP95 = v.at("de2000_p95").get<double>();
    EXPECT_GE(deMean, 0.0);
    EXPECT_GE(deP95, 0.0);
    EXPECT_TRUE(std::isfinite(deMean) && std::isfinite(deP95));
  }
  // The side views are turned by the angle, the centre is not.
  EXPECT_EQ(m["centre"]["rot_h_deg"].get<double>(), 0.0);
  EXPECT_EQ(m["left"]["rot_h_deg"].get<double>(), -7.0);
  EXPECT_EQ(m["top"]["rot_v_deg"].get<double>(), 7.0);
  EXPECT_EQ(m["calibration"], "none");
}

// With a calibration that halves the drive, the EIA's brightest drive is 0.5 where auto
// exposure puts full drive (1) without one; metrics.json and the printout name the file.
TEST(CliFig11, CalibrationReachesTheEiaAndIsRecorded) {
  const std::string out = path("fig11_cal"), lut = writeScalingCube(path("half.cube"), 0.5);
  const CliResult r =
      runInim("fig11 --out " + out + " --width 48 --spp 1 --reference-spp 1 --eia-spp 1 --calibration " + lut);
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("calibration: " + lut), std::string::npos) << r.output;
  std::ifstream in(fs::path(out) / "metrics.json");
  const nlohmann::json m = nlohmann::json::parse(in);
  EXPECT_EQ(m["calibration"], lut);
  const inim::Image eia = inim::readImage((fs::path(out) / "eia.exr").string());
  float brightest = 0.0f;
  for (float v : eia.data) brightest = std::max(brightest, v);
  EXPECT_NEAR(brightest, 0.5f, 1e-6f);
}

TEST(CliFig11, BadSettingsNameTheirFlags) {
  const std::string out = path("fig11_bad");
  expectBadInputWith(runInim, "fig11 --out " + out + " --spp 0", {"--spp", "0"}, {out + "/metrics.json"});
  expectBadInputWith(runInim, "fig11 --out " + out + " --reference-spp 0", {"--reference-spp"}, {out + "/metrics.json"});
  expectBadInputWith(runInim, "fig11 --out " + out + " --width 0", {"--width"}, {out + "/metrics.json"});
  expectBadInputWith(runInim, "fig11 --out " + out + " --angle 75", {"--angle", "75"}, {out + "/metrics.json"});
  expectBadInputWith(runInim, "fig11 --out " + out + " --field " + path("scene.txt"), {"--field", "scene.txt"},
                     {out + "/metrics.json"});
  expectBadInputWith(runInim, "fig11 --out " + out + " --calibration " + path("lut.png"), {"--calibration", "lut.png"},
                     {out + "/metrics.json"});
  expectBadInputWith(runInim, "fig11 --out " + out + " --calibration " + path("missing.cube"),
                     {"--calibration", "missing.cube", "readable"}, {out + "/metrics.json"});
  const std::string nan = path("nan.cube");
  writeText(nan, "LUT_3D_SIZE 2\n0 0 0\n1 0 0\n0 1 0\n1 1 0\n0 0 1\n1 0 1\n0 nan 1\n1 1 1\n");
  expectBadInputWith(runInim, "fig11 --out " + out + " --calibration " + nan, {nan, "line 8", "nan", "finite"},
                     {out + "/metrics.json"});
}

namespace {

// One pose at a small size: a calibration run of seconds.
std::string smallCalibration(const std::string& out) {
  return "calibrate --out " + out +
         " --poses centre --width 64 --holdout 20 --holdout-out-of-gamut 5 --lut-size 9 --direct-checks 0";
}

}  // namespace

TEST(CliCalibrate, SmallRunExportsTheCorrectionThatEiaReads) {
  const std::string out = path("calibrate");
  const CliResult r = runInim(smallCalibration(out));
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("hold-out in gamut"), std::string::npos) << r.output;
  for (const char* f : {"panel_correction.cube", "panel_correction.clf", "panel_correction.ocio", "calibration.json",
                        "stages.csv", "verification.csv"})
    EXPECT_TRUE(fs::exists(fs::path(out) / f)) << f;
  // The hold-out colours meet the verification grade after calibration, and never get worse
  // than a 3D LUT's interpolation allows.
  std::ifstream in(fs::path(out) / "calibration.json");
  const nlohmann::json j = nlohmann::json::parse(in);
  const nlohmann::json& h = j.at("holdout").at("in_gamut");
  EXPECT_LE(h.at("de2000_mean_after").get<double>(), 1.0);
  EXPECT_LE(h.at("de2000_max_after").get<double>(), 3.0);
  EXPECT_LE(h.at("de2000_mean_after").get<double>(), h.at("de2000_mean_before").get<double>() + 0.05);
  EXPECT_TRUE(j.at("grade").at("pass").get<bool>());  // the default grade, 1 and 3: exit status 0 above
  // inim eia reads the exported table and says so.
  const std::string display = path("calibrate_display.json");
  writeText(display, smallDisplayJson(11, 9, 9));
  const std::string cube = (fs::path(out) / "panel_correction.cube").string();
  const CliResult e = runInim("eia --display " + display + " --calibration " + cube + " --out " + path("cal_eia.exr"));
  ASSERT_EQ(e.status, 0) << e.output;
  EXPECT_NE(e.output.find("calibration: " + cube + " (3D LUT, 9 nodes per axis"), std::string::npos) << e.output;
}

// A calibration that misses its grade still writes everything, says which poses failed, and
// exits 3 (not bad input's 2); the grade is in calibration.json.
TEST(CliCalibrate, AMissedGradeExitsThreeWithItsOutputsWritten) {
  const std::string out = path("calibrate_grade");
  const CliResult r = runInim(smallCalibration(out) + " --grade 0.0001,0.0002");
  EXPECT_EQ(r.status, 3) << r.output;
  EXPECT_NE(r.output.find("inim: grade failed: the calibration misses its grade at centre"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("centre FAIL"), std::string::npos) << r.output;
  std::ifstream in(fs::path(out) / "calibration.json");
  const nlohmann::json j = nlohmann::json::parse(in);
  EXPECT_FALSE(j.at("grade").at("pass").get<bool>());
  EXPECT_DOUBLE_EQ(j.at("grade").at("de2000_mean_at_most").get<double>(), 0.0001);
  EXPECT_TRUE(fs::exists(fs::path(out) / "panel_correction.cube"));
  expectBadInputWith(runInim, "calibrate --out " + path("calibrate_grade_bad") + " --grade 3,1", {"--grade", "3,1"},
                     {path("calibrate_grade_bad") + "/calibration.json"});
}

TEST(CliCalibrate, BadSettingsNameTheirFlagsAndWriteNothing) {
  const std::string out = path("calibrate_bad");
  const std::string json = out + "/calibration.json";
  expectBadInputWith(runInim, "calibrate --out " + out + " --poses centre,sideways", {"--poses", "sideways"}, {json});
  expectBadInputWith(runInim, "calibrate --out " + out + " --field-space rec9999", {"--field-space", "rec9999"},
                     {json});
  expectBadInputWith(runInim, "calibrate --out " + out + " --angle 95", {"--angle", "95"}, {json});
  expectBadInputWith(runInim, "calibrate --out " + out + " --correction spline", {"--correction", "spline"}, {json});
  expectBadInputWith(runInim, "calibrate --out " + out + " --grid-levels 1", {"--grid-levels", "1"}, {json});
  const std::string csv = path("patches_wrong.csv");
  writeText(csv, "name,R,G,B\nred,1,0,0\n");
  expectBadInputWith(runInim, "calibrate --out " + out + " --patches " + csv, {csv, "name,X,Y,Z"}, {json});
}

TEST(CliStudy, QuickStudyWritesReportAndData) {
  const std::string out = path("flip_onset");
  const CliResult r = runInim("study flip-onset --quick --out " + out);
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("flip-onset: PASS"), std::string::npos) << r.output;
  EXPECT_TRUE(fs::exists(fs::path(out) / "report.md"));
  EXPECT_GT(fs::file_size(fs::path(out) / "report.md"), 0u);
  EXPECT_TRUE(fs::exists(fs::path(out) / "flip_onset.csv"));
  EXPECT_TRUE(fs::exists(fs::path(out) / "flip_onset.png"));
}

TEST(CliStudy, UnknownStudyIsBadInput) {
  const CliResult r = runInim("study no-such-study --quick --out " + path("none"));
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_FALSE(fs::exists(path("none")));
}

// The Fig. 11 set on the prototype's panel and EI grid behind a compound stack (two PMMA lens
// arrays, caps facing): every pose is reconstructed through both arrays and scored.
TEST(CliFig11, ACompoundStackDisplayRunsTheSet) {
  const std::string display = path("compound.json");
  std::ofstream(display) << R"json({"name": "double MLA (test)", "panel": "sony-xperia-1-ii", "generation_gap_mm": 3.3,
    "ei_px": 25, "ei_count": [153, 65],
    "stack": {"layers": [{"type": "gap", "thickness_mm": 3},
      {"type": "lens_array", "pitch_mm": 1.0, "material": "PMMA", "thickness_mm": 1.5, "front": {"radius_mm": -1.62}},
      {"type": "gap", "thickness_mm": 1},
      {"type": "lens_array", "pitch_mm": 1.0, "material": "PMMA", "thickness_mm": 1.5, "back": {"radius_mm": 1.62}}]}})json";
  const std::string out = path("fig11_compound");
  const CliResult r =
      runInim("fig11 --display " + display + " --out " + out + " --width 48 --spp 1 --reference-spp 1 --eia-spp 1");
  ASSERT_EQ(r.status, 0) << r.output;
  std::ifstream in(fs::path(out) / "metrics.json");
  const nlohmann::json m = nlohmann::json::parse(in);
  for (const char* pose : {"centre", "left", "right", "top", "bottom"}) {
    const double psnr = m.at(pose).at("psnr_db").get<double>();
    EXPECT_TRUE(std::isfinite(psnr) && psnr > 0.0 && psnr < 100.0) << pose << ": " << psnr;
  }
}
