// The exported files as OpenColorIO reads them: its C++ API, its ociochecklut tool, and the
// exported config with the calibrated colour space.
#include <OpenColorIO/OpenColorIO.h>
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <sstream>

#include "calibration/lut_io.h"
#include "calibration/ocio_config.h"
#include "calibration/test_functions.h"
#include "expect_input_error.h"
#include "scratch_dir.h"
#include "spectral/color.h"

namespace OCIO = OCIO_NAMESPACE;

namespace inim {
namespace {

const ScratchDir& scratch() {
  static const ScratchDir dir("calibration_ocio");
  return dir;
}

// Agreement of OpenColorIO (float processing, its own tetrahedral interpolation) with
// Lut3d::eval.
constexpr double kTolerance = 1e-4;

Vec3d applyRgb(const OCIO::ConstCPUProcessorRcPtr& cpu, const Vec3d& rgb) {
  float pixel[3] = {float(rgb.x), float(rgb.y), float(rgb.z)};
  cpu->applyRGB(pixel);
  return {pixel[0], pixel[1], pixel[2]};
}

// The CPU processor of one LUT file, through a raw config (no colour spaces involved).
OCIO::ConstCPUProcessorRcPtr fileProcessor(const std::string& path) {
  OCIO::FileTransformRcPtr file = OCIO::FileTransform::Create();
  file->setSrc(path.c_str());
  file->setInterpolation(OCIO::INTERP_TETRAHEDRAL);
  return OCIO::Config::CreateRaw()->getProcessor(file)->getDefaultCPUProcessor();
}

void expectSameMapping(const OCIO::ConstCPUProcessorRcPtr& cpu, const ColourFunction& expected) {
  for (const Vec3d& x : testing::pseudoRandomColours(100)) {
    const Vec3d ocio = applyRgb(cpu, x), ours = expected(x);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(ocio[c], ours[c], kTolerance) << "input " << x.x << " " << x.y << " " << x.z;
  }
}

Lut3d testLut() { return Lut3d::sample(testing::asymmetric); }

TEST(OcioInterop, CubeReadByOpenColorIO) {
  const Lut3d lut = testLut();
  const std::string path = scratch().path("ocio.cube");
  writeCube(path, lut, "ocio");
  expectSameMapping(fileProcessor(path), [&](const Vec3d& x) { return lut.eval(x); });
}

TEST(OcioInterop, ClfReadByOpenColorIO) {
  const Lut3d lut = testLut();
  const std::string path = scratch().path("ocio.clf");
  writeClf(path, ClfProcess{std::nullopt, lut}, "ocio");
  expectSameMapping(fileProcessor(path), [&](const Vec3d& x) { return lut.eval(x); });
}

// The Matrix node is applied before the LUT, row by row as written.
TEST(OcioInterop, ClfWithMatrixReadByOpenColorIO) {
  const ClfProcess process{glm::transpose(glm::dmat3(0.7, 0.3, 0.0, 0.1, 0.6, 0.2, 0.0, 0.25, 0.75)), testLut()};
  const std::string path = scratch().path("ocio_matrix.clf");
  writeClf(path, process, "ocio matrix");
  expectSameMapping(fileProcessor(path), [&](const Vec3d& x) { return process.apply(x); });
}

// ociochecklut's path, or "" when it is not installed.
std::string ociochecklut() {
  const char* path = std::getenv("PATH");
  std::istringstream dirs(path ? path : "");
  for (std::string dir; std::getline(dirs, dir, ':');)
    if (std::filesystem::exists(std::filesystem::path(dir) / "ociochecklut"))
      return (std::filesystem::path(dir) / "ociochecklut").string();
  return "";
}

// "ociochecklut FILE r g b" prints the output triple on its last line.
Vec3d checkLut(const std::string& tool, const std::string& file, const Vec3d& rgb) {
  std::ostringstream command;
  command.precision(17);
  command << "'" << tool << "' '" << file << "' " << rgb.x << " " << rgb.y << " " << rgb.z << " 2>&1";
  FILE* pipe = popen(command.str().c_str(), "r");
  EXPECT_NE(pipe, nullptr);
  std::string output;
  for (char buffer[256]; pipe && fgets(buffer, sizeof buffer, pipe);) output += buffer;
  EXPECT_EQ(pipe ? pclose(pipe) : -1, 0) << output;
  std::istringstream lines(output);
  std::string line, last;
  while (std::getline(lines, line))
    if (!line.empty()) last = line;
  Vec3d out(std::nan(""));
  std::istringstream(last) >> out.x >> out.y >> out.z;
  return out;
}

TEST(OcioInterop, OciochecklutAgrees) {
  const std::string tool = ociochecklut();
  if (tool.empty()) GTEST_SKIP() << "ociochecklut not found on PATH (Debian package opencolorio-tools)";
  const Lut3d lut = testLut();
  const std::string cube = scratch().path("check.cube"), clf = scratch().path("check.clf");
  writeCube(cube, lut, "check");
  writeClf(clf, ClfProcess{std::nullopt, lut}, "check");
  for (const Vec3d& x : testing::pseudoRandomColours(6, 0.0, 1.0, 99)) {
    const Vec3d ours = lut.eval(x);
    for (const std::string& file : {cube, clf}) {
      const Vec3d tool_out = checkLut(tool, file, x);
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(tool_out[c], ours[c], kTolerance) << file;
    }
  }
}

// The exported config: the base config's spaces plus panel_calibrated, whose conversion from
// the reference applies the LUT; the LUT files are found beside the config.
TEST(OcioInterop, ExportedConfigConvertsThroughTheCalibratedSpace) {
  const Lut3d lut = testLut();
  for (LutFormat format : {LutFormat::Clf, LutFormat::Cube}) {
    const std::string folder = scratch().path(format == LutFormat::Clf ? "export_clf" : "export_cube");
    const CalibrationFiles files = exportCalibration(folder, "panel", lut, OcioColourSpaceSettings{}, format);
    for (const std::string& f : {files.cube, files.clf, files.config}) EXPECT_TRUE(std::filesystem::exists(f)) << f;
    OCIO::ConstConfigRcPtr config = OCIO::Config::CreateFromFile(files.config.c_str());
    config->validate();
    const auto toPanel = config->getProcessor("lin_rec709", "panel_calibrated")->getDefaultCPUProcessor();
    expectSameMapping(toPanel, [&](const Vec3d& x) { return lut.eval(x); });
    // The base config's own conversions are unchanged.
    const auto toXyz = config->getProcessor("lin_rec709", "cie_xyz_d65")->getDefaultCPUProcessor();
    expectSameMapping(toXyz, [](const Vec3d& x) {
      return Vec3d(ColorSystem::instance().convert(Vec3(x), "lin_rec709", "cie_xyz_d65"));
    });
  }
}

// ToReference: converting the new space to the reference applies the LUT.
TEST(OcioInterop, ToReferenceDirection) {
  const Lut3d lut = testLut();
  OcioColourSpaceSettings space;
  space.name = "camera_corrected";
  space.direction = LutDirection::ToReference;
  const CalibrationFiles files = exportCalibration(scratch().path("export_to_ref"), "camera", lut, space);
  OCIO::ConstConfigRcPtr config = OCIO::Config::CreateFromFile(files.config.c_str());
  expectSameMapping(config->getProcessor("camera_corrected", "lin_rec709")->getDefaultCPUProcessor(),
                    [&](const Vec3d& x) { return lut.eval(x); });
}

// A name the base config already has is refused, and nothing is left behind.
TEST(OcioInterop, ExportRefusesAnExistingSpaceAndWritesNothing) {
  OcioColourSpaceSettings space;
  space.name = "srgb";
  const std::string folder = scratch().path("export_refused");
  const InputError e = expectInputError([&] { exportCalibration(folder, "panel", Lut3d(2), space); });
  EXPECT_EQ(e.key(), "colour_space");
  EXPECT_EQ(e.value(), "srgb");
  EXPECT_TRUE(!std::filesystem::exists(folder) || std::filesystem::is_empty(folder));
}

}  // namespace
}  // namespace inim
