#include "sweep/sweep_plan.h"

#include <cmath>
#include <filesystem>
#include <map>
#include <set>
#include <tuple>

#include "core/content_hash.h"
#include "core/error.h"
#include "core/file_kinds.h"
#include "core/format.h"
#include "core/output_file.h"
#include "display/display.h"
#include "field_files/field_factory.h"
#include "sweep/fig11_settings_json.h"

namespace inim {
namespace fs = std::filesystem;

namespace {

// A path the plan gives: relative to the plan's folder when it exists there, else as the data
// folder resolves it (catalog-relative names such as scenes/paper-fig7.json).
std::string planPath(const std::string& planFile, const std::string& p) {
  if (p.empty()) return p;
  const fs::path beside = fs::path(planFile).parent_path() / p;
  if (fs::path(p).is_relative() && fs::exists(beside)) return fs::absolute(beside).lexically_normal().string();
  const std::string d = dataPath(p);
  return fs::exists(d) ? fs::absolute(d).lexically_normal().string() : p;
}

// A display given by name (optics/displays/NAME.json) or by path.
std::string displayPlanPath(const std::string& planFile, const std::string& d) {
  const std::string p = d.empty()                           ? defaultDisplayPath()
                        : !isFileKind(d, FileKind::Json) ? dataPath("optics/displays/" + d + ".json")
                                                            : planPath(planFile, d);
  return fs::absolute(p).lexically_normal().string();
}

// Relative "file" values of a part read in from `from` made absolute, so they still resolve.
void absoluteFiles(Json& j, const fs::path& folder) {
  if (j.is_object()) {
    for (auto& [k, v] : j.items()) {
      if (k == "file" && v.is_string() && fs::path(v.get<std::string>()).is_relative())
        v = (folder / v.get<std::string>()).lexically_normal().string();
      else absoluteFiles(v, folder);
    }
  } else if (j.is_array()) {
    for (Json& v : j) absoluteFiles(v, folder);
  }
}

void inlinePart(Json& display, const std::string& key, const std::string& folder, const fs::path& displayDir) {
  if (!display.contains(key) || !display[key].is_string()) return;
  const std::string s = display[key].get<std::string>();
  const std::string path = isFileKind(s, FileKind::Json) ? (displayDir / s).string()
                                                          : dataPath("optics/" + folder + "/" + s + ".json");
  if (!fs::exists(path)) return;  // left as it is: loading the display names it
  Json part = readJsonFile(path);
  absoluteFiles(part, fs::path(path).parent_path());
  display[key] = std::move(part);
}

struct PathStep {
  std::string key;  // empty: an index
  size_t index = 0;
};

std::vector<PathStep> parseKeyPath(const std::string& path) {
  std::vector<PathStep> steps;
  size_t i = 0;
  while (i < path.size()) {
    if (path[i] == '[') {
      const size_t close = path.find(']', i);
      if (close == std::string::npos || close == i + 1) return {};
      const std::string digits = path.substr(i + 1, close - i - 1);
      if (digits.find_first_not_of("0123456789") != std::string::npos || digits.size() > 6) return {};
      steps.push_back({"", size_t(std::stoul(digits))});
      i = close + 1;
      if (i < path.size() && path[i] == '.') ++i;
    } else {
      size_t end = path.find_first_of(".[", i);
      if (end == std::string::npos) end = path.size();
      if (end == i) return {};
      steps.push_back({path.substr(i, end - i), 0});
      i = end;
      if (i < path.size() && path[i] == '.') ++i;
    }
  }
  return steps;
}

std::string hashId(const std::vector<std::pair<std::string, double>>& values,
                   const std::vector<std::pair<std::string, std::string>>& choices) {
  Sha256 h;
  h.add("sweep point v1");
  for (const auto& [k, v] : choices) h.add(k), h.add(v);
  for (const auto& [k, v] : values) h.add(k), h.add(formatNumber(v, "%.12g"));
  return "p" + h.hex().substr(0, 12);
}

// A number as the plan gives it: its range is the design's, checked when its point runs.
double rawNumber(const JsonObject& o, const std::string& key) {
  const Json& v = o.raw(key);
  if (!v.is_number()) o.fail(key, jsonValueText(v), "a number");
  return v.get<double>();
}

std::vector<double> axisValues(const JsonObject& a) {
  std::vector<double> values;
  if (a.has("values") == a.has("range"))
    a.fail("values", a.has("values") ? "both values and range" : "neither values nor range",
           "either \"values\": [numbers] or \"range\": {\"from\", \"to\", \"count\"}");
  if (a.has("values")) {  // raw: each value's range is the design's, checked when its point runs
    const Json& v = a.raw("values");
    if (!v.is_array()) a.fail("values", jsonValueText(v), "a list of numbers");
    for (const Json& e : v) {
      if (!e.is_number()) a.fail("values", jsonValueText(v), "a list of numbers");
      values.push_back(e.get<double>());
    }
  } else {
    const JsonObject r = a.object("range");
    const double from = rawNumber(r, "from"), to = rawNumber(r, "to");
    const int count = r.integer("count", 1, 100000);
    r.rejectUnknown();
    for (int i = 0; i < count; ++i) values.push_back(count == 1 ? from : from + (to - from) * i / (count - 1));
  }
  if (values.empty()) a.fail(a.has("values") ? "values" : "range", "[]", "at least one value");
  return values;
}

SweepOption readOption(const JsonObject& o, const std::string& planFile) {
  SweepOption opt;
  opt.label = o.string("label");
  if (opt.label.empty() || opt.label.find_first_of(",\"\n/") != std::string::npos)
    o.fail("label", "\"" + opt.label + "\"", "a non-empty name without commas, quotes, slashes or newlines");
  if (o.has("display")) opt.display = displayPlanPath(planFile, o.string("display"));
  if (o.has("field")) opt.field = planPath(planFile, o.string("field"));
  if (o.has("camera")) opt.camera = o.string("camera");
  if (o.has("set")) {
    const JsonObject set = o.object("set");
    for (const auto& [k, v] : set.json().items()) {
      set.raw(k);  // marks it read
      opt.set.emplace_back(k, v);
    }
  }
  o.rejectUnknown();
  return opt;
}

}  // namespace

bool keyPathChangesReferences(const std::string& path) {
  if (path.rfind("placement.", 0) == 0) return true;
  for (const char* k : {"fig11.distance_mm", "fig11.angle", "fig11.width", "fig11.reference_spp", "fig11.seed",
                        "fig11.depth_error", "fig11.reference_every_pixel", "fig11.poses"})
    if (path == k) return true;
  return false;
}

Json* findKeyPath(Json& doc, const std::string& path) {
  const std::vector<PathStep> steps = parseKeyPath(path);
  if (steps.empty()) return nullptr;
  Json* at = &doc;
  for (const PathStep& s : steps) {
    if (!s.key.empty()) {
      if (!at->is_object() || !at->contains(s.key)) return nullptr;
      at = &(*at)[s.key];
    } else {
      if (!at->is_array() || s.index >= at->size()) return nullptr;
      at = &(*at)[s.index];
    }
  }
  return at;
}

void setKeyPath(Json& doc, const std::string& path, const Json& value, const std::string& file,
                const std::string& key, bool numeric) {
  Json* at = findKeyPath(doc, path);
  if (!at)
    throw InputError(file, key, "\"" + path + "\"",
                     "a key path that exists in the design (the display's JSON with its panel and mla, "
                     "placement.KEY or fig11.KEY; arrays as name[i])");
  if (numeric && !at->is_number())
    throw InputError(file, key, "\"" + path + "\" (" + jsonValueText(*at) + ")", "a key path to a number");
  if (!at->is_null() && at->type() != value.type() && !(at->is_number() && value.is_number()))
    throw InputError(file, key, "\"" + path + "\" = " + jsonValueText(value),
                     "a value of the same type as the design's (" + jsonValueText(*at) + ")");
  *at = value;
}

Json resolvedDisplayJson(const std::string& path) {
  Json display = readJsonFile(path);
  const fs::path dir = fs::path(path).parent_path();
  inlinePart(display, "panel", "panels", dir);
  inlinePart(display, "mla", "mlas", dir);
  return display;
}

SweepPlan sweepPlanFromJson(const Json& j, const std::string& file) {
  SweepPlan p;
  p.file = file;
  const JsonObject o(j, file, "");
  const JsonObject base = o.object("base");
  p.display = displayPlanPath(file, base.string("display", ""));
  p.field = base.has("field") ? planPath(file, base.string("field"))
                              : fs::absolute(defaultScenePath()).lexically_normal().string();
  p.camera = base.string("camera", Fig11Settings{}.camera);
  if (base.has("placement")) {
    const JsonObject pl = base.object("placement");
    for (const char* k : {"scale", "rotate_deg", "translate_mm"})
      if (pl.has(k)) pl.vec3(k), p.placement[k] = pl.raw(k);
    pl.rejectUnknown();
  }
  const Json fig11 = base.has("fig11") ? base.raw("fig11") : Json::object();
  const Fig11Settings s = fig11SettingsFromJson(JsonObject(fig11, file, "base.fig11"), sweepFig11Defaults());
  p.fig11 = fig11SettingsJson(s);
  base.rejectUnknown();
  if (o.has("axes")) {
    for (const JsonObject& a : o.objects("axes")) {
      SweepAxis axis;
      axis.path = a.string("path");
      axis.values = axisValues(a);
      a.rejectUnknown();
      p.axes.push_back(std::move(axis));
    }
  }
  p.zip = o.choice("combine", {"grid", "zip"}, "grid") == "zip";
  if (o.has("alternatives")) {
    for (const JsonObject& a : o.objects("alternatives")) {
      SweepAlternative alt;
      alt.name = a.string("name");
      for (const JsonObject& opt : a.objects("options")) alt.options.push_back(readOption(opt, file));
      if (alt.options.empty()) a.fail("options", "[]", "at least one option");
      a.rejectUnknown();
      p.alternatives.push_back(std::move(alt));
    }
  }
  o.rejectUnknown();
  if (p.axes.empty() && p.alternatives.empty()) o.fail("axes", "none", "at least one axis or alternative");
  return p;
}

SweepPlan loadSweepPlan(const std::string& path) { return sweepPlanFromJson(readJsonFile(path), path); }

Json sweepPlanJson(const SweepPlan& plan) {
  Json j;
  j["base"] = {{"display", plan.display}, {"field", plan.field}, {"camera", plan.camera},
               {"placement", plan.placement}, {"fig11", plan.fig11}};
  j["axes"] = Json::array();
  for (const SweepAxis& a : plan.axes) j["axes"].push_back({{"path", a.path}, {"values", a.values}});
  j["combine"] = plan.zip ? "zip" : "grid";
  j["alternatives"] = Json::array();
  for (const SweepAlternative& a : plan.alternatives) {
    Json options = Json::array();
    for (const SweepOption& opt : a.options) {
      Json oj = {{"label", opt.label}};
      if (!opt.display.empty()) oj["display"] = opt.display;
      if (!opt.field.empty()) oj["field"] = opt.field;
      if (!opt.camera.empty()) oj["camera"] = opt.camera;
      if (!opt.set.empty()) {
        oj["set"] = Json::object();
        for (const auto& [k, v] : opt.set) oj["set"][k] = v;
      }
      options.push_back(std::move(oj));
    }
    j["alternatives"].push_back({{"name", a.name}, {"options", std::move(options)}});
  }
  return j;
}

int64_t sweepPointCount(const SweepPlan& plan) {
  int64_t n = 1;
  constexpr int64_t kCap = int64_t(1) << 40;  // beyond any --max-points; no overflow
  if (plan.zip && !plan.axes.empty()) {
    for (size_t i = 1; i < plan.axes.size(); ++i)
      if (plan.axes[i].values.size() != plan.axes[0].values.size())
        throw InputError(plan.file, "axes[" + std::to_string(i) + "].values",
                         std::to_string(plan.axes[i].values.size()) + " values",
                         std::to_string(plan.axes[0].values.size()) + " values, as axes[0] (\"combine\": \"zip\")");
    n = int64_t(plan.axes[0].values.size());
  } else {
    for (const SweepAxis& a : plan.axes) n = std::min(kCap, n * int64_t(a.values.size()));
  }
  for (const SweepAlternative& a : plan.alternatives) n = std::min(kCap, n * int64_t(a.options.size()));
  return n;
}

namespace {

bool underPlacement(const std::string& path) { return path.rfind("placement.", 0) == 0; }

// The placement vectors that `paths` reach and the plan does not give, from the field's own
// placement (read once per field: a trained model's carries its units), so an axis can vary one
// component of them.
void fillPlacementDefaults(Json& config, const std::vector<std::string>& paths,
                           std::map<std::string, Placement>& ownPlacements) {
  Json& pl = config["placement"];
  for (const std::string& path : paths) {
    if (!underPlacement(path)) continue;
    const std::string name = path.substr(10, path.find('[') == std::string::npos ? std::string::npos : path.find('[') - 10);
    if (pl.contains(name) || (name != "scale" && name != "rotate_deg" && name != "translate_mm")) continue;
    const std::string field = config["field"].get<std::string>();
    auto it = ownPlacements.find(field);
    if (it == ownPlacements.end())
      it = ownPlacements.emplace(field, loadField(field, "field").placement.value_or(Placement{})).first;
    const Vec3d d = name == "scale" ? it->second.scale : name == "rotate_deg" ? it->second.rotateDeg : it->second.translateMm;
    pl[name] = {d.x, d.y, d.z};
  }
}

void setDesignValue(Json& config, const std::string& path, const Json& v, const std::string& file,
                    const std::string& key, bool numeric) {
  if (underPlacement(path)) {
    setKeyPath(config["placement"], path.substr(10), v, file, key, numeric);
  } else if (path.rfind("fig11.", 0) == 0) {
    setKeyPath(config["fig11"], path.substr(6), v, file, key, numeric);
  } else {
    setKeyPath(config["display"], path, v, file, key, numeric);
  }
}

std::vector<std::vector<int>> optionCombinations(const SweepPlan& plan) {
  std::vector<std::vector<int>> out{{}};
  for (const SweepAlternative& a : plan.alternatives) {
    std::vector<std::vector<int>> next;
    for (const auto& c : out)
      for (int i = 0; i < int(a.options.size()); ++i) next.push_back(c), next.back().push_back(i);
    out = std::move(next);
  }
  return out;
}

std::vector<std::vector<double>> axisCombinations(const SweepPlan& plan) {
  std::vector<std::vector<double>> out{{}};
  if (plan.zip && !plan.axes.empty()) {
    out.clear();
    for (size_t i = 0; i < plan.axes[0].values.size(); ++i) {
      out.emplace_back();
      for (const SweepAxis& a : plan.axes) out.back().push_back(a.values[i]);
    }
    return out;
  }
  for (const SweepAxis& a : plan.axes) {
    std::vector<std::vector<double>> next;
    for (const auto& c : out)
      for (double v : a.values) next.push_back(c), next.back().push_back(v);
    out = std::move(next);
  }
  return out;
}

}  // namespace

std::vector<SweepPoint> expandSweep(const SweepPlan& plan, int64_t maxPoints) {
  const int64_t count = sweepPointCount(plan);
  if (count > maxPoints)
    throw InputError(plan.file, "axes", std::to_string(count) + " points",
                     "at most " + std::to_string(maxPoints) + " (--max-points)");
  for (size_t i = 0; i < plan.axes.size(); ++i)
    for (double v : plan.axes[i].values)
      if (!std::isfinite(v))
        throw InputError(plan.file, "axes[" + std::to_string(i) + "].values", formatNumber(v), "finite numbers");
  std::map<std::string, Json> displays;  // each display file read once
  auto displayJson = [&](const std::string& path) -> const Json& {
    auto it = displays.find(path);
    if (it == displays.end()) {
      if (!fs::exists(path)) throw InputError(plan.file, "display", "\"" + path + "\"", "an existing display file");
      it = displays.emplace(path, resolvedDisplayJson(path)).first;
    }
    return it->second;
  };
  std::map<std::string, Placement> ownPlacements;  // each field's own placement, read once
  std::set<std::string> ids;
  std::vector<SweepPoint> points;
  const auto axisSets = axisCombinations(plan);
  for (const auto& options : optionCombinations(plan)) {
    Json config = {{"display", nullptr}, {"field", plan.field}, {"camera", plan.camera},
                   {"placement", plan.placement}, {"fig11", plan.fig11}};
    std::string display = plan.display;
    std::vector<std::pair<std::string, std::string>> choices;
    std::vector<std::tuple<std::string, Json, std::string>> sets;
    for (size_t a = 0; a < options.size(); ++a) {
      const SweepOption& opt = plan.alternatives[a].options[options[a]];
      choices.emplace_back(plan.alternatives[a].name, opt.label);
      if (!opt.display.empty()) display = opt.display;
      if (!opt.field.empty()) config["field"] = opt.field;
      if (!opt.camera.empty()) config["camera"] = opt.camera;
      const std::string where = "alternatives[" + std::to_string(a) + "].options[" + std::to_string(options[a]) + "].set";
      for (const auto& [k, v] : opt.set) sets.emplace_back(k, v, where);
    }
    config["display"] = displayJson(display);
    config["display_file"] = display;
    std::vector<std::string> paths;
    for (const auto& [k, v, where] : sets) paths.push_back(k);
    for (const SweepAxis& a : plan.axes) paths.push_back(a.path);
    fillPlacementDefaults(config, paths, ownPlacements);
    for (const auto& [k, v, where] : sets) setDesignValue(config, k, v, plan.file, where + "." + k, false);
    for (const auto& values : axisSets) {
      SweepPoint p;
      p.index = int(points.size());
      p.config = config;
      p.choices = choices;
      for (size_t i = 0; i < plan.axes.size(); ++i) {
        setDesignValue(p.config, plan.axes[i].path, values[i], plan.file, "axes[" + std::to_string(i) + "].path", true);
        p.values.emplace_back(plan.axes[i].path, values[i]);
      }
      p.id = hashId(p.values, p.choices);
      if (!ids.insert(p.id).second) {
        const int first = int(std::find_if(points.begin(), points.end(), [&](const SweepPoint& q) { return q.id == p.id; }) -
                              points.begin());
        throw InputError(plan.file, "axes", "points " + std::to_string(first) + " and " + std::to_string(p.index),
                         "different parameters (a value or an option label given twice)");
      }
      points.push_back(std::move(p));
    }
  }
  return points;
}

}  // namespace inim
