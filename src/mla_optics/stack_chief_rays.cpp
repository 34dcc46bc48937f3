#include "mla_optics/stack_chief_rays.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <mutex>
#include <vector>

#include "core/error.h"
#include "core/format.h"
#include "core/parallel.h"
#include "core/progress.h"
#include "display/stack_first_order.h"
#include "mla_optics/stack_tracer.h"
#include "spectral/dispersion.h"

namespace inim {

namespace {

constexpr double kMissTolMm = 1e-10;

double panelIndex(const OpticalStack& s, double lambdaNm) {
  if (s.layers.empty() || s.layers[0].material.empty()) return 1.0;
  return MaterialCatalog::standard().dielectric(s.layers[0].material)->n(float(lambdaNm));
}

OpticalStack layersBelow(const OpticalStack& s, size_t count) {
  OpticalStack below = s;
  below.layers.resize(count);
  return below;
}

double angleDeg(const Vec3d& a, const Vec3d& b) {
  // acos loses precision near 1: the cross product's length with the dot product.
  const Vec3d x(a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x);
  return std::atan2(std::sqrt(x.x * x.x + x.y * x.y + x.z * x.z), a.x * b.x + a.y * b.y + a.z * b.z) * 180.0 / M_PI;
}

bool uniformLattice(const OpticalStack& s) {
  const StackLayer* first = nullptr;
  for (const StackLayer& l : s.layers) {
    if (!(l.pitchMm > 0.0)) continue;
    if (!first) first = &l;
    if (l.lattice != first->lattice || std::fabs(l.pitchMm - first->pitchMm) > 1e-12) return false;
  }
  return true;
}

// A pixel's display ray (display frame, origin on z = 0) from its chief ray, or the pinhole ray
// through its lens centre.
struct PixelRay {
  Point3d o{0.0};
  Vec3d d{0.0, 0.0, 1.0};
  bool real = false, crosstalk = false;
};

PixelRay pixelRay(const StackChiefRaySolver& solver, double gap, double px, double py, double cx, double cy,
                  bool pinholeOnly = false) {
  PixelRay r;
  Point3d p;
  Vec3d d;
  if (!pinholeOnly && solver.solve(px, py, cx, cy, p, d, &r.crosstalk) && d.z > 0.0) {
    r.d = d;
    r.o = p + ((gap - p.z) / d.z) * d;
    r.o.z = 0.0;
    r.real = true;
    return r;
  }
  if (solver.curved()) {  // through the lenslet's principal point, from the panel as built
    r.d = solver.pinholeDirection(px, py, cx, cy);
    const Point3d q = solver.panelPoint(px, py);
    r.o = q + ((gap - q.z) / r.d.z) * r.d;
    r.o.z = 0.0;
    return r;
  }
  const Vec3d v(cx - px, cy - py, gap);
  r.d = v / std::sqrt(v.x * v.x + v.y * v.y + v.z * v.z);
  r.o = Point3d(cx, cy, 0.0);
  return r;
}

// Chief rays against the pixel's offset from its lens centre, on a grid with step h over
// [-maxDx, maxDx] x [-maxDy, maxDy]: exit slopes and the origin's offset, interpolated
// bilinearly.
class ChiefRayTable {
 public:
  ChiefRayTable(const StackChiefRaySolver& solver, double gap, double cx, double cy, double maxDx, double maxDy, double h)
      : h_(h) {
    nx_ = int(std::ceil(maxDx / h)), ny_ = int(std::ceil(maxDy / h));
    const int w = 2 * nx_ + 1;
    e_.resize(size_t(w) * size_t(2 * ny_ + 1));
    parallelForRange(
        int64_t(e_.size()),
        [&](int64_t a, int64_t b) {
          for (int64_t idx = a; idx < b; ++idx) {
            const double dx = (int(idx % w) - nx_) * h, dy = (int(idx / w) - ny_) * h;
            const PixelRay r = pixelRay(solver, gap, cx + dx, cy + dy, cx, cy);
            Entry& e = e_[size_t(idx)];
            e.ok = r.real && !r.crosstalk;
            e.tx = r.d.x / r.d.z, e.ty = r.d.y / r.d.z, e.ox = r.o.x - cx, e.oy = r.o.y - cy;
          }
        },
        nullptr, 8);
  }

