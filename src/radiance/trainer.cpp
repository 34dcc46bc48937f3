// The training loop: batches, chunked forward/backward, slab scatter, TV, lazy Adam,
// occupancy refresh and coarse-to-fine stages.
#include "radiance/trainer.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>

#include "core/error.h"
#include "core/rng.h"
#include "core/size_budget.h"
#include "radiance/occupancy_grid.h"
#include "radiance/sparse_adam.h"
#include "radiance/spherical_harmonics.h"
#include "radiance/volume_renderer.h"

namespace inim {
namespace {

constexpr int kChunkRays = 128;  // rays per chunk: the unit of parallel work
constexpr int kMaxSlabs = 32;    // x-slabs of the grid for the ordered scatter

void check(bool ok, const std::string& key, const std::string& value, const std::string& expected) {
  if (!ok) throw InputError("train config", key, value, expected);
}

void validate(const TrainingRays& rays, const TrainConfig& c) {
  size_t n = rays.origin.size();
  check(n > 0, "rays", "0", "at least one training ray");
  check(rays.dir.size() == n && rays.rgb.size() == n, "rays",
        std::to_string(rays.dir.size()) + " directions, " + std::to_string(rays.rgb.size()) + " colours",
        std::to_string(n) + " of each");
  check(rays.tNear.empty() || rays.tNear.size() == n, "tNear", std::to_string(rays.tNear.size()),
        "empty or one per ray");
  check(rays.tFar.empty() || rays.tFar.size() == n, "tFar", std::to_string(rays.tFar.size()),
        "empty or one per ray");
  check(glm::all(glm::lessThan(c.boxLo, c.boxHi)) && isFinite(c.boxLo) && isFinite(c.boxHi), "box",
        "lo >= hi", "finite box with lo < hi on every axis");
  check(c.iterations >= 0, "iterations", std::to_string(c.iterations), ">= 0");
  check(c.batchSize > 0, "batch_size", std::to_string(c.batchSize), "> 0");
  check(c.shDegree >= 0 && c.shDegree <= 2, "sh_degree", std::to_string(c.shDegree), "0, 1 or 2");
  check(!c.resolutions.empty() && c.resolutions.size() == c.stageStarts.size(), "resolutions",
        std::to_string(c.resolutions.size()) + " resolutions, " +
            std::to_string(c.stageStarts.size()) + " stage starts",
        "one stage start per resolution");
  for (size_t s = 0; s < c.resolutions.size(); ++s) {
    check(c.resolutions[s] >= 2 && c.resolutions[s] <= 1024, "resolutions",
          std::to_string(c.resolutions[s]), "between 2 and 1024");
    check(s == 0 ? c.stageStarts[s] == 0 : c.stageStarts[s] > c.stageStarts[s - 1], "stage_starts",
          std::to_string(c.stageStarts[s]), "0 first, then increasing");
  }
  // Per grid vertex while training: the parameters, their gradients and Adam's two moments
  // (density and colourStride colour floats each), the touched flag; a stage's growth holds the
  // grid it resamples beside the new one.
  const double floatsPerVertex = 1.0 + 3.0 * shCount(c.shDegree);
  for (size_t s = 0; s < c.resolutions.size(); ++s) {
    const glm::ivec3 res = VoxelGrid::resolutionFor(c.boxLo, c.boxHi, c.resolutions[s]);
    const double vertices = double(res.x) * res.y * res.z;
    checkAllocation("", "resolutions", std::to_string(c.resolutions[s]) + " (" + std::to_string(res.x) + " x " +
                                           std::to_string(res.y) + " x " + std::to_string(res.z) + " vertices)",
                    {{vertices, 4.0 * 4.0 * floatsPerVertex + 1.0}, {vertices, 4.0 * floatsPerVertex}},
                    "training stage " + std::to_string(s + 1) + "'s grid");
  }
  check(c.initAlpha > 0.0f && c.initAlpha < 1.0f, "init_alpha", std::to_string(c.initAlpha), "in (0, 1)");
  check(c.lrDensity >= 0.0f && c.lrColor >= 0.0f && c.lrFinalFactor > 0.0f, "lr", "negative",
        "non-negative learning rates and a positive final factor");
  check(c.tvDensity >= 0.0f && c.tvColor >= 0.0f, "tv", "negative", "non-negative TV weights");
  check(c.tvInterval > 0, "tv_interval", std::to_string(c.tvInterval), "> 0");
  check(c.march.stepVoxels > 0.0f, "step_voxels", std::to_string(c.march.stepVoxels), "> 0");
  check(c.occupancyInterval > 0, "occupancy_interval", std::to_string(c.occupancyInterval), "> 0");
}

struct SlabRecord {
  SampleGrad g;
  uint32_t ray;  // index of the ray within its chunk (its SH basis)
};

// Everything that depends on the grid's resolution.
struct Optimiser {
  std::vector<float> gradDensity, gradColor;
  std::vector<uint8_t> touchedFlag;
  SparseAdam adamDensity, adamColor;
  std::vector<int> slabOfX;
  int slabs = 1;
  int step = 0;

