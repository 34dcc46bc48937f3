// `inim compare` and `inim lens info` through the built binary: values agree with the library,
// options work, and bad input (size mismatch, missing file, NaN in an EXR, unknown colour
// space, bad lens options) gives exit status 2 with a message naming the input and no output.
// Also the lens analysis through the library: dgauss.50mm has EFL 50.36 mm (docs/design.md §5.1).
#include <gtest/gtest.h>
#include <unistd.h>

#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <limits>
#include <string>

#include "analysis/metrics.h"
#include "camera/lens_analysis.h"
#include "camera/lens_loader.h"
#include "cli/run_cli.h"
#include "core/image.h"
#include "core/json_config.h"

namespace fs = std::filesystem;
using namespace inim;

namespace {

struct TempDir {
  fs::path path;
  TempDir() {
    path = fs::temp_directory_path() / ("inim_cli_compare_" + std::to_string(::getpid()));
    fs::create_directories(path);
  }
  ~TempDir() { fs::remove_all(path); }
  std::string file(const std::string& name) const { return (path / name).string(); }
};

const TempDir& dir() {
  static TempDir d;
  return d;
}

Image pattern(int w, int h, float offset = 0.0f) {
  Image img(w, h, {"R", "G", "B"});
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int c = 0; c < 3; ++c)
        img.at(x, y, c) = 0.45f + 0.3f * std::sin(0.3f * x + 0.17f * y + c) + offset;
  return img;
}

std::string write(const std::string& name, const Image& img) {
  const std::string f = dir().file(name);
  writeImage(img, f);
  return f;
}

// Parses the JSON printed by a command (the output is the JSON document only).
Json parse(const CliResult& r) {
  try {
    return Json::parse(r.output);
  } catch (const std::exception& e) {
    ADD_FAILURE() << "not JSON: " << r.output;
    return Json();
  }
}

void expectMentions(const CliResult& r, std::initializer_list<std::string> needles) {
  for (const auto& n : needles) EXPECT_NE(r.output.find(n), std::string::npos) << "missing '" << n << "' in: " << r.output;
}

std::string data(const std::string& rel) { return std::string(INIM_SOURCE_DATA_DIR) + "/" + rel; }

}  // namespace

// ---------------------------------------------------------------------------------------
// Lens analysis through the library

TEST(LensInfo, DgaussEflThroughTheLibrary) {
  const LensInfo info = analyzeLens(loadLens(data("optics/lenses/dgauss.50mm.dat")));
  EXPECT_NEAR(info.eflMm, 50.36, 0.005 * 50.36);
  const Json j = lensInfoJson(info);
  EXPECT_NEAR(j["efl_mm"].get<double>(), 50.36, 0.005 * 50.36);
  EXPECT_TRUE(j.contains("bfl_mm"));
}

// ---------------------------------------------------------------------------------------
// inim compare

TEST(CliCompare, IdenticalImages) {
  const std::string a = write("same.exr", pattern(32, 24));
  CliResult r = runInim("compare " + a + " " + a + " --json");
  ASSERT_EQ(r.status, 0) << r.output;
  Json j = parse(r);
  EXPECT_TRUE(j["psnr_db"].is_null());  // infinite
  EXPECT_EQ(j["ssim"].get<double>(), 1.0);
  EXPECT_EQ(j["de2000_mean"].get<double>(), 0.0);
  EXPECT_EQ(j["de2000_p95"].get<double>(), 0.0);
  EXPECT_EQ(j["pixels"].get<int64_t>(), 32 * 24);
  r = runInim("compare " + a + " " + a);
  ASSERT_EQ(r.status, 0) << r.output;
  expectMentions(r, {"PSNR", "inf", "SSIM", "1.000000", "dE2000 mean"});
}

