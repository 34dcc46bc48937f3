// The validation studies run end to end into a temporary folder: every file is written and the
// verdict values are checked here (the flip onset and the image plane in their full form, as
// the physics tests once asserted them); the pipeline studies (depth-sharpness, braiding,
// telecentric, nerf-pipeline) run in their quick form (`inim study NAME --quick`), and each test
// checks every verdict value against its prediction and tolerance (or bound). The full forms are
// what `inim study NAME --out validation/NAME` runs.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <unistd.h>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "core/error.h"
#include "studies/studies.h"
#include "studies/study_report.h"

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
  ASSERT_EQ(r.values.size(), 4u);
  // The display as configured (values 0, 1): the panel's 0.55 mm N-BK7 cover glass puts the panel
  // at the optical gap g_eff = g - t (1 - 1/n) = 3.812 mm (n = 1.5185 at 550 nm), so
  // psi / 2 = atan(P / 2 g_eff). The control without the glass (values 2, 3): atan(P / 2g).
  const double gEff = 4.0 - 0.55 * (1.0 - 1.0 / 1.51852);
  const double withGlass = std::atan(0.5 / gEff) * 180.0 / M_PI, noGlass = std::atan(1.0 / 8.0) * 180.0 / M_PI;
  for (size_t i = 0; i < r.values.size(); ++i) {
    const StudyValue& v = r.values[i];
    const double predicted = i < 2 ? withGlass : noGlass;
    EXPECT_NEAR(v.predicted, predicted, i < 2 ? 2e-3 : 1e-6) << v.name;
    EXPECT_NEAR(v.measured, predicted, 0.10 * predicted) << v.name;
    EXPECT_TRUE(v.pass) << v.name;
  }
  // The glass widens the flip angle, for both lenslet arrays.
  EXPECT_GT(r.values[0].measured, r.values[2].measured + 0.2);
  EXPECT_GT(r.values[1].measured, r.values[3].measured + 0.2);
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
  ASSERT_EQ(r.values.size(), 9u);
  const StudyValue& parax = r.values[0];
  const StudyValue& full = r.values[1];
  EXPECT_NEAR(parax.predicted, 19.35, 0.02);
  EXPECT_NEAR(parax.measured, parax.predicted, 0.02 * parax.predicted);
  EXPECT_NEAR(full.measured, full.predicted, 0.25 * full.predicted);
  EXPECT_LT(full.measured, parax.measured);  // under-corrected spherical aberration
  // Under the panel's cover glass (0.55 mm N-BK7): H' + g_eff f / (g_eff - f), g_eff = 3.813 mm.
  const StudyValue& paraxG = r.values[7];
  const StudyValue& fullG = r.values[8];
  EXPECT_NEAR(paraxG.predicted, 25.04, 0.03);
  EXPECT_NEAR(paraxG.measured, paraxG.predicted, 0.02 * paraxG.predicted);
  EXPECT_LT(fullG.measured, paraxG.measured);
  for (size_t i = 2; i < r.values.size(); ++i)
    EXPECT_TRUE(r.values[i].pass) << r.values[i].name << " measured " << r.values[i].measured << " predicted "
                                  << r.values[i].predicted;
  EXPECT_TRUE(r.pass);
  ASSERT_EQ(r.files.size(), 5u);
  expectFiles(r);
  EXPECT_NE(readText(dir / "report.md").find("plane_vs_gap.png"), std::string::npos);
  if (!std::getenv("INIM_STUDIES_KEEP")) fs::remove_all(dir);
}

