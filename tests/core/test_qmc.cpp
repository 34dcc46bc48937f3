// The Owen-scrambled Sobol points: stratification of the pixel dimensions as a (0, 2)-sequence
// and of every dimension on its own, with and without the scramble.
#include <gtest/gtest.h>

#include <set>

#include "core/qmc.h"

using namespace inim;

TEST(SobolSequence, StratifiedPointSets) {
  // Dimensions 0 and 1 (the pixel position) form a (0, 2)-sequence: every elementary interval
  // of area 1/64 holds exactly one of the first 64 points, with or without the scramble.
  for (int shape = 0; shape <= 6; ++shape) {
    const int nx = 1 << shape, ny = 64 / nx;
    for (uint32_t seed : {0u, 12345u}) {
      std::set<int> cells;
      for (uint32_t i = 0; i < 64; ++i) {
        const float a = SobolSequence::sample(i, 0, seed), b = SobolSequence::sample(i, 1, seed * 7 + 1);
        cells.insert(int(a * nx) + nx * int(b * ny));
      }
      EXPECT_EQ(cells.size(), 64u) << "shape " << nx << "x" << ny;
    }
  }
  // Every dimension is stratified on its own; all values lie in [0, 1).
  for (int dim = 0; dim < SobolSequence::kDims; ++dim) {
    std::set<int> cells;
    for (uint32_t i = 0; i < 32; ++i) {
      const float u = SobolSequence::sample(i, dim, 99u + uint32_t(dim));
      EXPECT_GE(u, 0.0f);
      EXPECT_LT(u, 1.0f);
      cells.insert(int(u * 32));
    }
    EXPECT_EQ(cells.size(), 32u) << "dim " << dim;
  }
}
