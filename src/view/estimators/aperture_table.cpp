#include "view/aperture_kernel.h"

#include <algorithm>
#include <cmath>

namespace inim {

namespace {

// Inverse of sampleUniformDiskConcentric (Shirley-Chiu): unit disk -> [0, 1)^2.
Vec2d inverseConcentric(const Vec2d& d) {
  const double r = std::sqrt(d.x * d.x + d.y * d.y);
  if (r == 0.0) return Vec2d(0.5);
  const double q = 3.14159265358979323846 / 4.0;
  double phi = std::atan2(d.y, d.x);
  Vec2d o;
  if (phi >= -q && phi <= q) {
    o = Vec2d(r, r * phi / q);
  } else if (phi > q && phi <= 3.0 * q) {
    o = Vec2d(r * (2.0 * q - phi) / q, r);
  } else if (phi < -q && phi >= -3.0 * q) {
    const double t = phi + 3.14159265358979323846;  // in [pi/4, 3pi/4]
    o = Vec2d(-r * (2.0 * q - t) / q, -r);
  } else {
    const double t = phi > 0.0 ? phi - 3.14159265358979323846 : phi + 3.14159265358979323846;  // in [-pi/4, pi/4]
    o = Vec2d(-r, -r * t / q);
  }
  return 0.5 * (o + Vec2d(1.0));
}

}  // namespace

ApertureSpace::ApertureSpace(const CameraModel& camera) : camera_(camera) {
  real_ = dynamic_cast<const RealLensCameraModel*>(&camera);
  thin_ = dynamic_cast<const ThinLensCameraModel*>(&camera) != nullptr;
  if (real_) {
    const double z = real_->lens().sensorZ() - real_->pupilBounds().rearZ();
    zScale_ = 1.0 / (z * z * real_->centreIrradiance());
  }
}

bool ApertureSpace::domain(Vec2 pixel, Vec2d& lo, Vec2d& hi) const {
  if (!real_) {
    lo = Vec2d(thin_ ? -1.0 : 0.0);
    hi = Vec2d(1.0);
    return true;
  }
  const Vec2d s = real_->sensorPoint(pixel);
  const double r = std::sqrt(s.x * s.x + s.y * s.y);
  const PupilBox& b = real_->pupilBounds().box(r);
  if (b.empty) return false;
  const double c = r > 0.0 ? s.x / r : 1.0, sn = r > 0.0 ? s.y / r : 0.0;
  lo = Vec2d(1e300);
  hi = Vec2d(-1e300);
  for (int i = 0; i < 4; ++i) {
    const Vec2d q((i & 1) ? b.hi.x : b.lo.x, (i & 2) ? b.hi.y : b.lo.y);
    const Vec2d p(c * q.x - sn * q.y, sn * q.x + c * q.y);
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  const Vec2d m = 0.05 * (hi - lo);
  lo -= m;
  hi += m;
  return true;
}

float ApertureSpace::ray(Vec2 pixel, const Vec2d& a, float lambdaNm, Ray& out) const {
  if (thin_) {
    if (!(a.x * a.x + a.y * a.y <= 1.0)) return 0.0f;
    const Vec2d u = glm::clamp(inverseConcentric(a), Vec2d(0.0), Vec2d(0x1.fffffep-1));
    return camera_.generateRay(pixel, Vec2(float(u.x), float(u.y)), lambdaNm, out) / float(3.14159265358979323846);
  }
  if (!real_) {
    if (!(a.x >= 0.0 && a.y >= 0.0 && a.x < 1.0 && a.y < 1.0)) return 0.0f;
    return camera_.generateRay(pixel, Vec2(float(a.x), float(a.y)), lambdaNm, out);
  }
  LensRay lr;
  const double w = real_->traceFromSensor(real_->sensorPoint(pixel), Point3d(a.x, a.y, real_->pupilBounds().rearZ()),
                                          lambdaNm, lr);
  if (!(w > 0.0)) return 0.0f;
  out = real_->lensToWorld(lr);
  return float(w * zScale_);
}

ApertureKernel buildApertureKernel(const ApertureSpace& space, Vec2 pixel, float lambdaNm, int grid, uint64_t& rays,
                                   float planeZ) {
  ApertureKernel k;
  Vec2d lo, hi;
  if (!space.domain(pixel, lo, hi)) return k;
  const int G = std::max(2, grid);
  const double cw = (hi.x - lo.x) / G, ch = (hi.y - lo.y) / G;
  k.cellW = cw;
  k.cellH = ch;
  std::vector<float> node(size_t(G + 1) * size_t(G + 1));
  Ray r;
  for (int j = 0; j <= G; ++j)
    for (int i = 0; i <= G; ++i) {
      node[size_t(j) * (G + 1) + size_t(i)] = std::max(0.0f, space.ray(pixel, Vec2d(lo.x + i * cw, lo.y + j * ch), lambdaNm, r));
      ++rays;
    }
  struct Raw {
    double ax, ay, w;
  };
  std::vector<Raw> raw;
  constexpr int kSub = 4;
  for (int j = 0; j < G; ++j)
    for (int i = 0; i < G; ++i) {
      const float w00 = node[size_t(j) * (G + 1) + size_t(i)], w10 = node[size_t(j) * (G + 1) + size_t(i + 1)];
      const float w01 = node[size_t(j + 1) * (G + 1) + size_t(i)], w11 = node[size_t(j + 1) * (G + 1) + size_t(i + 1)];
      const int pass = (w00 > 0) + (w10 > 0) + (w01 > 0) + (w11 > 0);
      const double x0 = lo.x + i * cw, y0 = lo.y + j * ch;
      if (pass == 4) {
        raw.push_back({x0 + 0.5 * cw, y0 + 0.5 * ch, 0.25 * (double(w00) + w10 + w01 + w11) * cw * ch});
      } else if (pass > 0) {
        double sw = 0.0, sx = 0.0, sy = 0.0;
        for (int b = 0; b < kSub; ++b)
          for (int a = 0; a < kSub; ++a) {
            const Vec2d q(x0 + (a + 0.5) / kSub * cw, y0 + (b + 0.5) / kSub * ch);
            const double w = std::max(0.0f, space.ray(pixel, q, lambdaNm, r));
            ++rays;
            sw += w;
            sx += w * q.x;
            sy += w * q.y;
          }
        if (sw > 0.0) raw.push_back({sx / sw, sy / sw, sw / (kSub * kSub) * cw * ch});
      }
    }
  double tw = 0.0, cx = 0.0, cy = 0.0;
  for (const Raw& p : raw) {
    tw += p.w;
    cx += p.w * p.ax;
    cy += p.w * p.ay;
  }
  if (!(tw > 0.0)) return k;
  cx /= tw;
  cy /= tw;
  k.total = tw;
  k.centre = Vec2d(cx, cy);
  // The rays' crossings of z = planeZ and slopes, relative to the centre ray's.
  auto cross = [&](const Vec2d& a, Vec2d& h, Vec2d& sl) -> float {
    Ray r2;
    const float w = space.ray(pixel, a, lambdaNm, r2);
    ++rays;
    if (!(w > 0.0f)) return w;
    if (!(r2.d.z < 0.0f) || !(r2.o.z > planeZ)) return -1.0f;
    const double t = (double(planeZ) - r2.o.z) / r2.d.z;
    h = Vec2d(r2.o.x + t * r2.d.x, r2.o.y + t * r2.d.y);
    sl = Vec2d(r2.d.x / -double(r2.d.z), r2.d.y / -double(r2.d.z));
    return w;
  };
  Vec2d hc, sc;
  k.centreWeight = cross(k.centre, hc, sc);
  if (!(k.centreWeight > 0.0f)) {
    k.centreWeight = 0.0f;
    return k;
  }
  double m2 = 0.0, mh = 0.0, ms = 0.0;
  // Normal equations of the affine fit (offsets = M (a - centre)), weighted.
  double Saa[2][2] = {}, Sha[2][2] = {}, Ssa[2][2] = {};
  for (const Raw& p : raw) {
    Vec2d h, sl;
    const float w = cross(Vec2d(p.ax, p.ay), h, sl);
    if (w < 0.0f) return ApertureKernel{};  // a ray that does not head down through the plane
    if (w == 0.0f) {
      // A refined cell's centroid that is itself blocked (a thin sliver): use the centre ray.
      h = hc;
      sl = sc;
    }
    const double ax = p.ax - cx, ay = p.ay - cy, dh[2] = {h.x - hc.x, h.y - hc.y}, ds[2] = {sl.x - sc.x, sl.y - sc.y};
    const double av[2] = {ax, ay};
    for (int i = 0; i < 2; ++i)
      for (int j = 0; j < 2; ++j) {
        Saa[i][j] += p.w * av[i] * av[j];
        Sha[i][j] += p.w * dh[i] * av[j];
        Ssa[i][j] += p.w * ds[i] * av[j];
      }
    m2 += p.w * (ax * ax + ay * ay);
    mh += p.w * (dh[0] * dh[0] + dh[1] * dh[1]);
    ms += p.w * (ds[0] * ds[0] + ds[1] * ds[1]);
    k.points.push_back({float(ax), float(ay), float(p.w), float(dh[0]), float(dh[1]), float(ds[0]), float(ds[1])});
  }
  const double det = Saa[0][0] * Saa[1][1] - Saa[0][1] * Saa[1][0];
  if (std::abs(det) > 0.0) {
    const double inv[2][2] = {{Saa[1][1] / det, -Saa[0][1] / det}, {-Saa[1][0] / det, Saa[0][0] / det}};
    for (int i = 0; i < 2; ++i)
      for (int j = 0; j < 2; ++j) {
        k.shiftH[i][j] = Sha[i][0] * inv[0][j] + Sha[i][1] * inv[1][j];
        k.shiftS[i][j] = Ssa[i][0] * inv[0][j] + Ssa[i][1] * inv[1][j];
      }
  }
  k.rmsRadius = std::sqrt(m2 / tw);
  k.rmsH = std::sqrt(mh / tw);
  k.rmsS = std::sqrt(ms / tw);
  return k;
}

}  // namespace inim
