#include "runs/calibrate_run.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "analysis/csv.h"
#include "core/error.h"
#include "core/format.h"
#include "core/output_file.h"
#include "core/progress.h"
#include "spectral/color.h"

namespace fs = std::filesystem;

namespace inim {

namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

void validate(const CalibrateSettings& s) {
  if (s.gradeMean > 0.0 && !(std::isfinite(s.gradeMean) && std::isfinite(s.gradeMax) && s.gradeMax >= s.gradeMean))
    throw InputError("", "grade", formatNumber(s.gradeMean) + "," + formatNumber(s.gradeMax),
                     "finite thresholds MEAN,MAX with MAX >= MEAN > 0");
  if (s.outDir.empty()) throw InputError("", "out", "\"\"", "an output folder");
  // Checked before the characterisation's minutes of rendering, not when writing.
  if (fs::exists(s.outDir) && !fs::is_directory(s.outDir))
    throw InputError("", "out", "\"" + s.outDir + "\"", "an output folder (this names an existing file)");
  if (!(s.angleDeg >= 0.0 && s.angleDeg < 90.0))
    throw InputError("", "angle_deg", formatNumber(s.angleDeg), "an angle in [0, 90) degrees");
  if (s.poses.empty()) throw InputError("", "poses", "none", "at least one of centre, left, right, top, bottom");
  for (auto [v, key, lo, hi] : {std::tuple{s.holdOutInGamut, "holdout", 10, 100000},
                                {s.holdOutOutOfGamut, "holdout_out_of_gamut", 0, 100000},
                                {s.lutSize, "lut_size", 2, 129},
                                {s.panelBits, "panel_bits", 0, 16},
                                {s.directChecks, "direct_checks", 0, 100}})
    if (v < lo || v > hi)
      throw InputError("", key, std::to_string(v), std::to_string(lo) + " to " + std::to_string(hi));
  if (s.correction != "auto" && s.correction != "matrix_3x3" && s.correction != "root_polynomial_2" &&
      s.correction != "lut3d")
    throw InputError("", "correction", "\"" + s.correction + "\"", "auto, matrix_3x3, root_polynomial_2 or lut3d");
}

std::vector<NamedPose> selectPoses(const CalibrateSettings& s, double distanceMm) {
  const std::vector<NamedPose> all = fig11Poses(s.angleDeg, distanceMm);
  std::vector<NamedPose> out;
  for (const std::string& name : s.poses) {
    auto it = std::find_if(all.begin(), all.end(), [&](const NamedPose& p) { return p.name == name; });
    if (it == all.end()) throw InputError("", "poses", "\"" + name + "\"", "centre, left, right, top or bottom");
    out.push_back(*it);
  }
  return out;
}

Json deJson(const DeltaESummary& d) {
  return Json{{"count", d.count}, {"mean", d.mean}, {"p95", d.p95}, {"max", d.max}};
}

Json matrixRows(const glm::dmat3& m) {
  Json rows = Json::array();
  for (int r = 0; r < 3; ++r) rows.push_back({m[0][r], m[1][r], m[2][r]});
  return rows;
}

Json xyJson(const Vec3d& xyz) {
  const double s = xyz.x + xyz.y + xyz.z;
  return s > 0.0 ? Json{xyz.x / s, xyz.y / s} : Json{0.0, 0.0};
}

// The chosen model sampled into the exported table (the fitted LUT itself when it is one).
std::shared_ptr<const Lut3d> exportedLut(const std::string& name, const std::shared_ptr<const ColourModel>& model,
                                         int size) {
  if (name == correctionName(CorrectionKind::Lut)) return std::static_pointer_cast<const Lut3d>(model);
  return std::make_shared<Lut3d>(Lut3d::sample(
      [&](const Vec3d& d) { return glm::clamp(model->apply(d), Vec3d(0.0), Vec3d(1.0)); }, size));
}

}  // namespace

