#pragma once
// A pinhole or thin-lens camera given by its horizontal field of view: the camera of
// `inim render` and `inim capture`, one variant of the CameraModel family
// (camera/camera_model.h).
//
// It differs from PinholeCameraModel / ThinLensCameraModel in what it is given (a field of view
// and an aperture diameter instead of a sensor and a focal length) and in how it maps a sample
// to a ray, so it is its own variant rather than a setting of those: rays are computed in single
// precision from the pose rounded to float, a thin-lens sample is aimed at the point of the
// chief ray at the focus distance along the optical axis, and the weight is always 1 (no natural
// vignetting). Those are the images `inim render` has always made; changing any of them would
// change every rendered and captured image.
//
// The sensor it reports is the one of an equivalent pinhole at an image distance of 1 mm: the
// pitch is 2 tan(hfov / 2) / width, pixels are square.
#include <string>

#include "camera/camera_model.h"

namespace inim {

struct FovCameraSettings {
  ViewingPose pose;              // display frame, mm; rounded to float by the camera
  int width = 960, height = 540;
  float hfovDeg = 26.0f;         // horizontal field of view
  float apertureMm = 0.0f;       // thin-lens aperture diameter; 0 = pinhole
  float focusDistanceMm = 0.0f;  // along the optical axis; 0 = |lookAt - eye|
};

// A point as the camera holds its pose: rounded to float. Callers that derive other quantities
// from the pose (capture's camera-to-world matrices) round with it to agree with the camera.
Point3d roundedToFloat(const Point3d& p);

class FovCameraModel final : public CameraModel {
 public:
  // InputError (keys width, height, hfov_deg, aperture_mm, pose, pose.up) for a non-positive
  // image size, a field of view outside (0, 179) degrees, a negative aperture or a degenerate
  // pose.
  explicit FovCameraModel(const FovCameraSettings& settings);

  // Weight 1 for every ray; the wavelength is ignored. Continuous pixel position, (0, 0) at the
  // top-left corner; lens sample ignored for a pinhole.
  float generateRay(Vec2 pixel, Vec2 uLens, float lambdaNm, Ray& out) const override;
  using CameraModel::generateRay;

  CameraModelKind kind() const override { return isPinhole() ? CameraModelKind::Pinhole : CameraModelKind::ThinLens; }
  std::string describe() const override;
  double horizontalFovDeg() const override { return settings_.hfovDeg; }

  const FovCameraSettings& settings() const { return settings_; }
  bool isPinhole() const { return settings_.apertureMm <= 0.0f; }

 private:
  FovCameraSettings settings_;
  Point3 eye_;     // the pose in float
  Frame frame_;    // x right, y up, z backward (the camera looks along -z), float
  float tanHalfX_, tanHalfY_, focusMm_;
};

}  // namespace inim
