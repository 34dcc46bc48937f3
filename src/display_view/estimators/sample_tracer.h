#pragma once
// One sample of a pixel traced from the camera to the panel: the sampled estimators' common
// path (point, footprint, and the quadrature's fallback).
//
// Per sample: a pixel position, a lens position and a wavelength number from the pixel's
// Owen-scrambled Sobol points (core/qmc.h) -> camera ray (display frame) -> does it cross the
// MLA's front plane inside the active area? (no: the background, a D65 grey of luminance
// ViewSettings::backgroundY, camera RGB (Y, Y, Y)) -> MlaModel::traceToPanel with the model's
// own (stochastic) Fresnel -> the panel's emission there -> camera weight x MLA throughput x
// emission, turned into camera RGB by ChannelResponse. Rays that the MLA reflects back or
// loses see nothing (the room is dark). The scrambles and the MLA's random stream depend on
// (seed, pixel, sample index) only.
#include <array>
#include <cstdint>

#include "core/qmc.h"
#include "core/rng.h"
#include "display_view/estimators/panel_estimator.h"

namespace inim {

// How a landing reads the panel: the subpixel under it (PanelEmitter::emit), or the exact
// average of the emitter over a box of half-widths (halfU, halfV) panel pixels around it
// (PanelEmitter::boxAveragePx; a zero box is the same value as the point read).
struct PanelRead {
  bool box = false;
  double halfU = 0.0, halfV = 0.0;
};

class SampleTracer {
 public:
  SampleTracer(const EstimatorContext& context, RayCounts& counts);
  // Starts pixel (x, y): its Sobol scrambles.
  void beginPixel(int x, int y);
  // Adds sample `index` of the current pixel to `rgb`.
  void addSample(int index, const PanelRead& read, Vec3d& rgb);

 private:
  enum class Outcome { Background, Panel, Nothing };
  Outcome trace(const Ray& ray, float lambda, Rng& rng, const PanelRead& read,
                std::array<float, kNumPrimaries>& emission, float& throughput);

  const EstimatorContext& context_;
  RayCounts& counts_;
  int x_ = 0, y_ = 0;
  uint64_t pixelIndex_ = 0;
  uint32_t scramble_[SobolSequence::kDims] = {};
};

}  // namespace inim
