#pragma once
// Small hex-lattice displays built in code (shared by the display, rays, mla, synthesis and
// triads tests).
#include <cmath>

#include "display/display.h"
#include "display/ei_layout.h"

namespace hex_test {

using namespace inim;

// K lenslets per row, R rows, EIs n px flat-to-flat, on the default display's panel primaries
// with a panel that holds the EIA plus `border` px on each side. lensPitch <= 0: n * pixel.
inline Display hexDisplay(int K = 9, int R = 7, int n = 9, double pixelMm = 0.1, double gap = 3.0,
                          EiLayoutKind layout = EiLayoutKind::Parallel, double lensPitch = 0.0,
                          double viewingDistance = 300.0, int border = 4) {
  Display d = loadDisplay(defaultDisplayPath());
  d.file = "small-hex-test-display";
  d.panel.pixelPitchMm = pixelMm;
  d.panel.widthPx = int(std::ceil((K + 1.5) * (n + 2))) + 2 * border;
  d.panel.heightPx = int(std::ceil((R + 1.5) * (n + 2))) + 2 * border;
  d.mla.lattice = Mla::Lattice::Hex;
  d.mla.aperture = Mla::Aperture::Hex;
  d.mla.pitchMm = lensPitch > 0.0 ? lensPitch : n * pixelMm;
  d.mla.apertureMm = d.mla.pitchMm;
  d.generationGapMm = d.reconstructionGapMm = gap;
  d.eiWidthPx = d.eiHeightPx = n;
  d.eiCols = K;
  d.eiRows = R;
  d.layout = layout;
  d.viewingDistanceMm = viewingDistance;
  return d;
}

// Site (EI centre) of EI (k, l) recomputed from first principles: the hex lattice of pitch a
// (rows a sqrt(3)/2 apart, odd rows shifted by a/2) centred on the origin.
inline void expectedSite(int K, int R, double a, int k, int l, double& x, double& y) {
  const double xc = 0.5 * (K - 1) + (R > 1 ? 0.25 : 0.0), yc = 0.5 * (R - 1);
  x = (k - xc + ((l & 1) ? 0.5 : 0.0)) * a;
  y = (yc - l) * a * std::sqrt(3.0) / 2.0;
}

}  // namespace hex_test
