#include "display/ei_layout.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/error.h"

namespace inim {

namespace {

std::string num(double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

// Places `count` EIs of `n` pixels along one axis. `centrePx(k)` is the ideal EI centre in
// pixels from the origin (the EIA centre), increasing with k and symmetric about 0. EI start
// positions are snapped to the pixel lattice that keeps the EIA centred on the origin
// (pixel boundaries at integers when count*n is even, at half-integers when odd); the second
// half mirrors the first, so the placement is exactly symmetric.
struct Axis {
  std::vector<int> start;  // first EIA pixel of each EI
  int size = 0;            // EIA extent in pixels
  int minStep = 0;         // smallest EI start-to-start step, pixels
};

template <class F>
Axis placeAxis(int count, int n, F centrePx) {
  double phi = ((int64_t(count) * n) % 2) ? 0.5 : 0.0;
  std::vector<double> s(static_cast<size_t>(count));
  for (int k = 0; k < count / 2; ++k) s[size_t(k)] = std::round(centrePx(k) - 0.5 * n - phi) + phi;
  if (count % 2) s[size_t(count / 2)] = -0.5 * n;
  for (int k = (count + 1) / 2; k < count; ++k) s[size_t(k)] = -s[size_t(count - 1 - k)] - n;
  Axis a;
  a.size = int(std::lround(-2.0 * s[0]));
  a.start.resize(size_t(count));
  a.minStep = n;
  for (int k = 0; k < count; ++k) {
    a.start[size_t(k)] = int(std::lround(s[size_t(k)] - s[0]));
    if (k > 0) a.minStep = std::min(a.minStep, a.start[size_t(k)] - a.start[size_t(k - 1)]);
  }
  return a;
}

}  // namespace

EiLayout computeLayout(const Display& d) {
  if (d.mla.lattice != Mla::Lattice::Square)
    throw InputError(d.file, "mla.lattice", "\"hex\"",
                     "a square lattice (hex MLAs are parsed, but EI layouts for them are not "
                     "implemented yet)");
  EiLayout L;
  L.kind = d.layout;
  L.eiCols = d.eiCols;
  L.eiRows = d.eiRows;
  L.eiW = d.eiWidthPx;
  L.eiH = d.eiHeightPx;
  L.panelW = d.panel.widthPx;
  L.panelH = d.panel.heightPx;
  L.pixelMm = d.panel.pixelPitchMm;
  L.gapMm = d.generationGapMm;
  const double P = d.mla.pitchMm, p = L.pixelMm, g = d.generationGapMm;
  const int K = L.eiCols, R = L.eiRows;

  L.lensX.resize(size_t(K));
  L.lensY.resize(size_t(R));
  for (int k = 0; k < K; ++k) L.lensX[size_t(k)] = (k - 0.5 * (K - 1)) * P;
  for (int l = 0; l < R; ++l) L.lensY[size_t(l)] = (0.5 * (R - 1) - l) * P;

  Axis ax, ay;
  if (d.layout == EiLayoutKind::ToedIn) {
    double D = *d.viewingDistanceMm;
    double m = 1.0 + g / D;  // projection of the lens centre from (0, 0, D) onto z = -g
    ax = placeAxis(K, L.eiW, [&](int k) { return L.lensX[size_t(k)] * m / p; });
    ay = placeAxis(R, L.eiH, [&](int l) { return -L.lensY[size_t(l)] * m / p; });
    if (ax.minStep < L.eiW || ay.minStep < L.eiH) {
      bool xs = ax.minStep < L.eiW;
      throw InputError(
          d.file, "viewing_distance_mm", num(D),
          "a distance whose toed-in EI pitch P (1 + g/D) = " + num(P * m) + " mm = " +
              num(P * m / p) + " px holds EIs of " + std::to_string(xs ? L.eiW : L.eiH) +
              " px without overlap (rounded EI step " + std::to_string(xs ? ax.minStep : ay.minStep) +
              " px); reduce ei_px or increase the lens pitch");
    }
  } else {
    // Contiguous EIs on the EI grid (pitch n pixels), centred on the origin.
    ax = placeAxis(K, L.eiW, [&](int k) { return (k - 0.5 * (K - 1)) * L.eiW; });
    ay = placeAxis(R, L.eiH, [&](int l) { return (l - 0.5 * (R - 1)) * L.eiH; });
  }
  L.eiCol0 = ax.start;
  L.eiRow0 = ay.start;
  L.eiaW = ax.size;
  L.eiaH = ay.size;
  if (L.eiaW > L.panelW || L.eiaH > L.panelH)
    throw InputError(d.file, "ei_count",
                     "[" + std::to_string(K) + ", " + std::to_string(R) + "] EIs of [" +
                         std::to_string(L.eiW) + ", " + std::to_string(L.eiH) + "] px (" +
                         layoutName(d.layout) + ") = " + std::to_string(L.eiaW) + " x " +
                         std::to_string(L.eiaH) + " px",
                     "an EIA that fits the panel's " + std::to_string(L.panelW) + " x " +
                         std::to_string(L.panelH) + " px");
  L.panelCol0 = (L.panelW - L.eiaW) / 2;
  L.panelRow0 = (L.panelH - L.eiaH) / 2;

  L.pinholeX.resize(size_t(K));
  L.pinholeY.resize(size_t(R));
  for (int k = 0; k < K; ++k)
    L.pinholeX[size_t(k)] = d.layout == EiLayoutKind::Parallel ? L.eiCentreX(k) : L.lensX[size_t(k)];
  for (int l = 0; l < R; ++l)
    L.pinholeY[size_t(l)] = d.layout == EiLayoutKind::Parallel ? L.eiCentreY(l) : L.lensY[size_t(l)];
  return L;
}

}  // namespace inim
