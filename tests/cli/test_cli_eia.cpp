// Command-line tests of `inim display info`, `inim rays`, `inim eia` and `inim triads`: they run
// the built binary (INIM_BINARY; the environment variable INIM_TEST_BINARY overrides it).
// Physics end to end with the real analytic scene (a point image lands on the predicted
// pixels), determinism across thread counts, and bad input: exit status 2, a message naming
// the file / key / value, and no output file left behind.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "cli/cli_helpers.h"
#include "cli/run_cli.h"
#include "core/image.h"
#include "core/input_file.h"
#include "display/display.h"
#include "display/ei_layout.h"
#include "rays/pinhole_rays.h"
#include "rays/ray_binary.h"
#include "synthesis/eia_synthesis.h"

#include "scratch_dir.h"

namespace fs = std::filesystem;
using namespace inim;

namespace {

std::string binary() {
  if (const char* b = std::getenv("INIM_TEST_BINARY"); b && *b) return b;
  return INIM_BINARY;
}

ScratchDir scratchFolder("test_cli_eia");
std::string path(const std::string& name) { return scratchFolder.path(name); }

using Result = CliResult;
Result run(const std::string& args) { return runInimBinary(binary(), args); }


std::string smallDisplay() {
  static std::string file = [] {
    std::string f = path("small.json");
    writeText(f, smallDisplayJson(11, 9, 9));
    return f;
  }();
  return file;
}


// Expects a bad-input failure: status 2, the message contains every `needle`, and no file
// of `outputs` exists (nor a temporary beside it).
void expectBadInput(const std::string& args, std::initializer_list<std::string> needles,
                    std::initializer_list<std::string> outputs) {
  expectBadInputWith([](const std::string& a) { return run(a); }, args, needles, outputs);
}

}  // namespace

TEST(CliDisplay, InfoTextAndJson) {
  Result r = run("display info");
  EXPECT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("paper prototype"), std::string::npos);
  EXPECT_NE(r.output.find("18.857"), std::string::npos) << "L = g f / (g - f) at g = 4";
  r = run("display info " + smallDisplay() + " --json");
  EXPECT_EQ(r.status, 0) << r.output;
  Json j = Json::parse(r.output);
  EXPECT_EQ(j["name"], "small test display");
}

TEST(CliRays, TextBinaryAndConversion) {
  std::string txt = path("rays.txt"), bin = path("rays.irays"), back = path("rays_back.irays");
  Result r = run("rays --display " + smallDisplay() + " --out " + txt);
  ASSERT_EQ(r.status, 0) << r.output;
  r = run("rays --display " + smallDisplay() + " --out " + bin);
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_EQ(fs::file_size(bin), kRayBinaryHeaderSize + 24u * 11 * 9 * 81);
  // The paper's macro format (UTF-16LE, CRLF, header) reads back as the same rays.
  std::string macro = path("rays_macro.txt");
  r = run("rays --display " + smallDisplay() + " --zemax-macro --out " + macro);
  ASSERT_EQ(r.status, 0) << r.output;
  r = run("rays --in " + macro + " --out " + back);
  ASSERT_EQ(r.status, 0) << r.output;
  RaySet a = readRayBinary(bin), b = readRayBinary(back);
  ASSERT_EQ(a.size(), b.size());
  for (size_t i = 0; i < a.size(); ++i) ASSERT_NEAR(a.dz[i], b.dz[i], 1e-7f);
  // The macro's single-EI file: the corner direction of a 25 x 25 EI of 0.0395 mm at g = 3 mm.
  std::string ei = path("ei.txt");
  r = run("rays --ei 0,0 --gap-mm 3 --out " + ei);
  ASSERT_EQ(r.status, 0) << r.output;
  std::ifstream in(ei);
  std::string first;
  std::getline(in, first);
  EXPECT_EQ(first, "0.00000000, 0.00000000, 0.00000000, 0.15419750, 0.15419750, 0.97593353");
}

