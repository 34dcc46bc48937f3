#pragma once
// Rendering a batch of rays through a trained VoxelGrid: parallel over fixed chunks, each
// ray a pure function of the grid, so results are bit-identical for any thread count.
#include <span>

#include "core/geometry.h"
#include "radiance/occupancy_grid.h"
#include "radiance/ray_march.h"
#include "radiance/voxel_grid.h"

namespace inim {

struct RenderRay {
  Point3 o{0.0f};
  Vec3 d{0.0f, 0.0f, -1.0f};  // any length; normalised (depth is along the unit direction)
  float tNear = 0.0f;         // interval along the unit direction, intersected with the box
  float tFar = kInfinity;
};

class VolumeRenderer {
 public:
  // Keeps a reference to `grid` (which must outlive the renderer) and builds its occupancy.
  explicit VolumeRenderer(const VoxelGrid& grid, const MarchSettings& settings = {});
  RadianceSample render(const RenderRay& ray) const;
  void render(std::span<const RenderRay> rays, std::span<RadianceSample> out) const;
  const OccupancyGrid& occupancy() const { return occupancy_; }
  const VoxelGrid& grid() const { return grid_; }

 private:
  const VoxelGrid& grid_;
  MarchSettings settings_;
  OccupancyGrid occupancy_;
};

// PSNR in dB of `a` against `b` with peak 1 (values as given; NeRF reports it on sRGB).
double psnr(std::span<const Vec3> a, std::span<const Vec3> b);
// PSNR in dB from a mean squared error, peak 1.
double psnrFromMse(double mse);

}  // namespace inim
