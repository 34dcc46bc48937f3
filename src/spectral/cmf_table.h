#pragma once
// The CIE 1931 CMFs tabulated on their own 1 nm grid (360-830 nm), in float, for hot loops:
// a sample's XYZ costs 4 indexed lookups instead of 12 binary searches. The same
// piecewise-linear functions as cie::X/Y/Z, already divided by the y-bar integral (the
// normalisation of spectrumToXYZ); sampledToXYZ (spectral/cie.h) is the double-precision
// equivalent. Used by EIA synthesis.
#include <algorithm>
#include <array>

#include "core/geometry.h"
#include "spectral/sampled.h"

namespace inim {

class CmfTable {
 public:
  CmfTable();
  // (x-bar, y-bar, z-bar) / yIntegral at `lambda` nm; 0 outside 360-830 nm.
  Vec3 operator()(float lambda) const {
    float u = lambda - kLambdaMin;
    if (!(u >= 0.0f) || !(u <= float(kN - 1))) return Vec3(0.0f);
    int i = std::min(int(u), kN - 2);
    float t = u - float(i);
    return xyz_[size_t(i)] + t * (xyz_[size_t(i) + 1] - xyz_[size_t(i)]);
  }
  // Monte Carlo XYZ of one sample (as sampledToXYZ).
  Vec3 toXYZ(const SampledSpectrum& L, const SampledWavelengths& lambda) const {
    Vec3 sum(0.0f);
    for (int i = 0; i < kNumWavelengths; ++i) {
      float pdf = lambda.pdf()[i];
      if (pdf != 0.0f) sum += (L[i] / pdf) * (*this)(lambda[i]);
    }
    return sum * (1.0f / float(kNumWavelengths));
  }

 private:
  static constexpr int kN = int(kLambdaMax - kLambdaMin) + 1;
  std::array<Vec3, size_t(kN)> xyz_{};
};

// The table, built on first use.
const CmfTable& cmfTable();

}  // namespace inim
