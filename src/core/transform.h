#pragma once
// Affine transforms (scale, rotation, translation) with a cached inverse.
#include <string>

#include "core/geometry.h"

namespace inim {

class Transform {
 public:
  Transform() = default;
  // Throws InputError (naming `context`) if m is singular or not finite.
  static Transform fromMatrix(const glm::dmat4& m, const std::string& context = "transform");
  static Transform translate(const Vec3d& t);
  static Transform scale(const Vec3d& s, const std::string& context = "scale");
  // Rotation by angle (degrees) about an axis through the origin.
  static Transform rotate(double angleDeg, const Vec3d& axis);
  // Rotations about x, then y, then z (degrees): R = Rz * Ry * Rx.
  static Transform rotateXYZ(const Vec3d& anglesDeg);

  Transform operator*(const Transform& rhs) const;  // applies rhs first
  Transform inverse() const;

  Point3d point(const Point3d& p) const { return Point3d(m_ * glm::dvec4(p, 1.0)); }
  Vec3d vector(const Vec3d& v) const { return Vec3d(m_ * glm::dvec4(v, 0.0)); }
  Vec3d normal(const Vec3d& n) const {  // transforms with the inverse transpose
    return Vec3d(glm::transpose(inv_) * glm::dvec4(n, 0.0));
  }
  Point3 point(const Point3& p) const { return Point3(point(Point3d(p))); }
  Vec3 vector(const Vec3& v) const { return Vec3(vector(Vec3d(v))); }
  Vec3 normal(const Vec3& n) const { return Vec3(normal(Vec3d(n))); }
  Ray ray(const Ray& r) const { return {point(r.o), vector(r.d), r.tMin, r.tMax}; }

  const glm::dmat4& matrix() const { return m_; }
  const glm::dmat4& inverseMatrix() const { return inv_; }
  bool isIdentity() const { return m_ == glm::dmat4(1.0); }
  // Uniform scale factor (cube root of |det| of the linear part).
  double scaleFactor() const;

 private:
  Transform(const glm::dmat4& m, const glm::dmat4& inv) : m_(m), inv_(inv) {}
  glm::dmat4 m_{1.0};
  glm::dmat4 inv_{1.0};
};

}  // namespace inim
