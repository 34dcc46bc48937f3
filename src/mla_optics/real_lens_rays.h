#pragma once
// Real-lens display rays (docs/design.md): for every pixel of every EI, the ray that
// actually leaves the refracting lenslet, traced through a RealMla at one wavelength. EI
// (k, l) is seen through the *physical* lenslet (k, l), at the layout's lensX / lensY (for the
// parallel layout that is the lens-grid geometry: the 1.0 mm lenses, not the EI-centred
// pinholes). Two definitions of "the" ray of a pixel:
//
//   Centroid (default): the pixel centre is a Lambertian point source (intensity ~ cos theta);
//     its light that leaves through its own lenslet's cap is sampled on a fixed N x N grid of
//     directions (stratified over the lenslet's clear aperture as seen from the pixel, padded
//     by 10 %; each sample weighted by cos theta x solid angle x Fresnel transmittance), and
//     the display ray is the power centroid of that exit bundle: direction = normalised mean
//     of the exit directions, origin = mean of the exit rays' crossings of z = 0. Rays that
//     leave through a neighbouring lenslet (crosstalk) belong to other views and are left out.
//     This is the direction the viewer sees the pixel from; it includes the lenslet's
//     aberrations (coma, spherical) and, off the d line, its dispersion.
//   Chief: the single real ray from the pixel centre through the centre of the lenslet's
//     clear aperture (its cap vertex, the aperture stop). Cheap and exact, but both surfaces
//     are perpendicular to the axis at the vertex, so the cap does not bend it: it is the ray
//     through a plane-parallel plate of thickness T.
//
// Paraxially both equal the pinhole ray's direction (the reference plane z = 0 holds the
// lenslets' panel-side nodal points, real_mla.h). The origin is moved back along the ray to
// z = 0, like the pinhole rays' (for a thick lens it is not the lens centre: the ray's line
// passes through the rear nodal point, T (n - 1)/n above it). Fresnel is Weighted (no Rng):
// the output is deterministic and independent of the thread count. A pixel whose bundle
// leaves entirely through other lenslets (or is lost) falls back to the pinhole ray through
// its lens centre; the stats count those.
#include <cstdint>
#include <optional>
#include <string>

#include "core/geometry.h"
#include "display/ei_layout.h"
#include "mla_optics/real_mla.h"
#include "rays/ray_set.h"

namespace inim {

class ProgressBar;

enum class RealLensRayModel { Centroid, Chief };
const char* realLensRayModelName(RealLensRayModel m);
// "centroid" or "chief"; InputError naming `key` otherwise.
RealLensRayModel parseRealLensRayModel(const std::string& text, const std::string& key);

struct RealLensRayOptions {
  double wavelengthNm = kLambdaDNm;
  RealLensRayModel model = RealLensRayModel::Centroid;
  // Centroid: an N x N midpoint grid over the clear aperture. The centroid converges as 1/N^2:
  // N = 8 is within 2e-4 of the converged angle (N = 64), relative, for the prototype.
  int samplesPerAxis = 8;
  // Whole layouts: every lenslet is the same, so a pixel's real-lens ray depends only on its
  // offset from its lens centre. generateRealLensRays computes the rays on a grid of offsets
  // with this step (using the lattice's mirror symmetry) and interpolates bilinearly the small
  // correction to the pinhole ray; 0 computes every pixel directly (10x slower for Chief,
  // 100x for Centroid). The interpolation error is below 1e-6 rad for the prototype
  // (tests/mla). Pixels next to a grid entry whose ray left through another lenslet are
  // traced directly.
  double tableStepMm = 0.02;
};

// The options as a run gives them (absent: not given): none without `on`; InputError naming
// real_lens_ray or wavelength_nm when one is given without it (the pinhole model has no
// refraction), for an unknown model, or for a wavelength outside the settings table's range.
std::optional<RealLensRayOptions> resolveRealLens(bool on, const std::optional<std::string>& model,
                                                  const std::optional<double>& wavelengthNm);

struct RealLensRay {
  Point3d o{0.0};   // on z = 0
  Vec3d d{0.0};     // unit, d.z > 0
  bool real = false;        // false: fell back to the pinhole direction through the lens centre
  int exitK = -1, exitL = -1;  // Chief: the lenslet the ray left through
  int samplesUsed = 0;      // Centroid: bundle rays that left through the pixel's own lenslet
};

struct RealLensRayStats {
  uint64_t rays = 0;
  uint64_t fallback = 0;   // no real ray: pinhole direction through the lens centre used
  uint64_t crosstalk = 0;  // Chief: left through another lenslet than the pixel's own
  double maxDeviationDeg = 0.0;   // largest angle to the pinhole ray through the same lens centre
  double meanDeviationDeg = 0.0;  // mean of that angle
  double seconds = 0.0;
};

// The real-lens ray of one panel point (usually a pixel centre, z = mla.panelZ()) through
// lenslet (k, l) of `mla`.
RealLensRay realLensRay(const RealMla& mla, const Point3d& pixel, int k, int l, const RealLensRayOptions& o);

// The air direction from `pixel` (below the MLA) that reaches the point `q` inside or on the
// MLA in a straight line (curved-toward-panel: q on a cap) or after refracting at the flat face
// (curved-toward-viewer). Unit, d.z > 0.
Vec3d aimAt(const RealMla& mla, const Point3d& pixel, const Point3d& q, double lambdaNm);

// One line for command output: model, wavelength, rays, time, deviation from the pinhole rays
// through the lens centres, fallbacks and crosstalk.
std::string summaryText(const RealLensRayOptions& o, const RealLensRayStats& st);

// All rays of the layout in ray order (rays/ray_set.h), like generatePinholeRays, through the
// real MLA `mla` (whose lenslet (k, l) must be EI (k, l)'s: RealMla::fromDisplay(display, L,
// L.gapMm)). Parallel over EIs; deterministic.
RaySet generateRealLensRays(const EiLayout& L, const RealMla& mla, const RealLensRayOptions& o,
                            RealLensRayStats* stats = nullptr, ProgressBar* progress = nullptr);

}  // namespace inim
