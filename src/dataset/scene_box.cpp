#include "dataset/scene_box.h"

#include <algorithm>
#include <cmath>

namespace inim {

bool closestPointToLines(const std::vector<glm::dvec3>& o, const std::vector<glm::dvec3>& d,
                         glm::dvec3& point) {
  // Minimise sum |(I - d d^T)(p - o)|^2: A p = b with A = sum (I - d d^T), b = sum (I - d d^T) o.
  glm::dmat3 A(0.0);
  glm::dvec3 b(0.0);
  for (size_t i = 0; i < o.size(); ++i) {
    glm::dmat3 P = glm::dmat3(1.0) - glm::outerProduct(d[i], d[i]);
    A += P;
    b += P * o[i];
  }
  // Parallel axes leave A rank 2; compare det to the scale of its diagonal.
  double tr = A[0][0] + A[1][1] + A[2][2];
  double det = glm::determinant(A);
  if (o.empty() || !(det > 1e-6 * tr * tr * tr / 27.0)) return false;
  point = glm::inverse(A) * b;
  return true;
}

SceneBoxEstimate estimateSceneBox(const std::vector<DatasetFrame>& frames) {
  SceneBoxEstimate e;
  if (frames.empty()) return e;
  std::vector<glm::dvec3> origins, dirs;
  glm::dvec3 meanPos(0.0), meanDir(0.0);
  double tanHalf = 0.0;
  for (const DatasetFrame& f : frames) {
    origins.push_back(f.position());
    dirs.push_back(f.forward());
    meanPos += origins.back();
    meanDir += dirs.back();
    tanHalf += f.intrinsics.tanHalfFov();
  }
  const double n = double(frames.size());
  meanPos /= n;
  tanHalf /= n;
  glm::dvec3 centre;
  if (!closestPointToLines(origins, dirs, centre)) {
    e.axesConverge = false;
    double spread = 0.0;
    for (const auto& p : origins) spread += glm::length(p - meanPos);
    spread = std::max(spread / n, 1e-6);
    double len = glm::length(meanDir);
    centre = meanPos + (len > 0 ? meanDir / len : glm::dvec3(0, 0, -1)) * spread;
  }
  double meanDist = 0.0, minDist = INFINITY, maxDist = 0.0;
  for (const auto& p : origins) {
    double dist = glm::length(p - centre);
    meanDist += dist;
    minDist = std::min(minDist, dist);
    maxDist = std::max(maxDist, dist);
  }
  meanDist /= n;
  double half = meanDist * tanHalf;
  e.box.lo = centre - glm::dvec3(half);
  e.box.hi = centre + glm::dvec3(half);
  double radius = half * std::sqrt(3.0);
  e.nearPlane = std::max(minDist - radius, 0.01 * meanDist);
  e.farPlane = maxDist + radius;
  return e;
}

}  // namespace inim
