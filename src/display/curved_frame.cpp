#include "display/curved_frame.h"

#include <algorithm>
#include <cmath>

namespace inim {

namespace {

// q(t) = |o + t d - C|^2 (cylinder: x and z only) = qa t^2 + qb t + qc.
struct Quadratic {
  double qa = 0.0, qb = 0.0, qc = 0.0;
  // Roots of q(t) = r^2, t0 <= t1; false when none.
  bool roots(double r, double& t0, double& t1) const {
    if (qa <= 0.0) return false;
    const double c = qc - r * r, disc = qb * qb - 4.0 * qa * c;
    if (disc < 0.0) return false;
    // The stable pair: no cancellation between -qb and the root of the discriminant.
    const double s = -0.5 * (qb + std::copysign(std::sqrt(disc), qb));
    t0 = s / qa, t1 = s != 0.0 ? c / s : t0;
    if (t0 > t1) std::swap(t0, t1);
    return true;
  }
};

Quadratic quadraticOf(const CurvedFrame& f, const Point3d& o, const Vec3d& d) {
  Vec3d v = o - f.centre(), e = d;
  if (f.shape == CurvedFrame::Shape::Cylinder) v.y = 0.0, e.y = 0.0;
  return {glm::dot(e, e), 2.0 * glm::dot(v, e), glm::dot(v, v)};
}

// The ray's part on the frame's side of the plane through C across the axis (a > 0).
void frontHalf(const CurvedFrame& f, const Point3d& o, const Vec3d& d, double& tMin, double& tMax) {
  const double a0 = -f.sign() * (o.z - f.centre().z), da = -f.sign() * d.z;
  if (da > 0.0) tMin = std::max(tMin, -a0 / da);
  else if (da < 0.0) tMax = std::min(tMax, -a0 / da);
  else if (a0 <= 0.0) tMax = tMin - 1.0;
}

}  // namespace

Vec3d CurvedFrame::toFrame(const Point3d& p) const {
  if (flat()) return Vec3d(p);
  const Vec3d v = p - centre();
  const double a = -sign() * v.z, R = std::fabs(radiusMm);
  if (shape == Shape::Cylinder)
    return {R * std::atan2(v.x, a), v.y, zRefMm + sign() * (R - std::hypot(v.x, v.z))};
  return {R * std::atan2(v.x, a), R * std::atan2(v.y, a), zRefMm + sign() * (R - glm::length(v))};
}

Point3d CurvedFrame::toWorld(double x, double y, double w) const {
  if (flat()) return {x, y, w};
  const double rho = shellRadius(w), R = std::fabs(radiusMm), tx = x / R;
  if (shape == Shape::Cylinder) return centre() + Vec3d(rho * std::sin(tx), y, -sign() * rho * std::cos(tx));
  const Vec3d u = glm::normalize(Vec3d(std::tan(tx), std::tan(y / R), -sign()));
  return centre() + rho * u;
}

Vec3d CurvedFrame::up(const Point3d& p) const {
  if (flat()) return {0.0, 0.0, 1.0};
  Vec3d v = p - centre();
  if (shape == Shape::Cylinder) v.y = 0.0;
  return -sign() * glm::normalize(v);
}

// X = |R| atan2(v.x, a), a = -s v.z: grad = |R| (a, 0, s v.x) / (v.x^2 + a^2); Y likewise in y
// (a cylinder's Y is y).
Vec3d CurvedFrame::gradX(const Point3d& p) const {
  if (flat()) return {1.0, 0.0, 0.0};
  const Vec3d v = p - centre();
  const double a = -sign() * v.z;
  return std::fabs(radiusMm) / (v.x * v.x + a * a) * Vec3d(a, 0.0, sign() * v.x);
}

Vec3d CurvedFrame::gradY(const Point3d& p) const {
  if (shape != Shape::Sphere) return {0.0, 1.0, 0.0};
  const Vec3d v = p - centre();
  const double a = -sign() * v.z;
  return std::fabs(radiusMm) / (v.y * v.y + a * a) * Vec3d(0.0, a, sign() * v.y);
}

void CurvedFrame::axisFrame(double x, double y, Vec3d& axis, Vec3d& e1, Vec3d& e2) const {
  if (flat()) {
    axis = {0.0, 0.0, 1.0}, e1 = {1.0, 0.0, 0.0}, e2 = {0.0, 1.0, 0.0};
    return;
  }
  const Point3d p = toWorld(x, y, zRefMm);
  axis = up(p);
  const double h = 1e-4 * std::fabs(radiusMm);
  const Vec3d dx = toWorld(x + h, y, zRefMm) - toWorld(x - h, y, zRefMm);
  e1 = glm::normalize(dx - glm::dot(dx, axis) * axis);
  e2 = glm::cross(axis, e1);
}

bool CurvedFrame::hitShell(const Point3d& o, const Vec3d& d, double w, double tMin, double tMax, double& t,
                           double maxX, double maxY) const {
  frontHalf(*this, o, d, tMin, tMax);
  double t0, t1;
  if (!(tMin <= tMax) || !quadraticOf(*this, o, d).roots(shellRadius(w), t0, t1)) return false;
  for (double c : {t0, t1}) {
    if (!(c >= tMin && c <= tMax)) continue;
    const Vec3d q = toFrame(o + c * d);
    if (std::fabs(q.x) <= maxX && std::fabs(q.y) <= maxY) {
      t = c;
      return true;
    }
  }
  return false;
}

int CurvedFrame::band(const Point3d& o, const Vec3d& d, double w0, double w1, double tMin, double tMax,
                      double (&lo)[2], double (&hi)[2]) const {
  frontHalf(*this, o, d, tMin, tMax);
  if (!(tMin <= tMax)) return 0;
  const double ra = shellRadius(w0), rb = shellRadius(w1);
  const double rLo = std::max(std::min(ra, rb), 0.0), rHi = std::max(ra, rb);
  const Quadratic q = quadraticOf(*this, o, d);
  double a0, a1, b0, b1;
  if (q.qa <= 0.0) {  // parallel to the cylinder's axis: at one radius throughout
    const double r = std::sqrt(q.qc);
    if (r < rLo || r > rHi) return 0;
    lo[0] = tMin, hi[0] = tMax;
    return 1;
  }
  if (!q.roots(rHi, a0, a1)) return 0;
  double cand[2][2] = {{a0, a1}, {1.0, 0.0}};
  if (rLo > 0.0 && q.roots(rLo, b0, b1)) cand[0][1] = std::min(a1, b0), cand[1][0] = std::max(a0, b1), cand[1][1] = a1;
  int n = 0;
  for (auto& c : cand) {
    const double s = std::max(c[0], tMin), e = std::min(c[1], tMax);
    if (s <= e) lo[n] = s, hi[n] = e, ++n;
  }
  return n;
}

}  // namespace inim
