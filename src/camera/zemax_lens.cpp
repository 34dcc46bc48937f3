#include "camera/zemax_lens.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <set>
#include <sstream>

#include "camera/lens_analysis.h"
#include "core/error.h"
#include "core/format.h"
#include "core/text_encoding.h"
#include "spectral/glass_catalog.h"

namespace fs = std::filesystem;

namespace inim {

namespace {

// One line of the file, split into words ("quoted text" is one word).
struct ZmxLine {
  int number = 0;
  std::vector<std::string> words;
  const std::string& key() const { return words[0]; }
};

std::vector<ZmxLine> splitLines(const std::string& text) {
  std::vector<ZmxLine> lines;
  std::istringstream in(text);
  std::string raw;
  for (int n = 1; std::getline(in, raw); ++n) {
    ZmxLine l{n, {}};
    for (size_t i = 0; i < raw.size();) {
      if (std::isspace(static_cast<unsigned char>(raw[i]))) {
        ++i;
      } else if (raw[i] == '"') {
        const size_t end = raw.find('"', i + 1);
        l.words.push_back(raw.substr(i + 1, end == std::string::npos ? std::string::npos : end - i - 1));
        i = end == std::string::npos ? raw.size() : end + 1;
      } else {
        size_t j = i;
        while (j < raw.size() && !std::isspace(static_cast<unsigned char>(raw[j]))) ++j;
        l.words.push_back(raw.substr(i, j - i));
        i = j;
      }
    }
    if (!l.words.empty()) lines.push_back(std::move(l));
  }
  return lines;
}

// A surface as the file gives it, in lens units.
struct ZmxSurface {
  int number = 0, line = 0;
  std::string type = "STANDARD";
  double curv = 0.0, conic = 0.0, disz = 0.0, semiDiameter = 0.0;
  double clearSemi = -1.0;  // CLAP's maximum radius, -1: none
  bool infiniteDisz = false, stop = false;
  std::map<int, double> parm;
  std::string glass;  // "" = air
  bool modelGlass = false;
  double nd = 0.0, vd = 0.0;
  int glassLine = 0;

  std::string where() const { return "SURF " + std::to_string(number) + " (line " + std::to_string(line) + ")"; }
};

// The file-level settings.
struct ZmxHeader {
  std::string name;
  double mmPerUnit = 1.0;
  std::vector<std::string> catalogues;  // GCAT, in order
  std::map<int, double> wavelengthsUm;  // WAVM slot -> um
  int primary = 1;
  int wavelengthCount = 0;  // FTYP's fourth field: how many WAVM slots are in use (0: all)
  double enpd = 0.0, fnum = 0.0;
  bool floatByStop = false;  // FLOA: the stop's DIAM is the aperture
};

// Surface keywords that do not change the lens as built: display, coatings, solves,
// tolerancing and optimisation data.
const std::set<std::string> kIgnoredSurfaceKeys = {
    "COMM", "HIDE", "MIRR", "SLAB", "POPS", "COAT", "MEMA", "FLAP", "VPAR", "VDSZ", "VCON", "VTHI", "VCUR",
    "PPAR", "BLNK", "PZUP", "CONF", "TOLE", "XDAT", "XDDN", "EDVA", "GLRS", "FLOA", "FIMP", "LOCK", "OEMA",
    "CSCR", "FLWD", "ISNR", "DMFS", "TCE", "NOTE", "RAYC", "MAZH", "FIMP",
    // after the surfaces: multi-configuration and tolerance operands (other configurations,
    // tolerances: not the lens as designed)
    "MNUM", "MOFF", "TOL"};
// Surface keywords that describe what inim cannot model.
const std::map<std::string, std::string> kRefusedSurfaceKeys = {
    {"SQAP", "a rectangular aperture"},  {"ELAP", "an elliptical aperture"}, {"OBSC", "a circular obscuration"},
    {"SQOB", "a rectangular obscuration"}, {"ELOB", "an elliptical obscuration"}, {"SPID", "a spider"},
    {"UDAP", "a user-defined aperture"}, {"UDOB", "a user-defined obscuration"}, {"NSOB", "a non-sequential object"},
    {"DECX", "a decentre"}, {"DECY", "a decentre"}, {"TILX", "a tilt"}, {"TILY", "a tilt"}, {"TILZ", "a tilt"}};

class ZmxParser {
 public:
  explicit ZmxParser(const std::string& file) : file_(file) {}

