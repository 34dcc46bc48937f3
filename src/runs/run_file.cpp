#include "runs/run_file.h"

#include <cmath>
#include <cstdio>
#include <limits>

#include "core/error.h"
#include "core/format.h"
#include "core/json_config.h"
#include "core/settings_table.h"

namespace inim {

namespace {

bool finite(const Vec3d& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

}  // namespace

RunFile loadRunFile(const std::string& path) {
  Json j = readJsonFile(path);
  JsonObject o(j, path, "");
  RunFile r;
  r.file = path;
  if (o.has("placement")) {
    JsonObject p = o.object("placement");
    Placement pl;
    pl.source = path;
    if (p.has("scale") && p.has("field_units_per_mm"))
      p.fail("field_units_per_mm", jsonValueText(p.raw("field_units_per_mm")),
             "either \"scale\" (mm per field unit) or \"field_units_per_mm\", not both");
    if (p.has("scale")) {
      pl.scaleKey = p.keyPath("scale");
      pl.scale = p.raw("scale").is_number() ? Vec3d(p.number("scale")) : p.vec3("scale");
    } else if (p.has("field_units_per_mm")) {
      pl.scaleKey = p.keyPath("field_units_per_mm");
      const Json& s = p.raw("field_units_per_mm");
      Vec3d u = s.is_number() ? Vec3d(p.number("field_units_per_mm")) : p.vec3("field_units_per_mm");
      if (u.x == 0.0 || u.y == 0.0 || u.z == 0.0 || !finite(u))
        p.fail("field_units_per_mm", jsonValueText(s), "non-zero, finite field units per mm");
      pl.scale = 1.0 / u;
    }
    pl.rotateDeg = p.vec3("rotate_deg", Vec3d(0.0));
    pl.translateMm = p.vec3("translate_mm", Vec3d(0.0));
    if (pl.scaleKey == "scale") pl.scaleKey = p.keyPath("scale");
    p.rejectUnknown();
    (void)pl.toDisplay();  // singular scales are reported here, naming the run file
    r.placement = pl;
  }
  if (o.has("display")) r.display = o.path("display");
  if (o.has("scene")) r.scene = o.path("scene");
  if (o.has("calibration")) r.calibration = o.path("calibration");
  if (o.has("vcp_mm")) {
    double v = o.number("vcp_mm");
    if (!std::isfinite(v)) o.fail("vcp_mm", formatNumber(v), "a finite distance in mm");
    r.vcpMm = v;
  }
  if (o.has("viewing_distance_mm")) r.viewingDistanceMm = o.positive("viewing_distance_mm");
  if (o.has("layout")) r.layout = o.choice("layout", {"parallel", "toed-in", "lens-grid"});
  if (o.has("spp")) {
    r.spp = o.integer("spp", 1, std::numeric_limits<int>::max());
  }
  if (o.has("exposure")) {
    const Json& e = o.raw("exposure");
    if (e.is_number()) {
      double v = e.get<double>();
      if (!(v > 0.0) || !std::isfinite(v)) o.fail("exposure", jsonValueText(e), "a number > 0 or \"auto\"");
      char buf[64];
      std::snprintf(buf, sizeof buf, "%.17g", v);
      r.exposure = buf;
    } else {
      r.exposure = o.choice("exposure", {"auto"});
    }
  }
  if (o.has("gamut")) r.gamut = o.choice("gamut", {"clip", "desaturate"});
  if (o.has("white_balance")) r.whiteBalance = o.choice("white_balance", {"none", "d65"});
  if (o.has("triad_wavelengths")) {
    const Json& t = o.raw("triad_wavelengths");
    if (t.is_string()) {
      r.triadWavelengths = t.get<std::string>();
    } else {
      std::vector<double> v = o.numbers("triad_wavelengths");
      if (v.size() != 3) o.fail("triad_wavelengths", jsonValueText(t), "\"panel\", \"paper\" or [R, G, B] in nm");
      char buf[96];
      std::snprintf(buf, sizeof buf, "%.17g,%.17g,%.17g", v[0], v[1], v[2]);
      r.triadWavelengths = buf;
    }
  }
  if (o.has("seed")) {
    const Json& s = o.raw("seed");
    if (!s.is_number_unsigned()) o.fail("seed", jsonValueText(s), "a whole number >= 0");
    r.seed = s.get<uint64_t>();
  }
  o.rejectUnknown();
  return r;
}

LayoutOverride resolveLayout(const RunFile* run, const std::optional<std::string>& layout,
                             const std::optional<double>& viewingDistanceMm) {
  LayoutOverride lo;
  if (layout) lo.layout = layout, lo.layoutKey = settingFlag("layout");
  else if (run && run->layout) lo.layout = run->layout, lo.layoutKey = "layout (" + run->file + ")";
  if (viewingDistanceMm) lo.viewingDistanceMm = viewingDistanceMm, lo.distanceKey = settingFlag("viewing_distance_mm");
  else if (run && run->viewingDistanceMm)
    lo.viewingDistanceMm = run->viewingDistanceMm, lo.distanceKey = "viewing_distance_mm (" + run->file + ")";
  return lo;
}

}  // namespace inim
