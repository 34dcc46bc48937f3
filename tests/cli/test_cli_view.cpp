// Command-line tests of `inim view` and `inim reference`: outputs (EXR + PNG), determinism over
// thread counts, the out-of-view warning, and bad input (exit status 2, a message naming the
// file / key / sizes, no output left behind).
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>

#include "cli/cli_helpers.h"
#include "cli/run_cli.h"
#include "core/image.h"

#include "scratch_dir.h"

namespace fs = std::filesystem;
using namespace inim;

namespace {

ScratchDir scratchFolder("test_cli_view");
std::string path(const std::string& name) { return scratchFolder.path(name); }


// 12 x 8 EIs of 10 px (0.1 mm pixels), 1.0 mm lenslets, f = 3 mm, viewed at g = 3.5 mm; panel with a
// 3 px border: 126 x 86 px.
constexpr int kPanelW = 126, kPanelH = 86;
std::string smallDisplay() {
  static std::string file = [] {
    std::string f = path("small.json");
    writeText(f, R"({"name": "small view test display",
  "panel": {"name": "test panel", "resolution_px": [126, 86], "pixel_pitch_mm": 0.1,
            "primaries": {"R": {"gaussian": {"mean_nm": 625, "fwhm_nm": 35}},
                          "G": {"gaussian": {"mean_nm": 530, "fwhm_nm": 35}},
                          "B": {"gaussian": {"mean_nm": 460, "fwhm_nm": 30}}},
            "peak_luminance_cd_m2": 500},
  "mla": {"name": "test mla", "pitch_mm": 1.0, "focal_length_mm": 3.0, "substrate_thickness_mm": 1.0,
          "material": "PMMA"},
  "generation_gap_mm": 3.0, "reconstruction_gap_mm": 3.5, "ei_px": 10, "ei_count": [12, 8]})");
    return f;
  }();
  return file;
}

// A panel-sized EIA with a pattern (and one NaN when asked).
std::string eiaFile(const std::string& name, int w = kPanelW, int h = kPanelH, bool nan = false) {
  Image img(w, h, {"R", "G", "B"});
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int c = 0; c < 3; ++c) img.at(x, y, c) = float(((x / 3 + y / 2 + c) % 4) / 3.0);
  if (nan) img.at(w / 2, h / 3, 1) = std::numeric_limits<float>::quiet_NaN();
  std::string f = path(name);
  writeImage(img, f);
  return f;
}

// The camera 40 mm from the small display, thin-lens or pinhole stand-ins, a small image.
std::string cameraArgs(const std::string& model = "pinhole") {
  return " --camera-model " + model + " --distance-mm 40 --width 64 --spp 4 --quiet";
}

void expectBadInput(const std::string& args, std::initializer_list<std::string> needles,
                    std::initializer_list<std::string> outputs) {
  expectBadInputWith([](const std::string& a) { return runInim(a); }, args, needles, outputs);
}

}  // namespace

TEST(CliView, WritesExrAndPng) {
  const std::string eia = eiaFile("eia.exr"), out = path("view.exr");
  CliResult r = runInim("view --display " + smallDisplay() + " --eia " + eia + " --out " + out +
                        " --camera-model thin-lens --distance-mm 40 --width 64 --spp 4");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("exposure"), std::string::npos) << r.output;
  ASSERT_TRUE(fs::exists(out));
  EXPECT_TRUE(fs::exists(path("view.png")));
  Image img = readImage(out);
  EXPECT_EQ(img.width, 64);
  EXPECT_EQ(img.height, 48);  // the sensor's 4:3 aspect
  double sum = 0.0;
  for (float v : img.data) sum += v;
  EXPECT_GT(sum, 0.0);
}

TEST(CliView, IdealMlaRealLensAndPng) {
  const std::string eia = eiaFile("eia_png_src.exr"), out = path("view_ideal.exr"), png = path("custom.png");
  CliResult r = runInim("view --display " + smallDisplay() + " --eia " + eia + " --out " + out + " --png " + png +
                        " --mla ideal --camera-model real-lens --distance-mm 40 --width 32 --spp 2 --exposure 0.01");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_TRUE(fs::exists(out));
  EXPECT_TRUE(fs::exists(png));
  EXPECT_NE(r.output.find("ideal"), std::string::npos) << r.output;
}

