#include "display/display.h"

#include "display/gap_range.h"
#include <algorithm>
#include <filesystem>
#include <limits>

#include "core/error.h"
#include "core/output_file.h"
#include "display/ei_layout.h"
#include "spectral/dispersion.h"
#include "core/file_kinds.h"

namespace fs = std::filesystem;

namespace inim {

const char* layoutName(EiLayoutKind k) {
  switch (k) {
    case EiLayoutKind::Parallel: return "parallel";
    case EiLayoutKind::ToedIn: return "toed-in";
    case EiLayoutKind::LensGrid: return "lens-grid";
  }
  return "?";
}

std::string defaultDisplayPath() { return dataPath("optics/displays/paper-prototype.json"); }
std::string displayPathOrDefault(const std::string& path) { return path.empty() ? defaultDisplayPath() : path; }

// A reference to a sub-description: an inline object, a .json path relative to the display
// file, or a catalog name under optics/<folder>/.
template <class T, class Parse, class Load>
static T readPart(const JsonObject& o, const std::string& key, const std::string& folder,
                  Parse parse, Load load) {
  const Json& v = o.raw(key);
  if (v.is_object()) return parse(o.object(key));
  if (!v.is_string()) o.fail(key, jsonValueText(v), "an object, a .json file path or a catalog name");
  std::string s = v.get<std::string>();
  std::string path;
  if (isFileKind(s, FileKind::Json)) {
    path = o.path(key);
  } else {
    path = dataPath("optics/" + folder + "/" + s + ".json");
    if (!fs::exists(path)) {
      std::vector<std::string> names;
      std::error_code ec;
      for (const auto& e : fs::directory_iterator(dataPath("optics/" + folder), ec))
        if (isFileKind(e.path().string(), FileKind::Json)) names.push_back(e.path().stem().string());
      std::sort(names.begin(), names.end());
      std::string list;
      for (const auto& n : names) list += (list.empty() ? "" : ", ") + n;
      o.fail(key, "\"" + s + "\"",
             "a .json file or a name in optics/" + folder + "/ (known: " + (list.empty() ? "none" : list) + ")");
    }
  }
  if (!fs::exists(path)) o.fail(key, "\"" + s + "\"", "an existing file (" + path + " not found)");
  return load(path);
}

static void readPair(const JsonObject& o, const std::string& key, int& a, int& b, bool allowScalar) {
  const Json& v = o.raw(key);
  constexpr int kMax = std::numeric_limits<int>::max();
  if (allowScalar && v.is_number()) {
    a = b = o.integer(key, 1, kMax);
    return;
  }
  if (!v.is_array() || v.size() != 2)
    o.fail(key, jsonValueText(v),
           std::string(allowScalar ? "a whole number >= 1 or " : "") + "[x, y], whole numbers >= 1");
  const std::vector<int> p = o.integers(key, 1, kMax);
  a = p[0];
  b = p[1];
}

// The lens and cover-glass materials, once for every command: an unknown name once passed `eia`
// and `rays` and was refused only by the commands that refract. Named as the display holds them
// (mla.material), with the part's own file when it has one.
static void checkMaterial(const Display& d, const std::string& key, const std::string& material,
                          const std::string& partFile) {
  const MaterialCatalog& catalog = MaterialCatalog::standard();
  if (catalog.hasDielectric(material)) return;
  throw InputError(d.file, key, "\"" + material + "\"" + (partFile != d.file ? " (in " + partFile + ")" : ""),
                   "a dielectric of the material catalog: " + catalog.dielectricsText());
}

// "stack" in place of "mla" and "reconstruction_gap_mm": the stack places the panel.
static void readStack(const JsonObject& o, Display& d) {
  if (o.has("mla") || o.has("reconstruction_gap_mm"))
    o.fail(o.has("mla") ? "mla" : "reconstruction_gap_mm", "given with \"stack\"",
           "either a stack (which places the panel) or an mla with its reconstruction_gap_mm");
  d.stack = parseOpticalStack(o.object("stack"), d.panel.widthMm(), d.panel.heightMm());
  std::string why;
  if (const std::optional<StackAsMla> m = mlaFromStack(*d.stack, why)) {
    d.mla = m->mla;
    d.reconstructionGapMm = checkGapMm(m->gapMm, d.file, "stack (panel to the lenslets' principal plane)");
    return;
  }
  const StackAsMla equivalent = equivalentMla(*d.stack);
  d.mla = equivalent.mla;
  d.reconstructionGapMm = checkGapMm(equivalent.gapMm, d.file, "stack (panel to the stack's principal plane)");
  d.stackTraced = true;
}

Display loadDisplay(const std::string& path) {
  Json j = readJsonFile(path);
  JsonObject o(j, path, "");
  Display d;
  d.file = path;
  d.name = o.string("name");
  d.panel = readPart<Panel>(o, "panel", "panels", parsePanel, loadPanel);
  if (o.has("stack")) {
    readStack(o, d);
    d.generationGapMm = checkGapMm(o.number("generation_gap_mm"), path, "generation_gap_mm");
  } else {
    d.mla = readPart<Mla>(o, "mla", "mlas", parseMla, loadMla);
    d.generationGapMm = checkGapMm(o.number("generation_gap_mm"), path, "generation_gap_mm");
    d.reconstructionGapMm = checkGapMm(o.number("reconstruction_gap_mm"), path, "reconstruction_gap_mm");
  }
  readPair(o, "ei_px", d.eiWidthPx, d.eiHeightPx, true);
  readPair(o, "ei_count", d.eiCols, d.eiRows, false);
  std::string layout = o.choice("layout", {"parallel", "toed-in", "lens-grid"}, "parallel");
  d.layout = layout == "parallel" ? EiLayoutKind::Parallel
             : layout == "toed-in" ? EiLayoutKind::ToedIn
                                   : EiLayoutKind::LensGrid;
  if (d.layout == EiLayoutKind::ToedIn)
    d.viewingDistanceMm = o.positive("viewing_distance_mm");
  else if (o.has("viewing_distance_mm"))
    d.viewingDistanceMm = o.positive("viewing_distance_mm");
  d.assumptions = readAssumptions(o);
  o.rejectUnknown();
  checkMaterial(d, "mla.material", d.mla.material, d.mla.file);
  if (d.panel.coverGlass) checkMaterial(d, "panel.cover_glass.material", d.panel.coverGlass->material, d.panel.file);
  (void)computeLayout(d);  // validates the EI layout against the panel
  return d;
}

}  // namespace inim
