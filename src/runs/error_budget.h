#pragma once
// The error budget of a reconstruction (docs/design.md §1.9): a ladder of simulations from an
// ideal display to the real one, each rung adding one effect, all seen by the same camera from
// the same pose, exposed alike and compared with the same reference over the same mask.
//
//   ideal display     thin ideal lenslets, each panel pixel a uniform emitter of its R, G, B
//                     (no subpixel pattern), no cover glass, no colour chain (the observer sees
//                     the panel's XYZ, put into camera RGB as the reference puts an RGB field's)
//   + subpixels       the panel's subpixel layout and black matrix
//   + real MLA        the refracting lenslets (aberration, dispersion, Fresnel, crosstalk)
//   + cover glass     the panel's cover glass
//   + colour chain    the panel's spectra seen by the camera's sensor: the full chain
//   + calibration     the same with the panel-side correction of `inim calibrate` on the EIA
//
// A display given as an optical stack with aperture sheets or barrier walls gets a rung for each
// of those layer kinds after "+ real MLA" (which then refracts through the stack's lens arrays
// and plates only, the sheets and walls standing as air): "+ apertures", "+ barriers", and their
// removals from the full chain ("-apertures", "-barriers"). Other displays' ladders are as above.
//
// Effects interact, so the budget also removes one effect at a time from the full chain. The
// noise floor is the reference against a reference of another seed. A rung that cannot be
// built (no cover glass to add, no calibration given) is skipped with a note.
//
//   BudgetScene scene{display, layout, eia, calibratedEia, camera};
//   PoseBudget b = poseBudget(scene, *cameraModel, reference, secondReference, exposure, mask, budgetRungs());
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "analysis/metrics.h"
#include "camera/camera_config.h"
#include "core/image.h"
#include "core/json_config.h"
#include "core/pixel_mask.h"
#include "display/display.h"
#include "display/ei_layout.h"
#include "display_view/panel_emitter.h"
#include "display_view/view_settings.h"