TEST(CliRays, BadInput) {
  std::string out = path("bad_rays.txt");
  expectBadInput("rays --display " + smallDisplay() + " --gap-mm 0 --out " + out, {"--gap-mm", "0"}, {out});
  expectBadInput("rays --display " + smallDisplay() + " --gap-mm -2 --out " + out, {"--gap-mm", "-2"}, {out});
  expectBadInput("rays --display " + smallDisplay() + " --out " + path("rays.bin"), {"--out", "rays.bin"},
                 {path("rays.bin")});
  // Zemax text with a wrong line after the first ray.
  std::string badTxt = path("bad_zemax.txt"), conv = path("bad_conv.irays");
  writeText(badTxt, "header line\n0.1, 0.2, 0.0, 0.0, 0.0, 1.0\n0.1, 0.2, 0.0, oops\n");
  expectBadInput("rays --in " + badTxt + " --out " + conv, {badTxt}, {conv});
  // Binary rays of the wrong size, and with a wrong magic.
  std::string goodBin = path("good.irays"), badBin = path("bad_size.irays");
  ASSERT_EQ(run("rays --display " + smallDisplay() + " --out " + goodBin).status, 0);
  fs::copy_file(goodBin, badBin);
  fs::resize_file(badBin, fs::file_size(goodBin) - 24);
  expectBadInput("rays --in " + badBin + " --out " + path("conv.txt"), {badBin}, {path("conv.txt")});
  std::string badMagic = path("bad_magic.irays");
  writeText(badMagic, std::string(64, 'x'));
  expectBadInput("rays --in " + badMagic + " --out " + path("conv2.txt"), {badMagic}, {path("conv2.txt")});
}

// The real analytic scene: a small emitter (scenes/test/point-sphere.json, placed by the
// command-line placement) lands on the pixel pinhole geometry predicts, in at least 95 % of the
// EIs that see it, behind the MLA (virtual) and in front of it (real); every lit pixel is within
// a pixel or two of the prediction; the depth channel gives its display z; and the output is
// bit-identical on 1 and 2 threads.
class CliPointImage : public ::testing::TestWithParam<double> {};

TEST_P(CliPointImage, OnPredictedPixelsWithAnalyticScene) {
  const double z = GetParam(), scale = 3.0, radius = 0.25 * scale;
  // The file's sphere is at (0, 0, -10): scaled by 3 it is at z = -30; translate to z.
  char place[128];
  std::snprintf(place, sizeof place, " --scale %g --translate-mm 0,0,%g", scale, z + 30.0);
  const std::string tag = z > 0 ? "real" : "virtual";
  std::string out1 = path("point_" + tag + "1.exr"), out2 = path("point_" + tag + "2.exr");
  std::string preview = path("point_" + tag + "_preview.png");
  std::string args = "eia --display " + smallDisplay() + " --scene " + data("scenes/test/point-sphere.json") + place +
                     " --vcp-mm 40 --aovs --exposure 0.05 --quiet";
  Result r = run(args + " --threads 1 --out " + out1 + " --preview " + preview);
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_TRUE(fs::exists(path("point_" + tag + "1.png")));
  EXPECT_TRUE(fs::exists(preview));
  r = run(args + " --threads 2 --out " + out2);
  ASSERT_EQ(r.status, 0) << r.output;
  Image a = readImage(out1), b = readImage(out2);
  ASSERT_EQ(a.data.size(), b.data.size());
  EXPECT_EQ(0, std::memcmp(a.data.data(), b.data.data(), a.data.size() * sizeof(float))) << "thread count changed the EIA";

  Display d = loadDisplay(smallDisplay());
  EiLayout L = computeLayout(d);
  ASSERT_EQ(a.width, L.panelW);
  ASSERT_EQ(a.channels, (std::vector<std::string>{"R", "G", "B", "A", "Z"}));
  const Point3d p(0.0, 0.0, z);
  int seen = 0, lit = 0, depthOk = 0, litFar = 0, litTotal = 0;
  for (int k = 0; k < L.eiCols; ++k)
    for (int l = 0; l < L.eiRows; ++l) {
      auto pred = predictPixelForPoint(L, k, l, p);
      for (int i = 0; i < L.eiW; ++i)
        for (int j = 0; j < L.eiH; ++j) {
          PixelCoord px = eiaPixel(L, {k, l, i, j});
          int x = L.panelCol0 + px.col, y = L.panelRow0 + px.row;
          bool on = a.at(x, y, 0) + a.at(x, y, 1) + a.at(x, y, 2) > 0.0f;
          litTotal += on;
          // Lit: within 2 px of the prediction, or (EIs that see only the emitter's rim, whose
          // centre projects just outside the EI) within 2 px of the EI's border.
          bool nearPred = pred && std::max(std::abs(i - pred->i), std::abs(j - pred->j)) <= 2;
          bool nearBorder = !pred && std::min({i, j, L.eiW - 1 - i, L.eiH - 1 - j}) < 2;
          if (on && !nearPred && !nearBorder) ++litFar;
        }
      if (!pred) continue;
      ++seen;
      PixelCoord px = eiaPixel(L, *pred);
      int x = L.panelCol0 + px.col, y = L.panelRow0 + px.row;
      if (a.at(x, y, 0) + a.at(x, y, 1) + a.at(x, y, 2) > 0.0f) ++lit;
      float Z = a.at(x, y, 4);
      if (a.at(x, y, 3) == 1.0f && Z >= z - 0.01 && Z <= z + radius + 0.01) ++depthOk;
    }
  EXPECT_GE(seen, 20);
  EXPECT_GE(lit, int(std::ceil(0.95 * seen))) << lit << " of " << seen;
  EXPECT_GE(depthOk, int(std::ceil(0.95 * seen)));
  EXPECT_EQ(litFar, 0) << "lit pixels far from the predicted ones";
  std::printf("  emitter at z = %+g mm: predicted pixel lit in %d of %d EIs; %d of %d lit pixels > 2 px away\n", z,
              lit, seen, litFar, litTotal);
}