  void reset(const VoxelGrid& g) {
    size_t n = g.vertexCount();
    gradDensity.assign(n, 0.0f);
    gradColor.assign(n * size_t(g.colorStride()), 0.0f);
    touchedFlag.assign(n, 0);
    adamDensity = SparseAdam(n, 1);
    adamColor = SparseAdam(n, g.colorStride());
    slabs = std::min(kMaxSlabs, g.res.x);
    slabOfX.resize(size_t(g.res.x));
    for (int x = 0; x < g.res.x; ++x) slabOfX[size_t(x)] = int(int64_t(x) * slabs / g.res.x);
    step = 0;
  }
};

struct Chunk {
  MarchScratch scratch;
  std::vector<SampleGrad> grads;
  std::vector<float> sh;  // kMaxShCount per ray
  double sqError = 0.0;
  size_t samples = 0;
};

// Spreads one sample's gradient to the corners of its cell that lie in slab `s`.
template <int D>
inline void scatter(const SlabRecord& rec, const float* sh, int s, const VoxelGrid& g,
                    Optimiser& opt, std::vector<uint32_t>& touched) {
  constexpr int N = shCount(D), S = 3 * N;
  const size_t sy = size_t(g.res.z), sx = size_t(g.res.y) * sy;
  const SampleGrad& sg = rec.g;
  size_t x0 = sg.base / sx;
  bool low = opt.slabOfX[x0] == s, high = opt.slabOfX[x0 + 1] == s;
  float x1 = sg.fx, y1 = sg.fy, z1 = sg.fz, xa = 1 - x1, ya = 1 - y1, za = 1 - z1;
  const float w[8] = {xa * ya * za, xa * ya * z1, xa * y1 * za, xa * y1 * z1,
                      x1 * ya * za, x1 * ya * z1, x1 * y1 * za, x1 * y1 * z1};
  float gc[S];
  for (int l = 0; l < N; ++l)
    for (int ch = 0; ch < 3; ++ch) gc[3 * l + ch] = sh[l] * sg.gColor[ch];
  for (int k = 0; k < 8; ++k) {
    if (k < 4 ? !low : !high) continue;
    size_t i = sg.base + (k >> 2) * sx + ((k >> 1) & 1) * sy + (k & 1);
    if (!opt.touchedFlag[i]) {
      opt.touchedFlag[i] = 1;
      touched.push_back(uint32_t(i));
    }
    opt.gradDensity[i] += w[k] * sg.gDensity;
    float* dst = &opt.gradColor[i * S];
    for (int j = 0; j < S; ++j) dst[j] += w[k] * gc[j];
  }
}

// Gradient of  tv * sum over grid edges (a - b)^2 / 2  at vertex i, added to its gradient.
void addTv(const VoxelGrid& g, uint32_t i, float tvD, float tvC, Optimiser& opt) {
  const size_t sy = size_t(g.res.z), sx = size_t(g.res.y) * sy;
  int x = int(i / sx), y = int((i / sy) % size_t(g.res.y)), z = int(i % sy);
  const int S = g.colorStride();
  const int pos[3] = {x, y, z};
  const size_t strides[3] = {sx, sy, 1};
  float gd = 0.0f;
  float gc[3 * kMaxShCount] = {};
  const float* ci = &g.color[size_t(i) * S];
  for (int a = 0; a < 3; ++a)
    for (int sgn = -1; sgn <= 1; sgn += 2) {
      int p = pos[a] + sgn;
      if (p < 0 || p >= g.res[a]) continue;
      size_t n = sgn > 0 ? i + strides[a] : i - strides[a];
      gd += g.density[i] - g.density[n];
      if (tvC > 0.0f) {
        const float* cn = &g.color[n * S];
        for (int j = 0; j < S; ++j) gc[j] += ci[j] - cn[j];
      }
    }
  opt.gradDensity[i] += tvD * gd;
  if (tvC > 0.0f) {
    float* dst = &opt.gradColor[size_t(i) * S];
    for (int j = 0; j < S; ++j) dst[j] += tvC * gc[j];
  }
}

// The box of the cells whose opacity per cell exceeds `alpha`, grown by `margin` cells.
bool occupiedBox(const VoxelGrid& g, float alpha, int margin, Point3& lo, Point3& hi) {
  OccupancyGrid occ;
  occ.update(g, g.minCellSize(), alpha);
  glm::ivec3 cl, ch;
  if (!occ.occupiedBounds(cl, ch)) return false;
  Vec3 cell = g.cellSize();
  lo = glm::max(g.lo, g.lo + Vec3(cl - margin) * cell);
  hi = glm::min(g.hi, g.lo + Vec3(ch + 1 + margin) * cell);
  return glm::all(glm::lessThan(lo, hi));
}

// One training run's state and the steps of an iteration, in the order train() calls them.
class TrainingLoop {
 public:
  TrainingLoop(VoxelGrid& grid, const TrainingRays& rays, const TrainConfig& cfg)
      : grid_(grid),
        rays_(rays),
        cfg_(cfg),
        numChunks_((cfg.batchSize + kChunkRays - 1) / kChunkRays),
        lossWeight_(1.0f / (3.0f * float(cfg.batchSize))) {
    grid_ = VoxelGrid::create(cfg.boxLo, cfg.boxHi, VoxelGrid::resolutionFor(cfg.boxLo, cfg.boxHi, cfg.resolutions[0]),
                              cfg.shDegree, cfg.activation, cfg.background, cfg.initAlpha);
    opt_.reset(grid_);
    chunks_.resize(size_t(numChunks_));
  }

