#include "display_view/panel_emitter.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "camera/lens_system.h"
#include "core/error.h"
#include "core/large_buffer.h"
#include "spectral/cie.h"

namespace inim {

namespace {

std::string sizeText(int w, int h) { return std::to_string(w) + " x " + std::to_string(h) + " px"; }

// The sum of the three primaries (the panel white before scaling).
class SumSpectrum final : public Spectrum {
 public:
  explicit SumSpectrum(std::array<SpectrumPtr, kNumPrimaries> s) : s_(std::move(s)) {}
  float operator()(float l) const override { return (*s_[0])(l) + (*s_[1])(l) + (*s_[2])(l); }
  float maxValue() const override { return s_[0]->maxValue() + s_[1]->maxValue() + s_[2]->maxValue(); }

 private:
  std::array<SpectrumPtr, kNumPrimaries> s_;
};

// Crossing-number test (half-open edges, so a point on a shared edge belongs to one side).
bool insidePolygon(const std::vector<std::array<float, 2>>& p, float u, float v) {
  bool in = false;
  for (size_t i = 0, j = p.size() - 1; i < p.size(); j = i++) {
    const float ui = p[i][0], vi = p[i][1], uj = p[j][0], vj = p[j][1];
    if ((vi > v) != (vj > v)) {
      const float uc = ui + (v - vi) / (vj - vi) * (uj - ui);
      if (u < uc) in = !in;
    }
  }
  return in;
}

}  // namespace

PanelEmitter::PanelEmitter(const Panel& panel, const EiLayout& L, const Image& img, const std::string& file,
                           double gapMm, const EmitterSettings& s)
    : panel_(panel), settings_(s) {
  panelW_ = L.panelW;
  panelH_ = L.panelH;
  pitch_ = L.pixelMm;
  gap_ = gapMm;
  readDrive(L, img, file);
  // Display x = (u - uOff) p, y = (vOff - v) p, with (u, v) continuous panel pixel coordinates.
  uOff_ = 0.5 * L.eiaW + L.panelCol0;
  vOff_ = 0.5 * L.eiaH + L.panelRow0;
  placeSubpixels();
  readPrimariesAndGlass();
}

// The drive table: the image's R, G, B (decoded when encoded, clamped to [0, 1]) on the whole
// panel, 0 outside the EIA; or the one settings_.drive hands over.
void PanelEmitter::readDrive(const EiLayout& L, const Image& img, const std::string& file) {
  const bool panelSized = img.width == L.panelW && img.height == L.panelH;
  const bool eiaSized = img.width == L.eiaW && img.height == L.eiaH;
  if (!panelSized && !eiaSized)
    throw InputError(file, "resolution", sizeText(img.width, img.height),
                     "the panel's resolution " + sizeText(L.panelW, L.panelH) +
                         (panel_.file.empty() ? std::string() : " (" + panel_.file + ")") +
                         " or the EIA area's " + sizeText(L.eiaW, L.eiaH));
  if (img.numChannels() < 3)
    throw InputError(file, "channels", std::to_string(img.numChannels()), "at least 3 channels (R, G, B drive values)");
  int ch[3];
  const bool named = img.channelIndex("R") >= 0 && img.channelIndex("G") >= 0 && img.channelIndex("B") >= 0;
  for (int c = 0; c < 3; ++c) ch[c] = named ? img.channelIndex(channelName(c)) : c;
  const int x0 = panelSized ? 0 : L.panelCol0, y0 = panelSized ? 0 : L.panelRow0;
  const size_t driveSize = size_t(panelW_) * panelH_ * 3;
  if (settings_.drive && settings_.drive->size() == driveSize) {
    driveTable_ = settings_.drive;
  } else {
    auto drive = std::make_shared<std::vector<float>>(largeVector(driveSize, 0.0f));  // read at random by every view
    for (int y = 0; y < img.height; ++y)
      for (int x = 0; x < img.width; ++x)
        for (int c = 0; c < 3; ++c) {
          float v = img.at(x, y, ch[c]);
          if (!std::isfinite(v))
            throw InputError(file, "pixel (" + std::to_string(x) + ", " + std::to_string(y) + ") " + channelName(c),
                             std::isnan(v) ? "NaN" : "Inf", "finite drive values");
          if (settings_.encoded) v = float(panel_.eotf.decode(v));
          (*drive)[(size_t(y0 + y) * panelW_ + (x0 + x)) * 3 + size_t(c)] = std::clamp(v, 0.0f, 1.0f);
        }
    driveTable_ = std::move(drive);
  }
  drive_ = driveTable_->data();
}

// A subpixel's polygon in tile coordinates, its bounds, whether it is its own bounding box, and
// the tile's pixel that owns it (the one holding its centroid).
PanelEmitter::Poly PanelEmitter::makePoly(const Subpixel& sp, int tileW, int tileH) {
  Poly p;
  p.channel = sp.channel;
  p.u0 = p.v0 = 1e30f;
  p.u1 = p.v1 = -1e30f;
  double cx = 0, cy = 0, a2 = 0;
  for (size_t i = 0; i < sp.polygon.size(); ++i) {
    const auto& q = sp.polygon[i];
    const auto& r = sp.polygon[(i + 1) % sp.polygon.size()];
    const double cr = q[0] * r[1] - r[0] * q[1];
    a2 += cr;
    cx += (q[0] + r[0]) * cr;
    cy += (q[1] + r[1]) * cr;
    p.pts.push_back({float(q[0]), float(q[1])});
    p.u0 = std::min(p.u0, float(q[0]));
    p.u1 = std::max(p.u1, float(q[0]));
    p.v0 = std::min(p.v0, float(q[1]));
    p.v1 = std::max(p.v1, float(q[1]));
  }
  if (a2 != 0.0) {
    cx /= 3.0 * a2;
    cy /= 3.0 * a2;
  }
  // Axis-aligned rectangle: 4 corners, every edge horizontal or vertical, area = bbox area.
  bool axis = sp.polygon.size() == 4;
  for (size_t i = 0; axis && i < 4; ++i) {
    const auto& q = sp.polygon[i];
    const auto& r = sp.polygon[(i + 1) % 4];
    axis = q[0] == r[0] || q[1] == r[1];
  }
  // (The bounds are floats: compare at float precision.)
  p.rect = axis && std::abs(0.5 * std::abs(a2) - (double(p.u1) - p.u0) * (double(p.v1) - p.v0)) <=
                       1e-6 * std::max(1.0, 0.5 * std::abs(a2));
  p.pixU = std::clamp(int(std::floor(cx)), 0, tileW - 1);
  p.pixV = std::clamp(int(std::floor(cy)), 0, tileH - 1);
  return p;
}

// The subpixel tile: each channel's area factor (tile area / its emitting area), its polygons,
// and its one rectangle when it has a single rectangular subpixel (the fast path).
void PanelEmitter::placeSubpixels() {
  const SubpixelLayout& sl = panel_.subpixels;
  tileW_ = std::max(1, sl.tileW);
  tileH_ = std::max(1, sl.tileH);
  const double tileArea = double(tileW_) * tileH_;
  for (int c = 0; c < kNumPrimaries; ++c) {
    const double a = sl.emittingArea(c);
    if (!(a > 0.0))
      throw InputError(panel_.file, "subpixel_layout", std::string("no ") + channelName(c) + " subpixel",
                       "at least one subpixel of each channel R, G, B");
    areaFactor_[size_t(c)] = tileArea / a;
  }
  for (const Subpixel& sp : sl.subpixels) {
    Poly p = makePoly(sp, tileW_, tileH_);
    if (p.channel >= 0 && p.channel < kNumPrimaries) channelPolys_[size_t(p.channel)].push_back(int(polys_.size()));
    polys_.push_back(std::move(p));
  }
  for (int c = 0; c < kNumPrimaries; ++c) {
    const std::vector<int>& own = channelPolys_[size_t(c)];
    if (own.size() == 1 && polys_[size_t(own[0])].rect) channelRect_[size_t(c)] = own[0];
  }
}

// The primaries' spectra, the luminance scale (white = the peak luminance, or 1) and the cover
// glass's index and thickness when it is modelled.
void PanelEmitter::readPrimariesAndGlass() {
  for (int c = 0; c < kNumPrimaries; ++c) primary_[size_t(c)] = primarySpectrum(panel_.primaries[size_t(c)]);
  const double yWhite = spectrumToXYZ(SumSpectrum(primary_)).y;
  if (!(yWhite > 0.0))
    throw InputError(panel_.file, "primaries", "(no visible emission)", "primaries with a non-zero luminance");
  l0_ = (settings_.absolute ? panel_.peakLuminanceCdM2 : 1.0) / yWhite;
  uniformIntensity_ = panel_.angularProfile == "uniform";
  if (!settings_.coverGlass || !panel_.coverGlass) return;
  try {
    glassIor_ = MaterialCatalog::standard().dielectric(panel_.coverGlass->material);
  } catch (const InputError& e) {
    throw InputError(panel_.file, "cover_glass.material", "\"" + panel_.coverGlass->material + "\"",
                     "a dielectric of spectra/materials.json (" + std::string(e.what()) + ")");
  }
  glassT_ = panel_.coverGlass->thicknessMm;
}

PanelEmission PanelEmitter::lookup(double x, double y) const { return lookupPx(x / pitch_ + uOff_, vOff_ - y / pitch_); }

PanelEmission PanelEmitter::lookupPx(double u, double v) const {
  if (!(u >= 0.0 && v >= 0.0 && u < panelW_ && v < panelH_)) return {};
  const double tu = std::floor(u / tileW_), tv = std::floor(v / tileH_);
  const float fu = float(u - tu * tileW_), fv = float(v - tv * tileH_);
  for (const Poly& p : polys_) {
    if (fu < p.u0 || fu > p.u1 || fv < p.v0 || fv > p.v1) continue;
    if (!insidePolygon(p.pts, fu, fv)) continue;
    const int col = int(tu) * tileW_ + p.pixU, row = int(tv) * tileH_ + p.pixV;
    if (col >= panelW_ || row >= panelH_) return {};
    return {p.channel, drive_[(size_t(row) * panelW_ + col) * 3 + size_t(p.channel)]};
  }
  return {};
}

float PanelEmitter::channelDrivePx(int c, double u, double v) const {
  if (!(u >= 0.0 && v >= 0.0 && u < panelW_ && v < panelH_)) return 0.0f;
  const double tu = std::floor(u / tileW_), tv = std::floor(v / tileH_);
  const float fu = float(u - tu * tileW_), fv = float(v - tv * tileH_);
  for (int i : channelPolys_[size_t(c)]) {
    const Poly& p = polys_[size_t(i)];
    if (fu < p.u0 || fu >= p.u1 || fv < p.v0 || fv >= p.v1) continue;
    if (!p.rect && !insidePolygon(p.pts, fu, fv)) continue;
    const int col = int(tu) * tileW_ + p.pixU, row = int(tv) * tileH_ + p.pixV;
    if (col >= panelW_ || row >= panelH_) return 0.0f;
    return drive_[(size_t(row) * panelW_ + col) * 3 + size_t(c)];
  }
  return 0.0f;
}

float PanelEmitter::angular(float cosTheta) const {
  float a = 1.0f;
  if (uniformIntensity_) a = 1.0f / std::max(cosTheta, 0.05f);
  if (settings_.cosExponent != 0.0) a *= std::pow(std::max(cosTheta, 0.0f), float(settings_.cosExponent));
  return a;
}

bool PanelEmitter::emissionPointPx(const Point3& p, const Vec3& dIn, float lambdaNm, Vec2d& uv, float& factor) const {
  const Vec3 d = glm::normalize(dIn);
  if (!(d.z < 0.0f)) return false;
  if (!glassIor_) {
    uv = toPanelPx(p.x, p.y);
    factor = angular(-d.z);
    return true;
  }
  // Back along the ray to the plate's top, refract into the glass, go down to z = -g.
  const double zTop = -gap_ + glassT_;
  const Vec3d dd(d);
  const Point3d top = Point3d(p) + dd * ((zTop - double(p.z)) / dd.z);
  const double n = glassIor_->n(lambdaNm);
  Vec3d dg;
  if (!snellRefract(dd, Vec3d(0, 0, 1), 1.0, n, dg)) return false;  // cannot happen from air
  const Point3d q = top + dg * (-glassT_ / dg.z);
  uv = toPanelPx(q.x, q.y);
  const double t = fresnelTransmittance(-dd.z, 1.0, n) / fresnelTransmittance(1.0, 1.0, n);
  factor = float(t) * angular(float(-dg.z));
  return true;
}

PanelEmission PanelEmitter::emit(const Point3& p, const Vec3& d, float lambdaNm) const {
  Vec2d uv;
  float factor = 0.0f;
  if (!emissionPointPx(p, d, lambdaNm, uv, factor)) return {};
  PanelEmission e = lookupPx(uv.x, uv.y);
  if (e.channel < 0 || e.weight == 0.0f) return e;
  e.weight *= factor;
  return e;
}

double PanelEmitter::polyBoxArea(const Poly& p, double u0, double v0, double u1, double v1) const {
  // Sutherland-Hodgman against the four half-planes of the box (box in tile coordinates). The
  // subject may be concave: the clipped polygon can then have degenerate edges, but its signed
  // area is still the area of the intersection.
  constexpr size_t kMax = 64;
  std::array<double, 2> bufA[kMax], bufB[kMax];
  size_t n = p.pts.size();
  if (n < 3 || n + 8 > kMax / 2) {
    // Too many vertices for the fixed buffers: 8 x 8 midpoint sub-samples of the box.
    int in = 0;
    for (int j = 0; j < 8; ++j)
      for (int i = 0; i < 8; ++i)
        if (insidePolygon(p.pts, float(u0 + (i + 0.5) / 8 * (u1 - u0)), float(v0 + (j + 0.5) / 8 * (v1 - v0)))) ++in;
    return in / 64.0 * (u1 - u0) * (v1 - v0);
  }
  for (size_t i = 0; i < n; ++i) bufA[i] = {double(p.pts[i][0]), double(p.pts[i][1])};
  std::array<double, 2>* src = bufA;
  std::array<double, 2>* dst = bufB;
  for (int side = 0; side < 4 && n > 0; ++side) {
    const int axis = side & 1;                       // 0: u, 1: v
    const bool keepAbove = side < 2;                 // sides 0, 1: >= lower bound; 2, 3: <= upper
    const double bound = side == 0 ? u0 : side == 1 ? v0 : side == 2 ? u1 : v1;
    auto inside = [&](const std::array<double, 2>& q) { return keepAbove ? q[axis] >= bound : q[axis] <= bound; };
    size_t m = 0;
    for (size_t i = 0; i < n; ++i) {
      const auto& a = src[i];
      const auto& b = src[(i + 1) % n];
      const bool ia = inside(a), ib = inside(b);
      if (ia) dst[m++] = a;
      if (ia != ib) {
        const double t = (bound - a[axis]) / (b[axis] - a[axis]);
        std::array<double, 2> c{a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])};
        c[axis] = bound;
        dst[m++] = c;
      }
    }
    std::swap(src, dst);
    n = m;
  }
  double a2 = 0.0;
  for (size_t i = 0; i < n; ++i) {
    const auto& q = src[i];
    const auto& r = src[(i + 1) % n];
    a2 += q[0] * r[1] - r[0] * q[1];
  }
  return 0.5 * std::abs(a2);
}

