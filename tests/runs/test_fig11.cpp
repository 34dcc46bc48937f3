// The Fig. 11 experiment's settings: defaults as the paper's figure was reproduced, and bad
// values reported by their setting names before any work or output.
#include <gtest/gtest.h>

#include <filesystem>

#include "expect_input_error.h"
#include "runs/fig11.h"
#include "scratch_dir.h"
#include "display_view/view_renderer.h"

using namespace inim;

namespace {
ScratchDir scratch("fig11");
}

TEST(Fig11, DefaultsAreTheFiguresAndTheViewDefaults) {
  const Fig11Settings s;
  EXPECT_EQ(s.width, 648);
  EXPECT_EQ(s.angleDeg, 7.0);
  EXPECT_EQ(s.mla, MlaKind::Real);
  // The reconstruction uses the view tools' estimator, with a coarser quadrature than theirs
  // (fig11.h: 1 stratum on an 8 x 8 aperture grid, a quarter of the reference's noise), the
  // budget's too, so that its full chain is the run's own view.
  const ViewSettings vs;
  EXPECT_EQ(vs.panelEstimator, PanelEstimator::Quadrature);
  EXPECT_EQ(s.spp, 1);
  EXPECT_EQ(s.budgetSpp, s.spp);
  EXPECT_EQ(s.apertureGrid, 8);
  EXPECT_LT(s.apertureGrid, vs.apertureGrid);
}

TEST(Fig11, BadSettingsAreNamedBeforeAnyOutput) {
  Fig11Settings s;
  s.outDir = scratch.path("out");
  auto keyOf = [&](Fig11Settings bad) { return expectInputError([&] { (void)runFig11(bad); }).key(); };
  Fig11Settings b = s;
  b.spp = 0;
  EXPECT_EQ(keyOf(b), "spp");
  b = s, b.referenceSpp = -1;
  EXPECT_EQ(keyOf(b), "reference_spp");
  b = s, b.eiaSpp = 0;
  EXPECT_EQ(keyOf(b), "eia_spp");
  b = s, b.width = 0;
  EXPECT_EQ(keyOf(b), "width");
  b = s, b.angleDeg = 60.0;
  EXPECT_EQ(keyOf(b), "angle_deg");
  b = s, b.poses = {"centre", "sideways"};
  EXPECT_EQ(keyOf(b), "poses");
  b = s, b.budgetSpp = 0;
  EXPECT_EQ(keyOf(b), "budget_spp");
  b = s, b.fieldPath = "scene.obj";
  EXPECT_EQ(keyOf(b), "field");
  b = s, b.calibrationPath = "panel.3dl";
  EXPECT_EQ(keyOf(b), "calibration");
  b = s, b.calibrationPath = scratch.path("missing.cube");
  EXPECT_EQ(keyOf(b), "calibration");
  EXPECT_FALSE(std::filesystem::exists(s.outDir));
}
