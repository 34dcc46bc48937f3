// The shipped design fix of the prototype (optics/displays/paper-prototype-toed-in.json): the
// paper's hardware with the EIs toed-in for one viewer and made at the viewing gap. It must be
// the same panel, MLA and gap as the paper's display, fit the panel, and centre every EI on the
// projection of its lenslet's centre from the viewer (the toed-in layout's definition).
#include <gtest/gtest.h>

#include <cmath>

#include "core/output_file.h"
#include "display/display.h"
#include "display/display_info.h"
#include "display/ei_layout.h"
#include "display/stack_first_order.h"

using namespace inim;

TEST(ShippedDisplays, ToedInPrototypeCentresEachEiOnItsLensletSeenFromTheViewer) {
  const Display paper = loadDisplay(dataPath("optics/displays/paper-prototype.json"));
  const Display fix = loadDisplay(dataPath("optics/displays/paper-prototype-toed-in.json"));
  EXPECT_EQ(fix.panel.name, paper.panel.name);
  EXPECT_EQ(fix.mla.name, paper.mla.name);
  EXPECT_EQ(fix.reconstructionGapMm, paper.reconstructionGapMm);
  EXPECT_EQ(fix.generationGapMm, fix.reconstructionGapMm);  // made where it is seen from
  ASSERT_TRUE(fix.viewingDistanceMm.has_value());
  const EiLayout L = computeLayout(fix);
  ASSERT_EQ(L.kind, EiLayoutKind::ToedIn);
  EXPECT_LE(L.eiaW, L.panelW);
  EXPECT_LE(L.eiaH, L.panelH);
  const double g = fix.generationGapMm, D = *fix.viewingDistanceMm;
  for (int k = 0; k < L.eiCols; ++k) {
    // The viewer at (0, 0, D) sees lens k's centre against the panel (z = -g) at x (1 + g / D).
    const double seen = L.lensX[size_t(k)] * (1.0 + g / D);
    const double eiCentre = L.pixelCentreX(L.eiCol0[size_t(k)]) + 0.5 * (L.eiW - 1) * L.pixelMm;
    EXPECT_LE(std::abs(seen - eiCentre), L.pixelMm) << "EI column " << k;  // within one pixel
  }
  // The EI pitch is P (1 + g/D) on average: 25.6 px here, not the paper's 25.
  const double pitch = (L.pixelCentreX(L.eiCol0.back()) - L.pixelCentreX(L.eiCol0.front())) / (L.eiCols - 1);
  EXPECT_NEAR(pitch, L.lensPitchMm * (1.0 + g / D), L.pixelMm / (L.eiCols - 1));
}

// The catalogue of stack designs (optics/displays, optics/README.md): each loads for tracing on
// the shipped panel, its EIs on the panel, with an aperture stop and the first order its file
// states: the compound array's 68.6 deg viewing angle through the cover glass (Wen et al.'s), the
// double MLA's longer focal length than its convex array's 3.3 mm, the pinhole sheet afocal at
// 3.3 mm, the barrier MLA's lenslets at the paper's 4 mm gap.
TEST(ShippedDisplays, TheStackCatalogueLoadsWithItsStatedFirstOrder) {
  auto load = [](const char* name) { return loadDisplay(dataPath(std::string("optics/displays/") + name + ".json")); };
  for (const char* name :
       {"double-mla-convex-concave", "compound-symmetric", "pinhole-array", "barrier-mla", "curved-mla-flat-panel"}) {
    const Display d = load(name);
    EXPECT_TRUE(d.stackTraced) << name;
    EXPECT_EQ(d.panel.name, load("paper-prototype").panel.name) << name;
    ASSERT_TRUE(d.stack) << name;
    EXPECT_TRUE(findApertureStop(*d.stack, kLambdaDNm).has_value()) << name;
    EXPECT_FALSE(d.assumptions.empty()) << name;
    const EiLayout L = computeLayout(d);
    EXPECT_LE(L.eiaW, L.panelW) << name;
    EXPECT_LE(L.eiaH, L.panelH) << name;
  }
  const GapInfo compound = derive(load("compound-symmetric")).reconstruction;
  ASSERT_TRUE(compound.opticalViewingAngleDeg.has_value());
  EXPECT_NEAR(*compound.opticalViewingAngleDeg, 68.6, 0.1);
  const StackFirstOrder dbl = stackFirstOrder(*load("double-mla-convex-concave").stack);
  EXPECT_GT(dbl.focalLengthMm, 3.3);
  EXPECT_LT(*dbl.referencePlaneMm, 0.0);  // the panel inside the focal length: a virtual image
  const Display pinhole = load("pinhole-array");
  EXPECT_TRUE(stackFirstOrder(*pinhole.stack).afocal);
  EXPECT_NEAR(pinhole.reconstructionGapMm, 3.3, 1e-12);
  EXPECT_NEAR(load("barrier-mla").reconstructionGapMm, 4.0, 1e-3);
  // The curved array: the prototype's gap to H on its axis; its edge EIs (where the outermost
  // axes meet the flat panel) lie outward of the lenslets by |z_C| tan(X / R) - X.
  const Display curved = load("curved-mla-flat-panel");
  EXPECT_NEAR(curved.reconstructionGapMm, 4.0, 1e-3);
  const EiLayout L = computeLayout(curved);
  const double X = L.lensX.back(), zc = 2.994 + 2000.0;
  EXPECT_NEAR(L.eiCentreX(L.eiCols - 1), zc * std::tan(X / 2000.0), 0.5 * L.pixelMm + 1e-9);
  EXPECT_GT(L.eiCentreX(L.eiCols - 1) - X, 0.05);
}