std::array<float, kNumPrimaries> PanelEmitter::boxAveragePx(double u0, double v0, double u1, double v1) const {
  std::array<float, kNumPrimaries> out{0.0f, 0.0f, 0.0f};
  const double area = (u1 - u0) * (v1 - v0);
  if (!(area > 0.0)) {
    const PanelEmission e = lookupPx(0.5 * (u0 + u1), 0.5 * (v0 + v1));
    if (e.channel >= 0) out[size_t(e.channel)] = e.weight;
    return out;
  }
  BoxTiles b;  // only the part on the panel can emit
  if (!boxTiles(u0, v0, u1, v1, b)) return out;
  double sum[kNumPrimaries] = {0.0, 0.0, 0.0};
  for (int tv = b.tv0; tv <= b.tv1; ++tv)
    for (int tu = b.tu0; tu <= b.tu1; ++tu) {
      const double ou = double(tu) * tileW_, ov = double(tv) * tileH_;
      const double bu0 = b.cu0 - ou, bu1 = b.cu1 - ou, bv0 = b.cv0 - ov, bv1 = b.cv1 - ov;  // in tile coordinates
      for (const Poly& p : polys_) {
        if (bu1 <= p.u0 || bu0 >= p.u1 || bv1 <= p.v0 || bv0 >= p.v1) continue;
        const int col = tu * tileW_ + p.pixU, row = tv * tileH_ + p.pixV;
        if (col >= panelW_ || row >= panelH_) continue;
        const float drive = drive_[(size_t(row) * panelW_ + col) * 3 + size_t(p.channel)];
        if (drive == 0.0f) continue;
        double a;
        if (p.rect) {
          a = (std::min(bu1, double(p.u1)) - std::max(bu0, double(p.u0))) *
              (std::min(bv1, double(p.v1)) - std::max(bv0, double(p.v0)));
        } else {
          a = polyBoxArea(p, std::max(bu0, double(p.u0)), std::max(bv0, double(p.v0)), std::min(bu1, double(p.u1)),
                          std::min(bv1, double(p.v1)));
        }
        if (a > 0.0) sum[p.channel] += a * drive;
      }
    }
  for (int c = 0; c < kNumPrimaries; ++c) out[size_t(c)] = float(sum[c] / area);
  return out;
}

