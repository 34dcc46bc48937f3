#pragma once
// The mean camera weight per pixel (vignetting), for the reference's aperture-normalised
// estimator (display_view/reference_renderer.h).
//
// A real lens samples its exit pupil through a bounding box: about 40 % of the default camera's
// lens samples are vignetted, and with 8 lens positions per pixel the number that pass varies
// from pixel to pixel, a grain of about 25 % (RMSE) that dominated the reference's noise. The
// estimator therefore averages the surviving rays by their weights and multiplies by the mean
// weight, which it knows from a quadrature of the aperture: the integral of
// CameraModel::apertureRay's weight (display_view/estimators/aperture_table.h), computed on a grid of
// nodes every `block` pixels (at least 20 across the image) and interpolated bilinearly
// (vignetting is smooth across the sensor). The ratio is consistent, with a bias of order 1 / (rays per pixel) where few pass.
//
//   ApertureMeanWeight mean(camera);
//   double w = mean.at(Vec2(x + 0.5f, y + 0.5f));  // = E[generateRay's weight] at that pixel
#include <vector>

#include "camera/camera_model.h"
#include "core/geometry.h"

namespace inim {

class ApertureMeanWeight {
 public:
  // Quadrature on a grid x grid aperture table at 550 nm per node; nodes every
  // min(maxBlock, width / 20) pixels (at least 1).
  explicit ApertureMeanWeight(const CameraModel& camera, int maxBlock = 32, int grid = 16);
  double at(Vec2 pixel) const;  // pixel position (x + 0.5, y + 0.5 at a pixel's centre)
  uint64_t tracedRays() const { return rays_; }

 private:
  int block_, nx_, ny_;
  std::vector<double> nodes_;  // (nx_ x ny_), node (i, j) at pixel position (i * block, j * block)
  uint64_t rays_ = 0;
};

}  // namespace inim
