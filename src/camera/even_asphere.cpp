#include "camera/even_asphere.h"

#include <cmath>
#include <limits>

#include "camera/lens_system.h"

namespace inim {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

bool hasTerms(const EvenAsphere& s) { return s.a != nullptr && !s.a->empty(); }

}  // namespace

double EvenAsphere::sag(double rho) const {
  double z = 0.0;
  if (c != 0.0) {
    const double arg = 1.0 - (1.0 + k) * c * c * rho;
    if (arg < 0.0) return kNaN;
    z = c * rho / (1.0 + std::sqrt(arg));
  }
  if (a) {
    double poly = 0.0;  // Horner: rho (a0 + rho (a1 + ...))
    for (size_t i = a->size(); i-- > 0;) poly = poly * rho + (*a)[i];
    z += poly * rho;
  }
  return z;
}

double EvenAsphere::slope(double rho) const {
  double z, dz;
  sagAndSlope(rho, z, dz);
  return dz;
}

void EvenAsphere::sagAndSlope(double rho, double& z, double& dz) const {
  z = 0.0, dz = 0.0;
  if (c != 0.0) {
    const double arg = 1.0 - (1.0 + k) * c * c * rho;
    if (arg <= 0.0) {
      z = dz = kNaN;
      return;
    }
    const double q = std::sqrt(arg);
    z = c * rho / (1.0 + q);
    dz = 0.5 * c / q;
  }
  if (a) {
    double poly = 0.0, dpoly = 0.0;
    for (size_t i = a->size(); i-- > 0;) {
      poly = poly * rho + (*a)[i];
      dpoly = dpoly * rho + double(i + 1) * (*a)[i];
    }
    z += poly * rho;
    dz += dpoly;
  }
}

double intersectEvenAsphere(const Vec3d& o, const Vec3d& d, const EvenAsphere& s, double tMin, int* steps,
                            double* slopeAtHit) {
  if (steps) *steps = 0;
  if (!hasTerms(s)) {
    const double t = intersectConic(o, d, s.c, s.k, tMin);
    if (slopeAtHit && t > tMin) {
      const Vec3d p = o + t * d;
      *slopeAtHit = s.slope(p.x * p.x + p.y * p.y);
    }
    return t;
  }
  double t = intersectConic(o, d, s.c, s.k, tMin);
  if (t < 0.0 && t <= tMin) {
    if (d.z == 0.0) return -1.0;
    t = -o.z / d.z;
  }
  for (int i = 1; i <= kAsphereNewtonMaxSteps; ++i) {
    const Vec3d p = o + t * d;
    double z, dz;
    s.sagAndSlope(p.x * p.x + p.y * p.y, z, dz);
    const double f = p.z - z;
    const double df = d.z - 2.0 * dz * (p.x * d.x + p.y * d.y);
    if (!std::isfinite(f) || !std::isfinite(df) || df == 0.0) return -1.0;
    const double step = f / df;
    t -= step;
    if (steps) *steps = i;
    if (std::abs(step) <= kAsphereNewtonTolMm) {
      if (slopeAtHit) *slopeAtHit = dz;  // at the last iterate, within a step of the root
      return t > tMin ? t : -1.0;
    }
  }
  return -1.0;
}

Vec3d evenAsphereNormal(const Vec3d& p, const EvenAsphere& s) {
  if (!hasTerms(s)) return conicNormal(p, s.c, s.k);
  const double g = 2.0 * s.slope(p.x * p.x + p.y * p.y);
  return glm::normalize(Vec3d(g * p.x, g * p.y, -1.0));
}

}  // namespace inim
