// Pinhole rays on hex-lattice layouts: every ray runs from its pixel centre through its EI's
// pinhole; drive values round-trip; predictPixelForPoint agrees with the rays' geometry.
#include <gtest/gtest.h>

#include <cmath>

#include "fixtures.h"
#include "rays/pinhole_rays.h"
#include "rays/ray_set.h"

using namespace inim;
using fixtures::hexDisplay;

TEST(HexRays, PinholeRaysRunFromPixelThroughPinhole) {
  for (EiLayoutKind kind : {EiLayoutKind::Parallel, EiLayoutKind::ToedIn, EiLayoutKind::LensGrid}) {
    Display d = hexDisplay({.cols = 7,
                            .rows = 6,
                            .layout = kind,
                            .lensPitchMm = kind == EiLayoutKind::Parallel ? 0.0 : 0.92,
                            .viewingDistanceMm = 100.0});
    EiLayout L = computeLayout(d);
    RaySet rays = generatePinholeRays(L);
    ASSERT_EQ(int64_t(rays.size()), L.numRays());
    for (int64_t r = 0; r < L.numRays(); ++r) {
      const RayAddress a = rayAddress(L, r);
      ASSERT_EQ(rayIndex(L, a), r);
      const PixelCoord p = eiaPixel(L, a);
      auto back = addressAtEiaPixel(L, p);
      ASSERT_TRUE(back.has_value());
      ASSERT_EQ(*back, a);
      const Ray ray = rays.ray(size_t(r));
      EXPECT_NEAR(ray.o.x, L.pinholeXAt(a.k, a.l), 1e-6);
      EXPECT_NEAR(ray.o.y, L.pinholeYAt(a.k, a.l), 1e-6);
      // Backward along the ray from the pinhole, z = -g lands on the pixel centre.
      const double t = -L.gapMm / ray.d.z;
      EXPECT_NEAR(ray.o.x + t * ray.d.x, L.pixelCentreX(p.col), 1e-5);
      EXPECT_NEAR(ray.o.y + t * ray.d.y, L.pixelCentreY(p.row), 1e-5);
      const RayD rd = pinholeRay(L, r);
      EXPECT_NEAR(rd.d.x, ray.d.x, 1e-6);
      EXPECT_NEAR(rd.d.y, ray.d.y, 1e-6);
    }
    // Drive values round-trip through the EIA image; pixels outside every EI are 0.
    std::vector<float> drive(size_t(L.numRays()) * 3);
    for (size_t i = 0; i < drive.size(); ++i) drive[i] = float(i % 97) + 1.0f;
    Image eia = eiaFromDrive(L, drive);
    EXPECT_EQ(driveFromEia(L, eia), drive);
    int64_t lit = 0;
    for (int y = 0; y < L.eiaH; ++y)
      for (int x = 0; x < L.eiaW; ++x) lit += eia.at(x, y, 0) > 0.0f;
    EXPECT_EQ(lit, L.numRays());
  }
}

// A point at depth z: in each hex EI whose pinhole line to the point reaches the panel inside
// the EI, predictPixelForPoint names the pixel holding that landing point, and that pixel's
// own ray passes within half a pixel's footprint of the point.
TEST(HexRays, PredictedPixelRaysPassThroughThePoint) {
  Display d = hexDisplay({.cols = 11, .rows = 9});
  EiLayout L = computeLayout(d);
  for (double z : {12.0, -12.0, 30.0}) {
    const Point3d p(0.23, -0.17, z);
    int seen = 0;
    for (int k = 0; k < L.eiCols; ++k)
      for (int l = 0; l < L.eiRows; ++l) {
        auto a = predictPixelForPoint(L, k, l, p);
        // Landing point of the line pinhole -> point on the panel.
        const double cx = L.pinholeXAt(k, l), cy = L.pinholeYAt(k, l), g = L.gapMm;
        const double qx = cx - g * (p.x - cx) / p.z, qy = cy - g * (p.y - cy) / p.z;
        const int col = int(std::floor(qx / L.pixelMm + 0.5 * L.eiaW)), row = int(std::floor(0.5 * L.eiaH - qy / L.pixelMm));
        int kk = -1, ll = -1;
        const bool owned = L.eiAtPixel(col, row, kk, ll) && kk == k && ll == l;
        ASSERT_EQ(a.has_value(), owned) << k << "," << l;
        if (!a) continue;
        ++seen;
        EXPECT_EQ(eiaPixel(L, *a), (PixelCoord{col, row}));
        const RayD r = pinholeRay(L, *a);
        const double t = (p.z - r.o.z) / r.d.z;
        const double miss = std::hypot(r.o.x + t * r.d.x - p.x, r.o.y + t * r.d.y - p.y);
        EXPECT_LE(miss, 0.5 * std::sqrt(2.0) * L.pixelMm * std::abs(z) / g + 1e-9);
      }
    EXPECT_GE(seen, 12) << "z = " << z;
    std::printf("  z = %+.0f mm: %d hex EIs see the point\n", z, seen);
  }
}
