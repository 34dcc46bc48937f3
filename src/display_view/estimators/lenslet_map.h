#pragma once
// The MLA as the Quadrature estimator sees it: deterministic landings (Fresnel as a
// transmittance, no random reflection) and, per lenslet, the affine map of a ray's landing
// point on the panel about a reference ray.
#include <cstdint>
#include <vector>

#include "core/geometry.h"
#include "display_view/estimators/aperture_table.h"
#include "display_view/estimators/panel_estimator.h"

namespace inim {

// Where a ray lands on the emitter (panel pixels) and through which lenslet.
struct Landing {
  Vec2d uv{0.0};
  float throughput = 0.0f;  // the MLA's Fresnel transmittance (and absorption)
  float factor = 0.0f;      // the emitter's angular and cover-glass factor there
  int k = -1, l = -1;
  bool sameLenslet(const Landing& other) const { return k == other.k && l == other.l; }
};

// The MLA alone, traced with its Fresnel handling made deterministic (Stochastic becomes
// Weighted: the transmitted path, weighted by T; the ghosts of >= 2 reflections are dropped).
class MlaLanding {
 public:
  // `rays` counts every ray traced.
  MlaLanding(const EstimatorContext& context, uint64_t& rays);
  // The ray crossing the front plane at `crossing` with slope (d.x, d.y) / -d.z = `slope`;
  // false when it misses the active area, the MLA loses it or it lands off the emitter.
  bool land(const Vec2d& crossing, const Vec2d& slope, float lambdaNm, Landing& out) const;

 private:
  const EstimatorContext& context_;
  FresnelMode mode_;
  uint64_t& rays_;
};

// A lenslet's Jacobians of the landing point (panel pixels) with respect to a ray's front-plane
// crossing (A, per mm) and slope (B), and an aperture table's points mapped to panel offsets
// A dh + B ds (2 per point).
struct LensletMap {
  int k = -1, l = -1;
  bool ok = false;
  double A[2][2] = {}, B[2][2] = {};
  std::vector<float> offsets;
};

// One tile's lenslet maps, one per (table block, lenslet), measured at the reference
// wavelength at the first ray that lands through that lenslet (one thread renders a tile in a
// fixed order, so the cache is deterministic); a failed measurement (probes straddling a
// lenslet border) is retried at the next ray through that lenslet.
class LensletMapCache {
 public:
  LensletMapCache(const MlaLanding& mla, float referenceLambdaNm) : mla_(mla), lambdaNm_(referenceLambdaNm) {}
  // The map of (block, the lenslet of `landing`), measured on first need about the ray that
  // crosses the front plane at `crossing` with `slope`; nullptr while it cannot be measured.
  const LensletMap* find(size_t block, const ApertureTable& table, const Vec2d& crossing, const Vec2d& slope,
                         const Landing& landing);

 private:
  bool measure(const Vec2d& crossing, const Vec2d& slope, const ApertureTable& table, LensletMap& out) const;
  struct Entry {
    size_t block;
    int k, l;
    LensletMap map;
  };
  const MlaLanding& mla_;
  float lambdaNm_;
  std::vector<Entry> entries_;
};

}  // namespace inim
