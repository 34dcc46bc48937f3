// The settings policies and checks that the commands share through the experiment runs: view's
// estimator choice, the query rays' sampling, exposure and white balance, camera vectors, and
// compare and capture named by their settings before any output.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "core/image.h"
#include "expect_input_error.h"
#include "runs/camera_run.h"
#include "runs/capture_run.h"
#include "runs/compare_run.h"
#include "runs/eia_run.h"
#include "runs/render_run.h"
#include "scene/analytic_scene.h"
#include "scratch_dir.h"

using namespace inim;

namespace {
ScratchDir scratch("run_settings");
}

TEST(ViewEstimatorPolicy, AutoIsQuadratureForPrimariesWithOneStratumUnlessSppIsGiven) {
  ViewSettings vs;  // primaries, spp 16
  applyEstimatorPolicy(vs, "auto", false);
  EXPECT_EQ(vs.panelEstimator, PanelEstimator::Quadrature);
  EXPECT_EQ(vs.spp, 1);
  ViewSettings given;
  given.spp = 9;
  applyEstimatorPolicy(given, "auto", true);
  EXPECT_EQ(given.spp, 9);
  ViewSettings visible;
  visible.spectral = SpectralSampling::Visible;  // quadrature integrates the primaries' spectra only
  applyEstimatorPolicy(visible, "auto", false);
  EXPECT_EQ(visible.panelEstimator, PanelEstimator::Footprint);
  EXPECT_EQ(visible.spp, 16);
  ViewSettings point;
  applyEstimatorPolicy(point, "point", false);
  EXPECT_EQ(point.panelEstimator, PanelEstimator::PointSample);
  EXPECT_EQ(point.spp, 16);
}

TEST(ViewRun, MissingEiaIsNamedBeforeAnyOutput) {
  ViewRunSettings s;
  s.eiaPath = scratch.path("missing.exr");
  s.camera.out = scratch.path("view.exr");
  const InputError e = expectInputError([&] { (void)runView(s); });
  EXPECT_EQ(e.key(), "eia");
  EXPECT_EQ(e.file(), s.eiaPath);
  s.eiaPath = scratch.path("eia.jpg");
  EXPECT_EQ(expectInputError([&] { (void)runView(s); }).key(), "eia");
  EXPECT_FALSE(std::filesystem::exists(s.camera.out));
}

TEST(EiaSettings, QuerySamplingExposureAndWhiteBalance) {
  EXPECT_EQ(expectInputError([] { checkQuerySampling(INFINITY, 0); }).key(), "vcp_mm");  // the VCP first
  EXPECT_EQ(expectInputError([] { checkQuerySampling(100.0, 0); }).key(), "spp");
  EXPECT_NO_THROW(checkQuerySampling(-50.0, 1));  // a VCP behind the MLA is allowed
  SynthesisSettings s;
  applyExposure("2.5", s);
  EXPECT_FALSE(s.autoExposure);
  EXPECT_EQ(s.exposure, 2.5);
  applyExposure("auto", s);
  EXPECT_TRUE(s.autoExposure);
  for (const char* bad : {"0", "-1", "x", "", "2.5x", "inf"}) {
    SynthesisSettings t;
    EXPECT_EQ(expectInputError([&] { applyExposure(bad, t); }).key(), "exposure") << bad;
  }
  EXPECT_TRUE(parseWhiteBalanceD65("d65"));
  EXPECT_FALSE(parseWhiteBalanceD65("none"));
  EXPECT_EQ(expectInputError([] { (void)parseWhiteBalanceD65("D50"); }).key(), "white_balance");
}

TEST(RenderSettings, CameraVectorsAreThreeFiniteNumbers) {
  const Vec3 v = parseCameraVector("1,-2.5,350", "eye");
  EXPECT_EQ(v.x, 1.0f);
  EXPECT_EQ(v.y, -2.5f);
  EXPECT_EQ(v.z, 350.0f);
  EXPECT_EQ(expectInputError([] { (void)parseCameraVector("1,2", "look_at"); }).key(), "look_at");
  EXPECT_EQ(expectInputError([] { (void)parseCameraVector("1,2,3,4", "up"); }).key(), "up");
  EXPECT_EQ(expectInputError([] { (void)parseCameraVector("1,nan,3", "eye"); }).key(), "eye");
}

TEST(CompareRun, AnImageAgainstItselfHasNoErrorAndSettingsAreNamedFirst) {
  Image img(16, 16, {"R", "G", "B"});
  for (size_t i = 0; i < img.data.size(); ++i) img.data[i] = float(i % 7) / 8.0f;
  const std::string a = scratch.path("a.exr");
  writeImage(img, a);
  CompareRunSettings s;
  s.a = s.b = a;
  const CompareRunResult r = runCompare(s);
  EXPECT_EQ(r.options.spaceA, "lin_rec709");  // an EXR is linear Rec.709 unless told
  EXPECT_TRUE(std::isinf(r.metrics.psnrDb));
  EXPECT_NEAR(r.metrics.ssim, 1.0, 1e-9);
  EXPECT_EQ(r.metrics.deltaE.max, 0.0);
  EXPECT_EQ(r.metrics.pixels, 16 * 16);
  CompareRunSettings bad = s;
  bad.space = "no_such_space";
  EXPECT_EQ(expectInputError([&] { (void)runCompare(bad); }).key(), "space");
  bad = s, bad.deMap = scratch.path("map.png");
  EXPECT_EQ(expectInputError([&] { (void)runCompare(bad); }).key(), "de_map");
  EXPECT_FALSE(std::filesystem::exists(bad.deMap));
}

TEST(CaptureRun, DefaultTargetIsWhatTheDisplayCanShow) {
  auto scene = AnalyticScene::load(defaultScenePath());
  const Box3d t = captureTargetForDisplay(*scene, defaultScenePath(), "");
  const Display d = loadDisplay(displayPathOrDefault(""));
  const AreaMm area = computeLayout(d).activeArea();
  EXPECT_LT(t.lo.x, t.hi.x);
  EXPECT_GE(t.lo.x, area.x0);
  EXPECT_LE(t.hi.x, area.x1);
  EXPECT_GE(t.lo.y, area.y0);
  EXPECT_LE(t.hi.y, area.y1);
  EXPECT_GE(t.lo.z, -kDefaultVcpMm);
  EXPECT_LE(t.hi.z, kDefaultVcpMm);
}

TEST(CaptureRun, BadFramingIsNamedBeforeAnyOutput) {
  CaptureRunSettings s;
  s.outDir = scratch.path("capture");
  s.elevationDeg = "50";
  EXPECT_EQ(expectInputError([&] { (void)runCapture(s); }).key(), "elevation_deg");
  s.elevationDeg = "50,90";
  s.target = "0,0,0,-1,1,1";  // x1 < x0
  EXPECT_EQ(expectInputError([&] { (void)runCapture(s); }).key(), "target");
  EXPECT_FALSE(std::filesystem::exists(s.outDir));
}
