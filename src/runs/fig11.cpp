#include "runs/fig11.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <stdexcept>

#include <tbb/task_group.h>

#include "display_view/reference_cache.h"
#include "analysis/band_limit.h"
#include "analysis/contact_sheet.h"
#include "analysis/plot.h"
#include "calibration/calibration_file.h"
#include "camera/camera_config.h"
#include "core/error.h"
#include "core/format.h"
#include "core/output_file.h"
#include "display/display.h"
#include "display/ei_layout.h"
#include "runs/fig11_depth.h"
#include "runs/pose_comparison.h"
#include "field_files/field_factory.h"
#include "synthesis/eia_correction.h"
#include "synthesis/eia_synthesis.h"
#include "display_view/reference_renderer.h"
#include "display_view/estimators/quadrature_tables.h"
#include "display_view/view_camera.h"
#include "display_view/view_image.h"
#include "display_view/view_renderer.h"

namespace fs = std::filesystem;

namespace inim {

namespace {

void validate(const Fig11Settings& s) {
  for (auto [v, key] : {std::pair{s.spp, "spp"}, {s.referenceSpp, "reference_spp"}, {s.eiaSpp, "eia_spp"},
                        {s.budgetSpp, "budget_spp"},
                        {s.width, "width"}})
    if (v < 1) throw InputError("", key, std::to_string(v), "a whole number >= 1");
  if (!(s.angleDeg >= 0.0 && s.angleDeg < 60.0))
    throw InputError("", "angle_deg", std::to_string(s.angleDeg), "an angle in [0, 60) degrees");
}

// Everything a run reads, loaded before any work so that every error comes first.
struct Inputs {
  Display display;
  EiLayout layout;
  LoadedField field;
  std::shared_ptr<const ColourModel> calibration;  // null: none
  std::shared_ptr<const ColourModel> budgetCalibration;  // the budget's calibration rung, when given
  DisplayRays rays;  // the EIA's display rays (none: the pinhole rays)
  CameraDescription camera;
  Placement placement;
  Transform fieldToDisplay;
  std::string fieldKey;  // the references' cache key of the field (display_view/reference_cache.h)
  double distanceMm = 0;
};

Inputs loadInputs(const Fig11Settings& s) {
  Inputs in;
  in.display = s.display ? *s.display : loadDisplay(displayPathOrDefault(s.displayPath));
  const std::vector<NamedPose> all = fig11Poses(s.angleDeg, 350.0);  // the names only
  for (const std::string& p : s.poses)
    if (std::none_of(all.begin(), all.end(), [&](const NamedPose& n) { return n.name == p; }))
      throw InputError("", "poses", "\"" + p + "\"", "centre, left, right, top or bottom");
  in.layout = computeLayout(in.display);
  in.rays = displayRaysFor(in.display, in.layout, s.rays, false);
  in.field = loadField(s.fieldPath.empty() ? defaultScenePath() : s.fieldPath, "field");
  if (!s.calibrationPath.empty()) in.calibration = loadCalibration(s.calibrationPath);
  if (s.budget && !s.budgetCalibrationPath.empty())
    in.budgetCalibration = loadCalibration(s.budgetCalibrationPath, "budget_calibration");
  if (s.budget && !s.budgetRungs.empty()) selectRungs(s.budgetRungs, &in.display);  // unknown names fail here
  in.camera = loadCameraDescription(s.camera);
  in.placement = resolvePlacement(in.field.placement, s.placement);
  in.fieldToDisplay = in.placement.toDisplay();
  in.fieldKey = fieldContentKey(in.field.path);
  in.distanceMm = s.distanceMm > 0.0 ? s.distanceMm : in.camera.distanceMm;
  return in;
}

void writeJson(const Json& j, const std::string& path) { writeTextFile(path, j.dump(2) + "\n"); }

std::optional<ViewPair>& sheetSlot(Fig11Views& sheet, const std::string& name) {
  if (name == "left") return sheet.left;
  if (name == "right") return sheet.right;
  if (name == "top") return sheet.top;
  if (name == "bottom") return sheet.bottom;
  return sheet.centre;
}

ViewCameraOptions cameraOptions(const Fig11Settings& s) {
  ViewCameraOptions co;
  co.width = s.width;
  return co;
}

// A pose's two renders, before they are compared.
struct PoseRenders {
  Fig11View view;
  std::unique_ptr<CameraModel> camera;
  ViewResult rec, ref;
  ReferenceDepth refDepth;
  PixelMask mask;
  std::shared_ptr<QuadratureTableCache> tables;  // the view's aperture tables, for the budget's rungs
  std::vector<std::pair<BudgetRung, Image>> rungViews;  // the budget's rungs rendered in the view's pass
};

// A run: the inputs, the synthesized display and the outputs being collected.
class Fig11Run {
 public:
  // `firstCamera`: the first pose's camera (made while the EIA is); the others are it moved.
  Fig11Run(const Fig11Settings& s, Inputs& in, const DisplayModel& dm, double refToCdM2, const BudgetScene* budget,
           std::unique_ptr<CameraModel> firstCamera)
      : s_(s), in_(in), dm_(dm), refToCdM2_(refToCdM2), budget_(budget), dir_(s.outDir),
        firstCamera_(std::move(firstCamera)) {
    if (budget_ && viewIsFullChain())
      carriedRungs_ = fullChainCompanions(*budget_, budgetRungList(), dm_.gapMm, dm_.panel->driveTable());
  }