// The overlaps of [b0, b1] with a rectangle's side [r0, r1] in each of the tiles t0..t1 (tile
// size w), kept where positive and inside the panel (index of the pixel < limit); false when
// there are more than kMaxBoxTiles tiles.
bool PanelEmitter::sideOverlaps(double b0, double b1, int t0, int t1, int w, float r0, float r1, int pix, int limit,
                                SideOverlaps& out) {
  out.n = 0;
  if (t1 - t0 >= kMaxBoxTiles) return false;
  for (int t = t0; t <= t1; ++t) {
    const double o = double(t) * w;
    const double a = std::min(b1 - o, double(r1)) - std::max(b0 - o, double(r0));
    const int index = t * w + pix;
    if (!(a > 0.0) || index >= limit) continue;
    out.length[out.n] = a;
    out.index[out.n] = index;
    ++out.n;
  }
  return true;
}

bool PanelEmitter::boxTiles(double u0, double v0, double u1, double v1, BoxTiles& b) const {
  b.cu0 = std::max(u0, 0.0), b.cv0 = std::max(v0, 0.0);
  b.cu1 = std::min(u1, double(panelW_)), b.cv1 = std::min(v1, double(panelH_));
  if (!(b.cu1 > b.cu0 && b.cv1 > b.cv0)) return false;
  // x / 1 is x: the division only for tiles of several pixels (it is most of a small box's cost).
  auto tile = [](double x, int w) { return int(w == 1 ? std::floor(x) : std::floor(x / w)); };
  b.tu0 = tile(b.cu0, tileW_), b.tu1 = tile(b.cu1, tileW_);
  b.tv0 = tile(b.cv0, tileH_), b.tv1 = tile(b.cv1, tileH_);
  return true;
}

