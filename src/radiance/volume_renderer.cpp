// VolumeRenderer: batches of rays through the march, and the PSNR helper.
#include "radiance/volume_renderer.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace inim {

VolumeRenderer::VolumeRenderer(const VoxelGrid& grid, const MarchSettings& settings)
    : grid_(grid), settings_(settings) {
  occupancy_.update(grid_, settings_.stepWorld(grid_), settings_.occupancyAlpha);
}

RadianceSample VolumeRenderer::render(const RenderRay& ray) const {
  float len = glm::length(ray.d);
  if (!(len > 0.0f) || !std::isfinite(len)) return backgroundResult(grid_);
  GridRay gr;
  if (!makeGridRay(grid_, ray.o, ray.d / len, ray.tNear, ray.tFar, settings_.stepWorld(grid_), gr))
    return backgroundResult(grid_);
  return marchRay(grid_, occupancy_, gr, 0.5f, settings_);
}

void VolumeRenderer::render(std::span<const RenderRay> rays, std::span<RadianceSample> out) const {
  if (out.size() < rays.size()) throw std::invalid_argument("VolumeRenderer: output too small");
  tbb::parallel_for(tbb::blocked_range<size_t>(0, rays.size(), 256),
                    [&](const tbb::blocked_range<size_t>& r) {
                      for (size_t i = r.begin(); i < r.end(); ++i) out[i] = render(rays[i]);
                    });
}

double psnrFromMse(double mse) {
  return mse > 0.0 ? -10.0 * std::log10(mse) : std::numeric_limits<double>::infinity();
}

double psnr(std::span<const Vec3> a, std::span<const Vec3> b) {
  if (a.size() != b.size() || a.empty()) throw std::invalid_argument("psnr: sizes differ or empty");
  double sum = 0.0;
  for (size_t i = 0; i < a.size(); ++i)
    for (int c = 0; c < 3; ++c) {
      double d = double(a[i][c]) - double(b[i][c]);
      sum += d * d;
    }
  return psnrFromMse(sum / (3.0 * double(a.size())));
}

}  // namespace inim
