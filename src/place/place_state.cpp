#include "place/place_state.h"

#include <algorithm>

#include "core/error.h"
#include "core/format.h"

namespace inim {

namespace {

Json vec3Json(const Vec3d& v) { return Json::array({v.x, v.y, v.z}); }

std::string exact(double v) { return formatNumber(v, "%.17g"); }  // every bit, as the run file keeps it

std::string range(double lo, double hi) { return "a number in [" + exact(lo) + ", " + exact(hi) + "]"; }

// A number or each of 3 numbers within [lo, hi], else an error naming the key and the value.
void checkRange(const JsonObject& o, const std::string& key, const Vec3d& v, double lo, double hi) {
  for (int i = 0; i < 3; ++i)
    if (!(v[i] >= lo && v[i] <= hi)) o.fail(key, jsonValueText(o.raw(key)), "each " + range(lo, hi));
}
double checkedNumber(const JsonObject& o, const std::string& key, double lo, double hi) {
  const double v = o.number(key);
  if (!(v >= lo && v <= hi)) o.fail(key, jsonValueText(o.raw(key)), range(lo, hi));
  return v;
}

void applyPlacementPatch(Placement& p, const JsonObject& o, const PlaceLimits& lim) {
  if (o.has("scale")) {
    const Vec3d s = o.raw("scale").is_number() ? Vec3d(o.number("scale")) : o.vec3("scale");
    checkRange(o, "scale", s, lim.scaleMin, lim.scaleMax);
    p.scale = s;
  }
  if (o.has("rotate_deg")) {
    p.rotateDeg = o.vec3("rotate_deg");
    checkRange(o, "rotate_deg", p.rotateDeg, -lim.rotateMaxDeg, lim.rotateMaxDeg);
  }
  if (o.has("translate_mm")) {
    p.translateMm = o.vec3("translate_mm");
    checkRange(o, "translate_mm", p.translateMm, -lim.translateMaxMm, lim.translateMaxMm);
  }
  o.rejectUnknown();
}

}  // namespace

Json placeStateJson(const PlaceState& s) {
  Json j;
  j["placement"] = {{"scale", vec3Json(s.placement.scale)},
                    {"rotate_deg", vec3Json(s.placement.rotateDeg)},
                    {"translate_mm", vec3Json(s.placement.translateMm)}};
  j["vcp_mm"] = s.vcpMm;
  j["layout"] = s.layout;
  j["viewing_distance_mm"] = s.viewingDistanceMm;
  j["display"] = s.display;
  j["revision"] = s.revision;
  return j;
}

PlaceState applyStatePatch(const PlaceState& cur, const Json& patch, const std::vector<std::string>& displays) {
  const PlaceLimits lim;
  if (!patch.is_object()) throw InputError("request body", "", jsonValueText(patch), "a JSON object of state keys");
  JsonObject o(patch, "request body", "");
  PlaceState s = cur;
  if (o.has("placement")) applyPlacementPatch(s.placement, o.object("placement"), lim);
  if (o.has("vcp_mm")) s.vcpMm = checkedNumber(o, "vcp_mm", -lim.vcpMaxMm, lim.vcpMaxMm);
  if (o.has("layout")) s.layout = o.choice("layout", {"parallel", "toed-in"});
  if (o.has("viewing_distance_mm"))
    s.viewingDistanceMm = checkedNumber(o, "viewing_distance_mm", lim.viewingDistanceMinMm, lim.viewingDistanceMaxMm);
  if (o.has("display")) {
    const std::string d = o.string("display");
    if (std::find(displays.begin(), displays.end(), d) == displays.end())
      o.fail("display", "\"" + d + "\"", "one of /api/info's displays[].path");
    s.display = d;
  }
  if (o.has("revision")) (void)o.raw("revision");  // read-only: the page may send it back
  o.rejectUnknown();
  (void)s.placement.toDisplay();  // a singular transform is an InputError here, before any work
  return s;
}

Json runFileJson(const PlaceState& s, const std::string& fieldPath) {
  Json j;
  j["placement"] = {{"scale", vec3Json(s.placement.scale)},
                    {"rotate_deg", vec3Json(s.placement.rotateDeg)},
                    {"translate_mm", vec3Json(s.placement.translateMm)}};
  j["display"] = s.display;
  j["scene"] = fieldPath;
  j["vcp_mm"] = s.vcpMm;
  j["layout"] = s.layout;
  j["viewing_distance_mm"] = s.viewingDistanceMm;
  return j;
}

std::vector<std::string> eiaArguments(const PlaceState& s, const std::string& fieldPath) {
  auto v3 = [](const Vec3d& v) { return exact(v.x) + "," + exact(v.y) + "," + exact(v.z); };
  return {"--field", fieldPath, "--display", s.display, "--scale", v3(s.placement.scale),
          "--rotate-deg", v3(s.placement.rotateDeg), "--translate-mm", v3(s.placement.translateMm),
          "--vcp-mm", exact(s.vcpMm), "--layout", s.layout, "--viewing-distance-mm", exact(s.viewingDistanceMm)};
}

}  // namespace inim
