#include "mla_optics/ideal_mla.h"

#include <cmath>

#include "core/error.h"
#include "core/format.h"

namespace inim {

IdealLensletMla::IdealLensletMla(const EiLayout& L, double pitchMm, double focalLengthMm, double gapMm)
    : K_(L.eiCols), L_(L.eiRows), pitch_(pitchMm), f_(focalLengthMm), g_(gapMm) {
  if (!(pitch_ > 0.0) || !std::isfinite(pitch_)) throw InputError("", "mla.pitch_mm", formatNumber(pitch_), "a pitch > 0");
  if (!(f_ > 0.0) || !std::isfinite(f_)) throw InputError("", "mla focal length", formatNumber(f_), "a focal length > 0 mm");
  if (!(g_ > 0.0) || !std::isfinite(g_)) throw InputError("", "gap_mm", formatNumber(g_), "a gap > 0 mm");
  if (K_ < 1 || L_ < 1 || L.lensX.size() != size_t(K_) || L.lensY.size() != size_t(L_))
    throw InputError("", "ei_count", std::to_string(K_) + " x " + std::to_string(L_), "at least one lenslet");
  hex_ = L.isHex();
  rowPitch_ = hex_ ? pitch_ * std::sqrt(3.0) / 2.0 : pitch_;
  x0_ = L.lensXAt(0, 0);
  y0_ = L.lensYAt(0, 0);
}

bool IdealLensletMla::cellAt(double x, double y, int& k, int& l) const {
  if (hex_) {
    // The nearest lens centre (of the infinite lattice), among the three nearest rows.
    if (!std::isfinite(x) || !std::isfinite(y)) return false;
    const int l0 = int(std::floor((y0_ - y) / rowPitch_ + 0.5));
    double best = INFINITY;
    int bk = 0, bl = 0;
    for (int li = l0 - 1; li <= l0 + 1; ++li) {
      const double sh = (li & 1) ? 0.5 : 0.0;
      const int ki = int(std::floor((x - x0_) / pitch_ - sh + 0.5));
      const double dx = x - (x0_ + (ki + sh) * pitch_), dy = y - (y0_ - li * rowPitch_);
      const double d2 = dx * dx + dy * dy;
      if (d2 < best) best = d2, bk = ki, bl = li;
    }
    if (bk < 0 || bl < 0 || bk >= K_ || bl >= L_) return false;
    k = bk, l = bl;
    return true;
  }
  const double fk = (x - x0_) / pitch_ + 0.5, fl = (y0_ - y) / pitch_ + 0.5;
  if (!(fk >= 0.0 && fl >= 0.0 && fk < K_ && fl < L_)) return false;
  k = int(fk);
  l = int(fl);
  return true;
}

bool IdealLensletMla::lensletCell(double x, double y, LensletCell& out) const {
  if (!cellAt(x, y, out.k, out.l)) return false;
  out.cx = lensXAt(out.k, out.l);
  out.cy = lensYAt(out.k, out.l);
  out.pitch = pitch_;
  out.n = hex_ ? 6 : 4;
  for (int i = 0; i < out.n; ++i) {  // square: +-x, +-y; hex (pointy-top): normals every 60 deg
    const double a = hex_ ? i * M_PI / 3.0 : i * M_PI / 2.0;
    out.nx[size_t(i)] = std::abs(std::cos(a)) < 1e-15 ? 0.0 : std::cos(a);
    out.ny[size_t(i)] = std::abs(std::sin(a)) < 1e-15 ? 0.0 : std::sin(a);
    out.h[size_t(i)] = 0.5 * pitch_;
  }
  return true;
}

bool IdealLensletMla::traceToPanel(const Ray& ray, float, FresnelMode, Rng*, PanelArrival& out) const {
  const Vec3d o(ray.o), d(ray.d);
  if (!(d.z < 0.0) || !(o.z >= 0.0)) return false;
  const double t = -o.z / d.z;
  const double x = o.x + t * d.x, y = o.y + t * d.y;
  int k, l;
  if (!cellAt(x, y, k, l)) return false;
  // Viewer-side slope s' (dx/dz of the light going to the viewer = of the reversed ray).
  const double sx = d.x / d.z + (x - lensXAt(k, l)) / f_;
  const double sy = d.y / d.z + (y - lensYAt(k, l)) / f_;
  out.p = Point3(float(x - g_ * sx), float(y - g_ * sy), float(-g_));
  out.d = Vec3(glm::normalize(Vec3d(-sx, -sy, -1.0)));
  out.throughput = 1.0f;
  out.lensletK = k;
  out.lensletL = l;
  return true;
}

}  // namespace inim
