#pragma once
// The paper's gimbal (docs/design.md, viewing poses): the display turns about its centre
// (the display-frame origin) while the camera stays put on the world +z axis, looking at the
// origin with y up.
//
// World frame: the display frame of the unrotated display. Display -> world:
//     p_world = Ry(h) * Rx(-v) * p_display
// (Ry, Rx: right-handed rotations about +y and +x; the vertical tilt is applied first).
// Sign convention:
//   +H (rotHDeg > 0): the display turns so that its RIGHT edge (+x) moves AWAY from the camera
//                     and its normal swings toward +x; the camera then sees it from the
//                     display's left, i.e. the camera sits at azimuth -H in the display frame.
//   +V (rotVDeg > 0): the display tilts so that its TOP edge (+y) moves AWAY from the camera;
//                     the camera then sees it from below (elevation -V in the display frame).
// The camera's eye (entrance-pupil centre for the real lens) is at (0, 0, distanceMm) in the
// world. The simulation works in the display frame: the camera pose is expressed there
// (cameraPose()), so camera rays come out of the camera model already in the display frame.
// Focus (camera_config.h) defaults to the eye-to-centre distance, i.e. the MLA plane.
#include <string>
#include <vector>

#include "camera/camera_model.h"
#include "core/transform.h"

namespace inim {

struct DisplayPose {
  double rotHDeg = 0.0;        // about the display's vertical axis (y)
  double rotVDeg = 0.0;        // about its horizontal axis (x)
  double distanceMm = 350.0;   // eye (entrance pupil) to the display centre, world +z

  // Display frame -> world frame (a rotation about the display centre).
  Transform displayToWorld() const;
  Transform worldToDisplay() const { return displayToWorld().inverse(); }
  // The camera's pose in the display frame: eye R^T (0, 0, D), looking at the origin, up R^T y.
  ViewingPose cameraPose() const;
  // The display's unit normal (+z of the display) in the world frame.
  Vec3d normalInWorld() const;
  // "H +7 deg, V 0 deg, camera 350 mm"
  std::string describe() const;
};

// A pose with the names reports use for it.
struct NamedPose {
  std::string name;   // file-name stem: centre, left, right, top, bottom
  std::string label;  // "0°", "H -7°", ...
  DisplayPose pose;
};

// The paper's Fig. 11 set: centre, left (H -a), right (H +a), top (V +a), bottom (V -a): the
// display turned about its vertical axis for left/right and its horizontal axis for top/bottom.
std::vector<NamedPose> fig11Poses(double angleDeg, double distanceMm);

}  // namespace inim
