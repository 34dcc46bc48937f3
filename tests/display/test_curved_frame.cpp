// CurvedFrame (display/curved_frame.h): the coordinates a curved stack is flat in. Round trips,
// the axis, the shells' intersections and bands, and where a lenslet's axis meets the panel.
#include <gtest/gtest.h>

#include <cmath>

#include "core/rng.h"
#include "display/curved_frame.h"
#include "display/optical_stack.h"

using namespace inim;

namespace {

CurvedFrame frame(CurvedFrame::Shape shape, double radius, double zRef = 3.0) {
  CurvedFrame f;
  f.shape = shape, f.radiusMm = radius, f.zRefMm = zRef;
  return f;
}

const CurvedFrame kFrames[] = {frame(CurvedFrame::Shape::Cylinder, 80.0), frame(CurvedFrame::Shape::Cylinder, -60.0),
                               frame(CurvedFrame::Shape::Sphere, 80.0), frame(CurvedFrame::Shape::Sphere, -60.0)};

}  // namespace

// Frame coordinates and back, to 1e-10 mm, for points over +-25 mm and 5 mm of depth; the axis
// is W = z; X is the arc length on the reference shell (a cylinder's, exactly R theta).
TEST(CurvedFrame, MapsPointsBothWaysAndKeepsTheAxis) {
  Rng rng(3, 1);
  for (const CurvedFrame& f : kFrames) {
    for (int i = 0; i < 2000; ++i) {
      const double x = -25.0 + 50.0 * rng.uniformDouble(), y = -25.0 + 50.0 * rng.uniformDouble();
      const double w = 5.0 * rng.uniformDouble();
      const Point3d p = f.toWorld(x, y, w);
      const Vec3d q = f.toFrame(p);
      EXPECT_NEAR(q.x, x, 1e-10);
      EXPECT_NEAR(q.y, y, 1e-10);
      EXPECT_NEAR(q.z, w, 1e-10);
      Vec3d v = p - f.centre();
      if (f.shape == CurvedFrame::Shape::Cylinder) v.y = 0.0;
      EXPECT_NEAR(glm::length(v), f.shellRadius(w), 1e-9);  // on its shell
    }
    const Vec3d axial = f.toFrame({0.0, 0.0, 1.25});
    EXPECT_NEAR(axial.x, 0.0, 1e-15);
    EXPECT_NEAR(axial.z, 1.25, 1e-12);
  }
  const CurvedFrame c = kFrames[0];
  const Point3d p = c.toWorld(10.0, 4.0, c.zRefMm);
  EXPECT_NEAR(std::atan2(p.x, c.centre().z - p.z) * 80.0, 10.0, 1e-12);  // arc length on the reference shell
  EXPECT_DOUBLE_EQ(p.y, 4.0);
}

// Every lenslet's axis (the line along `up` through a point) passes through the centre of
// curvature (a cylinder's axis), and W grows along it toward the viewer; the axis frame is orthonormal.
TEST(CurvedFrame, LensletAxesPassThroughTheCentre) {
  for (const CurvedFrame& f : kFrames)
    for (double x : {-20.0, 0.0, 7.5})
      for (double y : {-15.0, 0.0, 12.0}) {
        const Point3d p = f.toWorld(x, y, 4.0);
        // A cylinder's centre: the point of its axis level with p.
        const Point3d c = f.centre() + Vec3d(0.0, f.shape == CurvedFrame::Shape::Cylinder ? p.y : 0.0, 0.0);
        const Vec3d up = f.up(p), toC = c - p;
        EXPECT_NEAR(glm::length(glm::cross(up, toC)), 0.0, 1e-9);
        EXPECT_GT(f.toFrame(p + 1e-3 * up).z, 4.0);
        Vec3d axis, e1, e2;
        f.axisFrame(x, y, axis, e1, e2);
        EXPECT_NEAR(glm::dot(axis, e1), 0.0, 1e-12);
        EXPECT_NEAR(glm::dot(axis, e2), 0.0, 1e-12);
        EXPECT_NEAR(glm::length(e2), 1.0, 1e-12);
        EXPECT_NEAR(glm::length(glm::cross(axis, glm::normalize(c - f.toWorld(x, y, 0.0)))), 0.0, 1e-9);
      }
}

// A ray meets a shell where the shell is (W there = w), first along the ray; the band of a slab
// holds exactly the points whose W lies in it.
TEST(CurvedFrame, ShellsAndBandsAreWhereTheRaySays) {
  Rng rng(9, 4);
  for (const CurvedFrame& f : kFrames)
    for (int i = 0; i < 500; ++i) {
      const Point3d o(-10.0 + 20.0 * rng.uniformDouble(), -10.0 + 20.0 * rng.uniformDouble(), 20.0);
      const Vec3d d = glm::normalize(Vec3d(0.6 * (rng.uniformDouble() - 0.5), 0.6 * (rng.uniformDouble() - 0.5), -1.0));
      double t;
      ASSERT_TRUE(f.hitShell(o, d, 4.0, 0.0, 1e9, t));
      EXPECT_NEAR(f.toFrame(o + t * d).z, 4.0, 1e-9);
      EXPECT_GT(f.toFrame(o + (t - 1e-3) * d).z, 4.0);  // the first crossing: still in front before it
      double lo[2], hi[2];
      const int n = f.band(o, d, 3.0, 4.0, 0.0, 1e9, lo, hi);
      ASSERT_GE(n, 1);
      for (int k = 0; k < n; ++k)
        for (double u : {0.01, 0.5, 0.99}) {
          const double w = f.toFrame(o + (lo[k] + u * (hi[k] - lo[k])) * d).z;
          EXPECT_GE(w, 3.0 - 1e-9);
          EXPECT_LE(w, 4.0 + 1e-9);
        }
      EXPECT_GT(f.toFrame(o + (lo[0] - 1e-3) * d).z, 4.0);
    }
}

// A cylinder's lenslet axes meet a flat panel at x = |z_C| tan(X / |R|) (z_C the centre's height
// above the panel), y unchanged; a concentric panel's arc coordinates scale by its radius.
TEST(CurvedFrame, AxesMeetTheFlatPanelWhereTheGeometrySays) {
  for (double R : {80.0, -60.0}) {
    OpticalStack s;
    StackLayer gap, lens;
    gap.kind = StackLayer::Kind::Gap, gap.thicknessMm = 3.0;
    lens.kind = StackLayer::Kind::LensArray, lens.thicknessMm = 1.0, lens.pitchMm = 1.0, lens.material = "PMMA";
    s.layers = {gap, lens};
    s.curvature = StackCurvature{StackCurvature::Shape::Cylinder, R};
    const double zc = 3.0 + R;
    for (double X : {-20.0, 0.5, 13.0}) {
      double px, py;
      axisFootOnPanel(s, X, 2.5, px, py);
      EXPECT_NEAR(px, std::fabs(zc) * std::tan(X / std::fabs(R)), 1e-9);
      EXPECT_NEAR(py, 2.5, 1e-12);
    }
    s.panelRadiusMm = zc;  // concentric
    double px, py;
    axisFootOnPanel(s, 13.0, 2.5, px, py);
    EXPECT_NEAR(px, 13.0 * std::fabs(zc) / std::fabs(R), 1e-9);
  }
}
