// The validation studies run end to end into a temporary folder: every file is written and the
// verdict values are those the physics tests assert (tests/view/test_flip_onset.cpp,
// tests/mla/test_reference_image_plane.cpp).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <unistd.h>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/error.h"
#include "studies/studies.h"

namespace fs = std::filesystem;
using namespace inim;

namespace {

// INIM_STUDIES_KEEP=DIR: write the studies into DIR/<name> and keep them (to look at the reports).
fs::path tempDir(const std::string& name) {
  if (const char* keep = std::getenv("INIM_STUDIES_KEEP")) return fs::path(keep) / name;
  fs::path p = fs::temp_directory_path() / ("inim_test_studies_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(p);
  return p;
}

std::string readText(const fs::path& p) {
  std::ifstream f(p);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

void expectFiles(const StudyReport& r) {
  for (const auto& f : r.files) {
    EXPECT_TRUE(fs::exists(f)) << f;
    EXPECT_GT(fs::file_size(f), 100u) << f;
  }
  // No temporaries left behind.
  for (const auto& e : fs::directory_iterator(fs::path(r.files.front()).parent_path()))
    EXPECT_NE(e.path().filename().string().find(".tmp"), 0u) << e.path();
}

}  // namespace

TEST(Studies, FlipOnsetWithinTenPercentOfHalfViewingAngle) {
  const fs::path dir = tempDir("flip");
  const StudyReport r = runFlipOnset({dir.string(), ""});
  ASSERT_EQ(r.values.size(), 2u);
  const double predicted = std::atan(1.0 / 8.0) * 180.0 / M_PI;  // P = 1 mm, g = 4 mm
  for (const auto& v : r.values) {
    EXPECT_NEAR(v.predicted, predicted, 1e-6) << v.name;
    EXPECT_NEAR(v.measured, predicted, 0.10 * predicted) << v.name;
    EXPECT_TRUE(v.pass) << v.name;
  }
  EXPECT_TRUE(r.pass);
  ASSERT_EQ(r.files.size(), 3u);
  expectFiles(r);
  const std::string md = readText(dir / "report.md");
  EXPECT_NE(md.find("PASS"), std::string::npos);
  EXPECT_NE(md.find("inim study flip-onset --out"), std::string::npos);
  EXPECT_NE(md.find("flip_onset.png"), std::string::npos);
  if (!std::getenv("INIM_STUDIES_KEEP")) fs::remove_all(dir);
}

TEST(Studies, ImagePlaneMatchesThickLensPrediction) {
  const fs::path dir = tempDir("plane");
  const StudyReport r = runImagePlane({dir.string(), ""});
  ASSERT_EQ(r.values.size(), 7u);
  const StudyValue& parax = r.values[0];
  const StudyValue& full = r.values[1];
  EXPECT_NEAR(parax.predicted, 19.35, 0.02);
  EXPECT_NEAR(parax.measured, parax.predicted, 0.02 * parax.predicted);
  EXPECT_NEAR(full.measured, full.predicted, 0.25 * full.predicted);
  EXPECT_LT(full.measured, parax.measured);  // under-corrected spherical aberration
  for (size_t i = 2; i < r.values.size(); ++i)
    EXPECT_TRUE(r.values[i].pass) << r.values[i].name << " measured " << r.values[i].measured << " predicted "
                                  << r.values[i].predicted;
  EXPECT_TRUE(r.pass);
  ASSERT_EQ(r.files.size(), 5u);
  expectFiles(r);
  EXPECT_NE(readText(dir / "report.md").find("plane_vs_gap.png"), std::string::npos);
  if (!std::getenv("INIM_STUDIES_KEEP")) fs::remove_all(dir);
}

TEST(Studies, UnknownNameIsInputError) {
  EXPECT_THROW(runStudy("no-such-study", {"/nonexistent", ""}), InputError);
  EXPECT_EQ(studyNames().size(), 2u);
}
