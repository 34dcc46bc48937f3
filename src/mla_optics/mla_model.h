#pragma once
// How light crosses the microlens array between the viewer and the panel. The view
// simulation traces backwards: a camera ray reaches the display from the viewer's side and
// an MlaModel carries it to the panel's emitting plane (z = -g in the display frame), where
// the panel says what it emits there. Implementations:
//   IdealLensletMla (ideal_mla.h): each lenslet a paraxial thin lens of focal length f at
//                                  z = 0: the "pinhole-MLA" comparison model, no refraction.
//   RealMla (real_mla.h):          the plano-convex lenslets as refracting geometry: n(lambda),
//                                  Fresnel, TIR, rays crossing into neighbouring lenslets.
#include <array>
#include <cstdint>
#include <memory>

#include "core/geometry.h"
#include "core/rng.h"

namespace inim {

// How an MLA with refracting interfaces uses the unpolarised Fresnel reflectance R and
// transmittance T = 1 - R at each interface:
//   Stochastic: reflect with probability R, else refract, drawn from the caller's Rng.
//               Throughput is unchanged (unbiased Monte Carlo); reflected rays keep being
//               traced (they may enter a neighbour lenslet).
//   Weighted:   always refract and multiply the throughput by T (deterministic, no Rng; the
//               reflected energy is dropped). Total internal reflection still reflects.
//   Off:        always refract, throughput 1 (an ideal anti-reflection coating).
enum class FresnelMode { Stochastic, Weighted, Off };
const char* fresnelModeName(FresnelMode m);  // "stochastic", "weighted", "off"

struct PanelArrival {
  Point3 p;               // where the ray meets the panel's emitting plane z = -g (display frame, mm)
  Vec3 d;                 // unit direction of travel of the traced ray there (d.z < 0)
  float throughput = 1;   // Fresnel / absorption along the way (MC weights included)
  int lensletK = -1;      // lenslet the ray left through on its way to the panel (column from left)
  int lensletL = -1;      // (row from top); -1 when it missed every lenslet aperture
};
// The light the panel emits toward the viewer travels along -d; its emission angle is the
// angle between -d and +z.

// One lattice cell of an MLA: the points q of the border plane with
// nx[i] (q.x - cx) + ny[i] (q.y - cy) <= h[i] for i < n (a square or a hexagon).
struct LensletCell {
  int k = -1, l = -1;            // lattice indices (may lie outside the indexed lenslets)
  double cx = 0.0, cy = 0.0;     // the lenslet's axis
  double pitch = 0.0;            // lattice pitch (centre to nearest centre)
  int n = 0;
  std::array<double, 6> nx{}, ny{}, h{};
};

class MlaModel {
 public:
  virtual ~MlaModel() = default;
  // `ray` is in the display frame, starting in front of the MLA (z > its top) and heading
  // toward the panel (d.z < 0). Returns false if the ray does not reach the panel (reflected
  // away, absorbed, TIR out, or blocked). `mode` says how Fresnel reflection is handled (a
  // model without interfaces ignores it); `rng` drives the Stochastic choices and must then be
  // the caller's per-sample stream, for determinism (it may be null for the other modes).
  virtual bool traceToPanel(const Ray& ray, float lambdaNm, FresnelMode mode, Rng* rng,
                            PanelArrival& out) const = 0;
  // The same with the model's own Fresnel mode.
  bool traceToPanel(const Ray& ray, float lambdaNm, Rng& rng, PanelArrival& out) const {
    return traceToPanel(ray, lambdaNm, fresnelMode(), &rng, out);
  }
  // The model's own Fresnel mode (RealMlaOptions::fresnel; Off for a model without interfaces).
  virtual FresnelMode fresnelMode() const { return FresnelMode::Off; }
  // True when the result depends on wavelength (then each wavelength needs its own ray).
  virtual bool isDispersive() const = 0;
  // z of the MLA's front-most point (rays must start above it), display frame.
  virtual float frontZ() const = 0;
  // The lattice, for estimators that cut a pixel's footprint along the lenslet borders (the
  // view renderer's Quadrature estimator). A ray that crosses z = frontZ() at (x, y) with slope
  // s = (d.x, d.y) / -d.z passes from one lenslet into the next where the point
  // (x, y) + cellDepth() s crosses a cell border: cellDepth() is the depth below frontZ() of
  // the plane where neighbouring lenslets meet, reduced to air (divided by n when the ray is in
  // glass by then). lensletCell: the cell holding a point of that plane; false when the model
  // has no lattice (the default) or the point is outside it.
  virtual bool lensletCell(double /*x*/, double /*y*/, LensletCell& /*out*/) const { return false; }
  virtual double cellDepth() const { return 0.0; }
  // The same depth for border e of a cell, at the point of that border nearest (x, y): the
  // neighbouring caps meet lower toward the cell's corners, so the depth varies along a border.
  virtual double cellBorderDepth(const LensletCell& /*cell*/, int /*e*/, double /*x*/, double /*y*/) const {
    return cellDepth();
  }
};

}  // namespace inim
