#include "display/panel.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <memory>

#include "core/error.h"

namespace fs = std::filesystem;

namespace inim {

const char* channelName(int channel) {
  static const char* names[] = {"R", "G", "B"};
  return (channel >= 0 && channel < kNumPrimaries) ? names[channel] : "?";
}

static int channelIndex(const std::string& s) {
  for (int c = 0; c < kNumPrimaries; ++c)
    if (s == channelName(c)) return c;
  return -1;
}

// ---------------------------------------------------------------- primaries

SpectrumPtr primarySpectrum(const PrimarySpec& p) {
  if (p.kind == PrimarySpec::Kind::Gaussian)
    return std::make_shared<GaussianSpectrum>(float(p.meanNm), float(p.fwhmNm), float(p.scale));
  auto s = loadSpectrumCSV(p.csvPath, p.csvColumn);
  if (p.scale != 1.0) return std::make_shared<ScaledSpectrum>(s, float(p.scale));
  return s;
}

double primaryPeakNm(const PrimarySpec& p) {
  if (p.kind == PrimarySpec::Kind::Gaussian) return p.meanNm;
  auto s = loadSpectrumCSV(p.csvPath, p.csvColumn);
  const auto& v = s->values();
  size_t i = size_t(std::max_element(v.begin(), v.end()) - v.begin());
  return s->lambdas()[i];
}

// ---------------------------------------------------------------- EOTF

double Eotf::decode(double e) const {
  e = std::clamp(e, 0.0, 1.0);
  switch (kind) {
    case Kind::Linear: return e;
    case Kind::SRGB: return e <= 0.04045 ? e / 12.92 : std::pow((e + 0.055) / 1.055, 2.4);
    case Kind::Gamma: return std::pow(e, gamma);
  }
  return e;
}

double Eotf::encode(double l) const {
  l = std::clamp(l, 0.0, 1.0);
  switch (kind) {
    case Kind::Linear: return l;
    case Kind::SRGB: return l <= 0.0031308 ? 12.92 * l : 1.055 * std::pow(l, 1.0 / 2.4) - 0.055;
    case Kind::Gamma: return std::pow(l, 1.0 / gamma);
  }
  return l;
}

std::string Eotf::name() const {
  switch (kind) {
    case Kind::Linear: return "linear";
    case Kind::SRGB: return "sRGB";
    case Kind::Gamma: {
      char buf[32];
      std::snprintf(buf, sizeof buf, "gamma %g", gamma);
      return buf;
    }
  }
  return "?";
}

// ---------------------------------------------------------------- subpixels

static double polygonArea(const std::vector<std::array<double, 2>>& p) {
  double a = 0.0;
  for (size_t i = 0; i < p.size(); ++i) {
    const auto& q = p[i];
    const auto& r = p[(i + 1) % p.size()];
    a += q[0] * r[1] - r[0] * q[1];
  }
  return 0.5 * std::abs(a);
}

double SubpixelLayout::emittingArea(int channel) const {
  double a = 0.0;
  for (const auto& s : subpixels)
    if (s.channel == channel) a += polygonArea(s.polygon);
  return a;
}

static std::vector<std::array<double, 2>> rect(double u0, double v0, double u1, double v1) {
  return {{u0, v0}, {u1, v0}, {u1, v1}, {u0, v1}};
}
static std::vector<std::array<double, 2>> diamond(double cu, double cv, double h) {
  return {{cu, cv - h}, {cu + h, cv}, {cu, cv + h}, {cu - h, cv}};
}

SubpixelLayout rgbStripeLayout(double fillFactor, const std::string& order) {
  SubpixelLayout L;
  L.type = "rgb-stripe";
  L.fillFactor = fillFactor;
  double margin = (1.0 - fillFactor) * 0.5;
  for (int s = 0; s < 3; ++s) {
    int c = channelIndex(std::string(1, order[size_t(s)]));
    double u0 = (s + margin) / 3.0, u1 = (s + 1 - margin) / 3.0;
    L.subpixels.push_back({c, rect(u0, margin, u1, 1.0 - margin)});
  }
  return L;
}

SubpixelLayout diamondLayout(double fillFactor) {
  // PenTile-style RGBG on a 2 x 2 pixel tile: every pixel has a small green diamond; the
  // large red and blue diamonds alternate on a checkerboard. Sizes scale with fillFactor
  // (0.8 gives half-diagonals 0.28 px and 0.18 px).
  SubpixelLayout L;
  L.type = "diamond";
  L.fillFactor = fillFactor;
  L.tileW = L.tileH = 2;
  double s = fillFactor / 0.8;
  for (int j = 0; j < 2; ++j)
    for (int i = 0; i < 2; ++i) {
      int big = ((i + j) % 2 == 0) ? 0 : 2;
      L.subpixels.push_back({big, diamond(i + 0.30, j + 0.5, 0.28 * s)});
      L.subpixels.push_back({1, diamond(i + 0.78, j + 0.5, 0.18 * s)});
    }
  return L;
}

static SubpixelLayout parseSubpixels(const JsonObject& o) {
  std::string type = o.choice("type", {"rgb-stripe", "diamond", "custom"});
  SubpixelLayout L;
  if (type == "rgb-stripe") {
    double ff = o.positive("fill_factor", 0.8);
    if (ff > 1.0) o.fail("fill_factor", jsonValueText(o.raw("fill_factor")), "a fraction in (0, 1]");
    std::string order = o.string("order", "RGB");
    std::string sorted = order;
    std::sort(sorted.begin(), sorted.end());
    if (sorted != "BGR") o.fail("order", "\"" + order + "\"", "a permutation of \"RGB\"");
    L = rgbStripeLayout(ff, order);
  } else if (type == "diamond") {
    double ff = o.positive("fill_factor", 0.8);
    if (ff > 1.0) o.fail("fill_factor", jsonValueText(o.raw("fill_factor")), "a fraction in (0, 1]");
    L = diamondLayout(ff);
  } else {
    L.type = "custom";
    L.fillFactor = 0.0;
    const std::vector<int> t = o.integers("tile_px", 1, std::numeric_limits<int>::max());
    if (t.size() != 2) o.fail("tile_px", jsonValueText(o.raw("tile_px")), "[width, height] in whole pixels, each >= 1");
    L.tileW = t[0];
    L.tileH = t[1];
    auto subs = o.objects("subpixels");
    if (subs.empty()) o.fail("subpixels", "[]", "at least one subpixel");
    for (const auto& s : subs) {
      Subpixel sp;
      std::string ch = s.choice("channel", {"R", "G", "B"});
      sp.channel = channelIndex(ch);
      const Json& poly = s.raw("polygon");
      bool ok = poly.is_array() && poly.size() >= 3;
      if (ok)
        for (const auto& v : poly) {
          if (!v.is_array() || v.size() != 2 || !v[0].is_number() || !v[1].is_number()) {
            ok = false;
            break;
          }
          double u = v[0].get<double>(), w = v[1].get<double>();
          if (!(u >= 0.0 && u <= L.tileW && w >= 0.0 && w <= L.tileH)) {
            ok = false;
            break;
          }
          sp.polygon.push_back({u, w});
        }
      if (!ok)
        s.fail("polygon", jsonValueText(poly),
               "at least 3 [u, v] vertices in pixel units inside the tile [0, " +
                   std::to_string(L.tileW) + "] x [0, " + std::to_string(L.tileH) + "]");
      if (polygonArea(sp.polygon) <= 0.0) s.fail("polygon", jsonValueText(poly), "a polygon with area > 0");
      s.rejectUnknown();
      L.subpixels.push_back(std::move(sp));
    }
    for (int c = 0; c < kNumPrimaries; ++c)
      if (L.emittingArea(c) <= 0.0)
        o.fail("subpixels", "(no " + std::string(channelName(c)) + " subpixel)",
               "at least one subpixel of each channel R, G, B");
  }
  o.rejectUnknown();
  return L;
}

// ---------------------------------------------------------------- panel

std::vector<std::string> readAssumptions(const JsonObject& o) {
  std::vector<std::string> r;
  if (!o.has("assumptions")) return r;
  const Json& a = o.raw("assumptions");
  if (!a.is_array()) o.fail("assumptions", jsonValueText(a), "an array of strings");
  for (const auto& s : a) {
    if (!s.is_string()) o.fail("assumptions", jsonValueText(a), "an array of strings");
    r.push_back(s.get<std::string>());
  }
  return r;
}

static PrimarySpec parsePrimary(const JsonObject& o) {
  PrimarySpec p;
  bool g = o.has("gaussian"), c = o.has("csv");
  if (g == c) o.fail(g ? "csv" : "gaussian", g ? "(both given)" : "(missing)", "exactly one of \"gaussian\" or \"csv\"");
  if (g) {
    JsonObject go = o.object("gaussian");
    p.kind = PrimarySpec::Kind::Gaussian;
    p.meanNm = go.positive("mean_nm");
    p.fwhmNm = go.positive("fwhm_nm");
    if (p.meanNm < 360.0 || p.meanNm > 830.0)
      go.fail("mean_nm", jsonValueText(go.raw("mean_nm")), "a wavelength in 360..830 nm");
    go.rejectUnknown();
  } else {
    JsonObject co = o.object("csv");
    p.kind = PrimarySpec::Kind::Csv;
    p.csvPath = co.path("file");
    // Checked here, where the panel file can be named: a missing spectrum once passed
    // `display info` and was blamed on --triad-wavelengths by `eia`.
    std::error_code ec;
    if (!fs::is_regular_file(p.csvPath, ec))
      co.fail("file", jsonValueText(co.raw("file")), "an existing CSV file (" + p.csvPath + " not found)");
    p.csvColumn = co.string("column", "relative_power");
    co.rejectUnknown();
  }
  p.scale = o.positive("scale", 1.0);
  o.rejectUnknown();
  return p;
}

Panel parsePanel(const JsonObject& o) {
  Panel p;
  p.file = o.file();
  p.name = o.string("name");
  const std::vector<int> res = o.integers("resolution_px", 1, std::numeric_limits<int>::max());
  if (res.size() != 2)
    o.fail("resolution_px", jsonValueText(o.raw("resolution_px")), "[width, height] in whole pixels, each >= 1");
  p.widthPx = res[0];
  p.heightPx = res[1];
  p.pixelPitchMm = o.positive("pixel_pitch_mm");

  JsonObject prim = o.object("primaries");
  for (int c = 0; c < kNumPrimaries; ++c) p.primaries[size_t(c)] = parsePrimary(prim.object(channelName(c)));
  prim.rejectUnknown();

  p.peakLuminanceCdM2 = o.positive("peak_luminance_cd_m2");
  if (o.has("eotf")) {
    const Json& e = o.raw("eotf");
    if (e.is_string()) {
      std::string s = o.choice("eotf", {"sRGB", "linear"});
      p.eotf.kind = s == "sRGB" ? Eotf::Kind::SRGB : Eotf::Kind::Linear;
    } else if (e.is_object()) {
      JsonObject eo = o.object("eotf");
      p.eotf.kind = Eotf::Kind::Gamma;
      p.eotf.gamma = eo.positive("gamma");
      eo.rejectUnknown();
    } else {
      o.fail("eotf", jsonValueText(e), "\"sRGB\", \"linear\" or {\"gamma\": 2.2}");
    }
  }
  p.angularProfile = o.choice("angular_profile", {"lambertian", "uniform"}, "lambertian");
  if (o.has("cover_glass") && !o.raw("cover_glass").is_null()) {
    JsonObject cg = o.object("cover_glass");
    CoverGlass g;
    g.thicknessMm = cg.positive("thickness_mm");
    g.material = cg.string("material");
    cg.rejectUnknown();
    p.coverGlass = g;
  }
  if (o.has("subpixel_layout"))
    p.subpixels = parseSubpixels(o.object("subpixel_layout"));
  else
    p.subpixels = rgbStripeLayout(0.8);
  p.assumptions = readAssumptions(o);
  o.rejectUnknown();
  return p;
}

Panel loadPanel(const std::string& path) {
  Json j = readJsonFile(path);
  return parsePanel(JsonObject(j, path, ""));
}

}  // namespace inim
