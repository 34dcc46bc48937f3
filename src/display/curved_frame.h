#pragma once
// The coordinates a curved optical stack is flat in (docs/formats.md §3.6a, "Curved stacks").
//
// A curved stack is its flat description bent around one centre of curvature C on the stack's
// axis: every plane z = w of the flat stack becomes the shell (a cylinder about an axis along y,
// or a sphere) of radius rho(w) = |R| - s (w - zRef), s = sign(R), concentric with C =
// (0, 0, zRef + R); R > 0 puts C on the viewer's side. The shell of radius |R| passes through
// (0, 0, zRef), the first lens array's back vertex plane. A world point p (stack frame: panel
// vertex at z = 0, + toward the viewer) has frame coordinates (X, Y, W):
//   W = zRef + s (|R| - rho), rho = |p - C| (cylinder: its distance to the axis through C);
//   X = |R| atan2(v.x, a), a = -s v.z, v = p - C (an arc length on the reference shell);
//   Y = |R| atan2(v.y, a) for a sphere, v.y for a cylinder.
// A lattice point (X, Y) of the flat lattice is a lenslet whose axis is the line from C through
// it (the sphere's lenslets on the directions (tan(X/|R|), tan(Y/|R|), -s): rows and columns of
// the lattice lie on great circles through the x and y axes, which keeps a flat panel's EIs a
// separable grid). On the shell at w, lengths along X (and a sphere's Y) are scale(w) = rho(w) /
// |R| of their flat values; a lenslet's sag is taken at the physical distance from its axis
// measured that way. A flat frame (no curvature) is the identity.
#include "core/geometry.h"

namespace inim {

struct CurvedFrame {
  enum class Shape { Flat, Cylinder, Sphere };
  Shape shape = Shape::Flat;
  double radiusMm = 0.0;  // signed; > 0: the centre on the viewer's side
  double zRefMm = 0.0;

  bool flat() const { return shape == Shape::Flat; }
  double sign() const { return radiusMm > 0.0 ? 1.0 : -1.0; }
  Point3d centre() const { return {0.0, 0.0, zRefMm + radiusMm}; }
  double shellRadius(double w) const { return std::fabs(radiusMm) - sign() * (w - zRefMm); }
  // Physical length per unit of X (and Y) on the shell at w.
  double scaleX(double w) const { return flat() ? 1.0 : shellRadius(w) / std::fabs(radiusMm); }
  double scaleY(double w) const { return shape == Shape::Sphere ? scaleX(w) : 1.0; }

  Vec3d toFrame(const Point3d& p) const;
  Point3d toWorld(double x, double y, double w) const;
  // Unit direction of increasing W (toward the viewer) at p: the lenslet axis there; the
  // gradients of X and Y at p.
  Vec3d up(const Point3d& p) const;
  Vec3d gradX(const Point3d& p) const;
  Vec3d gradY(const Point3d& p) const;
  // The axis of the lenslet at (X, Y), toward the viewer, and two unit vectors across it (along
  // increasing X, and Y made orthogonal to both).
  void axisFrame(double x, double y, Vec3d& axis, Vec3d& e1, Vec3d& e2) const;
  // The smallest t in [tMin, tMax] at which o + t d meets the shell W = w on the side the frame
  // maps (a > 0) within |X| <= maxX, |Y| <= maxY; false when there is none.
  bool hitShell(const Point3d& o, const Vec3d& d, double w, double tMin, double tMax, double& t,
                double maxX = 1e300, double maxY = 1e300) const;
  // The parts of [tMin, tMax] on which W(o + t d) lies in [w0, w1]: at most two intervals, in
  // order; returns their number.
  int band(const Point3d& o, const Vec3d& d, double w0, double w1, double tMin, double tMax, double (&lo)[2],
           double (&hi)[2]) const;
};

}  // namespace inim
