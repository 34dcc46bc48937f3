#pragma once
// The colour chain of one pose, from a field colour to what is measured
// (docs/colour-calibration.md):
//
//   field XYZ -> the field's colour space (a field stores RGB there: negative components
//   cannot be stored and are clipped) -> panel drive (FieldToDrive: the path of `inim eia`,
//   with its exposure, white gains, gamut mapping and optional correction) -> the panel's
//   8-bit input through its EOTF -> the pose's response (chain_response.h) -> XYZ (observer)
//   and camera RGB (sensor) -> camera XYZ (the sensor's own 3x3).
//
// Relative colorimetry per pose: the reference white is the brightest D65 the chain can show
// at that pose (whiteY), as a display calibrated to D65 at its maximum luminance shows it.
// A field colour's target is its XYZ scaled so the field's white (D65, Y = 1) becomes that
// white; CIELAB and CIEDE2000 use it as the reference white. A colour is in the pose's gamut
// when some drive in [0,1]^3 shows its target.
#include <string>
#include <vector>

#include "camera/sensor.h"
#include "colour_chain/chain_response.h"
#include "colour_chain/patch_sets.h"
#include "display/panel.h"
#include "synthesis/panel_color.h"

namespace inim {

// The panel's input: `bits`-bit encoded values through its EOTF (0: float, not quantised).
struct PanelInput {
  Eotf eotf;
  int bits = 8;
  Vec3d quantise(const Vec3d& linearDrive) const;
};

// A field colour as a field in `space` can hold it: XYZ -> RGB, negatives clipped to 0, -> XYZ.
// "spectral": unchanged. InputError (key field_space) for a space OpenColorIO does not know.
Vec3d representableInField(const Vec3d& xyz, const std::string& space);

// The exposure that maps the field's white (D65, Y = 1) to the brightest D65 the nominal panel
// shows: 1 / max channel of its native drive.
double calibrationExposure(const PanelColor& panel);

double deltaE2000(const Vec3d& xyzA, const Vec3d& xyzB, const Vec3d& whiteXyz);

struct DeltaESummary {
  int count = 0;
  double mean = 0.0, p95 = 0.0, max = 0.0;
};
DeltaESummary summarise(std::vector<double> deltaE);

class PoseChain {
 public:
  PoseChain(const PoseResponse& response, const PanelInput& input);

  const PoseResponse& response() const { return response_; }
  const std::string& name() const { return response_.pose.name; }
  double whiteY() const { return whiteY_; }
  Vec3d labWhite() const { return d65WhiteXyz() * whiteY_; }
  Vec3d target(const Vec3d& fieldXyz) const { return fieldXyz * whiteY_; }

  // What the observer and the camera measure for a linear drive (clamped to [0,1], quantised).
  Vec3d shownXyz(const Vec3d& drive) const { return response_.xyz(input_.quantise(drive)); }
  Vec3d cameraRgb(const Vec3d& drive) const { return response_.cameraRgb(input_.quantise(drive)); }
  // The continuous chain (no quantisation, no clamping): for inversion and one-stage studies.
  Vec3d linearXyz(const Vec3d& drive) const { return response_.xyz(drive); }
  Vec3d linearCameraRgb(const Vec3d& drive) const { return response_.cameraRgb(drive); }
  // The drive that shows `xyz` (the continuous chain inverted; may leave [0,1]).
  Vec3d driveFor(const Vec3d& xyz) const { return xyzToDrive_ * xyz; }
  bool inGamut(const Vec3d& targetXyz, double tolerance = 2e-3) const;

 private:
  PoseResponse response_;
  PanelInput input_;
  glm::dmat3 xyzToDrive_;
  double whiteY_ = 0.0;
};

}  // namespace inim