  std::vector<PoseBudget> budgets;

  OutputSet outputs;
  Fig11Views sheet;
  Json metrics = Json::object();
  std::vector<std::vector<std::string>> rows;

  std::string out(const std::string& name) { return outputs.add((dir_ / name).string()); }

  // Left/right: the display turned about its vertical axis; top/bottom: about its horizontal
  // axis (display_view/display_pose.h fig11Poses, and its sign convention).
  PoseRenders renderPose(const NamedPose& p) const {
    PoseRenders r;
    Fig11View& v = r.view;
    v.name = p.name;
    v.label = p.label;
    v.pose = p.pose;
    r.camera = makeViewCamera(in_.camera, v.pose, cameraOptions(s_), firstCamera_.get());

    ViewSettings vs;  // the estimator and aperture grid of every view tool
    vs.spp = s_.spp;
    vs.apertureGrid = s_.apertureGrid;
    vs.seed = s_.seed;
    if (budget_) vs.tableCache = r.tables = std::make_shared<QuadratureTableCache>(*r.camera);
    renderViewAndRungs(r, vs);
    v.displayInView = r.rec.stats.displayInView();
    v.reconstructionSeconds = r.rec.stats.seconds;
    // The reference in full where it is compared (the mask and the band limit's reach), one
    // sample per pixel around that: pose_comparison.h.
    r.mask = displayMask(*r.camera, dm_.area);
    ReferenceSettings rs = referenceSettings(s_.seed);
    rs.depth = s_.depthError;
    r.ref = renderComparedReference(*in_.field.field, in_.fieldToDisplay, *r.camera, in_.camera.sensor, rs,
                                    s_.referenceEveryPixel ? PixelMask{} : r.mask, bandLimitOf(*r.camera));
    r.refDepth = takeDepthChannels(r.ref.image);  // the reference images stay RGB
    v.referenceSeconds = r.ref.stats.seconds;
    v.referenceCached = r.ref.cached;
    return r;
  }

  // The renders exposed alike, written, compared (metrics, band limit, depth, budget).
  Fig11View comparePose(const PoseRenders& r) {
    Fig11View v = r.view;
    const CameraModel* camera = r.camera.get();
    const PixelMask& mask = r.mask;
    const ReferenceDepth& refDepth = r.refDepth;
    const PoseImages img = exposeAlike(r.rec.image, r.ref.image, refToCdM2_, in_.camera.sensor);
    const Image limited = bandLimitedReference(img.refExposed, refDepth, bandLimitOf(*camera));
    writeImage(img.recExposed, out("view_" + v.name + ".exr"));
    writeImage(img.recSrgb, out("view_" + v.name + ".png"));
    writeImage(img.refExposed, out("reference_" + v.name + ".exr"));
    writeImage(img.refSrgb, out("reference_" + v.name + ".png"));
    if (mask.count() == 0) return v;
    CompareOptions copt;
    copt.spaceA = copt.spaceB = "srgb";
    std::vector<float> deltaE;  // per pixel, for the error map and the depth bins
    v.metrics =
        compareImages(img.refSrgb, img.recSrgb, copt, &mask, "reference_" + v.name, "view_" + v.name, &deltaE);
    v.hasMetrics = true;
    record(v, img, mask, deltaE);
    compareWithBandLimited(v, img, limited, refDepth, mask, *camera);
    v.depthBins = depth.addPose(v.name, v.label, {img.refExposed, img.recExposed, img.refSrgb, img.recSrgb}, refDepth,
                                mask, deltaE, metrics[v.name]);
    if (budget_) budgets.push_back(poseBudgetOf(v, r, img, limited));
    return v;
  }