TEST(CliCompare, AgreesWithTheLibrary) {
  const std::string a = write("a.exr", pattern(40, 30)), b = write("b.exr", pattern(40, 30, 0.03f));
  CliResult r = runInim("compare " + a + " " + b + " --json");
  ASSERT_EQ(r.status, 0) << r.output;
  Json j = parse(r);
  const ImageMetrics m = compareImageFiles(a, b);
  EXPECT_NEAR(j["psnr_db"].get<double>(), m.psnrDb, 1e-9);
  EXPECT_NEAR(j["ssim"].get<double>(), m.ssim, 1e-12);
  EXPECT_NEAR(j["de2000_mean"].get<double>(), m.deltaE.mean, 1e-9);
  EXPECT_NEAR(j["de2000_p95"].get<double>(), m.deltaE.p95, 1e-9);
  EXPECT_EQ(j["space_a"], "lin_rec709");
  EXPECT_EQ(j["values"], "encoded");
  EXPECT_GT(j["de2000_mean"].get<double>(), 0.1);

  // Linear values with a peak: PSNR changes by 20 log10(peak) at the same MSE.
  r = runInim("compare " + a + " " + b + " --json --values linear --peak 2");
  ASSERT_EQ(r.status, 0) << r.output;
  CompareOptions lin;
  lin.values = MetricValues::Linear;
  lin.peak = 2.0;
  EXPECT_NEAR(parse(r)["psnr_db"].get<double>(), compareImageFiles(a, b, lin).psnrDb, 1e-9);

  // Declared colour space: both images as sRGB-encoded values.
  r = runInim("compare " + a + " " + b + " --json --space srgb");
  ASSERT_EQ(r.status, 0) << r.output;
  CompareOptions srgb;
  srgb.spaceA = srgb.spaceB = "srgb";
  EXPECT_NEAR(parse(r)["de2000_mean"].get<double>(), compareImageFiles(a, b, srgb).deltaE.mean, 1e-9);
}

TEST(CliCompare, MaskAndDeltaEMap) {
  Image a = pattern(30, 30), b = pattern(30, 30, 0.02f);
  Image mask(30, 30, {"Y"});
  for (int y = 0; y < 30; ++y)
    for (int x = 0; x < 30; ++x) {
      mask.at(x, y, 0) = x < 15 ? 1.0f : 0.0f;
      if (x >= 15) b.at(x, y, 0) = 5.0f;  // a gross error where the mask excludes
    }
  const std::string fa = write("ma.exr", a), fb = write("mb.exr", b), fm = write("mask.png", mask);
  const std::string map = dir().file("de.exr");
  CliResult r = runInim("compare " + fa + " " + fb + " --json --mask " + fm + " --de-map " + map);
  ASSERT_EQ(r.status, 0) << r.output;
  Json j = parse(r);
  EXPECT_EQ(j["pixels"].get<int64_t>(), 15 * 30);
  const PixelMask pm = loadMask(fm);
  const ImageMetrics m = compareImages(a, b, {}, &pm);
  EXPECT_NEAR(j["psnr_db"].get<double>(), m.psnrDb, 1e-9);
  EXPECT_LT(j["de2000_p95"].get<double>(), 10.0);  // the gross error is excluded
  ASSERT_TRUE(fs::exists(map));
  Image de = readImage(map);
  EXPECT_EQ(de.width, 30);
  EXPECT_GT(de.at(20, 10, 0), 10.0f);  // ... but it is in the map
}

TEST(CliCompare, SizeMismatchIsRejected) {
  const std::string a = write("s1.exr", pattern(20, 20)), b = write("s2.exr", pattern(24, 20));
  const std::string map = dir().file("never.exr");
  CliResult r = runInim("compare " + a + " " + b + " --de-map " + map);
  EXPECT_EQ(r.status, 2) << r.output;
  expectMentions(r, {"s1.exr", "s2.exr", "20 x 20", "24 x 20"});
  EXPECT_FALSE(fs::exists(map)) << "partial output";
}

