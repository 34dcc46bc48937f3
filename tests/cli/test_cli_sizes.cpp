// Sizes beyond the memory budget (core/size_budget.h), and values that passed some commands and
// not others. Each case once ended in std::bad_alloc (exit 1), a machine that swapped, a black
// image or exit 0; now: exit status 2, one message naming the file or setting (and, for sizes,
// the limit), nothing written.
//
// The size cases run under a 6 GiB address-space limit (ulimit -v), so an allocation made before
// the check fails at once, as it did before the budget, instead of being slow and passing.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "cli/cli_helpers.h"
#include "cli/run_cli.h"
#include "core/image.h"
#include "scratch_dir.h"

namespace fs = std::filesystem;
using namespace inim;

namespace {

ScratchDir scratchFolder("test_cli_sizes");
std::string path(const std::string& name) { return scratchFolder.path(name); }

CliResult runLimited(const std::string& args) {
  return runInimBinary("ulimit -v 6291456; " + std::string(INIM_BINARY), args);
}

void expectBadInput(const std::string& args, std::initializer_list<std::string> needles,
                    std::initializer_list<std::string> outputs) {
  expectBadInputWith(runLimited, args, needles, outputs);
}

std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

std::string writeDisplay(const std::string& name, const std::string& json) {
  const std::string file = path(name);
  writeText(file, json);
  return file;
}

const std::string kScene = "scenes/test/point-sphere.json";

}  // namespace

// ---------------------------------------------------------------- sizes

TEST(CliSizes, BillionEisAreRefusedBeforeAnyPerEiArray) {
  const std::string d = writeDisplay("billion.json", replaced(smallDisplayJson(4, 3, 5), "\"ei_count\": [4, 3]",
                                                              "\"ei_count\": [1000000000, 1]"));
  expectBadInput("display info " + d, {"billion.json", "ei_count", "1000000000", "panel"}, {});
}

TEST(CliSizes, HexDisplayWithSixteenMillionEisNamesTheMemoryLimit) {
  // 1300 x 1300 hex EIs of 25 px on a 32768 x 32768 px panel (the largest the settings table
  // allows): the EIA fits, but its pixel map (12 bytes a pixel, ~12 GB) does not fit a 4 GiB limit.
  std::string json = smallDisplayJson(1300, 1300, 25, 3.0, 2.5, 32768, 32768);
  json = replaced(json, "\"material\": \"PMMA\"", "\"material\": \"PMMA\", \"lattice\": \"hex\"");
  const std::string d = writeDisplay("hex16m.json", json);
  expectBadInput("display info --max-memory 4G " + d, {"hex16m.json", "ei_count", "GiB", "--max-memory"}, {});
}

TEST(CliSizes, RenderSizesBeyondTheBudgetAreRefused) {
  const std::string out = path("render.exr"), scene = data(kScene);
  const std::string base = "render --scene " + scene + " --out " + out;
  expectBadInput(base + " --width 65536 --height 8", {"--width", "65536", "[1, 32768]"}, {out, path("render.png")});
  expectBadInput(base + " --width 32768 --height 32768", {"--width/--height", "32768 x 32768", "--max-memory"},
                 {out, path("render.png")});
  expectBadInput(base + " --width 8 --height 8 --spp 2147483647", {"--spp", "2.14748e+09"}, {out, path("render.png")});
  // The limit is the user's: a 64 x 64 image of 5 floats (80 KiB) is refused under 64K, before
  // or after the command name.
  expectBadInput("--max-memory 64K " + base + " --width 64 --height 64 --spp 1", {"--width/--height", "64 KiB"},
                 {out});
  expectBadInput(base + " --width 64 --height 64 --spp 1 --max-memory 64K", {"--width/--height", "64 KiB"}, {out});
  expectBadInput(base + " --width 8 --height 8 --max-memory lots", {"--max-memory", "lots"}, {out});
  const CliResult ok = runLimited("--max-memory 1M " + base + " --width 8 --height 8 --spp 1");
  EXPECT_EQ(ok.status, 0) << ok.output;
  EXPECT_TRUE(fs::exists(out));
}

