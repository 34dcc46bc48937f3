#include "runs/eia_run.h"

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstdio>
#include <filesystem>
#include <future>

#include "calibration/calibration_file.h"
#include "core/error.h"
#include "core/format.h"
#include "core/output_file.h"
#include "core/file_kinds.h"
#include "core/progress.h"
#include "rays/pinhole_rays.h"
#include "triads/zemax_nsc_model.h"

namespace inim {

namespace {

// Checked before any work: every output's kind.
std::string checkOutputs(const EiaRunSettings& s) {
  requireFileKind(s.out, "out", {FileKind::Exr}, "an OpenEXR file name (.exr)");
  const std::string png = s.png.empty() ? std::filesystem::path(s.out).replace_extension(".png").string() : s.png;
  requireFileKind(png, "png", {FileKind::Png}, "a PNG file name (.png)");
  if (!s.preview.empty()) requireFileKind(s.preview, "preview", {FileKind::Png}, "a PNG file name (.png)");
  if (!s.sdf.empty()) requireFileKind(s.sdf, "sdf", {FileKind::Sdf, FileKind::Dat}, "a Zemax source file name (.sdf or .dat)");
  if (!s.zemaxModel.empty()) {
    requireFileKind(s.zemaxModel, "zemax_model", {FileKind::Zmx}, "a Zemax file name (.zmx)");
    if (s.sdf.empty())
      throw InputError("", "zemax_model", "\"" + s.zemaxModel + "\"", "--sdf as well (the model reads the SDF)");
  }
  return png;
}

// Each output to a temporary, written concurrently (EXR and PNG compression are single
// threaded), renamed into place together only when all succeeded.
void writeOutputs(const EiaRunSettings& s, EiaRunResult& r, const Field& field, const RaySet* realRays) {
  OutputSet outputs;
  const std::string exrTmp = outputs.add(s.out), pngTmp = outputs.add(r.png);
  const std::string previewTmp = s.preview.empty() ? "" : outputs.add(s.preview);
  const std::string sdfTmp = s.sdf.empty() ? "" : outputs.add(s.sdf);
  if (!s.preview.empty()) {
    PreviewSettings ps;
    ps.seed = s.synthesis.seed;
    r.preview = renderPlacementPreview(r.layout, field, r.placement.toDisplay(), s.synthesis.vcpMm, ps);
  }
  const Image& eia = r.synthesis.eia;
  std::vector<std::future<void>> writes;
  writes.push_back(std::async(std::launch::async, [&] { writeEiaExr(eia, r.synthesis.stats.exposureUsed, exrTmp); }));
  writes.push_back(std::async(std::launch::async, [&] { writeImage(encodeForPanel(eia, r.display.panel.eotf), pngTmp); }));
  if (!previewTmp.empty())
    writes.push_back(std::async(std::launch::async, [&] { writeImage(r.preview.image, previewTmp); }));
  if (!sdfTmp.empty()) {
    TriadOptions to;
    to.description = "inim triads: " + r.display.name + ", " + r.triadWavelengths.source;
    const bool bar = s.synthesis.progress && ProgressBar::stderrIsTerminal();
    ProgressBar progress("triads", uint64_t(r.layout.numRays()) * 3, bar);
    r.triads = writeTriadSdf(sdfTmp, realRays ? *realRays : generatePinholeRays(r.layout), r.synthesis.drive,
                             r.triadWavelengths, to, &progress);
    progress.finish();
    if (!s.zemaxModel.empty())
      writeZemaxNscModel(outputs.add(s.zemaxModel),
                         zemaxNscModelFor(r.layout, s.sdf, r.triads, r.triadWavelengths.nm, r.display.name));
  }
  for (auto& w : writes) w.get();  // rethrows a writer's failure (the temporaries are removed)
  outputs.commit();
}

}  // namespace

void checkQuerySampling(double vcpMm, int spp) {
  if (!std::isfinite(vcpMm)) throw InputError("", "vcp_mm", formatNumber(vcpMm), "a finite distance in mm");
  if (spp < 1) throw InputError("", "spp", std::to_string(spp), "a whole number >= 1");
}

void applyExposure(const std::string& text, SynthesisSettings& s) {
  if (text == "auto") {
    s.autoExposure = true;
    return;
  }
  char* end = nullptr;
  s.autoExposure = false;
  s.exposure = std::strtod(text.c_str(), &end);
  if (text.empty() || *end || !(s.exposure > 0.0) || !std::isfinite(s.exposure))
    throw InputError("", "exposure", "\"" + text + "\"", "a number > 0 or auto");
}

bool parseWhiteBalanceD65(const std::string& text) {
  if (text != "none" && text != "d65") throw InputError("", "white_balance", "\"" + text + "\"", "none or d65");
  return text == "d65";
}

EiaRunResult runEia(const EiaRunSettings& s, const std::function<void(const EiaRunResult&)>& loaded) {
  const auto t0 = std::chrono::steady_clock::now();
  EiaRunResult r;
  // The field first: a trained field carries its own default placement.
  LoadedField field;
  if (s.fieldColorsPath.empty()) field = loadField(s.fieldPath.empty() ? defaultScenePath() : s.fieldPath, s.fieldKey);
  SynthesisSettings synthesis = s.synthesis;
  r.placement = synthesis.placement = resolvePlacement(s.placement ? s.placement : field.placement, s.placementOverride);
  r.png = checkOutputs(s);
  if (!s.calibrationPath.empty()) {
    synthesis.correction = loadCalibration(s.calibrationPath, s.calibrationKey);
    r.calibration = describeCalibration(s.calibrationPath, *synthesis.correction);
  } else if (synthesis.correction) {
    r.calibration = synthesis.correction->name() + " (given in the settings)";
  }
  r.display = loadDisplay(displayPathOrDefault(s.displayPath));
  r.layout = applyLayoutOverride(r.display, s.layout);
  const DisplayRays rays = displayRaysFor(r.display, r.layout, s.rays, synthesis.progress);
  if (rays.rays) synthesis.displayRays = &*rays.rays, r.raysSummary = rays.summary;
  r.triadWavelengths = parseTriadWavelengths(r.display.panel, s.triadWavelengths, s.triadWavelengthsKey);
  if (!s.fieldColorsPath.empty())
    field = loadFieldColors(s.fieldColorsPath, synthesis.spp, size_t(r.layout.numRays()) * size_t(synthesis.spp),
                            s.colorsEncoding);
  r.fieldPath = field.path;
  r.fieldKind = field.kind;
  if (loaded) loaded(r);

  r.loadSeconds = secondsSince(t0);
  r.synthesis = synthesizeEia(r.layout, r.display.panel, *field.field, synthesis);
  const auto tw0 = std::chrono::steady_clock::now();
  writeOutputs(s, r, *field.field, rays.rays ? &*rays.rays : nullptr);
  r.writeSeconds = secondsSince(tw0);
  return r;
}

std::string setupText(const EiaRunResult& r, double vcpMm) {
  const Display& d = r.display;
  const EiLayout& L = r.layout;
  std::string t =
      L.isHex() ? formatText("display:     %s (%s layout, hex lattice: %d rows of %d EIs, %d px across the flats, g = %s "
                         "mm; panel %d x %d px)\n",
                         d.name.c_str(), layoutName(L.kind), L.eiRows, L.eiCols, d.eiWidthPx,
                         formatNumber(L.gapMm).c_str(), L.panelW, L.panelH)
                : formatText("display:     %s (%s layout, %d x %d EIs of %d x %d px, g = %s mm; panel %d x %d px)\n",
                         d.name.c_str(), layoutName(L.kind), L.eiCols, L.eiRows, L.eiW, L.eiH,
                         formatNumber(L.gapMm).c_str(), L.panelW, L.panelH);
  t += "field:       " + r.fieldPath + " (" + fieldKindName(r.fieldKind) + ")\n";
  t += "placement:   " + r.placement.describe() + "; VCP at z = " + formatNumber(vcpMm) + " mm\n";
  if (!r.raysSummary.empty()) t += "rays:        " + r.raysSummary + "\n";
  return t;
}

std::string summaryText(const EiaRunResult& r, const EiaRunSettings& s) {
  const std::string summary = summaryText(r.synthesis.stats, s.synthesis.gamut);
  std::string t;
  for (size_t pos = 0; pos < summary.size();) {
    const size_t nl = summary.find('\n', pos);
    const std::string line = summary.substr(pos, nl == std::string::npos ? std::string::npos : nl - pos + 1);
    if (line.rfind("warning:", 0) != 0) t += line;
    pos = nl == std::string::npos ? summary.size() : nl + 1;
  }
  t += "calibration: " + r.calibration + "\n";
  const Image& eia = r.synthesis.eia;
  t += formatText("wrote:       %s (%d x %d, %s), %s", s.out.c_str(), eia.width, eia.height,
              s.synthesis.aovs ? "R G B A Z" : "R G B", r.png.c_str());
  const PreviewResult& pv = r.preview;
  if (!s.preview.empty())
    t += formatText(", %s (%d lenslets: %d real, %d virtual, %d on the MLA plane, %d missed; scene crosses the MLA at %d)",
                s.preview.c_str(), pv.lenslets, pv.real, pv.virtualHits, pv.onPlane, pv.missed, pv.crossingLenslets);
  const TriadWavelengths& tw = r.triadWavelengths;
  if (!s.sdf.empty())
    t += formatText(", %s (%llu triad rays at %s/%s/%s nm)", s.sdf.c_str(), (unsigned long long)r.triads,
                formatNumber(tw.nm[0]).c_str(), formatNumber(tw.nm[1]).c_str(), formatNumber(tw.nm[2]).c_str());
  if (!s.zemaxModel.empty()) t += ", " + s.zemaxModel + " (Zemax NSC model reading it)";
  return t + "\n";
}

EiaRunSettings resolveEiaRun(EiaRunSettings e, const RunFile& run, const EiaGiven& g) {
  if (int(g.scene.has_value()) + int(g.field.has_value()) + int(!e.fieldColorsPath.empty()) > 1)
    throw InputError("", "--field", "more than one of --scene, --field, --field-colors", "one field source");
  resolveSetting(e.fieldPath, run.scene, g.scene ? g.scene : g.field);
  if (g.field) e.fieldKey = "field";
  e.placement = run.placement;
  e.placementOverride = g.placement;
  SynthesisSettings& s = e.synthesis;
  resolveSetting(s.vcpMm, run.vcpMm, g.vcpMm);
  resolveSetting(s.spp, run.spp, g.spp);
  checkQuerySampling(s.vcpMm, s.spp);
  resolveSetting(s.seed, run.seed, g.seed);
  if (const auto& text = chosenText(run.exposure, g.exposure)) try {
      applyExposure(*text, s);
    } catch (const InputError& err) {
      throw g.exposure ? err : err.withFile(run.file);  // a run file's value is named as the file spells it
    }
  if (const auto& text = chosenText(run.gamut, g.gamut)) s.gamut = parseGamut(*text);
  if (const auto& text = chosenText(run.whiteBalance, g.whiteBalance)) s.whiteBalanceD65 = parseWhiteBalanceD65(*text);
  resolveSetting(e.calibrationPath, run.calibration, g.calibration);
  if (!g.calibration && run.calibration) e.calibrationKey = "calibration (" + run.file + ")";
  resolveSetting(e.displayPath, run.display, g.display.display);
  e.layout = resolveLayout(&run, g.display.layout, g.display.viewingDistanceMm);
  resolveSetting(e.triadWavelengths, run.triadWavelengths, g.triads);
  if (!g.triads && run.triadWavelengths) e.triadWavelengthsKey = "triad_wavelengths (" + run.file + ")";
  return e;
}

}  // namespace inim
