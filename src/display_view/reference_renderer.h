#pragma once
// The reference view (the paper's Fig. 11(a); docs/design.md): the same camera at the same pose,
// looking at the scene itself, placed where the display reconstructs it. It is the field
// renderer (field_render/field_renderer.h) with what is specific to the reference: the placement
// between the camera's frame and the field's, Owen-scrambled Sobol samples like renderView's,
// and a film in camera RGB through the sensor's spectral response.
//
// Frames: field --placement--> display --DisplayPose--> world. The camera model is built in
// the display frame (makeViewCamera), so a camera ray only needs the inverse placement to
// reach the field frame; the rotation of the gimbal turns the scene with the display.
//
// "Where the display reconstructs it" is, by definition here, the placement used to make the
// EIA (the same run file or scale / rotate_deg / translate_mm settings). That is exact for the
// generation geometry. A display viewed at a reconstruction gap g_rec different from the
// generation gap g_gen (the prototype: 4 mm against 3.3 mm) reconstructs the scene with its
// depths scaled (roughly by g_rec / g_gen for the pinhole model) and blurred away from the
// reference image plane; the reference deliberately does NOT apply that: it shows the scene at
// the placement, and the difference is what the comparison measures. No VCP clipping either:
// the reference shows everything the scene holds.
//
// Colour: spectral samples are weighted by the sensor's white-balanced channel responses (a
// dispersive camera lens, when traced (CameraDispersion): each ray by its hero wavelength's).
// The surviving camera rays of a pixel are averaged by their weights and scaled by the pixel's
// mean camera weight (display_view/aperture_mean.h), so vignetted lens samples add no grain. RGB fields are converted to XYZ
// (their colour space, through OCIO) and then to camera RGB by the inverse of the sensor's
// fitted camera RGB -> XYZ matrix. The output is linear white-balanced camera RGB like
// renderView's, so the same exposure logic applies (auto exposure maps each image's 99th
// percentile to 0.9: brightness is comparable, absolute scales are not, since the scene's
// radiance units and the panel's cd/m^2 differ).
//
// Depth (ReferenceSettings::depth): three more channels after R, G, B, for asking where in depth
// a reconstruction goes wrong (analysis/depth_error.h):
//   A  the fraction of the pixel's camera rays that hit a surface (FieldSample::opacity > 0);
//      rays the camera vignetted entirely are not counted, so a covered pixel has A = 1;
//   Z  the mean display-frame z (mm, > 0 toward the viewer, the MLA at 0) of the first surface
//      over the rays that hit with a finite depth; 0 where none did. A hit is found in the
//      field frame (the ray's origin + FieldSample::depth along it, field units) and placed
//      with `fieldToDisplay`, so any scale of the placement is accounted for.
//   dZ the max - min of those z (0 with fewer than two): large where the pixel straddles an
//      edge between surfaces at different depths, so that Z lies where neither is.
// R, G, B are the same, bit for bit, with depth on or off.
//
//   ReferenceSettings s;
//   s.depth = true;
//   Image img = renderReference(field, placement.toDisplay(), camera, sensor, s).image;
//   float z = img.at(x, y, img.channelIndex("Z"));
#include <cstdint>
#include <string>
#include <vector>

#include "camera/camera_model.h"
#include "camera/sensor.h"
#include "core/transform.h"
#include "field/field.h"
#include "display_view/view_renderer.h"

namespace inim {

// Whether a dispersive camera's rays are traced per wavelength (Trace) or at 550 nm carrying
// every wavelength (Ignore); Auto traces them only when the camera spreads the colours of a
// point over more than kDispersionThresholdPx pixels (camera/chromatic_spread.h). The default
// camera at 648 px spreads them 0.1 px: ignoring it is 2.7 x faster and measured identical
// within the noise of 64-sample references (docs/error-budget.md).
enum class CameraDispersion { Auto, Trace, Ignore };
const char* cameraDispersionName(CameraDispersion d);  // "auto", "trace", "ignore"
constexpr double kDispersionThresholdPx = 0.25;

struct ReferenceSettings {
  // 16: at 648 px the default scene's noise floor (CIEDE2000 between two seeds, 0°, within the
  // display) is 2.0; 8 gave 3.45 (docs/error-budget.md). Also fig11's and view --reference's.
  int spp = 16;
  const char* sppKey = "spp";  // the setting spp came from, named when it is refused
  CameraDispersion dispersion = CameraDispersion::Auto;
  uint64_t seed = 1;
  bool progress = true;
  int raysPerBatch = 4096;
  bool depth = false;  // add channels A, Z and dZ (see above)
  // Pixels a comparison does not read (0 in this width x height map) get sppElsewhere samples,
  // the first of the same pixel's full set (0: none, black); see field_render/field_renderer.h.
  const std::vector<uint8_t>* fullSamples = nullptr;
  int sppElsewhere = 1;
  // The field's content key (fieldContentKey of its file, display_view/reference_cache.h): the
  // image is then rendered once and read back from the reference cache. "": always rendered.
  std::string fieldKey;
  // The cache's folder; "": referenceCacheDir() (off when INIM_REFERENCE_CACHE=0). A sweep gives
  // its own, shared by its points (on a cluster, on the shared file system).
  std::string cacheDir;
};

// `fieldToDisplay`: the placement (Placement::toDisplay()). InputError (key sppKey) for spp < 1
// or beyond the memory budget.
// stats.displayRays counts nothing here; stats.emittingRays counts samples that hit a surface
// (FieldSample::opacity > 0).
ViewResult renderReference(const Field& field, const Transform& fieldToDisplay, const CameraModel& camera,
                           const CameraSensor& sensor, const ReferenceSettings& s);

}  // namespace inim
