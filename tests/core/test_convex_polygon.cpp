// ConvexPolygon: moments against closed forms, clipping against point counting, and the
// pulled-back half-plane against the affine map it pulls back through.
#include <gtest/gtest.h>

#include <cmath>

#include "core/convex_polygon.h"
#include "core/rng.h"

using namespace inim;

TEST(ConvexPolygon, MomentsOfASquareAndATriangle) {
  const PolygonMoments sq = ConvexPolygon::rect(2.0, 3.0, 3.0, 4.0).moments();
  EXPECT_NEAR(sq.area, 1.0, 1e-12);
  EXPECT_NEAR(sq.centroid.x, 2.5, 1e-12);
  EXPECT_NEAR(sq.centroid.y, 3.5, 1e-12);
  EXPECT_NEAR(sq.cxx, 1.0 / 12.0, 1e-12);
  EXPECT_NEAR(sq.cyy, 1.0 / 12.0, 1e-12);
  EXPECT_NEAR(sq.cxy, 0.0, 1e-12);
  // The right triangle (0,0) (1,0) (0,1): area 1/2, centroid (1/3, 1/3), covariance
  // [1/18, -1/36; -1/36, 1/18]; clockwise order gives the same.
  for (bool cw : {false, true}) {
    ConvexPolygon t;
    t.n = 3;
    t.v[0] = Vec2d(0, 0);
    t.v[1] = cw ? Vec2d(0, 1) : Vec2d(1, 0);
    t.v[2] = cw ? Vec2d(1, 0) : Vec2d(0, 1);
    const PolygonMoments m = t.moments();
    EXPECT_NEAR(m.area, 0.5, 1e-12);
    EXPECT_NEAR(m.centroid.x, 1.0 / 3.0, 1e-12);
    EXPECT_NEAR(m.centroid.y, 1.0 / 3.0, 1e-12);
    EXPECT_NEAR(m.cxx, 1.0 / 18.0, 1e-12);
    EXPECT_NEAR(m.cyy, 1.0 / 18.0, 1e-12);
    EXPECT_NEAR(m.cxy, -1.0 / 36.0, 1e-12);
  }
}

TEST(ConvexPolygon, ClippingAgreesWithPointCounting) {
  // A unit square cut by random half-planes: the clipped area against the share of a 400 x 400
  // grid of points that satisfy every cut.
  Rng rng(7, 1);
  for (int trial = 0; trial < 50; ++trial) {
    ConvexPolygon p = ConvexPolygon::rect(0, 0, 1, 1);
    Vec2d a[3];
    double c[3];
    for (int k = 0; k < 3; ++k) {
      const double ang = 6.283185307 * rng.uniformDouble();
      a[k] = Vec2d(std::cos(ang), std::sin(ang));
      c[k] = a[k].x * 0.5 + a[k].y * 0.5 + (rng.uniformDouble() - 0.3) * 0.6;
      p = p.clipped(a[k], c[k]);
    }
    int in = 0;
    const int n = 400;
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const Vec2d q((i + 0.5) / n, (j + 0.5) / n);
        bool ok = true;
        for (int k = 0; k < 3; ++k) ok = ok && a[k].x * q.x + a[k].y * q.y <= c[k];
        in += ok;
      }
    EXPECT_NEAR(p.empty() ? 0.0 : p.moments().area, double(in) / (n * n), 4.0 / n) << "trial " << trial;
  }
}

TEST(ConvexPolygon, PulledBackHalfPlaneHoldsExactlyWhereTheMappedPointSatisfiesIt) {
  Rng rng(3, 4);
  const double J[2][2] = {{0.07, -0.004}, {0.003, -0.065}};  // a camera pixel -> MLA mm map
  const Vec2d q0(1.3, -0.7), p0(100.5, 200.5), nrm(0.5, 0.8660254);
  const double c = 0.2;
  Vec2d a;
  double cc;
  pullBackHalfPlane(q0, J, p0, nrm, c, a, cc);
  for (int i = 0; i < 2000; ++i) {
    const Vec2d p(p0.x + 40.0 * (rng.uniformDouble() - 0.5), p0.y + 40.0 * (rng.uniformDouble() - 0.5));
    const Vec2d d = p - p0;
    const Vec2d q(q0.x + J[0][0] * d.x + J[0][1] * d.y, q0.y + J[1][0] * d.x + J[1][1] * d.y);
    const double sq = nrm.x * q.x + nrm.y * q.y - c, sp = a.x * p.x + a.y * p.y - cc;
    if (std::abs(sq) < 1e-9) continue;
    EXPECT_EQ(sq <= 0.0, sp <= 0.0) << i;
  }
}