 private:
  // The references' sample count, named as the user gives it (reference_spp).
  ReferenceSettings referenceSettings(uint64_t seed) const {
    ReferenceSettings rs;
    rs.spp = s_.referenceSpp;
    rs.sppKey = "reference_spp";
    rs.seed = seed;
    rs.fieldKey = s_.referenceCache ? in_.fieldKey : "";
    rs.cacheDir = s_.referenceCacheDir;
    return rs;
  }

  // The view, and with it (one pass: renderViews) the budget's rungs that differ from it in the
  // panel only, when the view is the budget's full chain.
  void renderViewAndRungs(PoseRenders& r, const ViewSettings& vs) const {
    std::vector<const PanelEmitter*> panels{dm_.panel.get()};
    for (const RungPanel& p : carriedRungs_) panels.push_back(p.panel.get());
    std::vector<ViewResult> views = renderViews(*r.camera, in_.camera.sensor, *dm_.mla, panels, dm_.area, vs);
    r.rec = std::move(views[0]);
    for (size_t k = 0; k < carriedRungs_.size(); ++k)
      r.rungViews.emplace_back(carriedRungs_[k].rung, std::move(views[k + 1].image));
  }

  bool viewIsFullChain() const { return !in_.calibration && s_.mla == MlaKind::Real && s_.budgetSpp == s_.spp; }
  std::vector<BudgetRung> budgetRungList() const {
    return s_.budgetRungs.empty() ? budgetRungs(&in_.display) : selectRungs(s_.budgetRungs, &in_.display);
  }

  // The view against the band-limited reference: metrics, and error against depth.
  void compareWithBandLimited(Fig11View& v, const PoseImages& img, const Image& limited, const ReferenceDepth& depth,
                              const PixelMask& mask, const CameraModel& camera) {
    CompareOptions copt;
    copt.spaceA = copt.spaceB = "srgb";
    const Image limitedSrgb = cameraRgbToSrgb(limited, in_.camera.sensor);
    std::vector<float> de;
    v.bandLimitedMetrics = compareImages(limitedSrgb, img.recSrgb, copt, &mask, "band-limited reference_" + v.name,
                                         "view_" + v.name, &de);
    Json& m = metrics[v.name];
    m["band_limited"] = metricsJson(v.bandLimitedMetrics);
    m["band_limited"]["filter"] = bandLimitJson(bandLimitOf(camera));
    if (!depth.present) return;
    v.depthBinsBandLimited = errorVsDepth(limited, img.recExposed, depth, &mask, {}, &de);
    m["depth_error_band_limited"] = depthBinsJson(v.depthBinsBandLimited);
  }

  BandLimit bandLimitOf(const CameraModel& camera) const {
    return inim::bandLimitOf(in_.layout.lensPitchMm, in_.display.panel.pixelPitchMm, in_.display.reconstructionGapMm,
                             in_.distanceMm, camera);
  }

  void record(const Fig11View& v, const PoseImages& img, const PixelMask& mask, const std::vector<float>& deltaE) {
    Json mj = metricsJson(v.metrics);
    mj["rot_h_deg"] = v.pose.rotHDeg;
    mj["rot_v_deg"] = v.pose.rotVDeg;
    mj["reconstruction_seconds"] = v.reconstructionSeconds;
    metrics[v.name] = mj;
    rows.push_back(metricsCsvRow(v.name, v.metrics));
    sheetSlot(sheet, v.name) = ViewPair{v.label, img.refSrgb, img.recSrgb, errorMap(deltaE, img, mask)};
  }

