#pragma once
// A small convex polygon in the plane, clipped by half-planes, and its moments (area, centroid,
// covariance). The view renderer's Quadrature estimator cuts a pixel stratum (sensor pixel
// coordinates) along the display's edge and the lenslet borders with it, and places and sizes
// each piece's footprint on the panel from the moments.
//
//   ConvexPolygon p = ConvexPolygon::rect(x, y, x + 1, y + 1);
//   ConvexPolygon q = p.clipped({1.0, 0.0}, x + 0.3);   // the part with p.x <= x + 0.3
//   PolygonMoments m = q.moments();                      // area 0.3, centroid (x + 0.15, y + 0.5)
#include <array>

#include "core/geometry.h"

namespace inim {

using Vec2d = glm::dvec2;  // (the same alias as camera/lens_system.h)

struct PolygonMoments {
  double area = 0.0;
  Vec2d centroid{0.0};
  double cxx = 0.0, cxy = 0.0, cyy = 0.0;  // covariance of a uniform density over the polygon
};

struct ConvexPolygon {
  // A rectangle clipped by at most 12 half-planes (a square cell, a hexagon, the display's
  // edges) stays within 16 vertices: each clip adds at most one.
  static constexpr int kMaxVertices = 16;
  int n = 0;
  std::array<Vec2d, kMaxVertices> v{};

  static ConvexPolygon rect(double x0, double y0, double x1, double y1);
  // The part where a.x p.x + a.y p.y <= c (Sutherland-Hodgman against one half-plane). A clip
  // that would exceed kMaxVertices leaves the polygon unchanged (cannot happen for the cuts
  // above).
  ConvexPolygon clipped(const Vec2d& a, double c) const;
  bool empty() const { return n < 3; }
  Vec2d centroid() const;                // of the vertices (a point inside a convex polygon)
  PolygonMoments moments() const;
};

// The half-plane n . q <= c of a plane mapped to the plane of p by the affine map
// q = q0 + J (p - p0) (J row-major: J[row][col]): returns a and c' with a . p <= c'.
void pullBackHalfPlane(const Vec2d& q0, const double J[2][2], const Vec2d& p0, const Vec2d& n, double c, Vec2d& a,
                       double& cOut);

}  // namespace inim
