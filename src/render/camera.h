#pragma once
// Cameras that look at a Field: pinhole and thin lens, posed by eye/look-at/up.
// Image convention (DESIGN.md): row 0 at the top, column 0 at the left, pixel centres at
// half-integers.
#include "core/geometry.h"

namespace inim {

struct CameraPose {
  Point3 eye{0.0f, 0.0f, 350.0f};
  Point3 lookAt{0.0f};
  Vec3 up{0.0f, 1.0f, 0.0f};
};

struct CameraSpec {
  CameraPose pose;
  int width = 960, height = 540;
  float hfovDeg = 26.0f;       // horizontal field of view
  float apertureMm = 0.0f;     // thin-lens aperture diameter; 0 = pinhole
  float focusDistanceMm = 0.0f;  // along the optical axis; 0 = |lookAt - eye|
};

class ThinLensCamera {
 public:
  // Throws InputError for non-positive sizes/fov or a degenerate pose.
  explicit ThinLensCamera(const CameraSpec& spec);
  // Ray through film position (px, py) in pixels (continuous; (0,0) is the top-left corner)
  // with lens sample u in [0,1)^2 (ignored for a pinhole). Unit direction.
  Ray generateRay(float px, float py, Vec2 uLens) const;
  const CameraSpec& spec() const { return spec_; }
  bool isPinhole() const { return spec_.apertureMm <= 0.0f; }

 private:
  CameraSpec spec_;
  Frame frame_;  // x right, y up, z backward (camera looks along -z)
  float tanHalfX_, tanHalfY_, focus_;
};

}  // namespace inim
