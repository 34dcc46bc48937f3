#pragma once
// A design sweep's plan (docs/sweeps.md): a base design and the axes to vary, expanded into
// design points, each a whole configuration that `inim sweep --point ID` runs alone.
//
//   {
//     "base": {"display": "paper-prototype", "field": "scenes/paper-fig7.json",
//              "camera": "alvium-1800-u-500c", "placement": {"translate_mm": [0, 0, 0]},
//              "fig11": {"width": 648, "poses": ["centre", "left"], "budget": true}},
//     "axes": [{"path": "reconstruction_gap_mm", "values": [3.6, 4.0, 4.4]},
//              {"path": "mla.pitch_mm", "range": {"from": 0.98, "to": 1.02, "count": 3}}],
//     "combine": "grid" | "zip",
//     "alternatives": [{"name": "layout", "options": [
//         {"label": "stripe", "set": {"panel.subpixel_layout.type": "rgb-stripe"}},
//         {"label": "barrier", "display": "barrier-mla"}]}]
//   }
//
// A key path names a value of the point's design: the display's JSON (its panel and MLA read in
// as objects, so "panel.pitch_mm" and "mla.pitch_mm" reach them; "stack.layers[2].pitch_mm"),
// "placement.KEY[i]" (the field's placement: scale, rotate_deg, translate_mm) or "fig11.KEY"
// (the run's settings: width, spp, distance_mm, ...). Axes vary numbers that exist; the plan is
// refused before anything runs (InputError naming the plan, the axis and the value) otherwise.
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "core/json_config.h"

namespace inim {

constexpr int kDefaultMaxSweepPoints = 10000;

struct SweepAxis {
  std::string path;
  std::vector<double> values;
};

// One named alternative: another whole display, field or camera, and/or values set by key path.
struct SweepOption {
  std::string label;
  std::string display, field, camera;           // "": the base's
  std::vector<std::pair<std::string, Json>> set;  // key path -> value
};

struct SweepAlternative {
  std::string name;
  std::vector<SweepOption> options;
};

struct SweepPlan {
  std::string file;
  std::string display, field, camera;  // resolved paths (or the camera's catalog name)
  Json placement = Json::object();      // over the field's own placement
  Json fig11 = Json::object();          // every fig11 setting, the defaults filled in
  std::vector<SweepAxis> axes;
  bool zip = false;
  std::vector<SweepAlternative> alternatives;
};

struct SweepPoint {
  int index = 0;
  std::string id;  // "p" + 12 hex digits of the SHA-256 of its parameters
  std::vector<std::pair<std::string, double>> values;        // axis path -> value
  std::vector<std::pair<std::string, std::string>> choices;  // alternative -> option label
  // {"display": {...}, "field": path, "camera": name, "placement": {...}, "fig11": {...}}
  Json config;
};

SweepPlan loadSweepPlan(const std::string& path);
// The plan as JSON again (written into the sweep's folder, so later steps read the same plan).
Json sweepPlanJson(const SweepPlan& plan);
SweepPlan sweepPlanFromJson(const Json& j, const std::string& file);

// How many points the plan makes (InputError when the axes of a zip differ in length).
int64_t sweepPointCount(const SweepPlan& plan);
// Every point, alternatives outermost, then the axes (the first outermost). Refused before any
// work when there are more than `maxPoints` or a key path does not resolve in some point.
std::vector<SweepPoint> expandSweep(const SweepPlan& plan, int64_t maxPoints = kDefaultMaxSweepPoints);

// The display file as one JSON document: its panel and MLA (catalog names or files) read in as
// objects, relative file names inside them made absolute.
Json resolvedDisplayJson(const std::string& path);

// Whether a key path's value changes the reference views (the field's placement, the camera's
// pose and distance, the references' render settings): such axes make the points render their
// own; every display, panel and MLA key lets them share the sweep's cache.
bool keyPathChangesReferences(const std::string& path);

// Key paths: "a.b[2].c". `set` replaces an existing value (InputError naming `key` and `file`
// when the path does not exist or, with `numeric`, the value there is not a number).
Json* findKeyPath(Json& doc, const std::string& path);
void setKeyPath(Json& doc, const std::string& path, const Json& value, const std::string& file,
                const std::string& key, bool numeric);

}  // namespace inim