  // Coarse-to-fine growth (and box tightening after the first stage), the occupancy refresh and
  // what the iteration's steps share.
  void beginIteration(int it) {
    if (stage_ + 1 < cfg_.resolutions.size() && it == cfg_.stageStarts[stage_ + 1]) {
      ++stage_;
      Point3 lo = grid_.lo, hi = grid_.hi;
      if (stage_ == 1 && cfg_.tightenBox) {
        Point3 tlo, thi;
        if (occupiedBox(grid_, cfg_.tightenAlpha, cfg_.tightenMarginCells, tlo, thi)) lo = tlo, hi = thi;
      }
      grid_ = grid_.resampled(lo, hi, VoxelGrid::resolutionFor(lo, hi, cfg_.resolutions[stage_]));
      opt_.reset(grid_);
    }
    if (it % cfg_.occupancyInterval == 0 || occ_.cellRes() != grid_.res - 1)
      occ_.update(grid_, cfg_.march.stepWorld(grid_), cfg_.march.occupancyAlpha);
    buckets_.resize(size_t(numChunks_) * size_t(opt_.slabs));
    touched_.resize(size_t(opt_.slabs));
    step_ = cfg_.march.stepWorld(grid_);
  }

  // 1. Forward + backward per chunk; records go to per-(chunk, slab) buckets.
  void forwardBackward(int it) {
    tbb::parallel_for(tbb::blocked_range<int>(0, numChunks_, 1), [&](const tbb::blocked_range<int>& r) {
      for (int c = r.begin(); c < r.end(); ++c) forwardBackwardChunk(it, c);
    });
  }

  // 2. Ordered scatter per slab, then TV on the touched vertices.
  void scatterAndTv(int it) {
    tbb::parallel_for(tbb::blocked_range<int>(0, opt_.slabs, 1), [&](const tbb::blocked_range<int>& r) {
      for (int s = r.begin(); s < r.end(); ++s) scatterSlab(it, s);
    });
  }

  // 3. Lazy Adam on the touched vertices (after all TV reads of the current values).
  void adamStep(int it) {
    opt_.step++;
    const float decay = std::pow(cfg_.lrFinalFactor, float(it) / float(std::max(1, cfg_.iterations)));
    tbb::parallel_for(tbb::blocked_range<int>(0, opt_.slabs, 1), [&](const tbb::blocked_range<int>& r) {
      for (int s = r.begin(); s < r.end(); ++s) {
        const auto& list = touched_[size_t(s)];
        opt_.adamDensity.update(list, grid_.density.data(), opt_.gradDensity.data(), cfg_.lrDensity * decay,
                                opt_.step);
        opt_.adamColor.update(list, grid_.color.data(), opt_.gradColor.data(), cfg_.lrColor * decay, opt_.step);
        for (uint32_t v : list) opt_.touchedFlag[v] = 0;
      }
    });
  }

