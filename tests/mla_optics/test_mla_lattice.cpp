// The lattice queries of the MLA models (MlaModel::lensletCell, cellDepth), which the view
// renderer's Quadrature estimator cuts pixels along: square and hex lattices, real and ideal.
#include <gtest/gtest.h>

#include <cmath>

#include "core/rng.h"
#include "mla_optics/ideal_mla.h"
#include "mla_optics/real_mla.h"
#include "mla_test_util.h"

using namespace inim;
using namespace mla_test;

TEST(MlaLattice, LensletCellHoldsThePointAndIsTheNearestCentre) {
  const double P = 1.0, f = 3.3, g = 4.0;
  for (bool hex : {false, true}) {
    // 6 x 4 square lenslets, or 5 x 5 pointy-top hexagons, of pitch 1 mm.
    Display d = hex ? smallDisplay(5, 5, 20, 0.05, P, f, g, 14) : smallDisplay(6, 4, 20, 0.05, P, f, g);
    d.mla.radiusMm = 1.62;
    if (hex) {
      d.mla.lattice = Mla::Lattice::Hex;
      d.mla.aperture = Mla::Aperture::Hex;
    }
    const EiLayout layout = computeLayout(d);
    const auto real = RealMla::fromDisplay(d, layout, g);
    IdealLensletMla ideal(layout, P, f, g);
    const MlaModel* models[2] = {real.get(), &ideal};
    Rng rng(11, 5);
    for (const MlaModel* m : models) {
      int checked = 0;
      for (int i = 0; i < 4000; ++i) {
        const double x = 6.0 * (rng.uniformDouble() - 0.5), y = 4.0 * (rng.uniformDouble() - 0.5);
        LensletCell c;
        if (!m->lensletCell(x, y, c)) continue;
        ++checked;
        for (int e = 0; e < c.n; ++e)
          EXPECT_LE(c.nx[size_t(e)] * (x - c.cx) + c.ny[size_t(e)] * (y - c.cy), c.h[size_t(e)] + 1e-9);
        // No other lattice centre is nearer (neighbours one pitch away in the 12 directions).
        const double d0 = std::hypot(x - c.cx, y - c.cy);
        for (int k = 0; k < 12; ++k) {
          const double ang = k * M_PI / 6.0, rr = (k & 1) ? c.pitch * std::sqrt(3.0) : c.pitch;
          LensletCell o;
          if (!m->lensletCell(c.cx + rr * std::cos(ang), c.cy + rr * std::sin(ang), o)) continue;
          EXPECT_GE(std::hypot(x - o.cx, y - o.cy), d0 - 1e-9);
        }
      }
      EXPECT_GT(checked, 2000) << (hex ? "hex" : "square");
    }
    // Caps toward the viewer: the lenslets meet at the edge middles, sag(P/2) below the vertex.
    EXPECT_NEAR(real->cellDepth(), real->capSag(0.5 * P) + (real->frontZ() - real->vertexZ()), 1e-3);
    EXPECT_EQ(ideal.cellDepth(), 0.0);
  }
}
