#pragma once
// Where every elemental image (EI) and its pinhole lie: the geometry all pinhole ray
// generation, EIA filling and EIA formation share.
//
// Frames (docs/design.md §2.2): display frame in mm, origin at the centre of the EIA,
// x right, y up, z toward the viewer; the pinhole plane is z = 0, the panel at z = -g.
// EIA image: column 0 left, row 0 top, pixel centres at half-integers, so EIA pixel (c, r)
// has its centre at x = (c + 0.5 - W/2) p, y = (H/2 - r - 0.5) p (p = pixel pitch).
// EI (k, l): k counts columns from the left, l rows from the top.
//
// Curved stacks (display/curved_frame.h; parallel layout only): lensX / lensY are the lenslets'
// arc coordinates on the curved array, and EI (k, l) is centred where lenslet (k, l)'s axis
// meets the panel (a curved panel's arc coordinates); on a hex lattice a pixel belongs to the
// lenslet nearest (in arc coordinates) to the pixel's projection from the centre of curvature,
// and odd rows' EI centres are eiSiteXOdd. The pinholes are the lenses' arc positions; the
// pinhole rays themselves come from mla_optics/stack_chief_rays.h.
//
// Lattices. Square MLAs give a separable layout: rectangular EIs of eiW x eiH pixels, EI
// (k, l) covering EIA columns eiCol0[k] .. + eiW and rows eiRow0[l] .. + eiH, its pinhole at
// (pinholeX[k], pinholeY[l]), its lens at (lensX[k], lensY[l]).
// Hex MLAs (RealMla's convention, mla_optics/real_mla.h): "pointy-top" cells, horizontal rows of
// lenslets, rows P sqrt(3)/2 apart, l counted from the top, ODD rows shifted right by P/2;
// lens (k, l) at (lensX[k] + (l odd ? oddRowLensShiftMm : 0), lensY[l]), pinholes likewise
// with oddRowPinholeShiftMm. Each EI is a hexagon of pixels: EIA pixel (c, r) belongs to the
// EI whose centre ("site": the pinhole for the parallel layout, the toed-in projection
// P (1 + g/D) of the lens centre for toed-in, the EI grid for lens-grid) is nearest to the
// pixel centre (a Voronoi assignment on the pixel grid; exact ties are broken
// deterministically), when that EI exists (pixels nearest a lenslet outside the K x L array belong to no
// EI) and, for toed-in, when the pixel lies inside the EI's hexagon of flat-to-flat width
// ei_px (so toed-in EIs keep their size and leave gaps, as square ones do). ei_px is the EI
// pitch along a row (flat-to-flat width) in pixels; the EI rows are ei_px sqrt(3)/2 pixels
// apart (not a whole number: EI centres are not on pixel centres). ei_count = [lenslets per
// row, rows]. For hex, eiW x eiH is the bounding box of the largest EI, EI (k, l)'s box
// starts at EIA column eiBoxCol0(k, l) and row eiBoxRow0(k, l), and only the box pixels the
// EI owns are rays (RayAddress (i, j) is box-local). Every consumer should use the (k, l)
// accessors below (lensXAt, pinholeXAt, eiBoxCol0, eiAtPixel, eiRayBegin, forEachRayOfEi,
// activeArea), which work for both lattices; the per-column / per-row vectors hold row 0's
// (even rows') values for hex.
#include <cmath>
#include <cstdint>
#include <memory>
#include <vector>

#include "display/display.h"

