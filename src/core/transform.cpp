#include "core/transform.h"

#include <cmath>
#include <glm/gtc/matrix_transform.hpp>

#include "core/error.h"

namespace inim {

Transform Transform::fromMatrix(const glm::dmat4& m, const std::string& context) {
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r)
      if (!std::isfinite(m[c][r])) throw InputError("", context, "non-finite entry", "a finite matrix");
  double det = glm::determinant(glm::dmat3(m));
  double norm = 0.0;
  for (int c = 0; c < 3; ++c) norm = std::max(norm, glm::length(glm::dvec3(m[c])));
  if (!(std::abs(det) > 1e-12 * norm * norm * norm) || norm == 0.0)
    throw InputError("", context, "singular (determinant " + std::to_string(det) + ")",
                     "an invertible transform");
  return Transform(m, glm::inverse(m));
}

Transform Transform::translate(const Vec3d& t) {
  return Transform(glm::translate(glm::dmat4(1.0), t), glm::translate(glm::dmat4(1.0), -t));
}

Transform Transform::scale(const Vec3d& s, const std::string& context) {
  return fromMatrix(glm::scale(glm::dmat4(1.0), s), context);
}

Transform Transform::rotate(double angleDeg, const Vec3d& axis) {
  double len = glm::length(axis);
  if (!(len > 0.0)) throw InputError("", "rotation axis", "zero vector", "a non-zero axis");
  glm::dmat4 r = glm::rotate(glm::dmat4(1.0), glm::radians(angleDeg), axis / len);
  return Transform(r, glm::transpose(r));
}

Transform Transform::rotateXYZ(const Vec3d& a) {
  return rotate(a.z, {0, 0, 1}) * rotate(a.y, {0, 1, 0}) * rotate(a.x, {1, 0, 0});
}

Transform Transform::operator*(const Transform& rhs) const {
  return Transform(m_ * rhs.m_, rhs.inv_ * inv_);
}

Transform Transform::inverse() const { return Transform(inv_, m_); }

double Transform::scaleFactor() const {
  return std::cbrt(std::abs(glm::determinant(glm::dmat3(m_))));
}

}  // namespace inim
