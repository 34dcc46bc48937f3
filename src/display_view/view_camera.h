#pragma once
// The viewing camera of `inim view` / `inim reference`: a camera description
// (optics/cameras/*.json) at a DisplayPose, with the image size and focus the command asks for.
//
// Image size: by default the sensor's own resolution. A smaller (or larger) width W keeps the
// sensor's physical size along x and scales the pixel pitch by sensorW / W, so the field of view
// (and the framing) stays the same and each pixel integrates a proportionally larger area; the
// height defaults to round(W * sensorH / sensorW), and an explicit height H gives a sensor
// H * pitch' tall (another aspect ratio crops or extends the frame vertically).
// Focus: `focusMm` (from the entrance pupil) > 0 overrides the description's focus distance; by
// default the camera is focused on the display centre (the MLA plane), at the pose distance.
#include <memory>
#include <optional>

#include "camera/camera_config.h"
#include "display_view/display_pose.h"

namespace inim {

struct ViewCameraOptions {
  std::optional<CameraModelKind> kind;  // default: the description's model
  int width = 0, height = 0;            // 0: the sensor's resolution (see above)
  double focusMm = 0.0;                 // 0: the description's, else the pose distance
};

// The sensor geometry for the requested image size. InputError for sizes < 1.
SensorGeometry viewSensorGeometry(const CameraDescription& c, int width, int height);

// Builds the camera model in the DISPLAY frame (pose.cameraPose()), so its rays need no
// further transform. InputError for a bad size, focus, or pose. `samePrecomputed`: a camera
// this made from the same description at another pose; a real lens with the same sensor and
// focus is then that one moved (RealLensCameraModel::atPose), not focused and scanned again.
std::unique_ptr<CameraModel> makeViewCamera(const CameraDescription& c, const DisplayPose& pose,
                                            const ViewCameraOptions& o,
                                            const CameraModel* samePrecomputed = nullptr);

}  // namespace inim
