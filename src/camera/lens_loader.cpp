#include "camera/lens_loader.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>

#include "camera/zemax_lens.h"
#include "core/input_file.h"
#include "spectral/glass_catalog.h"
#include "core/error.h"
#include "core/format.h"
#include "core/output_file.h"
#include "core/file_kinds.h"

namespace fs = std::filesystem;

namespace inim {

namespace {

// Rows listed with "before" thicknesses -> "after" thicknesses (same listed order).
void toAfterConvention(std::vector<LensSurface>& s) {
  for (size_t i = 0; i < s.size(); ++i) s[i].thicknessMm = i + 1 < s.size() ? s[i + 1].thicknessMm : 0.0;
}

std::string knownGlasses() { return "air, " + MaterialCatalog::standard().dielectricsText(); }

}  // namespace

const char* thicknessConventionName(ThicknessConvention c) {
  return c == ThicknessConvention::After ? "after" : "before";
}

std::string resolveLensPath(const std::string& s, const std::string& contextFile, const std::string& key) {
  const std::optional<FileKind> kind = fileKindOf(s);
  const bool isPath = s.find('/') != std::string::npos || kind == FileKind::Dat || kind == FileKind::Json ||
                      kind == FileKind::Zmx;
  if (isPath) {
    std::string p = s;
    if (fs::path(s).is_relative() && !contextFile.empty()) {
      fs::path rel = fs::path(contextFile).parent_path() / s;
      if (fs::exists(rel)) p = rel.lexically_normal().string();
      else p = dataPath(s);
    } else {
      p = dataPath(s);
    }
    if (!fs::exists(p))
      throw InputError(contextFile.empty() ? p : contextFile, contextFile.empty() ? "" : key,
                       "\"" + s + "\"", "an existing lens file (" + p + " not found)");
    return p;
  }
  for (const char* ext : {".json", ".zmx", ".dat"}) {
    std::string p = dataPath("optics/lenses/" + s + ext);
    if (fs::exists(p)) return p;
  }
  std::vector<std::string> names;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(dataPath("optics/lenses"), ec)) {
    const std::optional<FileKind> k = fileKindOf(e.path().string());
    if (k == FileKind::Json || k == FileKind::Dat || k == FileKind::Zmx) names.push_back(e.path().stem().string());
  }
  std::sort(names.begin(), names.end());
  std::string list;
  for (const auto& n : names) list += (list.empty() ? "" : ", ") + n;
  const std::string expected = "a lens file (.json, .zmx or .dat) or a name in optics/lenses/ (known: " +
                               (list.empty() ? "none" : list) + ")";
  if (contextFile.empty()) throw InputError(s, "", "", expected + "; not found");
  throw InputError(contextFile, key, "\"" + s + "\"", expected);
}

namespace {

LensSystem parseLensFile(const std::string& path, const LensLoadOptions& opt) {
  if (isFileKind(path, FileKind::Json)) {
    Json j = readJsonFile(path);
    return parseLensJson(JsonObject(j, path, ""), opt);
  }
  const std::string bytes = readInputFile(path);
  if (isFileKind(path, FileKind::Zmx)) return parseZmxLens(bytes, path, opt);
  return parsePbrtLens(bytes, path, opt);
}

}  // namespace

void addGlassRangeWarnings(LensSystem& lens) {
  LensDesignInfo design = lens.design();
  std::vector<double> used = {kLensVisibleMinNm, kLensVisibleMaxNm};
  for (double nm : design.wavelengthsNm) used.push_back(nm);
  const double lo = *std::min_element(used.begin(), used.end()), hi = *std::max_element(used.begin(), used.end());
  std::set<std::string> seen;
  for (const LensSurface& s : lens.surfaces()) {
    const auto* g = dynamic_cast<const CatalogGlassIor*>(s.medium.get());
    if (!g || !seen.insert(s.mediumName).second) continue;
    if (g->glass().covers(lo * 1e-3) && g->glass().covers(hi * 1e-3)) continue;
    design.warnings.push_back("glass " + s.mediumName + ": its catalogue data cover " + formatNumber(g->glass().minUm * 1e3) +
                              "-" + formatNumber(g->glass().maxUm * 1e3) + " nm, the lens is used at " + formatNumber(lo) +
                              "-" + formatNumber(hi) + " nm; the formula is extrapolated there");
  }
  lens.setDesign(std::move(design));
}

LensSystem loadLens(const std::string& pathOrName, const LensLoadOptions& opt) {
  LensSystem lens = parseLensFile(resolveLensPath(pathOrName), opt);
  addGlassRangeWarnings(lens);
  return lens;
}

