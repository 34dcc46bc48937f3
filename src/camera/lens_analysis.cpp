#include "camera/lens_analysis.h"

#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <sstream>

#include "core/error.h"
#include "core/format.h"

namespace inim {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// Q(0) from Q(h) and Q(2h) for Q(h) = Q0 + a h^2 + O(h^4).
double extrapolate(const std::function<double(double)>& q, double h) {
  const double q1 = q(h), q2 = q(2.0 * h);
  return (4.0 * q1 - q2) / 3.0;
}

// z where a meridional ray (in the y-z plane) crosses the axis.
double axisCrossingZ(const LensRay& r) {
  if (r.d.y == 0.0) return r.d.z > 0.0 ? std::numeric_limits<double>::infinity() : -std::numeric_limits<double>::infinity();
  return r.o.z - r.o.y * r.d.z / r.d.y;
}

TraceOptions noApertures(int first = 0, int last = -1) {
  TraceOptions o;
  o.apertures = false;
  o.first = first;
  o.last = last;
  return o;
}

void require(const TraceResult& r, const LensSystem& lens, const char* what) {
  if (!r.ok())
    throw InputError(lens.file(), "surface " + std::to_string(r.surface), traceStatusName(r.status),
                     std::string("a lens that passes near-axis rays (") + what + ")");
}

// Height at surface `target` of a path.
double heightAt(const std::vector<SurfaceHit>& path, int target) {
  for (const auto& h : path)
    if (h.surface == target) return h.p.y;
  return kNaN;
}

std::string fmt(const char* f, double v) {
  char b[64];
  std::snprintf(b, sizeof b, f, v);
  return b;
}

}  // namespace

double nearAxisHeight(const LensSystem& lens) {
  double m = std::numeric_limits<double>::infinity();
  for (const auto& s : lens.surfaces()) m = std::min(m, s.semiAperture());
  return 1e-3 * m;
}

double paraxialImageDistance(const LensSystem& lens, double objectZ, double lambdaNm) {
  const double h = nearAxisHeight(lens);
  const double zLast = lens.lastVertexZ();
  auto q = [&](double hh) {
    LensRay r;
    if (std::isinf(objectZ)) {
      r = {{0.0, hh, -1.0}, {0.0, 0.0, 1.0}};
    } else {
      // A ray from the axial object point reaching height hh at the first vertex plane.
      r.o = {0.0, 0.0, objectZ};
      r.d = glm::normalize(Vec3d(0.0, hh, -objectZ));
    }
    TraceResult tr = lens.trace(r, lambdaNm, TraceDirection::ObjectToImage, noApertures());
    require(tr, lens, "image distance");
    return axisCrossingZ(r) - zLast;
  };
  return extrapolate(q, h);
}

namespace {

std::vector<std::string> surfaceRows(const LensSystem& lens) {
  std::vector<std::string> rows;
  char buf[256];
  for (int k = 0; k < lens.surfaceCount(); ++k) {
    const LensSurface& s = lens.surfaces()[size_t(k)];
    std::snprintf(buf, sizeof buf, "%2d %-12s t %-9.5g %-24s D %.4g", k,
                  s.isStop ? "stop" : ("R " + formatNumber(s.radiusMm, "%.6g")).c_str(), s.thicknessMm,
                  s.mediumName.c_str(), s.apertureMm);
    std::string row = buf;
    if (s.conic != 0.0) row += "  conic " + formatNumber(s.conic, "%.6g");
    for (size_t a = 0; a < s.asphere.size(); ++a)
      if (s.asphere[a] != 0.0) row += "  a" + std::to_string(2 * a + 2) + " " + formatNumber(s.asphere[a], "%.6g");
    if (!s.source.empty()) row += "  (" + s.source + ")";
    rows.push_back(row);
  }
  return rows;
}

}  // namespace

