#include "display_view/display_pose.h"

#include <cmath>
#include <cstdio>

#include "core/error.h"

namespace inim {

Transform DisplayPose::displayToWorld() const {
  if (!std::isfinite(rotHDeg)) throw InputError("", "--rot-h-deg", std::to_string(rotHDeg), "a finite angle in degrees");
  if (!std::isfinite(rotVDeg)) throw InputError("", "--rot-v-deg", std::to_string(rotVDeg), "a finite angle in degrees");
  return Transform::rotate(rotHDeg, {0.0, 1.0, 0.0}) * Transform::rotate(-rotVDeg, {1.0, 0.0, 0.0});
}

ViewingPose DisplayPose::cameraPose() const {
  if (!(distanceMm > 0.0) || !std::isfinite(distanceMm))
    throw InputError("", "--distance-mm", std::to_string(distanceMm), "a camera distance > 0 mm");
  const Transform w2d = worldToDisplay();
  ViewingPose p;
  p.eye = w2d.point(Point3d(0.0, 0.0, distanceMm));
  p.lookAt = Point3d(0.0);
  p.up = glm::normalize(w2d.vector(Vec3d(0.0, 1.0, 0.0)));
  return p;
}

Vec3d DisplayPose::normalInWorld() const { return glm::normalize(displayToWorld().vector(Vec3d(0.0, 0.0, 1.0))); }

std::string DisplayPose::describe() const {
  char b[128];
  std::snprintf(b, sizeof b, "H %+g deg, V %+g deg, camera at %g mm", rotHDeg, rotVDeg, distanceMm);
  return b;
}

std::vector<NamedPose> fig11Poses(double a, double distanceMm) {
  auto label = [](const char* axis, double deg) {
    char b[32];
    std::snprintf(b, sizeof b, "%s %+g°", axis, deg);
    return std::string(b);
  };
  std::vector<NamedPose> poses = {{"centre", "0°", {0.0, 0.0, distanceMm}},
                                  {"left", label("H", -a), {-a, 0.0, distanceMm}},
                                  {"right", label("H", a), {a, 0.0, distanceMm}},
                                  {"top", label("V", a), {0.0, a, distanceMm}},
                                  {"bottom", label("V", -a), {0.0, -a, distanceMm}}};
  return poses;
}

}  // namespace inim
