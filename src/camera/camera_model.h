#pragma once
// Viewing-camera models behind one interface: a pinhole, an ideal thin lens, and a real lens
// (sequential surfaces traced per wavelength); camera/fov_camera.h adds the pinhole / thin lens
// given by a field of view that `inim render` and `inim capture` use. Each turns a sensor
// sample into a world-space ray in the display frame (docs/design.md), with a weight.
//
// Image orientation: pixel (x, y) has (0, 0) at the top-left corner of the final image, row 0
// at the top and column 0 at the left as a person looking through the camera sees the scene;
// pixel centres are at half-integers. The real lens inverts the image on the sensor; the
// model flips it so the output is upright.
//
// Weights: the sensor irradiance for a scene of uniform radiance, relative to the image
// centre (1 there). The pinhole and the thin lens give the natural cos^4 falloff of the chief
// ray (or 1 with naturalVignetting off); the real lens gives its traced relative
// illumination, including vignetting by every element (0 for a blocked ray).
//
// Determinism: ray generation has no state and no randomness of its own; samples come from
// the caller (or from the Rng passed in).
#include <memory>
#include <string>

#include "camera/exit_pupil.h"
#include "camera/lens_analysis.h"
#include "camera/lens_focus.h"
#include "camera/lens_system.h"
#include "camera/sensor.h"
#include "core/geometry.h"
#include "core/rng.h"

namespace inim {

// Where the camera is in the display frame (mm). For the real lens `eye` is the centre of the
// entrance pupil (the centre of perspective); for the others, the pinhole / lens centre.
struct ViewingPose {
  Point3d eye{0.0, 0.0, 350.0};
  Point3d lookAt{0.0, 0.0, 0.0};
  Vec3d up{0.0, 1.0, 0.0};
};

enum class CameraModelKind { Pinhole, ThinLens, RealLens };
const char* cameraModelName(CameraModelKind k);  // "pinhole", "thin-lens", "real-lens"

// How a real-lens camera is stopped down and focused.
struct RealLensSettings {
  double fNumber = 0.0;          // 0: the design's stop
  double focusDistanceMm = 0.0;  // from the entrance pupil; 0: |lookAt - eye|; inf: infinity
  FocusMode focusMode = FocusMode::BestRms;
  double focusWavelengthNm = kLensReferenceLambdaNm;
  bool fresnel = false;          // Fresnel transmittance at every surface (off: ideal coatings)
  ExitPupilBounds::Settings pupil;  // empty wavelengths: the focus wavelength, plus 360 and
                                    // 830 nm for dispersive glass
};

class CameraModel {
 public:
  virtual ~CameraModel() = default;

  // The ray for continuous pixel position `pixel` and lens sample `uLens` in [0,1)^2 at a
  // wavelength (nm): unit direction, origin on the lens (or at the pinhole). Returns the
  // weight; 0 when the ray is vignetted (then `out` is unspecified).
  virtual float generateRay(Vec2 pixel, Vec2 uLens, float lambdaNm, Ray& out) const = 0;
  // Pixel (col, row) with a jitter and a lens sample drawn from rng (4 uniforms, in the order
  // jitter x, jitter y, lens u, lens v).
  float generateRay(int col, int row, Rng& rng, float lambdaNm, Ray& out) const;

  // False when the ray of a sample does not depend on the wavelength (no dispersive glass),
  // so one ray can carry every wavelength of a spectral sample.
  virtual bool isDispersive() const { return false; }
  virtual CameraModelKind kind() const = 0;
  virtual std::string describe() const = 0;
  // Horizontal field of view (degrees) of the chief rays at the image edges.
  virtual double horizontalFovDeg() const = 0;

