#pragma once
// Occupancy for empty-space skipping: one flag per grid cell, plus one per block of
// kBlock^3 cells so a ray can jump over large empty regions in one step.
//
// A cell is occupied when the largest raw density at its 8 corners gives, after
// activation, an opacity >= alphaThreshold over one march step. Activations are monotone
// and trilinear weights are convex, so no point inside an empty cell can exceed that
// opacity: skipping is conservative at the chosen threshold.
#include <cstdint>
#include <glm/glm.hpp>
#include <vector>

#include "radiance/voxel_grid.h"

namespace inim {

class OccupancyGrid {
 public:
  static constexpr int kBlockLog2 = 3;
  static constexpr int kBlock = 1 << kBlockLog2;

  OccupancyGrid() = default;
  // Every cell occupied (no skipping; gradient checks and the first iterations).
  void fillAll(const VoxelGrid& grid);
  // Recomputes the flags from the grid's densities (parallel, deterministic).
  void update(const VoxelGrid& grid, float stepWorld, float alphaThreshold);

  bool cell(int x, int y, int z) const {
    return cells_[(size_t(x) * cellRes_.y + y) * cellRes_.z + z] != 0;
  }
  bool block(int bx, int by, int bz) const {
    return blocks_[(size_t(bx) * blockRes_.y + by) * blockRes_.z + bz] != 0;
  }
  const glm::ivec3& cellRes() const { return cellRes_; }
  double occupiedFraction() const;
  // Cell-index bounds [lo, hi] of the occupied cells; false when none is occupied.
  bool occupiedBounds(glm::ivec3& lo, glm::ivec3& hi) const;

 private:
  void rebuildBlocks();
  glm::ivec3 cellRes_{0}, blockRes_{0};
  std::vector<uint8_t> cells_, blocks_;
};

}  // namespace inim