TEST(CliView, SameImageOnOneAndTwoThreads) {
  const std::string eia = eiaFile("eia_det.exr"), a = path("det1.exr"), b = path("det2.exr");
  ASSERT_EQ(runInim("view --display " + smallDisplay() + " --eia " + eia + " --out " + a + cameraArgs() +
                    " --threads 1 --seed 7 --exposure 1").status, 0);
  ASSERT_EQ(runInim("view --display " + smallDisplay() + " --eia " + eia + " --out " + b + cameraArgs() +
                    " --threads 2 --seed 7 --exposure 1").status, 0);
  Image ia = readImage(a), ib = readImage(b);
  ASSERT_EQ(ia.data.size(), ib.data.size());
  EXPECT_EQ(std::memcmp(ia.data.data(), ib.data.data(), ia.data.size() * sizeof(float)), 0);
}

TEST(CliView, OutOfViewPoseWarnsAndWrites) {
  const std::string eia = eiaFile("eia_oov.exr"), out = path("oov.exr");
  CliResult r = runInim("view --display " + smallDisplay() + " --eia " + eia + " --out " + out + cameraArgs() +
                        " --rot-h-deg 120");
  EXPECT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("warning"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("out of the camera's view"), std::string::npos) << r.output;
  EXPECT_TRUE(fs::exists(out));
  EXPECT_TRUE(fs::exists(path("oov.png")));
}

TEST(CliView, EiaResolutionMismatchIsBadInput) {
  const std::string eia = eiaFile("eia_wrong.exr", 100, 60), out = path("wrong.exr");
  expectBadInput("view --display " + smallDisplay() + " --eia " + eia + " --out " + out + cameraArgs(),
                 {eia, "resolution", "100 x 60 px", "126 x 86 px"}, {out, path("wrong.png")});
}

TEST(CliView, NanInEiaIsBadInput) {
  const std::string eia = eiaFile("eia_nan.exr", kPanelW, kPanelH, true), out = path("nan.exr");
  expectBadInput("view --display " + smallDisplay() + " --eia " + eia + " --out " + out + cameraArgs(),
                 {eia, "NaN"}, {out, path("nan.png")});
}

TEST(CliView, BadOptionsAreBadInput) {
  const std::string eia = eiaFile("eia_opts.exr"), out = path("opts.exr");
  const std::string base = "view --display " + smallDisplay() + " --eia " + eia + " --camera-model pinhole --width 16 ";
  expectBadInput(base + "--out " + out + " --spp 0", {"--spp"}, {out});
  expectBadInput(base + "--out " + path("opts.png"), {"--out", ".exr"}, {path("opts.png")});
  expectBadInput(base + "--out " + out + " --exposure bright", {"--exposure", "auto"}, {out});
  expectBadInput(base + "--out " + out + " --distance-mm -5", {"--distance-mm"}, {out});
  expectBadInput(base + "--out " + out + " --focus-mm -1", {"--focus-mm"}, {out});
  expectBadInput("view --display " + smallDisplay() + " --eia " + path("missing.exr") + " --out " + out,
                 {"missing.exr"}, {out});
  expectBadInput(base + "--out " + out + " --camera no-such-camera", {"no-such-camera"}, {out});
}

// `inim view --reference`: the comparison's outputs beside --out; an EIA without the exposure in
// its header needs --eia-exposure; bad rung names list the valid ones; nothing is left behind.
TEST(CliView, ReferenceWritesTheComparisonAndTheBudget) {
  const std::string eia = eiaFile("eia_ref.exr"), out = path("ref_view.exr");
  const std::string base = "view --display " + smallDisplay() + " --eia " + eia + cameraArgs() +
                           " --reference --scene " + data("scenes/test/point-sphere.json") + " --reference-spp 2 ";
  const std::vector<std::string> files = {out, path("ref_view_reference.exr"), path("ref_view_error.png"),
                                          path("ref_view_metrics.json"), path("ref_view_budget.json")};
  expectBadInput(base + "--out " + out, {"inim:exposure", "--eia-exposure"}, {out, files[1], files[3]});
  expectBadInput(base + "--out " + out + " --eia-exposure 0.5 --budget-rungs ideal,+sparkle",
                 {"--budget-rungs", "+sparkle", "+real_mla"}, {out, files[1], files[3]});
  expectBadInput(base + "--out " + out + " --eia-exposure 0", {"--eia-exposure"}, {out, files[1]});
  // The reference's own sample count is named when its ray buffer is over the memory budget.
  const std::string bigReference = "view --display " + smallDisplay() + " --eia " + eia + cameraArgs() +
                                   " --reference --scene " + data("scenes/test/point-sphere.json") +
                                   " --eia-exposure 0.5 --max-memory 64M --out " + out;
  expectBadInput(bigReference + " --reference-spp 1048576", {"--reference-spp", "1048576", "memory"},
                 {out, files[1], files[3]});
  expectBadInput(bigReference + " --reference-spp 100000000", {"--reference-spp", "1e+08", "[1, 1048576]"},
                 {out, files[1], files[3]});
  const CliResult r = runInim(base + "--out " + out + " --eia-exposure 0.5 --budget-rungs ideal,+colour_chain");
  ASSERT_EQ(r.status, 0) << r.output;
  for (const std::string& f : files) EXPECT_TRUE(fs::exists(f)) << f;
  std::ifstream metrics(files[3]);
  std::stringstream text;
  text << metrics.rdbuf();
  for (const char* key : {"\"de2000_mean\"", "\"band_limited\"", "\"eia_exposure\": 0.5"})
    EXPECT_NE(text.str().find(key), std::string::npos) << key;
}

