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
  if (!tracer_->trace(o, glm::normalize(Vec3d(ray.d)), lambdaNm, mode, rng, ex) || ex.towardViewer) return false;
  out.p = Point3(float(ex.p.x), float(ex.p.y), float(-gapMm_));
  out.d = Vec3(ex.d);
  out.throughput = float(ex.throughput);
  out.lensletK = out.lensletL = -1;
  if (ex.crossedLens) lensletAt(ex.lensXMm, ex.lensYMm, out.lensletK, out.lensletL);
  return true;
}

}  // namespace inim