  [[noreturn]] void fail(const ZmxLine& l, const std::string& value, const std::string& expected) const {
    throw InputError(file_, where(l), value, expected);
  }

  double number(const ZmxLine& l, size_t i) const {
    if (i >= l.words.size()) fail(l, "(missing)", "a number after " + l.key());
    const std::string& w = l.words[i];
    char* end = nullptr;
    const double v = std::strtod(w.c_str(), &end);
    if (w.empty() || *end != '\0' || !std::isfinite(v)) fail(l, "\"" + w.substr(0, 40) + "\"", "a number");
    return v;
  }

  void parse(const std::vector<ZmxLine>& lines) {
    for (const ZmxLine& l : lines) {
      if (l.key() == "SURF") {
        surfaces_.push_back({});
        surfaces_.back().number = int(number(l, 1));
        surfaces_.back().line = l.number;
        if (surfaces_.back().number != int(surfaces_.size()) - 1)
          fail(l, l.words[1], "surface " + std::to_string(surfaces_.size() - 1) + " (surfaces numbered from 0, in order)");
      } else if (surfaces_.empty() || isHeaderKey(l.key())) {
        header(l);
      } else {
        surface(l, surfaces_.back());
      }
    }
    if (surfaces_.size() < 3)
      throw InputError(file_, "SURF", std::to_string(surfaces_.size()) + " surfaces",
                       "a sequential lens: an object surface, at least one lens surface and the image surface "
                       "(a truncated or non-Zemax file?)");
  }

  const ZmxHeader& head() const { return head_; }
  const std::vector<ZmxSurface>& surfaces() const { return surfaces_; }
  std::vector<std::string> unreadKeys() const { return {unread_.begin(), unread_.end()}; }

 private:
  static bool isHeaderKey(const std::string& k) {
    return k == "GCAT" || k == "WAVM" || k == "WAVL" || k == "PWAV" || k == "ENPD" || k == "FNUM" || k == "UNIT" ||
           k == "FTYP" || k == "FLOA";
  }

  std::string where(const ZmxLine& l) const { return "line " + std::to_string(l.number) + ": " + l.key(); }

  void header(const ZmxLine& l) {
    const std::string& k = l.key();
    if (k == "MODE" && l.words.size() > 1 && l.words[1] != "SEQ")
      fail(l, l.words[1], "a sequential lens (MODE SEQ); non-sequential models are not lenses inim reads");
    if (k == "NSOB") fail(l, "NSOB", "a sequential lens (no non-sequential objects)");
    if (k == "NAME") head_.name = l.words.size() > 1 ? l.words[1] : "";
    for (size_t i = 2; k == "NAME" && i < l.words.size(); ++i) head_.name += " " + l.words[i];
    if (k == "UNIT") head_.mmPerUnit = unit(l);
    if (k == "GCAT") head_.catalogues.assign(l.words.begin() + 1, l.words.end());
    if (k == "WAVM") wavelength(l, int(number(l, 1)), number(l, 2));
    for (size_t i = 1; k == "WAVL" && i < l.words.size(); ++i) wavelength(l, int(i), number(l, i));
    if (k == "PWAV") head_.primary = int(number(l, 1));
    if (k == "ENPD") head_.enpd = number(l, 1);
    if (k == "FNUM") head_.fnum = number(l, 1);
    if (k == "FLOA") head_.floatByStop = true;
    if (k == "FTYP" && l.words.size() > 4) head_.wavelengthCount = int(number(l, 4));
  }

  void wavelength(const ZmxLine& l, int slot, double um) {
    if (!(um > 0.0)) fail(l, formatNumber(um), "a wavelength > 0 um");
    head_.wavelengthsUm[slot] = um;
  }

  double unit(const ZmxLine& l) const {
    const std::string u = l.words.size() > 1 ? l.words[1] : "";
    if (u == "MM") return 1.0;
    if (u == "CM") return 10.0;
    if (u == "IN" || u == "INCH") return 25.4;
    if (u == "M" || u == "METER" || u == "METERS" || u == "METRE") return 1000.0;
    fail(l, "\"" + u + "\"", "a lens unit MM, CM, IN or METER");
  }