bool PanelEmitter::channelColumns(int c, const BoxTiles& b, SideOverlaps& cols) const {
  const Poly* p = channelRect(c);
  return p && sideOverlaps(b.cu0, b.cu1, b.tu0, b.tu1, tileW_, p->u0, p->u1, p->pixU, panelW_, cols);
}

bool PanelEmitter::channelRows(int c, const BoxTiles& b, SideOverlaps& rows) const {
  const Poly* p = channelRect(c);
  return p && sideOverlaps(b.cv0, b.cv1, b.tv0, b.tv1, tileH_, p->v0, p->v1, p->pixV, panelH_, rows);
}

double PanelEmitter::overlapSum(int c, const SideOverlaps& cols, const SideOverlaps& rows) const {
  double sum = 0.0;
  for (int j = 0; j < rows.n; ++j) {
    const float* row = drive_ + size_t(rows.index[j]) * size_t(panelW_) * 3 + size_t(c);
    double s = 0.0;
    for (int i = 0; i < cols.n; ++i) s += cols.length[i] * double(row[size_t(cols.index[i]) * 3]);
    sum += rows.length[j] * s;
  }
  return sum;
}

double PanelEmitter::boxSumByPolygons(int c, const BoxTiles& b) const {
  double sum = 0.0;
  for (int tv = b.tv0; tv <= b.tv1; ++tv)
    for (int tu = b.tu0; tu <= b.tu1; ++tu) {
      const double ou = double(tu) * tileW_, ov = double(tv) * tileH_;
      const double bu0 = b.cu0 - ou, bu1 = b.cu1 - ou, bv0 = b.cv0 - ov, bv1 = b.cv1 - ov;
      for (int i : channelPolys_[size_t(c)]) {
        const Poly& p = polys_[size_t(i)];
        if (bu1 <= p.u0 || bu0 >= p.u1 || bv1 <= p.v0 || bv0 >= p.v1) continue;
        const int col = tu * tileW_ + p.pixU, row = tv * tileH_ + p.pixV;
        if (col >= panelW_ || row >= panelH_) continue;
        const float drive = drive_[(size_t(row) * panelW_ + col) * 3 + size_t(c)];
        if (drive == 0.0f) continue;
        const double a = p.rect ? (std::min(bu1, double(p.u1)) - std::max(bu0, double(p.u0))) *
                                      (std::min(bv1, double(p.v1)) - std::max(bv0, double(p.v0)))
                                : polyBoxArea(p, std::max(bu0, double(p.u0)), std::max(bv0, double(p.v0)),
                                              std::min(bu1, double(p.u1)), std::min(bv1, double(p.v1)));
        if (a > 0.0) sum += a * drive;
      }
    }
  return sum;
}

