#include "render/camera.h"

#include <cmath>

#include "core/error.h"
#include "core/sampling.h"

namespace inim {

ThinLensCamera::ThinLensCamera(const CameraSpec& spec) : spec_(spec) {
  if (spec.width <= 0 || spec.height <= 0)
    throw InputError("", "--width/--height", std::to_string(spec.width) + "x" + std::to_string(spec.height),
                     "positive image size");
  if (!(spec.hfovDeg > 0.0f && spec.hfovDeg < 179.0f))
    throw InputError("", "--fov", std::to_string(spec.hfovDeg), "a field of view in (0, 179) degrees");
  if (!(spec.apertureMm >= 0.0f))
    throw InputError("", "--aperture", std::to_string(spec.apertureMm), "an aperture >= 0 mm");
  Vec3 back = spec.pose.eye - spec.pose.lookAt;
  float dist = glm::length(back);
  if (!(dist > 0.0f) || !isFinite(back))
    throw InputError("", "camera pose", "eye == look-at", "distinct eye and look-at points");
  Vec3 z = back / dist;
  Vec3 x = glm::cross(spec.pose.up, z);
  if (!(glm::length(x) > 1e-6f))
    throw InputError("", "camera up", "parallel to the view direction", "an up vector not along the view");
  x = glm::normalize(x);
  frame_ = {x, glm::cross(z, x), z};
  tanHalfX_ = std::tan(radians(spec.hfovDeg) * 0.5f);
  tanHalfY_ = tanHalfX_ * float(spec.height) / float(spec.width);
  focus_ = spec.focusDistanceMm > 0.0f ? spec.focusDistanceMm : dist;
}

Ray ThinLensCamera::generateRay(float px, float py, Vec2 uLens) const {
  // Camera space: x right, y up, looking along -z.
  float sx = (2.0f * px / spec_.width - 1.0f) * tanHalfX_;
  float sy = (1.0f - 2.0f * py / spec_.height) * tanHalfY_;
  Vec3 dirCam(sx, sy, -1.0f);
  Point3 originCam(0.0f);
  if (!isPinhole()) {
    // Points on the plane of focus are sharp: aim the lens sample at them.
    Point3 focusPoint = dirCam * focus_;
    Vec2 lens = sampleUniformDiskConcentric(uLens) * (0.5f * spec_.apertureMm);
    originCam = Point3(lens.x, lens.y, 0.0f);
    dirCam = focusPoint - originCam;
  }
  Ray r;
  r.o = spec_.pose.eye + frame_.fromLocal(originCam);
  r.d = glm::normalize(frame_.fromLocal(dirCam));
  return r;
}

}  // namespace inim
