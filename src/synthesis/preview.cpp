#include "synthesis/preview.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "core/parallel.h"
#include "core/rng.h"
#include "synthesis/orthoscopic.h"

namespace inim {

namespace {

// A 5x7 bitmap font (rows top to bottom, bit 4 = leftmost column).
struct Glyph {
  char c;
  uint8_t rows[7];
};
constexpr Glyph kFont[] = {
    {'A', {14, 17, 17, 31, 17, 17, 17}}, {'B', {30, 17, 17, 30, 17, 17, 30}}, {'C', {14, 17, 16, 16, 16, 17, 14}},
    {'D', {30, 17, 17, 17, 17, 17, 30}}, {'E', {31, 16, 16, 30, 16, 16, 31}}, {'F', {31, 16, 16, 30, 16, 16, 16}},
    {'G', {14, 17, 16, 23, 17, 17, 15}}, {'H', {17, 17, 17, 31, 17, 17, 17}}, {'I', {14, 4, 4, 4, 4, 4, 14}},
    {'J', {7, 2, 2, 2, 2, 18, 12}},      {'K', {17, 18, 20, 24, 20, 18, 17}}, {'L', {16, 16, 16, 16, 16, 16, 31}},
    {'M', {17, 27, 21, 21, 17, 17, 17}}, {'N', {17, 17, 25, 21, 19, 17, 17}}, {'O', {14, 17, 17, 17, 17, 17, 14}},
    {'P', {30, 17, 17, 30, 16, 16, 16}}, {'Q', {14, 17, 17, 17, 21, 18, 13}}, {'R', {30, 17, 17, 30, 20, 18, 17}},
    {'S', {15, 16, 16, 14, 1, 1, 30}},   {'T', {31, 4, 4, 4, 4, 4, 4}},       {'U', {17, 17, 17, 17, 17, 17, 14}},
    {'V', {17, 17, 17, 17, 17, 10, 4}},  {'W', {17, 17, 17, 21, 21, 21, 10}}, {'X', {17, 17, 10, 4, 10, 17, 17}},
    {'Y', {17, 17, 10, 4, 4, 4, 4}},     {'Z', {31, 1, 2, 4, 8, 16, 31}},     {'0', {14, 17, 19, 21, 25, 17, 14}},
    {'1', {4, 12, 4, 4, 4, 4, 14}},      {'2', {14, 17, 1, 2, 4, 8, 31}},     {'3', {31, 2, 4, 2, 1, 17, 14}},
    {'4', {2, 6, 10, 18, 31, 2, 2}},     {'5', {31, 16, 30, 1, 1, 17, 14}},   {'6', {6, 8, 16, 30, 17, 17, 14}},
    {'7', {31, 1, 2, 4, 8, 8, 8}},       {'8', {14, 17, 17, 14, 17, 17, 14}}, {'9', {14, 17, 17, 15, 1, 2, 12}},
    {'-', {0, 0, 0, 31, 0, 0, 0}},       {'=', {0, 0, 31, 0, 31, 0, 0}},      {'.', {0, 0, 0, 0, 0, 12, 12}},
    {'(', {2, 4, 8, 8, 8, 4, 2}},        {')', {8, 4, 2, 2, 2, 4, 8}},        {':', {0, 12, 12, 0, 12, 12, 0}},
    {'/', {0, 1, 2, 4, 8, 16, 0}},       {'+', {0, 4, 4, 31, 4, 4, 0}},       {',', {0, 0, 0, 0, 12, 4, 8}},
    {'<', {2, 4, 8, 16, 8, 4, 2}},       {'>', {8, 4, 2, 1, 2, 4, 8}},        {' ', {0, 0, 0, 0, 0, 0, 0}},
};

const Glyph* glyph(char c) {
  if (c >= 'a' && c <= 'z') c = char(c - 'a' + 'A');
  for (const Glyph& g : kFont)
    if (g.c == c) return &g;
  return nullptr;
}

class Canvas {
 public:
  explicit Canvas(int w, int h) : img(w, h, {"R", "G", "B"}) { std::fill(img.data.begin(), img.data.end(), 1.0f); }
  void blend(int x, int y, const Vec3& c, float a = 1.0f) {
    if (x < 0 || y < 0 || x >= img.width || y >= img.height) return;
    for (int k = 0; k < 3; ++k) img.at(x, y, k) = img.at(x, y, k) * (1.0f - a) + c[k] * a;
  }
  void dot(double x, double y, double r, const Vec3& c, float a = 1.0f) {
    int x0 = int(std::floor(x - r)), x1 = int(std::ceil(x + r)), y0 = int(std::floor(y - r)), y1 = int(std::ceil(y + r));
    for (int j = y0; j <= y1; ++j)
      for (int i = x0; i <= x1; ++i) {
        double dx = i + 0.5 - x, dy = j + 0.5 - y;
        if (dx * dx + dy * dy <= r * r) blend(i, j, c, a);
      }
  }
  // A line of `width` px; dashed when dash > 0 (px on, px off).
  void line(double x0, double y0, double x1, double y1, const Vec3& c, double width = 1.0, float a = 1.0f,
            double dash = 0.0) {
    if (!std::isfinite(x0) || !std::isfinite(y0) || !std::isfinite(x1) || !std::isfinite(y1)) return;
    // Clip to a generous box so that huge coordinates do not loop forever.
    const double lim = 4.0 * (img.width + img.height);
    if (std::max({std::abs(x0), std::abs(y0), std::abs(x1), std::abs(y1)}) > lim) {
      if (!clip(x0, y0, x1, y1, -2.0, -2.0, img.width + 2.0, img.height + 2.0)) return;
    }
    double len = std::hypot(x1 - x0, y1 - y0);
    int n = std::max(1, int(std::ceil(len * 2.0)));
    double r = 0.5 * width;
    int lastX = INT32_MIN, lastY = INT32_MIN;
    for (int i = 0; i <= n; ++i) {
      double t = double(i) / n;
      if (dash > 0.0 && std::fmod(t * len, 2.0 * dash) > dash) continue;
      double x = x0 + t * (x1 - x0), y = y0 + t * (y1 - y0);
      if (width <= 1.0) {
        int xi = int(std::floor(x)), yi = int(std::floor(y));
        if (xi == lastX && yi == lastY) continue;
        lastX = xi, lastY = yi;
        blend(xi, yi, c, a);
      } else {
        for (int j = int(std::floor(y - r)); j < int(std::ceil(y + r)); ++j)
          for (int k = int(std::floor(x - r)); k < int(std::ceil(x + r)); ++k) set(k, j, c);
      }
    }
  }
  void rect(double x0, double y0, double x1, double y1, const Vec3& c, double width = 1.0, double dash = 0.0) {
    line(x0, y0, x1, y0, c, width, 1.0f, dash);
    line(x1, y0, x1, y1, c, width, 1.0f, dash);
    line(x1, y1, x0, y1, c, width, 1.0f, dash);
    line(x0, y1, x0, y0, c, width, 1.0f, dash);
  }
  void fill(double x0, double y0, double x1, double y1, const Vec3& c, float a) {
    for (int j = int(std::floor(std::min(y0, y1))); j < int(std::ceil(std::max(y0, y1))); ++j)
      for (int i = int(std::floor(std::min(x0, x1))); i < int(std::ceil(std::max(x0, x1))); ++i) blend(i, j, c, a);
  }
  // Text with its top-left corner at (x, y), glyphs scaled by `s`.
  void text(int x, int y, const std::string& t, const Vec3& c, int s = 2) {
    for (char ch : t) {
      if (const Glyph* g = glyph(ch))
        for (int r = 0; r < 7; ++r)
          for (int col = 0; col < 5; ++col)
            if (g->rows[r] & (16 >> col))
              for (int a = 0; a < s; ++a)
                for (int b = 0; b < s; ++b) set(x + col * s + b, y + r * s + a, c);
      x += 6 * s;
    }
  }
  static int textWidth(const std::string& t, int s = 2) { return int(t.size()) * 6 * s; }
  Image img;

