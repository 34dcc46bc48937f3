#include "analysis/band_limit.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "core/parallel.h"

namespace inim {

double BandLimit::sigmaPx(double zMm) const {
  const double lens = lensPitchMm / footprintMm;
  const double cone = std::abs(zMm) * eiPixelMm / gapMm * distanceMm / std::max(1e-9, distanceMm - zMm) / footprintMm;
  return std::sqrt((lens * lens + cone * cone) / 12.0);
}

Image bandLimited(const Image& reference, const std::vector<float>& depthZ, const std::vector<float>& coverage,
                  const BandLimit& b) {
  const size_t n = size_t(reference.width) * size_t(reference.height);
  if (depthZ.size() != n || coverage.size() != n)
    throw InputError("", "depth", std::to_string(depthZ.size()), "one depth per pixel of the reference");
  if (!(b.footprintMm > 0.0 && b.gapMm > 0.0 && b.lensPitchMm > 0.0 && b.distanceMm > 0.0))
    throw InputError("", "band_limit", "pitch, gap, distance and footprint", "all > 0");
  Image out = reference;
  const int W = reference.width, H = reference.height, C = reference.numChannels();
  parallelForRange(H, [&](int64_t y0, int64_t y1) {
    std::vector<double> acc(static_cast<size_t>(C), 0.0), g;
    for (int y = int(y0); y < int(y1); ++y)
      for (int x = 0; x < W; ++x) {
        const size_t i = size_t(y) * W + x;
        const double sigma = b.sigmaPx(coverage[i] >= 0.5f ? double(depthZ[i]) : 0.0);
        const int r = std::max(1, int(std::ceil(3.0 * sigma)));
        // The Gaussian is separable: g[d + r] = exp(k d^2), one exponential per offset, not per tap.
        const double k = -0.5 / (sigma * sigma);
        g.resize(size_t(2 * r + 1));
        for (int d = -r; d <= r; ++d) g[size_t(d + r)] = std::exp(k * double(d * d));
        std::fill(acc.begin(), acc.end(), 0.0);
        double wsum = 0.0;
        for (int v = std::max(0, y - r); v <= std::min(H - 1, y + r); ++v)
          for (int u = std::max(0, x - r); u <= std::min(W - 1, x + r); ++u) {
            const double w = g[size_t(v - y + r)] * g[size_t(u - x + r)];
            const float* p = &reference.data[(size_t(v) * W + u) * size_t(C)];
            for (int c = 0; c < C; ++c) acc[size_t(c)] += w * p[c];
            wsum += w;
          }
        for (int c = 0; c < C; ++c) out.data[i * size_t(C) + size_t(c)] = float(acc[size_t(c)] / wsum);
      }
  }, nullptr, 8);
  return out;
}

}  // namespace inim
