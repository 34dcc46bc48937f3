#include "dataset/intrinsics.h"

#include <algorithm>
#include <cmath>

namespace inim {

Intrinsics Intrinsics::resized(int newWidth, int newHeight) const {
  // Pixel edges scale exactly: new u = old u * (W'/W) in the half-integer convention.
  double sx = double(newWidth) / width, sy = double(newHeight) / height;
  Intrinsics r = *this;
  r.width = newWidth;
  r.height = newHeight;
  r.fx *= sx;
  r.cx *= sx;
  r.fy *= sy;
  r.cy *= sy;
  return r;
}

double Intrinsics::tanHalfFov() const {
  return std::max(0.5 * width / fx, 0.5 * height / fy);
}

glm::dvec2 distortNormalized(const Intrinsics& k, glm::dvec2 p) {
  double x = p.x, y = p.y, r2 = x * x + y * y;
  double radial = 1.0 + r2 * (k.k1 + r2 * k.k2);
  return {x * radial + 2.0 * k.p1 * x * y + k.p2 * (r2 + 2.0 * x * x),
          y * radial + k.p1 * (r2 + 2.0 * y * y) + 2.0 * k.p2 * x * y};
}

glm::dvec2 undistortNormalized(const Intrinsics& k, glm::dvec2 target) {
  if (!k.distorted()) return target;
  // Newton on f(p) = distort(p) - target with the analytic Jacobian; the distorted point is a
  // good start because real distortion is a small perturbation of the identity.
  glm::dvec2 p = target;
  for (int it = 0; it < 20; ++it) {
    double x = p.x, y = p.y, r2 = x * x + y * y;
    double radial = 1.0 + r2 * (k.k1 + r2 * k.k2);
    double dr = 2.0 * (k.k1 + 2.0 * k.k2 * r2);  // d radial / d(x or y), divided by x or y
    glm::dvec2 f = distortNormalized(k, p) - target;
    double a = radial + x * x * dr + 2.0 * k.p1 * y + 6.0 * k.p2 * x;  // dfx/dx
    double b = x * y * dr + 2.0 * k.p1 * x + 2.0 * k.p2 * y;           // dfx/dy = dfy/dx
    double d = radial + y * y * dr + 6.0 * k.p1 * y + 2.0 * k.p2 * x;  // dfy/dy
    double det = a * d - b * b;
    if (!(std::abs(det) > 1e-300)) break;
    glm::dvec2 step((d * f.x - b * f.y) / det, (a * f.y - b * f.x) / det);
    p -= step;
    if (std::abs(step.x) + std::abs(step.y) < 1e-15) break;
  }
  return p;
}

glm::dvec2 pixelToNormalized(const Intrinsics& k, glm::dvec2 px) {
  return undistortNormalized(k, {(px.x - k.cx) / k.fx, (px.y - k.cy) / k.fy});
}

glm::dvec2 normalizedToPixel(const Intrinsics& k, glm::dvec2 xy) {
  glm::dvec2 d = distortNormalized(k, xy);
  return {d.x * k.fx + k.cx, d.y * k.fy + k.cy};
}

}  // namespace inim
