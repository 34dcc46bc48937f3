#pragma once
// What `inim calibrate` reports (docs/colour-calibration.md): the stage table (where the
// colour error comes from, one stage switched on at a time, on the ColorChecker) and the
// verification of corrections on colours never fitted (the hold-out sets), per pose.
#include <memory>
#include <string>
#include <vector>

#include "calibration/colour_model.h"
#include "colour_chain/colour_chain.h"

namespace inim {

// The chain's colour path, the same at every pose.
struct ColourPath {
  PanelColor panel;             // the panel the EIAs are made for (the assumed display's)
  PanelColor shownPanel;        // the panel shown (the measured display's; often the same)
  DriveSettings drive;          // exposure, white gains, gamut mapping (no correction)
  std::string fieldSpace;       // "spectral" or an OCIO linear space
  PanelInput input;             // the panel's EOTF and input bits
  CameraSensor sensor;          // the viewing camera's

  FieldToDrive uncalibrated() const { return FieldToDrive(panel, drive); }
  FieldToDrive corrected(std::shared_ptr<const ColourModel> correction) const;
  // The drive `inim eia` puts on the panel for a field colour (field space, exposure, gamut
  // mapping, correction).
  Vec3d driveOf(const FieldToDrive& toDrive, const Vec3d& fieldXyz) const;
};

// One patch at one pose: the target and what the chain shows, colorimetric and by the camera.
struct PatchOutcome {
  std::string name;
  Vec3d target{0.0}, shown{0.0};              // observer XYZ (pose units)
  Vec3d cameraTarget{0.0}, cameraShown{0.0};  // camera XYZ (the sensor's own 3x3)
  double deltaE = 0.0, cameraDeltaE = 0.0;    // CIEDE2000, reference white: the pose's white
  bool inGamut = true;                        // the pose can show the target
  bool inAssumedGamut = true;                 // the panel the EIA is made for can encode it unmapped
};
PatchOutcome measurePatch(const ColourPath& path, const FieldToDrive& toDrive, const PoseChain& chain,
                          const Patch& patch);

struct StageRow {
  std::string stage, pose, note;  // pose "" when it does not depend on the pose
  DeltaESummary colorimetric;
  bool inDefaultChain = true;     // false: shown for comparison (another mapping, the paper's path)
};
// One stage switched on at a time against an ideal chain, on `patches` (the ColorChecker).
std::vector<StageRow> stageTable(const ColourPath& path, const std::vector<PoseChain>& chains, const PatchSet& patches);

struct VerificationRow {
  std::string pose, correction, scope;  // scope: "all poses", "this pose" or "" (uncalibrated)
  DeltaESummary inGamut, outOfGamut, cameraInGamut;
  DeltaESummary outOfGamutMapping;      // the gamut mapping's own error on those colours
  // Colours the shown panel can show but the assumed one cannot encode (the EIA is made for a
  // panel other than the one shown): neither in- nor out-of-gamut, reported on their own.
  DeltaESummary outsideAssumedGamut;
};
VerificationRow verify(const ColourPath& path, const FieldToDrive& toDrive, const PoseChain& chain,
                       const std::vector<const PatchSet*>& holdOut, const std::string& correction,
                       const std::string& scope);

// The camera side on the hold-out colours shown (uncalibrated) at a pose: camera RGB -> XYZ by
// `model` (null: the sensor's own 3x3) against the observer.
DeltaESummary cameraSideError(const ColourPath& path, const PoseChain& chain, const ColourModel* model,
                              const std::vector<const PatchSet*>& holdOut);

}  // namespace inim
