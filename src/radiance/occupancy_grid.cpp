// OccupancyGrid: cell flags from corner densities, block flags from cells.
#include "radiance/occupancy_grid.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

namespace inim {

void OccupancyGrid::fillAll(const VoxelGrid& grid) {
  cellRes_ = grid.res - 1;
  cells_.assign(size_t(cellRes_.x) * cellRes_.y * cellRes_.z, 1);
  rebuildBlocks();
}

void OccupancyGrid::update(const VoxelGrid& grid, float stepWorld, float alphaThreshold) {
  cellRes_ = grid.res - 1;
  cells_.resize(size_t(cellRes_.x) * cellRes_.y * cellRes_.z);
  // Threshold on the raw value: act(raw) * scale * step >= -log(1 - alpha).
  float sigmaMin = -std::log(1.0f - alphaThreshold) / (grid.densityScale * stepWorld);
  float rawMin = grid.actInverse(sigmaMin);
  const float* d = grid.density.data();
  size_t dy = size_t(grid.res.z), dx = size_t(grid.res.y) * dy;
  tbb::parallel_for(tbb::blocked_range<int>(0, cellRes_.x), [&](const tbb::blocked_range<int>& r) {
    for (int x = r.begin(); x < r.end(); ++x)
      for (int y = 0; y < cellRes_.y; ++y) {
        size_t base = grid.index(x, y, 0);
        uint8_t* out = &cells_[(size_t(x) * cellRes_.y + y) * cellRes_.z];
        for (int z = 0; z < cellRes_.z; ++z) {
          size_t i = base + z;
          float m = std::max(std::max(std::max(d[i], d[i + 1]), std::max(d[i + dy], d[i + dy + 1])),
                             std::max(std::max(d[i + dx], d[i + dx + 1]),
                                      std::max(d[i + dx + dy], d[i + dx + dy + 1])));
          out[z] = m >= rawMin ? 1 : 0;
        }
      }
  });
  rebuildBlocks();
}

void OccupancyGrid::rebuildBlocks() {
  blockRes_ = (cellRes_ + kBlock - 1) / kBlock;
  blocks_.assign(size_t(blockRes_.x) * blockRes_.y * blockRes_.z, 0);
  tbb::parallel_for(tbb::blocked_range<int>(0, blockRes_.x), [&](const tbb::blocked_range<int>& r) {
    for (int bx = r.begin(); bx < r.end(); ++bx)
      for (int x = bx * kBlock; x < std::min(cellRes_.x, (bx + 1) * kBlock); ++x)
        for (int y = 0; y < cellRes_.y; ++y)
          for (int z = 0; z < cellRes_.z; ++z)
            if (cell(x, y, z))
              blocks_[(size_t(bx) * blockRes_.y + (y >> kBlockLog2)) * blockRes_.z +
                      (z >> kBlockLog2)] = 1;
  });
}

double OccupancyGrid::occupiedFraction() const {
  if (cells_.empty()) return 0.0;
  size_t n = 0;
  for (uint8_t c : cells_) n += c;
  return double(n) / double(cells_.size());
}

bool OccupancyGrid::occupiedBounds(glm::ivec3& lo, glm::ivec3& hi) const {
  lo = cellRes_;
  hi = glm::ivec3(-1);
  for (int x = 0; x < cellRes_.x; ++x)
    for (int y = 0; y < cellRes_.y; ++y)
      for (int z = 0; z < cellRes_.z; ++z)
        if (cell(x, y, z)) {
          lo = glm::min(lo, glm::ivec3(x, y, z));
          hi = glm::max(hi, glm::ivec3(x, y, z));
        }
  return hi.x >= 0;
}

}  // namespace inim
