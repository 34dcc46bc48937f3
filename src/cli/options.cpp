#include "cli/options.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

#include "core/format.h"
#include "core/parallel.h"

namespace inim::cli {

void addRunOptions(CLI::App* cmd, RunOptions& opts, std::function<void()> body) {
  cmd->add_option("--seed", opts.seed, "Random seed; output depends on it only (default: 1)");
  cmd->add_option("--threads", opts.threads, "Worker threads (0 = all cores)")->capture_default_str();
  cmd->callback([&opts, body = std::move(body)] {
    if (opts.threads < 0)
      throw InputError("", "threads", std::to_string(opts.threads), "a thread count >= 0 (0 = all cores)");
    ThreadLimit threads(opts.threads);
    body();
  });
}

void addDisplayOptions(CLI::App* cmd, DisplayArgs& a) {
  a.displayOpt = cmd->add_option("--display", a.display, "Display JSON (default: optics/displays/paper-prototype.json)");
  a.layoutOpt = cmd->add_option("--layout", a.layout, "EI layout: parallel, toed-in or lens-grid (default: the display's)");
  a.distanceOpt = cmd->add_option("--viewing-distance-mm", a.viewingDistanceMm, "Viewing distance D for toed-in");
}

LayoutOverride layoutOverride(const DisplayArgs& a, const RunFile* run) {
  // Errors about the display file name an override by where it came from: its flag, or the run file.
  LayoutOverride lo;
  if (a.layoutOpt->count()) lo.layout = a.layout, lo.layoutKey = flagForSetting("layout");
  else if (run && run->layout) lo.layout = *run->layout, lo.layoutKey = "layout (" + run->file + ")";
  if (a.distanceOpt->count())
    lo.viewingDistanceMm = a.viewingDistanceMm, lo.distanceKey = flagForSetting("viewing_distance_mm");
  else if (run && run->viewingDistanceMm)
    lo.viewingDistanceMm = *run->viewingDistanceMm, lo.distanceKey = "viewing_distance_mm (" + run->file + ")";
  return lo;
}

void addPlacementOptions(CLI::App* cmd, PlacementArgs& a) {
  cmd->add_option("--scale", a.scale,
                  "Placement scale, display mm per field unit: S or sx,sy,sz (analytic scenes are in mm: 1; the "
                  "paper's NeRF at 0.0075 units/mm: 133.33)");
  cmd->add_option("--rotate-deg", a.rotate, "Placement rotation rx,ry,rz (x, then y, then z), degrees");
  cmd->add_option("--translate-mm", a.translate, "Placement translation x,y,z in mm (applied last)");
}

PlacementOverride placementOverride(const PlacementArgs& a) {
  PlacementOverride o;
  if (!a.scale.empty()) o.scale = parseVec3(a.scale, "--scale", true);
  if (!a.rotate.empty()) o.rotateDeg = parseVec3(a.rotate, "--rotate-deg");
  if (!a.translate.empty()) o.translateMm = parseVec3(a.translate, "--translate-mm");
  return o;
}

void addRealLensOptions(CLI::App* cmd, RealLensArgs& a, const std::string& help) {
  a.onOpt = cmd->add_flag("--real-lens", a.on, help);
  a.modelOpt = cmd->add_option("--real-lens-ray", a.model,
                               "With --real-lens: centroid (the power centroid of each pixel's exit bundle through "
                               "its lenslet, default) or chief (the ray through the lenslet's aperture centre)");
  a.wavelengthOpt =
      cmd->add_option("--wavelength-nm", a.wavelengthNm, "With --real-lens: the wavelength, nm")->capture_default_str();
}

RealLensRayOptions realLensRayOptions(const RealLensArgs& a) {
  const bool modelGiven = a.modelOpt->count() > 0;
  if (!a.on && (modelGiven || a.wavelengthOpt->count()))
    throw InputError("", modelGiven ? "--real-lens-ray" : "--wavelength-nm",
                     modelGiven ? "\"" + a.model + "\"" : formatNumber(a.wavelengthNm),
                     "--real-lens as well (the pinhole model has no refraction)");
  RealLensRayOptions ro;
  if (!a.on) return ro;
  ro.model = parseRealLensRayModel(a.model, "--real-lens-ray");
  if (!(a.wavelengthNm >= 360.0 && a.wavelengthNm <= 830.0))
    throw InputError("", "--wavelength-nm", formatNumber(a.wavelengthNm), "a wavelength in 360-830 nm");
  ro.wavelengthNm = a.wavelengthNm;
  return ro;
}

std::string flagForSetting(const std::string& key) {
  // Setting keys as the library and run files spell them. Most are their flag in snake_case
  // ("vcp_mm" -> "--vcp-mm"); the rest are named by flags of other names.
  static const std::set<std::string> kSnakeCaseFlags = {
      "spp", "seed", "threads", "out", "png", "preview", "sdf", "eia", "in", "ei", "flux_scale", "width", "height",
      "field", "scene", "field_model", "display", "layout", "viewing_distance_mm", "gap_mm", "vcp_mm", "scale",
      "rotate_deg", "translate_mm", "exposure", "gamut", "white_balance", "calibration", "triad_wavelengths",
      "real_lens_ray", "wavelength_nm", "camera", "camera_model", "distance_mm", "rot_h_deg", "rot_v_deg",
      "focus_mm", "estimator", "spectral", "wavelength_nodes", "background", "emission_cos_n", "mla",
      "reference_spp", "eia_spp", "fov", "aperture", "max_depth", "integrator", "resolutions", "stage_starts",
      "holdout_every", "elevation_deg", "target", "space", "de_map", "eye", "look_at", "up", "poses", "field_space",
      "correction", "grid_levels", "holdout", "holdout_out_of_gamut", "budget_rungs", "budget_calibration",
      "budget_spp", "eia_exposure", "lut_size", "panel_bits", "direct_checks"};
  static const std::map<std::string, std::string> kOtherFlags = {
      {"width/height", "--width/--height"}, {"panel_estimator", "--estimator"}, {"background_y", "--background"},
      {"cos_exponent", "--emission-cos-n"}, {"angle_deg", "--angle"}, {"hfov_deg", "--fov"},
      {"aperture_mm", "--aperture"}, {"focus_distance_mm", "--focus"}};
  if (auto it = kOtherFlags.find(key); it != kOtherFlags.end()) return it->second;
  if (!kSnakeCaseFlags.count(key)) return key;
  std::string flag = "--" + key;
  std::replace(flag.begin(), flag.end(), '_', '-');
  return flag;
}

InputError asCommandLineError(const InputError& e) {
  // An error about a file keeps the file's own key, unless the file is the setting's value or
  // the key is a setting that no file holds (how a dataset is split).
  static const std::set<std::string> kSettingsAboutAFile = {"holdout_every"};
  if (!e.file().empty() && e.value() != "\"" + e.file() + "\"" && !kSettingsAboutAFile.count(e.key())) return e;
  const std::string flag = flagForSetting(e.key());
  return flag == e.key() ? e : InputError(e.file(), flag, e.value(), e.expected());
}

}  // namespace inim::cli
