#include "display/optical_stack.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/error.h"
#include "core/format.h"
#include "display/stack_first_order.h"
#include "spectral/dispersion.h"

namespace inim {

namespace {

constexpr double kSqrt3 = 1.7320508075688772;
// Sag is sampled this finely across an aperture to find where a surface is undefined or where
// two surfaces cross (a lenslet's profile is smooth: a few hundred points resolve it).
constexpr int kSagSamples = 256;

Mla::Lattice readLattice(const JsonObject& o) {
  return o.choice("lattice", {"square", "hex"}, "square") == "hex" ? Mla::Lattice::Hex : Mla::Lattice::Square;
}

Mla::Aperture readShape(const JsonObject& o, const std::string& key, const std::string& fallback) {
  const std::string s = o.choice(key, {"square", "circle", "hex"}, fallback);
  return s == "circle" ? Mla::Aperture::Circle : s == "hex" ? Mla::Aperture::Hex : Mla::Aperture::Square;
}

std::string readMaterial(const JsonObject& o) {
  const std::string name = o.string("material");
  const MaterialCatalog& catalog = MaterialCatalog::standard();
  if (catalog.hasDielectric(name)) return name;
  o.fail("material", "\"" + name + "\"", "a dielectric of the material catalog: " + catalog.dielectricsText());
}

// "plane", or {"radius_mm": R, "conic": k, "asphere": [a4, a6, ...]}.
StackSurface readSurface(const JsonObject& layer, const std::string& key) {
  StackSurface s;
  if (!layer.has(key)) return s;
  const Json& v = layer.raw(key);
  if (v.is_string()) {
    if (v.get<std::string>() != "plane") layer.fail(key, jsonValueText(v), "\"plane\" or a surface object");
    return s;
  }
  const JsonObject o = layer.object(key);
  s.radiusMm = o.number("radius_mm", 0.0);
  s.conic = o.number("conic", 0.0);
  if (o.has("asphere")) s.asphereMm = o.numbers("asphere");
  o.rejectUnknown();
  if (s.radiusMm != 0.0 && std::fabs(s.radiusMm) < 1e-3)
    o.fail("radius_mm", formatText("%g", s.radiusMm), "0 (flat) or |R| >= 0.001 mm");
  return s;
}

void readLatticeLayer(const JsonObject& o, StackLayer& l) {
  l.lattice = readLattice(o);
  l.pitchMm = o.positive("pitch_mm");
  if (o.has("lattice_offset_mm")) {
    const std::vector<double> off = o.numbers("lattice_offset_mm");
    if (off.size() != 2) o.fail("lattice_offset_mm", jsonValueText(o.raw("lattice_offset_mm")), "[x, y] in mm");
    l.offsetXMm = off[0], l.offsetYMm = off[1];
  }
  if (o.has("count")) {
    const std::vector<int> n = o.integers("count", 1, 1 << 20);
    if (n.size() != 2) o.fail("count", jsonValueText(o.raw("count")), "[columns, rows], whole numbers >= 1");
    l.cols = n[0], l.rows = n[1];
  }
}

StackLayer readLayer(const JsonObject& o) {
  StackLayer l;
  l.keyPath = o.keyPath();
  const std::string type = o.choice("type", {"gap", "plate", "lens_array", "apertures", "barriers"});
  if (type == "barriers") {
    l.kind = StackLayer::Kind::Barriers;
    readLatticeLayer(o, l);
    l.thicknessMm = o.positive("height_mm");
    l.wallMm = o.number("wall_mm", 0.0);
    l.reflectance = o.number("wall_reflectance", 0.0);
  } else {
    l.kind = type == "gap"          ? StackLayer::Kind::Gap
             : type == "plate"      ? StackLayer::Kind::Plate
             : type == "lens_array" ? StackLayer::Kind::LensArray
                                    : StackLayer::Kind::Apertures;
    l.thicknessMm = l.kind == StackLayer::Kind::Apertures ? o.number("thickness_mm", 0.0) : o.positive("thickness_mm");
    if (!(l.thicknessMm >= 0.0)) o.fail("thickness_mm", formatText("%g", l.thicknessMm), "a thickness >= 0");
  }
  if (l.kind == StackLayer::Kind::Plate || l.kind == StackLayer::Kind::LensArray) l.material = readMaterial(o);
  if (l.kind == StackLayer::Kind::LensArray) {
    readLatticeLayer(o, l);
    l.back = readSurface(o, "back");
    l.front = readSurface(o, "front");
    l.aperture = readShape(o, "aperture", "square");
    l.apertureMm = o.positive("aperture_mm", l.pitchMm);
    if (l.apertureMm > l.pitchMm * (1.0 + 1e-12))
      o.fail("aperture_mm", formatText("%g", l.apertureMm), formatText("at most the pitch, %g mm", l.pitchMm));
  }
  if (l.kind == StackLayer::Kind::Apertures) {
    readLatticeLayer(o, l);
    l.hole = readShape(o, "hole", "circle");
    l.holeMm = o.positive("hole_mm");
    if (l.holeMm > l.pitchMm) o.fail("hole_mm", formatText("%g", l.holeMm), formatText("at most the pitch, %g mm", l.pitchMm));
  }
  if (l.kind == StackLayer::Kind::Barriers && l.wallMm >= l.pitchMm)
    o.fail("wall_mm", formatText("%g", l.wallMm), formatText("less than the pitch, %g mm", l.pitchMm));
  o.rejectUnknown();
  return l;
}

[[noreturn]] void failLayer(const OpticalStack& s, const StackLayer& l, const std::string& key, const std::string& value,
                            const std::string& expected) {
  throw InputError(s.file, l.keyPath + (key.empty() ? "" : "." + key), value, expected);
}

// A lens array's surfaces: defined over the whole clear aperture, not crossing each other, and
// bulging out of the layer only into an air layer beside it that holds the bulge.
void checkLensArray(const OpticalStack& s, size_t i) {
  const StackLayer& l = s.layers[i];
  const double rMax = l.apertureRadiusMm();
  double backOut = 0.0, frontOut = 0.0;  // how far each surface leaves the layer
  for (int k = 0; k <= kSagSamples; ++k) {
    const double r = rMax * k / kSagSamples;
    const std::optional<double> sb = l.back.sag(r), sf = l.front.sag(r);
    if (!sb || !sf)
      failLayer(s, l, !sb ? "back" : "front", formatText("no surface at r = %.4g mm from the lenslet's axis", r),
                formatText("a surface defined over the clear aperture (radius %.4g mm): (1 + conic) r^2 < R^2", rMax));
    if (!(l.thicknessMm + *sf - *sb > 0.0))
      failLayer(s, l, "thickness_mm", formatText("%g (the surfaces meet at r = %.4g mm)", l.thicknessMm, r),
                "a lenslet whose front and back surfaces do not cross inside its clear aperture");
    backOut = std::max(backOut, -*sb);
    frontOut = std::max(frontOut, *sf);
  }
  auto holds = [&](size_t j, double depth) {
    const StackLayer::Kind k = s.layers[j].kind;
    return (k == StackLayer::Kind::Gap || k == StackLayer::Kind::Barriers) && s.layers[j].thicknessMm > depth;
  };
  if (backOut > 0.0 && (i == 0 || !holds(i - 1, backOut)))
    failLayer(s, l, "back", formatText("a surface reaching %.4g mm behind the layer", backOut),
              "layers that do not overlap: an air gap behind the lens array deeper than its back surface's sag");
  if (frontOut > 0.0 && i + 1 < s.layers.size() && !holds(i + 1, frontOut))
    failLayer(s, l, "front", formatText("a surface reaching %.4g mm beyond the layer", frontOut),
              "layers that do not overlap: an air gap in front of the lens array deeper than its front surface's sag");
}

// A lattice with a count must cover the panel's active area.
void checkCoverage(const OpticalStack& s, const StackLayer& l, double panelW, double panelH) {
  if (!l.cols) return;
  const double w = *l.cols * l.pitchMm;
  const double h = *l.rows * l.pitchMm * (l.lattice == Mla::Lattice::Hex ? kSqrt3 / 2.0 : 1.0);
  const double halfW = w / 2.0 - std::fabs(l.offsetXMm), halfH = h / 2.0 - std::fabs(l.offsetYMm);
  if (halfW < panelW / 2.0 * (1.0 - 1e-9) || halfH < panelH / 2.0 * (1.0 - 1e-9))
    failLayer(s, l, "count",
              formatText("[%d, %d]: %.4g x %.4g mm, offset (%.4g, %.4g) mm", *l.cols, *l.rows, w, h, l.offsetXMm, l.offsetYMm),
              formatText("a lattice that covers the panel's %.4g x %.4g mm", panelW, panelH));
}

void checkCurvature(const OpticalStack& s, const JsonObject& o, double panelW, double panelH) {
  if (!s.curvature) return;
  const double half = s.curvature->shape == StackCurvature::Shape::Cylinder ? panelW / 2.0
                                                                             : std::hypot(panelW, panelH) / 2.0;
  if (std::fabs(s.curvature->radiusMm) < half)
    throw InputError(s.file, o.keyPath("curvature") + ".radius_mm", formatText("%g", s.curvature->radiusMm),
                     formatText("a radius of at least half the array (%.4g mm)", half));
  if (s.panelRadiusMm && std::fabs(*s.panelRadiusMm) < half)
    throw InputError(s.file, o.keyPath("panel_radius_mm"), formatText("%g", *s.panelRadiusMm),
                     formatText("a radius of at least half the panel (%.4g mm)", half));
  // The innermost shell of a stack curved around a centre on its own side must not reach it.
  const double depth = s.totalThicknessMm();
  if (std::fabs(s.curvature->radiusMm) <= depth)
    throw InputError(s.file, o.keyPath("curvature") + ".radius_mm", formatText("%g", s.curvature->radiusMm),
                     formatText("a radius larger than the stack's depth (%.4g mm)", depth));
  // The first gap at the panel's edge (cylinder) or corner (sphere), where a curved array comes
  // nearest a flat panel or one of another radius.
  const CurvedFrame array = s.arrayFrame(), panel = s.panelFrame();
  const double ex = panelW / 2.0, ey = s.curvature->shape == StackCurvature::Shape::Sphere ? panelH / 2.0 : 0.0;
  const double gapAtEdge = array.zRefMm - array.toFrame(panel.toWorld(ex, ey, 0.0)).z;
  if (!(gapAtEdge > 0.0))
    throw InputError(s.file, o.keyPath("curvature") + ".radius_mm", formatText("%g", s.curvature->radiusMm),
                     formatText("a curvature that keeps the array off the panel (at the panel's edge the gap before "
                                "the array would be %.4g mm)", gapAtEdge));
}

}  // namespace

bool StackSurface::isPlane() const { return radiusMm == 0.0 && asphereMm.empty(); }

std::optional<double> StackSurface::sag(double r) const {
  const double c = curvature(), r2 = r * r;
  const double q = 1.0 - (1.0 + conic) * c * c * r2;
  if (q < 0.0) return std::nullopt;
  double z = c * r2 / (1.0 + std::sqrt(q));
  double rp = r2 * r2;
  for (double a : asphereMm) z += a * rp, rp *= r2;
  if (!std::isfinite(z)) return std::nullopt;
  return z;
}

double StackLayer::apertureRadiusMm() const {
  switch (aperture) {
    case Mla::Aperture::Circle: return apertureMm / 2.0;
    case Mla::Aperture::Hex: return apertureMm / kSqrt3;  // flat to flat a: corners at a / sqrt(3)
    case Mla::Aperture::Square: break;
  }
  return apertureMm / std::sqrt(2.0);
}

const char* layerKindName(StackLayer::Kind k) {
  switch (k) {
    case StackLayer::Kind::Gap: return "gap";
    case StackLayer::Kind::Plate: return "plate";
    case StackLayer::Kind::LensArray: return "lens_array";
    case StackLayer::Kind::Apertures: return "apertures";
    case StackLayer::Kind::Barriers: return "barriers";
  }
  return "?";
}

double OpticalStack::totalThicknessMm() const { return layerBackZ(layers.size()); }

double OpticalStack::layerBackZ(size_t i) const {
  double z = 0.0;
  for (size_t j = 0; j < i && j < layers.size(); ++j) z += layers[j].thicknessMm;
  return z;
}

CurvedFrame OpticalStack::arrayFrame() const {
  CurvedFrame f;
  if (!curvature) return f;
  f.shape = curvature->shape == StackCurvature::Shape::Cylinder ? CurvedFrame::Shape::Cylinder : CurvedFrame::Shape::Sphere;
  f.radiusMm = curvature->radiusMm;
  // The first layer that is not an air gap; a stack cut short before it (the layers below a
  // stop) keeps the reference at the top of its gaps, where that layer would begin.
  size_t first = 0;
  while (first < layers.size() && layers[first].kind == StackLayer::Kind::Gap) ++first;
  f.zRefMm = layerBackZ(first);
  return f;
}

CurvedFrame OpticalStack::panelFrame() const {
  CurvedFrame f;
  if (!panelRadiusMm || !curvature) return f;
  f.shape = arrayFrame().shape;
  f.radiusMm = *panelRadiusMm;
  return f;
}

void axisFootOnPanel(const OpticalStack& s, double x, double y, double& px, double& py) {
  const CurvedFrame array = s.arrayFrame(), panel = s.panelFrame();
  px = x, py = y;
  if (array.flat()) return;
  const Point3d q = array.toWorld(x, y, array.zRefMm);
  const Vec3d down = -array.up(q);
  double t = q.z / -down.z;
  if (!panel.flat() && !panel.hitShell(q, down, 0.0, 0.0, 1e12, t)) return;
  const Vec3d foot = panel.toFrame(q + t * down);
  px = foot.x, py = foot.y;
}

int OpticalStack::lensArrayCount() const {
  return int(std::count_if(layers.begin(), layers.end(), [](const StackLayer& l) { return l.kind == StackLayer::Kind::LensArray; }));
}

OpticalStack parseOpticalStack(const JsonObject& o, double panelWidthMm, double panelHeightMm) {
  OpticalStack s;
  s.file = o.file();
  for (const JsonObject& layer : o.objects("layers")) s.layers.push_back(readLayer(layer));
  if (s.layers.empty()) o.fail("layers", "[]", "at least one layer");
  if (s.lensArrayCount() == 0 && std::none_of(s.layers.begin(), s.layers.end(), [](const StackLayer& l) {
        return l.kind == StackLayer::Kind::Apertures;
      }))
    o.fail("layers", formatText("%zu layers without a lens or an aperture array", s.layers.size()),
           "at least one lens array or aperture array (what forms the views)");
  if (o.has("curvature")) {
    const JsonObject c = o.object("curvature");
    StackCurvature curv;
    curv.shape = c.choice("shape", {"cylinder", "sphere"}) == "cylinder" ? StackCurvature::Shape::Cylinder
                                                                        : StackCurvature::Shape::Sphere;
    curv.radiusMm = c.number("radius_mm");
    c.rejectUnknown();
    s.curvature = curv;
  }
  if (o.has("panel_radius_mm")) {
    s.panelRadiusMm = o.number("panel_radius_mm");
    if (!s.curvature)
      o.fail("panel_radius_mm", formatText("%g", *s.panelRadiusMm), "a curved panel under a curved array (give \"curvature\")");
  }
  s.panelWidthMm = panelWidthMm, s.panelHeightMm = panelHeightMm;
  o.rejectUnknown();
  for (size_t i = 0; i < s.layers.size(); ++i) {
    if (s.layers[i].kind == StackLayer::Kind::LensArray) checkLensArray(s, i);
    checkCoverage(s, s.layers[i], panelWidthMm, panelHeightMm);
  }
  checkCurvature(s, o, panelWidthMm, panelHeightMm);
  return s;
}

OpticalStack stackFromMla(const Mla& mla, double gapMm) {
  const LensletFocus focus = lensletFocus(mla);
  const std::string material = mla.material.empty() ? "PMMA" : mla.material;
  const double n = MaterialCatalog::standard().dielectric(material)->n(float(kLambdaDNm));
  const double radius = mla.radiusMm ? *mla.radiusMm : (n - 1.0) * focus.focalLengthMm;
  StackLayer lens;
  lens.kind = StackLayer::Kind::LensArray;
  lens.keyPath = "mla";
  lens.thicknessMm = mla.substrateThicknessMm;
  lens.material = material;
  lens.lattice = mla.lattice;
  lens.pitchMm = mla.pitchMm;
  lens.aperture = mla.aperture;
  lens.apertureMm = mla.apertureMm > 0.0 ? mla.apertureMm : mla.pitchMm;
  StackSurface cap;
  cap.conic = mla.conic;
  // The panel-side principal plane of a plano-convex lens: T / n inside the flat face (cap toward
  // the viewer), at the cap's vertex (cap toward the panel).
  double hInside = 0.0;
  if (mla.orientation == Mla::Orientation::CurvedTowardViewer) {
    cap.radiusMm = -radius;
    lens.front = cap;
    hInside = mla.substrateThicknessMm / n;
  } else {
    cap.radiusMm = radius;
    lens.back = cap;
  }
  StackLayer gap;
  gap.kind = StackLayer::Kind::Gap;
  gap.keyPath = "gap";
  gap.thicknessMm = gapMm - hInside;
  OpticalStack s;
  s.file = mla.file;
  s.layers = {gap, lens};
  return s;
}

std::optional<StackAsMla> mlaFromStack(const OpticalStack& s, std::string& why) {
  const auto lens = std::find_if(s.layers.begin(), s.layers.end(),
                                 [](const StackLayer& l) { return l.kind == StackLayer::Kind::LensArray; });
  why.clear();
  if (s.curvature || s.panelRadiusMm) why = "a curved array or panel";
  else if (s.lensArrayCount() != 1) why = formatText("%d lens arrays", s.lensArrayCount());
  else if (lens + 1 != s.layers.end()) why = std::string("a ") + layerKindName(lens[1].kind) + " layer in front of the lens array";
  else if (std::any_of(s.layers.begin(), lens, [](const StackLayer& l) { return l.kind != StackLayer::Kind::Gap; }))
    why = "a layer other than an air gap between the panel and the lens array";
  if (!why.empty()) return std::nullopt;
  const StackLayer& l = *lens;
  const bool capFront = l.back.isPlane() && l.front.radiusMm < 0.0 && l.front.asphereMm.empty();
  const bool capBack = l.front.isPlane() && l.back.radiusMm > 0.0 && l.back.asphereMm.empty();
  if (!capFront && !capBack) why = "lenslets other than a flat face and one convex spherical or conic cap";
  else if (l.offsetXMm != 0.0 || l.offsetYMm != 0.0) why = "a lattice offset";
  else if (l.cols) why = "a lenslet count (the display's ei_count sets it)";
  if (!why.empty()) return std::nullopt;
  StackAsMla r;
  r.mla.name = "lens array of " + s.file;
  r.mla.file = s.file;
  r.mla.lattice = l.lattice;
  r.mla.pitchMm = l.pitchMm;
  r.mla.radiusMm = std::fabs(capFront ? l.front.radiusMm : l.back.radiusMm);
  r.mla.conic = capFront ? l.front.conic : l.back.conic;
  r.mla.aperture = l.aperture;
  r.mla.apertureMm = l.apertureMm;
  r.mla.substrateThicknessMm = l.thicknessMm;
  r.mla.material = l.material;
  r.mla.orientation = capFront ? Mla::Orientation::CurvedTowardViewer : Mla::Orientation::CurvedTowardPanel;
  const double n = MaterialCatalog::standard().dielectric(l.material)->n(float(kLambdaDNm));
  r.gapMm = s.layerBackZ(s.layers.size() - 1) + (capFront ? l.thicknessMm / n : 0.0);  // H, as stackFromMla
  return r;
}

StackAsMla equivalentMla(const OpticalStack& s) {
  const StackFirstOrder fo = stackFirstOrder(s);
  auto first = [&](StackLayer::Kind k) {
    return std::find_if(s.layers.begin(), s.layers.end(), [k](const StackLayer& l) { return l.kind == k; });
  };
  const bool lenses = first(StackLayer::Kind::LensArray) != s.layers.end();
  const auto grid = lenses ? first(StackLayer::Kind::LensArray) : first(StackLayer::Kind::Apertures);
  StackAsMla r;
  r.mla.name = "equivalent lens array of " + s.file;
  r.mla.file = s.file;
  r.mla.lattice = grid->lattice;
  r.mla.pitchMm = grid->pitchMm;
  r.mla.aperture = lenses ? grid->aperture : grid->hole;
  r.mla.apertureMm = lenses ? grid->apertureMm : grid->holeMm;
  r.mla.material = lenses ? grid->material : "PMMA";
  r.mla.substrateThicknessMm = grid->thicknessMm;
  // A pinhole array (no power): the pinholes' plane is the reference plane, and the pinhole
  // model's "focal length" is its gap (its image of the panel lies at infinity).
  r.gapMm = fo.afocal ? s.layerBackZ(size_t(grid - s.layers.begin())) : fo.reducedGapMm;
  r.mla.focalLengthMm = fo.afocal ? r.gapMm : fo.focalLengthMm;
  return r;
}

}  // namespace inim