  // The lens aperture in 2-D coordinates `a` in which ray generation is a fixed function of
  // (pixel, a, wavelength), for quadrature over the aperture (display_view/estimators/aperture_table.h):
  // the pinhole's lens sample in [0, 1)^2 (ignored), the thin lens's lens-plane point in units
  // of its radius (the unit disk), the real lens's point on its rear-vertex plane (mm).
  // apertureDomain: the box of `a` worth scanning for a pixel position (false: no ray passes).
  // apertureRay: the ray through `a`, with its weight per unit area of `a` (0: blocked), so that
  // the integral of the weight over the domain is the mean of generateRay's weight over uLens.
  virtual bool apertureDomain(Vec2 pixel, Vec2d& lo, Vec2d& hi) const;
  virtual float apertureRay(Vec2 pixel, const Vec2d& a, float lambdaNm, Ray& out) const;
  // This camera moved to `pose`, when a real lens with this sensor and these settings would
  // be focused and scanned exactly as this one was (so nothing need be traced again); null
  // otherwise, and for models that precompute nothing.
  virtual std::unique_ptr<CameraModel> sameLensAt(const ViewingPose& pose, const SensorGeometry& sensor,
                                                  const RealLensSettings& settings) const;

  const SensorGeometry& sensor() const { return sensor_; }
  const ViewingPose& pose() const { return pose_; }
  int width() const { return sensor_.widthPx; }
  int height() const { return sensor_.heightPx; }
  // Camera frame in the display frame: right, up, back (the camera looks along -back).
  const Vec3d& right() const { return right_; }
  const Vec3d& up() const { return up_; }
  const Vec3d& back() const { return back_; }

 protected:
  // Throws InputError for a non-positive sensor or a degenerate pose (eye at lookAt, or up
  // along the viewing direction).
  CameraModel(const SensorGeometry& sensor, const ViewingPose& pose);
  void setPose(const ViewingPose& pose);  // the same checks
  // Offset of a pixel position from the image centre on the sensor, in mm, upright: x to the
  // right and y up as seen in the final image.
  Vec2d uprightSensorOffset(Vec2 pixel) const;
  Point3d toWorld(const Vec3d& cameraLocal) const {  // camera coordinates, origin at the eye
    return pose_.eye + cameraLocal.x * right_ + cameraLocal.y * up_ + cameraLocal.z * back_;
  }
  Vec3d toWorldDir(const Vec3d& v) const { return v.x * right_ + v.y * up_ + v.z * back_; }
  static void setRay(const Point3d& o, const Vec3d& d, Ray& out);

  SensorGeometry sensor_;
  ViewingPose pose_;
  Vec3d right_{1, 0, 0}, up_{0, 1, 0}, back_{0, 0, 1};
};

class PinholeCameraModel final : public CameraModel {
 public:
  // `imageDistanceMm`: pinhole to sensor (the field of view follows from the sensor size).
  PinholeCameraModel(const SensorGeometry& sensor, const ViewingPose& pose, double imageDistanceMm,
                     bool naturalVignetting = true);
  float generateRay(Vec2 pixel, Vec2 uLens, float lambdaNm, Ray& out) const override;
  CameraModelKind kind() const override { return CameraModelKind::Pinhole; }
  std::string describe() const override;
  double horizontalFovDeg() const override;
  double imageDistanceMm() const { return d_; }

 private:
  double d_;
  bool vignetting_;
};

class ThinLensCameraModel final : public CameraModel {
 public:
  // An ideal lens of focal length f and aperture f/N (aperture diameter f/N), focused at
  // `focusDistanceMm` from the lens (> f): the sensor sits at s' = f s / (s - f).
  ThinLensCameraModel(const SensorGeometry& sensor, const ViewingPose& pose, double focalLengthMm, double fNumber,
                      double focusDistanceMm, bool naturalVignetting = true);
  float generateRay(Vec2 pixel, Vec2 uLens, float lambdaNm, Ray& out) const override;
  CameraModelKind kind() const override { return CameraModelKind::ThinLens; }
  std::string describe() const override;
  double horizontalFovDeg() const override;
  double sensorDistanceMm() const { return sPrime_; }
  double focusDistanceMm() const { return s_; }
  double apertureRadiusMm() const { return aperture_; }
  bool apertureDomain(Vec2 pixel, Vec2d& lo, Vec2d& hi) const override;
  float apertureRay(Vec2 pixel, const Vec2d& a, float lambdaNm, Ray& out) const override;