TEST(CliReference, PointSphereLandsAtTheImageCentre) {
  const std::string out = path("ref.exr");
  // The test sphere sits at z = -10 mm; move it onto the MLA plane, in front of the camera.
  CliResult r = runInim("reference --scene " + data("scenes/test/point-sphere.json") + " --translate-mm 0,0,10 --display " +
                        smallDisplay() + " --out " + out + " --camera-model pinhole --distance-mm 40 --width 64 --spp 4");
  ASSERT_EQ(r.status, 0) << r.output;
  ASSERT_TRUE(fs::exists(out));
  EXPECT_TRUE(fs::exists(path("ref.png")));
  Image img = readImage(out);
  double sx = 0, sy = 0, sw = 0;
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) {
      const double v = img.at(x, y, 0) + img.at(x, y, 1) + img.at(x, y, 2);
      sx += v * (x + 0.5);
      sy += v * (y + 0.5);
      sw += v;
    }
  ASSERT_GT(sw, 0.0);
  EXPECT_NEAR(sx / sw, 32.0, 0.5);
  EXPECT_NEAR(sy / sw, 24.0, 0.5);
}

TEST(CliReference, BadInput) {
  const std::string out = path("ref_bad.exr");
  expectBadInput("reference --scene " + data("scenes/test/point-sphere.json") + " --scale 0 --out " + out +
                     " --camera-model pinhole --width 16",
                 {"--scale"}, {out});
  expectBadInput("reference --scene " + path("nope.json") + " --out " + out + " --camera-model pinhole --width 16",
                 {"nope.json"}, {out});
  // A parse error (CLI11's message): exit 2, the option and the value named, nothing written.
  const CliResult r = runInim("reference --camera-dispersion sometimes --out " + out + " --width 16");
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find("--camera-dispersion"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("sometimes"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(out));
}

// A display given as a compound stack (two PMMA lens arrays, caps facing): `eia` places its EIs
// on the equivalent MLA and `view` refracts through both arrays.
TEST(CliView, ACompoundStackDisplayRunsEiaAndView) {
  const std::string layers =
      R"({"type": "gap", "thickness_mm": 2.5},
          {"type": "lens_array", "pitch_mm": 0.9, "material": "PMMA", "thickness_mm": 1.0, "front": {"radius_mm": -2.0}},
          {"type": "gap", "thickness_mm": 0.8},
          {"type": "lens_array", "pitch_mm": 0.9, "material": "PMMA", "thickness_mm": 1.0, "back": {"radius_mm": 2.0}})";
  Json j = Json::parse(fixtures::smallDisplayJson());
  j.erase("mla");
  j.erase("reconstruction_gap_mm");
  j["stack"] = Json::parse("{\"layers\": [" + layers + "]}");
  const std::string display = fixtures::scratchFile("compound.json", j.dump(2));
  const std::string eia = path("compound_eia.exr"), out = path("compound_view.exr");
  CliResult r = runInim("eia --quiet --display " + display + " --out " + eia);
  ASSERT_EQ(r.status, 0) << r.output;
  r = runInim("view --display " + display + " --eia " + eia + " --out " + out + cameraArgs());
  ASSERT_EQ(r.status, 0) << r.output;
  const Image view = readImage(out);
  double sum = 0.0;
  for (float v : view.data) sum += v;
  EXPECT_GT(sum, 0.0);  // the scene shows through both arrays
  // Calibration through the chain works through the stack too.
  const std::string cal = path("compound_calibration");
  r = runInim("calibrate --display " + display + " --poses centre --distance-mm 40 --width 48 --out " + cal);
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_TRUE(fs::exists(cal + "/panel_correction.cube"));
}