// The pipeline studies run in their quick form (fewer depths, smaller images; the views by the
// Quadrature estimator, ViewSettings' default): the verdict values are the same quantities with
// the same tolerances as the full run.
TEST(Studies, DepthSharpnessPeaksNearTheReferenceImagePlane) {
  const fs::path dir = tempDir("depth");
  StudyOptions o{dir.string(), ""};
  o.quick = true;
  const StudyReport r = runDepthSharpness(o);
  ASSERT_EQ(r.values.size(), 6u);
  // The control (no cover glass): L = g f / (g - f). The display as configured: its 0.55 mm N-BK7
  // cover glass shortens the optical gap to g_eff = g - t (1 - 1/n), and the facets line up for the
  // target depth z_g = g f / (g_eff - f).
  EXPECT_NEAR(r.values[0].predicted, 18.857, 0.01);
  EXPECT_NEAR(r.values[1].predicted, 25.77, 0.05);
  EXPECT_NEAR(r.values[3].predicted, 18.857, 0.01);
  for (const auto& v : r.values) {
    EXPECT_NEAR(v.measured, v.predicted, v.tolerance * v.predicted) << v.name;
    EXPECT_TRUE(v.pass) << v.name << " measured " << v.measured << " predicted " << v.predicted;
  }
  EXPECT_TRUE(r.pass);
  ASSERT_EQ(r.files.size(), 5u);
  expectFiles(r);
  const std::string md = readText(dir / "report.md");
  EXPECT_NE(md.find("PASS"), std::string::npos);
  EXPECT_NE(md.find("inim study depth-sharpness --out"), std::string::npos);
  if (!std::getenv("INIM_STUDIES_KEEP")) fs::remove_all(dir);
}

TEST(Studies, BraidingFollowsTheParaxialFacetJump) {
  const fs::path dir = tempDir("braid");
  StudyOptions o{dir.string(), ""};
  o.quick = true;
  const StudyReport r = runBraiding(o);
  ASSERT_GE(r.values.size(), 4u);
  for (const auto& v : r.values) {
    EXPECT_NEAR(v.measured, v.predicted, v.tolerance * std::abs(v.predicted)) << v.name;
    EXPECT_TRUE(v.pass) << v.name << " measured " << v.measured << " predicted " << v.predicted;
  }
  // Signs: the facets jump backwards between the MLA and the depth where they line up, forwards
  // beyond it, and by more than P behind the MLA; with the cover glass (the display as configured)
  // and without it (the control).
  for (const char* mla : {"ideal MLA", "real MLA", "ideal MLA, no cover glass", "real MLA, no cover glass"}) {
    const StudyValue* far = r.find(std::string("facet jump at z = 40 mm, ") + mla);
    const StudyValue* near = r.find(std::string("facet jump at z = 10 mm, ") + mla);
    const StudyValue* virt = r.find(std::string("facet jump at z = -20 mm (virtual), ") + mla);
    ASSERT_TRUE(far && near && virt) << mla;
    EXPECT_GT(far->measured, 0.0) << mla;
    EXPECT_LT(near->measured, 0.0) << mla;
    EXPECT_GT(virt->measured, 1.0) << mla;  // more than P behind the MLA (inverted facets)
  }
  // The ideal lenslets' facets line up within 10% of z_g = g f / (g_eff - f) = 25.75 mm with the
  // panel's 0.55 mm N-BK7 cover glass (n_d), and of L = g f / (g - f) = 18.857 mm without it.
  const StudyValue* zero = r.find("depth of zero braiding, ideal MLA");
  const StudyValue* zeroNo = r.find("depth of zero braiding, ideal MLA, no cover glass");
  ASSERT_TRUE(zero && zeroNo);
  EXPECT_NEAR(zero->predicted, 25.75, 0.05);
  EXPECT_NEAR(zero->measured, 25.75, 0.1 * 25.75);
  EXPECT_NEAR(zeroNo->predicted, 18.857, 0.01);
  EXPECT_NEAR(zeroNo->measured, 18.857, 0.1 * 18.857);
  EXPECT_TRUE(r.pass);
  ASSERT_EQ(r.files.size(), 4u);
  expectFiles(r);
  if (!std::getenv("INIM_STUDIES_KEEP")) fs::remove_all(dir);
}