INSTANTIATE_TEST_SUITE_P(RealAndVirtual, CliPointImage, ::testing::Values(-30.0, 15.0));

TEST(CliEia, SceneBehindVcpWarnsEmptyAndSucceeds) {
  std::string out = path("empty.exr");
  Result r = run("eia --display " + smallDisplay() + " --scene " + data("scenes/test/point-sphere.json") +
                 " --translate-mm 0,0,80 --vcp-mm 50 --out " + out);
  EXPECT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("warning"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("empty"), std::string::npos) << r.output;
  ASSERT_TRUE(fs::exists(out));
  Image img = readImage(out);
  for (float v : img.data) ASSERT_EQ(v, 0.0f);
}

TEST(CliEia, BadInputLeavesNoOutput) {
  const std::string out = path("bad.exr"), png = path("bad.png"), sdf = path("bad.sdf"), pv = path("bad_pv.png");
  const std::string outs = " --out " + out + " --sdf " + sdf + " --preview " + pv;
  const std::string scene = " --scene " + data("scenes/test/point-sphere.json");
  // EI grid larger than the panel.
  std::string big = path("big.json");
  writeText(big, smallDisplayJson(11, 9, 9, 3.0, 0.9, 60, 60));
  expectBadInput("eia --display " + big + scene + outs, {big, "ei_count", "[11, 9]"}, {out, png, sdf, pv});
  // Gap <= 0 and pitch <= 0.
  std::string gap0 = path("gap0.json");
  writeText(gap0, smallDisplayJson(5, 5, 9, 0.0));
  expectBadInput("eia --display " + gap0 + scene + outs, {gap0, "generation_gap_mm", "0"}, {out, png, sdf, pv});
  std::string pitch0 = path("pitch0.json");
  writeText(pitch0, smallDisplayJson(5, 5, 9, 3.0, -1.0));
  expectBadInput("eia --display " + pitch0 + scene + outs, {pitch0, "pitch_mm", "-1"}, {out, png, sdf, pv});
  // Toed-in EIs that would overlap at the given viewing distance.
  // Toed-in EIs that would overlap: lens pitch 0.8 mm < EI width 0.9 mm, EI pitch P (1 + g/D) =
  // 0.808 mm at D = 300 mm.
  std::string narrow = path("narrow_lenses.json");
  writeText(narrow, smallDisplayJson(5, 5, 9, 3.0, 0.8));
  expectBadInput("eia --display " + narrow + scene + " --layout toed-in --viewing-distance-mm 300" + outs,
                 {narrow, "--viewing-distance-mm", "300", "overlap"}, {out, png, sdf, pv});
  expectBadInput("eia --display " + smallDisplay() + scene + " --layout toed-in --viewing-distance-mm 1" + outs,
                 {"ei_count", "toed-in", "fits the panel"}, {out, png, sdf, pv});
  expectBadInput("eia --display " + smallDisplay() + scene + " --layout toed-in --viewing-distance-mm -5" + outs,
                 {"--viewing-distance-mm", "-5"}, {out, png, sdf, pv});
  expectBadInput("eia --display " + smallDisplay() + scene + " --layout diagonal" + outs, {"--layout", "diagonal"},
                 {out, png, sdf, pv});
  // A singular placement: a zero scale is outside the scale's range.
  expectBadInput("eia --display " + smallDisplay() + scene + " --scale 1,0,1" + outs, {"--scale", "1,0,1", "[1e-12, 1e+15]"},
                 {out, png, sdf, pv});
  std::string run0 = path("run_singular.json");
  writeText(run0, R"({"placement": {"scale": 0}})");
  expectBadInput("eia --display " + smallDisplay() + scene + " --run " + run0 + outs, {run0, "placement.scale"},
                 {out, png, sdf, pv});
  std::string runUnknown = path("run_unknown.json");
  writeText(runUnknown, R"({"vcp": 10})");
  expectBadInput("eia --display " + smallDisplay() + scene + " --run " + runUnknown + outs, {runUnknown, "vcp"},
                 {out, png, sdf, pv});
  // Bad settings.
  expectBadInput("eia --display " + smallDisplay() + scene + " --spp 0" + outs, {"--spp", "0"}, {out, png, sdf, pv});
  expectBadInput("eia --display " + smallDisplay() + scene + " --exposure -1" + outs, {"--exposure", "-1"},
                 {out, png, sdf, pv});
  expectBadInput("eia --display " + smallDisplay() + scene + " --gamut wrap" + outs, {"--gamut", "wrap"},
                 {out, png, sdf, pv});
  expectBadInput("eia --display " + smallDisplay() + scene + " --triad-wavelengths 656,566" + outs,
                 {"--triad-wavelengths", "656,566"}, {out, png, sdf, pv});
  expectBadInput("eia --display " + smallDisplay() + scene + " --out " + path("bad.tiff"), {"--out", "bad.tiff"},
                 {path("bad.tiff")});
  // A scene file that does not exist.
  expectBadInput("eia --display " + smallDisplay() + " --scene " + path("nope.json") + outs, {"nope.json"},
                 {out, png, sdf, pv});
}

