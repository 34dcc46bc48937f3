#pragma once
// Quadrature: no sampling at all. A pixel's value is an integral over its area, the camera's
// aperture and each primary's spectrum, and each is done by a deterministic rule, so there is
// no noise, only a quadrature error that falls with spp:
//   - area: the pixel is cut into spp strata (nx x ny, nx ny = spp); each stratum is cut along
//     the display's edge and the lenslet borders (MlaModel::lensletCell at cellBorderDepth),
//     mapped back to the sensor through the block's affine camera (block_camera.h; per primary
//     for a dispersive camera, whose lateral colour moves the borders);
//   - each piece (one per lenslet it sees) is integrated through its own lenslet: its centroid's
//     centre ray is traced through the MLA at each primary's wavelength node with Fresnel as a
//     transmittance (lenslet_map.h), and the lenslet's map about that ray is measured by
//     MLA-only probes at the same wavelength (secant over the piece, curvature for the shift of
//     its mean); pieces whose probes cross a lenslet border use the tile's cached lenslet map;
//   - aperture: the block's aperture table (aperture_table.h), its points mapped to panel
//     offsets through the piece's Jacobians; each reads the exact average of its channel's
//     subpixels (PanelEmitter::channelBoxAveragePx; all three at once, channelBoxAveragesPx,
//     when nothing is dispersive) over a box with the variance of the piece's image, so an
//     affine map integrates the pixel's area exactly;
//   - spectrum: wavelengthNodes nodes per primary (1: the median of its spectrum, weighted by
//     the whole spectrum's camera RGB), not tied to strata (that would tie colour to position).
// Bias: the dropped Fresnel ghosts (paths with >= 2 reflections inside the MLA), the aperture
// table's grid, the box for a sheared image, the tables and camera taken per block (their sizes:
// docs/view-estimators.md).
// Cost per piece and primary: 1 + 4 MLA rays (landing, pixel Jacobian) plus 2 per stratum
// (slope Jacobian), no camera-lens rays, and one box average per table point (~0.8 G^2); per
// block of pixels one table (~G^2 camera rays). Falls back to PointSample for the pixels of a
// block whose table or camera cannot be built. Needs SpectralSampling::Primaries.
// Companions: panels that emit like the context's (PanelEmitter::emitsLike; another subpixel
// layout or drive) and share its wavelength nodes are integrated in the same pass, each piece's
// geometry (landing, maps, table offsets) traced once and read on every panel; each companion's
// image is bit for bit its own render's (renderViews).
#include <cstdint>
#include <memory>
#include <vector>

#include "display_view/estimators/aperture_table.h"
#include "display_view/estimators/block_camera.h"
#include "display_view/estimators/panel_estimator.h"
#include "display_view/estimators/quadrature_tables.h"

namespace inim {

struct QuadratureStats {
  uint64_t pieces = 0;       // pieces of pixel strata integrated (one per lenslet seen)
  uint64_t splitStrata = 0;  // strata cut into >= 2 pieces by a lenslet border
  uint64_t lostPieces = 0;   // piece x primary whose centre ray the MLA lost (counted 0)
  uint64_t fallbacks = 0;    // strata sampled by the point estimator, and pieces integrated
                             // without a lenslet map (the whole aperture at the landing point)
  uint64_t probeRays = 0;    // rays traced for the aperture tables, block cameras and MLA maps
};

// Per primary: the wavelength nodes (the middles of equal-mass bins of its spectrum) and each
// bin's exact camera-RGB integral (the bins' integrals sum to ChannelResponse::channelRgb).
struct WavelengthNodes {
  std::vector<float> lambda[kNumPrimaries];
  std::vector<Vec3d> rgb[kNumPrimaries];
};

class QuadratureEstimator final : public PixelEstimator {
 public:
  // Sizes the aperture tables and block cameras (each built on first use). InputError for visible spectral sampling
  // (key spectral), wavelength_nodes outside 1..64 or aperture_grid outside 2..64.
  // `companions` (contexts of the same camera, MLA, area and settings; they must outlive it): each
  // must be canCarry(context, companion).
  explicit QuadratureEstimator(const EstimatorContext& context,
                               std::vector<const EstimatorContext*> companions = {});
  PanelEstimator kind() const override { return PanelEstimator::Quadrature; }
  std::unique_ptr<TileEstimator> beginTile() const override;
  int companions() const override { return int(companions_.size()); }
  void addStats(ViewStats& stats) const override;
  // True when `companion`'s panel can be rendered in `context`'s pass: it emits like it, both
  // are dispersive or neither, and their wavelength nodes are the same.
  static bool canCarry(const EstimatorContext& context, const EstimatorContext& companion);

 private:
  friend class QuadratureTile;
  const EstimatorContext& context_;
  int strataX_ = 1, strataY_ = 1;
  int nodesPerPrimary_ = 1;
  WavelengthNodes nodes_;          // dispersive only
  std::vector<const EstimatorContext*> companions_;
  std::vector<WavelengthNodes> companionNodes_;  // dispersive only
  int blockSize_ = 1, blocksX_ = 1;  // pixels per table block, blocks per row
  // Built when a pixel of the block is first rendered (the tiles that cannot see the display
  // need none); shared with other renders through ViewSettings::tableCache.
  std::shared_ptr<const QuadratureTables> tables_;
  uint64_t raysBefore_ = 0;  // the shared tables' rays before this render
};

}  // namespace inim
