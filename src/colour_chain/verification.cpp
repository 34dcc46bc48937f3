#include "colour_chain/verification.h"

#include "core/error.h"

namespace inim {

FieldToDrive ColourPath::corrected(std::shared_ptr<const ColourModel> correction) const {
  DriveSettings d = drive;
  d.correction = std::move(correction);
  return FieldToDrive(panel, d);
}

Vec3d ColourPath::driveOf(const FieldToDrive& toDrive, const Vec3d& fieldXyz) const {
  return Vec3d(toDrive.fromXyz(Vec3(representableInField(fieldXyz, fieldSpace))));
}

PatchOutcome measurePatch(const ColourPath& path, const FieldToDrive& toDrive, const PoseChain& chain,
                          const Patch& patch) {
  PatchOutcome o;
  o.name = patch.name;
  const Vec3d d = path.driveOf(toDrive, patch.xyz);
  o.target = chain.target(patch.xyz);
  o.shown = chain.shownXyz(d);
  const Vec3d sceneXyz = patch.radiance ? path.sensor.toXyz(path.sensor.cameraRgb(*patch.radiance)) : patch.xyz;
  o.cameraTarget = chain.target(sceneXyz);
  o.cameraShown = path.sensor.toXyz(chain.cameraRgb(d));
  o.deltaE = deltaE2000(o.shown, o.target, chain.labWhite());
  o.cameraDeltaE = deltaE2000(o.cameraShown, o.cameraTarget, chain.labWhite());
  o.inGamut = chain.inGamut(o.target);
  // The same tolerance as PoseChain::inGamut, on the assumed panel's drive before mapping.
  GamutStats stats;
  path.uncalibrated().fromXyz(Vec3(representableInField(patch.xyz, path.fieldSpace)), stats);
  o.inAssumedGamut = stats.minChannel >= -2e-3 && stats.maxChannel <= 1.0 + 2e-3;
  return o;
}

namespace {

// The field colour a drive stands for on an ideal display (the nominal panel, no optics).
Vec3d idealXyz(const ColourPath& path, const FieldToDrive& toDrive, const Vec3d& drive) {
  return path.panel.driveToXYZ() * (drive / Vec3d(toDrive.gains()));
}

StageRow row(std::string stage, std::string pose, std::vector<double> e, std::string note, bool inDefault = true) {
  return StageRow{std::move(stage), std::move(pose), std::move(note), summarise(std::move(e)), inDefault};
}

// The stages before the optics: field colour space, gamut mapping, 8-bit EOTF, white point.
void drivingStages(const ColourPath& path, const PatchSet& cc, std::vector<StageRow>& rows) {
  const Vec3d white = d65WhiteXyz();
  const FieldToDrive toDrive = path.uncalibrated();
  std::vector<double> field, mapping, other, eotf, paper;
  DriveSettings otherMapping = path.drive, paperPath = path.drive;
  otherMapping.gamut = path.drive.gamut == GamutMapping::Clip ? GamutMapping::Desaturate : GamutMapping::Clip;
  paperPath.whiteBalanceD65 = true;
  const FieldToDrive otherDrive(path.panel, otherMapping), paperDrive(path.panel, paperPath);
  for (const Patch& p : cc.patches) {
    field.push_back(deltaE2000(representableInField(p.xyz, path.fieldSpace), p.xyz, white));
    const Vec3d mapped = Vec3d(toDrive.fromXyz(Vec3(p.xyz)));
    mapping.push_back(deltaE2000(idealXyz(path, toDrive, mapped), p.xyz, white));
    other.push_back(deltaE2000(idealXyz(path, otherDrive, Vec3d(otherDrive.fromXyz(Vec3(p.xyz)))), p.xyz, white));
    eotf.push_back(deltaE2000(idealXyz(path, toDrive, path.input.quantise(mapped)), idealXyz(path, toDrive, mapped), white));
    // The paper's display shows D65 as its own white (drive e, e, e): colours relative to it.
    const Vec3d shown = path.panel.driveToXYZ() * Vec3d(paperDrive.fromXyz(Vec3(p.xyz))) / path.drive.exposure;
    paper.push_back(deltaE2000(shown, p.xyz, white));
  }
  rows.push_back(row("field colour space", "", field, path.fieldSpace + ": colours the field cannot store are clipped"));
  rows.push_back(row("gamut mapping", "", mapping, std::string(gamutName(path.drive.gamut)) + " into the panel's primaries"));
  rows.push_back(row("gamut mapping", "", other, std::string(gamutName(otherMapping.gamut)) + " instead", false));
  rows.push_back(row("panel EOTF", "", eotf,
                     std::to_string(path.input.bits) + "-bit input through the panel's " + path.input.eotf.name() +
                         " EOTF"));
  rows.push_back(row("panel white point", "", paper,
                     "D65 shown as the panel's own white (d65 white gains: the paper's path, RGB straight to the panel)",
                     path.drive.whiteBalanceD65));
}

}  // namespace

std::vector<StageRow> stageTable(const ColourPath& path, const std::vector<PoseChain>& chains, const PatchSet& cc) {
  std::vector<StageRow> rows;
  drivingStages(path, cc, rows);
  const double e = path.drive.exposure;
  // The panel shown against the one assumed, on axis without optics (relative to its own
  // brightest D65, as at a pose).
  const double eShown = calibrationExposure(path.shownPanel);
  std::vector<double> primaries;
  for (const Patch& p : cc.patches)
    primaries.push_back(deltaE2000(path.shownPanel.driveToXYZ() * (e * path.panel.driveFromXYZ(p.xyz)) / eShown,
                                   p.xyz, d65WhiteXyz()));
  rows.push_back(row("panel primaries", "", primaries,
                     "the panel's emission spectra against those the EIA is made for (0 when they are the same)"));
  // The optics alone: the drive the shown panel needs, through the pose's chain.
  for (const PoseChain& c : chains) {
    std::vector<double> optics;
    for (const Patch& p : cc.patches)
      optics.push_back(
          deltaE2000(c.linearXyz(eShown * path.shownPanel.driveFromXYZ(p.xyz)), c.target(p.xyz), c.labWhite()));
    rows.push_back(row("display optics", c.response().pose.label, optics,
                       "subpixels, real MLA (dispersion, Fresnel, crosstalk), cover glass, camera lens"));
  }
  std::vector<double> onDisplay, inScene;
  const PoseChain& front = chains.front();
  for (const Patch& p : cc.patches) {
    const Vec3d d = e * path.panel.driveFromXYZ(p.xyz);
    onDisplay.push_back(deltaE2000(path.sensor.toXyz(front.linearCameraRgb(d)), front.linearXyz(d), front.labWhite()));
    inScene.push_back(deltaE2000(path.sensor.toXyz(path.sensor.cameraRgb(*p.radiance)), p.xyz, d65WhiteXyz()));
  }
  rows.push_back(row("camera metamerism", front.response().pose.label, onDisplay,
                     path.sensor.name() + ": its own camera RGB -> XYZ 3x3 on the display's light"));
  rows.push_back(row("camera metamerism", "", inScene,
                     path.sensor.name() + ": the same 3x3 on the chart's reflected D65 (the reference view)", false));
  const FieldToDrive toDrive = path.uncalibrated();
  for (const PoseChain& c : chains) {
    std::vector<double> whole;
    for (const Patch& p : cc.patches) whole.push_back(measurePatch(path, toDrive, c, p).deltaE);
    rows.push_back(row("whole chain, uncalibrated", c.response().pose.label, whole, "every stage on"));
  }
  return rows;
}

VerificationRow verify(const ColourPath& path, const FieldToDrive& toDrive, const PoseChain& chain,
                       const std::vector<const PatchSet*>& holdOut, const std::string& correction,
                       const std::string& scope) {
  VerificationRow r{chain.response().pose.name, correction, scope, {}, {}, {}, {}, {}};
  std::vector<double> in, out, camIn, mapping, outsideAssumed;
  const FieldToDrive uncal = path.uncalibrated();
  for (const PatchSet* set : holdOut)
    for (const Patch& p : set->patches) {
      const PatchOutcome o = measurePatch(path, toDrive, chain, p);
      if (o.inGamut && !o.inAssumedGamut) {
        outsideAssumed.push_back(o.deltaE);
        continue;
      }
      if (o.inGamut) {
        in.push_back(o.deltaE);
        camIn.push_back(o.cameraDeltaE);
        continue;
      }
      out.push_back(o.deltaE);
      mapping.push_back(deltaE2000(idealXyz(path, uncal, path.driveOf(uncal, p.xyz)), p.xyz, d65WhiteXyz()));
    }
  r.inGamut = summarise(in);
  r.outOfGamut = summarise(out);
  r.cameraInGamut = summarise(camIn);
  r.outOfGamutMapping = summarise(mapping);
  r.outsideAssumedGamut = summarise(outsideAssumed);
  return r;
}

DeltaESummary cameraSideError(const ColourPath& path, const PoseChain& chain, const ColourModel* model,
                              const std::vector<const PatchSet*>& holdOut) {
  std::vector<double> e;
  const FieldToDrive uncal = path.uncalibrated();
  for (const PatchSet* set : holdOut)
    for (const Patch& p : set->patches) {
      const Vec3d d = path.driveOf(uncal, p.xyz);
      const Vec3d rgb = chain.cameraRgb(d);
      const Vec3d estimate = model ? model->apply(rgb) : path.sensor.toXyz(rgb);
      e.push_back(deltaE2000(estimate, chain.shownXyz(d), chain.labWhite()));
    }
  return summarise(e);
}

}  // namespace inim
