#include "core/convex_polygon.h"

#include <cmath>

namespace inim {

ConvexPolygon ConvexPolygon::rect(double x0, double y0, double x1, double y1) {
  ConvexPolygon p;
  p.n = 4;
  p.v[0] = Vec2d(x0, y0);
  p.v[1] = Vec2d(x1, y0);
  p.v[2] = Vec2d(x1, y1);
  p.v[3] = Vec2d(x0, y1);
  return p;
}

ConvexPolygon ConvexPolygon::clipped(const Vec2d& a, double c) const {
  ConvexPolygon out;
  if (n == 0) return out;
  for (int i = 0; i < n; ++i) {
    const Vec2d& p = v[size_t(i)];
    const Vec2d& q = v[size_t((i + 1) % n)];
    const double dp = a.x * p.x + a.y * p.y - c, dq = a.x * q.x + a.y * q.y - c;
    if (dp <= 0.0) {
      if (out.n == kMaxVertices) return *this;
      out.v[size_t(out.n++)] = p;
    }
    if ((dp < 0.0 && dq > 0.0) || (dp > 0.0 && dq < 0.0)) {
      if (out.n == kMaxVertices) return *this;
      const double t = dp / (dp - dq);
      out.v[size_t(out.n++)] = p + t * (q - p);
    }
  }
  return out;
}

Vec2d ConvexPolygon::centroid() const {
  Vec2d s(0.0);
  for (int i = 0; i < n; ++i) s += v[size_t(i)];
  return n > 0 ? s / double(n) : s;
}

PolygonMoments ConvexPolygon::moments() const {
  PolygonMoments m;
  if (n < 3) return m;
  // Green's theorem, about the first vertex (small numbers: pixel coordinates reach thousands).
  const Vec2d o = v[0];
  double a2 = 0.0, sx = 0.0, sy = 0.0, sxx = 0.0, syy = 0.0, sxy = 0.0;
  for (int i = 0; i < n; ++i) {
    const Vec2d p = v[size_t(i)] - o, q = v[size_t((i + 1) % n)] - o;
    const double cr = p.x * q.y - q.x * p.y;
    a2 += cr;
    sx += (p.x + q.x) * cr;
    sy += (p.y + q.y) * cr;
    sxx += (p.x * p.x + p.x * q.x + q.x * q.x) * cr;
    syy += (p.y * p.y + p.y * q.y + q.y * q.y) * cr;
    sxy += (p.x * q.y + 2.0 * p.x * p.y + 2.0 * q.x * q.y + q.x * p.y) * cr;
  }
  if (!(std::abs(a2) > 0.0)) return m;
  const double A = 0.5 * a2;
  const double cx = sx / (6.0 * A), cy = sy / (6.0 * A);
  m.area = std::abs(A);
  m.centroid = o + Vec2d(cx, cy);
  m.cxx = std::max(0.0, sxx / (12.0 * A) - cx * cx);
  m.cyy = std::max(0.0, syy / (12.0 * A) - cy * cy);
  m.cxy = sxy / (24.0 * A) - cx * cy;
  return m;
}

void pullBackHalfPlane(const Vec2d& q0, const double J[2][2], const Vec2d& p0, const Vec2d& nrm, double c, Vec2d& a,
                       double& cOut) {
  // n . (q0 + J (p - p0)) <= c  <=>  (J^T n) . p <= c - n . q0 + (J^T n) . p0
  a = Vec2d(J[0][0] * nrm.x + J[1][0] * nrm.y, J[0][1] * nrm.x + J[1][1] * nrm.y);
  cOut = c - (nrm.x * q0.x + nrm.y * q0.y) + (a.x * p0.x + a.y * p0.y);
}

}  // namespace inim