// --calibration (or a run file's "calibration", relative to the run file) applies the LUT to
// the drive values: an identity LUT leaves the EIA as it is, a halving one halves it; the
// summary names the file.
TEST(CliEia, CalibrationAppliesTheLut) {
  const std::string args = "eia --display " + smallDisplay() + " --scene " + data("scenes/paper-fig7.json") +
                           " --exposure 0.5 --out ";
  const std::string plain = path("cal_plain.exr"), same = path("cal_identity.exr"), half = path("cal_half.exr");
  Result r = run(args + plain);
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("calibration: none"), std::string::npos) << r.output;
  const std::string identity = writeScalingCube(path("identity.cube"), 1.0);
  r = run(args + same + " --calibration " + identity);
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("calibration: " + identity + " (3D LUT, 2 nodes per axis"), std::string::npos) << r.output;
  fs::create_directories(path("luts"));
  writeScalingCube(path("luts/half.cube"), 0.5);
  const std::string runFile = path("run_calibrated.json");
  writeText(runFile, R"({"calibration": "luts/half.cube"})");
  r = run(args + half + " --run " + runFile);
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("calibration: " + path("luts/half.cube")), std::string::npos) << r.output;
  const Image a = readImage(plain), b = readImage(same), c = readImage(half);
  ASSERT_EQ(a.data.size(), b.data.size());
  ASSERT_EQ(a.data.size(), c.data.size());
  EXPECT_TRUE(a.data == b.data);
  double worst = 0.0, brightest = 0.0;
  for (size_t i = 0; i < a.data.size(); ++i) {
    worst = std::max(worst, std::abs(double(c.data[i]) - 0.5 * double(a.data[i])));
    brightest = std::max(brightest, double(a.data[i]));
  }
  EXPECT_LE(worst, 1e-6);
  EXPECT_GT(brightest, 0.2);
}

