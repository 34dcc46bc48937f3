#pragma once
// What a camera sees when the display shows an EIA (docs/design.md; the estimators'
// derivations and measurements: docs/view-estimators.md): spectral rendering traced backwards
// from the sensor, through the camera lens and the MLA to the panel's subpixels.
//
//   auto camera = makeViewCamera(description, pose, {});          // rays in the display frame
//   DisplayModel dm = makeDisplayModel(display, layout, eia, "eia.exr", MlaKind::Real);
//   ViewSettings settings;                                         // Quadrature, grid 16
//   ViewResult r = renderView(*camera, description.sensor, *dm.mla, *dm.panel, dm.area, settings);
//   writeImage(r.image, "view.exr");                               // linear camera RGB
//
// The renderer runs the tile loop (16 x 16 tiles, in parallel), skips tiles that cannot see
// the display and writes the image; a panel estimator (estimators/panel_estimator.h) says what
// each pixel sees. Output: linear, white-balanced camera RGB (a D65 grey of luminance Y gives
// (Y, Y, Y)); with the emitter in absolute units that is cd/m^2 of the equivalent D65 grey.
//
// Determinism: every pixel's value depends on (seed, pixel index, sample index) only, and each
// estimator's caches are per tile, filled in the tile's fixed order, so the image is
// bit-identical for any thread count.
#include <cstdint>
#include <vector>

#include "camera/camera_model.h"
#include "camera/sensor.h"
#include "core/image.h"
#include "core/pixel_mask.h"
#include "display/ei_layout.h"
#include "mla_optics/mla_model.h"
#include "display_view/estimators/footprint_estimator.h"
#include "display_view/estimators/panel_estimator.h"
#include "display_view/estimators/quadrature_estimator.h"
#include "display_view/panel_emitter.h"
#include "display_view/view_settings.h"

namespace inim {

// Fraction of a grid x grid set of pixel centres whose central ray (lens sample at the pupil's
// centre, 550 nm) reaches the plane z = 0 inside `area`: 0 means the display is out of view.
double displayCoverage(const CameraModel& camera, const AreaMm& area, int grid = 32);
// The pixels whose central ray (lens centre, 550 nm) meets the MLA plane inside `area`: where
// the display can show anything, so where reconstructions and references are compared.
PixelMask displayMask(const CameraModel& camera, const AreaMm& area);

struct ViewStats {
  // Rays of every estimator (RayCounts, summed over the image).
  uint64_t tracedRays = 0;    // camera rays traced (weight > 0; one per slot when dispersive)
  uint64_t displayRays = 0;   // ... that reached the MLA inside the active area
  uint64_t panelRays = 0;     // ... that reached the panel (MLA did not lose them)
  uint64_t emittingRays = 0;  // ... that read a non-zero emission
  uint64_t culledPixels = 0;  // pixels of tiles that cannot see the display (left 0)
  FootprintStats footprint;   // the Footprint estimator's own
  QuadratureStats quadrature; // the Quadrature estimator's own
  int raysPerSample = 1;      // 1, 3 (primaries, dispersive) or 4 (visible, dispersive)
  bool dispersive = false;
  double seconds = 0.0;
  bool displayInView() const { return displayRays > 0; }
  void addRayCounts(const RayCounts& counts) {
    tracedRays += counts.traced;
    displayRays += counts.onDisplay;
    panelRays += counts.onPanel;
    emittingRays += counts.emitting;
  }
};

struct ViewResult {
  Image image;  // R, G, B: linear white-balanced camera RGB, unexposed
  ViewStats stats;
  bool carried = false;  // rendered in another panel's pass (renderViews; stats are the pass's)
  bool cached = false;   // read from the reference cache (display_view/reference_cache.h; seconds 0)
};

// The view through `camera` of the display (MLA, panel, active area on the MLA's front plane,
// all in the display frame). InputError for spp < 1, a non-finite or negative background, or
// settings the estimator cannot use.
ViewResult renderView(const CameraModel& camera, const CameraSensor& sensor, const MlaModel& mla,
                      const PanelEmitter& panel, const AreaMm& area, const ViewSettings& settings);

// The views of several panels through the same camera, MLA and area: result k is panel k's,
// bit for bit what renderView gives it. Panels that the Quadrature estimator can carry along
// with the first (QuadratureEstimator::canCarry: another subpixel layout or drive) share one
// pass, its geometry traced once (their stats are the pass's); the others render one by one.
std::vector<ViewResult> renderViews(const CameraModel& camera, const CameraSensor& sensor, const MlaModel& mla,
                                    const std::vector<const PanelEmitter*>& panels, const AreaMm& area,
                                    const ViewSettings& settings);

}  // namespace inim