float PanelEmitter::channelBoxAveragePx(int c, double u0, double v0, double u1, double v1) const {
  const double area = (u1 - u0) * (v1 - v0);
  if (!(area > 0.0)) return channelDrivePx(c, 0.5 * (u0 + u1), 0.5 * (v0 + v1));
  BoxTiles b;
  if (!boxTiles(u0, v0, u1, v1, b)) return 0.0f;
  // One rectangle of the channel per tile (the stripe layouts): its overlap with the box is a
  // column's length times a row's, each found once (the hot path of the Quadrature estimator).
  SideOverlaps cols, rows;
  if (channelColumns(c, b, cols) && channelRows(c, b, rows)) return float(overlapSum(c, cols, rows) / area);
  return float(boxSumByPolygons(c, b) / area);
}

std::array<float, kNumPrimaries> PanelEmitter::channelBoxAveragesPx(double u0, double v0, double u1,
                                                                   double v1) const {
  std::array<float, kNumPrimaries> out{0.0f, 0.0f, 0.0f};
  auto byChannel = [&] {
    for (int c = 0; c < kNumPrimaries; ++c) out[size_t(c)] = channelBoxAveragePx(c, u0, v0, u1, v1);
    return out;
  };
  const double area = (u1 - u0) * (v1 - v0);
  if (!(area > 0.0) || !(channelRect(0) && channelRect(1) && channelRect(2))) return byChannel();
  BoxTiles b;
  if (!boxTiles(u0, v0, u1, v1, b)) return out;
  SideOverlaps cols[kNumPrimaries], rows[kNumPrimaries];
  const SideOverlaps* colsOf[kNumPrimaries];
  const SideOverlaps* rowsOf[kNumPrimaries];
  for (int c = 0; c < kNumPrimaries; ++c) {
    // A channel whose rectangle spans the same columns (rows) as an earlier one's shares them.
    const Poly& p = *channelRect(c);
    colsOf[c] = rowsOf[c] = nullptr;
    for (int e = 0; e < c; ++e) {
      const Poly& q = *channelRect(e);
      if (!colsOf[c] && p.u0 == q.u0 && p.u1 == q.u1 && p.pixU == q.pixU) colsOf[c] = colsOf[e];
      if (!rowsOf[c] && p.v0 == q.v0 && p.v1 == q.v1 && p.pixV == q.pixV) rowsOf[c] = rowsOf[e];
    }
    if (!colsOf[c]) {
      if (!channelColumns(c, b, cols[c])) return byChannel();
      colsOf[c] = &cols[c];
    }
    if (!rowsOf[c]) {
      if (!channelRows(c, b, rows[c])) return byChannel();
      rowsOf[c] = &rows[c];
    }
  }
  for (int c = 0; c < kNumPrimaries; ++c) out[size_t(c)] = float(overlapSum(c, *colsOf[c], *rowsOf[c]) / area);
  return out;
}

