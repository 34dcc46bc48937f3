#include "mla_optics/stack_tracer.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <vector>

#include "core/error.h"
#include "core/format.h"
#include "mla_optics/real_mla.h"
#include "spectral/dispersion.h"

namespace inim {

namespace {

constexpr double kSqrt3 = 1.7320508075688772;
constexpr double kEps = 1e-9;        // mm: a new ray starts this far along its direction
constexpr double kBisectTol = 1e-13;  // mm along the ray
constexpr double kNone = std::numeric_limits<double>::infinity();

struct Lattice {
  bool hex = false;
  double pitch = 1.0, ox = 0.0, oy = 0.0;
  // Centre of the cell holding (x, y): the nearest lattice point.
  void centre(double x, double y, double& cx, double& cy) const {
    cx = ox, cy = oy;
    if (!hex) {
      cx = ox + std::round((x - ox) / pitch) * pitch;
      cy = oy + std::round((y - oy) / pitch) * pitch;
      return;
    }
    const double rowH = pitch * kSqrt3 / 2.0;
    const double l0 = std::floor((y - oy) / rowH);
    double best = kNone;
    for (double l = l0; l <= l0 + 1.0; l += 1.0) {  // the two nearest rows hold the nearest point
      const double shift = std::fmod(std::fabs(l), 2.0) == 1.0 ? pitch / 2.0 : 0.0;
      const double px = ox + shift + std::round((x - ox - shift) / pitch) * pitch, py = oy + l * rowH;
      const double d2 = (px - x) * (px - x) + (py - y) * (py - y);
      if (d2 < best) best = d2, cx = px, cy = py;
    }
  }
};

Lattice latticeOf(const StackLayer& l, double originX, double originY) {
  return {l.lattice == Mla::Lattice::Hex, l.pitchMm, originX + l.offsetXMm, originY + l.offsetYMm};
}

// Unit normals of a cell's sides (square: 4, hex with vertical flats: 6); each side lies at
// half the pitch from the centre.
int cellSides(bool hex, std::array<Vec3d, 6>& n) {
  if (!hex) {
    n = {Vec3d(1, 0, 0), Vec3d(-1, 0, 0), Vec3d(0, 1, 0), Vec3d(0, -1, 0), Vec3d(0), Vec3d(0)};
    return 4;
  }
  for (int i = 0; i < 6; ++i) n[i] = Vec3d(std::cos(i * M_PI / 3.0), std::sin(i * M_PI / 3.0), 0.0);
  return 6;
}

// Is cell-local (x, y) inside a hole of `shape` and size `size` (square side, circle diameter,
// hex flat to flat with vertical flats)?
bool insideShape(Mla::Aperture shape, double size, double x, double y) {
  const double h = size / 2.0;
  switch (shape) {
    case Mla::Aperture::Circle: return x * x + y * y <= h * h;
    case Mla::Aperture::Square: return std::fabs(x) <= h && std::fabs(y) <= h;
    case Mla::Aperture::Hex: break;
  }
  std::array<Vec3d, 6> n;
  cellSides(true, n);
  for (const Vec3d& e : n)
    if (e.x * x + e.y * y > h) return false;
  return true;
}

double sagSlope(const StackSurface& s, double r) {
  const double c = s.curvature();
  const double q = 1.0 - (1.0 + s.conic) * c * c * r * r;
  double slope = q > 0.0 ? c * r / std::sqrt(q) : 0.0;
  double rp = r * r * r;
  for (size_t i = 0; i < s.asphereMm.size(); ++i) slope += s.asphereMm[i] * double(2 * i + 4) * rp, rp *= r * r;
  return slope;
}

Vec3d reflectDir(const Vec3d& d, const Vec3d& n) { return d - 2.0 * glm::dot(d, n) * n; }

// The root of f in [a, c] (f(a), f(c) of opposite signs) to kBisectTol: the Illinois variant of
// regula falsi (superlinear on the smooth caps), with a bisection whenever it stalls.
template <class F>
double refineRoot(const F& f, double a, double fa, double c, double fc) {
  int side = 0;
  double last = a;
  for (int i = 0; i < 200 && c - a > kBisectTol; ++i) {
    double m = (fa * c - fc * a) / (fa - fc);
    if (!(m > a && m < c) || i % 8 == 7) m = 0.5 * (a + c);
    if (std::fabs(m - last) <= kBisectTol) return m;  // converged from one side
    last = m;
    const double fm = f(m);
    if ((fm <= 0.0) == (fa <= 0.0)) {
      a = m, fa = fm;
      if (side == -1) fc *= 0.5;
      side = -1;
    } else {
      c = m, fc = fm;
      if (side == 1) fa *= 0.5;
      side = 1;
    }
    if (fm == 0.0) return m;
  }
  return 0.5 * (a + c);
}

// The first root of f in [a, c] that `accept` takes: steps of max(minStep, |f| / lipschitz), a step
// that cannot pass a root, each change of sign refined.
template <class F, class Accept>
bool marchToRoot(const F& f, double a, double c, double minStep, double lipschitz, const Accept& accept, double& t) {
  double fa = f(a);
  while (a < c) {
    const double m = std::min(a + std::max(minStep, std::fabs(fa) / lipschitz), c), fm = f(m);
    if ((fa <= 0.0) != (fm <= 0.0)) {
      t = refineRoot(f, a, fa, m, fm);
      if (accept(t)) return true;
    }
    a = m, fa = fm;
  }
  return false;
}

// A walled surface (f jumps where the ray crosses an aperture's edge): march between the
// crossings `cuts` (sorted) over [a, end]; at each, a change of sign across it is a hit on the
// wall there, its normal in *wallNormal.
template <class F, class March, class Cuts>
bool marchBetweenCuts(const F& f, const March& march, const Cuts& cuts, double a, double end, double& t, Vec3d* wallNormal) {
  for (const auto& cut : cuts) {
    const double before = std::max(a, cut.t - 1e-10);
    if (march(a, before)) return true;
    const double fl = f(before), fr = f(std::min(cut.t + 1e-10, end));
    if ((fl <= 0.0) != (fr <= 0.0)) {
      t = cut.t;
      if (wallNormal && std::fabs(fl - fr) > 1e-9) *wallNormal = cut.normal;
      return true;
    }
    a = std::min(cut.t + 1e-10, end);
  }
  return march(a, end);
}

}  // namespace

struct StackTracer::Boundary {
  double z = 0.0;                 // the plane (a surface's vertex plane)
  // Curved stacks: the frame the boundary is flat in (curved_frame.h; null: the world's, z the
  // world's z), the physical length per unit of its X and Y, and the Lipschitz factor of its
  // height field along a unit ray (the map's largest stretch over the slab).
  const CurvedFrame* frame = nullptr;
  double scaleX = 1.0, scaleY = 1.0, stretch = 1.0;
  std::optional<StackSurface> surface;  // none: the plane itself
  Lattice lattice;
  double rClamp = 0.0;            // the clear aperture's radius: flat land beyond it
  double zMin = 0.0, zMax = 0.0;  // the slab the surface fills
  double maxSlope = 0.0;          // largest |dz/dr| over the aperture: the height field's Lipschitz bound
  // A clear aperture of the cell's shape but smaller (square on a square lattice, hex on a hex
  // one): the cap inside it, flat land at the cap's corner height outside, vertical walls between.
  bool walled = false;
  Mla::Aperture apertureShape = Mla::Aperture::Square;
  double apertureMm = 0.0;
  // An aperture sheet of no thickness lies on this boundary: rays pass only through its holes.
  bool masked = false;
  Lattice maskLattice;
  Mla::Aperture hole = Mla::Aperture::Circle;
  double holeMm = 0.0;
};

struct StackTracer::Region {
  std::vector<float> nTable;      // n at 300, 301, ..., 1000 nm; empty: air
  enum class Kind { Open, Sheet, Walls } kind = Kind::Open;
  Lattice lattice;                // sheets and walls
  Mla::Aperture hole = Mla::Aperture::Circle;
  double holeMm = 0.0;
  double openHalf = 0.0;          // walls: half the open width of a cell
  double reflectance = 0.0;       // walls
  const CurvedFrame* frame = nullptr;  // sheets of a curved stack: their frame and scale
  double scaleX = 1.0, scaleY = 1.0;
};

StackTracer::StackTracer(const OpticalStack& s, FresnelMode fresnel, double originX, double originY)
    : fresnel_(fresnel), array_(std::make_unique<CurvedFrame>(s.arrayFrame())), panel_(std::make_unique<CurvedFrame>(s.panelFrame())) {
  const MaterialCatalog& catalog = MaterialCatalog::standard();
  Boundary panel;  // z = 0: the panel emits into the first layer
  if (!panel_->flat()) panel.frame = panel_.get();
  boundaries_.push_back(panel);
  for (size_t i = 0; i < s.layers.size(); ++i) {
    const StackLayer& l = s.layers[i];
    const double z0 = s.layerBackZ(i), z1 = s.layerBackZ(i + 1);
    Region r;
    if (!l.material.empty()) {
      const IorPtr ior = catalog.dielectric(l.material);
      for (int nm = 300; nm <= 1000; ++nm) r.nTable.push_back(ior->n(float(nm)));
    }
    if (l.kind == StackLayer::Kind::LensArray && i > 0 && s.layers[i - 1].kind == StackLayer::Kind::LensArray &&
        (boundaries_.back().surface || !l.back.isPlane())) {
      // In contact with the lens array before it, a curved face between them: the air they
      // enclose (no thickness where the vertices touch) is a region of its own.
      regions_.push_back(Region{});
      Boundary air;
      air.z = z0;
      boundaries_.push_back(air);
    }
    if (l.kind == StackLayer::Kind::LensArray) {
      Boundary& back = boundaries_.back();
      if (!l.back.isPlane()) back.surface = l.back;
      back.lattice = latticeOf(l, originX, originY);
      back.rClamp = l.apertureRadiusMm();
      // Walls where the clear aperture is not the whole cell: smaller, or a square on a hex cell.
      const bool cellShaped = (l.aperture == Mla::Aperture::Hex) == (l.lattice == Mla::Lattice::Hex);
      const bool walls = l.aperture != Mla::Aperture::Circle && (!cellShaped || l.apertureMm < l.pitchMm * (1.0 - 1e-12));
      back.walled = walls && !l.back.isPlane();
      back.apertureShape = l.aperture, back.apertureMm = l.apertureMm;
      Boundary front;
      front.z = z1;
      if (!l.front.isPlane()) front.surface = l.front;
      front.lattice = back.lattice;
      front.rClamp = back.rClamp;
      front.walled = walls && !l.front.isPlane();
      front.apertureShape = l.aperture, front.apertureMm = l.apertureMm;
      boundaries_.push_back(front);
    } else {
      Boundary next;
      next.z = z1;
      boundaries_.push_back(next);
    }
    if (l.kind == StackLayer::Kind::Apertures) {
      if (z1 == z0) {  // a sheet of no thickness: a mask on the boundary, no region
        boundaries_.pop_back();
        Boundary& b = boundaries_.back();
        b.masked = true, b.maskLattice = latticeOf(l, originX, originY), b.hole = l.hole, b.holeMm = l.holeMm;
        continue;
      }
      r.kind = Region::Kind::Sheet, r.lattice = latticeOf(l, originX, originY), r.hole = l.hole, r.holeMm = l.holeMm;
    }
    if (l.kind == StackLayer::Kind::Barriers)
      r.kind = Region::Kind::Walls, r.lattice = latticeOf(l, originX, originY),
      r.openHalf = (l.pitchMm - l.wallMm) / 2.0, r.reflectance = l.reflectance;
    if (!array_->flat())
      r.frame = array_.get(), r.scaleX = array_->scaleX(0.5 * (z0 + z1)), r.scaleY = array_->scaleY(0.5 * (z0 + z1));
    boundaries_.back().z = z1;
    regions_.push_back(r);
  }
  for (size_t i = 1; i < boundaries_.size() && !array_->flat(); ++i) {
    Boundary& b = boundaries_[i];
    b.frame = array_.get(), b.scaleX = array_->scaleX(b.z), b.scaleY = array_->scaleY(b.z);
  }
  for (Boundary& b : boundaries_) {
    b.zMin = b.zMax = b.z;
    if (!b.surface) continue;
    for (int k = 0; k <= 1024; ++k) {  // the slab and the slope bound: extremes over the aperture
      const double r = b.rClamp * k / 1024.0, z = b.z + b.surface->sag(r).value_or(0.0);
      b.zMin = std::min(b.zMin, z), b.zMax = std::max(b.zMax, z);
      b.maxSlope = std::max(b.maxSlope, std::fabs(sagSlope(*b.surface, r)));
    }
    b.maxSlope *= 1.0 + 1e-6;  // sampled: a margin for the maximum between samples
  }
  top_ = boundaries_.back().z;
  front_ = std::max(top_, boundaries_.back().zMax);
  if (!array_->flat()) setCurvedExtent(s);
  outside_ = std::make_unique<Region>();
}

void StackTracer::setCurvedExtent(const OpticalStack& s) {
  const CurvedFrame& array = *array_;
  // The map's stretch: the lateral coordinates change at most 1 / (rho cos^2 theta) per mm along a
  // ray (theta the sphere's largest angle off the axis), against 1 / rho_b on the boundary's shell.
  const double R = std::fabs(array.radiusMm), margin = 2.0 * boundaries_.back().lattice.pitch;
  const double halfW = s.panelWidthMm / 2.0 + margin, halfH = s.panelHeightMm / 2.0 + margin;
  // The array ends two pitches beyond the panel (arc lengths on the reference shell; a stack
  // given without its panel's size: a quarter turn).
  extentX_ = s.panelWidthMm > 0.0 ? halfW : 0.5 * M_PI * R;
  extentY_ = s.panelHeightMm > 0.0 ? halfH : 0.5 * M_PI * R;
  double cos2 = 1.0;
  if (array.shape == CurvedFrame::Shape::Sphere) cos2 = std::max(std::pow(std::cos(std::hypot(halfW, halfH) / R), 2.0), 0.1);
  for (size_t i = 1; i < boundaries_.size(); ++i) {
    Boundary& b = boundaries_[i];
    const double rhoMin = std::min(array.shellRadius(b.zMin), array.shellRadius(b.zMax));
    b.stretch = array.shellRadius(b.z) / (rhoMin * cos2) * (1.0 + 1e-6);
  }
  // The highest world point: the front slab's top shell at the array's centre or its edges.
  const double w = boundaries_.back().zMax;
  top_ = front_ = -kNone;
  for (double x : {0.0, halfW})
    for (double y : {0.0, halfH}) front_ = std::max(front_, array.toWorld(x, y, w).z);
  top_ = front_ += 1e-9;
}

StackTracer::~StackTracer() = default;
StackTracer::StackTracer(StackTracer&&) noexcept = default;

double StackTracer::boundaryZ(const Boundary& b, double x, double y) const {
  if (!b.surface) return b.z;
  double cx, cy;
  b.lattice.centre(x, y, cx, cy);
  const double dx = b.scaleX * (x - cx), dy = b.scaleY * (y - cy);
  if (b.walled && !insideShape(b.apertureShape, b.apertureMm, dx, dy)) return b.z + b.surface->sag(b.rClamp).value_or(0.0);
  const double r = std::min(std::hypot(dx, dy), b.rClamp);
  return b.z + b.surface->sag(r).value_or(0.0);
}

double StackTracer::heightAbove(const Boundary& b, const Point3d& p) const {
  if (!b.frame) return p.z - boundaryZ(b, p.x, p.y);
  const Vec3d q = b.frame->toFrame(p);
  return q.z - boundaryZ(b, q.x, q.y);
}

Vec3d StackTracer::boundaryNormalAt(const Boundary& b, const Point3d& p) const {
  if (!b.frame) return boundaryNormal(b, p.x, p.y);
  const Vec3d up = b.frame->up(p);
  if (!b.surface) return up;
  // The gradient of the height above the surface, W - sag(r), r the scaled distance from the
  // cell's centre in (X, Y): grad W - sag'(r) / r (sx^2 dX grad X + sy^2 dY grad Y).
  const Vec3d q = b.frame->toFrame(p);
  double cx, cy;
  b.lattice.centre(q.x, q.y, cx, cy);
  const double dx = b.scaleX * (q.x - cx), dy = b.scaleY * (q.y - cy), r = std::hypot(dx, dy);
  if (r >= b.rClamp || r == 0.0) return up;
  if (b.walled && !insideShape(b.apertureShape, b.apertureMm, dx, dy)) return up;  // the land
  const double k = sagSlope(*b.surface, r) / r;
  return glm::normalize(up - k * (b.scaleX * dx * b.frame->gradX(p) + b.scaleY * dy * b.frame->gradY(p)));
}

Vec3d StackTracer::boundaryNormal(const Boundary& b, double x, double y) const {
  if (!b.surface) return {0.0, 0.0, 1.0};
  double cx, cy;
  b.lattice.centre(x, y, cx, cy);
  const double r = std::hypot(x - cx, y - cy);
  if (r >= b.rClamp || r == 0.0) return {0.0, 0.0, 1.0};
  if (b.walled && !insideShape(b.apertureShape, b.apertureMm, x - cx, y - cy)) return {0.0, 0.0, 1.0};  // the land
  const double slope = sagSlope(*b.surface, r);
  return glm::normalize(Vec3d(-slope * (x - cx) / r, -slope * (y - cy) / r, 1.0));
}

bool StackTracer::hitBoundary(const Boundary& b, const Point3d& o, const Vec3d& d, double tMax, double& t,
                              Vec3d* wallNormal) const {
  if (wallNormal) *wallNormal = Vec3d(0.0);
  if (b.frame) return hitCurvedBoundary(b, o, d, tMax, t, wallNormal);
  // The part of the ray inside the slab [zMin, zMax].
  double t0 = kEps, t1 = tMax;
  if (d.z != 0.0) {
    const double ta = (b.zMin - o.z) / d.z, tb = (b.zMax - o.z) / d.z;
    t0 = std::max(t0, std::min(ta, tb) - kEps), t1 = std::min(t1, std::max(ta, tb) + kEps);
  } else if (o.z < b.zMin || o.z > b.zMax) {
    return false;
  }
  if (!(t0 <= t1)) return false;
  if (!b.surface) {
    if (d.z == 0.0) return false;
    t = (b.z - o.z) / d.z;
    return t >= kEps && t <= tMax;
  }
  auto f = [&](double s) { return o.z + s * d.z - boundaryZ(b, o.x + s * d.x, o.y + s * d.y); };
  // March: |f(t)| / L is a distance along the ray within which f keeps its sign (f is Lipschitz
  // with L = |d.z| + maxSlope |d_xy|: the caps meet continuously at the cell borders), so such a
  // step cannot pass a root; the fixed step (1/128 of the pitch across, 1/16 of the slab's depth)
  // keeps the march moving where f is near zero.
  const double across = std::hypot(d.x, d.y), depth = std::max(b.zMax - b.zMin, 1e-12);
  const double lipschitz = std::fabs(d.z) + b.maxSlope * across;
  double minStep = kNone;
  if (across > 0.0) minStep = b.lattice.pitch / 128.0 / across;
  if (d.z != 0.0) minStep = std::min(minStep, depth / 16.0 / std::fabs(d.z));
  if (!std::isfinite(minStep)) return false;
  auto march = [&](double a, double c) { return marchToRoot(f, a, c, minStep, lipschitz, [](double) { return true; }, t); };
  if (!b.walled) return march(t0, t1);
  return marchBetweenCuts(f, march, wallCrossings(b, o, d, t0, t1), t0, t1, t, wallNormal);
}

bool StackTracer::hitCurvedBoundary(const Boundary& b, const Point3d& o, const Vec3d& d, double tMax, double& t,
                                    Vec3d* wallNormal) const {
  const CurvedFrame& fr = *b.frame;
  // W is |R| - rho: good to a few ulps of the radius, which a new ray must start beyond.
  const double R = std::fabs(fr.radiusMm), eps = kEps + 64.0 * (std::nextafter(R, kNone) - R);
  if (!b.surface) return fr.hitShell(o, d, b.z, eps, tMax, t, extentX_, extentY_);
  double lo[2], hi[2];
  const int parts = fr.band(o, d, b.zMin - eps, b.zMax + eps, eps, tMax, lo, hi);
  auto f = [&](double s) { return heightAbove(b, o + s * d); };
  // As the flat march, with the map's stretch in the Lipschitz bound and steps not scaled by the
  // ray's slope (it turns against the local axis along the way).
  const double lipschitz = 1.0 + b.maxSlope * b.stretch;
  const double minStep = std::min(b.lattice.pitch * b.scaleX / 128.0, std::max(b.zMax - b.zMin, 1e-12) / 16.0);
  auto onArray = [&](double s) {  // the array ends at its extent
    const Vec3d q = fr.toFrame(o + s * d);
    return std::fabs(q.x) <= extentX_ && std::fabs(q.y) <= extentY_;
  };
  auto march = [&](double a, double c) { return marchToRoot(f, a, c, minStep, lipschitz, onArray, t); };
  for (int i = 0; i < parts; ++i) {
    if (!b.walled) {
      if (march(lo[i], hi[i])) return true;
      continue;
    }
    // Walls, as flat: march between the ray's crossings of the aperture edges' planes.
    const std::vector<WallCrossing> cuts = b.apertureShape == Mla::Aperture::Hex ? apertureCrossings(b, o, d, lo[i], hi[i])
                                                                                 : curvedWallCrossings(b, o, d, lo[i], hi[i]);
    if (marchBetweenCuts(f, march, cuts, lo[i], hi[i], t, wallNormal)) return true;
  }
  return false;
}

// A curved array's square apertures: their edges lie on planes through the centre of curvature
// (constant X; a sphere's constant Y, a cylinder's y = Y), at the cells' centres' arc positions
// (square lattice: every P; hex: every P / 2 in X, every row in Y) plus or minus half the aperture
// (physical, so a / (2 scale) in arc length). Along a line the angles change monotonically.
std::vector<StackTracer::WallCrossing> StackTracer::curvedWallCrossings(const Boundary& b, const Point3d& o,
                                                                        const Vec3d& d, double t0, double t1) const {
  const CurvedFrame& fr = *b.frame;
  const double R = std::fabs(fr.radiusMm), sg = fr.sign();
  const Vec3d v0 = o - fr.centre();
  std::vector<WallCrossing> cuts;
  for (int axis = 0; axis < 2; ++axis) {
    const double spacing = axis == 0 ? (b.lattice.hex ? b.lattice.pitch / 2.0 : b.lattice.pitch)
                                     : (b.lattice.hex ? b.lattice.pitch * kSqrt3 / 2.0 : b.lattice.pitch);
    const double h = b.apertureMm / 2.0 / (axis == 0 ? b.scaleX : b.scaleY), base = axis == 0 ? b.lattice.ox : b.lattice.oy;
    const Vec3d qa = fr.toFrame(o + t0 * d), qb = fr.toFrame(o + t1 * d);
    const double ua = (axis == 0 ? qa.x : qa.y) - base, ub = (axis == 0 ? qb.x : qb.y) - base;
    const double lo = std::min(ua, ub), hi = std::max(ua, ub);
    const bool plane = axis == 0 || fr.shape == CurvedFrame::Shape::Sphere;
    for (double m = std::floor((lo - h) / spacing); m * spacing - h <= hi; m += 1.0)
      for (double side : {-1.0, 1.0}) {
        const double value = m * spacing + side * h;
        if (value < lo || value > hi) continue;
        Vec3d n;
        double t;
        if (plane) {  // the plane at angle value / R: n . v = 0
          const double a = (value + base) / R;
          n = axis == 0 ? Vec3d(std::cos(a), 0.0, sg * std::sin(a)) : Vec3d(0.0, std::cos(a), sg * std::sin(a));
          const double along = glm::dot(n, d);
          if (std::fabs(along) < 1e-15) continue;
          t = -glm::dot(n, v0) / along;
        } else {  // a cylinder's y = value + base
          n = Vec3d(0.0, 1.0, 0.0);
          if (std::fabs(d.y) < 1e-15) continue;
          t = (value + base - o.y) / d.y;
        }
        if (t >= t0 && t <= t1) cuts.push_back({t, side * n});
        if (cuts.size() > 4096) break;
      }
  }
  std::sort(cuts.begin(), cuts.end(), [](const WallCrossing& x, const WallCrossing& y) { return x.t < y.t; });
  return cuts;
}

// Aperture edges on no lattice of lines or planes (a hex aperture on a square lattice; a curved
// array's hex apertures): where the ray's point crosses into or out of its cell's aperture, found
// by stepping 1/256 of the pitch and bisecting each change to 1e-13 mm (a corner cut within one
// step is missed); the wall's normal is the gradient of the aperture side it crossed.
std::vector<StackTracer::WallCrossing> StackTracer::apertureCrossings(const Boundary& b, const Point3d& o, const Vec3d& d,
                                                                      double t0, double t1) const {
  std::array<Vec3d, 6> sides;
  const int count = cellSides(b.apertureShape == Mla::Aperture::Hex, sides);
  auto local = [&](double s, double& x, double& y) {
    const Point3d p = o + s * d;
    const Vec3d q = b.frame ? b.frame->toFrame(p) : Vec3d(p);
    double cx, cy;
    b.lattice.centre(q.x, q.y, cx, cy);
    x = b.scaleX * (q.x - cx), y = b.scaleY * (q.y - cy);
  };
  auto inside = [&](double s) {
    double x, y;
    local(s, x, y);
    return insideShape(b.apertureShape, b.apertureMm, x, y);
  };
  std::vector<WallCrossing> cuts;
  const double step = b.lattice.pitch * b.scaleX / 256.0;
  bool in = inside(t0);
  for (double a = t0; a < t1 && cuts.size() < 4096;) {
    const double c = std::min(a + step, t1);
    if (inside(c) == in) {
      a = c;
      continue;
    }
    double lo = a, hi = c;
    while (hi - lo > kBisectTol) (inside(0.5 * (lo + hi)) == in ? lo : hi) = 0.5 * (lo + hi);
    const double t = 0.5 * (lo + hi);
    double x, y;
    local(in ? lo : hi, x, y);  // the side of the aperture at the crossing, from its inside
    int side = 0;
    for (int i = 1; i < count; ++i)
      if (sides[i].x * x + sides[i].y * y > sides[side].x * x + sides[side].y * y) side = i;
    const Point3d p = o + t * d;
    const Vec3d n = b.frame ? sides[side].x * b.frame->gradX(p) + sides[side].y * b.frame->gradY(p) : sides[side];
    cuts.push_back({t, glm::normalize(n)});
    in = !in, a = c;
  }
  return cuts;
}

std::vector<StackTracer::WallCrossing> StackTracer::wallCrossings(const Boundary& b, const Point3d& o, const Vec3d& d,
                                                                  double t0, double t1) const {
  if (b.apertureShape == Mla::Aperture::Hex && !b.lattice.hex) return apertureCrossings(b, o, d, t0, t1);
  // The lines of every aperture edge: for each side normal e of the aperture's shape, the cells'
  // centres project onto e on a 1D lattice of spacing s (a square lattice onto its axes: P; a hex
  // lattice onto its cells' normals: P / 2, onto y: its rows' P sqrt(3) / 2), and the edges lie
  // at h = a / 2 either side of each; a crossing that is on no aperture's edge only splits the
  // march.
  std::array<Vec3d, 6> sides;
  const bool hexAperture = b.apertureShape == Mla::Aperture::Hex;
  const int count = cellSides(hexAperture, sides);
  const double h = b.apertureMm / 2.0;
  std::vector<WallCrossing> cuts;
  for (int i = 0; i < count; i += (hexAperture ? 1 : 2)) {  // e and -e give the same lines
    const Vec3d& e = sides[i];
    const double s = !b.lattice.hex ? b.lattice.pitch : std::fabs(e.x) < 1e-12 ? b.lattice.pitch * kSqrt3 / 2.0
                                                                                 : b.lattice.pitch / 2.0;
    const double du = e.x * d.x + e.y * d.y;
    if (std::fabs(du) < 1e-15) continue;
    const double base = e.x * b.lattice.ox + e.y * b.lattice.oy;
    const double ua = e.x * (o.x + t0 * d.x) + e.y * (o.y + t0 * d.y) - base, ub = ua + du * (t1 - t0);
    const double lo = std::min(ua, ub), hi = std::max(ua, ub);
    for (double m = std::floor((lo - h) / s); m * s - h <= hi; m += 1.0)
      for (double side : {-1.0, 1.0}) {
        const double v = m * s + side * h;
        if (v < lo || v > hi) continue;
        cuts.push_back({t0 + (v - ua) / du, side * e});
        if (cuts.size() > 4096) break;  // a grazing ray over very many cells: the rest unsplit
      }
  }
  std::sort(cuts.begin(), cuts.end(), [](const WallCrossing& x, const WallCrossing& y) { return x.t < y.t; });
  return cuts;
}

bool StackTracer::hitWall(const Region& r, const Point3d& o, const Vec3d& d, double tMax, double& t, Vec3d& n) const {
  if (r.frame) return hitCurvedWall(r, o, d, tMax, t, n);
  double cx, cy;
  r.lattice.centre(o.x, o.y, cx, cy);
  std::array<Vec3d, 6> sides;
  const int count = cellSides(r.lattice.hex, sides);
  t = kNone;
  for (int i = 0; i < count; ++i) {
    const double along = sides[i].x * d.x + sides[i].y * d.y;
    if (along <= 0.0) continue;
    const double at = (r.openHalf - (sides[i].x * (o.x - cx) + sides[i].y * (o.y - cy))) / along;
    if (at < t) t = std::max(at, 0.0), n = -sides[i];
  }
  return t <= tMax;
}

// A curved square lattice's cell borders are planes through the centre of curvature: X = |R| a
// is the plane v.x cos a + s v.z sin a = 0 (v = p - C), a sphere's Y likewise in y, a cylinder's Y
// the plane y = Y. The walls' faces lie openHalf (arc length) either side of the cell's centre.
bool StackTracer::hitCurvedWall(const Region& r, const Point3d& o, const Vec3d& d, double tMax, double& t,
                                Vec3d& n) const {
  const CurvedFrame& fr = *r.frame;
  const Vec3d q = fr.toFrame(o + 1e-9 * d), v = o - fr.centre();  // the cell ahead: o may lie on a wall
  double cx, cy;
  r.lattice.centre(q.x, q.y, cx, cy);
  if (r.lattice.hex) return hitCurvedHexWall(r, o, d, tMax, cx, cy, t, n);
  const double R = std::fabs(fr.radiusMm), s = fr.sign();
  t = kNone;
  auto face = [&](const Vec3d& normal, double offset, double inward) {  // inside: inward (N.v + offset) > 0
    const double g = inward * (glm::dot(normal, v) + offset), along = -inward * glm::dot(normal, d);
    if (along <= 0.0) return;
    const double at = g / along;
    if (at < t) t = std::max(at, 0.0), n = inward * normal;
  };
  for (double side : {-1.0, 1.0}) {
    const double a = (cx + side * r.openHalf) / R;
    face(Vec3d(std::cos(a), 0.0, s * std::sin(a)), 0.0, -side);
    if (fr.shape == CurvedFrame::Shape::Sphere) {
      const double b = (cy + side * r.openHalf) / R;
      face(Vec3d(0.0, std::cos(b), s * std::sin(b)), 0.0, -side);
    } else {
      face(Vec3d(0.0, 1.0, 0.0), -(cy + side * r.openHalf), -side);
    }
  }
  return t <= tMax;
}

// A hex cell's borders in the arc coordinates are no planes: march to where the ray leaves the
// cell's open hexagon, g(t) = max_i e_i . (X - cx, Y - cy) - openHalf turning positive (g changes
// at most `stretch` per mm along the ray, the map's bound), then refine; the wall's normal is the
// gradient of the side it crossed.
bool StackTracer::hitCurvedHexWall(const Region& r, const Point3d& o, const Vec3d& d, double tMax, double cx, double cy,
                                   double& t, Vec3d& n) const {
  const CurvedFrame& fr = *r.frame;
  std::array<Vec3d, 6> sides;
  cellSides(true, sides);
  int side = 0;
  auto g = [&](double s) {
    const Vec3d q = fr.toFrame(o + s * d);
    double best = -kNone;
    for (int i = 0; i < 6; ++i)
      if (const double e = sides[i].x * (q.x - cx) + sides[i].y * (q.y - cy); e > best) best = e, side = i;
    return best - r.openHalf;
  };
  const double stretch = 2.0, minStep = r.lattice.pitch / 256.0;
  const double tEnd = std::min(tMax, 1e3);
  double a = 0.0, ga = g(a);
  if (ga > 0.0) ga = -1e-15;  // on a wall, leaving it: inside
  while (a < tEnd) {
    const double m = std::min(a + std::max(minStep, -ga / stretch), tEnd), gm = g(m);
    if (gm > 0.0) {
      t = refineRoot(g, a, ga, m, gm);
      g(t + 1e-12);  // the side crossed
      const Point3d p = o + t * d;
      n = -glm::normalize(sides[side].x * fr.gradX(p) + sides[side].y * fr.gradY(p));  // into the cell
      return true;
    }
    a = m, ga = gm;
  }
  return false;
}

bool StackTracer::passesSheet(const Region& r, const Point3d& a0, const Point3d& b0) const {
  const Vec3d a = r.frame ? r.frame->toFrame(a0) : Vec3d(a0), b = r.frame ? r.frame->toFrame(b0) : Vec3d(b0);
  double ax, ay, bx, by;
  r.lattice.centre(a.x, a.y, ax, ay);
  r.lattice.centre(b.x, b.y, bx, by);
  return ax == bx && ay == by && insideShape(r.hole, r.holeMm, r.scaleX * (a.x - ax), r.scaleY * (a.y - ay)) &&
         insideShape(r.hole, r.holeMm, r.scaleX * (b.x - bx), r.scaleY * (b.y - by));
}

// n(lambda) by linear interpolation in the 1 nm table, as real_mla.h does.
double StackTracer::index(const Region& r, double lambdaNm) const {
  if (r.nTable.empty()) return 1.0;
  const double x = std::clamp(lambdaNm - 300.0, 0.0, double(r.nTable.size() - 1));
  const size_t i = std::min(size_t(x), r.nTable.size() - 2);
  const double f = x - double(i);
  return double(r.nTable[i]) + f * double(r.nTable[i + 1] - r.nTable[i]);
}

bool StackTracer::trace(const Point3d& o0, const Vec3d& d0, double lambdaNm, FresnelMode fresnel, Rng* rng,
                        StackExit& out) const {
  Point3d p = o0;
  Vec3d d = d0;
  int region;
  if (!panel_->flat()) {
    // A curved panel: the ray starts on it (within 1e-6 mm), heading out of it.
    if (std::fabs(panel_->toFrame(p).z) <= 1e-6 && glm::dot(d, panel_->up(p)) > 0.0) region = 0;
    else if (p.z >= top_ && d.z < 0.0) region = int(regions_.size());
    else return false;
  } else if (p.z <= 0.0 && d.z > 0.0) {  // from the panel: it emits into the first layer
    p += d * (-p.z / d.z);
    region = 0;
  } else if (p.z >= top_ && d.z < 0.0) {
    region = int(regions_.size());  // outside, in front of the stack
  } else {
    return false;
  }
  out = StackExit{};
  Point3d entry = p;
  for (int events = 0; events < maxEvents_; ++events) {
    const bool outside = region == int(regions_.size());
    const Region& r = outside ? *outside_ : regions_[size_t(region)];
    const Boundary& lower = boundaries_[size_t(region)];
    double tLow = kNone, tUp = kNone, tWall = kNone, t;
    Vec3d wallN(0.0), lowCap(0.0), upCap(0.0);  // a lens array's wall between caps, when one is hit
    if (hitBoundary(lower, p, d, kNone, t, &lowCap)) tLow = t;
    if (!outside && hitBoundary(boundaries_[size_t(region) + 1], p, d, tLow, t, &upCap)) tUp = t;
    if (outside && !(tLow < kNone)) return false;  // leaving in front without meeting the stack
    if (r.kind == Region::Kind::Walls && hitWall(r, p, d, std::min(tLow, tUp), t, wallN)) tWall = t;
    const double tHit = std::min({tLow, tUp, tWall});
    if (!(tHit < kNone) && !array_->flat()) {
      // Around a curved stack's edge (its shells unbounded, the panel's plane below them, the
      // frame's half-space ending at the centre): the ray leaves the display there.
      out.p = p, out.d = d, out.towardViewer = false, out.aroundEdge = true;
      return true;
    }
    if (!(tHit < kNone)) return false;
    p += d * tHit;
    out.events = events + 1;
    if (tWall == tHit) {  // a barrier wall: absorbed, or reflected with its reflectance
      if (r.reflectance <= 0.0) return false;
      if (fresnel == FresnelMode::Stochastic) {
        if (!rng || rng->uniformDouble() >= r.reflectance) return false;
      } else {
        out.throughput *= r.reflectance;
      }
      d = reflectDir(d, wallN);
      continue;
    }
    const bool goingUp = tUp == tHit;
    const size_t bi = size_t(region) + (goingUp ? 1 : 0);
    const Boundary& b = boundaries_[bi];
    if (r.kind == Region::Kind::Sheet && !passesSheet(r, entry, p)) return false;
    if (b.masked) {
      const Vec3d q = b.frame ? b.frame->toFrame(p) : Vec3d(p);
      double cx, cy;
      b.maskLattice.centre(q.x, q.y, cx, cy);
      if (!insideShape(b.hole, b.holeMm, b.scaleX * (q.x - cx), b.scaleY * (q.y - cy))) return false;
    }
    const int next = goingUp ? region + 1 : region - 1;
    if (next < 0) {  // back through the panel plane
      out.p = p, out.d = d, out.towardViewer = false;
      return true;
    }
    const double n1 = index(r, lambdaNm), n2 = next < int(regions_.size()) ? index(regions_[size_t(next)], lambdaNm) : 1.0;
    const Vec3d& capWall = goingUp ? upCap : lowCap;
    Vec3d n = capWall != Vec3d(0.0) ? capWall : boundaryNormalAt(b, p);
    if (glm::dot(n, d) > 0.0) n = -n;  // facing the incoming ray
    const double cosi = -glm::dot(n, d), eta = n1 / n2, sin2t = eta * eta * (1.0 - cosi * cosi);
    const double refl = sin2t >= 1.0 ? 1.0 : fresnelReflectance(cosi, n1, n2);
    bool reflect = sin2t >= 1.0;
    if (!reflect && fresnel == FresnelMode::Stochastic && rng) reflect = rng->uniformDouble() < refl;
    if (!reflect && fresnel == FresnelMode::Weighted) out.throughput *= 1.0 - refl;
    if (reflect) {
      d = reflectDir(d, n);
      continue;
    }
    d = glm::normalize(eta * d + (eta * cosi - std::sqrt(1.0 - sin2t)) * n);
    if (b.surface) {
      const Vec3d q = b.frame ? b.frame->toFrame(p) : Vec3d(p);
      out.crossedLens = true, out.lensXMm = q.x, out.lensYMm = q.y;
    }
    region = next;
    entry = p;
    // Out in front, unless the ray meets the front surface again (a neighbouring cap that rises
    // above where it left): then on it goes, in through that cap.
    if (double again; region == int(regions_.size()) && !hitBoundary(boundaries_.back(), p, d, kNone, again)) {
      out.p = p, out.d = d, out.towardViewer = true;
      return true;
    }
  }
  out.trapped = true;
  return false;
}

}  // namespace inim
