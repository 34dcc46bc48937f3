#pragma once
// Small value types for geometry, in millimetres, on GLM.
// Float for rays and hits (Embree is single precision); double where optics needs it.
#include <glm/glm.hpp>
#include <limits>

namespace inim {

using Vec2 = glm::vec2;
using Vec3 = glm::vec3;
using Point3 = glm::vec3;
using Vec3d = glm::dvec3;
using Point3d = glm::dvec3;
using Mat3 = glm::mat3;
using Mat4 = glm::mat4;

constexpr float kPi = 3.14159265358979323846f;
constexpr double kPiD = 3.14159265358979323846;
constexpr float kInvPi = 0.31830988618379067154f;
constexpr float kInfinity = std::numeric_limits<float>::infinity();

inline float radians(float deg) { return deg * (kPi / 180.0f); }
inline float degrees(float rad) { return rad * (180.0f / kPi); }

// A ray with its valid parameter interval; d need not be normalized unless stated.
struct Ray {
  Point3 o{0.0f};
  Vec3 d{0.0f, 0.0f, 1.0f};
  float tMin = 0.0f;
  float tMax = kInfinity;
  Point3 at(float t) const { return o + t * d; }
};

// Orthonormal frame built from a unit normal (Duff et al. 2017, branchless).
struct Frame {
  Vec3 x, y, z;
  static Frame fromZ(const Vec3& n) {
    float sign = std::copysign(1.0f, n.z);
    float a = -1.0f / (sign + n.z);
    float b = n.x * n.y * a;
    return {Vec3(1.0f + sign * n.x * n.x * a, sign * b, -sign * n.x),
            Vec3(b, sign + n.y * n.y * a, -n.y), n};
  }
  Vec3 toLocal(const Vec3& v) const { return {glm::dot(v, x), glm::dot(v, y), glm::dot(v, z)}; }
  Vec3 fromLocal(const Vec3& v) const { return v.x * x + v.y * y + v.z * z; }
};

inline float maxComponent(const Vec3& v) { return std::max(v.x, std::max(v.y, v.z)); }
inline bool isFinite(const Vec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

}  // namespace inim
