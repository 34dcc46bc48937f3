// SparseAdam: the per-vertex Adam update.
#include "radiance/sparse_adam.h"

#include <cmath>

namespace inim {

SparseAdam::SparseAdam(size_t vertices, int stride, AdamSettings s)
    : stride_(stride), s_(s), mv_(2 * vertices * size_t(stride), 0.0f) {}

void SparseAdam::update(std::span<const uint32_t> vertices, float* params, float* grads, float lr,
                        int step) const {
  // Bias corrections folded into the step size and epsilon (Kingma & Ba, section 2).
  const float c1 = 1.0f - std::pow(s_.beta1, float(step));
  const float c2 = 1.0f - std::pow(s_.beta2, float(step));
  const float stepSize = lr * std::sqrt(c2) / c1, eps = s_.eps * std::sqrt(c2);
  const float b1 = s_.beta1, b2 = s_.beta2;
  float* __restrict mv = mv_.data();
  float* __restrict p = params;
  float* __restrict g = grads;
  const size_t stride = size_t(stride_);
  for (uint32_t vertex : vertices) {
    const size_t base = size_t(vertex) * stride;
    for (size_t i = base; i < base + stride; ++i) {
      float gi = g[i];
      float mi = b1 * mv[2 * i] + (1.0f - b1) * gi;
      float vi = b2 * mv[2 * i + 1] + (1.0f - b2) * gi * gi;
      mv[2 * i] = mi;
      mv[2 * i + 1] = vi;
      p[i] -= stepSize * mi / (std::sqrt(vi) + eps);
      g[i] = 0.0f;
    }
  }
}

}  // namespace inim