TEST(CliSizes, ViewWidthBeyondTheBudgetIsRefused) {
  const std::string eia = path("eia.exr"), out = path("view.exr");
  writeImage(Image(3840, 1644, {"R", "G", "B"}), eia);
  expectBadInput("view --eia " + eia + " --width 100000 --out " + out, {"--width", "100000", "[1, 32768]"}, {out});
  expectBadInput("view --eia " + eia + " --width 32768 --max-memory 1G --out " + out,
                 {"--width/--height", "32768", "--max-memory"}, {out});
}

TEST(CliSizes, NpyShapeBeyondTheFileOrTheBudgetIsRefused) {
  auto writeNpy = [](const std::string& name, const std::string& shape, size_t dataBytes) {
    std::string header = "{'descr': '<f4', 'fortran_order': False, 'shape': " + shape + ", }";
    header.append(64 - (10 + header.size() + 1) % 64, ' ');
    header += '\n';
    std::ofstream f(path(name), std::ios::binary);
    f.write("\x93NUMPY\x01\x00", 8);
    const uint16_t len = uint16_t(header.size());
    f.write(reinterpret_cast<const char*>(&len), 2);
    f << header << std::string(dataBytes, '\0');
    return path(name);
  };
  const std::string out = path("colors.npy");
  const std::string base = "query --field " + data(kScene) + " --out " + out + " --rays ";
  expectBadInput(base + writeNpy("huge.npy", "(1000000000000, 3)", 96), {"huge.npy", "data", "(1000000000000, 3)"},
                 {out});
  expectBadInput(base + writeNpy("negative.npy", "(25000, -3)", 25000 * 12), {"negative.npy", "shape", "-3"}, {out});
  expectBadInput("--max-memory 4K " + base + writeNpy("big.npy", "(1000, 8)", 32000),
                 {"big.npy", "shape", "--max-memory"}, {out});
}

// ---------------------------------------------------------------- values

TEST(CliSizes, UnknownLensOrCoverGlassMaterialIsRefusedByEveryCommand) {
  const std::string mla = writeDisplay("mla.json", replaced(smallDisplayJson(4, 3, 5), "\"PMMA\"", "\"Unobtainium\""));
  const std::string glass = writeDisplay(
      "glass.json", replaced(smallDisplayJson(4, 3, 5), "\"peak_luminance_cd_m2\": 500",
                             "\"peak_luminance_cd_m2\": 500, \"cover_glass\": {\"thickness_mm\": 0.5, \"material\": "
                             "\"Unobtainium\"}"));
  const std::string eia = path("m-eia.exr"), rays = path("m-rays.txt");
  for (const auto& [d, key] : {std::pair{mla, "'mla.material'"}, {glass, "'panel.cover_glass.material'"}}) {
    const std::string name = fs::path(d).filename().string();
    expectBadInput("display info " + d, {name, key, "Unobtainium"}, {});
    expectBadInput("eia --display " + d + " --scene " + data(kScene) + " --out " + eia, {name, key}, {eia});
    expectBadInput("rays --display " + d + " --out " + rays, {name, key}, {rays});
    const CliResult r = runInim("rays --display " + d + " --out " + rays);
    EXPECT_EQ(r.output.find("materials.json"), std::string::npos) << "blames the catalog: " << r.output;
  }
}

TEST(CliSizes, MissingPrimarySpectrumIsNamedAtDisplayLoad) {
  const std::string panel = path("csv-panel.json");
  writeText(panel, R"({"name": "panel with a missing spectrum", "resolution_px": [26, 21], "pixel_pitch_mm": 0.1,
    "primaries": {"R": {"csv": {"file": "no-such-red.csv"}},
                  "G": {"gaussian": {"mean_nm": 530, "fwhm_nm": 35}},
                  "B": {"gaussian": {"mean_nm": 460, "fwhm_nm": 30}}},
    "peak_luminance_cd_m2": 500})");
  std::string json = smallDisplayJson(4, 3, 5);
  const size_t b = json.find("{\"name\": \"test panel\""), e = json.find("},\n  \"mla\"");
  ASSERT_NE(b, std::string::npos);
  ASSERT_NE(e, std::string::npos);
  json.replace(b, e + 1 - b, "\"" + panel + "\"");
  const std::string d = writeDisplay("csv-display.json", json);
  const std::string eia = path("csv-eia.exr");
  expectBadInput("display info " + d, {"csv-panel.json", "primaries.R.csv.file", "no-such-red.csv"}, {});
  const CliResult r = runLimited("eia --display " + d + " --scene " + data(kScene) + " --out " + eia);
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find("primaries.R.csv.file"), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find("--triad-wavelengths"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(eia));
}

