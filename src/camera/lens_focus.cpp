#include "core/format.h"
#include "camera/lens_focus.h"

#include <cmath>
#include <cstdio>

#include "camera/lens_analysis.h"
#include "core/error.h"

namespace inim {

namespace {

// Traces a grid of rays over the paraxial entrance pupil; `makeRay(x, y, zEP)` builds the ray
// aimed at (x, y) on the entrance-pupil plane.
template <class MakeRay>
SpotDiagram spot(const LensSystem& lens, double sensorDistanceMm, double lambdaNm, int grid, MakeRay makeRay) {
  const LensInfo info = analyzeLens(lens, lambdaNm);
  const double zEP = info.entrancePupil.positionMm;
  const double R = 0.65 * info.entrancePupil.diameterMm;
  const std::vector<double> idx = lens.indicesAt(lambdaNm);
  const double zS = lens.lastVertexZ() + sensorDistanceMm;
  std::vector<Vec2d> a, b;  // position at zS and its slope dx/dz
  grid = std::max(grid, 2);
  for (int j = 0; j < grid; ++j)
    for (int i = 0; i < grid; ++i) {
      const double x = R * (2.0 * (i + 0.5) / grid - 1.0);
      const double y = R * (2.0 * (j + 0.5) / grid - 1.0);
      if (x * x + y * y > R * R) continue;
      LensRay r = makeRay(x, y, zEP);
      if (!lens.traceWithIndices(r, idx.data(), TraceDirection::ObjectToImage).ok() || r.d.z <= 0.0) continue;
      const Vec2d slope(r.d.x / r.d.z, r.d.y / r.d.z);
      a.push_back(Vec2d(r.o.x, r.o.y) + slope * (zS - r.o.z));
      b.push_back(slope);
    }
  SpotDiagram s;
  s.rays = int(a.size());
  if (a.empty()) return s;
  Vec2d ma(0.0), mb(0.0);
  for (size_t k = 0; k < a.size(); ++k) {
    ma += a[k];
    mb += b[k];
  }
  ma /= double(a.size());
  mb /= double(a.size());
  double varA = 0, cov = 0, varB = 0;
  for (size_t k = 0; k < a.size(); ++k) {
    const Vec2d da = a[k] - ma, db = b[k] - mb;
    varA += glm::dot(da, da);
    cov += glm::dot(da, db);
    varB += glm::dot(db, db);
  }
  varA /= double(a.size());
  cov /= double(a.size());
  varB /= double(a.size());
  s.centroidMm = ma;
  s.rmsRadiusMm = std::sqrt(std::max(0.0, varA));
  s.bestShiftMm = varB > 0.0 ? -cov / varB : 0.0;
  s.bestRmsRadiusMm = std::sqrt(std::max(0.0, varA + 2.0 * s.bestShiftMm * cov + s.bestShiftMm * s.bestShiftMm * varB));
  return s;
}

double frontStartZ(const LensSystem& lens, double zEP) {
  double m = 0.0;
  for (const auto& s : lens.surfaces()) m = std::max(m, s.apertureMm);
  return std::min(0.0, zEP) - m - 1.0;
}

}  // namespace

const char* focusModeName(FocusMode m) { return m == FocusMode::Paraxial ? "paraxial" : "best-rms"; }

SpotDiagram spotDiagram(const LensSystem& lens, const Point3d& P, double sensorDistanceMm, double lambdaNm, int grid) {
  return spot(lens, sensorDistanceMm, lambdaNm, grid, [&](double x, double y, double zEP) {
    return LensRay{P, glm::normalize(Point3d(x, y, zEP) - P)};
  });
}

SpotDiagram spotDiagramAtInfinity(const LensSystem& lens, const Vec3d& dir, double sensorDistanceMm, double lambdaNm,
                                  int grid) {
  const Vec3d d = glm::normalize(dir);
  return spot(lens, sensorDistanceMm, lambdaNm, grid, [&](double x, double y, double zEP) {
    const double z0 = frontStartZ(lens, zEP);
    const Point3d target(x, y, zEP);
    return LensRay{target - d * ((zEP - z0) / d.z), d};
  });
}

double focusSensorDistance(const LensSystem& lens, double objectZ, FocusMode mode, double lambdaNm) {
  const double parax = paraxialImageDistance(lens, objectZ, lambdaNm);
  if (mode == FocusMode::Paraxial) return parax;
  SpotDiagram s = std::isinf(objectZ) ? spotDiagramAtInfinity(lens, {0.0, 0.0, 1.0}, parax, lambdaNm, 61)
                                      : spotDiagram(lens, {0.0, 0.0, objectZ}, parax, lambdaNm, 61);
  return parax + s.bestShiftMm;
}

double widestFNumber(const LensSystem& lens, double lambdaNm) {
  const LensInfo info = analyzeLens(lens, lambdaNm);
  return info.fNumber * lens.stopDiameterMm() / lens.designStopDiameterMm();
}

double setFNumber(LensSystem& lens, double fNumber, double lambdaNm) {
  if (!(fNumber > 0.0) || !std::isfinite(fNumber))
    throw InputError(lens.file(), "f_number", formatNumber(fNumber), "an f-number > 0");
  const LensInfo info = analyzeLens(lens, lambdaNm);
  const double stop = lens.stopDiameterMm() * (info.eflMm / fNumber) / info.entrancePupil.diameterMm;
  if (stop > lens.designStopDiameterMm() * (1.0 + 1e-9)) {
    const double n0 = info.fNumber * lens.stopDiameterMm() / lens.designStopDiameterMm();
    throw InputError(lens.file(), "f_number", formatNumber(fNumber),
                     "an f-number >= " + formatNumber(n0) + " (the widest aperture of the design's stop)");
  }
  lens.setStopDiameterMm(stop);
  return stop;
}

}  // namespace inim
