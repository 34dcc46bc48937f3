#pragma once
// Volume rendering of one ray through a VoxelGrid: the forward march, and the forward march
// followed by its analytic backward pass (used by training and the gradient check).
//
// Samples sit at t_k = t0 + (k + jitter) * step from the box entry t0 (jitter in [0,1) is
// random in training, 0.5 when rendering). Empty cells and blocks of the OccupancyGrid are
// skipped; the march stops once transmittance drops below minTransmittance.
//   C = sum_i T_i alpha_i c_i + T_N * background,   alpha_i = 1 - exp(-sigma_i * step)
#include <cstdint>
#include <vector>

#include "core/geometry.h"
#include "radiance/occupancy_grid.h"
#include "radiance/voxel_grid.h"

namespace inim {

struct MarchSettings {
  float stepVoxels = 0.5f;          // step in units of the smallest cell size
  float minTransmittance = 1e-4f;   // early ray termination
  float occupancyAlpha = 1e-3f;     // a cell is empty below this opacity per step
  // A ray ended early takes, for its remaining transmittance, the colour and depth it has seen
  // (opacity 1) rather than the background: with a high minTransmittance, the far side of a
  // soft surface looks like its near side, not like the background.
  bool completeEnded = false;
  // Colour is evaluated only for samples carrying at least colourMinWeight of the ray's light
  // (T * alpha), as long as the weight left without colour stays under colourSkipBudget; that
  // weight takes the mean colour of the samples evaluated, so a ray's colour is off by at most
  // colourSkipBudget times the spread of its colours. 0: every sample's colour.
  float colourMinWeight = 0.0f;
  float colourSkipBudget = 0.0f;
  float stepWorld(const VoxelGrid& g) const { return stepVoxels * g.minCellSize(); }
};

// A ray in the grid's vertex coordinates (g = (p - lo) / cellSize), clipped to the box.
struct GridRay {
  Vec3 o{0.0f}, d{0.0f}, invD{0.0f};  // grid-space origin and per-unit-t direction
  Vec3 dir{0.0f, 0.0f, 1.0f};         // unit world direction (for the SH basis)
  float t0 = 0.0f, t1 = 0.0f;         // world distances along dir
  float step = 0.0f;
};

// Fills `r` for the ray o + t * dir (dir unit) on [tNear, tFar]; false when it misses the box,
// the interval is empty, or the input is not finite.
bool makeGridRay(const VoxelGrid& grid, const Point3& o, const Vec3& dir, float tNear, float tFar,
                 float step, GridRay& r);

struct RadianceSample {
  Vec3 rgb{0.0f};           // sRGB-encoded (the model's space), background composited
  float depth = kInfinity;  // expected depth sum(w t) / sum(w) along the unit direction
  float opacity = 0.0f;     // accumulated alpha, 1 - T_N
};

// Result for a ray that sees nothing: the background.
inline RadianceSample backgroundResult(const VoxelGrid& g) { return {g.background, kInfinity, 0.0f}; }

RadianceSample marchRay(const VoxelGrid& grid, const OccupancyGrid& occ, const GridRay& r,
                      float jitter, const MarchSettings& settings);

// Gradient of the loss w.r.t. one sample's interpolated raw values; the caller spreads it
// to the 8 corners of cell `base` with trilinear weights from f (and the SH basis for colour).
struct SampleGrad {
  uint32_t base;  // vertex index of the cell's (0,0,0) corner
  float fx, fy, fz;
  float gDensity;   // dL / d raw density
  float gColor[3];  // dL / d pre-sigmoid colour, per channel
};

// Per-thread storage of the forward samples that the backward pass revisits.
struct MarchSample {
  uint32_t base;
  Vec3 f;
  float alpha, transmittance, dSigmaDRaw;
  Vec3 c;
};
struct MarchScratch {
  std::vector<MarchSample> samples;
};

// Forward march, then the backward pass for the loss  lossWeight * |C - target|^2.
// Appends one SampleGrad per visited sample to `out`; returns the forward result.
RadianceSample marchRayGrad(const VoxelGrid& grid, const OccupancyGrid& occ, const GridRay& r,
                          float jitter, float minTransmittance, const Vec3& target,
                          float lossWeight, MarchScratch& scratch, std::vector<SampleGrad>& out);

}  // namespace inim