 private:
  double f_, n_, s_, sPrime_, aperture_;
  bool vignetting_;
};

class RealLensCameraModel final : public CameraModel {
 public:
  using Settings = RealLensSettings;

  // Sets the f-number, focuses by moving the sensor and precomputes the exit-pupil bounds
  // and the centre irradiance. Throws InputError for an unreachable f-number or focus.
  RealLensCameraModel(LensSystem lens, const SensorGeometry& sensor, const ViewingPose& pose,
                      const Settings& settings);
  RealLensCameraModel(LensSystem lens, const SensorGeometry& sensor, const ViewingPose& pose)
      : RealLensCameraModel(std::move(lens), sensor, pose, Settings{}) {}

  float generateRay(Vec2 pixel, Vec2 uLens, float lambdaNm, Ray& out) const override;
  bool isDispersive() const override { return lens_.isDispersive(); }
  CameraModelKind kind() const override { return CameraModelKind::RealLens; }
  std::string describe() const override;
  double horizontalFovDeg() const override;
  bool apertureDomain(Vec2 pixel, Vec2d& lo, Vec2d& hi) const override;
  float apertureRay(Vec2 pixel, const Vec2d& a, float lambdaNm, Ray& out) const override;
  std::unique_ptr<CameraModel> sameLensAt(const ViewingPose& pose, const SensorGeometry& sensor,
                                          const RealLensSettings& settings) const override;

  // A ray from the sensor point (lens x, y, on the sensor plane) toward `rearPoint` on the
  // rear-vertex plane, traced out of the lens; returns cos^4(theta) x Fresnel (0 if blocked),
  // with `lensRay` the ray leaving the front surface in lens coordinates. No normalisation.
  double traceFromSensor(const Vec2d& sensorXY, const Point3d& rearPoint, double lambdaNm, LensRay& lensRay) const;
  // The lens ray for a sensor point and a sample of the exit-pupil bounds, with the weight
  // cos^4 / (z^2 pdf) (irradiance per unit radiance, mm^2/mm^2); 0 if blocked.
  double sampleLensRay(const Vec2d& sensorXY, Vec2 uLens, double lambdaNm, LensRay& lensRay) const;
  // Sensor point (lens coordinates) of a pixel position: inverted, as the real lens images.
  Vec2d sensorPoint(Vec2 pixel) const;
  // Lens coordinates -> display frame (lens z axis along -viewing direction, eye at the
  // entrance pupil).
  Ray lensToWorld(const LensRay& r) const;
  // The same lens, focus, exit-pupil bounds and centre irradiance (none depends on the pose)
  // at another pose: nothing is traced again.
  std::unique_ptr<RealLensCameraModel> atPose(const ViewingPose& pose) const;

  const LensSystem& lens() const { return lens_; }
  const LensInfo& lensInfo() const { return info_; }
  const ExitPupilBounds& pupilBounds() const { return *bounds_; }
  const Settings& settings() const { return settings_; }
  double sensorDistanceMm() const { return lens_.sensorDistanceMm(); }
  double focusDistanceMm() const { return focus_; }
  // Irradiance at the image centre for unit radiance, E/L (sr-equivalent, ~ pi / (4 N_w^2)):
  // generateRay divides by it so the centre weight is 1.
  double centreIrradiance() const { return e0_; }

 private:
  LensSystem lens_;
  LensInfo info_;
  Settings settings_;
  std::shared_ptr<const ExitPupilBounds> bounds_;  // shared by the cameras of one lens (fig11's poses)
  double focus_ = 0.0, e0_ = 1.0;
  // The media's indices at 550 nm, where non-dispersive camera rays are traced: looked up once
  // instead of per ray (a tenth of a reference's time).
  std::vector<double> indices550_;
};

}  // namespace inim
