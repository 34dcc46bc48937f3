#include "spectral/glass_catalog.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <limits>
#include <sstream>

#include "core/error.h"
#include "core/text_encoding.h"
#include "core/input_file.h"

namespace inim {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// How many coefficients each formula takes (index: the code).
constexpr int kCoefficientCount[] = {0, 6, 6, 6, 5, 3, 8, 4, 4, 5, 8, 10, 8, 9};
constexpr int kLastFormula = 13;

double sqrtOrNaN(double n2) { return n2 >= 0.0 ? std::sqrt(n2) : kNaN; }

// n^2 - 1 = sum K_i l^2 / (l^2 - L_i) over `terms` pairs.
double sellmeier(const std::vector<double>& c, int terms, double l2) {
  double n2 = 1.0;
  for (int i = 0; i < terms; ++i) n2 += c[2 * i] * l2 / (l2 - c[2 * i + 1]);
  return sqrtOrNaN(n2);
}

// sum a_i l^(p_i) for the given powers.
double powerSeries(const std::vector<double>& a, std::initializer_list<int> powers, double l) {
  double s = 0.0;
  int i = 0;
  for (int p : powers) s += a[i++] * std::pow(l, p);
  return s;
}

std::vector<std::string> words(const std::string& line) {
  std::istringstream in(line);
  std::vector<std::string> w;
  for (std::string s; in >> s;) w.push_back(s);
  return w;
}

struct LineReader {
  const std::string& file;
  int line;
  std::string glass;  // the glass being read, for messages

