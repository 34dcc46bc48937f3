#pragma once
// The panel estimators behind one interface, as pbrt-v4's ImageTileIntegrator: the renderer
// (view_renderer.cpp) keeps the tile loop, tile culling and the image; an estimator says what
// one pixel sees (linear camera RGB, summed over its spp samples or strata).
//
//   PointEstimator      (point_estimator.h):      the subpixel under each sampled ray; the reference.
//   FootprintEstimator  (footprint_estimator.h):  a box average around each sampled ray's landing.
//   QuadratureEstimator (quadrature_estimator.h): no sampling: area, aperture and spectra by quadrature.
//
// Per-tile state (caches filled in the tile's fixed pixel order, and statistics) lives in a
// TileEstimator that one thread owns for one tile, so images are bit-identical for any thread
// count. docs/view-estimators.md derives each estimator and records measurements.
#include <memory>
#include <vector>

#include "camera/camera_model.h"
#include "camera/sensor.h"
#include "core/geometry.h"
#include "display/ei_layout.h"
#include "mla_optics/mla_model.h"
#include "display_view/estimators/channel_response.h"
#include "display_view/panel_emitter.h"
#include "display_view/view_settings.h"

namespace inim {

struct ViewStats;

// Everything an estimator reads, built once per renderView call (display frame, mm).
struct EstimatorContext {
  EstimatorContext(const CameraModel& camera, const CameraSensor& sensor, const MlaModel& mla,
                   const PanelEmitter& panel, const AreaMm& area, const ViewSettings& settings);
  const CameraModel& camera;
  const MlaModel& mla;
  const PanelEmitter& panel;
  AreaMm area;                   // the display's active area on the MLA's front plane
  const ViewSettings& settings;
  float frontZ;                  // camera rays are cut to start here, in air just above the MLA
  float referenceLambdaNm;       // the wavelength of rays that carry every wavelength
  bool cameraDispersive;
  ChannelResponse channels;      // emission -> camera RGB; how many rays a sample traces
};

// The rays an estimator traced (every estimator counts them; ViewStats holds the image's sums).
struct RayCounts {
  uint64_t traced = 0;     // camera rays (weight > 0; one per slot when dispersive)
  uint64_t onDisplay = 0;  // ... that reached the MLA inside the active area
  uint64_t onPanel = 0;    // ... that reached the panel (the MLA did not lose them)
  uint64_t emitting = 0;   // ... that read a non-zero emission
};

// One tile's estimator state; one thread calls pixel() in the tile's row-major order.
class TileEstimator {
 public:
  virtual ~TileEstimator() = default;
  // Linear camera RGB of pixel (x, y) summed over its spp samples (the renderer divides).
  virtual Vec3d pixel(int x, int y) = 0;
  // The same sum for companion panel k (PixelEstimator::companions) at the pixel last asked for.
  virtual Vec3d companionPixel(int /*k*/) const { return Vec3d(0.0); }
  // Adds the tile's statistics (ray counts and the estimator's own) to `stats`.
  virtual void addStats(ViewStats& stats) const = 0;
};

class PixelEstimator {
 public:
  virtual ~PixelEstimator() = default;
  virtual PanelEstimator kind() const = 0;
  virtual std::unique_ptr<TileEstimator> beginTile() const = 0;
  // How many companion panels each tile also renders (renderViews; Quadrature only).
  virtual int companions() const { return 0; }
  // Adds the statistics of the work done once per image (tables) to `stats`.
  virtual void addStats(ViewStats& /*stats*/) const {}
};

// The panel estimators, in one table in the order of PanelEstimator: adding one is its file, an
// enum value and a line in the table (docs/view-estimators.md documents each by name).
struct PanelEstimatorInfo {
  PanelEstimator kind;
  const char* name;     // as --estimator takes it
  const char* summary;  // one line
  std::unique_ptr<PixelEstimator> (*make)(const EstimatorContext& context);
};
const std::vector<PanelEstimatorInfo>& panelEstimators();

// The estimator `kind` for `context` (which must outlive it). InputError for settings the
// estimator cannot use (named by their ViewSettings key in snake_case).
std::unique_ptr<PixelEstimator> makePanelEstimator(PanelEstimator kind, const EstimatorContext& context);

}  // namespace inim