TEST(Studies, TelecentricParallelMagnifiesToedInDoesNot) {
  const fs::path dir = tempDir("tele");
  StudyOptions o{dir.string(), ""};
  o.quick = true;
  const StudyReport r = runTelecentric(o);
  ASSERT_EQ(r.values.size(), 12u);  // 3 depths x 2 layouts x with / without the cover glass
  for (const auto& v : r.values) {
    EXPECT_NEAR(v.measured, v.predicted, v.tolerance * v.predicted) << v.name;
    EXPECT_TRUE(v.pass) << v.name << " measured " << v.measured << " predicted " << v.predicted;
  }
  // At L the parallel layout's error (about +8%) is far beyond the resolution there, with the
  // cover glass and without it.
  for (const char* sfx : {"", ", no cover glass"}) {
    const StudyValue* par = r.find(std::string("width, parallel, z = 19 mm") + sfx);
    const StudyValue* toe = r.find(std::string("width, toed-in, z = 19 mm") + sfx);
    ASSERT_TRUE(par && toe) << sfx;
    EXPECT_GT(par->measured, toe->measured + 1.0) << sfx;
  }
  EXPECT_TRUE(r.pass);
  ASSERT_EQ(r.files.size(), 3u);
  expectFiles(r);
  if (!std::getenv("INIM_STUDIES_KEEP")) fs::remove_all(dir);
}

// The whole workflow, quick form (24 views of 64 x 48 px, 300 iterations, the central 41 x 21
// lenslets, a 200 px thin-lens camera, Quadrature views at 4 strata): each step's agreement with
// its analytic counterpart is above the quick form's bounds (measured: held-out 16.2 dB, EIA
// 13.7 dB, view 15.6 dB, ΔE 12.9).
TEST(Studies, NerfPipelineFieldTracksTheAnalyticScene) {
  const fs::path dir = tempDir("nerf");
  StudyOptions o{dir.string(), ""};
  o.quick = true;
  const StudyReport r = runNerfPipeline(o);
  ASSERT_EQ(r.values.size(), 4u);
  for (const auto& v : r.values) {
    EXPECT_TRUE(std::isfinite(v.measured)) << v.name;
    EXPECT_TRUE(v.pass) << v.name << " measured " << v.measured << " bound " << v.predicted;
  }
  const StudyValue* held = r.find("held-out PSNR of the field (dB)");
  const StudyValue* eia = r.find("field EIA vs analytic EIA, PSNR (dB)");
  const StudyValue* view = r.find("view(field EIA) vs view(analytic EIA) at 0°, PSNR (dB)");
  ASSERT_TRUE(held && eia && view);
  EXPECT_GE(held->measured, 14.0);
  EXPECT_GE(eia->measured, 11.0);
  EXPECT_GE(view->measured, 13.0);
  const StudyValue* deltaE = r.find("view(field EIA) vs view(analytic EIA) at 0°, mean ΔE2000");
  ASSERT_TRUE(deltaE);
  EXPECT_LE(deltaE->measured, 18.0);
  EXPECT_TRUE(r.pass);
  ASSERT_EQ(r.files.size(), 4u);
  expectFiles(r);
  const std::string md = readText(dir / "report.md");
  EXPECT_NE(md.find("PASS"), std::string::npos);
  EXPECT_NE(md.find("inim study nerf-pipeline --out"), std::string::npos);
  EXPECT_NE(md.find("strip.png"), std::string::npos);
  EXPECT_NE(md.find("psnr_per_step.png"), std::string::npos);
  if (!std::getenv("INIM_STUDIES_KEEP")) fs::remove_all(dir);
}

TEST(Studies, UnknownNameIsInputError) {
  EXPECT_THROW(runStudy("no-such-study", {"/nonexistent", ""}), InputError);
  EXPECT_EQ(studyNames().size(), 9u);
}

