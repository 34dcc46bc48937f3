#pragma once
// `inim eia` as a library: display + field + placement -> the EIA files. The EIA at the panel's
// full resolution as a linear EXR of drive values (+ A, Z with aovs) and an encoded PNG beside
// it; optionally the placement preview (PNG) and the triads as a Zemax SDF source file. All are
// written together at the end, or none. Errors name settings (out, png, scene, ...) before any
// work. See src/synthesis/eia_synthesis.h.
#include <functional>
#include <optional>
#include <string>

#include "display/display.h"
#include "display/ei_layout.h"
#include "field/placement.h"
#include "field/ray_table.h"
#include "field_files/field_factory.h"
#include "runs/display_rays.h"
#include "runs/run_file.h"
#include "display/layout_override.h"
#include "synthesis/eia_synthesis.h"
#include "synthesis/preview.h"
#include "triads/triads.h"

namespace inim {

struct EiaRunSettings {
  std::string displayPath;   // "": the paper's prototype
  LayoutOverride layout;
  std::string fieldPath;     // scene JSON or trained model; "": scenes/paper-fig7.json
  std::string fieldKey = "scene";  // the setting an unusable fieldPath is reported as
  std::string fieldColorsPath;     // instead of a field: an external field's colours (inim rays --for-field)
  ColorEncoding colorsEncoding = ColorEncoding::SRGB;
  std::optional<Placement> placement;   // a run file's; absent: the field's own
  PlacementOverride placementOverride;  // given one by one, over that
  SynthesisSettings synthesis;          // its placement and display rays are set by the run
  // A calibration file (.cube or .clf, calibration/calibration_file.h) loaded with the other
  // inputs and set as synthesis.correction; "": synthesis.correction as given (normally none).
  std::string calibrationPath;
  std::string calibrationKey = "calibration";  // the setting an unusable calibrationPath is reported as
  DisplayRayChoice rays;  // which display rays to query along (runs/display_rays.h)
  std::string triadWavelengths = "panel";
  std::string triadWavelengthsKey = "triad_wavelengths";  // the setting a bad value is reported as
  std::string out, png, preview, sdf;   // EXR; PNG ("": beside it); optional preview and SDF
  std::string zemaxModel;               // optional, with sdf: the NSC model (.zmx) reading it
};

struct EiaRunResult {
  Display display;
  EiLayout layout;
  std::string fieldPath;
  FieldKind fieldKind = FieldKind::AnalyticScene;
  Placement placement;
  std::string raysSummary;  // with real-lens or traced chief rays: how they were traced
  std::string calibration = "none";  // the calibration applied (describeCalibration), or "none"
  std::string png;
  TriadWavelengths triadWavelengths;
  double loadSeconds = 0, writeSeconds = 0;
  SynthesisResult synthesis;
  PreviewResult preview;
  uint64_t triads = 0;  // triad rays written to the SDF
};

// The query rays' sampling as `inim eia` and `inim rays --for-field` check it before any work:
// a finite VCP distance (InputError naming vcp_mm), then spp >= 1 (naming spp).
void checkQuerySampling(double vcpMm, int spp);
// An exposure setting on `s`: auto, or a factor > 0. InputError naming `exposure` otherwise.
void applyExposure(const std::string& text, SynthesisSettings& s);
// A white balance setting: none or d65 (true). InputError naming `white_balance` otherwise.
bool parseWhiteBalanceD65(const std::string& text);

// The settings given one by one (the command line; absent: not given), over a run file's.
struct EiaGiven {
  std::optional<std::string> scene, field, triads, exposure, gamut, whiteBalance, calibration;
  std::optional<double> vcpMm;
  std::optional<int> spp;
  std::optional<uint64_t> seed;
  DisplayGiven display;
  PlacementOverride placement;
};
// The one rule: `base` (the library's defaults, with the settings only the command line sets:
// outputs, field colours, real-lens rays) < the run file < the settings given. A setting is
// named in errors as the file spells it when its value came from the run file; the field's own
// default placement (a trained model's) is below the run file's.
EiaRunSettings resolveEiaRun(EiaRunSettings base, const RunFile& run, const EiaGiven& given);

// `loaded` (optional) is called when everything is loaded, before the synthesis.
EiaRunResult runEia(const EiaRunSettings& s, const std::function<void(const EiaRunResult&)>& loaded = {});

// What `inim eia` prints: the setup (display, field, placement, real-lens rays) once loaded,
// and after the run the synthesis summary (its warnings left out: they go to stderr), the
// calibration applied and the files written, each line ending in a newline.
std::string setupText(const EiaRunResult& r, double vcpMm);
std::string summaryText(const EiaRunResult& r, const EiaRunSettings& s);

}  // namespace inim