TEST(CliSizes, RenderFocusDepthAndThreadsOutOfRangeAreRefused) {
  const std::string out = path("r.exr");
  const std::string base = "render --scene " + data(kScene) + " --out " + out + " --width 8 --height 8 --spp 1";
  for (const char* focus : {"0", "-5", "nan", "inf"})
    expectBadInput(base + " --aperture 2 --focus " + std::string(focus), {"--focus"}, {out});
  expectBadInput(base + " --max-depth -1", {"--max-depth", "-1"}, {out});
  expectBadInput(base + " --threads -1", {"--threads", "-1"}, {out});
  const CliResult ok = runInim(base + " --aperture 2 --focus 300 --max-depth 0 --threads 1");
  EXPECT_EQ(ok.status, 0) << ok.output;
}

TEST(CliSizes, DatasetPrincipalPointFarOutsideTheImageIsRefused) {
  const std::string dir = path("cx-dataset"), model = path("cx.inimrf");
  fs::create_directories(dir);
  writeImage(Image(8, 6, {"R", "G", "B"}), dir + "/a.png");
  const std::string frame = R"({"file_path": "a.png", "transform_matrix": [[1,0,0,0],[0,1,0,0],[0,0,1,4],[0,0,0,1]]})";
  for (const auto& [key, value] : {std::pair{"cx", "1e30"}, {"cy", "-20"}, {"cx", "12.5"}}) {
    writeText(dir + "/transforms.json", std::string(R"({"fl_x": 10, ")") + key + "\": " + value +
                                            R"(, "frames": [)" + frame + "]}");
    expectBadInput("train --data " + dir + " --out " + model, {"transforms.json", key}, {model});
  }
}

TEST(CliSizes, CorruptPngGivesInimsMessageOnly) {
  // A valid 4 x 4 PNG, then the same with its compressed data damaged.
  const std::string good = path("good.png"), bad = path("bad.png");
  writeImage(Image(4, 4, {"R", "G", "B"}), good);
  std::ifstream in(good, std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const size_t idat = bytes.find("IDAT");
  ASSERT_NE(idat, std::string::npos);
  bytes[idat + 6] = char(bytes[idat + 6] ^ 0x55);
  bytes[idat + 7] = char(bytes[idat + 7] ^ 0x55);
  writeText(bad, bytes);
  const CliResult r = runInim("compare " + good + " " + bad);
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_EQ(r.output.rfind("inim: error: " + bad, 0), 0u) << "something before inim's message:\n" << r.output;
  EXPECT_EQ(r.output.find("libpng"), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find('\n'), r.output.size() - 1) << "not one line:\n" << r.output;
}

TEST(CliSizes, ViewSaysHowManyDriveValuesItClamps) {
  const std::string eia = path("clamped-eia.exr"), out = path("clamped-view.exr");
  Image e(3840, 1644, {"R", "G", "B"});
  e.at(0, 0, 0) = -0.5f;  // below black
  e.at(10, 20, 1) = 7.0f;  // far above white
  e.at(11, 20, 2) = 1.0f;  // white: shown as it is
  writeImage(e, eia);
  const CliResult r = runInim("view --eia " + eia + " --width 32 --spp 1 --quiet --out " + out);
  EXPECT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("inim: warning: " + eia + ": 2 of 18938880 drive values are outside [0, 1] (from -0.5 to 7)"),
            std::string::npos)
      << r.output;
  const size_t first = r.output.find("drive values");
  EXPECT_EQ(r.output.find("drive values", first + 1), std::string::npos) << "warned more than once:\n" << r.output;
  // In range: no warning.
  writeImage(Image(3840, 1644, {"R", "G", "B"}), eia);
  const CliResult quiet = runInim("view --eia " + eia + " --width 32 --spp 1 --quiet --out " + out);
  EXPECT_EQ(quiet.status, 0) << quiet.output;
  EXPECT_EQ(quiet.output.find("drive values"), std::string::npos) << quiet.output;
}