// The studies sample lenslet cells and EIs as squares: a hex-lattice display is refused by every
// study before anything is written, naming the setting (architectures, which compares the
// catalogue's designs, refuses any --display).
TEST(Studies, HexLatticeDisplayIsInputError) {
  const fs::path dir = tempDir("hex");
  const std::string hex = std::string(INIM_SOURCE_DATA_DIR) + "/optics/displays/hex-prototype-variant.json";
  for (const auto& name : studyNames()) {
    try {
      runStudy(name, {dir.string(), hex});
      ADD_FAILURE() << name << " accepted a hex-lattice display";
    } catch (const InputError& e) {
      const std::string key = name == "architectures" ? "display" : "mla.lattice";
      EXPECT_NE(std::string(e.what()).find(key), std::string::npos) << name << ": " << e.what();
    }
    EXPECT_FALSE(fs::exists(dir)) << name;
  }
}

// The report writer: report.md and the files beside it appear together, report first; a study
// that fails before commit leaves nothing behind.
TEST(Studies, ReportWriterWritesEverythingOrNothing) {
  using namespace study_detail;
  const fs::path dir = tempDir("writer");
  const std::vector<StudyValue> values = {compare("a", 1.05, 1.0, 0.10), compare("b", 1.2, 1.0, 0.10),
                                          bound("c", 20.0, 19.0, true), bound("d", 11.0, 10.0, false)};
  EXPECT_TRUE(values[0].pass);
  EXPECT_FALSE(values[1].pass);
  EXPECT_TRUE(values[2].pass);
  EXPECT_FALSE(values[3].pass);
  EXPECT_FALSE(compare("nan", std::nan(""), 1.0, 0.5).pass);
  {
    ReportWriter w("demo", {dir.string(), ""}, "demo");
    w.csv("data.csv", {"x"}, {{"1"}});
    // No commit: the writer goes out of scope as a failing study's would.
  }
  EXPECT_FALSE(fs::exists(dir / "data.csv"));
  EXPECT_FALSE(fs::exists(dir / "report.md"));
  ReportWriter w("demo", {dir.string(), ""}, "demo");
  w.section("What", "a test");
  w.results({values[0], values[1]}, "mm");
  w.verdict("±10%", {values[0], values[1]});
  w.csv("data.csv", {"x"}, {{"1"}});
  const std::vector<std::string> files = w.commit();
  ASSERT_EQ(files.size(), 2u);
  EXPECT_EQ(fs::path(files[0]).filename(), "report.md");
  EXPECT_EQ(fs::path(files[1]).filename(), "data.csv");
  const std::string md = readText(files[0]);
  EXPECT_EQ(md.rfind("# Study: demo\n\n**What.** a test", 0), 0u) << md;
  EXPECT_NE(md.find("| b | 1.200 | 1.000 | 20.00% | ±10% | **no** |"), std::string::npos) << md;
  EXPECT_NE(md.find("**FAIL**: 1 of 2 quantities are outside their tolerance."), std::string::npos) << md;
  EXPECT_NE(md.find("inim study demo --out " + dir.string()), std::string::npos) << md;
  const std::string bounds = boundsTable({values[2], values[3]});
  EXPECT_NE(bounds.find("| c | 20.00 | ≥ 19.0 | yes |"), std::string::npos) << bounds;
  EXPECT_NE(bounds.find("| d | 11.00 | ≤ 10.0 | **no** |"), std::string::npos) << bounds;
  if (!std::getenv("INIM_STUDIES_KEEP")) fs::remove_all(dir);
}

// The colour-calibration study in its quick form (two poses, small renders, a 17³ table): the
// in-gamut hold-out colours at 0° meet the verification grade after calibration on the default
// display and on the measured panel driven as the placeholder file says, and calibration at
// least halves the latter's error.
TEST(Studies, ColourCalibrationMeetsTheVerificationGrade) {
  const fs::path dir = tempDir("colour");
  StudyOptions o{dir.string(), ""};
  o.quick = true;
  const StudyReport r = runColourCalibration(o);
  ASSERT_EQ(r.values.size(), 7u);
  for (const auto& v : r.values) EXPECT_TRUE(v.pass) << v.name << " measured " << v.measured << " bound " << v.predicted;
  EXPECT_TRUE(r.pass);
  expectFiles(r);
  std::ifstream f(dir / "metrics.json");
  const nlohmann::json m = nlohmann::json::parse(f);
  EXPECT_LE(m["holdout"]["in_gamut"]["de2000_mean_after"].get<double>(), 1.0);
  EXPECT_TRUE(m["holdout"]["per_pose"]["right"]["in_gamut"].contains("de2000_max_after"));
  EXPECT_TRUE(fs::exists(dir / "mismatch" / "panel_correction.cube"));
  if (!std::getenv("INIM_STUDIES_KEEP")) fs::remove_all(dir);
}

