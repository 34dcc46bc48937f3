#include "core/format.h"
#include "display/ei_layout.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>

#include "core/error.h"
#include "core/size_budget.h"

namespace inim {

namespace {

// The toed-in EIA spans (K - 1) steps of P (1 + g/D) plus an EI. A span no pixel count can hold
// comes from the viewing distance: say so before any pixel count is formed (a distance of 1e-9 mm
// once gave "694574528 x -830233771 px"); an ordinary overflow is the panel-fit check's to name.
void checkToedInSpan(const Display& d, int K, int R, int eiW, int eiH, double stepPx) {
  constexpr double kMaxSpanPx = 1e8;
  const double w = (K - 1) * stepPx + eiW, h = (R - 1) * stepPx + eiH;
  if (w <= kMaxSpanPx && h <= kMaxSpanPx) return;
  throw InputError(d.file, "viewing_distance_mm", formatNumber(*d.viewingDistanceMm),
                   "a distance whose toed-in EI step P (1 + g/D) = " + formatNumber(stepPx) + " px keeps the " +
                       std::to_string(K) + " x " + std::to_string(R) + " EIs on the panel's " +
                       std::to_string(d.panel.widthPx) + " x " + std::to_string(d.panel.heightPx) +
                       " px (they would span " + formatNumber(w, "%.4g") + " x " + formatNumber(h, "%.4g") + " px)");
}

std::string eiCountText(const Display& d) {
  char text[48];
  std::snprintf(text, sizeof text, "[%d, %d]", d.eiCols, d.eiRows);
  return text;
}

// The EIs of a row never overlap (the layouts refuse it), so the EIA is at least K ei_px wide,
// and R ei_px high (square) or R ei_px sqrt(3)/2 (hex rows). Checked before any per-EI array is
// formed: [1000000000, 1] EIs once allocated 8 GB of lens positions before the panel check.
void checkEisCanFit(const Display& d) {
  const double rowPitch = d.mla.lattice == Mla::Lattice::Hex ? std::sqrt(3.0) / 2.0 : 1.0;
  const double minW = double(d.eiCols) * d.eiWidthPx, minH = double(d.eiRows) * d.eiHeightPx * rowPitch;
  if (minW <= d.panel.widthPx && minH <= d.panel.heightPx * (1.0 + 1e-12)) return;
  throw InputError(d.file, "ei_count",
                   eiCountText(d) + " EIs of [" + std::to_string(d.eiWidthPx) + ", " +
                       std::to_string(d.eiHeightPx) + "] px = at least " + formatNumber(minW, "%.6g") + " x " +
                       formatNumber(minH, "%.6g") + " px",
                   "an EIA that fits the panel's " + std::to_string(d.panel.widthPx) + " x " +
                       std::to_string(d.panel.heightPx) + " px");
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

// What every layout takes from the display as it is: the layout kind, the EI counts, the panel,
// the generation gap and the lens pitch.
EiLayout layoutFrame(const Display& d) {
  EiLayout L;
  L.kind = d.layout;
  L.eiCols = d.eiCols;
  L.eiRows = d.eiRows;
  L.panelW = d.panel.widthPx;
  L.panelH = d.panel.heightPx;
  L.pixelMm = d.panel.pixelPitchMm;
  L.gapMm = d.generationGapMm;
  L.lensPitchMm = d.mla.pitchMm;
  return L;
}

// Hex lattice, step 1: lens centres, EI centres (sites) and pinholes, from the lattice's centre
// (odd rows are shifted right by half a pitch).
void placeHexLattice(const Display& d, EiLayout& L) {
  const double P = d.mla.pitchMm, p = L.pixelMm, g = d.generationGapMm;
  const int K = L.eiCols, R = L.eiRows;
  const double s3 = std::sqrt(3.0);
  const double E = d.eiWidthPx * p;  // EI pitch along a row (parallel, lens-grid), mm
  const double xc = 0.5 * (K - 1) + (R > 1 ? 0.25 : 0.0), yc = 0.5 * (R - 1);
  L.lensX.resize(size_t(K));
  L.lensY.resize(size_t(R));
  for (int k = 0; k < K; ++k) L.lensX[size_t(k)] = (k - xc) * P;
  for (int l = 0; l < R; ++l) L.lensY[size_t(l)] = (yc - l) * P * s3 / 2.0;
  L.oddRowLensShiftMm = 0.5 * P;

  double a = E;  // site pitch along a row
  if (d.layout == EiLayoutKind::ToedIn) {
    const double D = *d.viewingDistanceMm, m = 1.0 + g / D;
    a = P * m;
    if (a < E * (1.0 - 1e-12))
      throw InputError(d.file, "viewing_distance_mm", formatNumber(D),
                       "a distance whose toed-in EI pitch P (1 + g/D) = " + formatNumber(a) + " mm = " + formatNumber(a / p) +
                           " px holds hex EIs " + std::to_string(d.eiWidthPx) +
                           " px wide without overlap; reduce ei_px or increase the lens pitch");
  }
  L.eiSitePitchMm = a;
  L.eiFlatMm = E;
  L.eiSiteX.resize(size_t(K));
  L.eiSiteY.resize(size_t(R));
  for (int k = 0; k < K; ++k) L.eiSiteX[size_t(k)] = (k - xc) * a;
  for (int l = 0; l < R; ++l) L.eiSiteY[size_t(l)] = (yc - l) * a * s3 / 2.0;
  L.oddRowEiShiftMm = 0.5 * a;
  if (d.stack && d.stack->curvature) {  // the EIs where the lenslets' axes meet the panel
    double fx, fy;
    L.eiSiteXOdd.resize(size_t(K));
    for (int k = 0; k < K; ++k) {
      axisFootOnPanel(*d.stack, L.lensX[size_t(k)], 0.0, fx, fy), L.eiSiteX[size_t(k)] = fx;
      axisFootOnPanel(*d.stack, L.lensX[size_t(k)] + L.oddRowLensShiftMm, 0.0, fx, fy), L.eiSiteXOdd[size_t(k)] = fx;
    }
    for (int l = 0; l < R; ++l) axisFootOnPanel(*d.stack, 0.0, L.lensY[size_t(l)], fx, fy), L.eiSiteY[size_t(l)] = fy;
  }
  const bool onSites = d.layout == EiLayoutKind::Parallel;
  L.pinholeX = onSites ? L.eiSiteX : L.lensX;
  L.pinholeY = onSites ? L.eiSiteY : L.lensY;
  L.oddRowPinholeShiftMm = onSites ? L.oddRowEiShiftMm : L.oddRowLensShiftMm;
}

// Step 2: the EIA's size (every EI's hexagon, flat-to-flat E and circumradius E / sqrt(3), fits),
// checked against the panel and the memory budget, centred on the panel.
void sizeHexEia(const Display& d, EiLayout& L) {
  const int K = L.eiCols, R = L.eiRows;
  const double a = L.eiSitePitchMm, p = L.pixelMm, s3 = std::sqrt(3.0);
  const double xc = 0.5 * (K - 1) + (R > 1 ? 0.25 : 0.0), yc = 0.5 * (R - 1);
  const double hw = 0.5 * L.eiFlatMm, rc = L.eiFlatMm / s3;
  double maxX = (K - 1 - xc + (R > 1 ? 0.5 : 0.0)) * a + hw, maxY = yc * a * s3 / 2.0 + rc;
  if (!L.eiSiteXOdd.empty())  // curved: the outermost feet
    maxX = std::max({std::fabs(L.eiSiteX.front()), std::fabs(L.eiSiteX.back()), std::fabs(L.eiSiteXOdd.front()),
                     std::fabs(L.eiSiteXOdd.back())}) + hw,
    maxY = std::max(std::fabs(L.eiSiteY.front()), std::fabs(L.eiSiteY.back())) + rc;
  L.eiaW = int(std::ceil(2.0 * maxX / p - 1e-9));
  L.eiaH = int(std::ceil(2.0 * maxY / p - 1e-9));
  if (L.eiaW > L.panelW || L.eiaH > L.panelH)
    throw InputError(d.file, "ei_count",
                     "[" + std::to_string(K) + ", " + std::to_string(R) + "] hex EIs of " +
                         std::to_string(d.eiWidthPx) + " px (" + layoutName(d.layout) + ") = " +
                         std::to_string(L.eiaW) + " x " + std::to_string(L.eiaH) + " px",
                     "an EIA that fits the panel's " + std::to_string(L.panelW) + " x " +
                         std::to_string(L.panelH) + " px");
  L.panelCol0 = (L.panelW - L.eiaW) / 2;
  L.panelRow0 = (L.panelH - L.eiaH) / 2;
  // The pixel map: owner, pixelRay, rayPixel (4 bytes each per EIA pixel) and 4 box bounds per EI.
  checkAllocation(d.file, "ei_count", eiCountText(d) + " hex EIs on " + std::to_string(L.eiaW) + " x " +
                                          std::to_string(L.eiaH) + " px",
                  {{double(L.eiaW) * L.eiaH, 12.0}, {double(K) * R, 16.0}}, "the hex EI pixel map");
}

// Step 3, the Voronoi assignment: each EIA pixel to its nearest site (of the infinite lattice),
// kept when that site is an indexed EI (and, toed-in, when the pixel is inside its hexagon).
// Per pixel: its EI in ray order, -1 for none.
std::vector<int32_t> hexPixelOwners(const EiLayout& L, const OpticalStack* curved) {
  const int W = L.eiaW, H = L.eiaH, K = L.eiCols, R = L.eiRows;
  double a = L.eiSitePitchMm, sx0 = L.eiSiteX[0], sy0 = L.eiSiteY[0];
  const double p = L.pixelMm, s3 = std::sqrt(3.0), hw = 0.5 * L.eiFlatMm;
  // A curved stack: the Voronoi cells of the lenslets' arc lattice, each pixel taken at its
  // projection from the centre of curvature (the reference shell's arc coordinates).
  CurvedFrame array, panel;
  if (curved) array = curved->arrayFrame(), panel = curved->panelFrame(), a = L.lensPitchMm, sx0 = L.lensX[0], sy0 = L.lensY[0];
  const double rowH = a * s3 / 2.0;
  const bool clip = L.kind == EiLayoutKind::ToedIn;
  std::vector<int32_t> owner(size_t(W) * size_t(H), -1);
  for (int r = 0; r < H; ++r) {
    for (int c = 0; c < W; ++c) {
      double x = (c + 0.5 - 0.5 * W) * p, y = (0.5 * H - r - 0.5) * p;
      if (curved) {
        const Vec3d q = array.toFrame(panel.toWorld(x, y, 0.0));
        x = q.x, y = q.y;
      }
      const int l0 = int(std::floor((sy0 - y) / rowH + 0.5));
      double best = std::numeric_limits<double>::infinity(), bdx = 0.0, bdy = 0.0;
      int bk = 0, bl = 0;
      for (int li = l0 - 1; li <= l0 + 1; ++li) {
        const double sh = (li & 1) ? 0.5 * a : 0.0;
        const int ki = int(std::floor((x - sx0 - sh) / a + 0.5));
        const double dx = x - (sx0 + sh + ki * a), dy = y - (sy0 - li * rowH);
        const double d2 = dx * dx + dy * dy;
        if (d2 < best) best = d2, bk = ki, bl = li, bdx = dx, bdy = dy;
      }
      if (bk < 0 || bl < 0 || bk >= K || bl >= R) continue;
      if (clip && std::max(std::abs(bdx), 0.5 * std::abs(bdx) + 0.5 * s3 * std::abs(bdy)) > hw * (1.0 + 1e-12))
        continue;
      owner[size_t(r) * size_t(W) + size_t(c)] = int32_t(L.eiOrder(bk, bl));
    }
  }
  return owner;
}

// Step 4: the EIs' boxes, per EI column and row parity (columns) and per row (rows), and the
// largest box's size (eiW x eiH). An EI without pixels (ei_px tiny) gets its site's pixel.
void placeHexBoxes(EiLayout& L, const std::vector<int32_t>& owner) {
  const int W = L.eiaW, H = L.eiaH, K = L.eiCols, R = L.eiRows;
  const int64_t nE = L.numEis();
  std::vector<int> c0(size_t(nE), INT32_MAX), c1(size_t(nE), -1), r0(size_t(nE), INT32_MAX), r1(size_t(nE), -1);
  for (int r = 0; r < H; ++r)
    for (int c = 0; c < W; ++c) {
      const int32_t e = owner[size_t(r) * size_t(W) + size_t(c)];
      if (e < 0) continue;
      c0[size_t(e)] = std::min(c0[size_t(e)], c), c1[size_t(e)] = std::max(c1[size_t(e)], c);
      r0[size_t(e)] = std::min(r0[size_t(e)], r), r1[size_t(e)] = std::max(r1[size_t(e)], r);
    }
  L.eiCol0.assign(size_t(K), INT32_MAX);
  L.eiCol0Odd.assign(size_t(K), INT32_MAX);
  L.eiRow0.assign(size_t(R), INT32_MAX);
  for (int k = 0; k < K; ++k)
    for (int l = 0; l < R; ++l) {
      const size_t e = size_t(L.eiOrder(k, l));
      if (c1[e] < 0) continue;
      int& col0 = (l & 1) ? L.eiCol0Odd[size_t(k)] : L.eiCol0[size_t(k)];
      col0 = std::min(col0, c0[e]);
      L.eiRow0[size_t(l)] = std::min(L.eiRow0[size_t(l)], r0[e]);
    }
  const double p = L.pixelMm;
  auto fallbackCol = [&](double x) { return std::clamp(int(std::floor(x / p + 0.5 * W)), 0, W - 1); };
  for (int k = 0; k < K; ++k) {
    if (L.eiCol0[size_t(k)] == INT32_MAX) L.eiCol0[size_t(k)] = fallbackCol(L.eiSiteX[size_t(k)]);
    if (L.eiCol0Odd[size_t(k)] == INT32_MAX) L.eiCol0Odd[size_t(k)] = fallbackCol(L.eiCentreXAt(k, 1));
  }
  for (int l = 0; l < R; ++l)
    if (L.eiRow0[size_t(l)] == INT32_MAX)
      L.eiRow0[size_t(l)] = std::clamp(int(std::floor(0.5 * H - L.eiSiteY[size_t(l)] / p)), 0, H - 1);
  L.eiW = L.eiH = 1;
  for (int k = 0; k < K; ++k)
    for (int l = 0; l < R; ++l) {
      const size_t e = size_t(L.eiOrder(k, l));
      if (c1[e] < 0) continue;
      L.eiW = std::max(L.eiW, c1[e] - L.eiBoxCol0(k, l) + 1);
      L.eiH = std::max(L.eiH, r1[e] - L.eiBoxRow0(k, l) + 1);
    }
}

// Step 5, the rays in ray order: EIs (columns from the left, rows from the bottom), then in each
// EI's box columns from the left, rows from the bottom, the pixels the EI owns.
std::shared_ptr<EiPixelMap> hexPixelMap(const EiLayout& L, const std::vector<int32_t>& owner) {
  const int W = L.eiaW, H = L.eiaH;
  const int64_t nE = L.numEis();
  auto map = std::make_shared<EiPixelMap>();
  map->eiRayStart.resize(size_t(nE) + 1);
  map->pixelRay.assign(owner.size(), -1);
  map->rayPixel.reserve(owner.size());
  for (int64_t e = 0; e < nE; ++e) {
    map->eiRayStart[size_t(e)] = int64_t(map->rayPixel.size());
    int k, l;
    L.eiFromOrder(e, k, l);
    const int bc = L.eiBoxCol0(k, l), br = L.eiBoxRow0(k, l);
    for (int i = 0; i < L.eiW; ++i) {
      const int c = bc + i;
      if (c >= W) break;
      for (int jb = 0; jb < L.eiH; ++jb) {
        const int r = br + L.eiH - 1 - jb;
        if (r >= H) continue;
        const size_t px = size_t(r) * size_t(W) + size_t(c);
        if (owner[px] != int32_t(e)) continue;
        map->pixelRay[px] = int32_t(map->rayPixel.size());
        map->rayPixel.push_back(int32_t(px));
      }
    }
  }
  map->eiRayStart[size_t(nE)] = int64_t(map->rayPixel.size());
  map->rayPixel.shrink_to_fit();
  return map;
}

// Hex lattice: hexagonal EIs by a Voronoi assignment of the pixel grid (ei_layout.h).
EiLayout computeHexLayout(const Display& d) {
  EiLayout L = layoutFrame(d);
  L.lattice = Mla::Lattice::Hex;
  if (d.eiWidthPx != d.eiHeightPx)
    throw InputError(d.file, "ei_px", "[" + std::to_string(d.eiWidthPx) + ", " + std::to_string(d.eiHeightPx) + "]",
                     "one number for a hex lattice: the EI pitch along a row (flat-to-flat width) in pixels");
  placeHexLattice(d, L);
  sizeHexEia(d, L);
  const bool curved = d.stack && d.stack->curvature;
  const std::vector<int32_t> owner = hexPixelOwners(L, curved ? &*d.stack : nullptr);
  placeHexBoxes(L, owner);
  L.pixelMap = hexPixelMap(L, owner);
  return L;
}

}  // namespace

bool EiLayout::eiAtPixel(int col, int row, int& k, int& l) const {
  k = l = -1;
  if (col < 0 || row < 0 || col >= eiaW || row >= eiaH) return false;
  if (isHex()) {
    const int32_t r = pixelMap->pixelRay[size_t(row) * size_t(eiaW) + size_t(col)];
    if (r < 0) return false;
    const auto& st = pixelMap->eiRayStart;
    const int64_t e = int64_t(std::upper_bound(st.begin(), st.end(), int64_t(r)) - st.begin()) - 1;
    eiFromOrder(e, k, l);
    return true;
  }
  auto find = [](const std::vector<int>& starts, int n, int x) {
    auto it = std::upper_bound(starts.begin(), starts.end(), x);
    if (it == starts.begin()) return -1;
    int i = int(it - starts.begin()) - 1;
    return x - starts[size_t(i)] < n ? i : -1;
  };
  const int kk = find(eiCol0, eiW, col), ll = find(eiRow0, eiH, row);
  if (kk < 0 || ll < 0) return false;
  k = kk, l = ll;
  return true;
}

bool EiLayout::nearestLens(double x, double y, int& k, int& l) const {
  if (lensX.empty() || lensY.empty() || !std::isfinite(x) || !std::isfinite(y)) return false;
  const double rowH = lensRowPitchMm(), P = lensPitchMm;
  const int l0 = int(std::floor((lensY[0] - y) / rowH + 0.5));
  double best = std::numeric_limits<double>::infinity();
  for (int li = l0 - (isHex() ? 1 : 0); li <= l0 + (isHex() ? 1 : 0); ++li) {
    const double sh = isHex() && (li & 1) ? oddRowLensShiftMm : 0.0;
    const int ki = int(std::floor((x - lensX[0] - sh) / P + 0.5));
    const double dx = x - (lensX[0] + sh + ki * P), dy = y - (lensY[0] - li * rowH), d2 = dx * dx + dy * dy;
    if (d2 < best) best = d2, k = ki, l = li;
  }
  return k >= 0 && l >= 0 && k < eiCols && l < eiRows;
}

AreaMm EiLayout::activeArea() const {
  AreaMm a;
  if (lensX.empty() || lensY.empty()) return a;
  const double P = lensPitchMm;
  if (!isHex()) {
    a.x0 = lensX.front() - 0.5 * P;
    a.x1 = lensX.back() + 0.5 * P;
    a.y0 = lensY.back() - 0.5 * P;
    a.y1 = lensY.front() + 0.5 * P;
    return a;
  }
  const double shift = eiRows > 1 ? oddRowLensShiftMm : 0.0;
  a.x0 = lensX.front() - 0.5 * P;
  a.x1 = lensX.back() + shift + 0.5 * P;
  a.y0 = lensY.back() - P / std::sqrt(3.0);
  a.y1 = lensY.front() + P / std::sqrt(3.0);
  return a;
}

EiLayout computeLayout(const Display& d) {
  checkEisCanFit(d);
  if (d.stack && d.stack->curvature) {
    if (d.layout != EiLayoutKind::Parallel)
      throw InputError(d.file, "layout", "\"" + std::string(layoutName(d.layout)) + "\"",
                       "\"parallel\" for a curved stack: its lenslets' axes place the EIs");
  }
  if (d.mla.lattice == Mla::Lattice::Hex) return computeHexLayout(d);
  EiLayout L = layoutFrame(d);
  L.eiW = d.eiWidthPx;
  L.eiH = d.eiHeightPx;
  const double P = d.mla.pitchMm, p = L.pixelMm, g = d.generationGapMm;
  const int K = L.eiCols, R = L.eiRows;

  L.lensX.resize(size_t(K));
  L.lensY.resize(size_t(R));
  for (int k = 0; k < K; ++k) L.lensX[size_t(k)] = (k - 0.5 * (K - 1)) * P;
  for (int l = 0; l < R; ++l) L.lensY[size_t(l)] = (0.5 * (R - 1) - l) * P;

  Axis ax, ay;
  const bool curved = d.stack && d.stack->curvature;
  if (curved) {
    // Each EI centred where its lenslet's axis meets the panel (ei_layout.h): the curvature aims
    // the lenslets; EIs that would overlap are refused.
    double fx, fy;
    ax = placeAxis(K, L.eiW, [&](int k) { return axisFootOnPanel(*d.stack, L.lensX[size_t(k)], 0.0, fx, fy), fx / p; });
    ay = placeAxis(R, L.eiH, [&](int l) { return axisFootOnPanel(*d.stack, 0.0, L.lensY[size_t(l)], fx, fy), -fy / p; });
    if (ax.minStep < L.eiW || ay.minStep < L.eiH)
      throw InputError(d.file, "stack.curvature.radius_mm", formatNumber(d.stack->curvature->radiusMm),
                       formatText("a curvature whose lenslet axes meet the panel at least an EI apart (%d x %d px; "
                                  "the nearest are %d px apart)",
                                  L.eiW, L.eiH, std::min(ax.minStep, ay.minStep)));
  } else if (d.layout == EiLayoutKind::ToedIn) {
    double D = *d.viewingDistanceMm;
    double m = 1.0 + g / D;  // projection of the lens centre from (0, 0, D) onto z = -g
    checkToedInSpan(d, K, R, L.eiW, L.eiH, P * m / p);
    ax = placeAxis(K, L.eiW, [&](int k) { return L.lensX[size_t(k)] * m / p; });
    ay = placeAxis(R, L.eiH, [&](int l) { return -L.lensY[size_t(l)] * m / p; });
    if (ax.minStep < L.eiW || ay.minStep < L.eiH) {
      bool xs = ax.minStep < L.eiW;
      throw InputError(
          d.file, "viewing_distance_mm", formatNumber(D),
          "a distance whose toed-in EI pitch P (1 + g/D) = " + formatNumber(P * m) + " mm = " +
              formatNumber(P * m / p) + " px holds EIs of " + std::to_string(xs ? L.eiW : L.eiH) +
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
  const bool onEis = d.layout == EiLayoutKind::Parallel && !curved;
  for (int k = 0; k < K; ++k) L.pinholeX[size_t(k)] = onEis ? L.eiCentreX(k) : L.lensX[size_t(k)];
  for (int l = 0; l < R; ++l) L.pinholeY[size_t(l)] = onEis ? L.eiCentreY(l) : L.lensY[size_t(l)];
  return L;
}

}  // namespace inim