  std::string where(const std::string& key) const {
    return "line " + std::to_string(line) + (glass.empty() ? "" : " (glass " + glass + ")") + ": " + key;
  }
  double number(const std::string& text, const std::string& key) const {
    size_t used = 0;
    double v = kNaN;
    try {
      v = std::stod(text, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used != text.size() || !std::isfinite(v)) throw InputError(file, where(key), "\"" + text.substr(0, 40) + "\"", "a number");
    return v;
  }
};

void finishGlass(const LineReader& r, std::vector<CatalogGlass>& glasses, bool haveCd) {
  if (glasses.empty() || haveCd) return;
  throw InputError(r.file, "line " + std::to_string(glasses.back().line) + " (glass " + glasses.back().name + ")", "no CD line",
                   "the glass's dispersion coefficients (CD) after its NM line");
}

}  // namespace

std::string dispersionFormulaName(int code) {
  static const char* const names[] = {"",           "Schott",      "Sellmeier 1", "Herzberger", "Sellmeier 2",
                                      "Conrady",    "Sellmeier 3", "Handbook 1",  "Handbook 2", "Sellmeier 4",
                                      "Extended",   "Sellmeier 5", "Extended 2",  "Extended 3"};
  return code >= 1 && code <= kLastFormula ? names[code] : "";
}

double CatalogGlass::index(double l) const {
  const std::vector<double>& c = coefficients;
  const double l2 = l * l;
  switch (formula) {
    case 1: return sqrtOrNaN(powerSeries(c, {0, 2, -2, -4, -6, -8}, l));
    case 2: return sellmeier(c, 3, l2);
    case 3: {
      const double L = 1.0 / (l2 - 0.028);
      return c[0] + c[1] * L + c[2] * L * L + powerSeries({c[3], c[4], c[5]}, {2, 4, 6}, l);
    }
    case 4: return sqrtOrNaN(1.0 + c[0] + c[1] * l2 / (l2 - c[2] * c[2]) + c[3] / (l2 - c[4] * c[4]));
    case 5: return c[0] + c[1] / l + c[2] / std::pow(l, 3.5);
    case 6: return sellmeier(c, 4, l2);
    case 7: return sqrtOrNaN(c[0] + c[1] / (l2 - c[2]) - c[3] * l2);
    case 8: return sqrtOrNaN(c[0] + c[1] * l2 / (l2 - c[2]) - c[3] * l2);
    case 9: return sqrtOrNaN(c[0] + c[1] * l2 / (l2 - c[2]) + c[3] * l2 / (l2 - c[4]));
    case 10: return sqrtOrNaN(powerSeries(c, {0, 2, -2, -4, -6, -8, -10, -12}, l));
    case 11: return sellmeier(c, 5, l2);
    case 12: return sqrtOrNaN(powerSeries(c, {0, 2, -2, -4, -6, -8, 4, 6}, l));
    case 13: return sqrtOrNaN(powerSeries(c, {0, 2, 4, -2, -4, -6, -8, -10, -12}, l));
  }
  return kNaN;
}

const CatalogGlass* GlassCatalog::find(const std::string& glass) const {
  auto upper = [](std::string s) {
    for (char& ch : s) ch = char(std::toupper(static_cast<unsigned char>(ch)));
    return s;
  };
  const std::string want = upper(glass);
  for (const CatalogGlass& g : glasses)
    if (upper(g.name) == want) return &g;
  return nullptr;
}

GlassCatalog parseAgf(const std::string& bytes, const std::string& file) {
  GlassCatalog cat;
  cat.file = file;
  cat.name = std::filesystem::path(file).stem().string();
  std::transform(cat.name.begin(), cat.name.end(), cat.name.begin(), [](unsigned char ch) { return char(std::toupper(ch)); });
  std::istringstream in(utf8FromBytes(bytes, file));
  LineReader r{file, 0, ""};
  bool haveCd = true;
  for (std::string text; std::getline(in, text);) {
    ++r.line;
    if (!text.empty() && text.back() == '\r') text.pop_back();
    const std::vector<std::string> w = words(text);
    if (w.empty()) continue;
    const std::string& key = w[0];
    if (key == "NM") {
      finishGlass(r, cat.glasses, haveCd);
      if (w.size() < 6) throw InputError(file, r.where("NM"), "\"" + text.substr(0, 60) + "\"", "NM name formula MIL# n_d V_d ...");
      r.glass = w[1];
      CatalogGlass g;
      g.name = w[1];
      g.line = r.line;
      const double code = r.number(w[2], "NM formula");
      g.formula = int(code);
      if (code != g.formula || dispersionFormulaName(g.formula).empty())
        throw InputError(file, r.where("NM formula"), w[2],
                         "a dispersion formula inim knows: 1 (Schott) to 13 (Extended 3), as listed in spectral/glass_catalog.h");
      g.nd = r.number(w[4], "NM n_d");
      g.vd = r.number(w[5], "NM V_d");
      cat.glasses.push_back(std::move(g));
      haveCd = false;
    } else if (key == "CD" || key == "LD") {
      if (cat.glasses.empty()) throw InputError(file, r.where(key), "before any NM line", "a glass (NM) first");
      CatalogGlass& g = cat.glasses.back();
      std::vector<double> v;
      for (size_t i = 1; i < w.size(); ++i) v.push_back(r.number(w[i], key));
      if (key == "CD") {
        v.resize(std::max<size_t>(v.size(), size_t(kCoefficientCount[g.formula])), 0.0);
        g.coefficients = std::move(v);
        haveCd = true;
      } else {
        if (v.size() < 2 || !(v[0] < v[1]) || v[0] <= 0.0)
          throw InputError(file, r.where("LD"), "\"" + text.substr(0, 60) + "\"", "LD min max, in um, 0 < min < max");
        g.minUm = v[0], g.maxUm = v[1];
      }
    } else if (key != "CC" && key != "GC" && key != "ED" && key != "TD" && key != "OD" && key != "IT" && key != "BD" &&
               key != "MD") {
      throw InputError(file, "line " + std::to_string(r.line), "\"" + text.substr(0, 40) + "\"",
                       "an .agf line: NM, CD, LD, CC, GC, ED, TD, OD, IT, BD or MD");
    }
  }
  finishGlass(r, cat.glasses, haveCd);
  if (cat.glasses.empty()) throw InputError(file, "", "no glass", "an .agf catalogue with at least one NM line");
  return cat;
}

GlassCatalog loadAgf(const std::string& path) {
  if (!std::filesystem::exists(path)) throw InputError(path, "", "missing", "a readable .agf glass catalogue");
  return parseAgf(readInputFile(path), path);
}

}  // namespace inim