LensSystem parsePbrtLens(const std::string& text, const std::string& file, const LensLoadOptions& opt) {
  std::istringstream in(text);
  std::string line, name;
  std::optional<ThicknessConvention> fileConvention;
  std::vector<LensSurface> rows;
  static const std::regex directive(R"(^#\s*thickness_convention\s*[:=]\s*(\S+)\s*$)");
  int lineNo = 0;
  while (std::getline(in, line)) {
    ++lineNo;
    std::string t = trim(line);
    if (t.empty()) continue;
    if (t[0] == '#') {
      std::smatch m;
      if (std::regex_match(t, m, directive)) {
        std::string v = m[1];
        if (v == "after") fileConvention = ThicknessConvention::After;
        else if (v == "before") fileConvention = ThicknessConvention::Before;
        else throw InputError(file, "line " + std::to_string(lineNo) + ", thickness_convention", "\"" + v + "\"",
                              "after or before");
      } else if (name.empty()) {
        name = trim(t.substr(1));
      }
      continue;
    }
    size_t hash = t.find('#');
    if (hash != std::string::npos) t = trim(t.substr(0, hash));
    std::replace(t.begin(), t.end(), ',', ' ');
    std::istringstream row(t);
    std::vector<double> v;
    std::string tok;
    const std::string where = "line " + std::to_string(lineNo) + " (row " + std::to_string(rows.size() + 1) + ")";
    while (row >> tok) {
      char* end = nullptr;
      double x = std::strtod(tok.c_str(), &end);
      if (end != tok.data() + tok.size() || tok.empty() || !std::isfinite(x)) {  // "29\0.475" is not 29
        std::replace(tok.begin(), tok.end(), '\0', '?');
        throw InputError(file, where, "\"" + tok + "\"", "a finite number (row: radius thickness index aperture)");
      }
      v.push_back(x);
    }
    if (v.size() != 4)
      throw InputError(file, where, "\"" + trim(line) + "\"",
                       "4 numbers: radius thickness index aperture (mm; got " + std::to_string(v.size()) + ")");
    LensSurface s;
    s.source = where;
    s.radiusMm = v[0];
    s.thicknessMm = v[1];
    s.apertureMm = v[3];
    const double nd = v[2];
    if (nd == 0.0 && v[0] == 0.0) {
      s.isStop = true;
    } else if (nd == 0.0 || nd == 1.0) {
      // air
    } else if (nd > 1.0 && nd < 5.0) {
      if (opt.pbrtDispersion == PbrtDispersion::Abbe) {
        s.medium = std::make_shared<CauchyIor>(CauchyIor::fromAbbe(nd, opt.abbeNumber));
        s.mediumName = "n_d " + formatNumber(nd) + ", V_d " + formatNumber(opt.abbeNumber);
      } else {
        s.medium = std::make_shared<ConstantIor>(float(nd));
        s.mediumName = "n_d " + formatNumber(nd);
      }
    } else {
      throw InputError(file, where + ", column 'index'", formatNumber(nd), "an index n_d in (1, 5), or 0 or 1 for air");
    }
    rows.push_back(std::move(s));
  }
  if (rows.empty()) throw InputError(file, "", "no surface rows", "rows of: radius thickness index aperture");
  ThicknessConvention conv = opt.thicknessConvention.value_or(fileConvention.value_or(ThicknessConvention::After));
  if (conv == ThicknessConvention::Before) toAfterConvention(rows);
  LensSystem lens(std::move(rows), name.empty() ? fs::path(file).stem().string() : name, file);
  lens.validate();
  return lens;
}

namespace {

// The medium after a surface from a JSON "glass" value.
void readGlass(const JsonObject& s, LensSurface& out) {
  const Json& g = s.raw("glass");
  if (g.is_string()) {
    std::string name = g.get<std::string>();
    if (name == "air") return;
    const MaterialCatalog& cat = MaterialCatalog::standard();
    if (!cat.hasDielectric(name))
      s.fail("glass", "\"" + name + "\"", "a glass in spectra/materials.json (known: " + knownGlasses() + ")");
    out.medium = cat.dielectric(name);
    out.mediumName = name;
    return;
  }
  if (!g.is_object()) s.fail("glass", jsonValueText(g), "a glass name, or an object with nd/vd, sellmeier_b/sellmeier_c or n");
  JsonObject o = s.object("glass");
  std::string label = o.string("name", "");
  if (o.has("nd")) {
    double nd = o.number("nd");
    double vd = o.positive("vd");
    if (!(nd > 1.0)) o.fail("nd", formatNumber(nd), "an index n_d > 1");
    out.medium = std::make_shared<CauchyIor>(CauchyIor::fromAbbe(nd, vd));
    out.mediumName = (label.empty() ? "" : label + ": ") + "n_d " + formatNumber(nd) + ", V_d " + formatNumber(vd);
  } else if (o.has("sellmeier_b")) {
    std::vector<double> B = o.numbers("sellmeier_b"), C = o.numbers("sellmeier_c");
    if (B.empty() || B.size() != C.size())
      o.fail("sellmeier_c", jsonValueText(o.raw("sellmeier_c")), "as many coefficients as sellmeier_b (at least 1)");
    auto ior = std::make_shared<SellmeierIor>(B, C);
    float nd = ior->n(float(kLensReferenceLambdaNm));
    if (!(nd > 1.0f) || !std::isfinite(nd))
      o.fail("sellmeier_b", jsonValueText(o.raw("sellmeier_b")), "coefficients giving n_d > 1");
    out.medium = ior;
    out.mediumName = (label.empty() ? "Sellmeier" : label) + ", n_d " + formatNumber(nd);
  } else if (o.has("n")) {
    double n = o.number("n");
    if (!(n >= 1.0)) o.fail("n", formatNumber(n), "an index >= 1");
    if (n > 1.0) {
      out.medium = std::make_shared<ConstantIor>(float(n));
      out.mediumName = (label.empty() ? "" : label + ": ") + "n " + formatNumber(n);
    }
  } else {
    s.fail("glass", jsonValueText(g), "an object with nd and vd, sellmeier_b and sellmeier_c, or n");
  }
  o.rejectUnknown();
}

}  // namespace

