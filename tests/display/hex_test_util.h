#pragma once
// Forwarding header for tests not yet moved to fixtures.h: hexDisplay with positional
// arguments (K x R EIs of n px of pixelMm, gap, layout, lens pitch, viewing distance, border).
#include "fixtures.h"

namespace hex_test {

using namespace inim;

inline Display hexDisplay(int K = 9, int R = 7, int n = 9, double pixelMm = 0.1, double gap = 3.0,
                          EiLayoutKind layout = EiLayoutKind::Parallel, double lensPitch = 0.0,
                          double viewingDistance = 300.0, int border = 4) {
  return fixtures::hexDisplay({K, R, n, pixelMm, gap, layout, lensPitch, viewingDistance, border});
}

}  // namespace hex_test
