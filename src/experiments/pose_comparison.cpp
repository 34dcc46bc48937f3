#include "experiments/pose_comparison.h"

#include <cmath>

#include "analysis/contact_sheet.h"
#include "analysis/metrics.h"
#include "core/geometry.h"

namespace inim {

PoseImages exposeAlike(const Image& rec, const Image& ref, double refToCdM2, const CameraSensor& sensor,
                       const Exposure& e) {
  const Image refCdM2 = scaledImage(ref, refToCdM2);
  const double k = exposureFactor(refCdM2, sensor, e);
  PoseImages p;
  p.exposure = k;
  p.recExposed = scaledImage(rec, k);
  p.refExposed = scaledImage(refCdM2, k);
  p.recSrgb = cameraRgbToSrgb(p.recExposed, sensor);
  p.refSrgb = cameraRgbToSrgb(p.refExposed, sensor);
  return p;
}

std::vector<float> deltaE2000Of(const PoseImages& img) {
  return deltaE2000Map(img.refSrgb, img.recSrgb, "srgb", "srgb");
}

Image errorMap(const std::vector<float>& deltaE, const PoseImages& img, const PixelMask& mask) {
  return errorMapImage(deltaE, img.refSrgb.width, img.refSrgb.height, kErrorMapMax, &mask.on);
}

BandLimit bandLimitOf(double lensPitchMm, double eiPixelMm, double gapMm, double distanceMm, const CameraModel& camera) {
  BandLimit b;
  b.lensPitchMm = lensPitchMm;
  b.eiPixelMm = eiPixelMm;
  b.gapMm = gapMm;
  b.distanceMm = distanceMm;
  b.footprintMm = 2.0 * distanceMm * std::tan(0.5 * camera.horizontalFovDeg() * kPiD / 180.0) / camera.width();
  return b;
}

Json bandLimitJson(const BandLimit& b) {
  return Json{{"kind", "gaussian, variance of the lenslet box and the EI pixel's cone at the pixel's depth"},
              {"lens_pitch_mm", b.lensPitchMm}, {"ei_pixel_mm", b.eiPixelMm}, {"gap_mm", b.gapMm},
              {"distance_mm", b.distanceMm}, {"footprint_mm", b.footprintMm}, {"sigma_px_at_mla", b.sigmaPx(0.0)}};
}

Image bandLimitedReference(const Image& ref, const ReferenceDepth& d, const BandLimit& b) {
  const size_t n = size_t(ref.width) * size_t(ref.height);
  return bandLimited(ref, d.present ? d.z : std::vector<float>(n, 0.0f),
                     d.present ? d.coverage : std::vector<float>(n, 0.0f), b);
}

}  // namespace inim
