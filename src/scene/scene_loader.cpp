#include "scene/scene_loader.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <map>
#include <unordered_map>

#include "core/error.h"
#include "core/image.h"
#include "core/interrupt.h"
#include "core/size_budget.h"
#include "core/file_kinds.h"
#include "core/format.h"
#include "core/output_file.h"
#include "scene/obj_loader.h"
#include "spectral/cie.h"
#include "spectral/rgb_to_spectrum.h"

namespace inim {

namespace {

namespace fs = std::filesystem;

std::string joinNames(const std::vector<std::string>& names) {
  std::string s;
  for (const auto& n : names) s += (s.empty() ? "" : ", ") + n;
  return s.empty() ? "none" : s;
}

std::string quoteStr(const std::string& s) { return "\"" + s + "\""; }

// A smooth step filter edge: lo + (hi - lo) * logistic((lambda - cut) / s), with the
// 10%-90% transition over `width` nm (s = width / (2 ln 9)).
class EdgeSpectrum final : public Spectrum {
 public:
  EdgeSpectrum(float cut, float width, float lo, float hi, bool longpass)
      : cut_(cut), s_(width / (2.0f * std::log(9.0f))), lo_(lo), hi_(hi), sign_(longpass ? 1.0f : -1.0f) {}
  float operator()(float l) const override {
    float x = sign_ * (l - cut_) / s_;
    return lo_ + (hi_ - lo_) / (1.0f + std::exp(-x));
  }
  float maxValue() const override { return std::max(lo_, hi_); }

