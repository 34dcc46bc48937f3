#pragma once
// `inim calibrate` as a library (docs/colour-calibration.md): characterise the colour chain
// of a display seen by a camera at several poses, say where the colour error comes from, fit
// panel-side and camera-side corrections, verify them on colours never fitted, and export the
// chosen panel-side correction as .cube, CLF and an OpenColorIO config.
//
//   CalibrateSettings s;
//   s.outDir = "out/calibration";
//   CalibrateResult r = runCalibration(s);   // r.files.cube is what `inim eia --calibration` reads
//
// Outputs (all written together at the end, or none): calibration.json (everything below),
// stages.csv, verification.csv, patches.csv (the ColorChecker and the hold-out colours per pose,
// before and after), panel_correction.{cube,clf,ocio}.
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "calibration/ocio_config.h"
#include "colour_chain/chain_fit.h"
#include "colour_chain/verification.h"
#include "core/json_config.h"

namespace inim {

struct CalibrateSettings {
  std::string outDir;
  std::string displayPath;                    // "": the paper's prototype
  // The display the EIAs are made for (its panel primaries drive the colour path), when it is
  // not the one shown: e.g. a panel file with placeholder spectra while the panel itself has
  // measured ones. "": the same display.
  std::string assumedDisplayPath;
  std::string camera = "alvium-1800-u-500c";  // a name in optics/cameras or a file
  double angleDeg = 7.0;                      // the side poses (H and V)
  double distanceMm = 0.0;                    // 0: the camera description's
  std::vector<std::string> poses = {"centre", "left", "right", "top", "bottom"};
  std::string fieldSpace = "lin_rec709";      // the field's colour space, or "spectral"
  bool whiteBalanceD65 = false;               // the EIA's white gains (eia --white-balance)
  GamutMapping gamut = GamutMapping::Clip;
  int gridLevels = 5;                         // N of the N^3 drive grid
  int holdOutInGamut = 120, holdOutOutOfGamut = 40;
  uint64_t seed = 1;                          // hold-out colours and renders
  int lutSize = 33;
  int panelBits = 8;                          // the panel's input (0: float)
  std::string correction = "auto";            // matrix_3x3, root_polynomial_2, lut3d or auto
  std::string patchCsv;                       // optional: more colours to verify (name,X,Y,Z)
  int directChecks = 3;                       // patches rendered directly against the linear model
  bool progress = true;                       // a bar over the renders, on a terminal only
  ChainRenderSettings render;
  // The grade each pose is held to: the exported correction's in-gamut hold-out CIEDE2000 mean
  // and maximum (DisplayCAL's "recommended" tolerances). gradeMean <= 0: no grade.
  double gradeMean = 1.0, gradeMax = 3.0;
};

// "MEAN,MAX" (e.g. "1,3") or "off" into the settings; InputError naming --grade otherwise.
void parseGrade(const std::string& text, CalibrateSettings& s);

struct CorrectionReport {
  std::string name;                            // correctionName
  std::shared_ptr<const ColourModel> allPoses; // one correction for every pose
  std::vector<VerificationRow> rows;           // per pose, all-poses then per-pose scope
};

struct CalibrateResult {
  std::vector<PoseChain> chains;               // in the order of settings.poses
  PatchSet colorChecker, grid, holdIn, holdOut, userPatches;
  ColourPath path;
  std::vector<StageRow> stages;
  std::vector<VerificationRow> uncalibrated;   // per pose
  std::vector<CorrectionReport> corrections;
  std::string chosen;                          // the exported model
  std::shared_ptr<const Lut3d> exported;       // the chosen model sampled into the exported LUT
  std::vector<VerificationRow> exportedRows;   // per pose, through the exported LUT
  Json cameraSide;                             // camera RGB -> XYZ models and their errors
  double maxDirectCheckError = 0.0;            // relative, direct render against the linear model
  CalibrationFiles files;
  Json json;                                   // calibration.json
  std::vector<std::string> failedPoses;        // poses that miss the grade (empty: pass, or no grade)
  double characteriseSeconds = 0, fitSeconds = 0, verifySeconds = 0;
};

struct CalibrateObserver {
  std::function<void(const PoseResponse&)> poseDone;  // after each pose's renders
};

// InputError naming the setting (display, camera, poses, field_space, grid_levels, correction,
// patches, angle_deg, pose, ...) before any output.
// `outputs`: add the files to it and leave the commit to the caller (a study's report);
// null: write them and commit.
CalibrateResult runCalibration(const CalibrateSettings& s, const CalibrateObserver& observer = {},
                               OutputSet* outputs = nullptr);

// The ColorChecker as measured at `chain`'s pose through `toDrive`: per patch outcome.
std::vector<PatchOutcome> measureSet(const CalibrateResult& r, const FieldToDrive& toDrive, const PoseChain& chain,
                                     const PatchSet& set);

// What `inim calibrate` prints: stages, models, verification, files.
// "pose NAME LABEL N px measured, S s".
std::string poseResponseText(const PoseResponse& p);
std::string calibrationSummary(const CalibrateResult& r);

}  // namespace inim
