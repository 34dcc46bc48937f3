#pragma once
// Shared helpers for the MLA tests: small lens arrays and displays built in code.
#include <cmath>
#include <memory>

#include "fixtures.h"
#include "display/display.h"
#include "display/ei_layout.h"
#include "mla_optics/real_mla.h"
#include "core/rng.h"
#include "spectral/dispersion.h"

namespace mla_test {

using namespace inim;

constexpr auto kViewer = Mla::Orientation::CurvedTowardViewer;
constexpr auto kPanel = Mla::Orientation::CurvedTowardPanel;

struct Spec {
  Mla::Orientation orientation = kViewer;
  Mla::Lattice lattice = Mla::Lattice::Square;
  Mla::Aperture aperture = Mla::Aperture::Square;
  double pitch = 1.0, aperture_mm = 1.0, radius = 1.62, conic = 0.0, thickness = 1.5, gap = 3.3;
  int cols = 11, rows = 11;
  RealMlaOptions options{};
};

inline IorPtr pmma() { return MaterialCatalog::standard().dielectric("PMMA"); }

// An array centred on the origin: lenslet (cols/2, rows/2) on the axis (odd counts).
inline std::unique_ptr<RealMla> makeMla(const Spec& s) {
  RealMlaGeometry g;
  g.lattice = s.lattice;
  g.aperture = s.aperture;
  g.orientation = s.orientation;
  g.pitchMm = s.pitch;
  g.apertureMm = s.aperture_mm;
  g.radiusMm = s.radius;
  g.conic = s.conic;
  g.thicknessMm = s.thickness;
  g.cols = s.cols;
  g.rows = s.rows;
  const double rowH = s.lattice == Mla::Lattice::Hex ? s.pitch * std::sqrt(3.0) / 2.0 : s.pitch;
  g.originXMm = -(s.cols / 2) * s.pitch - (s.lattice == Mla::Lattice::Hex && ((s.rows / 2) & 1) ? 0.5 * s.pitch : 0.0);
  g.originYMm = (s.rows / 2) * rowH;
  g.gapMm = s.gap;
  return std::make_unique<RealMla>(g, pmma(), s.options, "(test MLA)");
}

// A small square-lattice display on the default display's panel and MLA material: K x R EIs
// of n x n pixels of `pixelMm`, lens pitch P, focal length f, gap g, the panel `border` px
// larger than the EIA on each side.
inline Display smallDisplay(int K, int R, int n, double pixelMm, double P, double f, double g, int border = 4) {
  return fixtures::lensletTestDisplay({K, R, n, pixelMm, P, f, g, border});
}

inline Spec spec(Mla::Orientation o) {
  Spec s;
  s.orientation = o;
  return s;
}

inline bool finite(const Vec3d& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }
inline double norm(const Vec3d& v) { return std::sqrt(v.x * v.x + v.y * v.y + v.z * v.z); }
inline Vec3d cross(const Vec3d& a, const Vec3d& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline double dot(const Vec3d& a, const Vec3d& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline Vec3d unit(const Vec3d& v) { return v / norm(v); }
// A direction toward +z within maxDeg of it (theta = maxDeg sqrt(u1), phi = 2 pi u2): the
// stack tests' random rays.
inline Vec3d coneDirection(Rng& rng, double maxDeg) {
  const double theta = maxDeg * M_PI / 180.0 * std::sqrt(rng.uniformDouble()), phi = 2.0 * M_PI * rng.uniformDouble();
  return {std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)};
}

// Angle between unit vectors, accurate near 0.
inline double angle(const Vec3d& a, const Vec3d& b) { return std::atan2(norm(cross(a, b)), dot(a, b)); }

}  // namespace mla_test
