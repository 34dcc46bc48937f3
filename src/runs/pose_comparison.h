#pragma once
// A reconstruction and its reference at one pose, compared as `inim fig11` and `inim view
// --reference` both compare them: exposed alike in the display's units, the band-limited
// reference beside the full one, and the second reference of the budget's noise floor.
//
//   PoseImages img = exposeAlike(rec, ref, eiaExposure * peakCdM2, sensor);
//   BandLimit b = bandLimitOf(layout.lensPitchMm, panel.pixelPitchMm, gapMm, distanceMm, camera);
//   Image limited = bandLimitedReference(img.refExposed, depth, b);
#include "analysis/band_limit.h"
#include "camera/camera_model.h"
#include "camera/sensor.h"
#include "core/image.h"
#include "core/json_config.h"
#include "core/pixel_mask.h"
#include "runs/fig11_depth.h"
#include "display_view/reference_renderer.h"
#include "display_view/view_image.h"

namespace inim {

struct PoseImages {
  Image recExposed, refExposed, recSrgb, refSrgb;
  double exposure = 1.0;  // the factor on the reconstruction (display units)
};

// One exposure for both, in the same units: the EIA maps field luminance Y to drive
// eiaExposure x Y, which the panel shows at eiaExposure x Y x peak luminance (cd/m^2), the unit
// of the reconstruction. So the reference, scaled by `refToCdM2` (that product), is what an
// ideal display would show; the exposure that suits the reference (`e`, auto by default) then
// applies to both, and what the optics lose or add (Fresnel, black matrix, crosstalk) stays
// visible in the metrics.
PoseImages exposeAlike(const Image& rec, const Image& ref, double refToCdM2, const CameraSensor& sensor,
                       const Exposure& e = Exposure{});

// The per-pixel error maps of fig11's contact sheet and of `inim view --reference`: CIEDE2000 of
// the sRGB images, shown 0 to kErrorMapMax (viridis; larger errors saturate), grey off the mask.
constexpr double kErrorMapMax = 50.0;
Image errorMap(const std::vector<float>& deltaE, const PoseImages& img, const PixelMask& mask);

// The display's sampling limit for this camera (analysis/band_limit.h): the lenslet pitch, the
// panel pixel, the gap, the camera distance and the footprint of an image pixel on the MLA plane
// at the image centre (from the horizontal field of view).
BandLimit bandLimitOf(double lensPitchMm, double eiPixelMm, double gapMm, double distanceMm, const CameraModel& camera);
Json bandLimitJson(const BandLimit& b);  // the filter's parameters, for metrics.json

// The reference filtered to what an ideal display of this pitch can show; without depth
// channels every pixel is taken at the MLA plane.
Image bandLimitedReference(const Image& ref, const ReferenceDepth& depth, const BandLimit& b);

// The reference in full (s.spp) only where the comparison reads it: the mask's pixels and those
// the band-limited reference's filter reaches from them (3 sigma at each pixel's depth); the
// others get s.sppElsewhere samples (default 1: a grainy picture, but the whole image's
// statistics, so the automatic exposure (99th percentile) stays that of the full reference;
// black there would raise the exposure and change every metric). Two passes:
// the mask grown by the filter's reach at the MLA plane, then the pixels a deeper pixel's
// filter reaches beyond that (s.depth only). A pixel's samples do not depend on the pass, so
// the compared pixels, and the band-limited reference on the mask, are those of a reference
// rendered in full, bit for bit. An empty mask: the whole reference (nothing is compared, the
// picture is all there is).
ViewResult renderComparedReference(const Field& field, const Transform& fieldToDisplay, const CameraModel& camera,
                                   const CameraSensor& sensor, const ReferenceSettings& s, const PixelMask& mask,
                                   const BandLimit& b);

}  // namespace inim
