// .cube and CLF files: layout, exact round trips, and refusal of malformed files.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "calibration/lut_io.h"
#include "calibration/lut_text.h"
#include "calibration/test_functions.h"
#include "expect_input_error.h"
#include "scratch_dir.h"

namespace inim {
namespace {

const ScratchDir& scratch() {
  static const ScratchDir dir("calibration_io");
  return dir;
}

std::vector<std::string> lines(const std::string& path) {
  std::ifstream in(path);
  std::vector<std::string> out;
  for (std::string line; std::getline(in, line);) out.push_back(line);
  return out;
}

std::string writeText(const std::string& name, const std::string& text) {
  const std::string path = scratch().path(name);
  std::ofstream(path) << text;
  return path;
}

// A 2-node identity .cube with `edit` applied to its text.
std::string cubeText(int tableLines = 8) {
  std::string text = "TITLE \"t\"\nLUT_3D_SIZE 2\nDOMAIN_MIN 0 0 0\nDOMAIN_MAX 1 1 1\n";
  for (int i = 0; i < tableLines; ++i)
    text += std::to_string(i & 1) + " " + std::to_string(i >> 1 & 1) + " " + std::to_string(i >> 2 & 1) + "\n";
  return text;
}

InputError cubeError(const std::string& name, const std::string& text) {
  const std::string path = writeText(name, text);
  InputError e = expectInputError([&] { readCube(path); });
  EXPECT_EQ(e.file(), path);
  return e;
}

TEST(CubeFile, HeaderAndRedFastestOrder) {
  const Lut3d lut = Lut3d::sample(testing::asymmetric, 5);
  const std::string path = scratch().path("order.cube");
  writeCube(path, lut, "order test");
  const auto text = lines(path);
  ASSERT_EQ(text.size(), 4u + 125u);
  EXPECT_EQ(text[0], "TITLE \"order test\"");
  EXPECT_EQ(text[1], "LUT_3D_SIZE 5");
  EXPECT_EQ(text[2], "DOMAIN_MIN 0 0 0");
  EXPECT_EQ(text[3], "DOMAIN_MAX 1 1 1");
  EXPECT_EQ(text[4], tripleText(lut.at(0, 0, 0)));
  EXPECT_EQ(text[5], tripleText(lut.at(1, 0, 0)));  // red changes fastest
  EXPECT_EQ(text[4 + 5], tripleText(lut.at(0, 1, 0)));
  EXPECT_EQ(text[4 + 25], tripleText(lut.at(0, 0, 1)));
}

// Numbers are written in their shortest exact form: reading gives back every bit.
TEST(CubeFile, RoundTripIsExact) {
  const Lut3d lut = Lut3d::sample(testing::asymmetric, 17);
  const std::string path = scratch().path("round.cube");
  writeCube(path, lut, "round");
  EXPECT_EQ(readCube(path).values(), lut.values());
}

TEST(CubeFile, AcceptsCommentsAndBlankLines) {
  std::string text = "# made by hand\n\n" + cubeText();
  text.insert(text.find("0 0 0\n1"), "# the table\n");
  const Lut3d lut = readCube(writeText("comments.cube", text));
  EXPECT_EQ(lut.values(), Lut3d(2).values());
}

TEST(CubeFile, RefusesMalformedFiles) {
  std::string text = cubeText();
  EXPECT_EQ(cubeError("short_line.cube", text.replace(text.find("1 0 0\n"), 6, "1 0\n")).key(), "line 6");
  text = cubeText();
  const InputError junk = cubeError("junk.cube", text.replace(text.find("1 0 0\n"), 6, "1 0 0x\n"));
  EXPECT_EQ(junk.key(), "line 6");
  EXPECT_EQ(junk.value(), "0x");
  text = cubeText();
  const InputError nan = cubeError("nan.cube", text.replace(text.rfind("1 1 1\n"), 6, "1 nan 1\n"));
  EXPECT_EQ(nan.key(), "line 12");
  EXPECT_EQ(nan.value(), "nan");
  EXPECT_NE(nan.expected().find("finite"), std::string::npos);
  const InputError few = cubeError("few.cube", cubeText(7));
  EXPECT_EQ(few.key(), "LUT_3D_SIZE");
  EXPECT_NE(few.expected().find("8 table lines (found 7)"), std::string::npos);
  EXPECT_EQ(cubeError("many.cube", cubeText(9)).key(), "LUT_3D_SIZE");
  EXPECT_EQ(cubeError("nosize.cube", "0 0 0\n").key(), "LUT_3D_SIZE");
  EXPECT_EQ(cubeError("size1.cube", "LUT_3D_SIZE 1\n0 0 0\n").key(), "LUT_3D_SIZE");
  EXPECT_EQ(cubeError("unknown.cube", "LUT_3D_SIZE 2\nGAMMA 2.2\n").value(), "GAMMA");
}

TEST(CubeFile, RefusesA1dLutAndOtherDomains) {
  EXPECT_EQ(cubeError("1d.cube", "LUT_1D_SIZE 2\n0 0 0\n1 1 1\n").key(), "LUT_1D_SIZE");
  std::string text = cubeText();
  const InputError max = cubeError("max.cube", text.replace(text.find("DOMAIN_MAX 1 1 1"), 16, "DOMAIN_MAX 1 0.5 1"));
  EXPECT_EQ(max.key(), "DOMAIN_MAX");
  EXPECT_EQ(max.value(), "1 0.5 1");
  text = cubeText();
  EXPECT_EQ(cubeError("min.cube", text.replace(text.find("DOMAIN_MIN 0 0 0"), 16, "DOMAIN_MIN 0.1 0 0")).key(),
            "DOMAIN_MIN");
  EXPECT_EQ(expectInputError([] { readCube("/nonexistent/x.cube"); }).file(), "/nonexistent/x.cube");
}

// The lines of the first Array in a CLF file.
std::vector<std::string> arrayLines(const std::vector<std::string>& text, const std::string& owner) {
  std::vector<std::string> out;
  bool inOwner = false, inArray = false;
  for (const std::string& line : text) {
    if (line.find("<" + owner) != std::string::npos) inOwner = true;
    if (inOwner && line.find("</Array>") != std::string::npos) break;
    if (inArray) out.push_back(line);
    if (inOwner && line.find("<Array") != std::string::npos) inArray = true;
  }
  return out;
}

// The CLF table has BLUE changing fastest, the reverse of .cube; with an asymmetric function a
// swapped order would show.
TEST(ClfFile, LayoutIsBlueFastest) {
  const Lut3d lut = Lut3d::sample(testing::asymmetric, 4);
  const glm::dmat3 m = glm::transpose(glm::dmat3(0.9, 0.1, 0.0, 0.05, 0.9, 0.05, 0.0, 0.2, 0.8));
  const std::string path = scratch().path("layout.clf");
  writeClf(path, ClfProcess{m, lut}, "layout & <order>");
  const auto text = lines(path);
  EXPECT_EQ(text[1], "<ProcessList id=\"inim_calibration\" name=\"layout &amp; &lt;order&gt;\" compCLFversion=\"3\">");
  const auto table = arrayLines(text, "LUT3D");
  ASSERT_EQ(table.size(), 64u);
  EXPECT_EQ(table[0], tripleText(lut.at(0, 0, 0)));
  EXPECT_EQ(table[1], tripleText(lut.at(0, 0, 1)));  // blue fastest
  EXPECT_EQ(table[4], tripleText(lut.at(0, 1, 0)));
  EXPECT_EQ(table[16], tripleText(lut.at(1, 0, 0)));
  const auto matrix = arrayLines(text, "Matrix");
  ASSERT_EQ(matrix.size(), 3u);
  EXPECT_EQ(matrix[0], "0.9 0.1 0");  // row by row
  EXPECT_EQ(matrix[2], "0 0.2 0.8");
}

TEST(ClfFile, RoundTripIsExact) {
  const Lut3d lut = Lut3d::sample(testing::asymmetric, 9);
  const glm::dmat3 m = glm::transpose(glm::dmat3(0.9, 0.1, 0.0, 0.05, 0.9, 0.05, 0.0, 0.2, 0.8));
  const std::string path = scratch().path("round.clf");
  writeClf(path, ClfProcess{m, lut}, "round");
  const ClfProcess read = readClf(path);
  ASSERT_TRUE(read.matrix.has_value());
  EXPECT_EQ(*read.matrix, m);
  EXPECT_EQ(read.lut.values(), lut.values());
  writeClf(path, ClfProcess{std::nullopt, lut}, "no matrix");
  EXPECT_FALSE(readClf(path).matrix.has_value());
}

// A valid CLF text with one substitution applied.
std::string clfWith(const std::string& from, const std::string& to) {
  const std::string path = scratch().path("base.clf");
  writeClf(path, ClfProcess{std::nullopt, Lut3d(2)}, "base");
  std::ostringstream text;
  text << std::ifstream(path).rdbuf();
  std::string out = text.str();
  const size_t at = out.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return at == std::string::npos ? out : out.replace(at, from.size(), to);
}

InputError clfError(const std::string& name, const std::string& text) {
  const std::string path = writeText(name, text);
  InputError e = expectInputError([&] { readClf(path); });
  EXPECT_EQ(e.file(), path);
  return e;
}

TEST(ClfFile, RefusesWhatItDoesNotWrite) {
  const InputError dims = clfError("dims.clf", clfWith("dim=\"2 2 2 3\"", "dim=\"3 3 3 3\""));
  EXPECT_EQ(dims.key(), "Array values, line 5");
  EXPECT_EQ(dims.value(), "24");
  EXPECT_EQ(clfError("dims4.clf", clfWith("dim=\"2 2 2 3\"", "dim=\"2 2 3\"")).key(), "Array dim, line 5");
  const InputError inf = clfError("inf.clf", clfWith("1 1 1\n", "1 inf 1\n"));
  EXPECT_EQ(inf.key(), "Array value 22, line 5");
  EXPECT_EQ(inf.value(), "inf");
  EXPECT_EQ(clfError("count.clf", clfWith("1 1 1\n", "1 1\n")).value(), "23");
  EXPECT_EQ(clfError("version.clf", clfWith("compCLFversion=\"3\"", "compCLFversion=\"2\"")).value(), "2");
  EXPECT_EQ(clfError("interp.clf", clfWith("tetrahedral", "trilinear")).key(), "LUT3D interpolation, line 4");
  EXPECT_EQ(clfError("depth.clf", clfWith("outBitDepth=\"32f\"", "outBitDepth=\"10i\"")).value(), "10i");
  EXPECT_EQ(clfError("root.clf", "<LUT3D/>").value(), "LUT3D");
  EXPECT_EQ(clfError("nolut.clf", "<ProcessList compCLFversion=\"3\"></ProcessList>").key(), "LUT3D");
  EXPECT_EQ(clfError("other.clf", clfWith("<LUT3D", "<Range/><LUT3D")).value(), "Range");
  EXPECT_EQ(clfError("xml.clf", clfWith("</ProcessList>", "</Process>")).expected(), "well-formed XML");
}

}  // namespace
}  // namespace inim
