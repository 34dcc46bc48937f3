#include "runs/pose_comparison.h"

#include <algorithm>
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

namespace {

int filterReachPx(const BandLimit& b, double zMm) { return std::max(1, int(std::ceil(3.0 * b.sigmaPx(zMm)))); }

// Marks (as 1) the pixels within `reach` (a square, as the filter's window) of a mask pixel.
std::vector<uint8_t> grownMask(const PixelMask& mask, int reach) {
  const int W = mask.width, H = mask.height;
  std::vector<uint8_t> rows(mask.on.size(), 0), out(mask.on.size(), 0);
  for (int y = 0; y < H; ++y)  // along x, then along y: a square
    for (int x = 0; x < W; ++x)
      if (mask.counts(x, y))
        for (int u = std::max(0, x - reach); u <= std::min(W - 1, x + reach); ++u) rows[size_t(y) * W + u] = 1;
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x)
      if (rows[size_t(y) * W + x])
        for (int v = std::max(0, y - reach); v <= std::min(H - 1, y + reach); ++v) out[size_t(v) * W + x] = 1;
  return out;
}

// The pixels the filter reads from the mask's pixels at their depths, not yet in `full`.
std::vector<uint8_t> missingReach(const Image& ref, const PixelMask& mask, const BandLimit& b,
                                  const std::vector<uint8_t>& full) {
  const int W = ref.width, H = ref.height, z = ref.channelIndex("Z"), a = ref.channelIndex("A");
  std::vector<uint8_t> out(full.size(), 0);
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x) {
      if (!mask.counts(x, y)) continue;
      const double depth = ref.at(x, y, a) >= 0.5f ? double(ref.at(x, y, z)) : 0.0;
      const int r = filterReachPx(b, depth);
      for (int v = std::max(0, y - r); v <= std::min(H - 1, y + r); ++v)
        for (int u = std::max(0, x - r); u <= std::min(W - 1, x + r); ++u) {
          const size_t i = size_t(v) * W + u;
          if (!full[i]) out[i] = 1;
        }
    }
  return out;
}

}  // namespace

ViewResult renderComparedReference(const Field& field, const Transform& fieldToDisplay, const CameraModel& camera,
                                   const CameraSensor& sensor, const ReferenceSettings& s, const PixelMask& mask,
                                   const BandLimit& b) {
  if (mask.count() == 0) return renderReference(field, fieldToDisplay, camera, sensor, s);  // a picture only
  ReferenceSettings first = s;
  const std::vector<uint8_t> full = grownMask(mask, filterReachPx(b, 0.0));
  first.fullSamples = &full;
  ViewResult r = renderReference(field, fieldToDisplay, camera, sensor, first);
  if (!s.depth) return r;
  const std::vector<uint8_t> missing = missingReach(r.image, mask, b, full);
  if (std::find(missing.begin(), missing.end(), uint8_t(1)) == missing.end()) return r;
  ReferenceSettings second = s;
  second.fullSamples = &missing;
  second.sppElsewhere = 0;
  second.progress = false;
  const ViewResult more = renderReference(field, fieldToDisplay, camera, sensor, second);
  const size_t C = size_t(r.image.numChannels());
  for (size_t i = 0; i < missing.size(); ++i)
    if (missing[i]) std::copy_n(&more.image.data[i * C], C, &r.image.data[i * C]);
  r.stats.tracedRays += more.stats.tracedRays;
  r.stats.emittingRays += more.stats.emittingRays;
  r.stats.seconds += more.stats.seconds;
  return r;
}

Image bandLimitedReference(const Image& ref, const ReferenceDepth& d, const BandLimit& b) {
  const size_t n = size_t(ref.width) * size_t(ref.height);
  return bandLimited(ref, d.present ? d.z : std::vector<float>(n, 0.0f),
                     d.present ? d.coverage : std::vector<float>(n, 0.0f), b);
}

}  // namespace inim
