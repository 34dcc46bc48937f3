#pragma once
// The paper's Fig. 11 reproduced in software. One run makes the EIA of a field for a display,
// then looks at the display and at the field itself with the same camera from five directions
// (0 deg, +-angle horizontally, +-angle vertically, the display turned about its centre as the
// paper's gimbal does), and writes into the output folder: eia.exr/png, view_POSE and
// reference_POSE (.exr linear camera RGB x exposure, .png sRGB; the reference in full where it
// is compared, one sample per pixel elsewhere: pose_comparison.h), a contact sheet laid out like
// the figure, and metrics.json / metrics.csv (PSNR, SSIM, CIEDE2000 mean and 95th percentile
// over the pixels that see the display; both images at one exposure, compared as sRGB). With a
// calibration file the EIA's drive values go through it (as `inim eia --calibration`);
// metrics.json's "calibration" and the contact-sheet heading name it ("none" without).
// With depthError (the default) the error is also binned by scene depth: depth_error_POSE.csv,
// reference_POSE_depth.exr, depth_error.png and metrics.json's "depth_error" (fig11_depth.h).
// All outputs are written together at the end, or none.
//
//   Fig11Settings s;
//   s.outDir = "out/fig11";
//   Fig11Result r = runFig11(s);
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "runs/display_rays.h"
#include "analysis/depth_error.h"
#include "analysis/metrics.h"
#include "display/display.h"
#include "runs/error_budget.h"
#include "field/placement.h"
#include "display_view/display_model.h"
#include "display_view/display_pose.h"
#include "display_view/reference_renderer.h"

namespace inim {

struct Fig11Settings {
  std::string outDir;
  std::string displayPath;                     // "": the paper's prototype
  std::string fieldPath;                       // "": scenes/paper-fig7.json; or a trained model (.inimrf)
  std::string camera = "alvium-1800-u-500c";   // a name in optics/cameras or a file
  std::string calibrationPath;                 // .cube or .clf applied to the EIA's drive values; "": none
  MlaKind mla = MlaKind::Real;                 // of the reconstruction
  DisplayRayChoice rays;                       // the EIA's display rays (runs/display_rays.h)
  PlacementOverride placement;                 // over the field's own placement
  int width = 648;        // view width in pixels (the sensor's pitch scales; 2592 = full)
  int sheetImageWidth = 0;  // > 0: the contact sheet's images downscaled (area average) to this width
  // The reconstructions' quadrature: 1 stratum per pixel on an 8 x 8 aperture grid, RMSE 2.5 %
  // of the mean against 16 strata on 32 x 32 at 648 px (2 strata: 2.2 % in 1.5 x the time; `inim
  // bench --filter '^view/' --view-estimators quadrature --view-spp 1 2 --view-grid 8
  // --view-ref-spp 16 --view-ref-grid 32`), a quarter of the reference's noise (9.6 %). It is
  // also the budget's, so the budget's full chain is this view (budgetSpp).
  int spp = 1;            // strata per pixel of the reconstructed views (ViewSettings' estimator)
  int apertureGrid = 8;   // ViewSettings::apertureGrid
  int referenceSpp = ReferenceSettings{}.spp;  // samples per pixel of the reference views
  // Field samples per display ray of the EIA. 2 with the default scene's every-light sampling
  // gives the EIA the same noise (RMSE between seeds 37 % per EIA pixel) as 4 picking one light
  // per sample, in the same time.
  int eiaSpp = 2;
  double angleDeg = 7.0;  // viewing angle of the four side views
  double distanceMm = 0;  // camera distance; 0: the camera description's
  uint64_t seed = 1;
  // The error budget (runs/error_budget.h): the ladder from an ideal display to the
  // real one and the full chain with one effect removed, per pose; budget.json, .csv, .png.
  bool budget = false;
  std::string budgetCalibrationPath;     // the "+ calibration" rung's (default: calibrationPath)
  std::vector<std::string> budgetRungs;  // names of the rungs to run; empty: all
  // Strata per pixel of every rung, the full chain included (it is rendered again unless this
  // equals spp; when it does, the view's pass also renders the rungs that differ from it in the
  // panel only: - subpixels, + calibration): 1 keeps the budgeted run within 3 x the plain one,
  // with the quadrature's own error (RMSE 2.5 % of the mean) the same for every rung.
  int budgetSpp = 1;
  bool depthError = true;  // error against scene depth per pose (runs/fig11_depth.h)
  // For studies: a display used instead of displayPath, and the poses to render by name
  // (centre, left, right, top, bottom; empty: all five).
  std::optional<Display> display;
  std::vector<std::string> poses;
  // The reference cache's folder (ReferenceSettings::cacheDir); "": the user's. Without
  // referenceCache, references are always rendered.
  std::string referenceCacheDir;
  bool referenceCache = true;
  // The references in full at every pixel, not only where the display is seen (its pixels get
  // the same samples either way, so the metrics are the same): they then depend on the scene,
  // placement, camera and pose only, and the points of a sweep that change the display's optics
  // or size share them through the cache. Off: pixels away from the display get one sample.
  bool referenceEveryPixel = false;
};

struct Fig11View {
  std::string name;   // file-name stem: centre, left, right, top, bottom
  std::string label;  // contact-sheet label: "0°", "H -7°", ...
  DisplayPose pose;
  bool displayInView = true;  // some camera ray of the reconstruction reached the display
  bool hasMetrics = false;    // false when no pixel sees the display
  ImageMetrics metrics;
  ImageMetrics bandLimitedMetrics;  // against the band-limited reference (analysis/band_limit.h)
  // Error against depth (empty without depth channels): against the reference and against the
  // band-limited reference.
  std::vector<DepthBin> depthBins, depthBinsBandLimited;
  // The view's render (with the budget, its pass also renders the rungs it carries), the reference's.
  double reconstructionSeconds = 0, referenceSeconds = 0;
  bool referenceCached = false;  // read from the reference cache (display_view/reference_cache.h)
};

struct Fig11Result {
  std::vector<PoseBudget> budgets;    // with settings.budget, per pose with metrics
  std::string fieldPath;
  std::string calibration = "none";  // the calibration applied (describeCalibration), or "none"
  int eiaWidth = 0, eiaHeight = 0;
  double eiaSeconds = 0;
  std::vector<Fig11View> views;
};

// Progress as the run goes (optional): after the EIA, and after each view.
struct Fig11Observer {
  std::function<void(const Fig11Result&)> eiaDone;
  std::function<void(const Fig11View&)> viewDone;
  std::function<void(const PoseBudget&)> budgetDone;
};

// InputError naming the setting (spp, reference_spp, eia_spp, width, angle_deg, field,
// calibration, ...) before any work or output.
Fig11Result runFig11(const Fig11Settings& settings, const Fig11Observer& observer = {});

// What `inim fig11` prints as it goes: the EIA and the table's header; a view's row (none when
// it has no metrics) with the warnings it gives on stderr; the files written.
std::string fig11EiaText(const Fig11Result& r);
std::string fig11ViewText(const Fig11View& v);
std::string fig11ViewWarnings(const Fig11View& v);
// "  budget POSE <rungs>".
std::string fig11BudgetText(const PoseBudget& b);
std::string fig11WrittenText(const Fig11Settings& s);

}  // namespace inim
