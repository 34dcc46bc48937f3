#pragma once
// How the simulated chain answers a flat patch (docs/colour-calibration.md): the display
// shows the same drive value on every panel pixel, and the viewing camera of `inim view` looks
// at it from a pose, through the real MLA, the cover glass and the camera lens.
//
// Everything from the panel's linear drive to the sensor is linear in the drive (emission is
// proportional to it; optics and sensor add light linearly; renderView's samples depend only
// on the seed and the pixel), so a pose is characterised by rendering each primary alone at
// full drive, twice:
//   - with the camera's sensor: camera RGB (white balanced: D65 at Y = 1 gives (1, 1, 1));
//   - with the CIE 1931 observer as the sensor: the XYZ of the light leaving the display
//     toward the camera, what a spectroradiometer there would report.
// A patch's value is then a 3x3 matrix times its drive, exactly (to float rounding): what
// one render of the patch itself gives (tests/colour_chain: a direct render against it).
//
// Robust mean: a fixed set of pixels, the same for every patch so the mean stays linear:
// the pixels that see the display (displayMask), inside the central `interiorFraction` of
// its bounding box (away from the edges, where lenslets are cut), without those whose
// white luminance is outside the [trimPercent, 100 - trimPercent] percentiles (seams,
// dark lenslet edges, aliasing extremes).
//
// Units: the panel in relative units (panel white on axis, without optics, Y = 1).
#include <string>

#include "camera/camera_config.h"
#include "core/image.h"
#include "core/pixel_mask.h"
#include "display/display.h"
#include "display/ei_layout.h"
#include "display_view/display_pose.h"
#include "display_view/view_settings.h"

namespace inim {

using Vec3d = glm::dvec3;

struct ChainRenderSettings {
  ChainRenderSettings() { view.spp = 1; }
  int width = 324;               // view width in pixels (the sensor's field of view)
  ViewSettings view;             // estimator, aperture grid, seed; spp 1 (Quadrature: no noise)
  double interiorFraction = 0.8; // of the display's bounding box in the image
  double trimPercent = 1.0;      // per side, on the white luminance
  bool coverGlass = true;
};

// The CIE 1931 observer as a sensor of `geometry`: its white-balanced "camera RGB" is
// XYZ / XYZ(D65, Y = 1), so XYZ = rgb * d65WhiteXyz().
CameraSensor cieObserverSensor(const SensorGeometry& geometry);

struct PoseResponse {
  NamedPose pose;
  glm::dmat3 xyzPerDrive{0.0};     // columns: XYZ of R, G, B at full drive (robust mean)
  glm::dmat3 cameraPerDrive{0.0};  // columns: camera RGB of R, G, B at full drive
  int64_t pixels = 0;              // pixels in the robust mean
  int64_t displayPixels = 0;       // pixels that see the display
  double seconds = 0.0;
  PixelMask measured;              // the pixels of the mean

  Vec3d xyz(const Vec3d& drive) const { return xyzPerDrive * drive; }
  Vec3d cameraRgb(const Vec3d& drive) const { return cameraPerDrive * drive; }
};

// The display, its layout and the camera, loaded once for every pose.
struct ChainOptics {
  Display display;
  EiLayout layout;
  CameraDescription camera;
};

// Renders the three primaries at one pose and returns the matrices. InputError (key "pose")
// when the camera cannot see the display at that pose, or sees too little of it to measure.
PoseResponse characterisePose(const ChainOptics& optics, const NamedPose& pose, const ChainRenderSettings& s);

// One render of a flat drive value through the chain, as camera RGB and as XYZ, averaged over
// `pixels` (for checks of the linear model).
struct FlatPatchMeasurement {
  Vec3d xyz{0.0}, cameraRgb{0.0};
};
FlatPatchMeasurement renderFlatPatch(const ChainOptics& optics, const NamedPose& pose, const Vec3d& drive,
                                     const PixelMask& pixels, const ChainRenderSettings& s);

}  // namespace inim
