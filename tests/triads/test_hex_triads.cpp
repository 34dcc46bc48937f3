// Triads on hex-lattice layouts: traced straight back to the panel plane they rebuild the EIA
// (hexagonal EIs) they were made from.
#include <gtest/gtest.h>

#include <random>

#include "display/hex_test_util.h"
#include "rays/pinhole_rays.h"
#include "triads/triads.h"

using namespace inim;

TEST(HexTriads, EiaFormationEqualsDirectAssignment) {
  for (EiLayoutKind kind : {EiLayoutKind::Parallel, EiLayoutKind::ToedIn, EiLayoutKind::LensGrid}) {
    Display d = hex_test::hexDisplay(9, 6, 25, 0.0395, 3.3, kind, 1.0, 300.0);
    EiLayout L = computeLayout(d);
    RaySet rays = generatePinholeRays(L);
    Image eia(L.eiaW, L.eiaH, {"R", "G", "B"});
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    for (int y = 0; y < L.eiaH; ++y)
      for (int x = 0; x < L.eiaW; ++x)
        if (addressAtEiaPixel(L, {x, y}))
          for (int c = 0; c < 3; ++c) eia.at(x, y, c) = u(rng);
    std::vector<float> drive = driveFromEia(L, eia);
    TriadWavelengths w = triadWavelengths(d.panel);
    EiaFormation f = formEia(L, expandTriads(rays, drive, w), w);
    EXPECT_EQ(f.binned, 3 * rays.size());
    EXPECT_EQ(f.missed, 0u);
    ASSERT_EQ(f.eia.data.size(), eia.data.size());
    float worst = 0.0f;
    for (size_t i = 0; i < eia.data.size(); ++i) worst = std::max(worst, std::abs(f.eia.data[i] - eia.data[i]));
    EXPECT_LE(worst, 1e-6f) << layoutName(kind);
  }
}
