#pragma once
// Where every elemental image (EI) and its pinhole lie: the geometry all pinhole ray
// generation, EIA filling and EIA formation share.
//
// Frames (DESIGN.md section 2): display frame in mm, origin at the centre of the EIA,
// x right, y up, z toward the viewer; the pinhole plane is z = 0, the panel at z = -g.
// EIA image: column 0 left, row 0 top, pixel centres at half-integers, so EIA pixel (c, r)
// has its centre at x = (c + 0.5 - W/2) p, y = (H/2 - r - 0.5) p (p = pixel pitch).
// EI (k, l): k counts columns from the left, l rows from the top.
#include <cstdint>
#include <vector>

#include "display/display.h"

namespace inim {

struct EiLayout {
  EiLayoutKind kind = EiLayoutKind::Parallel;
  int eiCols = 0, eiRows = 0;  // K, L
  int eiW = 0, eiH = 0;        // pixels per EI
  int eiaW = 0, eiaH = 0;      // EIA image size (bounding box of all EIs), pixels
  int panelW = 0, panelH = 0;  // panel size, pixels
  int panelCol0 = 0, panelRow0 = 0;  // panel pixel of EIA pixel (0, 0)
  double pixelMm = 0.0;
  double gapMm = 0.0;  // the gap rays are generated for (default: the generation gap)
  std::vector<int> eiCol0;        // [K] first EIA column of EI column k
  std::vector<int> eiRow0;        // [L] first EIA row of EI row l (from the top)
  std::vector<double> pinholeX;   // [K] x of the pinholes of EI column k, mm
  std::vector<double> pinholeY;   // [L] y of the pinholes of EI row l (decreasing with l), mm
  std::vector<double> lensX;      // [K] x of the physical lens centres (pitch P), mm
  std::vector<double> lensY;      // [L] y of the physical lens centres, mm

  int64_t numEis() const { return int64_t(eiCols) * eiRows; }
  int64_t raysPerEi() const { return int64_t(eiW) * eiH; }
  int64_t numRays() const { return numEis() * raysPerEi(); }
  double pixelCentreX(int eiaCol) const { return (eiaCol + 0.5 - 0.5 * eiaW) * pixelMm; }
  double pixelCentreY(int eiaRow) const { return (0.5 * eiaH - eiaRow - 0.5) * pixelMm; }
  double eiCentreX(int k) const { return (eiCol0[size_t(k)] + 0.5 * eiW - 0.5 * eiaW) * pixelMm; }
  double eiCentreY(int l) const { return (0.5 * eiaH - eiRow0[size_t(l)] - 0.5 * eiH) * pixelMm; }
  // The same placement with rays generated at another gap (e.g. the reconstruction gap).
  EiLayout withGap(double g) const {
    EiLayout r = *this;
    r.gapMm = g;
    return r;
  }
};

// Places the EIs of a display (EI positions use the generation gap: for toed-in the EI
// pitch is P (1 + g_gen / D)). Throws InputError naming the display file when the EIA does
// not fit the panel, toed-in EIs would overlap, or the MLA lattice is not square.
EiLayout computeLayout(const Display& d);

}  // namespace inim
