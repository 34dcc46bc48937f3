#include "synthesis/preview.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <unordered_map>
#include <vector>

#include "core/parallel.h"
#include "core/rng.h"
#include "draw/canvas.h"
#include "field/placement.h"
#include "synthesis/orthoscopic.h"

namespace inim {

namespace {

using draw::Canvas;
using draw::Stroke;

// Every lenslet's central ray and where it first meets the scene.
struct CentralHits {
  int K = 0, R = 0;
  std::vector<OrthoscopicQuery::Query> qs;
  std::vector<Point3d> hit;
  std::vector<int> kind;       // 0 missed, 1 real, 2 virtual, 3 on plane
  std::vector<uint8_t> cross;  // the scene crosses the MLA plane at this lenslet
  size_t idx(int k, int l) const { return size_t(k) * size_t(R) + size_t(l); }
};

// The central ray of every lenslet (from the EI centre on the panel through the pinhole),
// queried in the field; hits within `tol` of z = 0 are on the plane.
// The field's answers to the central rays `rays` (in CentralHits order).
std::vector<LensletFirstHit> queryCentralRays(const Field& field, const std::vector<FieldRay>& rays, uint64_t seed,
                                              const std::function<bool()>& cancelled) {
  const size_t n = rays.size();
  std::vector<SampledWavelengths> lambdas(n);
  for (size_t i = 0; i < n; ++i) lambdas[i] = SampledWavelengths::sampleVisible(Rng::forSample(seed, i, 0).uniform());
  std::vector<FieldSample> out(n);
  const bool spectral = field.encoding() == FieldEncoding::Spectral;
  parallelForRange(int64_t(n), [&](int64_t a, int64_t b) {
    if (cancelled && cancelled()) return;  // the caller throws after the loop
    size_t m = size_t(b - a);
    field.query(std::span(rays).subspan(size_t(a), m),
                spectral ? std::span<const SampledWavelengths>(lambdas).subspan(size_t(a), m)
                         : std::span<const SampledWavelengths>(),
                std::span(out).subspan(size_t(a), m), seed);
  }, nullptr, 256);
  std::vector<LensletFirstHit> hits(n);
  for (size_t i = 0; i < n; ++i) hits[i] = {out[i].depth, out[i].opacity};
  return hits;
}

CentralHits traceCentralRays(const EiLayout& L, const Field& field, const OrthoscopicQuery& oq, double tol,
                             const PreviewSettings& s, PreviewResult& res) {
  CentralHits h;
  h.K = L.eiCols, h.R = L.eiRows;
  const size_t n = size_t(h.K) * size_t(h.R);
  h.qs.resize(n);
  std::vector<FieldRay> rays(n);
  for (int k = 0; k < h.K; ++k)
    for (int l = 0; l < h.R; ++l) {
      const size_t i = h.idx(k, l);
      Point3d pin(L.pinholeXAt(k, l), L.pinholeYAt(k, l), 0.0);
      Vec3d d = pin - Point3d(L.eiCentreXAt(k, l), L.eiCentreYAt(k, l), -L.gapMm);
      d /= std::sqrt(glm::dot(d, d));
      h.qs[i] = oq.make(pin, d, i, 0);
      rays[i] = h.qs[i].ray;
    }
  std::vector<LensletFirstHit> out;
  if (s.knownHits.size() == n) {  // given in level-0 order, l * K + k
    out.resize(n);
    for (int k = 0; k < h.K; ++k)
      for (int l = 0; l < h.R; ++l) out[h.idx(k, l)] = s.knownHits[size_t(l) * size_t(h.K) + size_t(k)];
  } else {
    out = queryCentralRays(field, rays, s.seed, s.cancelled);
  }

  res.lenslets = int(n);
  h.hit.resize(n);
  h.kind.assign(n, 0);
  for (size_t i = 0; i < n; ++i) {
    if (!(out[i].opacity > 0.0f) || !std::isfinite(out[i].depth) || h.qs[i].ray.tFar < 0.0f) {
      ++res.missed;
      continue;
    }
    h.hit[i] = OrthoscopicQuery::hitPoint(h.qs[i], out[i].depth);
    double z = h.hit[i].z;
    h.kind[i] = std::abs(z) <= tol ? 3 : z > 0 ? 1 : 2;
    (h.kind[i] == 1 ? res.real : h.kind[i] == 2 ? res.virtualHits : res.onPlane)++;
  }
  return h;
}

// Where the scene crosses the MLA plane: a hit on the plane, or neighbouring lenslets whose
// hits lie on opposite sides of it on one continuous surface (depth jump < 4 lens pitches).
void markCrossings(CentralHits& h, double tol, PreviewResult& res) {
  h.cross.assign(h.kind.size(), 0);
  for (int k = 0; k < h.K; ++k)
    for (int l = 0; l < h.R; ++l) {
      size_t i = h.idx(k, l);
      if (!h.kind[i]) continue;
      if (h.kind[i] == 3) h.cross[i] = 1;
      for (auto [dk, dl] : {std::pair{1, 0}, std::pair{0, 1}}) {
        if (k + dk >= h.K || l + dl >= h.R) continue;
        size_t j = h.idx(k + dk, l + dl);
        if (h.kind[j] && h.hit[i].z * h.hit[j].z < 0.0 && std::abs(h.hit[i].z - h.hit[j].z) < 8.0 * tol)
          h.cross[i] = h.cross[j] = 1;
      }
    }
  for (uint8_t c : h.cross) res.crossingLenslets += c;
}

// The region drawn (display mm) and its mapping to pixels.
struct ViewBox {
  Point3d lo, hi;
  Point3d blo, bhi;  // the scene's bounds (empty when blo.x > bhi.x)
  double mmPerPx = 1.0;
  int panelAW = 0, panelBW = 0, width = 0, height = 0;
  static constexpr int kMargin = 40, kTop = 60, kBottom = 90;
  double py(double z) const { return kTop + (hi.z - z) / mmPerPx; }
  double pxA(double x) const { return kMargin + (x - lo.x) / mmPerPx; }
  double pxB(double y) const { return 2 * kMargin + panelAW + (y - lo.y) / mmPerPx; }
};

// The EIA, the panel, the VCP, the hits and the scene bounds (the bounds clamped, so a huge
// backdrop does not shrink everything else), with a margin; two panels side by side.
ViewBox viewBox(const EiLayout& L, const Field& field, const Transform& fieldToDisplay, double vcpMm,
                const CentralHits& h, int width) {
  ViewBox v;
  v.blo = Point3d(std::numeric_limits<double>::infinity());  // unknown bounds: none drawn
  v.bhi = -v.blo;
  boundsInFrame(field, fieldToDisplay, v.blo, v.bhi);
  const double g = L.gapMm;
  const double halfW = 0.5 * L.eiaW * L.pixelMm, halfH = 0.5 * L.eiaH * L.pixelMm;
  const double lim = 1.5 * std::max({halfW, halfH, std::abs(vcpMm), 10.0});
  Point3d lo(-halfW, -halfH, std::min({-g, vcpMm, 0.0})), hi(halfW, halfH, std::max({vcpMm, 0.0}));
  for (size_t i = 0; i < h.kind.size(); ++i)
    if (h.kind[i]) lo = glm::min(lo, glm::clamp(h.hit[i], Point3d(-lim), Point3d(lim))),
                   hi = glm::max(hi, glm::clamp(h.hit[i], Point3d(-lim), Point3d(lim)));
  if (v.blo.x <= v.bhi.x) {
    lo = glm::min(lo, glm::clamp(v.blo, Point3d(-lim), Point3d(lim)));
    hi = glm::max(hi, glm::clamp(v.bhi, Point3d(-lim), Point3d(lim)));
  }
  const Vec3d span = hi - lo;
  v.lo = lo - 0.06 * span - Vec3d(1.0);
  v.hi = hi + 0.06 * span + Vec3d(1.0);

  const int W = std::max(400, width);
  v.mmPerPx = (v.hi.x - v.lo.x + v.hi.y - v.lo.y) / double(W - 3 * ViewBox::kMargin);
  v.mmPerPx = std::max(v.mmPerPx, (v.hi.z - v.lo.z) / 1400.0);
  v.panelAW = int(std::ceil((v.hi.x - v.lo.x) / v.mmPerPx));
  v.panelBW = int(std::ceil((v.hi.y - v.lo.y) / v.mmPerPx));
  v.height = int(std::ceil((v.hi.z - v.lo.z) / v.mmPerPx)) + ViewBox::kTop + ViewBox::kBottom;
  v.width = std::max(W, v.panelAW + v.panelBW + 3 * ViewBox::kMargin);
  return v;
}

std::string fmt(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.4g", v);
  return buf;
}

const Vec3 kReal(0.93f, 0.45f, 0.05f), kVirtual(0.12f, 0.35f, 0.85f), kOnPlane(0.1f, 0.62f, 0.2f);
const Vec3 kRay(0.55f, 0.72f, 0.95f), kMla(0.0f), kCross(0.9f, 0.05f, 0.05f), kPanel(0.35f),
    kVcp(0.1f, 0.3f, 0.9f), kBounds(0.6f), kLabel(0.1f);
const draw::Font kFont{15.0};

struct PreviewInput {
  const EiLayout& L;
  const CentralHits& h;
  const ViewBox& v;
  double vcpMm;
};

// The scene's bounds (dashed, lightly filled) and the central rays of the middle row (top
// view) or column (side view): panel -> pinhole (dark) and VCP -> first hit (light).
void drawBoundsAndRays(Canvas& cv, const PreviewInput& in, int view) {
  const EiLayout& L = in.L;
  const CentralHits& h = in.h;
  const ViewBox& v = in.v;
  auto ph = [&](double a) { return view == 0 ? v.pxA(a) : v.pxB(a); };
  const double a0 = view == 0 ? v.lo.x : v.lo.y, a1 = view == 0 ? v.hi.x : v.hi.y;
  cv.strokeRect(ph(a0), v.py(v.hi.z), ph(a1), v.py(v.lo.z), {Vec3(0.85f)});
  if (v.blo.x <= v.bhi.x) {
    double b0 = view == 0 ? v.blo.x : v.blo.y, b1 = view == 0 ? v.bhi.x : v.bhi.y;
    double c0 = std::clamp(b0, a0, a1), c1 = std::clamp(b1, a0, a1);
    double z0 = std::clamp(v.blo.z, v.lo.z, v.hi.z), z1 = std::clamp(v.bhi.z, v.lo.z, v.hi.z);
    cv.fillRect(ph(c0), v.py(z1), ph(c1), v.py(z0), Vec3(0.5f), 0.08);
    cv.strokeRect(ph(c0), v.py(z1), ph(c1), v.py(z0), {kBounds, 1.0, 4.0});
  }
  const int midRow = h.R / 2, midCol = h.K / 2;
  const int count = view == 0 ? h.K : h.R;
  for (int m = 0; m < count; ++m) {
    const size_t i = view == 0 ? h.idx(m, midRow) : h.idx(midCol, m);
    const auto& q = h.qs[i];
    const double pin = view == 0 ? L.pinholeXAt(m, midRow) : L.pinholeYAt(midCol, m);
    const double ec = view == 0 ? L.eiCentreXAt(m, midRow) : L.eiCentreYAt(midCol, m);
    cv.line({ph(ec), v.py(-L.gapMm)}, {ph(pin), v.py(0.0)}, {kPanel, 1.0, 0.0, 0.6});
    Point3d end = h.kind[i] ? h.hit[i]
                            : q.vcpPoint + (q.vcpPoint.z - v.lo.z) / std::max(1e-9, -q.displayDir.z) * q.displayDir;
    double s0 = view == 0 ? q.vcpPoint.x : q.vcpPoint.y, s1 = view == 0 ? end.x : end.y;
    cv.line({ph(s0), v.py(q.vcpPoint.z)}, {ph(s1), v.py(end.z)}, {kRay, 1.0, 0.0, 0.7});
  }
}

// The planes (panel, MLA, VCP), the MLA highlighted where the scene crosses it, the first
// hits of every lenslet's central ray, and the planes' labels.
void drawPlanesAndHits(Canvas& cv, const PreviewInput& in, int view) {
  const EiLayout& L = in.L;
  const CentralHits& h = in.h;
  const ViewBox& v = in.v;
  auto ph = [&](double a) { return view == 0 ? v.pxA(a) : v.pxB(a); };
  const double a0 = view == 0 ? v.lo.x : v.lo.y, a1 = view == 0 ? v.hi.x : v.hi.y;
  const double half = view == 0 ? 0.5 * L.eiaW * L.pixelMm : 0.5 * L.eiaH * L.pixelMm;
  const double g = L.gapMm;
  const double eiPitch = L.isHex() ? L.eiSitePitchMm : double(L.eiW) * L.pixelMm;
  cv.line({ph(-half), v.py(-g)}, {ph(half), v.py(-g)}, {kPanel, 3.0});
  cv.line({ph(-half), v.py(0.0)}, {ph(half), v.py(0.0)}, {kMla, 2.0});
  cv.line({ph(a0), v.py(in.vcpMm)}, {ph(a1), v.py(in.vcpMm)}, {kVcp, 2.0, 8.0});
  const int midRow = h.R / 2, midCol = h.K / 2;
  const int count = view == 0 ? h.K : h.R;
  for (int m = 0; m < count; ++m) {
    bool any = false;
    for (int o = 0; o < (view == 0 ? h.R : h.K) && !any; ++o) any = h.cross[view == 0 ? h.idx(m, o) : h.idx(o, m)];
    if (!any) continue;
    double c = view == 0 ? L.pinholeXAt(m, midRow) : L.pinholeYAt(midCol, m);
    cv.line({ph(c - 0.5 * eiPitch), v.py(0.0)}, {ph(c + 0.5 * eiPitch), v.py(0.0)}, {kCross, 6.0});
  }
  const double r = std::clamp(0.25 * eiPitch / v.mmPerPx, 1.2, 3.0);
  // Thousands of hits share a few hundred quarter-pixel positions in each view: one disc per
  // position and colour, as opaque as the n stacked discs it stands for (1 - 0.2^n), draws the
  // same picture in a fraction of the time.
  auto quarterPx = [](double a) { return uint64_t(std::lround(4.0 * std::clamp(a, -1e6, 1e6))) & 0xFFFFFF; };
  std::unordered_map<uint64_t, size_t> slot;  // position and colour -> index in `marks`
  std::vector<std::pair<size_t, int>> marks;  // first hit there, number of hits there
  for (size_t i = 0; i < h.kind.size(); ++i) {
    if (!h.kind[i]) continue;
    const uint64_t key = (uint64_t(h.kind[i]) << 48) | (quarterPx(ph(view == 0 ? h.hit[i].x : h.hit[i].y)) << 24) |
                         quarterPx(v.py(h.hit[i].z));
    const auto [it, added] = slot.try_emplace(key, marks.size());
    if (added) marks.push_back({i, 0});
    ++marks[it->second].second;
  }
  for (const auto& [i, n] : marks) {
    const Vec3& c = h.kind[i] == 1 ? kReal : h.kind[i] == 2 ? kVirtual : kOnPlane;
    cv.disc({ph(view == 0 ? h.hit[i].x : h.hit[i].y), v.py(h.hit[i].z)}, r, c, 1.0 - std::pow(0.2, n));
  }
  const double lx = std::floor(ph(a0)) + 6;
  cv.text(view == 0 ? "Top view x-z (x right, z up = toward the viewer)" : "Side view y-z (y right, z up)",
          {std::floor(ph(a0)), 14.0}, kFont, kLabel);
  cv.text("VCP z = " + fmt(in.vcpMm), {lx, std::floor(v.py(in.vcpMm)) - 22}, kFont, kVcp);
  cv.text("MLA z = 0", {lx, std::floor(v.py(0.0)) - 22}, kFont, kMla);
  cv.text("panel z = -" + fmt(g), {lx, std::floor(v.py(-g)) + 6}, kFont, kPanel);
}

// The colour legend along the bottom, and a scale bar of a round length below it.
void drawKey(Canvas& cv, const ViewBox& v) {
  double ly = v.height - ViewBox::kBottom + 24, lx = ViewBox::kMargin;
  for (auto [c, t] : {std::pair{kReal, "real (z > 0)"}, std::pair{kVirtual, "virtual (z < 0)"},
                      std::pair{kOnPlane, "on the MLA plane"}, std::pair{kCross, "scene crosses the MLA"},
                      std::pair{kRay, "central query rays"}, std::pair{kBounds, "scene bounds"}}) {
    cv.fillRect(lx, ly, lx + 14, ly + 14, c);
    const draw::TextSize s = cv.text(t, {lx + 20, ly + 7}, kFont, kLabel, {draw::Align::Start, draw::Align::Centre});
    lx += 40 + std::ceil(s.width);
  }
  const double bar = std::pow(10.0, std::floor(std::log10(std::max(1e-6, 200.0 * v.mmPerPx))));
  const double barPx = std::round(bar / v.mmPerPx);
  cv.line({double(ViewBox::kMargin), ly + 40}, {ViewBox::kMargin + barPx, ly + 40}, {kLabel, 3.0});
  cv.text(fmt(bar) + " mm", {ViewBox::kMargin + barPx + 10, ly + 40}, kFont, kLabel,
          {draw::Align::Start, draw::Align::Centre});
}

}  // namespace

PreviewResult renderPlacementPreview(const EiLayout& L, const Field& field, const Transform& fieldToDisplay,
                                     double vcpMm, const PreviewSettings& s) {
  const OrthoscopicQuery oq(fieldToDisplay, vcpMm);
  const int K = L.eiCols;
  const double eiPitch = L.isHex() ? L.eiSitePitchMm : double(L.eiW) * L.pixelMm;
  const double tol = 0.5 * (K > 1 ? std::abs(L.lensX[1] - L.lensX[0]) : eiPitch);
  auto stopIfCancelled = [&] {
    if (s.cancelled && s.cancelled()) throw PreviewCancelled{};
  };
  PreviewResult res;
  CentralHits h = traceCentralRays(L, field, oq, tol, s, res);
  stopIfCancelled();
  markCrossings(h, tol, res);

  const ViewBox v = viewBox(L, field, fieldToDisplay, vcpMm, h, s.width);
  Canvas cv(v.width, v.height);
  const PreviewInput in{L, h, v, vcpMm};
  for (int view = 0; view < 2; ++view) {
    drawBoundsAndRays(cv, in, view);
    stopIfCancelled();
    drawPlanesAndHits(cv, in, view);
    stopIfCancelled();
  }
  drawKey(cv, v);
  res.image = cv.toImage();
  return res;
}

}  // namespace inim