  // The budget's rungs at this pose, against the same reference and a second one (another
  // seed) for the noise floor; the run's own view is the full chain when it is one, and the
  // rungs rendered in its pass are reused.
  PoseBudget poseBudgetOf(const Fig11View& v, const PoseRenders& r, const PoseImages& img, const Image& limited) {
    const CameraModel& camera = *r.camera;
    const PixelMask& mask = r.mask;
    ReferenceSettings rs = referenceSettings(s_.seed + 1);
    rs.progress = false;
    if (!s_.referenceEveryPixel) {
      rs.fullSamples = &mask.on;  // the floor is measured on the mask only
      rs.sppElsewhere = 0;
    }
    const Image second = renderReference(*in_.field.field, in_.fieldToDisplay, camera, in_.camera.sensor, rs).image;
    const Image secondExposed = scaledImage(second, refToCdM2_ * img.exposure);
    std::vector<MadeRungView> made;
    if (viewIsFullChain()) made.push_back({fullChainRung(), &r.rec.image, ""});
    for (const auto& [rung, view] : r.rungViews) made.push_back({rung, &view, "rendered in one pass with the view"});
    PoseBudget b = poseBudget(*budget_, camera, img.refExposed, secondExposed, img.exposure, mask, budgetRungList(),
                              made, &limited, r.tables);
    b.pose = v.name;
    return b;
  }

  const Fig11Settings& s_;
  Inputs& in_;
  const DisplayModel& dm_;
  double refToCdM2_;
  const BudgetScene* budget_;
  std::vector<RungPanel> carriedRungs_;  // the budget's rungs the view's pass renders (their panels)
  fs::path dir_;
  // The first pose's camera: the others are it moved (makeViewCamera), its lens focused once.
  std::unique_ptr<CameraModel> firstCamera_;

