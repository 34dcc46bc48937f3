#include "display_view/estimators/quadrature_estimator.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>

#include "core/convex_polygon.h"
#include "core/error.h"
#include "display_view/estimators/lenslet_map.h"
#include "display_view/estimators/sample_tracer.h"
#include "display_view/view_renderer.h"

namespace inim {

namespace {

constexpr double kMaxBoxHalfWidthPx = 8.0;  // cap on a piece's box half-width (panel pixels)

// The bins of ChannelResponse's samplers: `count` equal-mass bins per primary, each with its
// middle and its exact camera-RGB integral (Simpson on steps of <= 0.25 nm), scaled so that the
// bins of a primary sum to its channelRgb exactly.
WavelengthNodes wavelengthNodes(const ChannelResponse& channels, int count) {
  WavelengthNodes nodes;
  for (int c = 0; c < kNumPrimaries; ++c) {
    const ChannelSampler& sampler = channels.sampler(c);
    Vec3d sum(0.0);
    for (int b = 0; b < count; ++b) {
      const double la = b == 0 ? double(kLambdaMin) : double(sampler.quantile(double(b) / count));
      const double lb = b + 1 == count ? double(kLambdaMax) : double(sampler.quantile(double(b + 1) / count));
      nodes.lambda[c].push_back(sampler.quantile((b + 0.5) / count));
      const int n = 2 * std::max(1, int(std::ceil((lb - la) / 0.5)));
      Vec3d integral(0.0);
      for (int i = 0; i <= n && lb > la; ++i) {
        const double l = la + (lb - la) * i / n;
        const double weight = (i == 0 || i == n) ? 1.0 : (i & 1) ? 4.0 : 2.0;
        integral += channels.sensor().response(l) * (weight * channels.panel().channelSpectrum(c, float(l)));
      }
      nodes.rgb[c].push_back(integral * ((lb - la) / (3.0 * n)));
      sum += nodes.rgb[c].back();
    }
    for (int i = 0; i < 3; ++i) {
      const double r = sum[i] != 0.0 ? channels.channelRgb(c)[i] / sum[i] : 0.0;
      for (auto& v : nodes.rgb[c]) v[i] *= r;
    }
  }
  return nodes;
}

// The lenslet cells a piece of a stratum touches (at most 24, each once).
struct CellList {
  std::array<LensletCell, 24> cells;
  int count = 0;
  void add(const LensletCell& c) {
    for (int i = 0; i < count; ++i)
      if (cells[size_t(i)].k == c.k && cells[size_t(i)].l == c.l) return;
    if (count < int(cells.size())) cells[size_t(count++)] = c;
  }
};

// A stratum's landing per unit slope (B), shared by its pieces (it hardly varies over a pixel
// or with the wavelength); `measured` once a measurement succeeded.
struct SlopeJacobian {
  bool measured = false;
  double B[2][2] = {};
};

// The block camera at one primary's geometry (its lateral colour for a dispersive camera).
struct StratumGeometry {
  const BlockCamera& camera;
  Vec2d crossing, slope;  // the block's centre ray at this geometry
  // Where pixel position p's centre ray is at `depth` below the front plane.
  Vec2d atDepth(const Vec2d& p, double depth) const {
    const Vec2d d = p - camera.pixelCentre;
    const auto& Jh = camera.dCrossing;
    const auto& Js = camera.dSlope;
    return crossing + depth * slope +
           Vec2d((Jh[0][0] + depth * Js[0][0]) * d.x + (Jh[0][1] + depth * Js[0][1]) * d.y,
                 (Jh[1][0] + depth * Js[1][0]) * d.x + (Jh[1][1] + depth * Js[1][1]) * d.y);
  }
};

}  // namespace

class QuadratureTile final : public TileEstimator {
 public:
  explicit QuadratureTile(const QuadratureEstimator& estimator)
      : estimator_(estimator),
        context_(estimator.context_),
        fallback_(context_, counts_),
        mla_(context_, stats_.probeRays),
        lensletMaps_(mla_, context_.referenceLambdaNm),
        companionRgb_(estimator.companions_.size()),
        companionCounts_(estimator.companions_.size()) {
    companionFallbacks_.reserve(estimator.companions_.size());
    for (size_t k = 0; k < estimator.companions_.size(); ++k)
      companionFallbacks_.emplace_back(*estimator.companions_[k], companionCounts_[k]);
  }
  Vec3d pixel(int x, int y) override;
  Vec3d companionPixel(int k) const override { return companionRgb_[size_t(k)]; }
  void addStats(ViewStats& stats) const override {
    stats.addRayCounts(counts_);
    stats.quadrature.pieces += stats_.pieces;
    stats.quadrature.splitStrata += stats_.splitStrata;
    stats.quadrature.lostPieces += stats_.lostPieces;
    stats.quadrature.fallbacks += stats_.fallbacks;
    stats.quadrature.probeRays += stats_.probeRays;
  }

