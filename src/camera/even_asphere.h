#pragma once
// Even aspheres, as Zemax's EVENASPH surface defines them: a conic plus a polynomial in r^2,
//   z(r) = c r^2 / (1 + sqrt(1 - (1+k) c^2 r^2)) + a1 r^2 + a2 r^4 + ... + an r^(2n),
// written here in rho = r^2 so that the sag and its slope are smooth through the axis.
// The conic part alone (no coefficients) is lens_system.h's intersectConic / conicNormal.
#include <vector>

#include "core/geometry.h"

namespace inim {

// The surface of vertex curvature c, conic k and coefficients a[i] on r^(2i+2), in mm units
// (a[i] in mm^(-2i-1)), with its vertex at the origin.
struct EvenAsphere {
  double c = 0.0;
  double k = 0.0;
  const std::vector<double>* a = nullptr;  // null or empty: a conic

  // z(rho); NaN where the conic's square root is not real.
  double sag(double rho) const;
  // dz/drho, = c / (2 sqrt(1 - (1+k) c^2 rho)) + sum (i+1) a_i rho^i; NaN as sag.
  double slope(double rho) const;
  // Both at once (one square root, one pass over the terms): the tracer's inner loop.
  void sagAndSlope(double rho, double& z, double& dz) const;
};

// Newton's method on f(t) = z(t) - sag(x(t)^2 + y(t)^2), started at the conic's (or, when the ray
// misses the conic, the vertex plane's) intersection. It stops when a step is below
// kAsphereNewtonTolMm. Newton converges quadratically: after a step of 1e-6 mm the root is within
// about C 1e-12 mm, C = |f''/2f'| (below 1/mm for lens surfaces met at less than 80 degrees), so
// one more step would only confirm it. test_even_asphere.cpp checks the result against bisection
// to 1e-9 mm, and the step count, over the whole aperture of a steep asphere.
constexpr int kAsphereNewtonMaxSteps = 40;
constexpr double kAsphereNewtonTolMm = 1e-6;

// The smallest root t > tMin near the start, or -1 when Newton fails (the ray misses the surface
// or leaves the region where it is defined). `steps` receives the number of Newton steps taken.
// `slopeAtHit` receives dz/drho at the root, which gives the normal without another evaluation.
double intersectEvenAsphere(const Vec3d& o, const Vec3d& d, const EvenAsphere& s, double tMin = 1e-9,
                            int* steps = nullptr, double* slopeAtHit = nullptr);
// Unit normal at p (on the surface), pointing toward -z at the vertex, as conicNormal.
Vec3d evenAsphereNormal(const Vec3d& p, const EvenAsphere& s);
// The same from dz/drho at p.
inline Vec3d evenAsphereNormalFromSlope(const Vec3d& p, double slope) {
  const double g = 2.0 * slope;
  return glm::normalize(Vec3d(g * p.x, g * p.y, -1.0));
}

}  // namespace inim
