// The shipped design fix of the prototype (optics/displays/paper-prototype-toed-in.json): the
// paper's hardware with the EIs toed-in for one viewer and made at the viewing gap. It must be
// the same panel, MLA and gap as the paper's display, fit the panel, and centre every EI on the
// projection of its lenslet's centre from the viewer (the toed-in layout's definition).
#include <gtest/gtest.h>

#include <cmath>

#include "core/output_file.h"
#include "display/display.h"
#include "display/ei_layout.h"

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