 private:
  void integrateStratum(int x, int y, int index, const ApertureTable& table, const BlockCamera& camera, size_t block,
                        Vec3d& rgb);
  ConvexPolygon clipToDisplay(const ConvexPolygon& stratum, const StratumGeometry& geometry) const;
  int integrateAcrossLenslets(const ConvexPolygon& onDisplay, double areaOnDisplay, double stratumArea,
                              const ApertureTable& table, const StratumGeometry& geometry, size_t block, int slot,
                              SlopeJacobian& slopeJacobian, Vec3d& rgb);
  void integratePiece(const PolygonMoments& piece, double stratumArea, const ApertureTable& table,
                      const BlockCamera& camera, size_t block, int slot, SlopeJacobian& slopeJacobian, Vec3d& rgb);
  void integratePieceAt(const PolygonMoments& piece, double fraction, const ApertureTable& table,
                        const BlockCamera& camera, size_t block, int primary, int node, SlopeJacobian& slopeJacobian,
                        Vec3d& rgb);
  bool measurePixelMap(const PolygonMoments& piece, const BlockCamera& camera, const Vec2d& crossing,
                       const Vec2d& slope, float lambda, const Landing& landing, double M[2][2], Vec2d& shift) const;
  bool measureSlopeMap(const Vec2d& crossing, const Vec2d& slope, float lambda, const Landing& landing,
                       const ApertureTable& table, double B[2][2]) const;
  const float* tableOffsets(const double M[2][2], const double B[2][2], const BlockCamera& camera,
                           const ApertureTable& table);
  bool addEmission(const PolygonMoments& piece, const ApertureTable& table, const Landing& landing,
                   const float* offsets, const double M[2][2], const Vec2d& shift, double scale, int primary, int node,
                   Vec3d& rgb);
  // Where a piece's table points read the panel: their offsets about (cu, cv) and the box's half sizes.
  struct PanelBoxes {
    const float* offsets;
    double cu, cv, halfU, halfV;
  };
  bool addPanelEmission(const EstimatorContext& panelContext, const WavelengthNodes& nodes, const ApertureTable& table,
                        const Landing& landing, const PanelBoxes& boxes, double scale, int primary, int node,
                        Vec3d& rgb) const;

