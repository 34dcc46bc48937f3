// VoxelGrid: activations, construction and trilinear resampling.
#include "radiance/voxel_grid.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

namespace inim {

float VoxelGrid::act(float raw) const {
  if (activation == DensityActivation::ReLU) return std::max(raw, 0.0f);
  return raw > 15.0f ? raw : std::log1p(std::exp(raw));
}

float VoxelGrid::actDerivative(float raw) const {
  if (activation == DensityActivation::ReLU) return raw > 0.0f ? 1.0f : 0.0f;
  return 1.0f / (1.0f + std::exp(-raw));
}

float VoxelGrid::actInverse(float value) const {
  if (activation == DensityActivation::ReLU) return value;
  if (value > 15.0f) return value;
  // Softplus never reaches 0; clamp so empty space maps to a finite, very negative raw.
  return std::log(std::expm1(std::max(value, 1e-30f)));
}

VoxelGrid VoxelGrid::create(const Point3& lo, const Point3& hi, const glm::ivec3& res, int shDegree,
                            DensityActivation activation, const Vec3& background, float initAlpha) {
  VoxelGrid g;
  g.lo = lo;
  g.hi = hi;
  g.res = res;
  g.shDegree = shDegree;
  g.activation = activation;
  g.background = background;
  g.densityScale = 1.0f / g.minCellSize();
  // alpha over one cell = 1 - exp(-densityScale * act(raw) * cell) = 1 - exp(-act(raw)).
  float raw = g.actInverse(-std::log(1.0f - std::clamp(initAlpha, 0.0f, 0.999f)));
  g.density.assign(g.vertexCount(), raw);
  g.color.assign(g.vertexCount() * size_t(g.colorStride()), 0.0f);
  return g;
}

glm::ivec3 VoxelGrid::resolutionFor(const Point3& lo, const Point3& hi, int side) {
  Vec3 ext = hi - lo;
  double volume = double(ext.x) * ext.y * ext.z;
  double cell = std::cbrt(volume / (double(side) * side * side));
  glm::ivec3 r;
  for (int a = 0; a < 3; ++a) r[a] = std::max(2, int(std::lround(ext[a] / cell)) + 1);
  return r;
}

VoxelGrid VoxelGrid::resampled(const Point3& newLo, const Point3& newHi,
                               const glm::ivec3& newRes) const {
  VoxelGrid g;
  g.lo = newLo;
  g.hi = newHi;
  g.res = newRes;
  g.shDegree = shDegree;
  g.activation = activation;
  g.background = background;
  g.densityScale = 1.0f / g.minCellSize();
  g.density.resize(g.vertexCount());
  int stride = colorStride();
  g.color.resize(g.vertexCount() * size_t(stride));
  Vec3 newCell = g.cellSize(), invOld = Vec3(res - 1) / (hi - lo);
  float scaleRatio = densityScale / g.densityScale;
  tbb::parallel_for(tbb::blocked_range<int>(0, newRes.x), [&](const tbb::blocked_range<int>& r) {
    for (int x = r.begin(); x < r.end(); ++x)
      for (int y = 0; y < newRes.y; ++y)
        for (int z = 0; z < newRes.z; ++z) {
          Point3 p = newLo + Vec3(x, y, z) * newCell;
          Vec3 q = glm::clamp((p - lo) * invOld, Vec3(0.0f), Vec3(res - 1));
          glm::ivec3 c = glm::min(glm::ivec3(q), res - 2);
          Vec3 f = q - Vec3(c);
          size_t dst = g.index(x, y, z);
          float dens = 0.0f;
          float* col = &g.color[dst * stride];
          std::fill(col, col + stride, 0.0f);
          for (int k = 0; k < 8; ++k) {
            int dx = k >> 2, dy = (k >> 1) & 1, dz = k & 1;
            float w = (dx ? f.x : 1 - f.x) * (dy ? f.y : 1 - f.y) * (dz ? f.z : 1 - f.z);
            size_t src = index(c.x + dx, c.y + dy, c.z + dz);
            dens += w * density[src];
            const float* sc = &color[src * stride];
            for (int i = 0; i < stride; ++i) col[i] += w * sc[i];
          }
          g.density[dst] = g.actInverse(act(dens) * scaleRatio);
        }
  });
  return g;
}

}  // namespace inim
