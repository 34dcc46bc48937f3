#pragma once
// Training a VoxelGrid from posed rays (Plenoxels/DVGO-style, on the CPU), independent of
// any dataset file format: the caller turns images into rays.
//
// Each iteration renders a random batch of rays with the analytic backward pass, spreads the
// per-sample gradients to grid vertices, adds total variation on the touched vertices and
// takes a lazy Adam step. Coarse-to-fine: the grid starts coarse, may shrink its box to the
// occupied region after the first stage (DVGO's coarse geometry search), and is resampled
// trilinearly at each stage. An occupancy grid, refreshed from density, skips empty space.
//
// Determinism: the batch is split into fixed-size chunks that run in parallel and write
// their per-sample gradients into per-chunk buckets, one per x-slab of the grid; each slab
// then applies its buckets in chunk order. The summation order per vertex is therefore
// fixed and results are bit-identical for any thread count.
#include <functional>
#include <vector>

#include "core/geometry.h"
#include "radiance/ray_march.h"
#include "radiance/voxel_grid.h"

namespace inim {

struct TrainingRays {
  std::vector<Point3> origin;
  std::vector<Vec3> dir;   // any length; normalised internally
  std::vector<Vec3> rgb;   // target pixel values, sRGB-encoded in [0,1] (NeRF convention)
  std::vector<float> tNear, tFar;  // optional per-ray bounds along the unit direction
  size_t size() const { return origin.size(); }
};

struct TrainConfig {
  Point3 boxLo{-1.5f}, boxHi{1.5f};
  float nearT = 0.0f, farT = kInfinity;  // bounds for rays without per-ray bounds
  // Defaults: the Lego benchmark setting (200x200 views: ~31 dB held out in under 10 min on
  // 2 shared cores; see tests/radiance/test_lego_bench.cpp).
  int iterations = 3000;
  double timeBudgetSeconds = 0.0;  // > 0: also stop after this long (then not deterministic)
  int batchSize = 4096;
  // Coarse-to-fine: stage s has about resolutions[s]^3 cells and starts at stageStarts[s].
  std::vector<int> resolutions{64, 128, 160};
  std::vector<int> stageStarts{0, 500, 1500};
  bool tightenBox = true;       // after stage 0, shrink the box to the occupied cells
  float tightenAlpha = 0.02f;   // a cell counts as occupied above this opacity per cell
  int tightenMarginCells = 2;   // margin kept around them, in stage-0 cells
  int shDegree = 1;
  DensityActivation activation = DensityActivation::Softplus;
  Vec3 background{1.0f};
  float initAlpha = 0.01f;      // initial opacity per cell
  float lrDensity = 0.1f, lrColor = 0.05f;
  float lrFinalFactor = 0.1f;   // exponential decay to this fraction at the last iteration
  // Squared-difference total variation on the vertices a batch touches, each edge weighted
  // like one ray's squared error (so the weights do not depend on the batch size).
  // Applied every tvInterval iterations with tvInterval times the weight: TV gathers 6
  // neighbours per vertex, as costly as the Adam step, and a sparser schedule is as smooth.
  float tvDensity = 1e-5f, tvColor = 1e-6f;
  int tvInterval = 4;
  MarchSettings march;
  int occupancyInterval = 16;   // iterations between occupancy refreshes
  uint64_t seed = 1;
  int progressInterval = 50;    // iterations between progress callbacks
};

struct TrainProgress {
  int iteration = 0, iterations = 0;
  double loss = 0.0, psnr = 0.0;  // of the last batch (sRGB MSE)
  double elapsedSeconds = 0.0;
  glm::ivec3 res{0};
  double occupiedFraction = 0.0;
  double samplesPerRay = 0.0;  // of the last batch (march cost)
};

struct TrainStats {
  int iterations = 0;
  double loss = 0.0, psnr = 0.0;  // of the last batch
  double seconds = 0.0;
  bool stoppedEarly = false;      // by the callback or the time budget
};

// Trains `grid` from scratch (it is replaced). onProgress is called every progressInterval
// iterations and at the end; returning false stops training. Throws InputError on a bad
// config or mismatched ray arrays.
TrainStats train(VoxelGrid& grid, const TrainingRays& rays, const TrainConfig& config,
                 const std::function<bool(const TrainProgress&)>& onProgress = {});

// Mean squared error over rays and channels, and its gradient w.r.t. every raw parameter,
// with no empty-space skipping and no jitter (sample offset 0.5): the dense reference for
// the gradient check. Gradients are resized to match the grid.
double lossAndGradient(const VoxelGrid& grid, const TrainingRays& rays, const MarchSettings& march,
                       std::vector<float>& gradDensity, std::vector<float>& gradColor);

}  // namespace inim