TEST(CliCompare, MissingFileIsRejected) {
  const std::string a = write("present.exr", pattern(20, 20));
  CliResult r = runInim("compare " + a + " " + dir().file("absent.exr"));
  EXPECT_EQ(r.status, 2) << r.output;
  expectMentions(r, {"absent.exr"});
}

TEST(CliCompare, NaNInAnExrIsRejected) {
  Image n = pattern(20, 20);
  n.at(7, 3, 2) = std::numeric_limits<float>::quiet_NaN();
  const std::string a = write("fine.exr", pattern(20, 20)), b = write("nan.exr", n);
  CliResult r = runInim("compare " + a + " " + b + " --json");
  EXPECT_EQ(r.status, 2) << r.output;
  expectMentions(r, {"nan.exr", "NaN"});
  Image inf = pattern(20, 20);
  inf.at(1, 1, 0) = std::numeric_limits<float>::infinity();
  r = runInim("compare " + write("inf.exr", inf) + " " + a);
  EXPECT_EQ(r.status, 2) << r.output;
  expectMentions(r, {"inf.exr", "Inf"});
}

TEST(CliCompare, BadOptionsAreRejected) {
  const std::string a = write("o.exr", pattern(20, 20));
  CliResult r = runInim("compare " + a + " " + a + " --space rec2020");
  EXPECT_EQ(r.status, 2) << r.output;
  expectMentions(r, {"rec2020", "--space"});
  r = runInim("compare " + a + " " + a + " --de-map " + dir().file("de.png"));
  EXPECT_EQ(r.status, 2) << r.output;
  expectMentions(r, {"--de-map", "de.png"});
  EXPECT_FALSE(fs::exists(dir().file("de.png")));
  r = runInim("compare " + a + " " + a + " --values gamma");
  EXPECT_EQ(r.status, 2) << r.output;
  Image rgb = pattern(20, 20);
  r = runInim("compare " + a + " " + a + " --mask " + write("rgbmask.exr", rgb));
  EXPECT_EQ(r.status, 2) << r.output;
  expectMentions(r, {"rgbmask.exr"});
}

// ---------------------------------------------------------------------------------------
// inim lens info

TEST(CliLens, InfoJsonGivesTheEfl) {
  CliResult r = runInim("lens info " + data("optics/lenses/dgauss.50mm.dat") + " --json");
  ASSERT_EQ(r.status, 0) << r.output;
  Json j = parse(r);
  EXPECT_NEAR(j["efl_mm"].get<double>(), 50.36, 0.005 * 50.36);
  EXPECT_TRUE(j.contains("bfl_mm"));
  r = runInim("lens info dgauss.50mm");  // by catalog name, text
  ASSERT_EQ(r.status, 0) << r.output;
  expectMentions(r, {"EFL", "BFL"});
}

TEST(CliLens, ThicknessConventionAndWavelength) {
  // dgauss rewritten with each thickness on the row after it ("before" convention).
  const std::string f = data("optics/lenses/dgauss.50mm.dat");
  std::ifstream in(f);
  std::vector<std::array<double, 4>> rows;
  for (std::string line; std::getline(in, line);) {
    std::istringstream ls(line);
    std::array<double, 4> r{};
    if (line.empty() || line[0] == '#' || !(ls >> r[0] >> r[1] >> r[2] >> r[3])) continue;
    rows.push_back(r);
  }
  ASSERT_EQ(rows.size(), 11u);
  std::ofstream out(dir().file("dgauss_before.dat"));
  out << "# dgauss with thicknesses from the previous surface\n";
  for (size_t i = 0; i < rows.size(); ++i)
    out << rows[i][0] << " " << (i == 0 ? 0.0 : rows[i - 1][1]) << " " << rows[i][2] << " " << rows[i][3] << "\n";
  out.close();

  CliResult ref = runInim("lens info " + f + " --json");
  CliResult before = runInim("lens info " + dir().file("dgauss_before.dat") + " --json --thickness-convention before");
  ASSERT_EQ(ref.status, 0) << ref.output;
  ASSERT_EQ(before.status, 0) << before.output;
  EXPECT_NEAR(parse(before)["efl_mm"].get<double>(), parse(ref)["efl_mm"].get<double>(), 1e-9);
  // Read with the default convention ("after") it is another lens, or an invalid one.
  CliResult after = runInim("lens info " + dir().file("dgauss_before.dat") + " --json --thickness-convention after");
  if (after.status == 0)
    EXPECT_GT(std::abs(parse(after)["efl_mm"].get<double>() - parse(ref)["efl_mm"].get<double>()), 0.1);
  else
    EXPECT_EQ(after.status, 2) << after.output;

  CliResult w = runInim("lens info " + f + " --json --wavelength-nm 486.13");
  ASSERT_EQ(w.status, 0) << w.output;
  EXPECT_NEAR(parse(w)["wavelength_nm"].get<double>(), 486.13, 1e-9);
}

