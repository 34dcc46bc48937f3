// `inim view --reference` compares one view as `inim fig11` compares each of its poses: on the
// same EIA, camera, pose, samples and seed, its metrics and its budget must be fig11's (the EIA's
// exposure travels in its EXR header). Its inputs are checked before anything is written.
#include <gtest/gtest.h>

#include <filesystem>

#include "core/output_file.h"
#include "runs/fig11.h"
#include "runs/view_reference.h"
#include "fixtures.h"
#include "synthesis/eia_synthesis.h"

using namespace inim;
namespace fs = std::filesystem;

namespace {

const fixtures::ScratchDir& scratch() {
  static const fixtures::ScratchDir dir("view_reference");
  return dir;
}

// - subpixels: both renders carry it in the view's pass (renderViews).
const std::vector<std::string> kRungs = {"ideal", "+subpixels", "+colour_chain", "-subpixels", "-real_mla"};

// The slanted-edge scene's Fig. 11 at its centre pose, small and quick.
const Fig11Result& fig11Centre() {
  static const Fig11Result r = [] {
    Fig11Settings s;
    s.outDir = scratch().path("fig11");
    s.fieldPath = dataPath("scenes/test/slanted-edge.json");
    s.width = 96;
    s.spp = 1;
    s.referenceSpp = 4;
    s.eiaSpp = 1;
    s.poses = {"centre"};
    s.budget = true;
    s.budgetRungs = kRungs;
    return runFig11(s);
  }();
  return r;
}

ViewRunSettings viewOfFig11Eia(const std::string& name) {
  ViewRunSettings s;
  s.eiaPath = scratch().path("fig11/eia.exr");
  s.camera.width = 96;
  s.camera.out = scratch().path(name + ".exr");
  s.view.spp = 1;
  s.view.apertureGrid = Fig11Settings{}.apertureGrid;
  s.view.seed = 1;
  s.view.progress = false;
  return s;
}

ViewReferenceSettings referenceLikeFig11() {
  ViewReferenceSettings rs;
  rs.fieldPath = dataPath("scenes/test/slanted-edge.json");
  rs.referenceSpp = 4;
  rs.budgetRungs = kRungs;
  return rs;
}

void expectSameMetrics(const ImageMetrics& a, const ImageMetrics& b, const std::string& what) {
  EXPECT_NEAR(a.psnrDb, b.psnrDb, 1e-9) << what;
  EXPECT_NEAR(a.ssim, b.ssim, 1e-9) << what;
  EXPECT_NEAR(a.deltaE.mean, b.deltaE.mean, 1e-9) << what;
  EXPECT_NEAR(a.deltaE.p95, b.deltaE.p95, 1e-9) << what;
}

}  // namespace

TEST(ViewReference, OneViewIsComparedAsFig11ComparesItsPose) {
  const Fig11Result& f = fig11Centre();
  ASSERT_EQ(f.views.size(), 1u);
  ASSERT_EQ(f.budgets.size(), 1u);
  const ViewReferenceResult r = runViewWithReference(viewOfFig11Eia("centre"), referenceLikeFig11());
  EXPECT_TRUE(r.eiaExposureFromHeader);
  ASSERT_TRUE(r.hasMetrics);
  EXPECT_GT(r.metrics.deltaE.mean, 0.5);  // a real difference, not two identical images
  expectSameMetrics(r.metrics, f.views[0].metrics, "against the reference");
  expectSameMetrics(r.bandLimitedMetrics, f.views[0].bandLimitedMetrics, "against the band-limited reference");
  ASSERT_TRUE(r.budget.has_value());
  const PoseBudget &a = *r.budget, &b = f.budgets[0];
  expectSameMetrics(a.noiseFloor, b.noiseFloor, "noise floor");
  ASSERT_EQ(a.ladder.size(), b.ladder.size());
  for (size_t i = 0; i < a.ladder.size(); ++i) expectSameMetrics(a.ladder[i].metrics, b.ladder[i].metrics, a.ladder[i].rung.name);
  ASSERT_EQ(a.removeOne.size(), 2u);
  for (size_t i = 0; i < 2; ++i) expectSameMetrics(a.removeOne[i].metrics, b.removeOne[i].metrics, a.removeOne[i].rung.name);
  EXPECT_EQ(a.removeOne[0].note, "rendered in one pass with the view");
  EXPECT_EQ(b.removeOne[0].note, "rendered in one pass with the view");
  for (const char* suffix : {".exr", ".png", "_reference.exr", "_reference.png", "_error.png", "_metrics.json",
                             "_budget.json", "_budget.csv", "_budget.png"})
    EXPECT_TRUE(fs::exists(scratch().path(std::string("centre") + suffix))) << suffix;
}

TEST(ViewReference, BadInputIsNamedBeforeAnythingIsWritten) {
  (void)fig11Centre();
  ViewRunSettings s = viewOfFig11Eia("bad");
  ViewReferenceSettings rs = referenceLikeFig11();
  rs.budgetRungs = {"ideal", "+sparkle"};
  InputError e = fixtures::expectInputError([&] { (void)runViewWithReference(s, rs); });
  EXPECT_EQ(e.key(), "budget_rungs");
  EXPECT_NE(e.expected().find("+cover_glass"), std::string::npos);  // the valid names are listed

  rs = referenceLikeFig11();
  rs.eiaExposure = -1.0;
  EXPECT_EQ(fixtures::expectInputError([&] { (void)runViewWithReference(s, rs); }).key(), "eia_exposure");

  // An EIA without the header (its PNG) needs the exposure given.
  s.eiaPath = scratch().path("fig11/eia.png");
  e = fixtures::expectInputError([&] { (void)runViewWithReference(s, referenceLikeFig11()); });
  EXPECT_EQ(e.key(), kEiaExposureHeader);
  EXPECT_EQ(e.file(), s.eiaPath);

  rs = referenceLikeFig11();
  rs.referenceSpp = 0;
  EXPECT_EQ(fixtures::expectInputError([&] { (void)runViewWithReference(viewOfFig11Eia("bad"), rs); }).key(),
            "reference_spp");
  for (const char* suffix : {".exr", ".png", "_reference.exr", "_metrics.json", "_budget.json"})
    EXPECT_FALSE(fs::exists(scratch().path(std::string("bad") + suffix))) << suffix;
}
