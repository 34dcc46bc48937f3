#include "field/placement.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <limits>

#include "core/error.h"
#include "core/format.h"
#include "core/json_config.h"
#include "field/field.h"

namespace fs = std::filesystem;

namespace inim {

namespace {

std::string vecText(const Vec3d& v) { return formatNumber(v.x) + ", " + formatNumber(v.y) + ", " + formatNumber(v.z); }
bool finite(const Vec3d& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

}  // namespace

Transform Placement::toDisplay() const {
  const std::string file = source == "command line" ? "" : source;
  auto bad = [&](const std::string& key, const Vec3d& v, const std::string& expected) {
    throw InputError(file, key, "[" + vecText(v) + "]", expected);
  };
  if (!finite(scale) || scale.x == 0.0 || scale.y == 0.0 || scale.z == 0.0)
    bad(scaleKey, scale, "a non-zero, finite scale on every axis (a singular placement maps the field onto a plane)");
  if (!finite(rotateDeg)) bad(source == "command line" ? "rotate_deg" : "placement.rotate_deg", rotateDeg, "finite angles");
  if (!finite(translateMm))
    bad(source == "command line" ? "translate_mm" : "placement.translate_mm", translateMm, "a finite offset");
  try {
    return Transform::translate(translateMm) * Transform::rotateXYZ(rotateDeg) *
           Transform::scale(scale, scaleKey);
  } catch (const InputError& e) {
    throw e.withFile(file);
  }
}

bool Placement::isIdentity() const {
  return scale == Vec3d(1.0) && rotateDeg == Vec3d(0.0) && translateMm == Vec3d(0.0);
}

std::string Placement::describe() const {
  std::string s = scale.x == scale.y && scale.y == scale.z ? "scale " + formatNumber(scale.x) : "scale (" + vecText(scale) + ")";
  return s + " mm/unit, rotate (" + vecText(rotateDeg) + ") deg, translate (" + vecText(translateMm) + ") mm";
}

Placement resolvePlacement(const std::optional<Placement>& base, const PlacementOverride& given) {
  Placement p = base.value_or(Placement{});
  if (given.scale) p.scale = *given.scale, p.scaleKey = "scale", p.source = "command line";
  if (given.rotateDeg) p.rotateDeg = *given.rotateDeg, p.source = "command line";
  if (given.translateMm) p.translateMm = *given.translateMm, p.source = "command line";
  (void)p.toDisplay();
  return p;
}

Vec3d parseVec3(const std::string& text, const std::string& key, bool allowScalar) {
  std::vector<double> v;
  const char* p = text.c_str();
  bool ok = !text.empty();
  while (ok && *p) {
    char* end = nullptr;
    double x = std::strtod(p, &end);
    if (end == p || !std::isfinite(x)) {
      ok = false;
      break;
    }
    v.push_back(x);
    p = end;
    while (*p == ' ') ++p;
    if (*p == ',') {
      ++p;
      if (!*p) ok = false;
    } else if (*p) {
      ok = false;
    }
  }
  if (ok && v.size() == 3) return {v[0], v[1], v[2]};
  if (ok && allowScalar && v.size() == 1) return Vec3d(v[0]);
  throw InputError("", key, "\"" + text + "\"",
                   allowScalar ? "one number or three comma-separated numbers x,y,z"
                               : "three comma-separated numbers x,y,z");
}

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

bool boundsInFrame(const Field& field, const Transform& fieldToFrame, Point3d& lo, Point3d& hi) {
  Point3 flo, fhi;
  field.bounds(flo, fhi);
  if (!(flo.x <= fhi.x && flo.y <= fhi.y && flo.z <= fhi.z)) return false;
  lo = Point3d(std::numeric_limits<double>::infinity());
  hi = -lo;
  for (int c = 0; c < 8; ++c) {
    const Point3d p = fieldToFrame.point(Point3d((c & 1) ? fhi.x : flo.x, (c & 2) ? fhi.y : flo.y, (c & 4) ? fhi.z : flo.z));
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  return true;
}

}  // namespace inim
