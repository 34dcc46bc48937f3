#pragma once
// `inim view --reference`: one view of the display compared with the scene itself from the same
// pose, as `inim fig11` compares each of its five (runs/pose_comparison.h), and its error
// budget (runs/error_budget.h). The EIA's exposure (drive per unit of field luminance)
// puts the reference in the display's units; `inim eia` and `inim fig11` keep it in the EIA's
// EXR header (kEiaExposureHeader), else it must be given.
//
// Outputs beside the view's EXR `dir/NAME.exr`, all written together or none:
//   NAME.exr, NAME.png              the view, exposed like the reference
//   NAME_reference.exr, .png        the reference
//   NAME_error.png                  CIEDE2000 per pixel (viridis, 0-50), grey off the display
//   NAME_metrics.json               PSNR, SSIM, CIEDE2000 mean and p95 against the reference and
//                                   the band-limited reference, error against depth
//   NAME_budget.json, .csv, .png    the budget (unless budget = false)
//
//   ViewReferenceSettings rs;  rs.fieldPath = "scenes/paper-fig7.json";
//   ViewReferenceResult r = runViewWithReference(viewSettings, rs);
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "analysis/depth_error.h"
#include "analysis/metrics.h"
#include "display_view/reference_renderer.h"
#include "runs/camera_run.h"
#include "runs/error_budget.h"
#include "field/placement.h"

namespace inim {

struct ViewReferenceSettings {
  std::string fieldPath;                // the EIA's scene or field; "": scenes/paper-fig7.json
  std::optional<Placement> placement;   // a run file's; absent: the field's own
  PlacementOverride placementOverride;  // given one by one, over that
  std::optional<double> eiaExposure;    // default: the EIA's header (kEiaExposureHeader)
  int referenceSpp = ReferenceSettings{}.spp;  // samples per pixel of each reference
  bool budget = true;
  std::vector<std::string> budgetRungs;  // empty: all (budgetRungs())
  std::string budgetCalibrationPath;     // the "+ calibration" rung's correction; "": skipped
  int budgetSpp = 1;                     // strata per pixel of every rung (fig11's default)
};

struct ViewReferenceResult {
  ViewRunResult view;
  std::string fieldPath;
  Placement placement;
  double eiaExposure = 1.0;
  bool eiaExposureFromHeader = false;
  double exposure = 1.0;  // the factor on both images
  bool hasMetrics = false;  // false when no pixel sees the display
  ImageMetrics metrics, bandLimitedMetrics;
  std::vector<DepthBin> depthBins;
  double referenceSeconds = 0.0;
  bool referenceCached = false;  // read from the reference cache (display_view/reference_cache.h)
  std::optional<PoseBudget> budget;
  std::vector<std::string> written;
};

// Every input (the field, placement, exposure, calibration, rung names) is checked before any
// work. `loaded` as runView's.
ViewReferenceResult runViewWithReference(const ViewRunSettings& s, const ViewReferenceSettings& rs,
                                         const std::function<void(const ViewRunResult&)>& loaded = {});

// The comparison's lines as `inim view --reference` prints them: the reference, its metrics
// against the view and the band-limited reference, the budget (no metrics when no pixel sees
// the display).
std::string comparisonText(const ViewReferenceResult& r);
// The view's out-of-view warning and, when no pixel sees the display, that there are no metrics.
std::string comparisonWarnings(const ViewReferenceResult& r);

}  // namespace inim