  void surface(const ZmxLine& l, ZmxSurface& s) {
    const std::string& k = l.key();
    if (k == "TYPE") s.type = l.words.size() > 1 ? l.words[1] : "";
    else if (k == "CURV") s.curv = number(l, 1);
    else if (k == "CONI") s.conic = number(l, 1);
    else if (k == "PARM") s.parm[int(number(l, 1))] = number(l, 2);
    else if (k == "DIAM") s.semiDiameter = number(l, 1);
    else if (k == "STOP") s.stop = true;
    else if (k == "DISZ") disz(l, s);
    else if (k == "GLAS") glass(l, s);
    else if (k == "CLAP") clearAperture(l, s);
    else if (kRefusedSurfaceKeys.count(k))
      throw InputError(file_, s.where() + ", " + k, "line " + std::to_string(l.number),
                       "a surface inim can model (this is " + kRefusedSurfaceKeys.at(k) + ")");
    else if (!kIgnoredSurfaceKeys.count(k))
      unread_.insert(k);
  }

  void disz(const ZmxLine& l, ZmxSurface& s) {
    s.infiniteDisz = l.words.size() > 1 && l.words[1] == "INFINITY";
    s.disz = s.infiniteDisz ? 0.0 : number(l, 1);
  }

  void glass(const ZmxLine& l, ZmxSurface& s) {
    s.glass = l.words.size() > 1 ? l.words[1] : "";
    s.glassLine = l.number;
    if (s.glass == "MIRROR")
      throw InputError(file_, s.where() + ", GLAS", "MIRROR", "a refracting surface (inim's camera lenses have no mirrors)");
    s.modelGlass = l.words.size() > 2 && l.words[2] == "1";
    if (l.words.size() > 5) s.nd = number(l, 4), s.vd = number(l, 5);
  }

  void clearAperture(const ZmxLine& l, ZmxSurface& s) {
    const double inner = number(l, 1), outer = number(l, 2);
    if (inner > 0.0)
      throw InputError(file_, s.where() + ", CLAP", formatNumber(inner),
                       "a circular aperture without a central obscuration (minimum radius 0)");
    s.clearSemi = outer;
  }

  std::string file_;
  ZmxHeader head_;
  std::vector<ZmxSurface> surfaces_;
  std::set<std::string> unread_;
};

// ---- From the file's surfaces to inim's -------------------------------------------------------

class ZmxLensBuilder {
 public:
  ZmxLensBuilder(const std::string& file, const ZmxHeader& head) : file_(file), head_(head) {}

  std::vector<LensSurface> build(const std::vector<ZmxSurface>& zs) {
    std::vector<LensSurface> out;
    for (size_t i = 1; i + 1 < zs.size(); ++i) {
      const ZmxSurface& z = zs[i];
      if (z.infiniteDisz)
        throw InputError(file_, z.where() + ", DISZ", "INFINITY", "a finite thickness (only the object surface may be at infinity)");
      if (z.type == "COORDBRK") {
        coordinateBreak(z, out);
        continue;
      }
      if (z.type != "STANDARD" && z.type != "EVENASPH")
        throw InputError(file_, z.where() + ", TYPE", z.type,
                         "a surface inim can model: STANDARD, EVENASPH, or a coordinate break without decentre or tilt");
      LensSurface s = surface(z);
      const bool sameMedium = s.mediumName == (out.empty() ? "air" : out.back().mediumName);
      if (!z.stop && s.radiusMm == 0.0 && !s.isAsphere() && sameMedium) {
        // A dummy surface: nothing happens there. Before the first lens surface, only the
        // object's distance changes, which the camera sets.
        if (!out.empty()) out.back().thicknessMm += s.thicknessMm;
        continue;
      }
      if (z.stop && (s.radiusMm != 0.0 || s.isAsphere() || !sameMedium)) {
        addStopBefore(z, s, out);
      } else {
        s.isStop = z.stop;
      }
      out.push_back(std::move(s));
    }
    if (out.empty()) throw InputError(file_, "SURF", "no lens surfaces", "at least one refracting surface");
    return out;
  }

