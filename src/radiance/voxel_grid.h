#pragma once
// The explicit radiance-field model (Plenoxels/DVGO style): values on the vertices of a
// regular grid over an axis-aligned box, trilinearly interpolated. Each vertex holds a raw
// density and 3 x shCount(shDegree) raw spherical-harmonic colour coefficients.
//
//   sigma(p) = densityScale * act(trilerp(rawDensity)(p))        (1 / length)
//   rgb(p,d) = sigmoid(sum_l Y_l(d) * trilerp(rawSh_l)(p))         (sRGB-encoded, NeRF convention)
//
// Interpolating raw values and activating afterwards ("post-activation", DVGO) gives sharp
// surfaces inside a single cell. densityScale = 1 / cell size, so raw densities of order 1-10
// mean "opaque within a cell" at every resolution and one learning rate works for all
// stages; resampling converts raw values so that sigma in world units is preserved.
#include <cstdint>
#include <glm/glm.hpp>
#include <string>
#include <vector>

#include "core/geometry.h"
#include "radiance/spherical_harmonics.h"

namespace inim {

// Softplus (default): smooth and never "dead", so a region wrongly emptied early still gets
// gradients and empty space fades out gradually; with post-activation it still reaches
// sharp opaque surfaces. ReLU (Plenoxels) is available for comparison.
enum class DensityActivation : uint32_t { Softplus = 0, ReLU = 1 };

struct VoxelGrid {
  Point3 lo{-1.5f}, hi{1.5f};
  glm::ivec3 res{2};  // vertices per axis (>= 2)
  int shDegree = 1;   // 0..2
  DensityActivation activation = DensityActivation::Softplus;
  Vec3 background{1.0f};     // composited by the remaining transmittance (sRGB-encoded)
  float densityScale = 1.0f;  // sigma = densityScale * act(raw)
  std::vector<float> density;  // raw, one per vertex, z fastest: ((x * res.y) + y) * res.z + z
  std::vector<float> color;    // raw SH, colorStride() per vertex: [sh][channel]
  std::string metadata;        // JSON: the dataset, its format and units (saved with the model)

  int colorStride() const { return 3 * shCount(shDegree); }
  size_t vertexCount() const { return size_t(res.x) * size_t(res.y) * size_t(res.z); }
  size_t index(int x, int y, int z) const {
    return (size_t(x) * size_t(res.y) + size_t(y)) * size_t(res.z) + size_t(z);
  }
  Vec3 cellSize() const { return (hi - lo) / Vec3(res - 1); }
  float minCellSize() const {
    Vec3 c = cellSize();
    return std::min(c.x, std::min(c.y, c.z));
  }
  float act(float raw) const;
  float actDerivative(float raw) const;  // d act / d raw
  float actInverse(float value) const;

  // A grid whose every cell has opacity `initAlpha` across one cell, colour grey (SH 0).
  static VoxelGrid create(const Point3& lo, const Point3& hi, const glm::ivec3& res, int shDegree,
                          DensityActivation activation, const Vec3& background, float initAlpha);
  // Vertices per axis for about side^3 cells spread over the box with near-cubic cells
  // (DVGO's num_voxels convention): a tight box gets the same budget at finer cells.
  static glm::ivec3 resolutionFor(const Point3& lo, const Point3& hi, int side);
  // This grid resampled trilinearly onto a new box and resolution (coarse-to-fine growth,
  // box tightening). World-space sigma is preserved; outside the old box values clamp.
  VoxelGrid resampled(const Point3& newLo, const Point3& newHi, const glm::ivec3& newRes) const;
};

}  // namespace inim
