#pragma once
// Deterministic inputs shared by the calibration tests.
#include <cmath>
#include <cstdint>
#include <vector>

#include "core/geometry.h"

namespace inim::testing {

// `count` points in [lo, hi]^3 from a fixed linear congruential sequence (same on every machine).
inline std::vector<Vec3d> pseudoRandomColours(size_t count, double lo = 0.0, double hi = 1.0, uint64_t seed = 12345) {
  std::vector<Vec3d> out;
  auto next = [&seed] {
    seed = seed * 6364136223846793005ull + 1442695040888963407ull;
    return double(seed >> 11) / double(1ull << 53);
  };
  for (size_t i = 0; i < count; ++i) {
    const double r = next(), g = next(), b = next();
    out.push_back(lo + (hi - lo) * Vec3d(r, g, b));
  }
  return out;
}

// A smooth function that treats the three channels differently, so that a table stored in the
// wrong order (red fastest vs blue fastest) cannot pass for the right one.
inline Vec3d asymmetric(const Vec3d& x) {
  return {0.1 + 0.7 * x.x * x.x + 0.15 * x.y, 0.5 * x.y + 0.3 * x.z * x.x + 0.05,
          0.8 * std::sqrt(x.z + 0.01) + 0.1 * x.x};
}

}  // namespace inim::testing
