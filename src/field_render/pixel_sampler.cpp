#include "field_render/pixel_sampler.h"

#include "core/rng.h"

namespace inim {

void IndependentPixelSampler::pixelSamples(uint64_t pixelIndex, std::span<CameraSample> out) const {
  for (size_t i = 0; i < out.size(); ++i) {
    Rng rng = Rng::forSample(seed_ ^ 0xC0FFEEull, pixelIndex, i);
    // Kept as written when these images were first made: the order in which the two uniforms
    // of one constructor are drawn is the compiler's, and changing the expression could change
    // every image.
    Vec2 jitter(rng.uniform(), rng.uniform()), lens(rng.uniform(), rng.uniform());
    out[i] = {jitter, lens, rng.uniform()};
  }
}

}  // namespace inim