  // The iteration's loss (mean squared error per channel) and samples marched per ray.
  double loss(double& samplesPerRay) const {
    double sq = 0.0;
    size_t samples = 0;
    for (const Chunk& ch : chunks_) sq += ch.sqError, samples += ch.samples;
    samplesPerRay = double(samples) / double(cfg_.batchSize);
    return sq / (3.0 * double(cfg_.batchSize));
  }
  double occupiedFraction() const { return occ_.occupiedFraction(); }

 private:
  void forwardBackwardChunk(int it, int c) {
    Chunk& ch = chunks_[size_t(c)];
    ch.sqError = 0.0;
    ch.samples = 0;
    ch.sh.resize(size_t(kChunkRays) * kMaxShCount);
    for (int s = 0; s < opt_.slabs; ++s) buckets_[size_t(c) * opt_.slabs + s].clear();
    const size_t sx = size_t(grid_.res.y) * size_t(grid_.res.z), numRays = rays_.size();
    const int k0 = c * kChunkRays, k1 = std::min(cfg_.batchSize, k0 + kChunkRays);
    for (int k = k0; k < k1; ++k) {
      Rng rng = Rng::forSample(cfg_.seed, uint64_t(it), uint64_t(k));
      uint64_t pick = (uint64_t(rng.nextU32()) << 32) | rng.nextU32();
      size_t idx = size_t(pick % numRays);
      float jitter = rng.uniform();
      Vec3 dir = rays_.dir[idx];
      float len = glm::length(dir);
      const Vec3& target = rays_.rgb[idx];
      GridRay gr;
      RadianceSample res = backgroundResult(grid_);
      ch.grads.clear();
      if (len > 0.0f && makeGridRay(grid_, rays_.origin[idx], dir / len, rays_.tNear.empty() ? cfg_.nearT : rays_.tNear[idx],
                                    rays_.tFar.empty() ? cfg_.farT : rays_.tFar[idx], step_, gr)) {
        res = marchRayGrad(grid_, occ_, gr, jitter, cfg_.march.minTransmittance, target, lossWeight_, ch.scratch,
                           ch.grads);
        evalSh(grid_.shDegree, gr.dir, &ch.sh[size_t(k - k0) * kMaxShCount]);
      }
      Vec3 e = res.rgb - target;
      ch.sqError += double(e.x) * e.x + double(e.y) * e.y + double(e.z) * e.z;
      ch.samples += ch.grads.size();
      for (const SampleGrad& sg : ch.grads) {
        size_t x0 = sg.base / sx;
        int s0 = opt_.slabOfX[x0], s1 = opt_.slabOfX[x0 + 1];
        buckets_[size_t(c) * opt_.slabs + s0].push_back({sg, uint32_t(k - k0)});
        if (s1 != s0) buckets_[size_t(c) * opt_.slabs + s1].push_back({sg, uint32_t(k - k0)});
      }
    }
  }

  void scatterSlab(int it, int s) {
    auto& list = touched_[size_t(s)];
    list.clear();
    for (int c = 0; c < numChunks_; ++c) {
      const float* shBase = chunks_[size_t(c)].sh.data();
      for (const SlabRecord& rec : buckets_[size_t(c) * opt_.slabs + s]) {
        const float* sh = shBase + size_t(rec.ray) * kMaxShCount;
        switch (grid_.shDegree) {
          case 0: scatter<0>(rec, sh, s, grid_, opt_, list); break;
          case 1: scatter<1>(rec, sh, s, grid_, opt_, list); break;
          default: scatter<2>(rec, sh, s, grid_, opt_, list); break;
        }
      }
    }
    if ((cfg_.tvDensity > 0.0f || cfg_.tvColor > 0.0f) && it % cfg_.tvInterval == 0) {
      float w = lossWeight_ * float(cfg_.tvInterval);
      for (uint32_t v : list) addTv(grid_, v, cfg_.tvDensity * w, cfg_.tvColor * w, opt_);
    }
  }

