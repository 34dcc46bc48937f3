#include "field/placement.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <limits>

#include "core/error.h"
#include "core/settings_table.h"
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

PlacementOverride parsePlacementOverride(const std::string& scale, const std::string& rotateDeg,
                                         const std::string& translateMm, const std::string& prefix) {
  // Each part in the range its key has in the files (core/settings_table.h): a negative scale
  // would mirror the scene without a word.
  auto parse = [&](const std::string& text, const std::string& key, bool allowScalar) {
    const Vec3d v = parseVec3(text, prefix + key, allowScalar);
    const SettingInfo& info = *findSetting(key, kFileScope);
    for (int i = 0; i < 3; ++i)
      if (!(v[i] >= info.lo && v[i] <= info.hi))
        throw InputError("", prefix + key, "\"" + text + "\"", rangeText(info) + " for each of x, y, z");
    return v;
  };
  PlacementOverride o;
  if (!scale.empty()) o.scale = parse(scale, "scale", true);
  if (!rotateDeg.empty()) o.rotateDeg = parse(rotateDeg, "rotate_deg", false);
  if (!translateMm.empty()) o.translateMm = parse(translateMm, "translate_mm", false);
  return o;
}

}  // namespace inim
