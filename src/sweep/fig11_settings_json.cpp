#include "sweep/fig11_settings_json.h"

#include "core/error.h"
#include "core/settings_table.h"

namespace inim {

Fig11Settings sweepFig11Defaults() {
  Fig11Settings s;
  s.referenceEveryPixel = true;
  return s;
}

Json fig11SettingsJson(const Fig11Settings& s) {
  Json j;
  j["width"] = s.width;
  j["spp"] = s.spp;
  j["aperture_grid"] = s.apertureGrid;
  j["reference_spp"] = s.referenceSpp;
  j["eia_spp"] = s.eiaSpp;
  j["angle"] = s.angleDeg;
  j["distance_mm"] = s.distanceMm;
  j["seed"] = s.seed;
  j["mla"] = mlaKindName(s.mla);
  j["chief_rays"] = s.rays.chiefRays ? chiefRaysName(*s.rays.chiefRays) : "display";
  j["calibration"] = s.calibrationPath;
  j["budget"] = s.budget;
  j["budget_calibration"] = s.budgetCalibrationPath;
  j["budget_rungs"] = s.budgetRungs;
  j["budget_spp"] = s.budgetSpp;
  j["depth_error"] = s.depthError;
  j["poses"] = s.poses;
  j["reference_every_pixel"] = s.referenceEveryPixel;
  return j;
}

namespace {

// A number of the settings table's "fig11" (or general) entry, in its range.
double tableNumber(const JsonObject& o, const std::string& key, double fallback) {
  if (!o.has(key)) return fallback;
  const double v = o.number(key);
  if (const SettingInfo* info = findSetting(key, "fig11")) checkSettingRange(*info, v, o.file(), o.keyPath(key));
  return v;
}

int tableInteger(const JsonObject& o, const std::string& key, int fallback) {
  const double v = tableNumber(o, key, fallback);
  return o.has(key) ? o.integer(key) : int(v);
}

std::vector<std::string> names(const JsonObject& o, const std::string& key) {
  std::vector<std::string> out;
  if (!o.has(key)) return out;
  const Json& v = o.raw(key);
  if (!v.is_array()) o.fail(key, jsonValueText(v), "a list of names");
  for (const Json& e : v) {
    if (!e.is_string()) o.fail(key, jsonValueText(v), "a list of names");
    out.push_back(e.get<std::string>());
  }
  return out;
}

}  // namespace

Fig11Settings fig11SettingsFromJson(const JsonObject& o, const Fig11Settings& defaults) {
  Fig11Settings s = defaults;
  s.width = tableInteger(o, "width", s.width);
  s.spp = tableInteger(o, "spp", s.spp);
  s.apertureGrid = tableInteger(o, "aperture_grid", s.apertureGrid);
  s.referenceSpp = tableInteger(o, "reference_spp", s.referenceSpp);
  s.eiaSpp = tableInteger(o, "eia_spp", s.eiaSpp);
  s.angleDeg = tableNumber(o, "angle", s.angleDeg);
  if (o.has("distance_mm")) {  // raw: 0 (the camera's distance) is outside the files' range for distances
    const Json& v = o.raw("distance_mm");
    if (!v.is_number() || v.get<double>() < 0 || v.get<double>() > 1e6)
      o.fail("distance_mm", jsonValueText(v), "0 (the camera's) or a distance up to 1e6 mm");
    s.distanceMm = v.get<double>();
  }
  if (o.has("seed")) {
    const Json& v = o.raw("seed");
    if (!v.is_number_unsigned() && !(v.is_number_integer() && v.get<int64_t>() >= 0))
      o.fail("seed", jsonValueText(v), "a whole number 0 to 2^64-1");
    s.seed = v.get<uint64_t>();
  }
  s.mla = o.choice("mla", {"real", "ideal"}, "real") == "ideal" ? MlaKind::Ideal : MlaKind::Real;
  const std::string rays = o.choice("chief_rays", {"display", "pinhole", "traced"}, "display");
  if (rays != "display") s.rays.chiefRays = rays == "pinhole" ? ChiefRays::Pinhole : ChiefRays::Traced;
  s.calibrationPath = o.string("calibration", s.calibrationPath);
  s.budget = o.boolean("budget", s.budget);
  s.budgetCalibrationPath = o.string("budget_calibration", s.budgetCalibrationPath);
  s.budgetRungs = names(o, "budget_rungs");
  s.budgetSpp = tableInteger(o, "budget_spp", s.budgetSpp);
  s.depthError = o.boolean("depth_error", s.depthError);
  s.poses = names(o, "poses");
  s.referenceEveryPixel = o.boolean("reference_every_pixel", s.referenceEveryPixel);
  o.rejectUnknown();
  return s;
}

}  // namespace inim