LensInfo analyzeLens(const LensSystem& lens, double lambdaNm) {
  LensInfo info;
  info.name = lens.name();
  info.file = lens.file();
  info.wavelengthNm = lambdaNm;
  info.surfaceCount = lens.surfaceCount();
  info.stopSurface = lens.stopIndex();
  info.stopDiameterMm = lens.stopDiameterMm();
  info.dispersive = lens.isDispersive();
  info.design = lens.design();
  info.surfaceRows = surfaceRows(lens);
  info.lengthMm = lens.lengthMm();
  const int n = lens.surfaceCount();
  const int stop = lens.stopIndex();
  const double zLast = lens.lastVertexZ();
  const double h = nearAxisHeight(lens);
  const std::vector<double> idx = lens.indicesAt(lambdaNm);

  // Rear focal point and EFL: a ray parallel to the axis from the object side.
  auto forwardParallel = [&](double hh) {
    LensRay r{{0.0, hh, -1.0}, {0.0, 0.0, 1.0}};
    require(lens.traceWithIndices(r, idx.data(), TraceDirection::ObjectToImage, noApertures()), lens, "EFL");
    return r;
  };
  info.eflMm = extrapolate([&](double hh) { LensRay r = forwardParallel(hh); return -hh * r.d.z / r.d.y; }, h);
  // A lens without power (only a stop, or flat and afocal groups) sends parallel rays out
  // parallel: it has no focal length, and no camera can be built on it.
  if (!std::isfinite(info.eflMm) || std::abs(info.eflMm) > 1e9)
    throw InputError(lens.file(), "surfaces", std::to_string(n) + " surface" + (n == 1 ? "" : "s"),
                     "a lens with optical power (near-axis rays parallel to the axis leave it parallel: no focal "
                     "length)");
  info.bflMm = extrapolate([&](double hh) { return axisCrossingZ(forwardParallel(hh)) - zLast; }, h);

  // Front focal point: a ray parallel to the axis from the image side.
  auto backwardParallel = [&](double hh, int first, int last, std::vector<SurfaceHit>* path) {
    LensRay r{{0.0, hh, zLast + 1.0}, {0.0, 0.0, -1.0}};
    require(lens.traceWithIndices(r, idx.data(), TraceDirection::ImageToObject, noApertures(first, last), path),
            lens, "front focal length");
    return r;
  };
  info.fflMm = extrapolate([&](double hh) { return -axisCrossingZ(backwardParallel(hh, 0, -1, nullptr)); }, h);
  info.frontPrincipalMm = -info.fflMm + info.eflMm;
  info.rearPrincipalMm = info.bflMm - info.eflMm;

  // Pupils: the stop imaged through the front group (entrance) and the rear group (exit).
  const double rStop = 0.5 * lens.stopDiameterMm();
  const double zStop = lens.vertexZ(stop);
  if (stop == 0) {
    info.entrancePupil = {0.0, 2.0 * rStop};
  } else {
    const double a = h / std::max(1.0, std::abs(zStop));  // a small angle
    info.entrancePupil.positionMm = extrapolate(
        [&](double aa) {
          LensRay r{{0.0, 0.0, zStop}, glm::normalize(Vec3d(0.0, aa, -1.0))};
          require(lens.traceWithIndices(r, idx.data(), TraceDirection::ImageToObject, noApertures(0, stop - 1)), lens,
                  "entrance pupil");
          return axisCrossingZ(r);
        },
        a);
    info.entrancePupil.diameterMm = extrapolate(
        [&](double hh) {
          LensRay r{{0.0, hh, -1.0}, {0.0, 0.0, 1.0}};
          std::vector<SurfaceHit> path;
          require(lens.traceWithIndices(r, idx.data(), TraceDirection::ObjectToImage, noApertures(0, stop), &path),
                  lens, "entrance pupil");
          return 2.0 * hh * rStop / heightAt(path, stop);
        },
        h);
  }
  if (stop == n - 1) {
    info.exitPupil = {0.0, 2.0 * rStop};
  } else {
    const double a = h / std::max(1.0, std::abs(zLast - zStop));
    info.exitPupil.positionMm = extrapolate(
        [&](double aa) {
          LensRay r{{0.0, 0.0, zStop}, glm::normalize(Vec3d(0.0, aa, 1.0))};
          require(lens.traceWithIndices(r, idx.data(), TraceDirection::ObjectToImage, noApertures(stop + 1, -1)), lens,
                  "exit pupil");
          return axisCrossingZ(r) - zLast;
        },
        a);
    info.exitPupil.diameterMm = extrapolate(
        [&](double hh) {
          std::vector<SurfaceHit> path;
          backwardParallel(hh, stop, -1, &path);
          return 2.0 * hh * rStop / heightAt(path, stop);
        },
        h);
  }
  info.entrancePupil.diameterMm = std::abs(info.entrancePupil.diameterMm);
  info.exitPupil.diameterMm = std::abs(info.exitPupil.diameterMm);
  info.fNumber = info.eflMm / info.entrancePupil.diameterMm;
  info.totalTrackMm = info.lengthMm + info.bflMm;
  return info;
}