 private:
  void set(int x, int y, const Vec3& c) { blend(x, y, c, 1.0f); }
  // Liang-Barsky.
  static bool clip(double& x0, double& y0, double& x1, double& y1, double xmin, double ymin, double xmax,
                   double ymax) {
    double t0 = 0.0, t1 = 1.0, dx = x1 - x0, dy = y1 - y0;
    const double p[4] = {-dx, dx, -dy, dy}, q[4] = {x0 - xmin, xmax - x0, y0 - ymin, ymax - y0};
    for (int i = 0; i < 4; ++i) {
      if (p[i] == 0.0) {
        if (q[i] < 0.0) return false;
        continue;
      }
      double t = q[i] / p[i];
      if (p[i] < 0.0) t0 = std::max(t0, t);
      else t1 = std::min(t1, t);
      if (t0 > t1) return false;
    }
    double ax = x0 + t0 * dx, ay = y0 + t0 * dy;
    x1 = x0 + t1 * dx, y1 = y0 + t1 * dy;
    x0 = ax, y0 = ay;
    return true;
  }
};

std::string fmt(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.4g", v);
  return buf;
}

const Vec3 kReal(0.93f, 0.45f, 0.05f), kVirtual(0.12f, 0.35f, 0.85f), kOnPlane(0.1f, 0.62f, 0.2f);
const Vec3 kRay(0.55f, 0.72f, 0.95f), kMla(0.0f), kCross(0.9f, 0.05f, 0.05f), kPanel(0.35f),
    kVcp(0.1f, 0.3f, 0.9f), kBounds(0.6f), kLabel(0.1f);

}  // namespace

PreviewResult renderPlacementPreview(const EiLayout& L, const Field& field, const Transform& fieldToDisplay,
                                     double vcpMm, const PreviewSettings& s) {
  const OrthoscopicQuery oq(fieldToDisplay, vcpMm);
  const int K = L.eiCols, R = L.eiRows;
  const double g = L.gapMm;
  const double eiPitch = L.isHex() ? L.eiSitePitchMm : double(L.eiW) * L.pixelMm;
  const double tol = 0.5 * (K > 1 ? std::abs(L.lensX[1] - L.lensX[0]) : eiPitch);

  // The central ray of every lenslet: from the EI centre on the panel through the pinhole.
  const size_t n = size_t(K) * size_t(R);
  std::vector<OrthoscopicQuery::Query> qs(n);
  std::vector<FieldRay> rays(n);
  std::vector<SampledWavelengths> lambdas(n);
  std::vector<FieldSample> out(n);
  for (int k = 0; k < K; ++k)
    for (int l = 0; l < R; ++l) {
      size_t i = size_t(k) * size_t(R) + size_t(l);
      Point3d pin(L.pinholeXAt(k, l), L.pinholeYAt(k, l), 0.0);
      Vec3d d = pin - Point3d(L.eiCentreXAt(k, l), L.eiCentreYAt(k, l), -g);
      d /= std::sqrt(glm::dot(d, d));
      qs[i] = oq.make(pin, d, i, 0);
      rays[i] = qs[i].ray;
      lambdas[i] = SampledWavelengths::sampleVisible(Rng::forSample(s.seed, i, 0).uniform());
    }
  const bool spectral = field.encoding() == FieldEncoding::Spectral;
  parallelForRange(int64_t(n), [&](int64_t a, int64_t b) {
    size_t m = size_t(b - a);
    field.query(std::span(rays).subspan(size_t(a), m),
                spectral ? std::span<const SampledWavelengths>(lambdas).subspan(size_t(a), m)
                         : std::span<const SampledWavelengths>(),
                std::span(out).subspan(size_t(a), m), s.seed);
  }, nullptr, 256);

  PreviewResult res;
  res.lenslets = int(n);
  std::vector<Point3d> hit(n);
  std::vector<int> kind(n, 0);  // 0 missed, 1 real, 2 virtual, 3 on plane
  for (size_t i = 0; i < n; ++i) {
    if (!(out[i].opacity > 0.0f) || !std::isfinite(out[i].depth) || qs[i].ray.tFar < 0.0f) {
      ++res.missed;
      continue;
    }
    hit[i] = OrthoscopicQuery::hitPoint(qs[i], out[i].depth);
    double z = hit[i].z;
    kind[i] = std::abs(z) <= tol ? 3 : z > 0 ? 1 : 2;
    (kind[i] == 1 ? res.real : kind[i] == 2 ? res.virtualHits : res.onPlane)++;
  }
  // Where the scene crosses the MLA plane: a hit on the plane, or neighbouring lenslets whose
  // hits lie on opposite sides of it on one continuous surface (depth jump < 4 lens pitches).
  std::vector<uint8_t> cross(n, 0);
  auto idx = [R](int k, int l) { return size_t(k) * size_t(R) + size_t(l); };
  for (int k = 0; k < K; ++k)
    for (int l = 0; l < R; ++l) {
      size_t i = idx(k, l);
      if (!kind[i]) continue;
      if (kind[i] == 3) cross[i] = 1;
      for (auto [dk, dl] : {std::pair{1, 0}, std::pair{0, 1}}) {
        if (k + dk >= K || l + dl >= R) continue;
        size_t j = idx(k + dk, l + dl);
        if (kind[j] && hit[i].z * hit[j].z < 0.0 && std::abs(hit[i].z - hit[j].z) < 8.0 * tol)
          cross[i] = cross[j] = 1;
      }
    }
  for (uint8_t c : cross) res.crossingLenslets += c;

  // View box (display mm): the EIA, the panel, the VCP, the hits and the scene bounds (the
  // bounds clamped, so a huge backdrop does not shrink everything else).
  Point3 flo, fhi;
  field.bounds(flo, fhi);
  Point3d blo(std::numeric_limits<double>::infinity()), bhi(-std::numeric_limits<double>::infinity());
  for (int c = 0; c < 8; ++c) {
    Point3d p = fieldToDisplay.point(Point3d((c & 1) ? fhi.x : flo.x, (c & 2) ? fhi.y : flo.y, (c & 4) ? fhi.z : flo.z));
    blo = glm::min(blo, p);
    bhi = glm::max(bhi, p);
  }
  const double halfW = 0.5 * L.eiaW * L.pixelMm, halfH = 0.5 * L.eiaH * L.pixelMm;
  const double lim = 1.5 * std::max({halfW, halfH, std::abs(vcpMm), 10.0});
  Point3d lo(-halfW, -halfH, std::min({-g, vcpMm, 0.0})), hi(halfW, halfH, std::max({vcpMm, 0.0}));
  for (size_t i = 0; i < n; ++i)
    if (kind[i]) lo = glm::min(lo, glm::clamp(hit[i], Point3d(-lim), Point3d(lim))),
                 hi = glm::max(hi, glm::clamp(hit[i], Point3d(-lim), Point3d(lim)));
  if (blo.x <= bhi.x) {
    lo = glm::min(lo, glm::clamp(blo, Point3d(-lim), Point3d(lim)));
    hi = glm::max(hi, glm::clamp(bhi, Point3d(-lim), Point3d(lim)));
  }
  const Vec3d span = hi - lo;
  lo -= 0.06 * span + Vec3d(1.0);
  hi += 0.06 * span + Vec3d(1.0);

  const int margin = 40, top = 60, bottom = 90;
  const int W = std::max(400, s.width);
  double mmPerPx = (hi.x - lo.x + hi.y - lo.y) / double(W - 3 * margin);
  mmPerPx = std::max(mmPerPx, (hi.z - lo.z) / 1400.0);
  const int panelAW = int(std::ceil((hi.x - lo.x) / mmPerPx)), panelBW = int(std::ceil((hi.y - lo.y) / mmPerPx));
  const int H = int(std::ceil((hi.z - lo.z) / mmPerPx)) + top + bottom;
  Canvas cv(std::max(W, panelAW + panelBW + 3 * margin), H);

  // Panel A maps (x, z), panel B maps (y, z); z up.
  auto py = [&](double z) { return top + (hi.z - z) / mmPerPx; };
  auto pxA = [&](double x) { return margin + (x - lo.x) / mmPerPx; };
  auto pxB = [&](double y) { return 2 * margin + panelAW + (y - lo.y) / mmPerPx; };

  const int midRow = R / 2, midCol = K / 2;
  for (int view = 0; view < 2; ++view) {
    auto ph = [&](double v) { return view == 0 ? pxA(v) : pxB(v); };
    const double a0 = view == 0 ? lo.x : lo.y, a1 = view == 0 ? hi.x : hi.y;
    const double half = view == 0 ? halfW : halfH;
    cv.rect(ph(a0), py(hi.z), ph(a1), py(lo.z), Vec3(0.85f));
    // Scene bounds.
    if (blo.x <= bhi.x) {
      double b0 = view == 0 ? blo.x : blo.y, b1 = view == 0 ? bhi.x : bhi.y;
      double c0 = std::clamp(b0, a0, a1), c1 = std::clamp(b1, a0, a1);
      double z0 = std::clamp(blo.z, lo.z, hi.z), z1 = std::clamp(bhi.z, lo.z, hi.z);
      cv.fill(ph(c0), py(z1), ph(c1), py(z0), Vec3(0.5f), 0.08f);
      cv.rect(ph(c0), py(z1), ph(c1), py(z0), kBounds, 1.0, 4.0);
    }
    // Central rays of the middle row (top view) or column (side view): panel -> pinhole
    // (dark) and VCP -> first hit (light).
    const int count = view == 0 ? K : R;
    for (int m = 0; m < count; ++m) {
      size_t i = view == 0 ? idx(m, midRow) : idx(midCol, m);
      const auto& q = qs[i];
      const double pin = view == 0 ? L.pinholeXAt(m, midRow) : L.pinholeYAt(midCol, m);
      const double ec = view == 0 ? L.eiCentreXAt(m, midRow) : L.eiCentreYAt(midCol, m);
      cv.line(ph(ec), py(-g), ph(pin), py(0.0), kPanel, 1.0, 0.6f);
      Point3d end = kind[i] ? hit[i] : q.vcpPoint + (q.vcpPoint.z - lo.z) / std::max(1e-9, -q.displayDir.z) * q.displayDir;
      double s0 = view == 0 ? q.vcpPoint.x : q.vcpPoint.y, s1 = view == 0 ? end.x : end.y;
      cv.line(ph(s0), py(q.vcpPoint.z), ph(s1), py(end.z), kRay, 1.0, 0.7f);
    }
    // Planes.
    cv.line(ph(-half), py(-g), ph(half), py(-g), kPanel, 3.0);
    cv.line(ph(-half), py(0.0), ph(half), py(0.0), kMla, 2.0);
    cv.line(ph(a0), py(vcpMm), ph(a1), py(vcpMm), kVcp, 2.0, 1.0f, 8.0);
    // MLA plane highlighted where the scene crosses it.
    for (int m = 0; m < count; ++m) {
      bool any = false;
      for (int o = 0; o < (view == 0 ? R : K) && !any; ++o) any = cross[view == 0 ? idx(m, o) : idx(o, m)];
      if (!any) continue;
      double c = view == 0 ? L.pinholeXAt(m, midRow) : L.pinholeYAt(midCol, m);
      cv.line(ph(c - 0.5 * eiPitch), py(0.0), ph(c + 0.5 * eiPitch), py(0.0), kCross, 6.0);
    }
    // First hits of every lenslet's central ray.
    const double r = std::clamp(0.25 * eiPitch / mmPerPx, 1.2, 3.0);
    for (size_t i = 0; i < n; ++i) {
      if (!kind[i]) continue;
      const Vec3& c = kind[i] == 1 ? kReal : kind[i] == 2 ? kVirtual : kOnPlane;
      cv.dot(ph(view == 0 ? hit[i].x : hit[i].y), py(hit[i].z), r, c, 0.8f);
    }
    // Labels.
    const int lx = int(ph(a0)) + 6;
    cv.text(int(ph(a0)), 14, view == 0 ? "TOP VIEW X-Z (X RIGHT, Z UP = TOWARD VIEWER)" : "SIDE VIEW Y-Z (Y RIGHT, Z UP)",
            kLabel);
    cv.text(lx, int(py(vcpMm)) - 20, "VCP Z=" + fmt(vcpMm), kVcp);
    cv.text(lx, int(py(0.0)) - 20, "MLA Z=0", kMla);
    cv.text(lx, int(py(-g)) + 6, "PANEL Z=-" + fmt(g), kPanel);
  }
  // Legend and scale bar.
  int ly = H - bottom + 24, lx = margin;
  for (auto [c, t] : {std::pair{kReal, "REAL (Z>0)"}, std::pair{kVirtual, "VIRTUAL (Z<0)"},
                      std::pair{kOnPlane, "ON MLA PLANE"}, std::pair{kCross, "SCENE CROSSES MLA"},
                      std::pair{kRay, "CENTRAL QUERY RAYS"}, std::pair{kBounds, "SCENE BOUNDS"}}) {
    cv.fill(lx, ly, lx + 14, ly + 14, c, 1.0f);
    cv.text(lx + 20, ly, t, kLabel);
    lx += 40 + Canvas::textWidth(t);
  }
  double bar = std::pow(10.0, std::floor(std::log10(std::max(1e-6, 200.0 * mmPerPx))));
  int barPx = int(std::lround(bar / mmPerPx));
  cv.line(margin, ly + 40, margin + barPx, ly + 40, kLabel, 3.0);
  cv.text(margin + barPx + 10, ly + 33, fmt(bar) + " MM", kLabel);
  res.image = std::move(cv.img);
  return res;
}

}  // namespace inim
