#include "display_view/estimators/footprint_estimator.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "core/error.h"
#include "core/format.h"
#include "display_view/estimators/sample_tracer.h"
#include "display_view/view_renderer.h"

namespace inim {

namespace {

constexpr uint64_t kProbeSalt = 0x9B0BE5A17ull;  // salts the Jacobian probes' MLA stream
// Finite-difference steps of the probes (pixel units, and fractions of the lens sample square),
// and the cap on the box half-width (panel pixels).
constexpr float kProbePixelStep = 0.25f;
constexpr float kProbeLensStep = 0.05f;
constexpr double kMaxBoxHalfWidthPx = 8.0;

class FootprintTile final : public TileEstimator {
 public:
  FootprintTile(const EstimatorContext& context, double boxScale)
      : context_(context), boxScale_(boxScale), tracer_(context, counts_) {}
  Vec3d pixel(int x, int y) override;
  void addStats(ViewStats& stats) const override {
    stats.addRayCounts(counts_);
    stats.footprint.probeRays += footprint_.probeRays;
    stats.footprint.probeFailures += footprint_.probeFailures;
  }

 private:
  bool probe(const float coords[4], const Rng& rng0, Vec2d& uv, int& k, int& l);
  bool jacobian(int x, int y, double J[2][4]);
  PanelRead box(int x, int y);

  const EstimatorContext& context_;
  double boxScale_;
  RayCounts counts_;
  FootprintStats footprint_;
  SampleTracer tracer_;
  bool haveLastJacobian_ = false;  // the tile's last measured Jacobian, for pixels whose probe fails
  double lastJacobian_[2][4] = {};
};

// Where the ray of sample coordinates (pixel x, y, lens u, v) lands on the emitter (panel
// pixels) at the reference wavelength, and through which lenslet. Every probe of a pixel
// replays the same MLA random stream, so Fresnel choices agree between them.
bool FootprintTile::probe(const float coords[4], const Rng& rng0, Vec2d& uv, int& k, int& l) {
  ++footprint_.probeRays;
  const float lambdaRef = context_.referenceLambdaNm, frontZ = context_.frontZ;
  Ray r;
  if (!(context_.camera.generateRay(Vec2(coords[0], coords[1]), Vec2(coords[2], coords[3]), lambdaRef, r) > 0.0f))
    return false;
  if (!(r.d.z < 0.0f) || !(r.o.z > frontZ)) return false;
  const Point3 p = r.o + ((frontZ - r.o.z) / r.d.z) * r.d;
  if (!context_.area.contains(p.x, p.y)) return false;
  Rng rng = rng0;
  PanelArrival arrival;
  if (!context_.mla.traceToPanel(Ray{p, r.d, 0.0f, kInfinity}, lambdaRef, rng, arrival)) return false;
  float factor;
  if (!context_.panel.emissionPointPx(arrival.p, arrival.d, lambdaRef, uv, factor)) return false;
  k = arrival.lensletK;
  l = arrival.lensletL;
  return true;
}

// The 2 x 4 Jacobian of the landing point with respect to the sample coordinates, by one-sided
// differences from the pixel centre and the lens centre, each step taken toward the side that
// stays in the base ray's lenslet. False when the base ray does not reach the panel.
bool FootprintTile::jacobian(int x, int y, double J[2][4]) {
  const uint64_t pixelIndex = uint64_t(y) * uint64_t(context_.camera.width()) + uint64_t(x);
  const Rng rng0 = Rng::forSample(context_.settings.seed ^ kProbeSalt, pixelIndex, 0);
  const float base[4] = {float(x) + 0.5f, float(y) + 0.5f, 0.5f, 0.5f};
  Vec2d uv0;
  int k0, l0;
  if (!probe(base, rng0, uv0, k0, l0)) return false;
  for (int j = 0; j < 4; ++j) {
    bool ok = false;
    // +step, -step, then 1/16 of the step each way (pixels much larger than a lenslet).
    for (int attempt = 0; attempt < 4 && !ok; ++attempt) {
      const float sign = (attempt & 1) ? -1.0f : 1.0f;
      const float step = (j < 2 ? kProbePixelStep : kProbeLensStep) * (attempt < 2 ? 1.0f : 0.0625f);
      float q[4] = {base[0], base[1], base[2], base[3]};
      q[j] += sign * step;
      Vec2d uv;
      int k, l;
      if (!probe(q, rng0, uv, k, l) || k != k0 || l != l0) continue;
      J[0][j] = (uv.x - uv0.x) / double(sign * step);
      J[1][j] = (uv.y - uv0.y) / double(sign * step);
      ok = true;
    }
    if (!ok) {
      J[0][j] = J[1][j] = 0.0;
      ++footprint_.probeFailures;
    }
  }
  return true;
}

// The pixel's box: half-widths from the row norms of its Jacobian (the header's formula).
PanelRead FootprintTile::box(int x, int y) {
  double J[2][4];
  if (jacobian(x, y, J)) {
    std::memcpy(lastJacobian_, J, sizeof J);
    haveLastJacobian_ = true;
  }
  PanelRead read;
  read.box = true;
  if (!haveLastJacobian_) return read;
  double sumU = 0.0, sumV = 0.0;
  for (int j = 0; j < 4; ++j) {
    sumU += lastJacobian_[0][j] * lastJacobian_[0][j];
    sumV += lastJacobian_[1][j] * lastJacobian_[1][j];
  }
  read.halfU = std::min(boxScale_ * std::sqrt(sumU), kMaxBoxHalfWidthPx);
  read.halfV = std::min(boxScale_ * std::sqrt(sumV), kMaxBoxHalfWidthPx);
  if (!std::isfinite(read.halfU) || !std::isfinite(read.halfV)) read.halfU = read.halfV = 0.0;
  return read;
}

Vec3d FootprintTile::pixel(int x, int y) {
  const PanelRead read = box(x, y);
  Vec3d rgb(0.0);
  tracer_.beginPixel(x, y);
  for (int i = 0; i < context_.settings.spp; ++i) tracer_.addSample(i, read, rgb);
  return rgb;
}

}  // namespace

FootprintEstimator::FootprintEstimator(const EstimatorContext& context) : context_(context) {
  const double scale = context.settings.footprintScale;
  if (!(scale >= 0.0 && std::isfinite(scale)))
    throw InputError("", "footprint_scale", formatNumber(scale), "a finite scale >= 0");
  boxScale_ = 0.5 * scale / std::sqrt(double(context.settings.spp));
}

std::unique_ptr<TileEstimator> FootprintEstimator::beginTile() const {
  return std::make_unique<FootprintTile>(context_, boxScale_);
}

}  // namespace inim
