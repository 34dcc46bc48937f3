#pragma once
// Footprint: each sampled ray (sample_tracer.h) reads the EXACT average of the emitter over a
// box around its landing point (PanelEmitter::boxAveragePx), the size of this sample's share of
// the pixel's footprint on the panel.
//
// The box: per pixel, the 2 x 4 Jacobian J of the landing point (panel pixels) with respect to
// the sample coordinates (pixel x, y; lens u, v) is measured by one-sided finite differences
// (5 probe rays at the reference wavelength from the pixel and lens centres, each step toward
// the side that stays in the same lenslet; a column that cannot be measured is 0; a pixel whose
// base probe fails reuses its tile's last Jacobian), and the half-widths are
//   h_u = 0.5 s |J_u.| / sqrt(spp),  h_v = 0.5 s |J_v.| / sqrt(spp)   (s = footprintScale),
// capped at 8 panel pixels: the box's variance is the sample's 1/spp share of the variance of
// the pixel's landing points.
// Bias: the panel-side blur of each pixel widens by ~sqrt(1 + s^2/spp); consistent (the bias
// vanishes as spp grows), and s = 0 is PointSample bit for bit.
// Cost: 5 probe rays per pixel plus one box integral per ray.
#include <cstdint>

#include "display_view/estimators/panel_estimator.h"

namespace inim {

struct FootprintStats {
  uint64_t probeRays = 0;      // rays traced to measure the pixels' Jacobians
  uint64_t probeFailures = 0;  // Jacobian columns that no probe could measure (set to 0)
};

class FootprintEstimator final : public PixelEstimator {
 public:
  // InputError (key footprint_scale) for a negative or non-finite scale.
  explicit FootprintEstimator(const EstimatorContext& context);
  PanelEstimator kind() const override { return PanelEstimator::Footprint; }
  std::unique_ptr<TileEstimator> beginTile() const override;

 private:
  const EstimatorContext& context_;
  double boxScale_;  // 0.5 x footprintScale / sqrt(spp)
};

}  // namespace inim