float PanelEmitter::radiance(const Point3& p, const Vec3& d, float lambdaNm) const {
  const PanelEmission e = emit(p, d, lambdaNm);
  return e.channel < 0 ? 0.0f : e.weight * channelSpectrum(e.channel, lambdaNm);
}

float PanelEmitter::channelSpectrum(int c, float lambdaNm) const {
  return float(areaFactor_[size_t(c)] * l0_) * (*primary_[size_t(c)])(lambdaNm);
}

float PanelEmitter::averageChannelSpectrum(int c, float lambdaNm) const {
  return float(l0_) * (*primary_[size_t(c)])(lambdaNm);
}

bool PanelEmitter::emitsLike(const PanelEmitter& o) const {
  if (panelW_ != o.panelW_ || panelH_ != o.panelH_ || pitch_ != o.pitch_ || uOff_ != o.uOff_ || vOff_ != o.vOff_ ||
      gap_ != o.gap_ || l0_ != o.l0_ || uniformIntensity_ != o.uniformIntensity_ ||
      settings_.cosExponent != o.settings_.cosExponent || hasCoverGlass() != o.hasCoverGlass() || glassT_ != o.glassT_)
    return false;
  if (hasCoverGlass() && panel_.coverGlass->material != o.panel_.coverGlass->material) return false;
  for (int c = 0; c < kNumPrimaries; ++c)
    for (int l = int(kLambdaMin); l <= int(kLambdaMax); ++l)
      if (averageChannelSpectrum(c, float(l)) != o.averageChannelSpectrum(c, float(l))) return false;
  return true;
}

Vec3d PanelEmitter::whiteXyz() const { return spectrumToXYZ(SumSpectrum(primary_)) * l0_; }

}  // namespace inim