TEST(CliLens, BadInputIsRejected) {
  CliResult r = runInim("lens info " + dir().file("nolens.dat"));
  EXPECT_EQ(r.status, 2) << r.output;
  expectMentions(r, {"nolens.dat"});
  r = runInim("lens info dgauss.50mm --thickness-convention sideways");
  EXPECT_EQ(r.status, 2) << r.output;
  r = runInim("lens info dgauss.50mm --wavelength-nm 2000");
  EXPECT_EQ(r.status, 2) << r.output;
  expectMentions(r, {"--wavelength-nm", "2000"});
}

// A vendor's .zmx lens through the binary: the surfaces as read and the model-glass warning; a
// damaged copy exits 2 naming the file, the line and the value.
TEST(CliLens, ZemaxFilesAndTheirBadCopies) {
  CliResult r = runInim("lens info " + data("tests/data/zmx/ACL3026U.zmx"));
  ASSERT_EQ(r.status, 0) << r.output;
  expectMentions(r, {"EFL", "conic -0.6301", "a4 5.513e-06", "Warning: SURF 2 (line 78): GLAS B270"});
  r = runInim("lens info " + data("tests/data/zmx/AC254-050-A.zmx") + " --json");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NEAR(parse(r)["efl_mm"].get<double>(), 50.0, 0.005 * 50.0);

  std::ifstream in(data("tests/data/zmx/LA1131-A.zmx"), std::ios::binary);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  auto damaged = [&](const std::string& name, const std::string& from, const std::string& to) {
    std::string t = text;
    t.replace(t.find(from), from.size(), to);
    const std::string f = dir().file(name);
    std::ofstream(f, std::ios::binary) << t;
    return f;
  };
  struct Case {
    std::string file;
    std::vector<std::string> mentions;
  };
  const std::vector<Case> cases = {
      {damaged("unit.zmx", "UNIT MM", "UNIT FT"), {"unit.zmx", "line 7: UNIT", "\"FT\""}},
      {damaged("glass.zmx", "GLAS N-BK7 0 0 0 0", "GLAS N-BK99 0 0 0 0"), {"glass.zmx", "GLAS (line 76)", "N-BK99"}},
      {damaged("garbled.zmx", "DISZ 5.34", "DISZ 5..34"), {"garbled.zmx", "line 75: DISZ", "5..34"}},
      {damaged("truncated.zmx", text.substr(text.find("SURF 1")), ""), {"truncated.zmx", "SURF", "truncated"}},
      {damaged("toroid.zmx", "SURF 2\r\n  TYPE STANDARD", "SURF 2\r\n  TYPE TOROIDAL"), {"toroid.zmx", "SURF 2", "TYPE", "TOROIDAL"}},
  };
  for (const Case& c : cases) {
    r = runInim("lens info " + c.file);
    EXPECT_EQ(r.status, 2) << c.file << ": " << r.output;
    for (const std::string& m : c.mentions) EXPECT_NE(r.output.find(m), std::string::npos) << m << " in: " << r.output;
  }
}
