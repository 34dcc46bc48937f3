#include "capture/capture_poses.h"

#include <cmath>

namespace inim {

std::vector<glm::dvec3> capDirections(int n, double minElDeg, double maxElDeg) {
  const double d2r = M_PI / 180.0;
  // cos(polar) = sin(elevation): uniform in it is uniform in area on the sphere.
  double zLo = std::sin(minElDeg * d2r), zHi = std::sin(maxElDeg * d2r);
  const double golden = M_PI * (3.0 - std::sqrt(5.0));  // 2 pi (1 - 1/phi)
  std::vector<glm::dvec3> dirs;
  dirs.reserve(size_t(std::max(n, 0)));
  for (int i = 0; i < n; ++i) {
    double z = zHi - (zHi - zLo) * (i + 0.5) / n;
    double r = std::sqrt(std::max(0.0, 1.0 - z * z));
    double phi = golden * i;
    dirs.emplace_back(r * std::cos(phi), r * std::sin(phi), z);
  }
  return dirs;
}

glm::dmat4 lookAtCameraToWorld(const glm::dvec3& eye, const glm::dvec3& target, glm::dvec3 up) {
  glm::dvec3 z = glm::normalize(eye - target);  // camera +z points back, away from the target
  if (glm::length(glm::cross(up, z)) < 1e-3) up = glm::dvec3(0.0, 0.0, -1.0);
  glm::dvec3 x = glm::normalize(glm::cross(up, z));
  glm::dvec3 y = glm::cross(z, x);
  glm::dmat4 m(1.0);
  m[0] = glm::dvec4(x, 0.0);
  m[1] = glm::dvec4(y, 0.0);
  m[2] = glm::dvec4(z, 0.0);
  m[3] = glm::dvec4(eye, 1.0);
  return m;
}

}  // namespace inim