  std::vector<std::string> warnings;

 private:
  [[noreturn]] void fail(const ZmxSurface& z, const std::string& key, const std::string& value,
                         const std::string& expected) const {
    throw InputError(file_, z.where() + ", " + key, value, expected);
  }

  void coordinateBreak(const ZmxSurface& z, std::vector<LensSurface>& out) const {
    for (const auto& [n, v] : z.parm)
      if (n >= 1 && n <= 5 && v != 0.0)
        fail(z, "PARM " + std::to_string(n), formatNumber(v),
             "a coordinate break without decentre or tilt (inim's lenses are rotationally symmetric about one axis)");
    if (z.stop) fail(z, "STOP", "on a coordinate break", "the stop on a surface");
    if (!out.empty()) out.back().thicknessMm += z.disz * head_.mmPerUnit;
  }

  LensSurface surface(const ZmxSurface& z) {
    const double u = head_.mmPerUnit;
    LensSurface s;
    s.source = z.where();
    s.radiusMm = z.curv == 0.0 ? 0.0 : u / z.curv;
    s.conic = z.conic;
    s.thicknessMm = z.disz * u;
    const double semi = z.clearSemi >= 0.0 ? z.clearSemi : z.semiDiameter;  // CLAP is the aperture
    s.apertureMm = 2.0 * semi * u;
    if (z.type == "EVENASPH") s.asphere = asphereTerms(z);
    medium(z, s);
    return s;
  }

  // PARM i is the term on r^(2i), in lens units^(1-2i).
  std::vector<double> asphereTerms(const ZmxSurface& z) const {
    std::vector<double> a;
    for (const auto& [n, v] : z.parm) {
      if (n < 1 || n > 8) fail(z, "PARM " + std::to_string(n), formatNumber(v), "even-asphere terms PARM 1 to 8");
      if (a.size() < size_t(n)) a.resize(size_t(n), 0.0);
      a[size_t(n - 1)] = v * std::pow(head_.mmPerUnit, 1.0 - 2.0 * n);
    }
    while (!a.empty() && a.back() == 0.0) a.pop_back();
    return a;
  }

  void medium(const ZmxSurface& z, LensSurface& s) {
    if (z.glass.empty() || z.glass == "AIR") return;
    if (z.modelGlass) return modelGlass(z, s, "");
    const MaterialCatalog& cat = MaterialCatalog::standard();
    for (const std::string& c : head_.catalogues)
      if (cat.hasDielectric(c + ":" + z.glass)) return catalogueGlass(s, c + ":" + z.glass);
    if (cat.hasDielectric(z.glass)) return catalogueGlass(s, z.glass);
    if (z.nd > 1.0 && z.vd > 0.0)
      return modelGlass(z, s, "GLAS " + z.glass + " is in no glass catalogue inim has (" + cataloguesText() +
                                  "); using the model glass the file gives");
    throw InputError(file_, z.where() + ", GLAS (line " + std::to_string(z.glassLine) + ")", z.glass,
                     "a glass of the catalogues (" + cataloguesText() + ") or of spectra/materials.json, "
                     "or the model-glass form with n_d > 1 and V_d > 0");
  }

  void catalogueGlass(LensSurface& s, const std::string& name) const {
    s.medium = MaterialCatalog::standard().dielectric(name);
    s.mediumName = name;
  }

  void modelGlass(const ZmxSurface& z, LensSurface& s, const std::string& warning) {
    if (!(z.nd > 1.0) || !(z.vd > 0.0))
      fail(z, "GLAS", z.glass + " n_d " + formatNumber(z.nd) + " V_d " + formatNumber(z.vd), "a model glass with n_d > 1 and V_d > 0");
    s.medium = std::make_shared<CauchyIor>(CauchyIor::fromAbbe(z.nd, z.vd));
    s.mediumName = "model n_d " + formatNumber(z.nd) + ", V_d " + formatNumber(z.vd);
    if (!warning.empty()) warnings.push_back(z.where() + ": " + warning + " (" + s.mediumName + ")");
  }