namespace inim {

// Hex layouts: which EIA pixels are rays, in ray order (shared between copies of a layout).
struct EiPixelMap {
  std::vector<int64_t> eiRayStart;  // [numEis + 1]: first ray of each EI, EIs in ray order
  std::vector<int32_t> rayPixel;    // [numRays]: EIA pixel row * eiaW + col of each ray
  std::vector<int32_t> pixelRay;    // [eiaW * eiaH]: ray of each EIA pixel, -1 outside every EI
};

// An axis-aligned rectangle in the display frame, mm.
struct AreaMm {
  double x0 = 0.0, x1 = 0.0, y0 = 0.0, y1 = 0.0;
  bool contains(double x, double y) const { return x >= x0 && x <= x1 && y >= y0 && y <= y1; }
};

struct EiLayout {
  EiLayoutKind kind = EiLayoutKind::Parallel;
  Mla::Lattice lattice = Mla::Lattice::Square;
  double lensPitchMm = 0.0;  // P (centre to nearest centre, both lattices)
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
  // Hex only (0 / empty for square):
  double oddRowLensShiftMm = 0.0;     // x shift of odd rows' lens centres (P / 2)
  double oddRowPinholeShiftMm = 0.0;  // x shift of odd rows' pinholes
  double oddRowEiShiftMm = 0.0;       // x shift of odd rows' EI centres (sites)
  double eiSitePitchMm = 0.0;         // EI centre pitch along a row (rows pitch * sqrt(3)/2 apart)
  double eiFlatMm = 0.0;              // EI hexagon's flat-to-flat width (ei_px * pixel), mm
  std::vector<double> eiSiteX;        // [K] x of the EI centres (Voronoi sites) of even rows, mm
  std::vector<double> eiSiteY;        // [L] y of the EI centres of row l, mm
  std::vector<int> eiCol0Odd;         // [K] first EIA column of the box of EI (k, odd l)
  std::vector<double> eiSiteXOdd;     // [K] curved stacks: x of the EI centres of odd rows (else empty)
  std::shared_ptr<const EiPixelMap> pixelMap;  // rays of the hex EIs

  bool isHex() const { return lattice == Mla::Lattice::Hex; }
  double rowShift(double shift, int l) const { return (l & 1) ? shift : 0.0; }
  // Lens centre, pinhole and EI centre of EI (k, l), any lattice, mm.
  double lensXAt(int k, int l) const { return lensX[size_t(k)] + rowShift(oddRowLensShiftMm, l); }
  double lensYAt(int /*k*/, int l) const { return lensY[size_t(l)]; }
  double pinholeXAt(int k, int l) const { return pinholeX[size_t(k)] + rowShift(oddRowPinholeShiftMm, l); }
  double pinholeYAt(int /*k*/, int l) const { return pinholeY[size_t(l)]; }
  double eiCentreXAt(int k, int l) const {
    if (!isHex()) return eiCentreX(k);
    return (l & 1) && !eiSiteXOdd.empty() ? eiSiteXOdd[size_t(k)] : eiSiteX[size_t(k)] + rowShift(oddRowEiShiftMm, l);
  }
  double eiCentreYAt(int /*k*/, int l) const { return isHex() ? eiSiteY[size_t(l)] : eiCentreY(l); }
  // First EIA column / row of EI (k, l)'s eiW x eiH box.
  int eiBoxCol0(int k, int l) const { return (isHex() && (l & 1)) ? eiCol0Odd[size_t(k)] : eiCol0[size_t(k)]; }
  int eiBoxRow0(int /*k*/, int l) const { return eiRow0[size_t(l)]; }
  // EIs in ray order: e = k L + (L - 1 - l) (columns from the left, rows from the bottom).
  int64_t eiOrder(int k, int l) const { return int64_t(k) * eiRows + (eiRows - 1 - l); }
  void eiFromOrder(int64_t e, int& k, int& l) const {
    k = int(e / eiRows);
    l = eiRows - 1 - int(e % eiRows);
  }
  // First ray of the e-th EI in ray order (e = numEis(): numRays()).
  int64_t rayBeginOfEiOrder(int64_t e) const {
    return isHex() ? pixelMap->eiRayStart[size_t(e)] : e * raysPerEi();
  }
  // The rays of EI (k, l) are [eiRayBegin, eiRayBegin + eiRayCount) in ray order.
  int64_t eiRayBegin(int k, int l) const {
    return isHex() ? pixelMap->eiRayStart[size_t(eiOrder(k, l))] : eiOrder(k, l) * raysPerEi();
  }
  int64_t eiRayCount(int k, int l) const {
    if (!isHex()) return raysPerEi();
    const size_t e = size_t(eiOrder(k, l));
    return pixelMap->eiRayStart[e + 1] - pixelMap->eiRayStart[e];
  }
  // The EI that owns EIA pixel (col, row); false (k = l = -1) outside every EI.
  bool eiAtPixel(int col, int row, int& k, int& l) const;
  // The lens whose centre is nearest (x, y) (lens coordinates: a curved stack's arc lengths);
  // false when it is not one of the K x L.
  bool nearestLens(double x, double y, int& k, int& l) const;
  // Calls f(ray, col, row, i, j) for every ray of EI (k, l) in ray order: its EIA pixel
  // (col, row) and box-local pixel (i, j) (j from the top).
  template <class F>
  void forEachRayOfEi(int k, int l, F&& f) const {
    const int c0 = eiBoxCol0(k, l), r0 = eiBoxRow0(k, l);
    if (!isHex()) {
      int64_t r = eiRayBegin(k, l);
      for (int i = 0; i < eiW; ++i)
        for (int jb = 0; jb < eiH; ++jb, ++r) f(r, c0 + i, r0 + eiH - 1 - jb, i, eiH - 1 - jb);
      return;
    }
    const int64_t b = eiRayBegin(k, l), e = b + eiRayCount(k, l);
    for (int64_t r = b; r < e; ++r) {
      const int32_t px = pixelMap->rayPixel[size_t(r)];
      const int col = px % eiaW, row = px / eiaW;
      f(r, col, row, col - c0, row - r0);
    }
  }
  // The lenslet array's bounding box (the cells of the K x L indexed lenslets: squares of
  // side P, or pointy-top hexagons of flat-to-flat width P), any lattice.
  AreaMm activeArea() const;
  // Area of one lattice cell, mm^2: P^2 (square) or P^2 sqrt(3)/2 (hex).
  double lensCellAreaMm2() const { return lensPitchMm * lensPitchMm * (isHex() ? std::sqrt(3.0) / 2.0 : 1.0); }
  // Row pitch of the lenses: P (square) or P sqrt(3)/2 (hex).
  double lensRowPitchMm() const { return isHex() ? lensPitchMm * std::sqrt(3.0) / 2.0 : lensPitchMm; }

