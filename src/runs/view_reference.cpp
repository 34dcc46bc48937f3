#include "runs/view_reference.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <future>

#include "analysis/contact_sheet.h"
#include "analysis/csv.h"
#include "calibration/calibration_file.h"
#include "core/error.h"
#include "core/format.h"
#include "core/file_kinds.h"
#include "core/output_file.h"
#include "runs/pose_comparison.h"
#include "field_files/field_factory.h"
#include "synthesis/eia_correction.h"
#include "synthesis/eia_synthesis.h"
#include "display_view/reference_renderer.h"
#include "display_view/reference_cache.h"

namespace fs = std::filesystem;

namespace inim {

namespace {

// Everything the comparison reads besides the view's own inputs, loaded before any work.
struct ReferenceInputs {
  LoadedField field;
  Placement placement;
  double eiaExposure = 1.0;
  bool fromHeader = false;
  std::shared_ptr<const ColourModel> calibration;
  std::vector<BudgetRung> rungs;
};

// The EIA's drive per unit field luminance: given, else from its header.
double eiaExposureOf(const std::string& eiaPath, const std::optional<double>& given, bool& fromHeader) {
  if (given) {
    if (!(*given > 0.0) || !std::isfinite(*given))
      throw InputError("", "eia_exposure", formatNumber(*given), "an exposure factor > 0");
    return *given;
  }
  const std::optional<double> h =
      isFileKind(eiaPath, FileKind::Exr) ? readImageNumber(eiaPath, kEiaExposureHeader) : std::nullopt;
  if (!h)
    throw InputError(eiaPath, kEiaExposureHeader, "(absent)",
                     "the EIA's exposure, kept in the EXR header by inim eia and inim fig11; for another EIA "
                     "give --eia-exposure (the factor inim eia printed as \"exposure:\")");
  if (!(*h > 0.0) || !std::isfinite(*h)) throw InputError(eiaPath, kEiaExposureHeader, formatNumber(*h), "a factor > 0");
  fromHeader = true;
  return *h;
}

ReferenceInputs loadReferenceInputs(const ViewRunSettings& s, const ViewReferenceSettings& rs) {
  for (auto [v, key] : {std::pair{rs.referenceSpp, "reference_spp"}, {rs.budgetSpp, "budget_spp"}})
    if (v < 1) throw InputError("", key, std::to_string(v), "a whole number >= 1");
  ReferenceInputs in;
  in.rungs = rs.budgetRungs.empty() ? budgetRungs() : selectRungs(rs.budgetRungs);
  in.field = loadField(rs.fieldPath.empty() ? defaultScenePath() : rs.fieldPath, "scene");
  in.placement = resolvePlacement(rs.placement ? rs.placement : in.field.placement, rs.placementOverride);
  in.eiaExposure = eiaExposureOf(s.eiaPath, rs.eiaExposure, in.fromHeader);
  if (!rs.budgetCalibrationPath.empty()) in.calibration = loadCalibration(rs.budgetCalibrationPath, "budget_calibration");
  return in;
}

// The EIA as linear drive values (a PNG decoded through the panel's EOTF, as the emitter does).
Image linearEia(const Image& eia, bool encoded, const Panel& panel) {
  if (!encoded) return eia;
  Image out = eia;
  for (float& v : out.data) v = float(panel.eotf.decode(v));
  return out;
}

// The run's own view is the budget's full chain when it was rendered as the rungs are.
bool viewIsFullChain(const ViewRunSettings& s, const ViewReferenceSettings& rs) {
  return s.mla == MlaKind::Real && s.emitter.coverGlass && s.emitter.absolute && s.emitter.cosExponent == 0.0 &&
         rs.budgetSpp == s.view.spp && isFileKind(s.eiaPath, FileKind::Exr);
}

std::string sibling(const std::string& out, const std::string& suffix) {
  const fs::path p(out);
  return (p.parent_path() / (p.stem().string() + suffix)).string();
}

void writeJsonFile(const Json& j, const std::string& path) { writeTextFile(path, j.dump(2) + "\n"); }

// The metrics JSON of the view against its reference (and the band-limited reference, and by
// depth when the reference has depth).
Json viewMetricsJson(const ViewReferenceResult& r, const CameraSetup& cs, int referenceSpp, const BandLimit& band,
                     bool withDepth) {
  Json m = metricsJson(r.metrics);
  m["pose"] = cs.pose.describe();
  m["rot_h_deg"] = cs.pose.rotHDeg;
  m["rot_v_deg"] = cs.pose.rotVDeg;
  m["field"] = r.fieldPath;
  m["reference_spp"] = referenceSpp;
  m["eia_exposure"] = r.eiaExposure;
  m["eia_exposure_source"] = r.eiaExposureFromHeader ? "the EIA's header" : "given";
  m["exposure"] = r.exposure;
  m["band_limited"] = metricsJson(r.bandLimitedMetrics);
  m["band_limited"]["filter"] = bandLimitJson(band);
  if (withDepth) m["depth_error"] = depthBinsJson(r.depthBins);
  return m;
}

// What the view's budget compares with: its reference, exposed, and where it is compared.
struct BudgetReference {
  const ReferenceSettings& settings;  // the reference's render settings
  const PoseImages& img;
  const PixelMask& mask;
  const Image& bandLimited;
  double toCdM2 = 1.0;  // the reference's scale to the view's units before exposure
};

// The view's error budget: the noise floor's second reference (another seed, on the mask only,
// exposed like the first) and the rungs, reusing the view's render and the rungs its pass carried.
PoseBudget viewBudget(const ViewRunSettings& s, const ViewReferenceSettings& rs, const ReferenceInputs& in,
                      const ViewReferenceResult& r, const BudgetReference& ref, std::optional<Image>& calibrated,
                      const std::vector<RungPanel>& carried) {
  const CameraSetup& cs = r.view.camera;
  ReferenceSettings second = ref.settings;
  second.seed = ref.settings.seed + 1;
  second.progress = false;
  second.depth = false;
  second.fullSamples = &ref.mask.on;  // the floor is measured on the mask only
  second.sppElsewhere = 0;
  const Image secondRef = renderReference(*in.field.field, in.placement.toDisplay(), *cs.camera, cs.desc.sensor, second).image;
  const Image secondExposed = scaledImage(secondRef, ref.toCdM2 * ref.img.exposure);
  const Image eia = linearEia(*r.view.eia, isFileKind(s.eiaPath, FileKind::Png), r.view.display.panel);
  if (in.calibration && !calibrated) calibrated = correctedEia(r.view.layout, eia, *in.calibration);
  BudgetScene scene{&r.view.display, &r.view.layout, &eia, calibrated ? &*calibrated : nullptr, &cs.desc, s.view,
                    r.view.gapMm};
  scene.view.spp = rs.budgetSpp;
  scene.view.progress = false;
  std::vector<MadeRungView> made;
  if (viewIsFullChain(s, rs)) made.push_back({fullChainRung(), &r.view.render.image, ""});
  for (size_t k = 0; k < carried.size(); ++k)
    made.push_back({carried[k].rung, &r.view.carriedViews[k], "rendered in one pass with the view"});
  PoseBudget b = poseBudget(scene, *cs.camera, ref.img.refExposed, secondExposed, ref.img.exposure, ref.mask, in.rungs,
                            made, &ref.bandLimited, r.view.tables);
  b.pose = "view";
  return b;
}

}  // namespace

ViewReferenceResult runViewWithReference(const ViewRunSettings& s, const ViewReferenceSettings& rs,
                                         const std::function<void(const ViewRunResult&)>& loaded) {
  checkEiaPath(s.eiaPath);
  ReferenceInputs in = loadReferenceInputs(s, rs);
  ViewReferenceResult r;
  r.fieldPath = in.field.path;
  r.placement = in.placement;
  r.eiaExposure = in.eiaExposure;
  r.eiaExposureFromHeader = in.fromHeader;
  // The budget's rungs that differ from the view in the panel only are seen in its pass.
  std::optional<Image> calibrated;
  std::vector<RungPanel> carried;
  auto carry = [&](const ViewRunResult& v, const DisplayModel& dm) {
    std::vector<const PanelEmitter*> panels;
    in.rungs = rs.budgetRungs.empty() ? budgetRungs(&v.display) : selectRungs(rs.budgetRungs, &v.display);
    if (!rs.budget || !viewIsFullChain(s, rs)) return panels;
    if (in.calibration) calibrated = correctedEia(v.layout, *v.eia, *in.calibration);
    const BudgetScene scene{&v.display, &v.layout, v.eia.get(), calibrated ? &*calibrated : nullptr, &v.camera.desc,
                            s.view, v.gapMm};
    carried = fullChainCompanions(scene, in.rungs, v.gapMm, dm.panel->driveTable());
    for (const RungPanel& p : carried) panels.push_back(p.panel.get());
    return panels;
  };
  r.view = renderViewRun(s, loaded, carry);
  const CameraSetup& cs = r.view.camera;

  // The reference, with its depth, and a view-sized comparison as fig11 makes it.
  ReferenceSettings ref;
  ref.spp = rs.referenceSpp;
  ref.sppKey = "reference_spp";
  ref.seed = s.view.seed;
  ref.progress = s.view.progress;
  ref.depth = true;
  ref.fieldKey = fieldContentKey(in.field.path);
  const PixelMask mask = displayMask(*cs.camera, r.view.layout.activeArea());
  const BandLimit band = bandLimitOf(r.view.layout.lensPitchMm, r.view.display.panel.pixelPitchMm, r.view.gapMm,
                                     cs.pose.distanceMm, *cs.camera);
  ViewResult refRender =
      renderComparedReference(*in.field.field, in.placement.toDisplay(), *cs.camera, cs.desc.sensor, ref, mask, band);
  r.referenceSeconds = refRender.stats.seconds;
  r.referenceCached = refRender.cached;
  const ReferenceDepth depth = takeDepthChannels(refRender.image);
  const double peak = s.emitter.absolute ? r.view.display.panel.peakLuminanceCdM2 : 1.0;
  const double refToCdM2 = in.eiaExposure * peak;
  const PoseImages img = exposeAlike(r.view.render.image, refRender.image, refToCdM2, cs.desc.sensor, cs.exposure);
  r.exposure = img.exposure;

  OutputSet outputs;
  auto out = [&](const std::string& path) {
    r.written.push_back(path);
    return outputs.add(path);
  };
  writeImage(img.recExposed, out(s.camera.out));
  writeImage(img.recSrgb, out(cs.png));
  writeImage(img.refExposed, out(sibling(s.camera.out, "_reference.exr")));
  writeImage(img.refSrgb, out(sibling(s.camera.out, "_reference.png")));
  if (mask.count() == 0) {  // nothing to compare: the images only
    outputs.commit();
    return r;
  }

  CompareOptions copt;
  copt.spaceA = copt.spaceB = "srgb";
  std::vector<float> de;
  r.metrics = compareImages(img.refSrgb, img.recSrgb, copt, &mask, "reference", "view", &de);
  r.hasMetrics = true;
  const Image limited = bandLimitedReference(img.refExposed, depth, band);
  r.bandLimitedMetrics = compareImages(cameraRgbToSrgb(limited, cs.desc.sensor), img.recSrgb, copt, &mask,
                                       "band-limited reference", "view");
  if (depth.present) r.depthBins = errorVsDepth(img.refExposed, img.recExposed, depth, &mask, {}, &de);
  writeImage(errorMap(de, img, mask), out(sibling(s.camera.out, "_error.png")));

  const Json m = viewMetricsJson(r, cs, rs.referenceSpp, band, depth.present);

  if (rs.budget) {
    PoseBudget b = viewBudget(s, rs, in, r, {ref, img, mask, limited, refToCdM2}, calibrated, carried);
    Json bj = Json::object();
    bj["view"] = poseBudgetJson(b);
    bj["view"]["pose"] = cs.pose.describe();
    writeJsonFile(bj, out(sibling(s.camera.out, "_budget.json")));
    writeCsv(out(sibling(s.camera.out, "_budget.csv")), budgetCsvHeader(), budgetCsvRows(b));
    writeBudgetPlot({b}, {"H " + formatNumber(cs.pose.rotHDeg) + "°, V " + formatNumber(cs.pose.rotVDeg) + "°"}, out(sibling(s.camera.out, "_budget.png")));
    r.budget = std::move(b);
  }
  writeJsonFile(m, out(sibling(s.camera.out, "_metrics.json")));
  outputs.commit();
  return r;
}

std::string comparisonText(const ViewReferenceResult& r) {
  const std::string seconds = r.referenceCached ? "from the reference cache\n"
                                                : formatNumber(r.referenceSeconds, "%.2f") + " s\n";
  std::string text = "reference:   " + r.fieldPath + "; placement " + r.placement.describe() + "; EIA exposure " +
                     formatNumber(r.eiaExposure) + " (" + (r.eiaExposureFromHeader ? "from its header" : "given") +
                     "); " + seconds;
  if (!r.hasMetrics) return text;
  char buf[256];
  for (const auto& [what, m] : {std::pair{"against:     reference", &r.metrics},
                                {"             band-limited", &r.bandLimitedMetrics}}) {
    std::snprintf(buf, sizeof buf, "%s: PSNR %s dB, SSIM %.4f, CIEDE2000 mean %.3f, p95 %.3f\n", what,
                  formatPsnr(m->psnrDb).c_str(), m->ssim, m->deltaE.mean, m->deltaE.p95);
    text += buf;
  }
  if (r.budget) text += "budget:      " + budgetLine(*r.budget) + "\n";
  text += "exposure:    " + formatNumber(r.exposure) + " (both images)\nwrote:       ";
  for (size_t i = 0; i < r.written.size(); ++i) text += (i ? ", " : "") + r.written[i];
  return text + "\n";
}

std::string comparisonWarnings(const ViewReferenceResult& r) {
  return outOfViewWarning(r.view) + (r.hasMetrics ? "" : "inim: warning: no pixel sees the display; no metrics\n");
}

}  // namespace inim
