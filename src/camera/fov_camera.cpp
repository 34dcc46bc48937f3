#include "camera/fov_camera.h"

#include <cmath>

#include "core/error.h"
#include "core/format.h"
#include "core/sampling.h"

namespace inim {

namespace {

// The settings checked before the base class sees them (it would report a bad size as a bad
// sensor), and the sensor of the equivalent pinhole at 1 mm.
SensorGeometry checkedSensor(const FovCameraSettings& s) {
  if (s.width <= 0) throw InputError("", "width", std::to_string(s.width), "a positive image width in pixels");
  if (s.height <= 0) throw InputError("", "height", std::to_string(s.height), "a positive image height in pixels");
  if (!(s.hfovDeg > 0.0f && s.hfovDeg < 179.0f))
    throw InputError("", "hfov_deg", formatNumber(s.hfovDeg), "a field of view in (0, 179) degrees");
  if (!(s.apertureMm >= 0.0f)) throw InputError("", "aperture_mm", formatNumber(s.apertureMm), "an aperture >= 0 mm");
  // 0 means "eye to look-at"; a negative or non-finite distance focuses nowhere (a black image).
  if (!(s.focusDistanceMm >= 0.0f && std::isfinite(s.focusDistanceMm)))
    throw InputError("", "focus_distance_mm", formatNumber(s.focusDistanceMm), "a focus distance > 0 mm");
  SensorGeometry g;
  g.widthPx = s.width;
  g.heightPx = s.height;
  g.pitchMm = 2.0 * std::tan(0.5 * double(s.hfovDeg) * M_PI / 180.0) / double(s.width);
  return g;
}

}  // namespace

Point3d roundedToFloat(const Point3d& p) {
  // Through volatile floats: GCC 12 at -O3 folds a vectorised double -> float -> double round
  // trip away (x and y keep their double values), which would break the agreement.
  volatile float x = float(p.x), y = float(p.y), z = float(p.z);
  return {x, y, z};
}

FovCameraModel::FovCameraModel(const FovCameraSettings& settings)
    : CameraModel(checkedSensor(settings), settings.pose), settings_(settings) {
  // The frame again in float, from the pose rounded to float: the rays are computed in float.
  eye_ = Point3(settings.pose.eye);
  const Vec3 back = eye_ - Point3(settings.pose.lookAt);
  const float dist = glm::length(back);
  if (!(dist > 0.0f) || !isFinite(back))
    throw InputError("", "pose", "eye == look-at", "distinct eye and look-at points");
  const Vec3 z = back / dist;
  Vec3 x = glm::cross(Vec3(settings.pose.up), z);
  if (!(glm::length(x) > 1e-6f))
    throw InputError("", "pose.up", "parallel to the view direction", "an up vector not along the view");
  x = glm::normalize(x);
  frame_ = {x, glm::cross(z, x), z};
  tanHalfX_ = std::tan(radians(settings.hfovDeg) * 0.5f);
  tanHalfY_ = tanHalfX_ * float(settings.height) / float(settings.width);
  focusMm_ = settings.focusDistanceMm > 0.0f ? settings.focusDistanceMm : dist;
}

float FovCameraModel::generateRay(Vec2 pixel, Vec2 uLens, float, Ray& out) const {
  // Camera space: x right, y up, looking along -z.
  const float sx = (2.0f * pixel.x / settings_.width - 1.0f) * tanHalfX_;
  const float sy = (1.0f - 2.0f * pixel.y / settings_.height) * tanHalfY_;
  Vec3 dirCam(sx, sy, -1.0f);
  Point3 originCam(0.0f);
  if (!isPinhole()) {
    // Points on the plane of focus are sharp: aim the lens sample at them.
    const Point3 focusPoint = dirCam * focusMm_;
    const Vec2 lens = sampleUniformDiskConcentric(uLens) * (0.5f * settings_.apertureMm);
    originCam = Point3(lens.x, lens.y, 0.0f);
    dirCam = focusPoint - originCam;
  }
  out.o = eye_ + frame_.fromLocal(originCam);
  out.d = glm::normalize(frame_.fromLocal(dirCam));
  out.tMin = 0.0f;
  out.tMax = kInfinity;
  return 1.0f;
}

std::string FovCameraModel::describe() const {
  std::string s = isPinhole() ? "pinhole camera" : "thin-lens camera, aperture " + formatNumber(settings_.apertureMm) +
                                                       " mm, focused at " + formatNumber(focusMm_) + " mm";
  return s + ", horizontal FOV " + formatNumber(settings_.hfovDeg) + " deg";
}

}  // namespace inim