TEST(CliEia, BadCalibrationLeavesNoOutput) {
  const std::string out = path("badcal.exr"), png = path("badcal.png");
  const std::string args = "eia --display " + smallDisplay() + " --scene " + data("scenes/test/point-sphere.json") +
                           " --out " + out;
  expectBadInput(args + " --calibration " + path("lut.3dl"), {"--calibration", "lut.3dl", ".cube or .clf"}, {out, png});
  expectBadInput(args + " --calibration " + path("missing.clf"), {"--calibration", "missing.clf", "readable"},
                 {out, png});
  const std::string shortCube = path("short.cube");
  writeText(shortCube, "LUT_3D_SIZE 2\n0 0 0\n1 0 0\n");
  expectBadInput(args + " --calibration " + shortCube, {shortCube, "LUT_3D_SIZE", "8 table lines (found 2)"},
                 {out, png});
  const std::string inf = path("inf.clf");
  writeText(inf, R"(<ProcessList compCLFversion="3"><LUT3D interpolation="tetrahedral" inBitDepth="32f" outBitDepth="32f">
<Array dim="2 2 2 3">0 0 0 0 0 1 0 1 0 0 1 1 1 0 0 1 0 1 1 1 0 1 1 inf</Array></LUT3D></ProcessList>)");
  expectBadInput(args + " --calibration " + inf, {inf, "inf", "finite"}, {out, png});
  // A run file's calibration is named with the run file.
  const std::string runFile = path("run_missing_cal.json");
  writeText(runFile, R"({"calibration": "nowhere.cube"})");
  expectBadInput(args + " --run " + runFile, {path("nowhere.cube"), "calibration (" + runFile + ")"}, {out, png});
}

// The measured-OLED display variant loads and reports its assumptions.
TEST(CliDisplay, MeasuredOledVariantLoads) {
  Result r = run("display info " + data("optics/displays/paper-prototype-measured-oled.json"));
  EXPECT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("measured-OLED primaries"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("iPhone 13 Pro"), std::string::npos) << r.output;
}

// The triads of a synthesized EIA, written as SDF and formed again on the detector, give the
// EIA back; Zemax SDF files with a wrong header or size are rejected.
TEST(CliTriads, ExportFormRoundTripAndBadSdf) {
  const std::string eia = path("tri.exr"), sdf = path("tri.sdf"), formed = path("tri_formed.exr");
  Result r = run("eia --display " + smallDisplay() + " --scene " + data("scenes/paper-fig7.json") +
                 " --quiet --out " + eia + " --sdf " + sdf + " --triad-wavelengths paper");
  ASSERT_EQ(r.status, 0) << r.output;
  r = run("triads form --display " + smallDisplay() + " --sdf " + sdf + " --triad-wavelengths 656,566,471 --out " +
          formed);
  ASSERT_EQ(r.status, 0) << r.output;
  Image a = readImage(eia), b = readImage(formed);
  ASSERT_EQ(a.data.size(), b.data.size());
  double maxErr = 0.0;
  for (size_t i = 0; i < a.data.size(); ++i) maxErr = std::max(maxErr, double(std::abs(a.data[i] - b.data[i])));
  EXPECT_LE(maxErr, 1e-6);
  // export from the EXR gives the same file as eia --sdf.
  const std::string sdf2 = path("tri2.sdf");
  r = run("triads export --display " + smallDisplay() + " --eia " + eia + " --triad-wavelengths paper --out " + sdf2);
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_EQ(fs::file_size(sdf2), fs::file_size(sdf));

  // Wrong size (truncated), wrong identifier, wrong ray format.
  const std::string out = path("sdf_bad.exr");
  std::string trunc = path("trunc.sdf");
  fs::copy_file(sdf, trunc);
  fs::resize_file(trunc, fs::file_size(sdf) - 7);
  expectBadInput("triads form --display " + smallDisplay() + " --sdf " + trunc + " --out " + out, {trunc}, {out});
  std::string badId = path("bad_id.sdf");
  fs::copy_file(sdf, badId);
  {
    std::fstream f(badId, std::ios::in | std::ios::out | std::ios::binary);
    int32_t v = 1011;
    f.write(reinterpret_cast<const char*>(&v), 4);
  }
  expectBadInput("triads form --display " + smallDisplay() + " --sdf " + badId + " --out " + out, {badId, "1011"},
                 {out});
  std::string tiny = path("tiny.sdf");
  writeText(tiny, std::string(100, '\0'));
  expectBadInput("triads form --display " + smallDisplay() + " --sdf " + tiny + " --out " + out, {tiny}, {out});
  // An EIA of the wrong size.
  std::string wrongEia = path("wrong.exr");
  writeImage(Image(10, 10, {"R", "G", "B"}), wrongEia);
  expectBadInput("triads export --display " + smallDisplay() + " --eia " + wrongEia + " --out " + path("w.sdf"),
                 {wrongEia, "10 x 10"}, {path("w.sdf")});
}

