#include "view/ideal_mla.h"

#include <cmath>
#include <cstdio>

#include "core/error.h"

namespace inim {

namespace {
std::string num(double v) {
  char b[40];
  std::snprintf(b, sizeof b, "%.6g", v);
  return b;
}
}  // namespace

IdealLensletMla::IdealLensletMla(const EiLayout& L, double pitchMm, double focalLengthMm, double gapMm)
    : K_(L.eiCols), L_(L.eiRows), pitch_(pitchMm), f_(focalLengthMm), g_(gapMm) {
  if (!(pitch_ > 0.0) || !std::isfinite(pitch_)) throw InputError("", "mla.pitch_mm", num(pitch_), "a pitch > 0");
  if (!(f_ > 0.0) || !std::isfinite(f_)) throw InputError("", "mla focal length", num(f_), "a focal length > 0 mm");
  if (!(g_ > 0.0) || !std::isfinite(g_)) throw InputError("", "gap_mm", num(g_), "a gap > 0 mm");
  if (K_ < 1 || L_ < 1 || L.lensX.size() != size_t(K_) || L.lensY.size() != size_t(L_))
    throw InputError("", "ei_count", std::to_string(K_) + " x " + std::to_string(L_), "at least one lenslet");
  x0_ = L.lensX.front();
  y0_ = L.lensY.front();
}

bool IdealLensletMla::cellAt(double x, double y, int& k, int& l) const {
  const double fk = (x - x0_) / pitch_ + 0.5, fl = (y0_ - y) / pitch_ + 0.5;
  if (!(fk >= 0.0 && fl >= 0.0 && fk < K_ && fl < L_)) return false;
  k = int(fk);
  l = int(fl);
  return true;
}

bool IdealLensletMla::traceToPanel(const Ray& ray, float, Rng&, PanelArrival& out) const {
  const Vec3d o(ray.o), d(ray.d);
  if (!(d.z < 0.0) || !(o.z >= 0.0)) return false;
  const double t = -o.z / d.z;
  const double x = o.x + t * d.x, y = o.y + t * d.y;
  int k, l;
  if (!cellAt(x, y, k, l)) return false;
  // Viewer-side slope s' (dx/dz of the light going to the viewer = of the reversed ray).
  const double sx = d.x / d.z + (x - lensX(k)) / f_;
  const double sy = d.y / d.z + (y - lensY(l)) / f_;
  out.p = Point3(float(x - g_ * sx), float(y - g_ * sy), float(-g_));
  out.d = Vec3(glm::normalize(Vec3d(-sx, -sy, -1.0)));
  out.throughput = 1.0f;
  out.lensletK = k;
  out.lensletL = l;
  return true;
}

}  // namespace inim
