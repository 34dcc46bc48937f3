// loadCalibration: a .cube or .clf file by its extension, mapping colours as the LUT it was
// written from; every kind of bad file refused with an InputError naming the file.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>

#include "calibration/calibration_file.h"
#include "calibration/test_functions.h"
#include "fixtures.h"

namespace inim {
namespace {

using fixtures::expectInputError;

const fixtures::ScratchDir& scratch() {
  static const fixtures::ScratchDir dir("calibration_file");
  return dir;
}

std::string writeText(const std::string& name, const std::string& text) {
  const std::string path = scratch().path(name);
  fixtures::writeBytes(path, text);
  return path;
}

// A file the loader must refuse: its name, its text, and part of what the error expects.
struct BadFile {
  const char* name;
  std::string text;
  const char* expected;
};

// Each file is refused with an InputError that names it and says what was expected.
void expectRefused(const std::vector<BadFile>& bad) {
  for (const BadFile& b : bad) {
    SCOPED_TRACE(b.name);
    const std::string path = writeText(b.name, b.text);
    const InputError e = expectInputError([&] { loadCalibration(path); });
    EXPECT_EQ(e.file(), path);
    EXPECT_NE(e.expected().find(b.expected), std::string::npos) << e.what();
  }
}

// The largest channel difference between the model and the LUT over a fixed set of colours
// (some outside [0,1], where both clamp).
double maxDifference(const ColourModel& model, const ColourFunction& lut) {
  double worst = 0.0;
  for (const Vec3d& c : testing::pseudoRandomColours(500, -0.1, 1.1)) {
    const Vec3d d = model.apply(c) - lut(c);
    worst = std::max({worst, std::abs(d.x), std::abs(d.y), std::abs(d.z)});
  }
  return worst;
}

TEST(CalibrationFile, CubeRoundTripMapsAsTheLut) {
  const Lut3d lut = Lut3d::sample(testing::asymmetric, 9);
  const std::string path = scratch().path("round.cube");
  writeCube(path, lut, "round trip");
  const auto model = loadCalibration(path);
  ASSERT_NE(dynamic_cast<const Lut3d*>(model.get()), nullptr);
  EXPECT_LE(maxDifference(*model, [&](const Vec3d& c) { return lut.eval(c); }), 1e-6);
  EXPECT_NE(describeCalibration(path, *model).find("9 nodes per axis"), std::string::npos);
}

TEST(CalibrationFile, ClfRoundTripMapsAsMatrixThenLut) {
  const Lut3d lut = Lut3d::sample(testing::asymmetric, 7);
  const glm::dmat3 m = glm::transpose(glm::dmat3(0.9, 0.1, 0.0, 0.05, 0.9, 0.05, 0.0, 0.2, 0.8));
  const ClfProcess process{m, lut};
  const std::string path = scratch().path("round.clf");
  writeClf(path, process, "round trip");
  const auto model = loadCalibration(path);
  EXPECT_EQ(model->name(), "clf_matrix_lut3d");
  EXPECT_LE(maxDifference(*model, [&](const Vec3d& c) { return process.apply(c); }), 1e-6);
  // The matrix is applied first: the model is not the LUT alone.
  EXPECT_GT(maxDifference(*model, [&](const Vec3d& c) { return lut.eval(c); }), 1e-3);
  EXPECT_EQ(model->parameters()["matrix_rows"][2][1].get<double>(), 0.2);
}

// The extension chooses the reader, whatever its case.
TEST(CalibrationFile, ExtensionIsCaseInsensitive) {
  const Lut3d lut = Lut3d::sample(testing::asymmetric, 3);
  const std::string cube = scratch().path("upper.CUBE"), clf = scratch().path("upper.Clf");
  writeCube(cube, lut, "upper");
  writeClf(clf, ClfProcess{std::nullopt, lut}, "upper");
  EXPECT_EQ(loadCalibration(cube)->name(), "lut3d");
  EXPECT_EQ(loadCalibration(clf)->name(), "clf_lut3d");
}

// Errors about the file as a whole name the file, the setting and the path.
TEST(CalibrationFile, RefusesOtherExtensionsAndMissingFiles) {
  const std::string cube = scratch().path("ok.cube");
  writeCube(cube, Lut3d(2), "ok");
  const std::string renamed = scratch().path("ok.3dl");
  std::filesystem::copy_file(cube, renamed, std::filesystem::copy_options::overwrite_existing);
  const std::string folder = scratch().path("folder.cube");
  std::filesystem::create_directories(folder);
  for (const std::string& path : {renamed, scratch().path("none.cube"), scratch().path("none.clf"), folder,
                                  scratch().path("noextension")}) {
    SCOPED_TRACE(path);
    const InputError e = expectInputError([&] { loadCalibration(path); });
    EXPECT_EQ(e.file(), path);
    EXPECT_EQ(e.key(), "calibration");
    EXPECT_EQ(e.value(), "\"" + path + "\"");
  }
  EXPECT_EQ(expectInputError([&] { loadCalibration(renamed, "calibration (run.json)"); }).key(),
            "calibration (run.json)");
}

// A 2-node identity .cube with its table lines as given.
std::string cube(const std::string& header, const std::vector<std::string>& table) {
  std::string text = "TITLE \"t\"\n" + header;
  for (const std::string& line : table) text += line + "\n";
  return text;
}
std::vector<std::string> identityLines() {
  std::vector<std::string> lines;
  for (int i = 0; i < 8; ++i)
    lines.push_back(std::to_string(i & 1) + " " + std::to_string(i >> 1 & 1) + " " + std::to_string(i >> 2 & 1));
  return lines;
}
const std::string kHeader = "LUT_3D_SIZE 2\nDOMAIN_MIN 0 0 0\nDOMAIN_MAX 1 1 1\n";

TEST(CalibrationFile, RefusesBadCubeFiles) {
  EXPECT_NO_THROW(loadCalibration(writeText("good.cube", cube(kHeader, identityLines()))));
  auto withLine = [](int i, const std::string& line) {
    std::vector<std::string> lines = identityLines();
    lines[size_t(i)] = line;
    return lines;
  };
  auto shorter = identityLines(), longer = identityLines();
  shorter.pop_back();
  longer.push_back("1 1 1");
  const std::vector<BadFile> bad = {
      {"malformed.cube", cube(kHeader, withLine(3, "1 1 x")), "a number"},
      {"two_numbers.cube", cube(kHeader, withLine(3, "1 1")), "three numbers"},
      {"few.cube", cube(kHeader, shorter), "8 table lines (found 7)"},
      {"many.cube", cube(kHeader, longer), "8 table lines (found 9)"},
      {"nan.cube", cube(kHeader, withLine(5, "1 nan 1")), "finite"},
      {"inf.cube", cube(kHeader, withLine(5, "inf 0 1")), "finite"},
      {"minus_inf.cube", cube(kHeader, withLine(5, "1 0 -inf")), "finite"},
      {"domain_min.cube", cube("LUT_3D_SIZE 2\nDOMAIN_MIN -0.5 0 0\nDOMAIN_MAX 1 1 1\n", identityLines()), "[0,1]"},
      {"domain_max.cube", cube("LUT_3D_SIZE 2\nDOMAIN_MIN 0 0 0\nDOMAIN_MAX 1 1 2\n", identityLines()), "[0,1]"},
      {"domain_nan.cube", cube("LUT_3D_SIZE 2\nDOMAIN_MAX 1 nan 1\n", identityLines()), "finite"},
      {"size1.cube", cube("LUT_3D_SIZE 1\n", {"0 0 0"}), "2 to 256"},
      {"size0.cube", cube("LUT_3D_SIZE 0\n", {}), "2 to 256"},
      {"input_range.cube", cube("LUT_3D_SIZE 2\nLUT_3D_INPUT_RANGE 0 2\n", identityLines()), "LUT_3D_SIZE, DOMAIN"},
  };
  expectRefused(bad);
}

// A valid CLF text (2-node identity LUT, optionally with a matrix) with one substitution.
std::string clfWith(const std::string& from, const std::string& to, bool matrix = false) {
  const std::string path = scratch().path("base.clf");
  writeClf(path, ClfProcess{matrix ? std::optional<glm::dmat3>(glm::dmat3(1.0)) : std::nullopt, Lut3d(2)}, "base");
  std::string text = fixtures::readBytes(path);
  const size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return at == std::string::npos ? text : text.replace(at, from.size(), to);
}

TEST(CalibrationFile, RefusesBadClfFiles) {
  EXPECT_NO_THROW(loadCalibration(writeText("good.clf", clfWith("", "", true))));
  const std::string indexMap = "<IndexMap dim=\"2\">-1@0 2@1</IndexMap>\n        <Array";
  const std::vector<BadFile> bad = {
      {"malformed.clf", clfWith("1 1 1\n", "1 1 x\n"), "a number"},
      {"few.clf", clfWith("1 1 1\n", "1 1\n"), "24 numbers"},
      {"many.clf", clfWith("1 1 1\n", "1 1 1 1\n"), "24 numbers"},
      {"matrix_few.clf", clfWith("0 0 1\n", "0 0\n", true), "9 numbers"},
      {"nan.clf", clfWith("1 1 1\n", "1 nan 1\n"), "finite"},
      {"inf.clf", clfWith("1 1 1\n", "inf 1 1\n"), "finite"},
      {"matrix_inf.clf", clfWith("0 1 0\n", "0 inf 0\n", true), "finite"},
      {"size1.clf", clfWith("dim=\"2 2 2 3\"", "dim=\"1 1 1 3\""), "N from 2 to 256"},
      {"index_map.clf", clfWith("<Array", indexMap), "one Array"},
      {"two_arrays.clf", clfWith("</Array>", "</Array>\n<Array dim=\"2 2 2 3\"></Array>"), "one Array"},
      {"range.clf", clfWith("<LUT3D", "<Range inBitDepth=\"32f\" outBitDepth=\"32f\"/>\n<LUT3D"), "Matrix, then one LUT3D"},
      {"lut1d.clf", clfWith("<LUT3D", "<LUT1D/>\n<LUT3D"), "Matrix, then one LUT3D"},
      {"xml.clf", clfWith("</LUT3D>", "</LUT>"), "well-formed XML"},
  };
  expectRefused(bad);
}

}  // namespace
}  // namespace inim
