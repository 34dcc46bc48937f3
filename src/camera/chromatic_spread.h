#pragma once
// How far apart a camera puts the colours of one point, in pixels: the test by which the
// reference view (display_view/reference_renderer.h) decides whether tracing the camera's dispersion is
// worth its cost (one camera ray per wavelength, 4 x the rays, and each wavelength's own light
// sample, which is colour noise) or whether rays traced at 550 nm may carry every wavelength.
//
// For sensor points at the centre and near the four corners, and a 3 x 3 grid of aperture points
// (CameraModel::apertureDomain), the rays at 450 and 650 nm against the one at 550 nm where they
// cross the plane the camera looks at (through pose().lookAt, facing the camera): the largest
// distance, over the footprint of one pixel on that plane. Lateral colour and the axial colour of
// the focused plane both show in it. A non-dispersive camera gives 0.
//
//   bool trace = chromaticSpreadPx(camera) > 0.25;
#include "camera/camera_model.h"

namespace inim {

double chromaticSpreadPx(const CameraModel& camera);

}  // namespace inim