  const QuadratureEstimator& estimator_;
  const EstimatorContext& context_;
  RayCounts counts_;
  QuadratureStats stats_;
  SampleTracer fallback_;
  MlaLanding mla_;
  LensletMapCache lensletMaps_;
  std::vector<float> pieceOffsets_;  // the table's panel offsets for the current piece
  // The companion panels' sums for the current pixel, and their point-sample fallbacks.
  std::vector<Vec3d> companionRgb_;
  std::vector<RayCounts> companionCounts_;  // (the pass's counts are the context panel's)
  std::vector<SampleTracer> companionFallbacks_;
};

Vec3d QuadratureTile::pixel(int x, int y) {
  const int blockSize = estimator_.blockSize_;
  const size_t block = size_t(y / blockSize) * size_t(estimator_.blocksX_) + size_t(x / blockSize);
  estimator_.tables_->ensure(block);
  const ApertureTable& table = estimator_.tables_->table(block);
  const BlockCamera& camera = estimator_.tables_->camera(block);
  const bool ready = table.valid() && camera.ok;
  Vec3d rgb(0.0);
  std::fill(companionRgb_.begin(), companionRgb_.end(), Vec3d(0.0));
  fallback_.beginPixel(x, y);
  for (SampleTracer& f : companionFallbacks_) f.beginPixel(x, y);
  for (int i = 0; i < context_.settings.spp; ++i) {
    if (!ready) {
      ++stats_.fallbacks;
      fallback_.addSample(i, PanelRead{}, rgb);
      for (size_t k = 0; k < companionFallbacks_.size(); ++k)
        companionFallbacks_[k].addSample(i, PanelRead{}, companionRgb_[k]);
      continue;
    }
    integrateStratum(x, y, i, table, camera, block, rgb);
  }
  return rgb;
}

// Stratum `index` of pixel (x, y), per primary's geometry for a dispersive camera (its lateral
// colour images the lenslet borders and the display's edge a little elsewhere).
void QuadratureTile::integrateStratum(int x, int y, int index, const ApertureTable& table, const BlockCamera& camera,
                                      size_t block, Vec3d& rgb) {
  const int strataX = estimator_.strataX_, strataY = estimator_.strataY_;
  const double stratumArea = 1.0 / (double(strataX) * strataY);
  const int sx = index % strataX, sy = index / strataX;
  const ConvexPolygon stratum = ConvexPolygon::rect(x + double(sx) / strataX, y + double(sy) / strataY,
                                                    x + double(sx + 1) / strataX, y + double(sy + 1) / strataY);
  const double background = context_.settings.backgroundY;
  const bool cameraDispersive = context_.cameraDispersive;
  const int nodes = estimator_.nodesPerPrimary_;
  SlopeJacobian slopeJacobian;
  const int geometries = cameraDispersive ? kNumPrimaries : 1;
  for (int g = 0; g < geometries; ++g) {
    StratumGeometry geometry{camera, camera.crossing, camera.slope};
    if (cameraDispersive) {  // the primary's lateral colour at its (middle) node
      const size_t i = size_t(g * nodes + nodes / 2);
      if (i < camera.colourCrossing.size()) {
        geometry.crossing += camera.colourCrossing[i];
        geometry.slope += camera.colourSlope[i];
      }
    }
    const ConvexPolygon onDisplay = clipToDisplay(stratum, geometry);
    const double areaOn = onDisplay.empty() ? 0.0 : onDisplay.moments().area;
    if (background > 0.0 && areaOn < stratumArea * (1.0 - 1e-9)) {
      // The rest sees the background: its camera weight is the aperture integral at the
      // stratum (the table's, scaled by the centre ray's weight there).
      Vec2d crossing, slope;
      double weight;
      camera.at(stratum.centroid(), -1, crossing, slope, weight);
      if (weight > 0.0) {
        const double seen = (stratumArea - areaOn) / stratumArea * (table.total * weight / table.centreWeight) *
                            background / double(geometries);
        rgb += seen;
        for (Vec3d& c : companionRgb_) c += seen;
      }
    }
    if (!(areaOn > 1e-12 * stratumArea)) continue;
    const int pieces = integrateAcrossLenslets(onDisplay, areaOn, stratumArea, table, geometry, block,
                                               cameraDispersive ? g : -1, slopeJacobian, rgb);
    if (pieces > 1 && g == 0) ++stats_.splitStrata;
  }
}

// The part of a stratum whose centre rays cross the front plane inside the active area.
ConvexPolygon QuadratureTile::clipToDisplay(const ConvexPolygon& stratum, const StratumGeometry& geometry) const {
  const AreaMm& area = context_.area;
  const Vec2d normals[4] = {{-1.0, 0.0}, {1.0, 0.0}, {0.0, -1.0}, {0.0, 1.0}};
  const double offsets[4] = {-area.x0, area.x1, -area.y0, area.y1};
  ConvexPolygon on = stratum;
  for (int e = 0; e < 4; ++e) {
    Vec2d a;
    double c;
    pullBackHalfPlane(geometry.crossing, geometry.camera.dCrossing, geometry.camera.pixelCentre, normals[e], offsets[e],
                      a, c);
    on = on.clipped(a, c);
  }
  return on;
}

// Cuts the stratum's part on the display along the borders of the lenslet cells it touches
// (found on the MLA's border plane) and integrates each piece; returns the number of pieces.
int QuadratureTile::integrateAcrossLenslets(const ConvexPolygon& onDisplay, double areaOnDisplay,
                                            double stratumArea, const ApertureTable& table,
                                            const StratumGeometry& geometry, size_t block, int slot,
                                            SlopeJacobian& slopeJacobian, Vec3d& rgb) {
  const MlaModel& mla = context_.mla;
  const BlockCamera& camera = geometry.camera;
  CellList cells;
  LensletCell cell;
  const Vec2d centreOnPlane = geometry.atDepth(onDisplay.centroid(), mla.cellDepth());
  if (mla.lensletCell(centreOnPlane.x, centreOnPlane.y, cell)) cells.add(cell);
  for (int i = 0; i < onDisplay.n; ++i) {
    const Vec2d q = geometry.atDepth(onDisplay.v[size_t(i)], mla.cellDepth());
    if (mla.lensletCell(q.x, q.y, cell)) cells.add(cell);
  }
  if (cells.count == 0) {  // no lattice: one piece
    integratePiece(onDisplay.moments(), stratumArea, table, camera, block, slot, slopeJacobian, rgb);
    return 1;
  }
  double covered = 0.0;
  int pieces = 0;
  auto cutPieces = [&](int from, int to) {
    for (int i = from; i < to; ++i) {
      const LensletCell& c = cells.cells[size_t(i)];
      ConvexPolygon piece = onDisplay;
      for (int e = 0; e < c.n && !piece.empty(); ++e) {
        // The border where the ray passes from this cap to the next, at its depth where the
        // part is along the edge (the caps meet lower toward the corners).
        const double depth = mla.cellBorderDepth(c, e, centreOnPlane.x, centreOnPlane.y);
        double J[2][2];
        for (int a = 0; a < 2; ++a)
          for (int b = 0; b < 2; ++b) J[a][b] = camera.dCrossing[a][b] + depth * camera.dSlope[a][b];
        Vec2d a;
        double cc;
        const Vec2d normal(c.nx[size_t(e)], c.ny[size_t(e)]);
        pullBackHalfPlane(geometry.crossing + depth * geometry.slope, J, camera.pixelCentre, normal,
                          c.h[size_t(e)] + normal.x * c.cx + normal.y * c.cy, a, cc);
        piece = piece.clipped(a, cc);
      }
      if (piece.empty()) continue;
      const PolygonMoments moments = piece.moments();
      if (!(moments.area > 1e-12 * stratumArea)) continue;
      covered += moments.area;
      ++pieces;
      integratePiece(moments, stratumArea, table, camera, block, slot, slopeJacobian, rgb);
    }
  };
  cutPieces(0, cells.count);
  if (covered < areaOnDisplay * (1.0 - 1e-6)) {
    // A cell touched without holding a vertex of the part (a hexagon's corner poking in): try
    // the neighbours of the cells found.
    const int found = cells.count;
    for (int i = 0; i < found; ++i) {
      const LensletCell c0 = cells.cells[size_t(i)];
      const double P = c0.pitch;
      const double neighbours[12][2] = {{P, 0}, {-P, 0}, {0, P}, {0, -P}, {P, P}, {P, -P}, {-P, P}, {-P, -P},
                                        {0.5 * P, 0.866 * P}, {-0.5 * P, 0.866 * P}, {0.5 * P, -0.866 * P},
                                        {-0.5 * P, -0.866 * P}};
      for (const auto& o : neighbours)
        if (mla.lensletCell(c0.cx + o[0], c0.cy + o[1], cell)) cells.add(cell);
    }
    cutPieces(found, cells.count);
  }
  return pieces;
}

// Adds a piece (pixel coordinates) of a stratum to rgb, per primary (slot -1: all, when
// nothing is dispersive) and wavelength node.
void QuadratureTile::integratePiece(const PolygonMoments& piece, double stratumArea, const ApertureTable& table,
                                    const BlockCamera& camera, size_t block, int slot, SlopeJacobian& slopeJacobian,
                                    Vec3d& rgb) {
  if (!(piece.area > 0.0)) return;
  ++stats_.pieces;
  const double fraction = piece.area / stratumArea;
  const bool dispersive = context_.channels.dispersive();
  const int slots = dispersive ? kNumPrimaries : 1, nodes = dispersive ? estimator_.nodesPerPrimary_ : 1;
  for (int primary = slot < 0 ? 0 : slot; primary < (slot < 0 ? slots : slot + 1); ++primary)
    for (int node = 0; node < nodes; ++node)
      integratePieceAt(piece, fraction, table, camera, block, primary, node, slopeJacobian, rgb);
}

// The lenslet's landing per pixel (M) over the piece: the secant over +-sqrt(3 var) of the
// piece along each axis, and from its curvature the shift of the mean landing from the
// centroid's, (L+ + L- - 2 L0) / 6 (exact for a quadratic map). False when neither probe of
// an axis stays in the landing's lenslet.
bool QuadratureTile::measurePixelMap(const PolygonMoments& piece, const BlockCamera& camera, const Vec2d& crossing,
                                     const Vec2d& slope, float lambda, const Landing& landing, double M[2][2],
                                     Vec2d& shift) const {
  for (int axis = 0; axis < 2; ++axis) {
    const double half = std::sqrt(3.0 * (axis == 0 ? piece.cxx : piece.cyy));
    if (!(half > 1e-6)) continue;
    Landing plus, minus;
    const Vec2d dh(camera.dCrossing[0][axis] * half, camera.dCrossing[1][axis] * half);
    const Vec2d ds(camera.dSlope[0][axis] * half, camera.dSlope[1][axis] * half);
    const bool inP = mla_.land(crossing + dh, slope + ds, lambda, plus) && plus.sameLenslet(landing);
    const bool inM = mla_.land(crossing - dh, slope - ds, lambda, minus) && minus.sameLenslet(landing);
    if (!inP && !inM) return false;
    const Vec2d up = inP ? plus.uv : landing.uv, um = inM ? minus.uv : landing.uv;
    const double span = (inP ? half : 0.0) + (inM ? half : 0.0);
    M[0][axis] = (up.x - um.x) / span;
    M[1][axis] = (up.y - um.y) / span;
    if (inP && inM) shift += (plus.uv + minus.uv - 2.0 * landing.uv) / 6.0;
  }
  return true;
}

// The landing per unit slope (B), one-sided over the aperture's rms slope; false when neither
// side stays in the landing's lenslet (B is then partly written; the caller retries).
bool QuadratureTile::measureSlopeMap(const Vec2d& crossing, const Vec2d& slope, float lambda, const Landing& landing,
                                     const ApertureTable& table, double B[2][2]) const {
  const double step = std::max(table.rmsS, 1e-5);
  for (int axis = 0; axis < 2; ++axis) {
    const Vec2d dv = axis == 0 ? Vec2d(step, 0.0) : Vec2d(0.0, step);
    Landing probe;
    if (mla_.land(crossing, slope + dv, lambda, probe) && probe.sameLenslet(landing)) {
      B[0][axis] = (probe.uv.x - landing.uv.x) / step;
      B[1][axis] = (probe.uv.y - landing.uv.y) / step;
    } else if (mla_.land(crossing, slope - dv, lambda, probe) && probe.sameLenslet(landing)) {
      B[0][axis] = (landing.uv.x - probe.uv.x) / step;
      B[1][axis] = (landing.uv.y - probe.uv.y) / step;
    } else {
      return false;
    }
  }
  return true;
}

// The table's points as panel offsets through the piece's map: A = (M - B Js) Jh^-1 per mm of
// crossing, B per unit slope, offset = A dh + B ds (into pieceOffsets_).
const float* QuadratureTile::tableOffsets(const double M[2][2], const double B[2][2], const BlockCamera& camera,
                                          const ApertureTable& table) {
  const auto& Jh = camera.dCrossing;
  const auto& Js = camera.dSlope;
  const double det = Jh[0][0] * Jh[1][1] - Jh[0][1] * Jh[1][0];
  const double inverseJh[2][2] = {{Jh[1][1] / det, -Jh[0][1] / det}, {-Jh[1][0] / det, Jh[0][0] / det}};
  double R[2][2], A[2][2];
  for (int a = 0; a < 2; ++a)
    for (int b = 0; b < 2; ++b) R[a][b] = M[a][b] - (B[a][0] * Js[0][b] + B[a][1] * Js[1][b]);
  for (int a = 0; a < 2; ++a)
    for (int b = 0; b < 2; ++b) A[a][b] = R[a][0] * inverseJh[0][b] + R[a][1] * inverseJh[1][b];
  pieceOffsets_.resize(2 * table.points.size());
  for (size_t i = 0; i < table.points.size(); ++i) {
    const auto& q = table.points[i];
    pieceOffsets_[2 * i] = float(A[0][0] * q.dhx + A[0][1] * q.dhy + B[0][0] * q.dsx + B[0][1] * q.dsy);
    pieceOffsets_[2 * i + 1] = float(A[1][0] * q.dhx + A[1][1] * q.dhy + B[1][0] * q.dsx + B[1][1] * q.dsy);
  }
  return pieceOffsets_.data();
}

// One primary and wavelength node of a piece: its centroid's centre ray landed through the MLA,
// the lenslet's map about it turns the table's points into panel offsets (tableOffsets), and
// each reads its channel's box average.
void QuadratureTile::integratePieceAt(const PolygonMoments& piece, double fraction, const ApertureTable& table,
                                      const BlockCamera& camera, size_t block, int primary, int node,
                                      SlopeJacobian& slopeJacobian, Vec3d& rgb) {
  const bool dispersive = context_.channels.dispersive();
  const int nodes = dispersive ? estimator_.nodesPerPrimary_ : 1;
  const float lambda = dispersive ? estimator_.nodes_.lambda[primary][size_t(node)] : context_.referenceLambdaNm;
  Vec2d crossing, slope;
  double weight;
  camera.at(piece.centroid, context_.cameraDispersive ? primary * nodes + node : -1, crossing, slope, weight);
  ++counts_.traced;
  Landing landing;
  if (!(weight > 0.0) || !mla_.land(crossing, slope, lambda, landing)) {
    ++stats_.lostPieces;
    return;
  }
  ++counts_.onDisplay;
  ++counts_.onPanel;
  const auto& Jh = camera.dCrossing;
  const auto& Js = camera.dSlope;
  const double det = Jh[0][0] * Jh[1][1] - Jh[0][1] * Jh[1][0];
  double M[2][2] = {{0.0, 0.0}, {0.0, 0.0}};
  Vec2d shift(0.0);
  bool ok = std::abs(det) > 0.0 && measurePixelMap(piece, camera, crossing, slope, lambda, landing, M, shift);
  double(&B)[2][2] = slopeJacobian.B;
  if (ok && !slopeJacobian.measured)
    ok = slopeJacobian.measured = measureSlopeMap(crossing, slope, lambda, landing, table, B);
  const float* offsets = nullptr;
  if (ok && slopeJacobian.measured) {
    offsets = tableOffsets(M, B, camera, table);
  } else if (const LensletMap* map = lensletMaps_.find(block, table, crossing, slope, landing)) {
    // Probes across a lenslet border: the lenslet's cached map, no curvature shift.
    offsets = map->offsets.data();
    shift = Vec2d(0.0);
    for (int a = 0; a < 2; ++a)
      for (int b = 0; b < 2; ++b)
        M[a][b] = map->A[a][0] * Jh[0][b] + map->A[a][1] * Jh[1][b] + map->B[a][0] * Js[0][b] + map->B[a][1] * Js[1][b];
  } else {
    ++stats_.fallbacks;  // no map: the whole aperture at the landing point
  }
  const double scale = fraction * weight / table.centreWeight * landing.throughput * landing.factor;
  if (addEmission(piece, table, landing, offsets, M, shift, scale, dispersive ? primary : -1, node, rgb))
    ++counts_.emitting;
}

// Adds scale x (the table's weights x each point's box average of its channel) to rgb, per
// channel (`primary` only when dispersive, else all three), and the same of each companion
// panel to its sum; the box has the variance of the piece's image on the panel (its covariance
// through M). Without offsets, the whole table's weight reads the drive at the landing point.
// True when the context's panel emitted anything.
bool QuadratureTile::addEmission(const PolygonMoments& piece, const ApertureTable& table, const Landing& landing,
                                 const float* offsets, const double M[2][2], const Vec2d& shift, double scale,
                                 int primary, int node, Vec3d& rgb) {
  double halfU = 0.0, halfV = 0.0;
  if (offsets) {
    const double varU =
        M[0][0] * M[0][0] * piece.cxx + 2.0 * M[0][0] * M[0][1] * piece.cxy + M[0][1] * M[0][1] * piece.cyy;
    const double varV =
        M[1][0] * M[1][0] * piece.cxx + 2.0 * M[1][0] * M[1][1] * piece.cxy + M[1][1] * M[1][1] * piece.cyy;
    halfU = std::min(std::sqrt(3.0 * std::max(0.0, varU)), kMaxBoxHalfWidthPx);
    halfV = std::min(std::sqrt(3.0 * std::max(0.0, varV)), kMaxBoxHalfWidthPx);
  }
  const PanelBoxes boxes{offsets, landing.uv.x + shift.x, landing.uv.y + shift.y, halfU, halfV};
  for (size_t k = 0; k < companionRgb_.size(); ++k)
    addPanelEmission(*estimator_.companions_[k], estimator_.companionNodes_[k], table, landing, boxes, scale, primary,
                     node, companionRgb_[k]);
  return addPanelEmission(context_, estimator_.nodes_, table, landing, boxes, scale, primary, node, rgb);
}

// One panel's part of addEmission (its subpixels, drive, channel RGB and wavelength nodes).
bool QuadratureTile::addPanelEmission(const EstimatorContext& panelContext, const WavelengthNodes& nodes,
                                      const ApertureTable& table, const Landing& landing, const PanelBoxes& boxes,
                                      double scale, int primary, int node, Vec3d& rgb) const {
  const PanelEmitter& panel = panelContext.panel;
  const size_t n = table.points.size();
  const double cu = boxes.cu, cv = boxes.cv, halfU = boxes.halfU, halfV = boxes.halfV;
  const float* offsets = boxes.offsets;
  double e[kNumPrimaries] = {0.0, 0.0, 0.0};
  if (!offsets) {
    for (int c = 0; c < kNumPrimaries; ++c)
      if (primary < 0 || c == primary) e[c] = table.total * panel.channelDrivePx(c, landing.uv.x, landing.uv.y);
  } else if (primary >= 0) {
    for (size_t i = 0; i < n; ++i) {
      const double u = cu + offsets[2 * i], v = cv + offsets[2 * i + 1];
      e[primary] +=
          double(table.points[i].w) * panel.channelBoxAveragePx(primary, u - halfU, v - halfV, u + halfU, v + halfV);
    }
  } else {
    // All three channels over the same boxes: one lookup finds their tiles once.
    for (size_t i = 0; i < n; ++i) {
      const double u = cu + offsets[2 * i], v = cv + offsets[2 * i + 1];
      const std::array<float, kNumPrimaries> a = panel.channelBoxAveragesPx(u - halfU, v - halfV, u + halfU, v + halfV);
      for (int c = 0; c < kNumPrimaries; ++c) e[c] += double(table.points[i].w) * a[size_t(c)];
    }
  }
  bool emitted = false;
  for (int c = 0; c < kNumPrimaries; ++c) {
    if (e[c] == 0.0) continue;
    emitted = true;
    rgb += (scale * e[c]) * (primary >= 0 ? nodes.rgb[c][size_t(node)] : panelContext.channels.channelRgb(c));
  }
  return emitted;
}

QuadratureEstimator::QuadratureEstimator(const EstimatorContext& context,
                                         std::vector<const EstimatorContext*> companions)
    : context_(context), companions_(std::move(companions)) {
  const ViewSettings& s = context.settings;
  if (!context.channels.primaries())
    throw InputError("", "spectral", spectralSamplingName(s.spectral),
                     "primaries (the quadrature estimator integrates each primary's spectrum by quadrature)");
  nodesPerPrimary_ = s.wavelengthNodes;
  if (nodesPerPrimary_ < 1 || nodesPerPrimary_ > 64)
    throw InputError("", "wavelength_nodes", std::to_string(nodesPerPrimary_), "a whole number in 1..64");
  if (s.apertureGrid < 2 || s.apertureGrid > 64)
    throw InputError("", "aperture_grid", std::to_string(s.apertureGrid), "a grid size in 2..64");
  for (int d = 1; d * d <= s.spp; ++d)
    if (s.spp % d == 0) strataX_ = d;
  strataY_ = s.spp / strataX_;
  if (context.channels.dispersive()) nodes_ = wavelengthNodes(context.channels, nodesPerPrimary_);
  for (const EstimatorContext* c : companions_) {
    if (!canCarry(context, *c)) throw std::logic_error("QuadratureEstimator: a companion panel it cannot carry");
    companionNodes_.push_back(c->channels.dispersive() ? wavelengthNodes(c->channels, nodesPerPrimary_)
                                                       : WavelengthNodes{});
  }
  // A dispersive camera: the block cameras' lateral colour at every node (primary-major).
  QuadratureTableKey key;
  if (context.cameraDispersive)
    for (int c = 0; c < kNumPrimaries; ++c)
      key.colourLambdas.insert(key.colourLambdas.end(), nodes_.lambda[c].begin(), nodes_.lambda[c].end());

  // One table per block of ~0.1 mm of the sensor (the pupil's shape, vignetting, changes
  // little over that), at most 32 pixels; built at the block's centre pixel.
  const CameraModel& camera = context.camera;
  const int W = camera.width(), H = camera.height();
  blockSize_ = s.apertureBlock > 0
                   ? s.apertureBlock
                   : std::clamp(int(std::lround(0.1 / std::max(1e-9, camera.sensor().pitchMm))), 1, 32);
  blocksX_ = (W + blockSize_ - 1) / blockSize_;
  const int blocksY = (H + blockSize_ - 1) / blockSize_;
  key.grid = s.apertureGrid;
  key.blockSize = blockSize_;
  key.blocksX = blocksX_;
  key.blocksY = blocksY;
  key.lambdaNm = context.referenceLambdaNm;
  key.frontZ = context.frontZ;
  tables_ = s.tableCache ? s.tableCache->tables(camera, key) : std::make_shared<const QuadratureTables>(camera, key);
  raysBefore_ = tables_->rays();
}

bool QuadratureEstimator::canCarry(const EstimatorContext& context, const EstimatorContext& companion) {
  if (!context.panel.emitsLike(companion.panel) || context.channels.dispersive() != companion.channels.dispersive())
    return false;
  if (!context.channels.dispersive()) return true;
  const int count = context.settings.wavelengthNodes;
  if (count < 1 || count > 64) return false;
  const WavelengthNodes a = wavelengthNodes(context.channels, count), b = wavelengthNodes(companion.channels, count);
  for (int c = 0; c < kNumPrimaries; ++c)
    if (a.lambda[c] != b.lambda[c]) return false;
  return true;
}

std::unique_ptr<TileEstimator> QuadratureEstimator::beginTile() const {
  return std::make_unique<QuadratureTile>(*this);
}

// The tables' rays traced during this render (shared tables: those it built).
void QuadratureEstimator::addStats(ViewStats& stats) const {
  stats.quadrature.probeRays += tables_->rays() - raysBefore_;
}

}  // namespace inim