LensSystem parseLensJson(const JsonObject& o, const LensLoadOptions& opt) {
  const std::string& file = o.file();
  std::string name = o.string("name", fs::path(file).stem().string());
  std::string orientation = o.choice("orientation", {"object-first", "image-first"}, "object-first");
  ThicknessConvention conv = ThicknessConvention::After;
  if (o.choice("thickness_convention", {"after", "before"}, "after") == "before") conv = ThicknessConvention::Before;
  if (opt.thicknessConvention) conv = *opt.thicknessConvention;
  double scale = o.positive("scale", 1.0);
  if (o.has("assumptions")) (void)o.raw("assumptions");
  std::vector<LensSurface> rows;
  for (const JsonObject& s : o.objects("surfaces")) {
    LensSurface r;
    r.source = s.keyPath();
    r.isStop = s.boolean("stop", false);
    r.radiusMm = s.number("radius_mm", 0.0) * scale;
    r.thicknessMm = s.number("thickness_mm", 0.0) * scale;
    r.apertureMm = s.number("aperture_mm") * scale;
    r.conic = s.number("conic", 0.0);
    if (s.has("asphere")) {
      // [a4, a6, ...] as a stack's lens array takes them; the term on r^(2j) scales as
      // length^(1-2j). Internally the list starts at r^2 (Zemax's PARM 1), here 0.
      const std::vector<double> terms = s.numbers("asphere");
      r.asphere.assign(1, 0.0);
      for (size_t i = 0; i < terms.size(); ++i) r.asphere.push_back(terms[i] * std::pow(scale, -3.0 - 2.0 * double(i)));
    }
    if (s.has("glass")) readGlass(s, r);
    if (r.isStop && r.medium) s.fail("glass", jsonValueText(s.raw("glass")), "air after the stop (a stop is a flat opening in air)");
    s.rejectUnknown();
    rows.push_back(std::move(r));
  }
  if (rows.empty()) o.fail("surfaces", "[]", "at least one surface");
  if (conv == ThicknessConvention::Before) toAfterConvention(rows);
  if (orientation == "image-first") {
    // Rows run from the image side; each row's glass and thickness describe the space that
    // follows it in the listed order (toward the object). Reverse into object-first order.
    const size_t n = rows.size();
    if (rows.back().medium)
      throw InputError(file, rows.back().source + ".glass", rows.back().mediumName,
                       "air after the last row of an image-first lens (object space)");
    std::vector<LensSurface> out(n);
    for (size_t j = 0; j < n; ++j) {
      const LensSurface& L = rows[n - 1 - j];
      LensSurface& S = out[j];
      S = L;
      S.radiusMm = -L.radiusMm;
      if (j + 1 < n) {
        const LensSurface& next = rows[n - 2 - j];
        S.medium = next.medium;
        S.mediumName = next.mediumName;
        S.thicknessMm = next.thicknessMm;
      } else {
        S.medium = nullptr;
        S.mediumName = "air";
        S.thicknessMm = 0.0;
      }
    }
    rows = std::move(out);
  }
  o.rejectUnknown();
  LensSystem lens(std::move(rows), name, file);
  lens.validate();
  return lens;
}

std::string lensToPbrtText(const LensSystem& lens) {
  std::ostringstream out;
  out << "# " << (lens.name().empty() ? "lens" : lens.name()) << "\n";
  out << "# radius\tthickness\tN\taperture(diameter)\n";
  char buf[160];
  for (const auto& s : lens.surfaces()) {
    if (s.isAsphere() || s.conic != 0.0)
      throw InputError(lens.file(), s.source, s.isAsphere() ? "an even asphere" : "conic " + formatNumber(s.conic),
                       "spherical surfaces (the pbrt lens format has no conic or aspheric terms)");
    double nd = s.isStop || !s.medium ? (s.isStop ? 0.0 : 1.0) : double(s.medium->n(float(kLensReferenceLambdaNm)));
    std::snprintf(buf, sizeof buf, "%.10g\t%.10g\t%.10g\t%.10g\n", s.radiusMm, s.thicknessMm, nd, s.apertureMm);
    out << buf;
  }
  return out.str();
}

}  // namespace inim
