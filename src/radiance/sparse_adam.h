#pragma once
// Adam (Kingma & Ba 2015) over a grid parameter array with `stride` values per vertex,
// updating only the vertices a batch touched ("lazy" Adam, as TensorFlow's LazyAdam):
// untouched vertices keep their moments and values, so a step costs O(touched), not O(grid).
// Bias correction uses the global step count.
#include <cstdint>
#include <span>
#include <vector>

namespace inim {

struct AdamSettings {
  float beta1 = 0.9f;
  float beta2 = 0.99f;
  float eps = 1e-8f;
};

class SparseAdam {
 public:
  SparseAdam() = default;
  SparseAdam(size_t vertices, int stride, AdamSettings s = {});
  // Updates params of `vertices` from grads, then zeroes those grads. `step` counts from 1.
  // Each vertex is independent, so disjoint lists may run in parallel.
  void update(std::span<const uint32_t> vertices, float* params, float* grads, float lr,
              int step) const;
  // Moments are mutable state owned by the optimiser; update() writes them for `vertices` only.
 private:
  int stride_ = 1;
  AdamSettings s_;
  mutable std::vector<float> mv_;  // first and second moments interleaved: one cache line
                                   // stream per vertex instead of two
};

}  // namespace inim