std::vector<PatchOutcome> measureSet(const CalibrateResult& r, const FieldToDrive& toDrive, const PoseChain& chain,
                                     const PatchSet& set) {
  std::vector<PatchOutcome> out;
  for (const Patch& p : set.patches) out.push_back(measurePatch(r.path, toDrive, chain, p));
  return out;
}

namespace {

struct Loaded {
  ChainOptics optics;
  Panel assumedPanel;
  std::string assumedDisplay;
  std::vector<NamedPose> poses;
};

Loaded load(const CalibrateSettings& s) {
  Loaded l;
  l.optics.display = loadDisplay(displayPathOrDefault(s.displayPath));
  l.optics.layout = computeLayout(l.optics.display);
  l.optics.camera = loadCameraDescription(s.camera);
  l.assumedDisplay = s.assumedDisplayPath.empty() ? l.optics.display.file : s.assumedDisplayPath;
  l.assumedPanel = s.assumedDisplayPath.empty() ? l.optics.display.panel : loadDisplay(s.assumedDisplayPath).panel;
  l.poses = selectPoses(s, s.distanceMm > 0.0 ? s.distanceMm : l.optics.camera.distanceMm);
  return l;
}

void makePatchSets(const CalibrateSettings& s, CalibrateResult& r) {
  r.colorChecker = colorCheckerPatches();
  r.grid = driveGrid(s.gridLevels);
  r.holdIn = holdOutInGamut(r.path.panel, r.path.drive.exposure, s.holdOutInGamut, s.seed, s.fieldSpace);
  r.holdOut = holdOutOutOfGamut(r.path.panel, r.path.drive.exposure, s.holdOutOutOfGamut, s.seed);
  if (!s.patchCsv.empty()) r.userPatches = readPatchCsv(s.patchCsv);
}

// Renders a few patches directly and compares them with the linear model of the first pose.
double directCheck(const Loaded& l, const CalibrateSettings& s, const PoseChain& chain) {
  const Vec3d drives[] = {{0.3, 0.6, 0.2}, {0.9, 0.1, 0.5}, {0.05, 0.4, 0.95}, {1, 1, 1}, {0.5, 0.5, 0.5}};
  double worst = 0.0;
  for (int i = 0; i < std::min(s.directChecks, 5); ++i) {
    const FlatPatchMeasurement m = renderFlatPatch(l.optics, chain.response().pose, drives[i], chain.response().measured, s.render);
    const Vec3d xyz = chain.linearXyz(drives[i]), rgb = chain.linearCameraRgb(drives[i]);
    worst = std::max({worst, glm::length(m.xyz - xyz) / glm::length(xyz), glm::length(m.cameraRgb - rgb) / glm::length(rgb)});
  }
  return worst;
}

std::vector<const PatchSet*> holdOutSets(const CalibrateResult& r) {
  std::vector<const PatchSet*> sets = {&r.holdIn, &r.holdOut};
  if (!r.userPatches.patches.empty()) sets.push_back(&r.userPatches);
  return sets;
}

void fitAndVerify(const CalibrateSettings& s, CalibrateResult& r) {
  std::vector<const PoseChain*> all;
  for (const PoseChain& c : r.chains) all.push_back(&c);
  const auto sets = holdOutSets(r);
  const FieldToDrive uncal = r.path.uncalibrated();
  for (const PoseChain& c : r.chains) r.uncalibrated.push_back(verify(r.path, uncal, c, sets, "none", ""));
  for (CorrectionKind kind : allCorrectionKinds()) {
    CorrectionReport rep;
    rep.name = correctionName(kind);
    rep.allPoses = fitPanelCorrection(kind, all, uncal, r.grid, s.lutSize);
    for (const PoseChain& c : r.chains) {
      rep.rows.push_back(verify(r.path, r.path.corrected(rep.allPoses), c, sets, rep.name, "all poses"));
      if (r.chains.size() > 1) {
        auto own = fitPanelCorrection(kind, {&c}, uncal, r.grid, s.lutSize);
        rep.rows.push_back(verify(r.path, r.path.corrected(own), c, sets, rep.name, "this pose"));
      }
    }
    r.corrections.push_back(rep);
  }
}

void choose(const CalibrateSettings& s, CalibrateResult& r) {
  const CorrectionReport* best = nullptr;
  for (const CorrectionReport& c : r.corrections)
    if (s.correction == c.name || (s.correction == "auto" && (!best || c.rows[0].inGamut.mean < best->rows[0].inGamut.mean)))
      best = &c;
  r.chosen = best->name;
  r.exported = exportedLut(best->name, best->allPoses, s.lutSize);
}

void fitCameraSide(CalibrateResult& r) {
  std::vector<const PoseChain*> all;
  for (const PoseChain& c : r.chains) all.push_back(&c);
  const auto sets = holdOutSets(r);
  Json j = Json::object();
  j["sensor"] = r.path.sensor.name();
  for (const PoseChain& c : r.chains) j["sensor_3x3"][c.name()] = deJson(cameraSideError(r.path, c, nullptr, sets));
  for (CorrectionKind kind : {CorrectionKind::Matrix, CorrectionKind::RootPolynomial}) {
    auto model = fitCameraCorrection(kind, all, r.grid);
    Json m{{"parameters", model->parameters()}};
    for (const PoseChain& c : r.chains) m["holdout"][c.name()] = deJson(cameraSideError(r.path, c, model.get(), sets));
    j[correctionName(kind)] = m;
  }
  r.cameraSide = j;
}

}  // namespace

