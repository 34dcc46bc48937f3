#pragma once
// The "pinhole-MLA" comparison model (docs/design.md): every lenslet an ideal paraxial thin
// lens of focal length f in the plane z = 0, at the physical lens centres (EiLayout::lensXAt /
// lensYAt, pitch P) of the layout's lattice, each owning its whole cell (fill factor 1):
// squares, or for a hex lattice pointy-top hexagons (rows P sqrt(3)/2 apart, odd rows shifted
// by P/2, as RealMla; a point belongs to the nearest lens centre). No refraction, no dispersion, no crosstalk, no Fresnel.
//
// The ideal-lens mapping uses slopes (tangents): a ray crossing z = 0 at x in the cell of the
// lens centred at c, with slope s = (dx/dz, dy/dz) on the panel side, leaves toward the viewer
// with slope s' = s - (x - c) / f. So rays through one panel-side slope meet at the focal
// point c + f s (z = +f), a panel point at z = -g images to z = L with 1/f = 1/g + 1/L, and a
// panel point at the focal plane (g = f) leaves as a parallel bundle. Traced backwards (the
// view simulation): a ray from the viewer with slope s' at x continues to the panel with
// s = s' + (x - c) / f and lands at x - g s.
//
// Rays that cross z = 0 outside the lenslet array (K P x L P about the lens centres; hex: in
// the cell of a lens outside the K x L indexed ones) are blocked (traceToPanel returns false).
#include <vector>

#include "display/ei_layout.h"
#include "mla_optics/mla_model.h"

namespace inim {

class IdealLensletMla final : public MlaModel {
 public:
  // Lens centres from the layout (physical pitch), focal length f, panel at z = -gapMm.
  IdealLensletMla(const EiLayout& layout, double pitchMm, double focalLengthMm, double gapMm);
  using MlaModel::traceToPanel;
  // No interfaces: `mode` and `rng` are ignored.
  bool traceToPanel(const Ray& ray, float lambdaNm, FresnelMode mode, Rng* rng, PanelArrival& out) const override;
  bool isDispersive() const override { return false; }
  float frontZ() const override { return 0.0f; }
  bool lensletCell(double x, double y, LensletCell& out) const override;  // cells on z = 0

  double focalLengthMm() const { return f_; }
  double gapMm() const { return g_; }
  double pitchMm() const { return pitch_; }
  // The lenslet cell holding a point of the plane z = 0 (false outside the array).
  bool cellAt(double x, double y, int& k, int& l) const;
  // Square: lens column k / row l. Hex: lensX is row 0's (even rows'); use lensXAt.
  double lensX(int k) const { return x0_ + k * pitch_; }
  double lensY(int l) const { return y0_ - l * rowPitch_; }
  double lensXAt(int k, int l) const { return x0_ + (k + (hex_ && (l & 1) ? 0.5 : 0.0)) * pitch_; }
  double lensYAt(int /*k*/, int l) const { return lensY(l); }
  bool isHex() const { return hex_; }

 private:
  int K_ = 0, L_ = 0;
  bool hex_ = false;
  double rowPitch_ = 0.0;  // P (square) or P sqrt(3)/2 (hex)
  double pitch_ = 0.0, f_ = 0.0, g_ = 0.0;
  double x0_ = 0.0, y0_ = 0.0;  // centre of lens (0, 0): left column, top row
};

}  // namespace inim
