#include "display_view/aperture_mean.h"

#include <algorithm>
#include <atomic>
#include <cmath>

#include "core/parallel.h"
#include "display_view/estimators/aperture_table.h"

namespace inim {

ApertureMeanWeight::ApertureMeanWeight(const CameraModel& camera, int maxBlock, int grid)
    : block_(std::clamp(camera.width() / 20, 1, std::max(1, maxBlock))),
      nx_((camera.width() + block_ - 1) / block_ + 1),
      ny_((camera.height() + block_ - 1) / block_ + 1),
      nodes_(size_t(nx_) * size_t(ny_), 0.0) {
  std::atomic<uint64_t> rays{0};
  parallelForRange(int64_t(nodes_.size()), [&](int64_t b, int64_t e) {
    uint64_t local = 0;
    for (int64_t k = b; k < e; ++k) {
      // Nodes past the image's edge sit on it, so the interpolation never extrapolates.
      const float x = float(std::min(int(k % nx_) * block_, camera.width()));
      const float y = float(std::min(int(k / nx_) * block_, camera.height()));
      nodes_[size_t(k)] = apertureWeightIntegral(camera, Vec2(x, y), 550.0f, grid, local);
    }
    rays += local;
  }, nullptr, 8);
  rays_ = rays;
}

double ApertureMeanWeight::at(Vec2 pixel) const {
  const double fx = std::clamp(double(pixel.x) / block_, 0.0, double(nx_ - 1));
  const double fy = std::clamp(double(pixel.y) / block_, 0.0, double(ny_ - 1));
  const int i = std::min(int(fx), nx_ - 2), j = std::min(int(fy), ny_ - 2);  // nx_, ny_ >= 2
  const double tx = fx - i, ty = fy - j;
  auto node = [&](int a, int b) { return nodes_[size_t(b) * size_t(nx_) + size_t(a)]; };
  return (1 - ty) * ((1 - tx) * node(i, j) + tx * node(i + 1, j)) + ty * ((1 - tx) * node(i, j + 1) + tx * node(i + 1, j + 1));
}

}  // namespace inim
