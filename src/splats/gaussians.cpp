#include "splats/gaussians.h"

namespace inim {

void Gaussians::resize(size_t n, int degree) {
  shDegree = degree;
  position.assign(n, Vec3(0.0f));
  rotation.assign(n, glm::vec4(1.0f, 0.0f, 0.0f, 0.0f));
  scale.assign(n, Vec3(1.0f));
  opacity.assign(n, 0.0f);
  sh.assign(n * size_t(splatShCount(degree)) * 3, 0.0f);
}

glm::mat3 quaternionToMatrix(const glm::vec4& q) {
  const float w = q.x, x = q.y, y = q.z, z = q.w;
  glm::mat3 R;  // glm is column-major: R[col][row]
  R[0] = Vec3(1 - 2 * (y * y + z * z), 2 * (x * y + w * z), 2 * (x * z - w * y));
  R[1] = Vec3(2 * (x * y - w * z), 1 - 2 * (x * x + z * z), 2 * (y * z + w * x));
  R[2] = Vec3(2 * (x * z + w * y), 2 * (y * z - w * x), 1 - 2 * (x * x + y * y));
  return R;
}

}  // namespace inim
