#include "display_view/view_camera.h"

#include <cmath>
#include <cstdio>

#include "camera/lens_analysis.h"
#include "core/error.h"
#include "core/size_budget.h"

namespace inim {

SensorGeometry viewSensorGeometry(const CameraDescription& c, int width, int height) {
  SensorGeometry g = c.sensor.geometry();
  if (width < 0 || height < 0)
    throw InputError("", width < 0 ? "--width" : "--height", std::to_string(width < 0 ? width : height),
                     "a whole number of pixels >= 1");
  if (width == 0 && height == 0) return g;
  const double physW = g.widthMm(), physH = g.heightMm();
  if (width == 0) width = std::max(1, int(std::lround(height * physW / physH)));
  if (width < 1) throw InputError("", "--width", std::to_string(width), "a whole number of pixels >= 1");
  const double pitch = physW / width;
  if (height == 0) height = std::max(1, int(std::lround(physH / pitch)));
  if (height < 1) throw InputError("", "--height", std::to_string(height), "a whole number of pixels >= 1");
  // Before the renderer's buffers: the RGB image and its accumulators, about 8 floats a pixel.
  const std::string size = std::to_string(width) + " x " + std::to_string(height);
  checkAllocation("", "--width/--height", size, {{double(width) * height, 8 * sizeof(float)}}, "a " + size + " view");
  g.widthPx = width;
  g.heightPx = height;
  g.pitchMm = pitch;
  return g;
}

std::unique_ptr<CameraModel> makeViewCamera(const CameraDescription& c, const DisplayPose& dp,
                                            const ViewCameraOptions& o, const CameraModel* samePrecomputed) {
  const ViewingPose pose = dp.cameraPose();
  const SensorGeometry sensor = viewSensorGeometry(c, o.width, o.height);
  if (o.focusMm < 0.0 || !std::isfinite(o.focusMm))
    throw InputError("", "--focus-mm", std::to_string(o.focusMm), "a focus distance > 0 mm");
  const double focus = o.focusMm > 0.0 ? o.focusMm
                       : c.focusDistanceMm > 0.0 ? c.focusDistanceMm
                                                 : glm::length(pose.lookAt - pose.eye);
  const CameraModelKind k = o.kind.value_or(c.model);
  if (k == CameraModelKind::RealLens) {
    const RealLensSettings s = realLensSettings(c, focus);
    if (samePrecomputed)
      if (auto moved = samePrecomputed->sameLensAt(pose, sensor, s)) return moved;
    return std::make_unique<RealLensCameraModel>(c.lens, sensor, pose, s);
  }
  LensSystem lens = c.lens;
  if (c.fNumber > 0.0) setFNumber(lens, c.fNumber);
  const LensInfo info = analyzeLens(lens);
  auto thin = std::make_unique<ThinLensCameraModel>(sensor, pose, info.eflMm, info.fNumber, focus);
  if (k == CameraModelKind::ThinLens) return thin;
  return std::make_unique<PinholeCameraModel>(sensor, pose, thin->sensorDistanceMm());
}

}  // namespace inim
