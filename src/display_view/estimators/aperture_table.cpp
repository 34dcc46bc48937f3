#include "display_view/estimators/aperture_table.h"

#include <algorithm>
#include <cmath>

namespace inim {

namespace {

// A point of the aperture before the centre is known: position and weight.
struct RawPoint {
  double ax, ay, w;
};

constexpr int kRefine = 4;  // sub-samples per side of a cell at the pupil's edge

// The weighted points of the G x G grid over [lo, hi] (see the header).
std::vector<RawPoint> gridPoints(const CameraModel& camera, Vec2 pixel, float lambdaNm, int G, const Vec2d& lo,
                                 double cellW, double cellH, uint64_t& rays) {
  std::vector<float> node(size_t(G + 1) * size_t(G + 1));
  Ray r;
  for (int j = 0; j <= G; ++j)
    for (int i = 0; i <= G; ++i) {
      node[size_t(j) * (G + 1) + size_t(i)] =
          std::max(0.0f, camera.apertureRay(pixel, Vec2d(lo.x + i * cellW, lo.y + j * cellH), lambdaNm, r));
      ++rays;
    }
  std::vector<RawPoint> raw;
  for (int j = 0; j < G; ++j)
    for (int i = 0; i < G; ++i) {
      const float w00 = node[size_t(j) * (G + 1) + size_t(i)], w10 = node[size_t(j) * (G + 1) + size_t(i + 1)];
      const float w01 = node[size_t(j + 1) * (G + 1) + size_t(i)], w11 = node[size_t(j + 1) * (G + 1) + size_t(i + 1)];
      const int pass = (w00 > 0) + (w10 > 0) + (w01 > 0) + (w11 > 0);
      const double x0 = lo.x + i * cellW, y0 = lo.y + j * cellH;
      if (pass == 4) {
        raw.push_back({x0 + 0.5 * cellW, y0 + 0.5 * cellH, 0.25 * (double(w00) + w10 + w01 + w11) * cellW * cellH});
      } else if (pass > 0) {
        double sw = 0.0, sx = 0.0, sy = 0.0;
        for (int b = 0; b < kRefine; ++b)
          for (int a = 0; a < kRefine; ++a) {
            const Vec2d q(x0 + (a + 0.5) / kRefine * cellW, y0 + (b + 0.5) / kRefine * cellH);
            const double w = std::max(0.0f, camera.apertureRay(pixel, q, lambdaNm, r));
            ++rays;
            sw += w;
            sx += w * q.x;
            sy += w * q.y;
          }
        if (sw > 0.0) raw.push_back({sx / sw, sy / sw, sw / (kRefine * kRefine) * cellW * cellH});
      }
    }
  return raw;
}

// The ray through aperture point `a`: its weight, and its crossing h of z = planeZ and slope sl
// there; -1 when it passes but does not head down through the plane.
float crossing(const CameraModel& camera, Vec2 pixel, const Vec2d& a, float lambdaNm, float planeZ, Vec2d& h,
               Vec2d& sl, uint64_t& rays) {
  Ray r;
  const float w = camera.apertureRay(pixel, a, lambdaNm, r);
  ++rays;
  if (!(w > 0.0f)) return w;
  if (!(r.d.z < 0.0f) || !(r.o.z > planeZ)) return -1.0f;
  const double t = (double(planeZ) - r.o.z) / r.d.z;
  h = Vec2d(r.o.x + t * r.d.x, r.o.y + t * r.d.y);
  sl = Vec2d(r.d.x / -double(r.d.z), r.d.y / -double(r.d.z));
  return w;
}

}  // namespace

double apertureWeightIntegral(const CameraModel& camera, Vec2 pixel, float lambdaNm, int grid, uint64_t& rays) {
  Vec2d lo, hi;
  if (!camera.apertureDomain(pixel, lo, hi)) return 0.0;
  const int G = std::max(2, grid);
  double total = 0.0;
  for (const RawPoint& p : gridPoints(camera, pixel, lambdaNm, G, lo, (hi.x - lo.x) / G, (hi.y - lo.y) / G, rays))
    total += p.w;
  return total;
}

ApertureTable buildApertureTable(const CameraModel& camera, Vec2 pixel, float lambdaNm, int grid, uint64_t& rays,
                                 float planeZ) {
  ApertureTable table;
  Vec2d lo, hi;
  if (!camera.apertureDomain(pixel, lo, hi)) return table;
  const int G = std::max(2, grid);
  table.cellW = (hi.x - lo.x) / G;
  table.cellH = (hi.y - lo.y) / G;
  const std::vector<RawPoint> raw = gridPoints(camera, pixel, lambdaNm, G, lo, table.cellW, table.cellH, rays);
  double totalWeight = 0.0, cx = 0.0, cy = 0.0;
  for (const RawPoint& p : raw) {
    totalWeight += p.w;
    cx += p.w * p.ax;
    cy += p.w * p.ay;
  }
  if (!(totalWeight > 0.0)) return table;
  cx /= totalWeight;
  cy /= totalWeight;
  table.total = totalWeight;
  table.centre = Vec2d(cx, cy);
  Vec2d centreH, centreS;
  table.centreWeight = crossing(camera, pixel, table.centre, lambdaNm, planeZ, centreH, centreS, rays);
  if (!(table.centreWeight > 0.0f)) {
    table.centreWeight = 0.0f;
    return table;
  }
  double sumH2 = 0.0, sumS2 = 0.0;
  for (const RawPoint& p : raw) {
    Vec2d h, sl;
    const float w = crossing(camera, pixel, Vec2d(p.ax, p.ay), lambdaNm, planeZ, h, sl, rays);
    if (w < 0.0f) return ApertureTable{};  // a ray that does not head down through the plane
    if (w == 0.0f) {
      // A refined cell's centroid that is itself blocked (a thin sliver): use the centre ray.
      h = centreH;
      sl = centreS;
    }
    const double dh[2] = {h.x - centreH.x, h.y - centreH.y}, ds[2] = {sl.x - centreS.x, sl.y - centreS.y};
    sumH2 += p.w * (dh[0] * dh[0] + dh[1] * dh[1]);
    sumS2 += p.w * (ds[0] * ds[0] + ds[1] * ds[1]);
    table.points.push_back(
        {float(p.ax - cx), float(p.ay - cy), float(p.w), float(dh[0]), float(dh[1]), float(ds[0]), float(ds[1])});
  }
  table.rmsH = std::sqrt(sumH2 / totalWeight);
  table.rmsS = std::sqrt(sumS2 / totalWeight);
  return table;
}

}  // namespace inim