std::string lensInfoText(const LensInfo& i) {
  std::ostringstream o;
  o << "Lens:                 " << (i.name.empty() ? "(unnamed)" : i.name) << "\n";
  if (!i.file.empty()) o << "File:                 " << i.file << "\n";
  o << "Surfaces:             " << i.surfaceCount << " (aperture stop: surface " << i.stopSurface << ", diameter "
    << fmt("%.4f", i.stopDiameterMm) << " mm)\n";
  o << "Wavelength:           " << fmt("%.2f", i.wavelengthNm) << " nm" << (i.dispersive ? " (dispersive glass)" : " (non-dispersive)") << "\n";
  o << "Effective focal length (EFL):  " << fmt("%.4f", i.eflMm) << " mm\n";
  o << "Back focal length (BFL):       " << fmt("%.4f", i.bflMm) << " mm  (last vertex to rear focal point)\n";
  o << "Front focal length (FFL):      " << fmt("%.4f", i.fflMm) << " mm  (front focal point to first vertex)\n";
  o << "f-number (EFL / EPD):          f/" << fmt("%.3f", i.fNumber) << "\n";
  o << "Entrance pupil:                diameter " << fmt("%.4f", i.entrancePupil.diameterMm) << " mm at "
    << fmt("%.4f", i.entrancePupil.positionMm) << " mm from the first vertex\n";
  o << "Exit pupil:                    diameter " << fmt("%.4f", i.exitPupil.diameterMm) << " mm at "
    << fmt("%.4f", i.exitPupil.positionMm) << " mm from the last vertex\n";
  o << "Principal planes:              P at " << fmt("%.4f", i.frontPrincipalMm) << " mm from the first vertex, P' at "
    << fmt("%.4f", i.rearPrincipalMm) << " mm from the last vertex\n";
  o << "Length (first to last vertex): " << fmt("%.4f", i.lengthMm) << " mm\n";
  o << "Total track:                   " << fmt("%.4f", i.totalTrackMm) << " mm  (first vertex to rear focal point)\n";
  o << "(+z toward the image; found by real ray tracing of near-axis rays, extrapolated to zero height)\n";
  if (!i.design.wavelengthsNm.empty()) {
    o << "Design wavelengths:            ";
    for (double nm : i.design.wavelengthsNm) o << fmt("%.2f", nm) << " ";
    o << "nm (primary " << fmt("%.2f", i.design.primaryWavelengthNm) << " nm)\n";
  }
  o << "Surfaces (radius, thickness to the next, medium after, clear aperture; mm):\n";
  for (const std::string& row : i.surfaceRows) o << "  " << row << "\n";
  for (const std::string& w : i.design.warnings) o << "Warning: " << w << "\n";
  return o.str();
}

Json lensInfoJson(const LensInfo& i) {
  Json j;
  j["name"] = i.name;
  j["file"] = i.file;
  j["wavelength_nm"] = i.wavelengthNm;
  j["surfaces"] = i.surfaceCount;
  j["stop_surface"] = i.stopSurface;
  j["stop_diameter_mm"] = i.stopDiameterMm;
  j["dispersive"] = i.dispersive;
  j["efl_mm"] = i.eflMm;
  j["bfl_mm"] = i.bflMm;
  j["ffl_mm"] = i.fflMm;
  j["f_number"] = i.fNumber;
  j["entrance_pupil"] = {{"position_mm", i.entrancePupil.positionMm},
                         {"diameter_mm", i.entrancePupil.diameterMm},
                         {"measured_from", "first vertex, +z toward the image"}};
  j["exit_pupil"] = {{"position_mm", i.exitPupil.positionMm},
                     {"diameter_mm", i.exitPupil.diameterMm},
                     {"measured_from", "last vertex, +z toward the image"}};
  j["front_principal_plane_mm"] = i.frontPrincipalMm;
  j["rear_principal_plane_mm"] = i.rearPrincipalMm;
  j["length_mm"] = i.lengthMm;
  j["total_track_mm"] = i.totalTrackMm;
  j["design_wavelengths_nm"] = i.design.wavelengthsNm;
  j["primary_wavelength_nm"] = i.design.primaryWavelengthNm;
  j["surface_rows"] = i.surfaceRows;
  j["warnings"] = i.design.warnings;
  return j;
}

}  // namespace inim