namespace {

Json verificationJson(const VerificationRow& v) {
  return Json{{"pose", v.pose},
              {"correction", v.correction},
              {"scope", v.scope},
              {"in_gamut", deJson(v.inGamut)},
              {"out_of_gamut", deJson(v.outOfGamut)},
              {"out_of_gamut_mapping", deJson(v.outOfGamutMapping)},
              {"outside_assumed_gamut", deJson(v.outsideAssumedGamut)},
              {"camera_in_gamut", deJson(v.cameraInGamut)}};
}

// holdout.in_gamut.de2000_{mean,p95,max}_{before,after}: the study's headline keys.
Json beforeAfter(const DeltaESummary& before, const DeltaESummary& after) {
  return Json{{"count", after.count},
              {"de2000_mean_before", before.mean},
              {"de2000_p95_before", before.p95},
              {"de2000_max_before", before.max},
              {"de2000_mean_after", after.mean},
              {"de2000_p95_after", after.p95},
              {"de2000_max_after", after.max}};
}

Json holdoutJson(const CalibrateResult& r, const std::vector<VerificationRow>& exported) {
  Json h{{"correction", r.chosen}, {"scope", "all poses"}};
  for (size_t i = 0; i < r.chains.size(); ++i) {
    Json pose{{"in_gamut", beforeAfter(r.uncalibrated[i].inGamut, exported[i].inGamut)},
              {"out_of_gamut", beforeAfter(r.uncalibrated[i].outOfGamut, exported[i].outOfGamut)},
              {"out_of_gamut_mapping", deJson(r.uncalibrated[i].outOfGamutMapping)},
              {"outside_assumed_gamut", beforeAfter(r.uncalibrated[i].outsideAssumedGamut, exported[i].outsideAssumedGamut)},
              {"label", r.chains[i].response().pose.label}};
    if (i == 0) h["in_gamut"] = pose["in_gamut"], h["out_of_gamut"] = pose["out_of_gamut"], h["pose"] = r.chains[i].name();
    h["per_pose"][r.chains[i].name()] = pose;
  }
  return h;
}

Json poseJson(const PoseChain& c) {
  const PoseResponse& p = c.response();
  Json gamut = Json::array();
  for (int k = 0; k < 3; ++k) gamut.push_back(xyJson(p.xyzPerDrive[k]));
  return Json{{"label", p.pose.label},          {"rot_h_deg", p.pose.pose.rotHDeg},
              {"rot_v_deg", p.pose.pose.rotVDeg}, {"distance_mm", p.pose.pose.distanceMm},
              {"xyz_per_drive", matrixRows(p.xyzPerDrive)}, {"camera_rgb_per_drive", matrixRows(p.cameraPerDrive)},
              {"white_Y", c.whiteY()},          {"primaries_xy", gamut},
              {"white_xy", xyJson(p.xyzPerDrive * Vec3d(1.0))}, {"pixels_measured", p.pixels},
              {"pixels_on_display", p.displayPixels}, {"seconds", p.seconds}};
}

Json stagesJson(const std::vector<StageRow>& rows, std::string& dominant) {
  Json j = Json::array();
  double worst = -1.0;
  for (const StageRow& s : rows) {
    j.push_back({{"stage", s.stage}, {"pose", s.pose}, {"note", s.note}, {"in_default_chain", s.inDefaultChain},
                 {"de2000", deJson(s.colorimetric)}});
    // The colorimetric chain's stages (the camera's metamerism is reported beside them).
    if (s.inDefaultChain && s.stage.rfind("whole chain", 0) != 0 && s.stage != "camera metamerism" &&
        s.colorimetric.mean > worst)
      worst = s.colorimetric.mean, dominant = s.stage + (s.pose.empty() ? "" : " (" + s.pose + ")");
  }
  return j;
}

Json patchesJson(const CalibrateResult& r, const PoseChain& c, const PatchSet& set) {
  const auto before = measureSet(r, r.path.uncalibrated(), c, set);
  const auto after = measureSet(r, r.path.corrected(r.exported), c, set);
  Json j = Json::array();
  for (size_t i = 0; i < before.size(); ++i) {
    auto v = [](const Vec3d& x) { return Json{x.x, x.y, x.z}; };
    j.push_back({{"name", before[i].name}, {"in_gamut", before[i].inGamut}, {"target_xyz", v(before[i].target)},
                 {"before_xyz", v(before[i].shown)}, {"after_xyz", v(after[i].shown)},
                 {"camera_target_xyz", v(before[i].cameraTarget)}, {"camera_before_xyz", v(before[i].cameraShown)},
                 {"camera_after_xyz", v(after[i].cameraShown)}, {"de2000_before", before[i].deltaE},
                 {"de2000_after", after[i].deltaE}, {"camera_de2000_before", before[i].cameraDeltaE},
                 {"camera_de2000_after", after[i].cameraDeltaE}});
  }
  return j;
}

Json settingsJson(const CalibrateSettings& s, const ColourPath& path, const Loaded& l) {
  return Json{{"display", l.optics.display.file},  {"display_name", l.optics.display.name},
              {"assumed_display", l.assumedDisplay},
              {"camera", l.optics.camera.name},    {"angle_deg", s.angleDeg},
              {"field_space", s.fieldSpace},       {"white_balance", s.whiteBalanceD65 ? "d65" : "none"},
              {"gamut", gamutName(s.gamut)},       {"exposure", path.drive.exposure},
              {"grid_levels", s.gridLevels},       {"holdout", s.holdOutInGamut},
              {"holdout_out_of_gamut", s.holdOutOutOfGamut}, {"seed", s.seed},
              {"lut_size", s.lutSize},             {"panel_bits", s.panelBits},
              {"panel_eotf", path.input.eotf.name()}, {"width", s.render.width},
              {"spp", s.render.view.spp},          {"interior_fraction", s.render.interiorFraction},
              {"trim_percent", s.render.trimPercent}, {"patches", s.patchCsv},
              {"direct_checks", s.directChecks}};
}

// The OCIO colour space reads linear Rec.709 (the config's reference): the same matrix as
// inim's drive (the panel's XYZ -> native drive, exposure and white gains) comes before the LUT.
OcioColourSpaceSettings ocioSpace(const ColourPath& path) {
  const FieldToDrive uncal = path.uncalibrated();
  const Vec3d gains(uncal.gains());
  glm::dmat3 g(0.0);
  for (int c = 0; c < 3; ++c) g[c][c] = gains[c];
  const glm::dmat3 m = g * path.panel.xyzToDrive() * glm::dmat3(ColorSystem::rec709ToXYZ());
  OcioColourSpaceSettings space;
  space.referenceToLutInput = std::array<double, 9>{};
  for (int row = 0; row < 3; ++row)
    for (int col = 0; col < 3; ++col) (*space.referenceToLutInput)[size_t(3 * row + col)] = m[col][row];
  return space;
}

// Each pose against the grade, through the exported correction (what a user ships).
Json gradeJson(const CalibrateSettings& s, CalibrateResult& r) {
  if (!(s.gradeMean > 0.0)) return Json{{"graded", false}};
  Json g{{"graded", true}, {"de2000_mean_at_most", s.gradeMean}, {"de2000_max_at_most", s.gradeMax}};
  for (const VerificationRow& v : r.exportedRows) {
    const bool pass = v.inGamut.mean <= s.gradeMean && v.inGamut.max <= s.gradeMax;
    g["per_pose"][v.pose] = {{"de2000_mean", v.inGamut.mean}, {"de2000_max", v.inGamut.max}, {"pass", pass}};
    if (!pass) r.failedPoses.push_back(v.pose);
  }
  g["pass"] = r.failedPoses.empty();
  return g;
}

Json panelJson(const PanelColor& p) {
  Json prim = Json::array();
  for (int c = 0; c < 3; ++c) prim.push_back({p.primaryXY(c).x, p.primaryXY(c).y});
  return Json{{"primaries_xy", prim}, {"white_xy", {p.whiteXY().x, p.whiteXY().y}}};
}

void writeTables(OutputSet& out, const fs::path& dir, const CalibrateResult& r) {
  std::vector<std::vector<std::string>> rows;
  for (const StageRow& s : r.stages)
    rows.push_back({s.stage, s.pose, formatNumber(s.colorimetric.mean, "%.4f"), formatNumber(s.colorimetric.p95, "%.4f"),
                    formatNumber(s.colorimetric.max, "%.4f"), s.inDefaultChain ? "yes" : "no", s.note});
  writeCsv(out.add((dir / "stages.csv").string()), {"stage", "pose", "de2000_mean", "de2000_p95", "de2000_max",
                                                    "in_default_chain", "note"}, rows);
  rows.clear();
  auto add = [&](const VerificationRow& v) {
    rows.push_back({v.pose, v.correction, v.scope, std::to_string(v.inGamut.count), formatNumber(v.inGamut.mean, "%.4f"),
                    formatNumber(v.inGamut.p95, "%.4f"), formatNumber(v.inGamut.max, "%.4f"), std::to_string(v.outOfGamut.count),
                    formatNumber(v.outOfGamut.mean, "%.4f"), formatNumber(v.outOfGamut.max, "%.4f"),
                    std::to_string(v.outsideAssumedGamut.count), formatNumber(v.outsideAssumedGamut.mean, "%.4f"),
                    formatNumber(v.outsideAssumedGamut.max, "%.4f")});
  };
  for (const VerificationRow& v : r.uncalibrated) add(v);
  for (const CorrectionReport& c : r.corrections)
    for (const VerificationRow& v : c.rows) add(v);
  for (const VerificationRow& v : r.exportedRows) add(v);
  writeCsv(out.add((dir / "verification.csv").string()),
           {"pose", "correction", "scope", "in_gamut_count", "in_gamut_mean", "in_gamut_p95", "in_gamut_max",
            "out_of_gamut_count", "out_of_gamut_mean", "out_of_gamut_max", "outside_assumed_gamut_count",
            "outside_assumed_gamut_mean", "outside_assumed_gamut_max"},
           rows);
}

}  // namespace

