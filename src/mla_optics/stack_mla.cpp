#include "mla_optics/stack_mla.h"

#include <cmath>

#include "core/error.h"
#include "core/format.h"
#include "spectral/dispersion.h"

namespace inim {

OpticalStack displayStackAtGap(const Display& d, double gapMm) {
  OpticalStack s = d.stack ? *d.stack : stackFromMla(d.mla, d.reconstructionGapMm);
  const double delta = gapMm - d.reconstructionGapMm;
  if (std::fabs(delta) <= 1e-12) return s;
  if (s.layers.empty() || s.layers[0].kind != StackLayer::Kind::Gap || !(s.layers[0].thicknessMm + delta > 0.0))
    throw InputError(d.file, "stack.layers[0]", formatText("a gap changed by %.4g mm", delta),
                     "a first air gap of the stack that can take the gap asked for");
  s.layers[0].thicknessMm += delta;
  return s;
}

StackMla::StackMla(const Display& d, const EiLayout& L, double gapMm, FresnelMode fresnel)
    : fresnel_(fresnel), gapMm_(gapMm), layout_(&L), pitchMm_(d.mla.pitchMm) {
  if (!d.stack) throw InputError(d.file, "stack", "(none)", "a display given as an optical stack");
  if (L.lensX.empty() || L.lensY.empty()) throw InputError(d.file, "ei_count", "(no lenses)", "at least one lenslet");
  const OpticalStack s = displayStackAtGap(d, gapMm);
  tracer_ = std::make_unique<StackTracer>(s, fresnel, L.lensXAt(0, 0), L.lensYAt(0, 0));
  panelFrame_ = s.panelFrame();
  frontZ_ = float(std::nextafter(tracer_->frontZ() - gapMm, 1e30));
  for (const StackLayer& l : s.layers)
    dispersive_ = dispersive_ || (!l.material.empty() && MaterialCatalog::standard().dielectric(l.material)->isDispersive());
}

void StackMla::lensletAt(double x, double y, int& k, int& l) const {
  const EiLayout& L = *layout_;
  const int rows = int(L.lensY.size()), cols = int(L.lensX.size());
  const double rowPitch = L.lensY.size() > 1 ? L.lensY[0] - L.lensY[1] : pitchMm_;
  l = int(std::lround((L.lensY[0] - y) / rowPitch));
  k = (l >= 0 && l < rows) ? int(std::lround((x - L.lensXAt(0, l)) / pitchMm_)) : -1;
  if (k < 0 || k >= cols || l < 0 || l >= rows) k = l = -1;
}

bool StackMla::traceToPanel(const Ray& ray, float lambdaNm, FresnelMode mode, Rng* rng, PanelArrival& out) const {
  StackExit ex;
  const Point3d o(ray.o.x, ray.o.y, double(ray.o.z) + gapMm_);
  if (!tracer_->trace(o, glm::normalize(Vec3d(ray.d)), lambdaNm, mode, rng, ex) || ex.towardViewer || ex.aroundEdge)
    return false;
  panelArrivalAt(panelFrame_, ex.p, ex.d, gapMm_, out);
  out.throughput = float(ex.throughput);
  out.lensletK = out.lensletL = -1;
  if (ex.crossedLens) lensletAt(ex.lensXMm, ex.lensYMm, out.lensletK, out.lensletL);
  return true;
}

void panelArrivalAt(const CurvedFrame& panel, const Point3d& p, const Vec3d& d, double gapMm, PanelArrival& out) {
  if (panel.flat()) {
    out.p = Point3(float(p.x), float(p.y), float(-gapMm));
    out.d = Vec3(d);
    return;
  }
  const Vec3d q = panel.toFrame(p);
  Vec3d axis, e1, e2;
  panel.axisFrame(q.x, q.y, axis, e1, e2);
  out.p = Point3(float(q.x), float(q.y), float(-gapMm));
  out.d = Vec3(glm::normalize(Vec3d(glm::dot(d, e1), glm::dot(d, e2), glm::dot(d, axis))));
}

CurvedIdealMla::CurvedIdealMla(const Display& d, const EiLayout& L, double focalLengthMm, double gapMm)
    : layout_(&L), f_(focalLengthMm), gapMm_(gapMm) {
  if (!d.stack || !d.stack->curved()) throw InputError(d.file, "stack", "(flat)", "a curved stack");
  if (L.lensX.empty() || L.lensY.empty()) throw InputError(d.file, "ei_count", "(no lenses)", "at least one lenslet");
  if (!(f_ > 0.0) || !std::isfinite(f_)) throw InputError(d.file, "stack", formatNumber(f_), "a focal length > 0 mm");
  const OpticalStack s = displayStackAtGap(d, gapMm);
  array_ = s.arrayFrame(), panel_ = s.panelFrame();
  // The highest point of the lens shell over the array (its centre or its edges).
  const AreaMm a = L.activeArea();
  double top = -1e300;
  for (double x : {0.0, a.x0, a.x1})
    for (double y : {0.0, a.y0, a.y1}) top = std::max(top, array_.toWorld(x, y, gapMm).z);
  frontZ_ = float(std::nextafter(top - gapMm, 1e30));
}

bool CurvedIdealMla::traceToPanel(const Ray& ray, float, FresnelMode, Rng*, PanelArrival& out) const {
  const EiLayout& L = *layout_;
  const Point3d o(ray.o.x, ray.o.y, double(ray.o.z) + gapMm_);
  const Vec3d d = glm::normalize(Vec3d(ray.d));
  double t;
  if (!array_.hitShell(o, d, gapMm_, 0.0, 1e12, t)) return false;
  const Point3d q = o + t * d;
  const Vec3d arc = array_.toFrame(q);
  int k, l;
  if (!L.nearestLens(arc.x, arc.y, k, l)) return false;
  Vec3d axis, e1, e2;
  array_.axisFrame(L.lensXAt(k, l), L.lensYAt(k, l), axis, e1, e2);
  const Vec3d off = q - array_.toWorld(L.lensXAt(k, l), L.lensYAt(k, l), gapMm_);
  const double dz = glm::dot(d, axis);
  if (!(dz < 0.0)) return false;
  // The viewer-side slopes, turned by the ideal lens as IdealLensletMla turns them.
  const double sx = glm::dot(d, e1) / dz + glm::dot(off, e1) / f_, sy = glm::dot(d, e2) / dz + glm::dot(off, e2) / f_;
  const Vec3d back = glm::normalize(-sx * e1 - sy * e2 - axis);
  double s;
  if (panel_.flat()) {
    if (!(back.z < 0.0)) return false;
    s = -q.z / back.z;
  } else if (!panel_.hitShell(q, back, 0.0, 0.0, 1e12, s)) {
    return false;
  }
  panelArrivalAt(panel_, q + s * back, back, gapMm_, out);
  out.throughput = 1.0f;
  out.lensletK = k, out.lensletL = l;
  return true;
}

}  // namespace inim
