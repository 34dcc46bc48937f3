#pragma once
// Where the camera samples of a pixel come from: a position in the pixel, a lens position and a
// wavelength sample, each in [0, 1). The field renderer (field_render/field_renderer.h) asks a
// PixelSampler for the samples of one pixel at a time; samplers hold no per-pixel state, so one
// sampler serves every thread.
#include <cstdint>
#include <span>

#include "core/geometry.h"

namespace inim {

struct CameraSample {
  Vec2 pixelOffset;    // within the pixel, [0, 1)^2
  Vec2 lens;           // lens sample, [0, 1)^2
  float wavelength;    // for SampledWavelengths::sampleVisible, [0, 1)
};

class PixelSampler {
 public:
  virtual ~PixelSampler() = default;
  // Samples 0 .. out.size() - 1 of the pixel with row-major index `pixelIndex` (y * width + x).
  virtual void pixelSamples(uint64_t pixelIndex, std::span<CameraSample> out) const = 0;
};

// Independent uniform samples, each sample from its own Rng stream keyed by (seed, pixel,
// sample): the sampler of `inim render` and `inim capture`. The seed is salted, so the camera's
// stream is independent of the stream a field derives from the same seed.
class IndependentPixelSampler final : public PixelSampler {
 public:
  explicit IndependentPixelSampler(uint64_t seed) : seed_(seed) {}
  void pixelSamples(uint64_t pixelIndex, std::span<CameraSample> out) const override;

 private:
  uint64_t seed_;
};

}  // namespace inim
