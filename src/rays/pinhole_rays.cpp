#include "rays/pinhole_rays.h"

#include <cmath>
#include <cstdio>
#include <string>

#include "core/error.h"
#include "core/parallel.h"
#include "core/progress.h"
#include "core/size_budget.h"

namespace inim {

Point3d pixelCentre(const EiLayout& L, const RayAddress& a) {
  PixelCoord p = eiaPixel(L, a);
  return {L.pixelCentreX(p.col), L.pixelCentreY(p.row), -L.gapMm};
}

RayD pinholeRay(const EiLayout& L, const RayAddress& a) {
  Point3d c(L.pinholeXAt(a.k, a.l), L.pinholeYAt(a.k, a.l), 0.0);
  Vec3d d = c - pixelCentre(L, a);
  return {c, d / std::sqrt(glm::dot(d, d))};
}

RaySet generatePinholeRays(const EiLayout& L, ProgressBar* progress) {
  char eis[96];
  std::snprintf(eis, sizeof eis, "[%d, %d] EIs of %d x %d px", L.eiCols, L.eiRows, L.eiW, L.eiH);
  checkAllocation("", "ei_count", eis, {{double(L.numRays()), 24.0}},
                  std::to_string(L.numRays()) + " rays of 24 bytes");
  RaySet rays;
  rays.resize(size_t(L.numRays()));
  const int n = L.eiW, m = L.eiH;
  const double g = L.gapMm;
  // One task per EI: its rays are a contiguous block [e * n * m, (e + 1) * n * m).
  parallelForRange(
      L.numEis(),
      [&](int64_t e0, int64_t e1) {
        for (int64_t e = e0; e < e1; ++e) {
          int k = int(e / L.eiRows);
          int l = L.eiRows - 1 - int(e % L.eiRows);
          if (L.isHex()) {
            const double cx = L.pinholeXAt(k, l), cy = L.pinholeYAt(k, l);
            L.forEachRayOfEi(k, l, [&](int64_t r, int col, int row, int, int) {
              double vx = cx - L.pixelCentreX(col), vy = cy - L.pixelCentreY(row);
              double inv = 1.0 / std::sqrt(vx * vx + vy * vy + g * g);
              rays.ox[size_t(r)] = float(cx);
              rays.oy[size_t(r)] = float(cy);
              rays.oz[size_t(r)] = 0.0f;
              rays.dx[size_t(r)] = float(vx * inv);
              rays.dy[size_t(r)] = float(vy * inv);
              rays.dz[size_t(r)] = float(g * inv);
            });
            if (progress) progress->add(uint64_t(L.eiRayCount(k, l)));
            continue;
          }
          double cx = L.pinholeX[size_t(k)], cy = L.pinholeY[size_t(l)];
          int col0 = L.eiCol0[size_t(k)], row0 = L.eiRow0[size_t(l)];
          size_t r = size_t(e) * size_t(n) * size_t(m);
          for (int i = 0; i < n; ++i) {
            double vx = cx - L.pixelCentreX(col0 + i);
            for (int jb = 0; jb < m; ++jb, ++r) {
              double vy = cy - L.pixelCentreY(row0 + m - 1 - jb);
              double inv = 1.0 / std::sqrt(vx * vx + vy * vy + g * g);
              rays.ox[r] = float(cx);
              rays.oy[r] = float(cy);
              rays.oz[r] = 0.0f;
              rays.dx[r] = float(vx * inv);
              rays.dy[r] = float(vy * inv);
              rays.dz[r] = float(g * inv);
            }
          }
          if (progress) progress->add(uint64_t(n) * uint64_t(m));
        }
      },
      nullptr, 16);
  return rays;
}

std::optional<RayAddress> predictPixelForPoint(const EiLayout& L, int k, int l, const Point3d& p) {
  if (k < 0 || l < 0 || k >= L.eiCols || l >= L.eiRows) return std::nullopt;
  if (!(std::abs(p.z) > 0.0) || !std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
    return std::nullopt;
  const double cx = L.pinholeXAt(k, l), cy = L.pinholeYAt(k, l), g = L.gapMm;
  // The line through the pinhole c and p meets z = -g at q = c - g (p - c) / p_z.
  double qx = cx - g * (p.x - cx) / p.z;
  double qy = cy - g * (p.y - cy) / p.z;
  if (L.isHex()) {
    // The EIA pixel holding q, when EI (k, l) owns it.
    const double u = qx / L.pixelMm + 0.5 * L.eiaW, v = 0.5 * L.eiaH - qy / L.pixelMm;
    if (!(u >= 0.0 && u < L.eiaW && v >= 0.0 && v < L.eiaH)) return std::nullopt;
    int ok, ol;
    const int col = int(u), row = int(v);
    if (!L.eiAtPixel(col, row, ok, ol) || ok != k || ol != l) return std::nullopt;
    return RayAddress{k, l, col - L.eiBoxCol0(k, l), row - L.eiBoxRow0(k, l)};
  }
  // EI-local pixel coordinates: columns from the EI's left edge, rows from its top edge.
  double left = L.pixelCentreX(L.eiCol0[size_t(k)]) - 0.5 * L.pixelMm;
  double top = L.pixelCentreY(L.eiRow0[size_t(l)]) + 0.5 * L.pixelMm;
  double u = (qx - left) / L.pixelMm, v = (top - qy) / L.pixelMm;
  if (!(u >= 0.0 && u < L.eiW && v >= 0.0 && v < L.eiH)) return std::nullopt;
  return RayAddress{k, l, int(u), int(v)};
}

std::vector<float> driveFromEia(const EiLayout& L, const Image& eia) {
  if (eia.width != L.eiaW || eia.height != L.eiaH || eia.numChannels() < 3)
    throw InputError("", "EIA image",
                     std::to_string(eia.width) + " x " + std::to_string(eia.height) + " px, " +
                         std::to_string(eia.numChannels()) + " channels",
                     "the display's EIA size " + std::to_string(L.eiaW) + " x " +
                         std::to_string(L.eiaH) + " px with at least 3 channels (R, G, B)");
  std::vector<float> drive(size_t(L.numRays()) * 3);
  parallelForRange(L.numRays(), [&](int64_t r0, int64_t r1) {
    for (int64_t r = r0; r < r1; ++r) {
      PixelCoord p = eiaPixel(L, rayAddress(L, r));
      for (int c = 0; c < 3; ++c) drive[size_t(r) * 3 + size_t(c)] = eia.at(p.col, p.row, c);
    }
  });
  return drive;
}

Image eiaFromDrive(const EiLayout& L, const std::vector<float>& drive) {
  if (drive.size() != size_t(L.numRays()) * 3)
    throw InputError("", "drive values", std::to_string(drive.size()),
                     "3 values (R, G, B) for each of the layout's " + std::to_string(L.numRays()) + " rays");
  Image eia(L.eiaW, L.eiaH, {"R", "G", "B"});
  parallelForRange(L.numRays(), [&](int64_t r0, int64_t r1) {
    for (int64_t r = r0; r < r1; ++r) {
      PixelCoord p = eiaPixel(L, rayAddress(L, r));
      for (int c = 0; c < 3; ++c) eia.at(p.col, p.row, c) = drive[size_t(r) * 3 + size_t(c)];
    }
  });
  return eia;
}

}  // namespace inim
