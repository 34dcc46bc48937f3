#include "runs/camera_run.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cmath>
#include <filesystem>
#include <future>

#include "display_view/reference_cache.h"
#include "display/gap_range.h"
#include "core/error.h"
#include "core/format.h"
#include "core/file_kinds.h"
#include "core/output_file.h"
#include "display/display.h"
#include "field_files/field_factory.h"
#include "display_view/estimators/quadrature_tables.h"
#include "display_view/view_camera.h"

namespace inim {

namespace {

CameraSetup setupCamera(const CameraRunSettings& o, int spp) {
  if (spp < 1) throw InputError("", "spp", std::to_string(spp), "a whole number >= 1");
  requireFileKind(o.out, "out", {FileKind::Exr}, "an OpenEXR file name (.exr)");
  CameraSetup s;
  s.png = o.png.empty() ? std::filesystem::path(o.out).replace_extension(".png").string() : o.png;
  requireFileKind(s.png, "png", {FileKind::Png}, "a PNG file name (.png)");
  s.exposure = parseExposure(o.exposure, "exposure");
  for (auto [v, key] : {std::pair{o.width, "width"}, {o.height, "height"}})
    if (v < 0) throw InputError("", key, std::to_string(v), "a whole number of pixels >= 1");
  s.desc = loadCameraDescription(o.camera.empty() ? defaultCameraPath() : o.camera);
  s.pose.rotHDeg = o.rotHDeg;
  s.pose.rotVDeg = o.rotVDeg;
  s.pose.distanceMm = o.distanceMm.value_or(s.desc.distanceMm);
  if (!(s.pose.distanceMm > 0.0) || !std::isfinite(s.pose.distanceMm))
    throw InputError("", "distance_mm", formatNumber(s.pose.distanceMm), "a camera distance > 0 mm");
  ViewCameraOptions co;
  co.kind = o.model;
  co.width = o.width;
  co.height = o.height;
  co.focusMm = o.focusMm;
  if (o.focusMm < 0.0 || !std::isfinite(o.focusMm))
    throw InputError("", "focus_mm", formatNumber(o.focusMm), "a focus distance > 0 mm");
  try {
    s.camera = makeViewCamera(s.desc, s.pose, co);
  } catch (const InputError& e) {
    // A lens that cannot focus there: the focus or distance asked for is the cause, not the lens.
    if (e.key() != "focus_distance_mm" || !(o.focusMm > 0.0 || o.distanceMm)) throw;
    const bool focus = o.focusMm > 0.0;
    throw InputError("", focus ? "focus_mm" : "distance_mm", formatNumber(focus ? o.focusMm : s.pose.distanceMm),
                     e.expected() + " for " + s.desc.name);
  }
  return s;
}

// Writes the exposed EXR and the sRGB PNG together (temporaries renamed only when both
// succeed); returns the exposure factor.
double writeExposed(const Image& cameraRgb, const CameraSetup& cs, const std::string& out) {
  const double k = exposureFactor(cameraRgb, cs.desc.sensor, cs.exposure);
  const Image exposed = scaledImage(cameraRgb, k);
  OutputSet outputs;
  const std::string exrTmp = outputs.add(out), pngTmp = outputs.add(cs.png);
  auto exr = std::async(std::launch::async, [&] { writeImage(exposed, exrTmp); });
  writeImage(cameraRgbToSrgb(exposed, cs.desc.sensor), pngTmp);
  exr.get();
  outputs.commit();
  return k;
}

}  // namespace

void checkEiaPath(const std::string& path) {
  requireFileKind(path, "eia", {FileKind::Exr, FileKind::Png}, "an EIA image: linear EXR (or encoded PNG)");
  if (!std::filesystem::exists(path)) throw InputError(path, "eia", "\"" + path + "\"", "an existing EIA image");
}

namespace {

// The display model; a gap the MLA cannot take blames the gap given, or the display's own.
DisplayModel displayModelAtGap(const Display& d, const EiLayout& L, const Image& eia, const ViewRunSettings& s,
                               double gapMm, const EmitterSettings& es) {
  try {
    return makeDisplayModel(d, L, eia, s.eiaPath, s.mla, gapMm, es);
  } catch (const InputError& e) {
    if (e.key() != "gap_mm") throw;
    const std::string why = e.expected() + " (" + d.mla.name + ")";
    if (s.gapMm) throw InputError("", "gap_mm", e.value(), why);
    throw InputError(d.file, "reconstruction_gap_mm", e.value(), why);
  }
}

// The EIA, as drive values (a PNG is decoded through the panel's EOTF by the emitter).
Image readEia(const std::string& path) {
  checkEiaPath(path);
  try {
    return readImage(path, true);
  } catch (const InputError& e) {
    throw e.file().empty() ? e.withFile(path) : e;
  }
}

}  // namespace

ViewRunResult renderViewRun(const ViewRunSettings& s, const std::function<void(const ViewRunResult&)>& loaded,
                            const CarriedPanels& carried) {
  const auto t0 = std::chrono::steady_clock::now();
  checkEiaPath(s.eiaPath);
  ViewRunResult r;
  r.camera = setupCamera(s.camera, s.view.spp);
  if (!(s.view.backgroundY >= 0.0) || !std::isfinite(s.view.backgroundY))
    throw InputError("", "background", formatNumber(s.view.backgroundY), "a luminance >= 0");
  if (!(s.emitter.cosExponent >= 0.0) || !std::isfinite(s.emitter.cosExponent))
    throw InputError("", "emission_cos_n", formatNumber(s.emitter.cosExponent), "an exponent >= 0");
  r.display = loadDisplay(displayPathOrDefault(s.displayPath));
  const EiLayout L = applyLayoutOverride(r.display, s.layout);
  r.gapMm = s.gapMm.value_or(r.display.reconstructionGapMm);
  if (s.gapMm) checkGapMm(*s.gapMm, "", "gap_mm");
  r.eia = std::make_shared<const Image>(readEia(s.eiaPath));
  r.eiaWidth = r.eia->width, r.eiaHeight = r.eia->height;
  r.layout = L;
  EmitterSettings es = s.emitter;
  es.encoded = isFileKind(s.eiaPath, FileKind::Png);
  const DisplayModel dm = displayModelAtGap(r.display, L, *r.eia, s, r.gapMm, es);
  r.coverGlass = dm.panel->hasCoverGlass();
  if (loaded) loaded(r);
  r.loadSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::vector<const PanelEmitter*> panels{dm.panel.get()};
  if (carried)
    for (const PanelEmitter* p : carried(r, dm)) panels.push_back(p);
  ViewSettings view = s.view;
  if (!view.tableCache) view.tableCache = std::make_shared<QuadratureTableCache>(*r.camera.camera);
  r.tables = view.tableCache;
  std::vector<ViewResult> views = renderViews(*r.camera.camera, r.camera.desc.sensor, *dm.mla, panels, dm.area, view);
  r.render = std::move(views[0]);
  for (size_t k = 1; k < views.size(); ++k) r.carriedViews.push_back(std::move(views[k].image));
  return r;
}

ViewRunResult runView(const ViewRunSettings& s, const std::function<void(const ViewRunResult&)>& loaded) {
  ViewRunResult r = renderViewRun(s, loaded);
  r.exposureFactor = writeExposed(r.render.image, r.camera, s.camera.out);
  return r;
}

ViewSettings autoViewSettings() {
  ViewSettings view;
  applyEstimatorPolicy(view, "auto", false);
  return view;
}

void applyEstimatorPolicy(ViewSettings& view, const std::string& estimator, bool sppGiven) {
  if (estimator == "auto")
    view.panelEstimator =
        view.spectral == SpectralSampling::Primaries ? PanelEstimator::Quadrature : PanelEstimator::Footprint;
  else
    parsePanelEstimator(estimator, view.panelEstimator);
  if (view.panelEstimator == PanelEstimator::Quadrature && !sppGiven) view.spp = 1;
}

std::string summaryText(const ReferenceRunResult& r, const ReferenceSettings& reference, double totalSeconds) {
  char buf[400];
  const std::string render = r.render.cached ? "from the reference cache" : formatNumber(r.render.stats.seconds, "%.2f") + " s render";
  std::snprintf(buf, sizeof buf, "rendered:    %d spp, %s, %.2f s total; %llu rays, %llu hit the scene\n", reference.spp,
                render.c_str(), totalSeconds, (unsigned long long)r.render.stats.tracedRays,
                (unsigned long long)r.render.stats.emittingRays);
  return buf;
}

std::string loadedText(const ReferenceRunResult& r) {
  return "scene:       " + r.fieldPath + "; placement " + r.placement.describe() + "\n" + cameraText(r.camera);
}

std::string displayOutOfViewWarning(const ReferenceRunResult& r) {
  if (r.displayInView) return "";
  return "inim: warning: the display is out of the camera's view (" + r.camera.pose.describe() +
         "); the reference is rendered anyway\n";
}

std::string cameraText(const CameraSetup& cs) {
  return "camera:      " + cs.desc.name + "; " + cs.camera->describe() + "\nimage:       " +
         std::to_string(cs.camera->width()) + " x " + std::to_string(cs.camera->height()) + " px, pitch " +
         formatNumber(cs.camera->sensor().pitchMm * 1e3) + " um; pose " + cs.pose.describe() + "\n";
}

namespace {

std::string writtenText(double k, const CameraSetup& cs, const std::string& out) {
  return "exposure:    " + formatNumber(k) + (cs.exposure.automatic ? " (auto: 99th percentile -> 0.9)" : "") +
         "\nwrote:       " + out + ", " + cs.png + "\n";
}

}  // namespace

std::string writtenText(const ReferenceRunResult& r, const std::string& out) {
  return writtenText(r.exposureFactor, r.camera, out);
}
std::string writtenText(const ViewRunResult& r, const std::string& out) {
  return writtenText(r.exposureFactor, r.camera, out);
}

std::string loadedText(const ViewRunSettings& s, const ViewRunResult& r) {
  return "display:     " + r.display.name + " (g = " + formatNumber(r.gapMm) + " mm, " +
         (s.mla == MlaKind::Ideal ? "ideal thin-lens" : "real refracting") + " MLA" +
         (r.coverGlass ? ", cover glass" : "") + ")\neia:         " + s.eiaPath + " (" + std::to_string(r.eiaWidth) +
         " x " + std::to_string(r.eiaHeight) + " px)\n" + cameraText(r.camera);
}

std::string summaryText(const ViewRunResult& run, const ViewSettings& vs, double totalSeconds) {
  const ViewStats& st = run.render.stats;
  char buf[3][400];
  std::snprintf(buf[0], sizeof buf[0],
                "rendered:    %d spp, %s wavelengths (%d ray%s per sample%s), %.2f s render, %.2f s total "
                "(loading %.2f s)\n",
                vs.spp, spectralSamplingName(vs.spectral), st.raysPerSample, st.raysPerSample > 1 ? "s" : "",
                st.dispersive ? ", dispersive" : "", st.seconds, totalSeconds, run.loadSeconds);
  std::snprintf(buf[1], sizeof buf[1],
                "rays:        %llu traced, %llu on the display, %llu reached the panel, %llu on a subpixel; %llu "
                "pixels skipped (their tiles cannot see the display)\n",
                (unsigned long long)st.tracedRays, (unsigned long long)st.displayRays,
                (unsigned long long)st.panelRays, (unsigned long long)st.emittingRays,
                (unsigned long long)st.culledPixels);
  if (vs.panelEstimator == PanelEstimator::Quadrature)
    std::snprintf(buf[2], sizeof buf[2],
                  "estimator:   quadrature: %llu pixel pieces integrated (%llu strata cut by a lenslet border), "
                  "%llu pieces x primaries lost by the MLA, %llu fallbacks, %llu table/Jacobian rays\n",
                  (unsigned long long)st.quadrature.pieces, (unsigned long long)st.quadrature.splitStrata,
                  (unsigned long long)st.quadrature.lostPieces, (unsigned long long)st.quadrature.fallbacks,
                  (unsigned long long)st.quadrature.probeRays);
  else
    std::snprintf(buf[2], sizeof buf[2], "estimator:   %s\n", panelEstimatorName(vs.panelEstimator));
  return std::string(buf[0]) + buf[1] + buf[2];
}

ReferenceRunResult runReference(const ReferenceRunSettings& s,
                                const std::function<void(const ReferenceRunResult&)>& loaded) {
  ReferenceRunResult r;
  const LoadedField field = loadField(s.fieldPath.empty() ? defaultScenePath() : s.fieldPath, "scene");
  r.fieldPath = field.path;
  r.placement = resolvePlacement(s.placement ? s.placement : field.placement, s.placementOverride);
  const Transform toDisplay = r.placement.toDisplay();
  r.camera = setupCamera(s.camera, s.reference.spp);
  const Display d = loadDisplay(displayPathOrDefault(s.displayPath));
  const AreaMm area = computeLayout(d).activeArea();
  if (loaded) loaded(r);
  ReferenceSettings rs = s.reference;
  rs.fieldKey = fieldContentKey(field.path);
  r.render = renderReference(*field.field, toDisplay, *r.camera.camera, r.camera.desc.sensor, rs);
  r.exposureFactor = writeExposed(r.render.image, r.camera, s.camera.out);
  r.displayInView = displayCoverage(*r.camera.camera, area) > 0.0;
  return r;
}

std::string outOfViewWarning(const ViewRunResult& r) {
  if (r.render.stats.displayInView()) return "";
  return "inim: warning: the display is out of the camera's view (" + r.camera.pose.describe() +
         "): no camera ray reaches its active area; the image shows only the background\n";
}

std::string driveClampedWarning(const ViewRunResult& r, const std::string& eiaPath) {
  const Image& e = *r.eia;
  const bool named = e.channelIndex("R") >= 0 && e.channelIndex("G") >= 0 && e.channelIndex("B") >= 0;
  int64_t outside = 0;
  float lo = 0.0f, hi = 1.0f;
  for (int c = 0; c < 3 && c < e.numChannels(); ++c) {
    const int ch = named ? e.channelIndex(std::string(1, "RGB"[c])) : c;
    for (int y = 0; y < e.height; ++y)
      for (int x = 0; x < e.width; ++x) {
        const float d = e.at(x, y, ch);
        if (d >= 0.0f && d <= 1.0f) continue;
        ++outside, lo = std::min(lo, d), hi = std::max(hi, d);
      }
  }
  if (outside == 0) return "";
  return "inim: warning: " + eiaPath + ": " + std::to_string(outside) + " of " +
         std::to_string(int64_t(e.width) * e.height * 3) + " drive values are outside [0, 1] (from " +
         formatNumber(lo) + " to " + formatNumber(hi) + "); the panel shows them clamped\n";
}

}  // namespace inim