 private:
  float cut_, s_, lo_, hi_, sign_;
};

SpectrumPtr borrowed(const Spectrum& s) {
  return SpectrumPtr(&s, [](const Spectrum*) {});
}

// A file named at obj[key], relative to the scene file, else under the data folder.
std::string resolveFile(const JsonObject& obj, const std::string& key) {
  std::string raw = obj.string(key);
  std::string p = obj.path(key);
  if (fs::is_regular_file(p)) return p;
  if (fs::path(raw).is_relative()) {
    std::string q = dataPath(raw);
    if (fs::is_regular_file(q)) return q;
  }
  obj.fail(key, quoteStr(raw), "an existing file (not found: " + p + ")");
}

SpectrumPtr namedIlluminant(const JsonObject& obj, const std::string& key, const std::string& name) {
  if (name == "D65") return borrowed(cie::D65());
  if (name == "A") return borrowed(cie::A());
  if (name == "E") return std::make_shared<ConstantSpectrum>(1.0f);
  obj.fail(key, quoteStr(name), "an illuminant name: D65, A or E");
}

// An RGB colour as the spectrum its role needs: an illuminant (emission), unbounded (generic),
// else an albedo in [0, 1].
SpectrumPtr rgbSpectrum(const JsonObject& obj, const std::string& key, const std::string& role) {
  const Vec3 rgb(obj.vec3(key));
  if (rgb.x < 0 || rgb.y < 0 || rgb.z < 0) obj.fail(key, jsonValueText(obj.raw(key)), "non-negative RGB");
  if (role == "emission") return std::make_shared<RGBIlluminantSpectrum>(rgb);
  if (role == "generic") return std::make_shared<RGBUnboundedSpectrum>(rgb);
  if (rgb.x > 1 || rgb.y > 1 || rgb.z > 1) obj.fail(key, jsonValueText(obj.raw(key)), "RGB in [0, 1]");
  return std::make_shared<RGBAlbedoSpectrum>(rgb);
}

// {"type": "gaussian", "mean_nm", "fwhm_nm", "peak" = 1, "base" = 0}: base + a Gaussian rising
// to peak.
SpectrumPtr gaussianSpectrum(const JsonObject& o) {
  float mean = float(o.positive("mean_nm")), fwhm = float(o.positive("fwhm_nm"));
  float peak = float(o.number("peak", 1.0)), base = float(o.number("base", 0.0));
  auto g = std::make_shared<GaussianSpectrum>(mean, fwhm, peak - base);
  if (base == 0.0f) return g;
  struct Offset final : Spectrum {
    SpectrumPtr g;
    float b;
    float operator()(float l) const override { return b + (*g)(l); }
    float maxValue() const override { return b + g->maxValue(); }
  };
  auto off = std::make_shared<Offset>();
  off->g = g;
  off->b = base;
  return off;
}

// {"type": "csv", "file", "column" = the first after wavelength_nm}.
SpectrumPtr csvFileSpectrum(const JsonObject& o) {
  std::string file = resolveFile(o, "file");
  std::string column;
  if (o.has("column")) {
    column = o.string("column");
  } else {
    std::vector<std::string> cols;
    try {
      cols = csvColumns(file);
    } catch (const InputError& e) {
      o.fail("file", quoteStr(file), std::string("a readable spectrum CSV (") + e.what() + ")");
    }
    if (cols.empty()) o.fail("file", quoteStr(file), "a CSV with a data column after wavelength_nm");
    column = cols.front();
  }
  try {
    return loadSpectrumCSV(file, column);
  } catch (const InputError& e) {
    o.fail("file", quoteStr(file) + " column " + quoteStr(column),
           std::string("a readable spectrum CSV (") + e.what() + ")");
  }
}

// {"type": "table", "lambda_nm": [...], "values": [...]}: piecewise linear.
SpectrumPtr tableSpectrum(const JsonObject& o) {
  std::vector<double> l = o.numbers("lambda_nm"), val = o.numbers("values");
  if (l.size() < 2 || l.size() != val.size())
    o.fail("values", jsonValueText(o.raw("values")), "as many values as lambda_nm entries (at least 2)");
  for (size_t i = 1; i < l.size(); ++i)
    if (!(l[i] > l[i - 1])) o.fail("lambda_nm", jsonValueText(o.raw("lambda_nm")), "increasing wavelengths");
  return std::make_shared<PiecewiseLinearSpectrum>(std::vector<float>(l.begin(), l.end()),
                                                   std::vector<float>(val.begin(), val.end()));
}

// A spectrum object: {"type": ..., its parameters}; unknown keys refused.
SpectrumPtr typedSpectrum(const JsonObject& o, const std::string& role) {
  const std::string type = o.choice("type", {"constant", "rgb", "blackbody", "illuminant", "gaussian", "csv", "table",
                                             "longpass", "shortpass"});
  SpectrumPtr s;
  if (type == "constant") {
    s = std::make_shared<ConstantSpectrum>(float(o.number("value")));
  } else if (type == "rgb") {
    s = rgbSpectrum(o, "rgb", role);
  } else if (type == "blackbody") {
    s = std::make_shared<BlackbodySpectrum>(float(o.positive("temperature_k")));
  } else if (type == "illuminant") {
    s = namedIlluminant(o, "name", o.string("name"));
  } else if (type == "gaussian") {
    s = gaussianSpectrum(o);
  } else if (type == "csv") {
    s = csvFileSpectrum(o);
  } else if (type == "table") {
    s = tableSpectrum(o);
  } else {  // longpass / shortpass
    float cut = float(o.positive("cut_nm"));
    float width = float(o.positive("width_nm", 20.0));
    float lo = float(o.number("min", 0.0)), hi = float(o.number("max", 1.0));
    s = std::make_shared<EdgeSpectrum>(cut, width, lo, hi, type == "longpass");
  }
  o.rejectUnknown();
  return s;
}

}  // namespace

SpectrumPtr parseSpectrum(const JsonObject& obj, const std::string& key, const std::string& role) {
  const Json& v = obj.raw(key);
  SpectrumPtr s;
  if (v.is_number()) {
    s = std::make_shared<ConstantSpectrum>(float(obj.number(key)));
  } else if (v.is_array()) {
    s = rgbSpectrum(obj, key, role);
  } else if (v.is_string()) {
    s = namedIlluminant(obj, key, v.get<std::string>());
  } else if (v.is_object()) {
    s = typedSpectrum(JsonObject(v, obj.file(), obj.keyPath(key)), role);
  } else {
    obj.fail(key, jsonValueText(v), "a spectrum: a number, [r, g, b], an illuminant name or an object with \"type\"");
  }
  // Range checks on the baked values.
  BakedSpectrum b(*s);
  if (role == "reflectance" || role == "transmittance") {
    if (b.minValue() < 0.0f || b.maxValue() > 1.0001f)
      obj.fail(key, jsonValueText(v), std::string("values in [0, 1] (a ") + role + ")");
  } else if (role == "emission") {
    if (b.minValue() < 0.0f) obj.fail(key, jsonValueText(v), "non-negative emission");
  }
  return s;
}

namespace {

// ---------------------------------------------------------------------------------------------

// Emission spectrum * scale, luminance-normalised first when asked.
BakedSpectrum parseEmission(const JsonObject& o, const std::string& spectrumKey, bool* twoSided) {
  SpectrumPtr s = o.has(spectrumKey) ? parseSpectrum(o, spectrumKey, "emission") : borrowed(cie::D65());
  // Named illuminants, blackbodies and Gaussians have no absolute scale: normalise them to
  // unit luminance by default. Numbers, RGB, CSV and tables are taken as given.
  bool relative = true;
  if (o.has(spectrumKey)) {
    const Json& v = o.raw(spectrumKey);
    if (v.is_number() || v.is_array()) relative = false;
    if (v.is_object()) {
      std::string t = v.value("type", "");
      relative = t == "blackbody" || t == "illuminant" || t == "gaussian";
    }
  }
  bool normalize = o.boolean("normalize", relative);
  float scale = float(o.number("scale", 1.0));
  if (scale < 0.0f) o.fail("scale", jsonValueText(o.raw("scale")), "a number >= 0");
  BakedSpectrum b(*s);
  if (normalize) {
    float y = b.luminance();
    if (!(y > 0.0f)) o.fail(spectrumKey, "(luminance 0)", "a spectrum with non-zero luminance to normalise");
    b = b.scaled(1.0f / y);
  }
  if (twoSided) *twoSided = o.boolean("two_sided", false);
  return b.scaled(scale);
}

TextureType textureType(const std::string& t) {
  if (t == "image") return TextureType::Image;
  if (t == "checker") return TextureType::Checker;
  if (t == "ruler") return TextureType::Ruler;
  if (t == "slanted_edge") return TextureType::SlantedEdge;
  if (t == "siemens_star") return TextureType::SiemensStar;
  if (t == "scale_target") return TextureType::ScaleTarget;
  return TextureType::Constant;
}

ReflectanceTexture parseReflectance(const JsonObject& m, const std::string& key) {
  if (!m.has(key)) return ReflectanceTexture::constant(BakedSpectrum(0.5f));
  const Json& v = m.raw(key);
  if (v.is_object() && v.contains("type")) {
    std::string t = v["type"].is_string() ? v["type"].get<std::string>() : "";
    TextureType tt = textureType(t);
    if (tt != TextureType::Constant) {
      JsonObject o(v, m.file(), m.keyPath(key));
      o.string("type");
      ReflectanceTexture tex;
      if (tt == TextureType::Image) {
        std::string file = resolveFile(o, "file");
        const std::optional<FileKind> kind = fileKindOf(file);
        bool floatFormat = kind == FileKind::Exr || kind == FileKind::Hdr || kind == FileKind::Tiff;
        std::string enc = o.choice("encoding", {"srgb", "linear"}, floatFormat ? "linear" : "srgb");
        bool repeat = o.boolean("repeat", false);
        Image img;
        try {
          img = readImage(file, true);
        } catch (const InputError& e) {
          o.fail("file", quoteStr(file), std::string("a readable image (") + e.what() + ")");
        }
        if (img.width <= 0 || img.height <= 0) o.fail("file", quoteStr(file), "a non-empty image");
        if (enc == "srgb")
          for (float& x : img.data) x = srgbToLinear(std::clamp(x, 0.0f, 1.0f));
        tex = ReflectanceTexture::image(img, repeat);
      } else {
        BakedSpectrum bg(o.has("background") ? BakedSpectrum(*parseSpectrum(o, "background", "reflectance"))
                                             : BakedSpectrum(0.85f));
        BakedSpectrum ink(o.has("ink") ? BakedSpectrum(*parseSpectrum(o, "ink", "reflectance"))
                                       : BakedSpectrum(0.03f));
        PatternParams p;
        if (o.has("center_mm")) {
          std::vector<double> c = o.numbers("center_mm");
          if (c.size() != 2) o.fail("center_mm", jsonValueText(o.raw("center_mm")), "[s, t] in mm");
          p.center_mm = Vec2(float(c[0]), float(c[1]));
        }
        switch (tt) {
          case TextureType::Checker: p.period_mm = float(o.positive("period_mm", 5.0)); break;
          case TextureType::Ruler:
            p.tick_mm = float(o.positive("tick_mm", 1.0));
            p.line_mm = float(o.positive("line_mm", 0.25));
            break;
          case TextureType::SlantedEdge: p.angle_deg = float(o.number("angle_deg", 5.0)); break;
          case TextureType::SiemensStar:
            p.spokes = o.has("spokes") ? o.integer("spokes", 1, std::numeric_limits<int>::max()) : 36;
            p.radius_mm = float(o.positive("radius_mm", 10.0));
            break;
          default: {  // scale target
            std::vector<double> sz = o.numbers("size_mm");
            if (sz.size() != 2 || !(sz[0] > 0) || !(sz[1] > 0))
              o.fail("size_mm", jsonValueText(o.raw("size_mm")), "[width, height] in mm, both > 0");
            p.size_mm = Vec2(float(sz[0]), float(sz[1]));
            p.tick_mm = float(o.positive("tick_mm", 1.0));
            p.line_mm = float(o.positive("line_mm", 0.25));
            p.period_mm = float(o.positive("period_mm", 2.0));
            p.angle_deg = float(o.number("angle_deg", 5.0));
            p.spokes = o.has("spokes") ? o.integer("spokes", 1, std::numeric_limits<int>::max()) : 24;
            break;
          }
        }
        tex = ReflectanceTexture::pattern(tt, bg, ink, p);
      }
      o.rejectUnknown();
      return tex;
    }
  }
  return ReflectanceTexture::constant(BakedSpectrum(*parseSpectrum(m, key, "reflectance")));
}

Material parseMaterial(const JsonObject& m, const std::string& name) {
  Material mat;
  mat.name = name;
  std::string type = m.choice("type", {"diffuse", "dielectric", "conductor", "emitter"});
  const MaterialCatalog* catalog = nullptr;
  auto cat = [&]() -> const MaterialCatalog& {
    if (!catalog) catalog = &MaterialCatalog::standard();
    return *catalog;
  };
  if (type == "diffuse") {
    mat.type = MaterialType::Diffuse;
    mat.reflectance = parseReflectance(m, "reflectance");
  } else if (type == "dielectric") {
    bool thin = m.boolean("thin", false);
    mat.type = thin ? MaterialType::ThinDielectric : MaterialType::Dielectric;
    if (m.has("ior")) {
      const Json& v = m.raw("ior");
      if (v.is_number()) {
        double n = m.positive("ior");
        if (n < 1.0 || n > 10.0) m.fail("ior", jsonValueText(v), "an index in [1, 10]");
        mat.ior = std::make_shared<ConstantIor>(float(n));
      } else if (v.is_string()) {
        std::string n = v.get<std::string>();
        if (!cat().hasDielectric(n))
          m.fail("ior", quoteStr(n), "a constant index or a dielectric of spectra/materials.json (known: " +
                                       cat().dielectricsText() + ")");
        mat.ior = cat().dielectric(n);
      } else {
        m.fail("ior", jsonValueText(v), "a number or a catalog name");
      }
    } else {
      mat.ior = std::make_shared<ConstantIor>(1.5f);
    }
    mat.dispersive = mat.ior->isDispersive();
    if (mat.dispersive) {
      struct N final : Spectrum {
        IorPtr ior;
        float operator()(float l) const override { return ior->n(l); }
        float maxValue() const override { return 10.0f; }
      } nspec;
      nspec.ior = mat.ior;
      mat.n = BakedSpectrum(nspec);
    } else {
      mat.n = BakedSpectrum(mat.ior->n(550.0f));
    }
    if (!(mat.n.minValue() > 0.0f)) m.fail("ior", jsonValueText(m.raw("ior")), "an index > 0 at every wavelength");
    if (m.has("transmittance")) {
      BakedSpectrum T(*parseSpectrum(m, "transmittance", "transmittance"));
      if (thin) {
        mat.tau = T;
        mat.negLogTau = T.map([](float t) { return t > 0.0f ? -std::log(t) : 1e30f; });
      } else {
        double d = m.positive("transmittance_thickness_mm");
        // Beer-Lambert: T = exp(-sigma d).
        mat.sigma = T.map([d](float t) { return t > 0.0f ? float(-std::log(t) / d) : 1e30f; });
        mat.absorbing = mat.sigma.maxValue() > 0.0f;
      }
    }
  } else if (type == "conductor") {
    mat.type = MaterialType::Conductor;
    if (m.has("metal")) {
      std::string n = m.string("metal");
      if (!cat().hasConductor(n))
        m.fail("metal", quoteStr(n), "a conductor of spectra/materials.json (known: " +
                                       joinNames(cat().conductorNames()) + ")");
      const ConductorIndex& ci = cat().conductor(n);
      mat.eta = BakedSpectrum(*ci.eta);
      mat.k = BakedSpectrum(*ci.k);
    } else {
      mat.eta = BakedSpectrum(*parseSpectrum(m, "eta", "generic"));
      mat.k = BakedSpectrum(*parseSpectrum(m, "k", "generic"));
    }
    if (!(mat.eta.minValue() > 0.0f) || mat.k.minValue() < 0.0f)
      m.fail(m.has("metal") ? "metal" : "eta", "(n <= 0 or k < 0)", "n > 0 and k >= 0");
    double a = m.number("roughness", 0.0);
    if (a < 0.0 || a > 1.0) m.fail("roughness", jsonValueText(m.raw("roughness")), "a GGX alpha in [0, 1]");
    mat.alpha = float(a);
  } else {  // emitter
    mat.type = MaterialType::Emitter;
    mat.emissive = true;
    mat.Le = parseEmission(m, "spectrum", &mat.twoSided);
  }
  if (type != "emitter" && m.has("emission")) {
    JsonObject e = m.object("emission");
    mat.emissive = true;
    mat.Le = parseEmission(e, "spectrum", &mat.twoSided);
    e.rejectUnknown();
  }
  m.rejectUnknown();
  return mat;
}

Transform parseTransform(const JsonObject& o) {
  Vec3d t = o.vec3("translate_mm", Vec3d(0.0));
  Vec3d r = o.vec3("rotate_deg", Vec3d(0.0));
  Vec3d s(1.0);
  if (o.has("scale")) {
    if (o.raw("scale").is_number()) s = Vec3d(o.number("scale"));
    else s = o.vec3("scale");
    if (!(s.x > 0.0 && s.y > 0.0 && s.z > 0.0))
      o.fail("scale", jsonValueText(o.raw("scale")), "scale factors > 0");
  }
  try {
    return Transform::translate(t) * Transform::rotateXYZ(r) * Transform::scale(s, o.keyPath("scale"));
  } catch (const InputError& e) {
    throw e.withFile(o.file());
  }
}

std::vector<double> sizeN(const JsonObject& o, const std::string& key, size_t n) {
  std::vector<double> v = o.numbers(key);
  if (v.size() != n) o.fail(key, jsonValueText(o.raw(key)), std::to_string(n) + " sizes in mm");
  for (double x : v)
    if (!(x > 0.0)) o.fail(key, jsonValueText(o.raw(key)), "sizes > 0 (mm)");
  return v;
}

// A quad (p0..p3 counter-clockwise seen from its front) appended to a mesh, with st in mm
// (face-local) and uv in [0,1].
void addQuad(Shape& s, const Transform& M, const Vec3 p[4], const Vec2 st[4]) {
  uint32_t base = uint32_t(s.P.size());
  const Vec2 uv[4] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  for (int i = 0; i < 4; ++i) {
    s.P.push_back(M.point(p[i]));
    s.ST.push_back(st[i]);
    s.UV.push_back(uv[i]);
  }
  s.indices.insert(s.indices.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
}

void buildRectangle(Shape& s, const Transform& M, float w, float h) {
  float x = 0.5f * w, y = 0.5f * h;
  const Vec3 p[4] = {{-x, -y, 0}, {x, -y, 0}, {x, y, 0}, {-x, y, 0}};
  const Vec2 st[4] = {{-x, -y}, {x, -y}, {x, y}, {-x, y}};
  addQuad(s, M, p, st);
}

void buildBox(Shape& s, const Transform& M, Vec3 size) {
  Vec3 h = 0.5f * size;
  // For each face: outward normal axis, and two in-plane axes (u, v) with u x v = normal.
  struct Face { int n; float sign; int u; int v; };
  const Face faces[6] = {{2, 1, 0, 1}, {2, -1, 1, 0}, {0, 1, 1, 2}, {0, -1, 2, 1}, {1, 1, 2, 0}, {1, -1, 0, 2}};
  for (const Face& f : faces) {
    Vec3 p[4];
    Vec2 st[4];
    const float cu[4] = {-1, 1, 1, -1}, cv[4] = {-1, -1, 1, 1};
    for (int i = 0; i < 4; ++i) {
      Vec3 q(0.0f);
      q[f.n] = f.sign * h[f.n];
      q[f.u] = cu[i] * h[f.u];
      q[f.v] = cv[i] * h[f.v];
      p[i] = q;
      st[i] = Vec2(q[f.u], q[f.v]);
    }
    addQuad(s, M, p, st);
  }
}

struct Loader {
  std::string file;
  SceneDescription d;
  std::map<std::string, int> materialIndex;
  std::unordered_map<int, size_t> objectOfId;  // an id -> the object that has it: one look-up per object

  int materialFor(const JsonObject& o) {
    const Json& v = o.raw("material");
    if (v.is_string()) {
      std::string n = v.get<std::string>();
      auto it = materialIndex.find(n);
      if (it == materialIndex.end()) {
        std::vector<std::string> names;
        for (const auto& [k, i] : materialIndex)
          if (k.rfind("light:", 0) != 0 && k.rfind("inline:", 0) != 0) names.push_back(k);
        o.fail("material", quoteStr(n), "a material defined under \"materials\" (known: " + joinNames(names) + ")");
      }
      return it->second;
    }
    if (v.is_object()) {
      std::string name = "inline:" + o.keyPath("material");
      d.materials.push_back(parseMaterial(o.object("material"), name));
      materialIndex[name] = int(d.materials.size()) - 1;
      return int(d.materials.size()) - 1;
    }
    o.fail("material", jsonValueText(v), "a material name or a material object");
  }

  void finalizeShape(Shape& s, const JsonObject& o) {
    size_t dropped = s.finalize();
    d.droppedTriangles += dropped;
    if (s.type == ShapeType::Mesh && s.numTriangles() == 0)
      o.fail(o.has("file") ? "file" : "type", o.has("file") ? quoteStr(o.string("file")) : quoteStr("mesh"),
             "a mesh with at least one non-degenerate triangle");
    if (!std::isfinite(s.extent) || !(s.extent > 0.0f))
      o.fail("type", "(degenerate or non-finite extent)", "a shape with finite, non-zero size");
  }

  void parseObject(const JsonObject& o, size_t index) {
    SceneObject so;
    throwIfInterrupted();  // a scene of a million objects still stops at once
    so.id = o.integer("id", int(index) + 1);
    if (auto [it, added] = objectOfId.emplace(so.id, d.objects.size()); !added)
      o.fail("id", std::to_string(so.id), "an id no other object has (\"" + d.objects[it->second].name + "\" has it)");
    so.name = o.string("name", "object" + std::to_string(so.id));
    so.type = o.choice("type", {"sphere", "box", "rectangle", "disk", "cylinder", "mesh"});
    int mi = materialFor(o);
    so.material = d.materials[mi].name;
    Transform M = parseTransform(o);
    Shape s;
    s.material = mi;
    s.objectId = so.id;
    s.name = so.name;
    if (so.type == "sphere" || so.type == "disk" || so.type == "cylinder") {
      s.type = so.type == "sphere" ? ShapeType::Sphere : so.type == "disk" ? ShapeType::Disk : ShapeType::Cylinder;
      s.radius = o.positive("radius_mm");
      if (s.type == ShapeType::Cylinder) {
        s.height = o.positive("height_mm");
        s.caps = o.boolean("caps", true);
      }
      s.setTransform(M);
    } else {
      s.type = ShapeType::Mesh;
      if (so.type == "box") {
        std::vector<double> sz = sizeN(o, "size_mm", 3);
        buildBox(s, M, Vec3(float(sz[0]), float(sz[1]), float(sz[2])));
      } else if (so.type == "rectangle") {
        std::vector<double> sz = sizeN(o, "size_mm", 2);
        buildRectangle(s, M, float(sz[0]), float(sz[1]));
      } else {
        std::string path = resolveFile(o, "file");
        ObjMesh mesh;
        try {
          mesh = loadObj(path);
        } catch (const InputError& e) {
          o.fail("file", quoteStr(o.string("file")), std::string("a valid OBJ file (") + e.what() + ")");
        }
        bool smooth = o.boolean("smooth_normals", true);
        for (const Vec3& p : mesh.P) {
          s.P.push_back(M.point(p));
          s.ST.push_back(Vec2(p.x, p.y));
        }
        if (smooth && !mesh.N.empty())
          for (const Vec3& n : mesh.N) {
            Vec3 w = M.normal(n);
            float l = glm::length(w);
            s.N.push_back(l > 0.0f && std::isfinite(l) ? w / l : Vec3(0.0f));
          }
        s.UV = mesh.UV;
        s.indices = mesh.indices;
      }
    }
    const Material& mat = d.materials[mi];
    s.mask = mat.type == MaterialType::ThinDielectric ? kMaskFilter : kMaskOpaque;
    s.needsUV = mat.type == MaterialType::Diffuse && mat.reflectance.type() != TextureType::Constant;
    finalizeShape(s, o);
    o.rejectUnknown();
    so.shape = uint32_t(d.shapes.size());
    d.shapes.push_back(std::move(s));
    d.objects.push_back(so);
  }

  void parseLight(const JsonObject& o, size_t index) {
    std::string type = o.choice("type", {"rect", "point", "spot", "environment"});
    Light l;
    l.name = o.string("name", type + std::to_string(index));
    if (type == "environment") {
      l.type = LightType::Environment;
      l.spectrum = parseEmission(o, "spectrum", nullptr);
      for (const Light& other : d.lights)
        if (other.type == LightType::Environment)
          o.fail("type", quoteStr(type), "at most one environment light");
    } else if (type == "point" || type == "spot") {
      l.type = type == "point" ? LightType::Point : LightType::Spot;
      l.position = Point3(o.vec3("position_mm"));
      l.spectrum = parseEmission(o, "spectrum", nullptr);
      if (l.type == LightType::Spot) {
        Vec3 dir;
        if (o.has("look_at_mm")) dir = Vec3(o.vec3("look_at_mm")) - l.position;
        else dir = Vec3(o.vec3("direction"));
        float len = glm::length(dir);
        if (!(len > 0.0f)) o.fail(o.has("look_at_mm") ? "look_at_mm" : "direction", "(zero vector)", "a direction of non-zero length");
        l.frame = Frame::fromZ(dir / len);
        double cone = o.number("cone_deg", 30.0);
        if (!(cone > 0.0 && cone <= 180.0)) o.fail("cone_deg", jsonValueText(o.raw("cone_deg")), "a half-angle in (0, 180] degrees");
        double start = o.number("falloff_start_deg", std::max(0.0, cone - 5.0));
        if (!(start >= 0.0 && start <= cone))
          o.fail("falloff_start_deg", jsonValueText(o.raw("falloff_start_deg")), "an angle in [0, cone_deg]");
        l.cosFalloffEnd = std::cos(radians(float(cone)));
        l.cosFalloffStart = std::cos(radians(float(start)));
      }
    } else {  // rect area light
      l.type = LightType::Area;
      std::vector<double> sz = sizeN(o, "size_mm", 2);
      Transform M;
      if (o.has("look_at_mm")) {
        Vec3d pos = o.vec3("position_mm");
        Vec3d z = o.vec3("look_at_mm") - pos;
        if (!(glm::length(z) > 0.0)) o.fail("look_at_mm", jsonValueText(o.raw("look_at_mm")), "a point other than position_mm");
        z = glm::normalize(z);
        Vec3d up = std::abs(z.y) > 0.999 ? Vec3d(0, 0, 1) : Vec3d(0, 1, 0);
        Vec3d x = glm::normalize(glm::cross(up, z));
        Vec3d y = glm::cross(z, x);
        glm::dmat4 m(1.0);
        m[0] = glm::dvec4(x, 0.0);
        m[1] = glm::dvec4(y, 0.0);
        m[2] = glm::dvec4(z, 0.0);
        m[3] = glm::dvec4(pos, 1.0);
        M = Transform::fromMatrix(m, o.keyPath("look_at_mm"));
      } else {
        M = parseTransform(o);
      }
      Material em;
      em.name = "light:" + l.name;
      em.type = MaterialType::Emitter;
      em.emissive = true;
      em.Le = parseEmission(o, "spectrum", &em.twoSided);
      l.spectrum = em.Le;
      l.twoSided = em.twoSided;
      d.materials.push_back(em);
      materialIndex[em.name] = int(d.materials.size()) - 1;
      Shape s;
      s.type = ShapeType::Mesh;
      s.material = int(d.materials.size()) - 1;
      s.name = l.name;
      buildRectangle(s, M, float(sz[0]), float(sz[1]));
      finalizeShape(s, o);
      l.shape = int(d.shapes.size());
      d.shapes.push_back(std::move(s));
    }
    o.rejectUnknown();
    d.lights.push_back(l);
  }

  void parseIntegrator(const JsonObject& o) {
    IntegratorSettings& s = d.integrator;
    s.type = o.choice("type", {"direct", "path"}, "direct") == "path" ? IntegratorSettings::Type::Path
                                                                      : IntegratorSettings::Type::Direct;
    s.maxDepth = o.has("max_depth") ? o.integer("max_depth", 0, 1000) : 8;
    std::string ls = o.choice("light_sampling", {"power", "uniform", "all"}, "power");
    s.lightSelection = ls == "power" ? LightSelection::Power : ls == "uniform" ? LightSelection::Uniform : LightSelection::All;
    s.rrDepth = o.integer("rr_depth", 3);
    s.filterShadows = o.boolean("filter_shadows", true);
    o.rejectUnknown();
  }

  void parse(const Json& j) {
    JsonObject root(j, file, "");
    if (root.has("units")) {
      std::string u = root.string("units");
      if (u != "mm") root.fail("units", quoteStr(u), "\"mm\" (all lengths are millimetres)");
    }
    if (root.has("integrator")) parseIntegrator(root.object("integrator"));
    if (root.has("materials")) {
      JsonObject mats = root.object("materials");
      for (auto it = mats.json().begin(); it != mats.json().end(); ++it) {
        const std::string& name = it.key();
        if (!name.empty() && name[0] == '_') continue;
        mats.has(name);
        if (!it.value().is_object())
          mats.fail(name, jsonValueText(it.value()), "a material object with a \"type\"");
        JsonObject m(it.value(), file, mats.keyPath(name));
        d.materials.push_back(parseMaterial(m, name));
        materialIndex[name] = int(d.materials.size()) - 1;
      }
      mats.rejectUnknown();
    }
    if (root.has("objects")) {
      std::vector<JsonObject> objs = root.objects("objects");
      checkAllocation(file, "objects", std::to_string(objs.size()) + " objects",
                      {{double(objs.size()), double(sizeof(Shape) + sizeof(SceneObject) + sizeof(Light))}},
                      "the scene's objects");
      d.objects.reserve(objs.size());  // no copies of a million shapes while they are added
      d.shapes.reserve(d.shapes.size() + objs.size());
      objectOfId.reserve(objs.size());
      for (size_t i = 0; i < objs.size(); ++i) parseObject(objs[i], i);
    }
    if (root.has("lights")) {
      std::vector<JsonObject> ls = root.objects("lights");
      for (size_t i = 0; i < ls.size(); ++i) parseLight(ls[i], i);
    }
    root.rejectUnknown();
    // Emissive objects are area lights too, except the rect lights registered above (marked
    // once: a look-up per shape in every light was quadratic in emissive meshes).
    std::vector<char> rectLight(d.shapes.size(), 0);
    for (const Light& l : d.lights)
      if (l.type == LightType::Area && l.shape >= 0) rectLight[size_t(l.shape)] = 1;
    for (size_t i = 0; i < d.shapes.size(); ++i) {
      Shape& s = d.shapes[i];
      const Material& m = d.materials[s.material];
      if (!m.emissive || (s.type == ShapeType::Mesh && rectLight[i])) continue;
      Light l;
      l.type = LightType::Area;
      l.name = s.name;
      l.shape = int(i);
      l.spectrum = m.Le;
      l.twoSided = m.twoSided;
      d.lights.push_back(l);
    }
    for (size_t i = 0; i < d.lights.size(); ++i)
      if (d.lights[i].type == LightType::Area) d.shapes[d.lights[i].shape].light = int(i);
  }
};

}  // namespace

SceneDescription parseSceneDescription(const Json& j, const std::string& file) {
  Loader l;
  l.file = file;
  l.d.file = file;
  l.parse(j);
  return std::move(l.d);
}

SceneDescription loadSceneDescription(const std::string& path) {
  Json j = readJsonFile(path);
  return parseSceneDescription(j, path);
}

}  // namespace inim