  std::string cataloguesText() const {
    std::string t;
    for (const GlassCatalog& c : MaterialCatalog::standard().glassCatalogues()) t += (t.empty() ? "" : ", ") + c.name;
    return t.empty() ? "none" : t;
  }

  // inim's stop is a flat opening in one medium: a stop on a refracting surface becomes a flat
  // stop just in front of it, at its vertex, or at its edge when it bows toward the object.
  void addStopBefore(const ZmxSurface& z, const LensSurface& s, std::vector<LensSurface>& out) const {
    const double edgeSag = s.shape().sag(s.semiAperture() * s.semiAperture());
    const double setBack = std::isfinite(edgeSag) ? std::max(0.0, -edgeSag) : 0.0;
    if (!out.empty()) {
      if (out.back().thicknessMm < setBack)
        fail(z, "STOP", "on a surface bowing " + formatNumber(setBack) + " mm toward the previous one",
             "room in front of the stop surface for a flat stop");
      out.back().thicknessMm -= setBack;
    }
    LensSurface stop;
    stop.isStop = true;
    stop.source = z.where();
    stop.apertureMm = s.apertureMm;
    stop.thicknessMm = setBack;
    if (!out.empty()) stop.medium = out.back().medium, stop.mediumName = out.back().mediumName;
    out.push_back(std::move(stop));
  }

  std::string file_;
  const ZmxHeader& head_;
};

// The file's system aperture (ENPD, else FNUM for an object at infinity) sets the stop's size;
// the stop surface's DIAM is only what the beam was drawn with. The entrance pupil scales with
// the stop, so one analysis of the lens as drawn gives the factor.
void sizeStopForAperture(std::vector<LensSurface>& surfaces, const std::string& name, const std::string& file,
                         const LensDesignInfo& design) {
  if (!(design.entrancePupilMm > 0.0) && !(design.fNumber > 0.0)) return;
  LensSystem drawn(surfaces, name, file);
  drawn.validate();
  const LensInfo info = analyzeLens(drawn);
  const double wanted = design.entrancePupilMm > 0.0 ? design.entrancePupilMm : info.eflMm / design.fNumber;
  if (!(info.entrancePupil.diameterMm > 0.0) || !std::isfinite(wanted)) return;
  surfaces[size_t(drawn.stopIndex())].apertureMm *= wanted / info.entrancePupil.diameterMm;
}

LensDesignInfo designInfo(const ZmxHeader& h) {
  LensDesignInfo d;
  for (const auto& [slot, um] : h.wavelengthsUm)
    if (h.wavelengthCount <= 0 || slot <= h.wavelengthCount) d.wavelengthsNm.push_back(um * 1e3);
  if (auto it = h.wavelengthsUm.find(h.primary); it != h.wavelengthsUm.end()) d.primaryWavelengthNm = it->second * 1e3;
  d.entrancePupilMm = h.floatByStop ? 0.0 : h.enpd * h.mmPerUnit;
  d.fNumber = h.floatByStop ? 0.0 : h.fnum;
  return d;
}

}  // namespace

LensSystem parseZmxLens(const std::string& bytes, const std::string& file, const LensLoadOptions& opt) {
  (void)opt;  // a .zmx file fixes its own conventions and glasses
  ZmxParser parser(file);
  parser.parse(splitLines(utf8FromBytes(bytes, file)));
  ZmxLensBuilder builder(file, parser.head());
  std::vector<LensSurface> surfaces = builder.build(parser.surfaces());
  std::string name = parser.head().name.empty() ? fs::path(file).stem().string() : parser.head().name;
  LensDesignInfo design = designInfo(parser.head());
  sizeStopForAperture(surfaces, name, file, design);
  LensSystem lens(std::move(surfaces), name, file);
  design.warnings = std::move(builder.warnings);
  const std::vector<std::string> unread = parser.unreadKeys();
  if (!unread.empty()) {
    std::string list;
    for (const std::string& k : unread) list += (list.empty() ? "" : ", ") + k;
    design.warnings.push_back("keywords not read (no effect on the lens as inim models it): " + list);
  }
  lens.setDesign(std::move(design));
  lens.validate();
  return lens;
}

}  // namespace inim
