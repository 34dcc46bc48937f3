#include "mla_optics/real_mla.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>

#include "core/error.h"
#include "core/format.h"

namespace inim {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
// Overlap of neighbouring cells' intervals and tolerance of the aperture tests (mm): rays on
// cell edges, corners or aperture boundaries are caught by at least one side.
constexpr double kEps = 1e-9;
// A new hit must lie this far along the ray (mm): a ray never re-hits the point it left.
constexpr double kTMin = 1e-10;
constexpr double kLambdaTable0 = 300.0;
constexpr int kLambdaTableN = 701;  // 300..1000 nm

// Unpolarised Fresnel reflectance for cosines of incidence and transmission (both >= 0).
inline double fresnelR(double cosi, double cost, double n1, double n2) {
  const double a = n1 * cosi, b = n2 * cost, c = n1 * cost, e = n2 * cosi;
  const double rs = (a + b) > 0.0 ? (a - b) / (a + b) : 1.0;
  const double rp = (c + e) > 0.0 ? (c - e) / (c + e) : 1.0;
  return std::min(1.0, 0.5 * (rs * rs + rp * rp));
}

inline bool finite3(const Vec3d& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

}  // namespace

double fresnelReflectance(double cosi, double n1, double n2) {
  cosi = std::clamp(cosi, 0.0, 1.0);
  const double eta = n1 / n2;
  const double sin2t = eta * eta * (1.0 - cosi * cosi);
  if (sin2t >= 1.0) return 1.0;
  return fresnelR(cosi, std::sqrt(1.0 - sin2t), n1, n2);
}

struct RealMla::Hit {
  double t = 0.0;
  Vec3d n{0.0};  // unit normal, canonical frame, pointing out of the material
  MlaTraceEvent::Surface surface = MlaTraceEvent::Surface::Cap;
  int k = 0, l = 0;
};

namespace {

[[noreturn]] void failInput(const std::string& file, const std::string& key, double v, const std::string& expected) {
  throw InputError(file, key, formatNumber(v), expected);
}

// The numbers of a geometry and its options that must hold before anything is derived.
void validateGeometry(const RealMlaGeometry& g, const RealMlaOptions& opt, const std::string& file) {
  auto fail = [&](const std::string& key, double v, const std::string& expected) { failInput(file, key, v, expected); };
  if (!(g.pitchMm > 0.0) || !std::isfinite(g.pitchMm)) fail("pitch_mm", g.pitchMm, "a pitch > 0 mm");
  if (!(g.apertureMm > 0.0) || g.apertureMm > g.pitchMm * (1.0 + 1e-9))
    fail("aperture_mm", g.apertureMm, "an aperture > 0 and <= pitch_mm (" + formatNumber(g.pitchMm) + ")");
  if (!(g.radiusMm > 0.0) || !std::isfinite(g.radiusMm))
    fail("radius_of_curvature_mm", g.radiusMm, "a radius > 0 mm (convex cap)");
  if (!std::isfinite(g.conic)) fail("conic", g.conic, "a finite conic constant");
  if (!(g.thicknessMm > 0.0) || !std::isfinite(g.thicknessMm))
    fail("substrate_thickness_mm", g.thicknessMm, "a thickness > 0 mm");
  if (!(g.gapMm > 0.0) || !std::isfinite(g.gapMm)) fail("gap_mm", g.gapMm, "a gap > 0 mm");
  if (g.cols < 1 || g.rows < 1) fail("ei_count", std::min(g.cols, g.rows), "at least 1 x 1 lenslets");
  if (!std::isfinite(g.originXMm) || !std::isfinite(g.originYMm))
    fail("lens centre", g.originXMm, "finite lenslet centres");
  if (opt.maxEvents < 1) fail("max events", opt.maxEvents, "at least 1 surface interaction");
  if (!(opt.absorptionPerMm >= 0.0) || !std::isfinite(opt.absorptionPerMm))
    fail("absorption_per_mm", opt.absorptionPerMm, "an absorption coefficient >= 0 per mm");
}

}  // namespace

RealMla::RealMla(const RealMlaGeometry& g, IorPtr ior, const RealMlaOptions& o, const std::string& file)
    : g_(g), opt_(o), ior_(std::move(ior)) {
  if (!ior_) throw InputError(file, "material", "(none)", "a dielectric of spectra/materials.json");
  validateGeometry(g, opt_, file);
  nTable_.resize(kLambdaTableN);
  for (int i = 0; i < kLambdaTableN; ++i) nTable_[size_t(i)] = ior_->n(float(kLambdaTable0 + i));
  nRef_ = g.referenceIndex > 0.0 ? g.referenceIndex : double(ior_->n(float(kLambdaDNm)));
  if (!(nRef_ > 1.0)) failInput(file, "material", nRef_, "a lens material with n_d > 1");
  hex_ = g.lattice == Mla::Lattice::Hex;
  rowH_ = hex_ ? g.pitchMm * std::sqrt(3.0) / 2.0 : g.pitchMm;
  R_ = g.radiusMm;
  K1_ = 1.0 + g.conic;
  buildCellAndAperture();
  buildOutline();
  placeSurfaces(file);
  placeExtent(file);
}

// Cell and aperture half-planes, in a cell's local frame (origin on the lenslet axis).
void RealMla::buildCellAndAperture() {
  const double P = g_.pitchMm, a = g_.apertureMm;
  auto polygon = [](bool hexShape, double width, std::array<Edge, 6>& e) {
    if (!hexShape) {
      e[0] = {1, 0, width / 2}, e[1] = {-1, 0, width / 2}, e[2] = {0, 1, width / 2}, e[3] = {0, -1, width / 2};
      return 4;
    }
    for (int i = 0; i < 6; ++i) {
      double ang = i * M_PI / 3.0;
      double c = std::cos(ang), s = std::sin(ang);
      if (std::abs(c) < 1e-15) c = 0.0;
      if (std::abs(s) < 1e-15) s = 0.0;
      e[size_t(i)] = {c, s, width / 2};
    }
    return 6;
  };
  nCellEdges_ = polygon(hex_, P, cellEdges_);
  circle_ = g_.aperture == Mla::Aperture::Circle;
  apR2_ = 0.25 * a * a;
  std::array<Edge, 6> ap{};
  int nAp = circle_ ? 0 : polygon(g_.aperture == Mla::Aperture::Hex, a, ap);
  // Cell vertices (for supports and the aperture's farthest point).
  std::vector<std::array<double, 2>> cellVerts;
  {
    const double c = hex_ ? P / std::sqrt(3.0) : P / 2;
    if (!hex_) cellVerts = {{c, c}, {-c, c}, {-c, -c}, {c, -c}};
    else
      for (int i = 0; i < 6; ++i)
        cellVerts.push_back({c * std::cos(M_PI / 6 + i * M_PI / 3), c * std::sin(M_PI / 6 + i * M_PI / 3)});
  }
  // Keep the aperture edges that bound A inside the cell (not on a cell edge, not outside it).
  nApEdges_ = 0;
  for (int i = 0; i < nAp; ++i) {
    const Edge& e = ap[size_t(i)];
    bool onCell = false;
    for (int j = 0; j < nCellEdges_; ++j) {
      const Edge& c = cellEdges_[size_t(j)];
      if (std::abs(e.nx - c.nx) < 1e-12 && std::abs(e.ny - c.ny) < 1e-12 && std::abs(e.h - c.h) < 1e-9 * P) onCell = true;
    }
    double support = -kInf;
    for (auto& v : cellVerts) support = std::max(support, v[0] * e.nx + v[1] * e.ny);
    if (!onCell && e.h < support - 1e-12 * P) apEdges_[size_t(nApEdges_++)] = e;
  }
  hasLand_ = circle_ || nApEdges_ > 0;
}

// A's farthest point from the axis, and its outline (vertices in angular order, then the edge
// midpoints; or 32 points on the circle).
void RealMla::buildOutline() {
  const double P = g_.pitchMm;
  if (circle_) {
    rMax_ = 0.5 * g_.apertureMm;
    for (int i = 0; i < 32; ++i) outline_.push_back({rMax_ * std::cos(i * M_PI / 16), rMax_ * std::sin(i * M_PI / 16)});
    return;
  }
  std::vector<Edge> all(cellEdges_.begin(), cellEdges_.begin() + nCellEdges_);
  all.insert(all.end(), apEdges_.begin(), apEdges_.begin() + nApEdges_);
  rMax_ = 0.0;
  for (size_t i = 0; i < all.size(); ++i)
    for (size_t j = i + 1; j < all.size(); ++j) {
      double det = all[i].nx * all[j].ny - all[i].ny * all[j].nx;
      if (std::abs(det) < 1e-12) continue;
      double x = (all[i].h * all[j].ny - all[i].ny * all[j].h) / det;
      double y = (all[i].nx * all[j].h - all[i].h * all[j].nx) / det;
      bool in = true;
      for (auto& e : all) in = in && x * e.nx + y * e.ny <= e.h + 1e-9 * P;
      if (in) {
        rMax_ = std::max(rMax_, std::hypot(x, y));
        outline_.push_back({x, y});
      }
    }
  std::sort(outline_.begin(), outline_.end(), [](const auto& p, const auto& q) {
    return std::atan2(p[1], p[0]) < std::atan2(q[1], q[0]);
  });
  outline_.erase(std::unique(outline_.begin(), outline_.end(),
                             [&](const auto& p, const auto& q) {
                               return std::hypot(p[0] - q[0], p[1] - q[1]) < 1e-9 * P;
                             }),
                 outline_.end());
  while (outline_.size() > 1 &&
         std::hypot(outline_.front()[0] - outline_.back()[0], outline_.front()[1] - outline_.back()[1]) < 1e-9 * P)
    outline_.pop_back();
  const size_t nv = outline_.size();
  for (size_t i = 0; i < nv; ++i) {
    const auto& p = outline_[i];
    const auto& q = outline_[(i + 1) % nv];
    outline_.push_back({0.5 * (p[0] + q[0]), 0.5 * (p[1] + q[1])});
  }
}

// The cap must cover A and fit in the substrate; the vertices, faces and panel along z.
void RealMla::placeSurfaces(const std::string& file) {
  if (!(K1_ * rMax_ * rMax_ < R_ * R_))
    failInput(file, "radius_of_curvature_mm", R_,
              "a radius whose cap covers the aperture: (1 + conic) r^2 < R^2 with r = " + formatNumber(rMax_) +
                  " mm, the aperture's farthest point from the lenslet axis");
  sMax_ = capSag(rMax_);
  if (!(g_.thicknessMm > sMax_ * (1.0 + 1e-9) + 1e-9))
    failInput(file, "substrate_thickness_mm", g_.thicknessMm,
              "a centre thickness larger than the cap depth s_max = " + formatNumber(sMax_) + " mm");
  const double T = g_.thicknessMm;
  if (g_.orientation == Mla::Orientation::CurvedTowardViewer) {
    s_ = 1.0;
    zv_ = T * (1.0 - 1.0 / nRef_);  // H (flat + T/n) on z = 0
    frontZ_ = zv_;
    backZ_ = zv_ - T;
  } else {
    s_ = -1.0;
    zv_ = 0.0;  // H at the vertex
    frontZ_ = T;
    backZ_ = 0.0;
  }
  frontZf_ = float(frontZ_);
  if (double(frontZf_) < frontZ_) frontZf_ = std::nextafter(frontZf_, std::numeric_limits<float>::infinity());
  if (!(-g_.gapMm < backZ_ - 1e-9))
    failInput(file, "gap_mm", g_.gapMm,
              "a panel gap larger than " + formatNumber(-backZ_) + " mm: the panel must lie behind the MLA (its " +
                  (s_ > 0 ? std::string("flat face is at z = ") + formatNumber(backZ_) + " mm, T/n_d behind the reference plane)"
                          : std::string("cap vertices are on the reference plane)")));
}

// The array's extent: the indexed lenslets and marginCells more on every side.
void RealMla::placeExtent(const std::string& file) {
  const double P = g_.pitchMm, x0 = g_.originXMm, y0 = g_.originYMm;
  if (g_.marginCells < 0) failInput(file, "margin cells", g_.marginCells, "a margin >= 0 lenslets");
  const int M = g_.marginCells;
  if (!hex_) {
    boxX0_ = x0 - (M + 0.5) * P, boxX1_ = x0 + (g_.cols - 1 + M + 0.5) * P;
    boxY0_ = y0 - (g_.rows - 1 + M + 0.5) * P, boxY1_ = y0 + (M + 0.5) * P;
  } else {
    boxX0_ = x0 - (M + 0.5) * P, boxX1_ = x0 + (g_.cols - 1 + M + 1.0) * P;
    boxY0_ = y0 - (g_.rows - 1 + M) * rowH_ - P / std::sqrt(3.0), boxY1_ = y0 + M * rowH_ + P / std::sqrt(3.0);
  }
  maxSteps_ = 2 * (g_.cols + g_.rows + 4 * M) + 16;
}

RealMlaGeometry RealMla::geometryFor(const Display& d, const EiLayout& L, double gapMm) {
  if (d.stackTraced)  // its mla only places the EIs: one plano-convex lens would not be its optics
    throw InputError(d.file, "stack", "a stack of several layers",
                     "a display with one MLA for this use of the single-lens model (view takes the stack)");
  const Mla& m = d.mla;
  RealMlaGeometry g;
  g.lattice = m.lattice;
  g.aperture = m.aperture;
  g.orientation = m.orientation;
  g.pitchMm = m.pitchMm;
  g.apertureMm = m.apertureMm > 0.0 ? m.apertureMm : m.pitchMm;
  g.conic = m.conic;
  g.thicknessMm = m.substrateThicknessMm;
  const std::string material = m.material.empty() ? "PMMA" : m.material;
  IorPtr ior = MaterialCatalog::standard().dielectric(material);
  const double nd = ior->n(float(kLambdaDNm));
  if (m.radiusMm) g.radiusMm = *m.radiusMm;
  else if (m.focalLengthMm) g.radiusMm = *m.focalLengthMm * (nd - 1.0);
  else throw InputError(m.file, "radius_of_curvature_mm", "(missing)", "radius_of_curvature_mm or focal_length_mm");
  if (L.lensX.empty() || L.lensY.empty())
    throw InputError(d.file, "ei_count", "(no lenses)", "a layout with at least one lenslet");
  if (L.isHex() != (m.lattice == Mla::Lattice::Hex))
    throw InputError(d.file, "mla.lattice", latticeName(m.lattice), "the lattice the EI layout was made for");
  // Lenslet (0, 0) is the top-left one; for hex, odd rows are shifted by +P/2 in both the
  // layout and RealMla, so every lenslet (k, l) sits at the layout's (lensXAt, lensYAt).
  g.originXMm = L.lensXAt(0, 0);
  g.originYMm = L.lensYAt(0, 0);
  g.cols = int(L.lensX.size());
  g.rows = int(L.lensY.size());
  g.gapMm = gapMm;
  g.referenceIndex = nd;
  return g;
}

std::unique_ptr<RealMla> RealMla::fromDisplay(const Display& d, const EiLayout& L, double gapMm,
                                              const RealMlaOptions& o) {
  RealMlaGeometry g = geometryFor(d, L, gapMm);
  const std::string material = d.mla.material.empty() ? "PMMA" : d.mla.material;
  return std::make_unique<RealMla>(g, MaterialCatalog::standard().dielectric(material), o,
                                   d.mla.file.empty() ? d.file : d.mla.file);
}

std::unique_ptr<MlaModel> makeRealMla(const Display& display, const EiLayout& layout, double gapMm) {
  return RealMla::fromDisplay(display, layout, gapMm);
}

double RealMla::n(double lambdaNm) const {
  double x = lambdaNm - kLambdaTable0;
  if (x >= 0.0 && x < double(kLambdaTableN - 1)) {
    int i = int(x);
    double f = x - i;
    return double(nTable_[size_t(i)]) + f * double(nTable_[size_t(i) + 1] - nTable_[size_t(i)]);
  }
  return double(ior_->n(float(lambdaNm)));
}

double RealMla::flatZ() const { return s_ > 0 ? zv_ - g_.thicknessMm : zv_ + g_.thicknessMm; }
double RealMla::rearNodalZ() const { return g_.thicknessMm * (nRef_ - 1.0) / nRef_; }
double RealMla::focalLength(double lambdaNm) const { return R_ / (n(lambdaNm) - 1.0); }
double RealMla::frontFocalZ(double lambdaNm) const {
  const double f = focalLength(lambdaNm), nn = n(lambdaNm);
  return s_ > 0 ? flatZ() - (f - g_.thicknessMm / nn) : zv_ - f;
}
double RealMla::rearFocalZ(double lambdaNm) const {
  const double f = focalLength(lambdaNm), nn = n(lambdaNm);
  return s_ > 0 ? zv_ + f : flatZ() + (f - g_.thicknessMm / nn);
}

double RealMla::capSag(double r) const {
  const double c = 1.0 / R_;
  const double x = K1_ * c * c * r * r;
  if (x >= 1.0) return K1_ > 0.0 ? R_ / K1_ : kInf;
  return c * r * r / (1.0 + std::sqrt(1.0 - x));
}

void RealMla::centreOf(int k, int l, double& cx, double& cy) const {
  if (!hex_) {
    cx = g_.originXMm + k * g_.pitchMm;
    cy = g_.originYMm - l * g_.pitchMm;
  } else {
    cx = g_.originXMm + (k + 0.5 * (l & 1)) * g_.pitchMm;
    cy = g_.originYMm - l * rowH_;
  }
}

Point3d RealMla::lensletCentre(int k, int l) const {
  double cx, cy;
  centreOf(k, l, cx, cy);
  return {cx, cy, 0.0};
}

void RealMla::cellAt(double x, double y, int& k, int& l) const {
  const double P = g_.pitchMm;
  if (!hex_) {
    k = int(std::floor((x - g_.originXMm) / P + 0.5));
    l = int(std::floor((g_.originYMm - y) / P + 0.5));
    return;
  }
  const int l0 = int(std::floor((g_.originYMm - y) / rowH_ + 0.5));
  double best = kInf;
  for (int li = l0 - 1; li <= l0 + 1; ++li) {
    int ki = int(std::floor((x - g_.originXMm) / P - 0.5 * (li & 1) + 0.5));
    double cx, cy;
    centreOf(ki, li, cx, cy);
    double d2 = (x - cx) * (x - cx) + (y - cy) * (y - cy);
    if (d2 < best) best = d2, k = ki, l = li;
  }
}

bool RealMla::lensletCell(double x, double y, LensletCell& out) const {
  if (!std::isfinite(x) || !std::isfinite(y)) return false;
  cellAt(x, y, out.k, out.l);
  centreOf(out.k, out.l, out.cx, out.cy);
  out.pitch = g_.pitchMm;
  out.n = nCellEdges_;
  for (int i = 0; i < nCellEdges_; ++i) {
    out.nx[size_t(i)] = cellEdges_[size_t(i)].nx;
    out.ny[size_t(i)] = cellEdges_[size_t(i)].ny;
    out.h[size_t(i)] = cellEdges_[size_t(i)].h;
  }
  return true;
}

namespace {
// Depth below the front plane of the caps' junction at radius r from a lenslet's axis.
double junctionDepth(double sag, double frontZ, double zv, double s, double nRef) {
  if (s > 0) return frontZ - (zv - sag);    // caps toward the viewer: in air
  return (frontZ - (zv + sag)) / nRef;      // caps toward the panel: in glass (reduced)
}
}  // namespace

double RealMla::cellDepth() const {
  // Where the caps meet at the middle of a cell edge (the apothem P/2, or the aperture's edge
  // when the caps stop short of it).
  return junctionDepth(capSag(std::min(0.5 * g_.pitchMm, rMax_)), frontZ_, zv_, s_, nRef_);
}

double RealMla::cellBorderDepth(const LensletCell& c, int e, double x, double y) const {
  if (e < 0 || e >= c.n) return cellDepth();
  // The point of edge e nearest (x, y), clamped to the edge's length (half of it: P/2 for a
  // square, P / (2 sqrt 3) for a hexagon, on either side of the edge's middle).
  const double nx = c.nx[size_t(e)], ny = c.ny[size_t(e)], h = c.h[size_t(e)];
  const double px = x - c.cx, py = y - c.cy;
  const double along = -ny * px + nx * py;  // along the edge, from its middle
  const double halfLen = hex_ ? g_.pitchMm / (2.0 * std::sqrt(3.0)) : 0.5 * g_.pitchMm;
  const double t = std::clamp(along, -halfLen, halfLen);
  const double r = std::min(std::sqrt(h * h + t * t), rMax_);
  return junctionDepth(capSag(r), frontZ_, zv_, s_, nRef_);
}

std::vector<std::array<double, 2>> RealMla::apertureOutline() const { return outline_; }

bool RealMla::inClearAperture(double lx, double ly) const {
  for (int i = 0; i < nCellEdges_; ++i) {
    const Edge& e = cellEdges_[size_t(i)];
    if (lx * e.nx + ly * e.ny > e.h) return false;
  }
  return !hasLand_ || insideAperture(lx, ly, 0.0);
}

bool RealMla::insideAperture(double lx, double ly, double tol) const {
  if (circle_) {
    const double r = std::sqrt(apR2_) + tol;
    return lx * lx + ly * ly <= r * r;
  }
  for (int i = 0; i < nApEdges_; ++i) {
    const Edge& e = apEdges_[size_t(i)];
    if (lx * e.nx + ly * e.ny > e.h + tol) return false;
  }
  return true;
}

bool RealMla::insideC(const Vec3d& q) const {
  if (!(q.z >= 0.0 && q.z <= g_.thicknessMm)) return false;
  if (q.x < boxX0_ || q.x > boxX1_ || q.y < boxY0_ || q.y > boxY1_) return false;
  if (q.z >= sMax_) return true;
  int k, l;
  cellAt(q.x, q.y, k, l);
  double cx, cy;
  centreOf(k, l, cx, cy);
  const double lx = q.x - cx, ly = q.y - cy;
  if (hasLand_ && !insideAperture(lx, ly, 0.0)) return false;
  return q.z >= capSag(std::sqrt(lx * lx + ly * ly));
}

bool RealMla::insideMaterial(const Point3d& p) const { return insideC(toC(p)); }

bool RealMla::boxInterval(const Vec3d& o, const Vec3d& d, double& t0, double& t1) const {
  t0 = -kInf, t1 = kInf;
  auto axis = [&](double oc, double dc, double lo, double hi) {
    if (dc == 0.0) return oc >= lo && oc <= hi;
    double a = (lo - oc) / dc, b = (hi - oc) / dc;
    if (a > b) std::swap(a, b);
    t0 = std::max(t0, a), t1 = std::min(t1, b);
    return t0 <= t1;
  };
  return axis(o.x, d.x, boxX0_, boxX1_) && axis(o.y, d.y, boxY0_, boxY1_);
}

bool RealMla::cellHit(const Vec3d& o, const Vec3d& d, int k, int l, double t0, double t1, bool entering,
                      Hit& h) const {
  double cx, cy;
  centreOf(k, l, cx, cy);
  const double px = o.x - cx, py = o.y - cy, pu = o.z;
  const double lo = std::max(t0 - kEps, kTMin);
  double best = t1 + kEps;
  bool found = false;

  // Cap: G(u, r) = 2 R u - r^2 - (1 + kappa) u^2 > 0 inside the material. Along the ray
  // G(t) = a t^2 + b t + c; the root where G increases (G' = +sqrt(D)) enters the material,
  // the other leaves it.
  {
    const double a = -(d.x * d.x + d.y * d.y) - K1_ * d.z * d.z;
    const double b = 2.0 * (R_ * d.z - px * d.x - py * d.y - K1_ * pu * d.z);
    const double c = 2.0 * R_ * pu - px * px - py * py - K1_ * pu * pu;
    double t = kInf;
    if (a != 0.0) {
      const double D = b * b - 4.0 * a * c;
      if (D >= 0.0) {
        const double sq = std::sqrt(D);
        const double q = -0.5 * (b + (b >= 0.0 ? sq : -sq));
        const double tq = q / a;
        const double tc = q != 0.0 ? c / q : tq;
        // b >= 0: tq leaves, tc enters; b < 0: tq enters, tc leaves.
        t = (entering == (b >= 0.0)) ? tc : tq;
      }
    } else if (b != 0.0 && ((b > 0.0) == entering)) {
      t = -c / b;
    }
    if (t >= lo && t <= best) {
      const double lx = px + t * d.x, ly = py + t * d.y;
      if (!hasLand_ || insideAperture(lx, ly, kEps)) {
        const double u = pu + t * d.z;
        Vec3d n(lx, ly, -(R_ - K1_ * u));
        const double len = std::sqrt(n.x * n.x + n.y * n.y + n.z * n.z);
        if (len > 0.0) {
          best = t;
          found = true;
          h.t = t;
          h.n = n / len;
          h.surface = MlaTraceEvent::Surface::Cap;
        }
      }
    }
  }
  if (hasLand_) {
    // Land: the plane u = s_max outside A; the material lies at u > s_max.
    if (d.z != 0.0 && ((d.z > 0.0) == entering)) {
      const double t = (sMax_ - pu) / d.z;
      if (t >= lo && t <= best) {
        const double lx = px + t * d.x, ly = py + t * d.y;
        if (!insideAperture(lx, ly, -kEps)) {
          best = t;
          found = true;
          h.t = t;
          h.n = Vec3d(0.0, 0.0, -1.0);
          h.surface = MlaTraceEvent::Surface::Land;
        }
      }
    }
    // Walls: A's edges inside the cell, between the cap edge and the land.
    for (int i = 0; i < nApEdges_; ++i) {
      const Edge& e = apEdges_[size_t(i)];
      const double dn = d.x * e.nx + d.y * e.ny;
      if (dn == 0.0 || ((dn < 0.0) != entering)) continue;
      const double t = (e.h - (px * e.nx + py * e.ny)) / dn;
      if (!(t >= lo && t <= best)) continue;
      const double lx = px + t * d.x, ly = py + t * d.y, u = pu + t * d.z;
      if (!insideAperture(lx, ly, kEps)) continue;
      if (u > sMax_ + kEps || u < capSag(std::sqrt(lx * lx + ly * ly)) - kEps) continue;
      best = t;
      found = true;
      h.t = t;
      h.n = Vec3d(e.nx, e.ny, 0.0);
      h.surface = MlaTraceEvent::Surface::Wall;
    }
  }
  if (found) h.k = k, h.l = l;
  return found;
}

bool RealMla::structuredHit(const Vec3d& o, const Vec3d& d, double tA, double tB, bool entering, Hit& h) const {
  // [tA, tB] is already clipped to the array's box by the caller.
  // The slab 0 <= u <= s_max that holds the caps, land and walls.
  double s0, s1;
  if (d.z != 0.0) {
    s0 = (0.0 - o.z) / d.z;
    s1 = (sMax_ - o.z) / d.z;
    if (s0 > s1) std::swap(s0, s1);
  } else {
    if (o.z < -kEps || o.z > sMax_ + kEps) return false;
    s0 = -kInf, s1 = kInf;
  }
  const double t0 = std::max(tA, s0 - kEps), t1 = std::min(tB, s1 + kEps);
  if (!(t0 <= t1)) return false;

  int k, l;
  cellAt(o.x + t0 * d.x, o.y + t0 * d.y, k, l);
  double tc = t0;
  for (int step = 0; step < maxSteps_; ++step) {
    double cx, cy;
    centreOf(k, l, cx, cy);
    const double px = o.x - cx, py = o.y - cy;
    double tExit = kInf;
    int edge = -1;
    for (int i = 0; i < nCellEdges_; ++i) {
      const Edge& e = cellEdges_[size_t(i)];
      const double dn = d.x * e.nx + d.y * e.ny;
      if (dn > 0.0) {
        const double te = (e.h - (px * e.nx + py * e.ny)) / dn;
        if (te < tExit) tExit = te, edge = i;
      }
    }
    if (cellHit(o, d, k, l, tc, std::min(tExit, t1), entering, h)) return true;
    if (edge < 0 || tExit >= t1) return false;
    tc = std::max(tc, tExit);
    if (!hex_) {
      switch (edge) {
        case 0: ++k; break;
        case 1: --k; break;
        case 2: --l; break;
        default: ++l; break;
      }
    } else {
      const int par = l & 1;
      switch (edge) {
        case 0: ++k; break;
        case 3: --k; break;
        case 1: k += par, --l; break;      // up-right
        case 2: k += par - 1, --l; break;  // up-left
        case 4: k += par - 1, ++l; break;  // down-left
        default: k += par, ++l; break;     // down-right
      }
    }
  }
  return false;
}

int RealMla::nextHit(const Vec3d& o, const Vec3d& d, bool inGlass, Hit& h) const {
  const double T = g_.thicknessMm;
  double b0, b1;
  const bool boxHit = boxInterval(o, d, b0, b1) && b1 >= std::max(b0, 0.0);
  if (inGlass) {
    if (!boxHit) return 2;  // outside the plate's footprint: cannot happen but stay safe
    double tf = kInf;
    if (d.z > 0.0) tf = std::max((T - o.z) / d.z, 0.0);
    const double tEnd = std::min(tf, b1);
    if (structuredHit(o, d, std::max(kTMin, b0), tEnd, false, h)) return 1;
    if (tf <= b1) {
      h.t = tf;
      h.n = Vec3d(0.0, 0.0, 1.0);
      h.surface = MlaTraceEvent::Surface::Flat;
      h.k = h.l = 0;
      return 1;
    }
    return 2;  // reaches the plate's side
  }
  if (!boxHit) return 0;
  if (b0 > kTMin) {  // the ray meets the box's side: from outside the plate, or through it
    Vec3d q = o + b0 * d;
    q.x = std::clamp(q.x, boxX0_, boxX1_);
    q.y = std::clamp(q.y, boxY0_, boxY1_);
    if (insideC(q)) return 2;
  }
  if (o.z >= T) {
    if (d.z < 0.0) {
      const double tf = (T - o.z) / d.z;
      if (tf >= b0 - kEps && tf <= b1 + kEps && tf >= 0.0) {
        h.t = std::max(tf, kTMin);
        h.n = Vec3d(0.0, 0.0, 1.0);
        h.surface = MlaTraceEvent::Surface::Flat;
        h.k = h.l = 0;
        return 1;
      }
    }
    return 0;
  }
  return structuredHit(o, d, std::max(kTMin, b0), b1, true, h) ? 1 : 0;
}

bool RealMla::trace(const Point3d& o, const Vec3d& dIn, double lambdaNm, FresnelMode mode, Rng* rng, MlaExit& out,
                    MlaTraceLog* log) const {
  out = MlaExit{};
  if (!finite3(o) || !finite3(dIn) || !std::isfinite(lambdaNm)) return false;
  const double len = std::sqrt(dIn.x * dIn.x + dIn.y * dIn.y + dIn.z * dIn.z);
  if (!(len > 0.0)) return false;
  if (mode == FresnelMode::Stochastic && !rng) mode = FresnelMode::Weighted;
  const double nGlass = n(lambdaNm);
  const double alpha = opt_.absorptionPerMm;

  Vec3d p = toC(o), d = dirC(dIn / len);
  bool inGlass = insideC(p);
  double throughput = 1.0, path = 0.0;
  int capK = -1, capL = -1;
  bool entered = false;
  for (int ev = 0;; ++ev) {
    Hit h;
    const int r = nextHit(p, d, inGlass, h);
    if (r == 2) return false;
    if (r == 0) break;
    if (ev >= opt_.maxEvents) return false;
    if (inGlass) {
      path += h.t;
      if (alpha > 0.0) throughput *= std::exp(-alpha * h.t);
    }
    p += h.t * d;
    if (h.surface == MlaTraceEvent::Surface::Flat && (!entered || log)) cellAt(p.x, p.y, h.k, h.l);
    if (!entered) {
      entered = true;
      if (inRange(h.k, h.l)) out.entryK = h.k, out.entryL = h.l;
    }
    // Interface: normal on the incident side, indices.
    const Vec3d nf = inGlass ? -h.n : h.n;
    const double n1 = inGlass ? nGlass : 1.0, n2 = inGlass ? 1.0 : nGlass;
    const double cosi = std::clamp(-(d.x * nf.x + d.y * nf.y + d.z * nf.z), 0.0, 1.0);
    const double eta = n1 / n2;
    const double sin2t = eta * eta * std::max(0.0, 1.0 - cosi * cosi);
    const Vec3d dBefore = d;
    MlaTraceEvent::Action action;
    double R = 1.0;
    if (sin2t >= 1.0) {
      action = MlaTraceEvent::Action::Tir;
      ++out.tir;
    } else {
      const double cost = std::sqrt(1.0 - sin2t);
      R = fresnelR(cosi, cost, n1, n2);
      bool reflect = false;
      if (mode == FresnelMode::Stochastic) reflect = double(rng->uniform()) < R;
      else if (mode == FresnelMode::Weighted) throughput *= 1.0 - R;
      if (reflect) {
        action = MlaTraceEvent::Action::Reflect;
        ++out.reflections;
      } else {
        action = MlaTraceEvent::Action::Refract;
        Vec3d t = eta * d + (eta * cosi - cost) * nf;
        d = t / std::sqrt(t.x * t.x + t.y * t.y + t.z * t.z);
        inGlass = !inGlass;
        if (h.surface == MlaTraceEvent::Surface::Cap) capK = h.k, capL = h.l;
      }
    }
    if (action != MlaTraceEvent::Action::Refract) {
      const double dn = d.x * nf.x + d.y * nf.y + d.z * nf.z;
      d -= 2.0 * dn * nf;
      d /= std::sqrt(d.x * d.x + d.y * d.y + d.z * d.z);
    }
    ++out.events;
    if (log) {
      MlaTraceEvent e;
      e.surface = h.surface;
      e.action = action;
      e.k = h.k, e.l = h.l;
      e.p = fromC(p);
      e.dIn = dirC(dBefore);
      e.dOut = dirC(d);
      e.normal = dirC(h.n);
      e.nIn = n1;
      e.nOut = action == MlaTraceEvent::Action::Refract ? n2 : n1;
      e.reflectance = R;
      log->events.push_back(e);
    }
  }
  out.p = fromC(p);
  out.d = dirC(d);
  out.throughput = throughput;
  out.glassPathMm = path;
  if (inRange(capK, capL)) out.capK = capK, out.capL = capL;
  return true;
}

bool RealMla::traceToViewer(const Point3d& o, const Vec3d& d, double lambdaNm, Rng* rng, MlaExit& out,
                            MlaTraceLog* log) const {
  const FresnelMode mode = rng ? opt_.fresnel : FresnelMode::Weighted;
  if (!trace(o, d, lambdaNm, mode, rng, out, log)) return false;
  return out.d.z > 0.0;
}

bool RealMla::traceToPanel(const Ray& ray, float lambdaNm, FresnelMode mode, Rng* rng, PanelArrival& out) const {
  const Vec3d d(ray.d);
  if (!(d.z < 0.0)) return false;
  MlaExit ex;
  if (!trace(Point3d(ray.o), d, double(lambdaNm), mode, rng, ex)) return false;
  if (!(ex.d.z < 0.0)) return false;
  const double zp = -g_.gapMm;
  const double t = (zp - ex.p.z) / ex.d.z;
  if (!(t >= 0.0)) return false;
  out.p = Point3(float(ex.p.x + t * ex.d.x), float(ex.p.y + t * ex.d.y), float(zp));
  out.d = Vec3(ex.d);
  out.throughput = float(ex.throughput);
  out.lensletK = ex.capK;
  out.lensletL = ex.capL;
  return true;
}

}  // namespace inim