  int64_t numEis() const { return int64_t(eiCols) * eiRows; }
  // Square: the pixels of every EI. Hex: the pixels of the EI bounding box (EIs own fewer,
  // and not all the same number: use eiRayCount / eiRayBegin).
  int64_t raysPerEi() const { return int64_t(eiW) * eiH; }
  int64_t numRays() const {
    return isHex() ? int64_t(pixelMap->rayPixel.size()) : numEis() * raysPerEi();
  }
  double pixelCentreX(int eiaCol) const { return (eiaCol + 0.5 - 0.5 * eiaW) * pixelMm; }
  double pixelCentreY(int eiaRow) const { return (0.5 * eiaH - eiaRow - 0.5) * pixelMm; }
  // Square: centre of EI column k / row l. Hex: the EI centre of EI (k, even row) / row l
  // (use eiCentreXAt for odd rows).
  double eiCentreX(int k) const {
    return isHex() ? eiSiteX[size_t(k)] : (eiCol0[size_t(k)] + 0.5 * eiW - 0.5 * eiaW) * pixelMm;
  }
  double eiCentreY(int l) const {
    return isHex() ? eiSiteY[size_t(l)] : (0.5 * eiaH - eiRow0[size_t(l)] - 0.5 * eiH) * pixelMm;
  }
  // The same placement with rays generated at another gap (e.g. the reconstruction gap).
  EiLayout withGap(double g) const {
    EiLayout r = *this;
    r.gapMm = g;
    return r;
  }
};

// Places the EIs of a display (EI positions use the generation gap: for toed-in the EI
// pitch is P (1 + g_gen / D)). Throws InputError naming the display file when the EIA does
// not fit the panel or toed-in EIs would overlap (hex: also when ei_px is not one number).
EiLayout computeLayout(const Display& d);

}  // namespace inim
