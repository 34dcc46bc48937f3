// IdealLensletMla: the ideal thin-lens mapping (focal plane -> parallel bundles, imaging with
// 1/f = 1/g + 1/L), lattice addressing and edges.
#include <gtest/gtest.h>

#include <cmath>

#include "mla_optics/ideal_mla.h"
#include "mla_test_util.h"

using namespace inim;
using namespace mla_test;

namespace {

Ray rayThrough(const Vec3d& from, const Vec3d& to) {
  Ray r;
  r.o = Point3(from);
  r.d = Vec3(glm::normalize(to - from));
  return r;
}

}  // namespace

TEST(IdealLensletMla, FocalPlanePointLeavesAsParallelBundle) {
  const double P = 1.0, f = 3.3, g = 3.3;
  Display d = smallDisplay(7, 5, 10, 0.1, P, f, g);
  const EiLayout L = computeLayout(d);
  IdealLensletMla mla(L, P, f, g);
  Rng rng;
  // Backward: parallel rays (one direction) through many points of one lenslet all land on the
  // same panel point, c - g s' (s' their slope dx/dz); i.e. that point's light leaves parallel.
  const int k = 4, l = 1;
  const double cx = mla.lensX(k), cy = mla.lensY(l);
  const Vec3d dir = glm::normalize(Vec3d(0.05, -0.03, -1.0));
  Point3d first(0.0);
  for (int i = 0; i < 25; ++i) {
    const Vec3d hit(cx + (i % 5 - 2) * 0.2, cy + (i / 5 - 2) * 0.2, 0.0);
    Ray r;
    r.o = Point3(hit - 50.0 * dir);
    r.d = Vec3(dir);
    PanelArrival a;
    ASSERT_TRUE(mla.traceToPanel(r, 550.0f, rng, a));
    EXPECT_EQ(a.lensletK, k);
    EXPECT_EQ(a.lensletL, l);
    EXPECT_NEAR(a.p.z, -g, 1e-6);
    EXPECT_NEAR(a.p.x, cx - g * dir.x / dir.z, 2e-5);
    EXPECT_NEAR(a.p.y, cy - g * dir.y / dir.z, 2e-5);
    if (i == 0) first = Point3d(a.p);
    EXPECT_NEAR(a.p.x, first.x, 2e-5);
    EXPECT_NEAR(a.p.y, first.y, 2e-5);
    EXPECT_LT(a.d.z, 0.0f);
  }
}

TEST(IdealLensletMla, DefocusedPanelImagesAtThinLensDistance) {
  const double P = 1.0, f = 3.3, g = 4.0;
  const double Limg = g * f / (g - f);  // 1/f = 1/g + 1/L: 18.857 mm
  EXPECT_NEAR(1.0 / f, 1.0 / g + 1.0 / Limg, 1e-12);
  Display d = smallDisplay(7, 5, 10, 0.1, P, f, g);
  const EiLayout L = computeLayout(d);
  IdealLensletMla mla(L, P, f, g);
  Rng rng;
  const int k = 2, l = 3;
  const double cx = mla.lensX(k), cy = mla.lensY(l);
  // The image point of the panel point q: P = c + L (c - q) / g at z = L. Reverse-trace rays
  // from that image point through many points of the lenslet: they all land on q.
  const double qx = cx + 0.12, qy = cy - 0.07;
  const Vec3d img(cx + Limg * (cx - qx) / g, cy + Limg * (cy - qy) / g, Limg);
  for (int i = 0; i < 25; ++i) {
    const Vec3d hit(cx + (i % 5 - 2) * 0.22, cy + (i / 5 - 2) * 0.22, 0.0);
    PanelArrival a;
    ASSERT_TRUE(mla.traceToPanel(rayThrough(img, hit), 550.0f, rng, a));
    EXPECT_NEAR(a.p.x, qx, 2e-5) << i;
    EXPECT_NEAR(a.p.y, qy, 2e-5) << i;
  }
  // A point that is not the image point spreads over the panel (defocus).
  const Vec3d off(img.x, img.y, Limg + 5.0);
  PanelArrival a0, a1;
  ASSERT_TRUE(mla.traceToPanel(rayThrough(off, Vec3d(cx - 0.4, cy, 0.0)), 550.0f, rng, a0));
  ASSERT_TRUE(mla.traceToPanel(rayThrough(off, Vec3d(cx + 0.4, cy, 0.0)), 550.0f, rng, a1));
  EXPECT_GT(std::abs(a0.p.x - a1.p.x), 0.01);
}

TEST(IdealLensletMla, EdgesCornersAndOutside) {
  const double P = 1.0, f = 3.3, g = 4.0;
  Display d = smallDisplay(4, 4, 10, 0.1, P, f, g);  // lens centres at +-0.5, +-1.5
  const EiLayout L = computeLayout(d);
  IdealLensletMla mla(L, P, f, g);
  Rng rng;
  PanelArrival a;
  // Exactly on an inner edge and an inner corner: a cell is chosen, the result is finite.
  for (Vec3d hit : {Vec3d(0.0, 0.3, 0.0), Vec3d(1.0, 1.0, 0.0), Vec3d(0.0, 0.0, 0.0)}) {
    ASSERT_TRUE(mla.traceToPanel(rayThrough(hit + Vec3d(0.1, 0.2, 30.0), hit), 550.0f, rng, a));
    EXPECT_TRUE(isFinite(a.p) && isFinite(a.d));
    EXPECT_GE(a.lensletK, 0);
    EXPECT_GE(a.lensletL, 0);
  }
  // Outside the array, rays parallel to the panel, rays going away: no arrival.
  EXPECT_FALSE(mla.traceToPanel(rayThrough(Vec3d(2.5, 0.0, 30.0), Vec3d(2.5, 0.0, 0.0)), 550.0f, rng, a));
  Ray parallel;
  parallel.o = Point3(0.0f, 0.0f, 1.0f);
  parallel.d = Vec3(1.0f, 0.0f, 0.0f);
  EXPECT_FALSE(mla.traceToPanel(parallel, 550.0f, rng, a));
  Ray away;
  away.o = Point3(0.0f, 0.0f, 1.0f);
  away.d = Vec3(0.0f, 0.0f, 1.0f);
  EXPECT_FALSE(mla.traceToPanel(away, 550.0f, rng, a));
  // Grazing but arriving: finite.
  ASSERT_TRUE(mla.traceToPanel(rayThrough(Vec3d(-1.9, 0.2, 0.001), Vec3d(1.9, 0.2, 0.0)), 550.0f, rng, a));
  EXPECT_TRUE(isFinite(a.p) && isFinite(a.d));
  EXPECT_FALSE(mla.isDispersive());
  EXPECT_EQ(mla.frontZ(), 0.0f);
}