  VoxelGrid& grid_;
  const TrainingRays& rays_;
  const TrainConfig& cfg_;
  const int numChunks_;
  const float lossWeight_;  // the loss is the mean over the batch's 3 channels
  Optimiser opt_;
  OccupancyGrid occ_;
  std::vector<Chunk> chunks_;
  std::vector<std::vector<SlabRecord>> buckets_;
  std::vector<std::vector<uint32_t>> touched_;
  size_t stage_ = 0;
  float step_ = 0.0f;  // the march step of the current grid
};

}  // namespace

TrainStats train(VoxelGrid& grid, const TrainingRays& rays, const TrainConfig& cfg,
                 const std::function<bool(const TrainProgress&)>& onProgress) {
  validate(rays, cfg);
  const auto start = std::chrono::steady_clock::now();
  auto elapsed = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(); };
  TrainingLoop loop(grid, rays, cfg);
  TrainStats stats;
  double lastLoss = 0.0;
  for (int it = 0; it < cfg.iterations; ++it) {
    loop.beginIteration(it);
    loop.forwardBackward(it);
    loop.scatterAndTv(it);
    loop.adamStep(it);
    double samplesPerRay = 0.0;
    lastLoss = loop.loss(samplesPerRay);
    stats.iterations = it + 1;
    const bool last = it + 1 == cfg.iterations;
    const bool overTime = cfg.timeBudgetSeconds > 0.0 && elapsed() > cfg.timeBudgetSeconds;
    if (onProgress && ((it + 1) % std::max(1, cfg.progressInterval) == 0 || last || overTime)) {
      TrainProgress p;
      p.iteration = it + 1;
      p.iterations = cfg.iterations;
      p.loss = lastLoss;
      p.psnr = psnrFromMse(lastLoss);
      p.elapsedSeconds = elapsed();
      p.res = grid.res;
      p.occupiedFraction = loop.occupiedFraction();
      p.samplesPerRay = samplesPerRay;
      if (!onProgress(p)) {
        stats.stoppedEarly = !last;
        break;
      }
    }
    if (overTime && !last) {
      stats.stoppedEarly = true;
      break;
    }
  }
  stats.loss = lastLoss;
  stats.psnr = psnrFromMse(lastLoss);
  stats.seconds = elapsed();
  return stats;
}

double lossAndGradient(const VoxelGrid& grid, const TrainingRays& rays, const MarchSettings& march,
                       std::vector<float>& gradDensity, std::vector<float>& gradColor) {
  const int S = grid.colorStride(), N = shCount(grid.shDegree);
  gradDensity.assign(grid.vertexCount(), 0.0f);
  gradColor.assign(grid.vertexCount() * size_t(S), 0.0f);
  OccupancyGrid occ;
  occ.fillAll(grid);
  MarchScratch scratch;
  std::vector<SampleGrad> grads;
  const float lossWeight = 1.0f / (3.0f * float(rays.size()));
  const size_t sy = size_t(grid.res.z), sx = size_t(grid.res.y) * sy;
  double sq = 0.0;
  for (size_t i = 0; i < rays.size(); ++i) {
    GridRay gr;
    RadianceSample res = backgroundResult(grid);
    grads.clear();
    float len = glm::length(rays.dir[i]);
    if (len > 0.0f && makeGridRay(grid, rays.origin[i], rays.dir[i] / len,
                                  rays.tNear.empty() ? 0.0f : rays.tNear[i],
                                  rays.tFar.empty() ? kInfinity : rays.tFar[i],
                                  march.stepWorld(grid), gr))
      res = marchRayGrad(grid, occ, gr, 0.5f, march.minTransmittance, rays.rgb[i], lossWeight,
                         scratch, grads);
    Vec3 e = res.rgb - rays.rgb[i];
    sq += double(glm::dot(e, e));
    float sh[kMaxShCount];
    evalSh(grid.shDegree, gr.dir, sh);
    for (const SampleGrad& g : grads) {
      float w[8];
      float x1 = g.fx, y1 = g.fy, z1 = g.fz;
      for (int k = 0; k < 8; ++k)
        w[k] = ((k >> 2) ? x1 : 1 - x1) * (((k >> 1) & 1) ? y1 : 1 - y1) * ((k & 1) ? z1 : 1 - z1);
      for (int k = 0; k < 8; ++k) {
        size_t v = g.base + (k >> 2) * sx + ((k >> 1) & 1) * sy + (k & 1);
        gradDensity[v] += w[k] * g.gDensity;
        for (int l = 0; l < N; ++l)
          for (int ch = 0; ch < 3; ++ch) gradColor[v * S + 3 * l + ch] += w[k] * sh[l] * g.gColor[ch];
      }
    }
  }
  return sq / (3.0 * double(rays.size()));
}

}  // namespace inim
