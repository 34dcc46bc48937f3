#pragma once
// The reference view (DESIGN.md section 1, step 7; issue 4 item 5; the paper's Fig. 11(a)): the
// same camera at the same pose, looking at the scene itself, placed where the display
// reconstructs it.
//
// Frames: field --placement--> display --DisplayPose--> world. The camera model is built in
// the display frame (makeViewCamera), so a camera ray only needs the inverse placement to
// reach the field frame; the rotation of the gimbal turns the scene with the display.
//
// "Where the display reconstructs it" is, by definition here, the placement used to make the
// EIA (the same run file or --scale / --rotate-deg / --translate-mm). That is exact for the
// generation geometry. A display viewed at a reconstruction gap g_rec different from the
// generation gap g_gen (the prototype: 4 mm against 3.3 mm) reconstructs the scene with its
// depths scaled (roughly by g_rec / g_gen for the pinhole model) and blurred away from the
// reference image plane; the reference deliberately does NOT apply that: it shows the scene at
// the placement, and the difference is what the comparison measures. No VCP clipping either:
// the reference shows everything the scene holds.
//
// Spectral: each sample carries pbrt-v4's 4-wavelength packet (sampleVisible) into the field.
// With a dispersive camera lens each sample traces 4 camera rays, one per wavelength of the
// stratified packet (the packet rotated so that the ray's own wavelength is the hero), each
// keeping only its hero wavelength and weighted 1/4: unbiased, and as little colour noise as
// one ray carrying 4 wavelengths; otherwise one ray carries the 4 wavelengths. RGB fields are converted to
// XYZ (their colour space, through OCIO) and then to camera RGB by the inverse of the sensor's
// fitted camera RGB -> XYZ matrix. The output is linear white-balanced camera RGB like
// renderView's, so the same exposure logic applies (auto exposure maps each image's 99th
// percentile to 0.9: brightness is comparable, absolute scales are not, since the scene's
// radiance units and the panel's cd/m^2 differ).
#include <cstdint>

#include "camera/camera_model.h"
#include "camera/sensor.h"
#include "core/transform.h"
#include "field/field.h"
#include "view/view_renderer.h"

namespace inim {

struct ReferenceSettings {
  int spp = 16;
  uint64_t seed = 1;
  bool progress = true;
  int raysPerBatch = 4096;
};

// `fieldToDisplay`: the placement (Placement::toDisplay()). Rays are generated per pixel with
// Owen-scrambled Sobol pixel and lens positions like renderView. InputError for spp < 1.
// stats.displayRays counts nothing here; stats.emittingRays counts samples that hit a surface
// (FieldSample::opacity > 0).
ViewResult renderReference(const Field& field, const Transform& fieldToDisplay, const CameraModel& camera,
                           const CameraSensor& sensor, const ReferenceSettings& s);

}  // namespace inim