 public:
  Fig11DepthError depth{outputs, dir_};  // after dir_: members are made in this order
};

// After a failure: the background work finished (its own failure dropped: the first one is thrown).
void waitQuietly(tbb::task_group& g) {
  try {
    g.wait();
  } catch (...) {
  }
}

// budget.json, budget.csv and the waterfall budget.png.
void writeBudget(Fig11Run& run, const Fig11Result& result) {
  Json j = Json::object();
  std::vector<std::vector<std::string>> rows;
  std::vector<std::string> labels;
  for (const PoseBudget& b : result.budgets) {
    j[b.pose] = poseBudgetJson(b);
    for (auto& r : budgetCsvRows(b)) rows.push_back(r);
    for (const Fig11View& v : result.views)
      if (v.name == b.pose) labels.push_back(v.label);
  }
  writeJson(j, run.out("budget.json"));
  writeCsv(run.out("budget.csv"), budgetCsvHeader(), rows);
  writeBudgetPlot(result.budgets, labels, run.out("budget.png"));
}

// How fig11 synthesizes its EIA: as `inim eia` does, with the run's calibration.
SynthesisSettings synthesisSettings(const Fig11Settings& s, const Inputs& in) {
  SynthesisSettings ss;
  ss.placement = in.placement;
  ss.spp = s.eiaSpp;
  ss.seed = s.seed;
  ss.correction = in.calibration;
  if (in.rays.rays) ss.displayRays = &*in.rays.rays;
  return ss;
}

// The poses asked for, in fig11Poses' order.
std::vector<NamedPose> selectPoses(const Fig11Settings& s, double distanceMm) {
  std::vector<NamedPose> poses;
  for (const NamedPose& p : fig11Poses(s.angleDeg, distanceMm))
    if (s.poses.empty() || std::find(s.poses.begin(), s.poses.end(), p.name) != s.poses.end()) poses.push_back(p);
  return poses;
}

// The EIA, as `inim eia` makes it, and meanwhile the first pose's camera (its lens focused, its
// exit pupil scanned: serial work).
SynthesisResult synthesizeWithFirstCamera(const Fig11Settings& s, const Inputs& in, const std::vector<NamedPose>& poses,
                                          std::unique_ptr<CameraModel>& firstCamera) {
  tbb::task_group background;
  if (!poses.empty())
    background.run([&] { firstCamera = makeViewCamera(in.camera, poses.front().pose, cameraOptions(s)); });
  std::optional<SynthesisResult> synthesized;
  try {
    synthesized = synthesizeEia(in.layout, in.display.panel, *in.field.field, synthesisSettings(s, in));
  } catch (...) {
    waitQuietly(background);
    throw;
  }
  background.wait();
  return std::move(*synthesized);
}

// The budget's EIAs: its ladder starts from the uncalibrated one; its calibration rung uses the
// run's calibration (the uncalibrated EIA then made again) or the budget's own (applied to the
// EIA made, which is exact: synthesis/eia_correction.h). `otherEia` holds the one made here.
BudgetScene budgetScene(const Fig11Settings& s, const Inputs& in, const Image& eia, std::optional<Image>& otherEia) {
  if (in.calibration) {
    SynthesisSettings ss = synthesisSettings(s, in);
    ss.correction = nullptr;
    otherEia = synthesizeEia(in.layout, in.display.panel, *in.field.field, ss).eia;
  } else if (in.budgetCalibration) {
    otherEia = correctedEia(in.layout, eia, *in.budgetCalibration);
  }
  const Image* calibrated = in.calibration ? &eia : (otherEia ? &*otherEia : nullptr);
  BudgetScene scene{&in.display, &in.layout, in.calibration ? &*otherEia : &eia, calibrated, &in.camera, {}};
  scene.view.spp = s.budgetSpp;
  scene.view.apertureGrid = s.apertureGrid;
  scene.view.seed = s.seed;
  return scene;
}

// Every pose rendered, then written and compared (mostly serial work) while the next one renders,
// one comparison at a time in pose order, so the outputs do not depend on it; the EIA is written
// while the first renders. Each pose is reported to `observer` as it is done.
void renderAndComparePoses(Fig11Run& run, const std::vector<NamedPose>& poses, const SynthesisResult& eia,
                           const Panel& panel, const Fig11Observer& observer, Fig11Result& result) {
  tbb::task_group background;
  std::vector<PoseRenders> renders(poses.size());
  std::vector<Fig11View> compared(poses.size());
  auto report = [&](size_t i) {
    result.views.push_back(std::move(compared[i]));
    renders[i] = PoseRenders{};
    if (observer.viewDone) observer.viewDone(result.views.back());
    if (observer.budgetDone && run.budgets.size() > result.budgets.size()) {
      result.budgets.push_back(run.budgets.back());
      observer.budgetDone(result.budgets.back());
    }
  };
  try {
    const std::string eiaExr = run.out("eia.exr"), eiaPng = run.out("eia.png");
    background.run([&] {
      writeEiaExr(eia.eia, eia.stats.exposureUsed, eiaExr);
      writeImage(encodeForPanel(eia.eia, panel.eotf), eiaPng);
    });
    for (size_t i = 0; i < poses.size(); ++i) {
      renders[i] = run.renderPose(poses[i]);
      background.wait();
      if (i > 0) report(i - 1);
      background.run([&, i] { compared[i] = run.comparePose(renders[i]); });
    }
    background.wait();
    if (!poses.empty()) report(poses.size() - 1);
  } catch (...) {
    background.cancel();
    waitQuietly(background);
    throw;
  }
  result.budgets = run.budgets;
}

// The contact sheet, the metrics and the depth figure; then every output lands together.
void writeSheetAndMetrics(Fig11Run& run, const Fig11Settings& s, const Inputs& in) {
  ContactSheetOptions cso;
  cso.maxImageWidth = s.sheetImageWidth;
  cso.heading = "inim fig11: " + fs::path(in.field.path).filename().string() + " on " + in.display.name + ", " +
                in.camera.name + " at " + std::to_string(int(std::lround(in.distanceMm))) + " mm, MLA " +
                mlaKindName(s.mla) + ", calibration " +
                (in.calibration ? fs::path(s.calibrationPath).filename().string() : std::string("none"));
  writeImage(composeFig11Sheet(run.sheet, cso, nullptr, "CIEDE2000 0-" + std::to_string(int(kErrorMapMax)) + " (viridis)"),
             run.out("contact_sheet.png"));
  run.metrics["calibration"] = s.calibrationPath.empty() ? std::string("none") : s.calibrationPath;
  writeJson(run.metrics, run.out("metrics.json"));
  writeCsv(run.out("metrics.csv"), metricsCsvHeader("view"), run.rows);
  run.depth.writeFigure(in.display);
  run.outputs.commit();
}

}  // namespace

Fig11Result runFig11(const Fig11Settings& s, const Fig11Observer& observer) {
  validate(s);
  Inputs in = loadInputs(s);
  Fig11Result result;
  result.fieldPath = in.field.path;
  if (in.calibration) result.calibration = describeCalibration(s.calibrationPath, *in.calibration);
  const std::vector<NamedPose> poses = selectPoses(s, in.distanceMm);

  // 1. The EIA, as `inim eia` makes it.
  std::unique_ptr<CameraModel> firstCamera;
  const SynthesisResult eia = synthesizeWithFirstCamera(s, in, poses, firstCamera);
  result.eiaWidth = eia.eia.width, result.eiaHeight = eia.eia.height, result.eiaSeconds = eia.stats.seconds;
  if (observer.eiaDone) observer.eiaDone(result);
  DisplayModel dm = makeDisplayModel(in.display, in.layout, eia.eia, "(synthesized EIA)", s.mla);
  std::optional<Image> otherEia;
  const BudgetScene scene = s.budget ? budgetScene(s, in, eia.eia, otherEia) : BudgetScene{};

  // 2. Five poses: reconstruction and reference through the same camera.
  Fig11Run run(s, in, dm, eia.stats.exposureUsed * in.display.panel.peakLuminanceCdM2, s.budget ? &scene : nullptr,
               std::move(firstCamera));
  renderAndComparePoses(run, poses, eia, in.display.panel, observer, result);
  if (s.budget) writeBudget(run, result);

  // 3. The contact sheet and the metrics; every output lands together.
  writeSheetAndMetrics(run, s, in);
  return result;
}

std::string fig11EiaText(const Fig11Result& r) {
  char buf[256];
  std::snprintf(buf, sizeof buf, "%-8s %-14s %9s %7s %9s %9s %8s %8s\n", "view", "pose", "PSNR dB", "SSIM", "dE mean",
                "dE p95", "rec s", "ref s");
  return "EIA:         " + std::to_string(r.eiaWidth) + " x " + std::to_string(r.eiaHeight) + " px from " + r.fieldPath +
         ", " + formatNumber(r.eiaSeconds, "%.2f") + " s\ncalibration: " + r.calibration + "\n" + buf;
}

std::string fig11ViewText(const Fig11View& v) {
  if (!v.hasMetrics) return "";
  const ImageMetrics& m = v.metrics;
  char buf[256];
  const std::string ref = v.referenceCached ? "cached" : formatNumber(v.referenceSeconds, "%.1f");
  std::snprintf(buf, sizeof buf, "%-8s %-14s %9s %7.4f %9.3f %9.3f %8.1f %8s\n", v.name.c_str(), v.label.c_str(),
                formatPsnr(m.psnrDb).c_str(), m.ssim, m.deltaE.mean, m.deltaE.p95, v.reconstructionSeconds, ref.c_str());
  return buf;
}

std::string fig11ViewWarnings(const Fig11View& v) {
  std::string w;
  if (!v.displayInView) w += "inim: warning: the display is out of view at " + v.pose.describe() + "\n";
  if (!v.hasMetrics) w += "inim: warning: the display is out of view at " + v.pose.describe() + "; no metrics\n";
  return w;
}

std::string fig11WrittenText(const Fig11Settings& s) {
  return "wrote:       " + s.outDir +
         "/{eia.exr,eia.png,view_*.exr|png,reference_*.exr|png,contact_sheet.png,metrics.json,metrics.csv" +
         (s.depthError ? ",depth_error_*.csv,reference_*_depth.exr,depth_error.png" : "") +
         (s.budget ? ",budget.json,budget.csv,budget.png" : "") + "}\n";
}

std::string fig11BudgetText(const PoseBudget& b) {
  return formatText("  budget %-7s %s\n", b.pose.c_str(), budgetLine(b).c_str());
}

}  // namespace inim
