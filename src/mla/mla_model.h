#pragma once
// How light crosses the microlens array between the viewer and the panel. The view
// simulation traces backwards: a camera ray reaches the display from the viewer's side and
// an MlaModel carries it to the panel's emitting plane (z = -g in the display frame), where
// the panel says what it emits there. Implementations:
//   IdealLensletMla (view stage): each lenslet a paraxial thin lens of focal length f at
//                                 z = 0: the "pinhole-MLA" comparison model, no refraction.
//   RealMla (mla stage):          the plano-convex lenslets as refracting geometry: n(lambda),
//                                 Fresnel, TIR, rays crossing into neighbouring lenslets.
#include <cstdint>
#include <memory>

#include "core/geometry.h"
#include "core/rng.h"

namespace inim {

struct PanelArrival {
  Point3 p;               // where the ray meets the panel's emitting plane z = -g (display frame, mm)
  Vec3 d;                 // unit direction of travel of the traced ray there (d.z < 0)
  float throughput = 1;   // Fresnel / absorption along the way (MC weights included)
  int lensletK = -1;      // lenslet the ray left through on its way to the panel (column from left)
  int lensletL = -1;      // (row from top); -1 when it missed every lenslet aperture
};
// The light the panel emits toward the viewer travels along -d; its emission angle is the
// angle between -d and +z.

class MlaModel {
 public:
  virtual ~MlaModel() = default;
  // `ray` is in the display frame, starting in front of the MLA (z > its top) and heading
  // toward the panel (d.z < 0). Returns false if the ray does not reach the panel (reflected
  // away, absorbed, TIR out, or blocked). `rng` drives stochastic choices (Fresnel
  // reflect/transmit); it must be the caller's per-sample stream for determinism.
  virtual bool traceToPanel(const Ray& ray, float lambdaNm, Rng& rng, PanelArrival& out) const = 0;
  // True when the result depends on wavelength (then each wavelength needs its own ray).
  virtual bool isDispersive() const = 0;
  // z of the MLA's front-most point (rays must start above it), display frame.
  virtual float frontZ() const = 0;
};

}  // namespace inim