// A pinhole-array display (a sheet of holes at the gap on the EI pitch, no lens): its EIA from
// each pixel's chief ray traced through the stack (the default for a stack that is not one thin
// lens array) is the pinhole model's EIA. The rays agree to float rounding (1e-7), so every
// pixel agrees to 1e-4 of the brightest; the default is the traced one, byte for byte.
// `--chief-rays` takes pinhole or traced and not --real-lens.
TEST(CliEia, APinholeArrayDisplaysTracedEiaIsThePinholeModels) {
  Json j = Json::parse(smallDisplayJson(11, 9, 9));  // EIs of 0.9 mm on the 0.9 mm lens pitch
  j.erase("mla");
  j.erase("reconstruction_gap_mm");
  j["stack"] = Json::parse(R"({"layers": [{"type": "gap", "thickness_mm": 3.0},
      {"type": "apertures", "pitch_mm": 0.9, "hole_mm": 0.1}]})");
  const std::string display = path("pinhole_sheet.json");
  writeText(display, j.dump(2));
  const std::string scene = "";  // the default scene
  const std::string traced = path("sheet_traced.exr"), pinhole = path("sheet_pinhole.exr"), dflt = path("sheet.exr");
  Result r = run("eia --display " + display + scene + " --chief-rays traced --out " + traced);
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("chief rays traced through the stack"), std::string::npos) << r.output;
  ASSERT_EQ(run("eia --display " + display + scene + " --chief-rays pinhole --out " + pinhole).status, 0);
  ASSERT_EQ(run("eia --display " + display + scene + " --out " + dflt).status, 0);
  const Image a = readImage(traced), b = readImage(pinhole), c = readImage(dflt);
  ASSERT_EQ(a.data.size(), b.data.size());
  float peak = 0.0f, worst = 0.0f;
  size_t differ = 0, lit = 0;
  for (size_t i = 0; i < a.data.size(); ++i) {
    peak = std::max(peak, b.data[i]);
    worst = std::max(worst, std::fabs(a.data[i] - b.data[i]));
    differ += a.data[i] != b.data[i];
    lit += b.data[i] > 0.0f;
  }
  EXPECT_GT(lit, a.data.size() / 20);  // the sphere shows
  EXPECT_LT(worst, 1e-4f * peak);
  EXPECT_GT(differ, 0u);  // rounding does show: the two runs did trace different rays
  EXPECT_EQ(a.data, c.data);

  // `inim rays` writes the same traced rays.
  const std::string raysOut = path("sheet.irays");
  r = run("rays --display " + display + " --chief-rays traced --out " + raysOut);
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("stop stack.layers[1] (holes)"), std::string::npos) << r.output;
  EXPECT_EQ(readRayBinary(raysOut).size(), size_t(11 * 9 * 9 * 9));

  const std::string out = path("sheet_bad.exr");
  expectBadInput("eia --display " + display + scene + " --chief-rays sideways --out " + out,
                 {"--chief-rays", "sideways"}, {out});
  expectBadInput("eia --display " + display + scene + " --chief-rays traced --real-lens --out " + out,
                 {"--chief-rays", "--real-lens"}, {out});
  expectBadInput("eia --display " + smallDisplay() + scene + " --wavelength-nm 500 --out " + out,
                 {"--wavelength-nm", "500"}, {out});
}