CalibrateResult runCalibration(const CalibrateSettings& s, const CalibrateObserver& observer, OutputSet* outputs) {
  validate(s);
  const Loaded l = load(s);
  CalibrateResult r;
  r.path = ColourPath{PanelColor(l.assumedPanel), PanelColor(l.optics.display.panel), {}, s.fieldSpace, PanelInput{l.optics.display.panel.eotf, s.panelBits},
                      l.optics.camera.sensor};
  representableInField(d65WhiteXyz(), s.fieldSpace);  // an unknown space fails here, before the renders
  r.path.drive = DriveSettings{calibrationExposure(r.path.panel), s.whiteBalanceD65, s.gamut, nullptr};
  makePatchSets(s, r);

  auto t = Clock::now();
  // Six renders per pose (three primaries, two sensors), two per direct check.
  const int directs = std::min(s.directChecks, 5);
  ProgressBar bar("calibrate", uint64_t(6 * l.poses.size() + 2 * size_t(directs)),
                  s.progress && ProgressBar::stderrIsTerminal());
  for (const NamedPose& pose : l.poses) {
    r.chains.emplace_back(characterisePose(l.optics, pose, s.render), r.path.input);
    bar.add(6);
    if (observer.poseDone) observer.poseDone(r.chains.back().response());
  }
  r.maxDirectCheckError = directCheck(l, s, r.chains.front());
  bar.add(uint64_t(2 * directs));
  bar.finish();
  r.characteriseSeconds = since(t);
  r.stages = stageTable(r.path, r.chains, r.colorChecker);
  t = Clock::now();
  fitAndVerify(s, r);
  fitCameraSide(r);
  choose(s, r);
  r.fitSeconds = since(t);

  t = Clock::now();
  std::vector<VerificationRow>& exported = r.exportedRows;
  const auto sets = holdOutSets(r);
  for (const PoseChain& c : r.chains)
    exported.push_back(verify(r.path, r.path.corrected(r.exported), c, sets, r.chosen + " (exported LUT)", "all poses"));
  std::string dominant;
  Json& j = r.json;
  j["settings"] = settingsJson(s, r.path, l);
  // The panel the EIAs are made for, and the one shown (they differ with --assumed-display).
  j["panel"] = panelJson(r.path.panel);
  j["shown_panel"] = panelJson(r.path.shownPanel);
  for (const PoseChain& c : r.chains) j["poses"][c.name()] = poseJson(c);
  j["pose_order"] = s.poses;
  j["stages"] = stagesJson(r.stages, dominant);
  j["dominant_stage"] = dominant;
  j["holdout"] = holdoutJson(r, exported);
  j["grade"] = gradeJson(s, r);
  for (const VerificationRow& v : r.uncalibrated) j["verification"].push_back(verificationJson(v));
  for (const CorrectionReport& c : r.corrections) {
    Json parameters = c.allPoses->parameters();
    if (parameters.contains("table")) parameters["table"] = "(" + std::to_string(s.lutSize) + "^3 nodes: the exported "
                                                            "panel_correction.cube when this model is chosen)";
    j["corrections"][c.name]["parameters"] = parameters;
    for (const VerificationRow& v : c.rows) j["verification"].push_back(verificationJson(v));
  }
  for (const VerificationRow& v : exported) j["verification"].push_back(verificationJson(v));
  j["chosen_correction"] = r.chosen;
  j["camera_side"] = r.cameraSide;
  j["direct_check_max_relative_error"] = r.maxDirectCheckError;
  for (const PoseChain& c : r.chains) j["colorchecker"][c.name()] = patchesJson(r, c, r.colorChecker);
  r.verifySeconds = since(t);
  j["seconds"] = {{"characterise", r.characteriseSeconds}, {"fit", r.fitSeconds}, {"verify", r.verifySeconds}};

  OutputSet own;
  OutputSet& out = outputs ? *outputs : own;
  const fs::path dir(s.outDir);
  r.files = exportCalibration(out, s.outDir, "panel_correction", *r.exported, ocioSpace(r.path));
  j["files"] = {{"cube", r.files.cube}, {"clf", r.files.clf}, {"ocio", r.files.config}};
  writeTables(out, dir, r);
  writeTextFile(out.add((dir / "calibration.json").string()), j.dump(2) + "\n");
  if (!outputs) out.commit();
  return r;
}

