// The ray march: box clipping, occupancy skipping, trilinear lookups, forward compositing
// and the backward pass. Templated on the SH degree so the colour loops unroll.
#include "radiance/ray_march.h"

#include <algorithm>
#include <cmath>

#include "radiance/spherical_harmonics.h"

namespace inim {

bool makeGridRay(const VoxelGrid& grid, const Point3& o, const Vec3& dir, float tNear, float tFar,
                 float step, GridRay& r) {
  if (!isFinite(o) || !isFinite(dir) || std::isnan(tNear) || std::isnan(tFar) || !(step > 0.0f))
    return false;
  Vec3 inv = Vec3(grid.res - 1) / (grid.hi - grid.lo);
  r.o = (o - grid.lo) * inv;
  r.d = dir * inv;
  r.dir = dir;
  r.step = step;
  float t0 = std::max(tNear, 0.0f), t1 = tFar;
  Vec3 top = Vec3(grid.res - 1);
  for (int a = 0; a < 3; ++a) {
    if (r.d[a] == 0.0f) {
      r.invD[a] = kInfinity;
      if (r.o[a] < 0.0f || r.o[a] > top[a]) return false;
      continue;
    }
    r.invD[a] = 1.0f / r.d[a];
    float ta = (0.0f - r.o[a]) * r.invD[a], tb = (top[a] - r.o[a]) * r.invD[a];
    if (ta > tb) std::swap(ta, tb);
    t0 = std::max(t0, ta);
    t1 = std::min(t1, tb);
  }
  r.t0 = t0;
  r.t1 = t1;
  return t0 < t1;
}

namespace {

// Distance along the ray to where it leaves occupancy block (bx, by, bz).
inline float blockExit(const GridRay& r, const glm::ivec3& cellRes, int bx, int by, int bz) {
  const int b[3] = {bx, by, bz};
  float t = kInfinity;
  for (int a = 0; a < 3; ++a) {
    if (r.d[a] == 0.0f) continue;
    float lo = float(b[a] * OccupancyGrid::kBlock);
    float hi = float(std::min((b[a] + 1) * OccupancyGrid::kBlock, cellRes[a]));
    float plane = r.d[a] > 0.0f ? hi : lo;
    t = std::min(t, (plane - r.o[a]) * r.invD[a]);
  }
  return t;
}

// Calls visit(t, base, f) for every sample in an occupied cell, in order, until it returns
// false or the ray leaves its interval.
template <class Visit>
inline void forEachSample(const VoxelGrid& grid, const OccupancyGrid& occ, const GridRay& r,
                          float jitter, Visit&& visit) {
  const glm::ivec3 cr = occ.cellRes();
  const size_t sy = size_t(grid.res.z), sx = size_t(grid.res.y) * sy;
  int64_t k = 0;
  for (;;) {
    float t = r.t0 + (float(k) + jitter) * r.step;
    if (!(t < r.t1)) return;
    Vec3 g = r.o + t * r.d;
    int cx = std::clamp(int(g.x), 0, cr.x - 1), cy = std::clamp(int(g.y), 0, cr.y - 1),
        cz = std::clamp(int(g.z), 0, cr.z - 1);
    int bx = cx >> OccupancyGrid::kBlockLog2, by = cy >> OccupancyGrid::kBlockLog2,
        bz = cz >> OccupancyGrid::kBlockLog2;
    if (!occ.block(bx, by, bz)) {
      float tExit = blockExit(r, cr, bx, by, bz);
      float kf = std::ceil((tExit - r.t0) / r.step - jitter);
      k = (kf > float(k + 1) && kf < 1e9f) ? int64_t(kf) : k + 1;
      continue;
    }
    if (occ.cell(cx, cy, cz)) {
      Vec3 f = glm::clamp(g - Vec3(cx, cy, cz), Vec3(0.0f), Vec3(1.0f));
      if (!visit(t, uint32_t(size_t(cx) * sx + size_t(cy) * sy + size_t(cz)), f)) return;
    }
    ++k;
  }
}

inline void trilinearWeights(const Vec3& f, float w[8]) {
  float x0 = 1.0f - f.x, y0 = 1.0f - f.y, z0 = 1.0f - f.z;
  w[0] = x0 * y0 * z0;
  w[1] = x0 * y0 * f.z;
  w[2] = x0 * f.y * z0;
  w[3] = x0 * f.y * f.z;
  w[4] = f.x * y0 * z0;
  w[5] = f.x * y0 * f.z;
  w[6] = f.x * f.y * z0;
  w[7] = f.x * f.y * f.z;
}

struct Corners {
  size_t off[8];
  explicit Corners(const VoxelGrid& g) {
    size_t sy = size_t(g.res.z), sx = size_t(g.res.y) * sy;
    for (int k = 0; k < 8; ++k) off[k] = (k >> 2) * sx + ((k >> 1) & 1) * sy + (k & 1);
  }
};

inline float sigmoid(float x) { return 1.0f / (1.0f + std::exp(-x)); }

// Interpolated raw density and sRGB colour of one sample.
template <int D>
inline float sampleRaw(const VoxelGrid& grid, const Corners& cn, uint32_t base, const float w[8],
                       const float* sh, Vec3& c) {
  constexpr int N = shCount(D), S = 3 * N;
  const float* dens = grid.density.data();
  float raw = 0.0f;
  for (int k = 0; k < 8; ++k) raw += w[k] * dens[base + cn.off[k]];
  float coef[S] = {};
  for (int k = 0; k < 8; ++k) {
    const float* src = grid.color.data() + (base + cn.off[k]) * S;
    for (int i = 0; i < S; ++i) coef[i] += w[k] * src[i];
  }
  for (int ch = 0; ch < 3; ++ch) {
    float v = 0.0f;
    for (int l = 0; l < N; ++l) v += sh[l] * coef[3 * l + ch];
    c[ch] = sigmoid(v);
  }
  return raw;
}

// The march's result: accumulated colour over the background by the remaining transmittance,
// opacity, and the expected depth (weights normalised by the opacity).
RadianceSample composite(const VoxelGrid& grid, float T, const Vec3& rgb, float depth) {
  RadianceSample res;
  res.opacity = 1.0f - T;
  res.rgb = rgb + T * grid.background;
  res.depth = res.opacity > 1e-3f ? depth / res.opacity : kInfinity;
  return res;
}

// A sample's opacity 1 - exp(-densityScale * act(raw) * step). With softplus,
// exp(-s softplus(raw)) = (1 + e^raw)^-s for s = densityScale * step, which for the usual
// steps (s = 1: one cell, s = 1/2) needs one exp instead of exp, log1p and exp, and is
// written without cancellation for small opacities.
struct SampleAlpha {
  const VoxelGrid& grid;
  float s;
  SampleAlpha(const VoxelGrid& g, float step) : grid(g), s(snap(g.densityScale * step)) {}
  // densityScale * step is 1 or 1/2 only up to rounding (densityScale = 1 / cell).
  static float snap(float s) {
    for (float exact : {1.0f, 0.5f})
      if (std::abs(s - exact) < 1e-5f * exact) return exact;
    return s;
  }
  float operator()(float raw) const {
    if (grid.activation != DensityActivation::Softplus) return -std::expm1(-s * grid.act(raw));
    if (s == 1.0f) return 1.0f / (1.0f + std::exp(-raw));
    if (s == 0.5f && raw < 40.0f) {  // above, the opacity is 1 in float
      const float u = std::exp(raw), q = std::sqrt(1.0f + u);
      return u / (q * (1.0f + q));
    }
    return -std::expm1(-s * grid.act(raw));
  }
};

template <int D>
RadianceSample marchRayT(const VoxelGrid& grid, const OccupancyGrid& occ, const GridRay& r,
                       float jitter, const MarchSettings& ms) {
  float sh[kMaxShCount];
  evalSh(D, r.dir, sh);
  Corners cn(grid);
  float T = 1.0f, depth = 0.0f, skipped = 0.0f, coloured = 0.0f;
  Vec3 rgb(0.0f);
  const float* dens = grid.density.data();
  const SampleAlpha alphaOf(grid, r.step);
  const float minT = ms.minTransmittance;
  forEachSample(grid, occ, r, jitter, [&](float t, uint32_t base, const Vec3& f) {
    float w[8];
    trilinearWeights(f, w);
    // Density first: most occupied-cell samples near a surface's edge are nearly empty and
    // need no colour.
    float raw = 0.0f;
    for (int k = 0; k < 8; ++k) raw += w[k] * dens[base + cn.off[k]];
    float alpha = alphaOf(raw);
    if (alpha < 1e-6f) return true;
    float wt = T * alpha;
    depth += wt * t;
    T *= 1.0f - alpha;
    // Colour is most of a sample's cost (12+ coefficients at 8 corners, far apart in memory).
    if (wt < ms.colourMinWeight && skipped + wt < ms.colourSkipBudget) {
      skipped += wt;
    } else {
      Vec3 c;
      sampleRaw<D>(grid, cn, base, w, sh, c);
      rgb += wt * c;
      coloured += wt;
    }
    return T >= minT;
  });
  if (skipped > 0.0f)  // the weight left without colour takes the others' mean (none: the background)
    rgb = coloured > 0.0f ? rgb * ((skipped + coloured) / coloured) : skipped * grid.background;
  if (ms.completeEnded && T < minT) {
    const float k = 1.0f / (1.0f - T);
    rgb *= k, depth *= k, T = 0.0f;
  }
  return composite(grid, T, rgb, depth);
}

template <int D>
RadianceSample marchRayGradT(const VoxelGrid& grid, const OccupancyGrid& occ, const GridRay& r,
                           float jitter, float minT, const Vec3& target, float lossWeight,
                           MarchScratch& scratch, std::vector<SampleGrad>& out) {
  float sh[kMaxShCount];
  evalSh(D, r.dir, sh);
  Corners cn(grid);
  auto& samples = scratch.samples;
  samples.clear();
  float T = 1.0f, depth = 0.0f;
  Vec3 rgb(0.0f);
  const SampleAlpha alphaOf(grid, r.step);
  forEachSample(grid, occ, r, jitter, [&](float t, uint32_t base, const Vec3& f) {
    float w[8];
    trilinearWeights(f, w);
    Vec3 c;
    float raw = sampleRaw<D>(grid, cn, base, w, sh, c);
    float alpha = alphaOf(raw);
    samples.push_back({base, f, alpha, T, grid.densityScale * grid.actDerivative(raw), c});
    float wt = T * alpha;
    rgb += wt * c;
    depth += wt * t;
    T *= 1.0f - alpha;
    return T >= minT;
  });
  const RadianceSample res = composite(grid, T, rgb, depth);

  // Backward. With acc_i = sum_{j<=i} w_j c_j and C the composited colour:
  //   dC/dc_i = T_i alpha_i,   dC/dsigma_i = step * (T_{i+1} c_i - (C - acc_i)).
  Vec3 g = 2.0f * lossWeight * (res.rgb - target);
  Vec3 acc(0.0f);
  for (const MarchSample& s : samples) {
    float wt = s.transmittance * s.alpha;
    acc += wt * s.c;
    float tNext = s.transmittance * (1.0f - s.alpha);
    Vec3 rest = res.rgb - acc;
    float dSigma = r.step * glm::dot(g, tNext * s.c - rest);
    SampleGrad sg;
    sg.base = s.base;
    sg.fx = s.f.x;
    sg.fy = s.f.y;
    sg.fz = s.f.z;
    sg.gDensity = dSigma * s.dSigmaDRaw;
    for (int ch = 0; ch < 3; ++ch) sg.gColor[ch] = g[ch] * wt * s.c[ch] * (1.0f - s.c[ch]);
    out.push_back(sg);
  }
  return res;
}

}  // namespace

RadianceSample marchRay(const VoxelGrid& grid, const OccupancyGrid& occ, const GridRay& r,
                      float jitter, const MarchSettings& settings) {
  switch (grid.shDegree) {
    case 0: return marchRayT<0>(grid, occ, r, jitter, settings);
    case 1: return marchRayT<1>(grid, occ, r, jitter, settings);
    default: return marchRayT<2>(grid, occ, r, jitter, settings);
  }
}

RadianceSample marchRayGrad(const VoxelGrid& grid, const OccupancyGrid& occ, const GridRay& r,
                          float jitter, float minTransmittance, const Vec3& target,
                          float lossWeight, MarchScratch& scratch, std::vector<SampleGrad>& out) {
  switch (grid.shDegree) {
    case 0:
      return marchRayGradT<0>(grid, occ, r, jitter, minTransmittance, target, lossWeight, scratch, out);
    case 1:
      return marchRayGradT<1>(grid, occ, r, jitter, minTransmittance, target, lossWeight, scratch, out);
    default:
      return marchRayGradT<2>(grid, occ, r, jitter, minTransmittance, target, lossWeight, scratch, out);
  }
}

}  // namespace inim