// A curved display (the small display's MLA bent into a 300 mm cylinder, centre in front) runs
// from its EIA to a view: traced chief rays by default, the pinhole model's rays through each
// lenslet's principal point with --chief-rays pinhole (different EIAs: the two models differ);
// on a hex lattice too, every pixel with its chief ray.
// Refused before any output: a toed-in layout (the curvature aims the lenslets), a curvature that
// brings the array onto the panel at its edge.
TEST(CliEia, ACurvedDisplayRunsFromEiaToViewAndRefusesWhatItCannot) {
  auto curved = [&](const std::string& name, const std::string& curvature) {
    Json j = Json::parse(smallDisplayJson(11, 9, 9));
    j.erase("mla");
    j.erase("reconstruction_gap_mm");
    j["stack"] = Json::parse(R"({"layers": [{"type": "gap", "thickness_mm": 3.0},
        {"type": "lens_array", "pitch_mm": 0.9, "material": "PMMA", "thickness_mm": 1.0,
         "front": {"radius_mm": -1.5}}], "curvature": )" + curvature + "}");
    const std::string file = path(name);
    writeText(file, j.dump(2));
    return file;
  };
  const std::string display = curved("curved.json", R"({"shape": "cylinder", "radius_mm": 300})");
  const std::string traced = path("curved_traced.exr"), pinhole = path("curved_pinhole.exr");
  Result r = run("eia --display " + display + " --out " + traced);
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("chief rays traced through the stack"), std::string::npos) << r.output;
  r = run("eia --display " + display + " --chief-rays pinhole --out " + pinhole);
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("principal points of a curved array"), std::string::npos) << r.output;
  EXPECT_NE(readImage(traced).data, readImage(pinhole).data);
  const std::string view = path("curved_view.exr");
  r = run("view --display " + display + " --eia " + traced + " --width 96 --out " + view);
  ASSERT_EQ(r.status, 0) << r.output;
  const Image v = readImage(view);
  float peak = 0.0f;
  for (float x : v.data) peak = std::max(peak, x);
  EXPECT_GT(peak, 0.0f);  // the display shows
  // On a hex lattice: EIs by the lenslets' cells projected from the centre.
  Json hex = readJsonFile(display);
  hex["stack"]["layers"][1]["lattice"] = "hex";
  hex["stack"]["layers"][1]["aperture"] = "hex";
  const std::string hexDisplay = path("curved_hex.json"), hexEia = path("curved_hex.exr");
  writeText(hexDisplay, hex.dump(2));
  r = run("eia --display " + hexDisplay + " --out " + hexEia);
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("0 fell back"), std::string::npos) << r.output;

  const std::string out = path("curved_bad.exr");
  expectBadInput("eia --display " + display + " --layout toed-in --viewing-distance-mm 500 --out " + out,
                 {"layout", "toed-in"}, {out});
  expectBadInput("eia --display " + curved("tight.json", R"({"shape": "cylinder", "radius_mm": -6})") + " --out " + out,
                 {"stack.curvature.radius_mm", "-6"}, {out});

}

// The paper's Zemax model beside the SDF: written with it, naming it, as OpticStudio's UTF-16;
// refused without --sdf or with another extension, before any work.
TEST(CliTriads, ZemaxModelBesideTheSdf) {
  const std::string eia = path("nsc.exr"), sdf = path("nsc.sdf"), zmx = path("nsc_model.zmx");
  const std::string args = "eia --display " + smallDisplay() + " --scene " + data("scenes/paper-fig7.json") + " --quiet --out " + eia;
  Result r = run(args + " --sdf " + sdf + " --zemax-model " + zmx);
  ASSERT_EQ(r.status, 0) << r.output;
  const std::string bytes = readInputFile(zmx);
  ASSERT_GE(bytes.size(), 2u);
  EXPECT_EQ(bytes.substr(0, 2), "\xFF\xFE");
  std::string ascii;
  for (size_t i = 2; i < bytes.size(); i += 2) ascii += bytes[i];
  EXPECT_NE(ascii.find("NSOH NSC_SFIL 0 0 nsc.sdf"), std::string::npos);
  EXPECT_NE(ascii.find("NSOH NSC_DETC"), std::string::npos);
  const std::string eia2 = path("nsc2.exr"), zmx2 = path("nsc2.zmx");
  const std::string args2 = "eia --display " + smallDisplay() + " --scene " + data("scenes/paper-fig7.json") + " --quiet --out " + eia2;
  expectBadInput(args2 + " --zemax-model " + zmx2, {"--zemax-model", "--sdf"}, {eia2, zmx2});
  expectBadInput(args2 + " --sdf " + path("nsc2.sdf") + " --zemax-model " + path("nsc2.txt"), {"--zemax-model", ".zmx"},
                 {eia2, path("nsc2.sdf")});
}
