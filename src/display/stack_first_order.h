#pragma once
// First-order (paraxial) optics of one lenslet column of an optical stack: the ray-transfer
// matrix of reduced ray heights and angles (y, n u) from the panel to the air beyond the last
// layer, and what follows from it (docs/design.md, "First-order quantities of a stack").
//
//   refraction at a surface of curvature c between indices n1 and n2:  [[1, 0], [-(n2 - n1) c, 1]]
//   transfer over a thickness t in index n:                            [[1, t / n], [0, 1]]
//
// With M = [[A, B], [C, D]] from the panel (z = 0, in the first layer's medium of index n0) to
// the air beyond the stack (z = Z, index 1), the power is P = -C, the focal length in air
// f = 1 / P, and (z from the panel)
//   rear focal point F' = Z - A / C      rear principal plane H' = Z + (1 - A) / C
//   front principal plane H = n0 (D - 1) / C
// The panel lies H before H in its medium, a reduced gap g = H / n0 (the gap air would give);
// its image, the reference plane, lies L = 1 / (P - 1 / g) beyond H' (g f / (g - f)), and the
// viewing angle is psi = 2 atan(pitch / (2 g)).
#include <optional>
#include <string>
#include <vector>

#include "display/optical_stack.h"

namespace inim {

struct StackFirstOrder {
  double wavelengthNm = 0.0;
  double a = 1, b = 0, c = 0, d = 1;      // the system matrix
  double panelIndex = 1.0;                // n0: the medium at the panel
  bool afocal = false;                    // C = 0: no power
  double focalLengthMm = 0.0;             // f = -1 / C (in air); 0 when afocal
  double frontPrincipalZMm = 0.0;         // H
  double rearPrincipalZMm = 0.0;          // H'
  double frontFocalZMm = 0.0;             // F = n0 D / C
  double rearFocalZMm = 0.0;              // F'
  double reducedGapMm = 0.0;              // g = H / n0: the gap as air would have it
  std::optional<double> referencePlaneMm;  // L beyond H'; nullopt at infinity; < 0 virtual
  double pitchMm = 0.0;                   // the first lens array's (or lattice layer's) pitch
  double viewingAngleDeg = 0.0;           // 2 atan(pitch / (2 g))
  double lensletDepthMm = 0.0;            // Z: the stack's total thickness
};

// Throws InputError (naming the stack's file and the layer) when a material is unknown.
StackFirstOrder stackFirstOrder(const OpticalStack& stack, double wavelengthNm = kLambdaDNm);

// Where a ray from the panel is at each layer's back and front plane, to first order: the
// matrix entries A and B of the system from the panel (z = 0) to that plane, so that a ray
// leaving the panel at height y0 with reduced angle n0 u0 crosses it at A y0 + B n0 u0. A ray's
// height is continuous across a surface, so A and B do not depend on the side. Entry 2 i is
// layer i's back plane, 2 i + 1 its front plane.
struct ParaxialPlane {
  double zMm = 0.0;
  double a = 1.0, b = 0.0;
};
std::vector<ParaxialPlane> stackParaxialPlanes(const OpticalStack& stack, double wavelengthNm = kLambdaDNm);

struct ApertureStop {
  size_t layer = 0;
  double zMm = 0.0;         // the stop's plane, from the panel
  double radiusMm = 0.0;    // its inscribed clear radius
  double a = 1.0, b = 0.0;  // the first-order system from the panel to the stop's plane
  bool front = false;       // at the layer's front plane (else its back plane)
  std::string what;         // "stack.layers[1].front", for reports
};

// The aperture stop of a lenslet column, to first order: of every clear aperture it has (each
// lens surface's, at its vertex plane; each aperture sheet's hole; each barrier cell's opening
// at its two ends), the one that admits the smallest cone from the lenslet's axial panel point,
// i.e. the smallest ratio of its inscribed radius to the height B of the axial marginal ray
// there. nullopt when no layer limits the bundle (a stack of plates and gaps).
std::optional<ApertureStop> findApertureStop(const OpticalStack& stack, double wavelengthNm);

// Text for `inim display info`: the layers and the first-order quantities.
std::string stackText(const OpticalStack& stack, const StackFirstOrder& fo);

}  // namespace inim