// The gap-tradeoff study in its quick form (gaps 3.3, 4 and 5 mm, 324 px, poses 0° and H +7°,
// the default scene and the depth ramp, each under the parallel and the toed-in layout): at every
// gap the ideal display is no worse than the full chain beyond the noise floor; under the toed-in
// layout the ramp's error, and the default scene's compared depth by depth across the gaps, is
// lower near L than away from it; the gap inside the focal length through the glass (3.3 mm: L
// virtual) does not give the lowest error; no run's scratch folder is left behind.
TEST(Studies, GapTradeoffIdealDisplayIsNeverWorseThanTheFullChain) {
  const fs::path dir = tempDir("gap");
  StudyOptions o{dir.string(), ""};
  o.quick = true;
  const StudyReport r = runGapTradeoff(o);
  // 4 series x 3 gaps, the toed-in ramp near L at the gaps whose L lies inside it (4 and 5 mm), and the
  // toed-in default scene's depths across the gaps near L at the gaps whose L lies in front within it (4, 5 mm).
  ASSERT_EQ(r.values.size(), 16u);
  for (const auto& v : r.values) EXPECT_TRUE(v.pass) << v.name << " measured " << v.measured << " bound " << v.predicted;
  EXPECT_TRUE(r.pass);
  expectFiles(r);
  EXPECT_FALSE(fs::exists(dir / ".gap-tradeoff-runs"));
  std::ifstream f(dir / "report.md");
  const std::string report((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
  EXPECT_NE(report.find("gives the lowest mean error"), std::string::npos);
  EXPECT_EQ(report.find("g = 3.30 mm** gives the lowest"), std::string::npos);
  if (!std::getenv("INIM_STUDIES_KEEP")) fs::remove_all(dir);
}

// The architectures study in its quick form (the five catalogue designs at 128 px, the 0° pose):
// for every design the ideal display is no worse than the full chain beyond the noise floor;
// each design's contact sheet and budget are kept beside the report, the stack designs' budgets
// have their layer kinds' rungs, and no run's scratch folder is left behind.
TEST(Studies, ArchitecturesCompareTheCatalogueDesigns) {
  const fs::path dir = tempDir("architectures");
  StudyOptions o{dir.string(), ""};
  o.quick = true;
  const StudyReport r = runArchitectures(o);
  ASSERT_EQ(r.values.size(), 6u);
  for (const auto& v : r.values) EXPECT_TRUE(v.pass) << v.name << " measured " << v.measured << " bound " << v.predicted;
  EXPECT_TRUE(r.pass);
  expectFiles(r);
  EXPECT_FALSE(fs::exists(dir / ".architectures-runs"));
  for (const char* d : {"paper-prototype", "double-mla-convex-concave", "compound-symmetric", "pinhole-array", "barrier-mla",
                        "curved-mla-flat-panel"})
    for (const char* what : {"contact_sheet_", "budget_"})
      EXPECT_TRUE(fs::exists(dir / (std::string(what) + d + ".png"))) << what << d;
  std::ifstream f(dir / "report.md");
  const std::string report((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
  EXPECT_NE(report.find("largest step is +barriers"), std::string::npos);  // the walls' light
  EXPECT_NE(report.find("largest step is +apertures"), std::string::npos);  // the pinholes' light
  if (!std::getenv("INIM_STUDIES_KEEP")) fs::remove_all(dir);
}
