#include "display/stack_first_order.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "core/format.h"
#include "spectral/dispersion.h"

namespace inim {

namespace {

constexpr double kDegreesPerRadian = 57.295779513082320876798;

struct Matrix2 {
  double a = 1, b = 0, c = 0, d = 1;
  Matrix2 then(const Matrix2& m) const {  // m applied after this
    return {m.a * a + m.b * c, m.a * b + m.b * d, m.c * a + m.d * c, m.c * b + m.d * d};
  }
};

Matrix2 refraction(double n1, double n2, double curvature) { return {1.0, 0.0, -(n2 - n1) * curvature, 1.0}; }
Matrix2 transfer(double thickness, double n) { return {1.0, thickness / n, 0.0, 1.0}; }

double layerIndex(const OpticalStack& s, const StackLayer& l, double lambdaNm) {
  if (l.material.empty()) return 1.0;
  const MaterialCatalog& catalog = MaterialCatalog::standard();
  if (!catalog.hasDielectric(l.material))
    throw InputError(s.file, l.keyPath + ".material", "\"" + l.material + "\"", "a dielectric of the material catalog");
  return catalog.dielectric(l.material)->n(float(lambdaNm));
}

double backCurvature(const StackLayer& l) { return l.kind == StackLayer::Kind::LensArray ? l.back.curvature() : 0.0; }
double frontCurvature(const StackLayer& l) { return l.kind == StackLayer::Kind::LensArray ? l.front.curvature() : 0.0; }

double firstLatticePitch(const OpticalStack& s) {
  for (const StackLayer& l : s.layers)
    if (l.kind == StackLayer::Kind::LensArray) return l.pitchMm;
  for (const StackLayer& l : s.layers)
    if (l.pitchMm > 0.0) return l.pitchMm;
  return 0.0;
}

// The system from the panel through every layer, calling `atPlane(z, m)` at each layer's back
// and front plane. The panel emits into the first layer's medium. Between two layers the light
// leaves the one through its front surface into air and enters the next through its back
// surface, with no air between: two layers in contact are a cemented interface, paraxially the
// same.
//
// A curved stack (curved_frame.h) is the axial lenslet's column: each surface bent onto its
// shell adds the shell's curvature s / rho(z) to its own (a plane becomes the shell).
template <class AtPlane>
Matrix2 walkStack(const OpticalStack& s, double wavelengthNm, AtPlane&& atPlane) {
  const CurvedFrame frame = s.arrayFrame();
  auto shell = [&](double z) { return frame.flat() ? 0.0 : frame.sign() / frame.shellRadius(z); };
  Matrix2 m;
  double n = s.layers.empty() ? 1.0 : layerIndex(s, s.layers[0], wavelengthNm);
  for (size_t i = 0; i < s.layers.size(); ++i) {
    const StackLayer& l = s.layers[i];
    const double nl = layerIndex(s, l, wavelengthNm), z = s.layerBackZ(i);
    if (i > 0)
      m = m.then(refraction(n, 1.0, frontCurvature(s.layers[i - 1]) + shell(z)))
              .then(refraction(1.0, nl, backCurvature(l) + shell(z)));
    atPlane(z, m);
    m = m.then(transfer(l.thicknessMm, nl));
    atPlane(s.layerBackZ(i + 1), m);
    n = nl;
  }
  if (!s.layers.empty())
    m = m.then(refraction(n, 1.0, frontCurvature(s.layers.back()) + shell(s.totalThicknessMm())));
  return m;
}

// The inscribed radius of each clear aperture layer i has, with the plane it limits at.
struct Opening {
  double radiusMm;
  bool front;
  const char* what;
};

std::vector<Opening> openingsOf(const StackLayer& l) {
  switch (l.kind) {
    case StackLayer::Kind::LensArray: {
      const double r = (l.apertureMm > 0.0 ? l.apertureMm : l.pitchMm) / 2.0;
      return {{r, false, ".back"}, {r, true, ".front"}};
    }
    case StackLayer::Kind::Apertures: return {{l.holeMm / 2.0, false, " (holes)"}, {l.holeMm / 2.0, true, " (holes)"}};
    case StackLayer::Kind::Barriers: {
      const double r = (l.pitchMm - l.wallMm) / 2.0;
      return {{r, false, " (barrier cells, back end)"}, {r, true, " (barrier cells, front end)"}};
    }
    default: return {};
  }
}

}  // namespace

std::vector<ParaxialPlane> stackParaxialPlanes(const OpticalStack& s, double wavelengthNm) {
  std::vector<ParaxialPlane> planes;
  walkStack(s, wavelengthNm, [&](double z, const Matrix2& m) { planes.push_back({z, m.a, m.b}); });
  return planes;
}

StackFirstOrder stackFirstOrder(const OpticalStack& s, double wavelengthNm) {
  const double n0 = s.layers.empty() ? 1.0 : layerIndex(s, s.layers[0], wavelengthNm);
  const Matrix2 m = walkStack(s, wavelengthNm, [](double, const Matrix2&) {});

  StackFirstOrder fo;
  fo.wavelengthNm = wavelengthNm;
  fo.a = m.a, fo.b = m.b, fo.c = m.c, fo.d = m.d;
  fo.panelIndex = n0;
  fo.lensletDepthMm = s.totalThicknessMm();
  fo.pitchMm = firstLatticePitch(s);
  fo.afocal = std::fabs(m.c) < 1e-15;
  if (fo.afocal) return fo;
  const double z = fo.lensletDepthMm;
  fo.focalLengthMm = -1.0 / m.c;
  fo.rearFocalZMm = z - m.a / m.c;
  fo.rearPrincipalZMm = z + (1.0 - m.a) / m.c;
  fo.frontPrincipalZMm = n0 * (m.d - 1.0) / m.c;
  fo.frontFocalZMm = n0 * m.d / m.c;
  fo.reducedGapMm = fo.frontPrincipalZMm / n0;
  const double vergence = 1.0 / fo.focalLengthMm - 1.0 / fo.reducedGapMm;  // P - n0 / g
  if (std::fabs(vergence) > 1e-15) fo.referencePlaneMm = 1.0 / vergence;
  if (fo.reducedGapMm > 0.0 && fo.pitchMm > 0.0)
    fo.viewingAngleDeg = 2.0 * std::atan(fo.pitchMm / (2.0 * fo.reducedGapMm)) * kDegreesPerRadian;
  return fo;
}

std::optional<ApertureStop> findApertureStop(const OpticalStack& s, double wavelengthNm) {
  const std::vector<ParaxialPlane> planes = stackParaxialPlanes(s, wavelengthNm);
  std::optional<ApertureStop> best;
  double bestRatio = 0.0;
  for (size_t i = 0; i < s.layers.size(); ++i)
    for (const Opening& o : openingsOf(s.layers[i])) {
      const ParaxialPlane& p = planes[2 * i + (o.front ? 1 : 0)];
      if (!(std::fabs(p.b) > 1e-12) || !(o.radiusMm > 0.0)) continue;
      const double ratio = o.radiusMm / std::fabs(p.b);
      if (best && !(ratio < bestRatio * (1.0 - 1e-12))) continue;
      bestRatio = ratio;
      best = ApertureStop{i, p.zMm, o.radiusMm, p.a, p.b, o.front, s.layers[i].keyPath + o.what};
    }
  return best;
}

std::string stackText(const OpticalStack& s, const StackFirstOrder& fo) {
  std::string t = formatText("Optical stack (%zu layers, panel at z = 0, + toward the viewer):\n", s.layers.size());
  for (size_t i = 0; i < s.layers.size(); ++i) {
    const StackLayer& l = s.layers[i];
    t += formatText("  %-10s z %8.4f .. %8.4f mm  %s", layerKindName(l.kind), s.layerBackZ(i), s.layerBackZ(i + 1),
                    l.material.empty() ? "air" : l.material.c_str());
    if (l.kind == StackLayer::Kind::LensArray)
      t += formatText("  pitch %g mm, back R %g, front R %g mm", l.pitchMm, l.back.radiusMm, l.front.radiusMm);
    if (l.kind == StackLayer::Kind::Apertures) t += formatText("  pitch %g mm, holes %g mm", l.pitchMm, l.holeMm);
    if (l.kind == StackLayer::Kind::Barriers) t += formatText("  pitch %g mm, walls %g mm wide", l.pitchMm, l.wallMm);
    t += "\n";
  }
  if (s.curvature) {
    const CurvedFrame array = s.arrayFrame();
    t += formatText("  curved: lenslet centres on a %s of radius %g mm through z = %.4f mm; every lenslet's axis passes\n"
                    "    through its centre of curvature at z = %.4g mm (%s); the first order below counts each surface's shell\n",
                    s.curvature->shape == StackCurvature::Shape::Sphere ? "sphere" : "cylinder (axis along y)",
                    s.curvature->radiusMm, array.zRefMm, array.centre().z,
                    s.curvature->radiusMm > 0.0 ? "in front: the axes converge" : "behind the panel: the axes diverge");
    if (s.panelWidthMm > 0.0) {
      const bool sphere = s.curvature->shape == StackCurvature::Shape::Sphere;
      const double ex = s.panelWidthMm / 2.0, ey = sphere ? s.panelHeightMm / 2.0 : 0.0;
      const double edge = array.zRefMm - array.toFrame(s.panelFrame().toWorld(ex, ey, 0.0)).z;
      t += formatText("    the %s panel's %s (%.4g mm off the axis) lies %.4f mm below the array (%.4f mm on the axis)\n",
                      s.panelRadiusMm ? formatText("curved (R %g mm)", *s.panelRadiusMm).c_str() : "flat",
                      sphere ? "corner" : "edge", std::hypot(ex, ey), edge, array.zRefMm);
    }
  }
  t += formatText("First order of one lenslet column at %.2f nm (docs/design.md):\n", fo.wavelengthNm);
  if (fo.afocal) return t + "  afocal (no power): no focal length, principal planes or reference plane\n";
  t += formatText("  effective focal length f = -1/C       %.5f mm\n", fo.focalLengthMm);
  t += formatText("  principal planes H, H'                z = %.5f, %.5f mm\n", fo.frontPrincipalZMm, fo.rearPrincipalZMm);
  t += formatText("  focal points F, F'                    z = %.5f, %.5f mm\n", fo.frontFocalZMm, fo.rearFocalZMm);
  t += formatText("  gap g (panel to H, reduced)           %.5f mm\n", fo.reducedGapMm);
  if (fo.referencePlaneMm)
    t += formatText("  reference image plane L (from H')     %.4f mm (%s)\n", *fo.referencePlaneMm,
                    *fo.referencePlaneMm > 0.0 ? "real" : "virtual");
  else
    t += "  reference image plane L               at infinity (g = f)\n";
  t += formatText("  viewing angle psi = 2 atan(P/2g)      %.3f deg\n", fo.viewingAngleDeg);
  t += formatText("  depth range |z| <= 2g                 %.3f mm\n", 2.0 * fo.reducedGapMm);
  if (const std::optional<ApertureStop> stop = findApertureStop(s, fo.wavelengthNm))
    t += formatText("  aperture stop                         %s, z = %.4f mm, radius %.4f mm\n", stop->what.c_str(),
                    stop->zMm, stop->radiusMm);
  return t;
}

}  // namespace inim