namespace inim {

struct BudgetRung {
  std::string name;    // "ideal", "+subpixels", ..., "-real_mla"
  std::string label;   // for tables and plots
  bool subpixels = false, realMla = false, coverGlass = false, colourChain = false, calibrated = false;
  bool removal = false;  // the full chain with one effect removed (not a ladder rung)
  // With the real MLA of a stack display: its aperture sheets and barrier walls (else air).
  bool apertures = true, barriers = true;
};

// The ladder, in order, then the full chain with one effect removed; with `display`, its stack's
// layer-kind rungs too.
std::vector<BudgetRung> budgetRungs(const Display* display = nullptr);
// Rung names for options, in budgetRungs() order: InputError (key "budget_rungs") listing the
// valid ones for an unknown name; a stack's rung names are valid for any display and select
// nothing on one without those layers.
std::vector<BudgetRung> selectRungs(const std::vector<std::string>& names, const Display* display = nullptr);

// What every rung of a run shares.
struct BudgetScene {
  const Display* display = nullptr;
  const EiLayout* layout = nullptr;
  const Image* eia = nullptr;            // uncalibrated drive values
  const Image* calibratedEia = nullptr;  // null: the calibration rung is skipped
  const CameraDescription* camera = nullptr;
  ViewSettings view;
  double gapMm = 0.0;  // panel to MLA; 0: the display's reconstruction gap
};

struct RungResult {
  BudgetRung rung;
  bool skipped = false;
  std::string note;          // why it was skipped, or what it stands for
  ImageMetrics metrics;      // against the reference
  std::optional<ImageMetrics> bandLimited;  // against the band-limited reference, when given
  double seconds = 0.0;
  Image srgb;                // the rung's view, sRGB (for error maps)
};

// A rung's render made before poseBudget (through the same camera, sensor and settings; linear
// camera RGB, unexposed): the run's own view as the full chain, and the rungs it carried along.
struct MadeRungView {
  BudgetRung rung;
  const Image* view = nullptr;
  std::string note;  // how it was made, for the budget
};

// The full chain (subpixels, real MLA, cover glass, colour chain; not calibrated).
BudgetRung fullChainRung();

// A rung that a render of the full chain can carry along (renderViews), and its panel.
struct RungPanel {
  BudgetRung rung;
  std::unique_ptr<PanelEmitter> panel;
};
// The rungs of `rungs` seen through the full chain's optics and colour chain with another panel
// (no subpixels; the calibrated EIA) that can be built, each once, with their panels at the gap
// `gapMm`; `drive`: the uncalibrated EIA's drive table (PanelEmitter::driveTable), shared.
std::vector<RungPanel> fullChainCompanions(const BudgetScene& scene, const std::vector<BudgetRung>& rungs,
                                           double gapMm, std::shared_ptr<const std::vector<float>> drive);

struct PoseBudget {
  std::string pose;
  ImageMetrics noiseFloor;   // reference against the reference of another seed
  std::vector<RungResult> ladder, removeOne;
};

// The rungs at one pose. `reference`, `secondReference`: linear camera RGB already scaled to
// the display's units and exposed by `exposure` (fig11's exposeAlike); rung views are
// multiplied by `exposure`. `rungs`: which rungs to render (budgetRungs() or a selection).
// `made`: rungs rendered before (the run's own reconstruction of the uncalibrated EIA as the full
// chain, and the companions it carried), reused instead of rendering them again; the rungs left
// that share their optics and sensor are rendered in one pass each (renderViews).
// `bandLimitedReference` (optional, exposed like `reference`; analysis/band_limit.h): every rung
// is also compared with it. `tables` (optional): the aperture tables of renders through
// `camera` made before (the run's own view's), which the rungs reuse.
PoseBudget poseBudget(const BudgetScene& scene, const CameraModel& camera, const Image& reference,
                      const Image& secondReference, double exposure, const PixelMask& mask,
                      const std::vector<BudgetRung>& rungs, const std::vector<MadeRungView>& made = {},
                      const Image* bandLimitedReference = nullptr,
                      std::shared_ptr<QuadratureTableCache> tables = nullptr);

// A render's camera RGB as another sensor would have recorded it, for the quadrature estimator
// with one wavelength node per primary (sensorSwapIsExact), where each channel's emission becomes
// camera RGB through one fixed vector per channel: `to`'s channel matrix times the inverse of
// `from`'s. Rungs that differ only by the colour chain share one render through it.
bool sensorSwapIsExact(const ViewSettings& vs);
glm::dmat3 sensorSwap(const PanelEmitter& panel, const CameraSensor& from, const CameraSensor& to);
Image transformedRgb(const Image& img, const glm::dmat3& m);  // m on every pixel's first 3 channels

// Physics' one ordering: the ideal display no worse than the full chain beyond the noise floor
// (mean CIEDE2000). nullopt when either rung was not run.
std::optional<bool> idealWithinFloorOfFullChain(const PoseBudget& b);

// One line for the terminal: the noise floor, each ladder rung's mean CIEDE2000 and whether the
// ideal display is within the floor of the full chain.
std::string budgetLine(const PoseBudget& b);

// budget.json's entry of a pose: noise floor, rungs with metrics and increments (each rung
// against the one before; each removal against the full chain).
Json poseBudgetJson(const PoseBudget& b);
// budget.csv rows: pose, kind (floor, ladder, remove), rung, PSNR, SSIM, dE mean, dE p95, increments.
std::vector<std::string> budgetCsvHeader();
std::vector<std::vector<std::string>> budgetCsvRows(const PoseBudget& b);
// The waterfall: mean CIEDE2000 rung by rung (floating bars from one rung to the next, red up,
// green down) for the first pose, the other poses' levels as markers; the noise floor marked.
void writeBudgetPlot(const std::vector<PoseBudget>& budgets, const std::vector<std::string>& poseLabels,
                     const std::string& path);

}  // namespace inim
