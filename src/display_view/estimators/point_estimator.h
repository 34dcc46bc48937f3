#pragma once
// PointSample, the reference estimator: each sampled ray (sample_tracer.h) reads the subpixel
// under its landing point on the panel.
//
// Integrates: the pixel's area, the camera's aperture, the wavelengths (importance-sampled per
// primary) and the MLA's Fresnel choices, all by Monte Carlo (Owen-scrambled Sobol points).
// Bias: none. Noise: high; at the default camera a pixel's aperture spreads through a lenslet
// over several subpixels of different colours, so each ray is a lottery between them and the
// black matrix; it falls as ~1/sqrt(spp) (measurements: docs/view-estimators.md).
// Cost: one camera ray and one MLA trace per sample (per primary when dispersive).
// Statistics: the ray counts only (RayCounts).
#include "display_view/estimators/panel_estimator.h"

namespace inim {

class PointEstimator final : public PixelEstimator {
 public:
  explicit PointEstimator(const EstimatorContext& context) : context_(context) {}
  PanelEstimator kind() const override { return PanelEstimator::PointSample; }
  std::unique_ptr<TileEstimator> beginTile() const override;

 private:
  const EstimatorContext& context_;
};

}  // namespace inim