  // False outside the grid or next to an entry without a chief ray.
  bool lookup(double dx, double dy, PixelRay& r) const {
    const double u = dx / h_ + nx_, v = dy / h_ + ny_;
    const int i = int(std::floor(u)), j = int(std::floor(v));
    if (i < 0 || j < 0 || i >= 2 * nx_ || j >= 2 * ny_) return false;
    const double fu = u - i, fv = v - j;
    const Entry &a = at(i, j), &b = at(i + 1, j), &c = at(i, j + 1), &d = at(i + 1, j + 1);
    if (!(a.ok && b.ok && c.ok && d.ok)) return false;
    auto mix = [&](double Entry::*m) {
      return (1 - fv) * ((1 - fu) * a.*m + fu * b.*m) + fv * ((1 - fu) * c.*m + fu * d.*m);
    };
    const double tx = mix(&Entry::tx), ty = mix(&Entry::ty), inv = 1.0 / std::sqrt(1.0 + tx * tx + ty * ty);
    r.d = Vec3d(tx * inv, ty * inv, inv);
    r.o = Point3d(mix(&Entry::ox), mix(&Entry::oy), 0.0);  // relative to the lens centre
    r.real = true;
    return true;
  }

 private:
  struct Entry {
    double tx = 0, ty = 0, ox = 0, oy = 0;
    bool ok = false;
  };
  const Entry& at(int i, int j) const { return e_[size_t(j) * size_t(2 * nx_ + 1) + size_t(i)]; }
  double h_;
  int nx_ = 0, ny_ = 0;
  std::vector<Entry> e_;
};

// Damped Newton on the two launch slopes (tx, ty) until miss(tx, ty, mx, my) puts the stop
// crossing within kMissTolMm of the lenslet's axis (false when a trace fails or the Jacobian is
// singular); true when it ends within 100 kMissTolMm.
template <class Miss>
bool newtonOnSlopes(const Miss& miss, double& tx, double& ty) {
  double mx, my;
  if (!miss(tx, ty, mx, my)) return false;
  for (int it = 0; it < 40 && std::hypot(mx, my) > kMissTolMm; ++it) {
    const double h = 1e-7 * (1.0 + std::hypot(tx, ty));
    double ax, ay, bx, by;
    if (!miss(tx + h, ty, ax, ay) || !miss(tx, ty + h, bx, by)) return false;
    const double j11 = (ax - mx) / h, j21 = (ay - my) / h, j12 = (bx - mx) / h, j22 = (by - my) / h;
    const double det = j11 * j22 - j12 * j21;
    if (!(std::fabs(det) > 0.0)) return false;
    double sx = -(j22 * mx - j12 * my) / det, sy = -(-j21 * mx + j11 * my) / det;
    // Damped: halve the step until the miss shrinks.
    bool better = false;
    for (int half = 0; half < 30 && !better; ++half, sx *= 0.5, sy *= 0.5) {
      double nx, ny;
      if (miss(tx + sx, ty + sy, nx, ny) && std::hypot(nx, ny) < std::hypot(mx, my))
        tx += sx, ty += sy, mx = nx, my = ny, better = true;
    }
    if (!better) break;
  }
  return std::hypot(mx, my) <= kMissTolMm * 100.0;
}

}  // namespace

StackChiefRaySolver::StackChiefRaySolver(const OpticalStack& s, double originX, double originY, double wavelengthNm)
    : wavelengthNm_(wavelengthNm) {
  const std::optional<ApertureStop> stop = findApertureStop(s, wavelengthNm);
  if (!stop)
    throw InputError(s.file, "stack", "(no lens array, aperture sheet or barriers)",
                     "a stack with an aperture stop for its chief rays");
  stop_ = *stop;
  const size_t below = stop_.layer + (stop_.front ? 1 : 0);
  if (below > 0) below_ = std::make_unique<StackTracer>(layersBelow(s, below), FresnelMode::Off, originX, originY);
  whole_ = std::make_unique<StackTracer>(s, FresnelMode::Off, originX, originY);
  panelIndex_ = panelIndex(s, wavelengthNm);
  pitchMm_ = s.layers[stop_.layer].pitchMm;
  stopOffsetX_ = s.layers[stop_.layer].offsetXMm, stopOffsetY_ = s.layers[stop_.layer].offsetYMm;
  array_ = s.arrayFrame(), panel_ = s.panelFrame();
  principalZ_ = stackFirstOrder(s, wavelengthNm).frontPrincipalZMm;
}

Vec3d StackChiefRaySolver::pinholeDirection(double px, double py, double cx, double cy) const {
  return glm::normalize(array_.toWorld(cx, cy, principalZ_) - panel_.toWorld(px, py, 0.0));
}

bool StackChiefRaySolver::curvedMiss(const Aim& a, double tx, double ty, double& mx, double& my) const {
  Point3d q = a.p0;
  Vec3d d = a.dir(tx, ty);
  if (below_) {
    StackExit ex;
    if (!below_->trace(a.p0, d, wavelengthNm_, nullptr, ex) || !ex.towardViewer) return false;
    q = ex.p, d = ex.d;
  }
  double t;
  if (!array_.hitShell(q, d, stop_.zMm, -1e-3, 1e12, t)) return false;
  const Vec3d f = array_.toFrame(q + t * d);
  mx = array_.scaleX(stop_.zMm) * (f.x - a.cx), my = array_.scaleY(stop_.zMm) * (f.y - a.cy);
  return std::isfinite(mx) && std::isfinite(my);
}

// As the flat solve, in the lenslet's own axes: the first-order slopes from the pixel's offset
// across the axis, then Newton on the stop crossing's arc coordinates.
bool StackChiefRaySolver::solveCurved(double px, double py, double cx, double cy, Point3d& exitP, Vec3d& exitD,
                                      bool* crosstalk) const {
  Aim a;
  a.cx = cx + stopOffsetX_, a.cy = cy + stopOffsetY_;
  a.p0 = panel_.toWorld(px, py, 0.0);
  array_.axisFrame(a.cx, a.cy, a.axis, a.e1, a.e2);
  const Vec3d off = a.p0 - array_.toWorld(a.cx, a.cy, array_.zRefMm);
  double tx = -stop_.a * glm::dot(off, a.e1) / (stop_.b * panelIndex_);
  double ty = -stop_.a * glm::dot(off, a.e2) / (stop_.b * panelIndex_);
  auto miss = [&](double x, double y, double& mx, double& my) { return curvedMiss(a, x, y, mx, my); };
  if (!newtonOnSlopes(miss, tx, ty)) return false;
  StackExit ex;
  if (!whole_->trace(a.p0, a.dir(tx, ty), wavelengthNm_, nullptr, ex) || !ex.towardViewer) return false;
  exitP = ex.p, exitD = ex.d;
  if (crosstalk)
    *crosstalk = ex.crossedLens && (std::fabs(ex.lensXMm - a.cx) > pitchMm_ / 2.0 || std::fabs(ex.lensYMm - a.cy) > pitchMm_ / 2.0);
  return true;
}

StackChiefRaySolver::~StackChiefRaySolver() = default;

bool StackChiefRaySolver::stopMiss(double px, double py, double tx, double ty, double cx, double cy, double& mx,
                                   double& my) const {
  double qx = px + tx * stop_.zMm, qy = py + ty * stop_.zMm;  // no layer below: a straight line
  if (below_) {
    const double inv = 1.0 / std::sqrt(1.0 + tx * tx + ty * ty);
    StackExit ex;
    if (!below_->trace(Point3d(px, py, 0.0), Vec3d(tx * inv, ty * inv, inv), wavelengthNm_, nullptr, ex) ||
        !ex.towardViewer || !(ex.d.z > 0.0))
      return false;
    const double t = (stop_.zMm - ex.p.z) / ex.d.z;
    qx = ex.p.x + t * ex.d.x, qy = ex.p.y + t * ex.d.y;
  }
  mx = qx - cx, my = qy - cy;
  return std::isfinite(mx) && std::isfinite(my);
}

bool StackChiefRaySolver::solve(double px, double py, double cx, double cy, Point3d& exitP, Vec3d& exitD,
                                bool* crosstalk) const {
  if (curved()) return solveCurved(px, py, cx, cy, exitP, exitD, crosstalk);
  cx += stopOffsetX_, cy += stopOffsetY_;
  // Paraxially the stop crossing is a (px - cx) + b n0 u0 from the axis: zero for u0 below.
  double tx = -stop_.a * (px - cx) / (stop_.b * panelIndex_), ty = -stop_.a * (py - cy) / (stop_.b * panelIndex_);
  auto miss = [&](double x, double y, double& mx, double& my) { return stopMiss(px, py, x, y, cx, cy, mx, my); };
  if (!newtonOnSlopes(miss, tx, ty)) return false;
  const double inv = 1.0 / std::sqrt(1.0 + tx * tx + ty * ty);
  StackExit ex;
  if (!whole_->trace(Point3d(px, py, 0.0), Vec3d(tx * inv, ty * inv, inv), wavelengthNm_, nullptr, ex) ||
      !ex.towardViewer || !(ex.d.z > 0.0))
    return false;
  exitP = ex.p, exitD = ex.d;
  if (crosstalk)
    *crosstalk = ex.crossedLens && (std::fabs(ex.lensXMm - cx) > pitchMm_ / 2.0 || std::fabs(ex.lensYMm - cy) > pitchMm_ / 2.0);
  return true;
}

RaySet generateTracedChiefRays(const EiLayout& L, const OpticalStack& stack, double panelDepthMm,
                               const TracedChiefRayOptions& o, TracedChiefRayStats* stats, ProgressBar* progress) {
  const auto t0 = std::chrono::steady_clock::now();
  if (L.lensX.empty() || L.lensY.empty()) throw InputError(stack.file, "ei_count", "(no lenses)", "at least one lenslet");
  const StackChiefRaySolver solver(stack, L.lensXAt(0, 0), L.lensYAt(0, 0), o.wavelengthNm);
  const double g = panelDepthMm;
  std::unique_ptr<ChiefRayTable> table;
  // Tables: one for every lenslet of a flat stack; one per lenslet column of a cylinder (its
  // lenslets differ only across its axis: a column's rays are the same shifted along y). A
  // sphere's lenslets all differ: every pixel is solved.
  std::vector<std::unique_ptr<ChiefRayTable>> columnTables;
  const bool cylinder = stack.curvature && stack.curvature->shape == StackCurvature::Shape::Cylinder;
  if (o.tableStepMm > 0.0 && uniformLattice(stack) && (!stack.curved() || cylinder) && !o.pinholeOnly) {
    double maxDx = 0.0, maxDy = 0.0;
    for (int k = 0; k < L.eiCols; ++k)
      for (int l = 0; l < L.eiRows; ++l) {
        const int c0 = L.eiBoxCol0(k, l), r0 = L.eiBoxRow0(k, l);
        for (int i : {0, L.eiW - 1}) maxDx = std::max(maxDx, std::abs(L.pixelCentreX(c0 + i) - L.lensXAt(k, l)));
        for (int j : {0, L.eiH - 1}) maxDy = std::max(maxDy, std::abs(L.pixelCentreY(r0 + j) - L.lensYAt(k, l)));
      }
    const double mx = maxDx + o.tableStepMm, my = maxDy + o.tableStepMm;
    if (!stack.curved()) {
      const int k0 = L.eiCols / 2, l0 = L.eiRows / 2;
      table = std::make_unique<ChiefRayTable>(solver, g, L.lensXAt(k0, l0), L.lensYAt(k0, l0), mx, my, o.tableStepMm);
    } else {
      for (int k = 0; k < L.eiCols; ++k)  // hex: even and odd rows' columns apart
        for (int parity = 0; parity < (L.isHex() ? 2 : 1); ++parity)
          columnTables.push_back(std::make_unique<ChiefRayTable>(solver, g, L.lensXAt(k, parity), 0.0, mx, my, o.tableStepMm));
    }
  }
  RaySet rays;
  for (auto* v : {&rays.ox, &rays.oy, &rays.oz, &rays.dx, &rays.dy, &rays.dz}) v->resize(size_t(L.numRays()));
  std::mutex statsMutex;
  TracedChiefRayStats st;
  double sumDev = 0.0;
  parallelForRange(
      L.numEis(),
      [&](int64_t e0, int64_t e1) {
        uint64_t fallback = 0, crosstalk = 0;
        double maxDev = 0.0, devSum = 0.0;
        for (int64_t e = e0; e < e1; ++e) {
          const int k = int(e / L.eiRows), l = L.eiRows - 1 - int(e % L.eiRows);
          const double cx = L.lensXAt(k, l), cy = L.lensYAt(k, l);
          const size_t column = L.isHex() ? size_t(2 * k + (l & 1)) : size_t(k);
          const ChiefRayTable* lensTable = columnTables.empty() ? table.get() : columnTables[column].get();
          L.forEachRayOfEi(k, l, [&](int64_t ri, int col, int row, int, int) {
            const double px = L.pixelCentreX(col), py = L.pixelCentreY(row);
            PixelRay r;
            if (lensTable && lensTable->lookup(px - cx, py - cy, r))
              r.o += Vec3d(cx, cy, 0.0);
            else
              r = pixelRay(solver, g, px, py, cx, cy, o.pinholeOnly);
            rays.set(size_t(ri), Vec3(r.o), Vec3(r.d));
            fallback += r.real || o.pinholeOnly ? 0 : 1;
            crosstalk += r.crosstalk ? 1 : 0;
            if (o.pinholeOnly) return;  // the rays are the pinhole rays: no deviation to measure
            const Vec3d pinhole = solver.curved() ? solver.pinholeDirection(px, py, cx, cy)
                                                  : glm::normalize(Vec3d(cx - px, cy - py, g));
            const double dev = angleDeg(pinhole, r.d);
            maxDev = std::max(maxDev, dev), devSum += dev;
          });
          if (progress) progress->add(uint64_t(L.eiRayCount(k, l)));
        }
        std::lock_guard<std::mutex> lock(statsMutex);
        st.fallback += fallback, st.crosstalk += crosstalk;
        st.maxDeviationDeg = std::max(st.maxDeviationDeg, maxDev);
        sumDev += devSum;
      },
      nullptr, 4);
  if (stats) {
    st.rays = uint64_t(L.numRays());
    st.meanDeviationDeg = st.rays ? sumDev / double(st.rays) : 0.0;
    st.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    st.stop = solver.stop().what;
    *stats = st;
  }
  return rays;
}

std::string summaryText(const TracedChiefRayOptions& o, const TracedChiefRayStats& st) {
  return formatText(
      "chief rays traced through the stack (%.6g nm, stop %s): %llu rays in %.2f s; angle to the pinhole rays "
      "through the lens centres: max %.4g deg, mean %.4g deg; %llu fell back to the pinhole ray, %llu crosstalk",
      o.wavelengthNm, st.stop.c_str(), (unsigned long long)st.rays, st.seconds, st.maxDeviationDeg,
      st.meanDeviationDeg, (unsigned long long)st.fallback, (unsigned long long)st.crosstalk);
}

}  // namespace inim