void parseGrade(const std::string& text, CalibrateSettings& s) {
  if (text == "off") {
    s.gradeMean = s.gradeMax = 0.0;
    return;
  }
  const size_t comma = text.find(',');
  char* end1 = nullptr;
  char* end2 = nullptr;
  const std::string a = text.substr(0, comma), b = comma == std::string::npos ? "" : text.substr(comma + 1);
  const double mean = std::strtod(a.c_str(), &end1), max = std::strtod(b.c_str(), &end2);
  if (comma == std::string::npos || a.empty() || b.empty() || *end1 || *end2 || !(mean > 0.0) || !(max >= mean) ||
      !std::isfinite(max))
    throw InputError("", "grade", "\"" + text + "\"", "MEAN,MAX in CIEDE2000 with MAX >= MEAN > 0 (e.g. 1,3), or off");
  s.gradeMean = mean, s.gradeMax = max;
}

std::string calibrationSummary(const CalibrateResult& r) {
  std::string t = "stages (ColorChecker, CIEDE2000 mean / p95 / max, one stage at a time):\n";
  for (const StageRow& s : r.stages)
    t += "  " + s.stage + (s.pose.empty() ? "" : " [" + s.pose + "]") + ": " + formatNumber(s.colorimetric.mean, "%.2f") +
         " / " + formatNumber(s.colorimetric.p95, "%.2f") + " / " + formatNumber(s.colorimetric.max, "%.2f") +
         (s.inDefaultChain ? "" : "  (not in this chain)") + "\n";
  t += "dominant stage of the colorimetric chain: " + r.json.value("dominant_stage", std::string()) + "\n";
  t += "hold-out in gamut (mean / p95 / max), before -> after (" + r.chosen + ", one correction for all poses):\n";
  const Json& h = r.json["holdout"]["per_pose"];
  for (const PoseChain& c : r.chains) {
    const Json& p = h[c.name()]["in_gamut"];
    t += "  " + c.response().pose.label + ": " + formatNumber(p["de2000_mean_before"].get<double>(), "%.2f") + " / " +
         formatNumber(p["de2000_p95_before"].get<double>(), "%.2f") + " / " + formatNumber(p["de2000_max_before"].get<double>(), "%.2f") +
         " -> " + formatNumber(p["de2000_mean_after"].get<double>(), "%.2f") + " / " +
         formatNumber(p["de2000_p95_after"].get<double>(), "%.2f") + " / " + formatNumber(p["de2000_max_after"].get<double>(), "%.2f") +
         " (" + std::to_string(p["count"].get<int>()) + " colours)\n";
  }
  if (r.json["settings"].value("direct_checks", 0) > 0)
    t += "direct renders against the linear chain model: max relative difference " +
         formatNumber(r.maxDirectCheckError, "%.2g") + "\n";
  t += "wrote " + r.files.cube + ", " + r.files.clf + ", " + r.files.config + "\n";
  const Json& g = r.json["grade"];
  if (g.value("graded", false)) {
    t += "grade (exported correction, in-gamut hold-out: mean <= " + formatNumber(g["de2000_mean_at_most"].get<double>()) +
         ", max <= " + formatNumber(g["de2000_max_at_most"].get<double>()) + "):";
    for (const auto& [pose, v] : g["per_pose"].items()) t += " " + pose + (v["pass"].get<bool>() ? " pass" : " FAIL");
    t += "\n";
  }
  return t;
}

std::string poseResponseText(const PoseResponse& p) {
  return formatText("pose %-7s %-7s %7lld px measured, %.1f s\n", p.pose.name.c_str(), p.pose.label.c_str(),
                    (long long)p.pixels, p.seconds);
}

}  // namespace inim
